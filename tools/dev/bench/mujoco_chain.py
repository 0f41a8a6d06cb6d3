#!/usr/bin/env python3
"""mujoco_chain.py - scale.sh's chain and tree (scale_bench.c) as MuJoCo models (MJCF), for
MuJoCo beside modrt at equal accuracy (docs/overhead.md, "Beside MuJoCo").

The same system as scale_bench.c builds: N point masses of 1 kg, each 1 m from its parent
(the anchor at the origin for the first), released at rest from the straight line along
+x (the chain: point k at (k, 0, 0)) or from the comb (the tree: spine point s at
(s + 1, 0, 0), a point hanging 1 m below each), gravity 9.81 m/s^2 along -z. In MuJoCo's
generalized coordinates a distance joint is a universal joint: two hinges at the parent's
point, both perpendicular to the link (a third, about the link, would carry no inertia:
a point mass has none about its link). The first hinge is about y, the second about the
link's other normal (z for a link along x, x for a link hanging along -z), so the
coordinates are singular only with the link along the parent frame's y axis: the motion
stays in the x-z plane, as modrt's does, far from it. Each body's frame sits at its parent
point, its mass at the link's end (inertial pos); the rotary inertia of the point is
1e-12 kg m^2 (MuJoCo's compiler refuses a moving body of zero inertia), 1e-12 of the
link's, below the accuracies measured.

Settings chosen for MuJoCo to be as cheap as it can be on this model: no geoms (no
collision detection at all), contacts, the constraint solver, equality, limits, friction
loss, passive forces, actuation, control clamping, warm start and sensors disabled (none
of them has work in this model; disabling them skips their stages). The integrator and
the step are set by the bench (mujoco_bench.c) at run time.

With "planar", one hinge per link (about y): the same motion from this start, but a
model that cannot leave the x-z plane (docs/overhead.md says what it would save).

Usage: mujoco_chain.py chain|tree N OUT.xml [planar]   (and OUT-partK.xml beside it, the subtrees
       from body K on: MuJoCo's XML parser refuses a nesting deeper than about 100)"""
import os
import sys


def link(shape, k, n):
    """(parent point index or -1, link direction) of point k, as scale_bench.c's body()"""
    if shape == "chain":
        return k - 1, (1, 0, 0)
    s, branch = divmod(k, 2)
    if branch:
        return 2 * s, (0, 0, -1)
    return (2 * (s - 1) if s else -1), (1, 0, 0)


DEPTH = 50  # bodies nested in one file: MuJoCo's XML parser refuses about 100; deeper
             # subtrees go to files of their own, included where they hang (<include>)


def main():
    if len(sys.argv) not in (4, 5) or sys.argv[1] not in ("chain", "tree") or \
            sys.argv[4:] not in ([], ["planar"]):
        sys.exit("usage: mujoco_chain.py chain|tree N OUT.xml [planar]")
    shape, n, path = sys.argv[1], int(sys.argv[2]), sys.argv[3]
    planar = len(sys.argv) == 5
    if n < 1 or (shape == "tree" and n % 2):
        sys.exit("mujoco_chain.py: N must be positive (even for a tree)")
    children = {k: [] for k in range(-1, n)}
    for k in range(n):
        children[link(shape, k, n)[0]].append(k)
    base = os.path.splitext(path)[0]

    def body(k, pos, depth, out):
        if depth == DEPTH:  # this subtree in a file of its own
            part = "%s-part%d.xml" % (base, k + 1)
            sub = ["<mujocoinclude>"]
            body(k, pos, 0, sub)
            sub.append("</mujocoinclude>")
            with open(part, "w") as f:
                f.write("\n".join(sub) + "\n")
            out.append('<include file="%s"/>' % os.path.basename(part))
            return
        _, d = link(shape, k, n)
        second = "0 0 1" if d == (1, 0, 0) else "1 0 0"
        ind = "  " * depth
        out.append('%s<body name="%s" pos="%g %g %g">'
                   % ((ind, "last" if k == n - 1 else "B%d" % (k + 1)) + pos))
        out.append('%s  <joint type="hinge" axis="0 1 0"/>' % ind)
        if not planar:
            out.append('%s  <joint type="hinge" axis="%s"/>' % (ind, second))
        out.append('%s  <inertial pos="%g %g %g" mass="1" diaginertia="1e-12 1e-12 1e-12"/>'
                   % ((ind,) + d))
        for c in children[k]:
            body(c, d, depth + 1, out)
        out.append('%s</body>' % ind)

    out = ['<mujoco model="%s%d">' % (shape, n),
           '  <compiler angle="radian" inertiafromgeom="false"/>',
           '  <option timestep="0.001" gravity="0 0 -9.81" integrator="RK4">',
           '    <flag contact="disable" constraint="disable" equality="disable"'
           ' frictionloss="disable" limit="disable" passive="disable" actuation="disable"'
           ' clampctrl="disable" warmstart="disable" sensor="disable"/>',
           '  </option>',
           '  <worldbody>']
    sys.setrecursionlimit(10 * n + 100)
    for c in children[-1]:
        body(c, (0, 0, 0), 0, out)
    out += ['  </worldbody>', '</mujoco>']
    with open(path, "w") as f:
        f.write("\n".join(out) + "\n")


main()
