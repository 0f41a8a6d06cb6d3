#!/usr/bin/env python3
"""seed_packets.py DIR - seed datagrams for the link fuzzer: a valid pi_link answer (with
the fuzz target's id 0x5a17c0de and 1 value) under each selector byte, sealed or not."""
import os
import struct
import sys
import zlib

head = struct.Struct("<4sBBH16sIIQ").pack(b"MRTL", 1, 2, 1, b"pi_link", 0x5A17C0DE, 7, 10)
body = head + struct.pack("<d", 0.25)
pkt = body + struct.pack("<I", zlib.crc32(body))
for sel in (1 | (1 << 2), 3 | (1 << 2), 3 | (2 << 2)):
    with open(os.path.join(sys.argv[1], "packet-%d" % sel), "wb") as f:
        f.write(bytes([sel]) + pkt)
