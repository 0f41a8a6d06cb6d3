#!/usr/bin/env python3
"""table_ref.py - the impacts of a ball on a table moving as A sin(w t), computed without
the runtime (tests/hard/events_table.scn): between impacts the ball flies on its exact
parabola z(t) = z_i + v_i (t - t_i) - g (t - t_i)^2 / 2; the next impact is the first
time the gap z(t) - A sin(w t) falls through zero, found by scanning the gap at 1/64 of a
millisecond (a flight from a table moving up is longer than that: the gap opens at the
relative speed) and bisecting the sign change to the last bit; there the velocity
relative to the table is reversed and scaled by e. Plain Python floats, no scipy.

Usage: table_ref.py [N]  prints the first N impact times (default 12)."""
import math
import sys

G, E, A = 9.81, 0.5, 0.01
W = math.sqrt(2 * G / A)  # table acceleration amplitude A w^2 = 2 g (Gamma = 2)
Z0, V0 = 0.05, 0.0
SCAN = 1e-3 / 64


def gap(t, ti, zi, vi):
    s = t - ti
    return zi + vi * s - 0.5 * G * s * s - A * math.sin(W * t)


def next_impact(ti, zi, vi, t_max):
    """the first time after ti the gap falls from > 0 to <= 0, or None before t_max"""
    a = ti
    ga = gap(a, ti, zi, vi)
    # just after an impact the gap is 0 and opening: start past it
    if ga <= 0:
        a, ga = ti + 1e-12, gap(ti + 1e-12, ti, zi, vi)
    while a < t_max:
        b = a + SCAN
        gb = gap(b, ti, zi, vi)
        if ga > 0 and gb <= 0:
            while True:
                m = 0.5 * (a + b)
                if m <= a or m >= b:
                    return b
                if gap(m, ti, zi, vi) > 0:
                    a = m
                else:
                    b = m
        a, ga = b, gb
    return None


def impacts(n, t_max=10.0):
    """the first n impact times (fewer if t_max comes first)"""
    t, z, v, out = 0.0, Z0, V0, []
    while len(out) < n:
        te = next_impact(t, z, v, t_max)
        if te is None:
            break
        s = te - t
        v_in = v - G * s
        vt = A * W * math.cos(W * te)
        z, v, t = A * math.sin(W * te), vt - E * (v_in - vt), te
        out.append(te)
    return out


if __name__ == "__main__":
    for k, te in enumerate(impacts(int(sys.argv[1]) if len(sys.argv) > 1 else 12)):
        print("%2d %.15f" % (k + 1, te))
