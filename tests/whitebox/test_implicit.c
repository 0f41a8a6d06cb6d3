/* test_implicit.c - tests of rt/integ_implicit.c: amplification on Dahlquist's equation
 * against each method's stability function, convergence orders on a smooth nonlinear
 * problem, a stiff 3x3 linear system against its matrix exponential, the degraded-step
 * counter, Jacobian reuse, a singular iteration matrix, multibody sets with projection
 * (a stand-in pendulum and the library's ten-body pendulum), state events, and
 * bit-identical replays. */
#include "linalg.h"
#include "rti.h" /* plan.set_flags' bits */
#include "scenes/scenes.h"
#include "testutil.h"

#define FLT RT_REAL_IS_FLOAT

static const rt_integrator *const methods[] = {&rt_beuler, &rt_trap, &rt_sdirk2, &rt_sdirk3,
                                               &rt_ros2};
#define NMETHODS (sizeof methods / sizeof methods[0])

/* ------------------------------------------------------------------ test kinds */

static const char *const x1_names[] = {"x"};
static const char *const p1_names[] = {"lambda"};
static void out_x(const rt_args *a, real_t *y) { y[0] = a->x[0]; }

/* Dahlquist's equation x' = lambda x */
static void dahl_deriv(const rt_args *a, real_t *xdot) { xdot[0] = a->p[0] * a->x[0]; }
static const rt_kind dahl = {
    .name = "dahlquist", .type = RT_KIND_NSS, .ny = 1, .nx = 1, .np = 1,
    .y_names = x1_names, .x_names = x1_names, .p_names = p1_names,
    .feed = RT_FEED_NONE, .output = out_x, .deriv = dahl_deriv,
};

/* x' = x cos t, x(0) = 1: x = exp(sin t) */
static void growth_deriv(const rt_args *a, real_t *xdot) { xdot[0] = a->x[0] * rt_cos(a->t); }
static const rt_kind growth = {
    .name = "growth", .type = RT_KIND_NSS, .ny = 1, .nx = 1,
    .y_names = x1_names, .x_names = x1_names,
    .feed = RT_FEED_NONE, .output = out_x, .deriv = growth_deriv,
};

/* a stiff cubic relaxation x' = -k (x^3 + x - a sin t): the slope of its right-hand side
   varies from -k (x = 0) to about -5.4 k (|x| = 1.2, a = 3), so a Jacobian frozen at the
   start is badly wrong later */
static const char *const cubic_p[] = {"k", "a"};
static void cubic_deriv(const rt_args *a, real_t *xdot)
{
    real_t x = a->x[0];
    xdot[0] = -a->p[0] * (x * x * x + x - a->p[1] * rt_sin(a->t));
}
static const rt_kind cubic = {
    .name = "cubic", .type = RT_KIND_NSS, .ny = 1, .nx = 1, .np = 2,
    .y_names = x1_names, .x_names = x1_names, .p_names = cubic_p,
    .feed = RT_FEED_NONE, .output = out_x, .deriv = cubic_deriv,
};

/* x' = A x with A = V diag(l) V^-1, built by stiff_matrix() */
static const char *const x3_names[] = {"x1", "x2", "x3"};
static real_t stiff_a[9];
static const real_t eye3[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
static const rt_lss_spec stiff_spec = {3, 0, 3, stiff_a, 0, eye3, 0};
static const rt_kind stiff3 = {
    .name = "stiff3", .type = RT_KIND_LSS, .ny = 3, .nx = 3,
    .y_names = x3_names, .x_names = x3_names,
    .feed = RT_FEED_NONE, .output = rt_lss_output, .deriv = rt_lss_deriv,
    .spec = &stiff_spec,
};

/* ------------------------------------------------------------------ running one block */

static rt_block blk;
static rt_set set;
static rt_scene scene;

/* builds a one-block scene of kind k (parameters p, initial state x0), integrated by m
   with settings cfg at step h up to t_end */
static void build(const rt_kind *k, const real_t *p, const real_t *x0, const rt_integrator *m,
                  rt_set_cfg cfg, real_t h, real_t t_end)
{
    blk = (rt_block){.name = "B", .kind = k, .p = p, .x0 = x0};
    set = (rt_set){.name = "s", .method = m, .ratio = 1, .cfg = cfg};
    scene = (rt_scene){.name = "implicit", .dt = h, .t_end = t_end, .blocks = &blk,
                       .nblocks = 1, .sets = &set, .nsets = 1};
}

/* build, then init; returns 1 when init succeeded */
static int setup(const rt_kind *k, const real_t *p, const real_t *x0, const rt_integrator *m,
                 rt_set_cfg cfg, real_t h, real_t t_end)
{
    build(k, p, x0, m, cfg, h, t_end);
    return tu_init(&scene);
}

/* setup, then every tick to t_end; returns 1 when each tick completed */
static int run(const rt_kind *k, const real_t *p, const real_t *x0, const rt_integrator *m,
               rt_set_cfg cfg, real_t h, real_t t_end)
{
    if (!setup(k, p, x0, m, cfg, h, t_end))
        return 0;
    rt_status st;
    while ((st = rt_tick(&scene, &tu_sim)) == RT_OK)
        ;
    return st == RT_E_DONE;
}

static double dabs(double v) { return v < 0 ? -v : v; }

/* ------------------------------------------------------------------ stability */

/* stability function R(z) of each method, from its tableau by hand */
static double stab_fn(const rt_integrator *m, double z)
{
    if (m == &rt_beuler)
        return 1 / (1 - z);
    if (m == &rt_trap)
        return (1 + z / 2) / (1 - z / 2);
    if (m == &rt_sdirk2) {
        double g = 0.29289321881345247560, d = 1 - g * z;
        return (1 + (1 - 2 * g) * z) / (d * d);
    }
    if (m == &rt_sdirk3) { /* stage by stage on y' = z y / h, y0 = 1 */
        double g = 0.43586652150845899942, b1 = 1.20849664917601007034;
        double b2 = -0.64436317068446906975, a21 = (1 - g) / 2, d = 1 - g * z;
        double y1 = 1 / d, y2 = (1 + a21 * z * y1) / d;
        return (1 + b1 * z * y1 + b2 * z * y2) / d;
    }
    /* ROS2: M k1 = z, M k2 = z (1 + k1) - 2 k1, R = 1 + 3/2 k1 + 1/2 k2 (h k scaled) */
    double g = 1.70710678118654752440, d = 1 - g * z;
    double k1 = z / d, k2 = (z * (1 + k1) - 2 * k1) / d;
    return 1 + 1.5 * k1 + 0.5 * k2;
}

/* y' = -1e6 y at h = 1e-3 (z = -1000) and y' = -1e12 y (z = -1e9): the one-step
   amplification equals R(z); 100 steps stay bounded and decay; the trapezoidal rule
   keeps |R(-inf)| = 1, the L-stable methods damp to ~0 */
static void test_dahlquist(void)
{
    static const real_t one[] = {1};
    static const real_t lam6[] = {(real_t)-1e6}, lam12[] = {(real_t)-1e12};
    rt_set_cfg cfg = {.substeps = 1}; /* the method's own step: ROS2 would split one
                                              whose estimate exceeds the accuracy */
    for (unsigned i = 0; i < NMETHODS; i++) {
        const rt_integrator *m = methods[i];
        double r1 = 0, r2 = 0, x100 = 0;
        if (run(&dahl, lam6, one, m, cfg, (real_t)1e-3, (real_t)1e-3))
            r1 = (double)tu_sim.state.x[0];
        TH_CHECK(rt_stats_of(&tu_sim)->count[RT_CNT_DEGRADED] == 0);
        if (run(&dahl, lam6, one, m, cfg, (real_t)1e-3, (real_t)0.1))
            x100 = (double)tu_sim.state.x[0];
        if (run(&dahl, lam12, one, m, cfg, (real_t)1e-3, (real_t)1e-3))
            r2 = (double)tu_sim.state.x[0];
        th_put("  ");
        th_put(m->name);
        th_note("R(-1000) =", r1);
        th_note("R(-1e9) =", r2);
        th_note("|x| after 100 steps =", dabs(x100));
        /* ROS2 has no Newton iteration to remove the error of the finite-difference
           Jacobian, sqrt(eps) relative: in single precision (3e-4) it shows in R */
        double rtol = FLT ? (m == &rt_ros2 ? 0.1 : 1e-5) : (m == &rt_ros2 ? 1e-6 : 1e-12);
        TH_NEAR(r1, stab_fn(m, -1000), rtol * dabs(r1) + 1e-12);
        TH_CHECK(dabs(x100) <= 1 && dabs(x100) < dabs(r1) && rt_isfinite((real_t)x100));
        if (m == &rt_trap) {
            TH_CHECK(dabs(r1) > 0.99 && dabs(r1) < 1);
            TH_CHECK(dabs(r2) > 0.999 && dabs(r2) <= 1);
            TH_CHECK(dabs(x100) > 0.5); /* 0.996^100: barely damped */
        } else {
            TH_CHECK(dabs(r1) < 1e-2); /* R(z) ~ R(inf) + O(1/z) */
            TH_CHECK(dabs(r2) < (FLT && m == &rt_ros2 ? 1e-4 : 1e-6));
            TH_CHECK(dabs(x100) < 1e-30 || (FLT && x100 == 0));
        }
    }
}

/* ------------------------------------------------------------------ order */

/* |x(2) - exp(sin 2)| for method m at step h */
static double growth_error(const rt_integrator *m, rt_set_cfg cfg, real_t h)
{
    static const real_t one[] = {1};
    if (!run(&growth, 0, one, m, cfg, h, 2))
        return 1e30;
    TH_CHECK(rt_stats_of(&tu_sim)->count[RT_CNT_DEGRADED] == 0);
    return dabs((double)tu_sim.state.x[0] - (double)rt_exp(rt_sin(rt_time(&scene, &tu_sim))));
}

typedef struct order_case {
    const rt_integrator *m;
    uint16_t jac_every;
    real_t h, h_float; /* coarse steps in the asymptotic range, well above roundoff */
} order_case;

/* error ratio when halving h ~ 2^p; ROS2 keeps its order with a stale Jacobian */
static void test_orders(void)
{
    static const order_case cases[] = {
        {&rt_beuler, 1, (real_t)0.01, (real_t)0.01},
        {&rt_trap, 1, (real_t)0.02, (real_t)0.05},
        {&rt_sdirk2, 1, (real_t)0.02, (real_t)0.05},
        {&rt_sdirk3, 1, (real_t)0.05, (real_t)0.2},
        {&rt_ros2, 1, (real_t)0.02, (real_t)0.05},
        {&rt_ros2, 10, (real_t)0.0125, (real_t)0.0125}, /* asymptotic later than fresh */
    };
    for (unsigned i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        const order_case *c = &cases[i];
        rt_set_cfg cfg = {.jac_every = c->jac_every};
        real_t h = FLT ? c->h_float : c->h;
        double e1 = growth_error(c->m, cfg, h), e2 = growth_error(c->m, cfg, h / 2);
        double p = (double)rt_log((real_t)(e1 / e2)) / (double)rt_log(2);
        th_put("  ");
        th_put(c->m->name);
        th_note(c->jac_every > 1 ? "order, Jacobian every 10 steps" : "order", p);
        TH_NEAR(p, c->m->order, 0.25);
    }
}

/* ------------------------------------------------------------------ stiff linear */

/* A = V diag(l) V^-1 with V unit upper triangular (ones), V^-1 bidiagonal */
static const double stiff_l[3] = {-1, -100, -10000};
static const double stiff_v[9] = {1, 1, 1, 0, 1, 1, 0, 0, 1};
static const double stiff_vi[9] = {1, -1, 0, 0, 1, -1, 0, 0, 1};

static void stiff_matrix(void)
{
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            double a = 0, e = 0;
            for (int k = 0; k < 3; k++) {
                a += stiff_v[i * 3 + k] * stiff_l[k] * stiff_vi[k * 3 + j];
                e += stiff_v[i * 3 + k] * stiff_vi[k * 3 + j];
            }
            stiff_a[i * 3 + j] = (real_t)a;
            TH_CHECK(e == (i == j)); /* V^-1 is the inverse */
        }
}

/* exp(A t) x0 = V diag(exp(l t)) V^-1 x0 */
static void stiff_exact(double t, const real_t *x0, double *x)
{
    double c[3];
    for (int k = 0; k < 3; k++) {
        c[k] = 0;
        for (int j = 0; j < 3; j++)
            c[k] += stiff_vi[k * 3 + j] * (double)x0[j];
        c[k] *= (double)rt_exp((real_t)(stiff_l[k] * t));
    }
    for (int i = 0; i < 3; i++)
        x[i] = stiff_v[i * 3] * c[0] + stiff_v[i * 3 + 1] * c[1] + stiff_v[i * 3 + 2] * c[2];
}

/* largest error at t = 1 against the exponential, at step h */
static double stiff_error(const rt_integrator *m, real_t h)
{
    static const real_t x0[] = {3, 2, 1}; /* V^-1 x0 = (1, 1, 1): every mode excited */
    rt_set_cfg cfg = {.jac_every = 1000, .substeps = 1};
    double ex[3], e = 0;
    if (!run(&stiff3, 0, x0, m, cfg, h, 1))
        return 1e30;
    stiff_exact((double)rt_time(&scene, &tu_sim), x0, ex);
    for (int i = 0; i < 3; i++) {
        double d = dabs((double)tu_sim.state.x[i] - ex[i]);
        e = d > e ? d : e;
    }
    /* linear: one Jacobian for the run, a few iterations per stage, never degraded */
    TH_CHECK(rt_stats_of(&tu_sim)->istats[0].jac_evals == 1 && rt_stats_of(&tu_sim)->istats[0].degraded == 0);
    TH_CHECK(rt_stats_of(&tu_sim)->istats[0].newton_iter_max <= 4u * m->stages);
    return e;
}

/* eigenvalues -1, -100, -1e4 at h = 0.01 (h l down to -100): the L-stable methods follow
   the slow mode at their order; the trapezoidal rule carries 0.96^100 of the fast one.
   In single precision the finite-difference Jacobian is off by 3e-4 of its largest
   entries (1e4): ROS2 takes that error into the slow mode, the Newton methods do not. */
static void test_stiff_linear(void)
{
    static const double bound[NMETHODS] = {3e-3, 3e-2, 3e-6, 3e-8, 1e-4};
    static const double bound_float[NMETHODS] = {3e-3, 3e-2, 2e-5, 2e-5, 5e-3};
    stiff_matrix();
    double e_trap = stiff_error(&rt_trap, (real_t)0.01);
    for (unsigned i = 0; i < NMETHODS; i++) {
        const rt_integrator *m = methods[i];
        double e1 = stiff_error(m, (real_t)0.01), e2 = stiff_error(m, (real_t)0.005);
        th_put("  ");
        th_put(m->name);
        th_note("error at h = 0.01", e1);
        th_note("error at h = 0.005", e2);
        TH_CHECK(e1 < (FLT ? bound_float[i] : bound[i]));
        if (m != &rt_trap && m->order >= 2)
            TH_CHECK(e1 < e_trap / (FLT && m == &rt_ros2 ? 5 : 100));
    }
}

/* ROS2 splits a step whose estimate exceeds the accuracy: on the stiff linear system
   with its Jacobian kept for the run (a W-method's error grows with the Jacobian's age)
   and a coarse step, the split steps are counted and the answer gets closer to the
   exponential than the unsplit method's; the bound rt_step_bound gives covers them */
static void test_ros2_split(void)
{
    static const real_t x0[] = {3, 2, 1};
    double ex[3], e_split = 0, e_one = 0;
    stiff_matrix();
    for (int split = 0; split < 2; split++) {
        rt_set_cfg cfg = {.jac_every = 1000, .substeps = (uint8_t)(split ? 0 : 1),
                               .accuracy = (real_t)1e-3};
        if (!TH_CHECK(run(&stiff3, 0, x0, &rt_ros2, cfg, (real_t)0.1, 1)))
            return;
        stiff_exact((double)rt_time(&scene, &tu_sim), x0, ex);
        double e = 0;
        for (int i = 0; i < 3; i++)
            e = dabs((double)tu_sim.state.x[i] - ex[i]) > e ? dabs((double)tu_sim.state.x[i] - ex[i]) : e;
        *(split ? &e_split : &e_one) = e;
        if (split)
            TH_CHECK(rt_stats_of(&tu_sim)->istats[0].substepped > 0 && rt_stats_of(&tu_sim)->count[RT_CNT_SUBSTEP] > 0);
        else
            TH_CHECK(rt_stats_of(&tu_sim)->istats[0].substepped == 0);
    }
    th_note("ROS2 at h = 0.1, error without splitting", e_one);
    th_note("ROS2 at h = 0.1, error with splitting", e_split);
    TH_CHECK(e_split < e_one);
    rt_step_work wk;
    rt_ros2.bound(&rt_ros2, &(rt_set_cfg){0}, 3, &wk);
    TH_CHECK(wk.rhs == (2 * RT_IMP_SUBSTEPS - 1) * (3 + 3) && wk.lu == 2 * RT_IMP_SUBSTEPS - 1);
}

/* ROS2 with its Jacobian every K steps spreads the refresh (rt/integ_implicit.c,
   spread_parts: n columns, M, n elimination stages, ceil((2n + 1) / (K - 1)) a step): on
   the stiff linear system (n = 3, K = 8) no step takes more than a step without any
   refresh (the start-only run: its first Jacobian is taken before the first tick) plus
   one column, where the whole refresh in one step took n = 3 more; one refresh per K
   steps as before, the first before the first tick. The error against the exponential
   stays within 1.5 times the error with a fresh Jacobian every step (binary32: 30 times;
   the system is linear: every column is the exact Jacobian's up to the rounding of its
   difference quotient). */
static double stiff_err_now(const real_t *x0)
{
    double ex[3], e = 0;
    stiff_exact((double)rt_time(&scene, &tu_sim), x0, ex);
    for (int i = 0; i < 3; i++)
        e = dabs((double)tu_sim.state.x[i] - ex[i]) > e ? dabs((double)tu_sim.state.x[i] - ex[i]) : e;
    return e;
}

static void test_ros2_spread(void)
{
    static const real_t x0[] = {3, 2, 1};
    real_t h = (real_t)0.01;
    stiff_matrix();
    rt_set_cfg never = {.jac_every = 60000, .substeps = 1}, fresh = {.jac_every = 1};
    if (!TH_CHECK(run(&stiff3, 0, x0, &rt_ros2, never, h, 1)))
        return;
    uint32_t plain = rt_stats_of(&tu_sim)->istats[0].rhs_step_max;
    TH_CHECK(rt_stats_of(&tu_sim)->istats[0].jac_evals == 1);
    if (!TH_CHECK(run(&stiff3, 0, x0, &rt_ros2, fresh, h, 1)))
        return;
    double e_fresh = stiff_err_now(x0);
    if (!TH_CHECK(run(&stiff3, 0, x0, &rt_ros2, (rt_set_cfg){.jac_every = 8, .substeps = 1},
                      h, 1)))
        return;
    const rt_istats *s = &rt_stats_of(&tu_sim)->istats[0];
    th_note("ROS2, Jacobian every 8 steps: most evaluations in one step", s->rhs_step_max);
    TH_CHECK(s->rhs_step_max == plain + 1);
    TH_CHECK(tu_sim.state.tick == 100 && s->jac_evals == 1 + (100 - 1) / 8);
    double e = stiff_err_now(x0);
    th_note("ROS2 at h = 0.01, error with a fresh Jacobian every step", e_fresh);
    th_note("ROS2 at h = 0.01, error with the refresh spread over 8 steps", e);
    /* binary32: the difference quotients' rounding (increment sqrt(eps) = 3.5e-4 on
       entries up to 1e4) makes a reused J off by some 1e-4 relative, which shows */
    TH_CHECK(e < (FLT ? 30 : 1.5) * e_fresh);
}

/* the spread refresh's factors are those of one whole refresh (rt/integ_implicit.c,
   m_columns: each column made M's of I - h gamma J as it comes, the pivot floor kept as a
   running maximum, the elimination stages over later steps). At the equilibrium x = 0 of
   the stiff linear system every forward-difference column is the same, (a_ij d) / d with
   d = sqrt(eps), whichever step takes it; after one cycle (K = 8: the factors installed
   at the ninth step) lu and its pivots equal rti_lu of I - h gamma J formed at once by
   hand, with the h gamma of a fresh Jacobian every step */
static void test_ros2_spread_factors(void)
{
    static const real_t zero[] = {0, 0, 0};
    real_t h = (real_t)0.01;
    stiff_matrix();
    if (!TH_CHECK(run(&stiff3, 0, zero, &rt_ros2, (rt_set_cfg){.jac_every = 1}, h, h)))
        return;
    real_t hg = tu_sim.state.imp[0].h_factored;
    if (!TH_CHECK(run(&stiff3, 0, zero, &rt_ros2, (rt_set_cfg){.jac_every = 8, .substeps = 1},
                      h, 9 * h)))
        return;
    const rt_implicit_ws *ws = &tu_sim.state.imp[0];
    TH_CHECK(tu_sim.state.tick == 9 && rt_stats_of(&tu_sim)->istats[0].jac_evals == 2);
    TH_CHECK(ws->valid && ws->h_factored == hg);
    real_t m[9], d = rt_sqrt(RT_EPS);
    uint16_t piv[3];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            m[i * 3 + j] = (i == j ? 1 : 0) - hg * (stiff_a[i * 3 + j] * d / d);
    if (!TH_CHECK(rti_lu(m, 3, piv, (real_t)1e-12) == RT_OK))
        return;
    int same = 1; /* values (a zero of either sign is the same M) */
    for (int k = 0; k < 9; k++)
        same = same && m[k] == ws->lu[k];
    for (int i = 0; i < 3; i++)
        same = same && piv[i] == ws->piv[i];
    TH_CHECK(same);
}

/* ------------------------------------------------------------------ degraded steps */

/* the cubic with k = 1e3 at h = 0.01 (h k = 10): a Jacobian frozen at x = 0 makes
   simplified Newton diverge once |x| grows, and two iterations cannot reach 1e-8. Every
   such step is retried with a Jacobian at its iterate (full Newton, twice the
   iterations) and converges there: no step is degraded, none is left at its start, and
   the answer is the converged one (eight iterations on fresh Jacobians at every step). */
static void test_degraded(void)
{
    static const real_t p[] = {1000, 3}, zero[] = {0};
    rt_set_cfg bad = {.newton_max = 2, .jac_every = 60000};
    rt_set_cfg good = {.newton_max = 8};
    for (unsigned i = 0; i < NMETHODS; i++) {
        const rt_integrator *m = methods[i];
        if (m == &rt_ros2)
            continue; /* no Newton iteration: never degraded by construction */
        TH_CHECK(run(&cubic, p, zero, m, bad, (real_t)0.01, 3));
        const rt_istats *s = &tu_sim.stats.istats[0];
        th_put("  ");
        th_put(m->name);
        th_note("retried steps of 300 with a frozen Jacobian", s->retried);
        TH_CHECK(s->retried > 0 && s->degraded == 0 && s->jac_evals > s->retried);
        TH_CHECK(rt_stats_of(&tu_sim)->count[RT_CNT_DEGRADED] == 0 && rt_stats_of(&tu_sim)->count[RT_CNT_NAN] == 0);
        /* the attempt (2 per stage) and the retry (4 per stage) */
        TH_CHECK(s->newton_iter_max <= 6u * m->stages);
        double x_bad = (double)tu_sim.state.x[0];

        TH_CHECK(run(&cubic, p, zero, m, good, (real_t)0.01, 3));
        TH_CHECK(s->degraded == 0 && s->retried == 0 && rt_stats_of(&tu_sim)->count[RT_CNT_DEGRADED] == 0);
        TH_CHECK(s->jac_evals == 300 && s->newton_iter_max <= 8u * m->stages);
        TH_CHECK(s->last_residual <= (FLT ? 1e-5 : 1e-8));
        th_note("|x(3) - converged x(3)|", dabs(x_bad - (double)tu_sim.state.x[0]));
        TH_CHECK(rt_isfinite((real_t)x_bad) && dabs(x_bad - (double)tu_sim.state.x[0]) < (FLT ? 1e-4 : 1e-7));
    }
    /* one iteration per stage, no substeps: the attempt (1) and the retry (2) cannot show
       convergence from a cold start; the step keeps its best iterate, is counted as
       degraded, and is not its start state */
    TH_CHECK(run(&cubic, p, zero, &rt_sdirk2,
                 (rt_set_cfg){.newton_max = 1, .substeps = 1}, (real_t)0.01, 1));
    /* (float's tolerance 1e-5 is met by two full-Newton iterations at some steps) */
    th_note("degraded of 100 with one iteration", rt_stats_of(&tu_sim)->istats[0].degraded);
    TH_CHECK(FLT ? rt_stats_of(&tu_sim)->istats[0].degraded > 0 : rt_stats_of(&tu_sim)->istats[0].degraded == 100);
    TH_CHECK(rt_isfinite(tu_sim.state.x[0]));
    TH_CHECK(rt_stats_of(&tu_sim)->status == RT_E_DEGRADED && tu_sim.state.x[0] != 0);
}

/* ------------------------------------------------------------------ Jacobian reuse */

/* the cubic with k = 100, a = 1 (h k = 1, slope varying by 2.4): a Jacobian kept 10
   steps costs a tenth of the refreshes; the Newton methods give the same answer within
   their tolerance, ROS2 (whose answer depends on the Jacobian) stays within 1e-3 */
static void test_jac_reuse(void)
{
    static const real_t p[] = {100, 1}, zero[] = {0};
    for (unsigned i = 0; i < NMETHODS; i++) {
        const rt_integrator *m = methods[i];
        TH_CHECK(run(&cubic, p, zero, m, (rt_set_cfg){.newton_max = 8, .substeps = 1},
                     (real_t)0.01, 3));
        double x1 = (double)tu_sim.state.x[0];
        uint32_t j1 = rt_stats_of(&tu_sim)->istats[0].jac_evals, it1 = rt_stats_of(&tu_sim)->istats[0].newton_iter_max;
        TH_CHECK(rt_stats_of(&tu_sim)->istats[0].degraded == 0);
        TH_CHECK(run(&cubic, p, zero, m,
                     (rt_set_cfg){.newton_max = 8, .jac_every = 10, .substeps = 1},
                     (real_t)0.01, 3));
        double x10 = (double)tu_sim.state.x[0];
        uint32_t j10 = rt_stats_of(&tu_sim)->istats[0].jac_evals, it10 = rt_stats_of(&tu_sim)->istats[0].newton_iter_max;
        th_put("  ");
        th_put(m->name);
        th_note("jac_evals every step", j1);
        th_note("jac_evals every 10 steps", j10);
        th_note("Newton iterations per step, max", it10 > it1 ? it10 : it1);
        th_note("|x(3) difference|", dabs(x1 - x10));
        TH_CHECK(j1 == 300 && j10 == 30);
        TH_CHECK(rt_stats_of(&tu_sim)->istats[0].degraded == 0);
        TH_CHECK(dabs(x1 - x10) < (m == &rt_ros2 ? 1e-3 : FLT ? 1e-4 : 1e-8));
    }
}

/* ------------------------------------------------------------------ singular matrix */

/* x1' = a x1, x2' = -x2, called directly on the simulator's workspace */
typedef struct diag_rhs {
    real_t *x;
    real_t a;
} diag_rhs;

static rt_status diag_eval(void *ctx, real_t t, real_t *xdot)
{
    const diag_rhs *c = ctx;
    (void)t;
    xdot[0] = c->a * c->x[0];
    xdot[1] = -c->x[1];
    return RT_OK;
}

static rt_iwork direct_work(const rt_set_cfg *cfg)
{
    rt_iwork w;
    for (int i = 0; i < RT_MAX_STAGES; i++)
        w.k[i] = tu_sim.work.w.k[i];
    w.x0 = tu_sim.work.x0, w.xs = 0;
    w.imp = &tu_sim.state.imp[0];
    w.stats = &tu_sim.stats.istats[0];
    w.cfg = cfg;
    w.autonomous = 0;
    tu_sim.state.imp[0].valid = 0, tu_sim.state.imp[0].age = 0;
    tu_sim.stats.istats[0] = (rt_istats){0};
    return w;
}

/* backward Euler with a = 1/h: I - h J is singular. Where the singular direction holds
   no residual the step converges and reports RT_E_SINGULAR; where it does, the step
   converges in two substeps (I - h/2 J is regular): x1 = 1 / (1 - 1/2)^2 = 4, exactly
   two backward Euler steps of h/2. Without substeps it completes finite and reports
   RT_E_NOCONV, counted as degraded. */
static void test_singular(void)
{
    static const rt_set_cfg cfg = {0};
    real_t x[2] = {0, 1}, h = (real_t)1e-3;
    diag_rhs c = {x, 1 / h};
    rt_rhs f = {diag_eval, &c};
    rt_iwork w = direct_work(&cfg);
    rt_status st = rt_beuler.step(&rt_beuler, &f, 0, h, x, 2, &w);
    TH_CHECK(st == RT_E_SINGULAR && tu_sim.state.imp[0].valid == 0);
    TH_CHECK(x[0] == 0);
    TH_NEAR(x[1], 1 / (1 + h), FLT ? 1e-6 : 1e-14);

    x[0] = 1, x[1] = 1;
    w = direct_work(&cfg);
    st = rt_beuler.step(&rt_beuler, &f, 0, h, x, 2, &w);
    TH_CHECK(st == RT_OK && rt_stats_of(&tu_sim)->istats[0].substepped == 1);
    TH_CHECK(rt_stats_of(&tu_sim)->istats[0].degraded == 0);
    TH_NEAR(x[0], 4, FLT ? 1e-5 : 1e-12);
    TH_NEAR(x[1], 1 / ((1 + h / 2) * (1 + h / 2)), FLT ? 1e-6 : 1e-14);

    static const rt_set_cfg nosplit = {.substeps = 1};
    x[0] = 1, x[1] = 1;
    w = direct_work(&nosplit);
    st = rt_beuler.step(&rt_beuler, &f, 0, h, x, 2, &w);
    TH_CHECK(st == RT_E_NOCONV && rt_stats_of(&tu_sim)->istats[0].degraded == 1);
    TH_CHECK(rt_isfinite(x[0]) && rt_isfinite(x[1]));
    TH_CHECK(rt_isfinite(rt_stats_of(&tu_sim)->istats[0].last_residual));
}

/* ------------------------------------------------------------------ multibody set */

/* a planar pendulum of unit length as a point mass in Cartesian coordinates (x, y, vx, vy)
   under g = 9.81 m/s^2, standing in for the multibody services: accel solves the index-1
   system (constraint r.r = 1 differentiated twice), project puts the state back on the
   position and velocity constraints after every step */
static const int pend_spec = 1;
static const char *const pend_x[] = {"x", "y", "vx", "vy"};
static void pend_out(const rt_args *a, real_t *y) { y[0] = a->x[0], y[1] = a->x[1]; }
static const rt_kind pend = {
    .name = "pendulum", .type = RT_KIND_MBS, .ny = 2, .nx = 4,
    .y_names = pend_x, .x_names = pend_x, .feed = RT_FEED_NONE, .output = pend_out,
    .spec = &pend_spec,
};

static int pend_init(const rt_scene *sc, rt_sim *sim)
{
    (void)sc, (void)sim;
    return RT_OK;
}

static void pend_accel(const rt_scene *sc, rt_sim *sim, uint8_t s, real_t t, real_t *xdot)
{
    const real_t *q = sim->state.x + sim->plan.set_x[s];
    real_t g = (real_t)9.81, rr = q[0] * q[0] + q[1] * q[1];
    real_t lam = (-g * q[1] + q[2] * q[2] + q[3] * q[3]) / rr;
    (void)sc, (void)t;
    xdot[0] = q[2], xdot[1] = q[3];
    xdot[2] = -lam * q[0], xdot[3] = -g - lam * q[1];
}

static void pend_project(const rt_scene *sc, rt_sim *sim, uint8_t s, real_t t)
{
    real_t *q = sim->state.x + sim->plan.set_x[s];
    real_t r = rt_sqrt(q[0] * q[0] + q[1] * q[1]);
    (void)sc, (void)t;
    q[0] /= r, q[1] /= r;
    real_t vr = q[2] * q[0] + q[3] * q[1];
    q[2] -= vr * q[0], q[3] -= vr * q[1];
}

static const rt_mbs_ops pend_ops = {.init = pend_init, .accel = pend_accel,
                                    .project = pend_project};

/* released horizontally: after 1 s the implicit methods (each step followed by the
   projection) agree with RK4 at a tenth of the step, and stay on the constraint */
static void test_multibody(void)
{
    static const real_t x0[] = {1, 0, 0, 0};
    static const double tol[NMETHODS] = {0.2, 2e-3, 2e-3, 1e-4, 2e-3};
    real_t ref[4];
    build(&pend, 0, x0, &rt_rk4, (rt_set_cfg){0}, (real_t)1e-4, 1);
    scene.mbs = &pend_ops;
    TH_CHECK(tu_init(&scene) && tu_run_to(&scene, 1) == RT_E_DONE);
    for (int i = 0; i < 4; i++)
        ref[i] = tu_sim.state.x[i];
    for (unsigned i = 0; i < NMETHODS; i++) {
        const rt_integrator *m = methods[i];
        build(&pend, 0, x0, m, (rt_set_cfg){0}, (real_t)1e-3, 1);
        scene.mbs = &pend_ops;
        TH_CHECK(tu_init(&scene) && tu_run_to(&scene, 1) == RT_E_DONE);
        double e = 0, c = (double)(tu_sim.state.x[0] * tu_sim.state.x[0] + tu_sim.state.x[1] * tu_sim.state.x[1]);
        for (int k = 0; k < 4; k++) {
            double d = dabs((double)(tu_sim.state.x[k] - ref[k]));
            e = d > e ? d : e;
        }
        th_put("  ");
        th_put(m->name);
        th_note("pendulum state error at 1 s", e);
        TH_CHECK(e < tol[i] + (FLT ? 1e-3 : 0));
        TH_NEAR(c, 1, FLT ? 1e-6 : 1e-14);
        TH_CHECK(rt_stats_of(&tu_sim)->count[RT_CNT_DEGRADED] == 0 && rt_stats_of(&tu_sim)->istats[0].jac_evals == 1000);
    }
}

/* largest |r_k - r_(k-1)| - 1 of the ten-body pendulum's joints, from its states */
static double chain_residual(void)
{
    double g = 0;
    for (int k = 0; k < 10; k++) {
        double d2 = 0;
        for (int c = 0; c < 3; c++) {
            double a = (double)tu_sim.state.x[6 * k + c], b = k ? (double)tu_sim.state.x[6 * k - 6 + c] : 0;
            d2 += (a - b) * (a - b);
        }
        double r = dabs((double)rt_sqrt((real_t)d2) - 1);
        g = r > g ? r : g;
    }
    return g;
}

/* the library's ten-body pendulum (60 states, the multibody services of rt/mbs.c) for
   0.5 s at 1 ms: SDIRK2 with a Jacobian kept 10 steps agrees with Dormand-Prince and
   keeps the constraints (projection after every step) */
static void test_pendulum10(void)
{
    rt_scene sc = mdl_scene_pendulum10;
    rt_set s = sc.sets[0];
    s.method = &rt_dopri5;
    sc.sets = &s, sc.dt = (real_t)1e-3, sc.t_end = (real_t)0.5, sc.nrecs = 0;
    real_t ref[60];
    if (!tu_init(&sc) || !TH_CHECK(tu_run_to(&sc, sc.t_end) == RT_E_DONE))
        return;
    uint16_t n = tu_sim.plan.set_x[1];
    if (!TH_CHECK(n == 60))
        return;
    for (uint16_t i = 0; i < n; i++)
        ref[i] = tu_sim.state.x[i];
    s.method = &rt_sdirk2, s.cfg = (rt_set_cfg){.jac_every = 10};
    if (!tu_init(&sc) || !TH_CHECK(tu_run_to(&sc, sc.t_end) == RT_E_DONE))
        return;
    double e = 0;
    for (uint16_t i = 0; i < n; i++) {
        double d = dabs((double)(tu_sim.state.x[i] - ref[i]));
        e = d > e ? d : e;
    }
    th_note("pendulum10, sdirk2 vs dopri5 at 0.5 s, largest state difference", e);
    th_note("largest constraint residual [m]", chain_residual());
    th_note("Newton iterations per step, max", rt_stats_of(&tu_sim)->istats[0].newton_iter_max);
    TH_CHECK(e < 1e-4 && chain_residual() < (FLT ? 1e-5 : 1e-12));
    TH_CHECK(rt_stats_of(&tu_sim)->istats[0].degraded == 0 && rt_stats_of(&tu_sim)->istats[0].jac_evals == 50);
}

/* ------------------------------------------------------------------ state events */

/* the library's bouncing ball at 1 ms for 3.5 s: event location re-steps from the saved
   state with trial fractions of the step (a new h gamma each: M refactored from the kept
   Jacobian), and the integration after the handlers takes a fresh one (they may have
   changed the dynamics: rt/step.c), one per impact. The order-2 and -3 methods integrate
   its quadratic motion exactly, so they find the same impacts as RK4; backward Euler is
   off by O(h). */
static void test_events(void)
{
    rt_set_cfg cfg = {.jac_every = 60000};
    double n_ref = 0, t_ref = 0;
    if (run(&mdl_ball_kind, 0, 0, &rt_rk4, (rt_set_cfg){0}, (real_t)1e-3, (real_t)3.5))
        n_ref = (double)tu_sim.state.d[MDL_BALL_D_N], t_ref = (double)tu_sim.state.d[MDL_BALL_D_T];
    TH_CHECK(n_ref >= 5);
    for (unsigned i = 0; i < NMETHODS; i++) {
        const rt_integrator *m = methods[i];
        TH_CHECK(run(&mdl_ball_kind, 0, 0, m, cfg, (real_t)1e-3, (real_t)3.5));
        double n = (double)tu_sim.state.d[MDL_BALL_D_N], t = (double)tu_sim.state.d[MDL_BALL_D_T];
        th_put("  ");
        th_put(m->name);
        th_note("impacts", n);
        th_note("last impact time - RK4's [s]", t - t_ref);
        th_note("Jacobians", rt_stats_of(&tu_sim)->istats[0].jac_evals);
        TH_CHECK(rt_stats_of(&tu_sim)->count[RT_CNT_EVENTS] == (uint32_t)n &&
                 rt_stats_of(&tu_sim)->istats[0].jac_evals == 1 + (uint32_t)n);
        TH_CHECK(rt_stats_of(&tu_sim)->count[RT_CNT_DEGRADED] == 0 && rt_stats_of(&tu_sim)->count[RT_CNT_EVENT_NOLOC] == 0);
        if (m->order >= 2)
            TH_CHECK(n == n_ref && dabs(t - t_ref) < (FLT ? 1e-4 : 1e-12));
        else
            TH_CHECK(dabs(n - n_ref) <= 1);
    }
}

/* ------------------------------------------------------------------ replay, registry */

/* the same run twice gives the same bits, statistics included */
static void test_replay(void)
{
    static const real_t p[] = {1000, 3}, zero[] = {0};
    rt_set_cfg cfg = {.newton_max = 3, .jac_every = 7};
    for (unsigned i = 0; i < NMETHODS; i++) {
        real_t x;
        rt_istats s;
        TH_CHECK(run(&cubic, p, zero, methods[i], cfg, (real_t)0.01, 2));
        x = tu_sim.state.x[0], s = rt_stats_of(&tu_sim)->istats[0];
        TH_CHECK(run(&cubic, p, zero, methods[i], cfg, (real_t)0.01, 2));
        TH_CHECK(rt_hash_real(0, x) == rt_hash_real(0, tu_sim.state.x[0]));
        TH_CHECK(s.degraded == rt_stats_of(&tu_sim)->istats[0].degraded &&
                 s.jac_evals == rt_stats_of(&tu_sim)->istats[0].jac_evals &&
                 s.newton_iter_max == rt_stats_of(&tu_sim)->istats[0].newton_iter_max &&
                 rt_hash_real(0, s.last_residual) ==
                     rt_hash_real(0, rt_stats_of(&tu_sim)->istats[0].last_residual));
    }
}

static void test_registry(void)
{
    for (unsigned i = 0; i < NMETHODS; i++) {
        TH_CHECK(rt_integrator_find(methods[i]->name) == methods[i]);
        TH_CHECK(methods[i]->implicit == 1 && methods[i]->stages <= RT_MAX_STAGES);
    }
}

/* ROS2 skips f(t + h, x0) in an autonomous set (docs/solvers.md) with the bits of the
   evaluation it skips (f_t = +0): Dahlquist's equation declared autonomous against the
   same kind undeclared, 100 steps; what is not autonomous: a kind that does not declare it
   (the growth equation, whose order with time test implicit_orders checks) and, in the
   library's pendulum10_actuated, the chain, which reads the servo's torque from its
   history, while the servo set (a controller sampled, a servo under its held command) is */
static void test_ros2_autonomous(void)
{
    static const real_t lam[] = {-2}, one[] = {1}; /* no step above the accuracy: no split */
    static rt_kind auto_dahl;
    auto_dahl = dahl, auto_dahl.autonomous = 1;
    real_t x[2];
    uint32_t evals[2];
    uint8_t flags[2];
    for (int v = 0; v < 2; v++) {
        if (!run(v ? &auto_dahl : &dahl, lam, one, &rt_ros2, (rt_set_cfg){.jac_every = 8},
                 (real_t)0.01, 1))
            return;
        x[v] = tu_sim.state.x[0];
        evals[v] = rt_stats_of(&tu_sim)->rhs_evals[0];
        flags[v] = tu_sim.plan.set_flags[0];
    }
    TH_CHECK(!(flags[0] & RTI_SET_AUTONOMOUS) && (flags[1] & RTI_SET_AUTONOMOUS));
    TH_CHECK(x[0] == x[1] && x[1] != 0);
    TH_CHECK(evals[0] == evals[1] + 100); /* one evaluation fewer per step */
    TH_NEAR(x[1], 0.1353352832366127, 5e-4); /* e^-2 (ROS2 at h = 0.01: 1.4e-4 off) */
    static const real_t x1[] = {1};
    TH_CHECK(setup(&growth, 0, x1, &rt_ros2, (rt_set_cfg){0}, (real_t)0.01, 1) &&
             !(tu_sim.plan.set_flags[0] & RTI_SET_AUTONOMOUS));
    const rt_scene *sc = &mdl_scene_pendulum10_actuated;
    if (!tu_init(sc))
        return;
    int chain = -1, servo = -1;
    for (int i = 0; i < sc->nsets; i++) {
        chain = rt_streq(sc->sets[i].name, "chain") ? i : chain;
        servo = rt_streq(sc->sets[i].name, "servo") ? i : servo;
    }
    TH_CHECK(chain >= 0 && servo >= 0);
    TH_CHECK(!(tu_sim.plan.set_flags[chain] & RTI_SET_AUTONOMOUS) &&
             (tu_sim.plan.set_flags[servo] & RTI_SET_AUTONOMOUS));
    /* pi_loop: kinds that all declare it, but an actual loop in its one set */
    if (!tu_init(&mdl_scene_pi_loop))
        return;
    TH_CHECK(tu_sim.plan.nloops > 0 && mdl_scene_pi_loop.nsets == 1 &&
             !(tu_sim.plan.set_flags[0] & RTI_SET_AUTONOMOUS));
}

const th_test th_implicit_tests[] = {
    {"implicit_dahlquist", test_dahlquist},
    {"implicit_orders", test_orders},
    {"implicit_stiff_linear", test_stiff_linear},
    {"implicit_ros2_split", test_ros2_split},
    {"implicit_ros2_spread", test_ros2_spread},
    {"implicit_ros2_spread_factors", test_ros2_spread_factors},
    {"implicit_ros2_autonomous", test_ros2_autonomous},
    {"implicit_degraded", test_degraded},
    {"implicit_jac_reuse", test_jac_reuse},
    {"implicit_singular", test_singular},
    {"implicit_multibody", test_multibody},
    {"implicit_pendulum10", test_pendulum10},
    {"implicit_events", test_events},
    {"implicit_replay", test_replay},
    {"implicit_registry", test_registry},
    {0, 0},
};
