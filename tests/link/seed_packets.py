#!/usr/bin/env python3
"""seed_packets.py DIR - seeds for the link fuzzer (tests/link/fuzz_link.c): a valid
pi_link answer of wire format version 2 (the fuzz target's id 0x5a17c0de, run nonce
0x0123456789abcdef, 1 value) under each selector byte, sealed or not; and small valid
replay logs of every version (1, 2 and 3, selector byte 0; version 3 also of a run
interrupted by SIGINT), written here from the layout of
tools/modrt/mrlog.c, so "logs accepted" is never 0 whatever the unit tests leave."""
import os
import struct
import sys
import zlib

RUN = 0x0123456789ABCDEF
head = struct.Struct("<4sBBBB16sIIQQ").pack(b"MRTL", 2, 2, 0, 1, b"pi_link", 0x5A17C0DE, 7,
                                            10, RUN)
body = head + struct.pack("<d", 0.25)
pkt = body + struct.pack("<I", zlib.crc32(body))


def crc(b):
    return b + struct.pack("<I", zlib.crc32(b))


def log(version, records, nsets=0, ended=0, last=1000):
    """a replay log: header, records (tick, values), end marker (version 3: how the run
    ended, mrl_end, and the last tick it reached)"""
    nimp = len(records[0][1]) if records else 1
    fixed = struct.pack("<4sHHIHBBdIHH", b"MRTR", version, 0, 0x5A17C0DE, nimp, 8, 0, 0.05,
                        1, nsets, 0)
    if version >= 2:
        fixed += struct.pack("<QQ", 0x1122334455667788, RUN)
    size = len(fixed) + 256 + 128 * nsets + 4
    fixed = fixed[:6] + struct.pack("<H", size) + fixed[8:]
    h = crc(fixed + b"pi_link".ljust(256, b"\0") + b"".join(
        ("Plant.K=%d" % i).encode().ljust(128, b"\0") for i in range(nsets)))
    out = h
    for tick, vals in records:
        out += crc(struct.pack("<Q%dd" % len(vals), tick, *vals))
    if version < 3:
        return out + crc(b"MRTE" + struct.pack("<Q", len(records)))
    return out + crc(b"MRTE" + struct.pack("<QQB3x", len(records), last, ended))


for sel in (1 | (1 << 2), 3 | (1 << 2), 3 | (2 << 2)):
    with open(os.path.join(sys.argv[1], "packet-%d" % sel), "wb") as f:
        f.write(bytes([sel]) + pkt)
THREE = [(0, [0.5]), (10, [1.0]), (20, [-2.0])]
for version in (1, 2, 3):
    for name, recs, nsets in (("empty", [], 0), ("three", THREE, 1)):
        with open(os.path.join(sys.argv[1], "log-v%d-%s" % (version, name)), "wb") as f:
            f.write(b"\0" + log(version, recs, nsets))
with open(os.path.join(sys.argv[1], "log-v3-sigint"), "wb") as f:
    f.write(b"\0" + log(3, THREE, 1, ended=1, last=25))
