/* fmu_call.c - FMI 2.0 and FMI 3.0 Model Exchange as one calling sequence (fmu_ops): each
 * version's table maps the sequence onto its functions, with the callbacks the FMU logs
 * through (the message lands in the instance's log, for the fault it explains). */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fmu_int.h"

/* ------------------------------------------------------------------ FMI 2.0 */

static void logger2(fmi2ComponentEnvironment env, fmi2String name, fmi2Status status,
                    fmi2String category, fmi2String message, ...)
{
    fmu_inst *in = env;
    (void)name, (void)status, (void)category;
    if (!in || !message)
        return;
    va_list ap;
    va_start(ap, message);
    vsnprintf(in->log, sizeof in->log, message, ap);
    va_end(ap);
}

#ifdef FMU_TARGET /* an image: static memory (fmu_arena.c), no resources directory */
#define FMU_ALLOC fmu_arena_calloc
#define FMU_FREE fmu_arena_free
#else
/* what the arena of an image would hand out for the FMI 2.0 FMUs' memory (fmu_arena_need) */
size_t fmu_alloc2_used;
static void *alloc2(size_t n, size_t size)
{
    void *p = calloc(n, size);
    if (p)
        fmu_alloc2_used = ((fmu_alloc2_used + FMU_ARENA_ALIGN - 1) &
                           ~(size_t)(FMU_ARENA_ALIGN - 1)) + n * size;
    return p;
}
#define FMU_ALLOC alloc2
#define FMU_FREE free
#endif

/* resourceLocation is a URI (file:///...) in 2.0; the FMU keeps the pointer to the
   callbacks, which live in the instance */
static int instantiate2(fmu_inst *in)
{
    fmu_model *m = in->m;
    in->cb2.logger = logger2, in->cb2.allocateMemory = FMU_ALLOC, in->cb2.freeMemory = FMU_FREE;
    in->cb2.componentEnvironment = in;
#ifdef FMU_TARGET
    in->c = m->f2.fmi2Instantiate(in->block, fmi2ModelExchange, m->md.token, "", &in->cb2,
                                  fmi2False, fmi2False);
#else
    size_t n = strlen(m->dir) + 32;
    char *uri = malloc(n);
    if (!uri)
        return -1;
    snprintf(uri, n, "file://%s/resources", m->dir);
    in->c = m->f2.fmi2Instantiate(in->block, fmi2ModelExchange, m->md.token, uri, &in->cb2,
                                  fmi2False, fmi2False);
    free(uri);
#endif
    return in->c ? 0 : -1;
}

static int enter_init2(fmu_inst *in, double t0)
{
    int s = in->m->f2.fmi2SetupExperiment(in->c, fmi2False, 0, t0, fmi2False, 0);
    return s > fmi2Warning ? s : (int)in->m->f2.fmi2EnterInitializationMode(in->c);
}

static int exit_init2(fmu_inst *in) { return in->m->f2.fmi2ExitInitializationMode(in->c); }

static int update2(fmu_inst *in, fmu_update *u)
{
    fmi2EventInfo e = {0};
    int s = in->m->f2.fmi2NewDiscreteStates(in->c, &e);
    u->again = e.newDiscreteStatesNeeded, u->terminate = e.terminateSimulation;
    u->x_changed = e.valuesOfContinuousStatesChanged;
    u->has_next = e.nextEventTimeDefined, u->next = e.nextEventTime;
    return s;
}

static int enter_ct2(fmu_inst *in) { return in->m->f2.fmi2EnterContinuousTimeMode(in->c); }
static int enter_event2(fmu_inst *in) { return in->m->f2.fmi2EnterEventMode(in->c); }
static int set_time2(fmu_inst *in, double t) { return in->m->f2.fmi2SetTime(in->c, t); }

static int set_x2(fmu_inst *in, const double *x, size_t n)
{
    return in->m->f2.fmi2SetContinuousStates(in->c, x, n);
}

static int get_x2(fmu_inst *in, double *x, size_t n)
{
    return in->m->f2.fmi2GetContinuousStates(in->c, x, n);
}

static int get_dx2(fmu_inst *in, double *dx, size_t n)
{
    return in->m->f2.fmi2GetDerivatives(in->c, dx, n);
}

static int get_z2(fmu_inst *in, double *z, size_t n)
{
    return in->m->f2.fmi2GetEventIndicators(in->c, z, n);
}

static int completed2(fmu_inst *in, int *enter_event, int *terminate)
{
    fmi2Boolean e = fmi2False, t = fmi2False;
    /* noSetFMUStatePriorToCurrentPoint: not where a snapshot may be restored (fmu_state.c) */
    fmi2Boolean no_back = in->m->md.can_state ? fmi2False : fmi2True;
    int s = in->m->f2.fmi2CompletedIntegratorStep(in->c, no_back, &e, &t);
    *enter_event = e != fmi2False, *terminate = t != fmi2False;
    return s;
}

/* fmi2GetReal into get, else fmi2SetReal from set, in blocks of 64 value references
   (fmi2ValueReference is unsigned int, the interface's are uint32_t) */
static int real2(fmu_inst *in, const uint32_t *vr, size_t n, double *get, const double *set)
{
    fmi2ValueReference r[64];
    int s = fmi2OK;
    for (size_t i = 0; i < n && s <= fmi2Warning; i += 64) {
        size_t k = n - i < 64 ? n - i : 64;
        for (size_t j = 0; j < k; j++)
            r[j] = vr[i + j];
        int t = get ? in->m->f2.fmi2GetReal(in->c, r, k, get + i)
                    : in->m->f2.fmi2SetReal(in->c, r, k, set + i);
        s = t > s ? t : s;
    }
    return s;
}

static int get2(fmu_inst *in, const uint32_t *vr, size_t n, double *v)
{
    return real2(in, vr, n, v, NULL);
}

static int set2(fmu_inst *in, const uint32_t *vr, size_t n, const double *v)
{
    return real2(in, vr, n, NULL, v);
}

static int reset2(fmu_inst *in) { return in->m->f2.fmi2Reset(in->c); }
static int terminate2(fmu_inst *in) { return in->m->f2.fmi2Terminate(in->c); }

static void free2(fmu_inst *in) { in->m->f2.fmi2FreeInstance(in->c); }

const fmu_ops fmu_ops2 = {
    .prefix = "fmi2", .instantiate = instantiate2, .enter_init = enter_init2,
    .exit_init = exit_init2, .update = update2, .enter_ct = enter_ct2,
    .enter_event = enter_event2, .set_time = set_time2, .set_x = set_x2, .get_x = get_x2,
    .get_dx = get_dx2, .get_z = get_z2, .completed = completed2, .get = get2, .set = set2, .reset = reset2,
    .terminate = terminate2, .free = free2,
};

/* ------------------------------------------------------------------ FMI 3.0 */

static void logger3(fmi3InstanceEnvironment env, fmi3Status status, fmi3String category,
                    fmi3String message)
{
    fmu_inst *in = env;
    (void)status, (void)category;
    if (in && message)
        snprintf(in->log, sizeof in->log, "%s", message);
}

/* resourcePath is a directory path with a trailing separator in 3.0 */
static int instantiate3(fmu_inst *in)
{
    fmu_model *m = in->m;
#ifdef FMU_TARGET
    in->c = m->f3.fmi3InstantiateModelExchange(in->block, m->md.token, "", fmi3False,
                                               fmi3False, in, logger3);
#else
    size_t n = strlen(m->dir) + 16;
    char *res = malloc(n);
    if (!res)
        return -1;
    snprintf(res, n, "%s/resources/", m->dir);
    in->c = m->f3.fmi3InstantiateModelExchange(in->block, m->md.token, res, fmi3False,
                                               fmi3False, in, logger3);
    free(res);
#endif
    return in->c ? 0 : -1;
}

static int enter_init3(fmu_inst *in, double t0)
{
    return in->m->f3.fmi3EnterInitializationMode(in->c, fmi3False, 0, t0, fmi3False, 0);
}

static int exit_init3(fmu_inst *in) { return in->m->f3.fmi3ExitInitializationMode(in->c); }

static int update3(fmu_inst *in, fmu_update *u)
{
    fmi3Boolean again = 0, term = 0, nom = 0, xch = 0, has = 0;
    fmi3Float64 next = 0;
    int s = in->m->f3.fmi3UpdateDiscreteStates(in->c, &again, &term, &nom, &xch, &has, &next);
    u->again = again, u->terminate = term, u->x_changed = xch;
    u->has_next = has, u->next = next;
    return s;
}

static int enter_ct3(fmu_inst *in) { return in->m->f3.fmi3EnterContinuousTimeMode(in->c); }
static int enter_event3(fmu_inst *in) { return in->m->f3.fmi3EnterEventMode(in->c); }
static int set_time3(fmu_inst *in, double t) { return in->m->f3.fmi3SetTime(in->c, t); }

static int set_x3(fmu_inst *in, const double *x, size_t n)
{
    return in->m->f3.fmi3SetContinuousStates(in->c, x, n);
}

static int get_x3(fmu_inst *in, double *x, size_t n)
{
    return in->m->f3.fmi3GetContinuousStates(in->c, x, n);
}

static int get_dx3(fmu_inst *in, double *dx, size_t n)
{
    return in->m->f3.fmi3GetContinuousStateDerivatives(in->c, dx, n);
}

static int get_z3(fmu_inst *in, double *z, size_t n)
{
    return in->m->f3.fmi3GetEventIndicators(in->c, z, n);
}

static int completed3(fmu_inst *in, int *enter_event, int *terminate)
{
    fmi3Boolean e = fmi3False, t = fmi3False;
    int s = in->m->f3.fmi3CompletedIntegratorStep(in->c, !in->m->md.can_state, &e, &t);
    *enter_event = e != fmi3False, *terminate = t != fmi3False;
    return s;
}

static int get3(fmu_inst *in, const uint32_t *vr, size_t n, double *v)
{
    return in->m->f3.fmi3GetFloat64(in->c, vr, n, v, n);
}

static int set3(fmu_inst *in, const uint32_t *vr, size_t n, const double *v)
{
    return in->m->f3.fmi3SetFloat64(in->c, vr, n, v, n);
}

static int reset3(fmu_inst *in) { return in->m->f3.fmi3Reset(in->c); }
static int terminate3(fmu_inst *in) { return in->m->f3.fmi3Terminate(in->c); }
static void free3(fmu_inst *in) { in->m->f3.fmi3FreeInstance(in->c); }

const fmu_ops fmu_ops3 = {
    .prefix = "fmi3", .instantiate = instantiate3, .enter_init = enter_init3,
    .exit_init = exit_init3, .update = update3, .enter_ct = enter_ct3,
    .enter_event = enter_event3, .set_time = set_time3, .set_x = set_x3, .get_x = get_x3,
    .get_dx = get_dx3, .get_z = get_z3, .completed = completed3, .get = get3, .set = set3, .reset = reset3,
    .terminate = terminate3, .free = free3,
};
