/* fmi3cs.c - a scene as an FMI 3.0 Co-Simulation FMU (docs/fmi.md, "Export"): the FMI
 * functions over one compiled scene (FMU_CS_SCENE, its generated C linked beside the
 * runtime) and one rt_sim per instance. fmi3DoStep runs whole base ticks, recording each
 * as `modrt run` does (so the scene's trace hash is the same); a communication point or
 * step that is not on the tick grid is refused with fmi3Error and a logged reason. The
 * FMU state is the runtime's snapshot (rt_snapshot / rt_restore) with the held inputs.
 * Variables: fmu_cs_vars.h. Functions of interfaces the FMU does not have return
 * fmi3Error with a logged reason, as the standard asks of an FMU that exports them all. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fmi_api.h"
#include "fmu_cs_vars.h"
#include "rt.h"
#include "rt_sim.h"

#define EXPORT __attribute__((visibility("default")))
#define CS_MAGIC "modrt-cs-state-1" /* serialized FMU states begin with it */
#define CS_MSG 256                  /* characters of a logged message */

extern const rt_scene FMU_CS_SCENE;

typedef enum { CS_INSTANTIATED, CS_INIT, CS_STEP, CS_TERMINATED } cs_mode;

typedef struct cs_inst {
    rt_sim sim;
    const rt_scene *sc;
    fmi3InstanceEnvironment env;
    fmi3LogMessageCallback log;
    cs_mode mode;
    uint32_t nvars;
    real_t *u;              /* the imports, as last set (applied at each step) */
} cs_inst;

/* a saved FMU state: the runtime's state and the held inputs */
typedef struct cs_state {
    char magic[16];
    uint32_t nimp;
    rt_state st;
    real_t u[];
} cs_state;

__attribute__((format(printf, 3, 4)))
static void say(cs_inst *in, fmi3Status s, const char *fmt, ...)
{
    char msg[CS_MSG];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    if (in && in->log)
        in->log(in->env, s, s >= fmi3Error ? "logStatusError" : "logStatusWarning", msg);
}

static fmi3Status refuse(cs_inst *in, const char *what)
{
    say(in, fmi3Error, "%s: not supported by a modrt Co-Simulation FMU", what);
    return fmi3Error;
}

static size_t state_size(const cs_inst *in)
{
    return sizeof(cs_state) + fmu_cs_nimp(in->sc) * sizeof(real_t);
}

/* ------------------------------------------------------------------ life */

static int setup(cs_inst *in)
{
    const rt_scene *sc = in->sc;
    rt_status st = rt_init(sc, &in->sim);
    if (st != RT_OK) {
        say(in, fmi3Error, "the runtime rejects the scene: %s", rt_error_text(&in->sim));
        return -1;
    }
    for (uint32_t i = 0; i < fmu_cs_nimp(sc); i++)
        in->u[i] = sc->link->def[i];
    in->mode = CS_INSTANTIATED;
    return 0;
}

EXPORT const char *fmi3GetVersion(void) { return "3.0"; }

EXPORT fmi3Status fmi3SetDebugLogging(fmi3Instance instance, fmi3Boolean loggingOn,
                                      size_t nCategories, const fmi3String categories[])
{
    (void)instance, (void)loggingOn, (void)nCategories, (void)categories;
    return fmi3OK;
}

EXPORT fmi3Instance fmi3InstantiateCoSimulation(
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
    if (!instantiationToken || strcmp(instantiationToken, FMU_CS_TOKEN) != 0) {
        say(&tmp, fmi3Error, "instantiationToken %s is not this FMU's",
            instantiationToken ? instantiationToken : "(null)");
        return NULL;
    }
    if (eventModeUsed) {
        say(&tmp, fmi3Error, "event mode: the FMU has none (hasEventMode false)");
        return NULL;
    }
    cs_inst *in = calloc(1, sizeof *in);
    const rt_scene *sc = &FMU_CS_SCENE;
    if (!in)
        return NULL;
    in->sc = sc, in->env = instanceEnvironment, in->log = logMessage;
    in->nvars = fmu_cs_count(sc);
    in->u = calloc(fmu_cs_nimp(sc) + 1, sizeof *in->u);
    if (!in->u || setup(in) != 0) {
        free(in->u), free(in);
        return NULL;
    }
    return in;
}

EXPORT void fmi3FreeInstance(fmi3Instance instance)
{
    cs_inst *in = instance;
    if (!in)
        return;
    free(in->u), free(in);
}

EXPORT fmi3Status fmi3EnterInitializationMode(fmi3Instance instance, fmi3Boolean toleranceDefined,
                                              fmi3Float64 tolerance, fmi3Float64 startTime,
                                              fmi3Boolean stopTimeDefined, fmi3Float64 stopTime)
{
    cs_inst *in = instance;
    (void)toleranceDefined, (void)tolerance;
    if (in->mode != CS_INSTANTIATED)
        return refuse(in, "fmi3EnterInitializationMode outside the instantiated state");
    if (startTime != 0) {
        say(in, fmi3Error, "startTime %g: the scene starts at 0", startTime);
        return fmi3Error;
    }
    if (stopTimeDefined && stopTime > (double)in->sc->t_end * (1 + 1e-12)) {
        say(in, fmi3Error, "stopTime %g is past the scene's end time", stopTime);
        return fmi3Error;
    }
    in->mode = CS_INIT;
    return fmi3OK;
}

EXPORT fmi3Status fmi3ExitInitializationMode(fmi3Instance instance)
{
    cs_inst *in = instance;
    if (in->mode != CS_INIT)
        return refuse(in, "fmi3ExitInitializationMode outside initialization mode");
    rt_link_apply(in->sc, &in->sim, in->u);
    rt_refresh(in->sc, &in->sim);
    rt_record(in->sc, &in->sim, NULL); /* the trace's row at t = 0, as modrt run's */
    in->mode = CS_STEP;
    return fmi3OK;
}

EXPORT fmi3Status fmi3Terminate(fmi3Instance instance)
{
    ((cs_inst *)instance)->mode = CS_TERMINATED;
    return fmi3OK;
}

EXPORT fmi3Status fmi3Reset(fmi3Instance instance)
{
    return setup(instance) == 0 ? fmi3OK : fmi3Error;
}

/* ------------------------------------------------------------------ values */

static fmi3Status get_one(cs_inst *in, fmi3ValueReference vr, fmi3Float64 *v)
{
    const rt_scene *sc = in->sc;
    if (vr >= in->nvars) {
        say(in, fmi3Error, "value reference %u does not exist", (unsigned)vr);
        return fmi3Error;
    }
    fmu_cs_var x = fmu_cs_at(sc, vr);
    switch (x.kind) {
    case FMU_CS_TIME: *v = (double)rt_time(sc, &in->sim); break;
    case FMU_CS_REC: *v = (double)rt_rec_value(sc, &in->sim, x.a); break;
    case FMU_CS_EXP: *v = (double)rt_link_export(sc, &in->sim, x.a); break;
    case FMU_CS_IMP: *v = (double)in->u[x.a]; break;
    default:
        *v = (double)in->sim.state.p[in->sim.plan.p_off[x.a] + x.b];
    }
    return fmi3OK;
}

static fmi3Status set_one(cs_inst *in, fmi3ValueReference vr, fmi3Float64 v)
{
    const rt_scene *sc = in->sc;
    fmu_cs_var x = vr < in->nvars ? fmu_cs_at(sc, vr) : (fmu_cs_var){FMU_CS_TIME, 0, 0};
    if (x.kind == FMU_CS_IMP) {
        in->u[x.a] = (real_t)v;
        return fmi3OK;
    }
    if (x.kind != FMU_CS_PAR) {
        say(in, fmi3Error, "value reference %u is not an input or a parameter", (unsigned)vr);
        return fmi3Error;
    }
    const rt_block *b = &sc->blocks[x.a];
    rt_status st = rt_set_param(sc, &in->sim, b->name, b->kind->p_names[x.b], (real_t)v);
    if (st != RT_OK) {
        say(in, fmi3Error, "parameter refused: %s (value %g)", rt_status_name(st), v);
        return fmi3Error;
    }
    return fmi3OK;
}

EXPORT fmi3Status fmi3GetFloat64(fmi3Instance instance, const fmi3ValueReference vr[],
                                 size_t nvr, fmi3Float64 values[], size_t nValues)
{
    fmi3Status s = nvr == nValues ? fmi3OK : fmi3Error;
    for (size_t i = 0; i < nvr && s == fmi3OK; i++)
        s = get_one(instance, vr[i], &values[i]);
    return s;
}

EXPORT fmi3Status fmi3SetFloat64(fmi3Instance instance, const fmi3ValueReference vr[],
                                 size_t nvr, const fmi3Float64 values[], size_t nValues)
{
    cs_inst *in = instance;
    fmi3Status s = nvr == nValues ? fmi3OK : fmi3Error;
    if (in->mode == CS_TERMINATED)
        return refuse(in, "fmi3SetFloat64 after fmi3Terminate");
    for (size_t i = 0; i < nvr && s == fmi3OK; i++)
        s = set_one(in, vr[i], values[i]);
    return s;
}

/* ------------------------------------------------------------------ stepping */

/* t as a whole number of base ticks, or -1 */
static int64_t ticks_of(const rt_scene *sc, double t)
{
    double n = floor(t / (double)sc->dt + 0.5);
    double err = fabs(n * (double)sc->dt - t);
    return n >= 0 && err <= 1e-9 * (fabs(t) > (double)sc->dt ? fabs(t) : (double)sc->dt)
         ? (int64_t)n : -1;
}

static uint64_t faults(const rt_sim *sim)
{
    uint64_t n = 0;
    for (int c = 0; c < RT_CNT_COUNT; c++)
        n += c == RT_CNT_EVENTS ? 0 : sim->stats.count[c];
    return n;
}

EXPORT fmi3Status fmi3DoStep(fmi3Instance instance, fmi3Float64 currentCommunicationPoint,
                             fmi3Float64 communicationStepSize,
                             fmi3Boolean noSetFMUStatePriorToCurrentPoint,
                             fmi3Boolean *eventHandlingNeeded, fmi3Boolean *terminateSimulation,
                             fmi3Boolean *earlyReturn, fmi3Float64 *lastSuccessfulTime)
{
    cs_inst *in = instance;
    const rt_scene *sc = in->sc;
    (void)noSetFMUStatePriorToCurrentPoint;
    *eventHandlingNeeded = 0, *terminateSimulation = 0, *earlyReturn = 0;
    *lastSuccessfulTime = (double)rt_time(sc, &in->sim);
    if (in->mode != CS_STEP)
        return refuse(in, "fmi3DoStep outside step mode");
    int64_t n = ticks_of(sc, communicationStepSize), at = ticks_of(sc, currentCommunicationPoint);
    if (n < 1) {
        say(in, fmi3Error, "communication step %.17g s is not a whole number of base ticks "
            "(%.17g s)", communicationStepSize, (double)sc->dt);
        return fmi3Error;
    }
    if (at != (int64_t)rt_ticks_done(&in->sim)) {
        say(in, fmi3Error, "communication point %.17g s is not the FMU's time (%.17g s)",
            currentCommunicationPoint, (double)rt_time(sc, &in->sim));
        return fmi3Error;
    }
    if (rt_ticks_done(&in->sim) + (uint64_t)n > rt_tick_count(&in->sim)) {
        say(in, fmi3Error, "the step ends past the scene's end time (%.17g s)",
            (double)sc->t_end);
        *terminateSimulation = 1;
        return fmi3Error;
    }
    uint64_t before = faults(&in->sim);
    rt_link_apply(sc, &in->sim, in->u);
    for (int64_t k = 0; k < n; k++) {
        rt_tick(sc, &in->sim);
        rt_record(sc, &in->sim, NULL);
    }
    *lastSuccessfulTime = (double)rt_time(sc, &in->sim);
    if (faults(&in->sim) == before)
        return fmi3OK;
    int sev = rt_status_severity(in->sim.stats.status);
    say(in, sev >= 2 ? fmi3Error : fmi3Warning, "the runtime counted a fault: %s (t = %.17g s)",
        rt_status_name(in->sim.stats.status), *lastSuccessfulTime);
    return sev >= 2 ? fmi3Error : fmi3Warning;
}

/* ------------------------------------------------------------------ FMU state */

EXPORT fmi3Status fmi3GetFMUState(fmi3Instance instance, fmi3FMUState *FMUState)
{
    cs_inst *in = instance;
    cs_state *s = *FMUState ? *FMUState : calloc(1, state_size(in));
    if (!s)
        return fmi3Error;
    memcpy(s->magic, CS_MAGIC, sizeof s->magic);
    s->nimp = fmu_cs_nimp(in->sc);
    rt_snapshot(&in->sim, &s->st);
    memcpy(s->u, in->u, s->nimp * sizeof *s->u);
    *FMUState = s;
    return fmi3OK;
}

EXPORT fmi3Status fmi3SetFMUState(fmi3Instance instance, fmi3FMUState FMUState)
{
    cs_inst *in = instance;
    cs_state *s = FMUState;
    if (!s || memcmp(s->magic, CS_MAGIC, sizeof s->magic) != 0 || s->nimp != fmu_cs_nimp(in->sc))
        return refuse(in, "fmi3SetFMUState with a state of another FMU");
    if (rt_restore(&in->sim, &s->st) != RT_OK)
        return refuse(in, "fmi3SetFMUState: the runtime refuses the state");
    memcpy(in->u, s->u, s->nimp * sizeof *s->u);
    return fmi3OK;
}

EXPORT fmi3Status fmi3FreeFMUState(fmi3Instance instance, fmi3FMUState *FMUState)
{
    (void)instance;
    free(*FMUState);
    *FMUState = NULL;
    return fmi3OK;
}

EXPORT fmi3Status fmi3SerializedFMUStateSize(fmi3Instance instance, fmi3FMUState FMUState,
                                             size_t *size)
{
    (void)FMUState;
    *size = state_size(instance);
    return fmi3OK;
}

EXPORT fmi3Status fmi3SerializeFMUState(fmi3Instance instance, fmi3FMUState FMUState,
                                        fmi3Byte serializedState[], size_t size)
{
    if (size != state_size(instance))
        return refuse(instance, "fmi3SerializeFMUState with a buffer of the wrong size");
    memcpy(serializedState, FMUState, size);
    return fmi3OK;
}

EXPORT fmi3Status fmi3DeserializeFMUState(fmi3Instance instance, const fmi3Byte serializedState[],
                                          size_t size, fmi3FMUState *FMUState)
{
    cs_inst *in = instance;
    const cs_state *src = (const cs_state *)(const void *)serializedState;
    if (size != state_size(in) || memcmp(src->magic, CS_MAGIC, sizeof src->magic) != 0)
        return refuse(in, "fmi3DeserializeFMUState: not a state of this FMU");
    cs_state *s = malloc(size);
    if (!s)
        return fmi3Error;
    memcpy(s, serializedState, size);
    *FMUState = s;
    return fmi3OK;
}

/* ------------------------------------------------------------------ what it does not have */

#pragma GCC diagnostic ignored "-Wunused-parameter"

EXPORT fmi3Instance fmi3InstantiateModelExchange(fmi3String n, fmi3String t, fmi3String r,
                                                 fmi3Boolean v, fmi3Boolean l,
                                                 fmi3InstanceEnvironment e,
                                                 fmi3LogMessageCallback log)
{
    if (log)
        log(e, fmi3Error, "logStatusError", "the FMU has no Model Exchange interface");
    return NULL;
}

EXPORT fmi3Instance fmi3InstantiateScheduledExecution(fmi3String n, fmi3String t, fmi3String r,
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
    EXPORT fmi3Status fmi3Get##name(fmi3Instance i, VREFS, T v[], size_t n)               \
    {                                                                                     \
        return refuse(i, "fmi3Get" #name ": the FMU has Float64 variables only");         \
    }                                                                                     \
    EXPORT fmi3Status fmi3Set##name(fmi3Instance i, VREFS, const T v[], size_t n)         \
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

EXPORT fmi3Status fmi3GetBinary(fmi3Instance i, VREFS, size_t s[], fmi3Binary v[], size_t n)
{
    return refuse(i, "fmi3GetBinary");
}
EXPORT fmi3Status fmi3SetBinary(fmi3Instance i, VREFS, const size_t s[], const fmi3Binary v[],
                                size_t n)
{
    return refuse(i, "fmi3SetBinary");
}
EXPORT fmi3Status fmi3GetClock(fmi3Instance i, VREFS, fmi3Clock v[]) { return refuse(i, "fmi3GetClock"); }
EXPORT fmi3Status fmi3SetClock(fmi3Instance i, VREFS, const fmi3Clock v[])
{
    return refuse(i, "fmi3SetClock");
}
EXPORT fmi3Status fmi3GetNumberOfVariableDependencies(fmi3Instance i, fmi3ValueReference vr,
                                                      size_t *n)
{
    return refuse(i, "fmi3GetNumberOfVariableDependencies");
}
EXPORT fmi3Status fmi3GetVariableDependencies(fmi3Instance i, fmi3ValueReference d, size_t e[],
                                              fmi3ValueReference ind[], size_t ei[],
                                              fmi3DependencyKind k[], size_t n)
{
    return refuse(i, "fmi3GetVariableDependencies");
}
EXPORT fmi3Status fmi3GetDirectionalDerivative(fmi3Instance i, const fmi3ValueReference u[],
                                               size_t nu, const fmi3ValueReference k[], size_t nk,
                                               const fmi3Float64 s[], size_t ns, fmi3Float64 o[],
                                               size_t no)
{
    return refuse(i, "fmi3GetDirectionalDerivative");
}
EXPORT fmi3Status fmi3GetAdjointDerivative(fmi3Instance i, const fmi3ValueReference u[], size_t nu,
                                           const fmi3ValueReference k[], size_t nk,
                                           const fmi3Float64 s[], size_t ns, fmi3Float64 o[],
                                           size_t no)
{
    return refuse(i, "fmi3GetAdjointDerivative");
}
EXPORT fmi3Status fmi3EnterConfigurationMode(fmi3Instance i) { return refuse(i, "fmi3EnterConfigurationMode"); }
EXPORT fmi3Status fmi3ExitConfigurationMode(fmi3Instance i) { return refuse(i, "fmi3ExitConfigurationMode"); }
EXPORT fmi3Status fmi3GetIntervalDecimal(fmi3Instance i, VREFS, fmi3Float64 iv[],
                                         fmi3IntervalQualifier q[])
{
    return refuse(i, "fmi3GetIntervalDecimal");
}
EXPORT fmi3Status fmi3GetIntervalFraction(fmi3Instance i, VREFS, fmi3UInt64 c[], fmi3UInt64 r[],
                                          fmi3IntervalQualifier q[])
{
    return refuse(i, "fmi3GetIntervalFraction");
}
EXPORT fmi3Status fmi3GetShiftDecimal(fmi3Instance i, VREFS, fmi3Float64 s[])
{
    return refuse(i, "fmi3GetShiftDecimal");
}
EXPORT fmi3Status fmi3GetShiftFraction(fmi3Instance i, VREFS, fmi3UInt64 c[], fmi3UInt64 r[])
{
    return refuse(i, "fmi3GetShiftFraction");
}
EXPORT fmi3Status fmi3SetIntervalDecimal(fmi3Instance i, VREFS, const fmi3Float64 iv[])
{
    return refuse(i, "fmi3SetIntervalDecimal");
}
EXPORT fmi3Status fmi3SetIntervalFraction(fmi3Instance i, VREFS, const fmi3UInt64 c[],
                                          const fmi3UInt64 r[])
{
    return refuse(i, "fmi3SetIntervalFraction");
}
EXPORT fmi3Status fmi3SetShiftDecimal(fmi3Instance i, VREFS, const fmi3Float64 s[])
{
    return refuse(i, "fmi3SetShiftDecimal");
}
EXPORT fmi3Status fmi3SetShiftFraction(fmi3Instance i, VREFS, const fmi3UInt64 c[],
                                       const fmi3UInt64 r[])
{
    return refuse(i, "fmi3SetShiftFraction");
}
EXPORT fmi3Status fmi3EvaluateDiscreteStates(fmi3Instance i) { return refuse(i, "fmi3EvaluateDiscreteStates"); }
EXPORT fmi3Status fmi3UpdateDiscreteStates(fmi3Instance i, fmi3Boolean *a, fmi3Boolean *t,
                                           fmi3Boolean *nc, fmi3Boolean *vc, fmi3Boolean *nd,
                                           fmi3Float64 *n)
{
    return refuse(i, "fmi3UpdateDiscreteStates (no event mode)");
}
EXPORT fmi3Status fmi3EnterEventMode(fmi3Instance i) { return refuse(i, "fmi3EnterEventMode (no event mode)"); }
EXPORT fmi3Status fmi3EnterContinuousTimeMode(fmi3Instance i) { return refuse(i, "fmi3EnterContinuousTimeMode"); }
EXPORT fmi3Status fmi3CompletedIntegratorStep(fmi3Instance i, fmi3Boolean ns, fmi3Boolean *e,
                                              fmi3Boolean *t)
{
    return refuse(i, "fmi3CompletedIntegratorStep");
}
EXPORT fmi3Status fmi3SetTime(fmi3Instance i, fmi3Float64 t) { return refuse(i, "fmi3SetTime"); }
EXPORT fmi3Status fmi3SetContinuousStates(fmi3Instance i, const fmi3Float64 x[], size_t n)
{
    return refuse(i, "fmi3SetContinuousStates");
}
EXPORT fmi3Status fmi3GetContinuousStateDerivatives(fmi3Instance i, fmi3Float64 d[], size_t n)
{
    return refuse(i, "fmi3GetContinuousStateDerivatives");
}
EXPORT fmi3Status fmi3GetEventIndicators(fmi3Instance i, fmi3Float64 z[], size_t n)
{
    return refuse(i, "fmi3GetEventIndicators");
}
EXPORT fmi3Status fmi3GetContinuousStates(fmi3Instance i, fmi3Float64 x[], size_t n)
{
    return refuse(i, "fmi3GetContinuousStates");
}
EXPORT fmi3Status fmi3GetNominalsOfContinuousStates(fmi3Instance i, fmi3Float64 x[], size_t n)
{
    return refuse(i, "fmi3GetNominalsOfContinuousStates");
}
EXPORT fmi3Status fmi3GetNumberOfEventIndicators(fmi3Instance i, size_t *n)
{
    return refuse(i, "fmi3GetNumberOfEventIndicators");
}
EXPORT fmi3Status fmi3GetNumberOfContinuousStates(fmi3Instance i, size_t *n)
{
    return refuse(i, "fmi3GetNumberOfContinuousStates");
}
EXPORT fmi3Status fmi3EnterStepMode(fmi3Instance i) { return refuse(i, "fmi3EnterStepMode (no event mode)"); }
EXPORT fmi3Status fmi3GetOutputDerivatives(fmi3Instance i, VREFS, const fmi3Int32 o[],
                                           fmi3Float64 v[], size_t n)
{
    return refuse(i, "fmi3GetOutputDerivatives");
}
EXPORT fmi3Status fmi3ActivateModelPartition(fmi3Instance i, fmi3ValueReference c,
                                             fmi3Float64 t)
{
    return refuse(i, "fmi3ActivateModelPartition");
}
