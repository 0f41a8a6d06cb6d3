/* describe.c - what rt_init decided, for tools that print or size a scene (`modrt info`,
 * `modrt sizes`, the tuner, the scene compiler), and what a run shows (its tick, trace
 * hash, outputs, states and stats): read-only accessors, so that nothing outside rt/
 * reads rt_sim's layout (rt_sim.h), which is the runtime's own business. */
#include "rti_mbs.h"

uint8_t rt_set_at(const rt_sim *sim, uint8_t i)
{
    return sim->plan.sched[i];
}

uint16_t rt_set_nx(const rt_sim *sim, uint8_t set)
{
    return rti_set_nx(sim, set);
}

rt_step_work rt_step_bound(const rt_scene *sc, uint8_t s, uint16_t n)
{
    rt_step_work w = {0, 0};
    const rt_integrator *m = sc->sets[s].method;
    m->bound(m, &sc->sets[s].cfg, n, &w);
    return w;
}

/* inputs of set s whose extrapolation the coupling monitor checks (rt/xset.c) */
static uint32_t checked_inputs(const rt_scene *sc, const rt_sim *sim, uint8_t s)
{
    (void)sc;
#if RT_MAX_XPRED > 0
    return (uint32_t)(sim->plan.xpred_of[s + 1] - sim->plan.xpred_of[s]);
#else
    (void)sim, (void)s;
    return 0;
#endif
}

/* the method's bound times the method steps one step of the set can take: the step
   itself and, with roots, every located event's re-steps and the rest of the step after
   it (rt/step.c), with one probe per handled event (and one integration more where a
   root's every sign change counts, up to its return) and one trial of an excursion (with
   a probe where no earlier point serves), and after each event one more probe and trial
   (and its integration again in a multibody set);
   each part at a known time event again (rt/tev.c); and the coupling monitor's two right-hand sides per sensitivity,
   measured at most twice a step per checked input (rt/xset.c) */
rt_step_work rt_set_step_bound(const rt_scene *sc, const rt_sim *sim, uint8_t s)
{
    rt_step_work w = rt_step_bound(sc, s, rt_set_nx(sim, s));
    uint32_t steps = 1, probes = 0;
    uint32_t parts = (sim->plan.set_flags[s] & RTI_SET_TEV) ? RT_TEV_PARTS_MAX : 1;
    if (sim->plan.set_r[s + 1] > sim->plan.set_r[s]) {
        /* (and one trial of a root's excursion within the step, rt/step.c; a multibody
           set integrates its step again after a trial that found nothing) */
        steps += RT_EVENTS_PER_STEP_MAX * (RT_EVENT_ITER_MAX + 3u) + 2u;
        /* a root that returns within the probe ends the next integration there */
        if (sim->plan.set_flags[s] & RTI_SET_EVERY_SIGN)
            steps += RT_EVENTS_PER_STEP_MAX;
        probes = 2u * RT_EVENTS_PER_STEP_MAX + 2u;
        /* an event of a set reading other sets is judged: a probe before its handlers
           and the derivatives after them (rt/step.c, unsure_by) */
        if (sim->plan.set_flags[s] & RTI_SET_XPRED)
            probes += 2u * RT_EVENTS_PER_STEP_MAX;
    }
    w.rhs = parts * (steps * w.rhs + probes) + 4u * checked_inputs(sc, sim, s);
    w.lu = parts * steps * w.lu;
    return w;
}

int rt_set_is_source(const rt_sim *sim, uint8_t set)
{
    return sim->plan.set_xout[set] != 0;
}

uint64_t rt_tick_count(const rt_sim *sim)
{
    return sim->plan.n_ticks;
}

rt_src_kind rt_input_source(const rt_sim *sim, uint16_t block, uint16_t u, rt_interp *interp)
{
    uint16_t gi = (uint16_t)(sim->plan.u_off[block] + u);
    if (interp)
        *interp = (rt_interp)sim->plan.interp[gi];
    return (rt_src_kind)sim->plan.src_kind[gi];
}

uint16_t rt_seq_count(const rt_sim *sim)
{
    return sim->plan.nseq;
}

rt_seq_step rt_seq_at(const rt_sim *sim, uint16_t i)
{
    return sim->plan.seq[i];
}

uint8_t rt_loop_count(const rt_sim *sim)
{
    return sim->plan.nloops;
}

const rt_loop *rt_loop_at(const rt_sim *sim, uint8_t l)
{
    return &sim->plan.loops[l];
}

uint16_t rt_loop_block(const rt_sim *sim, uint8_t l, uint16_t i)
{
    return sim->plan.loop_blocks[sim->plan.loops[l].first + i];
}

uint16_t rt_torn_count(const rt_sim *sim)
{
    return sim->plan.ntorn;
}

/* the block whose slice of off[] (size nblocks + 1) holds global index gi */
static uint16_t owner(const uint16_t *off, uint16_t nblocks, uint16_t gi)
{
    uint16_t b = 0;
    while (b + 1 < nblocks && off[b + 1] <= gi)
        b++;
    return b;
}

rt_torn rt_torn_at(const rt_scene *sc, const rt_sim *sim, uint16_t k)
{
    uint16_t gi = sim->plan.torn_in[k], src = sim->plan.torn_src[k];
    uint16_t to = owner(sim->plan.u_off, sc->nblocks, gi);
    uint16_t from = owner(sim->plan.y_off, sc->nblocks, src);
    return (rt_torn){from, (uint16_t)(src - sim->plan.y_off[from]), to,
                     (uint16_t)(gi - sim->plan.u_off[to])};
}

/* the multibody tables' exact sizes, from the tables init built */
static void mbs_sizes(const rt_scene *sc, const rt_sim *sim, rt_sizes *z)
{
    const rt_mbs_work *m = &sim->work.mbs;
    z->mbs_rows = z->mbs_touch = z->mbs_tw = z->mbs_ty = z->mbs_pairs = z->mbs_lnz = 0;
    z->mbs_m = z->mbs_jrows = z->mbs_jz = z->mbs_qt = 0;
    if (!sc->mbs)
        return;
    z->mbs_rows = m->rb[sc->nsets];
    z->mbs_lnz = m->lp[m->rb[sc->nsets]];
    z->mbs_touch = m->to[sc->nblocks];
    for (uint16_t b = 0; b < sc->nblocks; b++) {
        const rt_mbs_spec *sp = sc->blocks[b].kind->spec;
        if (sc->blocks[b].kind->type != RT_KIND_MBS)
            continue;
        uint16_t t = (uint16_t)(m->to[b + 1] - m->to[b]);
        z->mbs_tw = (uint16_t)(z->mbs_tw + t * sp->nz);
        if (!(sp->flags & RT_MBS_M_DIAG))
            z->mbs_ty = (uint16_t)(z->mbs_ty + t * sp->nz);
        z->mbs_pairs = (uint16_t)(z->mbs_pairs + t * (t + 1) / 2);
        z->mbs_m = (uint16_t)(z->mbs_m + rti_mbs_m_entries(sp)); /* factors (pivots) */
        if (!(sp->flags & RT_MBS_NODE_POINT) && sp->nz > z->mbs_jz)
            z->mbs_jz = sp->nz;
    }
    for (uint8_t s = 0; s < sc->nsets; s++) { /* qt of each set: its blocks' qo plus nq */
        uint16_t n = 0;
        for (uint16_t b = 0; b < sc->nblocks; b++) {
            const rt_mbs_spec *sp = sc->blocks[b].kind->spec;
            if (sc->blocks[b].kind->type == RT_KIND_MBS && sc->blocks[b].set == s &&
                (!(sp->flags & RT_MBS_K_CONST) || sp->kinb))
                n = (uint16_t)(m->qo[b] + sp->nq);
        }
        z->mbs_qt = n > z->mbs_qt ? n : z->mbs_qt;
    }
    for (uint16_t j = 0; j < sc->njoints; j++)
        z->mbs_jrows = (uint16_t)(z->mbs_jrows + sc->joints[j].kind->nc);
}

void rt_sizes_of(const rt_scene *sc, const rt_sim *sim, rt_sizes *z)
{
    uint16_t nb = sc->nblocks;
    z->blocks = nb;
    z->x = sim->plan.x_off[nb], z->d = sim->plan.d_off[nb];
    z->u = sim->plan.u_off[nb], z->y = sim->plan.y_off[nb], z->p = sim->plan.p_off[nb];
    z->roots = sim->plan.set_r[sc->nsets];
    z->sets = sc->nsets, z->recs = sc->nrecs, z->joints = sc->njoints;
    z->loops = sim->plan.nloops, z->torn = sim->plan.ntorn;
    z->implicit_n = z->transition_n = 0;
    for (uint8_t s = 0; s < sc->nsets; s++) {
        if (sc->sets[s].method->implicit && rt_set_nx(sim, s) > z->implicit_n)
            z->implicit_n = rt_set_nx(sim, s);
        if (sc->sets[s].method->linear && rt_set_nx(sim, s) > z->transition_n)
            z->transition_n = rt_set_nx(sim, s);
    }
    z->bg = (uint16_t)rti_bg_size(sc, sim);
    z->mbs_z = z->mbs_q = z->mbs_c = z->mbs_bz = 0;
    for (uint16_t b = 0; b < nb; b++) {
        const rt_kind *k = sc->blocks[b].kind;
        const rt_mbs_spec *m = k->spec;
        if (k->type == RT_KIND_MBS && m->nz > z->mbs_bz)
            z->mbs_bz = m->nz;
    }
    for (uint8_t s = 0; sc->mbs && s < sc->nsets; s++) {
        const rt_mbs_work *m = &sim->work.mbs;
        z->mbs_z = m->nz[s] > z->mbs_z ? m->nz[s] : z->mbs_z;
        z->mbs_q = m->nq[s] > z->mbs_q ? m->nq[s] : z->mbs_q;
        z->mbs_c = m->nc[s] > z->mbs_c ? m->nc[s] : z->mbs_c;
    }
    z->hist_y = z->event_x = 0;
    for (uint16_t v = 0; v < z->y && v < RT_MAX_HIST_Y; v++)
        if (sim->plan.xsrc[v])
            z->hist_y = (uint16_t)(v + 1);
    z->held_y = rti_held_top(sc, sim);
    z->held_sig = rti_held_sigs(sc);
    for (uint8_t s = 0; s < sc->nsets; s++)
        if (sim->plan.set_r[s + 1] > sim->plan.set_r[s] && rt_set_nx(sim, s) > z->event_x)
            z->event_x = rt_set_nx(sim, s);
    z->seq = sim->plan.nseq;
    z->xpred = rti_xset_npred(sc, sim);
    z->tev = 0;
    for (uint8_t s = 0; s < sc->nsets; s++)
        z->tev = (uint16_t)(z->tev + ((sim->plan.set_flags[s] & RTI_SET_TEV) != 0));
    uint32_t ks = 0; /* the kinds' internal states as they report them now */
    for (uint16_t b = 0; b < nb; b++) {
        const rt_kind *k = sc->blocks[b].kind;
        uint32_t n = 0;
        if (k->save && k->save(k->spec, (uint8_t *)0, 0, &n) == RT_OK)
            ks += 4 + n;
    }
    z->kstate = (uint16_t)(ks < 65535u ? ks : 65535u);
    z->loop_hist = 0;
    if (sim->plan.ntorn > 0)
        z->loop_hist = (uint16_t)((sc->loop_iter_max ? sc->loop_iter_max : RT_LOOP_ITER_MAX) + 1);
    mbs_sizes(sc, sim, z);
}

real_t rt_output(const rt_sim *sim, uint16_t block, uint16_t j)
{
    return sim->state.y[sim->plan.y_off[block] + j];
}

real_t rt_block_x(const rt_sim *sim, uint16_t block, uint16_t i)
{
    return sim->state.x[sim->plan.x_off[block] + i];
}

real_t rt_block_d(const rt_sim *sim, uint16_t block, uint16_t i)
{
    return sim->state.d[sim->plan.d_off[block] + i];
}

real_t rt_block_p(const rt_sim *sim, uint16_t block, uint16_t i)
{
    return sim->state.p[sim->plan.p_off[block] + i];
}

uint64_t rt_ticks_done(const rt_sim *sim)
{
    return sim->state.tick;
}

uint64_t rt_trace_hash(const rt_sim *sim)
{
    return sim->state.hash;
}

const rt_stats *rt_stats_of(const rt_sim *sim)
{
    return &sim->stats;
}
