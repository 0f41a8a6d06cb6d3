"""cases_loops.py - algebraic loops at every scale of their signals (tests/hard/hard.py):
loop_scale.scn's w = S cos(w / S + 0.3 t) for S from 1e3 to 1e-200 (written into the
scene: a scale set by --set after init starts the first solve from the solution at the
default, which may take more than the iteration bound: counted, not wrong), against c =
cos(c + 0.3 t) solved here by Newton to the last digit, times S.

What must hold (rt/loop.c): the loop's residual is judged relative to its signals' own
scale where that is below 1, so every S down to 1e-150 gives the same relative answer
(within 1e-9) with status ok; at 1e-200 products of two signals underflow and the solve
may fail, but a run off by more is never ok. And an ill-conditioned loop (loop_gain.scn,
a gain of 1 - 1e-9) is never ok more than ten times the accuracy off."""
import math
import os

from hard import run, run_text, HERE

SCALES = ["1e3", "1", "1e-3", "1e-9", "1e-11", "1e-13", "1e-100", "1e-150", "1e-200"]


def exact_c(t):
    c = 0.7
    for _ in range(60):
        c -= (c - math.cos(c + 0.3 * t)) / (1 + math.sin(c + 0.3 * t))
    return c


def lag_gain(t, g=0.999999999, K=1e-9, T=0.1, w=3.0):
    """loop_gain.scn's lag from 0 under K (1 + 0.05 sin w t) / (1 - g)"""
    a = K / (1 - g)
    b = 0.05 * a
    e = math.exp(-t / T)
    return a * (1 - e) + b * (math.sin(w * t) - w * T * math.cos(w * t) + w * T * e) / (1 + (w * T) ** 2)


def ill_conditioned(s):
    rc, summ, rows = run(s.modrt, "loop_gain.scn", [])
    i = summ["columns"].index("L.y") if rows else 0
    err = max((abs(r[i] - lag_gain(r[0])) / (1 + abs(r[i])) for r in rows), default=math.inf)
    s.row("loop_gain g = 1 - 1e-9", "broyden", "0.001", err, summ, rc)
    s.check(rc in (0, 1, 3), "loop_gain: modrt exit %d" % rc)
    s.check(rc != 0 or err <= 1e-2, "loop_gain: error %.3g with status ok" % err)


def gain_jump(s):
    """a loop whose gain jumps after its inverse Jacobian was formed: y = w - e (w - r),
    e from 1 to E at 0.5 s, r = sin t: the torn input is w = sin t for any E != 0. Never ok
    more than ten times the tolerance off (before: E = 1e-10 and 1e-12 left w at its value
    of 0.5 s, 0.43 off, status ok); E = 1e-6 is ok and right"""
    text = ("scene (loop_jump);\nbase tick (1 ms);\nend time (2 s);\n"
            "load system (E) of type (step) from file (\"sources\");\n"
            "load system (R) of type (sine) from file (\"sources\");\n"
            "E.t0 = 0.5; E.y0 = 1; E.y1 = %s;\nR.amp = 1; R.omega = 1;\n"
            "define ss_system (A) with inputs (w, e, r) outputs (y) by { y = w - e * (w - r); };\n"
            "define ss_system (B) with inputs (v) outputs (z) by { z = v; };\n"
            "load system (A) of type (A);\nload system (B) of type (B);\n"
            "connect(A.y, B.v);\nconnect(B.z, A.w);\nconnect(E.y, A.e);\nconnect(R.y, A.r);\n"
            "solve loops by (broyden);\nset (main) method (rk4) step (1 tick);\n"
            "record (B.z);\n")
    for e in ("1e-6", "1e-10", "1e-12"):
        rc, summ, rows = run_text(s.modrt, text % e, [])
        err = max((abs(r[1] - math.sin(r[0])) for r in rows), default=math.inf)
        s.row("a loop whose gain jumps to %s" % e, "broyden", "0.001", err, summ, rc)
        # (a solve's correction is within RT_LOOP_STEP_FACTOR (1000) tolerances (1e-10) of
        # |w| + 1: ten times that is 2e-6)
        s.check(rc in (0, 1, 3) and (rc != 0 or err <= 2e-6), "loop gain jump to %s: exit "
                "%d, error %.3g with status %s" % (e, rc, err, summ.get("status")))
        if e == "1e-6":
            s.check(rc == 0 and err <= 1e-6, "loop gain jump to 1e-6: exit %d, error %.3g"
                    % (rc, err))


def extra(s, long):
    gain_jump(s)
    ill_conditioned(s)
    for sc in SCALES:
        S = float(sc)
        with open(os.path.join(HERE, "loop_scale.scn")) as f:
            text = f.read().replace("parameters (S = 1)", "parameters (S = %s)" % sc)
        rc, summ, rows = run_text(s.modrt, text, [])
        err = max((abs(r[1] / S - exact_c(r[0])) for r in rows), default=math.inf)
        s.row("loop_scale S=%s" % sc, "broyden", "0.001", err, summ, rc)
        s.check(rc in (0, 1, 3), "loop_scale S=%s: modrt exit %d" % (sc, rc))
        s.check(rc != 0 or err <= 1e-9,
                "loop_scale S=%s: relative error %.3g with status ok" % (sc, err))
        s.check(S < 1e-150 or (rc == 0 and err <= 1e-9),
                "loop_scale S=%s: status %s, relative error %.3g (a loop at any scale "
                "converges)" % (sc, summ.get("status"), err))
