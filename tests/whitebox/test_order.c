/* test_order.c - tests of rt/order.c and rt/init.c: evaluation order, potential and
 * actual loops at block and port level, routing errors. Expected orders and values are
 * worked out by hand in the comments. */
#include "models.h"
#include "testutil.h"
#include "rt_sim.h" /* white box: reads rt_sim's parts (plan, state, work) */

static const rt_set one_set[] = {{.name = "s", .method = &rt_rk4, .ratio = 1}};

#define SCENE(bl, cn)                                                                  \
    {.name = "t", .dt = (real_t)0.01, .t_end = (real_t)0.1, .blocks = bl,            \
     .nblocks = sizeof bl / sizeof bl[0], .conns = cn, .nconns = sizeof cn / sizeof cn[0], \
     .sets = one_set, .nsets = 1}

/* blocks listed against the flow: G2 <- G1 <- Src must still run Src, G1, G2 */
static void test_chain_order(void)
{
    static const real_t src_p[] = {0, 3, 3}, g1_p[] = {2}, g2_p[] = {5};
    static const rt_block bl[] = {
        {.name = "G2", .kind = &mdl_gain_kind, .p = g2_p},
        {.name = "G1", .kind = &mdl_gain_kind, .p = g1_p},
        {.name = "Src", .kind = &mdl_step_kind, .p = src_p},
    };
    static const rt_conn cn[] = {{2, 0, 1, 0}, {1, 0, 0, 0}};
    static const rt_scene sc = SCENE(bl, cn);
    if (!tu_init(&sc))
        return;
    TH_CHECK(tu_sim.plan.nseq == 3);
    TH_CHECK(tu_sim.plan.seq[0].index == 2 && tu_sim.plan.seq[1].index == 1 && tu_sim.plan.seq[2].index == 0);
    TH_NEAR(tu_y(&sc, "G2", 0), 30, 0); /* 3 * 2 * 5 */
    TH_CHECK(tu_sim.plan.nloops == 0);
}

/* P (pt1, no throughput) -> G (gain) -> P: a potential loop, solved by ordering P, G */
static void test_potential_loop(void)
{
    static const real_t g_p[] = {-1};
    static const rt_block bl[] = {
        {.name = "G", .kind = &mdl_gain_kind, .p = g_p},
        {.name = "P", .kind = &mdl_pt1_kind},
    };
    static const rt_conn cn[] = {{1, 0, 0, 0}, {0, 0, 1, 0}};
    static const rt_scene sc = SCENE(bl, cn);
    if (!tu_init(&sc))
        return;
    TH_CHECK(tu_sim.plan.nloops == 1 && tu_sim.plan.loops[0].actual == 0 && tu_sim.plan.loops[0].nblocks == 2);
    TH_CHECK(tu_sim.plan.nseq == 2 && tu_sim.plan.seq[0].index == 1 && tu_sim.plan.seq[1].index == 0);
    /* y' = (-y - y) / 1 from y(0) = 0.5: y = 0.5 exp(-2t) */
    tu_sim.state.x[0] = (real_t)0.5;
    rt_refresh(&sc, &tu_sim);
    tu_run_to(&sc, (real_t)0.1);
    TH_NEAR(tu_sim.state.x[0], 0.5 * (double)rt_exp((real_t)-0.2), 1e-6);
}

/* G -> S.u1, Src -> S.u2, S -> G: every block on the cycle has throughput: actual */
static void test_actual_loop(void)
{
    static const rt_block bl[] = {
        {.name = "Src", .kind = &mdl_step_kind},
        {.name = "S", .kind = &mdl_sum_kind},
        {.name = "G", .kind = &mdl_gain_kind},
    };
    static const rt_conn cn[] = {{2, 0, 1, 0}, {0, 0, 1, 1}, {1, 0, 2, 0}};
    static const rt_scene sc = SCENE(bl, cn);
    TH_CHECK(rt_init(&sc, &tu_sim) == RT_E_LOOP);
    int actual = -1;
    for (int l = 0; l < tu_sim.plan.nloops; l++)
        if (tu_sim.plan.loops[l].actual)
            actual = l;
    TH_CHECK(actual >= 0);
    if (actual >= 0)
        TH_CHECK(tu_sim.plan.loops[actual].nblocks == 2);
    TH_CHECK(tu_sim.err[0] != 0);
}

/* a block whose output y0 depends on u0 but y1 on nothing: T.y1 -> G -> T.u0 closes a
   cycle of blocks but not of ports, so T is called twice: T (y1), G, T (y0) */
static const char *const two_names[] = {"a", "b"};
static const uint8_t split_feed[] = {1, 0, 0, 0}; /* y0 <- u0 only */
static void split_out(const rt_args *a, real_t *y)
{
    y[0] = 2 * a->u[0];
    y[1] = 3;
}
static const rt_kind split = {
    .name = "split", .type = RT_KIND_OUTPUT, .nu = 2, .ny = 2,
    .u_names = two_names, .y_names = two_names,
    .feed = RT_FEED_TABLE, .feed_table = split_feed, .output = split_out,
};

static void test_port_level(void)
{
    static const real_t g_p[] = {5};
    static const rt_block bl[] = {
        {.name = "T", .kind = &split},
        {.name = "G", .kind = &mdl_gain_kind, .p = g_p},
    };
    static const rt_conn cn[] = {{0, 1, 1, 0}, {1, 0, 0, 0}};
    static const rt_default df[] = {{0, 1, 0}};
    rt_scene sc = SCENE(bl, cn);
    sc.defaults = df, sc.ndefaults = 1;
    if (!tu_init(&sc))
        return;
    TH_CHECK(tu_sim.plan.nloops == 1 && tu_sim.plan.loops[0].actual == 0);
    TH_CHECK(tu_sim.plan.nseq == 3);
    TH_NEAR(tu_y(&sc, "G", 0), 15, 0);
    TH_NEAR(tu_y(&sc, "T", 0), 30, 0);
}

/* errors name what is wrong and where */
static void test_routing_errors(void)
{
    static const rt_block bl[] = {
        {.name = "Src", .kind = &mdl_step_kind},
        {.name = "Gain7", .kind = &mdl_gain_kind},
    };
    static const rt_conn none[] = {{0, 0, 0, 0}};
    rt_scene sc = SCENE(bl, none);
    sc.nconns = 0;
    TH_CHECK(rt_init(&sc, &tu_sim) == RT_E_UNCONNECTED);
    TH_CHECK(th_has(rt_error_text(&tu_sim), "Gain7.u"));

    static const rt_default df[] = {{1, 0, (real_t)4.5}};
    sc.defaults = df, sc.ndefaults = 1;
    TH_CHECK(rt_init(&sc, &tu_sim) == RT_OK);
    TH_NEAR(tu_y(&sc, "Gain7", 0), 4.5, 0);

    static const rt_conn twice[] = {{0, 0, 1, 0}, {0, 0, 1, 0}};
    rt_scene sc2 = SCENE(bl, twice);
    TH_CHECK(rt_init(&sc2, &tu_sim) == RT_E_SCENE);
    TH_CHECK(th_has(rt_error_text(&tu_sim), "driven twice"));

    static const rt_conn bad_port[] = {{0, 3, 1, 0}};
    rt_scene sc3 = SCENE(bl, bad_port);
    TH_CHECK(rt_init(&sc3, &tu_sim) == RT_E_SCENE);
}

/* a DSS period that is not a multiple of the base tick or of its set's step, a bad set
   index, a bad parameter */
static void test_scene_errors(void)
{
    static const rt_block bad_ts[] = {{.name = "C", .kind = &mdl_pi_kind, .ts = (real_t)0.015}};
    static const rt_default df[] = {{0, 0, 0}, {0, 1, 0}};
    static const rt_conn nc[] = {{0, 0, 0, 0}};
    rt_scene sc = SCENE(bad_ts, nc);
    sc.nconns = 0, sc.defaults = df, sc.ndefaults = 2;
    TH_CHECK(rt_init(&sc, &tu_sim) == RT_E_SCENE);
    TH_CHECK(th_has(rt_error_text(&tu_sim), "sample period"));

    /* 30 ms is 3 ticks, but its set steps every 2 ticks: a sample would fall between */
    static const rt_block odd_ts[] = {{.name = "C", .kind = &mdl_pi_kind, .ts = (real_t)0.03}};
    static const rt_set two_ticks[] = {{.name = "s", .method = &rt_rk4, .ratio = 2}};
    rt_scene sc4 = SCENE(odd_ts, nc);
    sc4.nconns = 0, sc4.defaults = df, sc4.ndefaults = 2, sc4.sets = two_ticks;
    TH_CHECK(rt_init(&sc4, &tu_sim) == RT_E_SCENE);
    TH_CHECK(th_has(rt_error_text(&tu_sim), "its set's step"));
    static const rt_block even_ts[] = {{.name = "C", .kind = &mdl_pi_kind, .ts = (real_t)0.04}};
    rt_scene sc5 = SCENE(even_ts, nc);
    sc5.nconns = 0, sc5.defaults = df, sc5.ndefaults = 2, sc5.sets = two_ticks;
    TH_CHECK(rt_init(&sc5, &tu_sim) == RT_OK);

    static const rt_block bad_set[] = {{.name = "O", .kind = &mdl_oscillator_kind, .set = 3}};
    rt_scene sc2 = SCENE(bad_set, nc);
    sc2.nconns = 0;
    TH_CHECK(rt_init(&sc2, &tu_sim) == RT_E_SCENE);

    static const real_t neg_T[] = {1, -1};
    static const rt_block bad_p[] = {{.name = "P", .kind = &mdl_pt1_kind, .p = neg_T}};
    static const rt_default d1[] = {{0, 0, 0}};
    rt_scene sc3 = SCENE(bad_p, nc);
    sc3.nconns = 0, sc3.defaults = d1, sc3.ndefaults = 1;
    TH_CHECK(rt_init(&sc3, &tu_sim) == RT_E_PARAM);
    TH_CHECK(th_has(rt_error_text(&tu_sim), "P"));
}

/* more blocks than RT_MAX_BLOCKS is refused before anything is written past a limit */
static void test_capacity(void)
{
    static rt_block many[RT_MAX_BLOCKS + 1];
    for (int i = 0; i <= RT_MAX_BLOCKS; i++)
        many[i] = (rt_block){.name = "S", .kind = &mdl_step_kind};
    rt_scene sc = {.name = "big", .dt = 1, .t_end = 1, .blocks = many,
                   .nblocks = RT_MAX_BLOCKS + 1, .sets = one_set, .nsets = 1};
    TH_CHECK(rt_init(&sc, &tu_sim) == RT_E_CAPACITY);
}

const th_test th_order_tests[] = {
    {"order_chain", test_chain_order},
    {"order_potential_loop", test_potential_loop},
    {"order_actual_loop", test_actual_loop},
    {"order_port_level", test_port_level},
    {"order_routing_errors", test_routing_errors},
    {"order_scene_errors", test_scene_errors},
    {"order_capacity", test_capacity},
    {0, 0},
};
