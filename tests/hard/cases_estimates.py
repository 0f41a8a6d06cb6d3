"""cases_estimates.py - hard cases of the error estimates, switching right-hand sides,
stalls and the per-set scale (issue 26, classes C, F, G and the scale): each against a
closed-form answer, each failing where its fix is missing. (The work bound of every
step of every run is checked in hard.py's Suite.row.)"""
import math
import os
import subprocess
import tempfile

from cases_global import check
from cases_tev import ORDER
from hard import HERE, REFS, STATUS, at, run, run_text

IMPLICIT = ["beuler", "trap", "sdirk2", "sdirk3", "ros2"]


def on_grid(t, h):
    return abs(t / h - round(t / h)) < 1e-6


def quadrature(s):
    """C: y' = 1 / (t - t1) through its pole and z' = w cos(w t): f of t alone. Past
    the pole no answer exists, so no method may say ok (rk4 said ok with the estimate 0
    on every step)"""
    for m in ("euler", "heun", "bs3", "rk4", "dopri5", "beuler", "sdirk2", "ros2"):
        for h in ("0.01", "0.05"):
            rc, summ, rows = run(s.modrt, "quad_pole.scn", ["--method", "main=" + m,
                                                           "--step", "main=" + h])
            s.row("quadrature through a pole: y(1)", m, h, rows[-1][1] if rows else math.nan,
                  summ, rc)
            s.check(rc != 0, "quad_pole %s %s: through the pole with status ok" % (m, h))


def quad_cos_err(rows, h):
    """largest error of z = sin(w t) and of the lag q at the set's steps"""
    w, T, e = 50.26548245743669, 0.1, 0.0
    for r in rows:
        if on_grid(r[0], h):
            t = r[0]
            q = (math.cos(w * t) + w * T * math.sin(w * t) - math.exp(-t / T)) / (1 + (w * T) ** 2)
            e = max(e, abs(r[1] - math.sin(w * t)), abs(r[2] - q))
    return e


def quad_cos(s):
    """C: z' = w cos(w t) and a lag driven by cos(w t), 8 Hz, at 10 and 20 ms: an answer
    more than 10x the accuracy (1e-3) off may not say ok"""
    for m in ("euler", "heun", "bs3", "rk4", "dopri5") + tuple(IMPLICIT):
        for h in ("0.01", "0.02"):
            rc, summ, rows = run(s.modrt, "quad_cos.scn", ["--method", "main=" + m,
                                                          "--step", "main=" + h])
            err = quad_cos_err(rows, float(h)) if rows else math.inf
            s.row("w cos(w t) and a lag driven by it", m, h, err, summ, rc)
            s.check(rc != 0 or err <= 1e-2, "quad_cos %s %s: error %.3g with status ok"
                    % (m, h, err))


def coulomb(s):
    """F: a block sliding to rest under Coulomb friction (library kind coulomb): stops
    at t = 2/3 s at x = 2/3 m and stays; every method of order >= 2 at 10 ms (ROS2's
    finite-difference Jacobian never straddles the switch: it is a located root)"""
    for m in ("heun", "bs3", "rk4", "dopri5", "trap", "sdirk2", "sdirk3", "ros2"):
        rc, summ, rows = run(s.modrt, "coulomb_stop.scn", ["--method", "main=" + m])
        err = max(abs(rows[-1][1] - 2.0 / 3.0), abs(rows[-1][2])) if rows else math.inf
        stuck = [r[0] for r in rows if r[3] == 0 and on_grid(r[0], 0.01)]
        s.row("coulomb: block sliding to rest, |x - 2/3|", m, "0.01", err, summ, rc)
        s.check(rc == 0 and err < 1e-9, "coulomb %s: x %g, status %s" % (
            m, rows[-1][1] if rows else math.nan, STATUS.get(rc)))
        s.check(stuck and 0.66 < 2.0 / 3.0 <= stuck[0] <= 0.67 + 1e-9,
                "coulomb %s: stuck from the step ending at %s s, analytic 2/3" % (m, stuck[:1]))


def relay_exact(t):
    """x of relay_lag.scn: falls to -1/2 at ln 2, then swings with half period ln 3"""
    t1 = math.log(2)
    if t < t1:
        return math.exp(-t) - 1
    k = int((t - t1) // math.log(3))
    tau = t - t1 - k * math.log(3)
    return 1 - 1.5 * math.exp(-tau) if k % 2 == 0 else -1 + 1.5 * math.exp(-tau)


def relay(s):
    """F: a relay with hysteresis around a first-order lag (library kinds relay, pt1):
    the limit cycle of period 2 ln 3 against its exponentials, within 10x the accuracy,
    and 9 switches in 10 s"""
    for m in ("heun", "bs3", "rk4", "dopri5", "sdirk2", "sdirk3", "ros2"):
        rc, summ, rows = run(s.modrt, "relay_lag.scn", ["--method", "main=" + m])
        err = max((abs(r[1] - relay_exact(r[0])) for r in rows if on_grid(r[0], 0.01)),
                  default=math.inf)
        s.row("relay around a lag: |x - exact|", m, "0.01", err, summ, rc)
        s.check(rc == 0 and err < 1e-2, "relay %s: error %.3g, status %s"
                % (m, err, STATUS.get(rc)))
        s.check(int(summ.get("events", "0").split()[0]) == 9,
                "relay %s: %s switches, 9 expected" % (m, summ.get("events")))


def stall(s):
    """G1: the scaled van der Pol (eps = 1e-6, h = 0.1 ms) through its jump at 0.807 s:
    SDIRK2's half steps settle on a cycle of the method and return the start state step
    after step; each such step is degraded, not a recovered substep"""
    for m in ("sdirk2", "sdirk3", "beuler", "trap"):
        rc, summ, rows = run(s.modrt, "vdp_eps.scn", ["--method", "main=" + m, "--t-end",
                                                      "2", "--set", "V.b=0"])
        still = sum(1 for a, b in zip(rows, rows[1:]) if a[1:] == b[1:] and b[2] != 0)
        deg = int(summ.get("degraded", "0").split()[0])
        s.row("scaled van der Pol: steps left at their start", m, "0.0001", still, summ, rc)
        s.check(still <= 10 or deg >= still, "vdp_eps %s: %d steps returned their start "
                "state, %d degraded" % (m, still, deg))


def scale(s):
    """the scale: Robertson with |e_i| <= 1e-8 + 1e-3 |y_i| declared. The trapezoidal
    rule at 20 and 50 ms leaves y2 6 to 19 % off; in the default norm that passed as
    ok, here it may not"""
    for h in ("0.02", "0.05"):
        rc, summ, rows = run(s.modrt, "robertson_scaled.scn", ["--step", "main=" + h])
        e2 = 0.0
        for ref in REFS[("robertson", "y")]:
            r = at(rows, ref[0])
            if r is not None:
                e2 = max(e2, abs(r[2] - ref[2]) / abs(ref[2]))
        s.row("robertson, accuracy (1e-3, 1e-8): y2 relative", "trap", h, e2, summ, rc)
        s.check(rc != 0 or e2 <= 1e-2, "robertson_scaled trap %s: y2 %.3g off with status "
                "ok" % (h, e2))


def refused(modrt, scene, args=()):
    """runs a scene rt_init must refuse; returns (exit code, stderr)"""
    p = subprocess.run([modrt, "run", os.path.join(HERE, scene), "--csv", os.devnull] +
                       list(args), capture_output=True, text=True, timeout=600)
    return p.returncode, p.stderr.strip()


def alias_lag_exact(t, w=2513.2741228718346, T=0.5, phi=1.0):
    """T y' = sin(w t + phi) - y, y(0) = 0"""
    a, b = 1 / (1 + (w * T) ** 2), -w * T / (1 + (w * T) ** 2)
    c = -(a * math.sin(phi) + b * math.cos(phi))
    return a * math.sin(w * t + phi) + b * math.cos(w * t + phi) + c * math.exp(-t / T)


def aliasing(s):
    """a sine integrated at a step that samples an alias of it (omega h >= pi; at 2 pi
    every stage sees one phase and no estimate or global check can tell: a lag of a 400
    Hz sine read 0.84 where it stays within 8e-4, status ok): refused at init, through
    a gain and across sets too; resolved at omega h = 2.5 (exact to the accuracy); a
    sampled block's own sampling of it is the model's, accepted"""
    for m in ("euler", "heun", "rk4", "dopri5", "trap", "ros2"):
        for h in ("0.01", "0.0025"):
            rc, msg = refused(s.modrt, "alias_lag.scn", ["--method", "main=" + m,
                                                         "--step", "main=" + h])
            s.check(rc == 2 and "W: 2.51e+03 rad/s aliased by set main's step" in msg,
                    "alias_lag %s %s: exit %d, %s" % (m, h, rc, msg))
        # (status ok speaks of each step's local error: ROS2's substeps keep that within
        # the accuracy while their bias adds up to 0.08; `modrt check` says so)
        args = ["--method", "main=" + m, "--step", "main=0.001"]
        rc, summ, rows = check(s.modrt, "alias_lag.scn", args)
        err = max((abs(r[1] - alias_lag_exact(r[0])) for r in rows), default=math.inf)
        s.row("lag of a 400 Hz sine at omega h = 2.5", m, "0.001", err, summ, rc)
        s.check(err <= 1e-2 or rc != 0 or summ.get("global_status") != "ok",
                "alias_lag %s 1 ms: error %.3g, status %s, global %s" % (
                    m, err, summ.get("status"), summ.get("global_status")))
    for scene, where in (("alias_chain.scn", "set main's"), ("alias_split.scn", "set slow's"),
                         ("alias_via.scn", "set slow's"), ("alias_loop.scn", "set main's")):
        rc, msg = refused(s.modrt, scene)
        s.check(rc == 2 and ("aliased by %s step" % where) in msg,
                "%s: exit %d, %s" % (scene, rc, msg))
    # the loop torn at its other input (the blocks declared the other way round)
    with open(os.path.join(HERE, "alias_loop.scn")) as f:
        text = f.read().replace("load system (A) of type (gain);\nload system (B) of type (sum);",
                                "load system (B) of type (sum);\nload system (A) of type (gain);")
    fd, path = tempfile.mkstemp(suffix=".scn", prefix="modrt-alias-")
    with os.fdopen(fd, "w") as f:
        f.write(text)
    try:
        rc, msg = refused(s.modrt, path)
    finally:
        os.unlink(path)
    s.check(rc == 2 and "aliased by set main's step" in msg, "alias_loop, B before A: exit %d, %s"
            % (rc, msg))
    # a sine of amplitude 0 is a constant: nothing to alias
    with open(os.path.join(HERE, "alias_lag.scn")) as f:
        text = f.read().replace("W.amp = 1;", "W.amp = 0;")
    rc, summ, rows = run_text(s.modrt, text, ["--step", "main=0.01"])
    s.check(rc == 0 and rows and abs(rows[-1][1]) < 1e-15,
            "alias_lag amp 0: exit %d" % rc)
    rc, summ, rows = run(s.modrt, "alias_sampled.scn", [])
    e, y = math.exp(-0.01 / 0.5), 0.0
    for k in range(100):
        y = y * e + math.sin(2513.2741228718346 * k * 0.01 + 1) * (1 - e)
    err = abs(rows[-1][1] - y) if rows else math.inf
    s.row("lag of a 400 Hz sine sampled every 10 ms", "rk4", "0.01", err, summ, rc)
    s.check(rc == 0 and err < 1e-8, "alias_sampled: exit %d, error %.3g" % (rc, err))


def nan_guard(s):
    """nan_guard.scn: a NaN inside a condition or limit of a defined system (min of
    sqrt of a negative level) reaches the derivative: counted (nan; an implicit method's
    Newton iteration fails on it), never a finite derivative from an invalid state with
    status ok. Before that, the level to the closed form"""
    for m in ("rk4", "dopri5", "bs3", "sdirk3"):
        rc, summ, rows = run(s.modrt, "nan_guard.scn", ["--method", "main=" + m])
        at1 = [r[1] for r in rows if abs(r[0] - 1.0) < 1e-9]
        err = abs(at1[0] - 0.5) if at1 else math.inf
        s.row("tank run dry, min(sqrt(z), q): level at 1 s; status after 2.5 s", m, "0.01",
              err, summ, rc)
        # (an implicit method's Newton iteration meets the NaN first: degraded, failed)
        s.check(rc != 0 and (m == "sdirk3" or summ.get("nan", "0") != "0") and err < 1e-12,
                "nan_guard %s: exit %d, status %s, nan %s, level at 1 s off by %.3g" % (
                    m, rc, summ.get("status"), summ.get("nan"), err))


GROWING = """scene (growing_mode) doc ("a mode that turns unstable at 0.2 s");
base tick (10 ms);
end time (0.6 s);
define ss_system (F) with outputs (yo) parameters (t1 = 0.2, lam = 50) states (y = 0.001) by {
    yo = y;
    der(y) = if(t < t1, -1000 * (y - 0.001), lam * y);
};
load system (S) of type (F);
set (main) method (%s) step (%s) jacobian (%d);
record (S.yo);
"""

PAIR = """scene (growing_pair) doc ("x1' = lam x1 driving x2' = 1000 x1 - x2");
base tick (10 ms);
end time (0.4 s);
define ss_system (F) with outputs (y1, y2) parameters (lam = 50) states (a = 0.000001, b = 0) by {
    y1 = a;  y2 = b;
    der(a) = lam * a;
    der(b) = 1000 * a - b;
};
load system (S) of type (F);
set (main) method (%s) step (10 ticks);
record (S.y1, S.y2);
"""


def damped(summ):
    """the summary's damped count (\"N (first at tick T)\"), -1 where it has none"""
    v = summ.get("damped")
    return int(v.split()[0]) if v else -1


def growing(s):
    """A mode that turns unstable: y = 0.001 held by a stiff mode until 0.2 s, then
    y' = 50 y, so y(0.6) = 0.001 e^20 = 4.85e5. An implicit method at 0.1 s (h lambda = 5,
    past the pole 1 / gamma of its stability function) decays or flips it; its estimate,
    filtered by M^-1 or from a companion that passes through M, read it small: backward
    Euler, SDIRK3, trap and ROS2 said ok (y(0.6) 1e-3 and less). Every method at 0.1 and
    0.01 s must be within 1 % or not say ok. The pair x1' = 50 x1, x2' = 1000 x1 - x2 from
    x1 = 1e-6 (x1(0.4) = 1e-6 e^20) has a row exchange in M's factors: the same; with
    lam = -50 (stable, the same exchange) no step may count damped."""
    for m in IMPLICIT:
        for h in ("0.1", "0.01"):
            for jac in ((1, 64) if m == "ros2" else (1,)):
                rc, summ, rows = run_text(s.modrt, GROWING % (m, h, jac), [])
                exact = 0.001 * math.exp(20)
                err = abs(rows[-1][1] - exact) / exact if rows else math.inf
                s.row("a mode turning unstable, jacobian %d (relative error)" % jac, m, h,
                      err, summ, rc)
                s.check(rc in (1, 3) or err <= 0.01, "growing mode, %s at %s s, jacobian %d: "
                        "y(0.6) %.3g for %.3g with status %s" % (
                            m, h, jac, rows[-1][1] if rows else math.nan, exact,
                            summ.get("status")))
                # past the pole (h lambda = 5 > 1 / gamma for every method): counted as such
                s.check(h != "0.1" or damped(summ) > 0 or err <= 0.01,
                        "growing mode, %s at 0.1 s, jacobian %d: no damped step (%s)" % (
                            m, jac, summ.get("status")))
        rc, summ, rows = run_text(s.modrt, PAIR % m, [])
        exact = 1e-6 * math.exp(20)
        err = abs(rows[-1][1] - exact) / exact if rows else math.inf
        s.row("x1' = 50 x1 driving x2 (relative error of x1)", m, "0.1", err, summ, rc)
        s.check(damped(summ) > 0 or err <= 0.01, "growing pair, %s: x1(0.4) %.3g for %.3g, "
                "no damped step (status %s)" % (m, rows[-1][1] if rows else math.nan, exact,
                                               summ.get("status")))
        rc, summ, rows = run_text(s.modrt, PAIR % m, ["--set", "S.lam=-50"])
        s.row("x1' = -50 x1 driving x2: damped steps", m, "0.1", damped(summ), summ, rc)
        s.check(damped(summ) == 0, "stable pair, %s: damped %s (status %s)" % (
            m, summ.get("damped"), summ.get("status")))


SWITCH = """scene (switch_in_step) doc ("x' jumps from 0 to J where y = t passes c");
base tick (1 ms);
end time (0.53 s);
define ss_system (Sw) with outputs (xo, yo) parameters (J = 100, c = 0.502)
    states (x = 0, y = 0) by {
    xo = x;  yo = y;
    der(y) = 1;
    der(x) = if(y > c, J, 0);
};
load system (S) of type (Sw);
set (main) method (%s) step (10 ticks);
record (S.xo, S.yo);
"""

KV = """scene (kelvin_voigt) doc ("a ball on a spring-damper ground, contact as a switch");
base tick (0.1 ms);
end time (1.2 s);
define ss_system (Ball) with outputs (zo, vo) parameters (g = 9.81, k = 10000, c = 20)
    states (z = 1, v = 0) by {
    zo = z;  vo = v;
    der(z) = v;
    der(v) = -g + if(z < 0, -k * z - c * v, 0);
};
load system (B) of type (Ball);
set (main) method (%s) step (10 ticks);
record (B.zo, B.vo);
"""


def kv_exact(t, g=9.81, k=1e4, c=20.0):
    """z, v of KV: free fall from 1 m, then at z = 0 the damped oscillator
    z'' + c z' + k z = -g until z returns to 0, then flight again (piecewise closed form;
    the contact's end by bisection of its closed form)"""
    def contact(z0, v0, s):
        zs, a = -g / k, c / 2
        wd = math.sqrt(k - a * a)
        A = z0 - zs
        B = (v0 + a * A) / wd
        e = math.exp(-a * s)
        cs, sn = math.cos(wd * s), math.sin(wd * s)
        return zs + e * (A * cs + B * sn), e * (-a * (A * cs + B * sn) + wd * (B * cs - A * sn))
    t0, z, v = 0.0, 1.0, 0.0
    while True:
        s = (v + math.sqrt(v * v + 2 * g * z)) / g  # flight to z = 0
        if t <= t0 + s:
            return z + v * (t - t0) - g * (t - t0) ** 2 / 2, v - g * (t - t0)
        t0, v, z = t0 + s, v - g * s, 0.0
        lo = 1e-6  # the contact: z < 0 until it returns to 0
        while contact(z, v, lo + 1e-5)[0] < 0:
            lo += 1e-5
        hi = lo + 1e-5
        for _ in range(200):
            mid = (lo + hi) / 2
            lo, hi = (mid, hi) if contact(z, v, mid)[0] < 0 else (lo, mid)
        if t <= t0 + hi:
            return contact(z, v, t - t0)
        z, v = 0.0, contact(z, v, hi)[1]
        t0 += hi


SWITCH_H = """scene (switch_h) doc ("a comparison of h: no switch");
base tick (1 ms);
end time (0.1 s);
define ss_system (P) with outputs (o) states (x = 0) by {
    o = x;
    der(x) = if(h > 0.005, 1, 2);
};
load system (B) of type (P);
set (main) method (rk4) step (10 ticks);
record (B.o);
"""

SWITCH_BESIDE = """scene (switch_beside) doc ("a switch beside a held reader");
base tick (1 ms);
end time (1 s);
define ss_system (Ramp) with outputs (p) states (q = 0) by {
    p = q;
    der(q) = 1;
};
define ss_system (Int) with inputs (u) outputs (xo) states (x = 0) by {
    xo = x;
    der(x) = u;
};
define ss_system (Other) with outputs (zo) states (z = 1) by {
    zo = z;
    der(z) = if(z > 2, 0, -z);
};
load system (R) of type (Ramp);
load system (A) of type (Int);
load system (B) of type (Other);
connect(R.p, A.u);
set (slow) method (rk4) step (10 ticks) members (R);
set (fast) method (rk4) step (1 tick) members (A, B) interpolation (hold);
record (A.xo, B.zo);
"""

SWITCH_INF = """scene (switch_inf) doc ("sides overflowing to one infinity");
base tick (1 ms);
end time (0.1 s);
define ss_system (P) with outputs (o) parameters (big = 1e308) states (x = 0.5, y = 1, z = 0)
    by {
    o = z;
    der(x) = 10;
    der(y) = 0;
    der(z) = if(x * big * 10 > y * big * 10, 1, 0);
};
load system (B) of type (P);
set (main) method (rk4) step (1 tick);
record (B.o);
"""

SWITCH_TABLE = """scene (switch_table) doc ("an output table integrated by another block");
base tick (1 ms);
end time (1 s);
define ss_system (P) with outputs (yo, tab) states (y = 0) by {
    yo = y;
    tab = if(y < 0.15, 0, if(y < 0.25, 1, if(y < 0.35, 2, if(y < 0.45, 3, if(y < 0.55, 4, 5)))));
    der(y) = 1;
};
define ss_system (I) with inputs (u) outputs (z) states (s = 0) by { z = s; der(s) = u; };
load system (B) of type (P);
load system (Z) of type (I);
connect(B.tab, Z.u);
set (main) method (rk4) step (100 ticks);
record (Z.z);
"""

# x' = u, u a comparator (a define without states) of another block's output r = t
# against 0.503: x(1) = 1 - 0.503
SWITCH_COMPARATOR = """scene (switch_comparator) doc ("a comparator without states, integrated");
base tick (10 ms);
end time (1 s);
define ss_system (R) with outputs (r) states (q = 0) by { r = q; der(q) = 1; };
define ss_system (C) with inputs (u) outputs (y) parameters (L = 0.503) by {
    y = if(u > L, 1, 0);
};
define ss_system (I) with inputs (u) outputs (z) states (s = 0) by { z = s; der(s) = u; };
load system (R) of type (R);
load system (C) of type (C);
load system (Z) of type (I);
connect(R.r, C.u);
connect(C.y, Z.u);
set (main) method (rk4) step (1 tick);
record (Z.z);
"""


SWITCH_REST = """scene (switch_rest) doc ("sides that rest on each other, then part");
base tick (1 ms);
end time (2 s);
define ss_system (B) with outputs (yv, yd) parameters (b = 0.5537, c = 2)
    states (y = 0, x = 0, v = 0, p = 0, w = 1) by {
    yv = v; yd = p;
    let pen = max(p - b, 0);
    der(y) = 1;
    der(x) = if(y > b, 1, 0);
    der(v) = if(x > 0, 1, 0);
    der(p) = w;
    der(w) = if(pen > 0, -c * w, 0);
};
load system (P) of type (B);
set (main) method (%s) step (0.1 s);
record (P.yv, P.yd);
"""


def located_switch_rest(s):
    """H: sides that are equal over a while and then part (a state resting on its level
    until another switch starts it; a clipped value against its clip level): the switch
    where they part is a crossing too. A valve x' = [y > b] opening v' = [x > 0]:
    v(2) = 2 - b; a damper acting where max(p - b, 0) > 0 on p' = w, w(0) = 1:
    p(2) = b + (1 - exp(-c (2 - b))) / c. rk4, dopri5, sdirk3 and ros2 at 0.1 s, status
    ok, within the accuracy (1e-3 (1 + |value|); rk4 1e-6, ros2 3.7e-4, its own order at
    c h = 0.2) (before: the switch a step late, v(2) 1.4 for 1.4463, p(2) 0.044 off,
    status ok and modrt check ok; audit 10)"""
    for m in ("rk4", "dopri5", "sdirk3", "ros2"):
        rc, summ, rows = run_text(s.modrt, SWITCH_REST % m, [])
        b, c = 0.5537, 2.0
        want = (2 - b, b + (1 - math.exp(-c * (2 - b))) / c)
        err = max(abs(rows[-1][1] - want[0]), abs(rows[-1][2] - want[1])) if rows else math.inf
        s.row("switches where resting sides part: v(2), p(2)", m, "0.1", err, summ, rc)
        s.check(rc == 0 and err <= 2e-3, "resting sides %s: v(2) %.6g for %.6g, p(2) %.6g "
                "for %.6g, status %s" % (m, rows[-1][1] if rows else math.nan, want[0],
                                         rows[-1][2] if rows else math.nan, want[1],
                                         summ.get("status")))


def located_switch_limits(s):
    """H: what stays a plain comparison: one of h, itself or through lets (x' = 1 at
    h = 10 ms: x(0.1) = 0.1; before the reviews 0.2, status ok); a switch beside a held reader keeps the set's
    step-end hold (A.x(1) = 0.495 less rk4's hold error, 0.4950117 as without the switch;
    0.4951667 before the review); 23 switches in one define compile and run (the 22nd
    was refused before the review: each added statement's stack depth was kept); sides
    that both overflow to +inf compare as 0 with status ok (their root by its sign, not
    inf - inf: 100 NaN counted before)"""
    for body in ("der(x) = if(h > 0.005, 1, 2);", "let hh = 2 * h;\n    let h2 = hh;\n"
                 "    der(x) = if(h2 > 0.01, 1, 2);"):
        rc, summ, rows = run_text(s.modrt, SWITCH_H.replace(
            "der(x) = if(h > 0.005, 1, 2);", body), [])
        err = abs(rows[-1][1] - 0.1) if rows else math.inf
        s.row("a comparison of h%s, x(0.1)" % (" through lets" if "let" in body else ""),
              "rk4", "0.01", err, summ, rc)
        s.check(rc == 0 and err <= 1e-12, "comparison of h (%s): x(0.1) off by %.3g "
                "(status %s)" % (body, err, summ.get("status")))
    rc, summ, rows = run_text(s.modrt, SWITCH_INF, [])  # inf > inf is 0: z stays 0
    err = abs(rows[-1][1]) if rows else math.inf
    s.row("a switch of sides at one infinity: z(0.1)", "rk4", "0.001", err, summ, rc)
    s.check(rc == 0 and err == 0, "switch of infinite sides: z(0.1) %.3g, status %s (its "
            "root inf - inf is NaN unless taken by sign)" % (err, summ.get("status")))
    rc, summ, rows = run_text(s.modrt, SWITCH_BESIDE, [])
    err = abs(rows[-1][1] - 0.4950116666666667) if rows else math.inf
    s.row("a switch beside a held reader: A.x(1) against the hold's", "rk4", "0.001", err,
          summ, rc)
    s.check(rc == 0 and err <= 1e-9, "switch beside a held reader: A.x(1) %.10g (status %s)"
            % (rows[-1][1] if rows else math.nan, summ.get("status")))
    lets = "".join("    let a%d = a%d + if(x > %g, 1, 0);\n" % (i, i - 1, 0.03 * i)
                   for i in range(1, 24))
    text = ("scene (many_switches) doc (\"23 switches\");\nbase tick (1 ms);\n"
            "end time (1 s);\ndefine ss_system (L) with outputs (o) states (x = 0) by {\n"
            "    o = x;\n    let a0 = 0;\n%s    der(x) = 1 + 0 * a23;\n};\n"
            "load system (B) of type (L);\nset (main) method (rk4) step (1 tick);\n"
            "record (B.o);\n" % lets)
    rc, summ, rows = run_text(s.modrt, text, [])
    s.row("23 switches in one define: events", "rk4", "0.001", float(
        summ.get("events", "0").split()[0]), summ, rc)
    s.check(rc == 0 and summ.get("events", "").split()[:1] == ["23"], "23 switches: exit %d, "
            "events %s, status %s" % (rc, summ.get("events"), summ.get("status")))


def located_switch(s):
    """H: a derivative that jumps where a state passes a level, written as a comparison
    (no when): x' = 0 until y = t passes c, then J = 100, x(0.53) = J (0.53 - c) exactly
    for every method at 10 ms, c at fractions 0.2, 0.25, 0.51 and 0.9 of the step, status
    ok (before: SDIRK3 3.0 for 2.8 and SDIRK2 3.0 for 2.9 with estimates of 7e-17, dopri5
    0.292 for 0.28 with J = 20, status ok). A ball on a spring-damper ground (contact as
    if(z < 0, ...)) against its piecewise closed form at the step ends: dopri5 and rk4 at
    1 ms within 10x the accuracy (before: dopri5 off by its whole velocity at the first
    impact, status ok)"""
    for m in sorted(ORDER):
        for c in (0.502, 0.5025, 0.5051, 0.509):
            rc, summ, rows = run_text(s.modrt, SWITCH % m, ["--set", "S.c=%r" % c])
            exact = 100 * (0.53 - c)
            err = abs(rows[-1][1] - exact) if rows else math.inf
            s.row("jump of x' where y passes %g: x(0.53)" % c, m, "0.01", err, summ, rc)
            s.check(rc == 0 and err <= 1e-9 * exact, "switch %s c=%g: x(0.53) %.12g for "
                    "%.12g, status %s" % (m, c, rows[-1][1] if rows else math.nan, exact,
                                         summ.get("status")))
    for m in ("dopri5", "rk4"):
        rc, summ, rows = run_text(s.modrt, KV % m, [])
        err = max((max(abs(r[1] - z) / (1 + abs(z)), abs(r[2] - v) / (1 + abs(v)))
                   for r in rows if on_grid(r[0], 1e-3) for z, v in [kv_exact(r[0])]),
                  default=math.inf)
        s.row("ball on a spring-damper ground: relative error at step ends", m, "0.001",
              err, summ, rc)
        s.check(rc == 0 and err <= 1e-2, "kelvin-voigt %s: error %.3g, status %s" % (
            m, err, summ.get("status")))


def output_switches(s):
    """H: a comparison in an output is a located switch, also in a define without states:
    the block that integrates the output reads one smooth branch per step part. An output
    table of y = t with levels between the steps of 0.1 s, integrated by another block:
    z(1) = 0.1 (1 + 2 + 3 + 4) + 0.45 * 5 = 3.25 within 1e-12, 5 events, status ok, every
    method (before: no event, z(1) off by up to 0.05 with status ok under rk4); a
    comparator without states of another block's output t against 0.503 at 10 ms:
    z(1) = 0.497 (before 0.4983, status ok)"""
    for m in ("heun", "bs3", "rk4", "dopri5", "ros2", "sdirk3"):
        rc, summ, rows = run_text(s.modrt, SWITCH_TABLE, ["--method", "main=" + m])
        err = abs(rows[-1][1] - 3.25) if rows else math.inf
        s.row("an output table integrated by another block: z(1)", m, "0.1", err, summ, rc)
        s.check(rc == 0 and err <= 1e-12 and summ.get("events", "").split()[:1] == ["5"],
                "output table %s: z(1) off by %.3g, events %s, status %s" % (
                    m, err, summ.get("events"), summ.get("status")))
    for m in ("heun", "rk4", "dopri5"):
        rc, summ, rows = run_text(s.modrt, SWITCH_COMPARATOR, ["--method", "main=" + m])
        err = abs(rows[-1][1] - 0.497) if rows else math.inf
        s.row("a comparator without states, integrated: z(1)", m, "0.01", err, summ, rc)
        s.check(rc == 0 and err <= 1e-12, "comparator %s: z(1) off by %.3g, status %s" % (
            m, err, summ.get("status")))


def floor_time(s):
    """H: a floor of t, floor(a t + b), jumps where a t + b is an integer: each jump is a
    time event, so a step ends a part there and every stage of a part reads one stair.
    x' = J min(floor(t / c), 1) (audit 14: dopri5 at 100 ms, c from 0.057 to 0.065,
    4 to 19 times its tolerance off with run and check ok; x(0.3) = J (0.3 - c)),
    x' = floor(-t / 0.07 + 5) (falling, x(1) = -2.65), x' = 10 floor(t + 0.58) (x(1) = 5.8):
    x' = max(floor((t - 10) / 0.03), 0) (x(10.2) = 0.57: a part ending a rounding before
    a jump, u = 0.99999999999997868, skipped the stair while its jump was taken as now's,
    0.600 with status ok, in the review), exact to 1e-12 by every method; over a let of
    parameters, 3 min(floor(t / P), 1) with P = 2 T0 (audit 14c: dopri5 8.6 times its
    tolerance off, run and check ok), exact; a staircase
    finer than a step's parts (floor(t / 0.003) at 100 ms) is never ok; a counter of
    samples in an output, n = floor(t / 0.001) at 10 ms steps, stays plain: n(1) = 1000,
    status ok"""
    text = ("scene (floor_t);\nbase tick (10 ms);\nend time (%s s);\n"
            "define ss_system (Q) with outputs (y) states (x = 0) by {\n    y = x;\n"
            "    der(x) = %s;\n};\nload system (P) of type (Q);\n"
            "set (main) method (rk4) step (10 ticks);\nrecord (P.y);\n")
    cases = [("3 * min(floor(t / %g), 1)" % c, 0.3, 3 * (0.3 - c))
             for c in (0.057, 0.06, 0.064, 0.065)]
    cases += [("floor(-t / 0.07 + 5)", 1, -2.65), ("10 * floor(t + 0.58)", 1, 5.8),
              ("max(floor((t - 10) / 0.03), 0)", 10.2, 0.57)]
    for der, t_end, exact in cases:
        for m in ("heun", "bs3", "rk4", "dopri5", "ros2", "sdirk3"):
            rc, summ, rows = run_text(s.modrt, text % (t_end, der), ["--method", "main=" + m])
            err = abs(rows[-1][1] - exact) if rows else math.inf
            s.row("x' = %s: x(%g)" % (der, t_end), m, "0.1", err, summ, rc)
            s.check(rc == 0 and err <= 1e-12 * (1 + abs(exact)), "floor of t %s, %s: x(%g) "
                    "off by %.3g, status %s" % (der, m, t_end, err, summ.get("status")))
    rc, summ, rows = run_text(s.modrt, text % (1, "floor(t / 0.003)"), [])
    s.row("x' = floor(t / 0.003): parts", "rk4", "0.1", rc, summ, rc)
    s.check(rc != 0, "a staircase finer than the parts: status %s" % summ.get("status"))
    let = text.replace("states (x = 0) by {", "parameters (T0 = 0.0325) states (x = 0) by {\n"
                       "    let P = 2 * T0;")
    for m in ("rk4", "dopri5"):
        rc, summ, rows = run_text(s.modrt, let % (1, "3 * min(floor(t / P), 1)"),
                                  ["--method", "main=" + m])
        err = abs(rows[-1][1] - 3 * (1 - 0.065)) if rows else math.inf
        s.row("x' = 3 min(floor(t / P), 1), P a let of parameters: x(1)", m, "0.1", err, summ,
              rc)
        s.check(rc == 0 and err <= 1e-12, "floor of t over a let %s: x(1) off by %.3g, status "
                "%s" % (m, err, summ.get("status")))
    counter = text.replace("    y = x;", "    y = floor(t / 0.001);").replace(
        "step (10 ticks)", "step (1 tick)")
    rc, summ, rows = run_text(s.modrt, counter % (1, "1"), [])
    n = rows[-1][1] if rows else math.nan
    s.row("an output counter n = floor(t / 0.001): n(1)", "rk4", "0.01", abs(n - 1000), summ,
          rc)
    s.check(rc == 0 and n == 1000, "output counter: n(1) %s, status %s" % (n, summ.get("status")))


def abs_split(s):
    """H: a comparison of abs(e) is two, e's and -e's: abs(z - zl) < w, a layer of 2 mm a
    falling body passes in 0.2 ms with damping k v inside it, at steps of 5 to 20 ms. As
    one comparison its root w - |z - zl| is a tent the step crosses through and back
    unseen (audit 14: free fall, z(1) 0.68 off with run and check ok); split, each side's
    root crosses and is located. z(1) from the closed form (free fall to zl + w, the lag
    v' = -g - k v to zl - w by Newton, free fall to 1 s) within 1e-5 (the tolerance 4e-3),
    2 events, status ok (bs3 at 20 ms doubtful: its estimate of the part after the layer);
    the same for `>`, for the mirrored `w > abs(z - zl)`, and for max(z - zl, zl - z) < w
    and min(zl - z, z - zl) > -w (split the same way). A pulse of t, 100 over
    |t - ts| < w = 2 ms inside a 50 ms step, written max(t - ts, ts - t) < w: x(1) = 0.4
    (audit 14: 0, run and check ok), the halves two time events; the same written with the
    kink wrapped once by a fixed operand, abs(t - ts) - w < 0, 2 * abs(t - ts) < 2 * w,
    w - abs(t - ts) > 0 (audit 14c: 0, run and check ok), and the layer as
    abs(z - zl) - w < 0"""
    g, zl, w, k = 9.81, 0.5, 0.001, 500.0
    t1 = math.sqrt(2 * (1 - (zl + w)) / g)
    v1, z1 = -g * t1, zl + w
    tau = 2e-4
    for _ in range(50):
        tau -= (z1 - g / k * tau + (v1 + g / k) * (1 - math.exp(-k * tau)) / k - (zl - w)) / (
            -g / k + (v1 + g / k) * math.exp(-k * tau))
    v2, rest = -g / k + (v1 + g / k) * math.exp(-k * tau), 1 - t1 - tau
    exact = zl - w + v2 * rest - g / 2 * rest * rest
    for form in ("if(abs(z - zl) < w, k * v, 0)", "if(abs(z - zl) > w, 0, k * v)",
                 "if(w > abs(z - zl), k * v, 0)", "if(max(z - zl, zl - z) < w, k * v, 0)",
                 "if(min(zl - z, z - zl) > -w, k * v, 0)", "if(abs(z - zl) - w < 0, k * v, 0)"):
        text = ("scene (layer);\nbase tick (0.1 ms);\nend time (1 s);\n"
                "define ss_system (B) with outputs (zo) parameters (g = 9.81, zl = 0.5, "
                "w = 0.001, k = 500) states (z = 1, v = 0) by {\n    zo = z;\n"
                "    der(z) = v;\n    der(v) = -g - %s;\n};\nload system (P) of type (B);\n"
                "set (main) method (rk4) step (100 ticks);\nrecord (P.zo);\n" % form)
        for m, step in (("rk4", "0.02"), ("rk4", "0.005"), ("dopri5", "0.01"), ("bs3", "0.02")):
            rc, summ, rows = run_text(s.modrt, text, ["--method", "main=" + m,
                                                      "--step", "main=" + step])
            err = abs(rows[-1][1] - exact) if rows else math.inf
            s.row("a layer %s passed: z(1)" % form, m, step, err, summ, rc)
            s.check(rc in (0, 3) and err <= 1e-5 and summ.get("events", "").split()[:1] == ["2"],
                    "layer %s, %s at %s: z(1) off by %.3g, events %s, status %s" % (
                        form, m, step, err, summ.get("events"), summ.get("status")))
    pulse = ("scene (pulse);\nbase tick (1 ms);\nend time (1 s);\n"
             "define ss_system (P) with outputs (y) parameters (ts = 0.4537, w = 0.002) "
             "states (x = 0) by {\n    y = x;\n    der(x) = if(max(t - ts, ts - t) < w, 100, 0);"
             "\n};\nload system (B) of type (P);\nset (main) method (rk4) step (50 ticks);\n"
             "record (B.y);\n")
    for form in ("max(t - ts, ts - t) < w", "abs(t - ts) - w < 0", "2 * abs(t - ts) < 2 * w",
                 "w - abs(t - ts) > 0"):
        for m in ("rk4", "dopri5", "sdirk3"):
            rc, summ, rows = run_text(s.modrt, pulse.replace("max(t - ts, ts - t) < w", form),
                                      ["--method", "main=" + m])
            err = abs(rows[-1][1] - 0.4) if rows else math.inf
            s.row("a pulse %s inside a step: x(1)" % form, m, "0.05", err, summ, rc)
            s.check(rc == 0 and err <= 1e-12, "pulse window %s %s: x(1) off by %.3g, status %s"
                    % (form, m, err, summ.get("status")))


def hidden_oscillation(s):
    """H: an undamped stiff oscillation an L-stable method wipes out: x'' = -w^2 x - 2 z w x',
    w = 1e4 (1.6 kHz), x(0) = 0, v(0) = 0.3, at 20 ms. Undamped (z = 0, the library
    oscillator) and lightly damped (z = 1e-3, h Re lambda = -0.2) the exact v keeps its
    amplitude while ROS2, SDIRK2, SDIRK3 and backward Euler return v near 0 from the first
    step: never ok (audit 14: ROS2 and SDIRK3 status ok, their estimates filtered by the
    iteration matrix 1e5 times below the error; modrt check ok). Strongly damped (z = 0.5:
    h Re lambda = -100, the mode gone within the step) ROS2's and SDIRK3's runs are right,
    v(1) within 1e-12 of 0, and ok: no alarm where the filter is right. (At z = 1e-3 the
    mode has decayed by e^-10 at 1 s: the error shown is v(1)'s; the run was 0.3 off over
    its first 0.1 s)"""
    text = ("scene (stiff_osc);\nbase tick (1 ms);\nend time (1 s);\n"
            "define ss_system (O) with outputs (xo, vo) parameters (w = 10000, z = %s) "
            "states (x = 0, v = 0.3) by {\n    xo = x;\n    vo = v;\n    der(x) = v;\n"
            "    der(v) = -w * w * x - 2 * z * w * v;\n};\nload system (A) of type (O);\n"
            "set (main) method (ros2) step (20 ticks);\nrecord (A.xo, A.vo);\n")
    lib = ("scene (stiff_lib);\nbase tick (1 ms);\nend time (1 s);\n"
           "load system (O) of type (oscillator);\nO.omega = 10000;\nO.x = 0;\nO.v = 0.3;\n"
           "set (main) method (ros2) step (20 ticks);\nrecord (O.x, O.v);\n")
    for m in ("ros2", "sdirk2", "sdirk3", "beuler"):
        for what, scene in (("undamped, the library oscillator", lib),
                            ("undamped", text % "0"), ("z = 1e-3", text % "0.001")):
            rc, summ, rows = run_text(s.modrt, scene, ["--method", "main=" + m])
            v = rows[-1][2] if rows else math.nan
            err = abs(v - 0.3 * math.cos(1e4) * (math.exp(-0.001 * 1e4) if "1e-3" in what
                                                   else 1))
            s.row("a stiff oscillation (%s) damped by the method: v(1)" % what, m, "0.02",
                  err, summ, rc)
            s.check(rc != 0, "hidden oscillation %s, %s: v(1) %.3g (%.3g off), status %s" % (
                what, m, v, err, summ.get("status")))
    for m in ("ros2", "sdirk3"):  # (SDIRK2's and backward Euler's estimates flag it anyway)
        rc, summ, rows = run_text(s.modrt, text % "0.5", ["--method", "main=" + m])
        v = rows[-1][2] if rows else math.nan
        s.row("a stiff oscillation, z = 0.5, gone within the step: v(1)", m, "0.02", abs(v),
              summ, rc)
        s.check(rc == 0 and abs(v) <= 1e-12, "damped stiff oscillation %s: v(1) %.3g, status "
                "%s" % (m, v, summ.get("status")))


def located_switch_review(s):
    """H: a switch whose side holds a truth value inside it but is none itself,
    x' = if(if(x > 0, x, -x) > 0.5, 1, 3) from -1: located where |x| = 0.5 (x(2) = 5/3
    exactly, every explicit method at 10 ms, status ok; before, the outer comparison
    stayed plain: 1 event, errest); 65 comparisons in a let nothing reads, and a
    comparison of a let of parameters in a define of 64 states, compile and run (refused
    for a while: the limit counted unread and fixed comparisons)"""
    text = ("scene (nested_switch);\nbase tick (10 ms);\nend time (2 s);\n"
            "define ss_system (S) with outputs (o) states (x = -1) by {\n    o = x;\n"
            "    der(x) = if(if(x > 0, x, -x) > 0.5, 1, 3);\n};\n"
            "load system (A) of type (S);\nset (main) method (rk4) step (1 tick);\n"
            "record (A.o);\n")
    for m in ("heun", "bs3", "rk4", "dopri5"):
        rc, summ, rows = run_text(s.modrt, text, ["--method", "main=" + m])
        err = abs(rows[-1][1] - 5.0 / 3.0) if rows else math.inf
        s.row("a switch of |x| = 0.5 (a truth value inside a side): x(2)", m, "0.01", err,
              summ, rc)
        s.check(rc == 0 and err <= 1e-9, "nested switch %s: x(2) off by %.3g (status %s)"
                % (m, err, summ.get("status")))
    unread = " + ".join("if(x > %g, 1, 0)" % (0.01 * i) for i in range(1, 66))
    states = ", ".join("s%d = 0" % i for i in range(1, 64))
    ders = "".join("    der(s%d) = 0;\n" % i for i in range(1, 64))
    for what, body, decl in (
            ("65 comparisons in an unread let", "    let a = %s;\n    o = x;\n"
             "    der(x) = 1;\n" % unread, "x = 0"),
            ("a let of parameters compared, 64 states", "    let k = 2 * p;\n    o = x;\n"
             "    der(x) = if(k > 1, 1, 2);\n%s" % ders, "x = 0, " + states)):
        text = ("scene (limits);\nbase tick (10 ms);\nend time (1 s);\n"
                "define ss_system (S) with outputs (o) parameters (p = 2) states (%s) by "
                "{\n%s};\nload system (A) of type (S);\n"
                "set (main) method (rk4) step (1 tick);\nrecord (state A.x);\n"
                % (decl, body))
        rc, summ, rows = run_text(s.modrt, text, [])
        err = abs(rows[-1][1] - 1.0) if rows else math.inf
        s.row(what + ": x(1)", "rk4", "0.01", err, summ, rc)
        s.check(rc == 0 and err <= 1e-12, "%s: exit %d, x(1) off by %.3g" % (what, rc, err))


def nan_lanes(s):
    """H: a derivative that turns NaN in any one of 1 to 9 states of a set, whatever its
    place among them (the step's norm takes four states at a time, rt/step.c): counted
    (nan), the set's state kept finite, never ok"""
    for n in range(1, 10):
        for j in range(n):
            states = ", ".join("s%d = 1" % i for i in range(n))
            ders = "".join("    der(s%d) = %s;\n" % (i, "if(t > 0.5, (s0 - s0) / (s0 - s0), 0)"
                                                     if i == j else "0") for i in range(n))
            text = ("scene (nan_lanes);\nbase tick (10 ms);\nend time (1 s);\n"
                    "define ss_system (S) with outputs (o) states (%s) by {\n    o = 0;\n%s};\n"
                    "load system (A) of type (S);\nset (main) method (rk4) step (1 tick);\n"
                    "record (state A.s%d);\n" % (states, ders, j))
            rc, summ, rows = run_text(s.modrt, text, [])
            last = rows[-1][1] if rows else math.nan
            s.check(rc != 0 and summ.get("nan", "0").split()[0] != "0" and last == last,
                    "NaN in state %d of %d: exit %d, nan %s, s%d(1) = %g" % (j, n, rc,
                                                                           summ.get("nan"), j, last))


def dirk_start(s):
    """H: SDIRK has no stage at its step's start: a jump of the derivative inside
    [t, t + c_1 h) reaches every stage and the first companion alike. An output's
    comparison integrated (z' = if(x > c, 10, 0), x = t: z(2) = 10 (2 - c); a located
    switch since output_switches, the case stays for a kind's output) and a floor
    of t (x' = 10 floor(t + 0.58): x(1) = 5.8), 100 ms steps: a run more than twice its
    tolerance off is never ok (before: SDIRK3 0.2 off, estimate 1e-16, status ok)"""
    out = ("scene (dirk_out);\nbase tick (100 ms);\nend time (2 s);\n"
           "define ss_system (A) with outputs (y) parameters (c = 1.02) states (x = 0) by {\n"
           "    y = if(x > c, 10, 0);\n    der(x) = 1;\n};\n"
           "define ss_system (I) with inputs (u) outputs (z) states (s = 0) by {\n"
           "    z = s;\n    der(s) = u;\n};\n"
           "load system (Src) of type (A);\nload system (Int) of type (I);\n"
           "connect(Src.y, Int.u);\nset (main) method (sdirk3) step (1 tick);\n"
           "record (Int.z);\n")
    stair = ("scene (dirk_stair);\nbase tick (100 ms);\nend time (1 s);\n"
             "define ss_system (A) with outputs (y) states (x = 0) by {\n    y = x;\n"
             "    der(x) = 10 * floor(t + 0.58);\n};\n"
             "load system (B) of type (A);\nset (main) method (sdirk3) step (1 tick);\n"
             "record (B.y);\n")
    for m in ("sdirk2", "sdirk3"):
        for c in ("1.003", "1.01", "1.02", "1.04"):
            rc, summ, rows = run_text(s.modrt, out, ["--method", "main=" + m,
                                                     "--set", "Src.c=" + c])
            exact = 10 * (2 - float(c))
            err = abs(rows[-1][1] - exact) if rows else math.inf
            s.row("an output's comparison at %s integrated: z(2)" % c, m, "0.1", err, summ, rc)
            s.check(rc != 0 or err <= 2e-3 * (1 + exact), "%s output switch at %s: z(2) off "
                    "by %.3g with status ok" % (m, c, err))
        rc, summ, rows = run_text(s.modrt, stair, ["--method", "main=" + m])
        err = abs(rows[-1][1] - 5.8) if rows else math.inf
        s.row("x' = 10 floor(t + 0.58): x(1)", m, "0.1", err, summ, rc)
        s.check(rc != 0 or err <= 2e-3 * 6.8, "%s floor staircase: x(1) off by %.3g with "
                "status ok" % (m, err))


def extra(s, long):
    dirk_start(s)
    nan_lanes(s)
    located_switch_review(s)
    output_switches(s)
    floor_time(s)
    abs_split(s)
    hidden_oscillation(s)
    located_switch(s)
    located_switch_rest(s)
    located_switch_limits(s)
    growing(s)
    nan_guard(s)
    aliasing(s)
    quadrature(s)
    quad_cos(s)
    coulomb(s)
    relay(s)
    stall(s)
    scale(s)
