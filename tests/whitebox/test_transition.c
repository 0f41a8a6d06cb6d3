/* test_transition.c - tests of the transition-matrix method (rt/integ_transition.c) and
 * its phi functions (rti_phi12, rt/linalg.c), against closed forms: phi1 and phi2 of a
 * diagonal and of a rotation generator; the 1 kHz servo of pendulum10_actuated under a
 * held command (the step response of a damped oscillator), exact at omega h = 6.3 where
 * the trapezoidal rule and ROS2 are off by percents; a first-order lag under a sine,
 * second order with an estimate of the size of its error; a time constant changed
 * mid-run; matrices that overflow, then recover; a NaN input; the scenes it refuses. */
#include "linalg.h"
#include "rti.h"
#include "scenes/scenes.h"
#include "testutil.h"

#define FLT RT_REAL_IS_FLOAT

static double dabs(double v) { return v < 0 ? -v : v; }

/* ------------------------------------------------------------------ phi functions */

/* phi1(a) = (e^a - 1)/a and phi2(a) = (e^a - 1 - a)/a^2 of a scalar, by their series
   where a is small (the closed forms cancel there) */
static double phi1_of(double a)
{
    if (dabs(a) < 1e-3)
        return 1 + a / 2 + a * a / 6 + a * a * a / 24;
    return ((double)rt_exp((real_t)a) - 1) / a;
}
static double phi2_of(double a)
{
    if (dabs(a) < 1e-3)
        return 0.5 + a / 6 + a * a / 24 + a * a * a / 120;
    return ((double)rt_exp((real_t)a) - 1 - a) / (a * a);
}

static int phi(const real_t *a_in, real_t *p1, real_t *p2)
{
    real_t a[4], t[4];
    for (int i = 0; i < 4; i++)
        a[i] = a_in[i];
    return rti_phi12(a, 2, p1, p2, t, RT_TRANSITION_THETA, RT_TRANSITION_TAYLOR,
                     RT_TRANSITION_HALVINGS) == RT_OK;
}

/* a diagonal A: phi of each entry, off-diagonals zero; from a mild one to a stiff one
   that needs 15 halvings (-1e4) and a growing one. The halvings the largest entry needs
   are taken by all (overscaling, Al-Mohy & Higham 2009): the squarings of e^A amplify
   the slow entry's rounding by about the spread of the entries (-1e4 / -50: 200, 70 ulp
   measured in double, 350 in float) */
static void test_phi_diagonal(void)
{
    static const double d[][2] = {{-0.3, 0.2}, {-6.3, -1}, {-1e4, -50}, {3, -2}};
    for (unsigned c = 0; c < sizeof d / sizeof d[0]; c++) {
        double tol = (FLT ? 2e-6 : 1e-14) * (c == 2 ? 50 : 1);
        real_t a[4] = {(real_t)d[c][0], 0, 0, (real_t)d[c][1]}, p1[4], p2[4];
        TH_CHECK(phi(a, p1, p2));
        for (int i = 0; i < 2; i++) {
            TH_NEAR(p1[3 * i], phi1_of(d[c][i]), tol * dabs(phi1_of(d[c][i])));
            TH_NEAR(p2[3 * i], phi2_of(d[c][i]), tol * dabs(phi2_of(d[c][i])));
        }
        TH_CHECK(p1[1] == 0 && p1[2] == 0 && p2[1] == 0 && p2[2] == 0);
    }
}

/* A = [[0, w], [-w, 0]], A^2 = -w^2 I: e^A the rotation by w, phi1 = (e^A - I) A^-1,
   phi2 = -(e^A - I - A) / w^2 */
static void test_phi_rotation(void)
{
    static const double ws[] = {0.3, 6.3, 40};
    for (unsigned c = 0; c < sizeof ws / sizeof ws[0]; c++) {
        double w = ws[c], s = (double)rt_sin((real_t)w), co = (double)rt_cos((real_t)w);
        real_t a[4] = {0, (real_t)w, (real_t)-w, 0}, p1[4], p2[4];
        TH_CHECK(phi(a, p1, p2));
        double e1[4] = {s / w, (1 - co) / w, -(1 - co) / w, s / w};
        double e2[4] = {(1 - co) / (w * w), (w - s) / (w * w), (s - w) / (w * w),
                        (1 - co) / (w * w)};
        double tol = FLT ? 1e-5 : 2e-14 * w; /* the doublings lose about a digit per 10 */
        for (int i = 0; i < 4; i++) {
            TH_NEAR(p1[i], e1[i], tol);
            TH_NEAR(p2[i], e2[i], tol);
        }
    }
}

/* a norm beyond theta 2^RT_TRANSITION_HALVINGS, or a NaN: refused, nothing written */
static void test_phi_refused(void)
{
    real_t big[4] = {(real_t)-1e30, 0, 0, 1}, nan[4] = {0, 0, 0, 0}, p1[4] = {7}, p2[4] = {7};
    TH_CHECK(!phi(big, p1, p2) && p1[0] == 7 && p2[0] == 7);
    nan[1] = (real_t)0 / (real_t)0;
    TH_CHECK(!phi(nan, p1, p2) && p1[0] == 7);
}

/* ------------------------------------------------------------------ scenes */

static rt_block blks[RT_MAX_TRANSITION_N + 1];
static rt_set set;
static rt_conn conn;
static rt_default dflt;
static rt_scene scene;

/* one set of n blocks stepped by m at h to t_end; blks[] filled by the caller, input
   conn (if any) and one default */
static int setup(uint16_t n, const rt_integrator *m, real_t h, real_t t_end, int connected,
                 int defaulted)
{
    set = (rt_set){.name = "s", .method = m, .ratio = 1,
                   .cfg = {.jac_every = rt_method_iterates(m) ? 1024 : 0, .accuracy = (real_t)1e-2}};
    scene = (rt_scene){.name = "transition", .dt = h, .t_end = t_end, .blocks = blks,
                       .nblocks = n, .sets = &set, .nsets = 1,
                       .conns = connected ? &conn : 0, .nconns = (uint16_t)connected,
                       .defaults = defaulted ? &dflt : 0, .ndefaults = (uint16_t)defaulted};
    return tu_init(&scene);
}

/* the servo y'' + 2 zeta w y' + w^2 y = w^2 k u from rest under u = 2: with
   s = zeta w, wd = w sqrt(1 - zeta^2), y = k u (1 - e^-st (cos wd t + s/wd sin wd t)),
   y' = k u e^-st (s^2/wd + wd) sin wd t */
static void servo_exact(double t, double *y, double *w)
{
    double om = 6283.1853071795865, z = 0.7, ku = 2, s = z * om;
    double wd = om * (double)rt_sqrt((real_t)(1 - z * z));
    double e = (double)rt_exp((real_t)(-s * t));
    double c = (double)rt_cos((real_t)(wd * t)), sn = (double)rt_sin((real_t)(wd * t));
    *y = ku * (1 - e * (c + s / wd * sn));
    *w = ku * e * (s * s / wd + wd) * sn / om;
}

/* at h = 1 ms (omega h = 6.3): exact to rounding at every tick, status ok, estimate 0,
   one evaluation per step (autonomous: the command holds), the Jacobian formed once; the
   trapezoidal rule and ROS2 at the same step are 1e-2 off in the first milliseconds */
static void test_servo_exact(void)
{
    blks[0] = (rt_block){.name = "Servo", .kind = &mdl_servo2_kind};
    dflt = (rt_default){0, 0, 2};
    const rt_integrator *ms[] = {&rt_transition, &rt_trap, &rt_ros2};
    double worst[3] = {0, 0, 0};
    for (int v = 0; v < 3; v++) {
        if (!setup(1, ms[v], (real_t)1e-3, (real_t)0.05, 0, 1))
            return;
        rt_status st;
        while ((st = rt_tick(&scene, &tu_sim)) == RT_OK || st == RT_E_DONE) {
            double y, w, t = (double)rt_time(&scene, &tu_sim);
            servo_exact(t, &y, &w);
            double e = dabs(tu_sim.state.x[0] - y) + dabs(tu_sim.state.x[1] - w);
            worst[v] = e > worst[v] ? e : worst[v];
            if (st == RT_E_DONE)
                break;
        }
        if (v == 0) {
            TH_CHECK(st == RT_E_DONE && rt_stats_of(&tu_sim)->status == RT_OK);
            TH_CHECK(tu_sim.plan.set_flags[0] & RTI_SET_AUTONOMOUS);
            TH_CHECK(rt_stats_of(&tu_sim)->istats[0].err_max == 0 && rt_stats_of(&tu_sim)->istats[0].jac_evals == 1);
            TH_EQ_U64(rt_stats_of(&tu_sim)->rhs_evals[0], 50 + 2); /* a step each, n for J */
        }
    }
    TH_CHECK(worst[0] < (FLT ? 1e-4 : 1e-12));
    TH_CHECK(worst[1] > 1e-2 && worst[2] > 1e-2);
}

/* T y' = K u - y under u = sin(om t) from y = 0: y = K / (1 + (om T)^2)
   (sin om t - om T cos om t + om T e^(-t/T)) */
static double lag_exact(double t)
{
    double om = 20, T = 0.01, K = 1.5, q = om * T;
    return K / (1 + q * q) * ((double)rt_sin((real_t)(om * t)) -
                              q * (double)rt_cos((real_t)(om * t)) +
                              q * (double)rt_exp((real_t)(-t / T)));
}

/* the lag behind a sine in its own set: the input ramps over each step (first-order
   hold), so the method is of second order (the error at t = 1 s falls by 4 when h
   halves); its estimate (the input's departure from its chord) has the size of the
   steps' errors: its largest is above the largest error of a step and within 4 times it
   (a single step may be off where g'' changes sign), and below the set's accuracy */
static void test_lag_second_order(void)
{
    static const real_t p_lag[] = {(real_t)1.5, (real_t)0.01}, p_sin[] = {1, 20, 0, 0};
    blks[0] = (rt_block){.name = "Src", .kind = &mdl_sine_kind, .p = p_sin};
    blks[1] = (rt_block){.name = "Lag", .kind = &mdl_pt1_kind, .p = p_lag};
    conn = (rt_conn){0, 0, 1, 0};
    double err[2];
    for (int v = 0; v < 2; v++) {
        real_t h = v ? (real_t)5e-3 : (real_t)1e-2;
        if (!setup(2, &rt_transition, h, 1, 1, 0))
            return;
        real_t prev = 0;
        double worst_d = 0, worst_e = 0;
        rt_status st;
        while ((st = rt_tick(&scene, &tu_sim)) == RT_OK || st == RT_E_DONE) {
            double t = (double)rt_time(&scene, &tu_sim), y = (double)tu_sim.state.x[0];
            /* the local error of this step: the exact flow from the previous state */
            double d = y - lag_exact(t) - (prev - lag_exact(t - (double)h)) *
                       (double)rt_exp((real_t)(-(double)h / 0.01));
            double e = (double)rt_stats_of(&tu_sim)->istats[0].last_err * (1 + dabs(y));
            worst_d = dabs(d) > worst_d ? dabs(d) : worst_d;
            worst_e = e > worst_e ? e : worst_e;
            prev = tu_sim.state.x[0];
            if (st == RT_E_DONE)
                break;
        }
        err[v] = dabs((double)tu_sim.state.x[0] - lag_exact(1));
        TH_CHECK(!(tu_sim.plan.set_flags[0] & RTI_SET_AUTONOMOUS));
        TH_CHECK(worst_e >= worst_d && worst_e < 4 * worst_d);
        TH_CHECK(rt_stats_of(&tu_sim)->status == RT_OK && rt_stats_of(&tu_sim)->istats[0].err_max < (real_t)1e-2);
    }
    TH_NEAR(err[0] / err[1], 4, 0.4);
    TH_CHECK(err[1] < 2e-3);
}

/* the lag's time constant halved at t = 0.5 s by rt_set_param: the next step forms J
   anew, and under a held input the method stays exact: y = K (1 - e^(-t/T1)) up to
   0.5 s, then K + (y(0.5) - K) e^(-(t - 0.5)/T2) */
static void test_param_change(void)
{
    static const real_t p_lag[] = {2, (real_t)0.1};
    blks[0] = (rt_block){.name = "Lag", .kind = &mdl_pt1_kind, .p = p_lag};
    dflt = (rt_default){0, 0, 1};
    if (!setup(1, &rt_transition, (real_t)0.01, 1, 0, 1))
        return;
    TH_CHECK(tu_run_to(&scene, (real_t)0.5) == RT_OK);
    TH_CHECK(rt_set_param(&scene, &tu_sim, "Lag", "T", (real_t)0.05) == RT_OK);
    TH_CHECK(tu_run_to(&scene, 1) == RT_E_DONE);
    double y5 = 2 * (1 - (double)rt_exp((real_t)-5));
    double y1 = 2 + (y5 - 2) * (double)rt_exp((real_t)-10);
    TH_NEAR(tu_sim.state.x[0], y1, FLT ? 1e-5 : 1e-13);
    TH_CHECK(rt_stats_of(&tu_sim)->istats[0].jac_evals == 2);
}

/* a mode growing by e^1990 over a step (a lag fed back through a gain of 200): its
   matrices overflow, each step is refused (singular) and leaves the state; once the gain
   is 0 the next refresh forms finite matrices again (no infinity of the last one
   multiplied into them) and the lag decays as it should */
static void test_overflow_recovers(void)
{
    static const real_t p_lag[] = {1, (real_t)1e-3}, p_gain[] = {200};
    blks[0] = (rt_block){.name = "Lag", .kind = &mdl_pt1_kind, .p = p_lag, .x0 = p_lag};
    blks[1] = (rt_block){.name = "G", .kind = &mdl_gain_kind, .p = p_gain};
    static const rt_conn loop[] = {{0, 0, 1, 0}, {1, 0, 0, 0}};
    set = (rt_set){.name = "s", .method = &rt_transition, .ratio = 1};
    scene = (rt_scene){.name = "transition", .dt = (real_t)0.01, .t_end = 1, .blocks = blks,
                       .nblocks = 2, .conns = loop, .nconns = 2, .sets = &set, .nsets = 1};
    if (!tu_init(&scene))
        return;
    tu_run_to(&scene, (real_t)0.1);
    uint32_t singular = rt_stats_of(&tu_sim)->count[RT_CNT_SINGULAR];
    TH_CHECK(singular == 10 && tu_sim.state.x[0] == 1);
    TH_CHECK(rt_set_param(&scene, &tu_sim, "G", "k", 0) == RT_OK);
    tu_run_to(&scene, (real_t)0.2);
    TH_CHECK(rt_stats_of(&tu_sim)->count[RT_CNT_SINGULAR] == singular);
    /* x' = -x / T from 1 at t = 0.1: e^-100. Each step forms e^-10 x0 as x0 + h phi1 f
       (the decay by cancellation): an error of about eps |x0| per step, 6e-11 relative
       after ten (in float 2 % and a subnormal result, resolved to 4 % of itself) */
    TH_NEAR(tu_sim.state.x[0], 3.720075976020836e-44, 3.7e-44 * (FLT ? 0.2 : 1e-9));
}

/* a NaN command when the matrices are due: counted as NaN with the servo, the state kept
   (rt/step.c), not a singular matrix */
static void test_nan_input(void)
{
    blks[0] = (rt_block){.name = "Servo", .kind = &mdl_servo2_kind};
    dflt = (rt_default){0, 0, (real_t)0 / (real_t)0};
    if (!setup(1, &rt_transition, (real_t)1e-3, (real_t)0.01, 0, 1))
        return;
    rt_tick(&scene, &tu_sim);
    TH_CHECK(rt_stats_of(&tu_sim)->count[RT_CNT_NAN] >= 1 && rt_stats_of(&tu_sim)->last_block[RT_CNT_NAN] == 0);
    TH_CHECK(rt_stats_of(&tu_sim)->count[RT_CNT_SINGULAR] == 0);
    TH_CHECK(tu_sim.state.x[0] == 0 && tu_sim.state.x[1] == 0);
}

/* refused at init, with the block named: a nonlinear block, a multibody module (the
   library's pendulum in one set of its own method), more states than
   RT_MAX_TRANSITION_N */
static void test_refused(void)
{
    blks[0] = (rt_block){.name = "Osc", .kind = &mdl_oscillator_kind};
    blks[1] = (rt_block){.name = "VdP", .kind = &mdl_vanderpol_kind};
    set = (rt_set){.name = "s", .method = &rt_transition, .ratio = 1};
    scene = (rt_scene){.name = "transition", .dt = (real_t)0.01, .t_end = 1, .blocks = blks,
                       .nblocks = 2, .sets = &set, .nsets = 1};
    TH_CHECK(rt_init(&scene, &tu_sim) == RT_E_SCENE &&
             th_has(rt_error_text(&tu_sim), "VdP") &&
             th_has(rt_error_text(&tu_sim), "transition"));
    scene.nblocks = 1; /* the oscillator alone is linear */
    TH_CHECK(rt_init(&scene, &tu_sim) == RT_OK);
    static rt_default zero[RT_MAX_TRANSITION_N + 1];
    for (uint16_t i = 0; i <= RT_MAX_TRANSITION_N; i++) {
        blks[i] = (rt_block){.name = "Lag", .kind = &mdl_pt1_kind};
        zero[i] = (rt_default){i, 0, 0};
    }
    scene.nblocks = RT_MAX_TRANSITION_N + 1;
    scene.defaults = zero, scene.ndefaults = RT_MAX_TRANSITION_N + 1;
    TH_CHECK(rt_init(&scene, &tu_sim) == RT_E_CAPACITY &&
             th_has(rt_error_text(&tu_sim), "RT_MAX_TRANSITION_N"));
    static rt_set mbs_set;
    mbs_set = mdl_scene_pendulum10.sets[0];
    mbs_set.method = &rt_transition;
    static rt_scene pend;
    pend = mdl_scene_pendulum10;
    pend.sets = &mbs_set;
    TH_CHECK(rt_init(&pend, &tu_sim) == RT_E_SCENE && th_has(rt_error_text(&tu_sim), "B1"));
}

const th_test th_transition_tests[] = {
    {"transition_phi_diagonal", test_phi_diagonal},
    {"transition_phi_rotation", test_phi_rotation},
    {"transition_phi_refused", test_phi_refused},
    {"transition_servo_exact", test_servo_exact},
    {"transition_lag_second_order", test_lag_second_order},
    {"transition_param_change", test_param_change},
    {"transition_overflow_recovers", test_overflow_recovers},
    {"transition_nan_input", test_nan_input},
    {"transition_refused", test_refused},
    {0, 0},
};
