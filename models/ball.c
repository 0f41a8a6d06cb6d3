/* ball.c - a ball bouncing on the ground (NSS with one state event, eq. 3 plus roots):
 * h' = v, v' = -g; the root h falls through zero at an impact, where v <- -e v.
 * States h [m], v [m/s]; discrete states n (impacts so far), t_hit [s] (last impact),
 * rest (1 once at rest) and t_rest [s]; parameters g [m/s^2], e (restitution, 0..1),
 * t_min [s] (shortest flight).
 *
 * Contact that comes to rest. With e < 1 the flights shrink geometrically and the impacts
 * accumulate at a finite time (Zeno): no fixed step can follow them, and a step that
 * ends below the floor moving down never sees another crossing (without a rest the ball
 * falls through after its 32nd impact). An impact whose rebound flight 2 v+ / g is shorter than
 * t_min ends the bouncing: the ball rests on the floor (h = v = 0, no acceleration: the
 * floor's reaction balances g), and t_rest is the accumulation time of the remaining
 * flights, t + 2 v+ / (g (1 - e)), the analytic time of rest. The root is a guard (the
 * floor): rt/step.c counts a step that ends further below it without a located crossing. */
#include "models.h"

static const char *const x_names[] = {"h", "v"};
static const char *const d_names[] = {"n", "t_hit", "rest", "t_rest"};
static const char *const p_names[] = {"g", "e", "t_min"};
static const real_t p_default[] = {(real_t)9.81, (real_t)0.8, (real_t)1e-3};
static const real_t x_default[] = {1, 0};
static const int8_t root_dir[] = {-1};
static const uint8_t root_guard[] = {1}; /* the floor: h must not sink below it */

static void output(const rt_args *a, real_t *y)
{
    y[0] = a->x[0];
    y[1] = a->x[1];
}

static void deriv(const rt_args *a, real_t *xdot)
{
    int rest = a->d[2] != 0;
    xdot[0] = rest ? 0 : a->x[1];
    xdot[1] = rest ? 0 : -a->p[0];
}

static void roots(const rt_args *a, real_t *r) { r[0] = a->x[0]; }

/* impact: reverse and damp the velocity, count it and note its time; a rebound flight
   shorter than t_min ends the bouncing at the accumulation time of the rest */
static void event(const rt_args *a, uint16_t which, real_t *x, real_t *d)
{
    real_t g = a->p[0], e = a->p[1];
    (void)which;
    x[1] = -e * x[1];
    d[0] = d[0] + 1;
    d[1] = a->t;
    real_t flight = 2 * x[1] / g;
    if (!(flight < a->p[2]))
        return;
    x[0] = 0, x[1] = 0, d[2] = 1;
    d[3] = e < 1 ? a->t + flight / (1 - e) : a->t;
}

static rt_status check(const real_t *p, const void *spec)
{
    (void)spec;
    return p[0] > 0 && p[1] >= 0 && p[1] <= 1 && p[2] >= 0 ? RT_OK : RT_E_PARAM;
}

const rt_kind mdl_ball_kind = {
    .name = "ball", .type = RT_KIND_NSS,
    .ny = 2, .nx = 2, .nd = 4, .np = 3, .nr = 1,
    .y_names = x_names, .x_names = x_names, .d_names = d_names, .p_names = p_names,
    .p_default = p_default, .x_default = x_default, .root_dir = root_dir,
    .root_guard = root_guard, .feed = RT_FEED_NONE, .autonomous = 1,
    .check = check, .output = output, .deriv = deriv, .roots = roots, .event = event,
    .doc = RT_DOC(
        "Ball bouncing on the ground (eq. (3) with one state event): h' = v, v' = -g.\n"
        "Root h falls through 0 at an impact, where v <- -e v; the discrete states count\n"
        "the impacts (n) and hold the time of the last one (t_hit). A rebound flight\n"
        "2 v / g shorter than t_min ends the bouncing: the ball rests (h = v = 0, rest = 1)\n"
        "from then on, and t_rest = t + 2 v / (g (1 - e)) is the accumulation time of the\n"
        "impacts (Zeno), the analytic time of rest. Outputs h and v.\n"
        "g: gravity, > 0; e: coefficient of restitution, 0 <= e <= 1; t_min >= 0."),
    .units = RT_DOC("m m/s m m/s - s - s m/s^2 - s"),
};
