/* pendulum_tight.c - the tightest hand-written program of scene pendulum10 that computes
 * what modrt computes: the yardstick of modrt's overhead on it (docs/overhead.md).
 *
 * The formulation and method of modrt's (pendulum_mono.c says them: ten Cartesian mass
 * points of 1 kg, ten distance constraints of 1 m, index-1 multipliers from the Schur
 * complement A = W M^-1 W^T, the projection of eq. 10 after every step, the explicit
 * Runge-Kutta tableaus and error estimates of rt/integ_erk.c), written as a performance
 * engineer writes it for this one scene:
 *   - a chain makes A tridiagonal: it is factored by the Thomas algorithm (LDL^T) in the
 *     same sweep that forms link k's direction, A's row k and eliminates it; the backward
 *     sweep gives lam_k and body k's acceleration together (no W, no A stored; the
 *     kernels are tight_chain.h's);
 *   - the unit mass and unit length are folded in, gravity acts on z only;
 *   - each method's stage sums are written out over the nonzero coefficients only, the
 *     positions' and velocities' sums in one loop; the positions' stage derivatives are
 *     the stage velocities, never copied;
 *   - the projection fuses its geometry, factorization and solves the same way.
 * The sums run in modrt's order, so the trajectories equal modrt's up to rounding in the
 * Schur complement's solve (tested to 1e-12 m: overhead_bench check). With estimate = 1
 * the step also computes modrt's embedded error estimate (one evaluation more) and the
 * projection's largest residual, as modrt's step does. */
#include "pendulum_tight.h"

#define TC_NB TIGHT_NB
#include "tight_chain.h"

#define NB TIGHT_NB
#define N3 (3 * NB)
#define AI TC_AI

/* accelerations a at positions q, velocities v (tight_chain.h) */
static void accel(const double *restrict q, const double *restrict v, double *restrict a)
{
    tc_accel(q, v, a, 3, 0, 0, 0);
}

/* the projection of eq. 10; the largest |g| after it */
static double project(double *restrict q, double *restrict v)
{
    return tc_project(q, v, 3);
}

/* ------------------------------------------------------------------ Runge-Kutta */

/* the stage buffers: stage velocities (the positions' derivatives) and accelerations */
typedef struct stages {
    double v[7][N3], a[7][N3];
} stages;

/* qs = q0 + h sum_j c_j vs_j, vs = v0 + h sum_j c_j as_j over the n nonzero terms (stage
   indices ix), summed from the first as modrt sums them */
AI void comb(double *restrict qs, double *restrict vs, const double *q0, const double *v0,
             double h, const stages *w, int n, const double *c, const int *ix)
{
    for (int m = 0; m < N3; m++) {
        double aq = 0, av = 0;
#pragma GCC unroll 7
        for (int j = 0; j < n; j++)
            aq += c[j] * w->v[ix[j]][m], av += c[j] * w->a[ix[j]][m];
        qs[m] = q0[m] + h * aq;
        vs[m] = v0[m] + h * av;
    }
}

/* max_m |h (sum_j c_j k_jm + ce kx_m)| / (1 + |x1_m|) for the positions (k: stage
   velocities, kx: vx) and the velocities (k: accelerations, kx: ax) */
AI double estimate(const double *q1, const double *v1, double h, const stages *w, int n,
                   const double *c, const int *ix, double ce, const double *vx,
                   const double *ax)
{
    double mx = 0;
    for (int m = 0; m < N3; m++) {
        double aq = 0, av = 0;
#pragma GCC unroll 7
        for (int j = 0; j < n; j++)
            aq += c[j] * w->v[ix[j]][m], av += c[j] * w->a[ix[j]][m];
        aq = aq + ce * vx[m], av = av + ce * ax[m];
        double rq = fabs(h * aq) / (1 + fabs(q1[m])), rv = fabs(h * av) / (1 + fabs(v1[m]));
        mx = rq > mx ? rq : mx;
        mx = rv > mx ? rv : mx;
    }
    return mx;
}

#define C(...) (const double[]){__VA_ARGS__}
#define I(...) (const int[]){__VA_ARGS__}

/* the step's start: v0 is stage 0's velocity, f(x0) its acceleration */
static void start(tight *m, stages *w, double *q0, double *v0)
{
    for (int i = 0; i < N3; i++)
        q0[i] = m->q[i], v0[i] = w->v[0][i] = m->v[i];
    accel(q0, v0, w->a[0]);
}

static double step_bs3(tight *m, stages *w)
{
    double q0[N3], v0[N3], qs[N3], h = m->h, *q = m->q, *v = m->v;
    start(m, w, q0, v0);
    comb(qs, w->v[1], q0, v0, h, w, 1, C(0.5), I(0));
    accel(qs, w->v[1], w->a[1]);
    comb(qs, w->v[2], q0, v0, h, w, 1, C(0.75), I(1));
    accel(qs, w->v[2], w->a[2]);
    comb(q, v, q0, v0, h, w, 3, C(2.0 / 9.0, 1.0 / 3.0, 4.0 / 9.0), I(0, 1, 2));
    if (!m->estimate)
        return 0;
    accel(q, v, w->a[3]); /* f(t + h, x1) */
    return estimate(q, v, h, w, 3, C(-5.0 / 72.0, 1.0 / 12.0, 1.0 / 9.0), I(0, 1, 2),
                    -1.0 / 8.0, v, w->a[3]);
}

static double step_rk4(tight *m, stages *w)
{
    double q0[N3], v0[N3], qs[N3], h = m->h, *q = m->q, *v = m->v;
    start(m, w, q0, v0);
    comb(qs, w->v[1], q0, v0, h, w, 1, C(0.5), I(0));
    accel(qs, w->v[1], w->a[1]);
    comb(qs, w->v[2], q0, v0, h, w, 1, C(0.5), I(1));
    accel(qs, w->v[2], w->a[2]);
    comb(qs, w->v[3], q0, v0, h, w, 1, C(1.0), I(2));
    accel(qs, w->v[3], w->a[3]);
    if (m->estimate) { /* the estimate's own stage at t + 3h/4 */
        comb(qs, w->v[4], q0, v0, h, w, 2, C(3.0 / 16.0, 9.0 / 16.0), I(0, 2));
        accel(qs, w->v[4], w->a[4]);
    }
    comb(q, v, q0, v0, h, w, 4, C(1.0 / 6.0, 1.0 / 3.0, 1.0 / 3.0, 1.0 / 6.0), I(0, 1, 2, 3));
    if (!m->estimate)
        return 0;
    return estimate(q, v, h, w, 4, C(1.0 / 32.0, -3.0 / 32.0, -3.0 / 32.0, -3.0 / 32.0),
                    I(0, 1, 2, 3), 1.0 / 4.0, w->v[4], w->a[4]);
}

static double step_dopri5(tight *m, stages *w)
{
    double q0[N3], v0[N3], qs[N3], h = m->h, *q = m->q, *v = m->v;
    start(m, w, q0, v0);
    comb(qs, w->v[1], q0, v0, h, w, 1, C(1.0 / 5.0), I(0));
    accel(qs, w->v[1], w->a[1]);
    comb(qs, w->v[2], q0, v0, h, w, 2, C(3.0 / 40.0, 9.0 / 40.0), I(0, 1));
    accel(qs, w->v[2], w->a[2]);
    comb(qs, w->v[3], q0, v0, h, w, 3, C(44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0), I(0, 1, 2));
    accel(qs, w->v[3], w->a[3]);
    comb(qs, w->v[4], q0, v0, h, w, 4,
         C(19372.0 / 6561.0, -25360.0 / 2187.0, 64448.0 / 6561.0, -212.0 / 729.0),
         I(0, 1, 2, 3));
    accel(qs, w->v[4], w->a[4]);
    comb(qs, w->v[5], q0, v0, h, w, 5,
         C(9017.0 / 3168.0, -355.0 / 33.0, 46732.0 / 5247.0, 49.0 / 176.0, -5103.0 / 18656.0),
         I(0, 1, 2, 3, 4));
    accel(qs, w->v[5], w->a[5]);
    comb(q, v, q0, v0, h, w, 5,
         C(35.0 / 384.0, 500.0 / 1113.0, 125.0 / 192.0, -2187.0 / 6784.0, 11.0 / 84.0),
         I(0, 2, 3, 4, 5));
    if (!m->estimate)
        return 0;
    accel(q, v, w->a[6]); /* f(t + h, x1) */
    return estimate(q, v, h, w, 5,
                    C(71.0 / 57600.0, -71.0 / 16695.0, 71.0 / 1920.0, -17253.0 / 339200.0,
                      22.0 / 525.0),
                    I(0, 2, 3, 4, 5), -1.0 / 40.0, v, w->a[6]);
}

/* ------------------------------------------------------------------ API */

void tight_init(tight *m, const double *x0)
{
    for (int k = 0; k < NB; k++)
        for (int i = 0; i < 3; i++)
            m->q[3 * k + i] = x0[6 * k + i], m->v[3 * k + i] = x0[6 * k + 3 + i];
    m->res_max = project(m->q, m->v);
    m->err_max = 0;
}

__attribute__((noinline)) void tight_steps(tight *m, long n)
{
    static stages w;
    for (long i = 0; i < n; i++) {
        double e = m->method == TIGHT_BS3   ? step_bs3(m, &w)
                   : m->method == TIGHT_RK4 ? step_rk4(m, &w)
                                            : step_dopri5(m, &w);
        m->err_max = e != e || e > m->err_max ? e : m->err_max;
        double r = project(m->q, m->v);
        if (m->estimate)
            m->res_max = r <= m->res_max ? m->res_max : r;
    }
}
