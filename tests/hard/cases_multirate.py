"""cases_multirate.py - the multirate coupling cases of tests/hard/hard.py: a slow set
extrapolating (or holding) a 10 Hz sine read from a 1 ms set, once integrated
(mr_sine.scn: sensitivity 1) and once through a 50 ms lag (mr_lag.scn: sensitivity 1/T),
over its step and its interpolation scheme, against the closed forms in the scene files.

What must hold (rt/xset.c, docs/multirate.md "Error control"):
  * a run more than ten times the reader's accuracy off never ends "ok": the coupling's
    estimated error (the missed prediction times the reader's sensitivity) is held to
    the reader's accuracy, past RT_XSET_LOST it fails;
  * a run flagged for its coupling is off by at least a tenth of that accuracy (no alarm
    on an accurate answer), and the library's multirate scenes stay ok;
  * the steps that alias (a hold at half the signal's period or at its period: every
    sample is the same, the monitor sees a constant) are what a sampled monitor cannot
    see: listed in the table, their status not asserted (the global error check re-runs
    the scene at half the steps, which catches them)."""
import math
import os
import tempfile

from hard import run, HERE

W = 2 * math.pi * 10      # the signal's angular frequency [rad/s]
T_LAG = 0.05              # mr_lag's time constant [s]
ACC = 1e-3                # the reader's accuracy (RT_ERR_TOL: the scenes declare none)
STEPS = ["0.002", "0.005", "0.01", "0.02", "0.025", "0.05", "0.1"]
SCHEMES = ["extrapolate", "hold", "hermite", "quadratic"]


def x_int(t):
    return (1 - math.cos(W * t)) / W


def x_lag(t):
    a = W * T_LAG
    return (math.sin(W * t) - a * math.cos(W * t) + a * math.exp(-t / T_LAG)) / (1 + a * a)


def aliased(scheme, h):
    """the hold of a sine sampled at a whole number of half periods reads a constant"""
    return scheme == "hold" and abs(h * 20 - round(h * 20)) < 1e-9


def variant(scene, scheme):
    """the scene with the slow set's scheme replaced, in a temporary file"""
    with open(os.path.join(HERE, scene)) as f:
        text = f.read().replace("interpolation (extrapolate)", "interpolation (%s)" % scheme)
    fd, path = tempfile.mkstemp(suffix=".scn", prefix="modrt-mr-")
    with os.fdopen(fd, "w") as f:
        f.write(text)
    return path


def error(rows, h, exact):
    """the largest error at the reader's step instants (its outputs are held between)"""
    e = 0.0
    for r in rows:
        if abs(r[0] / h - round(r[0] / h)) > 1e-6:
            continue
        e = max(e, abs(r[1] - exact(r[0]))) if r[1] == r[1] else math.inf
    return e


def grid(s):
    for scene, exact in (("mr_sine.scn", x_int), ("mr_lag.scn", x_lag)):
        name = scene[:-4]
        for scheme in SCHEMES:
            path = variant(scene, scheme)
            try:
                for h in STEPS:
                    rc, summ, rows = run(s.modrt, path, ["--step", "slow=" + h])
                    err = error(rows, float(h), exact) if rows else math.inf
                    tag = "%s %s" % (name, scheme) + (" (aliased)" if aliased(scheme, float(h))
                                                      else "")
                    s.row(tag, "rk4", h, err, summ, rc)
                    s.check(rc in (0, 1, 3), "%s h=%s: modrt exit %d" % (tag, h, rc))
                    if aliased(scheme, float(h)):
                        continue
                    s.check(rc != 0 or err <= 10 * ACC,
                            "%s h=%s: error %.3g above %g with status ok (xset_est %s)"
                            % (tag, h, err, 10 * ACC, summ.get("xset_est.slow", "-")))
                    s.check(rc == 0 or err >= ACC / 10,
                            "%s h=%s: flagged (%s) with error %.3g, within a tenth of the "
                            "accuracy" % (tag, h, summ.get("status"), err))
            finally:
                os.unlink(path)


def library(s):
    """the library's multirate scenes: accurate, and ok (their coupling estimate below
    their accuracy)"""
    for scene in ("pendulum10_actuated", "lane_change"):
        rc, summ, rows = run(s.modrt, "../../models/scenes/%s.scn" % scene, [])
        s.row(scene, "as shipped", "-", math.nan, summ, rc)
        s.check(rc == 0, "%s: status %s (xset_est %s)" % (
            scene, summ.get("status"), {k: v for k, v in summ.items()
                                        if k.startswith("xset_est")}))


def extra(s, long):
    grid(s)
    library(s)
