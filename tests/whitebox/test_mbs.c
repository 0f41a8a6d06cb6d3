/* test_mbs.c - tests of rt/mbs.c, rt/mbs_asm.c and rt/mbs_project.c with mass points:
 * the single pendulum's period and rod tension, a double pendulum against a
 * minimal-coordinate (angle) formulation written here, drift of energy and constraints
 * with and without the projection (10 s and 10^6 steps), the order of convergence with
 * projection, Baumgarte, redundant and straightened chains (status, never NaN), applied
 * force inputs, and the init checks. */
#include "models.h"
#include "testutil.h"
#include "rt_sim.h" /* white box: reads rt_sim's parts (plan, state, work) */

static double absd(double v) { return v < 0 ? -v : v; }

#define G 9.81

/* ------------------------------------------------------------------ reference */

/* A planar chain of n <= 3 point masses in angles phi_i (from +x towards +z), Lagrange's
   equations: sum_j M_ij phi_j'' = b_i with mu_i = sum_{k >= i} m_k,
   M_ij = l_i l_j mu_max(i,j) cos(phi_i - phi_j),
   b_i = -sum_j l_i l_j mu_max(i,j) sin(phi_i - phi_j) w_j^2 - g mu_i l_i cos phi_i. */
typedef struct chain {
    int n;
    double m[3], l[3];
    double y[6]; /* phi (n), then w (n) */
} chain;

static void chain_rhs(const chain *c, const double *y, double *dy)
{
    int n = c->n;
    double M[3][4], mu[4] = {0, 0, 0, 0};
    for (int i = n - 1; i >= 0; i--)
        mu[i] = mu[i + 1] + c->m[i];
    for (int i = 0; i < n; i++) {
        M[i][n] = -G * mu[i] * c->l[i] * (double)rt_cos((real_t)y[i]);
        for (int j = 0; j < n; j++) {
            double f = c->l[i] * c->l[j] * mu[i > j ? i : j];
            double d = y[i] - y[j];
            M[i][j] = f * (double)rt_cos((real_t)d);
            M[i][n] -= f * (double)rt_sin((real_t)d) * y[n + j] * y[n + j];
        }
    }
    for (int k = 0; k < n; k++) /* M is positive definite: no pivoting needed */
        for (int i = k + 1; i < n; i++) {
            double f = M[i][k] / M[k][k];
            for (int j = k; j <= n; j++)
                M[i][j] -= f * M[k][j];
        }
    for (int i = n - 1; i >= 0; i--) {
        double s = M[i][n];
        for (int j = i + 1; j < n; j++)
            s -= M[i][j] * dy[n + j];
        dy[n + i] = s / M[i][i];
    }
    for (int i = 0; i < n; i++)
        dy[i] = y[n + i];
}

/* advances the chain by time dt in k classic Runge-Kutta steps */
static void chain_advance(chain *c, double dt, int k)
{
    double h = dt / k, s[4][6], t[6];
    int m = 2 * c->n;
    for (int step = 0; step < k; step++) {
        for (int st = 0; st < 4; st++) {
            double a = st == 0 ? 0 : st == 3 ? h : h / 2;
            for (int i = 0; i < m; i++)
                t[i] = c->y[i] + (st ? a * s[st - 1][i] : 0);
            chain_rhs(c, t, s[st]);
        }
        for (int i = 0; i < m; i++)
            c->y[i] += h / 6 * (s[0][i] + 2 * s[1][i] + 2 * s[2][i] + s[3][i]);
    }
}

/* position (x, z) of mass i */
static void chain_pos(const chain *c, int i, double *x, double *z)
{
    *x = *z = 0;
    for (int k = 0; k <= i; k++) {
        *x += c->l[k] * (double)rt_cos((real_t)c->y[k]);
        *z += c->l[k] * (double)rt_sin((real_t)c->y[k]);
    }
}

/* ------------------------------------------------------------------ scenes */

static const real_t one[] = {1};
static const real_t horizontal[6] = {1, 0, 0, 0, 0, 0};
static const rt_block p1_blocks[] = {
    {.name = "P", .kind = &mdl_mbs_point_kind, .x0 = horizontal},
};
static const rt_joint p1_joints[] = {
    {.name = "rod", .kind = &rt_joint_sphdiff, .b1 = 0, .b2 = -1, .p = one},
    {.name = "rod2", .kind = &rt_joint_sphdiff, .b1 = 0, .b2 = -1, .p = one},
};
static const rt_rec p1_recs[] = {
    {0, RT_SIG_Y, 0}, {0, RT_SIG_Y, 2},
    {0, RT_SIG_MBS, RT_MBS_SIG_ENERGY}, {0, RT_SIG_MBS, RT_MBS_SIG_RESIDUAL},
    {0, RT_SIG_MBS, RT_MBS_SIG_RESIDUAL_V},
    {0, RT_SIG_MBS, RT_MBS_SIG_JOINT_AT(0, RT_MBS_JSIG_LAMBDA)},
    {0, RT_SIG_MBS, RT_MBS_SIG_JOINT_AT(0, RT_MBS_JSIG_FZ)},
};
enum { REC_X, REC_Z, REC_E, REC_RES, REC_RESV, REC_LAMBDA, REC_FZ, NREC };

static rt_set one_set;

/* the single pendulum of l = 1 m released horizontally; njoints = 2 doubles the rod */
static rt_scene pendulum(const rt_integrator *m, real_t h, real_t t_end, uint8_t stab,
                         uint16_t njoints)
{
    one_set = (rt_set){.name = "mbs", .method = m, .ratio = 1};
    return (rt_scene){.name = "pendulum", .dt = h, .t_end = t_end,
                      .blocks = p1_blocks, .nblocks = 1, .sets = &one_set, .nsets = 1,
                      .recs = p1_recs, .nrecs = NREC, .joints = p1_joints,
                      .njoints = njoints, .mbs = &rt_mbs, .stab = stab};
}

/* energy per unit mass and rod residuals of the single pendulum, from the state alone */
static double p1_energy(const real_t *x)
{
    double v2 = (double)x[3] * x[3] + (double)x[4] * x[4] + (double)x[5] * x[5];
    return 0.5 * v2 + G * (double)x[2];
}
static double p1_residual(const real_t *x)
{
    double r = (double)x[0] * x[0] + (double)x[1] * x[1] + (double)x[2] * x[2];
    return (double)rt_sqrt((real_t)r) - 1;
}

/* ------------------------------------------------------------------ single pendulum */

/* x(t) crosses zero at T/4, 3T/4, ...: each crossing is located on the cubic Hermite
   interpolant of (x, vx) between ticks, so the period error is the integrator's */
static double hermite_root(double x0, double x1, double v0, double v1, double h)
{
    double s = x0 / (x0 - x1);
    for (int it = 0; it < 20; it++) {
        double h00 = (1 + 2 * s) * (1 - s) * (1 - s), h10 = s * (1 - s) * (1 - s);
        double h01 = s * s * (3 - 2 * s), h11 = s * s * (s - 1);
        double p = h00 * x0 + h10 * h * v0 + h01 * x1 + h11 * h * v1;
        double dp = 6 * s * (s - 1) * (x0 - x1) + (1 - 4 * s + 3 * s * s) * h * v0 +
                    (3 * s * s - 2 * s) * h * v1;
        s -= p / dp;
    }
    return s * h;
}

static void test_period(void)
{
    rt_scene sc = pendulum(&rt_rk4, (real_t)1e-3, (real_t)5, RT_STAB_PROJECT, 1);
    if (!tu_init(&sc))
        return;
    double cross[8] = {0}, vmax = 0, tens = 0;
    int n = 0;
    const real_t *x = tu_sim.state.x;
    while (rt_ticks_done(&tu_sim) < rt_tick_count(&tu_sim)) {
        double t0 = (double)rt_time(&sc, &tu_sim), x0 = (double)x[0], v0 = (double)x[3];
        rt_tick(&sc, &tu_sim);
        double h = (double)rt_time(&sc, &tu_sim) - t0;
        if (((x0 > 0) != (x[0] > 0)) && n < 8)
            cross[n++] = t0 + hermite_root(x0, (double)x[0], v0, (double)x[3], h);
        double v = (double)rt_sqrt(x[3] * x[3] + x[4] * x[4] + x[5] * x[5]);
        vmax = v > vmax ? v : vmax;
        /* rod tension of a pendulum released horizontally: 3 m g cos(theta) = -3 m g z */
        double e = absd((double)rt_rec_value(&sc, &tu_sim, REC_LAMBDA) + 3 * G * (double)x[2]);
        tens = e > tens ? e : tens;
    }
    TH_CHECK(n == 4);
    double period = 2 * (cross[n - 1] - cross[0]) / (n - 1);
    th_note("period [s]", period);
    th_note("period error [s]", period - 2.367841948);
    th_note("worst |lambda - 3 m g cos theta| [N]", tens);
    TH_NEAR(period, 2.367841948, RT_REAL_IS_FLOAT ? 2e-4 : 2e-9);
    /* speed at the bottom sqrt(2 g l), sampled within half a tick of it */
    TH_NEAR(vmax, 4.429446918, RT_REAL_IS_FLOAT ? 1e-4 : 1e-5);
    TH_CHECK(tens < (RT_REAL_IS_FLOAT ? 2e-3 : 1e-8));
    TH_CHECK(rt_stats_of(&tu_sim)->status == RT_OK);
}

/* the redundant rod: W M^-1 W^T is singular with a rank deficit of one; the dependent
   row is dropped, found consistent (counted redundant, status ok, named at init) and the
   motion is the single rod's */
static void test_redundant(void)
{
    real_t ref[6];
    rt_scene sc = pendulum(&rt_rk4, (real_t)1e-3, 1, RT_STAB_PROJECT, 1);
    if (!tu_init(&sc))
        return;
    tu_run_to(&sc, 1);
    for (int i = 0; i < 6; i++)
        ref[i] = tu_sim.state.x[i];
    sc = pendulum(&rt_rk4, (real_t)1e-3, 1, RT_STAB_PROJECT, 2);
    if (!tu_init(&sc))
        return;
    TH_CHECK(th_has(rt_error_text(&tu_sim), "rod2 repeats constraints of rod"));
    tu_run_to(&sc, 1);
    double d = 0;
    for (int i = 0; i < 6; i++)
        d = absd((double)(tu_sim.state.x[i] - ref[i])) > d ? absd((double)(tu_sim.state.x[i] - ref[i])) : d;
    th_note("redundant rod: redundant counted", rt_stats_of(&tu_sim)->count[RT_CNT_REDUNDANT]);
    th_note("redundant rod: |x - x_single|", d);
    TH_CHECK(rt_stats_of(&tu_sim)->count[RT_CNT_SINGULAR] == 0 && rt_stats_of(&tu_sim)->status == RT_OK);
    TH_CHECK(rt_stats_of(&tu_sim)->count[RT_CNT_REDUNDANT] == 1 &&
             rt_stats_of(&tu_sim)->last_block[RT_CNT_REDUNDANT] == 0 &&
             rt_stats_of(&tu_sim)->first_tick[RT_CNT_REDUNDANT] == 0);
    TH_CHECK(rt_stats_of(&tu_sim)->count[RT_CNT_NAN] == 0 && rt_stats_of(&tu_sim)->count[RT_CNT_DEGRADED] == 0);
    TH_CHECK(d < (RT_REAL_IS_FLOAT ? 1e-4 : 1e-12));
}

/* two rods of different lengths from one anchor: the rows depend on each other and ask
   for different positions; refused at init naming both joints */
static void test_conflict(void)
{
    static const real_t longer[] = {(real_t)1.5};
    static const rt_joint joints[] = {
        {.name = "rod", .kind = &rt_joint_sphdiff, .b1 = 0, .b2 = -1, .p = one},
        {.name = "rod15", .kind = &rt_joint_sphdiff, .b1 = 0, .b2 = -1, .p = longer},
    };
    rt_scene sc = pendulum(&rt_rk4, (real_t)1e-3, 1, RT_STAB_PROJECT, 2);
    sc.joints = joints;
    TH_CHECK(rt_init(&sc, &tu_sim) == RT_E_INCONSISTENT);
    th_put("  conflict: ");
    th_put(rt_error_text(&tu_sim));
    th_put("\n");
    TH_CHECK(th_has(rt_error_text(&tu_sim), "joints rod15 and rod constrain the same motion"));
}

/* an initial state off its rod: moved and reported (counted with the block, the distance
   in the text) when within RT_INIT_TOL, refused beyond it */
static void test_init_moved(void)
{
    static real_t off[6] = {0, 0, 0, 0, 0, 0};
    static rt_block blocks[1];
    blocks[0] = p1_blocks[0], blocks[0].x0 = off;
    rt_scene sc = pendulum(&rt_rk4, (real_t)1e-3, 1, RT_STAB_PROJECT, 1);
    sc.blocks = blocks;
    off[0] = (real_t)1.0005;
    if (!tu_init(&sc))
        return;
    th_put("  moved: ");
    th_put(rt_error_text(&tu_sim));
    th_put("\n");
    TH_CHECK(rt_stats_of(&tu_sim)->count[RT_CNT_INIT_MOVED] == 1 &&
             rt_stats_of(&tu_sim)->last_block[RT_CNT_INIT_MOVED] == 0 && rt_stats_of(&tu_sim)->status == RT_OK);
    TH_CHECK(th_has(rt_error_text(&tu_sim), "P moved 5.00e-04 m"));
    TH_NEAR(tu_sim.state.x[0], 1, RT_REAL_IS_FLOAT ? 1e-6 : 1e-15);
    /* the same off the rod without projection: moved too (index 1 needs it) */
    sc.stab = RT_STAB_NONE;
    if (!tu_init(&sc))
        return;
    TH_CHECK(rt_stats_of(&tu_sim)->count[RT_CNT_INIT_MOVED] == 1);
    TH_NEAR(tu_sim.state.x[0], 1, RT_REAL_IS_FLOAT ? 1e-6 : 1e-15);
    /* 2 cm off: a set-up mistake */
    sc.stab = RT_STAB_PROJECT;
    off[0] = (real_t)1.02;
    TH_CHECK(rt_init(&sc, &tu_sim) == RT_E_INCONSISTENT);
    th_put("  refused: ");
    th_put(rt_error_text(&tu_sim));
    th_put("\n");
    TH_CHECK(th_has(rt_error_text(&tu_sim), "P starts 2.00e-02 m off its constraints (rod"));
    /* on the rod: nothing to report */
    off[0] = 1;
    if (!tu_init(&sc))
        return;
    TH_CHECK(rt_stats_of(&tu_sim)->count[RT_CNT_INIT_MOVED] == 0 && rt_error_text(&tu_sim)[0] == 0);
}

/* ------------------------------------------------------------------ drift */

typedef struct drift {
    double res, resv, energy; /* largest |g|, |g'|, |E - E0| over the run */
} drift;

/* prints a run's largest residuals and energy error, prefixed by label */
static void note_drift(const char *label, const drift *d)
{
    th_put("  ");
    th_put(label);
    th_put(" |g| ");
    th_put_real(d->res);
    th_put(", |g'| ");
    th_put_real(d->resv);
    th_put(", |E - E0| [J/kg] ");
    th_put_real(d->energy);
    th_put("\n");
}

static drift run_drift(const rt_scene *sc, uint64_t steps)
{
    drift d = {0, 0, 0};
    if (!tu_init(sc))
        return (drift){1, 1, 1};
    double e0 = p1_energy(tu_sim.state.x);
    for (uint64_t k = 0; k < steps; k++) {
        rt_tick(sc, &tu_sim);
        if (k % 64 != 63 && k + 1 != steps)
            continue;
        const real_t *x = tu_sim.state.x;
        double rv = (double)(x[0] * x[3] + x[1] * x[4] + x[2] * x[5]);
        d.res = rt_fmax((real_t)d.res, (real_t)absd(p1_residual(x)));
        d.resv = rt_fmax((real_t)d.resv, (real_t)absd(rv));
        d.energy = rt_fmax((real_t)d.energy, (real_t)absd(p1_energy(x) - e0));
    }
    return d;
}

/* 10 s of the single pendulum: the projection holds the constraints at roundoff, the
   energy error is the integrator's; without it the rod visibly stretches */
static void test_drift_10s(void)
{
    rt_scene sc = pendulum(&rt_rk4, (real_t)1e-3, 10, RT_STAB_PROJECT, 1);
    drift on = run_drift(&sc, 10000);
    TH_CHECK(tu_sim.work.mbs.projections == 10001); /* every step, and the initial state */
    sc.stab = RT_STAB_NONE;
    drift off = run_drift(&sc, 10000);
    sc.stab = RT_STAB_BAUMGARTE;
    sc.baumgarte[0] = 20, sc.baumgarte[1] = 100;
    drift baum = run_drift(&sc, 10000);
    /* alpha = beta = 0 would be no stabilization under Baumgarte's name: refused */
    rt_scene zero = sc;
    zero.baumgarte[0] = zero.baumgarte[1] = 0;
    TH_CHECK(rt_init(&zero, &tu_sim) == RT_E_SCENE);
    note_drift("10 s, projection:   ", &on);
    note_drift("10 s, no projection:", &off);
    th_note("10 s, Baumgarte 20/100: |g|", baum.res);
    double eps = RT_REAL_IS_FLOAT ? 1e-6 : 1e-15;
    TH_CHECK(on.res < 4 * eps && on.resv < 40 * eps);
    TH_CHECK(off.res > 100 * on.res && off.resv > (RT_REAL_IS_FLOAT ? 10 : 100) * on.resv);
    TH_CHECK(baum.res < off.res);
    if (!RT_REAL_IS_FLOAT)
        TH_CHECK(on.energy < 1e-9 && off.energy > 100 * on.energy && off.res > 1e-10);
}

#ifndef TEST_MBS_LONG_STEPS
/* the host's builds run the full 10^6 steps (about 2 s at -O2); sanitized builds (ten
   times slower) and the images under QEMU (TU_FULL 0) a shorter run that still shows the
   drift */
#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define TEST_MBS_SANITIZED 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__) || defined(TEST_MBS_SANITIZED)
#define TEST_MBS_LONG_STEPS 50000
#elif TU_FULL
#define TEST_MBS_LONG_STEPS 1000000
#else
#define TEST_MBS_LONG_STEPS 20000
#endif
#endif

/* 10^6 steps of 10 ms (10^4 s, some 4200 periods): with projection |g| and |g'| stay at
   roundoff and the energy error is dopri5's truncation error alone; without, the rod
   stretches by millimetres and the energy error is hundreds of times larger (ten to
   twenty times in the shorter runs) */
static void test_drift_long(void)
{
    real_t h = (real_t)0.01;
    rt_scene sc = pendulum(&rt_dopri5, h, h * (real_t)TEST_MBS_LONG_STEPS, RT_STAB_PROJECT, 1);
    drift on = run_drift(&sc, TEST_MBS_LONG_STEPS);
    TH_CHECK(rt_stats_of(&tu_sim)->count[RT_CNT_DEGRADED] == 0 && rt_stats_of(&tu_sim)->status == RT_OK);
    sc.stab = RT_STAB_NONE;
    drift off = run_drift(&sc, TEST_MBS_LONG_STEPS);
    th_note("steps", TEST_MBS_LONG_STEPS);
    note_drift("projection:   ", &on);
    note_drift("no projection:", &off);
    double eps = RT_REAL_IS_FLOAT ? 1e-6 : 1e-15;
    TH_CHECK(on.res < 4 * eps && on.resv < 40 * eps);
    TH_CHECK(off.res > 1e5 * eps && off.energy > 5 * on.energy);
}

/* ------------------------------------------------------------------ double pendulum */

static const real_t len2[] = {(real_t)0.7};
static const real_t p2_param[] = {(real_t)0.5, 0, 0, (real_t)-9.81};
static const real_t dp_x1[6] = {1, 0, 0, 0, 0, 0};
static const real_t dp_x2[6] = {1, 0, (real_t)0.7, 0, 0, 0};
static const rt_block dp_blocks[] = {
    {.name = "P1", .kind = &mdl_mbs_point_kind, .x0 = dp_x1},
    {.name = "P2", .kind = &mdl_mbs_point_kind, .x0 = dp_x2, .p = p2_param},
};
static const rt_joint dp_joints[] = {
    {.name = "rod1", .kind = &rt_joint_sphdiff, .b1 = 0, .b2 = -1, .p = one},
    {.name = "rod2", .kind = &rt_joint_sphdiff, .b1 = 1, .b2 = 0, .p = len2},
};
/* the same as one module: a dumbbell with its rod as an internal constraint */
static const real_t db_param[] = {1, (real_t)0.5, (real_t)0.7, 0, 0, (real_t)-9.81};
static const real_t db_x0[12] = {1, 0, 0, 1, 0, (real_t)0.7, 0, 0, 0, 0, 0, 0};
static const rt_block db_blocks[] = {
    {.name = "D", .kind = &mdl_mbs_dumbbell_kind, .x0 = db_x0, .p = db_param},
};
static const rt_joint db_joints[] = {
    {.name = "rod1", .kind = &rt_joint_sphdiff, .b1 = 0, .b2 = -1, .p = one},
};

static rt_scene double_pendulum(const rt_integrator *m, real_t h, real_t t_end, int dumbbell)
{
    one_set = (rt_set){.name = "mbs", .method = m, .ratio = 1};
    rt_scene sc = {.name = "double", .dt = h, .t_end = t_end, .sets = &one_set, .nsets = 1,
                   .mbs = &rt_mbs, .stab = RT_STAB_PROJECT};
    sc.blocks = dumbbell ? db_blocks : dp_blocks;
    sc.nblocks = dumbbell ? 1 : 2;
    sc.joints = dumbbell ? db_joints : dp_joints;
    sc.njoints = dumbbell ? 1 : 2;
    return sc;
}

static chain double_chain(void)
{
    return (chain){2, {1, 0.5, 0}, {1, 0.7, 0}, {0, RT_HALF_PI, 0, 0, 0, 0}};
}

/* positions of both masses (x, y, z each) from the runtime's state */
static void dp_positions(int dumbbell, double *p)
{
    for (int i = 0; i < 3; i++) {
        p[i] = (double)tu_sim.state.x[i];
        p[3 + i] = (double)tu_sim.state.x[dumbbell ? 3 + i : 6 + i];
    }
}

/* largest position difference against the angle formulation, sampled every 0.1 s; the
   reference takes steps of 2e-4 s (its error, some 1e-12 m, is far below what is compared) */
static double dp_compare(const rt_integrator *m, real_t h, real_t t_end, int dumbbell)
{
    rt_scene sc = double_pendulum(m, h, t_end, dumbbell);
    chain c = double_chain();
    if (!tu_init(&sc))
        return 1;
    double worst = 0;
    for (int k = 1; k <= (int)(t_end * 10 + (real_t)0.5); k++) {
        tu_run_to(&sc, (real_t)k / 10);
        chain_advance(&c, 0.1, 500);
        double p[6], x, z;
        dp_positions(dumbbell, p);
        for (int i = 0; i < 2; i++) {
            chain_pos(&c, i, &x, &z);
            double e = absd(p[3 * i] - x) + absd(p[3 * i + 1]) + absd(p[3 * i + 2] - z);
            worst = e > worst ? e : worst;
        }
    }
    return worst;
}

static void test_double_pendulum(void)
{
    double e2 = dp_compare(&rt_rk4, (real_t)5e-4, 3, 0);
    double e1 = dp_compare(&rt_rk4, (real_t)5e-4, 3, 1);
    th_note("double pendulum, two blocks: worst position error over 3 s [m]", e2);
    th_note("double pendulum, one dumbbell block: worst position error [m]", e1);
    double tol = RT_REAL_IS_FLOAT ? 2e-3 : 1e-8;
    TH_CHECK(e2 < tol && e1 < tol);
    TH_CHECK(rt_stats_of(&tu_sim)->status == RT_OK);
}

/* the order of each method survives the projection (double pendulum, largest error over
   1 s); steps in the asymptotic range, where halving them gives the ratio 2^p */
static void test_order(void)
{
    static const struct {
        const rt_integrator *m;
        real_t h;
    } cases[] = {
        {&rt_euler, (real_t)1e-3}, {&rt_heun, (real_t)0.01}, {&rt_bs3, (real_t)0.01},
        {&rt_rk4, (real_t)0.005}, {&rt_dopri5, (real_t)0.005},
    };
    for (unsigned i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        if (RT_REAL_IS_FLOAT && cases[i].m->order > 2)
            continue; /* single precision roundoff hides the higher orders */
        double a = dp_compare(cases[i].m, cases[i].h, 1, 0);
        double b = dp_compare(cases[i].m, cases[i].h / 2, 1, 0);
        double p = (double)rt_log((real_t)(a / b)) / (double)rt_log(2);
        th_note(cases[i].m->name, p);
        TH_NEAR(p, cases[i].m->order, 0.3);
    }
}

/* ------------------------------------------------------------------ singular chains */

/* two links between anchors 3 m apart, pulled straight: W M^-1 W^T has rank 2 of 3 */
static const real_t straight_x1[6] = {1, 0, 0, 0, 0, 0};
static const real_t straight_x2[6] = {2, 0, 0, 0, 0, 0};
static const real_t far_anchor[3] = {3, 0, 0};
static const rt_block straight_blocks[] = {
    {.name = "P1", .kind = &mdl_mbs_point_kind, .x0 = straight_x1},
    {.name = "P2", .kind = &mdl_mbs_point_kind, .x0 = straight_x2},
};
static const rt_joint straight_joints[] = {
    {.name = "left", .kind = &rt_joint_sphdiff, .b1 = 0, .b2 = -1, .p = one},
    {.name = "mid", .kind = &rt_joint_sphdiff, .b1 = 1, .b2 = 0, .p = one},
    {.name = "right", .kind = &rt_joint_sphdiff, .b1 = 1, .b2 = -1, .p = one,
     .at = far_anchor},
};

static void test_straight_chain(void)
{
    rt_set set = {.name = "mbs", .method = &rt_rk4, .ratio = 1};
    rt_scene sc = {.name = "straight", .dt = (real_t)1e-3, .t_end = (real_t)0.5,
                   .blocks = straight_blocks, .nblocks = 2, .sets = &set, .nsets = 1,
                   .joints = straight_joints, .njoints = 3, .mbs = &rt_mbs};
    for (int stab = RT_STAB_PROJECT; stab <= RT_STAB_NONE; stab++) {
        sc.stab = (uint8_t)stab;
        if (!tu_init(&sc))
            return;
        while (rt_tick(&sc, &tu_sim) == RT_OK)
            ;
        int finite = 1;
        for (int i = 0; i < 12; i++)
            finite = finite && rt_isfinite(tu_sim.state.x[i]);
        th_note("straightened chain: singular solves", rt_stats_of(&tu_sim)->count[RT_CNT_SINGULAR]);
        TH_CHECK(rt_ticks_done(&tu_sim) == 500 && finite && rt_stats_of(&tu_sim)->count[RT_CNT_NAN] == 0);
        TH_CHECK(rt_stats_of(&tu_sim)->count[RT_CNT_SINGULAR] > 0 && rt_stats_of(&tu_sim)->status == RT_E_SINGULAR);
        TH_CHECK(rt_stats_of(&tu_sim)->last_block[RT_CNT_SINGULAR] >= 0);
    }
}

/* ------------------------------------------------------------------ inputs and signals */

/* gravity applied as an input force (mbs_pointf, g = 0) gives the same motion */
static void test_force_input(void)
{
    static const real_t no_g[] = {1, 0, 0, 0};
    static const rt_block blocks[] = {
        {.name = "P", .kind = &mdl_mbs_pointf_kind, .x0 = horizontal, .p = no_g},
    };
    static const rt_default defs[] = {{0, 0, 0}, {0, 1, 0}, {0, 2, (real_t)-9.81}};
    real_t ref[6];
    rt_scene sc = pendulum(&rt_rk4, (real_t)1e-3, 1, RT_STAB_PROJECT, 1);
    if (!tu_init(&sc))
        return;
    tu_run_to(&sc, 1);
    for (int i = 0; i < 6; i++)
        ref[i] = tu_sim.state.x[i];
    sc.blocks = blocks;
    sc.defaults = defs, sc.ndefaults = 3;
    if (!tu_init(&sc))
        return;
    tu_run_to(&sc, 1);
    for (int i = 0; i < 6; i++)
        TH_NEAR(tu_sim.state.x[i], ref[i], RT_REAL_IS_FLOAT ? 1e-5 : 1e-13);
}

/* the recorded MBS signals: names, and values that agree with the state */
static void test_signals(void)
{
    rt_scene sc = pendulum(&rt_rk4, (real_t)1e-3, 1, RT_STAB_NONE, 1);
    if (!tu_init(&sc))
        return;
    tu_run_to(&sc, (real_t)0.5);
    TH_CHECK(rt_streq(rt_rec_signal(&sc, REC_E), "energy"));
    TH_CHECK(rt_streq(rt_rec_signal(&sc, REC_RES), "residual"));
    TH_CHECK(rt_streq(rt_rec_signal(&sc, REC_LAMBDA), "lambda1"));
    TH_CHECK(rt_streq(rt_rec_signal(&sc, REC_FZ), "fz"));
    const real_t *x = tu_sim.state.x;
    double tol = RT_REAL_IS_FLOAT ? 1e-5 : 1e-13;
    TH_NEAR(rt_rec_value(&sc, &tu_sim, REC_E), p1_energy(x), tol);
    TH_NEAR(rt_rec_value(&sc, &tu_sim, REC_RES), absd(p1_residual(x)), tol);
    /* the rod pulls the mass towards the anchor: fz = -lambda z / |r| */
    double lam = (double)rt_rec_value(&sc, &tu_sim, REC_LAMBDA);
    TH_CHECK(lam > 0);
    TH_NEAR(rt_rec_value(&sc, &tu_sim, REC_FZ), -lam * (double)x[2] / (1 + p1_residual(x)),
            10 * tol);
    /* a pendulum hanging at rest: the rod carries m g */
    static const real_t hang[6] = {0, 0, -1, 0, 0, 0};
    static const rt_block blocks[] = {{.name = "P", .kind = &mdl_mbs_point_kind, .x0 = hang}};
    sc.blocks = blocks;
    if (!tu_init(&sc))
        return;
    TH_NEAR(rt_rec_value(&sc, &tu_sim, REC_LAMBDA), G, tol * 10);
    TH_NEAR(rt_rec_value(&sc, &tu_sim, REC_FZ), G, tol * 10);
    tu_run_to(&sc, (real_t)0.1);
    TH_NEAR(rt_rec_value(&sc, &tu_sim, REC_FZ), G, tol * 10);
    TH_NEAR(tu_sim.state.x[2], -1, tol);
}

/* ------------------------------------------------------------------ init checks */

static rt_status init_with(const rt_joint *j, uint16_t nj, const rt_block *bl, uint16_t nb,
                           uint8_t nsets)
{
    static const rt_set sets[] = {{.name = "a", .method = &rt_rk4, .ratio = 1},
                                  {.name = "b", .method = &rt_rk4, .ratio = 1}};
    rt_scene sc = {.name = "bad", .dt = (real_t)1e-3, .t_end = 1, .blocks = bl,
                   .nblocks = nb, .sets = sets, .nsets = nsets, .joints = j, .njoints = nj,
                   .mbs = &rt_mbs};
    return rt_init(&sc, &tu_sim);
}

static void test_init_errors(void)
{
    static const real_t zero_len[] = {0};
    static const rt_block two_sets[] = {
        {.name = "A", .kind = &mdl_mbs_point_kind, .x0 = horizontal, .set = 0},
        {.name = "B", .kind = &mdl_mbs_point_kind, .x0 = horizontal, .set = 1},
    };
    static const rt_block with_osc[] = {
        {.name = "A", .kind = &mdl_mbs_point_kind, .x0 = horizontal},
        {.name = "Osc", .kind = &mdl_oscillator_kind},
    };
    static const rt_joint bad_node[] = {
        {.name = "Jnode", .kind = &rt_joint_sphdiff, .b1 = 0, .n1 = 3, .b2 = -1, .p = one}};
    static const rt_joint bad_set[] = {
        {.name = "Jsets", .kind = &rt_joint_sphdiff, .b1 = 0, .b2 = 1, .p = one}};
    static const rt_joint bad_kind[] = {
        {.name = "Jkind", .kind = &rt_joint_sphdiff, .b1 = 0, .b2 = 1, .p = one}};
    static const rt_joint bad_len[] = {
        {.name = "Jlen", .kind = &rt_joint_sphdiff, .b1 = 0, .b2 = -1, .p = zero_len}};
    static rt_joint many[RT_MAX_JOINTS + 1];
    for (int i = 0; i <= RT_MAX_JOINTS; i++)
        many[i] = p1_joints[0];

    TH_CHECK(init_with(bad_node, 1, two_sets, 1, 1) == RT_E_SCENE);
    TH_CHECK(th_has(rt_error_text(&tu_sim), "joint Jnode: node index out of range"));
    TH_CHECK(init_with(bad_set, 1, two_sets, 2, 2) == RT_E_SCENE);
    TH_CHECK(th_has(rt_error_text(&tu_sim), "joint Jsets: links blocks of different sets"));
    TH_CHECK(init_with(bad_kind, 1, with_osc, 2, 1) == RT_E_SCENE);
    TH_CHECK(th_has(rt_error_text(&tu_sim), "joint Jkind: links a block that"));
    TH_CHECK(init_with(bad_len, 1, two_sets, 1, 1) == RT_E_PARAM);
    TH_CHECK(th_has(rt_error_text(&tu_sim), "joint Jlen: parameters out of range"));
    TH_CHECK(init_with(many, RT_MAX_JOINTS + 1, two_sets, 1, 1) == RT_E_CAPACITY);
    TH_CHECK(th_has(rt_error_text(&tu_sim), "RT_MAX_JOINTS"));
    /* a recorded joint signal must name a joint acting on the recorded block */
    rt_scene sc = pendulum(&rt_rk4, (real_t)1e-3, 1, RT_STAB_PROJECT, 1);
    static const rt_rec bad_rec[] = {{0, RT_SIG_MBS, RT_MBS_SIG_JOINT_AT(1, 0)}};
    sc.recs = bad_rec, sc.nrecs = 1;
    TH_CHECK(rt_init(&sc, &tu_sim) == RT_E_SCENE);
    TH_CHECK(th_has(rt_error_text(&tu_sim), "recorded MBS signal of P"));
    /* so must an exported one (it was checked for an MBS scene only) */
    static const rt_link bad_link = {.name = "ctl", .period = 1, .exp = bad_rec, .nexp = 1};
    sc.recs = p1_recs, sc.nrecs = NREC, sc.link = &bad_link;
    TH_CHECK(rt_init(&sc, &tu_sim) == RT_E_SCENE);
    TH_CHECK(th_has(rt_error_text(&tu_sim), "exported MBS signal of P names no MBS quantity"));
}

/* a joint reaction exported to a controller and not recorded is kept as a recorded one:
   the rod of a pendulum hanging at rest carries m g, at init and at the end of a step */
static void test_export_reaction(void)
{
    static const real_t hang[6] = {0, 0, -1, 0, 0, 0};
    static const rt_block blocks[] = {{.name = "P", .kind = &mdl_mbs_point_kind, .x0 = hang}};
    static const rt_rec exp[] = {{0, RT_SIG_MBS, RT_MBS_SIG_JOINT_AT(0, RT_MBS_JSIG_FZ)}};
    static const rt_link lk = {.name = "ctl", .period = 1, .exp = exp, .nexp = 1};
    rt_scene sc = pendulum(&rt_rk4, (real_t)1e-3, 1, RT_STAB_PROJECT, 1);
    sc.blocks = blocks, sc.recs = 0, sc.nrecs = 0, sc.link = &lk;
    if (!tu_init(&sc))
        return;
    double tol = RT_REAL_IS_FLOAT ? 1e-4 : 1e-12;
    TH_NEAR(rt_link_export(&sc, &tu_sim, 0), G, tol);
    tu_run_to(&sc, (real_t)0.1);
    TH_NEAR(rt_link_export(&sc, &tu_sim, 0), G, tol);
}

/* a mass changed by rt_set_param during the run is factored anew (RT_MBS_M_CONST), also
   on the lean path of a set of points: a free point pushed by 1 N, 1 kg for 1 s, 2 kg
   after, x = t^2 / 2, then 1/2 + (t - 1) + (t - 1)^2 / 4 (RK4 is exact on these) */
static void test_mass_change(void)
{
    static const real_t no_g[] = {1, 0, 0, 0};
    static const real_t rest[6] = {0, 0, 0, 0, 0, 0};
    static const rt_block blocks[] = {
        {.name = "P", .kind = &mdl_mbs_pointf_kind, .x0 = rest, .p = no_g},
    };
    static const rt_default push[] = {{0, 0, 1}, {0, 1, 0}, {0, 2, 0}};
    rt_scene sc = pendulum(&rt_rk4, (real_t)1e-3, 2, RT_STAB_PROJECT, 0);
    sc.blocks = blocks, sc.recs = 0, sc.nrecs = 0;
    sc.defaults = push, sc.ndefaults = 3;
    if (!tu_init(&sc))
        return;
    TH_CHECK(tu_sim.work.mbs.points[0] == 1);
    double tol = RT_REAL_IS_FLOAT ? 2e-4 : 1e-12; /* float: 2000 steps' rounding, 5e-5 */
    tu_run_to(&sc, 1);
    TH_NEAR(tu_sim.state.x[0], 0.5, tol);
    TH_CHECK(rt_set_param(&sc, &tu_sim, "P", "m", 2) == RT_OK);
    tu_run_to(&sc, 2);
    TH_NEAR(tu_sim.state.x[0], 1.75, tol);
    TH_NEAR(tu_sim.state.x[3], 1.5, tol);
}

/* a set of point masses takes the lean multibody path (rt_mbs_work.points: 1/m, C.C and
   C . (a1 - a2) where the general one divides W by M row by row): the same motion to
   rounding. A spatial double pendulum hung from an anchor off the origin, masses 1.3 and
   0.7 kg, its first point pushed by an input force, against the same blocks of copies of
   the kinds that do not declare their nodes points (RT_MBS_NODE_POINT), which the
   general path evaluates through their node and kin services; projected and with
   Baumgarte's terms */
static void test_points_path(void)
{
    static const real_t at[3] = {(real_t)0.2, (real_t)-0.1, (real_t)0.3};
    static const real_t x1[6] = {(real_t)1.2, (real_t)-0.1, (real_t)0.3, 0, (real_t)0.8, 0};
    static const real_t x2[6] = {(real_t)1.2, (real_t)0.32, (real_t)0.86,
                                 (real_t)-0.4, 0, (real_t)0.2};
    static const real_t m1[] = {(real_t)1.3, 0, 0, (real_t)-9.81}; /* m, g */
    static const real_t m2[] = {(real_t)0.7, 0, 0, (real_t)-9.81};
    static const rt_default push[] = {{0, 0, (real_t)0.3}, {0, 1, (real_t)-0.5}, {0, 2, 0}};
    static const rt_joint joints[] = {
        {.name = "rod1", .kind = &rt_joint_sphdiff, .b1 = 0, .b2 = -1, .p = one, .at = at},
        {.name = "rod2", .kind = &rt_joint_sphdiff, .b1 = 1, .b2 = 0, .p = len2},
    };
    static rt_mbs_spec spec[2];
    static rt_kind kind[2];
    static rt_block blocks[2];
    const rt_kind *lib[2] = {&mdl_mbs_pointf_kind, &mdl_mbs_point_kind};
    for (int i = 0; i < 2; i++) {
        spec[i] = *(const rt_mbs_spec *)lib[i]->spec;
        spec[i].flags = (uint8_t)(spec[i].flags & ~RT_MBS_NODE_POINT);
        kind[i] = *lib[i], kind[i].spec = &spec[i];
    }
    for (uint8_t stab = RT_STAB_PROJECT; stab <= RT_STAB_BAUMGARTE; stab++) {
        real_t x[12], lam[2];
        for (int v = 0; v < 2; v++) {
            rt_scene sc = double_pendulum(&rt_bs3, (real_t)1e-3, 1, 0);
            sc.recs = p1_recs + REC_LAMBDA, sc.nrecs = 1; /* lambda of rod1 on P1 */
            sc.joints = joints, sc.defaults = push, sc.ndefaults = 3, sc.stab = stab;
            sc.baumgarte[0] = 20, sc.baumgarte[1] = 100;
            blocks[0] = dp_blocks[0], blocks[1] = dp_blocks[1];
            blocks[0].x0 = x1, blocks[1].x0 = x2, blocks[0].p = m1, blocks[1].p = m2;
            blocks[0].kind = v ? &kind[0] : lib[0];
            blocks[1].kind = v ? &kind[1] : lib[1];
            sc.blocks = blocks;
            if (!tu_init(&sc))
                return;
            TH_CHECK(tu_sim.work.mbs.points[0] == (v == 0));
            tu_run_to(&sc, 1);
            /* the second point starts moving along its rod at 0.32 m/s: only the
               projection keeps it on; without, the drift past the set's accuracy is
               counted (0.32 m at 1 s, none; 1.2e-2 m, Baumgarte) */
            TH_CHECK(rt_stats_of(&tu_sim)->status ==
                     (stab == RT_STAB_PROJECT ? RT_OK : RT_E_INVARIANT));
            if (v == 0) {
                for (int i = 0; i < 12; i++)
                    x[i] = tu_sim.state.x[i];
                lam[0] = rt_rec_value(&sc, &tu_sim, 0);
                continue;
            }
            double off = 0;
            for (int i = 0; i < 12; i++) {
                double e = rt_fabs(x[i] - tu_sim.state.x[i]);
                off = e > off ? e : off;
            }
            lam[1] = rt_rec_value(&sc, &tu_sim, 0);
            double el = rt_fabs(lam[0] - lam[1]) / rt_fabs(lam[1]);
            off = el > off ? el : off;
            th_note("points path against the general one", off);
            TH_CHECK(off <= (RT_REAL_IS_FLOAT ? 1e-3 : 1e-11) && lam[0] > 0);
        }
    }
}

const th_test th_mbs_tests[] = {
    {"mbs_period", test_period},
    {"mbs_redundant", test_redundant},
    {"mbs_conflict", test_conflict},
    {"mbs_init_moved", test_init_moved},
    {"mbs_drift_10s", test_drift_10s},
    {"mbs_drift_long", test_drift_long},
    {"mbs_double_pendulum", test_double_pendulum},
    {"mbs_order", test_order},
    {"mbs_straight_chain", test_straight_chain},
    {"mbs_force_input", test_force_input},
    {"mbs_signals", test_signals},
    {"mbs_init_errors", test_init_errors},
    {"mbs_export_reaction", test_export_reaction},
    {"mbs_points_path", test_points_path},
    {"mbs_mass_change", test_mass_change},
    {0, 0},
};
