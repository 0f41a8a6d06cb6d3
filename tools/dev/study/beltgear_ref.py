#!/usr/bin/python3
"""beltgear_ref.py - an independent reference for scene beltgear (python3 stdlib only): the
belt gear of models/scenes/beltgear.scn written as one ODE in five states (motor current
i, pulley angles and speeds phi1, omega1, phi2, omega2) with the drive train's algebraic
loop solved in closed form (it is linear), integrated by the classic Runge-Kutta method
piecewise: the current command's jump at t0 = 10 ms is a step boundary and each piece
sees only its own constant command. Prints, for each step h given, the speeds every 5 ms:

    h <step> t omega1 omega2 t omega1 omega2 ...

Parameters as in the scene file and the kinds' defaults (models/beltgear.c: k = 1e5 N/m,
c = 20 N s/m, belt mass 0.5 kg). Usage: beltgear_ref.py [H ...]"""
import sys

T0, I0, I1 = 0.01, 0.0, 2.0          # command [A] before and from t0 [s]
KC, T_M = 10.0, 0.005                # v = KC (i_ref - i); T i' = v - i
KT = 0.5                             # torque constant [N m/A]
J1, R1, J2, R2 = 0.01, 0.05, 0.04, 0.1
ML = -0.2                            # load torque on pulley 2 [N m]
K, C, MB = 1e5, 20.0, 0.5            # belt stiffness, damping, mass
T_END, EVERY = 0.5, 0.005


def rhs(x, iref):
    i, p1, w1, p2, w2 = x
    m1 = KT * i
    fe = 2 * (K * (R1 * p1 - R2 * p2) + C * (R1 * w1 - R2 * w2))
    # F = fe + MB (R1 a1 - R2 a2), a1 = (m1 - R1 F) / J1, a2 = (ML + R2 F) / J2
    f = (fe + MB * R1 * m1 / J1 - MB * R2 * ML / J2) / (1 + MB * R1 * R1 / J1 +
                                                         MB * R2 * R2 / J2)
    a1 = (m1 - R1 * f) / J1
    a2 = (ML + R2 * f) / J2
    return [(KC * (iref - i) - i) / T_M, w1, a1, w2, a2]


def run(h):
    x = [0.0] * 5
    out = []
    n_end, n_jump, n_every = round(T_END / h), round(T0 / h), round(EVERY / h)
    for n in range(n_end + 1):
        if n % n_every == 0:
            out.append((n * h, x[2], x[4]))
        if n == n_end:
            break
        iref = I0 if n < n_jump else I1
        k1 = rhs(x, iref)
        k2 = rhs([a + 0.5 * h * b for a, b in zip(x, k1)], iref)
        k3 = rhs([a + 0.5 * h * b for a, b in zip(x, k2)], iref)
        k4 = rhs([a + h * b for a, b in zip(x, k3)], iref)
        x = [a + h / 6 * (b + 2 * c + 2 * d + e) for a, b, c, d, e in zip(x, k1, k2, k3, k4)]
    return out


if __name__ == "__main__":
    for a in sys.argv[1:] or ["1e-5", "5e-6"]:
        pts = run(float(a))
        print("h %s %s" % (a, " ".join("%.17g %.17g %.17g" % p for p in pts)), flush=True)
