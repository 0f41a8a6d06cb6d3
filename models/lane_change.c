/* lane_change.c - the ISO 3888-1 double lane change of the paper's articulated vehicles
 * (docs/vehicles.md): the centre line of the course, a preview driver that follows it,
 * and the steering principle of the second vehicle from the tow-bar angles.
 *
 * Course (ISO 3888-1:2018, Table 1 and Figure 1; docs/vehicles.md): sections of 15, 30,
 * 25, 25, 15, 15 m from the start x0, coned lanes in sections 1, 3 and 5-6 of widths
 * 1.1 b + 0.25, 1.2 b + 0.25 and 1.3 b + 0.25 m (b the vehicle width). The figure
 * dimensions the track from its right-hand cone line: section 3's lies the offset (3.5 m)
 * to the left of section 1's, and sections 5-6 continue section 1's. With section 1
 * centred on y = 0 the lane centres are 0, offset + 0.05 b and 0.1 b (the 0.25 m cancels).
 * The centre line is section 1's centre up to the end of section 1, section 3's over
 * section 3, that of sections 5-6 from their start, and a quintic blend
 * S(s) = 10 s^3 - 15 s^4 + 6 s^5 between them over sections 2 and 4.
 *
 * iso_driver_cc keeps the project's earlier variant for a scene that names it: the offset
 * between lane centres and sections 5-6 centred on section 1 (centres 0, offset, 0).
 *
 * iso_driver (pure pursuit): the target is the centre line a look-ahead distance
 * ld = max(ld_min, u Tp) ahead along the track; with e its lateral offset in the car's
 * frame and d its distance, delta = atan(2 L e / d^2) (L the wheelbase), bounded by
 * delta_max.
 *
 * tow_steer (the paper's SteeringPrinciple): the tow bar runs from the second vehicle's
 * front hitch to the first's rear hitch; mu1 = psi1 - theta and mu2 = theta - psi2 with
 * theta the bar's heading; delta2 = K1 mu1 + K2 mu2. */
#include "models.h"

static const real_t sections[6] = {15, 30, 25, 25, 15, 15};
/* lane widths k b + 0.25 m of sections 1, 3 and 5-6 (b the vehicle width) */
static const real_t width_k[3] = {(real_t)1.1, (real_t)1.2, (real_t)1.3};

/* the lane centres of sections 3 and 5-6 (section 1's is 0) */
typedef struct course {
    real_t c3, c56;
} course;

/* the centre line at x: a lane centre, or a quintic blend between two */
static real_t centre(real_t x, real_t x0, course k)
{
    real_t s = x - x0, a = sections[0], b = a + sections[1], c = b + sections[2],
           d = c + sections[3];
    real_t w, from, to;
    if (s <= a)
        return 0;
    if (s >= d)
        return k.c56;
    if (s >= b && s <= c)
        return k.c3;
    if (s < b)
        w = (s - a) / sections[1], from = 0, to = k.c3;
    else
        w = (s - c) / sections[3], from = k.c3, to = k.c56;
    return from + (to - from) * w * w * w * (10 + w * (-15 + 6 * w));
}

/* ---------------------------------------------------------------- iso_driver */

enum { D_X0, D_OFF, D_TP, D_LDMIN, D_L, D_DMAX, D_B, D_NP };
static const char *const drv_u[] = {"x", "y", "psi", "u"};
static const char *const drv_y[] = {"delta", "yref"};
static const char *const drv_p[] = {"x0", "offset", "Tp", "ldmin", "L", "delta_max", "b"};
/* b: the width of CommonRoad vehicle 1, the cars of the lane change scenes */
static const real_t drv_def[D_NP] = {0, (real_t)3.5, (real_t)0.5, 5, (real_t)2.39268,
                                     (real_t)0.5, (real_t)1.674};

/* pure pursuit of the centre line of course k */
static void pursue(const rt_args *a, course k, real_t *y)
{
    const real_t *u = a->u, *p = a->p;
    real_t ld = u[3] * p[D_TP] > p[D_LDMIN] ? u[3] * p[D_TP] : p[D_LDMIN];
    real_t xt = u[0] + ld, yt = centre(xt, p[D_X0], k);
    real_t c = rt_cos(u[2]), s = rt_sin(u[2]), dx = xt - u[0], dy = yt - u[1];
    real_t e = -s * dx + c * dy, d2 = dx * dx + dy * dy;
    real_t delta = rt_atan(2 * p[D_L] * e / d2);
    y[0] = rt_fmax(-p[D_DMAX], rt_fmin(p[D_DMAX], delta));
    y[1] = centre(u[0], p[D_X0], k);
}

/* the course as ISO 3888-1 draws it: section 1's right-hand line at -(k1 b + 0.25) / 2,
   section 3's the offset to its left, that of sections 5-6 on it; a lane's centre lies
   half its width left of its right-hand line */
static void drv_output(const rt_args *a, real_t *y)
{
    const real_t *p = a->p;
    real_t r1 = -(width_k[0] * p[D_B] + (real_t)0.25) / 2;
    course k = {r1 + p[D_OFF] + (width_k[1] * p[D_B] + (real_t)0.25) / 2,
                r1 + (width_k[2] * p[D_B] + (real_t)0.25) / 2};
    pursue(a, k, y);
}

/* the project's earlier variant: the offset between lane centres, sections 5-6 on 0 */
static void drv_cc_output(const rt_args *a, real_t *y)
{
    course k = {a->p[D_OFF], 0};
    pursue(a, k, y);
}

static rt_status drv_check(const real_t *p, const void *spec)
{
    (void)spec;
    return rt_isfinite(p[D_X0]) && rt_isfinite(p[D_OFF]) && p[D_TP] > 0 &&
                   p[D_LDMIN] > 0 && p[D_L] > 0 && p[D_DMAX] > 0 && p[D_B] > 0 &&
                   rt_isfinite(p[D_TP]) && rt_isfinite(p[D_LDMIN]) && rt_isfinite(p[D_L]) &&
                   rt_isfinite(p[D_DMAX]) && rt_isfinite(p[D_B])
               ? RT_OK
               : RT_E_PARAM;
}

const rt_kind mdl_iso_driver_kind = {
    .name = "iso_driver", .type = RT_KIND_OUTPUT, .nu = 4, .ny = 2, .np = D_NP,
    .u_names = drv_u, .y_names = drv_y, .p_names = drv_p, .p_default = drv_def,
    .feed = RT_FEED_ALL, .autonomous = 1, .check = drv_check, .output = drv_output,
    .doc = RT_DOC(
        "Preview driver on the ISO 3888-1 double lane change (pure pursuit) as the\n"
        "standard draws it: the course starts at x0 (sections 15, 30, 25, 25, 15, 15 m;\n"
        "lanes 1.1 b + 0.25, 1.2 b + 0.25, 1.3 b + 0.25 m wide in sections 1, 3, 5-6 for\n"
        "the vehicle width b); section 3's right-hand cone line lies offset to the left of\n"
        "section 1's, sections 5-6 continue section 1's. Centre line: the lane centres\n"
        "(0, offset + 0.05 b, 0.1 b), quintic blends over sections 2 and 4. Target: the\n"
        "centre line ld = max(ldmin, u Tp) ahead; e its lateral offset in the car frame,\n"
        "d its distance: delta = atan(2 L e / d^2), |delta| <= delta_max. Output yref:\n"
        "the centre line at the car's x. L: wheelbase (CommonRoad vehicle 1)."),
    .units = RT_DOC("m m rad m/s rad m m m s m m rad m"),
};

const rt_kind mdl_iso_driver_cc_kind = {
    .name = "iso_driver_cc", .type = RT_KIND_OUTPUT, .nu = 4, .ny = 2, .np = D_NP,
    .u_names = drv_u, .y_names = drv_y, .p_names = drv_p, .p_default = drv_def,
    .feed = RT_FEED_ALL, .autonomous = 1, .check = drv_check, .output = drv_cc_output,
    .doc = RT_DOC(
        "iso_driver on a variant of the ISO 3888-1 course that is not the standard's:\n"
        "the offset between the lane centres of sections 1 and 3, sections 5-6 centred\n"
        "on section 1 (centre line 0, offset, 0; b is not used). For a scene that asks\n"
        "for this variant by name; the standard's course is iso_driver."),
    .units = RT_DOC("m m rad m/s rad m m m s m m rad m"),
};

/* ---------------------------------------------------------------- tow_steer */

enum { T_DR1, T_DF2, T_K1, T_K2, T_NP };
static const char *const tow_u[] = {"x1", "y1", "psi1", "x2", "y2", "psi2"};
static const char *const tow_y[] = {"delta", "mu1", "mu2"};
static const char *const tow_p[] = {"dr1", "df2", "K1", "K2"};
/* K1, K2: a drawbar steering (the bar's angle to the towed car, K2 = 1) with a share of
   the first car's angle to the bar (K1 = 0.5); hitches as the st_car defaults */
static const real_t tow_def[T_NP] = {2, 2, (real_t)0.5, 1};

/* a in (-pi, pi] */
static real_t wrap(real_t a)
{
    const real_t pi = (real_t)3.14159265358979323846;
    return a - 2 * pi * rt_floor((a + pi) / (2 * pi));
}

static void tow_output(const rt_args *a, real_t *y)
{
    const real_t *u = a->u, *p = a->p;
    real_t h1x = u[0] - p[T_DR1] * rt_cos(u[2]), h1y = u[1] - p[T_DR1] * rt_sin(u[2]);
    real_t h2x = u[3] + p[T_DF2] * rt_cos(u[5]), h2y = u[4] + p[T_DF2] * rt_sin(u[5]);
    real_t theta = rt_atan2(h1y - h2y, h1x - h2x);
    y[1] = wrap(u[2] - theta);
    y[2] = wrap(theta - u[5]);
    y[0] = p[T_K1] * y[1] + p[T_K2] * y[2];
}

static rt_status tow_check(const real_t *p, const void *spec)
{
    (void)spec;
    return p[T_DR1] >= 0 && p[T_DF2] >= 0 && rt_isfinite(p[T_DR1]) && rt_isfinite(p[T_DF2]) &&
                   rt_isfinite(p[T_K1]) && rt_isfinite(p[T_K2])
               ? RT_OK
               : RT_E_PARAM;
}

const rt_kind mdl_tow_steer_kind = {
    .name = "tow_steer", .type = RT_KIND_OUTPUT, .nu = 6, .ny = 3, .np = T_NP,
    .u_names = tow_u, .y_names = tow_y, .p_names = tow_p, .p_default = tow_def,
    .feed = RT_FEED_ALL, .autonomous = 1, .check = tow_check, .output = tow_output,
    .doc = RT_DOC(
        "Steering principle of a towed vehicle from the tow-bar angles (the paper's\n"
        "SteeringPrinciple): the bar from the second vehicle's front hitch (df2 ahead of\n"
        "its centre of mass) to the first's rear hitch (dr1 behind), heading theta;\n"
        "mu1 = psi1 - theta, mu2 = theta - psi2, delta = K1 mu1 + K2 mu2."),
    .units = RT_DOC("m m rad m m rad rad rad rad m m - -"),
};
