/* fmi_glue.c - the FMI functions of the test FMUs, written from the specification (FMI 2.0
 * and 3.0 Model Exchange; FMI_VERSION selects which set this build exports) on top of one
 * model (fmi_model.h). Modes are checked as far as the tests need: a call in the wrong
 * state returns Error with a logged reason. Fault injection for the bad-FMU corpus
 * (tests/fmi/bad.sh): FMU_BAD_ERROR_AT=t (derivatives return Error from time t),
 * FMU_BAD_NAN_AT=t (NaN derivatives from t), FMU_BAD_LOOP (no event iteration after the start ends),
 * FMU_BAD_NO_INDICATORS (the event-indicator function is missing), FMU_BAD_NEXT_PAST (after
 * the first event, nextEventTime is the current time). A model with a variable MODEL_LATE
 * (model_gen.h) counts there every SetTime in continuous-time mode to a time past the
 * nextEventTime its last event announced: the importer evaluating it across a time
 * event, which FMI forbids. A model with a variable MODEL_WRONG counts there every new
 * value set in continuous-time mode of a discrete input or a tunable parameter
 * (model_event_only), which FMI lets change in event mode only. FMU_BAD_STEP_TERMINATE=t:
 * CompletedIntegratorStep asks to terminate the simulation from time t. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fmi_api.h"
#include "fmi_model.h"

#ifndef FMI_VERSION /* a 2.0 source FMU is built without definitions */
#define FMI_VERSION 2
#endif
#define EXPORT __attribute__((visibility("default")))
/* a source FMU linked statically: the importer defines FMI2_FUNCTION_PREFIX /
   FMI3_FUNCTION_PREFIX (the model identifier and "_") and every function carries it */
#define FMI_PASTE(a, b) a##b
#define FMI_CAT(a, b) FMI_PASTE(a, b)
#if defined(FMI2_FUNCTION_PREFIX) && !defined(FMI2_OVERRIDE_FUNCTION_PREFIX)
#define F2(f) FMI_CAT(FMI2_FUNCTION_PREFIX, f)
#else
#define F2(f) f
#endif
#if defined(FMI3_FUNCTION_PREFIX) && !defined(FMI3_OVERRIDE_FUNCTION_PREFIX)
#define F3(f) FMI_CAT(FMI3_FUNCTION_PREFIX, f)
#else
#define F3(f) f
#endif

/* the sizes as values (a model without states compares against 0 without a warning) */
static const size_t model_nx = MODEL_NX;
__attribute__((unused)) static const size_t model_nz = MODEL_NZ;

typedef enum { M_INSTANTIATED, M_INIT, M_EVENT, M_CT, M_TERMINATED } mode;

typedef struct inst {
    model_data d;
    mode mode;
    int has_next;               /* the last event's nextEventTime, for MODEL_LATE */
    double next;
    char *name;
#if FMI_VERSION == 2
    const fmi2CallbackFunctions *cb;
#else
    fmi3InstanceEnvironment env;
    fmi3LogMessageCallback log;
#endif
} inst;

static void say(inst *in, int status, const char *msg)
{
#if FMI_VERSION == 2
    if (in->cb && in->cb->logger)
        in->cb->logger(in->cb->componentEnvironment, in->name, (fmi2Status)status, "error",
                       "%s", msg);
#else
    if (in->log)
        in->log(in->env, (fmi3Status)status, "error", msg);
#endif
}

/* a call made in a mode that does not allow it */
static int wrong_mode(inst *in, const char *what)
{
    char buf[160];
    snprintf(buf, sizeof buf, "%s called in mode %d", what, (int)in->mode);
    say(in, 3, buf);
    return 3;
}

static void reset_values(inst *in)
{
    for (int i = 0; i < MODEL_NV; i++)
        in->d.v[i] = model_start[i];
    in->d.time = 0;
}

static int get_values(inst *in, const unsigned *vr, size_t n, double *v)
{
    model_outputs(&in->d);
    for (size_t i = 0; i < n; i++) {
        if (vr[i] >= MODEL_NV) {
            say(in, 3, "value reference out of range");
            return 3;
        }
        v[i] = in->d.v[vr[i]];
    }
    return 0;
}

static int set_values(inst *in, const unsigned *vr, size_t n, const double *v)
{
    for (size_t i = 0; i < n; i++) {
        if (vr[i] >= MODEL_NV) {
            say(in, 3, "value reference out of range");
            return 3;
        }
#ifdef MODEL_WRONG
        if (in->mode == M_CT && model_event_only[vr[i]] && in->d.v[vr[i]] != v[i])
            in->d.v[MODEL_WRONG] += 1;
#endif
        in->d.v[vr[i]] = v[i];
    }
    return 0;
}

static int derivatives(inst *in, double *dx, size_t n)
{
    if (in->mode != M_CT && in->mode != M_EVENT)
        return wrong_mode(in, "GetDerivatives");
#ifdef FMU_BAD_ERROR_AT
    if (in->d.time >= FMU_BAD_ERROR_AT) {
        say(in, 3, "injected failure of the derivative call");
        return 3;
    }
#endif
    model_derivatives(&in->d);
    for (size_t i = 0; i < n && i < model_nx; i++)
        dx[i] = in->d.v[model_der[i]];
#ifdef FMU_BAD_NAN_AT
    if (in->d.time >= FMU_BAD_NAN_AT)
        for (size_t i = 0; i < n; i++)
            dx[i] = NAN;
#endif
    return 0;
}

/* the time of continuous-time mode set (SetTime) */
static void set_time(inst *in, double t)
{
#ifdef MODEL_LATE
    if (in->mode == M_CT && in->has_next && t > in->next)
        in->d.v[MODEL_LATE] += 1;
#endif
    in->d.time = t;
}

static int update(inst *in, int *again, int *x_changed, int *has_next, double *next)
{
    *again = 0, *x_changed = 0, *has_next = 0, *next = 0;
    if (in->mode != M_EVENT)
        return wrong_mode(in, "UpdateDiscreteStates");
    *x_changed = 0, *has_next = 0, *next = 0;
    *again = model_event(&in->d, x_changed, has_next, next);
    in->has_next = *has_next, in->next = *next;
#ifdef FMU_BAD_LOOP
    *again = in->d.time > 0; /* every event after the start */
#endif
#ifdef FMU_BAD_NEXT_PAST
    if (in->d.time > 0)      /* from the first event on: the next one "now" */
        *has_next = 1, *next = in->d.time;
#endif
    return 0;
}

/* the FMU state (GetFMUstate ... DeSerializeFMUstate): the model's values and the mode,
   copied; serialized as those bytes (the state of this build, read back by it alone) */
typedef struct saved {
    model_data d;
    mode mode;
    int has_next;
    double next;
} saved;

static void save_to(const inst *in, saved *s)
{
    s->d = in->d, s->mode = in->mode, s->has_next = in->has_next, s->next = in->next;
}
static void load_from(inst *in, const saved *s)
{
    in->d = s->d, in->mode = s->mode, in->has_next = s->has_next, in->next = s->next;
}

/* CompletedIntegratorStep: the model's hook if it has one */
static int completed(inst *in, int *enter, int *term)
{
    *enter = 0, *term = 0;
    if (in->mode != M_CT)
        return wrong_mode(in, "CompletedIntegratorStep");
#ifdef MODEL_NEEDS_STEP
    *enter = model_completed_step(&in->d);
#endif
#ifdef FMU_BAD_STEP_TERMINATE
    *term = in->d.time >= FMU_BAD_STEP_TERMINATE;
#endif
    return 0;
}

/* ------------------------------------------------------------------ FMI 2.0 */
#if FMI_VERSION == 2

/* a state of its own: from the environment's memory, the one given reused */
static fmi2Status state_alloc2(inst *in, fmi2FMUstate *s)
{
    if (!*s)
        *s = in->cb->allocateMemory(1, sizeof(saved));
    if (!*s) {
        say(in, 3, "out of memory for an FMU state");
        return fmi2Error;
    }
    return fmi2OK;
}

EXPORT fmi2Status F2(fmi2GetFMUstate)(fmi2Component c, fmi2FMUstate *s)
{
    if (state_alloc2(c, s) != fmi2OK)
        return fmi2Error;
    save_to(c, *s);
    return fmi2OK;
}

EXPORT fmi2Status F2(fmi2SetFMUstate)(fmi2Component c, fmi2FMUstate s)
{
    if (!s)
        return (fmi2Status)wrong_mode(c, "SetFMUstate without a state");
    load_from(c, s);
    return fmi2OK;
}

EXPORT fmi2Status F2(fmi2FreeFMUstate)(fmi2Component c, fmi2FMUstate *s)
{
    if (s && *s)
        ((inst *)c)->cb->freeMemory(*s), *s = NULL;
    return fmi2OK;
}

EXPORT fmi2Status F2(fmi2SerializedFMUstateSize)(fmi2Component c, fmi2FMUstate s, size_t *n)
{
    (void)c, (void)s;
    *n = sizeof(saved);
    return fmi2OK;
}

EXPORT fmi2Status F2(fmi2SerializeFMUstate)(fmi2Component c, fmi2FMUstate s, fmi2Byte b[],
                                          size_t n)
{
    if (n != sizeof(saved)) {
        say(c, 3, "SerializeFMUstate: wrong size");
        return fmi2Error;
    }
    memcpy(b, s, n);
    return fmi2OK;
}

EXPORT fmi2Status F2(fmi2DeSerializeFMUstate)(fmi2Component c, const fmi2Byte b[], size_t n,
                                            fmi2FMUstate *s)
{
    if (n != sizeof(saved)) {
        say(c, 3, "DeSerializeFMUstate: wrong size");
        return fmi2Error;
    }
    if (state_alloc2(c, s) != fmi2OK)
        return fmi2Error;
    memcpy(*s, b, n);
    return fmi2OK;
}

EXPORT const char *F2(fmi2GetTypesPlatform)(void) { return "default"; }
EXPORT const char *F2(fmi2GetVersion)(void) { return "2.0"; }

EXPORT fmi2Component F2(fmi2Instantiate)(fmi2String name, fmi2Type type, fmi2String guid,
                                     fmi2String resources, const fmi2CallbackFunctions *cb,
                                     fmi2Boolean visible, fmi2Boolean logging)
{
    (void)resources, (void)visible, (void)logging;
    inst tmp = {.cb = cb, .name = (char *)name};
    if (type != fmi2ModelExchange || !guid || strcmp(guid, MODEL_TOKEN) != 0) {
        say(&tmp, 3, "wrong GUID or not Model Exchange");
        return NULL;
    }
    /* FMI 2.0: memory from the environment only */
    size_t n = strlen(name ? name : "") + 1;
    inst *in = cb && cb->allocateMemory ? cb->allocateMemory(1, sizeof *in) : NULL;
    char *nm = in ? cb->allocateMemory(n, 1) : NULL;
    if (!nm) {
        if (in)
            cb->freeMemory(in);
        return NULL;
    }
    memcpy(nm, name ? name : "", n);
    in->cb = cb, in->name = nm;
    reset_values(in);
    return in;
}

EXPORT void F2(fmi2FreeInstance)(fmi2Component c)
{
    inst *in = c;
    if (in) {
        in->cb->freeMemory(in->name);
        in->cb->freeMemory(in);
    }
}

EXPORT fmi2Status F2(fmi2SetupExperiment)(fmi2Component c, fmi2Boolean tolDefined, fmi2Real tol,
                                      fmi2Real start, fmi2Boolean stopDefined, fmi2Real stop)
{
    inst *in = c;
    (void)tolDefined, (void)tol, (void)stopDefined, (void)stop;
    in->d.time = start;
    return fmi2OK;
}

EXPORT fmi2Status F2(fmi2EnterInitializationMode)(fmi2Component c)
{
    inst *in = c;
    if (in->mode != M_INSTANTIATED)
        return (fmi2Status)wrong_mode(in, "EnterInitializationMode");
    in->mode = M_INIT;
    return fmi2OK;
}

EXPORT fmi2Status F2(fmi2ExitInitializationMode)(fmi2Component c)
{
    inst *in = c;
    if (in->mode != M_INIT)
        return (fmi2Status)wrong_mode(in, "ExitInitializationMode");
    in->mode = M_EVENT;
    return fmi2OK;
}

EXPORT fmi2Status F2(fmi2Terminate)(fmi2Component c)
{
    ((inst *)c)->mode = M_TERMINATED;
    return fmi2OK;
}

EXPORT fmi2Status F2(fmi2Reset)(fmi2Component c)
{
    inst *in = c;
    in->mode = M_INSTANTIATED;
    reset_values(in);
    return fmi2OK;
}

EXPORT fmi2Status F2(fmi2GetReal)(fmi2Component c, const fmi2ValueReference vr[], size_t n,
                              fmi2Real v[])
{
    return (fmi2Status)get_values(c, vr, n, v);
}

EXPORT fmi2Status F2(fmi2SetReal)(fmi2Component c, const fmi2ValueReference vr[], size_t n,
                              const fmi2Real v[])
{
    return (fmi2Status)set_values(c, vr, n, v);
}

EXPORT fmi2Status F2(fmi2EnterEventMode)(fmi2Component c)
{
    inst *in = c;
    if (in->mode != M_CT)
        return (fmi2Status)wrong_mode(in, "EnterEventMode");
    in->mode = M_EVENT;
    return fmi2OK;
}

EXPORT fmi2Status F2(fmi2NewDiscreteStates)(fmi2Component c, fmi2EventInfo *e)
{
    int again, xch, has;
    double next;
    int s = update(c, &again, &xch, &has, &next);
    e->newDiscreteStatesNeeded = again, e->terminateSimulation = 0;
    e->nominalsOfContinuousStatesChanged = 0, e->valuesOfContinuousStatesChanged = xch;
    e->nextEventTimeDefined = has, e->nextEventTime = next;
    return (fmi2Status)s;
}

EXPORT fmi2Status F2(fmi2EnterContinuousTimeMode)(fmi2Component c)
{
    inst *in = c;
    if (in->mode != M_EVENT)
        return (fmi2Status)wrong_mode(in, "EnterContinuousTimeMode");
    in->mode = M_CT;
    return fmi2OK;
}

EXPORT fmi2Status F2(fmi2CompletedIntegratorStep)(fmi2Component c, fmi2Boolean noSet,
                                              fmi2Boolean *enter, fmi2Boolean *term)
{
    int e, t, s = completed(c, &e, &t);
    (void)noSet;
    *enter = e, *term = t;
    return (fmi2Status)s;
}

EXPORT fmi2Status F2(fmi2SetTime)(fmi2Component c, fmi2Real t)
{
    set_time(c, t);
    return fmi2OK;
}

EXPORT fmi2Status F2(fmi2SetContinuousStates)(fmi2Component c, const fmi2Real x[], size_t n)
{
    inst *in = c;
    for (size_t i = 0; i < n && i < model_nx; i++)
        in->d.v[model_state[i]] = x[i];
    return fmi2OK;
}

EXPORT fmi2Status F2(fmi2GetContinuousStates)(fmi2Component c, fmi2Real x[], size_t n)
{
    inst *in = c;
    for (size_t i = 0; i < n && i < model_nx; i++)
        x[i] = in->d.v[model_state[i]];
    return fmi2OK;
}

EXPORT fmi2Status F2(fmi2GetDerivatives)(fmi2Component c, fmi2Real dx[], size_t n)
{
    return (fmi2Status)derivatives(c, dx, n);
}

#ifndef FMU_BAD_NO_INDICATORS
EXPORT fmi2Status F2(fmi2GetEventIndicators)(fmi2Component c, fmi2Real z[], size_t n)
{
    double zz[MODEL_NZ + 1];
    model_indicators(&((inst *)c)->d, zz);
    for (size_t i = 0; i < n && i < model_nz; i++)
        z[i] = zz[i];
    return fmi2OK;
}
#endif

#else
/* ------------------------------------------------------------------ FMI 3.0 */

EXPORT const char *F3(fmi3GetVersion)(void) { return "3.0"; }

EXPORT fmi3Instance F3(fmi3InstantiateModelExchange)(fmi3String name, fmi3String token,
                                                 fmi3String resources, fmi3Boolean visible,
                                                 fmi3Boolean logging,
                                                 fmi3InstanceEnvironment env,
                                                 fmi3LogMessageCallback log)
{
    (void)resources, (void)visible, (void)logging;
    inst tmp = {.env = env, .log = log};
    if (!token || strcmp(token, MODEL_TOKEN) != 0) {
        say(&tmp, 3, "wrong instantiationToken");
        return NULL;
    }
    /* FMI 3.0 has no memory callbacks: calloc (an image links it to its static arena) */
    size_t n = strlen(name ? name : "") + 1;
    inst *in = calloc(1, sizeof *in);
    char *nm = in ? calloc(n, 1) : NULL;
    if (!nm) {
        free(in);
        return NULL;
    }
    memcpy(nm, name ? name : "", n);
    in->env = env, in->log = log, in->name = nm;
    reset_values(in);
    return in;
}

EXPORT void F3(fmi3FreeInstance)(fmi3Instance c)
{
    inst *in = c;
    if (in)
        free(in->name);
    free(in);
}

EXPORT fmi3Status F3(fmi3EnterInitializationMode)(fmi3Instance c, fmi3Boolean tolDefined,
                                              fmi3Float64 tol, fmi3Float64 start,
                                              fmi3Boolean stopDefined, fmi3Float64 stop)
{
    inst *in = c;
    (void)tolDefined, (void)tol, (void)stopDefined, (void)stop;
    if (in->mode != M_INSTANTIATED)
        return (fmi3Status)wrong_mode(in, "EnterInitializationMode");
    in->d.time = start, in->mode = M_INIT;
    return fmi3OK;
}

EXPORT fmi3Status F3(fmi3ExitInitializationMode)(fmi3Instance c)
{
    inst *in = c;
    if (in->mode != M_INIT)
        return (fmi3Status)wrong_mode(in, "ExitInitializationMode");
    in->mode = M_EVENT;
    return fmi3OK;
}

EXPORT fmi3Status F3(fmi3EnterEventMode)(fmi3Instance c)
{
    inst *in = c;
    if (in->mode != M_CT)
        return (fmi3Status)wrong_mode(in, "EnterEventMode");
    in->mode = M_EVENT;
    return fmi3OK;
}

EXPORT fmi3Status F3(fmi3Terminate)(fmi3Instance c)
{
    ((inst *)c)->mode = M_TERMINATED;
    return fmi3OK;
}

EXPORT fmi3Status F3(fmi3Reset)(fmi3Instance c)
{
    inst *in = c;
    in->mode = M_INSTANTIATED;
    reset_values(in);
    return fmi3OK;
}

EXPORT fmi3Status F3(fmi3GetFloat64)(fmi3Instance c, const fmi3ValueReference vr[], size_t n,
                                 fmi3Float64 v[], size_t nv)
{
    (void)nv;
    return (fmi3Status)get_values(c, vr, n, v);
}

EXPORT fmi3Status F3(fmi3SetFloat64)(fmi3Instance c, const fmi3ValueReference vr[], size_t n,
                                 const fmi3Float64 v[], size_t nv)
{
    (void)nv;
    return (fmi3Status)set_values(c, vr, n, v);
}

EXPORT fmi3Status F3(fmi3UpdateDiscreteStates)(fmi3Instance c, fmi3Boolean *again,
                                           fmi3Boolean *term, fmi3Boolean *nominals,
                                           fmi3Boolean *xch, fmi3Boolean *has,
                                           fmi3Float64 *next)
{
    int a, x, h;
    double n;
    int s = update(c, &a, &x, &h, &n);
    *again = a, *term = 0, *nominals = 0, *xch = x, *has = h, *next = n;
    return (fmi3Status)s;
}

EXPORT fmi3Status F3(fmi3EnterContinuousTimeMode)(fmi3Instance c)
{
    inst *in = c;
    if (in->mode != M_EVENT)
        return (fmi3Status)wrong_mode(in, "EnterContinuousTimeMode");
    in->mode = M_CT;
    return fmi3OK;
}

EXPORT fmi3Status F3(fmi3CompletedIntegratorStep)(fmi3Instance c, fmi3Boolean noSet,
                                              fmi3Boolean *enter, fmi3Boolean *term)
{
    int e, t, s = completed(c, &e, &t);
    (void)noSet;
    *enter = e, *term = t;
    return (fmi3Status)s;
}

EXPORT fmi3Status F3(fmi3SetTime)(fmi3Instance c, fmi3Float64 t)
{
    set_time(c, t);
    return fmi3OK;
}

EXPORT fmi3Status F3(fmi3SetContinuousStates)(fmi3Instance c, const fmi3Float64 x[], size_t n)
{
    inst *in = c;
    for (size_t i = 0; i < n && i < model_nx; i++)
        in->d.v[model_state[i]] = x[i];
    return fmi3OK;
}

EXPORT fmi3Status F3(fmi3GetContinuousStates)(fmi3Instance c, fmi3Float64 x[], size_t n)
{
    inst *in = c;
    for (size_t i = 0; i < n && i < model_nx; i++)
        x[i] = in->d.v[model_state[i]];
    return fmi3OK;
}

EXPORT fmi3Status F3(fmi3GetContinuousStateDerivatives)(fmi3Instance c, fmi3Float64 dx[], size_t n)
{
    return (fmi3Status)derivatives(c, dx, n);
}

#ifndef FMU_BAD_NO_INDICATORS
EXPORT fmi3Status F3(fmi3GetEventIndicators)(fmi3Instance c, fmi3Float64 z[], size_t n)
{
    double zz[MODEL_NZ + 1];
    model_indicators(&((inst *)c)->d, zz);
    for (size_t i = 0; i < n && i < model_nz; i++)
        z[i] = zz[i];
    return fmi3OK;
}
#endif

/* a state of its own: calloc (an image's arena), the one given reused */
static fmi3Status state_alloc3(inst *in, fmi3FMUState *s)
{
    if (!*s)
        *s = calloc(1, sizeof(saved));
    if (!*s) {
        say(in, 3, "out of memory for an FMU state");
        return fmi3Error;
    }
    return fmi3OK;
}

EXPORT fmi3Status F3(fmi3GetFMUState)(fmi3Instance c, fmi3FMUState *s)
{
    if (state_alloc3(c, s) != fmi3OK)
        return fmi3Error;
    save_to(c, *s);
    return fmi3OK;
}

EXPORT fmi3Status F3(fmi3SetFMUState)(fmi3Instance c, fmi3FMUState s)
{
    if (!s)
        return (fmi3Status)wrong_mode(c, "SetFMUState without a state");
    load_from(c, s);
    return fmi3OK;
}

EXPORT fmi3Status F3(fmi3FreeFMUState)(fmi3Instance c, fmi3FMUState *s)
{
    (void)c;
    if (s && *s)
        free(*s), *s = NULL;
    return fmi3OK;
}

EXPORT fmi3Status F3(fmi3SerializedFMUStateSize)(fmi3Instance c, fmi3FMUState s, size_t *n)
{
    (void)c, (void)s;
    *n = sizeof(saved);
    return fmi3OK;
}

EXPORT fmi3Status F3(fmi3SerializeFMUState)(fmi3Instance c, fmi3FMUState s, fmi3Byte b[],
                                          size_t n)
{
    if (n != sizeof(saved)) {
        say(c, 3, "SerializeFMUState: wrong size");
        return fmi3Error;
    }
    memcpy(b, s, n);
    return fmi3OK;
}

EXPORT fmi3Status F3(fmi3DeserializeFMUState)(fmi3Instance c, const fmi3Byte b[], size_t n,
                                            fmi3FMUState *s)
{
    if (n != sizeof(saved)) {
        say(c, 3, "DeserializeFMUState: wrong size");
        return fmi3Error;
    }
    if (state_alloc3(c, s) != fmi3OK)
        return fmi3Error;
    memcpy(*s, b, n);
    return fmi3OK;
}

EXPORT fmi3Status F3(fmi3GetNumberOfEventIndicators)(fmi3Instance c, size_t *n)
{
    (void)c;
    *n = MODEL_NZ;
    return fmi3OK;
}

EXPORT fmi3Status F3(fmi3GetNumberOfContinuousStates)(fmi3Instance c, size_t *n)
{
    (void)c;
    *n = MODEL_NX;
    return fmi3OK;
}

#endif
