/* test_tev.c - tests of rt/tev.c, known time events: step-driven linear systems against
 * their closed forms converge at every method's order, with the switch on a step boundary
 * and strictly inside a step of several ticks (also in the background set); a pulse train
 * splits steps at each edge; instants off the grid, or too many in one step, are refused
 * at rt_init and by rt_set_param; a discrete input read from a slower set is taken at the
 * instants where it changes (rt_kind.instant). */
#include "models.h"
#include "testutil.h"
#include "rt_sim.h" /* white box: reads rt_sim's parts (plan, state, work) */

#define DT 1e-3 /* base tick [s] of every scene here */

/* ------------------------------------------------------------------ closed forms */

static const real_t LAG_T = (real_t)0.2; /* T y' = u - y */
static const double SERVO_W = 20, SERVO_Z = 0.3; /* y'' + 2 z w y' + w^2 y = w^2 u */

/* the lag from y = 0 under a unit step at t0 */
static double lag_step(double t, double t0)
{
    return t < t0 ? 0 : 1 - rt_exp((real_t)(-(t - t0) / (double)LAG_T));
}

/* the servo at rest under a unit step at t0 */
static double servo_step(double t, double t0)
{
    if (t < t0)
        return 0;
    double s = t - t0, wd = SERVO_W * (double)rt_sqrt((real_t)(1 - SERVO_Z * SERVO_Z));
    return 1 - (double)rt_exp((real_t)(-SERVO_Z * SERVO_W * s)) *
                   ((double)rt_cos((real_t)(wd * s)) +
                    SERVO_Z * SERVO_W / wd * (double)rt_sin((real_t)(wd * s)));
}

/* the pulse train of pulse_p below, as edges, and the lag under it: exact from edge to
   edge, y = u + (y_a - u) exp(-(t - t_a) / T) */
static const double PULSE_T0 = 0.013, PULSE_P = 0.1, PULSE_W = 0.03;
static double lag_pulse(double t, double unused)
{
    (void)unused;
    double y = 0, ta = 0;
    for (int k = 0;; k++) {
        double on = PULSE_T0 + k * PULSE_P, off = on + PULSE_W;
        if (t <= on)
            return y * (double)rt_exp((real_t)(-(t - ta) / (double)LAG_T));
        y *= (double)rt_exp((real_t)(-(on - ta) / (double)LAG_T));
        if (t <= off)
            return 1 + (y - 1) * (double)rt_exp((real_t)(-(t - on) / (double)LAG_T));
        y = 1 + (y - 1) * (double)rt_exp((real_t)(-(off - on) / (double)LAG_T));
        ta = off;
    }
}

/* ------------------------------------------------------------------ the scenes */

enum { LAG, SERVO, PULSE };
static real_t step_p[3] = {0, 0, 1};
static const real_t pulse_p[] = {(real_t)PULSE_T0, (real_t)PULSE_P, (real_t)PULSE_W, 0, 1};
static const real_t lag_p[] = {1, (real_t)0.2};
static const real_t servo_p[] = {(real_t)SERVO_W, (real_t)SERVO_Z, 1};
static const rt_conn conn[] = {{0, 0, 1, 0}};

/* source -> plant in one set of `ratio` ticks (in the background when bg) */
static rt_scene scene(int which, const rt_integrator *m, uint32_t ratio, int bg,
                      rt_block *bl, rt_set *set)
{
    bl[0] = (rt_block){.name = "Src", .kind = which == PULSE ? &mdl_pulse_kind : &mdl_step_kind,
                       .p = which == PULSE ? pulse_p : step_p};
    bl[1] = (rt_block){.name = "Plant", .kind = which == SERVO ? &mdl_servo2_kind : &mdl_pt1_kind,
                       .p = which == SERVO ? servo_p : lag_p};
    /* no substeps on the estimate (ROS2 splits a step above its accuracy): the method's
       own order is measured */
    *set = (rt_set){.name = "main", .method = m, .ratio = ratio, .background = (uint8_t)bg,
                    .cfg = {.accuracy = 1}};
    return (rt_scene){.name = "tev", .dt = (real_t)DT, .t_end = 1, .blocks = bl, .nblocks = 2,
                      .conns = conn, .nconns = 1, .sets = set, .nsets = 1,
                      .bg = bg ? &rt_bg : 0};
}

/* the largest error of the plant's first state at the set's steps over the run */
static double run_error(int which, const rt_integrator *m, uint32_t ratio, int bg,
                        double (*exact)(double, double), double t0)
{
    rt_block bl[2];
    rt_set set;
    rt_scene sc = scene(which, m, ratio, bg, bl, &set);
    if (!TH_CHECK(rt_init(&sc, &tu_sim) == RT_OK))
        return -1;
    double e = 0;
    while (rt_tick(&sc, &tu_sim) == RT_OK || rt_ticks_done(&tu_sim) == rt_tick_count(&tu_sim)) {
        if (rt_ticks_done(&tu_sim) % ratio == 0) {
            double t = (double)rt_ticks_done(&tu_sim) * DT;
            double d = (double)tu_sim.state.x[tu_sim.plan.x_off[1]] - exact(t, t0);
            e = d < 0 ? -d > e ? -d : e : d > e ? d : e;
        }
        if (rt_ticks_done(&tu_sim) >= rt_tick_count(&tu_sim))
            break;
    }
    return e;
}

/* log2 of a ratio (rt_log is the natural one) */
static double log2d(double r)
{
    return (double)rt_log((real_t)r) / 0.69314718055994531;
}

/* every method: the errors at steps of r, r/2 and r/4 ticks, and the observed order of
   the last halving at least the method's order less 0.2. Errors near rounding (the
   transition method is exact for a piecewise constant input) tell no order: noted */
static void orders(int which, uint32_t r, int bg, double (*exact)(double, double), double t0)
{
    double floor = RT_REAL_IS_FLOAT ? 1e-4 : 5e-14;
    for (const rt_integrator_entry *e = rt_integrators; e->name; e++) {
        const rt_integrator *m = e->method;
        double e1 = run_error(which, m, r, bg, exact, t0);
        double e2 = run_error(which, m, r / 2, bg, exact, t0);
        double e3 = run_error(which, m, r / 4, bg, exact, t0);
        th_note(e->name, e3);
        if (e3 < floor || e2 < floor)
            continue;
        double p = log2d(e2 / e3);
        th_note("  observed order", p);
        if (!TH_CHECK(p >= m->order - 0.2) || !TH_CHECK(e1 > e2))
            th_note("  failing order at steps of r/2 -> r/4 ticks", p);
    }
}

/* the switch on a step boundary: 0.48 s is a multiple of 16, 8 and 4 ms */
static void test_lag_boundary(void)
{
    step_p[0] = (real_t)0.48;
    orders(LAG, 16, 0, lag_step, 0.48);
}

/* strictly inside every step: 501 ticks is odd (steps of 16, 8 and 4 ticks split) */
static void test_lag_inside(void)
{
    step_p[0] = (real_t)0.501;
    orders(LAG, 16, 0, lag_step, 0.501);
}

static void test_servo_boundary(void)
{
    step_p[0] = (real_t)0.48;
    orders(SERVO, 8, 0, servo_step, 0.48);
}

static void test_servo_inside(void)
{
    step_p[0] = (real_t)0.501;
    orders(SERVO, 8, 0, servo_step, 0.501);
}

/* each edge of the pulse train (13, 43, 113, ... ms) ends a part of a step */
static void test_pulse(void)
{
    orders(PULSE, 16, 0, lag_pulse, 0);
}

/* a background set's step splits too (rt/bg.c runs rti_tev_step); RK4 to its order */
static void test_background(void)
{
    step_p[0] = (real_t)0.501;
    double e2 = run_error(LAG, &rt_rk4, 8, 1, lag_step, 0.501);
    double e3 = run_error(LAG, &rt_rk4, 4, 1, lag_step, 0.501);
    th_note("background rk4, steps of 8 and 4 ticks", e3);
    if (!RT_REAL_IS_FLOAT)
        TH_CHECK(log2d(e2 / e3) >= 3.8);
}

/* the step before the instant never sees the new value: at the instant the state is
   still exactly 0; and a step of 8 ticks with the instant 3 ticks in ends at the lag's
   exact value to the method's accuracy (without the split, RK4's stages at 4 and 8 ticks
   read the new value over the whole step: 1e-3 off) */
static void test_no_change_before(void)
{
    rt_block bl[2];
    rt_set set;
    rt_scene sc = scene(LAG, &rt_rk4, 1, 0, bl, &set);
    step_p[0] = (real_t)0.48;
    if (!TH_CHECK(rt_init(&sc, &tu_sim) == RT_OK))
        return;
    tu_run_to(&sc, (real_t)0.48);
    TH_CHECK(tu_sim.state.x[tu_sim.plan.x_off[1]] == 0);
    TH_CHECK(tu_y(&sc, "Src", 0) == 1); /* the tick shows the right limit */
    sc = scene(LAG, &rt_rk4, 8, 0, bl, &set);
    step_p[0] = (real_t)0.483;
    if (!TH_CHECK(rt_init(&sc, &tu_sim) == RT_OK))
        return;
    tu_run_to(&sc, (real_t)0.488);
    double e = (double)tu_sim.state.x[tu_sim.plan.x_off[1]] - lag_step(0.488, 0.483);
    th_note("lag 5 ms after a step 3 ticks into a step of 8, error", e);
    TH_CHECK(e < (RT_REAL_IS_FLOAT ? 1e-5 : 1e-9) && e > -(RT_REAL_IS_FLOAT ? 1e-5 : 1e-9));
}

/* an instant off the grid is refused, naming the block; so is a parameter change that
   moves it off; and a step split into more than RT_TEV_PARTS_MAX parts */
static void test_refused(void)
{
    rt_block bl[2];
    rt_set set;
    rt_scene sc = scene(LAG, &rt_rk4, 1, 0, bl, &set);
    step_p[0] = (real_t)0.5005;
    TH_CHECK(rt_init(&sc, &tu_sim) == RT_E_SCENE);
    TH_CHECK(th_has(rt_error_text(&tu_sim), "block Src"));
    TH_CHECK(RT_REAL_IS_FLOAT || th_has(rt_error_text(&tu_sim), "t = 0.5005 s"));
    step_p[0] = (real_t)0.0004; /* before the first half tick: off the grid too */
    TH_CHECK(rt_init(&sc, &tu_sim) == RT_E_SCENE);
    step_p[0] = (real_t)0.5;
    if (!TH_CHECK(rt_init(&sc, &tu_sim) == RT_OK))
        return;
    TH_CHECK(rt_set_param(&sc, &tu_sim, "Src", "t0", (real_t)0.7003) == RT_E_PARAM);
    TH_CHECK(rt_set_param(&sc, &tu_sim, "Src", "t0", (real_t)0.7) == RT_OK);
    /* edges every 2 ms in steps of 16 ticks: 8 instants inside a step */
    static const real_t fast[] = {(real_t)0.001, (real_t)0.004, (real_t)0.002, 0, 1};
    rt_scene ps = scene(PULSE, &rt_rk4, 4 * RT_TEV_PARTS_MAX, 0, bl, &set);
    bl[0].p = fast;
    TH_CHECK(rt_init(&ps, &tu_sim) == RT_E_SCENE);
    TH_CHECK(th_has(rt_error_text(&tu_sim), "RT_TEV_PARTS_MAX"));
}

/* a root that crosses by the jump alone (a relay on the step's level): x counts its
   events, z' = 1 is reset by each, so z at the end dates it. Fired once, at the instant
   to rounding, in a set of 1 tick (the tick keeps the step end's roots, rt/sim.c) and
   of 8 (the split's second part sees the crossing from its start) */
static const char *const cnt_x[] = {"x", "z"};
static const char *const cnt_u[] = {"u"};
static const int8_t cnt_dir[] = {1};
static void cnt_out(const rt_args *a, real_t *y) { y[0] = a->x[0]; }
static void cnt_deriv(const rt_args *a, real_t *xd) { (void)a, xd[0] = 0, xd[1] = 1; }
static void cnt_roots(const rt_args *a, real_t *r) { r[0] = a->u[0] - (real_t)0.5; }
static void cnt_event(const rt_args *a, uint16_t which, real_t *x, real_t *d)
{
    (void)a, (void)which, (void)d;
    x[0] += 1, x[1] = 0;
}
static const rt_kind counter = {
    .name = "counter", .type = RT_KIND_NSS, .nu = 1, .ny = 1, .nx = 2, .nr = 1,
    .u_names = cnt_u, .y_names = cnt_x, .x_names = cnt_x, .feed = RT_FEED_NONE,
    .root_dir = cnt_dir, .output = cnt_out, .deriv = cnt_deriv, .roots = cnt_roots,
    .event = cnt_event,
};

static void test_root_at_instant(void)
{
    for (uint32_t r = 1; r <= 8; r *= 8) {
        rt_block bl[2];
        rt_set set;
        rt_scene sc = scene(LAG, &rt_rk4, r, 0, bl, &set);
        bl[1] = (rt_block){.name = "Cnt", .kind = &counter};
        step_p[0] = r == 1 ? (real_t)0.5 : (real_t)0.501;
        if (!TH_CHECK(rt_init(&sc, &tu_sim) == RT_OK))
            return;
        tu_run_to(&sc, 1);
        double z = (double)tu_sim.state.x[1], at = 1 - z - (double)step_p[0];
        th_note(r == 1 ? "set of 1 tick: event after the instant by [s]"
                       : "set of 8 ticks: event after the instant by [s]", at);
        TH_CHECK(tu_sim.state.x[0] == 1 && rt_stats_of(&tu_sim)->count[RT_CNT_EVENTS] == 1);
        TH_CHECK(at < (RT_REAL_IS_FLOAT ? 1e-5 : 1e-12) && at > -(RT_REAL_IS_FLOAT ? 1e-5 : 1e-12));
        TH_CHECK(rt_stats_of(&tu_sim)->status == RT_OK);
    }
}

/* values taken at instants (rt_kind.instant, an FMU's discrete input): Hold in a set of 3
   ticks reads, held, the ramp y = t of a set of 4 ticks. Its instant service takes a new
   value into x0 (counting in x2, dating in x3), its derivative integrates the held value
   (x1' = x0) and never reads u. Each source point inside a step of 3 ticks ends a part
   there, so every point is taken at its time: x2 = floor(t / 4 ticks), x3 = its last
   point, x1 = the staircase's integral, exactly (rk4 on constant derivatives). */
static const char *const hold_x[] = {"v", "s", "n", "at"};
static const char *const hold_u[] = {"u"};
static const char *const ramp_x[] = {"y"};
static const uint8_t hold_disc[] = {1};
static void hold_out(const rt_args *a, real_t *y) { y[0] = a->x[1]; }
static void hold_deriv(const rt_args *a, real_t *xd)
{
    xd[0] = 0, xd[1] = a->x[0], xd[2] = 0, xd[3] = 0;
}
static int hold_instant(const rt_args *a, real_t *x, real_t *d)
{
    (void)d;
    if (a->u[0] == x[0])
        return 0;
    x[0] = a->u[0], x[2] += 1, x[3] = a->t;
    return 1;
}
static const rt_kind holder = {
    .name = "holder", .type = RT_KIND_NSS, .nu = 1, .ny = 1, .nx = 4, .u_names = hold_u,
    .y_names = hold_x + 1, .x_names = hold_x, .feed = RT_FEED_NONE, .output = hold_out,
    .deriv = hold_deriv, .instant = hold_instant, .u_discrete = hold_disc,
};
static void ramp_out(const rt_args *a, real_t *y) { y[0] = a->x[0]; }
static void ramp_deriv(const rt_args *a, real_t *xd) { (void)a, xd[0] = 1; }
static const rt_kind ramp = {
    .name = "ramp", .type = RT_KIND_NSS, .nx = 1, .ny = 1, .y_names = ramp_x, .x_names = ramp_x,
    .feed = RT_FEED_NONE, .output = ramp_out, .deriv = ramp_deriv,
};

static void test_input_instants(void)
{
    rt_block bl[2] = {{.name = "Ramp", .kind = &ramp, .set = 0},
                      {.name = "Hold", .kind = &holder, .set = 1}};
    rt_set sets[2] = {{.name = "src", .method = &rt_rk4, .ratio = 4, .cfg = {.accuracy = 1}},
                      {.name = "hold", .method = &rt_rk4, .ratio = 3, .cfg = {.accuracy = 1}}};
    rt_scene sc = {.name = "instants", .dt = (real_t)DT, .t_end = (real_t)0.12, .blocks = bl,
                   .nblocks = 2, .conns = conn, .nconns = 1, .sets = sets, .nsets = 2};
    if (!TH_CHECK(rt_init(&sc, &tu_sim) == RT_OK))
        return;
    double worst = 0;
    int counts = 1;
    while (rt_tick(&sc, &tu_sim) == RT_OK || rt_ticks_done(&tu_sim) == rt_tick_count(&tu_sim)) {
        uint64_t k = rt_ticks_done(&tu_sim);
        if (k % 3 == 0) { /* the holder's state is at this tick */
            const real_t *x = tu_sim.state.x + tu_sim.plan.x_off[1];
            double t = (double)k * DT, d = 4 * DT, n = (double)(k / 4);
            double s = d * d * n * (n - 1) / 2 + d * n * (t - d * n);
            double e1 = (double)x[1] - s, e3 = (double)x[3] - d * n;
            e1 = e1 < 0 ? -e1 : e1, e3 = e3 < 0 ? -e3 : e3;
            worst = e1 > worst ? e1 : worst;
            worst = e3 > worst ? e3 : worst;
            counts &= x[2] == (real_t)n;
        }
        if (k >= rt_tick_count(&tu_sim))
            break;
    }
    th_note("held input: largest error of its integral and of its instants", worst);
    TH_CHECK(counts && worst < (RT_REAL_IS_FLOAT ? 1e-5 : 1e-14));
    TH_CHECK(rt_stats_of(&tu_sim)->status == RT_OK);
}

const th_test th_tev_tests[] = {
    {"tev_lag_boundary", test_lag_boundary},
    {"tev_lag_inside", test_lag_inside},
    {"tev_servo_boundary", test_servo_boundary},
    {"tev_servo_inside", test_servo_inside},
    {"tev_pulse", test_pulse},
    {"tev_background", test_background},
    {"tev_no_change_before", test_no_change_before},
    {"tev_refused", test_refused},
    {"tev_root_at_instant", test_root_at_instant},
    {"tev_input_instants", test_input_instants},
    {0, 0},
};
