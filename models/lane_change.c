/* lane_change.c - the ISO 3888-1 double lane change of the paper's articulated vehicles
 * (docs/vehicles.md): the centre line of the course, a preview driver that follows it,
 * and the steering principle of the second vehicle from the tow-bar angles.
 *
 * Course (ISO 3888-1, NUMERICS.md): sections of 15, 30, 25, 25, 15, 15 m from the start
 * x0; the centre line is y = 0 in section 1, rises by the offset (3.5 m, centre to centre,
 * our choice) over section 2 along the quintic S(s) = 10 s^3 - 15 s^4 + 6 s^5, stays in
 * section 3, returns over section 4 and stays at 0 in sections 5 and 6.
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

/* the centre line at x: 0, the offset, or a quintic blend between them */
static real_t centre(real_t x, real_t x0, real_t off)
{
    real_t s = x - x0, a = sections[0], b = a + sections[1], c = b + sections[2],
           d = c + sections[3];
    real_t w;
    if (s <= a || s >= d)
        return 0;
    if (s >= b && s <= c)
        return off;
    w = s < b ? (s - a) / sections[1] : 1 - (s - c) / sections[3];
    return off * w * w * w * (10 + w * (-15 + 6 * w));
}

/* ---------------------------------------------------------------- iso_driver */

enum { D_X0, D_OFF, D_TP, D_LDMIN, D_L, D_DMAX, D_NP };
static const char *const drv_u[] = {"x", "y", "psi", "u"};
static const char *const drv_y[] = {"delta", "yref"};
static const char *const drv_p[] = {"x0", "offset", "Tp", "ldmin", "L", "delta_max"};
static const real_t drv_def[D_NP] = {0, (real_t)3.5, (real_t)0.5, 5, (real_t)2.39268,
                                     (real_t)0.5};

static void drv_output(const rt_args *a, real_t *y)
{
    const real_t *u = a->u, *p = a->p;
    real_t ld = u[3] * p[D_TP] > p[D_LDMIN] ? u[3] * p[D_TP] : p[D_LDMIN];
    real_t xt = u[0] + ld, yt = centre(xt, p[D_X0], p[D_OFF]);
    real_t c = rt_cos(u[2]), s = rt_sin(u[2]), dx = xt - u[0], dy = yt - u[1];
    real_t e = -s * dx + c * dy, d2 = dx * dx + dy * dy;
    real_t delta = rt_atan(2 * p[D_L] * e / d2);
    y[0] = rt_fmax(-p[D_DMAX], rt_fmin(p[D_DMAX], delta));
    y[1] = centre(u[0], p[D_X0], p[D_OFF]);
}

static rt_status drv_check(const real_t *p, const void *spec)
{
    (void)spec;
    return rt_isfinite(p[D_X0]) && rt_isfinite(p[D_OFF]) && p[D_TP] > 0 &&
                   p[D_LDMIN] > 0 && p[D_L] > 0 && p[D_DMAX] > 0 && rt_isfinite(p[D_TP]) &&
                   rt_isfinite(p[D_LDMIN]) && rt_isfinite(p[D_L]) && rt_isfinite(p[D_DMAX])
               ? RT_OK
               : RT_E_PARAM;
}

const rt_kind mdl_iso_driver_kind = {
    .name = "iso_driver", .type = RT_KIND_OUTPUT, .nu = 4, .ny = 2, .np = D_NP,
    .u_names = drv_u, .y_names = drv_y, .p_names = drv_p, .p_default = drv_def,
    .feed = RT_FEED_ALL, .autonomous = 1, .check = drv_check, .output = drv_output,
    .doc = RT_DOC(
        "Preview driver on the ISO 3888-1 double lane change (pure pursuit): the course\n"
        "starts at x0 (sections 15, 30, 25, 25, 15, 15 m; centre line 0, the offset over\n"
        "section 3, quintic blends over sections 2 and 4). Target: the centre line\n"
        "ld = max(ldmin, u Tp) ahead; e its lateral offset in the car frame, d its\n"
        "distance: delta = atan(2 L e / d^2), |delta| <= delta_max. Output yref: the\n"
        "centre line at the car's x. L: wheelbase (CommonRoad vehicle 1)."),
    .units = RT_DOC("m m rad m/s rad m m m s m m rad"),
};

/* ---------------------------------------------------------------- iso_cones */

/* the cone lanes: first and last cone from the start [m], centre line (0 or the offset),
   width as a multiple of the vehicle's width plus 0.25 m (ISO 3888-1) */
static const real_t lane_from[3] = {0, 45, 95}, lane_to[3] = {15, 70, 125};
static const real_t lane_k[3] = {(real_t)1.1, (real_t)1.2, (real_t)1.3};
static const uint8_t lane_off[3] = {0, 1, 0};

enum { C_X0, C_OFF, C_LEN, C_WID, C_AHEAD, C_CAP, C_NP };
static const char *const cone_u[] = {"x", "y", "psi"};
static const char *const cone_y[] = {"margin"};
static const char *const cone_p[] = {"x0", "offset", "length", "width", "ahead", "cap"};
/* the footprint of lane_change's cars (CommonRoad vehicle 1: 4.298 m by 1.674 m), centred
   between the axles, (lf - lr) / 2 = -0.31242 m ahead of the centre of mass */
static const real_t cone_def[C_NP] = {0, (real_t)3.5, (real_t)4.298, (real_t)1.674,
                                      (real_t)-0.31242, 1};

/* the footprint's margin to lane l's cone lines, lowered into *m: the part of a convex box
   inside the lane's x range has its extreme y at a corner in the range or where an edge
   crosses the lane's first or last cone (a side can touch a cone there while every corner
   in the lane is clear) */
static void lane_margin(const real_t bx[4], const real_t by[4], real_t xa, real_t xb,
                        real_t c, real_t w, real_t *m)
{
    for (int i = 0; i < 4; i++) {
        int j = (i + 1) & 3;
        if (bx[i] >= xa && bx[i] <= xb)
            *m = rt_fmin(*m, w - rt_fabs(by[i] - c));
        for (int e = 0; e < 2; e++) {
            real_t xe = e ? xb : xa;
            if ((bx[i] - xe) * (bx[j] - xe) < 0) {
                real_t ye = by[i] + (by[j] - by[i]) * (xe - bx[i]) / (bx[j] - bx[i]);
                *m = rt_fmin(*m, w - rt_fabs(ye - c));
            }
        }
    }
}

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
    real_t m = p[C_CAP];
    for (int l = 0; l < 3; l++)
        lane_margin(bx, by, p[C_X0] + lane_from[l], p[C_X0] + lane_to[l],
                    lane_off[l] ? p[C_OFF] : 0, (lane_k[l] * p[C_WID] + (real_t)0.25) / 2, &m);
    y[0] = m;
}

static rt_status cone_check(const real_t *p, const void *spec)
{
    (void)spec;
    return rt_isfinite(p[C_X0]) && rt_isfinite(p[C_OFF]) && rt_isfinite(p[C_AHEAD]) &&
                   p[C_LEN] > 0 && p[C_WID] > 0 && p[C_CAP] > 0 && rt_isfinite(p[C_LEN]) &&
                   rt_isfinite(p[C_WID]) && rt_isfinite(p[C_CAP])
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
        "to the cone lines of the lane sections it overlaps (sections 1, 3, 5-6 from x0,\n"
        "half widths (1.1, 1.2, 1.3 width + 0.25 m) / 2 about 0, offset, 0), edges as well\n"
        "as corners; negative: a cone is hit. At most cap (outside every lane: cap)."),
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
