/* test_bg.c - the background set (rt/bg.c): its step run inline at release, in an attached
 * context right after the release, or as late as its deadline allows gives the same trace
 * bit for bit; a step not finished at its deadline is counted and published late; the
 * scene checks. Portable (runs on the cross targets too); the tests with threads, the
 * POSIX timer and the fine reference are in tests/whitebox/host/test_bg.c. */
#include "harness.h"
#include "rt.h"
#include "rt_math.h"
#include "scenes/scenes.h"
#include "testutil.h"
#include "rt_sim.h" /* white box: reads rt_sim's parts (plan, state, work) */

/* three simulators of one scene: inline, context run at once, context run at the last
   tick before the deadline; and the two contexts */
static rt_sim sims[3], ctx[2];

#ifndef TEST_BG_TICKS
#define TEST_BG_TICKS 400 /* ticks compared (pendulum10_actuated: 100 background steps) */
#endif

/* the recorded values of a and b now, bit for bit */
static int same_record(const rt_scene *sc, const rt_sim *a, const rt_sim *b)
{
    int same = rt_time(sc, a) == rt_time(sc, b);
    for (uint16_t i = 0; i < sc->nrecs; i++) {
        real_t x = rt_rec_value(sc, a, i), y = rt_rec_value(sc, b, i);
        same = same && (x == y || (x != x && y != y));
    }
    return same;
}

/* inline, eager and lazy background steps: the same trace at every tick */
static void test_bg_same_trace(void)
{
    const rt_scene *sc = &mdl_scene_pendulum10_actuated;
    int ok = 1, lazy_runs = 0, eager_runs = 0;
    for (int i = 0; i < 3; i++)
        ok = ok && rt_init(sc, &sims[i]) == RT_OK;
    TH_CHECK(ok && rt_bg_set(&sims[0]) >= 0);
    TH_CHECK(rt_bg_attach(sc, &sims[1], &ctx[0]) == RT_OK);
    TH_CHECK(rt_bg_attach(sc, &sims[2], &ctx[1]) == RT_OK);
    for (int i = 0; i < 3; i++)
        rt_record(sc, &sims[i], 0);
    for (int n = 0; ok && n < TEST_BG_TICKS; n++) {
        /* lazy: the step runs only when the next tick would publish it */
        if (rt_bg_pending(&sims[2]) && sims[2].state.tick + 1 >= sims[2].state.bg_due)
            lazy_runs += rt_background(sc, &sims[2]) == RT_OK;
        for (int i = 0; i < 3; i++) {
            rt_tick(sc, &sims[i]);
            rt_record(sc, &sims[i], 0);
        }
        TH_CHECK(!rt_bg_pending(&sims[0])); /* inline: nothing left to run */
        if (rt_bg_pending(&sims[1]))
            eager_runs += rt_background(sc, &sims[1]) == RT_OK;
        ok = same_record(sc, &sims[0], &sims[1]) && same_record(sc, &sims[0], &sims[2]);
    }
    TH_CHECK(ok);
    TH_EQ_U64(sims[1].state.hash, sims[0].state.hash);
    TH_EQ_U64(sims[2].state.hash, sims[0].state.hash);
    TH_CHECK(lazy_runs == TEST_BG_TICKS / (int)sc->sets[rt_bg_set(&sims[0])].ratio);
    TH_CHECK(eager_runs == lazy_runs);
    for (int i = 0; i < 3; i++)
        TH_CHECK(sims[i].stats.status == RT_OK && sims[i].stats.bg_late == 0);
    /* the step's statistics reach the tick's: same evaluations in every mode */
    uint8_t s = (uint8_t)rt_bg_set(&sims[0]);
    TH_EQ_U64(sims[1].stats.rhs_evals[s], sims[0].stats.rhs_evals[s]);
    TH_EQ_U64(sims[2].stats.rhs_evals[s], sims[0].stats.rhs_evals[s]);
    th_note("background steps compared", (double)lazy_runs);
}

/* a parameter changed between ticks reaches the background step at its next release,
   inline and in a context alike: a mass of the chain doubled (its constant mass matrix is
   factored anew in the context too), the same trace bit for bit, and a different one
   from the run without the change */
static void test_bg_param(void)
{
    const rt_scene *sc = &mdl_scene_pendulum10_actuated;
    int ok = 1;
    for (int i = 0; i < 3; i++)
        ok = ok && rt_init(sc, &sims[i]) == RT_OK;
    TH_CHECK(ok && rt_bg_attach(sc, &sims[1], &ctx[0]) == RT_OK);
    int differs = 0;
    for (int n = 0; ok && n < 200; n++) {
        if (n == 41) /* mid macro step: the step in flight keeps the old mass */
            for (int i = 0; i < 2; i++)
                ok = ok && rt_set_param(sc, &sims[i], "B5", "m", 2) == RT_OK;
        for (int i = 0; i < 3; i++)
            rt_tick(sc, &sims[i]);
        if (rt_bg_pending(&sims[1]))
            rt_background(sc, &sims[1]);
        ok = ok && same_record(sc, &sims[0], &sims[1]);
        differs |= !same_record(sc, &sims[0], &sims[2]);
    }
    TH_CHECK(ok && differs);
    TH_CHECK(sims[0].stats.status == RT_OK && sims[1].stats.status == RT_OK);
}

/* the background chain by ROS2 with a Jacobian every 1024 steps: a parameter set to its own
   value changes nothing; one changed and set back before the next release makes the step
   that release runs form its Jacobian anew, inline and in a context alike (the same bits
   at every tick), and the run then differs from one without the calls */
static void test_bg_param_jacobian(void)
{
    static rt_set sets[RT_MAX_SETS];
    rt_scene sc = mdl_scene_pendulum10_actuated;
    for (uint8_t s = 0; s < sc.nsets; s++)
        sets[s] = sc.sets[s];
    int chain = -1;
    for (uint8_t s = 0; s < sc.nsets; s++)
        chain = sets[s].background ? s : chain;
    if (!TH_CHECK(chain >= 0))
        return;
    sets[chain].method = &rt_ros2;
    sets[chain].cfg = (rt_set_cfg){.jac_every = 1024, .accuracy = (real_t)1e-2};
    sc.sets = sets;
    int ok = 1;
    for (int i = 0; i < 3; i++)
        ok = ok && rt_init(&sc, &sims[i]) == RT_OK;
    TH_CHECK(ok && rt_bg_attach(&sc, &sims[1], &ctx[0]) == RT_OK);
    int differs_before = 0, differs_after = 0;
    for (int n = 0; ok && n < 200; n++) {
        for (int i = 0; i < 2; i++) {
            if (n == 41) /* its own value: nothing to form anew */
                ok = ok && rt_set_param(&sc, &sims[i], "B5", "m", 1) == RT_OK;
            if (n == 81) /* changed and back, mid macro step */
                ok = ok && rt_set_param(&sc, &sims[i], "B5", "m", 2) == RT_OK &&
                     rt_set_param(&sc, &sims[i], "B5", "m", 1) == RT_OK;
        }
        for (int i = 0; i < 3; i++)
            rt_tick(&sc, &sims[i]);
        if (rt_bg_pending(&sims[1]))
            rt_background(&sc, &sims[1]);
        ok = ok && same_record(&sc, &sims[0], &sims[1]);
        if (n < 81)
            differs_before |= !same_record(&sc, &sims[0], &sims[2]);
        else
            differs_after |= !same_record(&sc, &sims[0], &sims[2]);
    }
    TH_CHECK(ok && !differs_before && differs_after);
    TH_CHECK(sims[0].stats.status == RT_OK && sims[1].stats.status == RT_OK);
}

/* a snapshot between two background steps (right after a publication), restored into a
   run with a context attached after a parameter changed there: the context is re-attached
   from the restored state and the run continues as one that never left it (the same
   records 40 ticks on as the inline run without the change); a snapshot with a step in
   flight is refused there (the step is the context's), and the run is left as it was */
static void test_bg_restore(void)
{
    static rt_state snap, busy;
    const rt_scene *sc = &mdl_scene_pendulum10_actuated;
    int ok = rt_init(sc, &sims[0]) == RT_OK && rt_init(sc, &sims[1]) == RT_OK &&
             rt_bg_attach(sc, &sims[1], &ctx[0]) == RT_OK;
    if (!TH_CHECK(ok))
        return;
    for (int n = 1; ok && n <= 100; n++) {
        rt_tick(sc, &sims[1]);
        if (rt_bg_pending(&sims[1]))
            rt_background(sc, &sims[1]);
        if (n == 40)
            rt_snapshot(&sims[1], &snap);
        if (n == 41)
            ok = rt_set_param(sc, &sims[1], "B5", "m", 2) == RT_OK;
        if (n == 42)
            rt_snapshot(&sims[1], &busy);
    }
    TH_CHECK(ok && !snap.bg_busy && busy.bg_busy);
    uint64_t tick = sims[1].state.tick;
    TH_CHECK(rt_restore(&sims[1], &busy) == RT_E_ARG && sims[1].state.tick == tick);
    TH_CHECK(rt_restore(&sims[1], &snap) == RT_OK && sims[1].state.tick == 40);
    for (int n = 1; n <= 80; n++)
        rt_tick(sc, &sims[0]);
    for (int n = 1; n <= 40; n++) {
        rt_tick(sc, &sims[1]);
        if (rt_bg_pending(&sims[1]))
            rt_background(sc, &sims[1]);
    }
    TH_CHECK(sims[1].state.tick == 80 && same_record(sc, &sims[0], &sims[1]));
}

/* a joint reaction of the background set, recorded: held like its residual (computed by
   the step at its end, in whichever context ran it), the same bits inline and in a
   context, and at the first publications the rod J1 carries the hanging chain, 10 m g
   (the servo's command is near zero while the arm still hangs) */
static void test_bg_reaction(void)
{
    static rt_rec recs[RT_MAX_REC];
    rt_scene sc = mdl_scene_pendulum10_actuated;
    uint16_t n = sc.nrecs;
    for (uint16_t i = 0; i < n; i++)
        recs[i] = sc.recs[i];
    recs[n] = (rt_rec){0, RT_SIG_MBS, RT_MBS_SIG_JOINT_AT(0, RT_MBS_JSIG_FZ)}; /* J1 on B1 */
    sc.recs = recs, sc.nrecs = (uint16_t)(n + 1);
    TH_CHECK(rt_streq(sc.blocks[0].name, "B1") && sc.joints[0].b1 == 0 && sc.joints[0].b2 < 0);
    int ok = rt_init(&sc, &sims[0]) == RT_OK && rt_init(&sc, &sims[1]) == RT_OK &&
             rt_bg_attach(&sc, &sims[1], &ctx[0]) == RT_OK;
    if (!TH_CHECK(ok))
        return;
    real_t first = 0, held = rt_rec_value(&sc, &sims[0], n);
    int steady = 1;
    for (int k = 1; ok && k <= 40; k++) {
        for (int i = 0; i < 2; i++)
            rt_tick(&sc, &sims[i]);
        if (rt_bg_pending(&sims[1]))
            rt_background(&sc, &sims[1]);
        ok = same_record(&sc, &sims[0], &sims[1]);
        real_t f = rt_rec_value(&sc, &sims[0], n);
        steady &= k % 4 == 0 || f == held; /* held between publications */
        held = f;
        if (k == 4)
            first = f;
    }
    TH_CHECK(ok && steady);
    TH_NEAR(first, 10 * 9.81, 0.05);
    TH_CHECK(sims[0].stats.status == RT_OK && sims[1].stats.status == RT_OK);
}

/* the other sets see the step only from its deadline on: before, the trace shows the set
   at its release, and its history ends there */
static void test_bg_deadline(void)
{
    const rt_scene *sc = &mdl_scene_pendulum10_actuated;
    rt_sim *sim = &sims[0];
    TH_CHECK(rt_init(sc, sim) == RT_OK && rt_bg_attach(sc, sim, &ctx[0]) == RT_OK);
    uint8_t s = (uint8_t)rt_bg_set(sim);
    uint32_t r = sc->sets[s].ratio;
    for (uint32_t n = 0; n < 2 * r; n++) {
        rt_tick(sc, sim);
        if (rt_bg_pending(sim))
            rt_background(sc, sim);
    }
    TH_CHECK(sim->state.set_tick[s] == 2 * r && !rt_bg_pending(sim));
    rt_tick(sc, sim);
    TH_CHECK(rt_bg_pending(sim)); /* released at 2r */
    TH_CHECK(rt_background(sc, sim) == RT_OK && !rt_bg_pending(sim));
    TH_CHECK(rt_background(sc, sim) == RT_E_ARG); /* nothing left */
    TH_CHECK(sim->state.set_tick[s] == 2 * r);    /* done, but not yet due */
    TH_CHECK(sim->state.hist_t[s][0] == (real_t)(2 * r) * sc->dt);
    while (rt_ticks_done(sim) < 3 * r - 1)
        rt_tick(sc, sim);
    TH_CHECK(sim->state.set_tick[s] == 2 * r);
    rt_tick(sc, sim);
    TH_CHECK(sim->state.set_tick[s] == 3 * r); /* published as the tick reached 3r */
    TH_CHECK(sim->state.hist_t[s][0] == (real_t)(3 * r) * sc->dt);
    TH_CHECK(rt_stats_of(sim)->status == RT_OK);
}

/* a step not finished at its deadline: counted once, never waited for, published at the
   first tick after it has finished, the next step released then with the same deadline */
static void test_bg_overrun(void)
{
    const rt_scene *sc = &mdl_scene_pendulum10_actuated;
    rt_sim *sim = &sims[0];
    TH_CHECK(rt_init(sc, sim) == RT_OK && rt_bg_attach(sc, sim, &ctx[0]) == RT_OK);
    uint8_t s = (uint8_t)rt_bg_set(sim);
    uint32_t r = sc->sets[s].ratio;
    for (uint32_t n = 0; n < r + 2; n++)
        rt_tick(sc, sim); /* the step released at tick 0 never ran */
    TH_CHECK(rt_stats_of(sim)->count[RT_CNT_OVERRUN] == 1 && rt_stats_of(sim)->bg_late == 1);
    TH_CHECK(rt_stats_of(sim)->status == RT_E_OVERRUN);
    TH_CHECK(sim->state.set_tick[s] == 0 && sim->state.hist_t[s][0] == 0);
    TH_CHECK(rt_background(sc, sim) == RT_OK);
    rt_tick(sc, sim);
    TH_CHECK(sim->state.set_tick[s] == r && !sim->state.bg_busy); /* published late */
    rt_tick(sc, sim);
    /* the next step, released at the next tick, keeps its deadline on the schedule */
    TH_CHECK(rt_bg_pending(sim) && sim->state.bg_due == 2 * r);
    /* with r <= 4 that step (from r to 2r, released at tick r + 3) was due at once */
    TH_CHECK(rt_stats_of(sim)->count[RT_CNT_OVERRUN] == (r + 4 >= 2 * r ? 2u : 1u));
}

/* what init refuses: two background sets, a sampled block or a state event in one */
static void test_bg_checks(void)
{
    rt_scene sc = mdl_scene_pendulum10_actuated;
    rt_set sets[2] = {sc.sets[0], sc.sets[1]};
    sc.sets = sets;
    sets[0].background = sets[1].background = 1;
    TH_CHECK(rt_init(&sc, &sims[0]) == RT_E_SCENE &&
             th_has(rt_error_text(&sims[0]), "at most one"));
    sets[0].background = 0; /* the servo set holds the sampled controller */
    TH_CHECK(rt_init(&sc, &sims[0]) == RT_E_SCENE && th_has(rt_error_text(&sims[0]), "Ctrl"));
    rt_scene ball = mdl_scene_bouncing_ball;
    rt_set one = ball.sets[0];
    one.background = 1;
    ball.sets = &one;
    TH_CHECK(rt_init(&ball, &sims[0]) == RT_E_SCENE);
    TH_CHECK(rt_bg_attach(&ball, &sims[0], &sims[0]) == RT_E_ARG);
    /* a scene without one: nothing released, nothing pending */
    TH_CHECK(rt_init(&mdl_scene_pendulum10, &sims[0]) == RT_OK && rt_bg_set(&sims[0]) == -1);
    rt_tick(&mdl_scene_pendulum10, &sims[0]);
    TH_CHECK(!rt_bg_pending(&sims[0]) &&
             rt_background(&mdl_scene_pendulum10, &sims[0]) == RT_E_ARG);
}

/* B1..B10's largest link-length error, by hand from their positions in the state */
static real_t chain_residual(const rt_scene *sc, const rt_sim *sim)
{
    static const char *const names[10] = {"B1", "B2", "B3", "B4", "B5",
                                          "B6", "B7", "B8", "B9", "B10"};
    real_t worst = 0, prev[3] = {0, 0, 0};
    for (int k = 0; k < 10; k++) {
        const real_t *r = sim->state.x + sim->plan.x_off[rt_block_index(sc, names[k])];
        real_t d[3] = {r[0] - prev[0], r[1] - prev[1], r[2] - prev[2]};
        real_t g = rt_sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) - 1;
        worst = rt_fmax(worst, rt_fabs(g));
        prev[0] = r[0], prev[1] = r[1], prev[2] = r[2];
    }
    return worst;
}

/* a recorded multibody signal of a set stepping every 4 ticks (B1.residual) is the
   residual of the set's state when it last reached a tick, held in between like its
   outputs: in the background (the published state) and in the tick (where the state is
   a step ahead of the tick between steps); a controller link exporting it reads the same
   held value, whether the signal is also recorded or only exported */
static void test_bg_held_signals(void)
{
    rt_scene sc = mdl_scene_pendulum10_actuated;
    rt_set sets[2] = {sc.sets[0], sc.sets[1]};
    sc.sets = sets;
    int chain = sets[0].background ? 0 : 1, rec = sc.nrecs - 1;
    rt_link lk = {.name = "ctl", .period = 1, .exp = &sc.recs[rec], .nexp = 1};
    sc.link = &lk;
    TH_CHECK(sets[chain].background && sets[chain].ratio == 4);
    for (int run = 0; run < 4; run++) {
        int bg = run < 2, exp_only = run % 2;
        sets[chain].background = (uint8_t)bg;
        sc.nrecs = (uint16_t)(mdl_scene_pendulum10_actuated.nrecs - exp_only);
        if (!TH_CHECK(rt_init(&sc, &sims[0]) == RT_OK))
            return;
        rt_sizes z;
        rt_sizes_of(&sc, &sims[0], &z);
        TH_CHECK(z.held_sig == (exp_only ? 1 : 2) && rt_rec_signal(&sc, (uint16_t)rec)[0] == 'r');
        real_t want = chain_residual(&sc, &sims[0]);
        int ok = rt_link_export(&sc, &sims[0], 0) == want, ahead = 0;
        ok &= exp_only || rt_rec_value(&sc, &sims[0], (uint16_t)rec) == want;
        real_t out[RT_MAX_REC];
        for (int i = 0; i < 200; i++) {
            rt_tick(&sc, &sims[0]);
            if (sims[0].state.tick % 4 == 0)
                want = chain_residual(&sc, &sims[0]);
            else
                ahead |= chain_residual(&sc, &sims[0]) != want;
            ok &= rt_link_export(&sc, &sims[0], 0) == want;
            if (exp_only)
                continue;
            /* before recording (a published value not yet held) and after */
            ok &= rt_rec_value(&sc, &sims[0], (uint16_t)rec) == want;
            rt_record(&sc, &sims[0], out);
            ok &= out[rec] == want && rt_rec_value(&sc, &sims[0], (uint16_t)rec) == want;
        }
        TH_CHECK(ok);
        TH_CHECK(ahead == !bg); /* in the tick the state between steps is not the held one */
        TH_CHECK(sims[0].stats.status == RT_OK);
    }
    /* a scene whose multibody set steps every tick holds none */
    rt_sizes z;
    TH_CHECK(rt_init(&mdl_scene_pendulum10, &sims[0]) == RT_OK);
    rt_sizes_of(&mdl_scene_pendulum10, &sims[0], &z);
    TH_CHECK(z.held_sig == 0);
}

/* ------------------------------------------------------------------ test-local kinds */

static const char *const one_name[] = {"v"};

/* a sampled counter: n[k+1] = n[k] + 1 at each sample, y = n (held between samples) */
static void count_out(const rt_args *a, real_t *y) { y[0] = a->d[0]; }
static void count_update(const rt_args *a, real_t *dnext) { dnext[0] = a->d[0] + 1; }
static const rt_kind count_kind = {
    .name = "count", .type = RT_KIND_DSS, .ny = 1, .nd = 1, .y_names = one_name,
    .d_names = one_name, .feed = RT_FEED_NONE, .autonomous = 1, .output = count_out,
    .update = count_update,
};

/* an integrator: x' = u, y = x */
static void integ_out(const rt_args *a, real_t *y) { y[0] = a->x[0]; }
static void integ_deriv(const rt_args *a, real_t *xdot) { xdot[0] = a->u[0]; }
static const rt_kind integ_kind = {
    .name = "integ", .type = RT_KIND_NSS, .nu = 1, .ny = 1, .nx = 1, .u_names = one_name,
    .y_names = one_name, .x_names = one_name, .feed = RT_FEED_NONE, .autonomous = 1,
    .output = integ_out, .deriv = integ_deriv,
};

/* a ramp x' = 1 whose output turns non-finite for t > 0.3 (its state stays finite) */
static void nan_out(const rt_args *a, real_t *y)
{
    real_t zero = 0;
    y[0] = a->t > (real_t)0.3 ? zero / zero : a->x[0];
}
static void one_deriv(const rt_args *a, real_t *xdot) { (void)a, xdot[0] = 1; }
static const rt_kind nan_out_kind = {
    .name = "nan_out", .type = RT_KIND_NSS, .ny = 1, .nx = 1, .y_names = one_name,
    .x_names = one_name, .feed = RT_FEED_NONE, .output = nan_out, .deriv = one_deriv,
};

/* a ramp x' = 1 whose derivative turns non-finite for t > 0.61, y = x */
static void nan_deriv(const rt_args *a, real_t *xdot)
{
    real_t zero = 0;
    xdot[0] = a->t > (real_t)0.61 ? zero / zero : 1;
}
static const rt_kind nan_deriv_kind = {
    .name = "nan_deriv", .type = RT_KIND_NSS, .ny = 1, .nx = 1, .y_names = one_name,
    .x_names = one_name, .feed = RT_FEED_NONE, .output = integ_out, .deriv = nan_deriv,
};

/* a sampled counter (every 3 ticks) read by the background set, which integrates it over
   steps of 4 ticks (H = 1): the step released at tick k reads the count as it stands
   then, floor(k / 3) (the output at a sample shows the count of the samples before it),
   so x at tick 4m is the sum of those counts at ticks 0, 4, ..., 4(m - 1) */
static double held_want(uint64_t tick)
{
    double x = 0;
    for (uint64_t k = 0; k + 4 <= tick; k += 4)
        x += (double)(k / 3);
    return x;
}

/* sim's largest error against held_want at its publications over 160 ticks; restore: a
   snapshot taken at tick 80 restored at tick 100 (then re-run from 80) */
static double held_run(const rt_scene *sc, rt_sim *sim, int restore)
{
    static rt_state snap;
    double worst = 0;
    int restored = 0;
    while (rt_ticks_done(sim) < 160) {
        rt_tick(sc, sim);
        if (rt_bg_pending(sim))
            rt_background(sc, sim);
        uint64_t k = rt_ticks_done(sim);
        if (k % 4 == 0) {
            double e = (double)rt_output(sim, 1, 0) - held_want(k);
            worst = rt_fmax((real_t)worst, (real_t)(e < 0 ? -e : e));
        }
        if (restore && k == 80)
            rt_snapshot(sim, &snap);
        if (restore && k == 100 && !restored)
            restored = rt_restore(sim, &snap) == RT_OK && rt_ticks_done(sim) == 80;
    }
    return restore && !restored ? 1e30 : worst;
}

/* the background set reads a sampled output of a set of the tick (RT_SRC_HELD) as it
   stood at the step's release: inline, and in a context, where the release copies it
   (plan.bg_in), also after a snapshot restored (the context attached anew) */
static void test_bg_held_input(void)
{
    static const rt_conn cn[] = {{0, 0, 1, 0}};
    static const rt_block bl[] = {
        {.name = "Cnt", .kind = &count_kind, .set = 0, .ts = (real_t)0.75},
        {.name = "Int", .kind = &integ_kind, .set = 1},
    };
    static const rt_set sets[] = {
        {.name = "tick", .method = &rt_rk4, .ratio = 1},
        {.name = "bg", .method = &rt_rk4, .ratio = 4, .background = 1},
    };
    const rt_scene sc = {.name = "held_input", .dt = (real_t)0.25, .t_end = 40, .blocks = bl,
                         .nblocks = 2, .conns = cn, .nconns = 1, .sets = sets, .nsets = 2,
                         .bg = &rt_bg};
    int ok = rt_init(&sc, &sims[0]) == RT_OK && rt_init(&sc, &sims[1]) == RT_OK &&
             rt_bg_attach(&sc, &sims[1], &ctx[0]) == RT_OK;
    if (!TH_CHECK(ok))
        return;
    TH_CHECK(rt_input_source(&sims[0], 1, 0, 0) == RT_SRC_HELD);
    double tol = (RT_REAL_IS_FLOAT ? 1e-5 : 1e-12) * held_want(160);
    TH_NEAR(held_run(&sc, &sims[0], 0), 0, tol);
    TH_NEAR(held_run(&sc, &sims[1], 1), 0, tol);
    TH_CHECK(rt_output(&sims[0], 1, 0) == rt_output(&sims[1], 1, 0));
    /* the counter samples inside the background step (every 0.75 s, the step 1 s), which
       holds its value from the release: judged as a hold (RTI_XP_HELD), inline and in a
       context alike */
    th_note("status inline", (double)sims[0].stats.status);
    th_note("status in a context", (double)sims[1].stats.status);
    TH_CHECK(sims[0].stats.status == RT_E_ACCURACY && sims[1].stats.status == RT_E_ACCURACY);
}

/* what the background step counts reaches the tick's statistics at its publication, and
   its outputs published non-finite are counted there, inline and in a context alike: a
   ramp whose output turns NaN for t > 0.3 (counted at each publication from tick 32,
   block Out), and one whose derivative does for t > 0.61 (counted by each step from the
   one released at tick 60, its state kept: block Bad) */
static void test_bg_faults(void)
{
    static const rt_block bl[] = {{.name = "Out", .kind = &nan_out_kind},
                                  {.name = "Bad", .kind = &nan_deriv_kind}};
    static const rt_set set[] = {{.name = "bg", .method = &rt_rk4, .ratio = 4, .background = 1}};
    const rt_scene sc = {.name = "bg_nan", .dt = (real_t)0.01, .t_end = 1, .blocks = bl,
                         .nblocks = 2, .sets = set, .nsets = 1, .bg = &rt_bg};
    int ok = rt_init(&sc, &sims[0]) == RT_OK && rt_init(&sc, &sims[1]) == RT_OK &&
             rt_bg_attach(&sc, &sims[1], &ctx[0]) == RT_OK;
    if (!TH_CHECK(ok))
        return;
    int counted = 1, same = 1;
    for (uint32_t n = 1; n <= 100; n++) {
        for (int i = 0; i < 2; i++)
            rt_tick(&sc, &sims[i]);
        if (rt_bg_pending(&sims[1]))
            rt_background(&sc, &sims[1]);
        if (n % 4)
            continue; /* inline, a step counts at its release; in a context, at publication */
        uint32_t want = (n >= 32 ? (n - 32) / 4 + 1 : 0) + (n >= 64 ? (n - 60) / 4 : 0);
        for (int i = 0; i < 2; i++) {
            const rt_stats *st = rt_stats_of(&sims[i]);
            counted &= st->count[RT_CNT_NAN] == want;
            counted &= want == 0 ? st->status == RT_OK
                                 : st->status == RT_E_NAN && st->first_tick[RT_CNT_NAN] == 32;
        }
        const rt_stats *a = rt_stats_of(&sims[0]), *b = rt_stats_of(&sims[1]);
        same &= a->last_block[RT_CNT_NAN] == b->last_block[RT_CNT_NAN];
        same &= rt_output(&sims[0], 1, 0) == rt_output(&sims[1], 1, 0);
    }
    TH_CHECK(counted && same);
    TH_EQ_U64(rt_stats_of(&sims[1])->count[RT_CNT_NAN], 28);
    TH_CHECK(rt_stats_of(&sims[1])->last_block[RT_CNT_NAN] == 0); /* the publication's */
    TH_NEAR(rt_output(&sims[1], 1, 0), 0.6, RT_REAL_IS_FLOAT ? 1e-5 : 1e-12); /* kept */
}

const th_test th_bg_tests[] = {
    {"bg_same_trace", test_bg_same_trace},
    {"bg_param", test_bg_param},
    {"bg_param_jacobian", test_bg_param_jacobian},
    {"bg_restore", test_bg_restore},
    {"bg_reaction", test_bg_reaction},
    {"bg_deadline", test_bg_deadline},
    {"bg_overrun", test_bg_overrun},
    {"bg_checks", test_bg_checks},
    {"bg_held_signals", test_bg_held_signals},
    {"bg_held_input", test_bg_held_input},
    {"bg_faults", test_bg_faults},
    {0, 0},
};
