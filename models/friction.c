/* friction.c - a mass on a surface with dry (Coulomb) friction, stick and slip (NSS with
 * two state events): the friction force switches with the direction of motion, so its
 * right-hand side is discontinuous at v = 0. The switch is a root, not a sign(v) inside
 * deriv: a fixed step across it (and a finite-difference Jacobian straddling it) would
 * mix the two laws, and an explicit method chatters about v = 0 at any step.
 *
 * Discrete state mode: +1 sliding forward, -1 backward, 0 stuck. Sliding with mode s,
 * x' = v, m v' = F - s Fc; stuck, x' = v' = 0. Root 0 (sliding: s v falls through 0) is
 * the stop: the mass sticks if |F| <= Fs, else it slides on in the direction of F.
 * Root 1 (stuck: |F| - Fs rises through 0) is the break-away. Each root is held at a
 * constant of the right sign in the other mode, so only the mode's own switch can fire.
 * States x [m], v [m/s]; input F [N]; parameters m [kg], Fc [N] (sliding friction), Fs [N]
 * (static friction, >= Fc); outputs x, v. */
#include "models.h"

static const char *const u_names[] = {"F"};
static const char *const x_names[] = {"x", "v"};
static const char *const d_names[] = {"mode"};
static const char *const p_names[] = {"m", "Fc", "Fs"};
static const real_t p_default[] = {1, 1, 1};
static const real_t x_default[] = {0, 1};
static const real_t d_default[] = {1};
static const int8_t root_dir[] = {-1, 1};

static void output(const rt_args *a, real_t *y)
{
    y[0] = a->x[0];
    y[1] = a->x[1];
}

static void deriv(const rt_args *a, real_t *xdot)
{
    real_t s = a->d[0];
    xdot[0] = s != 0 ? a->x[1] : 0;
    xdot[1] = s != 0 ? (a->u[0] - s * a->p[1]) / a->p[0] : 0;
}

static void roots(const rt_args *a, real_t *r)
{
    real_t s = a->d[0], f = a->u[0];
    r[0] = s != 0 ? s * a->x[1] : 1;
    r[1] = s != 0 ? -1 : (f < 0 ? -f : f) - a->p[2];
}

/* the mode after the motion stopped or the force broke the mass away: stuck while the
   force stays within static friction, else sliding the way it pushes */
static void event(const rt_args *a, uint16_t which, real_t *x, real_t *d)
{
    real_t f = a->u[0];
    x[1] = 0;
    /* a break-away is located where |F| meets Fs, to rounding: it slides the way F
       pushes, whatever side of Fs its last bit is on */
    if (which == 1)
        d[0] = f < 0 ? -1 : 1;
    else
        d[0] = f > a->p[2] ? 1 : f < -a->p[2] ? -1 : 0;
}

static rt_status check(const real_t *p, const void *spec)
{
    (void)spec;
    return p[0] > 0 && p[1] >= 0 && p[2] >= p[1] && rt_isfinite(p[2]) ? RT_OK : RT_E_PARAM;
}

/* the mode the motion needs: sliding the way v points (at v = 0 any mode: the start's
   roots settle it). A mode against v would hold the mass stuck while it moves, or fire
   the stop at t = 0 and take its velocity away */
static const char *check_start(const rt_args *a)
{
    real_t v = a->x[1], s = a->d[0];
    if (s != 1 && s != 0 && s != -1)
        return "mode must be +1, 0 or -1";
    if ((v > 0 && s != 1) || (v < 0 && s != -1))
        return "mode must be +1 for v > 0 and -1 for v < 0";
    return 0;
}

const rt_kind mdl_coulomb_kind = {
    .name = "coulomb", .type = RT_KIND_NSS,
    .nu = 1, .ny = 2, .nx = 2, .nd = 1, .np = 3, .nr = 2,
    .u_names = u_names, .y_names = x_names, .x_names = x_names, .d_names = d_names,
    .p_names = p_names, .p_default = p_default, .x_default = x_default,
    .d_default = d_default, .root_dir = root_dir,
    .feed = RT_FEED_NONE, .autonomous = 1, .roots_at_start = 1,
    .check = check, .check_start = check_start, .output = output, .deriv = deriv,
    .roots = roots, .event = event,
    .doc = RT_DOC(
        "Mass on a surface with dry (Coulomb) friction: stick and slip by two roots.\n"
        "mode +1/-1: sliding forward/backward, x' = v, m v' = F - mode Fc;\n"
        "mode 0: stuck, x' = v' = 0. Root 0: the sliding speed mode v falls through 0\n"
        "(stop): stuck if |F| <= Fs, else sliding the way F pushes. Root 1: |F| - Fs\n"
        "rises through 0 while stuck (break-away). The initial mode must match the\n"
        "initial v (+1 for v > 0, -1 for v < 0, 0 for v = 0); stuck under |F| > Fs\n"
        "at the start, it breaks away at once. Outputs x, v.\n"
        "m > 0; 0 <= Fc <= Fs (Fs finite)."),
    .units = RT_DOC("N m m/s m m/s - kg N N"),
};
