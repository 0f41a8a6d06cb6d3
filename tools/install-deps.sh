#!/bin/sh
# install-deps.sh - installs, from Debian's packages, everything `make test`, `make demo`
# and `make cross-test` use: the host compiler, the cross compilers and QEMU. Skips what is
# already there; needs root (or sudo) for apt-get.
set -eu
need=""
have() { command -v "$1" >/dev/null 2>&1; }
have gcc                     || need="$need gcc libc6-dev"
have make                    || need="$need make"
have arm-none-eabi-gcc       || need="$need gcc-arm-none-eabi"
[ -d /usr/lib/arm-none-eabi/newlib ] || need="$need libnewlib-arm-none-eabi"
have riscv64-unknown-elf-gcc || need="$need gcc-riscv64-unknown-elf"
have qemu-system-arm         || need="$need qemu-system-arm"
have qemu-system-riscv64     || need="$need qemu-system-misc"
have qemu-aarch64            || need="$need qemu-user"
have aarch64-linux-gnu-gcc   || need="$need gcc-aarch64-linux-gnu libc6-dev-arm64-cross"
# libFuzzer for the scene-language fuzz target (tests/scenec/fuzz.sh falls back to its
# own random mutator without it)
have clang                   || need="$need clang"
ls /usr/lib/llvm-*/lib/clang/*/lib/linux/libclang_rt.fuzzer-x86_64.a >/dev/null 2>&1 || \
    need="$need libclang-rt-dev"
if [ -z "$need" ]; then
    echo "install-deps: everything is installed"
    exit 0
fi
SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO=sudo
echo "install-deps: installing$need"
$SUDO apt-get update -qq
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends $need
