/* fmu_inst.c - one FMU block: its kind and the instance its services drive.
 *
 * The runtime calls a kind's services as functions of (t, x, u, p); an FMU is a state
 * machine holding its time, states and inputs. Each service first brings the instance to
 * the arguments (sync: only what changed is set), then asks for outputs, derivatives or
 * event indicators. The event indicators are the kind's roots, located by the runtime
 * (rt/step.c); the handler it runs just past a crossing is FMI's event mode: enter it,
 * update the discrete states until the FMU needs no more (at most FMU_EVENT_ITER_MAX
 * times), take the states it re-initialized, go back to continuous time. The time event
 * (nextEventTime) is the kind's run-time instant (rt_kind.next_event with time_event):
 * the runtime ends a part of the step exactly there, so the FMU is never evaluated in
 * continuous time past it, and runs the same event mode at t_next (rt/tev.c). An FMU that
 * needs CompletedIntegratorStep gets it at the end of each part of its set's steps
 * (rt_kind.step_end); asked for an event there, it runs one there. Discrete inputs and
 * tunable parameters change in event mode only: continuous-time evaluations hold them, and
 * the runtime hands the new values over at each start and end of a step part
 * (rt_kind.instant), where an event mode takes them.
 *
 * A call that returns Discard, Error or Fatal, a NaN, an event iteration that does not end
 * or an FMU that asks to terminate is a fault: the service writes NaN, which the runtime
 * counts with the block (nan) and never integrates; the first fault's call, status, time
 * and logged message are kept for the summary. After Error or Fatal the instance is dead:
 * no further call reaches it (FMI allows none but freeing, and not even that after Fatal). */
#define _POSIX_C_SOURCE 200809L /* (built for the host, and with FMU_TARGET for an image:
                                   the scene's C then defines the instances, fmu_emit.c) */
#ifndef FMU_TARGET
#include <dlfcn.h>
#endif
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fmu_int.h"

#ifndef FMU_TARGET
fmu_inst *fmu_instances[FMU_MAX_INSTANCES];
int fmu_ninstances;
#else /* an image has no fmu_md.c (no expat) */
#define fmu_md_variability_name(v) ((v) == FMU_V_FIXED ? "fixed" : "constant")
#endif

/* a root value exactly 0 belongs to FMI's z <= 0 side: the runtime counts a crossing only
   from a strictly signed value, so 0 is shown just below it */
#ifdef RT_REAL_FLOAT
#define FMU_ZERO_SIDE ((real_t)1e-37f)
#else
#define FMU_ZERO_SIDE ((real_t)1e-300)
#endif

static const char *const status_names[] = {"OK", "Warning", "Discard", "Error", "Fatal", "Pending"};

/* ------------------------------------------------------------------ faults */

static void fault(fmu_inst *in, double t, const char *fmt, ...)
{
    in->faults++;
    if (in->faults > 1)
        return;
    in->fault_t = t;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(in->fault, sizeof in->fault, fmt, ap);
    va_end(ap);
}

/* the status of call `what`: 0 to go on (OK, Warning), -1 after a fault */
static int check(fmu_inst *in, int s, const char *what, double t)
{
    if (s == 0)
        return 0;
    if (s == 1) {
        in->warnings++;
        return 0;
    }
    int st = s >= 0 && s <= 5 ? s : 4;
    fault(in, t, "%s%s returned %s%s%s%s", in->m->ops->prefix, what, in->m->ops->prefix,
          status_names[st], in->log[0] ? ": " : "", in->log);
    if (s >= 3)
        in->mode = FMU_M_DEAD;
    in->fatal |= s == 4;
    return -1;
}

#define CALL(in, t, name, expr) ((in)->log[0] = 0, check((in), (expr), (name), (t)))

int fmu_status(fmu_inst *in, int s, const char *what, double t) { return check(in, s, what, t); }

static int all_finite(const double *v, size_t n)
{
    for (size_t i = 0; i < n; i++)
        if (!isfinite(v[i]))
            return 0;
    return 1;
}

static void nan_fill(real_t *v, size_t n)
{
    for (size_t i = 0; i < n; i++)
        v[i] = (real_t)NAN;
}

/* ------------------------------------------------------------------ events */

/* the discrete-state updates of one event, from event mode (or initialization's end) to
   continuous time; writes re-initialized states into x (n == nx) when given */
static int iterate(fmu_inst *in, double t, real_t *x)
{
    const fmu_ops *o = in->m->ops;
    fmu_update u = {0};
    int x_changed = 0;
    uint32_t k = 0;
    for (;;) {
        if (CALL(in, t, "UpdateDiscreteStates", o->update(in, &u)))
            return -1;
        x_changed |= u.x_changed;
        if (u.terminate) {
            fault(in, t, "the FMU asked to terminate the simulation at t = %.17g%s%s", t,
                  in->log[0] ? ": " : "", in->log);
            in->mode = FMU_M_DEAD;
            return -1;
        }
        if (!u.again)
            break;
        if (++k >= FMU_EVENT_ITER_MAX) {
            fault(in, t, "event iteration at t = %.17g did not converge in %d discrete-state "
                  "updates (FMU_EVENT_ITER_MAX)", t, FMU_EVENT_ITER_MAX);
            in->mode = FMU_M_DEAD;
            return -1;
        }
    }
    in->iter_max = k + 1 > in->iter_max ? k + 1 : in->iter_max;
    if (u.has_next && !(u.next > t)) { /* it would never cross: a lost event */
        fault(in, t, "nextEventTime %.17g is not after the current time %.17g", u.next, t);
        in->mode = FMU_M_DEAD;
        return -1;
    }
    in->has_next = (uint8_t)u.has_next, in->t_next = u.next;
    if (CALL(in, t, "EnterContinuousTimeMode", o->enter_ct(in)))
        return -1;
    in->mode = FMU_M_CT;
    if (x_changed && in->m->nx) {
        if (CALL(in, t, "GetContinuousStates", o->get_x(in, in->x, in->m->nx)))
            return -1;
        if (!all_finite(in->x, in->m->nx)) {
            fault(in, t, "%sGetContinuousStates gave a non-finite state at t = %.17g",
                  o->prefix, t);
            return -1;
        }
        in->x_valid = 1;
        for (uint32_t i = 0; x && i < in->m->nx; i++)
            x[i] = (real_t)in->x[i];
    }
    return 0;
}

/* values changed in event mode (tunable parameters, discrete inputs), then the iteration */
static int set_in_event(fmu_inst *in, double t, const uint32_t *vr, size_t n, const double *v)
{
    const fmu_ops *o = in->m->ops;
    if (CALL(in, t, "EnterEventMode", o->enter_event(in)))
        return -1;
    in->mode = FMU_M_EVENT, in->fresh = 0;
    if (CALL(in, t, o == &fmu_ops2 ? "SetReal" : "SetFloat64", o->set(in, vr, n, v)))
        return -1;
    return iterate(in, t, NULL);
}

/* ------------------------------------------------------------------ bringing it to (t, x, u, p) */

/* FMI lets discrete inputs and tunable parameters change in event mode only: an evaluation
   in continuous time (an output, a derivative, the event indicators) holds the values the
   FMU took at its last instant, and the runtime hands the new ones over at the instants
   of the block's set (fmu_instant: the start and end of each step part and the tick its
   state reaches, rt/tev.c), where the FMU takes them in event mode. The first evaluation
   takes every input (at the start, t = 0). */

static int start(fmu_inst *in, const real_t *p, real_t *x0, const uint8_t *given);

/* a parameter of p that differs from the FMU's and is not tunable: a fault (before the
   run, fmu_check started the instance again with it) */
static int params_fixed(fmu_inst *in, const real_t *p, double t)
{
    const fmu_model *m = in->m;
    for (uint32_t i = 0; i < m->np; i++) {
        const fmu_var *v = &m->md.v[m->ip[i]];
        if (in->p[i] == (double)p[i] || v->variability == FMU_V_TUNABLE)
            continue;
        fault(in, t, "parameter %s is %s: it cannot change after the start (t = %.17g)",
              v->name, fmu_md_variability_name(v->variability), t);
        in->mode = FMU_M_DEAD;
        return -1;
    }
    return 0;
}

/* the first values of the inputs: all of them, the discrete ones in event mode */
static int inputs_first(fmu_inst *in, const rt_args *a, double t)
{
    const fmu_model *m = in->m;
    int du = !in->u_valid, disc = 0;
    for (uint32_t i = 0; i < m->nu; i++) {
        du |= in->u[i] != (double)a->u[i];
        disc |= in->u[i] != (double)a->u[i] && m->u_disc[i];
        in->u[i] = (double)a->u[i];
    }
    in->u_valid = 1;
    if (!du)
        return 0;
    if (disc)
        return set_in_event(in, t, m->vu, m->nu, in->u);
    return CALL(in, t, m->ops == &fmu_ops2 ? "SetReal" : "SetFloat64",
                m->ops->set(in, m->vu, m->nu, in->u));
}

/* is the instance in a run past its start (t > 0) */
static int running(const fmu_inst *in) { return in->mode == FMU_M_CT && in->t_valid && in->t > 0; }

/* an evaluation at t = 0 of an instance past its start: a new run (rt_init after one,
   fmu_check) starts it afresh with the parameters a gives */
static int restart_if_new(fmu_inst *in, const rt_args *a)
{
    if (!(a->t == 0 && running(in)))
        return 0;
    if (CALL(in, 0, "Reset", in->m->ops->reset(in)))
        return -1;
    in->mode = FMU_M_NONE;
    return start(in, a->p, NULL, NULL);
}

static int sync(fmu_inst *in, const rt_args *a)
{
    const fmu_model *m = in->m;
    const fmu_ops *o = m->ops;
    double t = (double)a->t;
    if (restart_if_new(in, a) || in->mode != FMU_M_CT)
        return -1;
    if (m->np && params_fixed(in, a->p, t))
        return -1;
    if (!in->t_valid || in->t != t) {
        if (CALL(in, t, "SetTime", o->set_time(in, t)))
            return -1;
        in->t = t, in->t_valid = 1;
    }
    int dx = !in->x_valid;
    for (uint32_t i = 0; i < m->nx; i++)
        dx |= in->x[i] != (double)a->x[i];
    if (m->nx && dx) {
        for (uint32_t i = 0; i < m->nx; i++)
            in->x[i] = (double)a->x[i];
        if (CALL(in, t, "SetContinuousStates", o->set_x(in, in->x, m->nx)))
            return -1;
        in->x_valid = 1;
    }
    if (!m->nu)
        return 0;
    if (!in->u_valid)
        return inputs_first(in, a, t);
    /* continuous time: the continuous inputs that changed; a discrete one is held */
    for (uint32_t i = 0; i < m->nu; i++) {
        if (m->u_disc[i] || in->u[i] == (double)a->u[i])
            continue;
        in->u[i] = (double)a->u[i];
        if (CALL(in, t, o == &fmu_ops2 ? "SetReal" : "SetFloat64",
                 o->set(in, &m->vu[i], 1, &in->u[i])))
            return -1;
    }
    return 0;
}

/* do a's discrete inputs or parameters differ from what the FMU holds */
static int pending(const fmu_inst *in, const rt_args *a)
{
    const fmu_model *m = in->m;
    int d = 0;
    for (uint32_t i = 0; i < m->nu; i++)
        d |= m->u_disc[i] && in->u[i] != (double)a->u[i];
    for (uint32_t i = 0; i < m->np; i++)
        d |= in->p[i] != (double)a->p[i];
    return d;
}

/* in event mode: each discrete input and parameter of a that differs from the FMU's (a
   parameter that may not change was refused by sync) */
static int set_pending(fmu_inst *in, const rt_args *a, double t)
{
    const fmu_model *m = in->m;
    const char *set = m->ops == &fmu_ops2 ? "SetReal" : "SetFloat64";
    for (uint32_t i = 0; i < m->nu; i++) {
        if (!m->u_disc[i] || in->u[i] == (double)a->u[i])
            continue;
        in->u[i] = (double)a->u[i];
        if (CALL(in, t, set, m->ops->set(in, &m->vu[i], 1, &in->u[i])))
            return -1;
    }
    for (uint32_t i = 0; i < m->np; i++) {
        if (in->p[i] == (double)a->p[i])
            continue;
        in->p[i] = (double)a->p[i];
        if (CALL(in, t, set, m->ops->set(in, &m->vp[i], 1, &in->p[i])))
            return -1;
    }
    return 0;
}

/* ------------------------------------------------------------------ the kind's services */

void fmu_output(const rt_args *a, real_t *y)
{
    fmu_inst *in = (fmu_inst *)a->spec;
    const fmu_model *m = in->m;
    if (sync(in, a) || CALL(in, (double)a->t, m->ops == &fmu_ops2 ? "GetReal" : "GetFloat64",
                            m->ops->get(in, m->vy, m->ny, in->buf))) {
        nan_fill(y, m->ny);
        return;
    }
    if (!all_finite(in->buf, m->ny) && in->faults == 0)
        fault(in, (double)a->t, "%s gave a non-finite output at t = %.17g",
              m->ops == &fmu_ops2 ? "fmi2GetReal" : "fmi3GetFloat64", (double)a->t);
    for (uint32_t i = 0; i < m->ny; i++)
        y[i] = (real_t)in->buf[i];
}

void fmu_deriv(const rt_args *a, real_t *xdot)
{
    fmu_inst *in = (fmu_inst *)a->spec;
    const fmu_model *m = in->m;
    double t = (double)a->t;
    if (sync(in, a) || CALL(in, t, m->ops == &fmu_ops2 ? "GetDerivatives"
                                                        : "GetContinuousStateDerivatives",
                            m->ops->get_dx(in, in->buf, m->nx))) {
        nan_fill(xdot, m->nx);
        return;
    }
    if (!all_finite(in->buf, m->nx) && in->faults == 0)
        fault(in, t, "%s gave a non-finite derivative at t = %.17g",
              m->ops == &fmu_ops2 ? "fmi2GetDerivatives" : "fmi3GetContinuousStateDerivatives", t);
    for (uint32_t i = 0; i < m->nx; i++)
        xdot[i] = (real_t)in->buf[i];
}

/* the event indicators */
void fmu_roots(const rt_args *a, real_t *r)
{
    fmu_inst *in = (fmu_inst *)a->spec;
    const fmu_model *m = in->m;
    if (m->nz && (sync(in, a) || CALL(in, (double)a->t, "GetEventIndicators",
                                      m->ops->get_z(in, in->buf, m->nz)))) {
        nan_fill(r, m->nz);
        return;
    }
    for (uint32_t i = 0; i < m->nz; i++) {
        real_t z = (real_t)in->buf[i];
        r[i] = z == 0 ? -FMU_ZERO_SIDE : z;
    }
}

/* FMI's event mode at a->t with the states x (re-initialized ones written back) */
static void event_mode(fmu_inst *in, const rt_args *a, real_t *x)
{
    const fmu_model *m = in->m;
    double t = (double)a->t;
    rt_args b = *a;
    b.x = x;
    if (sync(in, &b) || CALL(in, t, "EnterEventMode", m->ops->enter_event(in))) {
        nan_fill(x, m->nx);
        return;
    }
    in->mode = FMU_M_EVENT, in->fresh = 0, in->events++;
    if (set_pending(in, &b, t) || iterate(in, t, x)) {
        nan_fill(x, m->nx);
        return;
    }
    in->ev_valid = 1, in->ev_t = t;
    for (uint32_t i = 0; i < m->nx; i++)
        in->ev_x[i] = (double)x[i];
}

/* a state event at the located time; roots crossing together share one event mode */
void fmu_event(const rt_args *a, uint16_t which, real_t *x, real_t *d)
{
    fmu_inst *in = (fmu_inst *)a->spec;
    const fmu_model *m = in->m;
    (void)which, (void)d;
    int same = in->ev_valid && in->ev_t == (double)a->t;
    for (uint32_t i = 0; same && i < m->nx; i++)
        same = in->ev_x[i] == (double)x[i];
    if (!same)
        event_mode(in, a, x);
}

/* the pending time event: nextEventTime as the last event mode left it */
real_t fmu_next_event(const rt_args *a)
{
    const fmu_inst *in = (const fmu_inst *)a->spec;
    return in->has_next && in->mode == FMU_M_CT ? (real_t)in->t_next : RT_TEV_NEVER;
}

/* the time event, at t_next exactly (rt/tev.c ends a part there) */
void fmu_time_event(const rt_args *a, real_t *x, real_t *d)
{
    (void)d;
    event_mode((fmu_inst *)a->spec, a, x);
}

/* CompletedIntegratorStep at the end of a part of the set's step: an event mode there if
   the FMU asks for one (returns 1); terminateSimulation is a fault as in event mode */
int fmu_step_end(const rt_args *a, real_t *x, real_t *d)
{
    fmu_inst *in = (fmu_inst *)a->spec;
    double t = (double)a->t;
    int enter = 0, term = 0;
    rt_args b = *a;
    (void)d;
    b.x = x;
    if (sync(in, &b) || CALL(in, t, "CompletedIntegratorStep", in->m->ops->completed(in, &enter, &term)))
        return 0; /* dead: its outputs are NaN from now on, counted by the runtime */
    in->steps_done++;
    if (term) {
        fault(in, t, "the FMU asked to terminate the simulation at t = %.17g (in "
              "CompletedIntegratorStep)%s%s", t, in->log[0] ? ": " : "", in->log);
        in->mode = FMU_M_DEAD;
        return 0;
    }
    if (!enter)
        return 0;
    event_mode(in, a, x);
    return 1;
}

/* an instant of the block's set (the start or the end of a step part, rt/tev.c): the
   discrete inputs and parameters that changed since the last one, in an event mode there
   (returns 1), which the FMU then holds through the part that follows */
int fmu_instant(const rt_args *a, real_t *x, real_t *d)
{
    fmu_inst *in = (fmu_inst *)a->spec;
    (void)d;
    if (in->mode != FMU_M_CT || !pending(in, a))
        return 0;
    event_mode(in, a, x);
    return 1;
}

/* ------------------------------------------------------------------ start */

/* instantiation to continuous time: parameters and given initial states set before
   initialization, the event iteration after it, the states it starts from read back */
static int start(fmu_inst *in, const real_t *p, real_t *x0, const uint8_t *given)
{
    fmu_model *m = in->m;
    const fmu_ops *o = m->ops;
    in->t_valid = in->x_valid = in->u_valid = 0;
    in->ev_valid = 0, in->has_next = 0;
    for (uint32_t i = 0; i < m->np; i++)
        in->p[i] = (double)p[i];
    if (m->np && CALL(in, 0, o == &fmu_ops2 ? "SetReal" : "SetFloat64",
                      o->set(in, m->vp, m->np, in->p)))
        return -1;
    for (uint32_t i = 0; given && i < m->nx; i++) /* the scene's, kept for a restart */
        in->x_given[i] = given[i], in->x_start[i] = (double)x0[i];
    for (uint32_t i = 0; i < m->nx; i++)
        if (in->x_given[i] && CALL(in, 0, o == &fmu_ops2 ? "SetReal" : "SetFloat64",
                                   o->set(in, &m->vx[i], 1, &in->x_start[i])))
            return -1;
    if (CALL(in, 0, "EnterInitializationMode", o->enter_init(in, 0)) ||
        CALL(in, 0, "ExitInitializationMode", o->exit_init(in)))
        return -1;
    in->mode = FMU_M_EVENT;
    if (iterate(in, 0, NULL))
        return -1;
    if (m->nx && CALL(in, 0, "GetContinuousStates", o->get_x(in, in->x, m->nx)))
        return -1;
    for (uint32_t i = 0; x0 && i < m->nx; i++)
        x0[i] = (real_t)in->x[i];
    in->x_valid = 0; /* set again at the first evaluation */
    in->fresh = 1;
    return 0;
}

/* the runtime's init: a run starts from a fresh instance with these parameters. Also
   rt_set_param's check: a parameter written during a run is the instance's next instant's
   business (tunable: taken in event mode there; else a fault, params_fixed), and the
   instance goes on; a new run after one (rt_init, whose first evaluation is at t = 0)
   restarts it there (restart_if_new) */
rt_status fmu_check(const real_t *p, const void *spec)
{
    fmu_inst *in = (fmu_inst *)spec;
    const fmu_model *m = in->m;
    int same = in->fresh && in->mode == FMU_M_CT;
    for (uint32_t i = 0; same && i < m->np; i++)
        same = in->p[i] == (double)p[i];
    if (!same && in->c && running(in))
        return RT_OK;
#ifdef FMU_TARGET /* an image: the first rt_init instantiates, with the scene's values */
    if (!in->c)
        return m->ops->instantiate(in) || start(in, p, NULL, NULL) ? RT_E_PARAM : RT_OK;
#endif
    if (same || !in->c) /* (not yet instantiated: the scene compiler's own check) */
        return RT_OK;
    if (in->mode == FMU_M_DEAD)
        return RT_E_PARAM;
    if (CALL(in, 0, "Reset", m->ops->reset(in)))
        return RT_E_PARAM;
    in->mode = FMU_M_NONE;
    return start(in, p, NULL, NULL) ? RT_E_PARAM : RT_OK;
}

#ifndef FMU_TARGET /* the host's: instances made and started by the scene's loader */
int fmu_inst_start(fmu_inst *in, const real_t *p, real_t *x0, const uint8_t *given,
                   char *err, size_t errlen)
{
    fmu_model *m = in->m;
    if (m->md.once_per_process && m->ninst > 1) {
        snprintf(err, errlen, "%s: the FMU can be instantiated only once per process "
                 "(canBeInstantiatedOnlyOncePerProcess)", m->path);
        return -1;
    }
    if (!in->c && m->ops->instantiate(in) != 0) {
        snprintf(err, errlen, "%s: %sInstantiate%s failed for %s%s%s", m->path, m->ops->prefix,
                 m->ops == &fmu_ops2 ? "" : "ModelExchange", in->block,
                 in->log[0] ? ": " : "", in->log);
        return -1;
    }
    if (m->md.version == 3) { /* the binary's sizes against the description's */
        size_t nx = 0, nz = 0;
        if (m->f3.fmi3GetNumberOfContinuousStates(in->c, &nx) == fmi3OK &&
            m->f3.fmi3GetNumberOfEventIndicators(in->c, &nz) == fmi3OK &&
            (nx != m->nx || nz != m->nz)) {
            snprintf(err, errlen, "%s: modelDescription.xml declares %u states and %u event "
                     "indicators, the binary %zu and %zu", m->path, (unsigned)m->nx,
                     (unsigned)m->nz, nx, nz);
            return -1;
        }
    }
    if (in->mode != FMU_M_NONE) { /* started before (a second compilation) */
        if (CALL(in, 0, "Reset", m->ops->reset(in)) == 0)
            in->mode = FMU_M_NONE;
    }
    if (in->mode != FMU_M_NONE || start(in, p, x0, given)) {
        snprintf(err, errlen, "%s: %s", m->path, in->fault);
        return -1;
    }
    return 0;
}

/* ------------------------------------------------------------------ the kind */

/* at the process's end: every instance terminated and freed, as FMI's life cycle ends
   (an FMU may write its results there); none after Fatal, which allows no further call */
static void release_all(void)
{
    for (int i = 0; i < fmu_ninstances; i++) {
        fmu_inst *in = fmu_instances[i];
        if (!in->c || in->fatal)
            continue;
        if (in->mode == FMU_M_CT || in->mode == FMU_M_EVENT)
            in->m->ops->terminate(in);
        in->m->ops->free(in);
        in->c = NULL;
    }
}

fmu_inst *fmu_inst_new(fmu_model *m, const char *block, char *err, size_t errlen)
{
    if (fmu_ninstances >= FMU_MAX_INSTANCES) {
        snprintf(err, errlen, "more than %d FMU blocks (FMU_MAX_INSTANCES)", FMU_MAX_INSTANCES);
        return NULL;
    }
    fmu_inst *in = calloc(1, sizeof *in);
    size_t nb = m->nx > m->ny ? m->nx : m->ny;
    nb = nb > m->nz ? nb : m->nz;
    nb = nb > m->nu ? nb : m->nu;
    if (in) {
        in->m = m, in->block = strdup(block);
        in->x = calloc(m->nx + 1, sizeof *in->x), in->u = calloc(m->nu + 1, sizeof *in->u);
        in->p = calloc(m->np + 1, sizeof *in->p), in->buf = calloc(nb + 1, sizeof *in->buf);
        in->ev_x = calloc(m->nx + 1, sizeof *in->ev_x);
        in->x_start = calloc(m->nx + 1, sizeof *in->x_start);
        in->x_given = calloc(m->nx + 1, 1);
        in->root_dir = calloc(m->nz + 1, 1);
    }
    if (!in || !in->block || !in->x || !in->u || !in->p || !in->buf || !in->ev_x ||
        !in->root_dir || !in->x_start || !in->x_given) {
        snprintf(err, errlen, "out of memory");
        return NULL;
    }
    rt_kind *k = &in->kind;
    k->name = m->md.model_name;
    k->type = m->nx || m->nz ? RT_KIND_NSS : RT_KIND_OUTPUT;
    k->nu = (uint16_t)m->nu, k->ny = (uint16_t)m->ny, k->nx = (uint16_t)m->nx;
    k->np = (uint16_t)m->np, k->nr = (uint16_t)m->nz;
    k->u_names = m->u_names, k->y_names = m->y_names, k->x_names = m->x_names;
    k->p_names = m->p_names, k->p_default = m->p_def, k->x_default = m->x_def;
    k->feed = m->feed_class, k->feed_table = m->feed_class == RT_FEED_TABLE ? m->feed : NULL;
    k->root_dir = in->root_dir;
    k->check = fmu_check;
    k->output = m->ny ? fmu_output : NULL;
    k->deriv = k->type == RT_KIND_NSS ? fmu_deriv : NULL;
    k->roots = m->nz ? fmu_roots : NULL, k->event = m->nz ? fmu_event : NULL;
    k->next_event = fmu_next_event, k->time_event = fmu_time_event;
    k->step_end = m->md.needs_step_done ? fmu_step_end : NULL;
    k->instant = m->instants ? fmu_instant : NULL, k->u_discrete = m->u_disc;
    k->roots_every_sign = 1; /* FMI: every change of an indicator's domain is an event */
    k->save = fmu_save, k->restore = fmu_restore; /* (RT_E_SNAPSHOT unless it can) */
    k->spec = in;
    k->doc = m->md.model_name;
    k->units = m->units;
    if (m->nu + m->ny + m->nx + m->np > 4 * 65535u) {
        snprintf(err, errlen, "%s: too many variables for one block", m->path);
        return NULL;
    }
    m->ninst++;
    if (fmu_ninstances == 0)
        atexit(release_all);
    fmu_instances[fmu_ninstances++] = in;
    return in;
}

const rt_kind *fmu_inst_kind(const fmu_inst *in) { return &in->kind; }

long fmu_arena_need(void)
{
    size_t need = 0, a = FMU_ARENA_ALIGN;
    int any2 = 0;
    for (int i = 0; i < fmu_ninstances; i++) {
        fmu_model *m = fmu_instances[i]->m;
        any2 |= m->ops == &fmu_ops2;
        int first = 1; /* each FMI 3.0 binary once: its count covers all its instances */
        for (int j = 0; j < i; j++)
            first &= fmu_instances[j]->m != m;
        if (m->ops == &fmu_ops2 || !first)
            continue;
        size_t (*used)(void) = (size_t (*)(void))dlsym(m->so, "fmu_count_used");
        if (!used)
            return -1;
        need += (used() + a - 1) / a * a;
    }
    return (long)(need + (any2 ? (fmu_alloc2_used + a - 1) / a * a : 0));
}
#endif /* FMU_TARGET */
