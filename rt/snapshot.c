/* snapshot.c - snapshots of a run: the state part of rt_sim copied out, and copied back
 * in with what the plan and a background context derive from it made valid again
 * (rt_snapshot, rt_restore: an FMU's state save and restore, tests/whitebox/host/test_link.c). */
#include "rti.h"

void rt_snapshot(const rt_sim *sim, rt_state *out)
{
    *out = sim->state;
}

rt_status rt_restore(rt_sim *sim, const rt_state *in)
{
    /* with a context attached the step in flight is the context's, in no snapshot (and
       the context may be running it): only a state between steps can be restored there */
    if (sim->bg && (in->bg_busy || rt_bg_pending(sim) || sim->state.bg_busy))
        return RT_E_ARG;
    sim->state = *in;
    /* the parameters may differ: constant mass matrices are factored anew, and so is the
       background set's Jacobian, whose data a context kept and no snapshot holds */
    for (uint16_t b = 0; b < RT_MAX_BLOCKS; b++)
        sim->work.mbs.m_valid[b] = 0;
    if (sim->bg && sim->plan.bg_set >= 0) {
        sim->state.param_changed[sim->plan.bg_set] = 1;
        return rt_bg_attach(sim->sc, sim, sim->bg); /* the context from the restored state */
    }
    return RT_OK;
}
