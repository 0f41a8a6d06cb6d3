/* pendulum_chain.h - the ten-body chain of the hand-written monoliths (pendulum_mono.c for
 * scene pendulum10, actuated_mono.c for pendulum10_actuated_single, actuated_mr_mono.c for
 * the multirate pendulum10_actuated): constraint geometry,
 * the Schur complement A = W M^-1 W^T (eqs. 7b, 9) solved densely (Gauss with partial
 * pivoting, MONO_DENSE) or as the tridiagonal it is (Thomas, MONO_THOMAS), dz =
 * -M^-1 W^T lam, and the projection of eq. 10. Static functions: each monolith compiles
 * its own copy, inlined as the compiler sees fit, as if written in its file. The state is
 * laid out as modrt lays out the chain's: per body x, y, z, vx, vy, vz. */
#ifndef PENDULUM_CHAIN_H
#define PENDULUM_CHAIN_H

#include <math.h>

#include "pendulum_mono.h"

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

#endif
