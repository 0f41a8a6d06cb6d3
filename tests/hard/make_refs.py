#!/usr/bin/python3
"""make_refs.py - reference solutions of the hard-case suite, computed offline by a method
independent of modrt (scipy's Radau IIA, order 5, adaptive step, rtol 1e-11) and written
to tests/hard/refs.txt, which is committed. Run on a machine with python3-scipy
(Debian: apt-get install python3-scipy): /usr/bin/python3 tests/hard/make_refs.py

Lines: CASE KEY VALUE... (KEY y: t and the state at t; KEY cross: times where y1 falls
or rises through 0)."""
import os
import numpy as np
from scipy.integrate import solve_ivp

RTOL, ATOL = 1e-11, 1e-15


def robertson(t, y):
    a, b, c = y
    return [-0.04 * a + 1e4 * b * c, 0.04 * a - 1e4 * b * c - 3e7 * b * b, 3e7 * b * b]


def vdp(mu):
    def f(t, y):
        return [y[1], mu * (1 - y[0] ** 2) * y[1] - y[0]]
    return f


def main():
    out = []
    times = [0.4, 4, 40, 400, 4000, 40000, 400000]
    s = solve_ivp(robertson, (0, times[-1]), [1, 0, 0], method="Radau", rtol=RTOL,
                  atol=1e-20, t_eval=times, dense_output=False)
    assert s.success
    for i, t in enumerate(s.t):
        out.append("robertson y %.17g %.17g %.17g %.17g" % (t, *s.y[:, i]))
    mu = 1000.0
    s = solve_ivp(vdp(mu), (0, 5000), [2, 0], method="Radau", rtol=RTOL, atol=1e-12,
                  t_eval=[5000], events=[lambda t, y: y[0]])
    assert s.success
    out.append("vdp1000 y %.17g %.17g %.17g" % (s.t[0], *s.y[:, 0]))
    out.append("vdp1000 cross " + " ".join("%.17g" % t for t in s.t_events[0]))
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "refs.txt")
    with open(path, "w") as f:
        f.write("# tests/hard/refs.txt - written by tests/hard/make_refs.py (scipy Radau, "
                "rtol 1e-11); do not edit\n")
        f.write("\n".join(out) + "\n")
    print("\n".join(out))


if __name__ == "__main__":
    main()
