/* loop.c - the solver of actual algebraic loops (paper, section 3): simplified Newton on
 * the torn inputs with Broyden's update of the inverse Jacobian (Dennis & Schnabel).
 *
 * The unknowns w are the torn inputs of one loop; the residual is F(w) = w - y(w), where
 * y are the outputs on the loop-closing edges after the loop's segment of the evaluation
 * sequence ran with the inputs at w. The first solve estimates the Jacobian by forward
 * differences and inverts it; later solves start from the last solution and the last
 * inverse (both kept in rt_sim), so a linear loop converges in one iteration. At most
 * the scene's iteration bound per solve: a solve that does not converge is counted with
 * its residual and the tick goes on with the last iterate. */
#include "linalg.h"
#include "rti.h"

#define DEFAULT_TOL ((real_t)RT_LOOP_TOL)
#define SQRT_EPS (RT_REAL_IS_FLOAT ? (real_t)3.4526698e-04 : (real_t)1.4901161193847656e-08)
#define QUART_EPS (RT_REAL_IS_FLOAT ? (real_t)1.8581361e-02 : (real_t)1.2207031250e-04)
#define PIVOT_TOL ((real_t)RT_LOOP_PIVOT_TOL)

typedef struct solve_ctx {
    const rt_scene *sc;
    rt_sim *sim;
    const rt_loop *lp;
    real_t t;
    rti_mode mode;
    uint16_t n;
    real_t *w;     /* the torn inputs of this loop (in rt_sim.torn_val) */
    real_t *range; /* and their scales (rt_sim.torn_range) */
} solve_ctx;

/* F(w) = w - y(w) after running the loop's segment; 0 if any value is not finite */
static int residual(const solve_ctx *c, real_t *f)
{
    rt_sim *sim = c->sim;
    int finite = 1;
    rti_run_calls(c->sc, sim, c->lp->seq0, c->lp->seq1, (rti_at){c->t, RT_ALL_SETS, c->mode});
    for (uint16_t i = 0; i < c->n; i++) {
        f[i] = c->w[i] - sim->state.y[sim->plan.torn_src[c->lp->torn0 + i]];
        finite = finite && rt_isfinite(f[i]);
    }
    return finite;
}

/* the scale below which torn input i is taken as absolute: 1, or the largest |w_i| it
   has had if that is less (so a loop of signals near 1e-11 is solved to its digits, not to
   1e-10 of a unit; a first solve from 0, relative to the iterate alone) */
static real_t unit(const solve_ctx *c, uint16_t i)
{
    return c->range[i] < 1 ? c->range[i] : 1;
}

/* max_i |f_i| / (unit_i + |w_i|): relative for large signals, absolute near zero (a
   residual of exactly 0 is 0 whatever the scale) */
static real_t scaled_norm(const solve_ctx *c, const real_t *f)
{
    real_t m = 0;
    for (uint16_t i = 0; i < c->n; i++) {
        real_t a = rt_fabs(f[i]), v = a > 0 ? a / (unit(c, i) + rt_fabs(c->w[i])) : 0;
        m = v > m || v != v ? v : m;
    }
    return m;
}

/* H = J^-1 with J by forward differences at w (f = F(w) given); on a singular J the
   inverse degrades to the identity, i.e. plain fixed-point steps, and is counted.
   The increment grows with the residual: the roundoff in a difference quotient is about
   eps |F| / d, so d ~ eps^(1/4) |F| keeps it below the tolerance after one Newton step
   of a linear loop, while staying small against that step for a nonlinear one. */
static void fd_inverse(const solve_ctx *c, const real_t *f, real_t *H, real_t *J, real_t *fj)
{
    uint16_t n = c->n;
    real_t fmax = rti_norm_inf(f, n);
    for (uint16_t j = 0; j < n; j++) {
        real_t wj = c->w[j], aw = rt_fabs(wj), u = unit(c, j);
        real_t d = SQRT_EPS * (aw > u ? aw : u) + QUART_EPS * fmax;
        d = d > 0 ? d : SQRT_EPS; /* (w, its scale and F all 0: any size) */
        c->w[j] = wj + d;
        residual(c, fj);
        for (uint16_t i = 0; i < n; i++)
            J[i * n + j] = (fj[i] - f[i]) / d;
        c->w[j] = wj;
    }
    for (uint16_t i = 0; i < n; i++)
        for (uint16_t j = 0; j < n; j++)
            H[i * n + j] = i == j ? 1 : 0;
    if (rti_lu(J, n, c->sim->work.loop_piv, PIVOT_TOL) != RT_OK) {
        rti_count(c->sim, RT_CNT_SINGULAR, c->sim->plan.loop_blocks[c->lp->first], RT_E_SINGULAR);
        return;
    }
    rti_lu_solve_cols(J, n, c->sim->work.loop_piv, H, n);
}

/* Broyden's good update of the inverse: H += (s - H y) (s^T H) / (s^T H y) */
static void broyden_update(uint16_t n, real_t *H, const real_t *s, const real_t *y,
                           real_t *hy, real_t *sh)
{
    real_t den = 0;
    for (uint16_t i = 0; i < n; i++) {
        hy[i] = 0;
        for (uint16_t j = 0; j < n; j++)
            hy[i] += H[i * n + j] * y[j];
        den += s[i] * hy[i];
    }
    for (uint16_t j = 0; j < n; j++) {
        sh[j] = 0;
        for (uint16_t i = 0; i < n; i++)
            sh[j] += s[i] * H[i * n + j];
    }
    if (!(rt_fabs(den) > RT_EPS * rti_norm_inf(s, n) * rti_norm_inf(hy, n)))
        return; /* no usable secant information: keep H */
    for (uint16_t i = 0; i < n; i++)
        for (uint16_t j = 0; j < n; j++)
            H[i * n + j] += (s[i] - hy[i]) * sh[j] / den;
}

/* one Newton-Broyden step from w with residual f; returns 0 (and restores w and the
   segment's outputs) if the trial point gave non-finite values. A step that lands within
   the tolerance leaves H as it is: its secant is mostly roundoff, and updating with it
   would slowly spoil an inverse that is already good (seen in single precision). */
static int newton_step(const solve_ctx *c, real_t *H, real_t *f, real_t *fn, real_t *s,
                       real_t *scratch, real_t tol)
{
    uint16_t n = c->n;
    for (uint16_t i = 0; i < n; i++) {
        s[i] = 0;
        for (uint16_t j = 0; j < n; j++)
            s[i] -= H[i * n + j] * f[j];
        c->w[i] += s[i];
    }
    if (!residual(c, fn)) {
        for (uint16_t i = 0; i < n; i++)
            c->w[i] -= s[i];
        residual(c, f);
        return 0;
    }
    if (scaled_norm(c, fn) <= tol) {
        for (uint16_t i = 0; i < n; i++)
            f[i] = fn[i];
        return 1;
    }
    for (uint16_t i = 0; i < n; i++)
        fn[i] -= f[i]; /* y = F(w + s) - F(w) */
    broyden_update(n, H, s, fn, scratch, scratch + n);
    for (uint16_t i = 0; i < n; i++)
        f[i] += fn[i];
    return 1;
}

/* is the loop solved: its residual within tol, and (once its inverse Jacobian H is
   formed, h_valid) the Newton correction H F it still
   asks for within RT_LOOP_STEP_FACTOR tolerances of the torn inputs (scaled the same).
   An ill-conditioned loop (a gain near 1) has a residual within tol relative to a large
   torn input long before that input is right: |F| = (1 - g) |w - w*|. The check costs
   n^2 multiply-adds; a well-conditioned loop passes it where its residual does */
static int solved(const solve_ctx *c, const real_t *H, int h_valid, const real_t *f, real_t *s,
                  real_t tol)
{
    if (!(scaled_norm(c, f) <= tol))
        return 0;
    if (!h_valid)
        return 1;
    for (uint16_t i = 0; i < c->n; i++) {
        s[i] = 0;
        for (uint16_t j = 0; j < c->n; j++)
            s[i] += H[i * c->n + j] * f[j];
    }
    return scaled_norm(c, s) <= RT_LOOP_STEP_FACTOR * tol;
}

/* does H still invert the loop's Jacobian along the correction it proposes, u = H F
   (in u already: solved() formed it)?
   A solve that ends at once never updates H, so a loop whose gain jumped since H was
   formed (a factor 1 -> 1e-10 of w - r) leaves F small and H F smaller still while w is
   far off, tick after tick (its torn input frozen, 0.43 off, status ok). One difference
   along u (stretched to SQRT_EPS of the torn inputs' scale where it is smaller), w and
   the segment's outputs then put back bit for bit: stale when H (J u) is off u by more
   than half of u. u, fu, z and the kept w are n values each of the solver's scratch */
static int stale(const solve_ctx *c, const real_t *H, real_t *f, real_t *u, real_t *fu,
                 real_t *z)
{
    uint16_t n = c->n;
    real_t *keep = z + n, big = scaled_norm(c, u);
    if (!(big >= SQRT_EPS)) /* (too small to difference; 0: along every input) */
        for (uint16_t i = 0; i < n; i++)
            u[i] = big > 0 ? u[i] * (SQRT_EPS / big)
                           : SQRT_EPS * (unit(c, i) + rt_fabs(c->w[i]));
    for (uint16_t i = 0; i < n; i++)
        keep[i] = c->w[i], c->w[i] += u[i];
    int ok = residual(c, fu);
    for (uint16_t i = 0; i < n; i++)
        c->w[i] = keep[i];
    if (!residual(c, f) || !ok)
        return 0; /* (not finite: nothing to tell; the solve reports it) */
    for (uint16_t i = 0; i < n; i++)
        fu[i] -= f[i]; /* J u */
    for (uint16_t i = 0; i < n; i++) {
        z[i] = -u[i];
        for (uint16_t j = 0; j < n; j++)
            z[i] += H[i * n + j] * fu[j];
    }
    return scaled_norm(c, z) > (real_t)0.5 * scaled_norm(c, u);
}

static void solve(const rt_scene *sc, rt_sim *sim, uint8_t l, real_t t, int mode)
{
    rt_loop *lp = &sim->plan.loops[l];
    solve_ctx c = {sc, sim, lp, t, (rti_mode)mode, lp->ntorn, sim->state.torn_val + lp->torn0,
                   sim->state.torn_range + lp->torn0};
    uint16_t n = c.n;
    real_t *H = sim->state.loop_h + lp->h0;
    real_t *f = sim->work.loop_work, *fn = f + n, *s = fn + n, *scratch = s + n;
    real_t tol = sc->loop_tol > 0 ? sc->loop_tol : DEFAULT_TOL;
    if (rti_fault_due(RTI_FAULT_LOOP))
        tol = 0; /* the loop can only run to its iteration bound */
    uint32_t max = sc->loop_iter_max ? sc->loop_iter_max : RT_LOOP_ITER_MAX;
    uint32_t it = 0;
    int ok = residual(&c, f);
    max = max > RT_LOOP_ITER_LIMIT ? RT_LOOP_ITER_LIMIT : max;
    max = max > RT_MAX_LOOP_HIST - 1 ? RT_MAX_LOOP_HIST - 1 : max; /* init checked it */
    if (ok && scaled_norm(&c, f) > tol && !sim->state.loop_h_valid[l]) {
        fd_inverse(&c, f, H, scratch, fn);
        sim->state.loop_h_valid[l] = 1;
        ok = residual(&c, f); /* the difference steps left the segment at w + d e_n */
    }
    int done = ok && solved(&c, H, sim->state.loop_h_valid[l], f, s, tol);
    if (done && sim->state.loop_h_valid[l] && stale(&c, H, f, s, fn, scratch)) { /* s: H F */
        fd_inverse(&c, f, H, scratch, fn); /* formed afresh where the loop is now */
        ok = residual(&c, f);
        done = ok && solved(&c, H, 1, f, s, tol);
    }
    while (!done && ok && it < max) {
        ok = newton_step(&c, H, f, fn, s, scratch, tol);
        it++;
        done = ok && solved(&c, H, sim->state.loop_h_valid[l], f, s, tol);
    }
    sim->stats.loop_hist[it]++;
    sim->stats.loop_iter_max = it > sim->stats.loop_iter_max ? it : sim->stats.loop_iter_max;
    real_t r = done ? scaled_norm(&c, f) : (real_t)1 / (real_t)0;
    for (uint16_t i = 0; ok && i < n; i++)
        c.range[i] = rt_fabs(c.w[i]) > c.range[i] ? rt_fabs(c.w[i]) : c.range[i];
    if (!(r <= tol)) {
        rti_count(sim, RT_CNT_NOCONV, sim->plan.loop_blocks[lp->first], RT_E_NOCONV);
        sim->stats.loop_residual = r > sim->stats.loop_residual ? r : sim->stats.loop_residual;
    }
}

const rt_loop_ops rt_broyden = {.solve = solve};
