/* tight_chain.h - the chain's kernels as the tight programs write them (pendulum_tight.c
 * for pendulum10, actuated_mr_mono.c's MONO_TIGHT for pendulum10_actuated): one forward
 * sweep forms link k's direction, the Schur complement's row k and eliminates it (Thomas,
 * L D L^T of the tridiagonal A = W M^-1 W^T), the backward sweep gives lam_k and body k's
 * acceleration or correction together; no W or A stored, unit mass and length folded in.
 * Positions q and velocities v of body k are at q + s k and v + s k (stride s: 3 for
 * separate arrays, 6 for modrt's per-body layout x, y, z, vx, vy, vz); s is a constant
 * where the functions are inlined. Static inline functions: each program compiles its own. */
#ifndef TIGHT_CHAIN_H
#define TIGHT_CHAIN_H

#include <math.h>

#ifndef TC_NB
#define TC_NB 10 /* bodies = links of the chain */
#endif
#define TC_AI __attribute__((always_inline)) static inline
static const double TC_GZ = -9.81; /* gravity along z [m/s^2] */

/* accelerations a (stride s) at (q, v): A lam = W a_free + gam, a = a_free - W^T lam. The
   free accelerations are gravity, and with motor = 1 (pendulum10_actuated) body 1's
   (fx, 0, fz) instead: then link 1 sees e_1 . a_1 and link 2 e_2 . (g - a_1) */
TC_AI void tc_accel(const double *restrict q, const double *restrict v, double *restrict a,
                    int s, int motor, double fx, double fz)
{
    double e[TC_NB][3], dia[TC_NB], low[TC_NB], b[TC_NB];
    double px = 0, py = 0, pz = 0, ux0 = 0, uy0 = 0, uz0 = 0; /* the anchor */
    for (int k = 0; k < TC_NB; k++) {
        const double *r = q + s * k, *u = v + s * k;
        double dx = r[0] - px, dy = r[1] - py, dz = r[2] - pz;
        double wx = u[0] - ux0, wy = u[1] - uy0, wz = u[2] - uz0;
        px = r[0], py = r[1], pz = r[2], ux0 = u[0], uy0 = u[1], uz0 = u[2];
        double len = sqrt(dx * dx + dy * dy + dz * dz);
        double ex = dx / len, ey = dy / len, ez = dz / len;
        double ed = ex * wx + ey * wy + ez * wz;
        double gam = (wx * wx + wy * wy + wz * wz - ed * ed) / len;
        double ee = ex * ex + ey * ey + ez * ez;
        e[k][0] = ex, e[k][1] = ey, e[k][2] = ez;
        if (k == 0) {
            dia[0] = ee;
            b[0] = motor ? gam + (ex * fx + ez * fz) : gam + ez * TC_GZ;
        } else {
            double off = -(ex * e[k - 1][0] + ey * e[k - 1][1] + ez * e[k - 1][2]);
            low[k] = off / dia[k - 1];
            dia[k] = ee * 2 - low[k] * off;
            if (motor && k == 1)
                gam = gam + (ex * -fx + ez * (TC_GZ - fz));
            b[k] = gam - low[k] * b[k - 1];
        }
    }
    double ln = b[TC_NB - 1] / dia[TC_NB - 1];
    double *ak = a + s * (TC_NB - 1);
    ak[0] = -(e[TC_NB - 1][0] * ln), ak[1] = -(e[TC_NB - 1][1] * ln);
    ak[2] = TC_GZ - e[TC_NB - 1][2] * ln;
    for (int k = TC_NB - 2; k >= 0; k--) {
        double l = b[k] / dia[k] - low[k + 1] * ln;
        ak = a + s * k;
        double gx = motor && k == 0 ? fx : 0, gz = motor && k == 0 ? fz : TC_GZ;
        ak[0] = motor && k == 0 ? gx - (e[k][0] * l - e[k + 1][0] * ln)
                                : -(e[k][0] * l - e[k + 1][0] * ln);
        ak[1] = -(e[k][1] * l - e[k + 1][1] * ln);
        ak[2] = gz - (e[k][2] * l - e[k + 1][2] * ln);
        ln = l;
    }
}

/* the backward sweep of the Thomas solve, applying dx = -W^T lam to x (stride s) */
TC_AI void tc_back_apply(double e[TC_NB][3], const double *dia, const double *low,
                         const double *b, double *x, int s)
{
    double ln = b[TC_NB - 1] / dia[TC_NB - 1];
    double *xk = x + s * (TC_NB - 1);
    xk[0] -= e[TC_NB - 1][0] * ln, xk[1] -= e[TC_NB - 1][1] * ln;
    xk[2] -= e[TC_NB - 1][2] * ln;
    for (int k = TC_NB - 2; k >= 0; k--) {
        double l = b[k] / dia[k] - low[k + 1] * ln;
        xk = x + s * k;
        xk[0] -= e[k][0] * l - e[k + 1][0] * ln;
        xk[1] -= e[k][1] * l - e[k + 1][1] * ln;
        xk[2] -= e[k][2] * l - e[k + 1][2] * ln;
        ln = l;
    }
}

/* the projection of eq. 10: two position iterations with W and A frozen at the predicted
   q, one velocity solve at the projected q; returns the largest |g| there */
TC_AI double tc_project(double *restrict q, double *restrict v, int s)
{
    double e[TC_NB][3], dia[TC_NB], low[TC_NB], b[TC_NB];
    double px = 0, py = 0, pz = 0;
    for (int k = 0; k < TC_NB; k++) { /* geometry, factors, forward sweep of g */
        const double *r = q + s * k;
        double dx = r[0] - px, dy = r[1] - py, dz = r[2] - pz;
        px = r[0], py = r[1], pz = r[2];
        double len = sqrt(dx * dx + dy * dy + dz * dz);
        double ex = dx / len, ey = dy / len, ez = dz / len;
        double ee = ex * ex + ey * ey + ez * ez;
        e[k][0] = ex, e[k][1] = ey, e[k][2] = ez;
        if (k == 0)
            dia[0] = ee, b[0] = len - 1;
        else {
            double off = -(ex * e[k - 1][0] + ey * e[k - 1][1] + ez * e[k - 1][2]);
            low[k] = off / dia[k - 1];
            dia[k] = ee * 2 - low[k] * off;
            b[k] = (len - 1) - low[k] * b[k - 1];
        }
    }
    tc_back_apply(e, dia, low, b, q, s);
    px = py = pz = 0;
    for (int k = 0; k < TC_NB; k++) { /* g at the corrected q, the same factors */
        const double *r = q + s * k;
        double dx = r[0] - px, dy = r[1] - py, dz = r[2] - pz;
        px = r[0], py = r[1], pz = r[2];
        double g = sqrt(dx * dx + dy * dy + dz * dz) - 1;
        b[k] = k ? g - low[k] * b[k - 1] : g;
    }
    tc_back_apply(e, dia, low, b, q, s);
    double res = 0, ux0 = 0, uy0 = 0, uz0 = 0;
    px = py = pz = 0;
    for (int k = 0; k < TC_NB; k++) { /* velocities: W, A at the projected q; g' */
        const double *r = q + s * k, *u = v + s * k;
        double dx = r[0] - px, dy = r[1] - py, dz = r[2] - pz;
        double wx = u[0] - ux0, wy = u[1] - uy0, wz = u[2] - uz0;
        px = r[0], py = r[1], pz = r[2], ux0 = u[0], uy0 = u[1], uz0 = u[2];
        double len = sqrt(dx * dx + dy * dy + dz * dz);
        double g = fabs(len - 1);
        res = g <= res ? res : g; /* NaN counts as worst */
        double ex = dx / len, ey = dy / len, ez = dz / len;
        double ee = ex * ex + ey * ey + ez * ez;
        double ed = ex * wx + ey * wy + ez * wz;
        e[k][0] = ex, e[k][1] = ey, e[k][2] = ez;
        if (k == 0)
            dia[0] = ee, b[0] = ed;
        else {
            double off = -(ex * e[k - 1][0] + ey * e[k - 1][1] + ez * e[k - 1][2]);
            low[k] = off / dia[k - 1];
            dia[k] = ee * 2 - low[k] * off;
            b[k] = ed - low[k] * b[k - 1];
        }
    }
    tc_back_apply(e, dia, low, b, v, s);
    return res;
}

#endif /* TIGHT_CHAIN_H */
