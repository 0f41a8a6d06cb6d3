/* fmu_state.c - an FMU block's internal state in a snapshot of the run (rt_kind.save and
 * rt_kind.restore, rt/snapshot.c; docs/fmi.md, "Snapshots"). What a run needs to continue
 * from an FMU block is more than its continuous states: the FMU's own memory (discrete
 * states, counters, a pending time event) and the importer's view of the instance
 * (fmu_inst: its mode, what it last set, the pending nextEventTime, the last event). The
 * save writes that view and the FMU's serialized FMU state (fmi2GetFMUstate +
 * fmi2SerializeFMUstate, fmi3GetFMUState + fmi3SerializeFMUState) into the snapshot; the
 * restore deserializes it and sets it back. The FMU state passes through one copy per
 * instance, made by the FMU at the first save and handed back to it at every later one
 * (FMI lets GetFMUstate overwrite a state it returned), so on a target the arena serves
 * it once. An FMU whose description does not say canGetAndSetFMUstate and
 * canSerializeFMUstate (3.0: ...FMUState) cannot be saved: RT_E_SNAPSHOT, never half a
 * snapshot. A call that fails is the block's fault, counted as every other. */
#include <string.h>

#include "fmu_int.h"

/* ------------------------------------------------------------------ the two versions */

static const char *name(const fmu_inst *in, const char *v2, const char *v3)
{
    return in->m->ops == &fmu_ops2 ? v2 : v3;
}

static int get_state(fmu_inst *in)
{
    return in->m->ops == &fmu_ops2 ? in->m->f2.fmi2GetFMUstate(in->c, &in->fstate)
                                   : in->m->f3.fmi3GetFMUState(in->c, &in->fstate);
}

static int state_size(fmu_inst *in, size_t *n)
{
    return in->m->ops == &fmu_ops2
               ? in->m->f2.fmi2SerializedFMUstateSize(in->c, in->fstate, n)
               : in->m->f3.fmi3SerializedFMUStateSize(in->c, in->fstate, n);
}

static int serialize(fmu_inst *in, uint8_t *buf, size_t n)
{
    return in->m->ops == &fmu_ops2
               ? in->m->f2.fmi2SerializeFMUstate(in->c, in->fstate, (fmi2Byte *)buf, n)
               : in->m->f3.fmi3SerializeFMUState(in->c, in->fstate, buf, n);
}

/* into the instance's copy: the FMU may fill the one it is given or make another (then
   the old one goes back to it) */
static int deserialize(fmu_inst *in, const uint8_t *buf, size_t n)
{
    void *old = in->fstate;
    int s = in->m->ops == &fmu_ops2
                ? in->m->f2.fmi2DeSerializeFMUstate(in->c, (const fmi2Byte *)buf, n, &in->fstate)
                : in->m->f3.fmi3DeserializeFMUState(in->c, buf, n, &in->fstate);
    if (old && in->fstate != old) {
        if (in->m->ops == &fmu_ops2)
            in->m->f2.fmi2FreeFMUstate(in->c, &old);
        else
            in->m->f3.fmi3FreeFMUState(in->c, &old);
    }
    return s;
}

static int set_state(fmu_inst *in)
{
    return in->m->ops == &fmu_ops2 ? in->m->f2.fmi2SetFMUstate(in->c, in->fstate)
                                   : in->m->f3.fmi3SetFMUState(in->c, in->fstate);
}

/* ------------------------------------------------------------------ the importer's view */

enum { FLAGS = 8 }; /* mode, fresh, t_valid, x_valid, u_valid, has_next, ev_valid, 0 */

/* bytes of the view: the flags, t, t_next, ev_t, then x, ev_x, u and p */
static size_t view_size(const fmu_model *m)
{
    return FLAGS + sizeof(double) * (3 + 2 * (size_t)m->nx + m->nu + m->np);
}

static uint8_t *put(uint8_t *at, const void *v, size_t n)
{
    memcpy(at, v, n);
    return at + n;
}

static void write_view(const fmu_inst *in, uint8_t *at)
{
    const fmu_model *m = in->m;
    uint8_t f[FLAGS] = {in->mode, in->fresh, in->t_valid, in->x_valid, in->u_valid,
                        in->has_next, in->ev_valid, 0};
    at = put(at, f, FLAGS);
    at = put(at, &in->t, sizeof in->t), at = put(at, &in->t_next, sizeof in->t_next);
    at = put(at, &in->ev_t, sizeof in->ev_t);
    at = put(at, in->x, m->nx * sizeof *in->x), at = put(at, in->ev_x, m->nx * sizeof *in->ev_x);
    at = put(at, in->u, m->nu * sizeof *in->u);
    put(at, in->p, m->np * sizeof *in->p);
}

static const uint8_t *get(const uint8_t *at, void *v, size_t n)
{
    memcpy(v, at, n);
    return at + n;
}

static void read_view(fmu_inst *in, const uint8_t *at)
{
    const fmu_model *m = in->m;
    uint8_t f[FLAGS];
    at = get(at, f, FLAGS);
    in->mode = f[0], in->fresh = f[1], in->t_valid = f[2], in->x_valid = f[3];
    in->u_valid = f[4], in->has_next = f[5], in->ev_valid = f[6];
    at = get(at, &in->t, sizeof in->t), at = get(at, &in->t_next, sizeof in->t_next);
    at = get(at, &in->ev_t, sizeof in->ev_t);
    at = get(at, in->x, m->nx * sizeof *in->x), at = get(at, in->ev_x, m->nx * sizeof *in->ev_x);
    at = get(at, in->u, m->nu * sizeof *in->u);
    get(at, in->p, m->np * sizeof *in->p);
}

/* ------------------------------------------------------------------ the kind's services */

/* an instance that can be saved or restored now: one that says it can, alive, started */
static int can(const fmu_inst *in)
{
    return in->m->md.can_state && in->c && !in->fatal && in->mode == FMU_M_CT;
}

rt_status fmu_save(const void *spec, uint8_t *buf, uint32_t cap, uint32_t *n)
{
    fmu_inst *in = (fmu_inst *)(uintptr_t)spec;
    size_t fs = 0, view = view_size(in->m);
    if (!can(in) ||
        fmu_status(in, get_state(in), name(in, "GetFMUstate", "GetFMUState"), in->t) ||
        fmu_status(in, state_size(in, &fs),
                   name(in, "SerializedFMUstateSize", "SerializedFMUStateSize"), in->t))
        return RT_E_SNAPSHOT;
    if (fs > UINT32_MAX - view)
        return RT_E_CAPACITY;
    *n = (uint32_t)(view + fs);
    if (!buf)
        return RT_OK;
    if (*n > cap)
        return RT_E_CAPACITY;
    if (fmu_status(in, serialize(in, buf + view, fs),
                   name(in, "SerializeFMUstate", "SerializeFMUState"), in->t))
        return RT_E_SNAPSHOT;
    write_view(in, buf);
    return RT_OK;
}

rt_status fmu_restore(const void *spec, const uint8_t *buf, uint32_t n)
{
    fmu_inst *in = (fmu_inst *)(uintptr_t)spec;
    size_t view = view_size(in->m);
    if (!can(in) || n < view || buf[0] != FMU_M_CT)
        return RT_E_SNAPSHOT;
    if (fmu_status(in, deserialize(in, buf + view, n - view),
                   name(in, "DeSerializeFMUstate", "DeserializeFMUState"), in->t) ||
        fmu_status(in, set_state(in), name(in, "SetFMUstate", "SetFMUState"), in->t))
        return RT_E_SNAPSHOT;
    read_view(in, buf);
    return RT_OK;
}
