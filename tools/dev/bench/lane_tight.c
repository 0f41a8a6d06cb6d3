/* lane_tight.c - the tightest hand-written program of scene lane_change_planar that
 * computes what modrt computes: the yardstick of modrt's overhead on it (docs/overhead.md).
 *
 * The same formulation and method as modrt's: two planar single-track cars with linear
 * tires (models/vehicle_st.c: q = (x, y, psi), z = (vx, vy, r), M = diag(m, m, Iz)), the
 * pure-pursuit driver and the speed controller on V1, the tow-bar steering of V2
 * (models/lane_change.c, models/algebra.c), the tow bar a distance constraint of 1.8 m
 * between V1's rear and V2's front hitch (eq. 8) with its multiplier from the 1 x 1 Schur
 * complement A = W M^-1 W^T (index 1, eq. 7b), RK4 at 5 ms with modrt's tableau and
 * error estimate (rt/integ_erk.c), the projection of eq. 10 after every step (two position
 * iterations with W and A frozen at the predicted state, one velocity solve). The
 * elementary functions are modrt's own (rt/rmath.c: the scene's models call them, libm
 * would give other bits). Written as a performance engineer writes it for this one scene:
 *   - one evaluation computes each car's sin psi, cos psi and body speeds once and uses
 *     them for the tires, the forces in the ground frame, the hitches and the driver;
 *   - the constraint is one row: its W is two 3-vectors, A a scalar, lambda a division;
 *   - the driver's course is a constant (its lane centres folded in at compile time);
 *   - the stage sums are written out over RK4's nonzero coefficients, the state is the
 *     twelve numbers of modrt's layout, the stage derivatives are never copied.
 * Sums run in modrt's order where the order decides the bits, so the trajectories equal
 * modrt's to rounding (tested to 1e-12 m: tight_bench check). With estimate = 1 the step
 * also computes modrt's error estimate (its fifth evaluation) and the projection's
 * residual, as modrt's step does. */
#include "lane_tight.h"

#include <math.h>

#include "rt_math.h"

#define AI __attribute__((always_inline)) static inline

/* st_car's defaults (CommonRoad vehicle 1) and the scene's parameters */
static const double MASS = 1225.887, IZ = 1538.853, LF = 0.88392, LR = 1.50876;
static const double CF = 158000, CR = 170000, DHITCH = 2, UMIN = 1;
static const double BAR = 1.8;                             /* the tow bar [m] */
static const double VREF = 20, KV = 5000;                  /* Uref.y, Kv.k; Err = u1 - u2 */
static const double X0 = 20, TP = 0.5, LDMIN = 5, WB = 2.39268, DMAX = 0.5; /* Driver */
static const double K1 = 0.5, K2 = 1;                      /* Tow */
/* the course's lane centres (models/lane_change.c drv_output, offset 3.5 m, b 1.674 m) */
#define R1 (-(1.1 * 1.674 + 0.25) / 2)
static const double C3 = R1 + 3.5 + (1.2 * 1.674 + 0.25) / 2, C56 = R1 + (1.3 * 1.674 + 0.25) / 2;

/* the centre line at x (models/lane_change.c centre) */
AI double centre(double x)
{
    double s = x - X0, w, from, to;
    if (s <= 15)
        return 0;
    if (s >= 95)
        return C56;
    if (s >= 45 && s <= 70)
        return C3;
    if (s < 45)
        w = (s - 15) / 30, from = 0, to = C3;
    else
        w = (s - 70) / 25, from = C3, to = C56;
    return from + (to - from) * w * w * w * (10 + w * (-15 + 6 * w));
}

AI double wrap(double a)
{
    const double pi = 3.14159265358979323846;
    return a - 2 * pi * rt_floor((a + pi) / (2 * pi));
}

/* one car: sin, cos of psi and the body-frame speeds */
typedef struct car {
    double c, s, u, v;
} car;

AI car car_of(const double *x)
{
    car k;
    k.c = rt_cos(x[2]), k.s = rt_sin(x[2]);
    k.u = k.c * x[3] + k.s * x[4], k.v = -k.s * x[3] + k.c * x[4];
    return k;
}

/* the free accelerations M^-1 k of a car steered by delta and driven by fx */
AI void tires(const double *x, car k, double delta, double fx, double *a)
{
    double us = k.u > UMIN ? k.u : UMIN, r = x[5];
    double fyf = CF * (delta - (k.v + LF * r) / us), fyr = -CR * (k.v - LR * r) / us;
    double fy = fyf + fyr, mz = LF * fyf - LR * fyr;
    a[0] = (k.c * fx - k.s * fy) / MASS;
    a[1] = (k.s * fx + k.c * fy) / MASS;
    a[2] = mz / IZ;
}

/* the hitch d ahead of a car's centre of mass: position, velocity, the acceleration
   term, and W's angular entry's factors (-d s, d c) */
typedef struct hitch {
    double rx, ry, vx, vy, ax, ay, js, jc;
} hitch;

AI hitch hitch_of(const double *x, car k, double d)
{
    double r = x[5];
    hitch n = {x[0] + d * k.c, x[1] + d * k.s, x[3] - d * k.s * r, x[4] + d * k.c * r,
               -d * k.c * r * r, -d * k.s * r * r, -d * k.s, d * k.c};
    return n;
}

/* the tow bar's row: unit direction e, g, and W's two 3-vectors (V1 rear, V2 front) */
typedef struct bar {
    double ex, ey, len, w1[3], w2[3];
} bar;

AI bar bar_of(hitch n1, hitch n2)
{
    bar b;
    double dx = n1.rx - n2.rx, dy = n1.ry - n2.ry;
    b.len = sqrt(dx * dx + dy * dy + 0.0);
    b.ex = dx / b.len, b.ey = dy / b.len;
    b.w1[0] = b.ex, b.w1[1] = b.ey, b.w1[2] = b.ex * n1.js + b.ey * n1.jc;
    b.w2[0] = -b.ex, b.w2[1] = -b.ey, b.w2[2] = -b.ex * n2.js + -b.ey * n2.jc;
    return b;
}

/* W M^-1 W^T */
AI double schur(const bar *b)
{
    double a1 = b->w1[0] * (b->w1[0] / MASS) + b->w1[1] * (b->w1[1] / MASS) +
                b->w1[2] * (b->w1[2] / IZ);
    double a2 = b->w2[0] * (b->w2[0] / MASS) + b->w2[1] * (b->w2[1] / MASS) +
                b->w2[2] * (b->w2[2] / IZ);
    return a1 + a2;
}

/* z -= M^-1 W^T lam for both cars (z: V1's three velocities at z1, V2's at z2) */
AI void apply(const bar *b, double lam, double *z1, double *z2)
{
    z1[0] -= (b->w1[0] / MASS) * lam, z1[1] -= (b->w1[1] / MASS) * lam;
    z1[2] -= (b->w1[2] / IZ) * lam;
    z2[0] -= (b->w2[0] / MASS) * lam, z2[1] -= (b->w2[1] / MASS) * lam;
    z2[2] -= (b->w2[2] / IZ) * lam;
}

/* x' at x: q' = z, z' = M^-1 (k - W^T lam) */
static void accel(const double *restrict x, double *restrict xd)
{
    const double *x1 = x, *x2 = x + 6;
    car k1 = car_of(x1), k2 = car_of(x2);
    /* driver: pure pursuit of the centre line ld ahead */
    double ld = k1.u * TP > LDMIN ? k1.u * TP : LDMIN;
    double xt = x1[0] + ld, dx = xt - x1[0], dy = centre(xt) - x1[1];
    double e = -k1.s * dx + k1.c * dy;
    double delta1 = rt_atan(2 * WB * e / (dx * dx + dy * dy));
    delta1 = delta1 < -DMAX ? -DMAX : delta1 > DMAX ? DMAX : delta1;
    /* tow-bar steering from the bar's angles to both cars */
    hitch n1 = hitch_of(x1, k1, -DHITCH), n2 = hitch_of(x2, k2, DHITCH);
    double theta = rt_atan2(n1.ry - n2.ry, n1.rx - n2.rx);
    double delta2 = K1 * wrap(x1[2] - theta) + K2 * wrap(theta - x2[2]);
    tires(x1, k1, delta1, KV * (VREF + -k1.u), xd + 3);
    tires(x2, k2, delta2, 0, xd + 9);
    /* the multiplier: A lam = W M^-1 k + gam */
    bar b = bar_of(n1, n2);
    double ddx = n1.vx - n2.vx, ddy = n1.vy - n2.vy, ed = b.ex * ddx + b.ey * ddy;
    double gam = (b.ex * n1.ax + -b.ex * n2.ax) + (b.ey * n1.ay + -b.ey * n2.ay) +
                 (ddx * ddx + ddy * ddy - ed * ed) / b.len;
    double lam = gam + (b.w1[0] * xd[3] + b.w1[1] * xd[4] + b.w1[2] * xd[5]) +
                 (b.w2[0] * xd[9] + b.w2[1] * xd[10] + b.w2[2] * xd[11]);
    apply(&b, lam / schur(&b), xd + 3, xd + 9);
    xd[0] = x1[3], xd[1] = x1[4], xd[2] = x1[5];
    xd[6] = x2[3], xd[7] = x2[4], xd[8] = x2[5];
}

/* g of the bar at x, with the hitches */
AI double bar_g(const double *x, hitch *n1, hitch *n2)
{
    *n1 = hitch_of(x, car_of(x), -DHITCH), *n2 = hitch_of(x + 6, car_of(x + 6), DHITCH);
    double dx = n1->rx - n2->rx, dy = n1->ry - n2->ry;
    return sqrt(dx * dx + dy * dy + 0.0) - BAR;
}

/* the projection of eq. 10: two position iterations with W and A frozen at the predicted
   state, one velocity solve at the projected one; the largest |g| there */
static double project(double *x)
{
    hitch n1, n2;
    bar_g(x, &n1, &n2);
    bar b = bar_of(n1, n2);
    double a = schur(&b), dq[6] = {0, 0, 0, 0, 0, 0};
    for (int it = 0; it < 2; it++) {
        double g = it ? bar_g(x, &n1, &n2) : b.len - BAR;
        dq[0] = dq[1] = dq[2] = dq[3] = dq[4] = dq[5] = 0;
        apply(&b, g / a, dq, dq + 3);
        for (int i = 0; i < 3; i++)
            x[i] += dq[i], x[6 + i] += dq[3 + i];
    }
    double g = bar_g(x, &n1, &n2);
    b = bar_of(n1, n2);
    double gd = b.ex * n1.vx + -b.ex * n2.vx + (b.ey * n1.vy + -b.ey * n2.vy);
    apply(&b, gd / schur(&b), x + 3, x + 9);
    return fabs(g);
}

/* ------------------------------------------------------------------ RK4 */

#define N LT_NX

static double step(lane_tight *m)
{
    static double k[5][N];
    double x0[N], *x = m->x, h = m->h, xs[N];
    for (int i = 0; i < N; i++)
        x0[i] = x[i];
    accel(x0, k[0]);
    for (int i = 0; i < N; i++)
        xs[i] = x0[i] + h * (0.5 * k[0][i]);
    accel(xs, k[1]);
    for (int i = 0; i < N; i++)
        xs[i] = x0[i] + h * (0.5 * k[1][i]);
    accel(xs, k[2]);
    for (int i = 0; i < N; i++)
        xs[i] = x0[i] + h * (1.0 * k[2][i]);
    accel(xs, k[3]);
    if (m->estimate) { /* the estimate's own stage at t + 3h/4 */
        for (int i = 0; i < N; i++)
            xs[i] = x0[i] + h * (3.0 / 16.0 * k[0][i] + 9.0 / 16.0 * k[2][i]);
        accel(xs, k[4]);
    }
    for (int i = 0; i < N; i++)
        x[i] = x0[i] + h * (1.0 / 6.0 * k[0][i] + 1.0 / 3.0 * k[1][i] + 1.0 / 3.0 * k[2][i] +
                            1.0 / 6.0 * k[3][i]);
    if (!m->estimate)
        return 0;
    double mx = 0;
    for (int i = 0; i < N; i++) {
        double s = 1.0 / 32.0 * k[0][i] + -3.0 / 32.0 * k[1][i] + -3.0 / 32.0 * k[2][i] +
                   -3.0 / 32.0 * k[3][i] + 1.0 / 4.0 * k[4][i];
        double r = fabs(h * s) / (1 + fabs(x[i]));
        mx = r > mx ? r : mx;
    }
    return mx;
}

/* ------------------------------------------------------------------ API */

void lane_tight_init(lane_tight *m, const double *x0, double h)
{
    for (int i = 0; i < N; i++)
        m->x[i] = x0[i];
    m->h = h, m->t = 0, m->err_max = 0, m->res_max = 0;
}

__attribute__((noinline)) void lane_tight_steps(lane_tight *m, long n)
{
    for (long i = 0; i < n; i++) {
        double e = step(m);
        m->err_max = e != e || e > m->err_max ? e : m->err_max;
        double r = project(m->x);
        if (m->estimate)
            m->res_max = r <= m->res_max ? m->res_max : r;
        m->t += m->h;
    }
}
