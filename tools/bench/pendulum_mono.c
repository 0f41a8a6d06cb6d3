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
#include "pendulum_mono.h"

#include <math.h>

#define NB MONO_NB  /* bodies = constraints */
#define NX (6 * NB) /* states */
static const double G_Z = -9.81; /* gravity [m/s^2] */
static const double LEN = 1;     /* link length [m] */
static const double MASS = 1;    /* point mass [kg] */

/* ------------------------------------------------------------------ the Schur complement */

/* the chain's constraint geometry at positions q (velocities v may be NULL):
   unit directions e_k of link k (body k minus body k-1), g_k, g'_k and the acceleration
   term gam_k = (|d'|^2 - (e.d')^2) / |d| */
typedef struct chain {
    double e[NB][3], len[NB], g[NB], gd[NB], gam[NB];
} chain;

static void geometry(const double *x, chain *c, int vel)
{
    for (int k = 0; k < NB; k++) {
        const double *r = x + 6 * k, *p = k ? x + 6 * (k - 1) : 0;
        double d[3], dd[3], s = 0;
        for (int i = 0; i < 3; i++) {
            d[i] = r[i] - (p ? p[i] : 0);
            dd[i] = vel ? r[3 + i] - (p ? p[3 + i] : 0) : 0;
            s += d[i] * d[i];
        }
        double len = sqrt(s), ed = 0, dd2 = 0;
        c->len[k] = len;
        c->g[k] = len - LEN;
        for (int i = 0; i < 3; i++) {
            c->e[k][i] = d[i] / len;
            ed += c->e[k][i] * dd[i];
            dd2 += dd[i] * dd[i];
        }
        c->gd[k] = ed;
        c->gam[k] = (dd2 - ed * ed) / len;
    }
}

/* A = W M^-1 W^T: W has row k = [.. -e_k (body k-1) .. +e_k (body k) ..]; dense storage */
static void schur(const chain *c, double A[NB][NB])
{
    for (int k = 0; k < NB; k++)
        for (int j = 0; j < NB; j++)
            A[k][j] = 0;
    for (int k = 0; k < NB; k++) {
        const double *e = c->e[k];
        A[k][k] = (e[0] * e[0] + e[1] * e[1] + e[2] * e[2]) / MASS * (k ? 2 : 1);
        if (k) {
            const double *f = c->e[k - 1];
            double off = -(e[0] * f[0] + e[1] * f[1] + e[2] * f[2]) / MASS;
            A[k][k - 1] = A[k - 1][k] = off;
        }
    }
}

/* Gaussian elimination with partial pivoting, in place; then solves for each b */
static void lu(double A[NB][NB], int piv[NB])
{
    for (int k = 0; k < NB; k++) {
        int p = k;
        for (int i = k + 1; i < NB; i++)
            if (fabs(A[i][k]) > fabs(A[p][k]))
                p = i;
        piv[k] = p;
        if (p != k)
            for (int j = 0; j < NB; j++) {
                double t = A[k][j];
                A[k][j] = A[p][j], A[p][j] = t;
            }
        for (int i = k + 1; i < NB; i++) {
            double l = A[i][k] /= A[k][k];
            for (int j = k + 1; j < NB; j++)
                A[i][j] -= l * A[k][j];
        }
    }
}

static void lu_solve(double A[NB][NB], const int piv[NB], double *b)
{
    for (int k = 0; k < NB; k++) {
        double t = b[piv[k]];
        b[piv[k]] = b[k], b[k] = t;
    }
    for (int i = 1; i < NB; i++)
        for (int j = 0; j < i; j++)
            b[i] -= A[i][j] * b[j];
    for (int i = NB - 1; i >= 0; i--) {
        for (int j = i + 1; j < NB; j++)
            b[i] -= A[i][j] * b[j];
        b[i] /= A[i][i];
    }
}

/* the factored Schur complement: dense LU, or the tridiagonal factors of Thomas */
typedef struct factors {
    double A[NB][NB];
    int piv[NB];
    double dia[NB], low[NB]; /* Thomas: pivots and multipliers */
} factors;

static void factor(const chain *c, int solver, factors *f)
{
    schur(c, f->A);
    if (solver == MONO_DENSE) {
        lu(f->A, f->piv);
        return;
    }
    /* symmetric tridiagonal: LDL^T, low[k] = A[k][k-1] / dia[k-1] */
    f->dia[0] = f->A[0][0];
    for (int k = 1; k < NB; k++) {
        f->low[k] = f->A[k][k - 1] / f->dia[k - 1];
        f->dia[k] = f->A[k][k] - f->low[k] * f->A[k][k - 1];
    }
}

static void solve(factors *f, int solver, double *b)
{
    if (solver == MONO_DENSE) {
        lu_solve(f->A, f->piv, b);
        return;
    }
    for (int k = 1; k < NB; k++)
        b[k] -= f->low[k] * b[k - 1];
    b[NB - 1] /= f->dia[NB - 1];
    for (int k = NB - 2; k >= 0; k--)
        b[k] = b[k] / f->dia[k] - f->low[k + 1] * b[k + 1];
}

/* dz = -M^-1 W^T lam, added to the velocity (vel) or position part of x */
static void apply(const chain *c, const double *lam, double *x, int vel)
{
    for (int k = 0; k < NB; k++)
        for (int i = 0; i < 3; i++) {
            double f = c->e[k][i] * lam[k] - (k + 1 < NB ? c->e[k + 1][i] * lam[k + 1] : 0);
            x[6 * k + 3 * vel + i] -= f / MASS;
        }
}

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

/* ------------------------------------------------------------------ projection (eq. 10) */

static void project(double *x, int solver)
{
    chain c, c2;
    factors f;
    double v[NB];
    geometry(x, &c, 0);
    factor(&c, solver, &f);
    for (int it = 0; it < 2; it++) { /* W, A frozen at the predicted state */
        if (it)
            geometry(x, &c2, 0);
        for (int k = 0; k < NB; k++)
            v[k] = it ? c2.g[k] : c.g[k];
        solve(&f, solver, v);
        apply(&c, v, x, 0);
    }
    geometry(x, &c, 1); /* velocities at the projected positions */
    factor(&c, solver, &f);
    for (int k = 0; k < NB; k++)
        v[k] = c.gd[k];
    solve(&f, solver, v);
    apply(&c, v, x, 1);
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
