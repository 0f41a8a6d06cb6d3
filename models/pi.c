/* pi.c - a sampled PI controller in discrete state space (eq. 5):
 *   e[k] = r[k] - m[k],  c[k] = Kp e[k] + I[k],  I[k+1] = I[k] + Ki Ts e[k],
 * with the output held between samples (zero-order hold). c depends directly on r and m
 * at the sample instants (throughput); parameters Kp, Ki [1/s]. */
#include "models.h"

static const char *const u_names[] = {"r", "m"};
static const char *const y_names[] = {"c"};
static const char *const d_names[] = {"I"};
static const char *const p_names[] = {"Kp", "Ki"};
static const real_t p_default[] = {1, 1};

static void output(const rt_args *a, real_t *y)
{
    y[0] = a->p[0] * (a->u[0] - a->u[1]) + a->d[0];
}

/* forward-Euler accumulation of the error over one sample period a->h */
static void update(const rt_args *a, real_t *dnext)
{
    dnext[0] = a->d[0] + a->p[1] * a->h * (a->u[0] - a->u[1]);
}

const rt_kind mdl_pi_kind = {
    .name = "pi", .type = RT_KIND_DSS,
    .nu = 2, .ny = 1, .nd = 1, .np = 2,
    .u_names = u_names, .y_names = y_names, .d_names = d_names, .p_names = p_names,
    .p_default = p_default,
    .feed = RT_FEED_ALL, .autonomous = 1,
    .output = output, .update = update,
    .doc = RT_DOC(
        "Sampled PI controller (DSS, eq. (5)) with sample period Ts (the block's step):\n"
        "e[k] = r[k] - m[k], c[k] = Kp e[k] + I[k], I[k+1] = I[k] + Ki Ts e[k].\n"
        "c is held between samples and depends directly on r and m (throughput).\n"
        "Kp: proportional gain; Ki: integral gain; any values (no check)."),
    .units = RT_DOC("- - - - - 1/s"),
};
