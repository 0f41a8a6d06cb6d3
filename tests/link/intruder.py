#!/usr/bin/env python3
"""intruder.py PORT SECONDS - a third process on the same machine that sends the example
controller at 127.0.0.1:PORT well-formed plant requests of pi_link (its own run nonce,
sequence numbers from 2, Ref.y = 50 and Plant.y = 0) every 0.5 ms for SECONDS (it prints "sending" once under way). A
controller that answered anyone would integrate them and drive the real plant far from
pi_loop's trajectory; the example controllers ignore them (docs/link.md)."""
import os
import random
import socket
import struct
import sys
import time
import zlib

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "tools", "examples"))
import pi_controller as pc  # noqa: E402


def request(seq, tick, run, values):
    body = pc.HEAD.pack(pc.MAGIC, pc.VERSION, pc.EXPORTS, 0, len(values), pc.SCENE.encode(),
                        pc.ID, seq, tick, run) + struct.pack("<%dd" % len(values), *values)
    return body + struct.pack("<I", zlib.crc32(body))


def main():
    port, secs = int(sys.argv[1]), float(sys.argv[2])
    sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    run, seq, end = random.getrandbits(64), 2, time.monotonic() + secs
    while time.monotonic() < end:
        sock.sendto(request(seq, 10 * (seq - 1), run, [50.0, 0.0]), ("127.0.0.1", port))
        if seq == 100:
            print("sending", flush=True)  # the test starts the plant now
        seq += 1
        time.sleep(0.0005)
    return 0


if __name__ == "__main__":
    sys.exit(main())
