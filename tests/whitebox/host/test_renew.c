/* test_renew.c - the tick's renewal of a set's outputs (rt_tick: only the entries that may
 * differ from its step's end evaluation are called again, RTI_AT_TICK_RECALL) against a full
 * evaluation: after every tick of every library scene, and of three scenes built for the
 * renewal's conditions (and sets stepping over several ticks), the outputs must be the
 * bits that rt_refresh, which evaluates
 * every entry of every set whose state is at the tick, gives (an actual loop's outputs
 * within its tolerance: its solver re-solves from a new warm start). */
#include "models.h"
#include "rti.h"
#include "scenes/scenes.h"
#include "testutil.h"

#define RENEW_TICKS 3000 /* enough for every set's schedule and the samples to repeat */

static real_t before[RT_MAX_Y];
static uint8_t in_loop[RT_MAX_BLOCKS];

/* the same bits (NaN equal to NaN) */
static int same_bits(real_t u, real_t v)
{
    return u == v || (u != u && v != v);
}

/* outputs [0, ny) of two runs that differ */
static unsigned differing(const rt_sim *a, const rt_sim *b, uint16_t ny)
{
    unsigned n = 0;
    for (uint16_t j = 0; j < ny; j++)
        n += !same_bits(a->state.y[j], b->state.y[j]);
    return n;
}

/* called before tick k (a parameter change), or none */
typedef void (*renew_hook)(const rt_scene *sc, unsigned k);

/* renewed by rt_tick: a set of ratio 1, or stepping over several ticks in the tick, that
   other sets read (its step's end evaluated its outputs) */
static int renewed_set(const rt_scene *sc, uint8_t s)
{
    return !sc->sets[s].background && tu_sim.plan.set_xout[s];
}

/* the outputs of one scene after each tick, renewed and then evaluated in full: the
   number of outputs that differed; *left: entries of renewed sets a renewal leaves out */
static unsigned mismatches_hook(const rt_scene *sc, unsigned *left, renew_hook hook)
{
    unsigned bad = 0;
    if (!tu_init(sc)) {
        th_put(sc->name), th_put(": "), th_put(rt_error_text(&tu_sim)), th_put("\n");
        return 1;
    }
    for (uint16_t b = 0; b < sc->nblocks; b++)
        in_loop[b] = 0;
    for (uint8_t l = 0; l < tu_sim.plan.nloops; l++)
        for (uint16_t i = 0; i < tu_sim.plan.loops[l].nblocks; i++)
            in_loop[tu_sim.plan.loop_blocks[tu_sim.plan.loops[l].first + i]] = 1;
    uint16_t ny = tu_sim.plan.y_off[sc->nblocks];
    for (unsigned k = 0; k < RENEW_TICKS; k++) {
        if (hook)
            hook(sc, k);
        rt_status st = rt_tick(sc, &tu_sim);
        for (uint16_t j = 0; j < ny; j++)
            before[j] = tu_sim.state.y[j];
        rt_refresh(sc, &tu_sim);
        for (uint16_t b = 0; b < sc->nblocks; b++)
            for (uint16_t j = tu_sim.plan.y_off[b]; j < tu_sim.plan.y_off[b + 1]; j++) {
                real_t u = before[j], v = tu_sim.state.y[j];
                int near = in_loop[b] && rt_fabs(u - v) <= (real_t)1e-8 * (1 + rt_fabs(v));
                bad += !same_bits(u, v) && !near;
            }
        if (st != RT_OK)
            break;
    }
    for (uint8_t s = 0; s < sc->nsets; s++) {
        if (!renewed_set(sc, s))
            continue;
        for (uint16_t i = tu_sim.plan.seq_of[s]; i < tu_sim.plan.seq_of[s + 1]; i++)
            *left += !(tu_sim.plan.seq_flags[tu_sim.plan.set_seq[i]] & RTI_SEQ_RECALL);
    }
    return bad;
}

static unsigned mismatches(const rt_scene *sc, unsigned *left)
{
    return mismatches_hook(sc, left, 0);
}

/* another set's history: Gain (set a, stepping first) reads the oscillator of set b,
   which pushes its new point after a's step end evaluation, so a renewal must call Gain
   again, and Gain2 (set a), which reads Gain; Lag (set b) reads Gain, so a pushes */
static const rt_block xset_blocks[] = {
    {.name = "Gain", .kind = &mdl_gain_kind, .set = 0},
    {.name = "Osc", .kind = &mdl_oscillator_kind, .set = 1},
    {.name = "Lag", .kind = &mdl_pt1_kind, .set = 1},
    {.name = "Gain2", .kind = &mdl_gain_kind, .set = 0},
};
static const rt_conn xset_conns[] = {{1, 0, 0, 0}, {0, 0, 2, 0}, {0, 0, 3, 0}};
static const rt_set two_sets[] = {
    {.name = "a", .method = &rt_rk4, .ratio = 1},
    {.name = "b", .method = &rt_rk4, .ratio = 1},
};
static const rt_scene xset_scene = {.name = "xset", .dt = (real_t)0.01, .t_end = 40,
                                    .blocks = xset_blocks, .nblocks = 4, .conns = xset_conns,
                                    .nconns = 3, .sets = two_sets, .nsets = 2};

/* another set's sampled output: set a (stepping first) holds a PI sampled every tick;
   set b's Gain reads it live: the PI's new output comes at the tick's refresh of set a,
   after b's step end evaluation, so a renewal of b must call Gain */
static const real_t pi_p[] = {2, 5};
static const rt_block held_blocks[] = {
    {.name = "Osc", .kind = &mdl_oscillator_kind, .set = 0},
    {.name = "Pi", .kind = &mdl_pi_kind, .p = pi_p, .set = 0, .ts = (real_t)0.01},
    {.name = "Gain", .kind = &mdl_gain_kind, .set = 1},
    {.name = "Lag", .kind = &mdl_pt1_kind, .set = 1},
    {.name = "Lag2", .kind = &mdl_pt1_kind, .set = 0},
};
static const rt_conn held_conns[] = {{0, 0, 1, 0}, {1, 0, 2, 0}, {2, 0, 3, 0}, {3, 0, 4, 0}};
static const rt_default held_defaults[] = {{1, 1, 0}};
static const rt_scene held_scene = {.name = "held", .dt = (real_t)0.01, .t_end = 40,
                                    .blocks = held_blocks, .nblocks = 5, .conns = held_conns,
                                    .nconns = 4, .defaults = held_defaults, .ndefaults = 1,
                                    .sets = two_sets, .nsets = 2};

/* an actual loop reading another set's history: Sum = Osc + Gain, Gain = Sum / 2 in set
   a (stepping first), Osc in set b, which pushes after a's step end: a renewal must solve
   the loop again; Lag (set b) reads Sum, so a pushes */
static const real_t half[] = {(real_t)0.5};
static const rt_block loop_blocks[] = {
    {.name = "Sum", .kind = &mdl_sum_kind, .set = 0},
    {.name = "Gain", .kind = &mdl_gain_kind, .p = half, .set = 0},
    {.name = "Osc", .kind = &mdl_oscillator_kind, .set = 1},
    {.name = "Lag", .kind = &mdl_pt1_kind, .set = 1},
};
static const rt_conn loop_conns[] = {{2, 0, 0, 0}, {1, 0, 0, 1}, {0, 0, 1, 0}, {0, 0, 3, 0}};
static const rt_scene loop_scene = {.name = "loop", .dt = (real_t)0.01, .t_end = 40,
                                    .blocks = loop_blocks, .nblocks = 4, .conns = loop_conns,
                                    .nconns = 4, .sets = two_sets, .nsets = 2,
                                    .loop_solver = &rt_broyden};

/* sets stepping over several ticks in the tick (rt_tick keeps their step's end outputs
   in state.y_end and renews from them when their state reaches the tick): set b (every
   3 ticks, stepping first) holds Osc, read by Gain of set a (every tick), and Gain3,
   which reads Gain's history, so its renewal must call Gain3; Sine (b) is read by set
   a's Gain4: its amplitude changes between b's step and the tick its state reaches,
   so that tick must evaluate b in full (renew_amp) */
static const real_t sine_p[] = {1, 3, 0, 0};
static const rt_block multi_blocks[] = {
    {.name = "Gain", .kind = &mdl_gain_kind, .set = 0},
    {.name = "Osc", .kind = &mdl_oscillator_kind, .set = 1},
    {.name = "Gain3", .kind = &mdl_gain_kind, .set = 1},
    {.name = "Sine", .kind = &mdl_sine_kind, .p = sine_p, .set = 1},
    {.name = "Gain4", .kind = &mdl_gain_kind, .set = 0},
    {.name = "Lag", .kind = &mdl_pt1_kind, .set = 1},
};
static const rt_conn multi_conns[] = {{1, 0, 0, 0}, {0, 0, 2, 0}, {3, 0, 4, 0}, {2, 0, 5, 0}};
static const rt_set multi_sets[] = {
    {.name = "a", .method = &rt_rk4, .ratio = 1},
    {.name = "b", .method = &rt_rk4, .ratio = 3},
};
static const rt_scene multi_scene = {.name = "multi", .dt = (real_t)0.01, .t_end = 40,
                                     .blocks = multi_blocks, .nblocks = 6,
                                     .conns = multi_conns, .nconns = 4, .sets = multi_sets,
                                     .nsets = 2};

static void renew_amp(const rt_scene *sc, unsigned k)
{
    if (k % 3 == 1) /* after b's step, before its state reaches the tick */
        TH_CHECK(rt_set_param(sc, &tu_sim, "Sine", "amp", (real_t)(1 + k % 7)) == RT_OK);
}

/* the renewal of a multi-tick set against its full evaluation (the tick's path when a
   parameter of the set changed, param_changed), run side by side: set b (every 2 ticks) holds
   Osc, read by set a, and a PI sampled every 4 ticks whose output the test writes between
   ticks as the link writes an import (rt_link_apply: d and y), read by GainI (b) and
   GainH (a). The renewal must not put the PI's output from b's step's end back */
static const rt_block mdss_blocks[] = {
    {.name = "Osc", .kind = &mdl_oscillator_kind, .set = 1},
    {.name = "Pi", .kind = &mdl_pi_kind, .p = pi_p, .set = 1, .ts = (real_t)0.04},
    {.name = "GainI", .kind = &mdl_gain_kind, .set = 1},
    {.name = "GainH", .kind = &mdl_gain_kind, .set = 0},
    {.name = "Lag", .kind = &mdl_pt1_kind, .set = 0},
};
static const rt_conn mdss_conns[] = {{0, 0, 1, 0}, {1, 0, 2, 0}, {1, 0, 3, 0}, {0, 0, 4, 0}};
static const rt_set mdss_sets[] = {
    {.name = "a", .method = &rt_rk4, .ratio = 1},
    {.name = "b", .method = &rt_rk4, .ratio = 2},
};
static const rt_scene mdss_scene = {.name = "mdss", .dt = (real_t)0.01, .t_end = 40,
                                    .blocks = mdss_blocks, .nblocks = 5,
                                    .conns = mdss_conns, .nconns = 4,
                                    .defaults = held_defaults, .ndefaults = 1,
                                    .sets = mdss_sets, .nsets = 2};
static rt_sim full_sim;

/* what rt_link_apply does to an import: the PI's discrete state and output := v */
static void write_pi(rt_sim *sim, real_t v)
{
    sim->state.d[sim->plan.d_off[1]] = v;
    sim->state.y[sim->plan.y_off[1]] = v;
}

static void test_renew_multi_vs_full(void)
{
    if (!tu_init(&mdss_scene) || rt_init(&mdss_scene, &full_sim) != RT_OK)
        return;
    TH_CHECK(tu_sim.plan.set_xout[1] > 0); /* b is read: it is renewed */
    unsigned bad = 0;
    uint16_t ny = tu_sim.plan.y_off[mdss_scene.nblocks];
    for (unsigned k = 0; k < RENEW_TICKS; k++) {
        if (k % 4 == 1) { /* mid-step of b, between the PI's samples */
            write_pi(&tu_sim, (real_t)k);
            write_pi(&full_sim, (real_t)k);
        }
        full_sim.state.param_changed[1] = 1; /* its full evaluation */
        rt_tick(&mdss_scene, &tu_sim);
        rt_tick(&mdss_scene, &full_sim);
        bad += differing(&tu_sim, &full_sim, ny);
    }
    TH_CHECK(bad == 0);
}

/* a set with nothing to integrate (the PI sampled alone, as a controller in a set of
   its own) is not stepped: the same bits at every tick as with the PI in set a, and no
   right-hand side evaluated for it */
static const rt_block alone_blocks[] = {
    {.name = "Osc", .kind = &mdl_oscillator_kind, .set = 1},
    {.name = "Pi", .kind = &mdl_pi_kind, .p = pi_p, .set = 0, .ts = (real_t)0.01},
    {.name = "Gain", .kind = &mdl_gain_kind, .set = 2},
    {.name = "Lag", .kind = &mdl_pt1_kind, .set = 2},
    {.name = "Lag2", .kind = &mdl_pt1_kind, .set = 1},
};
/* (the PI's set first, as set a is in held_scene: a set's sampled outputs are refreshed
   with its set, in schedule order, and a later set's throughput reads them then) */
static const rt_set three_sets[] = {
    {.name = "pi", .method = &rt_rk4, .ratio = 1},
    {.name = "a", .method = &rt_rk4, .ratio = 1},
    {.name = "b", .method = &rt_rk4, .ratio = 1},
};
static const rt_scene alone_scene = {.name = "alone", .dt = (real_t)0.01, .t_end = 40,
                                     .blocks = alone_blocks, .nblocks = 5,
                                     .conns = held_conns, .nconns = 4,
                                     .defaults = held_defaults, .ndefaults = 1,
                                     .sets = three_sets, .nsets = 3};
static rt_sim alone_sim;

static void test_static_set(void)
{
    TH_CHECK(rt_init(&alone_scene, &alone_sim) == RT_OK);
    TH_CHECK(alone_sim.plan.set_flags[0] & RTI_SET_NO_STEP);
    TH_CHECK(!(alone_sim.plan.set_flags[1] & RTI_SET_NO_STEP));
    if (!tu_init(&held_scene))
        return;
    unsigned bad = 0;
    uint16_t ny = tu_sim.plan.y_off[held_scene.nblocks];
    for (unsigned k = 0; k < RENEW_TICKS; k++) {
        rt_tick(&held_scene, &tu_sim);
        rt_tick(&alone_scene, &alone_sim);
        bad += differing(&tu_sim, &alone_sim, ny);
    }
    TH_CHECK(bad == 0);
    TH_CHECK(rt_stats_of(&alone_sim)->rhs_evals[0] == 0 && rt_stats_of(&alone_sim)->rhs_evals[1] > 0);
}

static void test_renew_full(void)
{
    unsigned left = 0;
    for (const rt_scene_entry *e = mdl_scenes; e->name; e++) {
        unsigned bad = mismatches(e->scene, &left);
        if (bad)
            th_put(e->name), th_put(": outputs differ from a full evaluation\n");
        TH_CHECK(bad == 0);
    }
    TH_CHECK(left > 0); /* a renewal leaves something out (else it tests nothing) */
    const rt_scene *built[] = {&xset_scene, &held_scene, &loop_scene};
    for (unsigned i = 0; i < 3; i++) {
        left = 0;
        unsigned bad = mismatches(built[i], &left);
        if (bad)
            th_put(built[i]->name), th_put(": outputs differ from a full evaluation\n");
        TH_CHECK(bad == 0 && left > 0);
    }
    TH_CHECK(tu_sim.plan.nloops == 1 && tu_sim.plan.loops[0].actual);
    /* sets over several ticks, with a parameter changed between a step and the tick its
       state reaches (not renewed then: the trace would show the old amplitude) */
    left = 0;
    TH_CHECK(mismatches(&multi_scene, &left) == 0 && left > 0);
    left = 0;
    TH_CHECK(mismatches_hook(&multi_scene, &left, renew_amp) == 0);
}

/* rt_refresh before the first tick judges a changed start as rt_init judges a scene's: a
   point of pendulum10 set 0.5 m off its rods is refused, again on a second call (the
   state as given, not half projected); back on its rods the run starts clean */
static void test_refresh_start(void)
{
    const rt_scene *sc = &mdl_scene_pendulum10;
    int b = rt_block_index(sc, "B3");
    TH_CHECK(rt_init(sc, &tu_sim) == RT_OK && b >= 0);
    TH_CHECK(rt_set_param(sc, &tu_sim, "B3", "x", (real_t)3.5) == RT_OK);
    TH_CHECK(rt_refresh(sc, &tu_sim) == RT_E_INCONSISTENT);
    TH_CHECK(th_has(rt_error_text(&tu_sim), "B3 starts 5.00e-01 m off its constraints"));
    TH_CHECK(rt_block_x(&tu_sim, (uint16_t)b, 0) == (real_t)3.5);
    TH_CHECK(rt_refresh(sc, &tu_sim) == RT_E_INCONSISTENT);
    TH_CHECK(rt_set_param(sc, &tu_sim, "B3", "x", (real_t)3.0) == RT_OK);
    TH_CHECK(rt_refresh(sc, &tu_sim) == RT_OK);
    for (int i = 0; i < 20; i++)
        rt_tick(sc, &tu_sim);
    TH_CHECK(rt_stats_of(&tu_sim)->status == RT_OK &&
             rt_stats_of(&tu_sim)->count[RT_CNT_INIT_MOVED] == 0);
}

const th_test th_renew_tests[] = {
    {"renew_refresh_start", test_refresh_start},
    {"renew_full", test_renew_full},
    {"renew_static_set", test_static_set},
    {"renew_multi_vs_full", test_renew_multi_vs_full},
    {0, 0},
};
