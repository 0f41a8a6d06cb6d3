/* test_mbs_body.c - tests of the spatial rigid body (models/mbs_body.c) in the multibody
 * runtime: a compound pendulum on a revolute joint against the simple pendulum's period,
 * a heavy symmetric top on a spherical joint (energy, vertical angular momentum and spin
 * conserved), a torque-free tumbling body (energy and inertial angular momentum), a body
 * clamped by a fixed joint (at rest, reactions m g and its moment), a body sliding on a
 * tilted prismatic joint (analytic position and normal reaction), and torque inputs. */
#include "models.h"
#include "testutil.h"
#include "rt_sim.h" /* white box: reads rt_sim's parts (plan, state, work) */

static double absd(double v) { return v < 0 ? -v : v; }

#define G 9.81
#define SQRT_HALF 0.70710678118654752440

/* body state indices: x y z, p0..p3, vx vy vz, wx wy wz (body frame) */
enum { X = 0, P = 3, V = 7, W = 10 };

static void rotation(const real_t *q, double *R)
{
    double a = (double)q[0], b = (double)q[1], c = (double)q[2], d = (double)q[3];
    double n = a * a + b * b + c * c + d * d;
    a /= (double)rt_sqrt((real_t)n), b /= (double)rt_sqrt((real_t)n);
    c /= (double)rt_sqrt((real_t)n), d /= (double)rt_sqrt((real_t)n);
    R[0] = 1 - 2 * (c * c + d * d), R[1] = 2 * (b * c - a * d), R[2] = 2 * (b * d + a * c);
    R[3] = 2 * (b * c + a * d), R[4] = 1 - 2 * (b * b + d * d), R[5] = 2 * (c * d - a * b);
    R[6] = 2 * (b * d - a * c), R[7] = 2 * (c * d + a * b), R[8] = 1 - 2 * (b * b + c * c);
}

static double quat_norm_err(const real_t *x)
{
    double n = 0;
    for (int i = 0; i < 4; i++)
        n += (double)x[P + i] * (double)x[P + i];
    return absd((double)rt_sqrt((real_t)n) - 1);
}

static rt_set body_set;

static rt_scene body_scene(const rt_block *b, const rt_joint *j, uint16_t nj, real_t h,
                           real_t t_end)
{
    body_set = (rt_set){.name = "mbs", .method = &rt_rk4, .ratio = 1};
    return (rt_scene){.name = "body", .dt = h, .t_end = t_end, .blocks = b, .nblocks = 1,
                      .sets = &body_set, .nsets = 1, .joints = j, .njoints = nj,
                      .mbs = &rt_mbs, .stab = RT_STAB_PROJECT};
}

/* ------------------------------------------------------------------ compound pendulum */

/* m = 1 kg, centre of mass 0.5 m from the pivot, J = 0.25 kg m^2 about the axis through
   it: I_pivot / (m d) = 1 m, the simple pendulum's length, so released horizontally the
   period is again 2.367841948 s. The revolute axis is inertial y: body and anchor frames
   are turned -90 deg about x so that their z axes point along y. */
static const real_t cp_p[16] = {1, (real_t)0.1, (real_t)0.3, (real_t)0.25, 0, 0, 0,
                                0, 0, (real_t)-9.81, (real_t)-0.5, 0, 0, 0, 0, 0};
static const real_t cp_x0[13] = {(real_t)0.5, 0, 0, (real_t)SQRT_HALF, (real_t)-SQRT_HALF,
                                 0, 0, 0, 0, 0, 0, 0, 0};
static const real_t z_to_y[9] = {1, 0, 0, 0, 0, 1, 0, -1, 0};

static void test_compound_pendulum(void)
{
    static const rt_block b[] = {{.name = "Arm", .kind = &mdl_mbs_body_kind, .p = cp_p,
                                  .x0 = cp_x0}};
    static const rt_joint j[] = {{.name = "hinge", .kind = &rt_joint_revolute, .b1 = 0,
                                  .n1 = 1, .b2 = -1, .at_S = z_to_y}};
    rt_scene sc = body_scene(b, j, 1, (real_t)1e-3, (real_t)3.2); /* 3 crossings */
    if (!tu_init(&sc))
        return;
    const real_t *x = tu_sim.state.x;
    double cross[8] = {0}, qerr = 0, yoff = 0;
    int n = 0;
    while (rt_ticks_done(&tu_sim) < rt_tick_count(&tu_sim)) {
        double t0 = (double)rt_time(&sc, &tu_sim), x0 = (double)x[X], v0 = (double)x[V];
        rt_tick(&sc, &tu_sim);
        double h = (double)sc.dt, x1 = (double)x[X], v1 = (double)x[V];
        if ((x0 > 0) != (x1 > 0) && n < 8) { /* cubic Hermite root in the step */
            double s = x0 / (x0 - x1);
            for (int it = 0; it < 20; it++) {
                double p = (1 + 2 * s) * (1 - s) * (1 - s) * x0 + s * (1 - s) * (1 - s) * h * v0 +
                           s * s * (3 - 2 * s) * x1 + s * s * (s - 1) * h * v1;
                double dp = 6 * s * (s - 1) * (x0 - x1) + (1 - 4 * s + 3 * s * s) * h * v0 +
                            (3 * s * s - 2 * s) * h * v1;
                s -= p / dp;
            }
            cross[n++] = t0 + s * h;
        }
        qerr = quat_norm_err(x) > qerr ? quat_norm_err(x) : qerr;
        yoff = absd((double)x[X + 1]) > yoff ? absd((double)x[X + 1]) : yoff;
    }
    TH_CHECK(n == 3);
    /* the hinge node stays at the pivot (outputs n1x .. n1vz) */
    for (int i = 0; i < 6; i++)
        TH_NEAR(tu_y(&sc, "Arm", (uint16_t)(MDL_MBS_BODY_Y_N1 + i)), 0,
                RT_REAL_IS_FLOAT ? 1e-5 : 1e-12);
    double period = 2 * (cross[n - 1] - cross[0]) / (n - 1);
    th_note("compound pendulum period [s]", period);
    th_note("|quaternion| - 1", qerr);
    TH_NEAR(period, 2.367841948, RT_REAL_IS_FLOAT ? 5e-4 : 2e-9);
    TH_CHECK(qerr < (RT_REAL_IS_FLOAT ? 1e-6 : 1e-14) && yoff < (RT_REAL_IS_FLOAT ? 1e-5 : 1e-13));
    TH_CHECK(rt_stats_of(&tu_sim)->status == RT_OK);
}

/* ------------------------------------------------------------------ heavy top */

/* symmetric top, m = 1 kg, Jxx = Jyy = 0.1, Jzz = 0.05 kg m^2 about the centre of mass,
   which is 0.2 m up the figure axis from the tip; the tip sits in a spherical joint at the
   origin. Tilted 30 deg about x, spinning at 50 rad/s about its figure axis. */
#define TOP_D 0.2
static const real_t top_p[16] = {1, (real_t)0.1, (real_t)0.1, (real_t)0.05, 0, 0, 0,
                                 0, 0, (real_t)-9.81, 0, 0, (real_t)-TOP_D, 0, 0, 0};

/* L_O = m r x v + R J w, energy T + V, from the state alone */
static void top_invariants(const real_t *x, double *E, double *Lz)
{
    double R[9], w[3] = {(double)x[W], (double)x[W + 1], (double)x[W + 2]};
    double Jw[3] = {0.1 * w[0], 0.1 * w[1], 0.05 * w[2]}, v2 = 0;
    rotation(x + P, R);
    for (int i = 0; i < 3; i++)
        v2 += (double)x[V + i] * (double)x[V + i];
    *E = 0.5 * (v2 + w[0] * Jw[0] + w[1] * Jw[1] + w[2] * Jw[2]) + G * (double)x[X + 2];
    *Lz = (double)x[X] * (double)x[V + 1] - (double)x[X + 1] * (double)x[V] +
          R[6] * Jw[0] + R[7] * Jw[1] + R[8] * Jw[2];
}

static void test_heavy_top(void)
{
    static real_t x0[13];
    double c = 0.96592582628906828675, s = 0.25881904510252076235; /* cos, sin 15 deg */
    double q[4] = {c, s, 0, 0}, R[9];
    for (int i = 0; i < 13; i++)
        x0[i] = 0;
    for (int i = 0; i < 4; i++)
        x0[P + i] = (real_t)q[i];
    rotation(x0 + P, R);
    for (int i = 0; i < 3; i++)
        x0[X + i] = (real_t)(R[3 * i + 2] * TOP_D); /* tip at the origin */
    x0[W + 2] = 50;
    static rt_block b[1];
    b[0] = (rt_block){.name = "Top", .kind = &mdl_mbs_body_kind, .p = top_p, .x0 = x0};
    static const rt_joint j[] = {{.name = "tip", .kind = &rt_joint_spherical, .b1 = 0,
                                  .n1 = 1, .b2 = -1}};
    rt_scene sc = body_scene(b, j, 1, (real_t)1e-3, 2);
    if (!tu_init(&sc))
        return;
    double E0, L0, E, L, dE = 0, dL = 0, dw = 0, qerr = 0;
    top_invariants(tu_sim.state.x, &E0, &L0);
    while (rt_tick(&sc, &tu_sim) == RT_OK) {
        top_invariants(tu_sim.state.x, &E, &L);
        dE = absd(E - E0) > dE ? absd(E - E0) : dE;
        dL = absd(L - L0) > dL ? absd(L - L0) : dL;
        dw = absd((double)tu_sim.state.x[W + 2] - 50) > dw ? absd((double)tu_sim.state.x[W + 2] - 50) : dw;
        qerr = quat_norm_err(tu_sim.state.x) > qerr ? quat_norm_err(tu_sim.state.x) : qerr;
    }
    th_note("heavy top: |E - E0| [J]", dE);
    th_note("heavy top: |Lz - Lz0| [N m s]", dL);
    th_note("heavy top: |w3 - 50| [rad/s]", dw);
    th_note("heavy top: |quaternion| - 1", qerr);
    /* the figure axis moved: the top precesses and nutates */
    TH_CHECK(absd((double)tu_sim.state.x[X] - (double)x0[X]) > 1e-3);
    double rel = RT_REAL_IS_FLOAT ? 1e-3 : 1e-8;
    TH_CHECK(dE < rel * absd(E0) && dL < rel * absd(L0) && dw < rel * 50);
    TH_CHECK(qerr < (RT_REAL_IS_FLOAT ? 1e-6 : 1e-14) && rt_stats_of(&tu_sim)->status == RT_OK);
}

/* ------------------------------------------------------------------ torque-free body */

/* J = diag(1, 2, 3), spinning mostly about the unstable intermediate axis: it tumbles
   (Dzhanibekov), while energy and the inertial angular momentum R J w stay constant. The
   body has no joints, so the projection only renormalizes its quaternion. */
static void test_free_tumble(void)
{
    static const real_t p[16] = {2, 1, 2, 3, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
    static const real_t x0[13] = {0, 0, 0, 1, 0, 0, 0, (real_t)0.3, 0, 0,
                                  (real_t)0.01, 2, (real_t)0.01};
    static const rt_block b[] = {{.name = "Free", .kind = &mdl_mbs_body_kind, .p = p,
                                  .x0 = x0}};
    rt_scene sc = body_scene(b, 0, 0, (real_t)1e-3, 10);
    if (!tu_init(&sc))
        return;
    double L0[3], E0 = 0, dL = 0, dE = 0, wmin = 2;
    for (int k = 0;; k++) {
        const real_t *x = tu_sim.state.x;
        double R[9], Jw[3] = {(double)x[W], 2 * (double)x[W + 1], 3 * (double)x[W + 2]};
        double E = 0.5 * ((double)x[W] * Jw[0] + (double)x[W + 1] * Jw[1] +
                          (double)x[W + 2] * Jw[2]);
        rotation(x + P, R);
        for (int i = 0; i < 3; i++) {
            double Li = R[3 * i] * Jw[0] + R[3 * i + 1] * Jw[1] + R[3 * i + 2] * Jw[2];
            if (k == 0)
                L0[i] = Li;
            dL = absd(Li - L0[i]) > dL ? absd(Li - L0[i]) : dL;
        }
        E0 = k == 0 ? E : E0;
        dE = absd(E - E0) > dE ? absd(E - E0) : dE;
        wmin = (double)x[W + 1] < wmin ? (double)x[W + 1] : wmin;
        if (rt_tick(&sc, &tu_sim) != RT_OK)
            break;
    }
    th_note("tumbling body: |E - E0| [J]", dE);
    th_note("tumbling body: |L - L0| [N m s]", dL);
    TH_CHECK(wmin < -1); /* it flipped */
    double tol = RT_REAL_IS_FLOAT ? 1e-3 : 1e-8;
    TH_CHECK(dE < tol * E0 && dL < tol * 4);
    TH_NEAR(tu_sim.state.x[X], 3, RT_REAL_IS_FLOAT ? 3e-4 : 1e-12); /* 0.3 m/s for 10 s */
    TH_CHECK(quat_norm_err(tu_sim.state.x) < (RT_REAL_IS_FLOAT ? 1e-6 : 1e-14));
}

/* ------------------------------------------------------------------ fixed joint */

/* a body clamped at its node n1 (0.5 m from the centre of mass along -x) stays at rest;
   the joint carries its weight and the moment of it */
static void test_fixed(void)
{
    static const rt_block b[] = {{.name = "Arm", .kind = &mdl_mbs_body_kind, .p = cp_p,
                                  .x0 = cp_x0}};
    static const rt_joint j[] = {{.name = "clamp", .kind = &rt_joint_fixed, .b1 = 0,
                                  .n1 = 1, .b2 = -1, .at_S = z_to_y}};
    static const rt_rec recs[] = {
        {0, RT_SIG_MBS, RT_MBS_SIG_JOINT_AT(0, RT_MBS_JSIG_FX)},
        {0, RT_SIG_MBS, RT_MBS_SIG_JOINT_AT(0, RT_MBS_JSIG_FZ)},
        {0, RT_SIG_MBS, RT_MBS_SIG_JOINT_AT(0, RT_MBS_JSIG_MY)},
        {0, RT_SIG_MBS, RT_MBS_SIG_RESIDUAL},
    };
    rt_scene sc = body_scene(b, j, 1, (real_t)1e-3, 1);
    sc.recs = recs, sc.nrecs = 4;
    if (!tu_init(&sc))
        return;
    while (rt_tick(&sc, &tu_sim) == RT_OK)
        ;
    double tol = RT_REAL_IS_FLOAT ? 1e-4 : 1e-11;
    for (int i = 0; i < 13; i++)
        TH_NEAR(tu_sim.state.x[i], cp_x0[i], tol);
    TH_NEAR(rt_rec_value(&sc, &tu_sim, 0), 0, tol * 10);
    TH_NEAR(rt_rec_value(&sc, &tu_sim, 1), G, tol * 10);
    /* gravity's moment about the node: (0.5, 0, 0) x (0, 0, -m g) = (0, 0.5 m g, 0) */
    TH_NEAR(rt_rec_value(&sc, &tu_sim, 2), -0.5 * G, tol * 10);
    TH_CHECK(rt_rec_value(&sc, &tu_sim, 3) < tol);
    TH_CHECK(rt_streq(rt_rec_signal(&sc, 2), "my") && rt_stats_of(&tu_sim)->status == RT_OK);
}

/* ------------------------------------------------------------------ prismatic joint */

/* the same body on a prismatic joint to an anchor at the origin whose z axis is tilted by
   al from the vertical about y, u = (sin al, 0, cos al); node n1 starts at the anchor. The
   body keeps its orientation and slides down the axis: s(t) = -g cos(al) t^2 / 2 along u;
   the reaction is normal to u with magnitude m g sin(al). */
#define PR_AL 0.6
static void test_prismatic(void)
{
    double ca = (double)rt_cos((real_t)PR_AL), sa = (double)rt_sin((real_t)PR_AL);
    static real_t S[9], x0[13];
    const real_t Sv[9] = {(real_t)ca, 0, (real_t)sa, 0, 1, 0, (real_t)-sa, 0, (real_t)ca};
    const real_t xv[13] = {(real_t)(0.5 * ca), 0, (real_t)(-0.5 * sa), rt_cos((real_t)(PR_AL / 2)),
                           0, rt_sin((real_t)(PR_AL / 2)), 0, 0, 0, 0, 0, 0, 0};
    for (int i = 0; i < 9; i++)
        S[i] = Sv[i];
    for (int i = 0; i < 13; i++)
        x0[i] = xv[i];
    const rt_block b[] = {{.name = "Slider", .kind = &mdl_mbs_body_kind, .p = cp_p, .x0 = x0}};
    const rt_joint j[] = {{.name = "slide", .kind = &rt_joint_prismatic, .b1 = 0, .n1 = 1,
                           .b2 = -1, .at_S = S}};
    static const rt_rec recs[] = {
        {0, RT_SIG_MBS, RT_MBS_SIG_JOINT_AT(0, RT_MBS_JSIG_FX)},
        {0, RT_SIG_MBS, RT_MBS_SIG_JOINT_AT(0, RT_MBS_JSIG_FZ)},
    };
    rt_scene sc = body_scene(b, j, 1, (real_t)1e-3, 1);
    sc.recs = recs, sc.nrecs = 2;
    if (!tu_init(&sc))
        return;
    while (rt_tick(&sc, &tu_sim) == RT_OK)
        ;
    double s = -G * ca / 2, tol = RT_REAL_IS_FLOAT ? 1e-4 : 1e-10;
    TH_NEAR(tu_sim.state.x[X], 0.5 * ca + s * sa, tol);
    TH_NEAR(tu_sim.state.x[X + 1], 0, tol);
    TH_NEAR(tu_sim.state.x[X + 2], -0.5 * sa + s * ca, tol);
    TH_NEAR(tu_sim.state.x[V], -G * ca * sa, tol);
    for (int i = 0; i < 4; i++) /* orientation unchanged */
        TH_NEAR(tu_sim.state.x[P + i], xv[3 + i], tol);
    double fx = (double)rt_rec_value(&sc, &tu_sim, 0), fz = (double)rt_rec_value(&sc, &tu_sim, 1);
    TH_NEAR(absd(fx * sa + fz * ca), 0, tol * 10);      /* normal to the axis */
    TH_NEAR(rt_sqrt((real_t)(fx * fx + fz * fz)), G * sa, tol * 10); /* m g sin(al) */
    TH_CHECK(rt_stats_of(&tu_sim)->status == RT_OK);
}

/* ------------------------------------------------------------------ initial quaternion */

/* a non-unit initial quaternion is normalized at init and reported with the block and
   its norm; a zero one is refused */
static void test_quaternion(void)
{
    static const real_t p[16] = {2, 1, 2, 3, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
    static real_t x0[13];
    static rt_block b[1];
    b[0] = (rt_block){.name = "Free", .kind = &mdl_mbs_body_kind, .p = p, .x0 = x0};
    rt_scene sc = body_scene(b, 0, 0, (real_t)1e-3, 1);
    x0[P] = 0, x0[P + 1] = 2; /* 180 deg about x, twice too long */
    if (!tu_init(&sc))
        return;
    th_put("  quaternion: ");
    th_put(rt_error_text(&tu_sim));
    th_put("\n");
    TH_CHECK(th_has(rt_error_text(&tu_sim), "Free: quaternion of norm 2.00e+00 normalized"));
    TH_CHECK(rt_stats_of(&tu_sim)->count[RT_CNT_INIT_MOVED] == 1 && rt_stats_of(&tu_sim)->status == RT_OK);
    TH_CHECK(tu_sim.state.x[P] == 0 && tu_sim.state.x[P + 1] == 1);
    x0[P + 1] = 1; /* unit: nothing to say */
    if (!tu_init(&sc))
        return;
    TH_CHECK(rt_stats_of(&tu_sim)->count[RT_CNT_INIT_MOVED] == 0 && rt_error_text(&tu_sim)[0] == 0);
    x0[P + 1] = 0;
    TH_CHECK(rt_init(&sc, &tu_sim) == RT_E_PARAM);
    TH_CHECK(th_has(rt_error_text(&tu_sim), "Free: initial quaternion of norm 0.00e+00"));
}

/* ------------------------------------------------------------------ inputs */

/* a body-frame torque about z on a free body: w_z = tau t / Jzz; a force: x = F t^2/2m */
static void test_torque_input(void)
{
    static const real_t p[16] = {2, 1, 2, 4, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
    static const rt_block b[] = {{.name = "F", .kind = &mdl_mbs_bodyf_kind, .p = p}};
    static const rt_default defs[] = {{0, 0, 1}, {0, 1, 0}, {0, 2, 0},
                                      {0, 3, 0}, {0, 4, 0}, {0, 5, 2}};
    rt_scene sc = body_scene(b, 0, 0, (real_t)1e-3, 1);
    sc.defaults = defs, sc.ndefaults = 6;
    if (!tu_init(&sc))
        return;
    while (rt_tick(&sc, &tu_sim) == RT_OK)
        ;
    double tol = RT_REAL_IS_FLOAT ? 1e-5 : 1e-12;
    TH_NEAR(tu_sim.state.x[W + 2], 0.5, tol);
    TH_NEAR(tu_sim.state.x[X], 0.25, tol);
    /* turned by w t^2 / 2 = 0.25 rad about z: p = (cos 0.125, 0, 0, sin 0.125) */
    TH_NEAR(tu_sim.state.x[P + 3], rt_sin((real_t)0.125), RT_REAL_IS_FLOAT ? 1e-5 : 1e-11);
}

const th_test th_mbs_body_tests[] = {
    {"mbs_body_compound_pendulum", test_compound_pendulum},
    {"mbs_body_heavy_top", test_heavy_top},
    {"mbs_body_free_tumble", test_free_tumble},
    {"mbs_body_fixed", test_fixed},
    {"mbs_body_prismatic", test_prismatic},
    {"mbs_body_torque_input", test_torque_input},
    {"mbs_body_quaternion", test_quaternion},
    {0, 0},
};
