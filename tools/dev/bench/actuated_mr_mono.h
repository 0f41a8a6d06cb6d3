/* actuated_mr_mono.h - the hand-written monolith of the multirate scene pendulum10_actuated
 * (actuated_mr_mono.c), the yardstick of modrt's modular overhead on a multirate schedule
 * (tools/dev/bench/overhead_bench.c, docs/overhead.md). */
#ifndef ACTUATED_MR_MONO_H
#define ACTUATED_MR_MONO_H

#include "pendulum_mono.h"

#define AMR_RATIO 4 /* base ticks per step of the chain (the background set) */

typedef struct amr {
    int solver;            /* MONO_DENSE or MONO_THOMAS (the chain's Schur complement) */
    int estimate;          /* 1: what modrt computes and the schedule does not need: bs3's
                              embedded error estimate (one right-hand side more per chain
                              step) and the monitors of the cross-set histories; 0: not */
    double dt;             /* base tick = servo step = the controller's period [s] */
    long tick;             /* base ticks taken */
    double x[6 * MONO_NB]; /* chain: per body x, y, z [m], vx, vy, vz [m/s]; between its
                              releases already at its next communication point */
    double s[2];           /* servo: y, w [N m] */
    double c, thp;         /* controller: command [N m], last angle [rad] */
    int started;           /* controller: 0 before the first sample */
    double u;              /* controller output = servo input: the previous sample's c */
    /* the chain's history as the servo side reads it: B1's x, z [m] at its last three
       published communication points (newest first), and how many there are (<= 3) */
    double ct[3], cx[3], cz[3];
    int cn;
    /* the servo's history as the chain reads it: y at its last two step ends */
    double st[2], sy[2];
    int sn;
    /* ROS2 on the servo: forward-difference Jacobian, LU of I - gamma dt J */
    double jac[4], lu[4];
    int piv[2];
    int age, valid;        /* steps since the Jacobian's refresh; 0 before the first */
    long jac_evals;        /* Jacobian refreshes */
    long over;             /* servo steps whose estimate exceeded the set's accuracy (modrt
                              splits those; the monolith does not, so it must stay 0) */
    double err_servo;      /* largest ROS2 estimate */
    double err_chain;      /* largest bs3 estimate (estimate = 1) */
    double xerr_chain;     /* monitors (estimate = 1): largest distance of a new history */
    double xerr_servo;     /* point from the line through the previous two */
} amr;

/* Starts from modrt's state after rt_init: the chain's states x0 (projected already), the
   servo's s0; each history holds the one point at t = 0; the controller at its defaults. */
void amr_init(amr *m, const double *x0, const double *s0);
/* n base ticks: the chain's step every AMR_RATIO ticks, the controller's sample and one
   ROS2 step of the servo every tick. */
void amr_steps(amr *m, long n);

#endif
