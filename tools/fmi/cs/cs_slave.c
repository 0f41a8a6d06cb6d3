/* cs_slave.c - a compiled scene as a co-simulation slave (cs_slave.h): whole base ticks per
 * communication step, recorded as `modrt run` records them (so the scene's trace hash is
 * the same); a step off the tick grid refused with nothing changed; the FMU state is the
 * runtime's snapshot (rt_snapshot / rt_restore) with the held inputs. */
#include "cs_slave.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "fmu_cs_id.h"
#include "fmu_cs_vars.h"

#define CS_MAGIC "modrt-cs-state-2" /* a saved FMU state begins with it */

/* a saved FMU state: the runtime's state and the held inputs */
typedef struct cs_head {
    char magic[16];
    uint64_t scene;         /* which scene saved it (cs_scene_id) */
    uint32_t nimp;
} cs_head;

typedef struct cs_state {
    cs_head h;
    rt_state st;
    real_t u[];
} cs_state;

__attribute__((format(printf, 3, 4)))
static int why(cs_slave *s, int status, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(s->msg, sizeof s->msg, fmt, ap);
    va_end(ap);
    return status;
}

/* FNV-1a of the scene's name and variable count: a state of another scene is refused */
static uint64_t cs_scene_id(const cs_slave *s)
{
    uint64_t h = 0xcbf29ce484222325ull ^ s->nvars;
    for (const char *p = s->sc->name; *p; p++)
        h = (h ^ (unsigned char)*p) * 0x100000001b3ull;
    return h;
}

#ifdef FMU_CS_ONCE
static int live; /* instances of a scene with FMU blocks: 0 or 1 */
#endif

const char *cs_claim(void)
{
#ifdef FMU_CS_ONCE
    if (live)
        return "an instance of this FMU exists already: its scene's FMU blocks are static "
               "instances (canBeInstantiatedOnlyOncePerProcess)";
    live = 1;
#endif
    return NULL;
}

void cs_release(void)
{
#ifdef FMU_CS_ONCE
    live = 0;
#endif
}

size_t cs_size(const rt_scene *sc)
{
    return sizeof(cs_slave) + (fmu_cs_nimp(sc) + 1) * sizeof(real_t);
}

int cs_setup(cs_slave *s, const rt_scene *sc)
{
    s->sc = sc, s->nvars = fmu_cs_count(sc), s->msg[0] = 0;
    if (rt_init(sc, &s->sim) != RT_OK)
        return why(s, CS_ERROR, "the runtime rejects the scene: %s", rt_error_text(&s->sim));
    for (uint32_t i = 0; i < fmu_cs_nimp(sc); i++)
        s->u[i] = sc->link->def[i];
    s->mode = CS_INSTANTIATED;
    return CS_OK;
}

int cs_enter_init(cs_slave *s, double start, int stop_defined, double stop)
{
    if (s->mode != CS_INSTANTIATED)
        return why(s, CS_ERROR, "initialization entered outside the instantiated state");
    if (start != 0)
        return why(s, CS_ERROR, "startTime %g: the scene starts at 0", start);
    if (stop_defined && stop > (double)s->sc->t_end * (1 + 1e-12))
        return why(s, CS_ERROR, "stopTime %g is past the scene's end time (%g s)", stop,
                   (double)s->sc->t_end);
    s->mode = CS_INIT;
    return CS_OK;
}

int cs_exit_init(cs_slave *s)
{
    if (s->mode != CS_INIT)
        return why(s, CS_ERROR, "initialization exited outside initialization mode");
    rt_link_apply(s->sc, &s->sim, s->u);
    /* the start values set in initialization mode are judged as the scene's own */
    if (rt_refresh(s->sc, &s->sim) != RT_OK)
        return why(s, CS_ERROR, "the initial state is refused: %s", rt_error_text(&s->sim));
    rt_record(s->sc, &s->sim, NULL); /* the trace's row at t = 0, as modrt run's */
    s->mode = CS_STEP;
    return CS_OK;
}

/* ------------------------------------------------------------------ values */

int cs_get(cs_slave *s, uint32_t vr, double *v)
{
    const rt_scene *sc = s->sc;
    if (vr >= s->nvars)
        return why(s, CS_ERROR, "value reference %u does not exist", (unsigned)vr);
    fmu_cs_var x = fmu_cs_at(sc, vr);
    switch (x.kind) {
    case FMU_CS_TIME: *v = (double)rt_time(sc, &s->sim); break;
    case FMU_CS_REC: *v = (double)rt_rec_value(sc, &s->sim, x.a); break;
    case FMU_CS_EXP: *v = (double)rt_link_export(sc, &s->sim, x.a); break;
    case FMU_CS_IMP: *v = (double)s->u[x.a]; break;
    default: *v = (double)rt_block_p(&s->sim, x.a, x.b);
    }
    return CS_OK;
}

int cs_set(cs_slave *s, uint32_t vr, double v)
{
    const rt_scene *sc = s->sc;
    fmu_cs_var x = vr < s->nvars ? fmu_cs_at(sc, vr) : (fmu_cs_var){FMU_CS_TIME, 0, 0};
    if (s->mode == CS_TERMINATED)
        return why(s, CS_ERROR, "a value set after the FMU was terminated");
    if (x.kind == FMU_CS_IMP) {
        s->u[x.a] = (real_t)v;
        return CS_OK;
    }
    if (x.kind != FMU_CS_PAR)
        return why(s, CS_ERROR, "value reference %u is not an input or a parameter",
                   (unsigned)vr);
    const rt_block *b = &sc->blocks[x.a];
    rt_status st = rt_set_param(sc, &s->sim, b->name, b->kind->p_names[x.b], (real_t)v);
    if (st != RT_OK)
        return why(s, CS_ERROR, "parameter %s.%s refused: %s (value %g)", b->name,
                   b->kind->p_names[x.b], rt_status_name(st), v);
    return CS_OK;
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
        n += c == RT_CNT_EVENTS ? 0 : rt_stats_of(sim)->count[c];
    return n;
}

int cs_step(cs_slave *s, double t, double h, int *at_end)
{
    const rt_scene *sc = s->sc;
    *at_end = rt_ticks_done(&s->sim) >= rt_tick_count(&s->sim);
    if (s->mode != CS_STEP)
        return why(s, CS_ERROR, "a step outside step mode (after initialization, before "
                   "termination)");
    int64_t n = ticks_of(sc, h), at = ticks_of(sc, t);
    if (n < 1)
        return why(s, CS_ERROR, "communication step %.17g s is not a whole number of base "
                   "ticks (%.17g s)", h, (double)sc->dt);
    if (at != (int64_t)rt_ticks_done(&s->sim))
        return why(s, CS_ERROR, "communication point %.17g s is not the FMU's time (%.17g s)",
                   t, (double)rt_time(sc, &s->sim));
    if (rt_ticks_done(&s->sim) + (uint64_t)n > rt_tick_count(&s->sim))
        return why(s, CS_ERROR, "the step ends past the scene's end time (%.17g s)",
                   (double)sc->t_end);
    uint64_t before = faults(&s->sim);
    rt_link_apply(sc, &s->sim, s->u);
    for (int64_t k = 0; k < n; k++) {
        rt_tick(sc, &s->sim);
        rt_record(sc, &s->sim, NULL);
    }
    *at_end = rt_ticks_done(&s->sim) >= rt_tick_count(&s->sim);
    if (faults(&s->sim) == before)
        return CS_OK;
    rt_status status = rt_stats_of(&s->sim)->status;
    int sev = rt_status_severity(status);
    return why(s, sev >= 2 ? CS_ERROR : CS_WARNING, "the runtime counted a fault: %s "
               "(t = %.17g s)", rt_status_name(status),
               (double)rt_time(sc, &s->sim));
}

/* ------------------------------------------------------------------ FMU state */

size_t cs_state_size(const cs_slave *s)
{
    return sizeof(cs_state) + fmu_cs_nimp(s->sc) * sizeof(real_t);
}

int cs_state_save(cs_slave *s, void *buf)
{
    cs_state *st = buf;
    memcpy(st->h.magic, CS_MAGIC, sizeof st->h.magic);
    st->h.scene = cs_scene_id(s);
    st->h.nimp = fmu_cs_nimp(s->sc);
    rt_status rs = rt_snapshot(&s->sim, &st->st); /* an FMU block's state with it */
    memcpy(st->u, s->u, st->h.nimp * sizeof *st->u);
    return rs == RT_OK ? CS_OK
         : why(s, CS_ERROR, "the FMU state cannot be saved: %s", rt_status_name(rs));
}

int cs_state_check(cs_slave *s, const void *buf, size_t size)
{
    cs_head h; /* copied: a serialized state need not be aligned */
    if (buf && size == cs_state_size(s))
        memcpy(&h, buf, sizeof h);
    if (!buf || size != cs_state_size(s) || memcmp(h.magic, CS_MAGIC, sizeof h.magic) != 0 ||
        h.scene != cs_scene_id(s) || h.nimp != fmu_cs_nimp(s->sc))
        return why(s, CS_ERROR, "not an FMU state of this FMU");
    return CS_OK;
}

int cs_state_load(cs_slave *s, const void *buf, size_t size)
{
    const cs_state *st = buf;
    if (cs_state_check(s, buf, size) != CS_OK)
        return CS_ERROR;
    if (rt_restore(&s->sim, &st->st) != RT_OK)
        return why(s, CS_ERROR, "the runtime refuses the FMU state");
    memcpy(s->u, st->u, st->h.nimp * sizeof *s->u);
    return CS_OK;
}
