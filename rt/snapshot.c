/* snapshot.c - snapshots of a run: the state part of rt_sim copied out, with the internal
 * state of the blocks whose kind keeps one (rt_kind.save: an FMU's) appended in block
 * order, and copied back in with what the plan and a background context derive from it
 * made valid again (rt_snapshot, rt_restore: an FMU's state save and restore,
 * tests/whitebox/host/test_link.c, tests/whitebox/rt/test_sim.c, tests/fmi/snap.c). */
#include "rti.h"

/* a block's size word when its save failed: no restore takes such a snapshot */
#define RTI_KSTATE_BAD 0xffffffffu

static void put32(uint8_t *p, uint32_t v)
{
    for (int i = 0; i < 4; i++)
        p[i] = (uint8_t)(v >> (8 * i));
}

static uint32_t get32(const uint8_t *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

/* the kinds' states into buf (cap bytes): per block with a save, its size and its bytes */
rt_status rt_kinds_save(const rt_scene *sc, uint8_t *buf, uint32_t cap)
{
    uint32_t at = 0;
    for (uint16_t b = 0; b < sc->nblocks; b++) {
        const rt_kind *k = sc->blocks[b].kind;
        uint32_t n = 0;
        if (!k->save)
            continue;
        if (cap - at < 4) { /* no room for its size: the kind's own reason first, if any */
            rt_status st = k->save(k->spec, (uint8_t *)0, 0, &n);
            if (cap >= 4)
                put32(buf, RTI_KSTATE_BAD); /* (the first size word marks it) */
            return st != RT_OK ? st : RT_E_CAPACITY;
        }
        rt_status st = k->save(k->spec, buf + at + 4, cap - at - 4, &n);
        if (st == RT_OK && n > cap - at - 4)
            st = RT_E_CAPACITY;
        put32(buf + at, st == RT_OK ? n : RTI_KSTATE_BAD);
        if (st != RT_OK)
            return st;
        at += 4 + n;
    }
    return RT_OK;
}

/* the name in parentheses: rt_sim.h's rt_snapshot macro does not expand here */
rt_status (rt_snapshot)(const rt_sim *sim, rt_state *out)
{
    return rt_snapshot_checked(sim, out, RT_SIM_LAYOUT);
}

rt_status rt_snapshot_checked(const rt_sim *sim, rt_state *out, uint32_t caller_layout)
{
    if (caller_layout != RT_SIM_LAYOUT) /* out may be smaller than this build's rt_state */
        return RT_E_ARG;
    *out = sim->state;
#if RT_MAX_KSTATE > 0
    return rt_kinds_save(sim->sc, out->kstate, RT_MAX_KSTATE);
#else
    return rt_kinds_save(sim->sc, (uint8_t *)0, 0);
#endif
}

/* every block with a restore finds a whole state of its own in buf (cap bytes)? */
static int kinds_fit(const rt_scene *sc, const uint8_t *buf, uint32_t cap)
{
    uint32_t at = 0;
    for (uint16_t b = 0; b < sc->nblocks; b++) {
        if (!sc->blocks[b].kind->restore)
            continue;
        if (cap - at < 4)
            return 0;
        uint32_t n = get32(buf + at);
        if (n == RTI_KSTATE_BAD || n > cap - at - 4)
            return 0;
        at += 4 + n;
    }
    return 1;
}

/* the kinds' states back from buf, where kinds_fit found them whole */
static rt_status restore_kinds(const rt_scene *sc, const uint8_t *buf)
{
    rt_status st = RT_OK;
    uint32_t at = 0;
    for (uint16_t b = 0; b < sc->nblocks; b++) {
        const rt_kind *k = sc->blocks[b].kind;
        if (!k->restore)
            continue;
        uint32_t n = get32(buf + at);
        if (k->restore(k->spec, buf + at + 4, n) != RT_OK)
            st = RT_E_SNAPSHOT; /* the others are still restored: each FMU counts its own */
        at += 4 + n;
    }
    return st;
}

rt_status rt_kinds_restore(const rt_scene *sc, const uint8_t *buf, uint32_t cap)
{
    return kinds_fit(sc, buf, cap) ? restore_kinds(sc, buf) : RT_E_SNAPSHOT;
}

/* the name in parentheses: rt_sim.h's rt_restore macro does not expand here */
rt_status (rt_restore)(rt_sim *sim, const rt_state *in)
{
    return rt_restore_checked(sim, in, RT_SIM_LAYOUT);
}

rt_status rt_restore_checked(rt_sim *sim, const rt_state *in, uint32_t caller_layout)
{
    if (caller_layout != RT_SIM_LAYOUT) /* in may be smaller than this build's rt_state */
        return RT_E_ARG;
    /* with a context attached the step in flight is the context's, in no snapshot (and
       the context may be running it): only a state between steps can be restored there */
    if (sim->bg && (in->bg_busy || rt_bg_pending(sim) || sim->state.bg_busy))
        return RT_E_ARG;
#if RT_MAX_KSTATE > 0
    if (!kinds_fit(sim->sc, in->kstate, RT_MAX_KSTATE))
        return RT_E_SNAPSHOT;
#else
    if (!kinds_fit(sim->sc, (const uint8_t *)0, 0))
        return RT_E_SNAPSHOT;
#endif
    sim->state = *in;
    /* the parameters may differ: constant mass matrices are factored anew, and so is the
       background set's Jacobian, whose data a context kept and no snapshot holds */
    for (uint16_t b = 0; b < RT_MAX_BLOCKS; b++)
        sim->work.mbs.m_valid[b] = 0;
    rt_status st = RT_OK;
#if RT_MAX_KSTATE > 0
    st = restore_kinds(sim->sc, in->kstate);
#endif
    if (sim->bg && sim->plan.bg_set >= 0) {
        sim->state.param_changed[sim->plan.bg_set] = 1;
        rt_status a = rt_bg_attach(sim->sc, sim, sim->bg); /* the context from the restored state */
        return st != RT_OK ? st : a;
    }
    return st;
}
