/* integ_implicit.c - stiff fixed-step integrators with bounded work per step: backward
 * Euler, the trapezoidal rule and the L-stable SDIRK methods of orders 2 and 3 (simplified
 * Newton, capped), and the L-stable Rosenbrock-W method ROS2 (linear solves, no Newton).
 *
 * Iteration matrix. All implicit stages of a method share one diagonal coefficient gamma,
 * so one matrix M = I - h gamma J serves the whole step. J = df/dx comes from forward
 * differences at the step's first right-hand-side evaluation (state x0): x_j moves in place
 * by sqrt(eps) max(|x_j|, 1) (the rhs reads the state from x) and is restored bit for bit;
 * n more evaluations per refresh. J is refreshed every jac_every steps, and at the step
 * after one that was degraded or met a singular M. M is refactored from the stored J,
 * without new evaluations, when h gamma differs from the factored value (event re-steps).
 * All of it lives in the set's rt_implicit_ws, so a replay reproduces it bit for bit.
 *
 * Newton. A stage Y = v + h gamma f(t + c h, Y) is solved from the predictor Y0 = the
 * previous stage value (x0 for the first). Iteration m evaluates f once and solves
 * M d = v + h gamma f(Y_m) - Y_m; the residual of Y_m is the scaled norm
 * r_m = max_i |d_i| / (1 + |Y_i|), i.e. |d| <= tol (atol + rtol |Y|) with atol = rtol = 1.
 * Then: r_m <= tol: apply d, done. r_m not below r_{m-1} (not contracting): drop Y_m and
 * keep Y_{m-1}, whose residual is r_{m-1}. r_0 not finite: keep the predictor. Otherwise
 * apply d and go on, at most newton_max iterations. The stage's residual is the r of the
 * iterate kept, or of the one its final correction was applied to (that correction, in a
 * contracting iteration, only shrinks the error). The step's residual is the largest over
 * its stages: it goes to stats->last_residual, and above tol the step is counted as
 * degraded and returns RT_E_NOCONV. A first iteration cannot show convergence (its
 * correction is the whole stage increment), so newton_max = 1 makes every step degraded;
 * a linear problem converges in two or three (the Jacobian is exact to sqrt(eps)).
 *
 * Cost per step, s implicit stages: at most s * newton_max rhs evaluations and LU solves
 * (plus one evaluation for an explicit first stage); when J is due, n more evaluations and
 * one factorization (n^3/3 multiply-adds), or the factorization alone when h changed.
 * ROS2: three evaluations and two solves, plus the same refresh. No other data-dependent
 * loop; sums in a fixed order. */
#include "rti.h"

#include "linalg.h"

#define R(v) ((real_t)(v))

/* defaults of rt_implicit_cfg (zeros select them) */
#define IMP_NEWTON_MAX 4 /* Newton iterations per stage */
#define IMP_JAC_EVERY 1  /* steps between Jacobian refreshes */
/* residual tolerance: 1e-8 in double; single precision resolves about 1e-7 relative,
   so its default sits two digits above that */
#define IMP_TOL (RT_REAL_IS_FLOAT ? R(1e-5) : R(1e-8))
/* a pivot at most this times the largest entry of M marks M singular */
#define IMP_PIVOT_TOL (R(100) * RT_EPS)

/* stage buffers of rt_iwork this file uses besides the stage derivatives k[0..s-1] */
#define IMP_BUF_V (RT_MAX_STAGES - 3) /* base value v of the stage equation */
#define IMP_BUF_F (RT_MAX_STAGES - 2) /* f(Y), then the Newton correction */
#define IMP_BUF_D (RT_MAX_STAGES - 1) /* perturbed f of the finite differences */
#define IMP_MAX_S (RT_MAX_STAGES - 3) /* stages a tableau may have */

/* Diagonally implicit Runge-Kutta tableau with one diagonal gamma. a is s*s row-major,
   lower triangular; a_ii = gamma, except a_00 = 0 for an explicit first stage. Every
   method here is stiffly accurate (b_j = a_sj, c_s = 1): the last stage value is the new
   state, so no b row is stored. */
typedef struct dirk_tab {
    uint8_t s;
    const real_t *a, *c;
    real_t gamma;
} dirk_tab;

/* Rosenbrock-W method ROS2 of Verwer, Spee, Blom & Hundsdorfer (1999), M = I - h gamma J:
   M k1 = f(t, x0) + h gamma f_t, M k2 = f(t + h, x0 + h k1) - 2 k1 - h gamma f_t,
   x1 = x0 + h (3/2 k1 + 1/2 k2) */
typedef struct ros2_tab {
    real_t gamma;
} ros2_tab;

/* what one step carries between its parts */
typedef struct imp_step {
    const rt_rhs *f;
    real_t *x;          /* the set's state (stage values are written here) */
    uint16_t n;
    const rt_iwork *w;
    real_t hg;          /* h gamma of the iteration matrix */
    real_t tol;         /* residual tolerance (scaled norm) */
    uint8_t nmax;       /* Newton iterations per stage */
    uint8_t refresh;    /* the Jacobian is due at the step's first evaluation */
    uint8_t singular;   /* a factorization of this step was singular */
    rt_status rhs_st;   /* first error of the right-hand side */
    real_t res;         /* largest final residual of the stages */
    uint32_t iters;     /* Newton iterations of the step */
} imp_step;

/* ------------------------------------------------------------------ iteration matrix */

/* evaluates f at time t and the state in x, keeping the first error */
static void rhs(imp_step *c, real_t t, real_t *xdot)
{
    rt_status st = c->f->eval(c->f->ctx, t, xdot);
    if (c->rhs_st == RT_OK)
        c->rhs_st = st;
}

/* forward-difference Jacobian at (tb, x) around fb = f(tb, x), column by column; the
   increment is re-measured as the representable difference x_j + d - x_j */
static void fd_jacobian(imp_step *c, real_t tb, const real_t *fb)
{
    uint16_t n = c->n;
    real_t *x = c->x, *fd = c->w->k[IMP_BUF_D], *jac = c->w->imp->jac;
    real_t sq = rt_sqrt(RT_EPS);
    for (uint16_t j = 0; j < n; j++) {
        real_t xj = x[j], ax = rt_fabs(xj);
        x[j] = xj + sq * (ax > 1 ? ax : 1);
        real_t d = x[j] - xj;
        rhs(c, tb, fd);
        x[j] = xj;
        for (uint16_t i = 0; i < n; i++)
            jac[i * n + j] = (fd[i] - fb[i]) / d;
    }
}

/* factors M = I - hg J from the stored J; a singular M is completed at the pivot
   threshold (finite, deterministic) and forces a fresh Jacobian at the next step */
static void factor(imp_step *c)
{
    rt_implicit_ws *ws = c->w->imp;
    uint16_t n = c->n;
    for (uint16_t i = 0; i < n; i++)
        for (uint16_t j = 0; j < n; j++)
            ws->lu[i * n + j] = (i == j ? 1 : 0) - c->hg * ws->jac[i * n + j];
    rt_status st = rti_lu(ws->lu, n, ws->piv, IMP_PIVOT_TOL);
    ws->h_factored = c->hg;
    ws->valid = st == RT_OK;
    if (st != RT_OK)
        c->singular = 1;
}

/* starts a step: settings, and a refactorization when only h gamma changed */
static void begin(imp_step *c, const rt_rhs *f, real_t *x, uint16_t n, const rt_iwork *w,
                  real_t hg)
{
    const rt_implicit_cfg *cfg = w->cfg;
    uint16_t every = cfg->jac_every ? cfg->jac_every : IMP_JAC_EVERY;
    *c = (imp_step){.f = f, .x = x, .n = n, .w = w, .hg = hg};
    c->tol = cfg->tol > 0 ? cfg->tol : IMP_TOL;
    c->nmax = cfg->newton_max ? cfg->newton_max : IMP_NEWTON_MAX;
    c->refresh = !w->imp->valid || w->imp->age >= every;
    if (!c->refresh && w->imp->h_factored != hg)
        factor(c);
    for (uint16_t i = 0; i < n; i++)
        w->x0[i] = x[i];
}

/* at the step's first evaluation fb = f(tb, x0): refresh J and factor M if due */
static void at_base(imp_step *c, real_t tb, const real_t *fb)
{
    if (!c->refresh)
        return;
    fd_jacobian(c, tb, fb);
    c->w->stats->jac_evals++;
    c->w->imp->age = 0;
    c->refresh = 0;
    factor(c);
}

/* ends a step: ages J, records the statistics, picks the status to return; a step
   above tolerance forces a fresh Jacobian at the next step (a stale one is the usual
   cause, and iterating on it from a degraded state can only drift further) */
static rt_status finish(imp_step *c)
{
    rt_istats *s = c->w->stats;
    c->w->imp->age++;
    s->last_residual = c->res;
    if (c->iters > s->newton_iter_max)
        s->newton_iter_max = c->iters;
    if (!(c->res <= c->tol)) {
        s->degraded++;
        c->w->imp->valid = 0;
        return RT_E_NOCONV;
    }
    if (c->rhs_st != RT_OK)
        return c->rhs_st;
    return c->singular ? RT_E_SINGULAR : RT_OK;
}

/* ------------------------------------------------------------------ Newton */

/* max_i |d_i| / (1 + |y_i|); NaN when d holds one */
static real_t scaled_norm(const real_t *d, const real_t *y, uint16_t n)
{
    real_t m = 0;
    for (uint16_t i = 0; i < n; i++) {
        real_t r = rt_fabs(d[i]) / (1 + rt_fabs(y[i]));
        if (r != r)
            return r;
        m = r > m ? r : m;
    }
    return m;
}

/* solves Y = v + hg f(tc, Y) for Y in x, from the predictor in x; first: this is the
   step's first evaluation, at x = x0. Returns the residual of the last iteration. */
static real_t newton(imp_step *c, real_t tc, const real_t *v, int first)
{
    real_t *x = c->x, *d = c->w->k[IMP_BUF_F], *prev_x = c->w->k[IMP_BUF_D];
    const rt_implicit_ws *ws = c->w->imp;
    real_t res = 0;
    for (uint8_t m = 0; m < c->nmax; m++) {
        rhs(c, tc, d);
        if (first && m == 0)
            at_base(c, tc, d); /* uses prev_x's buffer before it holds anything */
        for (uint16_t i = 0; i < c->n; i++)
            d[i] = v[i] + c->hg * d[i] - x[i];
        rti_lu_solve(ws->lu, c->n, ws->piv, d);
        real_t r = scaled_norm(d, x, c->n);
        c->iters++;
        /* not contracting: the iterate before the last correction was better */
        if (m > 0 && !(r < res)) {
            for (uint16_t i = 0; i < c->n; i++)
                x[i] = prev_x[i];
            break;
        }
        res = r;
        if (!rt_isfinite(r)) /* nothing to compare with: keep the predictor */
            break;
        for (uint16_t i = 0; i < c->n; i++)
            prev_x[i] = x[i], x[i] += d[i];
        if (r <= c->tol)
            break;
    }
    return res;
}

/* ------------------------------------------------------------------ DIRK stepper */

/* v = x0 + h sum_{j<i} a_ij k_j, the known part of stage i */
static void stage_base(const dirk_tab *t, uint8_t i, real_t h, real_t *v, uint16_t n,
                       const rt_iwork *w)
{
    for (uint16_t m = 0; m < n; m++) {
        real_t acc = 0;
        for (uint8_t j = 0; j < i; j++)
            acc += t->a[i * t->s + j] * w->k[j][m];
        v[m] = w->x0[m] + h * acc;
    }
}

static rt_status dirk_step(const rt_integrator *m, const rt_rhs *f, real_t t, real_t h,
                           real_t *x, uint16_t n, const rt_iwork *w)
{
    const dirk_tab *tab = m->tab;
    real_t *v = w->k[IMP_BUF_V];
    imp_step c;
    if (!(h != 0)) /* an empty step leaves x alone (k = (Y - v) / (h gamma) needs h) */
        return RT_OK;
    begin(&c, f, x, n, w, h * tab->gamma);
    for (uint8_t i = 0; i < tab->s; i++) {
        real_t tc = t + tab->c[i] * h;
        if (tab->a[i * tab->s + i] == 0) { /* explicit first stage, at x0 */
            rhs(&c, tc, w->k[i]);
            at_base(&c, tc, w->k[i]);
            continue;
        }
        stage_base(tab, i, h, v, n, w);
        real_t res = newton(&c, tc, v, i == 0);
        if (c.res == c.res && !(res <= c.res)) /* the largest; a NaN sticks */
            c.res = res;
        /* the stage derivative consistent with the stage value (not f(Y), which would
           amplify the iteration error by the stiffness) */
        for (uint16_t j = 0; j < n; j++)
            w->k[i][j] = (x[j] - v[j]) / c.hg;
    }
    return finish(&c); /* stiffly accurate: x holds the last stage value */
}

/* ------------------------------------------------------------------ ROS2 stepper */

static rt_status ros2_step(const rt_integrator *m, const rt_rhs *f, real_t t, real_t h,
                           real_t *x, uint16_t n, const rt_iwork *w)
{
    const ros2_tab *tab = m->tab;
    real_t *k1 = w->k[0], *k2 = w->k[1], *ft = w->k[2], g = tab->gamma;
    const rt_implicit_ws *ws = w->imp;
    imp_step c;
    begin(&c, f, x, n, w, h * g);
    rhs(&c, t, k1);
    at_base(&c, t, k1);
    /* h gamma df/dt ~ gamma (f(t + h, x0) - f(t, x0)): over the whole step, so an input
       that jumps inside it costs no more than the jump itself */
    rhs(&c, t + h, ft);
    for (uint16_t i = 0; i < n; i++)
        ft[i] = g * (ft[i] - k1[i]), k1[i] += ft[i];
    rti_lu_solve(ws->lu, n, ws->piv, k1);
    for (uint16_t i = 0; i < n; i++)
        x[i] = w->x0[i] + h * k1[i];
    rhs(&c, t + h, k2);
    for (uint16_t i = 0; i < n; i++)
        k2[i] -= 2 * k1[i] + ft[i];
    rti_lu_solve(ws->lu, n, ws->piv, k2);
    for (uint16_t i = 0; i < n; i++)
        x[i] = w->x0[i] + h * (R(1.5) * k1[i] + R(0.5) * k2[i]);
    return finish(&c); /* no iteration: residual 0, never degraded */
}

/* ------------------------------------------------------------------ methods */

/* backward Euler: order 1, L-stable, R(z) = 1 / (1 - z) */
static const real_t be_a[] = {1};
static const real_t be_c[] = {1};
static const dirk_tab be_tab = {1, be_a, be_c, 1};

/* trapezoidal rule as a two-stage ESDIRK (explicit first stage): order 2, A-stable but
   not L-stable, R(z) = (1 + z/2) / (1 - z/2) -> -1 as z -> -inf */
static const real_t trap_a[] = {0, 0, R(0.5), R(0.5)};
static const real_t trap_c[] = {0, 1};
static const dirk_tab trap_tab = {2, trap_a, trap_c, R(0.5)};

/* Alexander (1977), two-stage SDIRK: gamma = 1 - 1/sqrt(2), order 2, L-stable */
#define SD2_G 0.29289321881345247560
static const real_t sd2_a[] = {R(SD2_G), 0, R(1 - SD2_G), R(SD2_G)};
static const real_t sd2_c[] = {R(SD2_G), 1};
static const dirk_tab sd2_tab = {2, sd2_a, sd2_c, R(SD2_G)};

/* Alexander (1977), three-stage SDIRK: gamma the root of x^3 - 3x^2 + 3/2 x - 1/6 in
   (1/6, 1/2), c2 = (1 + gamma)/2, b1 = -(6 gamma^2 - 16 gamma + 1)/4,
   b2 = (6 gamma^2 - 20 gamma + 5)/4; order 3, L-stable */
#define SD3_G 0.43586652150845899942
#define SD3_A21 0.28206673924577050029
#define SD3_B1 1.20849664917601007034
#define SD3_B2 (-0.64436317068446906975)
static const real_t sd3_a[] = {
    R(SD3_G), 0, 0,
    R(SD3_A21), R(SD3_G), 0,
    R(SD3_B1), R(SD3_B2), R(SD3_G),
};
static const real_t sd3_c[] = {R(SD3_G), R(SD3_A21 + SD3_G), 1};
static const dirk_tab sd3_tab = {3, sd3_a, sd3_c, R(SD3_G)};

/* ROS2 with gamma = 1 + 1/sqrt(2): L-stable, order 2 for any Jacobian approximation (a
   W-method: a stale Jacobian keeps the order, though on stiff problems the error then
   grows with the Jacobian's error, which no iteration removes) */
static const ros2_tab ros2_tab_ = {R(1.70710678118654752440)};

#if IMP_MAX_S < 3
#error "RT_MAX_STAGES leaves too few stage buffers for the implicit methods."
#endif

const rt_integrator rt_beuler = {.name = "beuler", .order = 1, .stages = 1, .implicit = 1,
                                 .step = dirk_step, .tab = &be_tab};
const rt_integrator rt_trap = {.name = "trap", .order = 2, .stages = 2, .implicit = 1,
                               .step = dirk_step, .tab = &trap_tab};
const rt_integrator rt_sdirk2 = {.name = "sdirk2", .order = 2, .stages = 2, .implicit = 1,
                                 .step = dirk_step, .tab = &sd2_tab};
const rt_integrator rt_sdirk3 = {.name = "sdirk3", .order = 3, .stages = 3, .implicit = 1,
                                 .step = dirk_step, .tab = &sd3_tab};
const rt_integrator rt_ros2 = {.name = "ros2", .order = 2, .stages = 2, .implicit = 1,
                               .step = ros2_step, .tab = &ros2_tab_};
