/* held.c - what a set shows between its steps: the outputs and multibody signals a set
 * holds while it steps over several ticks or in the background, their renewal when its
 * state reaches the tick, and recording (docs/multirate.md, "Held outputs").
 *
 * A set of ratio 1 steps to every tick and shows its outputs there. A set of ratio n > 1
 * shows, between its steps, its outputs at the tick its state belongs to: its step's
 * evaluations overwrite them in state.y, so they are kept aside in work.y_shown for the
 * step and put back after it. If other sets read it, its step's end evaluates its
 * outputs for its history, ahead of the tick: they wait in state.y_end and are taken
 * when its state reaches the tick, with only the sequence entries that may give
 * something else now called again (RTI_AT_TICK_RECALL). A background set's outputs
 * change when its step is published (rt/bg.c). Recorded and exported multibody signals
 * of such sets (energy, residual, reactions) are computed with their outputs and held in
 * state.held_sig, so recording and the controller link show what the trace shows. */
#include "rti.h"

/* does the set hold its outputs between ticks: it steps over several ticks or in the
   background */
static int holds_outputs(const rt_set *st)
{
    return st->ratio > 1 || st->background;
}

/* ------------------------------------------------------------------ held signals */

/* is recorded (or exported) signal r held between its set's steps: a multibody signal
   (energy, residual, reaction: worth computing once) of a set that holds. Its value
   changes with the set's state only, so it is computed when the set's outputs are and
   held in state.held_sig: the recorded ones in record order, then the link's exported
   ones in export order (RT_MAX_HELD_SIG), so a controller reads what the trace shows */
static int held_sig(const rt_scene *sc, const rt_rec *r)
{
    return r->what == RT_SIG_MBS && holds_outputs(&sc->sets[sc->blocks[r->block].set]);
}

/* held signals among n signals from r */
static uint16_t count_held(const rt_scene *sc, const rt_rec *r, uint16_t n)
{
    uint16_t k = 0;
    for (uint16_t i = 0; i < n; i++)
        k = (uint16_t)(k + held_sig(sc, &r[i]));
    return k;
}

/* does set s hold a recorded or exported signal between its steps */
static int holds_signals(const rt_scene *sc, uint8_t s)
{
    const rt_rec *lists[2] = {sc->recs, sc->link ? sc->link->exp : 0};
    uint16_t n[2] = {sc->nrecs, sc->link ? sc->link->nexp : 0};
    for (int l = 0; l < 2; l++)
        for (uint16_t i = 0; i < n[l]; i++)
            if (held_sig(sc, &lists[l][i]) && sc->blocks[lists[l][i].block].set == s)
                return 1;
    return 0;
}

uint16_t rti_held_sigs(const rt_scene *sc)
{
    return (uint16_t)(count_held(sc, sc->recs, sc->nrecs) +
                      (sc->link ? count_held(sc, sc->link->exp, sc->link->nexp) : 0));
}

real_t rti_sig_value(const rt_scene *sc, const rt_sim *sim, const rt_rec *r)
{
    switch (r->what) {
    case RT_SIG_X:
        return sim->state.x[sim->plan.x_off[r->block] + r->index];
    case RT_SIG_D:
        return sim->state.d[sim->plan.d_off[r->block] + r->index];
    case RT_SIG_MBS: /* energy, residuals, reactions (rt/mbs.c) */
        return sc->mbs ? sc->mbs->signal(sc, sim, r->block, r->index) : 0;
    default:
        return sim->state.y[sim->plan.y_off[r->block] + r->index];
    }
}

#if RT_MAX_HELD_SIG > 0
/* set s's held signals among n signals from r, slot by slot from `slot` into dst: copied
   from the same slots of src, or computed at sim's state when src is NULL; returns the
   slot after them */
static uint16_t held_walk(const rt_scene *sc, const rt_sim *sim, uint8_t s, const rt_rec *r,
                          uint16_t n, const real_t *src, real_t *dst, uint16_t slot)
{
    for (uint16_t i = 0; i < n; i++) {
        if (!held_sig(sc, &r[i]))
            continue;
        if (sc->blocks[r[i].block].set == s)
            dst[slot] = src ? src[slot] : rti_sig_value(sc, sim, &r[i]);
        slot++;
    }
    return slot;
}

/* set s's held signals, recorded then exported */
static inline void held_slots(const rt_scene *sc, const rt_sim *sim, uint8_t s, const real_t *src,
                              real_t *dst)
{
    uint16_t slot = held_walk(sc, sim, s, sc->recs, sc->nrecs, src, dst, 0);
    if (sc->link)
        held_walk(sc, sim, s, sc->link->exp, sc->link->nexp, src, dst, slot);
}
#endif

/* set s's held signals at its state now, into held_sig */
static void hold_signals(const rt_scene *sc, rt_sim *sim, uint8_t s)
{
#if RT_MAX_HELD_SIG > 0
    held_slots(sc, sim, s, 0, sim->state.held_sig);
#else
    (void)sc, (void)sim, (void)s;
#endif
}

void rti_hold_bg_signals(const rt_scene *sc, rt_sim *ctx, uint8_t s, uint64_t tick)
{
#if RT_MAX_HELD_SIG > 0
    uint64_t now = ctx->state.tick; /* the signals' time: the step's end */
    ctx->state.tick = tick;
    held_slots(sc, ctx, s, 0, ctx->state.bg_result_sig);
    ctx->state.tick = now;
#else
    (void)sc, (void)ctx, (void)s, (void)tick;
#endif
}

void rti_publish_signals(rt_sim *sim, const rt_sim *ctx)
{
#if RT_MAX_HELD_SIG > 0
    for (uint16_t k = 0; k < sim->plan.nbg_sig; k++) {
        uint16_t i = sim->plan.bg_sig[k];
        sim->state.held_sig[i] = ctx->state.bg_result_sig[i];
    }
#else
    (void)sim, (void)ctx;
#endif
}

uint16_t rti_held_slots(const rt_scene *sc, uint8_t s, uint16_t *slots)
{
    const rt_rec *lists[2] = {sc->recs, sc->link ? sc->link->exp : 0};
    uint16_t n[2] = {sc->nrecs, sc->link ? sc->link->nexp : 0}, slot = 0, k = 0;
    for (int l = 0; l < 2; l++)
        for (uint16_t i = 0; i < n[l]; i++) {
            if (!held_sig(sc, &lists[l][i]))
                continue;
            if (sc->blocks[lists[l][i].block].set == s)
                slots[k++] = slot;
            slot++;
        }
    return k;
}

real_t rti_export_value(const rt_scene *sc, const rt_sim *sim, uint16_t i)
{
    const rt_rec *r = &sc->link->exp[i];
#if RT_MAX_HELD_SIG > 0
    if (held_sig(sc, r))
        return sim->state.held_sig[count_held(sc, sc->recs, sc->nrecs) +
                                   count_held(sc, sc->link->exp, i)];
#endif
    return rti_sig_value(sc, sim, r);
}

/* ------------------------------------------------------------------ held outputs */

/* the highest output index of a set the tick steps over several ticks (not in the
   background), plus one: what y_shown must hold (RT_MAX_HELD_Y) */
uint16_t rti_held_top(const rt_scene *sc, const rt_sim *sim)
{
    uint16_t top = 0;
    for (uint16_t b = 0; b < sc->nblocks; b++) {
        const rt_set *st = &sc->sets[sc->blocks[b].set];
        if (st->ratio > 1 && !st->background && sim->plan.y_off[b + 1] > top)
            top = sim->plan.y_off[b + 1];
    }
    return top;
}

rt_status rti_held_plan(const rt_scene *sc, rt_sim *sim)
{
    for (uint16_t i = 0; i < sc->nrecs && i < RT_MAX_REC; i++) {
        const rt_rec *r = &sc->recs[i];
        sim->plan.rec_y[i] = r->what == RT_SIG_Y
                                 ? (uint16_t)(sim->plan.y_off[r->block] + r->index)
                                 : RTI_REC_OTHER;
    }
    for (uint8_t s = 0; s < sc->nsets; s++) {
        if (holds_signals(sc, s))
            sim->plan.set_flags[s] |= RTI_SET_HOLDS_SIG;
        if (sc->sets[s].ratio > 1 && !sc->sets[s].background && sim->plan.set_xout[s])
            sim->plan.set_flags[s] |= RTI_SET_KEEPS_END;
    }
    return RT_OK;
}

#if RT_MAX_HELD_Y > 0
/* copies the outputs of set s's blocks from one output vector to another */
static void copy_outputs(const rt_sim *sim, uint8_t s, const real_t *from, real_t *to)
{
    for (uint16_t k = sim->plan.blk_of[s], e; k < sim->plan.blk_of[s + 1];) {
        uint16_t b = rti_block_run(sim, s, &k, &e);
        for (uint16_t j = sim->plan.y_off[b]; j < sim->plan.y_off[e]; j++)
            to[j] = from[j];
    }
}

/* set s's outputs: y_end := y (its step's end), y := y_shown (what it shows until then) */
static void keep_step_end(rt_sim *sim, uint8_t s)
{
    real_t *y = sim->state.y, *end = sim->state.y_end;
    const real_t *shown = sim->work.y_shown;
    for (uint16_t k = sim->plan.blk_of[s], e; k < sim->plan.blk_of[s + 1];) {
        uint16_t b = rti_block_run(sim, s, &k, &e);
        for (uint16_t j = sim->plan.y_off[b]; j < sim->plan.y_off[e]; j++)
            end[j] = y[j], y[j] = shown[j];
    }
}

/* set s's outputs from its step's end (state.y_end) back into y, but a sampled block's:
   its step's end does not evaluate them, and the link may have written one since (an
   import, rt_link_apply) */
static void take_step_end(const rt_scene *sc, rt_sim *sim, uint8_t s)
{
    for (uint16_t k = sim->plan.blk_of[s]; k < sim->plan.blk_of[s + 1]; k++) {
        uint16_t b = sim->plan.set_blk[k];
        if (sc->blocks[b].kind->type == RT_KIND_DSS)
            continue;
        for (uint16_t j = sim->plan.y_off[b]; j < sim->plan.y_off[b + 1]; j++)
            sim->state.y[j] = sim->state.y_end[j];
    }
}

/* does set s, reaching the tick now, take its outputs from its step's end (state.y_end)
   rather than evaluate them: it keeps them (RTI_SET_KEEPS_END) and no parameter of it
   changed since */
static int takes_step_end(const rt_sim *sim, uint8_t s)
{
    return (sim->plan.set_flags[s] & RTI_SET_KEEPS_END) && !sim->state.param_changed[s];
}
#endif

void rti_held_before_step(rt_sim *sim, uint8_t s, uint32_t ratio)
{
#if RT_MAX_HELD_Y > 0
    if (ratio > 1)
        copy_outputs(sim, s, sim->state.y, sim->work.y_shown);
#else
    (void)sim, (void)s, (void)ratio;
#endif
}

void rti_held_after_step(rt_sim *sim, uint8_t s, uint32_t ratio)
{
#if RT_MAX_HELD_Y > 0
    if (ratio == 1)
        return;
    if (sim->plan.set_flags[s] & RTI_SET_KEEPS_END)
        keep_step_end(sim, s);
    else
        copy_outputs(sim, s, sim->work.y_shown, sim->state.y);
#else
    (void)sim, (void)s, (void)ratio;
#endif
}

/* ------------------------------------------------------------------ renewal at the tick */

/* does the tick keep set s's root values from its step's end: a known time event of the
   set is due now (rt/tev.c), and those values are its left limit, so a root that crosses
   by the jump alone is seen by the next step, from its start, and located there */
static int keeps_roots(const rt_scene *sc, rt_sim *sim, uint8_t s)
{
    return (sim->plan.set_flags[s] & RTI_SET_TEV) && rti_tev_at(sc, sim, s, sim->state.tick);
}

/* set s's roots recomputed at a tick (r) after an input jumped there (another set's new
   point, a sampled block's update): a root that crossed from its step's end (r0) by the
   jump alone keeps its value there, the left limit, and the set is marked (r_kept): its
   next step fires it at its start, the tick (the step would start past it otherwise,
   and the event be lost). How long before the tick it may have crossed (the
   longest interval of a source from another set over which the jump built up, 0 for a
   sampled block's or a known instant's) is kept in state.r_late for its event */
static void keep_jumped(const rt_scene *sc, rt_sim *sim, uint8_t s, const real_t *r0, real_t *r)
{
    uint16_t n = 0, base = sim->plan.set_r[s];
    int any = 0;
    for (uint16_t k = sim->plan.blk_of[s]; k < sim->plan.blk_of[s + 1]; k++) {
        const rt_kind *kd = sc->blocks[sim->plan.set_blk[k]].kind;
        for (uint16_t i = 0; i < kd->nr; i++, n++)
            if (rti_root_crossed(kd, i, r0[n], r[n], sim->state.r_lvl[base + n],
                                 sim->state.r_side[base + n]))
                r[n] = r0[n], any = 1;
    }
    sim->state.r_kept[s] = (uint8_t)any;
    sim->state.r_late[s] = any ? rti_xset_late(sc, sim, s) : 0;
}

/* set s's roots at the run's start (r): one of a kind whose roots are its mode's
   conditions (rt_kind.roots_at_start) that starts past its level, directional and free,
   is taken to start a hair before it, and the set marked as after a jump (r_kept): its
   first step fires the handler at t = 0, before any integration (a relay started on
   with its input below its switch-off level switches off; without this, never) */
static void start_past(const rt_scene *sc, rt_sim *sim, uint8_t s, real_t *r)
{
    uint16_t n = 0, base = sim->plan.set_r[s];
    sim->state.r_kept[s] = 0, sim->state.r_late[s] = 0; /* (this evaluation's decide) */
    for (uint16_t k = sim->plan.blk_of[s]; k < sim->plan.blk_of[s + 1]; k++) {
        const rt_kind *kd = sc->blocks[sim->plan.set_blk[k]].kind;
        for (uint16_t i = 0; i < kd->nr; i++, n++) {
            int dir = kd->root_dir ? kd->root_dir[i] : 0;
            if (kd->roots_at_start && dir != 0 && (real_t)dir * r[n] > 0 &&
                sim->state.r_side[base + n] == 0 && sim->state.r_lvl[base + n] == 0)
                r[n] = (real_t)-dir * RTI_ROOT_HAIR, sim->state.r_kept[s] = 1;
        }
    }
}

/* outputs and roots of set s at the time of its state (and its held signals); recall:
   its step's end evaluated its outputs at this time already (for its history), so only
   the entries that may give something else now are called (RTI_AT_TICK_RECALL);
   in_tick: rt_tick's */
static void evaluate_set(const rt_scene *sc, rt_sim *sim, uint8_t s, int recall, int in_tick)
{
    real_t ts = rti_tick_time(sim->state.set_tick[s], sc->dt);
    /* the tick its state reaches (and the start, where rt_refresh shows parameters set
       before the first tick) is an instant of its kinds that take values at instants
       (rt_kind.instant: an FMU's discrete inputs, rt/tev.c): what another set published
       for it shows in the row, after the event that took it */
    if ((in_tick || sim->state.tick == 0) && (sim->plan.set_flags[s] & RTI_SET_INSTANT) &&
        rti_tev_instant(sc, sim, s, ts))
        recall = 0;
    rti_mode mode = recall ? RTI_AT_TICK_RECALL
                  : rti_at_tick(sim, s) ? RTI_AT_TICK : RTI_IN_STEP;
    rti_outputs(sc, sim, (rti_at){ts, s, mode});
    uint16_t r0 = sim->plan.set_r[s], nr = (uint16_t)(sim->plan.set_r[s + 1] - r0);
    if (nr > 0 && !(in_tick && keeps_roots(sc, sim, s))) {
        real_t before[RT_MAX_ROOTS];
        for (uint16_t i = 0; i < nr; i++)
            before[i] = sim->state.r[r0 + i];
        rti_roots(sc, sim, s, ts, sim->state.r + r0);
        if (in_tick)
            keep_jumped(sc, sim, s, before, sim->state.r + r0);
        else if (sim->state.tick == 0)
            start_past(sc, sim, s, sim->state.r + r0);
    }
    if (sim->plan.set_flags[s] & RTI_SET_HOLDS_SIG)
        hold_signals(sc, sim, s);
}

/* are set s's outputs evaluated now: its state has reached the tick (a background set's
   outputs change only when its step is published, rt/bg.c), or the run is at its start */
static int evaluated_now(const rt_scene *sc, const rt_sim *sim, uint8_t s)
{
    return sim->state.tick == 0 || (!sc->sets[s].background && rti_at_tick(sim, s));
}

/* the outputs of every set evaluated now; recall: a bit per set whose outputs its
   step's end evaluated at this time; in_tick: rt_tick's (rt_refresh evaluates every set
   in full) */
static void renew(const rt_scene *sc, rt_sim *sim, uint32_t recall, int in_tick)
{
    for (uint8_t i = 0; i < sc->nsets; i++) {
        uint8_t s = sim->plan.rsched[i]; /* sampled sources before their readers */
        if (!evaluated_now(sc, sim, s))
            continue;
#if RT_MAX_HELD_Y > 0
        if (in_tick && takes_step_end(sim, s)) {
            take_step_end(sc, sim, s);
            recall |= 1u << s;
        }
#endif
        evaluate_set(sc, sim, s, ((recall >> s) & 1u) != 0, in_tick);
    }
}

void rti_held_renew(const rt_scene *sc, rt_sim *sim, uint32_t recall)
{
    renew(sc, sim, recall, 1);
}

rt_status rt_refresh(const rt_scene *sc, rt_sim *sim)
{
    /* before the first tick the initial state is judged again as rt_init judged it, the
       counts of the last such judgement taken back first (work.count0), and the loops
       learn their signals' scales afresh (rt/loop.c): the parameters they were solved
       with at init may have changed */
    if (sim->state.tick == 0) { /* (start_past marks the sets with roots afresh) */
        for (int c = 0; sim->work.has0 && c < RT_CNT_COUNT; c++) {
            sim->stats.count[c] = sim->work.count0[c];
            if (sim->stats.count[c] == 0)
                sim->stats.last_block[c] = -1;
        }
        sim->stats.status = sim->work.has0 ? sim->work.status0 : sim->stats.status;
        for (int c = 0; c < RT_CNT_COUNT; c++)
            sim->work.count0[c] = sim->stats.count[c];
        sim->work.status0 = sim->stats.status, sim->work.has0 = 1;
        rt_status st = rti_check_starts(sc, sim);
        if (st == RT_OK && sim->state.mbs_restart && sc->mbs)
            st = (rt_status)sc->mbs->restart(sc, sim);
        if (st != RT_OK) /* refused again by another call: never run from it */
            return st;
        sim->state.mbs_restart = 0;
        rti_zero(sim->state.torn_range, sizeof sim->state.torn_range);
        rti_zero(sim->state.hist_ev, sizeof sim->state.hist_ev);
    }
    renew(sc, sim, 0, 0);
    /* before the first tick the history starts afresh (parameters may have changed), and
       the sets are evaluated once more so each reads the others' initial outputs rather
       than an empty history */
    if (sim->state.tick == 0 && sc->nsets > 1) {
        for (uint8_t s = 0; s < sc->nsets; s++) {
            sim->state.hist_n[s] = 0;
            rti_xset_push(sc, sim, s, 0);
        }
        for (uint8_t i = 0; i < sc->nsets; i++)
            evaluate_set(sc, sim, sim->plan.rsched[i], 0, 0);
        for (uint8_t s = 0; s < sc->nsets; s++) {
            sim->state.hist_n[s] = 0;
            rti_xset_push(sc, sim, s, 0);
        }
        rti_xset_predict_reset(sim);
    }
    return RT_OK;
}

/* ------------------------------------------------------------------ recording */

/* recorded signal r: the *slot-th held one if it is held (then *slot moves on) */
static real_t rec_value(const rt_scene *sc, const rt_sim *sim, const rt_rec *r, uint16_t *slot)
{
#if RT_MAX_HELD_SIG > 0
    if (held_sig(sc, r))
        return sim->state.held_sig[(*slot)++];
#else
    (void)slot;
#endif
    return rti_sig_value(sc, sim, r);
}

real_t rt_rec_value(const rt_scene *sc, const rt_sim *sim, uint16_t i)
{
    uint16_t slot = count_held(sc, sc->recs, i);
    return rec_value(sc, sim, &sc->recs[i], &slot);
}

const char *rt_rec_signal(const rt_scene *sc, uint16_t i)
{
    const rt_rec *r = &sc->recs[i];
    const rt_kind *k = sc->blocks[r->block].kind;
    if (r->what == RT_SIG_MBS)
        return sc->mbs ? sc->mbs->signal_name(sc, r->block, r->index) : "?";
    const char *const *names = r->what == RT_SIG_X ? k->x_names
                             : r->what == RT_SIG_D ? k->d_names : k->y_names;
    return names ? names[r->index] : "?";
}

/* every tick, every recorded value: an output (the common case) by its place in y, listed
   at init (rt_plan.rec_y); the records past RT_MAX_REC through the scene's table */
void rt_record(const rt_scene *sc, rt_sim *sim, real_t *out)
{
    uint64_t h = rti_hash(sim->state.hash, rti_time(sc, sim));
    uint16_t slot = 0, n = sc->nrecs, listed = n < RT_MAX_REC ? n : (uint16_t)RT_MAX_REC;
    const real_t *y = sim->state.y;
    const uint16_t *rec_y = sim->plan.rec_y;
    real_t discard = 0; /* no output buffer: every value lands here */
    int step = out != 0;
    out = out ? out : &discard;
    for (uint16_t i = 0; i < listed; i++, out += step) {
        uint16_t k = rec_y[i];
        real_t v = k != RTI_REC_OTHER ? y[k] : rec_value(sc, sim, &sc->recs[i], &slot);
        *out = v;
        h = rti_hash(h, v);
    }
    for (uint16_t i = listed; i < n; i++, out += step) { /* past the list: any kind */
        real_t v = rec_value(sc, sim, &sc->recs[i], &slot);
        *out = v;
        h = rti_hash(h, v);
    }
    sim->state.hash = h;
}
