/* oscillator.c - the harmonic oscillator x'' = -omega^2 x as a nonlinear-state-space
 * kind (eq. 3): states x [m], v [m/s]; parameter omega [rad/s]. */
#include "models.h"

static const char *const x_names[] = {"x", "v"};
static const char *const p_names[] = {"omega"};
static const real_t p_default[] = {(real_t)RT_TWO_PI};
static const real_t x_default[] = {1, 0};

static void output(const rt_args *a, real_t *y)
{
    y[0] = a->x[0];
    y[1] = a->x[1];
}

static void deriv(const rt_args *a, real_t *xdot)
{
    real_t w = a->p[0];
    xdot[0] = a->x[1];
    xdot[1] = -w * w * a->x[0];
}

const rt_kind mdl_oscillator_kind = {
    .name = "oscillator", .type = RT_KIND_NSS,
    .ny = 2, .nx = 2, .np = 1,
    .y_names = x_names, .x_names = x_names, .p_names = p_names,
    .p_default = p_default, .x_default = x_default,
    .feed = RT_FEED_NONE, .autonomous = 1, .linear = 1,
    .output = output, .deriv = deriv,
    .doc = RT_DOC(
        "Harmonic oscillator x'' = -omega^2 x in nonlinear state space (eq. (3)):\n"
        "x' = v, v' = -omega^2 x; outputs the states x and v (no throughput).\n"
        "omega: angular eigenfrequency; any value is accepted (no check; only omega^2\n"
        "enters, so its sign does not matter)."),
    .units = RT_DOC("m m/s m m/s rad/s"),
};
