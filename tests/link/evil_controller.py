#!/usr/bin/env python3
"""evil_controller.py - the PI controller of tools/examples/pi_controller.py, but before
every good answer it sends one datagram of each bad kind (bad CRC, wrong magic, version,
type, scene name, link id, value count, truncated, oversized), the previous answer again
and the one before it (a duplicate and a late answer), and after the good answer the same
again (a duplicate). The plant must apply only
the good answers: its trace then equals pi_loop's, and its counters show each kind.
--silent-after N: stop answering after N packets (the plant's timeout and policy)."""
import os
import socket
import struct
import sys
import zlib

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "tools", "examples"))
import pi_controller as pc  # noqa: E402


def reseal(body):
    return body + struct.pack("<I", zlib.crc32(body))


def bad_packets(seq, tick, values):
    good = pc.encode(seq, tick, values)
    body = bytearray(good[:-4])
    out = [good[:-4] + bytes([good[-4] ^ 1]) + good[-3:]]  # bad CRC
    for off, val in ((0, ord("X")), (4, 9), (5, pc.EXPORTS), (8, ord("q")), (24, body[24] ^ 1)):
        b = bytearray(body)
        b[off] = val
        out.append(reseal(bytes(b)))                          # magic, version, type, scene, id
    two = pc.HEAD.pack(pc.MAGIC, pc.VERSION, pc.IMPORTS, 2, pc.SCENE.encode(), pc.ID, seq, tick)
    out.append(reseal(two + struct.pack("<2d", values[0], 0.0)))  # wrong count
    out.append(good[:-1])                                     # truncated
    out.append(good + b"\0" * 600)                            # oversized
    return out


def main():
    silent_after = int(sys.argv[sys.argv.index("--silent-after") + 1]) if "--silent-after" in sys.argv else -1
    sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    sock.bind(("127.0.0.1", 0))
    sock.settimeout(3)
    print("port", sock.getsockname()[1], flush=True)
    integral, count, last, older = 0.0, 0, None, None
    while True:
        try:
            pkt, peer = sock.recvfrom(2048)
        except socket.timeout:
            break
        got = pc.decode(pkt)
        if got is None:
            continue
        count += 1
        if 0 <= silent_after < count:
            continue
        seq, tick, (r, m) = got
        e = r - m
        c = 0.8 * e + integral
        integral += 3.0 * 0.01 * e
        for b in bad_packets(seq, tick, [c]):
            sock.sendto(b, peer)
        if last is not None:
            sock.sendto(last, peer)                           # the previous answer again: dup
        if older is not None:
            sock.sendto(older, peer)                          # one given up on: late
        older, last = last, pc.encode(seq, tick, [c])
        sock.sendto(last, peer)
        sock.sendto(last, peer)                               # duplicate
    return 0


if __name__ == "__main__":
    sys.exit(main())
