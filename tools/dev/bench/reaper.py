#!/usr/bin/python3
"""reaper.py - runs a command as a child subreaper (Linux, prctl PR_SET_CHILD_SUBREAPER),
so the processes it leaves orphaned (slurmd's double-forked slurmstepd and the job steps
under it) are reaped here and their CPU time adds to this process's children's. On
SIGUSR1 it writes the CPU time (user + system, seconds) of everything reaped so far to
FILE; SIGTERM goes on to the command. tools/dev/bench/sweep_bench.sh: what Slurm's array tasks
cost in CPU time, which a loaded machine does not stretch as it stretches wall time.
Usage: reaper.py FILE COMMAND [ARGS...]"""
import ctypes
import os
import resource
import signal
import sys

PR_SET_CHILD_SUBREAPER = 36


def dump(*_):
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    with open(sys.argv[1] + ".tmp", "w") as f:
        f.write("%.6f\n" % (r.ru_utime + r.ru_stime))
    os.replace(sys.argv[1] + ".tmp", sys.argv[1])


def main():
    if ctypes.CDLL(None, use_errno=True).prctl(PR_SET_CHILD_SUBREAPER, 1, 0, 0, 0) != 0:
        sys.exit("reaper: prctl(PR_SET_CHILD_SUBREAPER) failed")
    signal.signal(signal.SIGUSR1, dump)
    child = os.fork()
    if child == 0:
        os.execvp(sys.argv[2], sys.argv[2:])
    signal.signal(signal.SIGTERM, lambda *_: os.kill(child, signal.SIGTERM))
    while True:  # every descendant that ends, until none is left
        try:
            os.wait()
        except ChildProcessError:
            break
        except InterruptedError:
            continue
    dump()


if __name__ == "__main__":
    main()
