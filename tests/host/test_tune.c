/* test_tune.c - tests of tools/modrt/tune.c (`modrt tune`): on a two-set linear system
 * with a known solution, the schedule the tuner chooses meets its tolerance when re-run
 * and compared with the exact solution, doubling any set's step would not (so no cheaper
 * candidate was passed over), and the tuner's measured error is the re-run's.
 *
 * Slow set "osc": x'' = -x, x(0) = 1, x'(0) = 0, so x = cos t (RK4). Fast set "lag":
 * T y' = x - y, y(0) = 0, T = 0.05 s, so y = (cos t + T sin t - e^(-t/T)) / (1 + T^2)
 * (RK4; its input x by cubic Hermite from the oscillator's history). Host test: the tuner
 * uses libc. */
#include <math.h>

#include "models.h"
#include "testutil.h"
#include "tune.h"

#define LAG_T 0.05
#define DT (1.0 / 64)

enum { OSC, LAG };

static const real_t osc_p[] = {1};
static const real_t lag_p[] = {1, (real_t)LAG_T};
static const rt_block blocks[] = {
    [OSC] = {.name = "Osc", .kind = &mdl_oscillator_kind, .p = osc_p, .set = 0},
    [LAG] = {.name = "Lag", .kind = &mdl_pt1_kind, .p = lag_p, .set = 1},
};
static const rt_conn conns[] = {{OSC, MDL_OSC_Y_X, LAG, MDL_PT1_U}};
static const rt_set sets[] = {
    {.name = "osc", .method = &rt_rk4, .ratio = 1},
    {.name = "lag", .method = &rt_rk4, .ratio = 1, .interp = RT_INTERP_HERMITE},
};
static const rt_rec recs[] = {{OSC, RT_SIG_Y, MDL_OSC_Y_X}, {LAG, RT_SIG_Y, MDL_PT1_Y}};
static const rt_scene scene = {
    .name = "tune_lin", .doc = "oscillator feeding a lag, two sets", .dt = (real_t)DT,
    .t_end = 8, .blocks = blocks, .nblocks = 2, .conns = conns, .nconns = 1, .sets = sets,
    .nsets = 2, .recs = recs, .nrecs = 2,
};

static double exact(int i, double t)
{
    if (i == 0)
        return cos(t);
    return (cos(t) + LAG_T * sin(t) - exp(-t / LAG_T)) / (1 + LAG_T * LAG_T);
}

/* the scene with ratios r, run to its end: the largest |y - exact| at the ticks where
   both sets are at a communication point */
static double rerun(const uint32_t *r)
{
    rt_set s[2] = {sets[0], sets[1]};
    s[0].ratio = r[0], s[1].ratio = r[1];
    rt_scene sc = scene;
    sc.sets = s;
    if (!tu_init(&sc))
        return 1e300;
    uint32_t sync = r[0] > r[1] ? r[0] : r[1];
    double e = 0;
    while (rt_tick(&sc, &tu_sim) == RT_OK || rt_ticks_done(&tu_sim) == rt_tick_count(&tu_sim)) {
        if (rt_ticks_done(&tu_sim) % sync == 0) {
            double t = (double)rt_time(&sc, &tu_sim);
            for (uint16_t i = 0; i < 2; i++) {
                double d = fabs((double)rt_rec_value(&sc, &tu_sim, i) - exact(i, t));
                e = d > e || d != d ? d : e;
            }
        }
        if (rt_ticks_done(&tu_sim) == rt_tick_count(&tu_sim))
            break;
    }
    /* the tuner measures the error against its reference, so a step's conservative
       estimate above the default accuracy (severity 1) is allowed; nothing worse */
    TH_CHECK(rt_status_severity(rt_stats_of(&tu_sim)->status) < 2);
    return e;
}

static void test_tune_chosen_meets_tol(void)
{
    static tune_result r;
    double tol = RT_REAL_IS_FLOAT ? 1e-3 : 1e-4;
    tune_opts o = {.tol = tol};
    if (!TH_CHECK(tune_scene(&scene, &o, &r, NULL) == RT_OK) || !TH_CHECK(r.found))
        return;
    th_note("chosen ratio osc", r.best.ratio[0]);
    th_note("chosen ratio lag", r.best.ratio[1]);
    th_note("tuner's error against its reference", r.best.err);
    th_note("reference's own error estimate", r.ref_err);
    TH_CHECK(r.best.err <= tol && r.ref_err < tol / 20);
    TH_CHECK(r.nsig == 2 && r.r_min == 1 && r.doublings == 6 && r.ncand == 49);
    TH_CHECK(r.nrun >= 1 && r.nrun <= r.ncand);
    /* re-run independently, against the exact solution */
    double e = rerun(r.best.ratio);
    th_note("re-run error against the exact solution", e);
    TH_CHECK(e <= tol);
    TH_NEAR(e, r.best.err, tol / 100);
    /* cost: derivatives per simulated second, 4 RK4 stages and the end-point derivative
       of its error estimate x states x steps per second, and the coupling monitor's two
       right-hand sides per sensitivity measurement of the faster set's input from the
       slower (every RT_XSET_GAIN_EVERY steps, and near its accuracy: under 1 %) */
    double steps0 = 1 / (DT * r.best.ratio[0]), steps1 = 1 / (DT * r.best.ratio[1]);
    double base = 5 * (2 * steps0 + steps1);
    TH_CHECK(r.best.cost >= base - 1e-9 * base && r.best.cost <= 1.01 * base);
    /* no cheaper neighbour: doubling either step breaks the tolerance */
    for (int s = 0; s < 2; s++) {
        uint32_t d[2] = {r.best.ratio[0], r.best.ratio[1]};
        if (d[s] >= (uint32_t)1 << r.doublings)
            continue;
        d[s] *= 2;
        double ed = rerun(d);
        th_note(s ? "lag step doubled: error" : "osc step doubled: error", ed);
        TH_CHECK(ed > tol / 2);
    }
    /* tune_measure agrees with a re-run too */
    tune_sched m;
    TH_CHECK(tune_measure(&scene, r.best.ratio, &m) == RT_OK);
    TH_CHECK(m.complete && m.clean && m.err == r.best.err);
}

/* a looser tolerance never gives a costlier schedule; --only narrows the comparison */
static void test_tune_options(void)
{
    static tune_result tight, loose, only;
    tune_opts o = {.tol = RT_REAL_IS_FLOAT ? 1e-3 : 1e-4};
    TH_CHECK(tune_scene(&scene, &o, &tight, NULL) == RT_OK);
    o.tol *= 100;
    TH_CHECK(tune_scene(&scene, &o, &loose, NULL) == RT_OK);
    TH_CHECK(tight.found && loose.found && loose.best.cost <= tight.best.cost);
    o.only = "Osc";
    TH_CHECK(tune_scene(&scene, &o, &only, NULL) == RT_OK);
    TH_CHECK(only.nsig == 1 && only.found && only.best.cost <= loose.best.cost);
    o.only = "Nothing";
    TH_CHECK(tune_scene(&scene, &o, &only, NULL) == RT_E_ARG);
    o.only = NULL, o.tol = 0;
    TH_CHECK(tune_scene(&scene, &o, &only, NULL) == RT_E_ARG);
}

const th_test th_tune_tests[] = {
    {"tune_chosen_meets_tol", test_tune_chosen_meets_tol},
    {"tune_options", test_tune_options},
    {0, 0},
};
