/* test_beltgear.c - the beltgear scene (paper Fig. 6) against the same equations written
 * without an algebraic loop: the belt-inertia coupling solved by hand (Cramer's rule)
 * inside one state-space block; and the loop structure the scene must show. */
#include "models.h"
#include "scenes/scenes.h"
#include "testutil.h"
#include "rt_sim.h" /* white box: reads rt_sim's parts (plan, state, work) */

/* states i (motor current), phi1, w1, phi2, w2; parameters as in models/scenes/beltgear.c */
static void direct_deriv(const rt_args *a, real_t *xd)
{
    const real_t Kc = 10, Tm = (real_t)0.005, kt = (real_t)0.5, ML = (real_t)0.2;
    const real_t J1 = (real_t)0.01, r1 = (real_t)0.05, J2 = (real_t)0.04, r2 = (real_t)0.1;
    const real_t k = (real_t)1e5, c = 20, m = (real_t)0.5;
    const real_t *x = a->x;
    real_t iref = a->t_piece < (real_t)0.01 ? 0 : 2; /* a known time event, as the step's */
    real_t M = kt * x[0];
    real_t E = 2 * (k * (r1 * x[1] - r2 * x[3]) + c * (r1 * x[2] - r2 * x[4]));
    /* J1 a1 = M - r1 (E + m (r1 a1 - r2 a2)), J2 a2 = r2 (E + m (r1 a1 - r2 a2)) - ML */
    real_t a11 = J1 + m * r1 * r1, a12 = -m * r1 * r2, b1 = M - r1 * E;
    real_t a21 = -m * r1 * r2, a22 = J2 + m * r2 * r2, b2 = r2 * E - ML;
    real_t det = a11 * a22 - a12 * a21;
    xd[0] = (Kc * (iref - x[0]) - x[0]) / Tm;
    xd[1] = x[2];
    xd[2] = (b1 * a22 - a12 * b2) / det;
    xd[3] = x[4];
    xd[4] = (a11 * b2 - a21 * b1) / det;
}
static void direct_out(const rt_args *a, real_t *y)
{
    for (int i = 0; i < 5; i++)
        y[i] = a->x[i];
}
/* the command's step at 10 ms: each step ends there, as the scene's step source does */
static real_t direct_next(const rt_args *a)
{
    return a->t < (real_t)0.01 ? (real_t)0.01 : RT_TEV_NEVER;
}
static const char *const dn[] = {"i", "phi1", "w1", "phi2", "w2"};
static const rt_kind direct = {
    .name = "belt_direct", .type = RT_KIND_NSS, .ny = 5, .nx = 5, .y_names = dn,
    .x_names = dn, .feed = RT_FEED_NONE, .output = direct_out, .deriv = direct_deriv,
    .next_event = direct_next,
};

/* the loop-free model, run alongside: returns the worst speed difference */
static rt_sim ref;
static void test_against_direct(void)
{
    const rt_scene *sc = &mdl_scene_beltgear;
    static const rt_block bl[] = {{.name = "D", .kind = &direct}};
    static const rt_set set[] = {{.name = "s", .method = &rt_rk4, .ratio = 1}};
    rt_scene dsc = {.name = "direct", .dt = sc->dt, .t_end = sc->t_end, .blocks = bl,
                    .nblocks = 1, .sets = set, .nsets = 1};
    if (!tu_init(sc) || !TH_CHECK(rt_init(&dsc, &ref) == RT_OK))
        return;
    int r1 = rt_block_index(sc, "R1"), r2 = rt_block_index(sc, "R2");
    double worst = 0, wmax = 0;
    while (rt_tick(sc, &tu_sim) == RT_OK) {
        rt_tick(&dsc, &ref);
        double e1 = (double)tu_sim.state.x[tu_sim.plan.x_off[r1] + 1] - (double)ref.state.x[2];
        double e2 = (double)tu_sim.state.x[tu_sim.plan.x_off[r2] + 1] - (double)ref.state.x[4];
        e1 = e1 < 0 ? -e1 : e1, e2 = e2 < 0 ? -e2 : e2;
        worst = e1 > worst ? e1 : worst;
        worst = e2 > worst ? e2 : worst;
        double w = (double)ref.state.x[2];
        wmax = w > wmax ? w : wmax;
    }
    th_note("worst speed difference [rad/s]", worst);
    th_note("largest drive speed [rad/s]", wmax);
    TH_CHECK(wmax > 1); /* the drive did turn */
    TH_CHECK(worst < (RT_REAL_IS_FLOAT ? 1e-3 : 1e-9) * wmax);
    /* the actual loop was solved in one iteration at every evaluation after the first */
    th_note("most iterations in one solve", rt_stats_of(&tu_sim)->loop_iter_max);
    th_note("solves taking 2 iterations", rt_stats_of(&tu_sim)->loop_hist[2]);
    TH_CHECK(rt_stats_of(&tu_sim)->loop_iter_max == 1 && rt_stats_of(&tu_sim)->loop_hist[1] > 0);
    TH_CHECK(rt_stats_of(&tu_sim)->count[RT_CNT_NOCONV] == 0 && rt_stats_of(&tu_sim)->status == RT_OK);
}

/* one potential loop (the current loop) and one actual loop (the drive train) */
static void test_loop_classes(void)
{
    const rt_scene *sc = &mdl_scene_beltgear;
    if (!tu_init(sc))
        return;
    int potential = -1, actual = -1;
    for (int l = 0; l < tu_sim.plan.nloops; l++)
        *(tu_sim.plan.loops[l].actual ? &actual : &potential) = l;
    TH_CHECK(tu_sim.plan.nloops == 2 && potential >= 0 && actual >= 0);
    if (potential < 0 || actual < 0)
        return;
    const rt_loop *p = &tu_sim.plan.loops[potential], *a = &tu_sim.plan.loops[actual];
    TH_CHECK(p->nblocks == 2 && a->nblocks == 3 && a->ntorn >= 1);
    for (int i = 0; i < a->nblocks; i++) {
        const char *n = sc->blocks[tu_sim.plan.loop_blocks[a->first + i]].name;
        TH_CHECK(rt_streq(n, "P1") || rt_streq(n, "P2") || rt_streq(n, "Belt"));
    }
}

const th_test th_beltgear_tests[] = {
    {"beltgear_against_direct", test_against_direct},
    {"beltgear_loop_classes", test_loop_classes},
    {0, 0},
};
