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
 * iso_cones (the course check): the smallest margin of a car's footprint, a box turned by
 * its heading, to the cone lines of the lane sections 1, 3 and 5-6 it overlaps, so that a
 * run records it and a campaign's metric takes its minimum (docs/sweeps.md).
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
    return rt_all_finite(p, D_NP) && p[D_TP] > 0 && p[D_LDMIN] > 0 && p[D_L] > 0 &&
                   p[D_DMAX] > 0 && p[D_B] > 0
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

/* ---------------------------------------------------------------- iso_cones */

enum { C_X0, C_OFF, C_LEN, C_WID, C_AHEAD, C_CAP, C_NP };
static const char *const cone_u[] = {"x", "y", "psi"};
static const char *const cone_y[] = {"margin"};
static const char *const cone_p[] = {"x0", "offset", "length", "width", "ahead", "cap"};
/* the footprint of lane_change's cars (CommonRoad vehicle 1: 4.298 m by 1.674 m), centred
   between the axles, (lf - lr) / 2 = -0.31242 m ahead of the centre of mass; the lanes'
   widths follow the same width b */
static const real_t cone_def[C_NP] = {0, (real_t)3.5, (real_t)4.298, (real_t)1.674,
                                      (real_t)-0.31242, 1};

/* the footprint's margin to the cone lines r (right-hand) and l of the lane from xa to xb,
   lowered into *m: the part of a convex box inside the lane's x range has its extreme y
   at a corner in the range or where an edge crosses the lane's first or last cone (a side
   can touch a cone there while every corner in the lane is clear) */
static void lane_margin(const real_t bx[4], const real_t by[4], real_t xa, real_t xb,
                        real_t r, real_t l, real_t *m)
{
    for (int i = 0; i < 4; i++) {
        int j = (i + 1) & 3;
        if (bx[i] >= xa && bx[i] <= xb)
            *m = rt_fmin(*m, rt_fmin(by[i] - r, l - by[i]));
        for (int e = 0; e < 2; e++) {
            real_t xe = e ? xb : xa;
            if ((bx[i] - xe) * (bx[j] - xe) < 0) {
                real_t ye = by[i] + (by[j] - by[i]) * (xe - bx[i]) / (bx[j] - bx[i]);
                *m = rt_fmin(*m, rt_fmin(ye - r, l - ye));
            }
        }
    }
}

/* the cone lines as iso_driver's course draws them: section 1 centred on 0, section 3's
   right-hand line the offset to the left of section 1's, sections 5-6 on section 1's */
static void cone_output(const rt_args *a, real_t *y)
{
    const real_t *u = a->u, *p = a->p;
    real_t c = rt_cos(u[2]), s = rt_sin(u[2]), bx[4], by[4];
    real_t cx = u[0] + p[C_AHEAD] * c, cy = u[1] + p[C_AHEAD] * s;
    static const int8_t sa[4] = {1, 1, -1, -1}, sb[4] = {1, -1, -1, 1}; /* around the box */
    for (int i = 0; i < 4; i++) {
        real_t l = sa[i] * p[C_LEN] / 2, w = sb[i] * p[C_WID] / 2;
        bx[i] = cx + l * c - w * s, by[i] = cy + l * s + w * c;
    }
    real_t r1 = -(width_k[0] * p[C_WID] + (real_t)0.25) / 2, m = p[C_CAP], x = p[C_X0];
    for (size_t k = 0; k < 3; k++) { /* sections 1, 3 and 5-6: from the start of 1, 3, 5 */
        real_t xa = x, xb = x + sections[2 * k] + (k == 2 ? sections[5] : 0);
        real_t r = r1 + (k == 1 ? p[C_OFF] : 0);
        lane_margin(bx, by, xa, xb, r, r + width_k[k] * p[C_WID] + (real_t)0.25, &m);
        x = xb + sections[2 * k + 1];
    }
    y[0] = m;
}

static rt_status cone_check(const real_t *p, const void *spec)
{
    (void)spec;
    return rt_all_finite(p, C_NP) && p[C_LEN] > 0 && p[C_WID] > 0 && p[C_CAP] > 0
               ? RT_OK
               : RT_E_PARAM;
}

const rt_kind mdl_iso_cones_kind = {
    .name = "iso_cones", .type = RT_KIND_OUTPUT, .nu = 3, .ny = 1, .np = C_NP,
    .u_names = cone_u, .y_names = cone_y, .p_names = cone_p, .p_default = cone_def,
    .feed = RT_FEED_ALL, .autonomous = 1, .check = cone_check, .output = cone_output,
    .doc = RT_DOC(
        "The ISO 3888-1 course check: margin, the smallest distance of a car's footprint\n"
        "(a length x width box centred `ahead` of the inputs' point along the heading psi)\n"
        "to the cone lines of the lane sections it overlaps, edges as well as corners, on\n"
        "iso_driver's course for b = width (sections 1, 3, 5-6 from x0, lanes\n"
        "1.1 b + 0.25, 1.2 b + 0.25, 1.3 b + 0.25 m wide; section 1 centred on 0, section\n"
        "3's right-hand line offset to the left of section 1's, sections 5-6 on section\n"
        "1's); negative: a cone is hit. At most cap (outside every lane: cap)."),
    .units = RT_DOC("m m rad m m m m m m m"),
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
