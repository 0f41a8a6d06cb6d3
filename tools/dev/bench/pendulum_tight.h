/* pendulum_tight.h - the tightest hand-written program of scene pendulum10 (pendulum_tight.c),
 * the yardstick of modrt's overhead on it (tools/dev/bench/overhead_bench.c, docs/overhead.md). */
#ifndef PENDULUM_TIGHT_H
#define PENDULUM_TIGHT_H

#ifndef TIGHT_NB
#define TIGHT_NB 10 /* bodies and constraints of pendulum10 (tools/dev/bench/scale.sh: any chain) */
#endif

enum { TIGHT_BS3, TIGHT_RK4, TIGHT_DOPRI5 }; /* methods (tableaus of rt/integ_erk.c) */

typedef struct tight {
    int method;
    int estimate;              /* 1: modrt's embedded error estimate (one evaluation more) */
    double h;                  /* step [s] */
    double q[3 * TIGHT_NB];    /* positions per body x, y, z [m] */
    double v[3 * TIGHT_NB];    /* velocities [m/s] */
    double err_max;            /* largest error estimate, as modrt's err_max */
    double res_max;            /* largest |g| after a projection [m] */
} tight;

/* Copies the initial state x0 (per body x, y, z, vx, vy, vz) and projects it once. */
void tight_init(tight *m, const double *x0);
/* n steps of m->h, each followed by the projection (eq. 10). */
void tight_steps(tight *m, long n);

#endif
