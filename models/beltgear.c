/* beltgear.c - the parts of the belt gear of the paper's Fig. 6, split so that the
 * drive train closes an actual algebraic loop (every part on it has throughput):
 *   pulley: angular acceleration from torque and belt force, a = (M + s r F) / J;
 *   rotor:  integrates a into angle and speed (no throughput);
 *   belt:   force difference F_t - F_s = 2 (k D + c D') + m (r1 a1 - r2 a2),
 *           D = r1 phi1 - r2 phi2, with a belt-inertia term that depends on the
 *           accelerations (the throughput that makes the loop actual). */
#include "models.h"

/* ---- pulley: inputs M [N m], F [N]; output a [rad/s^2]; parameters J [kg m^2],
   r [m], s (+1 or -1: the side the belt force acts on) */
static const char *const pul_u[] = {"M", "F"};
static const char *const pul_y[] = {"a"};
static const char *const pul_p[] = {"J", "r", "s"};
static const real_t pul_def[] = {(real_t)0.01, (real_t)0.05, -1};

static void pul_out(const rt_args *a, real_t *y)
{
    y[0] = (a->u[0] + a->p[2] * a->p[1] * a->u[1]) / a->p[0];
}

static rt_status pul_check(const real_t *p, const void *spec)
{
    (void)spec;
    return p[0] > 0 && p[1] > 0 && (p[2] == 1 || p[2] == -1) ? RT_OK : RT_E_PARAM;
}

const rt_kind mdl_pulley_kind = {
    .name = "pulley", .type = RT_KIND_OUTPUT,
    .nu = 2, .ny = 1, .np = 3,
    .u_names = pul_u, .y_names = pul_y, .p_names = pul_p, .p_default = pul_def,
    .feed = RT_FEED_ALL, .autonomous = 1, .check = pul_check, .output = pul_out,
    .doc = RT_DOC(
        "Pulley of the belt gear (Fig. 6), output only with throughput (eq. (1)):\n"
        "angular acceleration a = (M + s r F) / J from drive torque M and belt force F.\n"
        "J: moment of inertia, > 0; r: radius, > 0; s: +1 or -1, the side the belt force\n"
        "acts on."),
    .units = RT_DOC("N*m N rad/s^2 kg*m^2 m -"),
};

/* ---- rotor: input a; states and outputs phi [rad], omega [rad/s] */
static const char *const rot_u[] = {"a"};
static const char *const rot_x[] = {"phi", "omega"};

static void rot_out(const rt_args *a, real_t *y)
{
    y[0] = a->x[0];
    y[1] = a->x[1];
}

static void rot_deriv(const rt_args *a, real_t *xdot)
{
    xdot[0] = a->x[1];
    xdot[1] = a->u[0];
}

const rt_kind mdl_rotor_kind = {
    .name = "rotor", .type = RT_KIND_NSS,
    .nu = 1, .ny = 2, .nx = 2,
    .u_names = rot_u, .y_names = rot_x, .x_names = rot_x,
    .feed = RT_FEED_NONE, .autonomous = 1, .output = rot_out, .deriv = rot_deriv,
    .doc = RT_DOC(
        "Rotor of the belt gear (Fig. 6, eq. (3)): integrates the angular acceleration a,\n"
        "phi' = omega, omega' = a; outputs phi and omega (no throughput). No parameters."),
    .units = RT_DOC("rad/s^2 rad rad/s rad rad/s"),
};

/* ---- belt: inputs phi1, omega1, phi2, omega2, a1, a2; output F [N];
   parameters k [N/m], c [N s/m], m [kg], r1, r2 [m] */
static const char *const belt_u[] = {"phi1", "omega1", "phi2", "omega2", "a1", "a2"};
static const char *const belt_y[] = {"F"};
static const char *const belt_p[] = {"k", "c", "m", "r1", "r2"};
static const real_t belt_def[] = {(real_t)1e5, 20, (real_t)0.5, (real_t)0.05, (real_t)0.1};
static const uint8_t belt_feed[] = {0, 0, 0, 0, 1, 1}; /* only the accelerations */

static void belt_out(const rt_args *a, real_t *y)
{
    const real_t *u = a->u, *p = a->p;
    real_t d = p[3] * u[0] - p[4] * u[2], dd = p[3] * u[1] - p[4] * u[3];
    y[0] = 2 * (p[0] * d + p[1] * dd) + p[2] * (p[3] * u[4] - p[4] * u[5]);
}

static rt_status belt_check(const real_t *p, const void *spec)
{
    (void)spec;
    return p[0] >= 0 && p[1] >= 0 && p[2] >= 0 && p[3] > 0 && p[4] > 0 ? RT_OK : RT_E_PARAM;
}

const rt_kind mdl_belt_kind = {
    .name = "belt", .type = RT_KIND_OUTPUT,
    .nu = 6, .ny = 1, .np = 5,
    .u_names = belt_u, .y_names = belt_y, .p_names = belt_p, .p_default = belt_def,
    .feed = RT_FEED_TABLE, .autonomous = 1, .feed_table = belt_feed,
    .check = belt_check, .output = belt_out,
    .doc = RT_DOC(
        "Elastic belt of the belt gear (Fig. 6), output only (eq. (1)): force difference\n"
        "F = F_t - F_s = 2 (k D + c D') + m (r1 a1 - r2 a2), D = r1 phi1 - r2 phi2;\n"
        "throughput only from a1, a2 (the belt inertia closes the algebraic loop).\n"
        "k: stiffness, >= 0; c: damping, >= 0; m: belt mass, >= 0; r1, r2: radii, > 0."),
    .units = RT_DOC("rad rad/s rad rad/s rad/s^2 rad/s^2 N N/m N*s/m kg m m"),
};
