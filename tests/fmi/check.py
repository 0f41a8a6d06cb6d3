#!/usr/bin/env python3
"""check.py - the traces of the FMU test scenes (tests/fmi/scenes/) against closed forms,
computed here from the equations, never from the code under test:

  ball  h'' = -g from h = 1, v = 0; at each impact v := -e v (ball_h2: from 2 m, e = 0.5). Impact k at t_k, bounce
        speed e^k v1 (v1 = sqrt(2 g)), flights of 2 e^k v1 / g: h and v at every row.
  liftoff  the ball whose gravity is a relation set in event mode (contact := h <= 0): the
        ball's closed form, contact = 0 on every row, if each lift-off is reported.
  stair y(t) = floor(t / period) at every row, for a period on the tick grid (0.5 s) and
        one between ticks (0.3 s); a row on a switching instant shows the value after it;
        late = 0 on every row (the FMU never set past its time event in continuous time).
  stepper  x' = 1 with CompletedIntegratorStep: n = the steps of its set completed by t
        (1/8 s and 1/2 s), te = the first step end with x >= at (0.375 s, 1.5 s) exactly,
        x = t - te after it (at the set's last step end: a slow set's outputs are held).
  osc   x'' + c x' + k x = b u, u constant, from rest: the underdamped step response;
        the feed-through y = gain P.y + offset (exactly the double arithmetic), y2 = u2.
  probe_hold  a discrete input read, held, from sets of other rates: taken in event mode
        exactly where the other set's value changes, x' = ud integrated exactly.
  probe_param  a tunable parameter written during the run: taken in event mode at the
        next instant of each set (where its state is), w' = q integrated exactly.

Usage: check.py KIND CSV [TOL]; prints one line, exit 1 when a row is off."""
import csv
import math
import sys


def rows(path):
    with open(path) as f:
        r = csv.reader(f)
        head = next(r)
        data = [[float(x) for x in row] for row in r]
    if not data:  # no row would be no deviation: never a pass
        sys.exit("%s: no rows" % path)
    return head, data


def ball_exact(t, g=9.81, e=0.7, h0=1.0):
    t1 = math.sqrt(2 * h0 / g)
    if t < t1:
        return h0 - g * t * t / 2, -g * t
    v = g * t1 * e      # speed just after the first impact
    tk = t1
    while v > 1e-12:    # (past the accumulation point of the impacts: at rest)
        flight = 2 * v / g
        if t < tk + flight:
            s = t - tk
            return v * s - g * s * s / 2, v - g * s
        tk += flight
        v *= e
    return 0.0, 0.0


def check_ball(path, tol, e=0.7, h0=1.0):
    head, data = rows(path)
    worst = 0.0
    for r in data:
        h, v = ball_exact(r[0], e=e, h0=h0)
        # next to an impact the sampled velocity jumps: compare the height there only
        worst = max(worst, abs(r[1] - h))
        if abs(r[2] - v) > 1e-3:
            if near_impact(r[0], e=e, h0=h0):
                continue
        worst = max(worst, abs(r[2] - v))
    return worst


def near_impact(t, g=9.81, e=0.7, h0=1.0):
    tk, v = math.sqrt(2 * h0 / g), math.sqrt(2 * g * h0) * e
    while tk < t + 1 and v > 1e-12:  # (the impacts accumulate before t + 1 s)
        if abs(t - tk) < 2e-3:
            return True
        tk += 2 * v / g
        v *= e
    return False


def check_stair(path, tol):
    head, data = rows(path)
    worst = 0.0
    for r in data:
        for p, y in zip([0.5, 0.3], r[1:3]):
            # a row on a switching instant shows the value after the event
            worst = max(worst, abs(y - math.floor(r[0] / p + 1e-12)))
        # the FMU's own count of continuous-time evaluations past its next time event
        worst = max([worst] + r[3:5])
    return worst


def check_liftoff(path, tol):
    """the bouncing ball's closed form, and contact = 0 on every row (it is true only from
    an impact to the lift-off right after it, far shorter than a tick)"""
    if any(r[3] != 0 for r in rows(path)[1]):
        return float("inf")
    return check_ball(path, tol)


def check_stepper(path, tol):
    """F: steps of 1/8 s, event asked at the first step end with x >= 0.3; Sl: steps of
    1/2 s (its outputs held between them), x >= 1.2. n and te exactly, x to tol."""
    head, data = rows(path)
    worst = 0.0
    for r in data:
        t = r[0]
        for (h, at), (x, n, te) in zip([(0.125, 0.3), (0.5, 1.2)], [r[1:4], r[4:7]]):
            k = math.floor(t / h + 1e-9)      # steps completed by t
            ts = k * h                        # the set's state is at its last step end
            t_ev = math.ceil(at / h - 1e-9) * h  # the first step end with x >= at
            te_x = t_ev if ts >= t_ev else 0.0
            if n != k or te != te_x:
                return float("inf")
            worst = max(worst, abs(x - (ts - te_x)))
    return worst


def check_osc(path, tol, k=9.0, c=0.6, b=1.5, u=2.0, gain=2.0, offset=0.5, u2=3.0):
    head, data = rows(path)
    w0 = math.sqrt(k)
    z = c / (2 * w0)
    wd = w0 * math.sqrt(1 - z * z)
    xs = b * u / k
    worst = 0.0
    for r in data:
        t = r[0]
        x = xs * (1 - math.exp(-z * w0 * t) * (math.cos(wd * t) + z * w0 / wd * math.sin(wd * t)))
        worst = max(worst, abs(r[1] - x))
        if r[2] != gain * r[1] + offset or r[3] != u2:  # the feed-through, bit for bit
            return float("inf")
    return worst


def probe_rows(path, names):
    """the rows, and for each of the blocks `names` the columns of its recorded signals"""
    head, data = rows(path)
    col = {h: i for i, h in enumerate(head)}
    return data, [{s: col["%s.%s" % (b, s)] for s in ("x", "w", "n", "tu", "nq", "tq", "nev",
                                                        "wrong") if "%s.%s" % (b, s) in col}
                  for b in names]


def held_time(t, h):
    """the time of the state a set of step h shows at a row at t (its outputs are held
    between its steps; the row at a step's end shows the values after its instant)"""
    return h * math.floor(t / h + 1e-9)


def check_probe_hold(path, tol):
    """ud reads the source's w = t, held: at a point every d of its history. A set reading
    a slower set (Pa, 10 ms, and Pb, 30 ms, reading 40 ms) finds each point published
    ahead: ud = d floor(t / d) with d = 40 ms, changing at the points (inside Pb's steps
    too); one reading a faster set (Pc, 80 ms) finds at its step start the point there and
    nothing newer: d = 80 ms. At a change the FMU counts n, records tu = the time (in event
    mode: its event iteration); x' = ud integrates the staircase exactly, x = sum of the
    steps d * d k for k < n plus d n (t - d n); nev = n (the continuous input uc, which
    reads the source too, needs no event); wrong = 0 (no new ud in continuous time). Pg
    reads a step of its own set (80 ms) from 0 to 2 at 0.13 s: taken there, x = 2 (t - 0.13)."""
    data, cols = probe_rows(path, ("Pa", "Pb", "Pc", "Pg"))
    worst = 0.0
    for r in data:
        # Pg: a step of its own set (80 ms) from 0 to 2 at 0.13 s, inside a step
        c, ts = cols[3], held_time(r[0], 0.08)
        on = ts >= 0.13
        worst = max(worst, abs(r[c["x"]] - (2 * (ts - 0.13) if on else 0)),
                    abs(r[c["tu"]] - (0.13 if on else 0)),
                    1.0 if r[c["n"]] != on or r[c["nev"]] != on or r[c["wrong"]] != 0 else 0.0)
        for c, (h, d) in zip(cols[:3], [(0.01, 0.04), (0.03, 0.04), (0.08, 0.08)]):
            ts = held_time(r[0], h)
            n = math.floor(ts / d + 1e-9)
            x = d * d * n * (n - 1) / 2 + d * n * (ts - d * n)
            worst = max(worst, abs(r[c["x"]] - x), abs(r[c["tu"]] - d * n),
                        1.0 if r[c["n"]] != n or r[c["nev"]] != n or r[c["wrong"]] != 0 else 0.0)
    return worst


def check_probe_param(path, tol, t1=0.25, q0=1.0, q1=3.0):
    """q (w' = q) goes from q0 to q1 by rt_set_param after the row at t1 (tests/fmi/setp.c):
    each FMU takes it at its set's next instant, where its state is: Pd (10 ms) at t1, Pe
    (40 ms) at 0.28 s, Pf (30 ms) at 0.27 s, in event mode (nq = 1, tq = that time, nev
    = 1, wrong = 0); w = q0 t before it and q0 te + q1 (t - te) after, at the held times"""
    data, cols = probe_rows(path, ("Pd", "Pe", "Pf"))
    worst = 0.0
    for r in data:
        for c, (h, te) in zip(cols, [(0.01, 0.25), (0.04, 0.28), (0.03, 0.27)]):
            ts = held_time(r[0], h)
            took = r[0] > t1 + 1e-9 and ts >= te - 1e-9
            w = q0 * ts if not took else q0 * te + q1 * (ts - te)
            n = 1 if took else 0
            worst = max(worst, abs(r[c["w"]] - w), abs(r[c["tq"]] - (te if took else 0)),
                        1.0 if r[c["nq"]] != n or r[c["nev"]] != n or r[c["wrong"]] != 0 else 0.0)
    return worst


def main():
    kind, path = sys.argv[1], sys.argv[2]
    tol = float(sys.argv[3]) if len(sys.argv) > 3 else 1e-6
    worst = {"ball": check_ball, "stair": check_stair, "osc": check_osc,
             "stepper": check_stepper, "liftoff": check_liftoff,
             "probe_hold": check_probe_hold, "probe_param": check_probe_param,
             "ball_h2": lambda p, t: check_ball(p, t, e=0.5, h0=2.0)}[kind](path, tol)
    ok = worst <= tol
    print("%s %s: largest deviation from the closed form %.3g (tolerance %.3g): %s"
          % (kind, path, worst, tol, "ok" if ok else "FAIL"))
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
