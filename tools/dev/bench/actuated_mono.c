/* actuated_mono.c - the hand-written monolith of scene pendulum10_actuated_single: the
 * ten-body pendulum of pendulum10 (pendulum_chain.h, shared with pendulum_mono.c) whose
 * first link a motor turns, driven by a second-order servo (models/actuator.c servo2,
 * arm_motor) under a sampled computed-torque controller (arm_pd, 1 kHz), all in one set
 * integrated by ROS2 at the base tick of 1 ms as rt/integ_implicit.c does it:
 * M = I - gamma h J with J from forward differences at the step's first evaluation
 * (x_j + sqrt(eps) max(|x_j|, 1), the increment re-measured), whole at the first step,
 * then every 1024 steps spread as modrt spreads it (rt/integ_implicit.c spread_parts): in
 * the last 2n + 1 steps of a cycle one part each, a column of J at that step's first
 * evaluation, then M formed, then one elimination stage of Gauss with partial pivoting;
 * the step at the cycle's end installs the factors;
 *     M k1 = f(t, x0),
 *     M k2 = f(t + h, x0 + h k1) - 2 k1,
 * (the f_t term gamma (f(t + h, x0) - f(t, x0)) is zero: the model does not read t and
 * the controller's output holds over the step, which modrt finds too and skips the
 * evaluation: rt/eval.c RTI_SET_AUTONOMOUS),
 *     x1 = x0 + h (3/2 k1 + 1/2 k2),
 * the estimate h/2 (k1 + k2) against x0 + h k1 (modrt splits a step above the scene's
 * accuracy 1e-2; in this scene none is: the monolith counts such steps instead, and the
 * trajectory check fails if there is one), then the projection of the chain (eq. 10).
 * Per tick, as rt/sim.c: the controller samples the arm at t (after the previous step's
 * projection); the servo reads the controller's output, which is the command of the
 * sample before (arm_pd's computation delay: the output is refreshed after the tick's
 * steps) and holds over the step. Plain C. */
#include "actuated_mono.h"

#include <float.h>
#include <string.h>

#include "actuated_model.h"

#define NA AMONO_NX
#define SERVO NX /* index of the servo's y; its w follows */

static const int JAC_EVERY = 1024;
static const double ACCURACY = 1e-2;

/* ------------------------------------------------------------------ right-hand side */

/* x' of the chain with the motor's force on B1 and of the servo under the held command */
static void rhs(const amono *m, const double *x, double *xd)
{
    motor_chain_rhs(x, x[SERVO], m->solver, xd);
    servo_rhs(x + SERVO, m->u, xd + SERVO);
}

/* ------------------------------------------------------------------ controller */

/* one sample at t: angle, backward-difference rate, computed torque on the quintic
   reference (models/actuator.c arm_pd) */
static void control(amono *m, double t)
{
    double th = atan2(m->x[2], m->x[0]);
    double w = m->started ? (th - m->thp) / m->h : 0;
    m->c = pd_command(th, w, t);
    m->thp = th;
    m->started = 1;
}

/* ------------------------------------------------------------------ ROS2 */

/* the spread refresh: 2 NA + 1 parts, PER per step in the last SPREAD steps of a cycle */
#define PARTS (2 * NA + 1)
#define PER ((PARTS + JAC_EVERY - 2) / (JAC_EVERY - 1))
#define SPREAD ((PARTS + PER - 1) / PER)

/* columns j0 .. j1 - 1 of the forward-difference Jacobian into a, at x around fb = f(x) */
static void columns(amono *m, const double *fb, double *a, int j0, int j1)
{
    double *x = m->x, fd[NA], sq = sqrt(DBL_EPSILON);
    for (int j = j0; j < j1; j++) {
        double xj = x[j], ax = fabs(xj);
        x[j] = xj + sq * (ax > 1 ? ax : 1);
        double d = x[j] - xj;
        rhs(m, x, fd);
        x[j] = xj;
        for (int i = 0; i < NA; i++)
            a[i * NA + j] = (fd[i] - fb[i]) / d;
    }
}

/* J in a becomes M = I - h gamma J */
static void iteration_matrix(const amono *m, double *a)
{
    double hg = m->h * GAMMA;
    for (int i = 0; i < NA; i++)
        for (int j = 0; j < NA; j++)
            a[i * NA + j] = (i == j ? 1 : 0) - hg * a[i * NA + j];
}

/* elimination stages k0 .. k1 - 1 of Gauss with partial pivoting on a */
static void eliminate(double *a, int *piv, int k0, int k1)
{
    for (int k = k0; k < k1; k++) {
        int p = k;
        for (int i = k + 1; i < NA; i++)
            if (fabs(a[i * NA + k]) > fabs(a[p * NA + k]))
                p = i;
        piv[k] = p;
        if (p != k)
            for (int j = 0; j < NA; j++) {
                double t = a[k * NA + j];
                a[k * NA + j] = a[p * NA + j], a[p * NA + j] = t;
            }
        for (int i = k + 1; i < NA; i++) {
            double l = a[i * NA + k] /= a[k * NA + k];
            for (int j = k + 1; j < NA; j++)
                a[i * NA + j] -= l * a[k * NA + j];
        }
    }
}

/* the whole refresh at x around fb = f(x) (the first step's; modrt's before the first tick) */
static void jacobian(amono *m, const double *fb)
{
    columns(m, fb, m->lu, 0, NA);
    iteration_matrix(m, m->lu);
    eliminate(m->lu, m->piv, 0, NA);
    m->age = 0, m->valid = 1;
    m->jac_evals++;
}

/* the parts of the spread refresh due at this step (in m->jac), or at the cycle's end its
   factors installed */
static void refresh(amono *m, const double *fb)
{
    if (!m->valid) {
        jacobian(m, fb);
        return;
    }
    if (m->age >= JAC_EVERY) {
        memcpy(m->lu, m->jac, sizeof m->lu);
        memcpy(m->piv, m->piv_next, sizeof m->piv);
        m->age = 0;
        m->jac_evals++;
        return;
    }
    if (m->age + SPREAD < JAC_EVERY)
        return;
    int p0 = (m->age + SPREAD - JAC_EVERY) * PER, p1 = p0 + PER < PARTS ? p0 + PER : PARTS;
    if (p0 < NA)
        columns(m, fb, m->jac, p0, p1 < NA ? p1 : NA);
    if (p0 <= NA && NA < p1)
        iteration_matrix(m, m->jac);
    if (p1 > NA + 1)
        eliminate(m->jac, m->piv_next, p0 > NA + 1 ? p0 - NA - 1 : 0, p1 - NA - 1);
}

static void msolve(const amono *m, double *b)
{
    const double *a = m->lu;
    for (int k = 0; k < NA; k++) {
        double t = b[m->piv[k]];
        b[m->piv[k]] = b[k], b[k] = t;
    }
    for (int i = 1; i < NA; i++)
        for (int j = 0; j < i; j++)
            b[i] -= a[i * NA + j] * b[j];
    for (int i = NA - 1; i >= 0; i--) {
        for (int j = i + 1; j < NA; j++)
            b[i] -= a[i * NA + j] * b[j];
        b[i] /= a[i * NA + i];
    }
}

/* one ROS2 step of h, then the chain's projection */
static void step(amono *m)
{
    double *x = m->x, x0[NA], k1[NA], k2[NA], h = m->h;
    memcpy(x0, x, sizeof x0);
    rhs(m, x, k1);
    refresh(m, k1);
    msolve(m, k1);
    for (int i = 0; i < NA; i++)
        x[i] = x0[i] + h * k1[i];
    rhs(m, x, k2);
    for (int i = 0; i < NA; i++)
        k2[i] -= 2 * k1[i];
    msolve(m, k2);
    double err = 0;
    for (int i = 0; i < NA; i++) {
        x[i] = x0[i] + h * (1.5 * k1[i] + 0.5 * k2[i]);
        double r = fabs(h * 0.5 * (k1[i] + k2[i])) / (1 + fabs(x[i]));
        err = r > err ? r : err;
    }
    m->age++;
    m->err_max = err > m->err_max ? err : m->err_max;
    m->over += !(err <= ACCURACY);
    project(x, m->solver);
}

/* ------------------------------------------------------------------ API */

void amono_init(amono *m, const double *x0)
{
    memcpy(m->x, x0, sizeof m->x);
    project(m->x, m->solver);
    m->tick = 0, m->u = 0, m->c = 0, m->thp = TH0, m->started = 0;
    m->age = 0, m->valid = 0, m->jac_evals = 0, m->over = 0, m->err_max = 0;
}

__attribute__((noinline)) void amono_steps(amono *m, long n)
{
    for (long i = 0; i < n; i++) {
        m->u = m->c; /* the output held over this step: the previous sample's command */
        control(m, (double)m->tick * m->h);
        step(m);
        m->tick++;
    }
}
