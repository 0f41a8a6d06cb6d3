"""cases_loops.py - algebraic loops at every scale of their signals (tests/hard/hard.py):
loop_scale.scn's w = S cos(w / S + 0.3 t) for S from 1e3 to 1e-200 (written into the
scene: a scale set by --set after init starts the first solve from the solution at the
default, which may take more than the iteration bound: counted, not wrong), against c =
cos(c + 0.3 t) solved here by Newton to the last digit, times S.

What must hold (rt/loop.c): the loop's residual is judged relative to its signals' own
scale where that is below 1, so every S down to 1e-150 gives the same relative answer
(within 1e-9) with status ok; at 1e-200 products of two signals underflow and the solve
may fail, but a run off by more is never ok."""
import math
import os
import tempfile

from hard import run, HERE

SCALES = ["1e3", "1", "1e-3", "1e-9", "1e-11", "1e-13", "1e-100", "1e-150", "1e-200"]


def exact_c(t):
    c = 0.7
    for _ in range(60):
        c -= (c - math.cos(c + 0.3 * t)) / (1 + math.sin(c + 0.3 * t))
    return c


def extra(s, long):
    for sc in SCALES:
        S = float(sc)
        with open(os.path.join(HERE, "loop_scale.scn")) as f:
            text = f.read().replace("parameters (S = 1)", "parameters (S = %s)" % sc)
        fd, path = tempfile.mkstemp(suffix=".scn", prefix="modrt-loop-")
        with os.fdopen(fd, "w") as f:
            f.write(text)
        try:
            rc, summ, rows = run(s.modrt, path, [])
        finally:
            os.unlink(path)
        err = max((abs(r[1] / S - exact_c(r[0])) for r in rows), default=math.inf)
        s.row("loop_scale S=%s" % sc, "broyden", "0.001", err, summ, rc)
        s.check(rc in (0, 1, 3), "loop_scale S=%s: modrt exit %d" % (sc, rc))
        s.check(rc != 0 or err <= 1e-9,
                "loop_scale S=%s: relative error %.3g with status ok" % (sc, err))
        s.check(S < 1e-150 or (rc == 0 and err <= 1e-9),
                "loop_scale S=%s: status %s, relative error %.3g (a loop at any scale "
                "converges)" % (sc, summ.get("status"), err))
