/* actuated_mono.h - the hand-written monolith of scene pendulum10_actuated_single
 * (actuated_mono.c), the yardstick of modrt's modular overhead with ROS2
 * (tools/dev/bench/overhead_bench.c, docs/overhead.md). */
#ifndef ACTUATED_MONO_H
#define ACTUATED_MONO_H

#include "pendulum_mono.h"

#define AMONO_NX (6 * MONO_NB + 2) /* the chain, then the servo's y [N m] and w [N m] */

typedef struct amono {
    int solver;            /* MONO_DENSE or MONO_THOMAS (the chain's Schur complement) */
    double h;              /* step = base tick = the controller's period [s] */
    long tick;             /* steps taken */
    double x[AMONO_NX];    /* per body x, y, z [m], vx, vy, vz [m/s]; servo y, w */
    double c, thp;         /* controller: command [N m], last angle [rad] */
    double u;              /* its output, the servo's input: the previous sample's c */
    int started;           /* controller: 0 before the first sample */
    double jac[AMONO_NX * AMONO_NX]; /* the spread refresh's J, then M, then its factors */
    double lu[AMONO_NX * AMONO_NX];  /* the factors of M in use */
    int piv[AMONO_NX], piv_next[AMONO_NX];
    int age, valid;        /* steps since the Jacobian's refresh; 0 before the first */
    long jac_evals;        /* Jacobian refreshes */
    long over;             /* steps whose estimate exceeded the accuracy (modrt splits
                              those; the monolith does not, so it must stay 0) */
    double err_max;        /* largest error estimate */
} amono;

/* Copies the initial state (chain and servo) and projects the chain (eq. 10), as modrt's
   init does; the controller starts at its defaults. */
void amono_init(amono *m, const double *x0);
/* n ticks: the controller's sample, one ROS2 step of m->h, the projection. */
void amono_steps(amono *m, long n);

#endif
