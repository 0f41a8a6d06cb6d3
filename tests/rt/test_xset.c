/* test_xset.c - tests of rt/xset.c: each interpolation scheme's order of the
 * communication error on a two-set system with a known solution, the fixed schedule,
 * and that a feedback between sets is no algebraic loop.
 *
 * Slow set (step H): a source y = sin t. Fast set (step 1 ms): omega' = y, omega(0) = 0,
 * so omega = 1 - cos t exactly. Within one fast step the reconstructed input is a
 * polynomial of degree <= 2, which RK4 integrates exactly, so the error in omega is the
 * integral of the reconstruction error: order 1 for hold, 2 for linear extrapolation and
 * interpolation, 3 for Hermite.
 *
 * The other way round (a slow set reading a fast source, which it extrapolates over its
 * whole step): the prediction check of rti_xset_predict against the same extrapolation
 * formed here from sin t alone. */
#include "models.h"
#include "testutil.h"

enum { SRC, ROT };
static const real_t sine_p[] = {1, 1, 0, 0};

/* the error in omega = 1 - cos t that the transfer from the source adds between t_from
   and t_end, with the slow step ratio m and scheme (t_from = 0: |omega(T) - (1 - cos T)|);
   bg: the source set steps in the background (rt/bg.c), so the fast set always
   extrapolates it and starts with the one point at t = 0 (a hold over the first macro
   step, an O(H^2) error of its own that t_from > 0 leaves out) */
static double comm_error_bg(uint32_t m, uint8_t scheme, real_t t_from, real_t t_end, int bg)
{
    static const rt_conn cn[] = {{SRC, 0, ROT, 0}};
    const rt_block bl[] = {
        [SRC] = {.name = "Src", .kind = &mdl_sine_kind, .p = sine_p, .set = 0},
        [ROT] = {.name = "Rot", .kind = &mdl_rotor_kind, .set = 1},
    };
    const rt_set sets[] = {
        {.name = "slow", .method = &rt_rk4, .ratio = m, .background = (uint8_t)bg},
        {.name = "fast", .method = &rt_rk4, .ratio = 1, .interp = scheme},
    };
    rt_scene sc = {.name = "xset", .dt = (real_t)1e-3, .t_end = t_end, .blocks = bl,
                   .nblocks = 2, .conns = cn, .nconns = 1, .sets = sets, .nsets = 2,
                   .bg = bg ? &rt_bg : 0};
    if (!tu_init(&sc))
        return 1e30;
    double e0 = 0, e = 0;
    uint64_t from = (uint64_t)(t_from / sc.dt + (real_t)0.5);
    for (rt_status st = RT_OK; st == RT_OK;) {
        if (tu_sim.state.tick == from && from > 0)
            e0 = e;
        st = rt_tick(&sc, &tu_sim);
        real_t t = rt_time(&sc, &tu_sim);
        e = (double)tu_sim.state.x[tu_sim.plan.x_off[ROT] + 1] - (1 - (double)rt_cos(t));
    }
    e -= e0;
    return e < 0 ? -e : e;
}

static double comm_error(uint32_t m, uint8_t scheme, real_t t_end)
{
    return comm_error_bg(m, scheme, 0, t_end, 0);
}

static void test_orders(void)
{
    static const struct { uint8_t scheme; const char *name; double p; } cases[] = {
        {RT_INTERP_HOLD, "hold", 1}, {RT_INTERP_EXTRAP, "extrap", 2},
        {RT_INTERP_LINEAR, "linear", 2}, {RT_INTERP_HERMITE, "hermite", 3},
    };
    for (unsigned i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        if (RT_REAL_IS_FLOAT && cases[i].p > 2)
            continue; /* single precision roundoff hides the third order */
        double e1 = comm_error(80, cases[i].scheme, (real_t)2.4);
        double e2 = comm_error(40, cases[i].scheme, (real_t)2.4);
        double p = (double)rt_log((real_t)(e1 / e2)) / (double)rt_log(2);
        th_note(cases[i].name, p);
        TH_NEAR(p, cases[i].p, 0.25);
    }
    /* and the schemes rank as their orders say */
    TH_CHECK(comm_error(40, RT_INTERP_HERMITE, (real_t)2.4) <
             comm_error(40, RT_INTERP_LINEAR, (real_t)2.4));
    TH_CHECK(comm_error(40, RT_INTERP_LINEAR, (real_t)2.4) <
             comm_error(40, RT_INTERP_HOLD, (real_t)2.4));
}

/* a background source is read ahead of its history: linear extrapolation (with the fade
   of its jumps) is second order, the parabola (quadratic) third, against 1 - cos t over
   [0.48 s, 2.4 s] (after the start's hold) */
static void test_background_orders(void)
{
    static const struct { uint8_t scheme; const char *name; double p; } cases[] = {
        {RT_INTERP_EXTRAP, "bg extrap", 2}, {RT_INTERP_HERMITE, "bg hermite", 2},
        {RT_INTERP_QUAD, "bg quadratic", 3},
    };
    for (unsigned i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        if (RT_REAL_IS_FLOAT && cases[i].p > 2)
            continue; /* single precision roundoff hides the third order */
        double e1 = comm_error_bg(80, cases[i].scheme, (real_t)0.48, (real_t)2.4, 1);
        double e2 = comm_error_bg(40, cases[i].scheme, (real_t)0.48, (real_t)2.4, 1);
        double p = (double)rt_log((real_t)(e1 / e2)) / (double)rt_log(2);
        th_note(cases[i].name, p);
        TH_CHECK(p > cases[i].p - 0.25); /* at least its order (the parabola: 3.4 here) */
    }
    TH_CHECK(comm_error_bg(40, RT_INTERP_QUAD, (real_t)0.48, (real_t)2.4, 1) <
             comm_error_bg(40, RT_INTERP_EXTRAP, (real_t)0.48, (real_t)2.4, 1));
}

/* slowest first; each set's clock advances by its ratio exactly when it steps */
static void test_schedule(void)
{
    static const rt_conn cn[] = {{SRC, 0, ROT, 0}};
    const rt_block bl[] = {
        [SRC] = {.name = "Src", .kind = &mdl_sine_kind, .p = sine_p, .set = 1},
        [ROT] = {.name = "Rot", .kind = &mdl_rotor_kind, .set = 0},
    };
    const rt_set sets[] = {
        {.name = "fast", .method = &rt_heun, .ratio = 2},
        {.name = "slow", .method = &rt_rk4, .ratio = 6, .interp = RT_INTERP_LINEAR},
    };
    rt_scene sc = {.name = "sched", .dt = (real_t)1e-3, .t_end = (real_t)0.05, .blocks = bl,
                   .nblocks = 2, .conns = cn, .nconns = 1, .sets = sets, .nsets = 2};
    if (!tu_init(&sc))
        return;
    TH_CHECK(tu_sim.plan.sched[0] == 1 && tu_sim.plan.sched[1] == 0);
    TH_CHECK(tu_sim.plan.src_kind[tu_sim.plan.u_off[ROT]] == RT_SRC_XSET);
    int ok = 1;
    for (uint64_t k = 0; k < 30; k++) {
        rt_tick(&sc, &tu_sim);
        /* after tick k each set is at the first multiple of its ratio above k */
        ok &= tu_sim.state.set_tick[0] == (k / 2 + 1) * 2;
        ok &= tu_sim.state.set_tick[1] == (k / 6 + 1) * 6;
    }
    TH_CHECK(ok);
}

/* a feedback that crosses sets is sampled, so it is no algebraic loop even when every
   block on it has throughput */
static void test_no_loop_across_sets(void)
{
    static const real_t g_p[] = {(real_t)0.5};
    static const rt_conn cn[] = {{0, 0, 1, 0}, {1, 0, 0, 0}};
    const rt_block bl[] = {
        {.name = "G1", .kind = &mdl_gain_kind, .p = g_p, .set = 0},
        {.name = "G2", .kind = &mdl_gain_kind, .p = g_p, .set = 1},
    };
    const rt_set sets[] = {
        {.name = "a", .method = &rt_euler, .ratio = 1},
        {.name = "b", .method = &rt_euler, .ratio = 3},
    };
    rt_scene sc = {.name = "noloop", .dt = (real_t)1e-2, .t_end = (real_t)0.1, .blocks = bl,
                   .nblocks = 2, .conns = cn, .nconns = 2, .sets = sets, .nsets = 2};
    TH_CHECK(rt_init(&sc, &tu_sim) == RT_OK);
    TH_CHECK(tu_sim.plan.nloops == 0 && tu_sim.plan.ntorn == 0);
}

/* the fast source y = amp sin(w t + ph) (ratio 1, 1 ms) read by a slow rotor (ratio m, linear
   extrapolation, in the tick or in the background) */
static int run_slow_reader(real_t amp, real_t w, real_t ph, uint32_t m, int bg, real_t t_end)
{
    static real_t p[4];
    static const rt_conn cn[] = {{SRC, 0, ROT, 0}};
    static rt_block bl[2];
    static rt_set sets[2];
    p[0] = amp, p[1] = w, p[2] = ph, p[3] = 0;
    bl[SRC] = (rt_block){.name = "Src", .kind = &mdl_sine_kind, .p = p, .set = 0};
    bl[ROT] = (rt_block){.name = "Rot", .kind = &mdl_rotor_kind, .set = 1};
    sets[0] = (rt_set){.name = "fast", .method = &rt_rk4, .ratio = 1};
    sets[1] = (rt_set){.name = "slow", .method = &rt_rk4, .ratio = m,
                       .interp = RT_INTERP_EXTRAP, .background = (uint8_t)bg};
    static rt_scene sc;
    sc = (rt_scene){.name = "reader", .dt = (real_t)1e-3, .t_end = t_end, .blocks = bl,
                    .nblocks = 2, .conns = cn, .nconns = 1, .sets = sets, .nsets = 2,
                    .bg = bg ? &rt_bg : 0};
    if (!tu_init(&sc))
        return 0;
    while (rt_tick(&sc, &tu_sim) == RT_OK)
        ;
    return 1;
}

/* what the slow set's extrapolation misses at each of its step starts kH after the
   first, formed from sin t alone: from (k-1)H, the line through the source's points there
   and 1 ms before (at t = 0 the one point, held); worst absolute miss, and the steps
   where the miss exceeds RT_XSET_LOST (1 + |y|) */
static double predicted_miss(double amp, double w, double ph, uint32_t m, double t_end,
                             uint32_t *lost)
{
    double worst = 0;
    *lost = 0;
    for (uint32_t k = 1; (double)(k * m) * 1e-3 < t_end - 0.5e-3; k++) {
        /* the times as the runtime forms them (tick count times the base tick) */
        double t0 = (double)((real_t)((k - 1) * m) * (real_t)1e-3);
        double tp = (double)((real_t)((k - 1) * m - 1) * (real_t)1e-3);
        double t1 = (double)((real_t)(k * m) * (real_t)1e-3);
        double y0 = amp * (double)rt_sin((real_t)(w * t0 + ph));
        double slope = k == 1 ? 0 : (y0 - amp * (double)rt_sin((real_t)(w * tp + ph))) / (t0 - tp);
        double y = amp * (double)rt_sin((real_t)(w * t1 + ph)), e = y - (y0 + (t1 - t0) * slope);
        e = e < 0 ? -e : e;
        worst = e > worst ? e : worst;
        *lost += e > (double)RT_XSET_LOST * (1 + (y < 0 ? -y : y));
    }
    return worst;
}

/* the monitor keeps the worst miss of the slow reader's prediction as the source set's
   xset_err (its own 1 ms extrapolation misses far less), and a sound coupling stays ok
   (at the phase pi/2 the start's hold misses amp (1 - cos w H), no more than the lines) */
static void test_prediction_monitor(void)
{
    uint32_t lost;
    double want = predicted_miss(1, 1, 1.5707963, 40, 2.4, &lost);
    TH_CHECK(lost == 0);
    for (int bg = 0; bg <= 1; bg++) {
        if (!run_slow_reader(1, 1, (real_t)1.5707963, 40, bg, (real_t)2.4))
            return;
        th_note(bg ? "bg monitor" : "monitor", (double)tu_sim.stats.xset_err[0]);
        TH_NEAR((double)tu_sim.stats.xset_err[0], want, want * (RT_REAL_IS_FLOAT ? 1e-3 : 1e-9));
        TH_CHECK(tu_sim.stats.status == RT_OK && tu_sim.stats.count[RT_CNT_ERREST] == 0);
        TH_CHECK(tu_sim.plan.nxpred == 1);
    }
}

/* an input extrapolated over 50 ms at 20 rad/s misses by more than its own size: every such
   step is counted (errest, the reader's block and set) and the status is failed; the same
   in the background, whose prediction the tick checks from the same history */
static void test_coupling_lost(void)
{
    uint32_t lost;
    predicted_miss(10, 20, 0, 50, 2.0, &lost);
    th_note("steps lost", lost);
    TH_CHECK(lost >= 3);
    for (int bg = 0; bg <= 1; bg++) {
        if (!run_slow_reader(10, 20, 0, 50, bg, (real_t)2.0))
            return;
        TH_CHECK(tu_sim.stats.count[RT_CNT_ERREST] == lost);
        TH_CHECK(tu_sim.stats.errest[1] == lost && tu_sim.stats.errest[0] == 0);
        TH_CHECK(tu_sim.stats.status == RT_E_COUPLING && rt_status_severity(RT_E_COUPLING) == 2);
        TH_CHECK(tu_sim.stats.last_block[RT_CNT_ERREST] == ROT);
    }
    /* a source no faster than its reader is not extrapolated over the reader's step by
       this rule: nothing to check */
    static const rt_conn cn[] = {{SRC, 0, ROT, 0}};
    static const real_t p[] = {10, 20, 0, 0};
    const rt_block bl[] = {
        [SRC] = {.name = "Src", .kind = &mdl_sine_kind, .p = p, .set = 0},
        [ROT] = {.name = "Rot", .kind = &mdl_rotor_kind, .set = 1},
    };
    const rt_set sets[] = {
        {.name = "a", .method = &rt_rk4, .ratio = 50},
        {.name = "b", .method = &rt_rk4, .ratio = 50, .interp = RT_INTERP_EXTRAP},
    };
    rt_scene sc = {.name = "same", .dt = (real_t)1e-3, .t_end = (real_t)0.5, .blocks = bl,
                   .nblocks = 2, .conns = cn, .nconns = 1, .sets = sets, .nsets = 2};
    if (tu_init(&sc))
        TH_CHECK(tu_sim.plan.nxpred == 0);
}

const th_test th_xset_tests[] = {
    {"xset_prediction_monitor", test_prediction_monitor},
    {"xset_coupling_lost", test_coupling_lost},
    {"xset_orders", test_orders},
    {"xset_background_orders", test_background_orders},
    {"xset_schedule", test_schedule},
    {"xset_no_loop_across_sets", test_no_loop_across_sets},
    {0, 0},
};
