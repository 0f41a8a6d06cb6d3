/* sources.c - signal sources without state (output-only kinds, eq. 1): step and sine. */
#include "models.h"

static const char *const y_names[] = {"y"};

/* step: y = y0 before t0 [s], y1 from t0 on */
static const char *const step_p[] = {"t0", "y0", "y1"};
static const real_t step_def[] = {0, 0, 1};

static void step_out(const rt_args *a, real_t *y) { y[0] = a->t < a->p[0] ? a->p[1] : a->p[2]; }

const rt_kind mdl_step_kind = {
    .name = "step", .type = RT_KIND_OUTPUT,
    .ny = 1, .np = 3,
    .y_names = y_names, .p_names = step_p, .p_default = step_def,
    .feed = RT_FEED_NONE, .linear = 1, .output = step_out,
    .doc = RT_DOC(
        "Step source (output only, eq. (1)): y = y0 for t < t0, y = y1 from t0 on.\n"
        "t0: switching time; y0, y1: the levels; any values (no check)."),
    .units = RT_DOC("- s - -"),
};

/* sine: y = amp sin(omega t + phase) + offset */
static const char *const sine_p[] = {"amp", "omega", "phase", "offset"};
static const real_t sine_def[] = {1, 1, 0, 0};

static void sine_out(const rt_args *a, real_t *y)
{
    y[0] = a->p[0] * rt_sin(a->p[1] * a->t + a->p[2]) + a->p[3];
}

const rt_kind mdl_sine_kind = {
    .name = "sine", .type = RT_KIND_OUTPUT,
    .ny = 1, .np = 4,
    .y_names = y_names, .p_names = sine_p, .p_default = sine_def,
    .feed = RT_FEED_NONE, .linear = 1, .output = sine_out,
    .doc = RT_DOC(
        "Sine source (output only, eq. (1)): y = amp sin(omega t + phase) + offset.\n"
        "amp: amplitude; omega: angular frequency; phase: phase at t = 0; offset: mean\n"
        "value; any values (no check)."),
    .units = RT_DOC("- - rad/s rad -"),
};
