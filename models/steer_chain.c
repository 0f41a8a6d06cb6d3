/* steer_chain.c - the actuators of a steering chain (docs/vehicles.md, "V2's steering
 * chain"): an electric actuator, a DC torque motor with its own PI current loop
 * (dc_motor), and the hydraulic servo it pilots, a valve with a spool lag feeding a
 * cylinder whose chamber pressure builds through the oil's bulk modulus against the
 * rack's inertia and the wheels' centring load (hyd_servo). Both are stiff (eigenvalues
 * of some 1e3 to 6e3 rad/s): the fast set of the lane change integrates them.
 *
 * Units are chosen so that the implicit methods' iteration matrices stay well scaled
 * (see servo2 in actuator.c): spool and rack travel in mm, pressure in MPa. */
#include "models.h"

/* ------------------------------------------------------------------ dc_motor */

/* A DC torque motor with an inner PI current loop (NSS, eq. 3). The current controller
   sets the armature voltage u = Kp (i_ref - i) + Ki e, e' = i_ref - i; the armature
   L i' = u - R i - k w; the rotor J w' = k i - b w - ks phi, phi' = w (a torque motor:
   a centring spring ks makes the angle proportional to the current, k/ks rad/A, as in a
   servo valve's pilot stage). Output s = ro phi: the travel of what it moves through a
   lever (the spool) [mm]; also phi, w, i. No voltage limit (the chain's commands stay
   small: docs/vehicles.md). States i [A], w [rad/s], phi [rad], e [A s]. */
enum { M_L, M_R, M_K, M_J, M_B, M_KS, M_KP, M_KI, M_RO, M_NP };
static const char *const mot_u[] = {"iref"};
static const char *const mot_y[] = {"s", "phi", "w", "i"};
static const char *const mot_x[] = {"i", "w", "phi", "e"};
static const char *const mot_p[] = {"L", "R", "k", "J", "b", "ks", "Kp", "Ki", "ro"};
/* a small torque motor (our choice, docs/vehicles.md): L 1 mH, R 1 Ohm (electrical time
   constant 1 ms), k 0.05 N m/A = V s/rad, J 1e-5 kg m^2, b 2e-3 N m s/rad, ks 0.5 N m/rad
   (rotor 224 rad/s, damping 0.45, 0.1 rad/A); current loop Kp 1 V/A, Ki = Kp R/L
   (cancels the armature pole: a first-order loop of Kp/L = 1000 rad/s, 160 Hz; a
   faster loop follows each 1 ms step of a digital command within a fraction of the
   fast set's step, which its error estimate then splits); lever 5 mm/rad */
static const real_t mot_def[M_NP] = {(real_t)1e-3, 1, (real_t)0.05, (real_t)1e-5,
                                     (real_t)2e-3, (real_t)0.5, 1, 1000, 5};

static void mot_output(const rt_args *a, real_t *y)
{
    y[0] = a->p[M_RO] * a->x[2];
    y[1] = a->x[2], y[2] = a->x[1], y[3] = a->x[0];
}

static void mot_deriv(const rt_args *a, real_t *xdot)
{
    const real_t *p = a->p, *x = a->x;
    real_t err = a->u[0] - x[0], volt = p[M_KP] * err + p[M_KI] * x[3];
    xdot[0] = (volt - p[M_R] * x[0] - p[M_K] * x[1]) / p[M_L];
    xdot[1] = (p[M_K] * x[0] - p[M_B] * x[1] - p[M_KS] * x[2]) / p[M_J];
    xdot[2] = x[1];
    xdot[3] = err;
}

/* L, J > 0; R, b, ks, Kp, Ki >= 0; all finite */
static rt_status mot_check(const real_t *p, const void *spec)
{
    (void)spec;
    int ok = rt_all_finite(p, M_NP) && p[M_L] > 0 && p[M_J] > 0 && p[M_R] >= 0 &&
             p[M_B] >= 0 && p[M_KS] >= 0 && p[M_KP] >= 0 && p[M_KI] >= 0;
    return ok ? RT_OK : RT_E_PARAM;
}

const rt_kind mdl_dc_motor_kind = {
    .name = "dc_motor", .type = RT_KIND_NSS, .nu = 1, .ny = 4, .nx = 4, .np = M_NP,
    .u_names = mot_u, .y_names = mot_y, .x_names = mot_x, .p_names = mot_p,
    .p_default = mot_def, .feed = RT_FEED_NONE,
    .autonomous = 1, .check = mot_check, .output = mot_output,
    .deriv = mot_deriv,
    .doc = RT_DOC(
        "DC torque motor with a PI current loop (eq. (3)): u = Kp (iref - i) + Ki e,\n"
        "e' = iref - i; L i' = u - R i - k w; J w' = k i - b w - ks phi; phi' = w.\n"
        "Outputs s = ro phi (the travel it drives through a lever), phi, w, i.\n"
        "L, J > 0; R, b, ks, Kp, Ki >= 0. Defaults: a small torque motor, current loop\n"
        "of 1000 rad/s (Ki = Kp R/L), 0.1 rad/A, lever 5 mm/rad (docs/vehicles.md)."),
    .units = RT_DOC("A mm rad rad/s A A rad/s rad A*s H Ohm N*m/A kg*m^2 N*m*s/rad N*m/rad "
                    "V/A V/(A*s) mm/rad"),
};

/* ------------------------------------------------------------------ hyd_servo */

/* A valve-controlled cylinder moving the steering rack (NSS, eq. 3; the linearized valve
   of Merritt, Hydraulic Control Systems, ch. 5). Spool lag Ts xs' = xv - xs; load flow
   Q = Kq xs - Kc p; the chamber pressure (load pressure p over the total volume Vt,
   bulk modulus beta) p' = 4 beta / Vt (Q - A v); the rack m v' = A p - b v - kL y,
   y' = v, with the wheels' centring (aligning) load kL. Output the wheel angle
   delta = y / arm, and y, p. States xs [mm], p [MPa], y [mm], v [m/s]. */
enum { H_TS, H_KQ, H_KC, H_BETA, H_VT, H_A, H_M, H_B, H_KL, H_ARM, H_NP };
static const char *const hyd_u[] = {"xv"};
static const char *const hyd_y[] = {"delta", "y", "p"};
static const char *const hyd_x[] = {"xs", "p", "y", "v"};
static const char *const hyd_p[] = {"Ts", "Kq", "Kc", "beta", "Vt", "A", "m", "b", "kL",
                                    "arm"};
/* a power-steering cylinder (our choice, docs/vehicles.md): spool lag 1 ms; Kq 0.2 m^2/s
   (0.5 mm of spool: 6 l/min), Kc 2e-12 m^3/(s Pa); beta 1.4 GPa (mineral oil), Vt
   2e-4 m^3, A 5e-4 m^2, rack and wheels 20 kg, b 2000 N s/m; kL 2e5 N/m (aligning
   stiffness at the rack); arm 150 mm: hydraulic natural frequency 600 rad/s */
static const real_t hyd_def[H_NP] = {(real_t)1e-3, (real_t)0.2, (real_t)2e-12, (real_t)1.4e9,
                                     (real_t)2e-4, (real_t)5e-4, 20, 2000, (real_t)2e5, 150};

static void hyd_output(const rt_args *a, real_t *y)
{
    y[0] = a->x[2] / a->p[H_ARM];
    y[1] = a->x[2], y[2] = a->x[1];
}

/* SI inside: xs, y in m (1e-3 mm), p in Pa (1e6 MPa) */
static void hyd_deriv(const rt_args *a, real_t *xdot)
{
    const real_t *p = a->p, *x = a->x;
    real_t xs = (real_t)1e-3 * x[0], pa = (real_t)1e6 * x[1], y = (real_t)1e-3 * x[2];
    real_t q = p[H_KQ] * xs - p[H_KC] * pa - p[H_A] * x[3];
    xdot[0] = (a->u[0] - x[0]) / p[H_TS];
    xdot[1] = (real_t)1e-6 * 4 * p[H_BETA] / p[H_VT] * q;
    xdot[2] = (real_t)1e3 * x[3];
    xdot[3] = (p[H_A] * pa - p[H_B] * x[3] - p[H_KL] * y) / p[H_M];
}

/* Ts, beta, Vt, A, m, arm > 0; Kq, Kc, b, kL >= 0; all finite */
static rt_status hyd_check(const real_t *p, const void *spec)
{
    (void)spec;
    int ok = rt_all_finite(p, H_NP) && p[H_TS] > 0 && p[H_BETA] > 0 && p[H_VT] > 0 &&
             p[H_A] > 0 && p[H_M] > 0 && p[H_ARM] > 0 && p[H_KQ] >= 0 && p[H_KC] >= 0 &&
             p[H_B] >= 0 && p[H_KL] >= 0;
    return ok ? RT_OK : RT_E_PARAM;
}

const rt_kind mdl_hyd_servo_kind = {
    .name = "hyd_servo", .type = RT_KIND_NSS, .nu = 1, .ny = 3, .nx = 4, .np = H_NP,
    .u_names = hyd_u, .y_names = hyd_y, .x_names = hyd_x, .p_names = hyd_p,
    .p_default = hyd_def, .feed = RT_FEED_NONE,
    .autonomous = 1, .check = hyd_check, .output = hyd_output,
    .deriv = hyd_deriv,
    .doc = RT_DOC(
        "Valve-controlled hydraulic cylinder on a steering rack (eq. (3)): spool lag\n"
        "Ts xs' = xv - xs; Q = Kq xs - Kc p; p' = 4 beta/Vt (Q - A v); m v' = A p - b v\n"
        "- kL y, y' = v. Outputs delta = y/arm, y, p. Spool and rack in mm, p in MPa.\n"
        "Ts, beta, Vt, A, m, arm > 0; Kq, Kc, b, kL >= 0. Defaults: a power-steering\n"
        "cylinder, hydraulic natural frequency 600 rad/s (docs/vehicles.md)."),
    .units = RT_DOC("mm rad mm MPa mm MPa mm m/s s m^2/s m^3/(s*Pa) Pa m^3 m^2 kg N*s/m N/m "
                    "mm/rad"),
};
