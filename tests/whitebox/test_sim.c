/* test_sim.c - tests of rt/sim.c, rt/lss.c and rt/util.c: integer time, deterministic
 * hashes, parameter setting, LSS against its closed form, NaN containment, and the
 * X-macro lists. */

#include "models.h"
#include "scenes/scenes.h"
#include "testutil.h"
#include "rti.h" /* white box: reads rt_sim's parts (plan, state, work), the tick helpers */

/* a and b have the same bits (NaN included; the freestanding targets have no memcmp) */
static int same_bits(real_t a, real_t b)
{
    const unsigned char *p = (const unsigned char *)&a, *q = (const unsigned char *)&b;
    for (size_t i = 0; i < sizeof a; i++)
        if (p[i] != q[i])
            return 0;
    return 1;
}

/* hash of a whole oscillator run, after optionally nudging omega by one bit */
static uint64_t run_hash(int nudge)
{
    const rt_scene *sc = &mdl_scene_oscillator;
    rt_scene short_sc = *sc;
    short_sc.t_end = 1;
    if (!tu_init(&short_sc))
        return 0;
    if (nudge) {
        union { real_t r; uint64_t u; } w;
        w.u = 0;
        w.r = tu_sim.state.p[0];
        w.u ^= 1; /* the least significant mantissa bit */
        TH_CHECK(rt_set_param(&short_sc, &tu_sim, "Osc", "omega", w.r) == RT_OK);
        rt_refresh(&short_sc, &tu_sim);
    }
    rt_record(&short_sc, &tu_sim, 0);
    while (rt_tick(&short_sc, &tu_sim) == RT_OK)
        rt_record(&short_sc, &tu_sim, 0);
    rt_record(&short_sc, &tu_sim, 0);
    return rt_trace_hash(&tu_sim);
}

static void test_hash_determinism(void)
{
    uint64_t a = run_hash(0), b = run_hash(0), c = run_hash(1);
    TH_EQ_U64(a, b);
    TH_CHECK(a != c);
    /* the hash of one value, folded here by hand: 1.0 is 0x3ff0000000000000 in double,
       0x3f800000 in float; the product by hand in 32-bit halves, so not by the same
       expression as rt/util.c */
    uint64_t bits = sizeof(real_t) == 8 ? 0x3ff0000000000000ull : 0x3f800000ull;
    uint64_t x = 0xcbf29ce484222325ull ^ bits;
    uint64_t m = 0x9e3779b97f4a7c15ull;
    uint64_t xl = x & 0xffffffffu, xh = x >> 32, ml = m & 0xffffffffu, mh = m >> 32;
    uint64_t h = xl * ml + (((xl * mh + xh * ml) & 0xffffffffu) << 32);
    h ^= h >> 32;
    TH_EQ_U64(rt_hash_real(RT_HASH_INIT, 1), h);
    TH_CHECK(rt_hash_real(RT_HASH_INIT, 1) != rt_hash_real(RT_HASH_INIT, -1)); /* sign bit */
}

/* t is tick * dt: after 10^6 ticks of 1 ms it is exactly the product, not a sum */
static void test_integer_time(void)
{
    static const rt_block bl[] = {{.name = "S", .kind = &mdl_step_kind}};
    static const rt_set set[] = {{.name = "s", .method = &rt_euler, .ratio = 1}};
    rt_scene sc = {.name = "clock", .dt = (real_t)1e-3, .t_end = 1000, .blocks = bl,
                   .nblocks = 1, .sets = set, .nsets = 1};
    if (!tu_init(&sc))
        return;
    TH_CHECK(rt_tick_count(&tu_sim) == 1000000);
    tu_sim.state.tick = 999999;
    TH_CHECK(rt_tick(&sc, &tu_sim) == RT_E_DONE);
    TH_CHECK(rt_time(&sc, &tu_sim) == (real_t)1000000 * (real_t)1e-3);
    TH_CHECK(rt_tick(&sc, &tu_sim) == RT_E_DONE && rt_ticks_done(&tu_sim) == 1000000);
}

/* the tick arithmetic taken through 32 bits while the count fits (rti_tick_mod,
   rti_tick_real, rti_real_tick) equals the 64-bit one on both sides of 2^32 */
static void test_tick_width(void)
{
    static const uint64_t ticks[] = {0, 1, 999, 4294967295u, 4294967296u, 4294967297u,
                                     ((uint64_t)1 << 40) | 12345u, ~(uint64_t)0 >> 11};
    static const uint32_t r[] = {1, 3, 4, 7, 1000, 4294967295u};
    for (unsigned i = 0; i < sizeof ticks / sizeof ticks[0]; i++) {
        uint64_t t = ticks[i];
        for (unsigned k = 0; k < sizeof r / sizeof r[0]; k++)
            TH_CHECK(rti_tick_mod(t, r[k]) == t % r[k]);
        TH_CHECK(same_bits(rti_tick_real(t), (real_t)t));
        TH_CHECK(same_bits(rti_tick_time(t, (real_t)1e-3), (real_t)t * (real_t)1e-3));
        real_t q = (real_t)t + (real_t)0.25;
        TH_CHECK(rti_real_tick(q) == (uint64_t)q);
    }
    TH_CHECK(rti_real_tick((real_t)4294967296.0) == 4294967296u);
}

static void test_set_param(void)
{
    const rt_scene *sc = &mdl_scene_pi_loop;
    if (!tu_init(sc))
        return;
    TH_CHECK(rt_set_param(sc, &tu_sim, "Plant", "T", (real_t)0.25) == RT_OK);
    TH_CHECK(rt_set_param(sc, &tu_sim, "Plant", "T", -1) == RT_E_PARAM);
    TH_NEAR(tu_sim.state.p[tu_sim.plan.p_off[2] + 1], 0.25, 0); /* the bad value was not kept */
    TH_CHECK(rt_set_param(sc, &tu_sim, "Plant", "nope", 1) == RT_E_ARG);
    TH_CHECK(rt_set_param(sc, &tu_sim, "Nobody", "T", 1) == RT_E_ARG);
    TH_CHECK(rt_set_param(sc, &tu_sim, "Plant", "y", 2) == RT_OK); /* initial state */
    TH_NEAR(tu_sim.state.x[0], 2, 0);
}

/* an LSS oscillator x' = v, v' = -w^2 x gives cos(w t) like the NSS one */
static const real_t lss_A[] = {0, 1, -(real_t)(4 * RT_PI * RT_PI), 0};
static const real_t lss_C[] = {1, 0};
static const rt_lss_spec lss_spec = {.nx = 2, .nu = 0, .ny = 1, .A = lss_A, .C = lss_C};
static const char *const lss_x[] = {"x", "v"};
static const real_t lss_x0[] = {1, 0};
static const rt_kind lss_osc = {
    .name = "lss_osc", .type = RT_KIND_LSS, .ny = 1, .nx = 2,
    .y_names = lss_x, .x_names = lss_x, .x_default = lss_x0, .feed = RT_FEED_NONE,
    .output = rt_lss_output, .deriv = rt_lss_deriv, .spec = &lss_spec,
};

static void test_lss(void)
{
    static const rt_block bl[] = {{.name = "L", .kind = &lss_osc}};
    static const rt_set set[] = {{.name = "s", .method = &rt_rk4, .ratio = 1}};
    rt_scene sc = {.name = "lss", .dt = (real_t)1e-3, .t_end = (real_t)2.25, .blocks = bl,
                   .nblocks = 1, .sets = set, .nsets = 1};
    if (!tu_init(&sc))
        return;
    while (rt_tick(&sc, &tu_sim) == RT_OK)
        ;
    /* x(2.25) = cos(4.5 pi) = 0, v(2.25) = -2 pi sin(4.5 pi) = -2 pi */
    double tol = RT_REAL_IS_FLOAT ? 2e-3 : 1e-9;
    TH_NEAR(tu_y(&sc, "L", 0), 0, tol);
    TH_NEAR(tu_sim.state.x[1], -2 * RT_PI, tol * 10);
}

/* a derivative that turns NaN at t > 0.5: the tick completes, the state is held, the
   fault is counted with its block */
static const char *const nan_names[] = {"x"};
static void nan_deriv(const rt_args *a, real_t *xdot)
{
    real_t zero = 0;
    xdot[0] = a->t > (real_t)0.5 ? zero / zero : 1;
}
static void nan_out(const rt_args *a, real_t *y) { y[0] = a->x[0]; }
static const rt_kind nan_kind = {
    .name = "nan", .type = RT_KIND_NSS, .ny = 1, .nx = 1, .y_names = nan_names,
    .x_names = nan_names, .feed = RT_FEED_NONE, .output = nan_out, .deriv = nan_deriv,
};

static void test_nan_contained(void)
{
    static const rt_block bl[] = {{.name = "Ok", .kind = &mdl_oscillator_kind},
                                  {.name = "Bad", .kind = &nan_kind}};
    static const rt_set set[] = {{.name = "s", .method = &rt_rk4, .ratio = 1}};
    rt_scene sc = {.name = "nan", .dt = (real_t)0.01, .t_end = 1, .blocks = bl,
                   .nblocks = 2, .sets = set, .nsets = 1};
    if (!tu_init(&sc))
        return;
    while (rt_tick(&sc, &tu_sim) == RT_OK)
        ;
    TH_CHECK(rt_ticks_done(&tu_sim) == 100);
    TH_CHECK(rt_stats_of(&tu_sim)->status == RT_E_NAN && rt_stats_of(&tu_sim)->count[RT_CNT_NAN] > 0);
    TH_CHECK(rt_stats_of(&tu_sim)->last_block[RT_CNT_NAN] == 1);
    TH_CHECK(rt_isfinite(tu_sim.state.x[0]) && rt_isfinite(tu_sim.state.x[2]));
    TH_NEAR(tu_sim.state.x[2], 0.5, 0.02); /* held near where it went bad */
}

/* a declared invariant (rt/invariant.c): x' = -1 from x = 1 keeps x >= 0 until t = 1;
   the first step ending below -RT_INV_TOL is counted with the block (one count per step,
   status invariant, the state untouched), and a declaration out of range is refused */
static void fall_deriv(const rt_args *a, real_t *xdot) { (void)a, xdot[0] = -1; }
static const uint16_t fall_x[] = {0};
static const rt_invariant fall_inv[] = {{.type = RT_INV_NONNEG, .n = 1, .x = fall_x}};
static const uint16_t bad_x[] = {1};
static const rt_invariant bad_inv[] = {{.type = RT_INV_SUM, .n = 1, .x = bad_x}};

static void test_invariant(void)
{
    static rt_kind k = {.name = "fall", .type = RT_KIND_NSS, .ny = 1, .nx = 1,
                        .y_names = nan_names, .x_names = nan_names, .feed = RT_FEED_NONE,
                        .output = nan_out, .deriv = fall_deriv, .inv = fall_inv, .ninv = 1};
    static const real_t one[] = {1};
    static const rt_block bl[] = {{.name = "Fall", .kind = &k, .x0 = one}};
    static const rt_set set[] = {{.name = "s", .method = &rt_rk4, .ratio = 1}};
    rt_scene sc = {.name = "inv", .dt = (real_t)0.125, .t_end = 2, .blocks = bl,
                   .nblocks = 1, .sets = set, .nsets = 1};
    if (!tu_init(&sc))
        return;
    while (rt_tick(&sc, &tu_sim) == RT_OK && rt_ticks_done(&tu_sim) < 8)
        ;
    TH_CHECK(rt_stats_of(&tu_sim)->count[RT_CNT_INVARIANT] == 0 && rt_stats_of(&tu_sim)->status == RT_OK);
    while (rt_tick(&sc, &tu_sim) == RT_OK)
        ;
    /* ticks 9 .. 16 end at x = -0.125 .. -1 */
    TH_CHECK(rt_stats_of(&tu_sim)->count[RT_CNT_INVARIANT] == 8 && rt_stats_of(&tu_sim)->first_tick[RT_CNT_INVARIANT] == 8);
    TH_CHECK(rt_stats_of(&tu_sim)->last_block[RT_CNT_INVARIANT] == 0 &&
             rt_stats_of(&tu_sim)->status == RT_E_INVARIANT);
    TH_NEAR(tu_sim.state.x[0], -1, 1e-6); /* the check changes no state */
    k.inv = bad_inv; /* reads state 1 of a kind with one */
    TH_CHECK(rt_init(&sc, &tu_sim) == RT_E_SCENE);
    TH_CHECK(th_has(rt_error_text(&tu_sim), "block Fall: kind fall declares an invariant"));
    k.inv = fall_inv;
}

/* every status and counter has a name, and out-of-range values are safe */
/* rt_record writes each recorded value as the scene's table names it, past RT_MAX_REC
   (where rt_init's list of outputs ends) too: pendulum10_actuated's records (outputs, a
   sampled block's outputs, a multibody residual held by its background set) and then
   outputs and states of every block in turn up to RT_MAX_REC + 9 records, the last a
   second held residual. Each value equals rt_rec_value's (which walks the scene's table)
   and, for outputs and states, the value in y or x itself. */
static void test_record_values(void)
{
    enum { NREC = RT_MAX_REC + 9 };
    const rt_scene *base = &mdl_scene_pendulum10_actuated;
    static rt_rec recs[NREC];
    static real_t out[NREC];
    rt_scene sc = *base;
    uint16_t n = 0, b = 0;
    for (; n < base->nrecs; n++)
        recs[n] = base->recs[n];
    for (int what = RT_SIG_Y; n < NREC - 1; b = (uint16_t)((b + 1) % base->nblocks)) {
        const rt_kind *k = base->blocks[b].kind;
        uint16_t m = what == RT_SIG_Y ? k->ny : k->nx;
        if (m > 0)
            recs[n] = (rt_rec){b, (uint8_t)what, (uint16_t)(n % m)}, n++;
        what = what == RT_SIG_Y ? RT_SIG_X : RT_SIG_Y;
    }
    recs[n++] = base->recs[base->nrecs - 1]; /* B1.residual again */
    TH_CHECK(base->recs[base->nrecs - 1].what == RT_SIG_MBS);
    sc.recs = recs, sc.nrecs = n, sc.t_end = sc.dt * 40;
    if (!tu_init(&sc))
        return;
    while (rt_tick(&sc, &tu_sim) == RT_OK)
        ;
    rt_record(&sc, &tu_sim, out);
    int bad = 0;
    for (uint16_t i = 0; i < n; i++) {
        const rt_rec *r = &recs[i];
        bad += !same_bits(out[i], rt_rec_value(&sc, &tu_sim, i));
        if (r->what == RT_SIG_Y)
            bad += !same_bits(out[i], tu_sim.state.y[tu_sim.plan.y_off[r->block] + r->index]);
        if (r->what == RT_SIG_X)
            bad += !same_bits(out[i], tu_sim.state.x[tu_sim.plan.x_off[r->block] + r->index]);
    }
    TH_CHECK(bad == 0 && same_bits(out[n - 1], out[base->nrecs - 1]));
}

static void test_lists(void)
{
    for (int s = 0; s < RT_STATUS_COUNT; s++)
        TH_CHECK(rt_status_name((rt_status)s)[0] != '?');
    for (int c = 0; c < RT_CNT_COUNT; c++)
        TH_CHECK(rt_counter_key((rt_counter)c)[0] != '?');
    TH_CHECK(rt_status_name(RT_STATUS_COUNT)[0] == '?');
    TH_CHECK(rt_counter_key(RT_CNT_COUNT)[0] == '?');
    TH_CHECK(rt_streq(rt_status_name(RT_OK), "ok"));
}

/* the host's builds replay 200 ticks; the images under QEMU (TU_FULL 0; binary64 in
   software on m3, m4f and rv32: a tick of these runs costs some 10^7 instructions) 50, past
   the first Jacobian and its reuse, which is what an earlier run could leave behind */
#if TU_FULL
#define TEST_REPLAY_TICKS 200
#else
#define TEST_REPLAY_TICKS 50
#endif

/* hash of TEST_REPLAY_TICKS ticks of sc from a fresh rt_init of the shared simulator */
static uint64_t short_run(const rt_scene *base, const rt_integrator *m)
{
    rt_scene sc = *base;
    rt_set sets[RT_MAX_SETS];
    for (uint8_t i = 0; i < sc.nsets; i++) {
        sets[i] = base->sets[i];
        sets[i].method = m ? m : sets[i].method;
    }
    sc.sets = sets;
    sc.t_end = sc.dt * TEST_REPLAY_TICKS;
    if (!tu_init(&sc))
        return 0;
    rt_record(&sc, &tu_sim, 0);
    while (rt_tick(&sc, &tu_sim) != RT_E_DONE)
        rt_record(&sc, &tu_sim, 0);
    rt_record(&sc, &tu_sim, 0);
    return rt_trace_hash(&tu_sim);
}

/* a replay does not depend on what the simulator ran before: rt_init leaves nothing of
   an earlier run (implicit methods start Newton from scratch that init zeroes) */
static void test_reinit_replay(void)
{
    const rt_scene *scenes[] = {&mdl_scene_beltgear, &mdl_scene_pendulum10};
    const rt_integrator *methods[] = {0, &rt_sdirk2};
    for (unsigned i = 0; i < 2; i++)
        for (unsigned j = 0; j < 2; j++) {
            uint64_t a = short_run(scenes[i], methods[j]);
            short_run(scenes[1 - i], &rt_sdirk3); /* something else in between */
            uint64_t b = short_run(scenes[i], methods[j]);
            TH_EQ_U64(b, a);
        }
}

/* a multirate scene for the held outputs: a slow set (5 ticks) with a source, a lag of
   it and a gain with throughput of the fast set's rotor; the fast set (1 tick) drives
   its rotor by the lag. Every cross-set input reads the history (Hermite in the fast
   set), so only recording sees the slow set's live outputs between its steps */
enum { H_SRC, H_LAG, H_G, H_ROT, H_RATIO = 5 };
static const real_t h_sine_p[] = {1, 7, (real_t)0.3, 0};
static const real_t h_gain_p[] = {(real_t)0.5};
static const rt_conn h_cn[] = {{H_SRC, 0, H_LAG, 0}, {H_ROT, 1, H_G, 0}, {H_LAG, 0, H_ROT, 0}};
static const rt_block h_bl[] = {
    [H_SRC] = {.name = "Src", .kind = &mdl_sine_kind, .p = h_sine_p, .set = 0},
    [H_LAG] = {.name = "Lag", .kind = &mdl_pt1_kind, .set = 0},
    [H_G] = {.name = "G", .kind = &mdl_gain_kind, .p = h_gain_p, .set = 0},
    [H_ROT] = {.name = "Rot", .kind = &mdl_rotor_kind, .set = 1},
};
static const rt_set h_sets[] = {
    {.name = "slow", .method = &rt_rk4, .ratio = H_RATIO},
    {.name = "fast", .method = &rt_rk4, .ratio = 1, .interp = RT_INTERP_HERMITE},
};
static const rt_scene h_sc = {.name = "held", .dt = (real_t)1e-3, .t_end = (real_t)0.2,
                              .blocks = h_bl, .nblocks = 4, .conns = h_cn, .nconns = 3,
                              .sets = h_sets, .nsets = 2};
#define h_fresh tu_spare /* a copy of tu_sim whose outputs are evaluated anew */

/* the slow set's outputs, offset and count */
static uint16_t slow_y0(void) { return tu_sim.plan.y_off[H_SRC]; }
static uint16_t slow_ny(void) { return (uint16_t)(tu_sim.plan.y_off[H_G + 1] - slow_y0()); }

/* a slow set's outputs are computed when it steps and held until its next step: between
   its steps the trace repeats the value at its last step instant, and that value equals
   the outputs evaluated afresh (from its state, with every output poisoned first) there */
static void test_held_outputs(void)
{
    if (!tu_init(&h_sc))
        return;
    TH_CHECK(tu_sim.plan.y_off[H_G + 1] == tu_sim.plan.y_off[H_ROT]); /* slow set first */
    real_t held[8];
    for (uint16_t j = 0; j < slow_ny(); j++)
        held[j] = tu_sim.state.y[slow_y0() + j]; /* the outputs at t = 0 */
    int fresh_ok = 1, held_ok = 1, src_ok = 1, steps = 0;
    for (rt_status st = RT_OK; st == RT_OK;) {
        st = rt_tick(&h_sc, &tu_sim);
        const real_t *y = tu_sim.state.y + slow_y0();
        if (rt_ticks_done(&tu_sim) % H_RATIO == 0) {
            h_fresh = tu_sim;
            for (uint16_t j = 0; j < RT_MAX_Y; j++)
                h_fresh.state.y[j] = (real_t)0 / (real_t)0;
            rt_refresh(&h_sc, &h_fresh);
            for (uint16_t j = 0; j < slow_ny(); j++) {
                held[j] = y[j];
                fresh_ok &= same_bits(h_fresh.state.y[slow_y0() + j], y[j]);
            }
            /* the source at the step instant, by its formula */
            real_t t = rt_time(&h_sc, &tu_sim);
            src_ok &= y[0] == h_sine_p[0] * rt_sin(h_sine_p[1] * t + h_sine_p[2]) + h_sine_p[3];
            steps++;
        } else {
            for (uint16_t j = 0; j < slow_ny(); j++)
                held_ok &= same_bits(held[j], y[j]);
        }
    }
    TH_CHECK(steps == 200 / H_RATIO);
    TH_CHECK(fresh_ok);
    TH_CHECK(held_ok);
    TH_CHECK(src_ok);
    TH_CHECK(rt_stats_of(&tu_sim)->status == RT_OK);
}

/* the fast set never reads the slow set's live outputs between its steps: poisoning them
   after every tick that did not end a slow step leaves the fast set's trace bit for bit */
static uint64_t fast_trace(int poison)
{
    if (!tu_init(&h_sc))
        return 0;
    uint64_t h = 0;
    for (rt_status st = RT_OK; st == RT_OK;) {
        st = rt_tick(&h_sc, &tu_sim);
        const real_t *y = tu_sim.state.y + tu_sim.plan.y_off[H_ROT];
        for (uint16_t j = 0; j < 2; j++)
            h = rt_hash_real(h, y[j]);
        if (poison && rt_ticks_done(&tu_sim) % H_RATIO != 0)
            for (uint16_t j = 0; j < slow_ny(); j++)
                tu_sim.state.y[slow_y0() + j] = (real_t)0 / (real_t)0;
    }
    TH_CHECK(rt_stats_of(&tu_sim)->count[RT_CNT_NAN] == 0);
    return h;
}

static void test_fast_reads_history(void)
{
    TH_EQ_U64(fast_trace(1), fast_trace(0));
}

/* a probe kind for the right-hand side's calls (rt/eval.c): x' = u - x; y0 = x, y1 = x + u
   (depends on its input), y2 = 2 x; its lean output equation gives y0 alone. It counts
   its calls */
static uint32_t lp_full, lp_lean;
static void lp_output(const rt_args *a, real_t *y)
{
    lp_full++;
    y[0] = a->x[0], y[1] = a->x[0] + a->u[0], y[2] = 2 * a->x[0];
}
static void lp_output_lean(const rt_args *a, real_t *y)
{
    lp_lean++;
    y[0] = a->x[0];
}
static void lp_deriv(const rt_args *a, real_t *xdot) { xdot[0] = a->u[0] - a->x[0]; }
static const uint8_t lp_feed[3] = {0, 1, 0}, lp_skip[3] = {0, 1, 1};
static const char *const lp_u[] = {"u"}, *const lp_y[] = {"y0", "y1", "y2"};
static const char *const lp_x[] = {"x"};
static const real_t lp_x0[] = {1};
static const rt_kind lp_kind = {
    .name = "lean_probe", .type = RT_KIND_NSS, .nu = 1, .ny = 3, .nx = 1,
    .u_names = lp_u, .y_names = lp_y, .x_names = lp_x, .x_default = lp_x0,
    .feed = RT_FEED_TABLE, .feed_table = lp_feed, .output = lp_output,
    .output_lean = lp_output_lean, .lean_skip = lp_skip, .deriv = lp_deriv};

/* A (the probe) feeds gain B by y0, B feeds A's input: the sequence calls A, B, A (its y1
   after B). Reader C (a gain) reads B (0), A.y2 (1: not in the lean equation) or
   A.y1 (2: that, and it depends on A's input); with 3, C reads B and a sampled block D
   (a PI every tick) reads A.y2 and A.y1, which it reads only at its sample hits. Returns
   A's x after 50 ticks of RK4 and the counts: a right-hand side calls the lean equation
   once while no reader needs more, else the full one, and the repeat only for a reader
   of y1 */
static real_t lean_run(int reader, int lean, uint32_t *full, uint32_t *lean_calls,
                       uint64_t *rhs)
{
    static const real_t half[] = {(real_t)0.5};
    rt_kind k = lp_kind;
    if (!lean)
        k.output_lean = 0;
    rt_block bl[4] = {{.name = "A", .kind = &k},
                      {.name = "B", .kind = &mdl_gain_kind, .p = half},
                      {.name = "C", .kind = &mdl_gain_kind, .p = half},
                      {.name = "D", .kind = &mdl_pi_kind, .ts = (real_t)0.01}};
    rt_conn cn[5] = {{0, 0, 1, 0}, {1, 0, 0, 0}, {0, (uint16_t)(reader == 1 ? 2 : 1), 2, 0},
                     {0, 2, 3, 0}, {0, 1, 3, 1}};
    if (!reader || reader == 3)
        cn[2].from = 1, cn[2].y = 0; /* C reads B */
    rt_set set = {.name = "s", .method = &rt_rk4, .ratio = 1};
    rt_rec rec = {.block = 0, .what = RT_SIG_Y, .index = 1};
    rt_scene sc = {.name = "lean", .dt = (real_t)0.01, .t_end = 1, .blocks = bl,
                   .nblocks = reader == 3 ? 4 : 3, .conns = cn,
                   .nconns = reader == 3 ? 5 : 3, .sets = &set,
                   .nsets = 1, .recs = &rec, .nrecs = 1};
    if (!tu_init(&sc))
        return -1;
    lp_full = lp_lean = 0;
    int y1_ok = 1;
    for (int i = 0; i < 50; i++) {
        rt_tick(&sc, &tu_sim);
        /* at the tick y1 is x + u, u = B's 0.5 x: every output is current */
        real_t x = tu_sim.state.x[0];
        y1_ok &= rt_rec_value(&sc, &tu_sim, 0) == x + (real_t)0.5 * x;
    }
    TH_CHECK(y1_ok && rt_stats_of(&tu_sim)->status == RT_OK);
    *full = lp_full, *lean_calls = lp_lean, *rhs = rt_stats_of(&tu_sim)->rhs_evals[0];
    return tu_sim.state.x[0];
}

static void test_rhs_lean_calls(void)
{
    uint32_t full, lean;
    uint64_t rhs;
    real_t plain = lean_run(0, 0, &full, &lean, &rhs);
    /* without a lean equation: A once per right-hand side (the repeat skipped), and both
       calls at each of the 50 ticks */
    TH_CHECK(lean == 0 && rhs >= 200 && full == rhs + 2 * 50);
    /* with it: the lean call in every right-hand side, the same state bit for bit */
    TH_CHECK(same_bits(lean_run(0, 1, &full, &lean, &rhs), plain));
    TH_CHECK(lean == rhs && full == 2 * 50);
    /* a reader of y2: the full equation, once */
    TH_CHECK(same_bits(lean_run(1, 1, &full, &lean, &rhs), plain));
    TH_CHECK(lean == 0 && full == rhs + 2 * 50);
    /* a reader of y1: the full equation, and again after B */
    TH_CHECK(same_bits(lean_run(2, 1, &full, &lean, &rhs), plain));
    TH_CHECK(lean == 0 && full == 2 * rhs + 2 * 50);
    /* a sampled reader of both: the lean call, as with none */
    TH_CHECK(same_bits(lean_run(3, 1, &full, &lean, &rhs), plain));
    TH_CHECK(lean == rhs && full == 2 * 50);
}

/* ---- snapshots of a kind with internal state (rt_kind.save / restore, rt/snapshot.c): its
   output counts the calls it had, in memory outside x, d and p, as an FMU's event counter.
   Four bytes, little-endian; `mode` 1 reports more than any snapshot holds, 2 cannot save */
typedef struct { uint32_t calls; int mode; } count_mem;
static count_mem cmem;
static const char *const count_names[] = {"n"};
static void count_out(const rt_args *a, real_t *y)
{
    count_mem *m = (count_mem *)(uintptr_t)a->spec;
    y[0] = (real_t)++m->calls;
}
static rt_status count_save(const void *spec, uint8_t *buf, uint32_t cap, uint32_t *n)
{
    const count_mem *m = spec;
    if (m->mode == 2)
        return RT_E_SNAPSHOT;
    *n = m->mode == 1 ? (uint32_t)RT_MAX_KSTATE : 4;
    if (*n > cap)
        return buf ? RT_E_CAPACITY : RT_OK;
    for (int i = 0; buf && i < 4; i++)
        buf[i] = (uint8_t)(m->calls >> (8 * i));
    return RT_OK;
}
static rt_status count_restore(const void *spec, const uint8_t *buf, uint32_t n)
{
    count_mem *m = (count_mem *)(uintptr_t)spec;
    if (n != 4)
        return RT_E_SNAPSHOT;
    m->calls = (uint32_t)buf[0] | (uint32_t)buf[1] << 8 | (uint32_t)buf[2] << 16 |
               (uint32_t)buf[3] << 24;
    return RT_OK;
}
static const rt_kind count_kind = {
    .name = "count", .type = RT_KIND_OUTPUT, .ny = 1, .y_names = count_names,
    .feed = RT_FEED_NONE, .output = count_out, .spec = &cmem, .save = count_save,
    .restore = count_restore,
};

/* snapshot at tick 10, 10 ticks on, restore: the next ticks show the counts they showed
   after the snapshot (11, 12, ...: one output call a tick), not the counter's later ones;
   a state too large for RT_MAX_KSTATE or one the kind cannot save is a status, and such
   a snapshot is refused by rt_restore with the run unchanged */
static void test_snapshot_kind_state(void)
{
    static const rt_block bl[] = {{.name = "C", .kind = &count_kind}};
    static const rt_set set[] = {{.name = "s", .method = &rt_rk4, .ratio = 1}};
    rt_state *snap = &tu_spare.state; /* the spare run's room (a third rt_state would not
                                         fit the Cortex-M unit-test images' RAM) */
    rt_scene sc = {.name = "count", .dt = (real_t)0.01, .t_end = 1, .blocks = bl, .nblocks = 1,
                   .sets = set, .nsets = 1};
    cmem.calls = 0, cmem.mode = 0;
    if (!tu_init(&sc))
        return;
    while (rt_ticks_done(&tu_sim) < 10)
        rt_tick(&sc, &tu_sim);
    uint32_t at = cmem.calls;
    TH_CHECK(rt_snapshot(&tu_sim, snap) == (RT_MAX_KSTATE >= 8 ? RT_OK : RT_E_CAPACITY));
    for (int i = 0; i < 10; i++)
        rt_tick(&sc, &tu_sim);
    TH_CHECK(cmem.calls == at + 10);
    if (RT_MAX_KSTATE >= 8) {
        TH_CHECK(rt_restore(&tu_sim, snap) == RT_OK && rt_ticks_done(&tu_sim) == 10);
        rt_tick(&sc, &tu_sim);
        TH_CHECK(rt_output(&tu_sim, 0, 0) == (real_t)(at + 1) && cmem.calls == at + 1);
    }
    for (int mode = 1; mode <= 2; mode++) {
        cmem.mode = mode;
        uint64_t tick = rt_ticks_done(&tu_sim);
        TH_CHECK(rt_snapshot(&tu_sim, snap) == (mode == 1 ? RT_E_CAPACITY : RT_E_SNAPSHOT));
        rt_tick(&sc, &tu_sim);
        TH_CHECK(rt_restore(&tu_sim, snap) == RT_E_SNAPSHOT && rt_ticks_done(&tu_sim) == tick + 1);
    }
    cmem.mode = 0;
}

const th_test th_sim_tests[] = {
    {"sim_reinit_replay", test_reinit_replay},
    {"sim_hash_determinism", test_hash_determinism},
    {"sim_integer_time", test_integer_time},
    {"sim_tick_width", test_tick_width},
    {"sim_set_param", test_set_param},
    {"sim_lss", test_lss},
    {"sim_nan_contained", test_nan_contained},
    {"sim_invariant", test_invariant},
    {"sim_lists", test_lists},
    {"sim_record_values", test_record_values},
    {"sim_held_outputs", test_held_outputs},
    {"sim_fast_reads_history", test_fast_reads_history},
    {"sim_rhs_lean_calls", test_rhs_lean_calls},
    {"sim_snapshot_kind_state", test_snapshot_kind_state},
    {0, 0},
};
