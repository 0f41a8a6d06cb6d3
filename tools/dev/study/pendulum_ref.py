#!/usr/bin/python3
"""pendulum_ref.py - an independent reference for scene pendulum10 (python3 stdlib only):
the chain of ten 1 kg mass points on 1 m rods, released at rest along +x, in minimal
coordinates (ten link angles from the downward vertical, Lagrange's equations, solved
densely), integrated by the classic Runge-Kutta method in binary64 at two steps. Prints
the positions (x, z) of B1..B10 at t = 2 s for each step, one line per step:

    h <step> x1 z1 x2 z2 ... x10 z10

Nothing of modrt is used: the formulation (angles instead of Cartesian coordinates with
constraints and projection) and the code are separate. Usage: pendulum_ref.py [H ...]"""
import math
import sys

N, L, M, G = 10, 1.0, 1.0, 9.81
MU = [M * (N - i) for i in range(N)]  # mass hanging from link i (0-based) and below


def rhs(phi, om):
    """angular accelerations: sum_j mu_max(i,j) l^2 [cos(phi_i - phi_j) a_j
    + sin(phi_i - phi_j) om_j^2] + mu_i g l sin(phi_i) = 0"""
    s = [math.sin(p) for p in phi]
    c = [math.cos(p) for p in phi]
    a = [[0.0] * (N + 1) for _ in range(N)]
    for i in range(N):
        row, b = a[i], -MU[i] * G * L * s[i]
        for j in range(N):
            mu = MU[max(i, j)] * L * L
            cij = c[i] * c[j] + s[i] * s[j]
            sij = s[i] * c[j] - c[i] * s[j]
            row[j] = mu * cij
            b -= mu * sij * om[j] * om[j]
        row[N] = b
    # Gaussian elimination (the matrix is symmetric positive definite: no pivoting)
    for k in range(N):
        piv = a[k][k]
        rk = a[k]
        for i in range(k + 1, N):
            f = a[i][k] / piv
            if f:
                ri = a[i]
                for j in range(k, N + 1):
                    ri[j] -= f * rk[j]
    x = [0.0] * N
    for i in range(N - 1, -1, -1):
        v = a[i][N]
        for j in range(i + 1, N):
            v -= a[i][j] * x[j]
        x[i] = v / a[i][i]
    return x


def run(h, t_end=2.0):
    phi = [math.pi / 2] * N
    om = [0.0] * N
    steps = round(t_end / h)
    for _ in range(steps):
        k1p, k1o = om, rhs(phi, om)
        p2 = [p + 0.5 * h * d for p, d in zip(phi, k1p)]
        o2 = [o + 0.5 * h * d for o, d in zip(om, k1o)]
        k2p, k2o = o2, rhs(p2, o2)
        p3 = [p + 0.5 * h * d for p, d in zip(phi, k2p)]
        o3 = [o + 0.5 * h * d for o, d in zip(om, k2o)]
        k3p, k3o = o3, rhs(p3, o3)
        p4 = [p + h * d for p, d in zip(phi, k3p)]
        o4 = [o + h * d for o, d in zip(om, k3o)]
        k4p, k4o = o4, rhs(p4, o4)
        phi = [p + h / 6 * (a + 2 * b + 2 * c + d)
               for p, a, b, c, d in zip(phi, k1p, k2p, k3p, k4p)]
        om = [o + h / 6 * (a + 2 * b + 2 * c + d)
              for o, a, b, c, d in zip(om, k1o, k2o, k3o, k4o)]
    out, x, z = [], 0.0, 0.0
    for p in phi:
        x += L * math.sin(p)
        z -= L * math.cos(p)
        out += [x, z]
    return out


if __name__ == "__main__":
    for a in sys.argv[1:] or ["2e-4", "1e-4"]:
        h = float(a)
        print("h %s %s" % (a, " ".join("%.17g" % v for v in run(h))), flush=True)
