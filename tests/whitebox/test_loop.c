/* test_loop.c - tests of rt/loop.c and the tearing in rt/order.c: a linear actual loop
 * solved in one iteration at every evaluation, a nonlinear one against its root found by
 * bisection inside the test, and bounded non-convergence without NaN. */
#include "models.h"
#include "rti.h" /* plan.set_flags' bits */
#include "testutil.h"

static const rt_set one_set[] = {{.name = "s", .method = &rt_rk4, .ratio = 1}};

/* y = a u^3, full throughput */
static const char *const cub_u[] = {"u"}, *const cub_y[] = {"y"}, *const cub_p[] = {"a"};
static void cub_out(const rt_args *a, real_t *y) { y[0] = a->p[0] * a->u[0] * a->u[0] * a->u[0]; }
static const rt_kind cubic = {
    .name = "cubic", .type = RT_KIND_OUTPUT, .nu = 1, .ny = 1, .np = 1,
    .u_names = cub_u, .y_names = cub_y, .p_names = cub_p, .feed = RT_FEED_ALL,
    .output = cub_out,
};

enum { SRC, SUM, FB };
/* Src -> Sum.u1, Fb -> Sum.u2, Sum -> Fb: Sum = c1 src + c2 fb(Sum), an actual loop */
static const rt_conn loop_conns[] = {{SRC, 0, SUM, 0}, {FB, 0, SUM, 1}, {SUM, 0, FB, 0}};

static rt_scene loop_scene(const rt_block *bl)
{
    rt_scene sc = {.name = "loop", .dt = (real_t)0.01, .t_end = 1, .blocks = bl,
                   .nblocks = 3, .conns = loop_conns, .nconns = 3, .sets = one_set,
                   .nsets = 1, .loop_solver = &rt_broyden};
    return sc;
}

/* s = sin t + 1, Sum = s - 0.5 * 3 * Sum  =>  Sum = s / 2.5 */
static void test_linear_loop(void)
{
    static const real_t sine_p[] = {1, 1, 0, 1}, sum_p[] = {1, (real_t)-0.5}, g_p[] = {3};
    static const rt_block bl[] = {
        [SRC] = {.name = "Src", .kind = &mdl_sine_kind, .p = sine_p},
        [SUM] = {.name = "Sum", .kind = &mdl_sum_kind, .p = sum_p},
        [FB] = {.name = "G", .kind = &mdl_gain_kind, .p = g_p},
    };
    rt_scene sc = loop_scene(bl);
    if (!tu_init(&sc))
        return;
    TH_CHECK(tu_sim.plan.ntorn >= 1);
    int actual = 0, marker = 0;
    for (int l = 0; l < tu_sim.plan.nloops; l++)
        actual += tu_sim.plan.loops[l].actual;
    for (int s = 0; s < tu_sim.plan.nseq; s++)
        marker += tu_sim.plan.seq[s].kind == RT_SEQ_LOOP;
    TH_CHECK(actual == 1 && marker == 1);
    double worst = 0;
    while (rt_tick(&sc, &tu_sim) == RT_OK) {
        double e = (double)tu_y(&sc, "Sum", 0) -
                   ((double)rt_sin(rt_time(&sc, &tu_sim)) + 1) / 2.5;
        worst = e < 0 ? (-e > worst ? -e : worst) : (e > worst ? e : worst);
    }
    th_note("worst loop error", worst);
    TH_CHECK(worst < (RT_REAL_IS_FLOAT ? 1e-5 : 1e-12));
    /* every solve took at most one iteration, and some took exactly one */
    TH_CHECK(rt_stats_of(&tu_sim)->loop_iter_max == 1 && rt_stats_of(&tu_sim)->loop_hist[1] > 0);
    TH_CHECK(rt_stats_of(&tu_sim)->count[RT_CNT_NOCONV] == 0 && rt_stats_of(&tu_sim)->status == RT_OK);
}

/* root of w = c - a w^3, by bisection (f is increasing in w) */
static double cubic_root(double c, double a)
{
    double lo = -10, hi = 10;
    for (int i = 0; i < 200; i++) {
        double m = 0.5 * (lo + hi);
        if (m + a * m * m * m - c > 0)
            hi = m;
        else
            lo = m;
    }
    return 0.5 * (lo + hi);
}

static void test_nonlinear_loop(void)
{
    static const real_t src_p[] = {0, 1, 1}, sum_p[] = {1, -1}, a_p[] = {1};
    static const rt_block bl[] = {
        [SRC] = {.name = "Src", .kind = &mdl_step_kind, .p = src_p},
        [SUM] = {.name = "Sum", .kind = &mdl_sum_kind, .p = sum_p},
        [FB] = {.name = "Cube", .kind = &cubic, .p = a_p},
    };
    rt_scene sc = loop_scene(bl);
    if (!tu_init(&sc))
        return;
    tu_run_to(&sc, (real_t)0.1);
    TH_NEAR(tu_y(&sc, "Sum", 0), cubic_root(1, 1), RT_REAL_IS_FLOAT ? 1e-5 : 1e-10);
    th_note("iterations at most", rt_stats_of(&tu_sim)->loop_iter_max);
    TH_CHECK(rt_stats_of(&tu_sim)->loop_iter_max <= RT_LOOP_ITER_MAX && rt_stats_of(&tu_sim)->count[RT_CNT_NOCONV] == 0);
}

/* a stiff cubic from a cold start with one iteration allowed: counted, finite, ticking */
static void test_loop_bound(void)
{
    static const real_t src_p[] = {0, 40, 40}, sum_p[] = {1, -1}, a_p[] = {50};
    static const rt_block bl[] = {
        [SRC] = {.name = "Src", .kind = &mdl_step_kind, .p = src_p},
        [SUM] = {.name = "Sum", .kind = &mdl_sum_kind, .p = sum_p},
        [FB] = {.name = "Cube", .kind = &cubic, .p = a_p},
    };
    rt_scene sc = loop_scene(bl);
    sc.loop_iter_max = 1;
    if (!tu_init(&sc))
        return;
    while (rt_tick(&sc, &tu_sim) == RT_OK)
        ;
    TH_CHECK(rt_ticks_done(&tu_sim) == 100);
    TH_CHECK(rt_stats_of(&tu_sim)->count[RT_CNT_NOCONV] > 0 && rt_stats_of(&tu_sim)->status == RT_E_NOCONV);
    TH_CHECK(rt_stats_of(&tu_sim)->last_block[RT_CNT_NOCONV] >= 0);
    TH_CHECK(rt_isfinite(tu_y(&sc, "Sum", 0)) && rt_isfinite(tu_y(&sc, "Cube", 0)));
    TH_CHECK(rt_stats_of(&tu_sim)->loop_iter_max == 1 && rt_stats_of(&tu_sim)->loop_residual > 0);
    /* with the default bound the same loop converges */
    sc.loop_iter_max = 0;
    sc.t_end = (real_t)0.05;
    if (!tu_init(&sc))
        return;
    while (rt_tick(&sc, &tu_sim) == RT_OK)
        ;
    TH_NEAR(tu_y(&sc, "Sum", 0), cubic_root(40, 50), RT_REAL_IS_FLOAT ? 1e-5 : 1e-10);
}

/* a set with an actual loop is never autonomous for ROS2 (rt/eval.c): its solver carries
   its estimates from one evaluation to the next, so f(t + h, x0) need not repeat f(t, x0)
   bit for bit even where every kind declares it reads no time (an oscillator, a sum and
   a gain here) */
static void test_loop_not_autonomous(void)
{
    static const real_t sum_p[] = {1, (real_t)-0.5}, g_p[] = {3};
    static const rt_block bl[] = {
        [SRC] = {.name = "Src", .kind = &mdl_oscillator_kind},
        [SUM] = {.name = "Sum", .kind = &mdl_sum_kind, .p = sum_p},
        [FB] = {.name = "G", .kind = &mdl_gain_kind, .p = g_p},
    };
    rt_scene sc = loop_scene(bl);
    if (!tu_init(&sc))
        return;
    TH_CHECK(bl[SRC].kind->autonomous && bl[SUM].kind->autonomous && bl[FB].kind->autonomous);
    TH_CHECK(tu_sim.plan.nloops == 1 && !(tu_sim.plan.set_flags[0] & RTI_SET_AUTONOMOUS));
}

const th_test th_loop_tests[] = {
    {"loop_linear_one_iteration", test_linear_loop},
    {"loop_nonlinear", test_nonlinear_loop},
    {"loop_bound", test_loop_bound},
    {"loop_not_autonomous", test_loop_not_autonomous},
    {0, 0},
};
