/* pendulum_mono.h - the hand-written monolith of scene pendulum10 (pendulum_mono.c), the
 * yardstick of modrt's modular overhead (tools/dev/bench/overhead_bench.c). */
#ifndef PENDULUM_MONO_H
#define PENDULUM_MONO_H

#define MONO_NB 10 /* bodies and constraints of pendulum10 */

enum { MONO_BS3, MONO_RK4, MONO_DOPRI5 };  /* methods (tableaus of rt/integ_erk.c) */
enum { MONO_DENSE, MONO_THOMAS, MONO_TIGHT }; /* solvers of the Schur complement (MONO_TIGHT:
                                                the fused kernels of tight_chain.h, in
                                                actuated_mr_mono.c) */

typedef struct mono {
    int method, solver;
    int estimate;          /* 1: the embedded error estimate, as modrt's steps compute it */
    double h;              /* step [s] */
    double x[6 * MONO_NB]; /* per body x, y, z [m], vx, vy, vz [m/s] */
    double err_max;        /* largest error estimate */
} mono;

/* Copies the initial state and projects it (eq. 10), as modrt's init does. */
void mono_init(mono *m, const double *x0);
/* n steps of m->h, each followed by the projection. */
void mono_steps(mono *m, long n);

#endif
