/* algebra.c - static signal operations with throughput (output-only kinds, eq. 1):
 * gain and weighted sum. */
#include "models.h"

static const char *const y_names[] = {"y"};

/* gain: y = k u */
static const char *const gain_u[] = {"u"};
static const char *const gain_p[] = {"k"};
static const real_t gain_def[] = {1};

static void gain_out(const rt_args *a, real_t *y) { y[0] = a->p[0] * a->u[0]; }

const rt_kind mdl_gain_kind = {
    .name = "gain", .type = RT_KIND_OUTPUT,
    .nu = 1, .ny = 1, .np = 1,
    .u_names = gain_u, .y_names = y_names, .p_names = gain_p, .p_default = gain_def,
    .feed = RT_FEED_ALL, .autonomous = 1, .linear = 1, .output = gain_out,
    .doc = RT_DOC(
        "Static gain (output only, eq. (1)): y = k u, with throughput from u.\n"
        "k: gain, any value (no check)."),
    .units = RT_DOC("- - -"),
};

/* sum: y = c1 u1 + c2 u2 */
static const char *const sum_u[] = {"u1", "u2"};
static const char *const sum_p[] = {"c1", "c2"};
static const real_t sum_def[] = {1, 1};

static void sum_out(const rt_args *a, real_t *y) { y[0] = a->p[0] * a->u[0] + a->p[1] * a->u[1]; }

const rt_kind mdl_sum_kind = {
    .name = "sum", .type = RT_KIND_OUTPUT,
    .nu = 2, .ny = 1, .np = 2,
    .u_names = sum_u, .y_names = y_names, .p_names = sum_p, .p_default = sum_def,
    .feed = RT_FEED_ALL, .autonomous = 1, .linear = 1, .output = sum_out,
    .doc = RT_DOC(
        "Weighted sum (output only, eq. (1)): y = c1 u1 + c2 u2, with throughput from\n"
        "both inputs. c1, c2: weights, any values (no check; c2 = -1 gives a difference)."),
    .units = RT_DOC("- - - - -"),
};
