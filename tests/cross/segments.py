#!/usr/bin/env python3
"""segments.py - what a loader writes for an image lands inside the target's memory.

A loader (QEMU's -kernel, a debugger's load) writes each PT_LOAD segment at its physical
address: FileSiz bytes of the file, then MemSiz - FileSiz zeros. Every such range must lie
inside one MEMORY region of the link script and no two may overlap; otherwise the zeros
of one segment land on another (on the MPS2 boards FLASH repeats at 0x400000, so zeros
written past its end erase the code at 0x0). The linker checks the sections' own
addresses, not this.

Usage: segments.py LINK_SCRIPT ELF...          regions from the script's MEMORY block
       segments.py --region NAME:ORIGIN:LENGTH ... -- ELF...
Prints one line per image that fails, saying which segment lands where; exits 1 if any
does, 2 on bad input."""
import os
import re
import struct
import sys

PT_LOAD = 1
UNITS = {"": 1, "K": 1024, "M": 1024 * 1024}


def number(text):
    m = re.fullmatch(r"(0[xX][0-9a-fA-F]+|[0-9]+)([KM]?)", text.strip())
    if not m:
        raise ValueError("not a length or address: %r" % text)
    return int(m.group(1), 0) * UNITS[m.group(2)]


def script_text(path):
    text = open(path).read()
    # INCLUDE file (ports/cmsis/link.ld takes its MEMORY from memory.ld)
    for name in re.findall(r"^\s*INCLUDE\s+(\S+)", text, re.M):
        text += script_text(os.path.join(os.path.dirname(path), name))
    return text


def regions_of(path):
    text = re.sub(r"/\*.*?\*/", " ", script_text(path), flags=re.S)
    m = re.search(r"MEMORY\s*{(.*?)}", text, re.S)
    if not m:
        raise ValueError("%s: no MEMORY block" % path)
    out = [(name, number(o), number(n)) for name, o, n in re.findall(
        r"(\w+)\s*(?:\([^)]*\))?\s*:\s*ORIGIN\s*=\s*(\w+)\s*,\s*LENGTH\s*=\s*(\w+)", m.group(1))]
    if not out:
        raise ValueError("%s: no region in its MEMORY block" % path)
    return out


def loads(path):
    """(index, paddr, filesz, memsz) of every PT_LOAD with memsz > 0"""
    data = open(path, "rb").read()
    if data[:4] != b"\x7fELF":
        raise ValueError("%s: not an ELF file" % path)
    end = "<" if data[5] == 1 else ">"
    if data[4] == 1:
        phoff, = struct.unpack_from(end + "I", data, 0x1C)
        phentsize, phnum = struct.unpack_from(end + "HH", data, 0x2A)
        fmt, fields = end + "8I", (0, 3, 4, 5)  # type offset vaddr paddr filesz memsz ...
    else:
        phoff, = struct.unpack_from(end + "Q", data, 0x20)
        phentsize, phnum = struct.unpack_from(end + "HH", data, 0x36)
        fmt, fields = end + "IIQQQQQQ", (0, 4, 5, 6)  # type flags offset vaddr paddr ...
    out = []
    for i in range(phnum):
        ph = struct.unpack_from(fmt, data, phoff + i * phentsize)
        ptype, paddr, filesz, memsz = (ph[k] for k in fields)
        if ptype == PT_LOAD and memsz > 0:
            out.append((i, paddr, filesz, memsz))
    return out


def check(path, regions):
    errors = []
    segs = loads(path)
    for i, paddr, filesz, memsz in segs:
        lo, hi = paddr, paddr + memsz
        if not any(o <= lo and hi <= o + n for _, o, n in regions):
            where = ", ".join("%s 0x%x..0x%x" % (name, o, o + n) for name, o, n in regions)
            errors.append("segment %d is written at 0x%x..0x%x (%d bytes of file, %d of "
                          "zeros), outside every memory region (%s)"
                          % (i, lo, hi, filesz, memsz - filesz, where))
    for a in range(len(segs)):
        for b in range(a + 1, len(segs)):
            (i, p, _, m), (j, q, _, n) = segs[a], segs[b]
            if p < q + n and q < p + m:
                errors.append("segments %d (0x%x..0x%x) and %d (0x%x..0x%x) are written "
                              "over each other" % (i, p, p + m, j, q, q + n))
    return ["%s: %s" % (path, e) for e in errors]


def main(argv):
    try:
        if argv and argv[0] == "--region":
            regions, k = [], 0
            while k < len(argv) and argv[k] == "--region":
                name, origin, length = argv[k + 1].split(":")
                regions.append((name, number(origin), number(length)))
                k += 2
            if argv[k:k + 1] != ["--"]:
                raise ValueError("--region NAME:ORIGIN:LENGTH ... -- ELF...")
            elfs = argv[k + 1:]
        else:
            regions, elfs = regions_of(argv[0]), argv[1:]
        if not elfs:
            raise ValueError("no image given")
        bad = [line for elf in elfs for line in check(elf, regions)]
    except (ValueError, IndexError, OSError, struct.error) as e:
        print("segments.py: %s" % e, file=sys.stderr)
        return 2
    for line in bad:
        print(line)
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
