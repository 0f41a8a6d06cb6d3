#!/usr/bin/env python3
"""evil_controller.py - the PI controller of tools/examples/pi_controller.py, but before
every good answer it sends one datagram of each bad kind (bad CRC, wrong magic, version,
an unknown flag, type, scene name, link id, value count, truncated, oversized, a tag the
plant has no key for, another run's nonce, a sequence number never sent, a wrong tick,
a NaN), each carrying a wrong command, and from another port of the machine an answer
right in every field but its wrong command (it must never reach the plant's checks: the
plant's socket takes only the --link address), then the previous answer again and the one before
it (answered already: duplicates), and after the good answer the same again (a
duplicate). The plant must apply only the good answers: its trace then equals pi_loop's,
and its counters show each kind.
--silent-after N: stop answering after N requests (the plant's timeout and policy).
--dups-only: no bad datagrams, only the good answers and the duplicates (harmless).
--answer-late: only the good answers, each sent when the next request arrives: after its
deadline by construction (lock-step: the plant sends the next request only after the
timeout of this one; real time: only at the next exchange tick)."""
import os
import socket
import struct
import sys
import zlib

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "tools", "examples"))
import pi_controller as pc  # noqa: E402

KINDS = 15  # bad datagrams per request


def reseal(body):
    return body + struct.pack("<I", zlib.crc32(body))


def bad_packets(seq, tick, run, values):
    wrong = [values[0] + 100.0]
    good = pc.encode(seq, tick, run, wrong)
    body = bytearray(good[:-4])
    out = [good[:-4] + bytes([good[-4] ^ 1]) + good[-3:]]  # bad CRC
    for off, val in ((0, ord("X")), (4, 1), (6, 4), (5, pc.EXPORTS), (8, ord("q")),
                     (24, body[24] ^ 1)):
        b = bytearray(body)
        b[off] = val
        out.append(reseal(bytes(b)))                 # magic, version, flag, type, scene, id
    two = pc.HEAD.pack(pc.MAGIC, pc.VERSION, pc.IMPORTS, 0, 2, pc.SCENE.encode(), pc.ID, seq,
                       tick, run)
    out.append(reseal(two + struct.pack("<2d", wrong[0], 0.0)))   # wrong count
    out.append(good[:-1])                                         # truncated
    out.append(good + b"\0" * 600)                                # oversized
    out.append(pc.encode(seq, tick, run, wrong, key=b"k"))        # a tag, the plant has no key
    out.append(pc.encode(seq, tick, run ^ 1, wrong))              # another run
    out.append(pc.encode(seq + 1000, tick, run, wrong))           # a request never sent
    out.append(pc.encode(seq, tick + 1, run, wrong))              # a wrong tick
    out.append(pc.encode(seq, tick, run, [float("nan")]))         # not finite
    assert len(out) == KINDS
    return out


OTHER = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)  # another port of this machine


def main():
    dups_only = "--dups-only" in sys.argv
    answer_late, held = "--answer-late" in sys.argv, None
    silent_after = int(sys.argv[sys.argv.index("--silent-after") + 1]) if "--silent-after" in sys.argv else -1
    sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    sock.bind(("127.0.0.1", 0))
    sock.settimeout(3)
    print("port", sock.getsockname()[1], flush=True)
    law, count, last, older = pc.Pi(0.8, 3.0, 0.01), 0, None, None
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
        seq, tick, run, (r, m) = got
        c = law.step(r, m)
        if answer_late:
            if held is not None:
                sock.sendto(held, peer)
            held = pc.encode(seq, tick, run, [c])
            continue
        for b in [] if dups_only else bad_packets(seq, tick, run, [c]):
            sock.sendto(b, peer)
        if not dups_only:  # a right-looking answer with a wrong value from another port:
            OTHER.sendto(pc.encode(seq, tick, run, [c + 100.0]), peer)  # the kernel drops it
        if last is not None:
            sock.sendto(last, peer)                  # the previous answer again: dup
        if older is not None:
            sock.sendto(older, peer)                 # the one before it: dup
        older, last = last, pc.encode(seq, tick, run, [c])
        sock.sendto(last, peer)
        sock.sendto(last, peer)                      # duplicate
    return 0


if __name__ == "__main__":
    sys.exit(main())
