/* sources.c - signal sources without state (output-only kinds, eq. 1): step, pulse and
 * sine. */
#include "models.h"

static const char *const y_names[] = {"y"};

/* step: y = y0 before t0 [s], y1 from t0 on. Its instant is a known time event: the step
   ending at t0 evaluates y0 there (the left limit), the step from t0 y1 (rt_args.t_piece,
   rt/tev.c), so every method keeps its order across the switch */
static const char *const step_p[] = {"t0", "y0", "y1"};
static const real_t step_def[] = {0, 0, 1};

static void step_out(const rt_args *a, real_t *y)
{
    y[0] = a->t_piece < a->p[0] ? a->p[1] : a->p[2];
}

static real_t step_next(const rt_args *a)
{
    return a->t < a->p[0] ? a->p[0] : RT_TEV_NEVER;
}

const rt_kind mdl_step_kind = {
    .name = "step", .type = RT_KIND_OUTPUT,
    .ny = 1, .np = 3,
    .y_names = y_names, .p_names = step_p, .p_default = step_def,
    .feed = RT_FEED_NONE, .linear = 1, .output = step_out, .next_event = step_next,
    .doc = RT_DOC(
        "Step source (output only, eq. (1)): y = y0 for t < t0, y = y1 from t0 on.\n"
        "t0: switching time, a known time event: a step of the block's set ends at it\n"
        "(a whole number of base ticks after 0, or before 0); y0, y1: the levels; any\n"
        "values (no check)."),
    .units = RT_DOC("- s - -"),
};

/* pulse: y = y1 on [t0 + k T, t0 + k T + w) for k = 0, 1, ..., y0 elsewhere; each edge
   is a known time event (a PWM command, a periodic load) */
static const char *const pulse_p[] = {"t0", "period", "width", "y0", "y1"};
static const real_t pulse_def[] = {0, 1, 0.5, 0, 1};

/* the index of the period t lies in (negative before t0) and the time into it */
static real_t pulse_phase(const real_t *p, real_t t, real_t *k)
{
    *k = rt_floor((t - p[0]) / p[1]);
    return t - p[0] - *k * p[1];
}

static void pulse_out(const rt_args *a, real_t *y)
{
    real_t k, into = pulse_phase(a->p, a->t_piece, &k);
    y[0] = k >= 0 && into < a->p[2] ? a->p[4] : a->p[3];
}

static real_t pulse_next(const rt_args *a)
{
    const real_t *p = a->p;
    if (a->t < p[0])
        return p[0];
    real_t k, into = pulse_phase(p, a->t, &k);
    /* the falling edge of this period, else the rising edge of the next */
    return into < p[2] ? p[0] + k * p[1] + p[2] : p[0] + (k + 1) * p[1];
}

static rt_status pulse_check(const real_t *p, const void *spec)
{
    (void)spec;
    return rt_all_finite(p, 5) && p[1] > 0 && p[2] > 0 && p[2] < p[1] ? RT_OK : RT_E_PARAM;
}

const rt_kind mdl_pulse_kind = {
    .name = "pulse", .type = RT_KIND_OUTPUT,
    .ny = 1, .np = 5,
    .y_names = y_names, .p_names = pulse_p, .p_default = pulse_def,
    .feed = RT_FEED_NONE, .linear = 1, .check = pulse_check, .output = pulse_out,
    .next_event = pulse_next,
    .doc = RT_DOC(
        "Pulse train (output only, eq. (1)): y = y1 on [t0 + k period, t0 + k period +\n"
        "width) for k = 0, 1, ..., y = y0 elsewhere (before t0 too).\n"
        "t0: first rising edge; period > 0; 0 < width < period; every edge is a known\n"
        "time event: a step of the block's set ends at it (whole numbers of base ticks)."),
    .units = RT_DOC("- s s s - -"),
};

/* sine: y = amp sin(omega t + phase) + offset */
static const char *const sine_p[] = {"amp", "omega", "phase", "offset"};
static const real_t sine_def[] = {1, 1, 0, 0};

static void sine_out(const rt_args *a, real_t *y)
{
    y[0] = a->p[0] * rt_sin(a->p[1] * a->t + a->p[2]) + a->p[3];
}

/* its band: omega (rt_kind.band); none at amplitude 0 (a constant) */
static real_t sine_band(const rt_args *a)
{
    return a->p[0] != 0 ? rt_fabs(a->p[1]) : 0;
}

const rt_kind mdl_sine_kind = {
    .name = "sine", .type = RT_KIND_OUTPUT,
    .ny = 1, .np = 4,
    .y_names = y_names, .p_names = sine_p, .p_default = sine_def,
    .feed = RT_FEED_NONE, .linear = 1, .output = sine_out, .band = sine_band,
    .doc = RT_DOC(
        "Sine source (output only, eq. (1)): y = amp sin(omega t + phase) + offset.\n"
        "amp: amplitude; omega: angular frequency; phase: phase at t = 0; offset: mean\n"
        "value; any values, but a set integrating y (or reading it through blocks with\n"
        "throughput or another set's history) must step below pi / |omega|: its steps\n"
        "would sample an alias (rt_init refuses the scene)."),
    .units = RT_DOC("- - rad/s rad -"),
};
