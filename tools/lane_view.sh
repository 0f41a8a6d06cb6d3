#!/bin/sh
# lane_view.sh - the top view of a lane-change trace as an xy table for svgplot --xy
# --lines: both cars' paths (centre of mass) and the cone lines of ISO 3888-1 sections 1,
# 3 and 5-6 as the standard draws them (course from X0 = 20 m, vehicle width 1.674 m;
# section 3's right-hand line 3.5 m left of section 1's, sections 5-6 continuing section
# 1's; docs/vehicles.md).
# Usage: lane_view.sh TRACE.csv > TABLE.csv
awk -F, -v x0=20 -v b=1.674 '
NR == 1 { for (i = 1; i <= NF; i++) col[$i] = i; print "series,x,y"; next }
{ v1[NR] = $col["V1.x"] "," $col["V1.y"]; v2[NR] = $col["V2.x"] "," $col["V2.y"]; n = NR }
function lane(a, e, r, k) {
    l = r + k * b + 0.25
    printf "cone lines,%g,%g\ncone lines,%g,%g\ncone lines,nan,nan\n", x0 + a, l, x0 + e, l
    printf "cone lines,%g,%g\ncone lines,%g,%g\ncone lines,nan,nan\n", x0 + a, r, x0 + e, r
}
END {
    for (i = 2; i <= n; i += 10) print "V1 (driven),"  v1[i]
    for (i = 2; i <= n; i += 10) print "V2 (towed)," v2[i]
    r1 = -(1.1 * b + 0.25) / 2
    lane(0, 15, r1, 1.1); lane(45, 70, r1 + 3.5, 1.2); lane(95, 125, r1, 1.3)
}' "$1"
