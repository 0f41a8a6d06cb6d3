/* test_events.c - tests of rt/step.c's state events: the bouncing ball's impact times
 * against the analytic ones, and the per-step event bound. */
#include "models.h"
#include "scenes/scenes.h"
#include "testutil.h"

/* impact k (0-based) of a ball dropped from h0 with restitution e:
   t_0 = sqrt(2 h0 / g), then each flight lasts 2 e^k v_0 / g with v_0 = g t_0 */
static double impact_time(int k, double h0, double g, double e)
{
    double t = (double)rt_sqrt((real_t)(2 * h0 / g)), v0 = g * t, ek = 1;
    for (int i = 1; i <= k; i++) {
        ek *= e;
        t += 2 * ek * v0 / g;
    }
    return t;
}

static void test_ball_impacts(void)
{
    const rt_scene *sc = &mdl_scene_bouncing_ball;
    if (!tu_init(sc))
        return;
    double tol = RT_REAL_IS_FLOAT ? 2e-4 : 1e-10, worst = 0;
    int seen = 0;
    while (rt_tick(sc, &tu_sim) == RT_OK) {
        int n = (int)tu_sim.state.d[MDL_BALL_D_N];
        if (n == seen)
            continue;
        TH_CHECK(n == seen + 1); /* one impact per step at most at this step size */
        double err = (double)tu_sim.state.d[MDL_BALL_D_T] - impact_time(seen, 1, 9.81, 0.8);
        err = err < 0 ? -err : err;
        worst = err > worst ? err : worst;
        seen = n;
    }
    int expect = 0;
    while (impact_time(expect, 1, 9.81, 0.8) < (double)sc->t_end)
        expect++;
    th_note("impacts", seen);
    th_note("worst impact time error [s]", worst);
    TH_CHECK(expect == 9 && seen == expect);
    TH_CHECK(worst <= tol);
    TH_CHECK(tu_sim.stats.count[RT_CNT_EVENTS] == (uint32_t)expect && tu_sim.stats.status == RT_OK);
    /* the guarded Illinois iteration needs a handful of re-steps, not dozens */
    TH_CHECK(tu_sim.stats.event_iter_max > 0 && tu_sim.stats.event_iter_max <= 8);
}

/* a sawtooth whose root fires every 0.2 ms: five events in a 1 ms step exceed the bound
   of four; the tick still completes and the excess is counted */
static const char *const names[] = {"x"};
static const int8_t rising[] = {1};
static void saw_deriv(const rt_args *a, real_t *xdot) { (void)a, xdot[0] = 1; }
static void saw_out(const rt_args *a, real_t *y) { y[0] = a->x[0]; }
static void saw_roots(const rt_args *a, real_t *r) { r[0] = a->x[0] - (real_t)1e-4; }
static void saw_event(const rt_args *a, uint16_t w, real_t *x, real_t *d)
{
    (void)a, (void)w, (void)d;
    x[0] -= (real_t)2e-4;
}
static const rt_kind saw = {
    .name = "saw", .type = RT_KIND_NSS, .ny = 1, .nx = 1, .nr = 1,
    .y_names = names, .x_names = names, .root_dir = rising, .feed = RT_FEED_NONE,
    .output = saw_out, .deriv = saw_deriv, .roots = saw_roots, .event = saw_event,
};

static void test_event_bound(void)
{
    static const rt_block bl[] = {{.name = "Saw", .kind = &saw}};
    static const rt_set set[] = {{.name = "s", .method = &rt_rk4, .ratio = 1}};
    rt_scene sc = {.name = "saw", .dt = (real_t)1e-3, .t_end = (real_t)0.01, .blocks = bl,
                   .nblocks = 1, .sets = set, .nsets = 1};
    if (!tu_init(&sc))
        return;
    while (rt_tick(&sc, &tu_sim) == RT_OK)
        ;
    TH_CHECK(tu_sim.state.tick == 10);
    TH_CHECK(tu_sim.stats.count[RT_CNT_EVENT_LIMIT] > 0);
    TH_CHECK(tu_sim.stats.status == RT_E_EVENT);
    TH_CHECK(tu_sim.stats.count[RT_CNT_EVENTS] <= 10 * RT_EVENTS_PER_STEP_MAX);
    TH_CHECK(rt_isfinite(tu_sim.state.x[0]));
}

const th_test th_event_tests[] = {
    {"events_ball_impacts", test_ball_impacts},
    {"events_bound", test_event_bound},
    {0, 0},
};
