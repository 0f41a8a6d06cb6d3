#!/usr/bin/env python3
"""serial_noise.py - a noisy serial line between two programs, for tests/link/serial.sh:
two pseudo-terminals (raw), one for the plant and one for the controller, printed as
"plant PATH" and "controller PATH"; every byte one side writes reaches the other, except
at the frames (the bytes between two zero bytes, docs/link.md "Over a serial line") named
by --faults, where one fault is injected:

  garbage   nonzero bytes written after the frame's closing zero (a frame of noise of its
            own; the real frames survive)
  drop      a byte in the middle of the frame is lost
  flip      one bit of a byte in the middle of the frame flips (the byte stays nonzero)
  inside    nonzero bytes written into the middle of the frame
  delim     the frame's closing zero is lost (the next frame's opening zero ends it: no loss)

--faults 'req:20=garbage,40=drop;ans:30=flip' (req: plant to controller, counted from 1
in each direction). --baud N paces each direction as a line of N baud, 8N1 (10 bits a
byte: what reaches the other side arrives when its last byte would have); without it the
relay forwards at once. --controller-dev PATH opens an existing terminal (the pty of a
QEMU board) as the controller's end instead of making one. Exits after --idle seconds
without traffic and prints what it did (tools/dev/bench/serial_bench.sh uses it too)."""
import argparse
import os
import select
import sys
import time
import tty

GARBAGE = bytes([0x55, 0xAA, 0x13, 0x37, 0xFE, 0x01, 0x02])


def schedule(spec):
    out = {"req": {}, "ans": {}}
    for part in filter(None, spec.split(";")):
        way, items = part.split(":", 1)
        for item in filter(None, items.split(",")):
            k, kind = item.split("=")
            out[way][int(k)] = kind
    return out


def corrupt(kind, run):
    """the frame's bytes as sent on, and garbage to send after its zero"""
    mid = len(run) // 2
    if kind == "drop":
        return run[:mid] + run[mid + 1:], b"", True
    if kind == "flip":
        b = run[mid]
        bit = 0x10 if b ^ 0x10 else 0x01
        return run[:mid] + bytes([b ^ bit]) + run[mid + 1:], b"", True
    if kind == "inside":
        return run[:mid] + GARBAGE + run[mid:], b"", True
    if kind == "garbage":
        return run, GARBAGE, True
    if kind == "delim":
        return run, None, True
    raise SystemExit("serial_noise: unknown fault " + kind)


class Way:
    """one direction: splits the byte stream at zero bytes, counts frames, injects faults"""

    def __init__(self, name, src, dst, faults, baud):
        self.name, self.src, self.dst, self.faults = name, src, dst, faults
        self.run, self.frames, self.done = bytearray(), 0, []
        self.byte_s, self.free_at = (10.0 / baud if baud else 0), 0.0

    def send(self, out):
        """on a paced line the bytes arrive when the last of them is through"""
        if self.byte_s:
            now = time.monotonic()
            self.free_at = max(now, self.free_at) + len(out) * self.byte_s
            time.sleep(max(0.0, self.free_at - now))
        os.write(self.dst, out)

    def feed(self, data):
        out = bytearray()
        for b in data:
            if b != 0:
                self.run.append(b)
                continue
            if not self.run:
                out.append(0)
                continue
            self.frames += 1
            run, after = bytes(self.run), b""
            self.run.clear()
            kind = self.faults.get(self.frames)
            if kind:
                run, after, _ = corrupt(kind, run)
                self.done.append("%d=%s" % (self.frames, kind))
            out += run
            if after is not None:
                out.append(0)
                out += after
        if out:
            self.send(bytes(out))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--faults", default="")
    ap.add_argument("--idle", type=float, default=5)
    ap.add_argument("--baud", type=int, default=0)
    ap.add_argument("--controller-dev")
    a = ap.parse_args()
    f = schedule(a.faults)
    ends = {}
    for side in ("plant", "controller"):
        if side == "controller" and a.controller_dev:
            m = os.open(a.controller_dev, os.O_RDWR | os.O_NOCTTY)
            tty.setraw(m)
            ends[side] = (m, None)
            continue
        m, s = os.openpty()
        tty.setraw(s)
        ends[side] = (m, s)
        print(side, os.ttyname(s))
    sys.stdout.flush()
    pm, cm = ends["plant"][0], ends["controller"][0]
    ways = {pm: Way("req", pm, cm, f["req"], a.baud), cm: Way("ans", cm, pm, f["ans"], a.baud)}
    seen = False
    while True:
        r, _, _ = select.select([pm, cm], [], [], a.idle)
        if not r:
            if seen:
                break
            continue
        for fd in r:
            try:
                data = os.read(fd, 4096)
            except OSError:
                data = b""
            if data:
                seen = True
                ways[fd].feed(data)
    for w in ways.values():
        print("%s frames %d faults %s" % (w.name, w.frames, " ".join(w.done) or "-"))


main()
