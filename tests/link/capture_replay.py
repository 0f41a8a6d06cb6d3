#!/usr/bin/env python3
"""capture_replay.py capture|replay FILE - an attack on a later run with the answers of an
earlier one. capture: the PI controller of pi_link with Kp = 2 (another law), which keeps
every answer it sends in FILE. replay: for every request of a new run it first sends the
captured answer of the same sequence number and tick (the earlier run's nonce), then the
right answer (Kp = 0.8). The plant must refuse every captured answer (link_bad.run) and
apply only the right ones: its trace is then pi_loop's."""
import os
import pickle
import socket
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "tools", "examples"))
import pi_controller as pc  # noqa: E402


def main():
    mode, path = sys.argv[1], sys.argv[2]
    captured = {}
    if mode == "replay":
        with open(path, "rb") as f:
            captured = pickle.load(f)
    law = pc.Pi(2.0 if mode == "capture" else 0.8, 3.0, 0.01)
    sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    sock.bind(("127.0.0.1", 0))
    sock.settimeout(3)
    print("port", sock.getsockname()[1], flush=True)
    while True:
        try:
            pkt, peer = sock.recvfrom(2048)
        except socket.timeout:
            break
        got = pc.decode(pkt)
        if got is None:
            continue
        seq, tick, run, (r, m) = got
        answer = pc.encode(seq, tick, run, [law.step(r, m)])
        if mode == "capture":
            captured[seq] = answer
            with open(path, "wb") as f:  # whole after every answer: the test ends it by kill
                pickle.dump(captured, f)
        elif seq in captured:
            sock.sendto(captured[seq], peer)
        sock.sendto(answer, peer)
    return 0


if __name__ == "__main__":
    sys.exit(main())
