/* pendulum_mono.c - the hand-written monolith of scene pendulum10: the program a
 * competent engineer writes for the same formulation without a runtime, the yardstick of
 * modrt's modular overhead (docs/overhead.md).
 *
 * Ten Cartesian mass points, ten distance constraints |r_k - r_(k-1)| - l = 0 (eq. 8; r_0
 * the anchor at the origin); index-1 multipliers from the Schur complement
 * A = W M^-1 W^T (eqs. 7b, 9), solved densely by Gaussian elimination with partial
 * pivoting (MONO_DENSE) or, using that a chain makes A tridiagonal, by the Thomas
 * algorithm (MONO_THOMAS); after every step the mass-weighted projection of eq. 10 (two
 * position iterations with W and A frozen at the predicted state, one velocity solve);
 * the explicit Runge-Kutta methods with the tableaus of rt/integ_erk.c and, like modrt's
 * steps, the embedded error estimate (one derivative more at the step's end) unless
 * mono.estimate is 0. The state is laid out as modrt lays out pendulum10's: per body
 * x, y, z, vx, vy, vz. Plain C, no runtime, no tables, no look-ups. */
#include "pendulum_chain.h"

/* ------------------------------------------------------------------ right-hand side */

/* x' for the chain: q' = v, z' = a - M^-1 W^T lam, A lam = W a + gam, a = g (eqs. 6, 7b) */
static void rhs(const double *x, double *xd, int solver)
{
    chain c;
    factors f;
    double lam[NB];
    geometry(x, &c, 1);
    factor(&c, solver, &f);
    /* W a + gam with a = (0, 0, g) for every body: internal links see no relative
       free acceleration, the first link sees e_1 . a */
    for (int k = 0; k < NB; k++)
        lam[k] = c.gam[k] + (k ? 0 : c.e[0][2] * G_Z);
    solve(&f, solver, lam);
    for (int k = 0; k < NB; k++)
        for (int i = 0; i < 3; i++) {
            xd[6 * k + i] = x[6 * k + 3 + i];
            xd[6 * k + 3 + i] = i == 2 ? G_Z : 0;
        }
    apply(&c, lam, xd, 1);
}

/* ------------------------------------------------------------------ Runge-Kutta */

static const double bs3_a[] = {0, 0, 0, 0.5, 0, 0, 0, 0.75, 0};
static const double bs3_b[] = {2.0 / 9.0, 1.0 / 3.0, 4.0 / 9.0};
static const double bs3_c[] = {0, 0.5, 0.75};
static const double bs3_e[] = {-5.0 / 72.0, 1.0 / 12.0, 1.0 / 9.0, -1.0 / 8.0};
static const double rk4_a[] = {0, 0, 0, 0, 0.5, 0, 0, 0, 0, 0.5, 0, 0, 0, 0, 1, 0};
static const double rk4_b[] = {1.0 / 6.0, 1.0 / 3.0, 1.0 / 3.0, 1.0 / 6.0};
static const double rk4_c[] = {0, 0.5, 0.5, 1};
static const double rk4_e[] = {0, 0, 0, 1.0 / 6.0, -1.0 / 6.0};
static const double dp5_a[] = {
    0, 0, 0, 0, 0, 0,
    1.0 / 5.0, 0, 0, 0, 0, 0,
    3.0 / 40.0, 9.0 / 40.0, 0, 0, 0, 0,
    44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0, 0, 0, 0,
    19372.0 / 6561.0, -25360.0 / 2187.0, 64448.0 / 6561.0, -212.0 / 729.0, 0, 0,
    9017.0 / 3168.0, -355.0 / 33.0, 46732.0 / 5247.0, 49.0 / 176.0, -5103.0 / 18656.0, 0,
};
static const double dp5_b[] = {35.0 / 384.0, 0, 500.0 / 1113.0, 125.0 / 192.0,
                               -2187.0 / 6784.0, 11.0 / 84.0};
static const double dp5_c[] = {0, 1.0 / 5.0, 3.0 / 10.0, 4.0 / 5.0, 8.0 / 9.0, 1};
static const double dp5_e[] = {71.0 / 57600.0, 0, -71.0 / 16695.0, 71.0 / 1920.0,
                               -17253.0 / 339200.0, 22.0 / 525.0, -1.0 / 40.0};

typedef struct tab {
    int s;
    const double *a, *b, *c, *e;
} tab;
static const tab tabs[] = {
    [MONO_BS3] = {3, bs3_a, bs3_b, bs3_c, bs3_e},
    [MONO_RK4] = {4, rk4_a, rk4_b, rk4_c, rk4_e},
    [MONO_DOPRI5] = {6, dp5_a, dp5_b, dp5_c, dp5_e},
};

/* one step of h, then the projection; returns the scaled error estimate (0 without) */
static double step(const mono *m, double *x)
{
    const tab *t = &tabs[m->method];
    double k[8][NX], x0[NX], xs[NX];
    for (int i = 0; i < NX; i++)
        x0[i] = x[i];
    for (int s = 0; s < t->s; s++) {
        for (int i = 0; i < NX; i++) {
            double acc = 0;
            for (int j = 0; j < s; j++)
                acc += t->a[s * t->s + j] * k[j][i];
            xs[i] = x0[i] + m->h * acc;
        }
        rhs(xs, k[s], m->solver);
    }
    for (int i = 0; i < NX; i++) {
        double acc = 0;
        for (int j = 0; j < t->s; j++)
            acc += t->b[j] * k[j][i];
        x[i] = x0[i] + m->h * acc;
    }
    double err = 0;
    if (m->estimate) { /* the embedded estimate needs f at the step's end */
        rhs(x, k[t->s], m->solver);
        for (int i = 0; i < NX; i++) {
            double acc = 0;
            for (int j = 0; j <= t->s; j++)
                acc += t->e[j] * k[j][i];
            double r = fabs(m->h * acc) / (1 + fabs(x[i]));
            err = r > err ? r : err;
        }
    }
    project(x, m->solver);
    return err;
}

/* ------------------------------------------------------------------ API */

void mono_init(mono *m, const double *x0)
{
    for (int i = 0; i < NX; i++)
        m->x[i] = x0[i];
    project(m->x, m->solver);
    m->err_max = 0;
}

__attribute__((noinline)) void mono_steps(mono *m, long n)
{
    for (long i = 0; i < n; i++) {
        double e = step(m, m->x);
        m->err_max = e > m->err_max ? e : m->err_max;
    }
}
