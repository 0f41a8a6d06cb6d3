#!/bin/sh
# install-deps.sh - installs, from Debian's packages, everything the make targets use: the
# host compiler, expat and libzip (FMUs), the cross compilers, QEMU, clang's libFuzzer,
# valgrind, python3, cppcheck and clang-tidy; GNU parallel, Slurm and MUNGE for the
# campaign engines (make test-sweep); MuJoCo for the benchmarks only (group bench: make test
# never needs it). Skips what is already there. Needs root (or sudo) for apt-get.
#
#   sh tools/install-deps.sh            install what is missing (every group, bench too)
#   sh tools/install-deps.sh --auto G   what the Makefile calls before a target that needs
#                                       group G (host | sweep | all | bench; all is what
#                                       make test needs, bench what make bench adds):
#                                       installs when it can (root, or sudo without a
#                                       password), otherwise prints one line naming the
#                                       command to run and fails
set -eu
auto=0 group=every
if [ "${1:-}" = "--auto" ]; then auto=1; group=${2:-all}; fi
need=""
have() { command -v "$1" >/dev/null 2>&1; }
have gcc                     || need="$need gcc libc6-dev"
have make                    || need="$need make"
have git                     || need="$need git"
have python3                 || need="$need python3"
# FMUs (tools/fmi/): modelDescription.xml by expat, the archive by libzip, zip for the
# test FMUs
[ -f /usr/include/expat.h ]  || need="$need libexpat1-dev"
[ -f /usr/include/zip.h ]    || need="$need libzip-dev"
have zip                     || need="$need zip"
if [ "$group" = every ] || [ "$group" = all ] || [ "$group" = sweep ]; then
    # the engines `modrt sweep` hands its task lines to (tests/sweep/sweep.sh runs both)
    have parallel                || need="$need parallel"
    have slurmctld               || need="$need slurm-wlm"
    have munged                  || need="$need munge"
fi
if [ "$group" = every ] || [ "$group" = all ]; then
    have arm-none-eabi-gcc       || need="$need gcc-arm-none-eabi"
    [ -d /usr/lib/arm-none-eabi/newlib ] || need="$need libnewlib-arm-none-eabi"
    have riscv64-unknown-elf-gcc || need="$need gcc-riscv64-unknown-elf"
    have qemu-system-arm         || need="$need qemu-system-arm"
    have qemu-system-riscv64     || need="$need qemu-system-misc"
    have qemu-aarch64            || need="$need qemu-user"
    have aarch64-linux-gnu-gcc   || need="$need gcc-aarch64-linux-gnu libc6-dev-arm64-cross"
    # libFuzzer for the fuzz targets
    have clang                   || need="$need clang"
    ls /usr/lib/llvm-*/lib/clang/*/lib/linux/libclang_rt.fuzzer-x86_64.a >/dev/null 2>&1 || \
        need="$need libclang-rt-dev"
    # callgrind: deterministic instruction counts of the benchmarks
    have valgrind                || need="$need valgrind"
    # the static checks of make test-static
    have cppcheck                || need="$need cppcheck"
    have clang-tidy              || need="$need clang-tidy"
fi
if [ "$group" = every ] || [ "$group" = bench ]; then
    # MuJoCo beside modrt (tools/dev/bench/mujoco_scale.py), counted by callgrind
    [ -f /usr/include/mujoco/mujoco.h ] || need="$need libmujoco-dev"
    have valgrind                || need="$need valgrind"
fi
if [ -z "$need" ]; then
    [ "$auto" -eq 1 ] || echo "install-deps: everything is installed"
    exit 0
fi
SUDO=""
if [ "$(id -u)" -ne 0 ]; then
    if have sudo && sudo -n true 2>/dev/null; then
        SUDO=sudo
    elif [ "$auto" -eq 1 ]; then
        echo "make: missing tools (${need# }); install them with: sudo sh tools/install-deps.sh" >&2
        exit 1
    else
        SUDO=sudo
    fi
fi
echo "install-deps: installing$need"
$SUDO apt-get update -qq
# $need is a list of package names: split on purpose
# shellcheck disable=SC2086
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends $need \
    >/tmp/install-deps.$$.log 2>&1 || {
    tail -20 /tmp/install-deps.$$.log >&2
    echo "install-deps: apt-get install failed (log above); run: sudo sh tools/install-deps.sh" >&2
    exit 1
}
rm -f /tmp/install-deps.$$.log
echo "install-deps: done"
