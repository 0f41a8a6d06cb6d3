/* ball.c - a ball bouncing on the ground (NSS with one state event, eq. 3 plus roots):
 * h' = v, v' = -g; the root h falls through zero at an impact, where v <- -e v.
 * States h [m], v [m/s]; discrete states n (impacts so far) and t_hit [s] (last impact);
 * parameters g [m/s^2], e (restitution, 0..1). */
#include "models.h"

static const char *const x_names[] = {"h", "v"};
static const char *const d_names[] = {"n", "t_hit"};
static const char *const p_names[] = {"g", "e"};
static const real_t p_default[] = {(real_t)9.81, (real_t)0.8};
static const real_t x_default[] = {1, 0};
static const int8_t root_dir[] = {-1};

static void output(const rt_args *a, real_t *y)
{
    y[0] = a->x[0];
    y[1] = a->x[1];
}

static void deriv(const rt_args *a, real_t *xdot)
{
    xdot[0] = a->x[1];
    xdot[1] = -a->p[0];
}

static void roots(const rt_args *a, real_t *r) { r[0] = a->x[0]; }

/* impact: reverse and damp the velocity, count it and note its time */
static void event(const rt_args *a, uint16_t which, real_t *x, real_t *d)
{
    (void)which;
    x[1] = -a->p[1] * x[1];
    d[0] = d[0] + 1;
    d[1] = a->t;
}

static rt_status check(const real_t *p, const void *spec)
{
    (void)spec;
    return p[0] > 0 && p[1] >= 0 && p[1] <= 1 ? RT_OK : RT_E_PARAM;
}

const rt_kind mdl_ball_kind = {
    .name = "ball", .type = RT_KIND_NSS,
    .ny = 2, .nx = 2, .nd = 2, .np = 2, .nr = 1,
    .y_names = x_names, .x_names = x_names, .d_names = d_names, .p_names = p_names,
    .p_default = p_default, .x_default = x_default, .root_dir = root_dir,
    .feed = RT_FEED_NONE,
    .check = check, .output = output, .deriv = deriv, .roots = roots, .event = event,
    .doc = RT_DOC(
        "Ball bouncing on the ground (eq. (3) with one state event): h' = v, v' = -g.\n"
        "Root h falls through 0 at an impact, where v <- -e v; the discrete states count\n"
        "the impacts (n) and hold the time of the last one (t_hit). Outputs h and v.\n"
        "g: gravity, > 0; e: coefficient of restitution, 0 <= e <= 1."),
    .units = RT_DOC("m m/s m m/s - s m/s^2 -"),
};
