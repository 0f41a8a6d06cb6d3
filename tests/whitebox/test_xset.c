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
#include "rti.h"
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
        if (rt_ticks_done(&tu_sim) == from && from > 0)
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

/* a source y = amp sin(w t + ph) + off (ratio rs, 1 ms ticks) read by a rotor (ratio rr,
   linear extrapolation; in the tick, after the source in the scene's order unless
   first, or in the background, with a context attached if attach) */
typedef struct reader_case {
    real_t amp, w, ph, off;
    uint32_t rs, rr;
    int first, bg, attach;
    real_t t_end;
    real_t acc; /* the reader's accuracy (0: none, 1e30: only a lost coupling counts) */
    int loop; /* the source's set reads the reader back (a gain on its phi): a loop of
                 sets, which puts sets of one ratio in name order ("reader" first) */
} reader_case;

#define reader_ctx tu_spare /* the background context */

static int run_reader(const reader_case *c)
{
    static real_t p[4];
    static rt_conn cn[2];
    static rt_block bl[3];
    static rt_set sets[2];
    p[0] = c->amp, p[1] = c->w, p[2] = c->ph, p[3] = c->off;
    int src = c->first ? 1 : 0, rot = 1 - src;
    cn[0] = (rt_conn){(uint16_t)src, 0, (uint16_t)rot, 0};
    cn[1] = (rt_conn){(uint16_t)rot, 0, 2, 0};
    bl[src] = (rt_block){.name = "Src", .kind = &mdl_sine_kind, .p = p, .set = (uint8_t)src};
    bl[rot] = (rt_block){.name = "Rot", .kind = &mdl_rotor_kind, .set = (uint8_t)rot};
    bl[2] = (rt_block){.name = "Back", .kind = &mdl_gain_kind, .set = (uint8_t)src};
    sets[src] = (rt_set){.name = "source", .method = &rt_rk4, .ratio = c->rs};
    /* (its own estimates never counted: errest is the coupling's alone here) */
    sets[rot] = (rt_set){.name = "reader", .method = &rt_rk4, .ratio = c->rr,
                         .interp = RT_INTERP_EXTRAP, .background = (uint8_t)c->bg,
                         .cfg = {.accuracy = c->acc > 0 ? c->acc : (real_t)1e30}};
    static rt_scene sc;
    sc = (rt_scene){.name = "reader", .dt = (real_t)1e-3, .t_end = c->t_end, .blocks = bl,
                    .nblocks = c->loop ? 3 : 2, .conns = cn, .nconns = c->loop ? 2 : 1,
                    .sets = sets, .nsets = 2,
                    .bg = c->bg ? &rt_bg : 0};
    if (!tu_init(&sc))
        return -1;
    if (c->attach && rt_bg_attach(&sc, &tu_sim, &reader_ctx) != RT_OK)
        return -1;
    while (rt_tick(&sc, &tu_sim) == RT_OK)
        if (c->attach && rt_bg_pending(&tu_sim))
            rt_background(&sc, &tu_sim);
    return rot;
}

/* the source's value at tick k, as the runtime forms its time */
static double source_at(const reader_case *c, uint64_t k)
{
    double t = (double)((real_t)k * (real_t)1e-3);
    return (double)c->amp * (double)rt_sin((real_t)((double)c->w * t + (double)c->ph)) +
           (double)c->off;
}

/* the source at reader tick T between its points (T not a multiple of rs): the source has
   stepped past T to t0, and the monitor reads its three newest points' parabola there
   (a line through the two where there are only two) */
static double around(const reader_case *c, uint64_t T)
{
    uint64_t t0 = (T + c->rs - 1) / c->rs * c->rs, t1 = t0 - c->rs;
    double x = (double)((real_t)T * (real_t)1e-3), x0 = (double)((real_t)t0 * (real_t)1e-3);
    double x1 = (double)((real_t)t1 * (real_t)1e-3), y0 = source_at(c, t0), y1 = source_at(c, t1);
    if (t1 < c->rs)
        return y1 + (y0 - y1) * (x - x1) / (x0 - x1);
    double x2 = (double)((real_t)(t1 - c->rs) * (real_t)1e-3), y2 = source_at(c, t1 - c->rs);
    return (x - x1) * (x - x2) / ((x0 - x1) * (x0 - x2)) * y0 +
           (x - x0) * (x - x2) / ((x1 - x0) * (x1 - x2)) * y1 +
           (x - x0) * (x - x1) / ((x2 - x0) * (x2 - x1)) * y2;
}

/* formed from the sine alone: at each reader step start T (a multiple of rr), the miss of
   the line the reader drew at its last start through the source's two newest points then
   (the one point at t = 0: held), against the source's point at T where it has one (a
   multiple of rs), else against its points around T (around); the worst miss (with the
   source's own, below), and the misses above RT_XSET_LOST (1 + the largest |y| at such
   places) */
static double predicted_miss(const reader_case *c, uint32_t *lost, uint32_t *checks)
{
    uint64_t n = (uint64_t)((double)c->t_end / 1e-3 + 0.5);
    double worst = 0, scale = 0, pred = 0;
    *lost = *checks = 0;
    for (uint64_t T = 0; T < n; T += c->rr) {
        double y = T % c->rs == 0 ? source_at(c, T) : around(c, T), e = y - pred;
        scale = (y < 0 ? -y : y) > scale ? (y < 0 ? -y : y) : scale;
        e = e < 0 ? -e : e;
        if (T > 0) {
            worst = e > worst ? e : worst;
            *lost += e > (double)RT_XSET_LOST * (1 + scale);
            ++*checks;
        }
        /* the source's newest point: it steps at the start of its own step, so it is
           ahead of T unless both step at T, where the reader steps first */
        uint64_t t0 = (T + c->rs - 1) / c->rs * c->rs;
        double y0 = source_at(c, t0), tn = (double)((real_t)(T + c->rr) * (real_t)1e-3);
        double ta = (double)((real_t)t0 * (real_t)1e-3);
        double slope = t0 == 0 ? 0 : (y0 - source_at(c, t0 - c->rs)) /
                                         (ta - (double)((real_t)(t0 - c->rs) * (real_t)1e-3));
        pred = y0 + (tn - ta) * slope;
    }
    /* the monitor also holds the source's own extrapolation over its step: each new point
       against the line through the two before it (rti_xset_push), up to the last point */
    for (uint64_t t = 2 * c->rs; t < n + c->rs; t += c->rs) {
        double line = 2 * source_at(c, t - c->rs) - source_at(c, t - 2 * c->rs);
        double e = source_at(c, t) - line;
        e = e < 0 ? -e : e;
        worst = e > worst ? e : worst;
    }
    return worst;
}

/* the inputs the monitor checks by prediction (those read ahead of their source) */
static int n_ahead(const rt_sim *sim)
{
    int n = 0;
    for (uint16_t k = 0; k < sim->plan.nxpred; k++)
        n += sim->plan.xpred_how[k] == RTI_XP_AHEAD;
    return n;
}

/* the run's monitor and counts against predicted_miss */
static void check_reader(const char *what, const reader_case *c, int want_lost)
{
    uint32_t lost, checks;
    double want = predicted_miss(c, &lost, &checks);
    int rot = run_reader(c);
    if (rot < 0)
        return;
    int src = 1 - rot;
    th_note(what, (double)rt_stats_of(&tu_sim)->xset_err[src]);
    TH_CHECK(checks > 0 && (want_lost ? lost >= 3 : lost == 0));
    TH_NEAR((double)rt_stats_of(&tu_sim)->xset_err[src], want, want * (RT_REAL_IS_FLOAT ? 1e-3 : 1e-9));
    TH_CHECK(rt_stats_of(&tu_sim)->count[RT_CNT_ERREST] == lost);
    TH_CHECK(rt_stats_of(&tu_sim)->errest[rot] == lost && rt_stats_of(&tu_sim)->errest[src] == 0);
    TH_CHECK(lost ? rt_stats_of(&tu_sim)->status == RT_E_COUPLING &&
                        rt_stats_of(&tu_sim)->last_block[RT_CNT_ERREST] == rot
                  : rt_stats_of(&tu_sim)->status == RT_OK);
    TH_CHECK(n_ahead(&tu_sim) == 1);
}

/* the monitor keeps the worst miss of the slower reader's prediction as the source set's
   xset_err (its own 1 ms extrapolation misses far less), and a sound coupling stays ok
   (at the phase pi/2 the start's hold misses amp (1 - cos w H), no more than the lines);
   in the tick, in the background inline and with a context; with steps that do not
   divide each other (30 and 40 ms: checked at every step of the reader, against the
   source's point where both meet, every 120 ms, else its points around); and with an
   amplitude of 1000 around an offset, whose misses near its zero crossings are large
   against the value there but not against its range */
/* the case in the tick, in the background inline, and with a context attached */
static void check_modes(reader_case c, int want_lost)
{
    check_reader("in the tick", &c, want_lost);
    c.bg = 1;
    check_reader("background", &c, want_lost);
    c.attach = 1;
    check_reader("background, context", &c, want_lost);
}

static void test_prediction_monitor(void)
{
    reader_case c = {1, 1, (real_t)1.5707963, 0, 1, 40, 0, 0, 0, (real_t)2.4, 0, 0};
    check_modes(c, 0);
    reader_case d = {10, 3, 0, 0, 30, 40, 0, 0, 0, (real_t)2.4, 0, 0};
    check_reader("30 ms read every 40 ms", &d, 0);
    reader_case e = {1000, 2, (real_t)0.3, 500, 1, 50, 0, 0, 0, (real_t)4.0, 0, 0};
    check_reader("amplitude 1000", &e, 0);
}

/* an input extrapolated over 50 ms at 60 rad/s misses by more than its range: every such
   step is counted (errest, the reader's block and set) and the status is failed; in the
   tick, in the background (inline and with a context: the tick checks the prediction and
   keeps the set's count), and from a source of the reader's own rate that steps after it
   (in a loop of sets: else the source steps first) */
static void test_coupling_lost(void)
{
    reader_case c = {10, 60, 0, 0, 1, 50, 0, 0, 0, (real_t)2.0, 0, 0};
    check_modes(c, 1);
    /* sets of one ratio in a loop step in name order: the reader first, extrapolating */
    reader_case d = {10, 60, 0, 0, 50, 50, 1, 0, 0, (real_t)2.0, 0, 1};
    check_reader("same rate, reader first", &d, 1);
    TH_CHECK(rt_status_severity(RT_E_COUPLING) == 2);
    /* without the loop the source steps first whichever set the scene lists first
       (rt/xset.c, by dependency): the reader interpolates its fresh point, nothing to
       check, and the rotor ends in the same state either way */
    real_t end[2] = {0, 0};
    d.loop = 0;
    for (d.first = 0; d.first < 2; d.first++) {
        int rot = run_reader(&d);
        if (rot < 0)
            return;
        TH_CHECK(n_ahead(&tu_sim) == 0 && rt_stats_of(&tu_sim)->count[RT_CNT_ERREST] == 0);
        end[d.first] = tu_sim.state.x[tu_sim.plan.x_off[rot]];
    }
    TH_CHECK(end[0] == end[1] && end[0] != 0);
}

/* below the lost threshold the miss is held to the reader's accuracy: the rotor's
   omega' = u has sensitivity 1 / (1 + |omega|) in the scaled norm, so the coupling's
   estimate of a step with miss e is e H / 2 / (1 + |omega|), |omega| <= 2 amp / w here;
   at 20 rad/s over 40 ms the worst miss (0.72, a third of the range) puts 1.4e-2 into
   the state: doubtful against 1e-3 (the reader's block, errest), ok against 5e-2. In the
   tick, in the background inline and with a context (its step measures the sensitivity,
   the tick's release judges) */
static void check_accuracy(reader_case c, int want_doubtful)
{
    for (int mode = 0; mode < 3; mode++) {
        c.bg = mode > 0, c.attach = mode > 1;
        uint32_t lost, checks;
        double worst = predicted_miss(&c, &lost, &checks), h = (double)c.rr * 1e-3;
        int rot = run_reader(&c);
        if (rot < 0)
            return;
        double est = (double)rt_stats_of(&tu_sim)->xset_est[rot];
        th_note(mode == 0 ? "in the tick: xset_est" : mode == 1 ? "background: xset_est"
                                                            : "context: xset_est", est);
        TH_CHECK(lost == 0 && checks > 0);
        TH_CHECK(est <= 0.5 * h * worst * (1 + 1e-6) &&
                 est >= 0.5 * h * worst / (1 + 2 * (double)c.amp / (double)c.w));
        TH_CHECK(want_doubtful ? rt_stats_of(&tu_sim)->status == RT_E_ACCURACY &&
                                     rt_stats_of(&tu_sim)->errest[rot] > 0 &&
                                     rt_stats_of(&tu_sim)->last_block[RT_CNT_ERREST] == rot
                               : rt_stats_of(&tu_sim)->status == RT_OK);
    }
}

static void test_coupling_accuracy(void)
{
    reader_case c = {1, 20, 0, 0, 1, 40, 0, 0, 0, (real_t)2.4, (real_t)1e-3, 0};
    check_accuracy(c, 1);
    c.acc = (real_t)5e-2;
    check_accuracy(c, 0);
}

/* rti_xset_value on a history filled by hand (points at 0.3, 0.2, 0.1 s of a source
   that has stepped past t): the line through the two points around t (linear) and the
   parabola through the three (hermite, quadratic), formed here in Lagrange's form, from
   the oldest point to the newest (between the two newest the tick's shortcut answers,
   elsewhere the general path); with two points, the line */
static void test_value_between_points(void)
{
    reader_case c = {1, 1, 0, 0, 1, 40, 0, 0, 0, (real_t)0.1, 0, 0};
    if (run_reader(&c) < 0)
        return;
    rt_sim *sim = &tu_sim;
    uint8_t q = 0; /* the source (set 0 when not first) */
    double T[3] = {0.3, 0.2, 0.1}, Y[3] = {2.0, -1.0, 0.5};
    for (int k = 0; k < 3; k++)
        sim->state.hist_t[q][k] = (real_t)T[k], sim->state.hist_y[k][0] = (real_t)Y[k];
    sim->state.hist_n[q] = 3;
    int ok = 1;
    for (int i = 0; i <= 20; i++) {
        double t = 0.1 + 0.01 * i; /* 0.1 .. 0.3 */
        double t_r = (double)(real_t)t;
        double line01 = Y[1] + (Y[0] - Y[1]) * (t_r - T[1]) / (T[0] - T[1]);
        double line12 = Y[2] + (Y[1] - Y[2]) * (t_r - T[2]) / (T[1] - T[2]);
        double par = 0;
        for (int a = 0; a < 3; a++) {
            double l = Y[a];
            for (int b = 0; b < 3; b++)
                if (b != a)
                    l *= (t_r - T[b]) / (T[a] - T[b]);
            par += l;
        }
        double lin = t_r >= T[1] ? line01 : line12;
        double tol = RT_REAL_IS_FLOAT ? 1e-5 : 1e-13;
        double got_l = (double)rti_xset_value(sim, 0, q, RT_INTERP_LINEAR, (real_t)t, RT_MAX_BLOCKS);
        double got_h = (double)rti_xset_value(sim, 0, q, RT_INTERP_HERMITE, (real_t)t, RT_MAX_BLOCKS);
        double got_q = (double)rti_xset_value(sim, 0, q, RT_INTERP_QUAD, (real_t)t, RT_MAX_BLOCKS);
        ok &= rt_fabs((real_t)(got_l - lin)) <= tol && rt_fabs((real_t)(got_q - par)) <= tol &&
              rt_fabs((real_t)(got_h - par)) <= tol;
    }
    TH_CHECK(ok);
    sim->state.hist_n[q] = 2; /* two points: the line for every interpolating scheme */
    double t = 0.25, line01 = Y[1] + (Y[0] - Y[1]) * ((double)(real_t)t - T[1]) / (T[0] - T[1]);
    TH_NEAR((double)rti_xset_value(sim, 0, q, RT_INTERP_HERMITE, (real_t)t, RT_MAX_BLOCKS), line01, 1e-5);
    TH_NEAR((double)rti_xset_value(sim, 0, q, RT_INTERP_QUAD, (real_t)t, RT_MAX_BLOCKS), line01, 1e-5);
}

const th_test th_xset_tests[] = {
    {"xset_value_between_points", test_value_between_points},
    {"xset_prediction_monitor", test_prediction_monitor},
    {"xset_coupling_lost", test_coupling_lost},
    {"xset_coupling_accuracy", test_coupling_accuracy},
    {"xset_orders", test_orders},
    {"xset_background_orders", test_background_orders},
    {"xset_schedule", test_schedule},
    {"xset_no_loop_across_sets", test_no_loop_across_sets},
    {0, 0},
};
