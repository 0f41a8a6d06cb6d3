/* actuated_mr_mono.c - the hand-written monolith of the multirate scene pendulum10_actuated:
 * the ten-body chain (pendulum_chain.h) whose first link the motor turns, stepped by
 * Bogacki-Shampine every AMR_RATIO base ticks in the background, and the servo (servo2)
 * under the sampled controller (arm_pd, 1 kHz), stepped by ROS2 every base tick, with the
 * rate transitions of rt/xset.c and rt/bg.c, as modrt computes them (docs/multirate.md,
 * "Held outputs", "Background sets"):
 *
 *  - the chain's step from kH to (k+1)H runs at the start of the tick at kH (its release)
 *    and reads the servo's torque by linear extrapolation from the servo's last two step
 *    ends (kH and kH - dt) at each stage time; then the projection (eq. 10). Its result
 *    becomes visible only when the tick count reaches (k+1)H (its publication): the new
 *    point of its history. A Jacobi transition: neither side reads the other's values
 *    from inside the window in which the step may run, so modrt may run it preemptible;
 *    the monolith, with nothing else reading the chain's state, steps it in place;
 *  - every tick the controller samples B1 at t from the chain's history: always ahead of
 *    it (the newest point is at or before t), so the servo set's Hermite scheme falls
 *    back to the line through the newest two points, plus the fade of the jump at the
 *    newest point, jump (1 - (t - T0) / (T0 - T1)), once three points exist; its command
 *    reaches the servo one sample later (the output is refreshed after the tick's steps)
 *    and is held over the servo's step;
 *  - the servo: ROS2 as rt/integ_implicit.c (forward-difference Jacobian at the step's
 *    first evaluation, refreshed every 64 steps and at the first; I - gamma h J factored
 *    by Gauss with partial pivoting; no f_t term (the servo is autonomous under its held
 *    command, as modrt finds too); the
 *    estimate h/2 (k1 + k2), which decides whether modrt splits the step: it never does
 *    in this scene, the monolith counts such steps instead and the check fails on one).
 *
 * What the schedule does not need and modrt computes anyway is behind m->estimate: bs3's
 * embedded error estimate (one right-hand side more per chain step) and the monitors of
 * the cross-set histories (rt_stats.xset_err). Plain C, the same order of operations as
 * modrt where it decides the bits. */
#include "actuated_mr_mono.h"

#include <float.h>
#include <string.h>

#include "actuated_model.h"
#include "tight_chain.h"

/* the servo set's Jacobian refresh and accuracy (ROS2's gamma: actuated_model.h) */
static const int JAC_EVERY = 64;
static const double ACCURACY = 1e-2;
/* Bogacki-Shampine 3(2) (rt/integ_erk.c): a21, a32, b, and b - bhat */
static const double A21 = 0.5, A32 = 0.75;
static const double BB1 = 2.0 / 9.0, BB2 = 1.0 / 3.0, BB3 = 4.0 / 9.0;
static const double BE1 = -5.0 / 72.0, BE2 = 1.0 / 12.0, BE3 = 1.0 / 9.0, BE4 = -1.0 / 8.0;

/* ------------------------------------------------------------------ the chain */

/* the servo's torque at t as the chain reads it: the line through its last two step
   ends (held while there is one) */
static double torque(const amr *m, double t)
{
    if (m->sn < 2)
        return m->sy[0];
    return m->sy[1] + (m->sy[0] - m->sy[1]) * (t - m->st[1]) / (m->st[0] - m->st[1]);
}

/* x' of the chain with the motor's force from the torque the chain reads at t */
static void rhs(const amr *m, double t, const double *x, double *xd)
{
    if (m->solver != MONO_TIGHT) {
        motor_chain_rhs(x, torque(m, t), m->solver, xd);
        return;
    }
    /* the tight program: the motor's force on B1 as motor_chain_rhs forms it, then the
       fused Thomas sweeps of tight_chain.h */
    double tau = torque(m, t), bx = x[0], bz = x[2], rr = bx * bx + bz * bz;
    double fm = rr > 0 ? tau / rr : 0;
    for (int k = 0; k < NB; k++)
        xd[6 * k] = x[6 * k + 3], xd[6 * k + 1] = x[6 * k + 4], xd[6 * k + 2] = x[6 * k + 5];
    tc_accel(x, x + 3, xd + 3, 6, 1, -fm * bz / MASS, (MASS * G_Z + fm * bx) / MASS);
}

/* one bs3 step of H from t (three stages; the fourth only for the estimate), then the
   projection */
static void chain_step(amr *m, double t, double H)
{
    double *x = m->x, x0[NX], k1[NX], k2[NX], k3[NX];
    memcpy(x0, x, sizeof x0);
    rhs(m, t, x, k1);
    for (int i = 0; i < NX; i++)
        x[i] = x0[i] + H * (A21 * k1[i]);
    rhs(m, t + A21 * H, x, k2);
    for (int i = 0; i < NX; i++)
        x[i] = x0[i] + H * (A32 * k2[i]);
    rhs(m, t + A32 * H, x, k3);
    for (int i = 0; i < NX; i++)
        x[i] = x0[i] + H * (BB1 * k1[i] + BB2 * k2[i] + BB3 * k3[i]);
    if (m->estimate) { /* against the embedded second-order solution, with f(t + H, x1) */
        double err = 0;
        for (int i = 0; i < NX; i++)
            x0[i] = BE1 * k1[i] + BE2 * k2[i] + BE3 * k3[i];
        rhs(m, t + H, x, k1);
        for (int i = 0; i < NX; i++) {
            double r = fabs(H * (x0[i] + BE4 * k1[i])) / (1 + fabs(x[i]));
            err = r > err ? r : err;
        }
        m->err_chain = err > m->err_chain ? err : m->err_chain;
    }
    if (m->solver == MONO_TIGHT)
        tc_project(x, x + 3, 6);
    else
        project(x, m->solver);
}

/* the distance of a new history value y from the line through the last two points */
static double monitor(double y0, double y1, double t0, double t1, double t, double y)
{
    return fabs(y0 + (y0 - y1) * (t - t0) / (t0 - t1) - y);
}

/* publication at t: B1's position becomes the newest point of the chain's history */
static void push_chain(amr *m, double t)
{
    if (m->estimate && m->cn >= 2) {
        double ex = monitor(m->cx[0], m->cx[1], m->ct[0], m->ct[1], t, m->x[0]);
        double ez = monitor(m->cz[0], m->cz[1], m->ct[0], m->ct[1], t, m->x[2]);
        ex = ez > ex ? ez : ex;
        m->xerr_chain = ex > m->xerr_chain ? ex : m->xerr_chain;
    }
    for (int k = 2; k > 0; k--)
        m->ct[k] = m->ct[k - 1], m->cx[k] = m->cx[k - 1], m->cz[k] = m->cz[k - 1];
    m->ct[0] = t, m->cx[0] = m->x[0], m->cz[0] = m->x[2];
    m->cn += m->cn < 3;
}

/* ------------------------------------------------------------------ controller */

/* B1's coordinate y (history cx or cz) at t as the controller samples it: ahead of the
   chain's history, the line through its newest two points, and from three points on the
   jump the newest point made against the line before it, faded out over a macro step */
static double b1_at(const amr *m, const double *y, double t)
{
    const double *T = m->ct;
    if (m->cn < 2)
        return y[0];
    double v = y[1] + (y[0] - y[1]) * (t - T[1]) / (T[0] - T[1]);
    if (m->cn == 3) {
        double jump = y[2] + (y[1] - y[2]) * (T[0] - T[2]) / (T[1] - T[2]) - y[0];
        double fade = 1 - (t - T[0]) / (T[0] - T[1]);
        v += jump * (fade > 0 ? fade : 0);
    }
    return v;
}

/* one sample at t: angle, backward-difference rate, computed torque on the quintic
   reference (models/actuator.c arm_pd) */
static void control(amr *m, double t)
{
    double th = atan2(b1_at(m, m->cz, t), b1_at(m, m->cx, t));
    double w = m->started ? (th - m->thp) / m->dt : 0;
    m->c = pd_command(th, w, t);
    m->thp = th;
    m->started = 1;
}

/* ------------------------------------------------------------------ the servo: ROS2 */

/* the servo under the held command */
static void srhs(const amr *m, const double *x, double *xd)
{
    servo_rhs(x, m->u, xd);
}

/* forward-difference Jacobian at s around fb = f(s); then I - h gamma J factored */
static void jacobian(amr *m, const double *fb)
{
    double *x = m->s, fd[2], sq = sqrt(DBL_EPSILON), hg = m->dt * GAMMA, *a = m->lu;
    for (int j = 0; j < 2; j++) {
        double xj = x[j], ax = fabs(xj);
        x[j] = xj + sq * (ax > 1 ? ax : 1);
        double d = x[j] - xj;
        srhs(m, x, fd);
        x[j] = xj;
        for (int i = 0; i < 2; i++)
            m->jac[2 * i + j] = (fd[i] - fb[i]) / d;
    }
    for (int i = 0; i < 4; i++)
        a[i] = (i == 0 || i == 3 ? 1 : 0) - hg * m->jac[i];
    /* Gauss with partial pivoting on 2 x 2 */
    m->piv[0] = fabs(a[2]) > fabs(a[0]), m->piv[1] = 1;
    if (m->piv[0]) {
        double t0 = a[0], t1 = a[1];
        a[0] = a[2], a[1] = a[3], a[2] = t0, a[3] = t1;
    }
    a[2] /= a[0];
    a[3] -= a[2] * a[1];
    m->age = 0, m->valid = 1;
    m->jac_evals++;
}

static void msolve(const amr *m, double *b)
{
    const double *a = m->lu;
    if (m->piv[0]) {
        double t = b[0];
        b[0] = b[1], b[1] = t;
    }
    b[1] -= a[2] * b[0];
    b[1] /= a[3];
    b[0] -= a[1] * b[1];
    b[0] /= a[0];
}

/* one ROS2 step of dt of the servo */
static void servo_step(amr *m)
{
    double *x = m->s, x0[2] = {x[0], x[1]}, k1[2], k2[2], h = m->dt, err = 0;
    srhs(m, x, k1);
    if (!m->valid || m->age >= JAC_EVERY)
        jacobian(m, k1);
    /* no f_t term: the servo does not read t and its command holds over the step (modrt
       finds the same and skips f(t + h, x0): rt/eval.c RTI_SET_AUTONOMOUS) */
    msolve(m, k1);
    for (int i = 0; i < 2; i++)
        x[i] = x0[i] + h * k1[i];
    srhs(m, x, k2);
    for (int i = 0; i < 2; i++)
        k2[i] -= 2 * k1[i];
    msolve(m, k2);
    for (int i = 0; i < 2; i++) {
        x[i] = x0[i] + h * (1.5 * k1[i] + 0.5 * k2[i]);
        double r = fabs(h * 0.5 * (k1[i] + k2[i])) / (1 + fabs(x[i]));
        err = r > err ? r : err;
    }
    m->age++;
    m->err_servo = err > m->err_servo ? err : m->err_servo;
    m->over += !(err <= ACCURACY);
}

/* the servo's step end at t becomes the newest point of its history */
static void push_servo(amr *m, double t)
{
    if (m->estimate && m->sn >= 2) {
        double e = monitor(m->sy[0], m->sy[1], m->st[0], m->st[1], t, m->s[0]);
        m->xerr_servo = e > m->xerr_servo ? e : m->xerr_servo;
    }
    m->st[1] = m->st[0], m->sy[1] = m->sy[0];
    m->st[0] = t, m->sy[0] = m->s[0];
    m->sn = 2;
}

/* ------------------------------------------------------------------ API */

void amr_init(amr *m, const double *x0, const double *s0)
{
    memcpy(m->x, x0, sizeof m->x);
    m->s[0] = s0[0], m->s[1] = s0[1];
    m->tick = 0, m->u = 0, m->c = 0, m->thp = TH0, m->started = 0;
    m->ct[0] = 0, m->cx[0] = x0[0], m->cz[0] = x0[2], m->cn = 1;
    m->st[0] = 0, m->sy[0] = s0[0], m->sn = 1;
    m->age = 0, m->valid = 0, m->jac_evals = 0, m->over = 0;
    m->err_servo = m->err_chain = m->xerr_chain = m->xerr_servo = 0;
}

__attribute__((noinline)) void amr_steps(amr *m, long n)
{
    for (long i = 0; i < n; i++) {
        double t = (double)m->tick * m->dt;
        if (m->tick % AMR_RATIO == 0) /* release: the chain's step to its next point */
            chain_step(m, t, m->dt * AMR_RATIO);
        m->u = m->c; /* the output held over this step: the previous sample's command */
        control(m, t);
        servo_step(m);
        push_servo(m, (double)(m->tick + 1) * m->dt);
        m->tick++;
        if (m->tick % AMR_RATIO == 0) /* publication */
            push_chain(m, (double)m->tick * m->dt);
    }
}
