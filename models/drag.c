/* drag.c - aerodynamic drag of a vehicle as its own block (an effect a scene may name or
 * omit, docs/vehicles.md): F = -1/2 rho cd A u |u| along the body's forward axis, from the
 * forward speed u. Parameters rho [kg/m^3] (air at 20 C), cd, A [m^2] (typical of a
 * compact car: our choice, the CommonRoad set has none). */
#include "models.h"

static const char *const u_names[] = {"u"};
static const char *const y_names[] = {"F"};
static const char *const p_names[] = {"rho", "cd", "A"};
static const real_t p_default[] = {(real_t)1.2041, (real_t)0.3, (real_t)2.2};

static void output(const rt_args *a, real_t *y)
{
    real_t u = a->u[0];
    y[0] = -(real_t)0.5 * a->p[0] * a->p[1] * a->p[2] * u * rt_fabs(u);
}

static rt_status check(const real_t *p, const void *spec)
{
    (void)spec;
    return p[0] >= 0 && p[1] >= 0 && p[2] >= 0 && rt_isfinite(p[0]) && rt_isfinite(p[1]) &&
                   rt_isfinite(p[2])
               ? RT_OK
               : RT_E_PARAM;
}

const rt_kind mdl_drag_kind = {
    .name = "drag", .type = RT_KIND_OUTPUT, .nu = 1, .ny = 1, .np = 3,
    .u_names = u_names, .y_names = y_names, .p_names = p_names, .p_default = p_default,
    .feed = RT_FEED_ALL, .autonomous = 1, .check = check, .output = output,
    .doc = RT_DOC(
        "Aerodynamic drag along the body's forward axis: F = -1/2 rho cd A u |u| from the\n"
        "forward speed u. rho: air density (1.2041 kg/m^3 at 20 C); cd, A: drag\n"
        "coefficient and frontal area (0.3, 2.2 m^2: a compact car); all >= 0."),
    .units = RT_DOC("m/s N kg/m^3 - m^2"),
};
