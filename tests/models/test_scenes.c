/* test_scenes.c - the library scenes against independent answers: the oscillator's
 * closed form, van der Pol's known limit-cycle period, and the sampled PI loop against
 * the exact discretisation of the plant under zero-order hold. */
#include "models.h"
#include "scenes/scenes.h"
#include "testutil.h"

static double absd(double v) { return v < 0 ? -v : v; }

/* x = cos(2 pi t): the worst error over the 10 s run */
static void test_oscillator(void)
{
    const rt_scene *sc = &mdl_scene_oscillator;
    if (!tu_init(sc))
        return;
    double worst = 0;
    for (;;) {
        double t = (double)rt_time(sc, &tu_sim);
        double e = absd((double)tu_y(sc, "Osc", 0) - (double)rt_cos((real_t)(RT_TWO_PI * t)));
        worst = e > worst ? e : worst;
        if (rt_ticks_done(&tu_sim) == rt_tick_count(&tu_sim))
            break;
        rt_tick(sc, &tu_sim);
    }
    th_note("worst |x - cos(2 pi t)|", worst);
    TH_CHECK(rt_ticks_done(&tu_sim) == 10000);
    TH_CHECK(worst < (RT_REAL_IS_FLOAT ? 5e-3 : 2e-9));
}

/* the limit cycle of mu = 1 has period 6.6632868593231 (Strogatz; Hairer-Norsett-Wanner) */
static void test_vanderpol_period(void)
{
    const rt_scene *sc = &mdl_scene_vanderpol;
    if (!tu_init(sc))
        return;
    double prev_x = (double)rt_block_x(&tu_sim, 0, 0), prev_t = 0, ups[4];
    int n = 0;
    while (rt_ticks_done(&tu_sim) < rt_tick_count(&tu_sim)) {
        rt_tick(sc, &tu_sim);
        double t = (double)rt_time(sc, &tu_sim), x = (double)rt_block_x(&tu_sim, 0, 0);
        if (prev_x < 0 && x >= 0 && n < 4) /* upward zero crossing, linearly interpolated */
            ups[n++] = prev_t + (t - prev_t) * (-prev_x) / (x - prev_x);
        prev_x = x, prev_t = t;
    }
    TH_CHECK(n >= 3);
    if (n >= 3) {
        th_note("period [s]", ups[n - 1] - ups[n - 2]);
        TH_NEAR(ups[n - 1] - ups[n - 2], 6.6632868593231, RT_REAL_IS_FLOAT ? 2e-3 : 2e-6);
    }
}

/* with u held over each 10 ms sample, the plant T y' = K u - y is exactly
   y[k+1] = a y[k] + K (1 - a) u[k], a = exp(-Ts / T); the PI law is applied by hand */
static void test_pi_loop(void)
{
    const rt_scene *sc = &mdl_scene_pi_loop;
    if (!tu_init(sc))
        return;
    const double K = 2, T = 0.5, Ts = 0.01, Kp = 0.8, Ki = 3, t0 = 0.1;
    const double a = (double)rt_exp((real_t)(-Ts / T));
    double y = 0, I = 0, worst = 0;
    for (int k = 0; k < 300; k++) {
        real_t tk = (real_t)(10 * k) * sc->dt; /* the sample instant as the runtime has it */
        double r = tk < (real_t)t0 ? 0 : 1, e = r - y, c = Kp * e + I;
        double err = absd((double)tu_y(sc, "Plant", 0) - y);
        worst = err > worst ? err : worst;
        TH_NEAR(tu_y(sc, "PI", 0), c, RT_REAL_IS_FLOAT ? 1e-4 : 1e-9);
        y = a * y + K * (1 - a) * c;
        I = I + Ki * Ts * e;
        tu_run_to(sc, (real_t)(10 * (k + 1)) * sc->dt);
    }
    th_note("worst |y - y_exact| at samples", worst);
    TH_CHECK(worst < (RT_REAL_IS_FLOAT ? 1e-4 : 1e-10));
    /* integral action: no steady-state error at 3 s */
    TH_NEAR(tu_y(sc, "Plant", 0), 1, 1e-3);
}

const th_test th_scene_tests[] = {
    {"scene_oscillator", test_oscillator},
    {"scene_vanderpol_period", test_vanderpol_period},
    {"scene_pi_loop", test_pi_loop},
    {0, 0},
};
