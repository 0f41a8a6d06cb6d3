#!/usr/bin/env python3
"""figures.py - the cost and accuracy figures of docs/vehicles.md for the lane change with
spatial cars: each schedule's largest position difference (both cars, at the 20 ms
instants: the multirate vehicles' steps) and wheel-angle difference (V2, every millisecond)
from the reference
(tests/vehicles/lane_change_ref.scn: dopri5 at 0.25 ms, whose own error vehicles.py shows
to be below 1e-9 m), its right-hand sides, its host time for 8 s (wall clock, best of three on a
shared machine) and, with --ir, its instructions counted by valgrind (deterministic).
Usage: figures.py MODRT [--ir]"""
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import vehicles  # noqa: E402

SCHEDULES = (
    ("lane_change: vehicles BS3 20 ms, steering ROS2 1 ms (as shipped)", ["lane_change"]),
    ("lane_change: vehicles BS3 10 ms, steering ROS2 1 ms",
     ["lane_change", "--step=vehicles=0.01"]),
    ("lane_change: vehicles BS3 5 ms, steering ROS2 1 ms",
     ["lane_change", "--step=vehicles=0.005"]),
    ("lane_change: vehicles RK4 20 ms, steering ROS2 1 ms",
     ["lane_change", "--method=vehicles=rk4"]),
    ("lane_change: vehicles RK4 5 ms, steering ROS2 1 ms at accuracy 1e-3 (until 852175e)",
     ["lane_change", "--method=vehicles=rk4", "--step=vehicles=0.005",
      "--accuracy=steering=1e-3"]),
    ("lane_change: vehicles BS3 20 ms, steering BS3 1 ms",
     ["lane_change", "--method=steering=bs3"]),
    ("lane_change_single: BS3 1 ms", ["lane_change_single"]),
    ("lane_change_single: RK4 1 ms", ["lane_change_single", "--method=all=rk4"]),
    ("lane_change_single: ROS2 1 ms (a Jacobian every step)",
     ["lane_change_single", "--method=all=ros2"]),
)


def instructions(modrt, args):
    out = "/tmp/figures.callgrind.%d" % os.getpid()
    p = subprocess.run(["valgrind", "--tool=callgrind", "--callgrind-out-file=" + out, modrt,
                        "run"] + args, capture_output=True, text=True)
    os.remove(out)
    for ln in p.stderr.splitlines():
        if "Collected" in ln:
            return int(ln.split()[-1])
    return 0


def main():
    modrt, ir = sys.argv[1], "--ir" in sys.argv
    _, _, head, ref = vehicles.run(modrt, os.path.join(HERE, "lane_change_ref.scn"))
    col = {h: i for i, h in enumerate(head)}
    at = {round(r[0] * 4000): r for r in ref}
    pos = [col[k] for k in ("V1.x", "V1.y", "V2.x", "V2.y")]
    wheel = col["Servo.delta"]
    print("| schedule | position error [m] | wheel angle error [rad] | right-hand sides | "
          "host time for 8 s [s] |%s" % (" instructions |" if ir else ""))
    print("|---|---:|---:|---:|---:|%s" % ("---:|" if ir else ""))
    for name, args in SCHEDULES:
        rc, summ, _, rows = vehicles.run(modrt, *args)
        e = ew = 0.0
        for r in rows:
            k = round(r[0] * 4000)
            if k in at:
                ew = max(ew, abs(r[wheel] - at[k][wheel]))
                if k % 80 == 0:
                    e = max([e] + [abs(r[i] - at[k][i]) for i in pos])
        walls = []
        for _ in range(3):
            p = subprocess.run([modrt, "run"] + args, capture_output=True, text=True)
            s = dict(ln.split(": ", 1) for ln in (p.stdout + p.stderr).splitlines() if ": " in ln)
            walls.append(float(s["wall_s"]))
        rhs = sum(int(v) for k, v in summ.items() if k.startswith("rhs_evals."))
        extra = " %.3g |" % instructions(modrt, args) if ir else ""
        print("| %s%s | %.2g | %.2g | %d | %.3f |%s" % (
            name, "" if rc == 0 else " (status: %s)" % summ.get("status"), e, ew, rhs,
            min(walls), extra))


if __name__ == "__main__":
    main()
