#!/usr/bin/env python3
"""figures.py - the cost and accuracy figures of docs/vehicles.md for the lane change with
spatial cars, printed as the doc's markdown tables. Each schedule's largest position
difference (both cars, at the 20 ms instants: the multirate vehicles' steps) and wheel-angle
difference (V2, every millisecond) from the reference (tests/vehicles/lane_change_ref.scn:
dopri5 at 0.25 ms, whose own error vehicles.py shows to be far below these), then:
  default  its right-hand sides; with --ir the whole process's instructions over the 8 s
           (valgrind, deterministic); with --time its host time for 8 s (wall clock, best of
           three: too short to read on a loaded machine)
  --cost   the table "What accuracy costs": instructions of rt_tick + rt_record per
           simulated second (callgrind --toggle-collect, deterministic) against the shipped
           schedule
Usage: figures.py MODRT [--ir] [--time] | figures.py MODRT --cost"""
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import vehicles  # noqa: E402

T_END = 8.0  # the scenes' end time [s]
RK4_5MS = ["lane_change", "--method=vehicles=rk4", "--step=vehicles=0.005",
           "--accuracy=steering=1e-3"]

SCHEDULES = (
    ("lane_change: vehicles BS3 20 ms, steering ROS2 1 ms (as shipped)", ["lane_change"]),
    ("lane_change: vehicles BS3 10 ms, steering ROS2 1 ms",
     ["lane_change", "--step=vehicles=0.01"]),
    ("lane_change: vehicles BS3 5 ms, steering ROS2 1 ms",
     ["lane_change", "--step=vehicles=0.005"]),
    ("lane_change: vehicles RK4 20 ms, steering ROS2 1 ms",
     ["lane_change", "--method=vehicles=rk4"]),
    ("lane_change: vehicles RK4 5 ms, steering ROS2 1 ms at accuracy 1e-3", RK4_5MS),
    ("lane_change: vehicles BS3 20 ms, steering BS3 1 ms",
     ["lane_change", "--method=steering=bs3"]),
    ("lane_change_single: BS3 1 ms", ["lane_change_single"]),
    ("lane_change_single: RK4 1 ms", ["lane_change_single", "--method=all=rk4"]),
    ("lane_change_single: ROS2 1 ms (a Jacobian every step)",
     ["lane_change_single", "--method=all=ros2"]),
)

COSTS = (
    ("20 ms (shipped)", ["lane_change"]),
    ("10 ms", ["lane_change", "--step=vehicles=0.01"]),
    ("5 ms", ["lane_change", "--step=vehicles=0.005"]),
    ("5 ms, RK4, steering accuracy 1e-3", RK4_5MS),
    ("single rate: everything BS3 at 1 ms (`lane_change_single`)", ["lane_change_single"]),
)


def instructions(modrt, args, fns=()):
    """instructions counted by callgrind: the whole process, or inside fns only"""
    out = "/tmp/figures.callgrind.%d" % os.getpid()
    tog = ["--collect-atstart=no"] + ["--toggle-collect=" + f for f in fns] if fns else []
    p = subprocess.run(["valgrind", "--tool=callgrind", "--callgrind-out-file=" + out] + tog +
                       [modrt, "run"] + args, capture_output=True, text=True)
    if os.path.exists(out):
        os.remove(out)
    for ln in p.stderr.splitlines():
        if "Collected" in ln:
            return int(ln.split()[-1])
    raise SystemExit("figures: callgrind failed on %s: %s" % (args, p.stderr[-400:]))


class Reference:
    def __init__(self, modrt):
        _, _, head, ref = vehicles.run(modrt, os.path.join(HERE, "lane_change_ref.scn"))
        col = {h: i for i, h in enumerate(head)}
        self.at = {round(r[0] * 4000): r for r in ref}
        self.pos = [col[k] for k in ("V1.x", "V1.y", "V2.x", "V2.y")]
        self.wheel = col["Servo.delta"]

    def errors(self, rows):
        """largest position error at the 20 ms instants, wheel-angle error at every tick"""
        e = ew = 0.0
        for r in rows:
            k = round(r[0] * 4000)
            if k in self.at:
                ew = max(ew, abs(r[self.wheel] - self.at[k][self.wheel]))
                if k % 80 == 0:
                    e = max([e] + [abs(r[i] - self.at[k][i]) for i in self.pos])
        return e, ew


def sci(v, digits=2):
    """v as the doc writes it: 3.3e-4, 9.4e6, 0 (no '+' or leading zeros in the exponent)"""
    if v == 0:
        return "0"
    m, e = ("%.*e" % (digits - 1, v)).split("e")
    return "%se%d" % (m, int(e))


def status(rc, summ):
    return "" if rc == 0 else " (status: %s)" % summ.get("status")


def wall(modrt, args):
    walls = []
    for _ in range(3):
        p = subprocess.run([modrt, "run"] + args, capture_output=True, text=True)
        s = dict(ln.split(": ", 1) for ln in (p.stdout + p.stderr).splitlines() if ": " in ln)
        walls.append(float(s["wall_s"]))
    return min(walls)


def schedules(modrt, ref, ir, timed):
    print("| schedule | position error [m] | wheel angle error [rad] | right-hand sides |%s%s"
          % (" host time for 8 s [s] |" if timed else "",
             " instructions for 8 s |" if ir else ""))
    print("|---|---:|---:|---:|%s%s" % ("---:|" if timed else "", "---:|" if ir else ""))
    for name, args in SCHEDULES:
        rc, summ, _, rows = vehicles.run(modrt, *args)
        e, ew = ref.errors(rows)
        rhs = sum(int(v) for k, v in summ.items() if k.startswith("rhs_evals."))
        print("| %s%s | %s | %s | %d |%s%s" % (
            name, status(rc, summ), sci(e), sci(ew), rhs,
            " %.3f |" % wall(modrt, args) if timed else "",
            " %s |" % sci(instructions(modrt, args), 3) if ir else ""))


def costs(modrt, ref):
    print("| vehicles' step H | position error [m] | wheel angle error [rad] | "
          "instructions per simulated s | relative to shipped |")
    print("|---|---:|---:|---:|---:|")
    base = None
    for name, args in COSTS:
        rc, summ, _, rows = vehicles.run(modrt, *args)
        e, ew = ref.errors(rows)
        per_s = instructions(modrt, args, ("rt_tick", "rt_record")) / T_END
        base = base or per_s
        print("| %s%s | %s | %s | %s | %.2f |" % (
            name, status(rc, summ), sci(e), sci(ew), sci(per_s, 3), per_s / base))


def main():
    if len(sys.argv) < 2:
        raise SystemExit(__doc__)
    modrt = sys.argv[1]
    ref = Reference(modrt)
    if "--cost" in sys.argv:
        costs(modrt, ref)
    else:
        schedules(modrt, ref, "--ir" in sys.argv, "--time" in sys.argv)


if __name__ == "__main__":
    main()
