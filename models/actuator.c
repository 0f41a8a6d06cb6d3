/* actuator.c - a driven arm: a stiff second-order servo (servo2), the controller that
 * raises an arm along a quintic reference (arm_pd), and the motor that turns the servo's
 * torque into the force on the arm's end point (arm_motor). Scenes pendulum10_actuated
 * and pendulum10_actuated_single drive the first link of the ten-body pendulum with them.
 *
 * The arm turns in the x-z plane about the y axis through the origin; its angle is
 * theta = atan2(z, x) of the end point: -pi/2 hanging along -z, 0 horizontal along +x.
 * A positive torque turns it towards larger theta (about the -y axis). */
#include "models.h"

/* ------------------------------------------------------------------ servo2 */

/* y'' + 2 zeta omega y' + omega^2 y = omega^2 k u: a servo of natural frequency omega
   [rad/s] and damping zeta. Eigenvalues -zeta omega +- i omega sqrt(1 - zeta^2): with the
   default 2 pi 1000 rad/s and zeta = 0.7 they lie 6283 rad/s from the origin, which makes
   any set integrating the servo stiff. States y and w = y' / omega, both in the unit of
   y: y' = omega w, w' = omega (k u - y) - 2 zeta omega w. With w instead of y' the
   Jacobian's entries grow with omega, not omega^2, which keeps the iteration matrix of
   an implicit method integrating the servo together with its load well scaled: with y'
   as a state, 2 pi 1000 rad/s and a continuous controller of gain 400 N m/rad put 1e10
   into the Jacobian and some 1e7 next to 1 into the iteration matrix, which the
   runtime's pivot threshold took for singular. Outputs y and y'. */
static const char *const servo_u[] = {"u"};
static const char *const servo_y[] = {"y", "yd"};
static const char *const servo_x[] = {"y", "w"};
static const char *const servo_p[] = {"omega", "zeta", "k"};
static const real_t servo_p_default[] = {(real_t)6283.1853071795865, (real_t)0.7, 1};

static void servo_output(const rt_args *a, real_t *y)
{
    y[0] = a->x[0];
    y[1] = a->p[0] * a->x[1];
}

static void servo_deriv(const rt_args *a, real_t *xdot)
{
    real_t om = a->p[0], z = a->p[1], k = a->p[2];
    xdot[0] = om * a->x[1];
    xdot[1] = om * (k * a->u[0] - a->x[0]) - 2 * z * om * a->x[1];
}

static rt_status servo_check(const real_t *p, const void *spec)
{
    (void)spec;
    return p[0] > 0 && p[1] > 0 && rt_isfinite(p[0]) && rt_isfinite(p[1]) &&
                   rt_isfinite(p[2])
               ? RT_OK
               : RT_E_PARAM;
}

const rt_kind mdl_servo2_kind = {
    .name = "servo2", .type = RT_KIND_NSS,
    .nu = 1, .ny = 2, .nx = 2, .np = 3,
    .u_names = servo_u, .y_names = servo_y, .x_names = servo_x, .p_names = servo_p,
    .p_default = servo_p_default,
    .feed = RT_FEED_NONE, .autonomous = 1, .linear = 1,
    .check = servo_check, .output = servo_output, .deriv = servo_deriv,
    .doc = RT_DOC(
        "Servo y'' + 2 zeta omega y' + omega^2 y = omega^2 k u (eq. (3)), states y and\n"
        "w = y'/omega: y' = omega w, w' = omega (k u - y) - 2 zeta omega w.\n"
        "Outputs y and y'. omega: natural frequency, > 0; zeta: damping ratio, > 0;\n"
        "k: gain; all finite. Units as in the actuated scenes (a torque); any unit works."),
    .units = RT_DOC("N*m N*m N*m/s N*m N*m rad/s - -"),
};

/* ------------------------------------------------------------------ arm_pd */

/* A digital controller (DSS, eq. 5): at every sample (period h, the block's ts) it reads
   the arm's end point x, z [m], measures the angle theta = atan2(z, x) (an encoder, range
   (-pi, pi]) and its rate as the backward difference w = (theta - thp) / h (0 at the
   first sample), and computes the command
       c = j thr'' + m_g cos(theta) + kp (thr - theta) + kd (thr' - w),
   computed torque: the feed-forward of an arm of inertia j [kg m^2] carrying the static
   moment m_g [N m] of everything that hangs from its end, plus PD on the angle. The
   reference is the quintic blend S(s) = 10 s^3 - 15 s^4 + 6 s^5, s = (t - t0) / T clipped
   to [0, 1], from th0 to th1 [rad] (zero rate and acceleration at both ends). Like a
   real drive it applies the command one sample later (computation delay) and holds it
   (zero-order hold): output u is the command of the previous sample, so no output
   depends directly on an input. Outputs u [N m], theta (the last measured angle) and thr
   (the reference now) [rad]; discrete states c [N m], thp [rad] and started (0 before
   the first sample). */
static const char *const pd_u[] = {"x", "z"};
static const char *const pd_y[] = {"u", "theta", "thr"};
static const char *const pd_d[] = {"c", "thp", "started"};
static const char *const pd_p[] = {"th0", "th1", "t0", "T", "kp", "kd", "j", "m_g"};
/* hanging to horizontal over 6 s from t = 0. PD: with j = 10 kg m^2 (the chain moving
   with the arm) the closed loop has omega = 6.3 rad/s, zeta = 0.32; with j = 1 kg m^2
   (B1 alone: the chain's first reaction) a double pole at -20 rad/s. m_g: ten 1 kg
   points on a 1 m arm. */
static const real_t pd_p_default[] = {
    -(real_t)RT_HALF_PI, 0, 0, 6, 400, 40, 10, (real_t)98.1,
};
static const real_t pd_d_default[] = {0, -(real_t)RT_HALF_PI, 0};

/* the blend's argument s at time t, clipped to [0, 1] */
static real_t pd_s(const real_t *p, real_t t)
{
    real_t s = (t - p[2]) / p[3];
    return s < 0 ? 0 : s > 1 ? 1 : s;
}

/* reference angle at blend argument s */
static real_t pd_angle(const real_t *p, real_t s)
{
    real_t s2 = s * s, s3 = s2 * s;
    return p[0] + (p[1] - p[0]) * s3 * (10 - 15 * s + 6 * s2);
}

/* reference angle, rate and acceleration at time t */
static void pd_reference(const real_t *p, real_t t, real_t r[3])
{
    real_t T = p[3], s = pd_s(p, t), d = p[1] - p[0];
    real_t s2 = s * s;
    r[0] = pd_angle(p, s);
    r[1] = d * 30 * s2 * (1 - 2 * s + s2) / T;
    r[2] = d * 60 * s * (1 - 3 * s + 2 * s2) / (T * T);
}

/* at every tick the output shows the reference angle only: its rate and acceleration,
   two divisions, are the update's */
static void pd_output(const rt_args *a, real_t *y)
{
    y[0] = a->d[0];
    y[1] = a->d[1];
    y[2] = pd_angle(a->p, pd_s(a->p, a->t));
}

/* one sample: measure, compute the command applied from the next sample on */
static void pd_update(const rt_args *a, real_t *dnext)
{
    const real_t *p = a->p;
    real_t r[3], th = rt_atan2(a->u[1], a->u[0]);
    real_t w = a->d[2] != 0 ? (th - a->d[1]) / a->h : 0;
    pd_reference(p, a->t, r);
    dnext[0] = p[6] * r[2] + p[7] * rt_cos(th) + p[4] * (r[0] - th) + p[5] * (r[1] - w);
    dnext[1] = th;
    dnext[2] = 1;
}

static rt_status pd_check(const real_t *p, const void *spec)
{
    (void)spec;
    for (int i = 0; i < 8; i++)
        if (!rt_isfinite(p[i]))
            return RT_E_PARAM;
    return p[3] > 0 ? RT_OK : RT_E_PARAM;
}

const rt_kind mdl_arm_pd_kind = {
    .name = "arm_pd", .type = RT_KIND_DSS,
    .nu = 2, .ny = 3, .nd = 3, .np = 8,
    .u_names = pd_u, .y_names = pd_y, .d_names = pd_d, .p_names = pd_p,
    .p_default = pd_p_default, .d_default = pd_d_default,
    .feed = RT_FEED_NONE,
    .check = pd_check, .output = pd_output, .update = pd_update,
    .doc = RT_DOC(
        "Digital arm controller (DSS, eq. (5)), sample period h: theta = atan2(z, x),\n"
        "w = (theta - thp)/h (0 at the first sample), c = j thr'' + m_g cos(theta)\n"
        "+ kp (thr - theta) + kd (thr' - w), applied a sample later and held (output u).\n"
        "Reference thr from th0 to th1: S(s) = 10 s^3 - 15 s^4 + 6 s^5, s = (t - t0)/T\n"
        "in [0, 1]. kp, kd: PD gains; j: arm inertia; m_g: static moment; T > 0; finite."),
    .units = RT_DOC("m m N*m rad rad N*m rad - rad rad s s N*m/rad N*m*s/rad kg*m^2 N*m"),
};

/* ------------------------------------------------------------------ arm_motor */

/* A motor at the origin turning a massless arm whose end is the point (x, z): the torque
   tau [N m] acts on the point as the force tau / r^2 (-z, 0, x) [N], perpendicular to the
   arm, of moment tau about the -y axis (r = |(x, z)|; zero force at r = 0). */
static const char *const mot_u[] = {"tau", "x", "z"};
static const char *const mot_y[] = {"fx", "fy", "fz"};

static void mot_output(const rt_args *a, real_t *y)
{
    real_t x = a->u[1], z = a->u[2], rr = x * x + z * z;
    real_t f = rr > 0 ? a->u[0] / rr : 0;
    y[0] = -f * z;
    y[1] = 0;
    y[2] = f * x;
}

const rt_kind mdl_arm_motor_kind = {
    .name = "arm_motor", .type = RT_KIND_OUTPUT,
    .nu = 3, .ny = 3,
    .u_names = mot_u, .y_names = mot_y,
    .feed = RT_FEED_ALL, .autonomous = 1,
    .output = mot_output,
    .doc = RT_DOC(
        "Motor at the origin turning a massless arm to the point (x, z), output only with\n"
        "throughput (eq. (1)): force f = tau / (x^2 + z^2) (-z, 0, x), perpendicular to\n"
        "the arm, of moment tau about -y (f = 0 at the origin). No parameters."),
    .units = RT_DOC("N*m m m N N N"),
};
