/* fmi2cs.c - a scene as an FMI 2.0 Co-Simulation FMU (docs/fmi.md, "Export"): the common and
 * Co-Simulation functions of FMI 2.0 over one compiled scene (FMU_CS_SCENE, named by
 * fmu_cs_id.h) and one co-simulation slave per instance (cs_slave.c). Memory comes from the
 * master's allocateMemory / freeMemory only (canNotUseMemoryManagementFunctions is false).
 * Names: FMI2_FUNCTION_PREFIX (fmu_cs_id.h: the model identifier and "_") prefixes every
 * function, as the standard asks of a source FMU, unless FMI2_OVERRIDE_FUNCTION_PREFIX is
 * defined (the shared object: plain fmi2DoStep ...). Functions the FMU does not support
 * return fmi2Error with a logged reason. */
#include <stdio.h>
#include <string.h>

#include "cs_slave.h"
#include "fmi_api.h"
#include "fmu_cs_id.h"

#define EXPORT __attribute__((visibility("default")))
#define FMI2_PASTE(a, b) a##b
#define FMI2_CAT(a, b) FMI2_PASTE(a, b)
#ifdef FMI2_OVERRIDE_FUNCTION_PREFIX
#define FMI2_NAME(f) f
#else
#define FMI2_NAME(f) FMI2_CAT(FMI2_FUNCTION_PREFIX, f)
#endif

extern const rt_scene FMU_CS_SCENE;

typedef struct cs_inst {
    cs_slave *s;
    fmi2CallbackFunctions cb; /* copied: the master's struct need not outlive the call */
    char name[64];            /* instanceName, for the logger */
    double start, stop;       /* from fmi2SetupExperiment */
    int stop_defined;
} cs_inst;

/* the logger's message is a printf format in which '#' starts a variable reference: a
   reason is passed with both escaped */
static void say(const cs_inst *in, fmi2Status st, const char *msg)
{
    char esc[2 * CS_MSG];
    size_t n = 0;
    for (const char *p = msg; *p && n + 3 < sizeof esc; p++) {
        if (*p == '%' || *p == '#')
            esc[n++] = *p;
        esc[n++] = *p;
    }
    esc[n] = 0;
    if (in && in->cb.logger)
        in->cb.logger(in->cb.componentEnvironment, in->name, st,
                      st >= fmi2Error ? "logStatusError" : "logStatusWarning", esc);
}

static fmi2Status done(const cs_inst *in, int st)
{
    if (st != CS_OK)
        say(in, (fmi2Status)st, in->s->msg);
    return (fmi2Status)st;
}

static fmi2Status refuse(const cs_inst *in, const char *what)
{
    char msg[CS_MSG];
    snprintf(msg, sizeof msg, "%s: not supported by a modrt Co-Simulation FMU", what);
    say(in, fmi2Error, msg);
    return fmi2Error;
}

/* ------------------------------------------------------------------ life */

EXPORT const char *FMI2_NAME(fmi2GetTypesPlatform)(void) { return "default"; }
EXPORT const char *FMI2_NAME(fmi2GetVersion)(void) { return "2.0"; }

EXPORT fmi2Status FMI2_NAME(fmi2SetDebugLogging)(fmi2Component c, fmi2Boolean loggingOn,
                                                 size_t nCategories,
                                                 const fmi2String categories[])
{
    (void)c, (void)loggingOn, (void)nCategories, (void)categories;
    return fmi2OK;
}

EXPORT fmi2Component FMI2_NAME(fmi2Instantiate)(fmi2String instanceName, fmi2Type fmuType,
                                                fmi2String fmuGUID,
                                                fmi2String fmuResourceLocation,
                                                const fmi2CallbackFunctions *functions,
                                                fmi2Boolean visible, fmi2Boolean loggingOn)
{
    (void)fmuResourceLocation, (void)visible, (void)loggingOn;
    cs_inst tmp = {0};
    char msg[CS_MSG];
    if (functions)
        tmp.cb = *functions;
    snprintf(tmp.name, sizeof tmp.name, "%s", instanceName ? instanceName : "");
    if (!fmuGUID || strcmp(fmuGUID, FMU_CS_TOKEN) != 0) {
        snprintf(msg, sizeof msg, "GUID %s is not this FMU's", fmuGUID ? fmuGUID : "(null)");
        say(&tmp, fmi2Error, msg);
        return NULL;
    }
    if (fmuType != fmi2CoSimulation) {
        say(&tmp, fmi2Error, "the FMU has no Model Exchange interface, only Co-Simulation");
        return NULL;
    }
    if (!tmp.cb.allocateMemory || !tmp.cb.freeMemory) {
        say(&tmp, fmi2Error, "allocateMemory and freeMemory are needed "
            "(canNotUseMemoryManagementFunctions is false)");
        return NULL;
    }
    const char *busy = cs_claim();
    if (busy) {
        say(&tmp, fmi2Error, busy);
        return NULL;
    }
    cs_inst *in = tmp.cb.allocateMemory(1, sizeof *in);
    cs_slave *s = tmp.cb.allocateMemory(1, cs_size(&FMU_CS_SCENE));
    if (!in || !s) {
        say(&tmp, fmi2Error, "allocateMemory returned NULL");
        tmp.cb.freeMemory(in), tmp.cb.freeMemory(s), cs_release();
        return NULL;
    }
    *in = tmp, in->s = s;
    if (done(in, cs_setup(s, &FMU_CS_SCENE)) != fmi2OK) {
        tmp.cb.freeMemory(in), tmp.cb.freeMemory(s), cs_release();
        return NULL;
    }
    return in;
}

EXPORT void FMI2_NAME(fmi2FreeInstance)(fmi2Component c)
{
    cs_inst *in = c;
    if (in) {
        void (*release)(void *) = in->cb.freeMemory;
        release(in->s), release(in), cs_release();
    }
}

EXPORT fmi2Status FMI2_NAME(fmi2SetupExperiment)(fmi2Component c, fmi2Boolean toleranceDefined,
                                                 fmi2Real tolerance, fmi2Real startTime,
                                                 fmi2Boolean stopTimeDefined, fmi2Real stopTime)
{
    cs_inst *in = c;
    (void)toleranceDefined, (void)tolerance;
    if (in->s->mode != CS_INSTANTIATED)
        return refuse(in, "fmi2SetupExperiment outside the instantiated state");
    in->start = startTime, in->stop = stopTime, in->stop_defined = stopTimeDefined != 0;
    return fmi2OK;
}

EXPORT fmi2Status FMI2_NAME(fmi2EnterInitializationMode)(fmi2Component c)
{
    cs_inst *in = c;
    return done(in, cs_enter_init(in->s, in->start, in->stop_defined, in->stop));
}

EXPORT fmi2Status FMI2_NAME(fmi2ExitInitializationMode)(fmi2Component c)
{
    cs_inst *in = c;
    return done(in, cs_exit_init(in->s));
}

EXPORT fmi2Status FMI2_NAME(fmi2Terminate)(fmi2Component c)
{
    ((cs_inst *)c)->s->mode = CS_TERMINATED;
    return fmi2OK;
}

EXPORT fmi2Status FMI2_NAME(fmi2Reset)(fmi2Component c)
{
    cs_inst *in = c;
    in->start = 0, in->stop_defined = 0;
    return done(in, cs_setup(in->s, in->s->sc));
}

/* ------------------------------------------------------------------ values */

EXPORT fmi2Status FMI2_NAME(fmi2GetReal)(fmi2Component c, const fmi2ValueReference vr[],
                                         size_t nvr, fmi2Real value[])
{
    cs_inst *in = c;
    int st = CS_OK;
    for (size_t i = 0; i < nvr && st == CS_OK; i++)
        st = cs_get(in->s, vr[i], &value[i]);
    return done(in, st);
}

EXPORT fmi2Status FMI2_NAME(fmi2SetReal)(fmi2Component c, const fmi2ValueReference vr[],
                                         size_t nvr, const fmi2Real value[])
{
    cs_inst *in = c;
    int st = CS_OK;
    for (size_t i = 0; i < nvr && st == CS_OK; i++)
        st = cs_set(in->s, vr[i], value[i]);
    return done(in, st);
}

/* the FMU has Real variables only: an empty request is served, any other refused */
static fmi2Status none_of(const cs_inst *in, const char *fn, const fmi2ValueReference vr[],
                          size_t nvr)
{
    char msg[CS_MSG];
    if (nvr == 0)
        return fmi2OK;
    snprintf(msg, sizeof msg, "%s: value reference %u: the FMU has Real variables only", fn,
             (unsigned)vr[0]);
    say(in, fmi2Error, msg);
    return fmi2Error;
}

EXPORT fmi2Status FMI2_NAME(fmi2GetInteger)(fmi2Component c, const fmi2ValueReference vr[],
                                            size_t nvr, fmi2Integer value[])
{
    (void)value;
    return none_of(c, "fmi2GetInteger", vr, nvr);
}

EXPORT fmi2Status FMI2_NAME(fmi2SetInteger)(fmi2Component c, const fmi2ValueReference vr[],
                                            size_t nvr, const fmi2Integer value[])
{
    (void)value;
    return none_of(c, "fmi2SetInteger", vr, nvr);
}

EXPORT fmi2Status FMI2_NAME(fmi2GetBoolean)(fmi2Component c, const fmi2ValueReference vr[],
                                            size_t nvr, fmi2Boolean value[])
{
    (void)value;
    return none_of(c, "fmi2GetBoolean", vr, nvr);
}

EXPORT fmi2Status FMI2_NAME(fmi2SetBoolean)(fmi2Component c, const fmi2ValueReference vr[],
                                            size_t nvr, const fmi2Boolean value[])
{
    (void)value;
    return none_of(c, "fmi2SetBoolean", vr, nvr);
}

EXPORT fmi2Status FMI2_NAME(fmi2GetString)(fmi2Component c, const fmi2ValueReference vr[],
                                           size_t nvr, fmi2String value[])
{
    (void)value;
    return none_of(c, "fmi2GetString", vr, nvr);
}

EXPORT fmi2Status FMI2_NAME(fmi2SetString)(fmi2Component c, const fmi2ValueReference vr[],
                                           size_t nvr, const fmi2String value[])
{
    (void)value;
    return none_of(c, "fmi2SetString", vr, nvr);
}

/* ------------------------------------------------------------------ stepping */

EXPORT fmi2Status FMI2_NAME(fmi2DoStep)(fmi2Component c, fmi2Real currentCommunicationPoint,
                                        fmi2Real communicationStepSize,
                                        fmi2Boolean noSetFMUStatePriorToCurrentPoint)
{
    cs_inst *in = c;
    int at_end = 0;
    (void)noSetFMUStatePriorToCurrentPoint;
    fmi2Status st = done(in, cs_step(in->s, currentCommunicationPoint, communicationStepSize,
                                     &at_end));
    if (in->cb.stepFinished) /* synchronous: the step is finished when DoStep returns */
        in->cb.stepFinished(in->cb.componentEnvironment, st);
    return st;
}

EXPORT fmi2Status FMI2_NAME(fmi2CancelStep)(fmi2Component c)
{
    return refuse(c, "fmi2CancelStep (fmi2DoStep is synchronous, never pending)");
}

EXPORT fmi2Status FMI2_NAME(fmi2GetStatus)(fmi2Component c, const fmi2StatusKind s,
                                           fmi2Status *value)
{
    (void)c, (void)s, (void)value;
    return fmi2Discard; /* only for a pending fmi2DoStep, which never is */
}

EXPORT fmi2Status FMI2_NAME(fmi2GetRealStatus)(fmi2Component c, const fmi2StatusKind s,
                                               fmi2Real *value)
{
    cs_inst *in = c;
    if (s != fmi2LastSuccessfulTime)
        return fmi2Discard;
    *value = (double)rt_time(in->s->sc, &in->s->sim);
    return fmi2OK;
}

EXPORT fmi2Status FMI2_NAME(fmi2GetIntegerStatus)(fmi2Component c, const fmi2StatusKind s,
                                                  fmi2Integer *value)
{
    (void)c, (void)s, (void)value;
    return fmi2Discard;
}

EXPORT fmi2Status FMI2_NAME(fmi2GetBooleanStatus)(fmi2Component c, const fmi2StatusKind s,
                                                  fmi2Boolean *value)
{
    cs_inst *in = c;
    if (s != fmi2Terminated)
        return fmi2Discard;
    *value = rt_ticks_done(&in->s->sim) >= rt_tick_count(&in->s->sim); /* at the end time */
    return fmi2OK;
}

EXPORT fmi2Status FMI2_NAME(fmi2GetStringStatus)(fmi2Component c, const fmi2StatusKind s,
                                                 fmi2String *value)
{
    (void)c, (void)s, (void)value;
    return fmi2Discard;
}

EXPORT fmi2Status FMI2_NAME(fmi2SetRealInputDerivatives)(fmi2Component c,
                                                         const fmi2ValueReference vr[],
                                                         size_t nvr, const fmi2Integer order[],
                                                         const fmi2Real value[])
{
    (void)vr, (void)nvr, (void)order, (void)value;
    return refuse(c, "fmi2SetRealInputDerivatives (canInterpolateInputs is false)");
}

EXPORT fmi2Status FMI2_NAME(fmi2GetRealOutputDerivatives)(fmi2Component c,
                                                          const fmi2ValueReference vr[],
                                                          size_t nvr, const fmi2Integer order[],
                                                          fmi2Real value[])
{
    (void)vr, (void)nvr, (void)order, (void)value;
    return refuse(c, "fmi2GetRealOutputDerivatives (maxOutputDerivativeOrder is 0)");
}

EXPORT fmi2Status FMI2_NAME(fmi2GetDirectionalDerivative)(
    fmi2Component c, const fmi2ValueReference vUnknown_ref[], size_t nUnknown,
    const fmi2ValueReference vKnown_ref[], size_t nKnown, const fmi2Real dvKnown[],
    fmi2Real dvUnknown[])
{
    (void)vUnknown_ref, (void)nUnknown, (void)vKnown_ref, (void)nKnown, (void)dvKnown;
    (void)dvUnknown;
    return refuse(c, "fmi2GetDirectionalDerivative (providesDirectionalDerivative is false)");
}

/* ------------------------------------------------------------------ FMU state */

EXPORT fmi2Status FMI2_NAME(fmi2GetFMUstate)(fmi2Component c, fmi2FMUstate *FMUstate)
{
    cs_inst *in = c;
    void *s = *FMUstate ? *FMUstate : in->cb.allocateMemory(1, cs_state_size(in->s));
    if (!s)
        return refuse(in, "fmi2GetFMUstate: allocateMemory returned NULL");
    if (done(in, cs_state_save(in->s, s)) != fmi2OK) {
        if (!*FMUstate)
            in->cb.freeMemory(s);
        return fmi2Error;
    }
    *FMUstate = s;
    return fmi2OK;
}

EXPORT fmi2Status FMI2_NAME(fmi2SetFMUstate)(fmi2Component c, fmi2FMUstate FMUstate)
{
    cs_inst *in = c;
    return done(in, cs_state_load(in->s, FMUstate, cs_state_size(in->s)));
}

EXPORT fmi2Status FMI2_NAME(fmi2FreeFMUstate)(fmi2Component c, fmi2FMUstate *FMUstate)
{
    cs_inst *in = c;
    in->cb.freeMemory(*FMUstate);
    *FMUstate = NULL;
    return fmi2OK;
}

EXPORT fmi2Status FMI2_NAME(fmi2SerializedFMUstateSize)(fmi2Component c, fmi2FMUstate FMUstate,
                                                        size_t *size)
{
    (void)FMUstate;
    *size = cs_state_size(((cs_inst *)c)->s);
    return fmi2OK;
}

EXPORT fmi2Status FMI2_NAME(fmi2SerializeFMUstate)(fmi2Component c, fmi2FMUstate FMUstate,
                                                   fmi2Byte serializedState[], size_t size)
{
    cs_inst *in = c;
    if (size != cs_state_size(in->s))
        return refuse(in, "fmi2SerializeFMUstate with a buffer of the wrong size");
    memcpy(serializedState, FMUstate, size);
    return fmi2OK;
}

EXPORT fmi2Status FMI2_NAME(fmi2DeSerializeFMUstate)(fmi2Component c,
                                                     const fmi2Byte serializedState[],
                                                     size_t size, fmi2FMUstate *FMUstate)
{
    cs_inst *in = c;
    if (done(in, cs_state_check(in->s, serializedState, size)) != fmi2OK)
        return fmi2Error;
    void *s = in->cb.allocateMemory(1, size);
    if (!s)
        return refuse(in, "fmi2DeSerializeFMUstate: allocateMemory returned NULL");
    memcpy(s, serializedState, size);
    *FMUstate = s;
    return fmi2OK;
}
