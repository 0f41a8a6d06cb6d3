/* relay.c - a relay with hysteresis (NSS without continuous state, two state events):
 * its output jumps between -A and +A, so whatever it drives has a discontinuous
 * right-hand side. The switching is a root, located by the runtime, not a comparison in
 * an output that a fixed step would straddle.
 *
 * Discrete state on (1: output +A, 0: -A). Root 0 (off: u - a rises through 0) switches
 * on, root 1 (on: u + a falls through 0) switches off; each root is held at a constant
 * of the right sign in the other state. Input u; parameters a (half the hysteresis
 * width, >= 0), A (output amplitude); output y. */
#include "models.h"

static const char *const u_names[] = {"u"};
static const char *const y_names[] = {"y"};
static const char *const d_names[] = {"on"};
static const char *const p_names[] = {"a", "A"};
static const real_t p_default[] = {(real_t)0.1, 1};
static const real_t d_default[] = {1};
static const int8_t root_dir[] = {1, -1};

static void output(const rt_args *a, real_t *y) { y[0] = a->d[0] != 0 ? a->p[1] : -a->p[1]; }

/* no continuous state: nothing to integrate (an NSS kind has the service) */
static void deriv(const rt_args *a, real_t *xdot) { (void)a, (void)xdot; }

static void roots(const rt_args *a, real_t *r)
{
    int on = a->d[0] != 0;
    r[0] = on ? -1 : a->u[0] - a->p[0];
    r[1] = on ? a->u[0] + a->p[0] : 1;
}

static void event(const rt_args *a, uint16_t which, real_t *x, real_t *d)
{
    (void)a, (void)x;
    d[0] = which == 0 ? 1 : 0;
}

static rt_status check(const real_t *p, const void *spec)
{
    (void)spec;
    return p[0] >= 0 && rt_isfinite(p[0]) && rt_isfinite(p[1]) ? RT_OK : RT_E_PARAM;
}

const rt_kind mdl_relay_kind = {
    .name = "relay", .type = RT_KIND_NSS,
    .nu = 1, .ny = 1, .nd = 1, .np = 2, .nr = 2,
    .u_names = u_names, .y_names = y_names, .d_names = d_names, .p_names = p_names,
    .p_default = p_default, .d_default = d_default, .root_dir = root_dir,
    .feed = RT_FEED_NONE, .autonomous = 1, .roots_at_start = 1,
    .check = check, .output = output, .deriv = deriv, .roots = roots, .event = event,
    .doc = RT_DOC(
        "Relay with hysteresis, switching by two roots: y = A while on = 1, -A\n"
        "while on = 0. Root 0: u - a rises through 0 while off (switch on); root 1:\n"
        "u + a falls through 0 while on (switch off). a: half the hysteresis width,\n"
        "finite and >= 0; A: amplitude, finite. Started on with u below -a (off with\n"
        "u above a), it switches at once."),
    .units = RT_DOC("- - - - -"),
};
