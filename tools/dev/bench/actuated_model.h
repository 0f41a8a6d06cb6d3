/* actuated_model.h - the actuated chain the two actuated monoliths share (actuated_mono.c
 * for pendulum10_actuated_single, actuated_mr_mono.c for the multirate
 * pendulum10_actuated): the defaults of models/actuator.c (servo2, arm_pd), the chain's
 * right-hand side with the motor's torque as a force on B1 (arm_motor), the computed
 * torque of one controller sample, and the servo's right-hand side. Static functions, as
 * pendulum_chain.h: each monolith compiles its own copy. */
#ifndef ACTUATED_MODEL_H
#define ACTUATED_MODEL_H

#include "pendulum_chain.h"

/* servo2 defaults: omega [rad/s], zeta, gain */
static const double OMEGA = 6283.1853071795865, ZETA = 0.7, GAIN = 1;
/* arm_pd defaults: reference from th0 to th1 over T from t0; PD, inertia, static moment */
static const double TH0 = -1.57079632679489661923, TH1 = 0, T0 = 0, TR = 6;
static const double KP = 400, KD = 40, JARM = 10, MG = 98.1;
static const double GAMMA = 1.70710678118654752440; /* ROS2: 1 + 1/sqrt(2) */

/* x' of the chain (NX states) with the motor's torque tau as the force tau / r^2
   (-z, 0, x) on the arm's end B1 */
static void motor_chain_rhs(const double *x, double tau, int solver, double *xd)
{
    chain c;
    factors f;
    double lam[NB];
    double bx = x[0], bz = x[2], rr = bx * bx + bz * bz;
    double fm = rr > 0 ? tau / rr : 0;
    double a0x = -fm * bz / MASS, a0z = (MASS * G_Z + fm * bx) / MASS; /* B1's free accel */
    geometry(x, &c, 1);
    factor(&c, solver, &f);
    /* W a + gam: link 1 sees e_1 . a_1, link 2 e_2 . (a_2 - a_1), the others none */
    lam[0] = c.gam[0] + (c.e[0][0] * a0x + c.e[0][2] * a0z);
    lam[1] = c.gam[1] + (c.e[1][0] * -a0x + c.e[1][2] * (G_Z - a0z));
    for (int k = 2; k < NB; k++)
        lam[k] = c.gam[k];
    solve(&f, solver, lam);
    for (int k = 0; k < NB; k++) {
        xd[6 * k] = x[6 * k + 3], xd[6 * k + 1] = x[6 * k + 4], xd[6 * k + 2] = x[6 * k + 5];
        xd[6 * k + 3] = 0, xd[6 * k + 4] = 0, xd[6 * k + 5] = G_Z;
    }
    xd[3] = a0x, xd[5] = a0z;
    apply(&c, lam, xd, 1);
}

/* the servo's y' = omega w, w' = omega (k u - y) - 2 zeta omega w under the command u */
static void servo_rhs(const double *s, double u, double *sd)
{
    sd[0] = OMEGA * s[1];
    sd[1] = OMEGA * (GAIN * u - s[0]) - 2 * ZETA * OMEGA * s[1];
}

/* arm_pd's computed torque at t for the arm's angle th and its backward-difference rate
   w, on the quintic reference */
static double pd_command(double th, double w, double t)
{
    double s = (t - T0) / TR, d = TH1 - TH0;
    s = s < 0 ? 0 : s > 1 ? 1 : s;
    double s2 = s * s, s3 = s2 * s;
    double r0 = TH0 + d * s3 * (10 - 15 * s + 6 * s2);
    double r1 = d * 30 * s2 * (1 - 2 * s + s2) / TR;
    double r2 = d * 60 * s * (1 - 3 * s + 2 * s2) / (TR * TR);
    return JARM * r2 + MG * cos(th) + KP * (r0 - th) + KD * (r1 - w);
}

#endif /* ACTUATED_MODEL_H */
