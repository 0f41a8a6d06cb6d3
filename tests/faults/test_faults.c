/* test_faults.c - fault injection (`make test-faults`, a build with -DRT_FAULT_INJECT=1;
 * docs/reliability.md). Each case forces one fault into a library scene over a window of
 * ticks: a NaN output of a chosen block, a zero pivot in every LU factorization (the
 * constraint matrix of the multibody solve), an algebraic loop that cannot converge, a
 * Newton iteration that diverges. Each must be counted, reported with its block where it
 * has one, leave the state finite, and let the run (and its trace) go to the end. Deadline
 * overruns and lost packets are injected on the host side (tests/link/link.sh: 1 us
 * ticks, a silent and an evil controller). */
#include "harness.h"
#include "testutil.h"

#include "rti.h"

extern const rt_scene mdl_scene_pi_loop, mdl_scene_pendulum10, mdl_scene_beltgear,
    mdl_scene_vanderpol;

/* runs sc to its end with fault f; checks the trace is complete and the state finite */
static int run_with(const rt_scene *sc, rti_fault f)
{
    rti_fault_plan = (rti_fault){RTI_FAULT_NONE, -1, 0, 0};
    if (!tu_init(sc))
        return 0;
    rti_fault_plan = f;
    real_t vals[RT_MAX_REC];
    uint64_t rows = 0;
    rt_status st;
    do {
        st = rt_tick(sc, &tu_sim);
        rt_record(sc, &tu_sim, vals);
        rows++;
    } while (st == RT_OK);
    rti_fault_plan.kind = RTI_FAULT_NONE;
    TH_CHECK(st == RT_E_DONE && rows == tu_sim.plan.n_ticks);
    int finite = 1;
    for (uint16_t i = 0; i < tu_sim.plan.set_x[sc->nsets]; i++)
        finite = finite && rt_isfinite(tu_sim.state.x[i]);
    for (uint16_t i = 0; i < sc->nrecs; i++)
        finite = finite && rt_isfinite(vals[i]);
    return TH_CHECK(finite);
}

static int16_t block_of(const rt_scene *sc, const char *name)
{
    return (int16_t)rt_block_index(sc, name);
}

/* a NaN output of the plant for one tick: counted with the plant, contained */
static void test_nan_output(void)
{
    const rt_scene *sc = &mdl_scene_pi_loop;
    int16_t b = block_of(sc, "Plant");
    if (!run_with(sc, (rti_fault){RTI_FAULT_NAN, b, 1000, 1001}))
        return;
    th_note("nan counted", tu_sim.stats.count[RT_CNT_NAN]);
    TH_CHECK(tu_sim.stats.count[RT_CNT_NAN] > 0 && tu_sim.stats.last_block[RT_CNT_NAN] == b);
    TH_CHECK(tu_sim.stats.status == RT_E_NAN && tu_sim.stats.first_tick[RT_CNT_NAN] >= 1000);
}

/* every factorization singular for ten ticks of pendulum10: counted with a body of the
   chain, the constraints hold again afterwards */
static void test_singular(void)
{
    const rt_scene *sc = &mdl_scene_pendulum10;
    if (!run_with(sc, (rti_fault){RTI_FAULT_SINGULAR, -1, 500, 510}))
        return;
    th_note("singular counted", tu_sim.stats.count[RT_CNT_SINGULAR]);
    TH_CHECK(tu_sim.stats.count[RT_CNT_SINGULAR] > 0);
    TH_CHECK(tu_sim.stats.last_block[RT_CNT_SINGULAR] >= 0);
    TH_CHECK(rt_status_severity(tu_sim.stats.status) == 2);
}

/* the belt gear's torn loop cannot converge for ten ticks: counted with a loop block */
static void test_loop(void)
{
    const rt_scene *sc = &mdl_scene_beltgear;
    if (!run_with(sc, (rti_fault){RTI_FAULT_LOOP, -1, 100, 110}))
        return;
    th_note("noconv counted", tu_sim.stats.count[RT_CNT_NOCONV]);
    TH_CHECK(tu_sim.stats.count[RT_CNT_NOCONV] > 0 && tu_sim.stats.last_block[RT_CNT_NOCONV] >= 0);
    TH_CHECK(tu_sim.stats.status == RT_E_NOCONV);
}

/* Van der Pol by SDIRK2 with every Newton iteration diverging for ten steps: degraded,
   never left silent, finite */
static void test_newton(void)
{
    rt_scene sc = mdl_scene_vanderpol;
    rt_set set = sc.sets[0];
    set.method = &rt_sdirk2;
    sc.sets = &set, sc.nsets = 1;
    if (!run_with(&sc, (rti_fault){RTI_FAULT_NEWTON, -1, 50, 60}))
        return;
    th_note("degraded counted", tu_sim.stats.count[RT_CNT_DEGRADED]);
    TH_CHECK(tu_sim.stats.count[RT_CNT_DEGRADED] == 10);
    TH_CHECK(tu_sim.stats.status == RT_E_DEGRADED);
}

static const th_test faults[] = {
    {"fault_nan_output", test_nan_output},
    {"fault_singular", test_singular},
    {"fault_loop", test_loop},
    {"fault_newton", test_newton},
    {0, 0},
};

int main(int argc, char **argv)
{
    const th_test *const tables[] = {faults, 0};
    th_run(tables, argc > 1 ? argv[1] : 0);
    return th_summary() ? 1 : 0;
}
