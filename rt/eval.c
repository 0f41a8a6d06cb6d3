/* eval.c - evaluation of one scene instant: input gathering (y = P u, eq. 2), the output
 * sequence, root functions, and the right-hand side of a set (eqs. 3-5).
 *
 * This is the inner loop of every integrator stage: no searching, only the tables
 * rt_init computed. */
#include "rti.h"

RTI_NOIPA void rti_gather(rt_sim *sim, uint16_t b, real_t t)
{
    /* GCC 12 on AArch64 (-O2): ivopts builds the addresses of this loop from -7 * sim,
       the pure-const pass then takes them for NULL dereferences and deletes every call of
       this function as having no effect (every scene's inputs stay 0). Pointers and a
       size_t index avoided it for one layout of rt_sim, not for the next; RTI_NOIPA keeps
       the interprocedural passes away from it for good (see the cross tests). */
    const uint8_t *kind = sim->plan.src_kind;
    const uint16_t *src = sim->plan.src;
    real_t *u = sim->work.u;
    for (size_t i = sim->plan.u_off[b], end = sim->plan.u_off[b + 1]; i < end; i++) {
        switch (kind[i]) {
        case RT_SRC_Y:
        case RT_SRC_HELD:
            u[i] = sim->state.y[src[i]];
            break;
        case RT_SRC_TORN:
            u[i] = sim->state.torn_val[src[i]];
            break;
        case RT_SRC_XSET:
            u[i] = rti_xset_value(sim, src[i], sim->plan.src_set[i], sim->plan.interp[i], t,
                                  (uint16_t)b);
            break;
        default:
            u[i] = sim->plan.def[i];
            break;
        }
    }
}

/* a DSS block produces new outputs only at its sample hits */
static int dss_hit(const rt_sim *sim, uint16_t b, rti_mode mode)
{
    return (mode == RTI_AT_TICK || mode == RTI_AT_TICK_RECALL) &&
           rti_tick_mod(sim->state.tick, sim->plan.period[b]) == 0;
}

/* calls the output equation of block b (its lean one if lean, rt_kind.output_lean) */
static void call_output(const rt_scene *sc, rt_sim *sim, uint16_t b, rti_at at, int lean)
{
    const rt_kind *k = sc->blocks[b].kind;
    real_t h = 0; /* a sampled block's is its sample period */
    if (k->type == RT_KIND_DSS) {
        if (!dss_hit(sim, b, at.mode))
            return;
        h = sc->dt * (real_t)sim->plan.period[b];
    }
    rt_args a;
    if (k->feed != RT_FEED_NONE) /* no output reads an input: nothing to gather */
        rti_gather(sim, b, at.t);
    rti_args(sc, sim, b, at.t, h, &a);
    if (k->next_event) /* a switch in time: which side of it (rt/tev.c) */
        a.t_piece = rti_piece(sc, sim, k, at.t);
    (lean ? k->output_lean : k->output)(&a, sim->state.y + sim->plan.y_off[b]);
#if RT_FAULT_INJECT
    if (rti_fault_due(RTI_FAULT_NAN) && rti_fault_plan.block == (int16_t)b && k->ny > 0)
        sim->state.y[sim->plan.y_off[b]] = (real_t)0 / (real_t)0;
#endif
}

void rti_run_calls(const rt_scene *sc, rt_sim *sim, uint16_t begin, uint16_t end, rti_at at)
{
    for (uint16_t s = begin; s < end; s++)
        call_output(sc, sim, sim->plan.seq[s].index, at, 0);
}

/* the set of sequence entry s: its block's, or for a loop its first block's (a loop lies
   in one set: cross-set edges are no algebraic dependency) */
static uint8_t entry_set(const rt_scene *sc, const rt_sim *sim, uint16_t s)
{
    const rt_seq_step *st = &sim->plan.seq[s];
    uint16_t b = st->kind == RT_SEQ_CALL ? st->index
                                         : sim->plan.loop_blocks[sim->plan.loops[st->index].first];
    return sc->blocks[b].set;
}


/* the sequence entry after entry s at the top level: a loop's calls follow its entry and
   are its solver's, not the walk's */
static uint16_t next_entry(const rt_sim *sim, uint16_t s)
{
    const rt_seq_step *st = &sim->plan.seq[s];
    return st->kind == RT_SEQ_LOOP ? sim->plan.loops[st->index].seq1 : (uint16_t)(s + 1);
}

/* each set's entries of the sequence, in sequence order, and its blocks, in block order */
static void set_lists(const rt_scene *sc, rt_sim *sim)
{
    uint16_t ne = 0, nb = 0;
    for (uint8_t set = 0; set < sc->nsets; set++) {
        sim->plan.seq_of[set] = ne;
        for (uint16_t s = 0; s < sim->plan.nseq; s = next_entry(sim, s))
            if (entry_set(sc, sim, s) == set)
                sim->plan.set_seq[ne++] = s;
        sim->plan.blk_of[set] = nb;
        for (uint16_t b = 0; b < sc->nblocks; b++)
            if (sc->blocks[b].set == set)
                sim->plan.set_blk[nb++] = b;
    }
    sim->plan.seq_of[sc->nsets] = ne;
    sim->plan.blk_of[sc->nsets] = nb;
}

/* does output j of kind k depend directly on any of its inputs */
static int fed(const rt_kind *k, uint16_t j)
{
    for (uint16_t i = 0; i < k->nu; i++)
        if (rti_feeds(k, j, i))
            return 1;
    return 0;
}

/* what a right-hand side reads of each block's outputs, live (RT_SRC_Y) from the block's
   own set: LIVE_ANY some output, LIVE_FED an output that depends on the block's inputs,
   LIVE_RICH one its lean output equation leaves out. Cross-set inputs read the history
   and sampled (DSS) outputs are held: neither needs a call in the right-hand side; nor
   does a sampled reader, which reads its inputs only at its sample hits, at a tick */
enum { LIVE_ANY = 1, LIVE_FED = 2, LIVE_RICH = 4 };
static void live_reads(const rt_scene *sc, const rt_sim *sim, uint8_t *live)
{
    for (uint16_t b = 0; b < sc->nblocks; b++)
        live[b] = 0;
    for (uint16_t b = 0; b < sc->nblocks; b++)
        for (uint16_t i = sim->plan.u_off[b]; i < sim->plan.u_off[b + 1]; i++) {
            if (sim->plan.src_kind[i] != RT_SRC_Y || sc->blocks[b].kind->type == RT_KIND_DSS)
                continue;
            uint16_t v = sim->plan.src[i], wb = rti_writer(sc, sim, v);
            if (sc->blocks[wb].set != sc->blocks[b].set)
                continue;
            const rt_kind *k = sc->blocks[wb].kind;
            uint16_t j = (uint16_t)(v - sim->plan.y_off[wb]);
            live[wb] |= LIVE_ANY;
            if (fed(k, j))
                live[wb] |= LIVE_FED;
            if (!k->output_lean || k->lean_skip[j])
                live[wb] |= LIVE_RICH;
        }
}

int rti_nonlinear_block(const rt_scene *sc, const rt_sim *sim, uint8_t set)
{
    for (uint16_t i = sim->plan.blk_of[set]; i < sim->plan.blk_of[set + 1]; i++) {
        uint16_t b = sim->plan.set_blk[i];
        const rt_kind *k = sc->blocks[b].kind;
        if (k->type == RT_KIND_DSS) /* its outputs hold between its sample hits */
            continue;
        if (!k->linear || k->type == RT_KIND_MBS)
            return b;
        for (uint16_t j = sim->plan.u_off[b]; j < sim->plan.u_off[b + 1]; j++)
            if (sim->plan.src_kind[j] == RT_SRC_TORN) /* a loop's solver is no matrix */
                return b;
    }
    return -1;
}

/* the rti_set_flag bits of set `set` */
static uint8_t set_flags(const rt_scene *sc, const rt_sim *sim, uint8_t set)
{
    uint8_t deriv = 0, autonomous = RTI_SET_AUTONOMOUS;
    for (uint16_t i = sim->plan.blk_of[set]; i < sim->plan.blk_of[set + 1]; i++) {
        uint16_t b = sim->plan.set_blk[i];
        const rt_kind *k = sc->blocks[b].kind;
        if (k->nx > 0 && k->deriv)
            deriv = RTI_SET_DERIV;
        if (k->type == RT_KIND_DSS) /* its outputs hold between its sample hits */
            continue;
        if (!k->autonomous)
            autonomous = 0;
        /* a history input changes over the step; a torn one is an actual loop's, whose
           solver carries its estimates from one evaluation to the next */
        for (uint16_t j = sim->plan.u_off[b]; j < sim->plan.u_off[b + 1]; j++)
            if (sim->plan.src_kind[j] == RT_SRC_XSET || sim->plan.src_kind[j] == RT_SRC_TORN)
                autonomous = 0;
    }
    return (uint8_t)(deriv | autonomous |
                     (rti_nonlinear_block(sc, sim, set) < 0 ? RTI_SET_LINEAR : 0));
}

/* rti_eval_plan's marks per block: called once in the sequence; called again by a renewal */
enum { SEEN_CALLED = 1, SEEN_RECALLED = 2 };

/* does a tick's renewal call block b again: sampled (its outputs change at sample hits,
   which the step's end evaluation does not call), or with throughput and an input that
   may have changed since that evaluation (another set's history or sampled output, a
   recalled block's output). One without throughput gives what it gave there. (A torn input is a
   loop's, whose entry a renewal always solves: recall_loop) */
static int recalled(const rt_scene *sc, const rt_sim *sim, uint16_t b, const uint8_t *seen)
{
    const rt_kind *k = sc->blocks[b].kind;
    if (k->type == RT_KIND_DSS)
        return 1;
    if (k->feed == RT_FEED_NONE)
        return 0;
    for (uint16_t j = sim->plan.u_off[b]; j < sim->plan.u_off[b + 1]; j++) {
        uint8_t src = sim->plan.src_kind[j];
        if (src == RT_SRC_XSET || src == RT_SRC_HELD)
            return 1;
        if (src == RT_SRC_Y && (seen[rti_writer(sc, sim, sim->plan.src[j])] & SEEN_RECALLED))
            return 1;
    }
    return 0;
}

/* a loop is solved again in a renewal; its blocks count as recalled for those after it */
static void recall_loop(const rt_sim *sim, uint16_t l, uint8_t *seen)
{
    const rt_loop *lp = &sim->plan.loops[l];
    for (uint16_t i = lp->first; i < lp->first + lp->nblocks; i++)
        seen[sim->plan.loop_blocks[i]] |= SEEN_RECALLED;
}

rt_status rti_eval_plan(const rt_scene *sc, rt_sim *sim)
{
    uint8_t live[RT_MAX_BLOCKS], seen[RT_MAX_BLOCKS];
    set_lists(sc, sim);
    live_reads(sc, sim, live);
    for (uint16_t b = 0; b < sc->nblocks; b++)
        seen[b] = 0;
    /* a block's first call gives the outputs that do not depend on its inputs; a repeated
       call (the sequence calls a block again once an algebraic chain has set its inputs,
       as lane_change's V1 after its driver) renews only those that do (its a_y), which
       the set may record but no right-hand side reads. A call whose readers read only
       what the kind's lean output equation gives calls that */
    for (uint16_t s = 0; s < sim->plan.nseq; s++) {
        const rt_seq_step *st = &sim->plan.seq[s];
        uint8_t *fl = &sim->plan.seq_flags[s];
        *fl = RTI_RHS_CALL;
        if (st->kind != RT_SEQ_CALL) {
            *fl |= RTI_SEQ_RECALL;
            recall_loop(sim, st->index, seen);
            continue;
        }
        uint8_t need = (seen[st->index] & SEEN_CALLED) ? LIVE_FED : LIVE_ANY;
        seen[st->index] |= SEEN_CALLED;
        /* a sampled block's outputs are held inside a step: its call would return */
        if (!(live[st->index] & need) || sc->blocks[st->index].kind->type == RT_KIND_DSS)
            *fl = RTI_RHS_SKIP;
        else if (!(live[st->index] & LIVE_RICH))
            *fl = RTI_RHS_LEAN;
        if (recalled(sc, sim, st->index, seen)) {
            *fl |= RTI_SEQ_RECALL;
            seen[st->index] |= SEEN_RECALLED;
        }
    }
    for (uint8_t set = 0; set < sc->nsets; set++) {
        sim->plan.set_flags[set] = set_flags(sc, sim, set);
        sim->plan.rhs_calls[set] = 0;
        for (uint16_t i = sim->plan.seq_of[set]; i < sim->plan.seq_of[set + 1]; i++)
            sim->plan.rhs_calls[set] = (uint16_t)(sim->plan.rhs_calls[set] +
                ((sim->plan.seq_flags[sim->plan.set_seq[i]] & RTI_SEQ_RHS) != RTI_RHS_SKIP));
        if (rti_set_nx(sim, set) == 0 && sim->plan.set_r[set + 1] == sim->plan.set_r[set] &&
            sim->plan.rhs_calls[set] == 0)
            sim->plan.set_flags[set] |= RTI_SET_NO_STEP;
        if (rti_xset_monitors(sc, sim, set))
            sim->plan.set_flags[set] |= RTI_SET_XPRED;
    }
    return RT_OK;
}

/* an actual loop: its solver runs the loop's segment until the torn inputs agree */
static void solve_loop(const rt_scene *sc, rt_sim *sim, const rt_seq_step *st, rti_at at)
{
    sc->loop_solver->solve(sc, sim, (uint8_t)st->index, at.t, (int)at.mode);
}

/* the entries of one set (plan.set_seq); in a right-hand side only the blocks whose
   outputs the set reads live (rti_rhs calls it only when there is one, plan.rhs_calls),
   in a renewal only those that may have changed */
static void set_outputs(const rt_scene *sc, rt_sim *sim, rti_at at)
{
    const uint8_t *fl = sim->plan.seq_flags;
    for (uint16_t i = sim->plan.seq_of[at.set]; i < sim->plan.seq_of[at.set + 1]; i++) {
        uint16_t s = sim->plan.set_seq[i];
        const rt_seq_step *st = &sim->plan.seq[s];
        if (at.mode == RTI_AT_TICK_RECALL && !(fl[s] & RTI_SEQ_RECALL))
            continue;
        if (st->kind == RT_SEQ_LOOP)
            solve_loop(sc, sim, st, at);
        else if (at.mode != RTI_IN_RHS)
            call_output(sc, sim, st->index, at, 0);
        else if ((fl[s] & RTI_SEQ_RHS) != RTI_RHS_SKIP)
            call_output(sc, sim, st->index, at, (fl[s] & RTI_SEQ_RHS) == RTI_RHS_LEAN);
    }
}

void rti_outputs(const rt_scene *sc, rt_sim *sim, rti_at at)
{
    if (at.set != RT_ALL_SETS) {
        if (!(sc->code && sc->code->outputs && sc->code->outputs(sc, sim, at.set, at.t, at.mode)))
            set_outputs(sc, sim, at); /* not written out for this scene (rt_scene_code) */
        return;
    }
    for (uint16_t s = 0; s < sim->plan.nseq; s = next_entry(sim, s)) {
        const rt_seq_step *st = &sim->plan.seq[s];
        if (st->kind == RT_SEQ_CALL)
            call_output(sc, sim, st->index, at, 0);
        else
            solve_loop(sc, sim, st, at);
    }
}

void rti_roots(const rt_scene *sc, rt_sim *sim, uint8_t s, real_t t, real_t *r)
{
    uint16_t n = 0;
    for (uint16_t i = sim->plan.blk_of[s]; i < sim->plan.blk_of[s + 1]; i++) {
        uint16_t b = sim->plan.set_blk[i];
        const rt_kind *k = sc->blocks[b].kind;
        if (k->nr == 0)
            continue;
        rt_args a;
        rti_gather(sim, b, t);
        rti_args(sc, sim, b, t, 0, &a);
        if (k->next_event)
            a.t_piece = rti_piece(sc, sim, k, t);
        k->roots(&a, r + n);
        n = (uint16_t)(n + k->nr);
    }
}

rt_status rti_rhs(void *ctx, real_t t, real_t *xdot)
{
    const rti_rhs_ctx *c = ctx;
    const rt_scene *sc = c->sc;
    rt_sim *sim = c->sim;
    uint8_t set = c->set;
    uint16_t base = sim->plan.set_x[set];

    sim->stats.rhs_evals[set]++;
    if (sc->code && sc->code->rhs && sc->code->rhs(sc, sim, set, t, c->h, xdot))
        return RT_OK; /* written out for this scene (rt_scene_code) */
    if (sim->plan.rhs_calls[set] > 0) /* else no output of the set is read live */
        set_outputs(sc, sim, (rti_at){t, set, RTI_IN_RHS});
    /* a multibody set's blocks have none (rti_mbs_accel gives their derivatives) */
    unsigned i1 = (sim->plan.set_flags[set] & RTI_SET_DERIV) ? sim->plan.blk_of[set + 1] : 0;
    for (unsigned i = sim->plan.blk_of[set]; i < i1; i++) {
        uint16_t b = sim->plan.set_blk[i];
        const rt_kind *k = sc->blocks[b].kind;
        if (k->nx == 0 || !k->deriv)
            continue;
        rt_args a;
        rti_gather(sim, b, t);
        rti_args(sc, sim, b, t, c->h, &a);
        if (k->next_event)
            a.t_piece = rti_piece(sc, sim, k, t);
        k->deriv(&a, xdot + (sim->plan.x_off[b] - base));
    }
    /* multibody blocks of the set are solved together (eqs. 6, 7b, 9) */
    if (sc->mbs && sim->work.mbs.nz[set] > 0)
        sc->mbs->accel(sc, sim, set, t, xdot);
    return RT_OK;
}

/* set s's earliest instant after t known only at run time (rt_kind.time_event: an FMU's
   nextEventTime, read from its own state; a defined system's comparison of t with a
   parameter); here, below rt/step.c and rt/tev.c, since both ask it (the parts of a
   step, an event that moves an instant) */
real_t rti_tev_dyn_next(const rt_scene *sc, rt_sim *sim, uint8_t s, real_t t)
{
    real_t tn = RT_TEV_NEVER;
    for (uint16_t k = sim->plan.blk_of[s]; k < sim->plan.blk_of[s + 1]; k++) {
        uint16_t b = sim->plan.set_blk[k];
        if (!sc->blocks[b].kind->time_event)
            continue;
        rt_args a;
        rti_args(sc, sim, b, t, 0, &a);
        real_t te = sc->blocks[b].kind->next_event(&a);
        tn = te < tn ? te : tn; /* (a NaN is no instant) */
    }
    return tn;
}
