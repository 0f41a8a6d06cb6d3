#!/usr/bin/env python3
"""vehicles.py - checks of the vehicle models and the lane change (docs/vehicles.md), each
against an independent answer:
  * steady-state cornering of the single-track car: the yaw rate and lateral speed after
    20 s against the 2 x 2 steady-state system of the linear single-track model solved
    here, and the yaw rate against the closed form U delta / (L + K_us U^2);
  * a straight free roll (no steering, no drive): x = 20 t, y = psi = 0;
  * the course (course.scn): the drivers' centre lines against the lane centres of the
    ISO 3888-1 cone lines computed by iso3888_cones.py from the standard's dimensions
    (lane widths 1.1 b + 0.25, 1.2 b + 0.25, 1.3 b + 0.25 m; the 3.5 m offset between
    the right-hand lines of sections 1 and 3, sections 5-6 on section 1's right-hand
    line), and iso_driver_cc's against its centre-to-centre variant;
  * the ISO 3888-1 lane change of lane_change_planar: V1's footprint (CommonRoad vehicle
    1: 4.298 m x 1.674 m, centred between the axles; its edges, not only its corners)
    inside those cone lines in sections 1, 3 and 5-6, V2 within 0.75 m of V1's track at
    the same x, the tow bar's residual at rounding level, status ok;
  * the spatial car (car3d, car3d_mf): static corner loads against the hand statics
    m g l_r / (2 L), m g l_f / (2 L) and the settled height and pitch of unloaded springs
    against the statics of the four springs; energy of the passive car with tires off
    and no dampers constant to the integrator's error (fourth order); steady cornering
    against the steady turn of the rigid car solved here (forces and moments with the
    gyroscopic term, Newton's method) and against the single-track closed form;
  * the effects variants (tests/vehicles/variants/, make effects) drive the course too;
  * lane_change and lane_change_single (spatial cars, V2's steering chain) against a
    reference by another method at a finer step (tests/vehicles/lane_change_ref.scn,
    dopri5 at 0.25 ms), whose own error is shown smaller.
Usage: vehicles.py MODRT"""
import math
import os
import subprocess
import sys

import iso3888_cones

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
M, IZ, LF, LR, CF, CR = 1225.887, 1538.853, 0.88392, 1.50876, 158000.0, 170000.0
# the spatial car's defaults (models/vehicle_3d.c: CommonRoad vehicle 1)
IXX, IYY, TF, TR, H, KS, G = 244.047, 1342.260, 1.389888, 1.423416, 0.557784, 19632.988, 9.81
KBF, KBR = 37900.0, 6900.0  # anti-roll bars: roll stiffness [N m/rad] front, rear
LENGTH, WIDTH = 4.298, 1.674
passed = failed = 0


def check(ok, what):
    global passed, failed
    if ok:
        passed += 1
    else:
        failed += 1
        print("FAIL vehicles: " + what)


def run(modrt, scene, *args):
    p = subprocess.run([modrt, "run", scene, "--csv", "-"] + list(args), capture_output=True,
                       text=True, timeout=120)
    lines = p.stdout.splitlines()
    head = lines[0].split(",") if lines else []
    rows = [[float(v) for v in ln.split(",")] for ln in lines[1:]]
    summ = dict(ln.split(": ", 1) for ln in p.stderr.splitlines() if ": " in ln)
    return p.returncode, summ, head, rows


def steady_state(U, d):
    """v, r of m (v' + U r) = F_yf + F_yr, Iz r' = lf F_yf - lr F_yr at v' = r' = 0"""
    a11, a12 = -(CF + CR) / U, -(CF * LF - CR * LR) / U - M * U
    a21, a22 = -(LF * CF - LR * CR) / U, -(LF * LF * CF + LR * LR * CR) / U
    b1, b2 = -CF * d, -LF * CF * d
    det = a11 * a22 - a12 * a21
    return (b1 * a22 - a12 * b2) / det, (a11 * b2 - a21 * b1) / det


def cornering(modrt):
    rc, summ, head, rows = run(modrt, os.path.join(HERE, "cornering.scn"))
    last = dict(zip(head, rows[-1]))
    v, r = steady_state(20.0, 0.02)
    L = LF + LR
    k_us = M * (LR / CF - LF / CR) / L
    r_closed = 20.0 * 0.02 / (L + k_us * 400.0)
    er, ev = abs(last["Car.r"] / r - 1), abs(last["Car.v"] / v - 1)
    print("vehicles: cornering: r %.9f (steady state %.9f, closed form %.9f), v %.9f (%.9f)"
          % (last["Car.r"], r, r_closed, last["Car.v"], v))
    check(rc == 0 and er < 1e-5 and ev < 1e-4 and abs(r / r_closed - 1) < 1e-12,
          "cornering: r off by %.3g, v by %.3g (exit %d)" % (er, ev, rc))
    check(abs(last["Car.ay"] - 20.0 * r) < 1e-4 * abs(20.0 * r),
          "cornering: ay %.6f, U r %.6f" % (last["Car.ay"], 20.0 * r))


def magic(alpha, ca, fz, mu=1.0, c=1.3, e=-0.5):
    d = mu * fz
    b = ca / (c * d)
    ba = b * alpha
    return d * math.sin(c * math.atan(ba - e * (ba - math.atan(ba))))


def steady_state_mf(U, d):
    """v, r of the Magic-Formula car in steady state: Newton's method on
    F_yf + F_yr - m U r = 0, lf F_yf - lr F_yr = 0 (finite-difference Jacobian)"""
    L, w = LF + LR, M * 9.81

    def res(v, r):
        fyf = magic(d - math.atan((v + LF * r) / U), CF, w * LR / L)
        fyr = magic(-math.atan((v - LR * r) / U), CR, w * LF / L)
        return fyf + fyr - M * U * r, LF * fyf - LR * fyr

    v, r = steady_state(U, d)  # the linear answer as the start
    for _ in range(50):
        f1, f2 = res(v, r)
        h = 1e-7
        a11, a21 = [(x - y) / h for x, y in zip(res(v + h, r), (f1, f2))]
        a12, a22 = [(x - y) / h for x, y in zip(res(v, r + h), (f1, f2))]
        det = a11 * a22 - a12 * a21
        dv, dr = (f1 * a22 - a12 * f2) / det, (a11 * f2 - a21 * f1) / det
        v, r = v - dv, r - dr
        if abs(dv) + abs(dr) < 1e-15:
            break
    return v, r


def cornering_mf(modrt):
    rc, summ, head, rows = run(modrt, os.path.join(HERE, "cornering_mf.scn"))
    last = dict(zip(head, rows[-1]))
    v, r = steady_state_mf(20.0, 0.04)
    vl, rl = steady_state(20.0, 0.04)
    er, ev = abs(last["Car.r"] / r - 1), abs(last["Car.v"] / v - 1)
    print("vehicles: cornering, Magic Formula: r %.9f (steady state %.9f; linear tires %.6f)"
          ", v %.9f (%.9f)" % (last["Car.r"], r, rl, last["Car.v"], v))
    check(rc == 0 and er < 1e-5 and ev < 1e-4 and abs(r / rl - 1) > 0.01,
          "cornering (Magic Formula): r off by %.3g, v by %.3g (exit %d)" % (er, ev, rc))


def free_roll(modrt):
    rc, summ, head, rows = run(modrt, os.path.join(HERE, "cornering.scn"), "--set",
                               "Steer.y0=0", "--set", "Steer.y1=0", "--set", "Kp.k=0")
    worst = max(max(abs(r[head.index("Car.x")] - 20 * r[0]), abs(r[head.index("Car.y")]),
                    abs(r[head.index("Car.psi")])) for r in rows)
    check(rc == 0 and worst < 1e-9, "free roll: off the straight line by %.3g" % worst)


def lanes(x0):
    """the cone lanes of ISO 3888-1 as the standard draws them (iso3888_cones.py): (x from,
    x to, centre, half width) for sections 1, 3 and 5-6"""
    return [(xa, xb, (r + l) / 2, (l - r) / 2)
            for _, xa, xb, r, l in iso3888_cones.lanes(WIDTH, x0)]


def corners(x, y, psi):
    """the footprint's corners in order around it: a box of LENGTH x WIDTH centred between
    the axles"""
    cx, cy = x + (LF - LR) / 2 * math.cos(psi), y + (LF - LR) / 2 * math.sin(psi)
    c, s = math.cos(psi), math.sin(psi)
    out = []
    for a, b in ((1, 1), (1, -1), (-1, -1), (-1, 1)):
        a, b = a * LENGTH / 2, b * WIDTH / 2
        out.append((cx + a * c - b * s, cy + a * s + b * c))
    return out


def lane_margin(x, y, psi, x0):
    """the footprint's smallest margin to the cone lines at this instant (1e9 outside the
    lane sections). Edges, not only corners: the part of the box inside a section's x
    range has its extreme y at a corner in that range or where an edge crosses the
    section's first or last cone (a box half inside a section touches a cone there with a
    side, while all its corners in the section are clear)"""
    box = corners(x, y, psi)
    worst = 1e9
    for xa, xb, c, w in lanes(x0):
        pts = [p for p in box if xa <= p[0] <= xb]
        for (ax, ay), (bx, by) in zip(box, box[1:] + box[:1]):
            for xe in (xa, xb):
                if (ax - xe) * (bx - xe) < 0:
                    pts.append((xe, ay + (by - ay) * (xe - ax) / (bx - ax)))
        for _, py in pts:
            worst = min(worst, w - abs(py - c))
    return worst


def course_centre(x, x0, lanes_):
    """the centre line through the lanes (x from, x to, centre, half width) of sections 1,
    3 and 5-6: each lane's centre within it and before/after the course, the quintic
    10 s^3 - 15 s^4 + 6 s^5 between neighbouring centres over sections 2 and 4"""
    (_, a1, c1, _), (a3, b3, c3, _), (a5, _, c5, _) = lanes_
    if x <= a1:
        return c1
    if x >= a5:
        return c5
    if a3 <= x <= b3:
        return c3
    p, q, ca, cb = (a1, a3, c1, c3) if x < a3 else (b3, a5, c3, c5)
    w = (x - p) / (q - p)
    return ca + (cb - ca) * w ** 3 * (10 - 15 * w + 6 * w * w)


def course(modrt):
    """the centre line the drivers follow (course.scn: a car rolling straight through the
    course): iso_driver's yref is the centre line of the cone lanes as ISO 3888-1 draws
    them (iso3888_cones.py: the 3.5 m offset between the right-hand cone lines of
    sections 1 and 3, sections 5-6 continuing section 1's right-hand line), for the
    default vehicle width and for another; iso_driver_cc's is the named variant's
    (centres 0, 3.5 and 0)"""
    x0 = 20.0
    cc = [(0.0, x0 + 15, 0.0, 0), (x0 + 45, x0 + 70, 3.5, 0), (x0 + 95, 0, 0.0, 0)]
    for b in (WIDTH, 2.0):
        rc, summ, head, rows = run(modrt, os.path.join(HERE, "course.scn"), "--set",
                                   "Drv.b=%r" % b, "--set", "Cc.b=%r" % b)
        col = {h: i for i, h in enumerate(head)}
        std = [(xa, xb, (r + l) / 2, (l - r) / 2)
               for _, xa, xb, r, l in iso3888_cones.lanes(b, x0)]
        e = max(abs(r[col["Drv.yref"]] - course_centre(r[col["Car.x"]], x0, std))
                for r in rows)
        ecc = max(abs(r[col["Cc.yref"]] - course_centre(r[col["Car.x"]], x0, cc))
                  for r in rows)
        span = (rows[0][col["Car.x"]], rows[-1][col["Car.x"]])
        print("vehicles: course (b = %g m, x %.0f to %.0f m): iso_driver's centre line off the "
              "ISO 3888-1 cone lanes by at most %.2g m (section 3 centre %.4f, sections 5-6 "
              "%.4f); iso_driver_cc off its variant by %.2g m"
              % (b, span[0], span[1], e, std[1][2], std[2][2], ecc))
        check(rc == 0 and span[0] < x0 and span[1] > x0 + 125,
              "course: exit %d, the run covers x %.1f to %.1f m" % (rc, span[0], span[1]))
        check(e < 1e-12, "course: iso_driver's centre line is %.3g m off the lane centres "
              "of ISO 3888-1 (b = %g m)" % (e, b))
        check(ecc < 1e-12, "course: iso_driver_cc's centre line is %.3g m off the "
              "centre-to-centre variant" % ecc)


def footprint_edges():
    """the footprint check tests edges: a box turned by 0.2 rad with one corner in section 3
    (0.76 m clear of its cones) whose side crosses the section's first cone pair 0.055 m
    outside the lane hits a cone"""
    x0 = 20.0
    xa, _, c3, _ = lanes(x0)[1]
    m = lane_margin(xa - 1.8, c3 + 0.82, 0.2, x0)
    check(-0.06 < m < -0.05, "footprint: a side across the first cone of section 3 "
          "not found (margin %.3f m)" % m)


def lane_change(modrt, scene="lane_change_planar", x0=20.0):
    """V1 inside the cones, V2 on V1's track, the tow bar's residual at rounding level; a
    scene without V2 (an effects variant) checks V1 alone"""
    rc, summ, head, rows = run(modrt, scene)
    col = {h: i for i, h in enumerate(head)}
    name = os.path.basename(scene)
    if "V2.x" not in col:
        worst = min(lane_margin(r[col["V1.x"]], r[col["V1.y"]], r[col["V1.psi"]], x0)
                    for r in rows)
        print("vehicles: %s: smallest margin to the cones %.3f m, status %s"
              % (name, worst, summ.get("status")))
        check(rc == 0 and worst > 0, "%s: exit %d, margin %.3f m" % (name, rc, worst))
        return
    worst = min(lane_margin(r[col["V1.x"]], r[col["V1.y"]], r[col["V1.psi"]], x0)
                for r in rows)  # smallest margin to a cone line [m]
    # V2's lateral distance from V1's track at the same x (V1's track interpolated)
    xs = [r[col["V1.x"]] for r in rows]
    ys = [r[col["V1.y"]] for r in rows]
    dev, j = 0.0, 0
    for r in rows:
        x2 = r[col["V2.x"]]
        while j + 1 < len(xs) and xs[j + 1] < x2:
            j += 1
        if xs[0] <= x2 <= xs[-1] and j + 1 < len(xs) and xs[j + 1] > xs[j]:
            y1 = ys[j] + (ys[j + 1] - ys[j]) * (x2 - xs[j]) / (xs[j + 1] - xs[j])
            dev = max(dev, abs(r[col["V2.y"]] - y1))
    res = max(abs(r[col["V1.residual"]]) for r in rows)
    ay = max(abs(r[col["V1.ay"]]) for r in rows)
    print("vehicles: %s: smallest margin to the cones %.3f m, V2 off V1's track by at most "
          "%.3f m, tow-bar residual %.2g m, peak |ay| of V1 %.2f m/s^2, status %s"
          % (name, worst, dev, res, ay, summ.get("status")))
    check(rc == 0, "%s: exit %d (%s)" % (name, rc, summ.get("status")))
    check(worst > 0, "%s: V1 hits a cone (margin %.3f m)" % (name, worst))
    check(dev < 0.75, "%s: V2 %.3f m off V1's track" % (name, dev))
    check(res < 1e-12, "%s: tow-bar residual %.3g" % (name, res))


def cones_block(modrt):
    """the course check iso_cones (models/lane_change.c) in docs/sweeps/lane_change_margin.scn
    against lane_margin above at every tick, capped at its 1 m; V1 moves as in lane_change
    (the block only reads it); the run's smallest margin is an edge's (leaving section 1,
    a side passes the last cone pair), below the corners' alone, so the edge crossings count"""
    scene = os.path.join(HERE, "..", "..", "docs", "sweeps", "lane_change_margin.scn")
    rc, summ, head, rows = run(modrt, scene)
    rc2, _, head2, rows2 = run(modrt, "lane_change")
    col, col2 = {h: i for i, h in enumerate(head)}, {h: i for i, h in enumerate(head2)}
    v1 = ("V1.x", "V1.y", "V1.psi")
    if rc or rc2 or "Cones.margin" not in col or len(rows) != len(rows2) or not rows:
        return check(False, "cones: exit %d and %d, %d and %d rows" % (rc, rc2, len(rows),
                                                                        len(rows2)))
    same = all([r[col[k]] for k in v1] == [q[col2[k]] for k in v1] for r, q in zip(rows, rows2))
    check(same, "cones: V1 in lane_change_margin differs from V1 in lane_change")
    off = max(abs(r[col["Cones.margin"]] - min(1.0, lane_margin(*[r[col[k]] for k in v1], 20.0)))
              for r in rows)
    low = min(r[col["Cones.margin"]] for r in rows)
    corner = 1e9
    for r in rows:
        for px, py in corners(*[r[col[k]] for k in v1]):
            for xa, xb, c, w in lanes(20.0):
                if xa <= px <= xb:
                    corner = min(corner, w - abs(py - c))
    print("vehicles: iso_cones: smallest margin %.4f m (corners alone %.4f m), off the "
          "footprint check by %.2g m" % (low, corner, off))
    check(off <= 1e-12 and low < corner - 0.005,
          "cones: off by %.3g m, smallest margin %.4f m, corners alone %.4f m" % (off, low, corner))


def multirate(modrt):
    """lane_change (vehicles BS3 20 ms, steering chain ROS2 1 ms) and lane_change_single
    (all BS3 1 ms) against a reference by another method at a finer step
    (lane_change_ref.scn: Dormand-Prince 5(4) at 0.25 ms), whose own error (against the
    same method at 0.5 ms) must be four times smaller: positions at the 20 ms instants (the
    multirate scene's vehicles show their state at the last published step between), the
    wheel angle of V2 at every millisecond (the reference's own error is some 1e-12 m,
    rounding accumulated over 8 s of closed-loop driving)"""
    ref_scn = os.path.join(HERE, "lane_change_ref.scn")
    runs = {}
    for name, args in (("ref", [ref_scn]), ("ref2", [ref_scn, "--step=all=0.0005"]),
                       ("lane_change", ["lane_change"]),
                       ("lane_change_single", ["lane_change_single"])):
        runs[name] = run(modrt, *args)
    _, _, head, ref = runs["ref"]
    col = {h: i for i, h in enumerate(head)}
    at = {round(r[0] * 4000): r for r in ref}
    pos = [col[k] for k in ("V1.x", "V1.y", "V2.x", "V2.y")]
    wheel = col["Servo.delta"]

    def diff(rows):
        e = ew = 0.0
        for r in rows:
            k = round(r[0] * 4000)
            if k % 4 or k not in at:
                continue
            ew = max(ew, abs(r[wheel] - at[k][wheel]))
            if k % 80 == 0:
                e = max([e] + [abs(r[i] - at[k][i]) for i in pos])
        return e, ew

    rc2, _, _, rows2 = runs["ref2"]
    e_ref, ew_ref = diff(rows2)
    print("vehicles: reference (dopri5 0.25 ms) against dopri5 0.5 ms: %.2g m, %.2g rad, "
          "host %s s" % (e_ref, ew_ref, runs["ref"][1].get("wall_s")))
    check(runs["ref"][0] == 0 and rc2 == 0, "reference runs failed")
    # bounded ticks: lane_change's steering set (ROS2, autonomous: two evaluations a step;
    # 8 states, a Jacobian every 64 steps) spreads the refresh, one column a step
    # (rt/integ_implicit.c): no step takes more than 2 + ceil(8 / 63) = 3 evaluations,
    # where the whole refresh in one step took 2 + 8
    most = runs["lane_change"][1].get("rhs_step_max.steering", "").split(" ")[0]
    print("vehicles: lane_change: most evaluations in one step of the steering set: %s" % most)
    check(most == "3", "lane_change: a steering step took %s evaluations (bound 3: the "
          "Jacobian refresh spread one column a step)" % most)
    for name in ("lane_change", "lane_change_single"):
        rc, summ, _, rows = runs[name]
        e, ew = diff(rows)
        print("vehicles: %s: largest position difference from the reference %.2g m, wheel "
              "angle %.2g rad, host %s s, status %s" % (name, e, ew, summ.get("wall_s"),
                                                        summ.get("status")))
        # lane_change's background vehicles every 20 ms, read by the parabola through
        # their last three points (interpolation quadratic), come within 3.3e-4 m and
        # 1.3e-4 rad (9.8e-4 m and 4.2e-4 rad by linear extrapolation, 5.8e-3 m with the
        # wheel angle held): 5e-4 fails if that is lost. The single-rate scene: 1e-4
        bound = 5e-4 if name == "lane_change" else 1e-4
        check(rc == 0 and e < bound and ew < bound,
              "%s: %.3g m / %.3g rad from the reference (bound %g)" % (name, e, ew, bound))
        check(e_ref < e / 4 and ew_ref < ew / 4,
              "%s: the reference's own error (%.3g m, %.3g rad) is not four times smaller "
              "than the error measured with it (%.3g m, %.3g rad)" % (name, e_ref, ew_ref,
                                                                     e, ew))


def newton(res, z, h=1e-7, tol=1e-13):
    """Newton's method on res(z) = 0 with a forward-difference Jacobian"""
    n = len(z)
    for _ in range(60):
        f = res(z)
        A = [[0.0] * n for _ in range(n)]
        for j in range(n):
            zz = list(z)
            hj = h * max(1.0, abs(z[j]))
            zz[j] += hj
            fj = res(zz)
            for i in range(n):
                A[i][j] = (fj[i] - f[i]) / hj
        ab = [A[i] + [-f[i]] for i in range(n)]  # Gauss with partial pivoting
        for i in range(n):
            p = max(range(i, n), key=lambda k: abs(ab[k][i]))
            ab[i], ab[p] = ab[p], ab[i]
            for k in range(i + 1, n):
                m = ab[k][i] / ab[i][i]
                ab[k] = [a - m * b for a, b in zip(ab[k], ab[i])]
        dz = [0.0] * n
        for i in reversed(range(n)):
            dz[i] = (ab[i][n] - sum(ab[i][k] * dz[k] for k in range(i + 1, n))) / ab[i][i]
        z = [a + b for a, b in zip(z, dz)]
        if max(abs(d) for d in dz) < tol:
            break
    return z


def static3d(modrt):
    """the spatial car at rest: with the preload (pre = 1) exactly the hand statics; with
    unloaded springs (pre = 0) the settled height, pitch and loads against the statics of
    the four springs solved here (and the small-angle hand formula within its error)"""
    L = LF + LR
    f0f, f0r = M * G * LR / (2 * L), M * G * LF / (2 * L)
    rc, summ, head, rows = run(modrt, os.path.join(HERE, "static3d.scn"))
    col = {h: i for i, h in enumerate(head)}
    loads = ("V.Fz_fl", "V.Fz_fr", "V.Fz_rl", "V.Fz_rr")
    want = (f0f, f0f, f0r, f0r)
    e = max(max(abs(r[col[k]] / w - 1) for k, w in zip(loads, want)) for r in rows)
    ez = max(abs(r[col["V.z"]] - H) for r in rows)
    print("vehicles: spatial car at rest: corner loads %.3f N front, %.3f N rear (m g l_r/(2L) "
          "= %.3f, m g l_f/(2L) = %.3f; largest relative difference %.2g), height off by %.2g m"
          % (rows[-1][col["V.Fz_fl"]], rows[-1][col["V.Fz_rl"]], f0f, f0r, e, ez))
    check(rc == 0 and e < 1e-12 and ez < 1e-12, "spatial car at rest: loads %.3g, height %.3g"
          % (e, ez))

    # unloaded springs: corner heights z_i = z - x_i sin(th) - h cos(th) (pitch th, nose
    # down positive about y), loads -k z_i at horizontal lever arms x_i cos(th) - h sin(th)
    def res(v):
        z, th = v
        f = [(-KS * (z - x * math.sin(th) - H * math.cos(th)), x * math.cos(th) - H * math.sin(th))
             for x in (LF, -LR)]
        return [2 * (f[0][0] + f[1][0]) - M * G, f[0][0] * f[0][1] + f[1][0] * f[1][1]]
    z, th = newton(res, [H, 0.0])
    fzf = -KS * (z - LF * math.sin(th) - H * math.cos(th))
    rc, summ, head, rows = run(modrt, os.path.join(HERE, "static3d.scn"), "--set", "V.pre=0")
    last = dict(zip(head, rows[-1]))
    # small angles: deflections d = F0 / k, z = h - (l_r d_f + l_f d_r) / L, th = (d_f - d_r) / L
    df, dr = f0f / KS, f0r / KS
    z_hand, th_hand = H - (LR * df + LF * dr) / L, (df - dr) / L
    print("vehicles: spatial car settling on unloaded springs: z %.6f m, pitch %.6f rad, front "
          "load %.3f N (statics %.6f, %.6f, %.3f; small-angle hand formula %.6f, %.6f)"
          % (last["V.z"], last["V.pitch"], last["V.Fz_fl"], z, th, fzf, z_hand, th_hand))
    check(rc == 0 and abs(last["V.z"] - z) < 1e-9 and abs(last["V.pitch"] - th) < 1e-9 and
          abs(last["V.Fz_fl"] / fzf - 1) < 1e-9,
          "spatial car settling: z %.3g, pitch %.3g off the statics"
          % (last["V.z"] - z, last["V.pitch"] - th))
    # the hand formula neglects that pitch moves the contacts by h sin(th) = 2 cm along
    # the car (a 1.3 % shift of load to the front, so 7 % more pitch) and the cos terms of
    # the deflections: within 2 mm and 10 % of the pitch
    check(abs(last["V.z"] - z_hand) < 2e-3 and abs(last["V.pitch"] / th_hand - 1) < 0.1,
          "spatial car settling: off the small-angle hand formula by %.3g m, %.3g rad"
          % (last["V.z"] - z_hand, last["V.pitch"] - th_hand))


def energy3d(modrt):
    """passive car, tires off, no dampers: the set's energy stays constant to the
    integration error. RK4 on an oscillation of frequency w damps each step by
    |R(i w h)| = 1 - (w h)^6 / 144, so the drift over a fixed time falls as h^5: halving
    the step divides it by about 32 (a conservative force law that were wrong would leave
    a drift that does not fall with the step)"""
    out = []
    for step in ("0.005", "0.0025"):
        rc, summ, head, rows = run(modrt, os.path.join(HERE, "energy3d.scn"),
                                   "--step=main=" + step)
        col = {h: i for i, h in enumerate(head)}
        e0 = rows[0][col["V.energy"]]
        drift = max(abs(r[col["V.energy"]] - e0) for r in rows)
        swing = max(r[col["V.potential"]] for r in rows) - min(r[col["V.potential"]] for r in rows)
        fz = min(min(r[col[k]] for k in ("V.Fz_fl", "V.Fz_fr", "V.Fz_rl", "V.Fz_rr")) for r in rows)
        out.append((rc, drift, swing, fz))
    (rc1, d1, sw, fz1), (rc2, d2, _, fz2) = out
    print("vehicles: passive spatial car, tires off, no dampers: energy drift %.2g J at 5 ms, "
          "%.2g J at 2.5 ms (ratio %.1f; the potential energy swings by %.1f J), smallest "
          "load %.0f N" % (d1, d2, d1 / d2 if d2 else float("inf"), sw, min(fz1, fz2)))
    check(rc1 == 0 and rc2 == 0 and min(fz1, fz2) > 0, "energy run: exit or a wheel lifts off")
    # the bound scales with the fastest mode: the roll mode with the anti-roll bars and
    # no tires (about the centre of mass) is at 18 rad/s, where RK4 at 5 ms loses 5e-6 of
    # the swing; what shows the force and energy hooks agree is the ratio
    check(d1 < 2e-5 * sw and 20 < d1 / d2 < 48,
          "energy: drift %.3g J at 5 ms, %.3g J at 2.5 ms (swing %.3g J)" % (d1, d2, sw))


def mat3(a, b):
    return [[sum(a[i][k] * b[k][j] for k in range(3)) for j in range(3)] for i in range(3)]


def mv3(a, x):
    return [sum(a[i][k] * x[k] for k in range(3)) for i in range(3)]


def cross3(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def magic3d(tana, ca0, f0, fz, mu=1.0, c=1.3, e=-0.5, fzpk=2.0):
    """car3d_mf's lateral law: D = mu fz, B C D = c1 sin(2 atan(fz / c2)), c2 = fzpk f0,
    equal to ca0 at f0"""
    if fz <= 0:
        return 0.0
    c2 = fzpk * f0
    c1 = ca0 / math.sin(2 * math.atan(f0 / c2))
    b = c1 * math.sin(2 * math.atan(fz / c2)) / (c * mu * fz)
    return mu * fz * math.sin(c * math.atan(b * tana - e * (b * tana - math.atan(b * tana))))


def steady_turn3d(U, delta, mf):
    """the steady turn of the spatial car as a rigid body at speed U and wheel angle delta:
    in the heading frame, with roll phi and pitch th (R = Ry(th) Rx(phi)), height z, the
    lateral speed v, the yaw rate r and the drive force Fx; forces balance the centripetal
    inertia (m (-v r, U r, g)) and moments about the centre of mass the gyroscopic term
    w x (R J R^T) w, w = (0, 0, r). Returns v, r, Fx, z, phi, th"""
    L = LF + LR
    f0f, f0r = M * G * LR / (2 * L), M * G * LF / (2 * L)
    cd, sd = math.cos(delta), math.sin(delta)

    def res(q):
        v, r, fx, z, phi, th = q
        cp, sp, ct, st = math.cos(phi), math.sin(phi), math.cos(th), math.sin(th)
        R = mat3([[ct, 0, st], [0, 1, 0], [-st, 0, ct]], [[1, 0, 0], [0, cp, -sp], [0, sp, cp]])
        F, T = [0.0] * 3, [0.0] * 3
        wheels = ((LF, TF / 2, f0f, CF / 2, 1), (LF, -TF / 2, f0f, CF / 2, 1),
                  (-LR, TR / 2, f0r, CR / 2, 0), (-LR, -TR / 2, f0r, CR / 2, 0))
        # contact heights; an anti-roll bar of roll stiffness K_b on a track t is a spring
        # K_b / t^2 on the difference of its two wheels' heights (roll phi: K_b phi / t at
        # each wheel, a moment K_b phi)
        zc = [z + mv3(R, [x, y, -H])[2] for x, y, _, _, _ in wheels]
        for i, (x, y, f0, ca0, front) in enumerate(wheels):
            rho = mv3(R, [x, y, -H])
            kb = (KBF / TF ** 2) if front else (KBR / TR ** 2)
            fz = max(0.0, f0 - KS * zc[i] - kb * (zc[i] - zc[i ^ 1]))
            vx, vy = U - rho[1] * r, v + rho[0] * r
            c, s = (cd, sd) if front else (1.0, 0.0)
            vxw, vyw = c * vx + s * vy, -s * vx + c * vy
            fxw = fx / 2 if front else 0.0
            if mf:  # friction circle
                fyw = magic3d(-vyw / vxw, ca0, f0, fz) * math.sqrt(1 - (fxw / fz) ** 2)
            else:
                fyw = ca0 * fz / f0 * (-vyw / vxw)
            f = [fxw * c - fyw * s, fxw * s + fyw * c, fz]
            F = [a + b for a, b in zip(F, f)]
            T = [a + b for a, b in zip(T, cross3(rho, f))]
        w = [0.0, 0.0, r]
        Ig = mat3(mat3(R, [[IXX, 0, 0], [0, IYY, 0], [0, 0, IZ]]), [list(c) for c in zip(*R)])
        gyro = cross3(w, mv3(Ig, w))
        return [F[0] + M * v * r, F[1] - M * U * r, F[2] - M * G] + \
            [a - b for a, b in zip(T, gyro)]
    return newton(res, [0.0, U * delta / 3.28, 0.0, H, 0.0, 0.0])


def cornering3d(modrt):
    """steady cornering of the spatial car: against the steady turn of the rigid car
    solved here; car3d (load-proportional linear tires: the load transfer cancels on each
    axle) also against the single-track closed form, car3d_mf against the single-track
    car with the same tires on static loads, off by the load transfer"""
    L = LF + LR
    k_us = M * (LR / CF - LF / CR) / L
    for scn, delta, mf in (("cornering3d.scn", 0.01, False), ("cornering3d_mf.scn", 0.02, True)):
        rc, summ, head, rows = run(modrt, os.path.join(HERE, scn))
        last = dict(zip(head, rows[-1]))
        U = last["V.u"]
        v, r, fx, z, phi, th = steady_turn3d(U, delta, mf)
        er, ev, ep = last["V.r"] / r - 1, last["V.v"] / v - 1, last["V.roll"] / phi - 1
        print("vehicles: %s: r %.9f, v %.9f, roll %.6f rad at a_y %.3f m/s^2 (steady turn "
              "%.9f, %.9f, %.6f: relative %.2g, %.2g, %.2g)" % (scn, last["V.r"], last["V.v"],
                                                                last["V.roll"], last["V.ay"],
                                                                r, v, phi, er, ev, ep))
        check(rc == 0 and abs(er) < 1e-7 and abs(ev) < 1e-6 and abs(ep) < 1e-6,
              "%s: off the steady turn by %.3g (r), %.3g (v), %.3g (roll)" % (scn, er, ev, ep))
        if not mf:
            # roll shifts the contact points sideways (their V_x by h sin(phi) r), the tires
            # take tan(slip) and turn with delta: second order in the angles
            r_cf = U * delta / (L + k_us * U * U)
            e = last["V.r"] / r_cf - 1
            print("vehicles: %s: single-track closed form r %.9f (relative %.2g)"
                  % (scn, r_cf, e))
            check(abs(e) < 1e-3, "%s: %.3g off the single-track closed form" % (scn, e))
        else:
            # the single-track car with these tires on the static loads: the lateral load
            # transfer costs each axle some of its degressive cornering stiffness, the more
            # the larger its share of the transfer. With the anti-roll bars 68 % of the roll
            # stiffness is at the front, more than the front's 63 % of the weight: the front
            # loses more and the car turns wider; without bars (equal springs, 49 % at the
            # front) the rear loses more and it turns tighter
            _, r_st = steady_state_mf3d(U, delta)
            e = last["V.r"] / r_st - 1
            rc0, _, head0, rows0 = run(modrt, os.path.join(HERE, scn), "--set", "V.kbf=0",
                                       "--set", "V.kbr=0")
            last0 = dict(zip(head0, rows0[-1]))
            e0 = last0["V.r"] / steady_state_mf3d(last0["V.u"], delta)[1] - 1
            print("vehicles: %s: single-track with the same tires on static loads r %.9f "
                  "(the spatial car's load transfer: %+.2g; without anti-roll bars %+.2g)"
                  % (scn, r_st, e, e0))
            check(-0.02 < e < -0.001 and rc0 == 0 and 0.001 < e0 < 0.02,
                  "%s: %.3g (bars), %.3g (no bars) off the single-track car" % (scn, e, e0))
        # roll gradient and lateral load transfer against the hand formulas with the roll
        # centre on the ground: roll phi = m h a_y / (K - m g h), K the springs' k t^2 / 2
        # and the bars' roll stiffness on both axles; the front's share of the transfer
        # (dF_f t_f over the total) is its share of K (small angles: the test allows 1 %)
        kf, kr = KS * TF ** 2 / 2 + KBF, KS * TR ** 2 / 2 + KBR
        grad = M * H / (kf + kr - M * G * H)
        g_sim = last["V.roll"] / last["V.ay"]
        dff = (last["V.Fz_fr"] - last["V.Fz_fl"]) / 2 * TF
        dfr = (last["V.Fz_rr"] - last["V.Fz_rl"]) / 2 * TR
        share = dff / (dff + dfr)
        print("vehicles: %s: roll gradient %.4f deg/g (hand %.4f), front share of the load "
              "transfer %.4f (of the roll stiffness %.4f)" % (scn, math.degrees(g_sim) * G,
                                                               math.degrees(grad) * G,
                                                               share, kf / (kf + kr)))
        check(abs(abs(g_sim) / grad - 1) < 0.01 and abs(share / (kf / (kf + kr)) - 1) < 0.01,
              "%s: roll gradient %.4g (hand %.4g), front share %.4g (%.4g)"
              % (scn, g_sim, grad, share, kf / (kf + kr)))


def steady_state_mf3d(U, d):
    """v, r of a single-track car whose axles carry two car3d_mf tires on the static
    loads, tan(slip) as car3d_mf: Newton's method"""
    L = LF + LR
    f0f, f0r = M * G * LR / (2 * L), M * G * LF / (2 * L)

    def res(q):
        v, r = q
        vf = v + LF * r  # the front contact's lateral speed, then tan(slip) in the wheel frame
        tf = (math.sin(d) * U - math.cos(d) * vf) / (math.cos(d) * U + math.sin(d) * vf)
        fyf = 2 * magic3d(tf, CF / 2, f0f, f0f) * math.cos(d)
        fyr = 2 * magic3d(-(v - LR * r) / U, CR / 2, f0r, f0r)
        return [fyf + fyr - M * U * r, LF * fyf - LR * fyr]
    return newton(res, [0.0, U * d / 3.28])


def main():
    modrt = sys.argv[1]
    cornering(modrt)
    cornering_mf(modrt)
    free_roll(modrt)
    footprint_edges()
    course(modrt)
    lane_change(modrt)
    lane_change(modrt, "lane_change")
    lane_change(modrt, "lane_change_single")
    cones_block(modrt)
    # the effects variants of make effects (each omits one effect of lane_change) still
    # drive the course
    for v in sorted(os.listdir(os.path.join(HERE, "variants"))):
        if v.endswith(".scn"):
            lane_change(modrt, os.path.join(HERE, "variants", v))
    static3d(modrt)
    energy3d(modrt)
    cornering3d(modrt)
    multirate(modrt)
    print("vehicles: %d passed, %d failed" % (passed, failed))
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
