#!/usr/bin/env python3
"""pi_controller.py - the PI controller of scene pi_link, outside the plant, over the
modrt controller link (docs/link.md, wire format version 2); Python's standard library only.

    python3 tools/examples/pi_controller.py --port 0     # prints "port N", then serves
    build/host/modrt run pi_link --link udp:127.0.0.1:N

Every request from the plant carries Ref.y and Plant.y; the answer carries the command c
of the same sampled PI law as models/pi.c (e = r - m; c = Kp e + I; then I = I + Ki Ts e),
so the loop behaves as scene pi_loop. The controller serves one plant: the address and
run nonce of the first valid request that starts a run (sequence 1 at tick 0; the same
address may start a new run). Requests from any other address, of another run, or not
newer than the last one answered are ignored and counted, so no other process can drive
its integrator once a run is under way.
Packets for another scene or layout are refused and counted. With --key FILE every
datagram carries an HMAC-SHA-256 tag under the shared key (modrt run --link-key FILE).
The controller exits after --idle seconds without packets, or --max-time."""
import argparse
import hashlib
import hmac
import socket
import struct
import sys
import time
import zlib

MAGIC, VERSION, EXPORTS, IMPORTS, FLAG_AUTH, TAG = b"MRTL", 2, 1, 2, 1, 32
# magic, version, type, flags, n, scene, link id, seq, tick, run nonce
HEAD = struct.Struct("<4sBBBB16sIIQQ")


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


def decode(pkt, key=None):
    """(seq, tick, run, values) of a valid plant request for this scene, else None; the
    checks in the plant's order (docs/link.md, "Checks")."""
    if len(pkt) < HEAD.size + 4 or pkt[:4] != MAGIC:
        return None
    flags, n = pkt[6], pkt[7]
    tagged = flags == FLAG_AUTH
    if pkt[4] != VERSION or flags & ~FLAG_AUTH or len(pkt) != HEAD.size + 8 * n + 4 + TAG * tagged:
        return None
    body = HEAD.size + 8 * n
    if zlib.crc32(pkt[:body]) != struct.unpack_from("<I", pkt, body)[0]:
        return None
    if tagged != (key is not None):
        return None
    if key is not None and not hmac.compare_digest(
            hmac.new(key, pkt[:body + 4], hashlib.sha256).digest(), pkt[body + 4:]):
        return None
    magic, version, kind, flags, n, scene, ident, seq, tick, run = HEAD.unpack_from(pkt)
    if kind != EXPORTS or scene.rstrip(b"\0") != SCENE.encode() or ident != ID or n != 2:
        return None
    values = struct.unpack_from("<%dd" % n, pkt, HEAD.size)
    if any(v != v or v in (float("inf"), float("-inf")) for v in values):
        return None
    return seq, tick, run, values


def encode(seq, tick, run, values, key=None):
    flags = FLAG_AUTH if key is not None else 0
    body = HEAD.pack(MAGIC, VERSION, IMPORTS, flags, len(values), SCENE.encode(), ID, seq,
                     tick, run)
    body += struct.pack("<%dd" % len(values), *values)
    body += struct.pack("<I", zlib.crc32(body))
    return body + (hmac.new(key, body, hashlib.sha256).digest() if key is not None else b"")


class Pi:
    """The law of models/pi.c in its exact order of arithmetic (bit-exact with pi_loop)."""

    def __init__(self, kp, ki, ts):
        self.kp, self.ki, self.ts, self.integral = kp, ki, ts, 0.0

    def step(self, r, m):
        e = r - m
        c = self.kp * e + self.integral
        self.integral = self.integral + self.ki * self.ts * e
        return c


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--host", default="127.0.0.1")
    ap.add_argument("--port", type=int, default=0, help="0: any free port (printed)")
    ap.add_argument("--kp", type=float, default=0.8)
    ap.add_argument("--ki", type=float, default=3.0)
    ap.add_argument("--ts", type=float, default=0.01, help="sample period [s]")
    ap.add_argument("--key", help="file with the shared key (authenticated mode)")
    ap.add_argument("--idle", type=float, default=5.0, help="exit after S s without packets")
    ap.add_argument("--max-time", type=float, default=60.0, help="exit after S s in all")
    a = ap.parse_args()
    key = None
    if a.key:
        with open(a.key, "rb") as f:
            key = f.read()
        key = key[:-1] if key.endswith(b"\n") else key
    family = socket.AF_INET6 if ":" in a.host else socket.AF_INET
    sock = socket.socket(family, socket.SOCK_DGRAM)
    sock.bind((a.host, a.port))
    sock.settimeout(a.idle)
    print("port", sock.getsockname()[1], flush=True)
    law, plant, run, last = Pi(a.kp, a.ki, a.ts), None, None, 0
    answered, refused, ignored, start = 0, 0, 0, time.monotonic()
    while time.monotonic() - start < a.max_time:
        try:
            pkt, peer = sock.recvfrom(2048)
        except socket.timeout:
            break
        got = decode(pkt, key)
        if got is None:
            refused += 1
            continue
        seq, tick, nonce, (r, m) = got
        if seq == 1 and tick == 0 and plant in (None, peer) and nonce != run:
            plant, run, last, law = peer, nonce, 0, Pi(a.kp, a.ki, a.ts)  # a (new) run
        if peer != plant or nonce != run or seq <= last:
            ignored += 1                       # another sender, another run, or stale
            continue
        last = seq
        sock.sendto(encode(seq, tick, run, [law.step(r, m)], key), peer)
        answered += 1
    print("answered", answered, "refused", refused, "ignored", ignored, flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
