/* link.c - the scene's link to an external controller, without any I/O: checks the link
 * description at init, reads exported signals and applies imported values. The transport
 * (UDP on POSIX, a UART or CAN driver on a board) is the application's: docs/link.md. */
#include "rti.h"

static int rec_ok(const rt_scene *sc, const rt_rec *r)
{
    if (r->block >= sc->nblocks)
        return 0;
    const rt_kind *k = sc->blocks[r->block].kind;
    switch (r->what) {
    case RT_SIG_Y: return r->index < k->ny;
    case RT_SIG_X: return r->index < k->nx;
    case RT_SIG_D: return r->index < k->nd;
    case RT_SIG_MBS: return sc->mbs != 0;
    default: return 0;
    }
}

/* the link names existing signals and a DSS import block whose discrete states and
   outputs are the imports (what the scene compiler generates for `import`) */
rt_status rti_link_check(const rt_scene *sc, rt_sim *sim)
{
    const rt_link *l = sc->link;
    if (!l)
        return RT_OK;
    if (l->period == 0 || (l->nexp && !l->exp) || (l->nimp && (!l->def || !l->policy)))
        return rti_fail(sim, RT_E_SCENE, "link ", l->name ? l->name : "?",
                        ": needs a period of at least one tick, its exports, defaults and "
                        "policies", (const char *)0);
    for (uint16_t i = 0; i < l->nexp; i++)
        if (!rec_ok(sc, &l->exp[i]))
            return rti_fail(sim, RT_E_SCENE, "link ", l->name,
                            ": an exported signal names no signal of the scene", (const char *)0);
    if (l->nimp == 0)
        return RT_OK;
    const rt_kind *k = l->block < sc->nblocks ? sc->blocks[l->block].kind : 0;
    if (!k || k->type != RT_KIND_DSS || k->nd != l->nimp || k->ny != l->nimp)
        return rti_fail(sim, RT_E_SCENE, "link ", l->name,
                        ": its import block must be a DSS block with one discrete state and "
                        "one output per import", (const char *)0);
    for (uint16_t i = 0; i < l->nimp; i++)
        if (l->policy[i] >= RT_LINK_POLICY_COUNT || !rt_isfinite(l->def[i]))
            return rti_fail(sim, RT_E_SCENE, "link ", l->name,
                            ": an import has an unknown policy or a non-finite default",
                            (const char *)0);
    return RT_OK;
}

int rt_link_due(const rt_scene *sc, const rt_sim *sim)
{
    return sc->link && rti_tick_mod(sim->state.tick, sc->link->period) == 0;
}

real_t rt_link_export(const rt_scene *sc, const rt_sim *sim, uint16_t i)
{
    /* a multibody signal of a set held between steps: its held value, as recorded */
    return sc->link && i < sc->link->nexp ? rti_export_value(sc, sim, i) : 0;
}

void rt_link_apply(const rt_scene *sc, rt_sim *sim, const real_t *v)
{
    const rt_link *l = sc->link;
    if (!l || l->nimp == 0)
        return;
    real_t *d = sim->state.d + sim->plan.d_off[l->block];
    real_t *y = sim->state.y + sim->plan.y_off[l->block];
    for (uint16_t i = 0; i < l->nimp; i++)
        d[i] = y[i] = v[i];
}
