/* pt1.c - first-order lag T y' = K u - y (NSS, eq. 3): state y; parameters K (gain),
 * T [s] (time constant, > 0). Output y has no throughput. */
#include "models.h"

static const char *const u_names[] = {"u"};
static const char *const y_names[] = {"y"};
static const char *const p_names[] = {"K", "T"};
static const real_t p_default[] = {1, 1};

static void output(const rt_args *a, real_t *y) { y[0] = a->x[0]; }

static void deriv(const rt_args *a, real_t *xdot)
{
    xdot[0] = (a->p[0] * a->u[0] - a->x[0]) / a->p[1];
}

static rt_status check(const real_t *p, const void *spec)
{
    (void)spec;
    return p[1] > 0 && rt_isfinite(p[0]) && rt_isfinite(p[1]) ? RT_OK : RT_E_PARAM;
}

const rt_kind mdl_pt1_kind = {
    .name = "pt1", .type = RT_KIND_NSS,
    .nu = 1, .ny = 1, .nx = 1, .np = 2,
    .u_names = u_names, .y_names = y_names, .x_names = y_names, .p_names = p_names,
    .p_default = p_default,
    .feed = RT_FEED_NONE, .autonomous = 1, .linear = 1,
    .check = check, .output = output, .deriv = deriv,
    .doc = RT_DOC(
        "First-order lag T y' = K u - y (eq. (3)); state and output y (no throughput).\n"
        "K: static gain, finite; T: time constant, finite and > 0.\n"
        "Signals carry the scene's unit (y in K times the unit of u)."),
    .units = RT_DOC("- - - - s"),
};
