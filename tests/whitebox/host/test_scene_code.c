/* test_scene_code.c - the code scenec writes for a library scene (rt_scene_code,
 * tools/scenec/spec.c) against the table-driven path: every library scene that has it
 * runs to its end time twice, once through it and once through a copy of the scene
 * without it; the state, every recorded value (the trace hash) and the fault counters
 * must agree to the bit, and the written code must have done the work (its functions
 * answered, not left every call to the generic path). White-box: includes rt/rt_sim.h
 * for the state. */
#include <string.h>

#include "harness.h"
#include "models.h"
#include "rt_sim.h"
#include "scenes/scenes.h"

static rt_sim a, b;

/* the scene's own table, and how often each of its functions did the work */
static const rt_scene_code *inner;
static unsigned long rhs_done, rhs_calls, proj_done, proj_calls, out_done, out_calls;

static int rhs_counted(const rt_scene *sc, rt_sim *sim, uint8_t set, real_t t, real_t h,
                       real_t *xdot)
{
    int r = inner->rhs(sc, sim, set, t, h, xdot);
    rhs_calls++, rhs_done += (unsigned long)r;
    return r;
}

static int project_counted(const rt_scene *sc, rt_sim *sim, uint8_t set, real_t t)
{
    int r = inner->project(sc, sim, set, t);
    proj_calls++, proj_done += (unsigned long)r;
    return r;
}

static int outputs_counted(const rt_scene *sc, rt_sim *sim, uint8_t set, real_t t, int mode)
{
    int r = inner->outputs(sc, sim, set, t, mode);
    out_calls++, out_done += (unsigned long)r;
    return r;
}

static void run(const rt_scene *sc, rt_sim *sim)
{
    TH_CHECK(rt_init(sc, sim) == RT_OK);
    rt_record(sc, sim, 0);
    while (rt_tick(sc, sim) != RT_E_DONE)
        rt_record(sc, sim, 0);
}

static void test_scene_code_equal(void)
{
    unsigned with_code = 0;
    for (const rt_scene_entry *e = mdl_scenes; e->name; e++) {
        if (!e->scene->code)
            continue;
        with_code++;
        rt_scene_code counted = *e->scene->code;
        rt_scene spec = *e->scene, generic = *e->scene;
        inner = e->scene->code;
        counted.rhs = inner->rhs ? rhs_counted : 0;
        counted.project = inner->project ? project_counted : 0;
        counted.outputs = inner->outputs ? outputs_counted : 0;
        spec.code = &counted;
        generic.code = 0;
        rhs_done = rhs_calls = proj_done = proj_calls = out_done = out_calls = 0;
        run(&spec, &a);
        run(&generic, &b);
        th_note(e->name, (double)rhs_done);
        /* a set the generator leaves out answers 0 (lane_change's vehicle); in
           pendulum10 only the first assembly (M factored) is the generic path's */
        TH_CHECK(rhs_done > 0);
        if (e->scene == &mdl_scene_pendulum10)
            TH_CHECK(rhs_done + 8 >= rhs_calls);
        TH_CHECK(!inner->project || (proj_calls > 0 && proj_done == proj_calls));
        /* every set's outputs at the ticks and in the steps are written out */
        TH_CHECK(inner->outputs && out_calls > 0 && out_done == out_calls);
        TH_CHECK(rt_trace_hash(&a) == rt_trace_hash(&b));
        TH_CHECK(memcmp(a.state.x, b.state.x, sizeof a.state.x) == 0);
        TH_CHECK(memcmp(a.stats.count, b.stats.count, sizeof a.stats.count) == 0);
        TH_CHECK(a.stats.status == b.stats.status);
    }
    /* pendulum10 is one (docs/overhead.md) */
    TH_CHECK(with_code >= 1);
    TH_CHECK(mdl_scene_pendulum10.code != 0);
}

/* a parameter changed mid-run reaches the written-out code: pendulum10's points keep
   M^-1 k of their parameters (RT_MBS_F_PARAM, after M in rt_mbs_work.M) until a parameter
   changes. Gravity and a mass (1.3 kg: its 1/m inexact, rt_mbs_work.im) changed at 1 s:
   the run through the code must follow the generic path's to the bit, and must differ
   from a run without the change */
static void test_scene_code_param(void)
{
    rt_scene generic = mdl_scene_pendulum10;
    const rt_scene *sc = &mdl_scene_pendulum10;
    static rt_sim c;
    generic.code = 0;
    TH_CHECK(rt_init(sc, &a) == RT_OK && rt_init(&generic, &b) == RT_OK &&
             rt_init(sc, &c) == RT_OK);
    for (int k = 0; k < 400; k++) {
        if (k == 200) {
            TH_CHECK(rt_set_param(sc, &a, "B3", "gz", (real_t)-5) == RT_OK);
            TH_CHECK(rt_set_param(&generic, &b, "B3", "gz", (real_t)-5) == RT_OK);
            TH_CHECK(rt_set_param(sc, &a, "B7", "m", (real_t)1.3) == RT_OK);
            TH_CHECK(rt_set_param(&generic, &b, "B7", "m", (real_t)1.3) == RT_OK);
        }
        rt_tick(sc, &a), rt_tick(&generic, &b), rt_tick(sc, &c);
        rt_record(sc, &a, 0), rt_record(&generic, &b, 0), rt_record(sc, &c, 0);
    }
    TH_CHECK(memcmp(a.state.x, b.state.x, sizeof a.state.x) == 0);
    TH_CHECK(rt_trace_hash(&a) == rt_trace_hash(&b));
    TH_CHECK(rt_trace_hash(&a) != rt_trace_hash(&c));
}

/* code compiled with other limits than the runtime reads rt_sim's members at other
   offsets: rt_init refuses it, it never runs (a Cortex-M7 image whose scene .c had the
   default RT_MAX_KSTATE, linked to a runtime library built with RT_MAX_KSTATE=256, ran
   beltgear's code and gave another trace hash than the host) */
static void test_scene_code_layout(void)
{
    rt_scene_code other = *mdl_scene_pendulum10.code;
    rt_scene sc = mdl_scene_pendulum10;
    /* each library scene's code was compiled with this build's limits */
    for (const rt_scene_entry *e = mdl_scenes; e->name; e++)
        TH_CHECK(!e->scene->code || e->scene->code->sim_layout == RT_SIM_LAYOUT);
    sc.code = &other;
    TH_CHECK(rt_init(&sc, &a) == RT_OK);
    other.sim_layout = RT_SIM_LAYOUT ^ 0x100u; /* rt_state 256 bytes longer, say */
    TH_CHECK(rt_init(&sc, &a) == RT_E_SCENE);
    TH_CHECK(strstr(a.err, "scene code compiled with other limits than the runtime") != 0);
}

const th_test th_scene_code_tests[] = {
    {"scene_code_equal", test_scene_code_equal},
    {"scene_code_param", test_scene_code_param},
    {"scene_code_layout", test_scene_code_layout},
    {0, 0},
};
