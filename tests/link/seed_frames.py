#!/usr/bin/env python3
"""seed_frames.py DIR - seed byte streams for the frame fuzzer (tests/link/fuzz_frame.c):
pi_link requests (the fuzz target's id 0x5a17c0de, 2 values) framed as docs/link.md says,
by a COBS encoder written here from the definition (not the one under test): one frame,
two frames, a frame after garbage, a frame cut short, the same request twice."""
import os
import struct
import sys
import zlib


def cobs(payload):
    out, block = bytearray(), bytearray()
    for b in payload:
        if b == 0:
            out += bytes([len(block) + 1]) + block
            block = bytearray()
        else:
            block.append(b)
            if len(block) == 254:
                out += bytes([255]) + block
                block = bytearray()
    # the last block, unless the payload ended on a full run (the minimal coding)
    if block or not payload or payload[-1] == 0:
        out += bytes([len(block) + 1]) + block
    return bytes(out)


def request(seq, tick, r, m):
    # wire format 2 (docs/link.md): flags 0, n in one byte, the run nonce after the tick
    head = struct.pack("<4sBBBB16sIIQQ", b"MRTL", 2, 1, 0, 2, b"pi_link", 0x5A17C0DE, seq,
                       tick, 0x1234)
    body = head + struct.pack("<dd", r, m)
    return body + struct.pack("<I", zlib.crc32(body))


def frame(d):
    return b"\0" + cobs(b"\x01" + d) + b"\0"


d = sys.argv[1]
a, b = frame(request(1, 0, 0.0, 0.0)), frame(request(2, 10, 1.0, 0.25))
# a frame of code-2 blocks (no COBS overhead) that fits the receiver's buffer but decodes
# past the largest payload: once a crash of the fuzzer's own length check (regression)
dense = b"\0\x02\x01" + b"\x02\x33" * 299 + b"\0"
seeds = {"one": a, "two": a + b, "garbage": b"\x55\xaa\x13" + a, "cut": a[:30],
         "repeat": a + a + b, "dense": dense + a}
for name, data in seeds.items():
    with open(os.path.join(d, name), "wb") as f:
        f.write(data)
