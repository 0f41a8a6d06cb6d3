/* vanderpol.c - the van der Pol oscillator x'' = mu (1 - x^2) x' - x (NSS, eq. 3):
 * states x, v; parameter mu (damping, dimensionless). */
#include "models.h"

static const char *const x_names[] = {"x", "v"};
static const char *const p_names[] = {"mu"};
static const real_t p_default[] = {1};
static const real_t x_default[] = {2, 0};

static void output(const rt_args *a, real_t *y)
{
    y[0] = a->x[0];
    y[1] = a->x[1];
}

static void deriv(const rt_args *a, real_t *xdot)
{
    real_t x = a->x[0], v = a->x[1];
    xdot[0] = v;
    xdot[1] = a->p[0] * (1 - x * x) * v - x;
}

/* mu < 0 makes the limit cycle repelling: the scene would blow up */
static rt_status check(const real_t *p, const void *spec)
{
    (void)spec;
    return p[0] >= 0 && rt_isfinite(p[0]) ? RT_OK : RT_E_PARAM;
}

const rt_kind mdl_vanderpol_kind = {
    .name = "vanderpol", .type = RT_KIND_NSS,
    .ny = 2, .nx = 2, .np = 1,
    .y_names = x_names, .x_names = x_names, .p_names = p_names,
    .p_default = p_default, .x_default = x_default,
    .feed = RT_FEED_NONE, .autonomous = 1,
    .check = check, .output = output, .deriv = deriv,
    .doc = RT_DOC(
        "Van der Pol oscillator x'' = mu (1 - x^2) x' - x (eq. (3)) in time scaled to\n"
        "the natural frequency 1 rad/s: x' = v, v' = mu (1 - x^2) v - x; outputs x, v.\n"
        "mu: damping, finite and >= 0 (mu < 0 makes the limit cycle repelling)."),
    .units = RT_DOC("- 1/s - 1/s -"),
};
