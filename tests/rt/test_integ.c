/* test_integ.c - tests of rt/integ_erk.c: each method's order of convergence on a
 * non-autonomous problem with a known solution, x' = x cos t, x = exp(sin t). */
#include "testutil.h"

static void deriv(const rt_args *a, real_t *xdot) { xdot[0] = a->x[0] * rt_cos(a->t); }
static void output(const rt_args *a, real_t *y) { y[0] = a->x[0]; }
static const char *const names[] = {"x"};
static const real_t x0[] = {1};
static const rt_kind growth = {
    .name = "growth", .type = RT_KIND_NSS, .ny = 1, .nx = 1,
    .y_names = names, .x_names = names, .x_default = x0,
    .feed = RT_FEED_NONE, .output = output, .deriv = deriv,
};

/* |x(T) - exp(sin T)| for method m at step h */
static double error_at(const rt_integrator *m, real_t h, real_t t_end)
{
    static const rt_block blocks[] = {{.name = "G", .kind = &growth}};
    rt_set set = {.name = "s", .method = m, .ratio = 1};
    rt_scene sc = {.name = "growth", .dt = h, .t_end = t_end, .blocks = blocks,
                   .nblocks = 1, .sets = &set, .nsets = 1};
    if (!tu_init(&sc))
        return 1e30;
    while (rt_tick(&sc, &tu_sim) == RT_OK)
        ;
    double e = (double)tu_sim.state.x[0] - (double)rt_exp(rt_sin(rt_time(&sc, &tu_sim)));
    return e < 0 ? -e : e;
}

typedef struct order_case {
    const rt_integrator *m;
    real_t h;       /* coarse step: error well above roundoff, in the asymptotic range */
    real_t h_float; /* the same in single precision; 0: roundoff hides the order there */
} order_case;

static void test_orders(void)
{
    static const order_case cases[] = {
        {&rt_euler, (real_t)0.01, (real_t)0.01}, {&rt_heun, (real_t)0.02, (real_t)0.05},
        {&rt_bs3, (real_t)0.05, (real_t)0.2}, {&rt_rk4, (real_t)0.1, 0},
        {&rt_dopri5, (real_t)0.1, 0},
    };
    for (unsigned i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        const order_case *c = &cases[i];
        real_t h = RT_REAL_IS_FLOAT ? c->h_float : c->h;
        if (h == 0)
            continue;
        double e1 = error_at(c->m, h, 2), e2 = error_at(c->m, h / 2, 2);
        double p = (double)rt_log((real_t)(e1 / e2)) / (double)rt_log(2);
        th_note(c->m->name, p);
        TH_NEAR(p, c->m->order, 0.25);
    }
}

/* the stage count is what a step costs; the registry finds every method */
static void test_registry(void)
{
    TH_CHECK(rt_integrator_find("rk4") == &rt_rk4);
    TH_CHECK(rt_integrator_find("dopri5") == &rt_dopri5);
    TH_CHECK(rt_integrator_find("nope") == 0);
    for (const rt_integrator_entry *e = rt_integrators; e->name; e++)
        TH_CHECK(e->method->stages <= RT_MAX_STAGES && rt_streq(e->name, e->method->name));
}

const th_test th_integ_tests[] = {
    {"integ_orders", test_orders},
    {"integ_registry", test_registry},
    {0, 0},
};
