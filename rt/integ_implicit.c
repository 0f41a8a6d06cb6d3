/* integ_implicit.c - stiff fixed-step integrators with bounded work per step: backward
 * Euler, the trapezoidal rule and the L-stable SDIRK methods of orders 2 and 3 (simplified
 * Newton, retried, split, capped), and the L-stable Rosenbrock-W method ROS2 (linear
 * solves, no Newton); each with an embedded local error estimate.
 *
 * Iteration matrix. All implicit stages of a method share one diagonal coefficient gamma,
 * so one matrix M = I - h gamma J serves the whole step. J = df/dx comes from forward
 * differences at the step's first right-hand-side evaluation (state x0): x_j moves in place
 * by sqrt(eps) max(|x_j|, 1) (the rhs reads the state from x) and is restored bit for bit;
 * n more evaluations per refresh. J is refreshed every jac_every steps, and at the step
 * after one that was degraded, split or met a singular M; ROS2 spreads a refresh over the
 * steps before it (spread_parts) and takes its first J before the first tick
 * (ros2_prime), so that no tick pays for a whole refresh. M is refactored from the stored
 * J, without new evaluations, when h gamma differs from the factored value (event
 * re-steps). All of it lives in the set's rt_implicit_ws, so a replay reproduces it bit for
 * bit.
 *
 * Newton. A stage Y = v + h gamma f(t + c h, Y) is solved from the predictor Y0 = the
 * previous stage value (x0 for the first). Iteration m evaluates f once and solves
 * M d = v + h gamma f(Y_m) - Y_m; the residual of Y_m is the scaled norm
 * r_m = max_i |d_i| / (1 + |Y_i|), i.e. |d| <= tol (atol + rtol |Y|) with atol = rtol = 1.
 * r_m <= tol: apply d, done. r_m not below r_{m-1} (not contracting) or not finite: stop
 * there (never back to the predictor: a step that returned its start state would meet the
 * same Jacobian at the same point next step and repeat the failure bit for bit: a method
 * would freeze on Robertson's kinetics). Otherwise apply d and go on,
 * at most newton_max iterations. A first iteration cannot show convergence (its
 * correction is the whole stage increment).
 *
 * A step that does not converge (docs/solvers.md, "Steps that cannot stall"):
 *  1. retry with full Newton: a Jacobian at every iterate, 2 newton_max iterations (the
 *     Jacobian at the step's start may not see the stiff direction at all: Robertson's at
 *     (1, 0, 0) has neither the 1e4 y2 y3 nor the 3e7 y2^2 terms);
 *  2. split the step into 2, 4, ... K substeps (K = the set's `substeps`, default
 *     RT_IMP_SUBSTEPS), each with a fresh Jacobian at its start; the first K that
 *     converges is the answer (counted: substep, a recovered step, not a fault);
 *  3. else keep the attempt with the smallest residual (never the start state unless
 *     every attempt gave NaN), count the step as degraded and return RT_E_NOCONV.
 * dirk_bound gives the most work this can take; `modrt info` prints it per set. ROS2,
 * which has no iteration, splits a step the same way when its error estimate exceeds the
 * set's accuracy (ros2_step, ros2_bound).
 *
 * Error estimate. A DIRK step's embedded first-order solution is x0 + h k_s (the last
 * stage's derivative alone), so e = h sum_j (a_sj - [j = s]) k_j; backward Euler, its own
 * companion, is compared with the trapezoidal rule, e = h/2 (k_1 - f(t, x0)). SDIRK2 and
 * SDIRK3, with no stage at the step's start, are also compared with a second companion
 * through f(t, x0) (dirk_attempt), filtered by M once more, and report the larger. The
 * difference is filtered by M for the L-stable methods (Hairer & Wanner II, IV.8:
 * e <- M^-1 e, so the stiff components, which the L-stable solution damps, are not read
 * as error); the trapezoidal rule, which carries them on, is judged by the raw e. ROS2 against its
 * first-order companion x0 + h k1: e = h/2 (k1 + k2), filtered by M likewise when the
 * Jacobian is refreshed every step (the companion damps a stiff mode only to
 * 1 - 1/gamma). The scaled norm of e goes to
 * stats->last_err; rt/step.c counts the step (errest) when it is above the set's accuracy.
 * The estimate only reports: the schedule never changes.
 *
 * Cost per step when it converges, s implicit stages: at most s * newton_max rhs
 * evaluations and LU solves (plus one evaluation for an explicit first stage); when J is
 * due, n more evaluations and one factorization (n^3/3 multiply-adds), or the
 * factorization alone when h changed. ROS2: three evaluations and two solves, plus the
 * same refresh. Sums in a fixed order. */
#include "rti.h"

#include "linalg.h"

#define R(v) ((real_t)(v))

/* a pivot at most this times the largest entry of M marks M singular */
#define IMP_PIVOT_TOL (R(100) * RT_EPS)

/* stage buffers of rt_iwork this file uses besides the stage derivatives k[0..s-1] */
#define IMP_BUF_V (RT_MAX_STAGES - 3) /* base value v of the stage equation */
#define IMP_BUF_F (RT_MAX_STAGES - 2) /* f(Y), then the Newton correction */
#define IMP_BUF_D (RT_MAX_STAGES - 1) /* perturbed f of the finite differences; the
                                        previous Newton iterate */
#define IMP_MAX_S (RT_MAX_STAGES - 3) /* stages a tableau may have */
#define IMP_BUF_S 3 /* ROS2 (stages in k[0..2]): f(t + h, x0) and r1 of its secant check */

/* Diagonally implicit Runge-Kutta tableau with one diagonal gamma. a is s*s row-major,
   lower triangular; a_ii = gamma, except a_00 = 0 for an explicit first stage. Every
   method here is stiffly accurate (b_j = a_sj, c_s = 1): the last stage value is the new
   state, so no b row is stored. */
typedef struct dirk_tab {
    uint8_t s;
    const real_t *a, *c;
    real_t gamma;
    uint8_t lstable; /* R(-inf) = 0: the error estimate may be filtered by M */
    const real_t *bhat; /* s weights of the embedded companion; NULL: x0 + h k_s */
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
    uint16_t part0, part1; /* parts of a spread refresh due at that evaluation */
    uint8_t singular;   /* a factorization of this step was singular */
    uint8_t full;       /* retrying: a Jacobian at every Newton iterate */
    real_t err;         /* local error estimate of the result (largest over substeps) */
    real_t sa;          /* floor of the estimate's norm (rti_err_floor) */
    real_t *f0;         /* where to keep the step's first evaluation, or NULL */
    real_t *fd;         /* scratch of the finite differences (fd_jacobian) */
    rt_status rhs_st;   /* first error of the right-hand side */
    real_t res;         /* largest final residual of the stages */
    uint32_t iters;     /* Newton iterations of the step */
    real_t r0;          /* the step's first Newton correction (scaled norm; -1: none yet):
                           how far its start derivative wants to move the state */
    uint8_t stall;      /* the step ended where it started though r0 said it must move */
    uint8_t damped;     /* an iteration matrix of the attempt (or its substeps) damps a
                           growing mode (watch_damping) */
    uint8_t fresh;      /* the attempt's Jacobian was taken at its own start (at_base) */
    uint8_t stale;      /* the attempt's kept Jacobian failed its secant check (ROS2) */
} imp_step;

/* ------------------------------------------------------------------ iteration matrix */

/* evaluates f at time t and the state in x, keeping the first error */
static void rhs(imp_step *c, real_t t, real_t *xdot)
{
    rt_status st = c->f->eval(c->f->ctx, t, xdot);
    if (c->rhs_st == RT_OK)
        c->rhs_st = st;
}

/* columns j0 .. j1 - 1 of the forward-difference Jacobian (rti_fd_jacobian) */
static rt_status fd_columns(const rt_rhs *f, real_t t, real_t *x, uint16_t n,
                            const real_t *fb, real_t inc, real_t *fd, real_t *jac, uint16_t j0,
                            uint16_t j1)
{
    rt_status st = RT_OK;
    for (uint16_t j = j0; j < j1; j++) {
        real_t xj = x[j], ax = rt_fabs(xj);
        x[j] = xj + inc * (ax > 1 ? ax : 1);
        real_t d = x[j] - xj;
        rt_status sj = f->eval(f->ctx, t, fd);
        st = st == RT_OK ? sj : st;
        x[j] = xj;
        for (uint16_t i = 0; i < n; i++)
            jac[i * n + j] = (fd[i] - fb[i]) / d;
    }
    return st;
}

rt_status rti_fd_jacobian(const rt_rhs *f, real_t t, real_t *x, uint16_t n, const real_t *fb,
                          real_t inc, real_t *fd, real_t *jac)
{
    return fd_columns(f, t, x, n, fb, inc, fd, jac, 0, n);
}

/* columns j0 .. j1 - 1 of the iteration's Jacobian at (tb, x) around fb = f(tb, x):
   increments sqrt(eps) */
static void fd_jacobian(imp_step *c, real_t tb, const real_t *fb, uint16_t j0, uint16_t j1)
{
    rt_status st = fd_columns(c->f, tb, c->x, c->n, fb, rt_sqrt(RT_EPS), c->fd,
                              c->w->imp->jac, j0, j1);
    if (c->rhs_st == RT_OK)
        c->rhs_st = st;
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
    ws->neg_det = (uint8_t)rti_lu_det_negative(ws->lu, n, ws->piv);
    if (st != RT_OK)
        c->singular = 1;
}

/* Spread refresh (ROS2 with jac_every = K >= 2). The next iteration matrix is built in
   jac over the steps before it is due, in 2n + 1 parts: the n columns of J (forward
   differences at each step's own first evaluation), each made M's column of I - hg J at
   once with the h gamma of the cycle's first column (m_columns), M's pivot floor, and
   its n elimination stages (rti_lu_stages, pivots in piv_next); the step
   at age K copies the factors into lu. Each step takes per = ceil((2n + 1) / (K - 1))
   parts, in the last ceil((2n + 1) / per) steps of the cycle (the freshest). No tick then pays for a whole
   refresh: a regular step adds at most `per` evaluations or elimination stages, or the
   copy. J is assembled from states up to K - 1 steps apart: a W-method keeps its order
   for any matrix (ros2_tab_). jac then holds no J to refactor from: when h gamma
   changes, M is rebuilt from lu (refactor_lu). */
static void spread_parts(imp_step *c, uint32_t age, uint32_t k)
{
    uint32_t parts = 2u * c->n + 1, per = (parts + k - 2) / (k - 1), steps = (parts + per - 1) / per;
    if (c->n == 0 || age + steps < k) /* not yet in the cycle's last `steps` steps */
        return;
    uint32_t p0 = (age + steps - k) * per, p1 = p0 + per < parts ? p0 + per : parts;
    c->part0 = (uint16_t)p0, c->part1 = (uint16_t)p1;
}

/* columns j0 .. j1 - 1 of J in jac become those of M = I - h_next J, each entry as
   (i == j) - hg J_ij (the same bits as a pass over the whole matrix), their largest
   magnitude joining floor_next (the running maximum until the floor is set): so no step
   of a spread refresh passes over all n^2 entries but an elimination stage */
static void m_columns(rt_implicit_ws *ws, uint16_t n, uint16_t j0, uint16_t j1)
{
    real_t hg = ws->h_next, big = ws->floor_next;
    for (uint16_t j = j0; j < j1; j++)
        for (uint16_t i = 0; i < n; i++) {
            real_t *e = &ws->jac[i * n + j];
            real_t v = (i == j ? 1 : 0) - hg * *e, a = rt_fabs(v);
            *e = v;
            big = a > big ? a : big;
        }
    ws->floor_next = big;
}

/* parts part0 .. part1 - 1 of a spread refresh, at the step's first evaluation
   fb = f(tb, x0): columns of J made M's, M's pivot floor, elimination stages */
static void spread_do(imp_step *c, real_t tb, const real_t *fb)
{
    rt_implicit_ws *ws = c->w->imp;
    uint16_t n = c->n, p0 = c->part0, p1 = c->part1;
    c->part0 = c->part1;
    if (p0 < n) {
        uint16_t j1 = p1 < n ? p1 : n;
        if (p0 == 0) /* the cycle's first column: its h gamma is the matrix's */
            ws->h_next = c->hg, ws->floor_next = 0;
        fd_jacobian(c, tb, fb, p0, j1);
        m_columns(ws, n, p0, j1);
    }
    if (p0 <= n && n < p1) { /* M = I - hg J is complete: its pivot floor */
        real_t big = ws->floor_next;
        ws->floor_next = IMP_PIVOT_TOL * (big > 0 ? big : 1); /* as rti_lu_floor */
        ws->singular_next = 0;
    }
    if (p1 <= n + 1)
        return;
    uint16_t k0 = (uint16_t)(p0 > n + 1 ? p0 - n - 1 : 0), k1 = (uint16_t)(p1 - n - 1);
    if (rti_lu_stages(ws->jac, n, ws->piv_next, ws->floor_next, k0, k1) != RT_OK)
        ws->singular_next = 1;
}

/* the step at the cycle's end: the factors built in jac become M (a singular one, as in
   factor, forces a whole fresh Jacobian at the next step) */
static void spread_install(imp_step *c)
{
    rt_implicit_ws *ws = c->w->imp;
    uint16_t n = c->n;
    for (uint32_t i = 0; i < (uint32_t)n * n; i++)
        ws->lu[i] = ws->jac[i];
    for (uint16_t i = 0; i < n; i++)
        ws->piv[i] = ws->piv_next[i];
    ws->h_factored = ws->h_next;
    ws->valid = !ws->singular_next;
    ws->neg_det = (uint8_t)rti_lu_det_negative(ws->lu, n, ws->piv);
    c->singular = ws->singular_next;
    ws->age = 0, ws->drift = 0;
    c->w->stats->jac_evals++;
}

/* M for a new h gamma when jac holds no J (a spread refresh builds its factors there):
   from the factors of M0 = I - hg0 J, M = (1 - r) I + r M0 with r = hg / hg0, no
   evaluation (event re-steps, time-event parts) */
static void refactor_lu(imp_step *c)
{
    rt_implicit_ws *ws = c->w->imp;
    uint16_t n = c->n;
    real_t r = c->hg / ws->h_factored;
    rti_lu_unfactor(ws->lu, n, ws->piv);
    for (uint16_t i = 0; i < n; i++)
        for (uint16_t j = 0; j < n; j++)
            ws->lu[i * n + j] = r * ws->lu[i * n + j] + (i == j ? 1 - r : 0);
    rt_status st = rti_lu(ws->lu, n, ws->piv, IMP_PIVOT_TOL);
    ws->h_factored = c->hg;
    ws->valid = st == RT_OK;
    ws->neg_det = (uint8_t)rti_lu_det_negative(ws->lu, n, ws->piv);
    if (st != RT_OK)
        c->singular = 1;
}

/* starts a step: settings, a refresh due at the first evaluation (or, spread, its parts
   due and at the cycle's end the factors built), and a refactorization when only h gamma
   changed */
static void begin(imp_step *c, const rt_rhs *f, real_t *x, uint16_t n, const rt_iwork *w,
                  real_t hg, int spread)
{
    rt_set_cfg cfg = rti_set_cfg_of(w->cfg);
    rt_implicit_ws *ws = w->imp;
    *c = (imp_step){.f = f, .x = x, .n = n, .w = w, .hg = hg, .r0 = -1,
                    .fd = w->k[IMP_BUF_D]};
    c->tol = cfg.tol;
    c->nmax = cfg.newton_max;
    c->sa = rti_err_floor(w->cfg);
    c->refresh = !ws->valid || ws->age >= cfg.jac_every;
    spread = spread && cfg.jac_every >= 2 && ws->valid;
    if (spread && c->refresh) {
        c->refresh = 0;
        spread_install(c);
    }
    else if (spread)
        spread_parts(c, ws->age, cfg.jac_every);
    if (!c->refresh && ws->valid && ws->h_factored != hg) {
        if (spread)
            refactor_lu(c);
        else
            factor(c);
    }
    for (uint16_t i = 0; i < n; i++)
        w->x0[i] = x[i];
}

/* at the step's first evaluation fb = f(tb, x0): refresh J and factor M if due, or do
   the parts of a spread refresh due at this step */
static void at_base(imp_step *c, real_t tb, const real_t *fb)
{
    if (!c->refresh) {
        if (c->part1 > c->part0)
            spread_do(c, tb, fb);
        return;
    }
    fd_jacobian(c, tb, fb, 0, c->n);
    c->w->stats->jac_evals++;
    c->w->imp->age = 0, c->w->imp->drift = 0;
    c->refresh = 0, c->fresh = 1;
    c->part0 = c->part1 = 0;
    factor(c);
}

/* ends a step: ages J, records the statistics, picks the status to return; a step
   above tolerance forces a fresh Jacobian at the next step (a stale one is the usual
   cause, and iterating on it from a degraded state can only drift further) */
static rt_status finish(imp_step *c, real_t res)
{
    rt_istats *s = c->w->stats;
    c->res = res;
    s->last_err = c->err;
    if (c->err != c->err || c->err > s->err_max)
        s->err_max = c->err;
    c->w->imp->age++;
    s->last_residual = c->res;
    if (c->iters > s->newton_iter_max)
        s->newton_iter_max = c->iters;
    if (!(c->res <= c->tol) || c->stall) {
        s->degraded++;
        c->w->imp->valid = 0;
        return RT_E_NOCONV;
    }
    if (c->rhs_st != RT_OK)
        return c->rhs_st;
    if (c->singular)
        return RT_E_SINGULAR;
    return c->damped ? RT_E_DAMPED : RT_OK;
}

/* An attempt's iteration matrix M = I - h gamma J with a negative determinant has an odd
   number of real eigenvalues with h gamma lambda > 1: a mode the exact solution grows by
   more than e^(1/gamma) over the step sits past the pole of the method's stability
   function, which turns it into a decaying or sign-flipping one. The error estimate,
   filtered by M^-1 or from a companion that passes through M too, reads that mode small
   (y' = 50 y at 0.1 s, backward Euler: 0.78 of the accuracy where the answer is 149 times
   off), so the step says so. A stable J never gives it (complex pairs add |1 - h gamma
   lambda|^2 > 0); an even number of such modes escapes the test. The sign is read off the
   factors where they are made (ws->neg_det), not at every step that reuses them. */
static void watch_damping(imp_step *c)
{
    const rt_implicit_ws *ws = c->w->imp;
    c->damped |= ws->valid && ws->neg_det;
}

/* ------------------------------------------------------------------ Newton */

/* the floor of the scale a Newton correction and a step's move are measured against:
   the set's (rti_err_floor) where it is below 1. A correction measured against a unit
   where the set's values that count are far smaller met the tolerance at once on a kept
   stiff Jacobian that shrank it: a state of 1e-6 held by a stiffness, growing once a
   sampled switch ended it, stayed at 1e-6 (485 at 1.5 s) with status ok under accuracy
   (1e-3, 1e-10). Above 1 (an absolute accuracy looser than the relative one) a unit
   stays: a looser Newton tolerance there bought Robertson's kinetics degraded steps and
   17 times the right-hand sides of its worst step */
static real_t newton_floor(const imp_step *c)
{
    return c->sa < 1 ? c->sa : 1;
}

/* max_i |d_i| / (sa + |y_i|); NaN when d holds one. sa: the set's floor (imp_step.sa,
   rti_err_floor: its absolute accuracy over its relative one, 1 unless the scene splits
   them) for an error estimate, and for a Newton correction that floor up to 1
   (newton_floor) */
static real_t scaled_norm(const real_t *d, const real_t *y, uint16_t n, real_t sa)
{
    real_t m = 0;
    for (uint16_t i = 0; i < n; i++) {
        real_t r = rt_fabs(d[i]) / (sa + rt_fabs(y[i]));
        if (r != r)
            return r;
        m = r > m ? r : m;
    }
    return m;
}

/* the step's local error estimate e (n values in buffer e, overwritten), filtered by the
   iteration matrix, M e (Hairer & Wanner II, IV.8: stiff components of the raw
   difference of two solutions are not errors of the L-stable one), as a scaled norm */
static real_t estimate(imp_step *c, real_t *e)
{
    const rt_implicit_ws *ws = c->w->imp;
    if (ws->valid)
        rti_lu_solve(ws->lu, c->n, ws->piv, e);
    return scaled_norm(e, c->x, c->n, c->sa);
}

/* Does the raw difference u of an estimate the filter read small hide an oscillation the
   step damps: a stiff mode lambda (|h lambda| > RT_HIDDEN_OSC_HL) that does not decay over
   the step (h Re lambda > -ln 2: the exact solution keeps more than half of it). M^-1
   divides such a mode by |1 - h gamma lambda| as it divides a decaying one, but the
   L-stable method's result has lost it where the exact solution has not: a 1.6 kHz
   oscillator at 20 ms, 0.3 m/s of 0.3 gone in the first step, read 3e-6 by ROS2 (Hairer &
   Wanner's filter presumes the mode decays). The mode comes from the Ritz values of M^-1
   on the Krylov space span {w, M^-1 w} of the difference's stiff part w = (I - M^-1) u
   (a slow mode's mu is near 1: without it the space holds the stiff pair alone), each
   mu = 1 / (1 - h_f lambda), h_f the factored h gamma, where that space is nearly
   invariant (an oscillation the difference holds alone). u, a and b (n values each) are
   overwritten. h: the step */
static int hidden_oscillation(const imp_step *c, real_t *u, real_t *a, real_t *b, real_t h)
{
    const rt_implicit_ws *ws = c->w->imp;
    uint16_t n = c->n;
    for (uint16_t i = 0; i < n; i++)
        a[i] = u[i];
    rti_lu_solve(ws->lu, n, ws->piv, a);
    for (uint16_t i = 0; i < n; i++)
        a[i] = u[i] - a[i], b[i] = a[i]; /* w */
    rti_lu_solve(ws->lu, n, ws->piv, b); /* M^-1 w */
    for (uint16_t i = 0; i < n; i++)
        u[i] = b[i];
    rti_lu_solve(ws->lu, n, ws->piv, u); /* M^-2 w */
    real_t ww = 0, wa = 0, aa = 0, wb = 0, ab = 0, bb = 0;
    for (uint16_t i = 0; i < n; i++)
        ww += a[i] * a[i], wa += a[i] * b[i], aa += b[i] * b[i], wb += a[i] * u[i],
        ab += b[i] * u[i], bb += u[i] * u[i];
    real_t nw = rt_sqrt(ww), al = wa / nw, p2 = aa - al * al;
    if (!(ww > 0 && p2 > 0))
        return 0; /* (w an eigenvector, or nothing: no pair) */
    real_t np = rt_sqrt(p2); /* M^-1 q1 = al q1 + np q2 over the orthonormal q1, q2 */
    real_t h11 = wa / ww, h21 = np / nw, h12 = (wb - al * al) / (nw * np);
    real_t h22 = ((ab - al * wb / nw) / np - al * np / nw) / np;
    real_t tr = R(0.5) * (h11 + h22), disc = tr * tr - (h11 * h22 - h12 * h21);
    if (!(disc < 0))
        return 0; /* real Ritz values: a real mode, decaying or caught by watch_damping */
    real_t mi = rt_sqrt(-disc), m2 = tr * tr + mi * mi; /* mu = tr +- i mi */
    /* the space must be nearly invariant: of M^-1 q2, what lies outside it (squared)
       below RT_HIDDEN_OSC_RES^2 |mu|^2. Else the Ritz values are points of M^-1's field
       of values, not its eigenvalues: a non-normal J with real decaying modes (a chain of
       stiff lags) gives complex ones that read as an oscillation */
    real_t c2 = al / nw, out = (bb - 2 * c2 * ab + c2 * c2 * aa) / p2 - h12 * h12 - h22 * h22;
    if (!(out <= R(RT_HIDDEN_OSC_RES) * R(RT_HIDDEN_OSC_RES) * m2))
        return 0;
    real_t s = h / ws->h_factored; /* h lambda = s (1 - 1 / mu) */
    real_t re = s * (1 - tr / m2), im = s * (mi / m2);
    return re > -R(0.6931471805599453) &&
           re * re + im * im > R(RT_HIDDEN_OSC_HL) * R(RT_HIDDEN_OSC_HL);
}

/* solves Y = v + hg f(tc, Y) for Y in x, from the predictor in x; first: this is the
   step's first evaluation, at x = x0. Returns the residual of the last iteration. */
static real_t newton(imp_step *c, real_t tc, const real_t *v, int first)
{
    real_t *x = c->x, *d = c->w->k[IMP_BUF_F];
    const rt_implicit_ws *ws = c->w->imp;
    real_t res = 0;
    for (uint8_t m = 0; m < c->nmax; m++) {
        rhs(c, tc, d);
        if (first && m == 0) {
            at_base(c, tc, d);
            for (uint16_t i = 0; c->f0 && i < c->n; i++)
                c->f0[i] = d[i];
        }
        else if (c->full) { /* a retry: the Jacobian at every iterate (full Newton) */
            fd_jacobian(c, tc, d, 0, c->n);
            c->w->stats->jac_evals++;
            factor(c);
        }
        for (uint16_t i = 0; i < c->n; i++)
            d[i] = v[i] + c->hg * d[i] - x[i];
        rti_lu_solve(ws->lu, c->n, ws->piv, d);
        real_t r = scaled_norm(d, x, c->n, newton_floor(c));
        if (c->r0 < 0)
            c->r0 = r;
        if (rti_fault_due(RTI_FAULT_NEWTON))
            r = R(1) / R(0); /* diverged */
        c->iters++;
        /* not contracting, or no finite correction: give up on this iteration matrix and
           leave the iterate where it is (never back at the predictor, which would repeat
           the same failure step after step); dirk_step retries */
        if ((m > 0 && !c->full && !(r < res)) || !rt_isfinite(r)) {
            res = rt_isfinite(r) ? r : r - r; /* NaN: a failure whatever the tolerance */
            break;
        }
        res = r;
        for (uint16_t i = 0; i < c->n; i++)
            x[i] += d[i];
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

/* one DIRK step of h from w->x0 into x; returns its residual (the largest of its stages,
   NaN sticks) */
static real_t dirk_attempt(imp_step *c, const void *tp, real_t t, real_t h)
{
    const dirk_tab *tab = tp;
    const rt_iwork *w = c->w;
    real_t *v = w->k[IMP_BUF_V], *x = c->x, worst = 0;
    for (uint16_t j = 0; j < c->n; j++)
        x[j] = w->x0[j];
    /* backward Euler's estimate needs f(t, x0): the first Newton evaluation,
       f(t + h, x0), is the same in an autonomous set; else one evaluation more (without
       it a set driven by t alone would show the estimate 0, k_1 = f(t + h, x0)). So does
       SDIRK's second companion (below), in k[IMP_BUF_D] */
    int start = tab->s > 1 && tab->a[0] != 0; /* no stage at the step's start */
    real_t *f0 = tab->s == 1 ? w->k[1] : start ? w->k[IMP_BUF_D] : NULL;
    c->f0 = w->autonomous ? f0 : NULL;
    if (f0 && !w->autonomous)
        rhs(c, t, f0);
    for (uint8_t i = 0; i < tab->s; i++) {
        real_t tc = t + tab->c[i] * h;
        if (tab->a[i * tab->s + i] == 0) { /* explicit first stage, at x0 */
            rhs(c, tc, w->k[i]);
            at_base(c, tc, w->k[i]);
            continue;
        }
        stage_base(tab, i, h, v, c->n, w);
        real_t res = newton(c, tc, v, i == 0);
        if (worst == worst && !(res <= worst)) /* the largest; a NaN sticks */
            worst = res;
        /* the stage derivative consistent with the stage value (not f(Y), which would
           amplify the iteration error by the stiffness) */
        for (uint16_t j = 0; j < c->n; j++)
            w->k[i][j] = (x[j] - v[j]) / c->hg;
    }
    /* embedded first-order solution x0 + h k_s: e = h sum_j (a_sj - [j = s]) k_j;
       backward Euler is its own companion: against the trapezoidal rule,
       e = h/2 (k_1 - f(t, x0)), about h^2/2 x'' */
    real_t *e = w->k[IMP_BUF_V], ce[IMP_MAX_S];
    for (uint8_t i = 0; i < tab->s; i++) /* the weights once, not per component */
        ce[i] = tab->a[(tab->s - 1) * tab->s + i] -
                (tab->bhat ? tab->bhat[i] : i + 1 == tab->s ? 1 : 0);
    for (uint16_t j = 0; j < c->n; j++) {
        real_t acc = 0;
        if (tab->s == 1)
            acc = R(0.5) * (w->k[0][j] - w->k[1][j]);
        for (uint8_t i = 0; tab->s > 1 && i < tab->s; i++)
            acc += ce[i] * w->k[i][j];
        e[j] = h * acc;
    }
    watch_damping(c);
    /* an A-stable method that does not damp stiff modes (trap: R(-inf) = -1) carries
       their error on, ringing: its estimate is taken raw. The raw difference of an
       L-stable one above the accuracy is kept in k[IMP_BUF_F] (the Newton corrections'
       buffer, done with) for hidden_oscillation */
    real_t raw = scaled_norm(e, c->x, c->n, c->sa), *u = w->k[IMP_BUF_F];
    for (uint16_t j = 0; tab->lstable && raw > rti_accuracy(w->cfg) && j < c->n; j++)
        u[j] = e[j];
    real_t err = tab->lstable ? estimate(c, e) : raw;
    if (start) {
        /* SDIRK has no stage at the step's start: a jump of f inside [t, t + c_1 h)
           (an output's comparison, a floor of t) reaches every stage and its companion
           alike, and the step integrates as if it came at t with the estimate 0. A second
           companion of the first one's order through f(t, x0): explicit Euler against the
           second-order method; against the third-order one the second-order rule on
           f(t, x0), the second stage's and the last stage's derivatives with the weight
           1/4 on the last (the second stage's error weighs less than in the rule on the
           first two nodes alone, the quadrature's less than in the trapezoidal rule: the
           estimate is 43 to 193 times the true local error on tests/whitebox/test_integ.c,
           the first companion's 29 to 90). The larger estimate */
        real_t wl = tab->bhat ? R(0.25) : 0, wk = tab->bhat ? (R(0.5) - wl) / tab->c[1] : 0;
        real_t wf = 1 - wk - wl;
        const real_t *k2 = w->k[tab->bhat ? 1 : 0], *kl = w->k[tab->s - 1];
        for (uint16_t j = 0; j < c->n; j++)
            e[j] = (x[j] - w->x0[j]) - h * (wf * f0[j] + wk * k2[j] + wl * kl[j]);
        if (c->w->imp->valid) /* (stiff components: f(t, x0) multiplies them by h lambda,
                                 each filter divides by about gamma h lambda: a 1 kHz servo
                                 stepped at 1 ms is no error, tests/whitebox/test_actuated.c) */
            rti_lu_solve(c->w->imp->lu, c->n, c->w->imp->piv, e);
        real_t e2 = tab->lstable ? estimate(c, e) : scaled_norm(e, c->x, c->n, c->sa);
        err = err == err && !(e2 <= err) ? e2 : err; /* (a NaN of either sticks) */
    }
    /* (e and f(t, x0) in k[IMP_BUF_D] are done with: the scratch) */
    if (tab->lstable && w->imp->valid && raw > rti_accuracy(w->cfg) &&
        err <= rti_accuracy(w->cfg) && hidden_oscillation(c, u, e, w->k[IMP_BUF_D], h))
        err = raw;
    if (c->err == c->err && !(err <= c->err))
        c->err = err;
    return worst;
}

/* keeps x as the best result so far when its residual is the smallest */
static void keep_best(imp_step *c, real_t res, real_t *best)
{
    if (!(res < *best))
        return;
    *best = res;
    for (uint16_t j = 0; j < c->n; j++)
        c->w->imp->best[j] = c->x[j];
}

/* one attempt of a method over [t, t + h] from w->x0 into x: its residual (DIRK) or its
   error estimate (ROS2) */
typedef real_t (*attempt_fn)(imp_step *c, const void *tab, real_t t, real_t h);

/* the step split into k substeps, each with a fresh Jacobian at its start; x from xs;
   returns the largest figure of the substeps (a NaN sticks and ends the split) */
static real_t split(imp_step *c, attempt_fn attempt, const void *tab, real_t gamma, real_t t,
                    real_t h, uint8_t k)
{
    real_t worst = 0, hk = h / (real_t)k;
    rt_implicit_ws *ws = c->w->imp;
    for (uint16_t j = 0; j < c->n; j++)
        c->x[j] = ws->xs[j];
    for (uint8_t i = 0; i < k && worst == worst; i++) {
        for (uint16_t j = 0; j < c->n; j++)
            c->w->x0[j] = c->x[j];
        c->hg = hk * gamma;
        c->refresh = 1;
        real_t r = attempt(c, tab, t + (real_t)i * hk, hk);
        if (!(r <= worst))
            worst = r;
    }
    return worst;
}


/* finish() of a DIRK step that met its tolerance, unless it stalled: it ended within
   the tolerance of its start (max_i |x_i - xs_i| / (newton_floor + |xs_i|), as the
   corrections are measured) while its first Newton
   correction, the move its start derivative asks for filtered by M (a stiff component at
   its equilibrium asks for none), was RT_IMP_STALL times larger. Nothing but a spurious
   root of the stage equations ends there (a method's cycle: SDIRK2's two half steps on a
   relaxation jump return the start state bit for bit, every step); degraded, not a
   recovered substep, and the next step takes a fresh Jacobian */
static rt_status finish_moved(imp_step *c, real_t res)
{
    const real_t *xs = c->w->imp->xs;
    real_t moved = 0;
    for (uint16_t i = 0; i < c->n; i++) {
        real_t r = rt_fabs(c->x[i] - xs[i]) / (newton_floor(c) + rt_fabs(xs[i]));
        moved = r > moved ? r : moved;
    }
    c->stall = moved <= c->tol && c->r0 > (real_t)RT_IMP_STALL * c->tol;
    return finish(c, res);
}

/* A step that does not converge is never left at its start (docs/solvers.md): retry
   with the Jacobian at the failed iterate, then split into 2, 4, ... substeps up to the
   set's bound; if all of that fails, keep the result with the smallest residual. */
static rt_status dirk_step(const rt_integrator *m, const rt_rhs *f, real_t t, real_t h,
                           real_t *x, uint16_t n, const rt_iwork *w)
{
    const dirk_tab *tab = m->tab;
    rt_implicit_ws *ws = w->imp;
    imp_step c;
    if (!(h != 0)) /* an empty step leaves x alone (k = (Y - v) / (h gamma) needs h) */
        return RT_OK;
    begin(&c, f, x, n, w, h * tab->gamma, 0);
    /* the differences' scratch: the last stage buffer, free while any stage iterates
       (stage i writes k[i] after its iteration); k[IMP_BUF_D] keeps f(t, x0) */
    c.fd = w->k[IMP_MAX_S - 1];
    for (uint16_t j = 0; j < n; j++)
        ws->xs[j] = x[j];
    real_t best = R(1) / R(0), res = dirk_attempt(&c, tab, t, h);
    if (res <= c.tol)
        return finish_moved(&c, res);
    keep_best(&c, res, &best);
    /* 1: full Newton, a Jacobian at every iterate (the start's may not see the stiff
       direction: Robertson's at y = (1, 0, 0) has no 1e4 y2 y3 or 3e7 y2^2 terms) */
    c.full = 1, c.err = 0, c.singular = 0, c.damped = 0; /* each attempt reports its own */
    c.nmax = (uint8_t)(2 * c.nmax < 255 ? 2 * c.nmax : 255); /* a cold start needs more */
    res = dirk_attempt(&c, tab, t, h);
    if (res <= c.tol) {
        rt_status st = finish_moved(&c, res);
        w->stats->retried += !c.stall;
        return st;
    }
    keep_best(&c, res, &best);
    /* 2: substeps, each with its own Jacobian at its start, and still full Newton with
       the retry's iterations (Robertson's first step at h = 0.1 s converges in no
       substep without them); dirk_bound counts it */
    uint8_t kmax = rti_set_cfg_of(w->cfg).substeps;
    for (uint8_t k = 2; k <= kmax && k != 0; k = (uint8_t)(k * 2)) {
        c.err = 0, c.singular = 0, c.damped = 0;
        res = split(&c, dirk_attempt, tab, tab->gamma, t, h, k);
        if (res <= c.tol) {
            ws->valid = 0; /* the next step's Jacobian belongs to its own h */
            rt_status st = finish_moved(&c, res);
            w->stats->substepped += !c.stall; /* a stall is no recovery */
            return st;
        }
        keep_best(&c, res, &best);
    }
    /* 3: the best of them (the start state only if every attempt gave NaN) */
    for (uint16_t j = 0; j < n; j++)
        x[j] = best == best && best < R(1) / R(0) ? ws->best[j] : x[j];
    ws->valid = 0;
    return finish(&c, best < R(1) / R(0) ? best : res);
}

/* ------------------------------------------------------------------ ROS2 stepper */

/* A kept Jacobian W checked along the step's first stage, at no evaluation: M k1 = r1
   gives W h k1 = (k1 - r1) / gamma, and f(t + h, x0 + h k1) - f(t + h, x0) is the true
   Jacobian along the same h k1 (to second order). W-methods keep their order for any W,
   but a stiff W where the dynamics no longer are stiff (an input switched the stiffness
   off at a sample hit, another set's history jumped) freezes the state: k1 is damped to
   nothing and the estimate, whose companion is damped with it, reads the step exact
   (y' = -1e5 (y - 1) until a sampled switch, then -10 y, jacobian (64): y(0.62) = 0.9986
   for 0.3012, ok). A component's mismatch above RT_W_SECANT of its W h k1 adds h times
   it, scaled as the estimate, to the drift since the refresh (the largest of them); W fails once the drift exceeds RT_W_DRIFT of
   the set's accuracy (a freeze slower than the accuracy per step adds up over the steps
   it is kept: -0.1 y after the switch, jacobian (1000), was 0.9995 for 0.638 at 5 s).
   Rounding in f at a steady state moves nothing the accuracy sees */
static int secant_fails(const imp_step *c, const real_t *f1, const real_t *r1,
                        const real_t *k1, const real_t *f2, real_t h, real_t g)
{
    real_t moved = 0;
    rt_implicit_ws *ws = c->w->imp;
    for (uint16_t i = 0; i < c->n; i++) { /* component by component: a well-modelled fast
                                             one elsewhere in the set hides none */
        real_t wk = (k1[i] - r1[i]) / g, d = rt_fabs(f2[i] - f1[i] - wk);
        if (d > RT_W_SECANT * rt_fabs(wk)) {
            real_t r = h * d / (c->sa + rt_fabs(c->x[i]));
            moved = r > moved ? r : moved;
        }
    }
    ws->drift += moved;
    return ws->drift > RT_W_DRIFT * rti_accuracy(c->w->cfg);
}

/* one ROS2 step of h from w->x0 into x (the Jacobian refreshed first when due); returns
   its local error estimate against the embedded x0 + h k1 */
static real_t ros2_attempt(imp_step *c, const void *tp, real_t t, real_t h)
{
    const ros2_tab *tab = tp;
    const rt_iwork *w = c->w;
    real_t *k1 = w->k[0], *k2 = w->k[1], *ft = w->k[2], g = tab->gamma, *x = c->x;
    const rt_implicit_ws *ws = w->imp;
    uint16_t n = c->n;
    for (uint16_t i = 0; i < n; i++)
        x[i] = w->x0[i];
    /* kept for the secant check: f(t + h, x0) and the first stage's right side */
    real_t *f1 = w->k[IMP_BUF_S], *r1 = w->k[IMP_BUF_S + 1];
    c->fresh = 0;
    rhs(c, t, k1);
    at_base(c, t, k1);
    /* h gamma df/dt ~ gamma (f(t + h, x0) - f(t, x0)): over the whole step, so an input
       that jumps inside it costs no more than the jump itself. An autonomous set's two
       evaluations are equal: their difference is k1 - k1 (+0, or NaN where k1 is not
       finite), the same bits without the second one */
    if (w->autonomous)
        for (uint16_t i = 0; i < n; i++)
            f1[i] = k1[i], ft[i] = g * (k1[i] - k1[i]), k1[i] += ft[i], r1[i] = k1[i];
    else {
        rhs(c, t + h, ft);
        for (uint16_t i = 0; i < n; i++)
            f1[i] = ft[i], ft[i] = g * (ft[i] - k1[i]), k1[i] += ft[i], r1[i] = k1[i];
    }
    watch_damping(c);
    rti_lu_solve(ws->lu, n, ws->piv, k1);
    for (uint16_t i = 0; i < n; i++)
        x[i] = w->x0[i] + h * k1[i];
    rhs(c, t + h, k2);
    if (!c->fresh)
        c->stale = secant_fails(c, f1, r1, k1, k2, h, g);
    for (uint16_t i = 0; i < n; i++)
        k2[i] -= 2 * k1[i] + ft[i];
    rti_lu_solve(ws->lu, n, ws->piv, k2);
    for (uint16_t i = 0; i < n; i++) {
        x[i] = w->x0[i] + h * (R(1.5) * k1[i] + R(0.5) * k2[i]);
        ft[i] = h * R(0.5) * (k1[i] + k2[i]); /* against the embedded x0 + h k1 */
    }
    /* filtered by M as the L-stable DIRKs' (its companion x0 + h k1 damps a stiff mode
       only to 1 - 1/gamma = 0.41, which the raw difference read as error: Prothero-
       Robinson at 10 ms, 5e-9 off, showed 0.21), but only in a set that refreshes its
       Jacobian every step (jacobian (1), the default): a W-method's error grows with its
       Jacobian's age, which the raw difference shows and an old M would filter away */
    real_t e;
    if (rti_set_cfg_of(w->cfg).jac_every <= 1) {
        real_t *u = w->k[IMP_BUF_S], raw = scaled_norm(ft, x, n, c->sa); /* (f1: done) */
        for (uint16_t i = 0; raw > rti_accuracy(w->cfg) && i < n; i++)
            u[i] = ft[i];
        e = estimate(c, ft);
        if (ws->valid && raw > rti_accuracy(w->cfg) && e <= rti_accuracy(w->cfg) &&
            hidden_oscillation(c, u, w->k[IMP_BUF_S + 1], w->k[IMP_BUF_D], h))
            e = raw;
    } else {
        e = scaled_norm(ft, x, n, c->sa);
    }
    return e == e ? e : R(1) / R(0);
}

/* ROS2 has no iteration that could fail; a step whose estimate exceeds the set's
   accuracy is what tells a bad step (a stale Jacobian, a transient the step cannot
   follow). It is split into 2, 4, ... K substeps with a fresh Jacobian each, as a DIRK
   step that does not converge (the same bound); the first split within the accuracy is
   the answer, else the one with the smallest estimate. */
static rt_status ros2_step(const rt_integrator *m, const rt_rhs *f, real_t t, real_t h,
                           real_t *x, uint16_t n, const rt_iwork *w)
{
    const ros2_tab *tab = m->tab;
    rt_implicit_ws *ws = w->imp;
    real_t acc = rti_accuracy(w->cfg);
    imp_step c;
    begin(&c, f, x, n, w, h * tab->gamma, 1);
    for (uint16_t j = 0; j < n; j++)
        ws->xs[j] = x[j];
    real_t e = ros2_attempt(&c, tab, t, h), best = e;
    if (c.stale) { /* the kept Jacobian is not the set's any more: the step on a fresh one */
        c.refresh = 1, c.damped = 0, c.stale = 0;
        e = best = ros2_attempt(&c, tab, t, h);
        w->stats->retried++;
    }
    uint8_t kmax = rti_set_cfg_of(w->cfg).substeps, damped = c.damped;
    for (uint16_t j = 0; j < n; j++)
        ws->best[j] = x[j];
    for (uint8_t k = 2; e > acc && k <= kmax && k != 0; k = (uint8_t)(k * 2)) {
        c.damped = 0;
        e = split(&c, ros2_attempt, tab, tab->gamma, t, h, k);
        ws->valid = 0; /* the next step's Jacobian belongs to its own h */
        if (e <= acc) {
            w->stats->substepped++;
            best = e, damped = c.damped;
            break;
        }
        if (e < best) {
            best = e, damped = c.damped;
            for (uint16_t j = 0; j < n; j++)
                ws->best[j] = x[j];
        }
    }
    if (e > acc) /* no split met the accuracy: the smallest estimate, reported as such */
        for (uint16_t j = 0; j < n; j++)
            x[j] = ws->best[j];
    c.err = best, c.damped = damped;
    return finish(&c, 0); /* no iteration: residual 0, never degraded */
}

/* Before the first tick: the first Jacobian of a spread refresh, at (t, x) with the
   step's h gamma, so that the first step does not pay for it whole either. A failing
   right-hand side leaves it to the first step, which reports it. */
static void ros2_prime(const rt_integrator *m, const rt_rhs *f, real_t t, real_t h, real_t *x,
                       uint16_t n, const rt_iwork *w)
{
    const ros2_tab *tab = m->tab;
    imp_step c;
    if (rti_set_cfg_of(w->cfg).jac_every < 2 || !(h != 0))
        return; /* a Jacobian at every step: nothing to spread */
    w->imp->valid = 0;
    begin(&c, f, x, n, w, h * tab->gamma, 0);
    rhs(&c, t, w->k[0]);
    at_base(&c, t, w->k[0]);
    if (c.rhs_st != RT_OK || c.singular)
        w->imp->valid = 0;
}

/* ------------------------------------------------------------------ work bounds */

/* A DIRK step: the attempt (a Jacobian, n evaluations, and nmax iterations per implicit
   stage), the full-Newton retry (2 nmax iterations per stage, each with a Jacobian, n
   evaluations, and a factorization), then 2, 4, ... K substeps, each as the retry plus a
   Jacobian at its start: 2 K - 1 full attempts after the first, 2 K - 2 of them with a
   fresh Jacobian. Backward Euler adds f(t, x0) to each attempt (its estimate, in a set
   that is not autonomous). */
static void dirk_bound(const rt_integrator *m, const rt_set_cfg *cfg, uint16_t n,
                       rt_step_work *w)
{
    const dirk_tab *tab = m->tab;
    rt_set_cfg d = rti_set_cfg_of(cfg);
    uint32_t nmax = d.newton_max;
    uint32_t k = d.substeps, expl = tab->a[0] == 0;
    uint32_t impl = tab->s - expl, full = 2 * nmax < 255 ? 2 * nmax : 255;
    /* evaluations besides Jacobians and Newton: an explicit first stage, or f(t, x0)
       for the estimate (backward Euler's, SDIRK's second companion; not counted apart in
       an autonomous set, where it is the first Newton evaluation) */
    uint32_t own = 1;
    uint32_t first = n + own + impl * nmax, retry = own + impl * full * (1u + n);
    w->rhs = first + (2 * k - 1) * retry + (2 * k - 2) * n;
    w->lu = 1 + (2 * k - 1) * impl * full + (2 * k - 2);
}

/* ROS2: an attempt is a Jacobian (n evaluations), f(t, x0), f(t + h, x0), f(t + h, x1)
   and one factorization; with the substeps 2, 4, ... K: 2 K - 1 attempts, and one more
   where a kept Jacobian may fail its secant check (jacobian (K), K >= 2) */
static void ros2_bound(const rt_integrator *m, const rt_set_cfg *cfg, uint16_t n,
                       rt_step_work *w)
{
    rt_set_cfg d = rti_set_cfg_of(cfg);
    uint32_t k = d.substeps, att = 2 * k - 1 + (d.jac_every >= 2);
    (void)m;
    w->rhs = att * (3u + n), w->lu = att;
}

/* ------------------------------------------------------------------ methods */

/* backward Euler: order 1, L-stable, R(z) = 1 / (1 - z) */
static const real_t be_a[] = {1};
static const real_t be_c[] = {1};
static const dirk_tab be_tab = {1, be_a, be_c, 1, 1, 0};

/* trapezoidal rule as a two-stage ESDIRK (explicit first stage): order 2, A-stable but
   not L-stable, R(z) = (1 + z/2) / (1 - z/2) -> -1 as z -> -inf */
static const real_t trap_a[] = {0, 0, R(0.5), R(0.5)};
static const real_t trap_c[] = {0, 1};
static const dirk_tab trap_tab = {2, trap_a, trap_c, R(0.5), 0, 0};

/* Alexander (1977), two-stage SDIRK: gamma = 1 - 1/sqrt(2), order 2, L-stable */
#define SD2_G 0.29289321881345247560
static const real_t sd2_a[] = {R(SD2_G), 0, R(1 - SD2_G), R(SD2_G)};
static const real_t sd2_c[] = {R(SD2_G), 1};
static const dirk_tab sd2_tab = {2, sd2_a, sd2_c, R(SD2_G), 1, 0};

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
/* its companion is second order, on the first two stages: bhat2 = (1/2 - c1) / (c2 - c1),
   bhat1 = 1 - bhat2 (a first-order x0 + h k3 made the estimate C / h^2 times the error,
   4e3 to 4e4 at h = 0.05 on a smooth problem: tests/whitebox/test_integ.c) */
#define SD3_BH2 ((0.5 - SD3_G) / SD3_A21)
static const real_t sd3_bhat[] = {R(1 - SD3_BH2), R(SD3_BH2), 0};
static const dirk_tab sd3_tab = {3, sd3_a, sd3_c, R(SD3_G), 1, sd3_bhat};

/* ROS2 with gamma = 1 + 1/sqrt(2): L-stable, order 2 for any Jacobian approximation (a
   W-method: a stale Jacobian keeps the order, though on stiff problems the error then
   grows with the Jacobian's error, which no iteration removes) */
static const ros2_tab ros2_tab_ = {R(1.70710678118654752440)};

#if IMP_MAX_S < 3
#error "RT_MAX_STAGES leaves too few stage buffers for the implicit methods."
#endif

const rt_integrator rt_beuler = {.name = "beuler", .order = 1, .stages = 1, .implicit = 1,
                                 .step = dirk_step, .bound = dirk_bound, .tab = &be_tab};
const rt_integrator rt_trap = {.name = "trap", .order = 2, .stages = 2, .implicit = 1,
                               .step = dirk_step, .bound = dirk_bound, .tab = &trap_tab};
const rt_integrator rt_sdirk2 = {.name = "sdirk2", .order = 2, .stages = 2, .implicit = 1,
                                 .step = dirk_step, .bound = dirk_bound, .tab = &sd2_tab};
const rt_integrator rt_sdirk3 = {.name = "sdirk3", .order = 3, .stages = 3, .implicit = 1,
                                 .step = dirk_step, .bound = dirk_bound, .tab = &sd3_tab};
const rt_integrator rt_ros2 = {.name = "ros2", .order = 2, .stages = 2, .implicit = 1,
                               .w_method = 1,
                               .step = ros2_step, .bound = ros2_bound, .tab = &ros2_tab_,
                               .prime = ros2_prime};
