/* invariant.c - the invariants a kind declares of its continuous state (rt_kind.inv:
 * nonnegative states, a conserved sum, a bounded norm), checked after every step of the
 * block's set, and the rules its initial state must keep (rt_kind.check_start), checked
 * at rt_init and again by rt_refresh before the first tick. A stiff solver can return
 * y1 = -4.36 for a concentration with a small error estimate; the kind knows better, and a broken invariant fails the run
 * (RT_CNT_INVARIANT with the block, RT_E_INVARIANT) instead of letting it pass as
 * doubtful. The check reads the state and changes nothing: a trace is the same with or
 * without declared invariants. */
#include "rti.h"

static real_t tol_of(const rt_invariant *v)
{
    return v->tol > 0 ? v->tol : RT_INV_TOL;
}

/* does x (the block's states) keep invariant v? NaN does not */
static int holds(const rt_invariant *v, const real_t *x)
{
    real_t tol = tol_of(v), acc = 0;
    switch (v->type) {
    case RT_INV_NONNEG:
        for (uint8_t i = 0; i < v->n; i++)
            if (!(x[v->x[i]] >= -tol))
                return 0;
        return 1;
    case RT_INV_SUM:
        for (uint8_t i = 0; i < v->n; i++)
            acc += x[v->x[i]];
        return rt_fabs(acc - v->c) <= tol;
    default: /* RT_INV_NORM */
        for (uint8_t i = 0; i < v->n; i++)
            acc += x[v->x[i]] * x[v->x[i]];
        return rt_sqrt(acc) <= v->c + tol;
    }
}

void rti_invariants(const rt_scene *sc, rt_sim *sim, uint8_t s)
{
    if (!((sim->plan.inv_sets >> s) & 1u)) /* no kind of the set declares one */
        return;
    for (unsigned k = sim->plan.blk_of[s], k1 = sim->plan.blk_of[s + 1]; k < k1; k++) {
        uint16_t b = sim->plan.set_blk[k];
        const rt_kind *kd = sc->blocks[b].kind;
        for (uint8_t i = 0; i < kd->ninv; i++)
            if (!holds(&kd->inv[i], sim->state.x + sim->plan.x_off[b])) {
                rti_count(sim, RT_CNT_INVARIANT, b, RT_E_INVARIANT);
                break; /* one count per block and step */
            }
    }
}

rt_status rti_check_starts(const rt_scene *sc, rt_sim *sim)
{
    for (uint16_t b = 0; b < sc->nblocks; b++) {
        const rt_kind *kd = sc->blocks[b].kind;
        rt_args a;
        if (!kd->check_start)
            continue;
        rti_args(sc, sim, b, 0, 0, &a);
        const char *why = kd->check_start(&a);
        if (why)
            return rti_fail(sim, RT_E_PARAM, "block ", sc->blocks[b].name,
                            ": initial state: ", why, (const char *)0);
    }
    return RT_OK;
}

rt_status rti_invariant_init(const rt_scene *sc, rt_sim *sim)
{
    sim->plan.inv_sets = 0;
    for (uint16_t b = 0; b < sc->nblocks; b++) {
        const rt_kind *kd = sc->blocks[b].kind;
        int ok = kd->ninv == 0 || kd->inv;
        for (uint8_t i = 0; ok && i < kd->ninv; i++) {
            const rt_invariant *v = &kd->inv[i];
            ok = v->type < RT_INV_COUNT && v->n > 0 && v->x && v->tol >= 0 &&
                 rt_isfinite(v->tol) && rt_isfinite(v->c);
            for (uint8_t j = 0; ok && j < v->n; j++)
                ok = v->x[j] < kd->nx;
        }
        if (!ok)
            return rti_fail(sim, RT_E_SCENE, "block ", sc->blocks[b].name, ": kind ", kd->name,
                            " declares an invariant with an unknown type, a state out of "
                            "range or a tolerance not finite and >= 0", (const char *)0);
        if (kd->ninv > 0)
            sim->plan.inv_sets |= 1u << sc->blocks[b].set;
    }
    return RT_OK;
}
