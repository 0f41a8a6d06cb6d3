#!/usr/bin/env python3
"""pi_controller.py - the PI controller of scene pi_link, outside the plant, over the
modrt controller link (docs/link.md); Python's standard library only.

    python3 tools/examples/pi_controller.py --port 0     # prints "port N", then serves
    build/host/modrt run pi_link --link udp:127.0.0.1:N

Every packet from the plant carries Ref.y and Plant.y; the answer carries the command c of
the same sampled PI law as models/pi.c (c = Kp e + I, I += Ki Ts e, e = r - m), so the
loop behaves as scene pi_loop. Packets for another scene or layout are refused and
counted. The controller exits after --idle seconds without packets, or --max-time."""
import argparse
import socket
import struct
import sys
import time
import zlib

MAGIC, VERSION, EXPORTS, IMPORTS = b"MRTL", 1, 1, 2
HEAD = struct.Struct("<4sBBH16sIIQ")  # magic, version, type, n, scene, id, seq, tick


def link_id(scene, controller, exports, imports):
    """FNV-1a 32 over the scene name and the link layout, each string followed by '|'."""
    h = 2166136261
    words = [scene, controller] + [w for e in exports for w in e.split(".")] + [">"] + imports
    for word in words:
        for byte in word.encode() + b"|":
            h = ((h ^ byte) * 16777619) & 0xFFFFFFFF
    return h


SCENE = "pi_link"
ID = link_id(SCENE, "Ctrl", ["Ref.y", "Plant.y"], ["c"])


def decode(pkt):
    """(seq, tick, values) of a valid plant packet for this scene, else None."""
    if len(pkt) < HEAD.size + 4 or zlib.crc32(pkt[:-4]) != struct.unpack("<I", pkt[-4:])[0]:
        return None
    magic, version, kind, n, scene, ident, seq, tick = HEAD.unpack_from(pkt)
    if (magic, version, kind) != (MAGIC, VERSION, EXPORTS) or len(pkt) != HEAD.size + 8 * n + 4:
        return None
    if scene.rstrip(b"\0").decode(errors="replace") != SCENE or ident != ID or n != 2:
        return None
    return seq, tick, struct.unpack_from("<%dd" % n, pkt, HEAD.size)


def encode(seq, tick, values):
    body = HEAD.pack(MAGIC, VERSION, IMPORTS, len(values), SCENE.encode(), ID, seq, tick)
    body += struct.pack("<%dd" % len(values), *values)
    return body + struct.pack("<I", zlib.crc32(body))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--host", default="127.0.0.1")
    ap.add_argument("--port", type=int, default=0, help="0: any free port (printed)")
    ap.add_argument("--kp", type=float, default=0.8)
    ap.add_argument("--ki", type=float, default=3.0)
    ap.add_argument("--ts", type=float, default=0.01, help="sample period [s]")
    ap.add_argument("--idle", type=float, default=5.0, help="exit after S s without packets")
    ap.add_argument("--max-time", type=float, default=60.0, help="exit after S s in all")
    a = ap.parse_args()
    family = socket.AF_INET6 if ":" in a.host else socket.AF_INET
    sock = socket.socket(family, socket.SOCK_DGRAM)
    sock.bind((a.host, a.port))
    sock.settimeout(a.idle)
    print("port", sock.getsockname()[1], flush=True)
    integral, answered, refused, start = 0.0, 0, 0, time.monotonic()
    while time.monotonic() - start < a.max_time:
        try:
            pkt, peer = sock.recvfrom(2048)
        except socket.timeout:
            break
        got = decode(pkt)
        if got is None:
            refused += 1
            continue
        seq, tick, (r, m) = got
        e = r - m
        c = a.kp * e + integral
        integral = integral + a.ki * a.ts * e
        sock.sendto(encode(seq, tick, [c]), peer)
        answered += 1
    print("answered", answered, "refused", refused, flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
