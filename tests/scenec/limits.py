#!/usr/bin/env python3
"""limits.py - every compile-time limit a scene file can reach, at the limit and one past
it (docs/reliability.md): at the limit the scene runs; one past, `modrt run` exits 2 with
one line naming the place, the number and the macro. Also the numeric ranges of the end
time and the CLI. The limits are read from rt/rt_config.h and the defaults its list writes
into rt/rt_limits.h, so the test follows them.
Usage: limits.py MODRT"""
import os
import re
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
CFG = "".join(open(os.path.join(ROOT, "rt", h)).read() for h in ("rt_config.h", "rt_limits.h"))
LIM = {m.group(1): int(m.group(2)) for m in re.finditer(r"#define (RT_\w+) (\d+)\b", CFG)}
TMP = os.path.join(ROOT, "build", "limits")
os.makedirs(TMP, exist_ok=True)
HEAD = "base tick (1 ms);\nend time (2 ms);\n"
passed = failed = 0


def run(modrt, text, *args):
    path = os.path.join(TMP, "limit.scn")
    with open(path, "w") as f:
        f.write(text)
    p = subprocess.run([modrt, "run", path] + list(args), capture_output=True, text=True,
                       timeout=60)
    return p.returncode, p.stdout + p.stderr


def check(ok, what):
    global passed, failed
    if ok:
        passed += 1
    else:
        failed += 1
        print("FAIL limits: " + what)


def systems(n):
    """n oscillators, 32 per load statement"""
    out = []
    for k in range(0, n, 32):
        names = ", ".join("O%d" % i for i in range(k, min(n, k + 32)))
        out.append("load system (%s) of type (oscillator);" % names)
    return "\n".join(out) + "\n"


def scene_systems(n):
    return HEAD + systems(n)


def scene_sets(n):
    return HEAD + systems(n) + "".join(
        "set (s%d) method (rk4) step (1 tick) members (O%d);\n" % (i, i) for i in range(n))


def scene_recs(n):
    return HEAD + systems(1) + "record (%s);\n" % ", ".join(["O0.x"] * n)


def scene_conns(n):
    """gains in a chain: each connection feeds one gain's input"""
    blocks = (n + 1 + 63) // 64  # not needed: one source, n sinks in groups
    text = HEAD + "load system (S) of type (oscillator);\n"
    k = 0
    body = []
    gains = []
    while k < n:
        g = "G%d" % len(gains)
        gains.append(g)
        body.append("connect(S.x, %s.u);" % g)
        k += 1
    text += "load system (%s) of type (gain) from file (\"algebra\");\n" % ", ".join(gains)
    return text + "\n".join(body) + "\n"


def scene_joints(n):
    text = HEAD + "load system (B) of type (mbs_point) from file (\"mbs_point\");\nB.x = 1;\n"
    names = ["J%d" % i for i in range(n)]
    text += "load joint (%s) of type (sphdiff);\n" % ", ".join(names)
    text += "".join("%s.l = 1;\n" % j for j in names)
    text += "".join("link(B.c, ground) by (%s);\n" % j for j in names)
    text += "stabilization (project);\n"
    return text


CASES = [  # (what, macro, scene of n): the scene compiler refuses n + 1
    ("systems", "RT_MAX_BLOCKS", scene_systems),
    ("sets", "RT_MAX_SETS", scene_sets),
    ("recorded signals", "RT_MAX_REC", scene_recs),
    ("joints", "RT_MAX_JOINTS", scene_joints),
]


def limit_text(macro, n):
    """what a capacity message says of the limit: its macro and value, from RT_LIMIT_LIST's
    row (the words it counts are the row's own)"""
    return "%s (%d in rt_config.h)" % (macro, n)


def scene_implicit(n):
    """n states in one set of an implicit method: oscillators of two"""
    return HEAD + systems((n + 1) // 2) + "set (main) method (sdirk2) step (1 tick);\n"


def scene_spherical(n):
    """n spherical joints (3 rows each) on one point mass, all in its set"""
    text = HEAD + "load system (B) of type (mbs_point) from file (\"mbs_point\");\n"
    names = ["J%d" % i for i in range(n)]
    text += "load joint (%s) of type (spherical);\n" % ", ".join(names)
    text += "".join("link(B.c, ground) by (%s);\n" % j for j in names)
    return text + "stabilization (project);\n"


RUNTIME_CASES = [  # (scene past a limit rt_init checks, the text it must give)
    (scene_implicit(LIM["RT_MAX_IMPLICIT_N"] + 1),
     "set main: states of a set with an implicit method exceed " +
     limit_text("RT_MAX_IMPLICIT_N", LIM["RT_MAX_IMPLICIT_N"])),
    # the joint whose rows no longer fit its set, by the one limit it passes (RT_MAX_MBS_C,
    # not also RT_MAX_MBS_JROWS, which holds them)
    (scene_spherical(LIM["RT_MAX_MBS_C"] // 3 + 1),
     "joint J%d: constraints of a multibody set exceed %s" % (
         LIM["RT_MAX_MBS_C"] // 3, limit_text("RT_MAX_MBS_C", LIM["RT_MAX_MBS_C"]))),
]


def limit_cases(modrt):
    for what, macro, make in CASES:
        n = LIM[macro]
        rc, out = run(modrt, make(n), "--t-end", "0.001")
        check(rc in (0, 1, 3), "%s at the limit %d: exit %d: %s" % (what, n, rc, out[-300:]))
        rc, out = run(modrt, make(n + 1))
        lines = out.strip().splitlines()
        check(rc == 2 and len(lines) == 1 and ("too many %s" % what) in out and
              limit_text(macro, n) in out,
              "%s one past the limit %d: exit %d: %s" % (what, n, rc, out[-300:]))
        print("limits: %-16s %s = %d: at the limit runs, one past: %s" % (what, macro, n,
                                                                          lines[-1] if lines else ""))
    for text, want in RUNTIME_CASES:
        rc, out = run(modrt, text)
        lines = out.strip().splitlines()
        check(rc == 2 and len(lines) == 1 and want in out,
              "rt_init past a limit: exit %d: %s\nwanted: %s" % (rc, out[-300:], want))
        print("limits: rt_init one past: %s" % (lines[-1] if lines else ""))


def end_time_cases(modrt):
    """the end time: whole ticks, not negative, at most 2^53 ticks, from the scene and
    from --t-end; every refusal one line, exit 2"""
    base = HEAD.replace("end time (2 ms);", "end time (%s);") + systems(1)
    for t, ok in (("1e-3 s", True), ("0.0015 s", False), ("1e300 s", False),
                  ("9007199254740.992 s", True), ("9007199254741 s", False)):
        rc, out = run(modrt, base % t, "--t-end", "0.002") if ok else run(modrt, base % t)
        check((rc in (0, 3)) if ok else (rc == 2 and len(out.strip().splitlines()) == 1),
              "end time (%s): exit %d: %s" % (t, rc, out[-200:]))
    for v in ("1e308", "2e16", "-1", "nan", "0.0005", "1e19"):
        rc, out = run(modrt, base % "1 s", "--t-end", v)
        check(rc == 2 and len(out.strip().splitlines()) == 1,
              "--t-end %s: exit %d: %s" % (v, rc, out[-200:]))


BALL = HEAD + "load system (Ball) of type (ball) from file (\"ball\");\n"


def one_line_refusal(rc, out):
    return rc == 2 and len(out.strip().splitlines()) == 1


def cli_cases(modrt):
    """every numeric option of `modrt run`: at its limit it runs, one past it is refused
    with one line and exit 2"""
    sdirk = BALL + "set (main) method (sdirk2) step (1 tick);\n"
    cases = [  # (scene, option, value at the limit, value one past)
        (BALL, "--every", "1000000000", "1000000001"), (BALL, "--every", "1", "0"),
        (BALL, "--link-timeout", "3600", "3600.5"), (BALL, "--link-timeout", "1e-9", "0"),
        (BALL, "--step", "main=0.001", "main=0.0005"), (BALL, "--step", "main=0.002", "main=0"),
        (sdirk, "--tol", "main=1e-300", "main=0"), (sdirk, "--accuracy", "main=1e-300", "main=-1"),
        (sdirk, "--accuracy", "main=1e-3,1e-300", "main=1e-3,0"),
        (sdirk, "--substeps", "main=128", "main=129"), (sdirk, "--substeps", "main=1", "main=3"),
        (sdirk, "--newton", "main=255", "main=256"), (sdirk, "--newton", "main=1", "main=0"),
        (BALL, "--set", "Ball.e=1", "Ball.e=1.0000001"), (BALL, "--set", "Ball.g=1e-300", "Ball.g=0"),
        (BALL, "--t-end", "0.002", "0.0025"),
    ]
    for scene, opt, ok_v, bad_v in cases:
        rc, out = run(modrt, scene, opt, ok_v)
        check(rc in (0, 1, 3), "%s %s at the limit: exit %d: %s" % (opt, ok_v, rc, out[-200:]))
        rc, out = run(modrt, scene, opt, bad_v)
        check(one_line_refusal(rc, out), "%s %s one past: exit %d: %s" % (opt, bad_v, rc, out[-200:]))


def tune_cases(modrt):
    """the numeric options of `modrt tune` at their limit and one past"""
    cases = [(["--tol", "1e-300"], ["--tol", "0"]),
             (["--tol", "1e-3", "--doublings", "12"], ["--tol", "1e-3", "--doublings", "13"]),
             (["--tol", "1e-3", "--ref-div", "1024"], ["--tol", "1e-3", "--ref-div", "2048"]),
             (["--tol", "1e-3", "--ref-div", "2"], ["--tol", "1e-3", "--ref-div", "3"])]
    for ok_args, bad_args in cases:
        p = subprocess.run([modrt, "tune", "oscillator"] + ok_args, capture_output=True,
                           text=True, timeout=120)
        check(p.returncode in (0, 1), "tune %s at the limit: exit %d" % (ok_args, p.returncode))
        p = subprocess.run([modrt, "tune", "oscillator"] + bad_args, capture_output=True,
                           text=True, timeout=120)
        check(one_line_refusal(p.returncode, p.stderr),
              "tune %s one past: exit %d: %s" % (bad_args, p.returncode, p.stderr[-200:]))


def scene_cases(modrt):
    """the numeric clauses of the scene language at their limit and one past"""
    def sset(clause):
        return BALL + "set (main) method (sdirk2) step (1 tick) %s;\n" % clause
    loops = HEAD + systems(1) + "solve loops by (broyden) iterations (%s);\n"
    cases = [
        (sset("newton (255)"), sset("newton (256)")), (sset("newton (1)"), sset("newton (0)")),
        (sset("jacobian (65535)"), sset("jacobian (65536)")),
        (sset("substeps (128)"), sset("substeps (129)")), (sset("substeps (2)"), sset("substeps (3)")),
        (sset("tolerance (1e-300)"), sset("tolerance (0)")),
        (sset("accuracy (1e-300)"), sset("accuracy (0)")),
        (sset("accuracy (1e-3, 1e-300)"), sset("accuracy (1e-3, 0)")),
        (loops % LIM["RT_LOOP_ITER_LIMIT"], loops % (LIM["RT_LOOP_ITER_LIMIT"] + 1)),
        (BALL + "set (main) method (rk4) step (2 ms);\n",
         BALL + "set (main) method (rk4) step (1.5 ms);\n"),
        (HEAD.replace("base tick (1 ms)", "base tick (1e-300 s)").replace("2 ms", "2e-300 s") +
         systems(1), HEAD.replace("base tick (1 ms)", "base tick (0 s)") + systems(1)),
        (BALL + "Ball.e = 1;\n", BALL + "Ball.e = 1.0000001;\n"),
    ]
    for ok_text, bad_text in cases:
        rc, out = run(modrt, ok_text, "--t-end", "0") if "1e-300 s" in ok_text else run(modrt, ok_text)
        check(rc in (0, 1, 3), "scene at the limit: exit %d: %s\n%s" % (rc, out[-200:], ok_text))
        rc, out = run(modrt, bad_text)
        check(one_line_refusal(rc, out), "scene one past: exit %d: %s\n%s" % (rc, out[-200:], bad_text))


def main():
    modrt = sys.argv[1]
    limit_cases(modrt)
    end_time_cases(modrt)
    cli_cases(modrt)
    tune_cases(modrt)
    scene_cases(modrt)
    print("limits: %d passed, %d failed" % (passed, failed))
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
