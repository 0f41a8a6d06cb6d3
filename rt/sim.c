/* sim.c - the tick: discrete updates at their sample hits, each set's step on its fixed
 * schedule, outputs at the new time; plus recording and look-ups by name.
 *
 * Time is the integer tick count times the base step, never an accumulated sum, so
 * t is the same bits after a million ticks on every target. */
#include "rti.h"

real_t rt_time(const rt_scene *sc, const rt_sim *sim)
{
    return (real_t)sim->state.tick * sc->dt;
}

/* do set s's outputs belong to the current tick: it has just stepped to it (each tick
   for a set of ratio 1), its background step was published at it (rt/bg.c), or the run
   is at its start? Between those ticks the outputs are held (docs/multirate.md) */
static int fresh(const rt_sim *sim, uint8_t s)
{
    return sim->state.set_tick[s] == sim->state.tick;
}

/* are the outputs of blocks [b, e) finite (one range of y) */
static int outputs_finite(const rt_sim *sim, uint16_t b, uint16_t e)
{
    const uint16_t *off = sim->plan.y_off;
    return rt_all_finite(sim->state.y + off[b], off[e] - off[b]);
}

/* the first block of a set with new outputs whose outputs are not finite, or -1 (held
   outputs were checked when they were new) */
static int nonfinite_output(const rt_scene *sc, const rt_sim *sim)
{
    int first = -1, bad = 0;
    for (uint8_t s = 0; s < sc->nsets; s++) { /* at once first; by block when one is not */
        if (!fresh(sim, s))
            continue;
        for (uint16_t k = sim->plan.blk_of[s], e; k < sim->plan.blk_of[s + 1];) {
            uint16_t b = rti_block_run(sim, s, &k, &e);
            bad |= !outputs_finite(sim, b, e);
        }
    }
    if (!bad)
        return -1;
    for (uint8_t s = 0; s < sc->nsets; s++) {
        if (!fresh(sim, s))
            continue;
        for (unsigned i = sim->plan.blk_of[s], i1 = sim->plan.blk_of[s + 1]; i < i1; i++) {
            uint16_t b = sim->plan.set_blk[i];
            if (first >= 0 && b > (unsigned)first)
                break; /* blocks ascend: an earlier set's find stands */
            if (!outputs_finite(sim, b, (uint16_t)(b + 1))) {
                first = (int)b;
                break;
            }
        }
    }
    return first;
}

/* does the set hold its outputs between ticks: it steps over several ticks or in the
   background */
static int held_set(const rt_set *st)
{
    return st->ratio > 1 || st->background;
}

/* is recorded (or exported) signal r held between its set's steps: a multibody signal
   (energy, residual, reaction: worth computing once) of a set that holds. Its value
   changes with the set's state only, so it is computed when the set's outputs are and
   held in state.held_sig: the recorded ones in record order, then the link's exported
   ones in export order (RT_MAX_HELD_SIG), so a controller reads what the trace shows */
static int held_sig(const rt_scene *sc, const rt_rec *r)
{
    return r->what == RT_SIG_MBS && held_set(&sc->sets[sc->blocks[r->block].set]);
}

/* held signals among n signals from r */
static uint16_t count_held(const rt_scene *sc, const rt_rec *r, uint16_t n)
{
    uint16_t k = 0;
    for (uint16_t i = 0; i < n; i++)
        k = (uint16_t)(k + held_sig(sc, &r[i]));
    return k;
}

int rti_set_holds(const rt_scene *sc, uint8_t s)
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

void rti_hold_signals(const rt_scene *sc, rt_sim *sim, uint8_t s)
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
    held_slots(sc, ctx, s, 0, ctx->state.bg_sig_new);
    ctx->state.tick = now;
#else
    (void)sc, (void)ctx, (void)s, (void)tick;
#endif
}

void rti_publish_signals(const rt_scene *sc, rt_sim *sim, const rt_sim *ctx, uint8_t s)
{
#if RT_MAX_HELD_SIG > 0
    held_slots(sc, sim, s, ctx->state.bg_sig_new, sim->state.held_sig);
#else
    (void)sc, (void)sim, (void)ctx, (void)s;
#endif
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

/* does the tick keep set s's root values from its step's end: a known time event of the
   set is due now (rt/tev.c), and those values are its left limit, so a root that crosses
   by the jump alone is seen by the next step, from its start, and located there */
static int keeps_roots(const rt_scene *sc, rt_sim *sim, uint8_t s)
{
    return (sim->plan.set_flags[s] & RTI_SET_TEV) && rti_tev_at(sc, sim, s, sim->state.tick);
}

/* outputs and roots of set s at the time of its state (and its held signals); renew: its
   step's end evaluated its outputs at this time already (for its history), so only the
   entries that may give something else now are called (RTI_RENEW); in_tick: rt_tick's */
static void refresh_set(const rt_scene *sc, rt_sim *sim, uint8_t s, int renew, int in_tick)
{
    real_t ts = (real_t)sim->state.set_tick[s] * sc->dt;
    rti_mode mode = renew ? RTI_RENEW
                  : sim->state.set_tick[s] == sim->state.tick ? RTI_AT_TICK : RTI_IN_STEP;
    rti_outputs(sc, sim, (rti_at){ts, s, mode});
    if (sim->plan.set_r[s + 1] > sim->plan.set_r[s] && !(in_tick && keeps_roots(sc, sim, s)))
        rti_roots(sc, sim, s, ts, sim->state.r + sim->plan.set_r[s]);
    if (sim->plan.set_flags[s] & RTI_SET_HELD_SIG)
        rti_hold_signals(sc, sim, s);
}

/* a set's outputs are computed when its state reaches the tick and held until its next
   step; a background set's change only when its step is published (rt/bg.c). Both are
   computed at the start */
static int refreshed(const rt_scene *sc, const rt_sim *sim, uint8_t s)
{
    return sim->state.tick == 0 || (!sc->sets[s].background && fresh(sim, s));
}

#if RT_MAX_HELD_Y > 0
/* copies the outputs of set s's blocks from one output vector to another */
static void copy_outputs(const rt_sim *sim, uint8_t s, const real_t *from,
                         real_t *to)
{
    for (uint16_t k = sim->plan.blk_of[s], e; k < sim->plan.blk_of[s + 1];) {
        uint16_t b = rti_block_run(sim, s, &k, &e);
        for (uint16_t j = sim->plan.y_off[b]; j < sim->plan.y_off[e]; j++)
            to[j] = from[j];
    }
}

/* set s's outputs: next := y (its step's end), y := held (what it shows until then) */
static void keep_next(rt_sim *sim, uint8_t s)
{
    real_t *y = sim->state.y, *next = sim->state.y_next;
    const real_t *held = sim->work.y_held;
    for (uint16_t k = sim->plan.blk_of[s], e; k < sim->plan.blk_of[s + 1];) {
        uint16_t b = rti_block_run(sim, s, &k, &e);
        for (uint16_t j = sim->plan.y_off[b]; j < sim->plan.y_off[e]; j++)
            next[j] = y[j], y[j] = held[j];
    }
}

/* set s's outputs from its step's end (state.y_next) back into y, but a sampled block's:
   its step's end does not evaluate them, and the link may have written one since (an
   import, rt_link_apply) */
static void take_next(const rt_scene *sc, rt_sim *sim, uint8_t s)
{
    for (uint16_t k = sim->plan.blk_of[s]; k < sim->plan.blk_of[s + 1]; k++) {
        uint16_t b = sim->plan.set_blk[k];
        if (sc->blocks[b].kind->type == RT_KIND_DSS)
            continue;
        for (uint16_t j = sim->plan.y_off[b]; j < sim->plan.y_off[b + 1]; j++)
            sim->state.y[j] = sim->state.y_next[j];
    }
}

/* does set s, reaching the tick now, renew its outputs from its step's end (state.y_next)
   rather than evaluate them: it keeps them (RTI_SET_NEXT) and no parameter of it changed
   since (imp_stale) */
static int renews_later(const rt_sim *sim, uint8_t s)
{
    return (sim->plan.set_flags[s] & RTI_SET_NEXT) && !sim->state.imp_stale[s];
}
#endif

/* the highest output index of a set the tick steps over several ticks (not in the
   background), plus one: what y_held must hold (RT_MAX_HELD_Y) */
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

/* rt_refresh; renew: a bit per set whose outputs its step's end evaluated at this time;
   in_tick: rt_tick's (rt_refresh evaluates every set in full) */
static void refresh(const rt_scene *sc, rt_sim *sim, uint32_t renew, int in_tick)
{
    for (uint8_t i = 0; i < sc->nsets; i++) {
        uint8_t s = sim->plan.rsched[i]; /* sampled sources before their readers */
        if (!refreshed(sc, sim, s))
            continue;
#if RT_MAX_HELD_Y > 0
        if (in_tick && renews_later(sim, s)) {
            take_next(sc, sim, s);
            renew |= 1u << s;
        }
#else
        (void)in_tick; /* no set steps over several ticks in the tick */
#endif
        refresh_set(sc, sim, s, ((renew >> s) & 1u) != 0, in_tick);
    }
}

rt_status rt_refresh(const rt_scene *sc, rt_sim *sim)
{
    refresh(sc, sim, 0, 0);
    /* before the first tick the history starts afresh (parameters may have changed), and
       the sets are refreshed once more so each reads the others' initial outputs rather
       than an empty history */
    if (sim->state.tick == 0 && sc->nsets > 1) {
        for (uint8_t s = 0; s < sc->nsets; s++) {
            sim->state.hist_n[s] = 0;
            rti_xset_push(sc, sim, s, 0);
        }
        for (uint8_t i = 0; i < sc->nsets; i++)
            refresh_set(sc, sim, sim->plan.rsched[i], 0, 0);
        for (uint8_t s = 0; s < sc->nsets; s++) {
            sim->state.hist_n[s] = 0;
            rti_xset_push(sc, sim, s, 0);
        }
        rti_xset_predict_reset(sim);
    }
    return RT_OK;
}

/* x[k+1] = f(x[k], u[k]) for every DSS block whose sample hits at this tick (eq. 5) */
static void discrete_updates(const rt_scene *sc, rt_sim *sim, real_t t)
{
    for (uint16_t b = sim->plan.dss_first; b < sim->plan.dss_end; b++) {
        /* a DSS block's period only is not 0 (rt/init.c): no kind to look up for others */
        uint32_t period = sim->plan.period[b];
        if (period == 0 || sim->state.tick % period != 0)
            continue;
        const rt_kind *k = sc->blocks[b].kind;
        real_t next[RT_MAX_D];
        rt_args a;
        rti_gather(sim, b, t);
        rti_args(sc, sim, b, t, sc->dt * (real_t)sim->plan.period[b], &a);
        k->update(&a, next);
        /* a non-finite next state (a NaN input at the sample) is not taken: the block
           keeps its discrete state, as a continuous set keeps its state (rt/step.c) */
        if (!rt_all_finite(next, k->nd)) {
            rti_count(sim, RT_CNT_NAN, (int)b, RT_E_NAN);
            continue;
        }
        real_t *d = sim->state.d + sim->plan.d_off[b];
        for (uint16_t i = 0, nd = k->nd; i < nd; i++)
            d[i] = next[i];
    }
}

rt_status rt_tick(const rt_scene *sc, rt_sim *sim)
{
    if (sim->state.tick >= sim->plan.n_ticks)
        return RT_E_DONE;
    real_t t = rt_time(sc, sim);
#if RT_FAULT_INJECT
    rti_fault_sim = sim;
#endif
    /* the background set's next step, from its communication point now (rt/bg.c) */
    if (sc->bg)
        sc->bg->release(sc, sim);
    discrete_updates(sc, sim, t);
    /* fixed schedule: a set steps when the tick count is a multiple of its ratio,
       slowest first (rt/xset.c), and publishes its outputs for the other sets */
    uint32_t renew = 0;
    for (uint8_t i = 0; i < sc->nsets; i++) {
        uint8_t s = sim->plan.sched[i];
        uint32_t ratio = sc->sets[s].ratio;
        if (sim->state.tick % ratio != 0 || sc->sets[s].background)
            continue;
        /* a set stepping over several ticks shows its outputs at this tick until its
           state reaches the next one: the step's evaluations (at its stages and its end,
           ahead of the tick) overwrite them, so they are kept aside */
#if RT_MAX_HELD_Y > 0
        if (ratio > 1)
            copy_outputs(sim, s, sim->state.y, sim->work.y_held);
#endif
        uint64_t r0 = sim->stats.rhs_evals[s];
        if (sim->plan.set_flags[s] & RTI_SET_XPRED)
            rti_xset_predict(sc, sim, s, t, sc->dt * (real_t)ratio);
        if (!(sim->plan.set_flags[s] & RTI_SET_STATIC)) /* ending parts at time events */
            rti_tev_step(sc, sim, s, sim->state.tick, ratio);
        else /* nothing to integrate; a parameter change is taken (renews_later) */
            sim->state.imp_stale[s] = 0;
        rti_step_witness(sim, s, r0);
        sim->state.set_tick[s] = sim->state.tick + ratio;
        if (sim->plan.set_xout[s]) {
            real_t ts = (real_t)sim->state.set_tick[s] * sc->dt;
            rti_outputs(sc, sim, (rti_at){ts, s, RTI_IN_STEP});
            rti_xset_push(sc, sim, s, ts);
            /* y holds them until the refresh; a set over several ticks keeps them in
               y_next until its state reaches the tick (renews_later) */
            renew |= (uint32_t)(ratio == 1) << s;
        }
#if RT_MAX_HELD_Y > 0
        if (ratio > 1) {
            if (sim->plan.set_flags[s] & RTI_SET_NEXT)
                keep_next(sim, s);
            else
                copy_outputs(sim, s, sim->work.y_held, sim->state.y);
        }
#endif
    }
    sim->state.tick++;
    /* the background step due at the new time: before the other sets read its history */
    if (sc->bg)
        sc->bg->publish(sc, sim);
    /* only the sets whose state reached the new tick are evaluated (and checked) */
    refresh(sc, sim, renew, 1);
    int bad = nonfinite_output(sc, sim);
    if (bad >= 0)
        rti_count(sim, RT_CNT_NAN, bad, RT_E_NAN);
    return sim->state.tick >= sim->plan.n_ticks ? RT_E_DONE : RT_OK;
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

/* every tick, every recorded value: an output (the common case) without a call */
void rt_record(const rt_scene *sc, rt_sim *sim, real_t *out)
{
    uint64_t h = rti_hash(sim->state.hash, rt_time(sc, sim));
    uint16_t slot = 0;
    const rt_rec *r = sc->recs, *end = r ? r + sc->nrecs : r; /* no records: NULL */
    const real_t *y = sim->state.y;
    const uint16_t *y_off = sim->plan.y_off;
    real_t discard = 0; /* no output buffer: every value lands here */
    int step = out != 0;
    out = out ? out : &discard;
    for (; r < end; r++, out += step) {
        real_t v;
        if (r->what == RT_SIG_Y)
            v = y[y_off[r->block] + r->index];
        else
            v = rec_value(sc, sim, r, &slot);
        *out = v;
        h = rti_hash(h, v);
    }
    sim->state.hash = h;
}

int rt_block_index(const rt_scene *sc, const char *name)
{
    for (uint16_t b = 0; b < sc->nblocks; b++)
        if (rt_streq(sc->blocks[b].name, name))
            return b;
    return -1;
}

/* index of name in a list of n names, or -1 */
static int name_index(const char *const *names, uint16_t n, const char *name)
{
    for (uint16_t i = 0; names && i < n; i++)
        if (rt_streq(names[i], name))
            return i;
    return -1;
}

int rt_param_index(const rt_kind *k, const char *name)
{
    return name_index(k->p_names, k->np, name);
}

rt_status rt_set_param(const rt_scene *sc, rt_sim *sim, const char *block, const char *name,
                       real_t value)
{
    int b = rt_block_index(sc, block);
    if (b < 0)
        return RT_E_ARG;
    const rt_kind *k = sc->blocks[b].kind;
    int i = rt_param_index(k, name);
    if (i >= 0) {
        real_t *p = sim->state.p + sim->plan.p_off[b];
        real_t old = p[i];
        p[i] = value;
        /* a known time event must stay on the grid, in few enough parts (rt/tev.c) */
        if ((k->check && k->check(p, k->spec) != RT_OK) ||
            rti_tev_check_block(sc, sim, (uint16_t)b) != RT_OK) {
            p[i] = old;
            return RT_E_PARAM;
        }
        sim->work.mbs.m_valid[b] = 0; /* a constant mass matrix is factored anew (#14) */
        if (value != old) /* and the set's Jacobian formed at its next step */
            sim->state.imp_stale[sc->blocks[b].set] = 1;
        return RT_OK;
    }
    /* before the first tick, initial states can be set by name too */
    if (sim->state.tick == 0 && (i = name_index(k->x_names, k->nx, name)) >= 0) {
        sim->state.x[sim->plan.x_off[b] + i] = value;
        return RT_OK;
    }
    if (sim->state.tick == 0 && (i = name_index(k->d_names, k->nd, name)) >= 0) {
        sim->state.d[sim->plan.d_off[b] + i] = value;
        return RT_OK;
    }
    return RT_E_ARG;
}
