/* test_integ.c - tests of rt/integ_erk.c: each method's order of convergence on a
 * non-autonomous problem with a known solution, x' = x cos t, x = exp(sin t), and each
 * method's error estimate against its true local error (with the implicit methods of
 * rt/integ_implicit.c, whose estimates follow the same rule). */
#include "testutil.h"
#include "rt_sim.h" /* white box: reads rt_sim's parts (plan, state, work) */

static void deriv(const rt_args *a, real_t *xdot) { xdot[0] = a->x[0] * rt_cos(a->t); }
static void output(const rt_args *a, real_t *y) { y[0] = a->x[0]; }
static const char *const names[] = {"x"};
static const real_t x0[] = {1};
static const rt_kind growth = {
    .name = "growth", .type = RT_KIND_NSS, .ny = 1, .nx = 1,
    .y_names = names, .x_names = names, .x_default = x0,
    .feed = RT_FEED_NONE, .output = output, .deriv = deriv,
};

/* |x(T) - exp(sin T)| for method m at step h */
static double error_at(const rt_integrator *m, real_t h, real_t t_end)
{
    static const rt_block blocks[] = {{.name = "G", .kind = &growth}};
    rt_set set = {.name = "s", .method = m, .ratio = 1};
    rt_scene sc = {.name = "growth", .dt = h, .t_end = t_end, .blocks = blocks,
                   .nblocks = 1, .sets = &set, .nsets = 1};
    if (!tu_init(&sc))
        return 1e30;
    while (rt_tick(&sc, &tu_sim) == RT_OK)
        ;
    double e = (double)tu_sim.state.x[0] - (double)rt_exp(rt_sin(rt_time(&sc, &tu_sim)));
    return e < 0 ? -e : e;
}

typedef struct order_case {
    const rt_integrator *m;
    real_t h;       /* coarse step: error well above roundoff, in the asymptotic range */
    real_t h_float; /* the same in single precision; 0: roundoff hides the order there */
} order_case;

static void test_orders(void)
{
    static const order_case cases[] = {
        {&rt_euler, (real_t)0.01, (real_t)0.01}, {&rt_heun, (real_t)0.02, (real_t)0.05},
        {&rt_bs3, (real_t)0.05, (real_t)0.2}, {&rt_rk4, (real_t)0.1, 0},
        {&rt_dopri5, (real_t)0.1, 0},
    };
    for (unsigned i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        const order_case *c = &cases[i];
        real_t h = RT_REAL_IS_FLOAT ? c->h_float : c->h;
        if (h == 0)
            continue;
        double e1 = error_at(c->m, h, 2), e2 = error_at(c->m, h / 2, 2);
        double p = (double)rt_log((real_t)(e1 / e2)) / (double)rt_log(2);
        th_note(c->m->name, p);
        TH_NEAR(p, c->m->order, 0.25);
    }
}

/* ------------------------------------------------------------------ error estimates */

/* a one-state problem stepped directly: x' = 1 / (1 + t) (a quadrature: f does not
   depend on x, x = x0 + ln((1 + t) / (1 + t0))) or x' = x^2 (autonomous,
   x = x0 / (1 - x0 (t - t0))); every derivative of both solutions is positive on the
   range tested, so the true local error never passes through 0 */
typedef struct est_rhs {
    real_t *x;
    int quad;
} est_rhs;

static rt_status est_eval(void *ctx, real_t t, real_t *xdot)
{
    const est_rhs *c = ctx;
    xdot[0] = c->quad ? 1 / (1 + t) : c->x[0] * c->x[0];
    return RT_OK;
}

static double est_exact(int quad, double t0, double x0, double h)
{
    return quad ? x0 + (double)rt_log((real_t)((1 + t0 + h) / (1 + t0))) : x0 / (1 - x0 * h);
}

typedef struct est_case {
    const rt_integrator *m;
    double lo, hi; /* the estimate / the true local error lies in [lo, hi] at h = 0.05 */
} est_case;

/* a step's workspace in the shared simulator's buffers, with fresh statistics */
static rt_iwork iwork(const rt_set_cfg *cfg, int autonomous)
{
    rt_iwork w;
    for (int i = 0; i < RT_MAX_STAGES; i++)
        w.k[i] = tu_sim.work.w.k[i];
    w.x0 = tu_sim.work.x0, w.xs = 0, w.tm = 0;
    w.imp = &tu_sim.state.imp[0], w.stats = &tu_sim.stats.istats[0], w.cfg = cfg;
    w.autonomous = (uint8_t)autonomous;
    tu_sim.stats.istats[0] = (rt_istats){0};
    return w;
}

/* one step of m from (t0, x0) by h: its estimate and the true local error, both in the
   scaled norm |e| / (1 + |x1|) */
static void est_step(const rt_integrator *m, int quad, real_t t0, real_t x0, real_t h,
                     double *est, double *err)
{
    static const rt_set_cfg cfg = {0};
    real_t x[1] = {x0};
    est_rhs c = {x, quad};
    rt_rhs f = {est_eval, &c};
    rt_iwork w = iwork(&cfg, !quad);
    tu_sim.state.imp[0].valid = 0, tu_sim.state.imp[0].age = 0;
    m->step(m, &f, t0, h, x, 1, &w);
    double x1 = (double)x[0], e = x1 - est_exact(quad, (double)t0, (double)x0, (double)h);
    *est = (double)w.stats->last_err;
    *err = (e < 0 ? -e : e) / (1 + (x1 < 0 ? -x1 : x1));
}

/* An estimate that is 0 when f depends on t alone lets a wrong step pass as exact (rk4
   against its old companion: y' = 1/x through x = 0 ended at -3.8e11 with status ok). On
   both problems, at 20 start points and h = 0.05, each method's estimate is not 0 and
   lies within the stated factors of its true local error: at least a quarter of it (an
   estimate of one order less bounds the method's error from above, up to the shape of
   the higher derivatives), at most the stated multiple (the companion's own error, about
   C / h times the method's) */
static void test_estimates(void)
{
    static const est_case cases[] = {
        {&rt_euler, 0.25, 2}, {&rt_heun, 0.25, 400}, {&rt_bs3, 0.25, 200},
        {&rt_rk4, 0.25, 400}, {&rt_dopri5, 0.25, 400}, {&rt_beuler, 0.25, 2},
        {&rt_trap, 0.25, 400}, {&rt_sdirk2, 0.25, 3000}, {&rt_sdirk3, 0.25, 200},
        {&rt_ros2, 0.25, 1000},
    };
    if (RT_REAL_IS_FLOAT) /* the local errors of the higher orders are below rounding */
        return;
    for (unsigned i = 0; i < sizeof cases / sizeof cases[0]; i++)
        for (int quad = 1; quad >= 0; quad--) {
            double lo = 1e300, hi = 0;
            for (int j = 0; j < 20; j++) {
                real_t t0 = (real_t)(0.1 * j), x0 = quad ? 1 : (real_t)(0.2 + 0.01 * j);
                double est, err;
                est_step(cases[i].m, quad, t0, x0, (real_t)0.05, &est, &err);
                double r = est / err;
                lo = r < lo ? r : lo, hi = r > hi ? r : hi;
                TH_CHECK(est > 0);
            }
            th_put("  note: ");
            th_put(cases[i].m->name);
            th_put(quad ? " quadrature: estimate / true local error in [" : " autonomous: "
                   "estimate / true local error in [");
            th_put_real(lo), th_put(", "), th_put_real(hi), th_put("]\n");
            TH_CHECK(lo >= cases[i].lo && hi <= cases[i].hi);
        }
}

/* x' = -k x (decay) or x'' = -k^2 x as (x, v) (oscillation): y' = lambda y with
   lambda = -k or +-i k */
typedef struct lin_rhs {
    real_t *x;
    real_t k;
    int osc;
} lin_rhs;

static rt_status lin_eval(void *ctx, real_t t, real_t *xdot)
{
    const lin_rhs *c = ctx;
    (void)t;
    if (c->osc)
        xdot[0] = c->k * c->x[1], xdot[1] = -c->k * c->x[0];
    else
        xdot[0] = -c->k * c->x[0];
    return RT_OK;
}

/* rk4's estimate is scaled to exceed its own local error on y' = lambda y for every
   |h lambda| <= 1 (rt/integ_erk.c): on the negative real axis and the imaginary axis at
   |h lambda| = 0.1, 0.5, 1 it does (Zonneveld's weights were blind at h lambda = -1) */
static void test_rk4_linear(void)
{
    static const rt_set_cfg cfg = {0};
    static const real_t hk[] = {(real_t)0.1, (real_t)0.5, 1};
    if (RT_REAL_IS_FLOAT)
        return;
    for (int osc = 0; osc <= 1; osc++)
        for (unsigned i = 0; i < sizeof hk / sizeof hk[0]; i++) {
            real_t x[2] = {1, 0};
            lin_rhs c = {x, hk[i], osc};
            rt_rhs f = {lin_eval, &c};
            rt_iwork w = iwork(&cfg, 1);
            rt_rk4.step(&rt_rk4, &f, 0, 1, x, (uint16_t)(osc + 1), &w);
            double e0, e1 = 0;
            if (osc) /* (cos k, -sin k) */
                e0 = (double)x[0] - (double)rt_cos(hk[i]), e1 = (double)x[1] + (double)rt_sin(hk[i]);
            else
                e0 = (double)x[0] - (double)rt_exp(-hk[i]);
            e0 = e0 < 0 ? -e0 : e0, e1 = e1 < 0 ? -e1 : e1;
            double err = (e0 > e1 ? e0 : e1) / 2; /* the norm's scale 1 + |x| >= 1, <= 2 */
            TH_CHECK((double)w.stats->last_err >= err);
        }
}

/* x_i' = a_i x_i cos t + b_i: states that do not touch each other */
typedef struct diag_rhs {
    real_t *x;
    uint16_t n, first; /* n states, the first of them state `first` of the table */
    uint16_t nan_at;   /* 1 + the state whose derivative is NaN, 0: none */
} diag_rhs;

static rt_status diag_eval(void *ctx, real_t t, real_t *xdot)
{
    const diag_rhs *c = ctx;
    for (uint16_t i = 0; i < c->n; i++) {
        uint16_t j = (uint16_t)(c->first + i);
        xdot[i] = (real_t)(0.3 - 0.11 * j) * c->x[i] * rt_cos(t) + (real_t)(0.05 * j);
        if (i + 1u == c->nan_at)
            xdot[i] = (real_t)0 / (real_t)0;
    }
    return RT_OK;
}

/* one step of the n uncoupled states; returns its error estimate */
static real_t diag_step(const rt_integrator *m, real_t *x, uint16_t n, uint16_t first,
                        uint16_t nan_at)
{
    static const rt_set_cfg cfg = {0};
    diag_rhs c = {x, n, first, nan_at};
    rt_rhs f = {diag_eval, &c};
    rt_iwork w = iwork(&cfg, 0);
    m->step(m, &f, (real_t)0.3, (real_t)0.25, x, n, &w);
    return w.stats->last_err;
}

/* the stage sums take two states at a time (a vector register's two lanes where the
   target has them) and an odd count's last state alone: every state of a set of 1 to 9
   uncoupled states must end each step with the same bits as the same state stepped
   alone, whatever its lane, for every explicit method. The estimate, a maximum over the
   states taken two at a time too, is the largest of the states' own, and NaN when any
   one state's is, in every lane */
static void test_lanes(void)
{
    static const rt_integrator *const ms[] = {&rt_euler, &rt_heun, &rt_bs3, &rt_rk4,
                                              &rt_dopri5};
    for (unsigned k = 0; k < sizeof ms / sizeof ms[0]; k++)
        for (uint16_t n = 1; n <= 9; n++) {
            real_t x[9], largest = 0;
            for (uint16_t i = 0; i < n; i++)
                x[i] = (real_t)(1 + 0.37 * i);
            real_t est = diag_step(ms[k], x, n, 0, 0);
            for (uint16_t i = 0; i < n; i++) {
                real_t xi = (real_t)(1 + 0.37 * i);
                real_t ei = diag_step(ms[k], &xi, 1, i, 0);
                TH_CHECK(x[i] == xi && x[i] != (real_t)(1 + 0.37 * i));
                largest = ei > largest ? ei : largest;
            }
            TH_CHECK(est == largest && est > 0);
            for (uint16_t j = 1; j <= n; j++) {
                for (uint16_t i = 0; i < n; i++)
                    x[i] = (real_t)(1 + 0.37 * i);
                est = diag_step(ms[k], x, n, 0, j);
                TH_CHECK(est != est);
            }
        }
}

/* a step whose caller keeps its start (rt_iwork.xs, as rt/step.c does) ends with the same
   bits and the same estimate as one that copies it into x0, and leaves the kept start as it
   is, for every method that takes any set (x0 filled with NaN: no method may read it as
   its start) */
static void test_kept_start(void)
{
    static const rt_set_cfg cfg = {0};
    for (const rt_integrator_entry *e = rt_integrators; e->name; e++) {
        const rt_integrator *m = e->method;
        if (m->linear) /* the transition method's workspace is rt/eval.c's */
            continue;
        real_t x[9], y[9], xs[9];
        for (uint16_t i = 0; i < 9; i++)
            x[i] = y[i] = xs[i] = (real_t)(1 + 0.37 * i);
        diag_rhs cx = {x, 9, 0, 0}, cy = {y, 9, 0, 0};
        rt_rhs fx = {diag_eval, &cx}, fy = {diag_eval, &cy};
        rt_iwork w = iwork(&cfg, 0);
        tu_sim.state.imp[0].valid = 0, tu_sim.state.imp[0].age = 0;
        m->step(m, &fx, (real_t)0.3, (real_t)0.25, x, 9, &w);
        real_t err = w.stats->last_err;
        w = iwork(&cfg, 0);
        w.xs = xs;
        for (uint16_t i = 0; i < 9; i++)
            w.x0[i] = (real_t)0 / (real_t)0;
        tu_sim.state.imp[0].valid = 0, tu_sim.state.imp[0].age = 0;
        m->step(m, &fy, (real_t)0.3, (real_t)0.25, y, 9, &w);
        TH_CHECK(w.stats->last_err == err);
        for (uint16_t i = 0; i < 9; i++)
            TH_CHECK(y[i] == x[i] && xs[i] == (real_t)(1 + 0.37 * i));
    }
}

/* the stage count is what a step costs; the registry finds every method */
static void test_registry(void)
{
    TH_CHECK(rt_integrator_find("rk4") == &rt_rk4);
    TH_CHECK(rt_integrator_find("dopri5") == &rt_dopri5);
    TH_CHECK(rt_integrator_find("nope") == 0);
    for (const rt_integrator_entry *e = rt_integrators; e->name; e++)
        TH_CHECK(e->method->stages <= RT_MAX_STAGES && rt_streq(e->name, e->method->name));
}

const th_test th_integ_tests[] = {
    {"integ_orders", test_orders},
    {"integ_registry", test_registry},
    {"integ_estimates", test_estimates},
    {"integ_rk4_linear", test_rk4_linear},
    {"integ_lanes", test_lanes},
    {"integ_kept_start", test_kept_start},
    {0, 0},
};
