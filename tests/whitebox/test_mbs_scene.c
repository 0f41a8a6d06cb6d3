/* test_mbs_scene.c - the library scene pendulum10 (models/scenes/pendulum10.c) against an
 * independent answer: the positions at t = 2 s of the same chain in minimal coordinates
 * (ten link angles, Lagrange's equations, classic Runge-Kutta at 5e-6 s in long double on
 * the host; halving that step changes no digit shown), and its ten-second run: projected
 * constraints at roundoff, recorded energy and residual named and bounded. */
#include "models.h"
#include "scenes/scenes.h"
#include "testutil.h"
#include "rt_sim.h" /* white box: reads rt_sim's parts (plan, state, work) */

static double absd(double v) { return v < 0 ? -v : v; }

/* (x, z) of B1..B10 at t = 2 s [m] */
static const double ref_2s[10][2] = {
    {-0.436609840360724997451, -0.899650958594599749587},
    {-0.890705126066417981437, -1.79060408390471675834},
    {-1.4112718224208537427, -2.644425092457814307},
    {-1.96974619272956156797, -3.47394686897021683319},
    {-2.62787213626156231604, -4.2268547268453447131},
    {-3.37648675451110546857, -4.8898601215014446059},
    {-4.22735286533642622055, -5.41524270728916652662},
    {-5.20495691374362154597, -5.62569537307855988819},
    {-6.19138675775958562814, -5.78987869389599484234},
    {-7.14490550087434047894, -6.09121240679393487162},
};

/* the scene's default integrator and step meet the 1e-6 m of issue 4 at t = 2 s */
static void test_pendulum10_accuracy(void)
{
    const rt_scene *sc = &mdl_scene_pendulum10;
    if (!tu_init(sc))
        return;
    tu_run_to(sc, 2);
    TH_NEAR(rt_time(sc, &tu_sim), 2, 1e-9);
    double worst = 0;
    for (int b = 0; b < 10; b++) {
        const real_t *y = tu_sim.state.y + tu_sim.plan.y_off[b];
        double e = absd((double)y[0] - ref_2s[b][0]) + absd((double)y[1]) +
                   absd((double)y[2] - ref_2s[b][1]);
        worst = e > worst ? e : worst;
    }
    th_note("dopri5 (the scene's method) at step [s]", (double)sc->dt);
    TH_CHECK(sc->sets[0].method == &rt_dopri5);
    th_note("worst position error at 2 s [m]", worst);
    TH_CHECK(worst < (RT_REAL_IS_FLOAT ? 1e-4 : 1e-6));
}

/* ten seconds: clean status, |g| at roundoff after every step, the records' names */
static void test_pendulum10_run(void)
{
    const rt_scene *sc = &mdl_scene_pendulum10;
    if (!tu_init(sc))
        return;
    TH_CHECK(sc->nrecs == 22);
    TH_CHECK(rt_streq(rt_rec_signal(sc, 0), "x") && rt_streq(rt_rec_signal(sc, 19), "z"));
    TH_CHECK(rt_streq(rt_rec_signal(sc, 20), "energy"));
    TH_CHECK(rt_streq(rt_rec_signal(sc, 21), "residual"));
    TH_CHECK(rt_streq(sc->blocks[sc->recs[19].block].name, "B10"));
    real_t vals[RT_MAX_REC];
    double e0 = (double)rt_rec_value(sc, &tu_sim, 20), de = 0, res = 0;
    for (rt_status st = RT_OK; st == RT_OK;) {
        st = rt_tick(sc, &tu_sim);
        rt_record(sc, &tu_sim, vals);
        de = absd((double)vals[20] - e0) > de ? absd((double)vals[20] - e0) : de;
        res = (double)vals[21] > res ? (double)vals[21] : res;
    }
    th_note("10 s: largest |g| after a step [m]", res);
    th_note("10 s: largest |E - E0| [J]", de);
    th_note("10 s: largest |g| right after a projection [m]", (double)tu_sim.work.mbs.res_max);
    TH_CHECK(rt_ticks_done(&tu_sim) == rt_tick_count(&tu_sim) && rt_stats_of(&tu_sim)->status == RT_OK);
    TH_CHECK(res < (RT_REAL_IS_FLOAT ? 1e-5 : 1e-13));
    /* the chain exchanges some 540 J between potential and kinetic energy */
    TH_CHECK(de < (RT_REAL_IS_FLOAT ? 1e-1 : 5e-3));
    TH_NEAR(e0, 0, 1e-12); /* V = 0 on the line z = 0, at rest */
}

const th_test th_mbs_scene_tests[] = {
    {"mbs_scene_pendulum10_accuracy", test_pendulum10_accuracy},
    {"mbs_scene_pendulum10_run", test_pendulum10_run},
    {0, 0},
};
