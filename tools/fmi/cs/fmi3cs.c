/* fmi3cs.c - a scene as an FMI 3.0 Co-Simulation FMU (docs/fmi.md, "Export"): the FMI 3.0
 * functions over one compiled scene (FMU_CS_SCENE, its generated C linked beside the
 * runtime; fmu_cs_id.h names it) and one co-simulation slave per instance (cs_slave.c,
 * which steps, serves the values and saves the state; this file binds it to FMI 3.0 and
 * logs its reasons). Functions of interfaces the FMU does not have return fmi3Error with a
 * logged reason, as the standard asks of an FMU that exports them all. Names, as the
 * standard's fmi3Functions.h has them: FMI3_FUNCTION_PREFIX (fmu_cs_id.h: the model
 * identifier and "_") prefixes every function, so several source FMUs link into one
 * program; with FMI3_OVERRIDE_FUNCTION_PREFIX defined (the shared object) the prefix is
 * FMI3_ACTUAL_FUNCTION_PREFIX if defined, else none (plain fmi3DoStep ...). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cs_slave.h"
#include "fmi_api.h"
#include "fmu_cs_id.h"

#define EXPORT __attribute__((visibility("default")))
#if !defined(FMI3_OVERRIDE_FUNCTION_PREFIX) && defined(FMI3_FUNCTION_PREFIX)
#define FMI3_ACTUAL_FUNCTION_PREFIX FMI3_FUNCTION_PREFIX
#endif
#define FMI3_PASTE(a, b) a##b
#define FMI3_CAT(a, b) FMI3_PASTE(a, b)
#ifdef FMI3_ACTUAL_FUNCTION_PREFIX
#define FMI3_NAME(f) FMI3_CAT(FMI3_ACTUAL_FUNCTION_PREFIX, f)
#else
#define FMI3_NAME(f) f
#endif

extern const rt_scene FMU_CS_SCENE;

typedef struct cs_inst {
    cs_slave *s;
    fmi3InstanceEnvironment env;
    fmi3LogMessageCallback log;
} cs_inst;

static void say(const cs_inst *in, fmi3Status st, const char *msg)
{
    if (in && in->log)
        in->log(in->env, st, st >= fmi3Error ? "logStatusError" : "logStatusWarning", msg);
}

/* a slave's status, its reason logged */
static fmi3Status done(const cs_inst *in, int st)
{
    if (st != CS_OK)
        say(in, (fmi3Status)st, in->s->msg);
    return (fmi3Status)st;
}

static fmi3Status refuse(const cs_inst *in, const char *what)
{
    char msg[CS_MSG];
    snprintf(msg, sizeof msg, "%s: not supported by a modrt Co-Simulation FMU", what);
    say(in, fmi3Error, msg);
    return fmi3Error;
}

/* ------------------------------------------------------------------ life */

EXPORT const char *FMI3_NAME(fmi3GetVersion)(void) { return "3.0"; }

EXPORT fmi3Status FMI3_NAME(fmi3SetDebugLogging)(fmi3Instance instance, fmi3Boolean loggingOn,
                                      size_t nCategories, const fmi3String categories[])
{
    (void)instance, (void)loggingOn, (void)nCategories, (void)categories;
    return fmi3OK;
}

EXPORT fmi3Instance FMI3_NAME(fmi3InstantiateCoSimulation)(
    fmi3String instanceName, fmi3String instantiationToken, fmi3String resourcePath,
    fmi3Boolean visible, fmi3Boolean loggingOn, fmi3Boolean eventModeUsed,
    fmi3Boolean earlyReturnAllowed, const fmi3ValueReference requiredIntermediateVariables[],
    size_t nRequiredIntermediateVariables, fmi3InstanceEnvironment instanceEnvironment,
    fmi3LogMessageCallback logMessage, fmi3IntermediateUpdateCallback intermediateUpdate)
{
    (void)instanceName, (void)resourcePath, (void)visible, (void)loggingOn;
    (void)earlyReturnAllowed, (void)requiredIntermediateVariables;
    (void)nRequiredIntermediateVariables, (void)intermediateUpdate;
    cs_inst tmp = {.env = instanceEnvironment, .log = logMessage};
    char msg[CS_MSG];
    if (!instantiationToken || strcmp(instantiationToken, FMU_CS_TOKEN) != 0) {
        snprintf(msg, sizeof msg, "instantiationToken %s is not this FMU's",
                 instantiationToken ? instantiationToken : "(null)");
        say(&tmp, fmi3Error, msg);
        return NULL;
    }
    if (eventModeUsed) {
        say(&tmp, fmi3Error, "event mode: the FMU has none (hasEventMode false)");
        return NULL;
    }
    const char *busy = cs_claim();
    if (busy) {
        say(&tmp, fmi3Error, busy);
        return NULL;
    }
    cs_inst *in = calloc(1, sizeof *in);
    cs_slave *s = calloc(1, cs_size(&FMU_CS_SCENE));
    if (!in || !s) {
        say(&tmp, fmi3Error, "out of memory");
        free(in), free(s), cs_release();
        return NULL;
    }
    *in = tmp, in->s = s;
    if (done(in, cs_setup(s, &FMU_CS_SCENE)) != fmi3OK) {
        free(in), free(s), cs_release();
        return NULL;
    }
    return in;
}

EXPORT void FMI3_NAME(fmi3FreeInstance)(fmi3Instance instance)
{
    cs_inst *in = instance;
    if (in)
        free(in->s), free(in), cs_release();
}

EXPORT fmi3Status FMI3_NAME(fmi3EnterInitializationMode)(fmi3Instance instance, fmi3Boolean toleranceDefined,
                                              fmi3Float64 tolerance, fmi3Float64 startTime,
                                              fmi3Boolean stopTimeDefined, fmi3Float64 stopTime)
{
    cs_inst *in = instance;
    (void)toleranceDefined, (void)tolerance;
    return done(in, cs_enter_init(in->s, startTime, stopTimeDefined, stopTime));
}

EXPORT fmi3Status FMI3_NAME(fmi3ExitInitializationMode)(fmi3Instance instance)
{
    cs_inst *in = instance;
    return done(in, cs_exit_init(in->s));
}

EXPORT fmi3Status FMI3_NAME(fmi3Terminate)(fmi3Instance instance)
{
    ((cs_inst *)instance)->s->mode = CS_TERMINATED;
    return fmi3OK;
}

EXPORT fmi3Status FMI3_NAME(fmi3Reset)(fmi3Instance instance)
{
    cs_inst *in = instance;
    return done(in, cs_setup(in->s, in->s->sc));
}

/* ------------------------------------------------------------------ values */

EXPORT fmi3Status FMI3_NAME(fmi3GetFloat64)(fmi3Instance instance, const fmi3ValueReference vr[],
                                 size_t nvr, fmi3Float64 values[], size_t nValues)
{
    cs_inst *in = instance;
    if (nvr != nValues)
        return refuse(in, "fmi3GetFloat64 with nValues other than nValueReferences");
    int st = CS_OK;
    for (size_t i = 0; i < nvr && st == CS_OK; i++)
        st = cs_get(in->s, vr[i], &values[i]);
    return done(in, st);
}

EXPORT fmi3Status FMI3_NAME(fmi3SetFloat64)(fmi3Instance instance, const fmi3ValueReference vr[],
                                 size_t nvr, const fmi3Float64 values[], size_t nValues)
{
    cs_inst *in = instance;
    if (nvr != nValues)
        return refuse(in, "fmi3SetFloat64 with nValues other than nValueReferences");
    int st = CS_OK;
    for (size_t i = 0; i < nvr && st == CS_OK; i++)
        st = cs_set(in->s, vr[i], values[i]);
    return done(in, st);
}

/* ------------------------------------------------------------------ stepping */

EXPORT fmi3Status FMI3_NAME(fmi3DoStep)(fmi3Instance instance, fmi3Float64 currentCommunicationPoint,
                             fmi3Float64 communicationStepSize,
                             fmi3Boolean noSetFMUStatePriorToCurrentPoint,
                             fmi3Boolean *eventHandlingNeeded, fmi3Boolean *terminateSimulation,
                             fmi3Boolean *earlyReturn, fmi3Float64 *lastSuccessfulTime)
{
    cs_inst *in = instance;
    (void)noSetFMUStatePriorToCurrentPoint;
    int at_end = 0;
    int st = cs_step(in->s, currentCommunicationPoint, communicationStepSize, &at_end);
    *eventHandlingNeeded = 0, *earlyReturn = 0;
    *terminateSimulation = st == CS_ERROR && at_end;
    *lastSuccessfulTime = (double)rt_time(in->s->sc, &in->s->sim);
    return done(in, st);
}

/* ------------------------------------------------------------------ FMU state */

EXPORT fmi3Status FMI3_NAME(fmi3GetFMUState)(fmi3Instance instance, fmi3FMUState *FMUState)
{
    cs_inst *in = instance;
    void *s = *FMUState ? *FMUState : calloc(1, cs_state_size(in->s));
    if (!s)
        return refuse(in, "fmi3GetFMUState: out of memory");
    if (done(in, cs_state_save(in->s, s)) != fmi3OK) {
        if (!*FMUState)
            free(s);
        return fmi3Error;
    }
    *FMUState = s;
    return fmi3OK;
}

EXPORT fmi3Status FMI3_NAME(fmi3SetFMUState)(fmi3Instance instance, fmi3FMUState FMUState)
{
    cs_inst *in = instance;
    return done(in, cs_state_load(in->s, FMUState, cs_state_size(in->s)));
}

EXPORT fmi3Status FMI3_NAME(fmi3FreeFMUState)(fmi3Instance instance, fmi3FMUState *FMUState)
{
    (void)instance;
    free(*FMUState);
    *FMUState = NULL;
    return fmi3OK;
}

EXPORT fmi3Status FMI3_NAME(fmi3SerializedFMUStateSize)(fmi3Instance instance, fmi3FMUState FMUState,
                                             size_t *size)
{
    (void)FMUState;
    *size = cs_state_size(((cs_inst *)instance)->s);
    return fmi3OK;
}

EXPORT fmi3Status FMI3_NAME(fmi3SerializeFMUState)(fmi3Instance instance, fmi3FMUState FMUState,
                                        fmi3Byte serializedState[], size_t size)
{
    cs_inst *in = instance;
    if (size != cs_state_size(in->s))
        return refuse(in, "fmi3SerializeFMUState with a buffer of the wrong size");
    memcpy(serializedState, FMUState, size);
    return fmi3OK;
}

EXPORT fmi3Status FMI3_NAME(fmi3DeserializeFMUState)(fmi3Instance instance, const fmi3Byte serializedState[],
                                          size_t size, fmi3FMUState *FMUState)
{
    cs_inst *in = instance;
    if (done(in, cs_state_check(in->s, serializedState, size)) != fmi3OK)
        return fmi3Error;
    void *s = malloc(size);
    if (!s)
        return refuse(in, "fmi3DeserializeFMUState: out of memory");
    memcpy(s, serializedState, size);
    *FMUState = s;
    return fmi3OK;
}

/* ------------------------------------------------------------------ what it does not have */

#pragma GCC diagnostic ignored "-Wunused-parameter"

EXPORT fmi3Instance FMI3_NAME(fmi3InstantiateModelExchange)(fmi3String n, fmi3String t, fmi3String r,
                                                 fmi3Boolean v, fmi3Boolean l,
                                                 fmi3InstanceEnvironment e,
                                                 fmi3LogMessageCallback log)
{
    if (log)
        log(e, fmi3Error, "logStatusError", "the FMU has no Model Exchange interface");
    return NULL;
}

EXPORT fmi3Instance FMI3_NAME(fmi3InstantiateScheduledExecution)(fmi3String n, fmi3String t, fmi3String r,
                                                      fmi3Boolean v, fmi3Boolean l,
                                                      fmi3InstanceEnvironment e,
                                                      fmi3LogMessageCallback log,
                                                      fmi3ClockUpdateCallback c,
                                                      fmi3LockPreemptionCallback lp,
                                                      fmi3UnlockPreemptionCallback up)
{
    if (log)
        log(e, fmi3Error, "logStatusError", "the FMU has no Scheduled Execution interface");
    return NULL;
}

#define VREFS const fmi3ValueReference vr[], size_t nvr
#define GETSET(T, name)                                                                   \
    EXPORT fmi3Status FMI3_NAME(fmi3Get##name)(fmi3Instance i, VREFS, T v[], size_t n)    \
    {                                                                                     \
        return refuse(i, "fmi3Get" #name ": the FMU has Float64 variables only");         \
    }                                                                                     \
    EXPORT fmi3Status FMI3_NAME(fmi3Set##name)(fmi3Instance i, VREFS, const T v[],        \
                                               size_t n)                                  \
    {                                                                                     \
        return refuse(i, "fmi3Set" #name ": the FMU has Float64 variables only");         \
    }
GETSET(fmi3Float32, Float32)
GETSET(fmi3Int8, Int8)
GETSET(fmi3UInt8, UInt8)
GETSET(fmi3Int16, Int16)
GETSET(fmi3UInt16, UInt16)
GETSET(fmi3Int32, Int32)
GETSET(fmi3UInt32, UInt32)
GETSET(fmi3Int64, Int64)
GETSET(fmi3UInt64, UInt64)
GETSET(fmi3Boolean, Boolean)
GETSET(fmi3String, String)
#undef GETSET

EXPORT fmi3Status FMI3_NAME(fmi3GetBinary)(fmi3Instance i, VREFS, size_t s[], fmi3Binary v[], size_t n)
{
    return refuse(i, "fmi3GetBinary");
}
EXPORT fmi3Status FMI3_NAME(fmi3SetBinary)(fmi3Instance i, VREFS, const size_t s[], const fmi3Binary v[],
                                size_t n)
{
    return refuse(i, "fmi3SetBinary");
}
EXPORT fmi3Status FMI3_NAME(fmi3GetClock)(fmi3Instance i, VREFS, fmi3Clock v[]) { return refuse(i, "fmi3GetClock"); }
EXPORT fmi3Status FMI3_NAME(fmi3SetClock)(fmi3Instance i, VREFS, const fmi3Clock v[])
{
    return refuse(i, "fmi3SetClock");
}
EXPORT fmi3Status FMI3_NAME(fmi3GetNumberOfVariableDependencies)(fmi3Instance i, fmi3ValueReference vr,
                                                      size_t *n)
{
    return refuse(i, "fmi3GetNumberOfVariableDependencies");
}
EXPORT fmi3Status FMI3_NAME(fmi3GetVariableDependencies)(fmi3Instance i, fmi3ValueReference d, size_t e[],
                                              fmi3ValueReference ind[], size_t ei[],
                                              fmi3DependencyKind k[], size_t n)
{
    return refuse(i, "fmi3GetVariableDependencies");
}
EXPORT fmi3Status FMI3_NAME(fmi3GetDirectionalDerivative)(fmi3Instance i, const fmi3ValueReference u[],
                                               size_t nu, const fmi3ValueReference k[], size_t nk,
                                               const fmi3Float64 s[], size_t ns, fmi3Float64 o[],
                                               size_t no)
{
    return refuse(i, "fmi3GetDirectionalDerivative");
}
EXPORT fmi3Status FMI3_NAME(fmi3GetAdjointDerivative)(fmi3Instance i, const fmi3ValueReference u[], size_t nu,
                                           const fmi3ValueReference k[], size_t nk,
                                           const fmi3Float64 s[], size_t ns, fmi3Float64 o[],
                                           size_t no)
{
    return refuse(i, "fmi3GetAdjointDerivative");
}
EXPORT fmi3Status FMI3_NAME(fmi3EnterConfigurationMode)(fmi3Instance i) { return refuse(i, "fmi3EnterConfigurationMode"); }
EXPORT fmi3Status FMI3_NAME(fmi3ExitConfigurationMode)(fmi3Instance i) { return refuse(i, "fmi3ExitConfigurationMode"); }
EXPORT fmi3Status FMI3_NAME(fmi3GetIntervalDecimal)(fmi3Instance i, VREFS, fmi3Float64 iv[],
                                         fmi3IntervalQualifier q[])
{
    return refuse(i, "fmi3GetIntervalDecimal");
}
EXPORT fmi3Status FMI3_NAME(fmi3GetIntervalFraction)(fmi3Instance i, VREFS, fmi3UInt64 c[], fmi3UInt64 r[],
                                          fmi3IntervalQualifier q[])
{
    return refuse(i, "fmi3GetIntervalFraction");
}
EXPORT fmi3Status FMI3_NAME(fmi3GetShiftDecimal)(fmi3Instance i, VREFS, fmi3Float64 s[])
{
    return refuse(i, "fmi3GetShiftDecimal");
}
EXPORT fmi3Status FMI3_NAME(fmi3GetShiftFraction)(fmi3Instance i, VREFS, fmi3UInt64 c[], fmi3UInt64 r[])
{
    return refuse(i, "fmi3GetShiftFraction");
}
EXPORT fmi3Status FMI3_NAME(fmi3SetIntervalDecimal)(fmi3Instance i, VREFS, const fmi3Float64 iv[])
{
    return refuse(i, "fmi3SetIntervalDecimal");
}
EXPORT fmi3Status FMI3_NAME(fmi3SetIntervalFraction)(fmi3Instance i, VREFS, const fmi3UInt64 c[],
                                          const fmi3UInt64 r[])
{
    return refuse(i, "fmi3SetIntervalFraction");
}
EXPORT fmi3Status FMI3_NAME(fmi3SetShiftDecimal)(fmi3Instance i, VREFS, const fmi3Float64 s[])
{
    return refuse(i, "fmi3SetShiftDecimal");
}
EXPORT fmi3Status FMI3_NAME(fmi3SetShiftFraction)(fmi3Instance i, VREFS, const fmi3UInt64 c[],
                                       const fmi3UInt64 r[])
{
    return refuse(i, "fmi3SetShiftFraction");
}
EXPORT fmi3Status FMI3_NAME(fmi3EvaluateDiscreteStates)(fmi3Instance i) { return refuse(i, "fmi3EvaluateDiscreteStates"); }
EXPORT fmi3Status FMI3_NAME(fmi3UpdateDiscreteStates)(fmi3Instance i, fmi3Boolean *a, fmi3Boolean *t,
                                           fmi3Boolean *nc, fmi3Boolean *vc, fmi3Boolean *nd,
                                           fmi3Float64 *n)
{
    return refuse(i, "fmi3UpdateDiscreteStates (no event mode)");
}
EXPORT fmi3Status FMI3_NAME(fmi3EnterEventMode)(fmi3Instance i) { return refuse(i, "fmi3EnterEventMode (no event mode)"); }
EXPORT fmi3Status FMI3_NAME(fmi3EnterContinuousTimeMode)(fmi3Instance i) { return refuse(i, "fmi3EnterContinuousTimeMode"); }
EXPORT fmi3Status FMI3_NAME(fmi3CompletedIntegratorStep)(fmi3Instance i, fmi3Boolean ns, fmi3Boolean *e,
                                              fmi3Boolean *t)
{
    return refuse(i, "fmi3CompletedIntegratorStep");
}
EXPORT fmi3Status FMI3_NAME(fmi3SetTime)(fmi3Instance i, fmi3Float64 t) { return refuse(i, "fmi3SetTime"); }
EXPORT fmi3Status FMI3_NAME(fmi3SetContinuousStates)(fmi3Instance i, const fmi3Float64 x[], size_t n)
{
    return refuse(i, "fmi3SetContinuousStates");
}
EXPORT fmi3Status FMI3_NAME(fmi3GetContinuousStateDerivatives)(fmi3Instance i, fmi3Float64 d[], size_t n)
{
    return refuse(i, "fmi3GetContinuousStateDerivatives");
}
EXPORT fmi3Status FMI3_NAME(fmi3GetEventIndicators)(fmi3Instance i, fmi3Float64 z[], size_t n)
{
    return refuse(i, "fmi3GetEventIndicators");
}
EXPORT fmi3Status FMI3_NAME(fmi3GetContinuousStates)(fmi3Instance i, fmi3Float64 x[], size_t n)
{
    return refuse(i, "fmi3GetContinuousStates");
}
EXPORT fmi3Status FMI3_NAME(fmi3GetNominalsOfContinuousStates)(fmi3Instance i, fmi3Float64 x[], size_t n)
{
    return refuse(i, "fmi3GetNominalsOfContinuousStates");
}
EXPORT fmi3Status FMI3_NAME(fmi3GetNumberOfEventIndicators)(fmi3Instance i, size_t *n)
{
    return refuse(i, "fmi3GetNumberOfEventIndicators");
}
EXPORT fmi3Status FMI3_NAME(fmi3GetNumberOfContinuousStates)(fmi3Instance i, size_t *n)
{
    return refuse(i, "fmi3GetNumberOfContinuousStates");
}
EXPORT fmi3Status FMI3_NAME(fmi3EnterStepMode)(fmi3Instance i) { return refuse(i, "fmi3EnterStepMode (no event mode)"); }
EXPORT fmi3Status FMI3_NAME(fmi3GetOutputDerivatives)(fmi3Instance i, VREFS, const fmi3Int32 o[],
                                           fmi3Float64 v[], size_t n)
{
    return refuse(i, "fmi3GetOutputDerivatives");
}
EXPORT fmi3Status FMI3_NAME(fmi3ActivateModelPartition)(fmi3Instance i, fmi3ValueReference c,
                                             fmi3Float64 t)
{
    return refuse(i, "fmi3ActivateModelPartition");
}
