/* test_renew.c - the tick's renewal of a set's outputs (rt_tick: only the entries that may
 * differ from its step's end evaluation are called again, RTI_RENEW) against a full
 * evaluation: after every tick of every library scene, and of three scenes built for the
 * renewal's conditions, the outputs must be the bits that rt_refresh, which evaluates
 * every entry of every set whose state is at the tick, gives (an actual loop's outputs
 * within its tolerance: its solver re-solves from a new warm start). */
#include "../../models/models.h"
#include "rti.h"
#include "testutil.h"

#define RENEW_TICKS 3000 /* enough for every set's schedule and the samples to repeat */

static real_t before[RT_MAX_Y];
static uint8_t in_loop[RT_MAX_BLOCKS];

/* the outputs of one scene after each tick, renewed and then evaluated in full: the
   number of outputs that differed; *left: entries of renewed sets a renewal leaves out */
static unsigned mismatches(const rt_scene *sc, unsigned *left)
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
        rt_status st = rt_tick(sc, &tu_sim);
        for (uint16_t j = 0; j < ny; j++)
            before[j] = tu_sim.state.y[j];
        rt_refresh(sc, &tu_sim);
        for (uint16_t b = 0; b < sc->nblocks; b++)
            for (uint16_t j = tu_sim.plan.y_off[b]; j < tu_sim.plan.y_off[b + 1]; j++) {
                real_t u = before[j], v = tu_sim.state.y[j];
                int same = u == v || (u != u && v != v);
                int near = in_loop[b] && rt_fabs(u - v) <= (real_t)1e-8 * (1 + rt_fabs(v));
                bad += !same && !near;
            }
        if (st != RT_OK)
            break;
    }
    for (uint8_t s = 0; s < sc->nsets; s++) {
        if (sc->sets[s].ratio != 1 || sc->sets[s].background || !tu_sim.plan.set_xout[s])
            continue; /* not renewed */
        for (uint16_t i = tu_sim.plan.seq_of[s]; i < tu_sim.plan.seq_of[s + 1]; i++)
            *left += !(tu_sim.plan.seq_flags[tu_sim.plan.set_seq[i]] & RTI_SEQ_RENEW);
    }
    return bad;
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
}

const th_test th_renew_tests[] = {{"renew_full", test_renew_full}, {0, 0}};
