/* lane_tight.h - the tightest hand-written program of scene lane_change_planar
 * (lane_tight.c), the yardstick of modrt's overhead on it (tools/dev/bench/tight_bench.c,
 * docs/overhead.md). */
#ifndef LANE_TIGHT_H
#define LANE_TIGHT_H

#define LT_NX 12 /* per car x, y, psi [m, m, rad], vx, vy [m/s], r [rad/s]: V1, then V2 */

typedef struct lane_tight {
    int estimate;      /* 1: modrt's embedded error estimate (RK4's extra stage) */
    double h;          /* step [s] */
    double t;          /* time [s] */
    double x[LT_NX];   /* the state, modrt's layout */
    double err_max;    /* largest error estimate, as modrt's err_max */
    double res_max;    /* largest |g| after a projection [m] */
} lane_tight;

/* Copies the state x0 (modrt's after init: consistent already). */
void lane_tight_init(lane_tight *m, const double *x0, double h);
/* n RK4 steps of m->h, each followed by the projection (eq. 10). */
void lane_tight_steps(lane_tight *m, long n);

#endif
