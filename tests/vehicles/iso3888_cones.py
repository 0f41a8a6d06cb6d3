#!/usr/bin/env python3
"""iso3888_cones.py - the cone lines of the ISO 3888-1:2018 double lane change, computed
here from the standard's dimensions alone (Table 1 and Figure 1; sources in
docs/vehicles.md), as the reference of the course check in vehicles.py. It shares no code
with models/lane_change.c (which needs only the lane centres): it draws every cone line
the way the figure dimensions it, from the right-hand line it is measured from, and the
test takes the centres from those lines.

Figure 1 dimensions the track from its right-hand cone line (the lane change is to the
left): section 3's right-hand line lies 3.5 m to the left of section 1's (the lane offset),
and sections 5 and 6 continue section 1's right-hand line, so the wider exit lane opens
to the left. Lane widths with the vehicle width b: 1.1 b + 0.25 m (section 1),
1.2 b + 0.25 m (section 3), 1.3 b + 0.25 m (sections 5 and 6).

Frame: x along the course from its start x0, y to the left with y = 0 on the centre line
of section 1 (where the car enters).
Usage: iso3888_cones.py [b [x0]]  prints each section's four corner cones."""
import sys

LENGTHS = (15.0, 30.0, 25.0, 25.0, 15.0, 15.0)  # sections 1..6 [m]
OFFSET = 3.5        # section 3's right-hand line left of section 1's [m]
WIDTH_B = 1.674     # CommonRoad vehicle 1, the cars of the lane change scenes [m]


def lanes(b=WIDTH_B, x0=0.0, offset=OFFSET):
    """the coned sections as (name, x from, x to, right-hand line y, left-hand line y)"""
    starts = [x0]
    for n in LENGTHS:
        starts.append(starts[-1] + n)
    w1, w3, w56 = 1.1 * b + 0.25, 1.2 * b + 0.25, 1.3 * b + 0.25
    r1 = -w1 / 2            # section 1 is centred on y = 0
    r3 = r1 + offset        # the offset, right-hand line to right-hand line
    r56 = r1                # sections 5 and 6 continue section 1's right-hand line
    return [("section 1", starts[0], starts[1], r1, r1 + w1),
            ("section 3", starts[2], starts[3], r3, r3 + w3),
            ("sections 5-6", starts[4], starts[6], r56, r56 + w56)]


def corners(b=WIDTH_B, x0=0.0):
    """each coned section's corner cones: (name, [(x, y) entry right, entry left, exit
    right, exit left])"""
    return [(n, [(xa, r), (xa, l), (xb, r), (xb, l)]) for n, xa, xb, r, l in lanes(b, x0)]


if __name__ == "__main__":
    b = float(sys.argv[1]) if len(sys.argv) > 1 else WIDTH_B
    x0 = float(sys.argv[2]) if len(sys.argv) > 2 else 0.0
    print("ISO 3888-1 cones for b = %g m, course from x0 = %g m (x, y; y to the left)" % (b, x0))
    for name, pts in corners(b, x0):
        print("%-13s" % name + "  ".join("(%.4f, %.4f)" % p for p in pts))
