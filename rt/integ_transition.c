/* integ_transition.c - the transition-matrix method for a set linear in its state (every
 * block not sampled of a kind declaring rt_kind.linear: the paper's linear state space,
 * eq. 4, and its kin). With the set's right-hand side f(t, x) = J x + g(t),
 *
 *     x1 = x0 + h phi1(h J) f(t, x0) + h phi2(h J) (f(t + h, x0) - f(t, x0))
 *
 * is the exact solution when g is linear over the step: exact when the inputs hold (a
 * sampled controller's command: the zero-order-hold discretization of control
 * engineering, x1 = e^hJ x0 + h phi1(h J) g), second order when they ramp (a first-order
 * hold of g through its two ends), at any h J: no stability limit and no damping the model
 * does not have, where the trapezoidal rule rings and ROS2 damps a 1 kHz servo stepped at
 * 1 ms. In an autonomous set (its inputs hold over the step, rti_eval_plan) the second term
 * is zero and left out: one evaluation per step.
 *
 * J is exact to rounding: f is linear in x, so differences over large increments
 * (RT_TRANSITION_INC max(1, |x_j|), re-measured as the representable difference) have no
 * truncation error. J is formed, and h phi1, h phi2 with it (rti_phi12; kept in the set's
 * rt_implicit_ws, lu and jac), at the first step, when h changes, and after a parameter of
 * one of the set's blocks changed (rt_set_param clears ws->valid); the set's `jacobian`
 * interval is not used; a located event re-forms them for its partial step, and for the
 * full step after it. The refresh costs n evaluations and about
 * (RT_TRANSITION_TAYLOR + 2 + 3 s) n^3 multiply-adds, s the halvings that bring |h J|_1
 * to RT_TRANSITION_THETA (5 for the servo of pendulum10_actuated at 1 ms); a step, one or
 * two evaluations and 2 n^2.
 *
 * Error estimate: 0 when the inputs hold (autonomous), where the step is exact. Else the
 * step's error is what g departs from its chord over the step, |g - chord| <= |g''| h^2 / 8
 * (at the midpoint), weighted by the flow: e_i = sum_j |h phi1(h J)|_ij |dev_j|, with dev
 * = (d_now - d_prev) / 8 from the change d = f(t + h, x0) - f(t, x0) of this step and the
 * last (a second difference, h^2 g''; kept in the set's rt_implicit_ws.best), and at the
 * first step after a refresh, which has no last one, dev = f(t + h/2, x0) - (f(t, x0) +
 * f(t + h, x0)) / 2 (one evaluation more). A jump of the inputs between steps moves g, not
 * d: a held command that changes at each sample is not read as an error.
 *
 * A refresh that would need more than RT_TRANSITION_HALVINGS halvings (|h J|_1 above
 * 5e11), meets a non-finite J or whose matrices overflow (a mode growing by e^1000 over
 * the step) leaves the state at x0 and returns RT_E_SINGULAR; the next step tries again.
 * A right-hand side that is not finite when a refresh is due (a NaN input) is put into the
 * state instead, which rt/step.c puts back and counts as NaN with its block. */
#include "rti.h"

#include "linalg.h"

#define R(v) ((real_t)(v))

/* n x n matrices in the set's rt_implicit_ws: h phi1(h J) in lu, h phi2(h J) in jac */
static rt_status refresh(const rt_rhs *f, real_t t, real_t h, real_t *x, uint16_t n,
                         const rt_iwork *w, const real_t *f0)
{
    rt_implicit_ws *ws = w->imp;
    real_t *a = w->tm, *scratch = n ? w->tm + (size_t)n * n : w->tm;
    rt_status st = rti_fd_jacobian(f, t, x, n, f0, RT_TRANSITION_INC, w->k[2], a);
    for (uint32_t i = 0; i < (uint32_t)n * n; i++) /* h J, what phi takes */
        a[i] *= h;
    w->stats->jac_evals++;
    ws->age = 0;
    ws->valid = 0;
    if (rti_phi12(a, n, ws->lu, ws->jac, scratch, RT_TRANSITION_THETA, RT_TRANSITION_TAYLOR,
                  RT_TRANSITION_HALVINGS) != RT_OK)
        return RT_E_SINGULAR;
    for (uint32_t i = 0; i < (uint32_t)n * n; i++)
        ws->lu[i] *= h, ws->jac[i] *= h;
    ws->h_factored = h;
    ws->valid = 1;
    return st;
}

/* the step of a set whose inputs change over it: the first-order hold, and its estimate
   into *err (the file's comment); df, dev in the stage buffers, d_prev in ws->best */
static rt_status ramp_step(const rt_rhs *f, real_t t, real_t h, real_t *x, uint16_t n,
                           const rt_iwork *w, const real_t *f0, real_t *err)
{
    rt_implicit_ws *ws = w->imp;
    real_t *df = w->k[1], *dev = w->k[2];
    rt_status st = f->eval(f->ctx, t + h, df);
    for (uint16_t i = 0; i < n; i++)
        df[i] -= f0[i];
    if (ws->age == 0) { /* no last step: the midpoint's departure from the chord */
        rt_status sm = f->eval(f->ctx, t + R(0.5) * h, dev);
        st = st == RT_OK ? sm : st;
        for (uint16_t i = 0; i < n; i++)
            dev[i] -= f0[i] + R(0.5) * df[i];
    } else {
        for (uint16_t i = 0; i < n; i++)
            dev[i] = R(0.125) * (df[i] - ws->best[i]);
    }
    const real_t *p1 = ws->lu, *p2 = ws->jac;
    real_t sa = rti_err_floor(w->cfg);
    for (uint16_t i = 0; i < n; i++, p1 += n, p2 += n) {
        real_t dx = 0, e = 0;
        for (uint16_t j = 0; j < n; j++)
            dx += p1[j] * f0[j];
        for (uint16_t j = 0; j < n; j++)
            dx += p2[j] * df[j], e += rt_fabs(p1[j]) * rt_fabs(dev[j]);
        x[i] += dx;
        real_t r = e / (sa + rt_fabs(x[i]));
        *err = r > *err || r != r ? r : *err; /* a NaN sticks */
    }
    for (uint16_t i = 0; i < n; i++)
        ws->best[i] = df[i];
    return st;
}

static rt_status transition_step(const rt_integrator *m, const rt_rhs *f, real_t t, real_t h,
                                 real_t *x, uint16_t n, const rt_iwork *w)
{
    rt_implicit_ws *ws = w->imp;
    real_t *f0 = w->k[0];
    (void)m;
    if (!(h != 0))
        return RT_OK;
    rt_status st = f->eval(f->ctx, t, f0);
    if (!ws->valid || ws->h_factored != h) {
        if (!rt_all_finite(f0, n)) {
            /* a NaN input: no Jacobian to form; the NaN goes into the state, which
               rt/step.c puts back and counts with its block */
            for (uint16_t i = 0; i < n; i++)
                x[i] += f0[i];
            return st;
        }
        rt_status sr = refresh(f, t, h, x, n, w, f0);
        if (sr == RT_E_SINGULAR)
            return sr;
        st = st == RT_OK ? sr : st;
    }
    real_t err = 0;
    if (w->autonomous) { /* exact: no estimate */
        const real_t *p1 = ws->lu;
        for (uint16_t i = 0; i < n; i++, p1 += n) {
            real_t dx = 0;
            for (uint16_t j = 0; j < n; j++)
                dx += p1[j] * f0[j];
            x[i] += dx;
        }
    } else {
        rt_status s1 = ramp_step(f, t, h, x, n, w, f0, &err);
        st = st == RT_OK ? s1 : st;
    }
    ws->age++;
    w->stats->last_err = err;
    if (err != err || err > w->stats->err_max)
        w->stats->err_max = err;
    w->stats->last_residual = 0;
    return st;
}

/* a step: f(t, x0) and f(t + h, x0); a refresh: n more and the midpoint's (the phi work
   is counted as factorizations of n^3 / 3 multiply-adds each) */
static void transition_bound(const rt_integrator *m, const rt_set_cfg *cfg, uint16_t n,
                             rt_step_work *w)
{
    (void)m, (void)cfg;
    w->rhs = 3u + n;
    w->lu = 3u * (RT_TRANSITION_TAYLOR + 2u + 3u * RT_TRANSITION_HALVINGS);
}

/* stages: the evaluations of a step in an autonomous set (the tuner's lower bound); it
   uses the stage buffers k[0..2] (RT_MAX_STAGES >= 6) */
const rt_integrator rt_transition = {.name = "transition", .order = 2, .stages = 1,
                                     .implicit = 1, .linear = 1, .step = transition_step,
                                     .bound = transition_bound};
