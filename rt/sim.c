/* sim.c - the tick: the background set's release, discrete updates at their sample
 * hits, each set's step on its fixed schedule, the background set's publication, then
 * what every set shows at the new time (rt/held.c) and its check; plus look-ups by name
 * and parameter changes.
 *
 * Time is the integer tick count times the base step, never an accumulated sum, so
 * t is the same bits after a million ticks on every target. */
#include "rti.h"

real_t rt_time(const rt_scene *sc, const rt_sim *sim)
{
    return rti_time(sc, sim);
}

/* are the outputs of blocks [b, e) finite (one range of y) */
static int outputs_finite(const rt_sim *sim, uint16_t b, uint16_t e)
{
    const uint16_t *off = sim->plan.y_off;
    return rt_all_finite(sim->state.y + off[b], off[e] - off[b]);
}

/* the first block of a set with new outputs whose outputs are not finite, or -1 (held
   outputs were checked when they were new; the background set's, published now, by its
   step: state.bg_nonfinite, rt/bg.c) */
static int nonfinite_output(const rt_scene *sc, const rt_sim *sim)
{
    int first = -1, bad = 0;
    for (uint8_t s = 0; s < sc->nsets; s++) { /* at once first; by block when one is not */
        if (!rti_at_tick(sim, s))
            continue;
        if (s == sim->plan.bg_set) {
            bad |= sim->state.bg_nonfinite >= 0;
            continue;
        }
        for (uint16_t k = sim->plan.blk_of[s], e; k < sim->plan.blk_of[s + 1];) {
            uint16_t b = rti_block_run(sim, s, &k, &e);
            bad |= !outputs_finite(sim, b, e);
        }
    }
    if (!bad)
        return -1;
    for (uint8_t s = 0; s < sc->nsets; s++) {
        if (!rti_at_tick(sim, s))
            continue;
        if (s == sim->plan.bg_set) {
            int b = sim->state.bg_nonfinite;
            first = b >= 0 && (first < 0 || b < first) ? b : first;
            continue;
        }
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

/* x[k+1] = f(x[k], u[k]) for every DSS block whose sample hits at this tick (eq. 5) */
static void discrete_updates(const rt_scene *sc, rt_sim *sim, real_t t)
{
    for (uint16_t b = sim->plan.dss_first; b < sim->plan.dss_end; b++) {
        /* a DSS block's period only is not 0 (rt/init.c): no kind to look up for others */
        uint32_t period = sim->plan.period[b];
        if (period == 0 || rti_tick_mod(sim->state.tick, period) != 0)
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

/* set s's step over its ratio of ticks from t, on the tick's schedule; returns its
   bit of the sets whose step's end evaluated their outputs at the new tick (rt/held.c) */
static uint32_t step_set(const rt_scene *sc, rt_sim *sim, uint8_t s, real_t t)
{
    uint32_t ratio = sc->sets[s].ratio, recall = 0;
    /* a set stepping over several ticks shows its outputs at this tick until its state
       reaches the next one: the step's evaluations overwrite them */
    rti_held_before_step(sim, s, ratio);
    uint64_t r0 = sim->stats.rhs_evals[s];
    if (sim->plan.set_flags[s] & RTI_SET_XPRED)
        rti_xset_predict(sc, sim, s, t, sim->plan.set_h[s]);
    if (!(sim->plan.set_flags[s] & RTI_SET_NO_STEP)) /* ending parts at time events */
        rti_tev_step(sc, sim, s, sim->state.tick, ratio);
    else /* nothing to integrate; a parameter change is taken */
        sim->state.param_changed[s] = 0, rti_tev_inside(sc, sim, s, sim->state.tick, ratio);
    rti_step_witness(sim, s, r0);
    sim->state.set_tick[s] = sim->state.tick + ratio;
    if (sim->plan.set_xout[s]) {
        real_t ts = rti_tick_time(sim->state.set_tick[s], sc->dt);
        rti_outputs(sc, sim, (rti_at){ts, s, RTI_IN_STEP});
        rti_xset_push(sc, sim, s, ts);
        /* y holds them until the renewal; a set over several ticks keeps them in y_end
           until its state reaches the tick (rt/held.c) */
        recall = (uint32_t)(ratio == 1) << s;
    }
    rti_held_after_step(sim, s, ratio);
    return recall;
}

/* fixed schedule: a set of the tick steps when the tick count is a multiple of its
   ratio, slowest first (rt/xset.c), and publishes its outputs for the other sets */
static uint32_t step_sets(const rt_scene *sc, rt_sim *sim, real_t t)
{
    uint32_t recall = 0;
    for (uint8_t i = 0; i < sc->nsets; i++) {
        uint8_t s = sim->plan.sched[i];
        if (rti_tick_mod(sim->state.tick, sc->sets[s].ratio) == 0 && !sc->sets[s].background)
            recall |= step_set(sc, sim, s, t);
    }
    return recall;
}

/* the outputs new at this tick are finite, else the first block that is not is counted */
static void check_outputs(const rt_scene *sc, rt_sim *sim)
{
    int bad = nonfinite_output(sc, sim);
    if (bad >= 0)
        rti_count(sim, RT_CNT_NAN, bad, RT_E_NAN);
}

rt_status rt_tick(const rt_scene *sc, rt_sim *sim)
{
    if (sim->state.tick >= sim->plan.n_ticks)
        return RT_E_DONE;
    real_t t = rti_time(sc, sim);
#if RT_FAULT_INJECT
    rti_fault_sim = sim;
#endif
    if (sc->bg) /* the background set's next step, from its communication point now */
        sc->bg->release(sc, sim);
    discrete_updates(sc, sim, t);
    uint32_t recall = step_sets(sc, sim, t);
    sim->state.tick++;
    if (sc->bg) /* the background step due now: before the other sets read its history */
        sc->bg->publish(sc, sim);
    rti_held_renew(sc, sim, recall); /* the sets whose state reached the new tick */
    check_outputs(sc, sim);
    return sim->state.tick >= sim->plan.n_ticks ? RT_E_DONE : RT_OK;
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

/* a multibody block's geometry or state changed before the first tick: its start is
   projected and judged again, as at rt_init (rt_refresh), not left to the first step's
   projection, which would move it silently */
static void mbs_changed(const rt_kind *k, rt_sim *sim)
{
    if (k->type == RT_KIND_MBS && sim->state.tick == 0)
        sim->state.mbs_restart = 1;
}

/* the largest constraint residual of block b's multibody set now (0: none) */
static real_t mbs_residual(const rt_scene *sc, const rt_sim *sim, uint16_t b)
{
    return sc->mbs && sc->blocks[b].kind->type == RT_KIND_MBS
               ? sc->mbs->signal(sc, sim, b, RT_MBS_SIG_RESIDUAL)
               : 0;
}

/* during the run, a parameter that moved a node (a body's joint point) puts its set off
   its constraints: the next projection moves the bodies back at once, a jump no step
   made. Past RT_INIT_TOL (and past the residual before) it is counted, with the block,
   and named, as a start that far off is */
static void mbs_moved(const rt_scene *sc, rt_sim *sim, uint16_t b, real_t before)
{
    real_t after = mbs_residual(sc, sim, b);
    if (!(after > (real_t)RT_INIT_TOL && after > before))
        return;
    char t1[RTI_REAL_TEXT];
    rti_count(sim, RT_CNT_INIT_MOVED, (int)b, RT_OK);
    rti_note(sim, "a parameter of ", sc->blocks[b].name, " put its set ", rti_real_text(t1, after),
             " m off its constraints: moved back at the next projection", (const char *)0);
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
        real_t old = p[i], before = sim->state.tick > 0 ? mbs_residual(sc, sim, (uint16_t)b) : 0;
        p[i] = value;
        /* a known time event must stay on the grid, in few enough parts (rt/tev.c) */
        if ((k->check && k->check(p, k->spec) != RT_OK) ||
            rti_tev_check_block(sc, sim, (uint16_t)b) != RT_OK) {
            p[i] = old;
            return RT_E_PARAM;
        }
        sim->work.mbs.m_valid[b] = 0; /* a constant mass matrix is factored anew (#14) */
        if (value != old) /* and the set's Jacobian formed at its next step */
            sim->state.param_changed[sc->blocks[b].set] = 1;
        mbs_changed(k, sim);
        if (sim->state.tick > 0 && value != old)
            mbs_moved(sc, sim, (uint16_t)b, before);
        return RT_OK;
    }
    /* before the first tick, initial states can be set by name too */
    if (sim->state.tick == 0 && (i = name_index(k->x_names, k->nx, name)) >= 0) {
        sim->state.x[sim->plan.x_off[b] + i] = value;
        mbs_changed(k, sim);
        return RT_OK;
    }
    if (sim->state.tick == 0 && (i = name_index(k->d_names, k->nd, name)) >= 0) {
        sim->state.d[sim->plan.d_off[b] + i] = value;
        return RT_OK;
    }
    return RT_E_ARG;
}
