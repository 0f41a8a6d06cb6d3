/* bg.c - the background set: its step runs preemptible below the tick, with a rate
 * transition whose data dependencies are fixed (docs/multirate.md, "Background sets").
 *
 * The step of the background set S from kH to (k+1)H is released at the start of the
 * tick that begins at kH, and is due at the end of the tick that ends at (k+1)H. It reads
 * the other sets only as they stood at its release: their history up to kH and their
 * held (sampled) outputs, copied at release. The other sets read S only from its
 * history, which gains the point (k+1)H when the step is published, as the tick count
 * reaches (k+1)H; until then they extrapolate S from its points up to kH (rt/xset.c), and
 * the trace shows S's state at kH. Each side thus reads values fixed before the window in
 * which the step may run (a Jacobi coupling across the rate transition), so the trace is
 * a function of the data alone: the same whether the step runs at its release (the
 * simulated clock, inline in the tick), in PendSV between ticks or in a thread the ticks
 * preempt at any point.
 *
 * Without a background context the step runs inline at release in the tick's own
 * rt_sim, and its result (x slice and outputs) waits in rt_state.bg_result with the state
 * the trace shows left as it was. With a context attached (rt_bg_attach, a second rt_sim
 * of the caller's) the step runs there, in memory the tick never touches while it runs:
 * the tick copies the inputs in at release and the result out at publication. */
#include "rti.h"

/* ------------------------------------------------------------------ checks at init */

/* what a background set may not hold: discrete (sampled) blocks, whose outputs the tick
   computes; state events, whose handlers change d where the trace reads it, and so a
   defined system's located switches, whose roots and handlers are state events. (Its recorded
   or exported multibody signals, joint reactions too, are held: the step computes them at
   its end in the context that stepped, rti_hold_bg_signals) */
static rt_status check_members(const rt_scene *sc, rt_sim *sim, uint8_t s)
{
    for (uint16_t b = 0; b < sc->nblocks; b++) {
        const rt_kind *k = sc->blocks[b].kind;
        if (sc->blocks[b].set != s)
            continue;
        if (k->type == RT_KIND_DSS || k->nr > 0)
            return rti_fail(sim, RT_E_SCENE, "block ", sc->blocks[b].name, " of background set ",
                            sc->sets[s].name, ": sampled blocks and state events (a when, "
                            "a located switch) must run in a set of the tick",
                            (const char *)0);
    }
    return RT_OK;
}

/* reals of the background set's result: its states and its blocks' outputs */
static uint32_t result_size(const rt_scene *sc, const rt_sim *sim, uint8_t s)
{
    uint32_t n = (uint32_t)(sim->plan.set_x[s + 1] - sim->plan.set_x[s]);
    for (uint16_t b = 0; b < sc->nblocks; b++)
        if (sc->blocks[b].set == s)
            n += (uint32_t)(sim->plan.y_off[b + 1] - sim->plan.y_off[b]);
    return n;
}

/* what the release and the publication copy, listed once (rt_plan.bg_in, bg_sig): the
   set's inputs from the other sets, whose values at release the step reads, and the
   slots of its held signals */
static void list_copies(const rt_scene *sc, rt_sim *sim, uint8_t s)
{
    sim->plan.nbg_y = sim->plan.nbg_in = 0;
    for (uint16_t k = sim->plan.blk_of[s], e; k < sim->plan.blk_of[s + 1];) {
        uint16_t b = rti_block_run(sim, s, &k, &e);
        sim->plan.bg_y[sim->plan.nbg_y++] = sim->plan.y_off[b];
        sim->plan.bg_y[sim->plan.nbg_y++] = sim->plan.y_off[e];
    }
    for (uint16_t k = sim->plan.blk_of[s]; k < sim->plan.blk_of[s + 1]; k++) {
        uint16_t b = sim->plan.set_blk[k];
        for (uint16_t i = sim->plan.u_off[b]; i < sim->plan.u_off[b + 1]; i++)
            if (sim->plan.src_kind[i] == RT_SRC_HELD || sim->plan.src_kind[i] == RT_SRC_XSET)
                sim->plan.bg_in[sim->plan.nbg_in++] = i;
    }
#if RT_MAX_HELD_SIG > 0
    sim->plan.nbg_sig = rti_held_slots(sc, s, sim->plan.bg_sig);
#else
    (void)sc;
#endif
}

static rt_status init(const rt_scene *sc, rt_sim *sim)
{
    for (uint8_t s = 0; s < sc->nsets; s++) {
        if (!sc->sets[s].background)
            continue;
        if (sim->plan.bg_set >= 0)
            return rti_fail(sim, RT_E_SCENE, "set ", sc->sets[s].name, ": a scene has at most "
                            "one background set", (const char *)0);
        rt_status st = check_members(sc, sim, s);
        if (st != RT_OK)
            return st;
        if (result_size(sc, sim, s) > RT_MAX_BG)
            return rti_capacity(sim, "set ", sc->sets[s].name, RT_LIM_BG);
        sim->plan.bg_set = s;
        sim->state.bg_nonfinite = -1;
        list_copies(sc, sim, s);
    }
    return RT_OK;
}

uint32_t rti_bg_size(const rt_scene *sc, const rt_sim *sim)
{
    return sim->plan.bg_set < 0 ? 0 : result_size(sc, sim, (uint8_t)sim->plan.bg_set);
}

/* ------------------------------------------------------------------ copies */

/* n values, four at a time (a quarter of a plain loop's counting and branching: the
   result is copied three times per background step without a context, and the
   publishing tick, the scene's slowest, copies it once with one) */
static void copy_reals(real_t *dst, const real_t *src, uint32_t n)
{
    uint32_t i = 0;
    for (; i + 4 <= n; i += 4) {
        real_t a = src[i], b = src[i + 1], c = src[i + 2], d = src[i + 3];
        dst[i] = a, dst[i + 1] = b, dst[i + 2] = c, dst[i + 3] = d;
    }
    for (; i < n; i++)
        dst[i] = src[i];
}

/* n values of a and b exchanged, four at a time */
static void swap_reals(real_t *a, real_t *b, uint32_t n)
{
    uint32_t i = 0;
    for (; i + 4 <= n; i += 4) {
        real_t a0 = a[i], a1 = a[i + 1], a2 = a[i + 2], a3 = a[i + 3];
        real_t b0 = b[i], b1 = b[i + 1], b2 = b[i + 2], b3 = b[i + 3];
        a[i] = b0, a[i + 1] = b1, a[i + 2] = b2, a[i + 3] = b3;
        b[i] = a0, b[i + 1] = a1, b[i + 2] = a2, b[i + 3] = a3;
    }
    for (; i < n; i++) {
        real_t v = a[i];
        a[i] = b[i], b[i] = v;
    }
}

/* n values between a and a packed buffer: dir 0 packs a into buf, 1 unpacks buf into a,
   2 swaps the two */
static void move_range(real_t *a, real_t *buf, uint32_t n, int dir)
{
    if (dir == 0)
        copy_reals(buf, a, n);
    else if (dir == 1)
        copy_reals(a, buf, n);
    else
        swap_reals(a, buf, n);
}

/* the set's result between rt_state arrays and a packed buffer (move_range's dir): its
   states, then its blocks' outputs, a run of consecutive blocks at a time */
static void move_result(const rt_sim *sim, uint8_t s, real_t *x, real_t *y, real_t *buf,
                        int dir)
{
    uint32_t n = (uint32_t)(sim->plan.set_x[s + 1] - sim->plan.set_x[s]);
    move_range(x + sim->plan.set_x[s], buf, n, dir);
    for (uint16_t k = 0; k < sim->plan.nbg_y; k += 2) {
        uint16_t y0 = sim->plan.bg_y[k];
        uint32_t m = (uint32_t)(sim->plan.bg_y[k + 1] - y0);
        move_range(y + y0, buf + n, m, dir);
        n += m;
    }
}

/* the set's result from one rt_sim to another of the same scene (same layout): from the
   context straight into the tick's state at publication, one pass instead of two through
   bg_result */
static void copy_result(const rt_sim *from, rt_sim *to, uint8_t s)
{
    uint16_t x0 = from->plan.set_x[s];
    copy_reals(to->state.x + x0, from->state.x + x0, (uint32_t)(from->plan.set_x[s + 1] - x0));
    for (uint16_t k = 0; k < from->plan.nbg_y; k += 2) {
        uint16_t y0 = from->plan.bg_y[k];
        copy_reals(to->state.y + y0, from->state.y + y0, (uint32_t)(from->plan.bg_y[k + 1] - y0));
    }
}

/* copies n values; 1 if any changed (parameters are finite: rt_set_param checks them) */
static int copy_changed(real_t *dst, const real_t *src, uint32_t n)
{
    int changed = 0;
    for (uint32_t i = 0; i < n; i++) {
        changed |= dst[i] != src[i];
        dst[i] = src[i];
    }
    return changed;
}

/* set s's sensitivities to the inputs it extrapolates (state.xgain, rt/xset.c) from one
   rt_sim to the other: the tick judges the misses, the step measures them */
static void copy_gains(const rt_scene *sc, const rt_sim *from, rt_sim *to, uint8_t s)
{
#if RT_MAX_XPRED > 0
    (void)sc;
    for (uint16_t k = from->plan.xpred_of[s]; k < from->plan.xpred_of[s + 1]; k++)
        to->state.xgain[k] = from->state.xgain[k];
#else
    (void)sc, (void)from, (void)to, (void)s;
#endif
}

/* set s's parameters into the context, a block whose changed with its constant mass
   matrix factored anew there (as rt_set_param makes the tick's) and the set's time events
   found anew (rt/tev.c) */
static void copy_params(const rt_sim *sim, rt_sim *bg, uint8_t s)
{
    for (uint16_t k = sim->plan.blk_of[s]; k < sim->plan.blk_of[s + 1]; k++) {
        uint16_t b = sim->plan.set_blk[k], p0 = sim->plan.p_off[b];
        if (copy_changed(bg->state.p + p0, sim->state.p + p0,
                         (uint32_t)(sim->plan.p_off[b + 1] - p0)))
            bg->work.mbs.m_valid[b] = 0, rti_tev_moved(bg, s);
    }
}

/* what the step reads from the tick's side, as it stands at release: the time, its own
   blocks' parameters (rt_set_param may change them between ticks; the set's Jacobian is
   then formed anew), the held outputs of sampled blocks and the history of the other
   sets' outputs its inputs read (plan.bg_in; its own states, outputs and discrete states
   are the context's already) */
static void copy_inputs(const rt_scene *sc, const rt_sim *sim, rt_sim *bg, uint8_t s)
{
    bg->state.tick = sim->state.tick;
    for (uint8_t q = 0; q < sc->nsets; q++) {
        bg->state.set_tick[q] = sim->state.set_tick[q];
        bg->state.hist_n[q] = sim->state.hist_n[q];
        copy_reals(bg->state.hist_t[q], sim->state.hist_t[q], RT_HIST);
    }
    copy_gains(sc, sim, bg, s); /* as the tick last judged them (NaN: measure afresh) */
    /* parameters change only by rt_set_param and rt_restore, which both mark the set
       (param_changed, handed over at release): unmarked, the context has them all */
    if (bg->state.param_changed[s])
        copy_params(sim, bg, s);
    for (uint16_t k = 0; k < sim->plan.nbg_in; k++) {
        uint16_t i = sim->plan.bg_in[k], v = sim->plan.src[i];
        if (sim->plan.src_kind[i] == RT_SRC_HELD)
            bg->state.y[v] = sim->state.y[v];
        else
            for (int h = 0; h < RT_HIST; h++)
                bg->state.hist_y[h][v] = sim->state.hist_y[h][v];
    }
}

static uint32_t umax(uint32_t a, uint32_t b)
{
    return a > b ? a : b;
}

/* did the step count anything that merge_counts adds up: a fault counter, the status, a
   loop solve (asked in the background context, after its step, so that the tick that
   publishes a clean step walks none of them) */
static uint8_t counted(const rt_stats *b)
{
    int any = b->status != RT_OK;
    for (int c = 0; c < RT_CNT_COUNT; c++)
        any |= b->count[c] != 0;
    for (int i = 0; i < RT_MAX_LOOP_HIST; i++)
        any |= b->loop_hist[i] != 0;
    return (uint8_t)any;
}

/* the context's counters, status and loop histogram, into the tick's stats (the
   context's restart from zero) */
static void merge_counts(rt_stats *a, rt_stats *b)
{
    for (int c = 0; c < RT_CNT_COUNT; c++) {
        if (b->count[c] == 0)
            continue;
        if (a->count[c] == 0)
            a->first_tick[c] = b->first_tick[c];
        a->count[c] += b->count[c];
        a->last_block[c] = b->last_block[c];
        b->count[c] = 0;
    }
    if (rt_status_severity(b->status) > rt_status_severity(a->status))
        a->status = b->status;
    b->status = RT_OK;
    /* the histogram's own size: a per-scene build without loops keeps one bin */
    for (int i = 0; i < RT_MAX_LOOP_HIST; i++)
        a->loop_hist[i] += b->loop_hist[i], b->loop_hist[i] = 0;
}

/* the counters and high-water marks the step left in the context, into the tick's stats
   (its per-set entries are its own) */
static void merge_stats(rt_sim *sim, rt_sim *bg, uint8_t s)
{
    rt_stats *a = &sim->stats, *b = &bg->stats;
    if (sim->bg_counted)
        merge_counts(a, b);
    a->growth[s] = b->growth[s], a->unstable[s] = b->unstable[s];
    /* added, not taken over: the tick counts the set's couplings lost (rti_xset_predict) */
    a->errest[s] += b->errest[s], b->errest[s] = 0;
    a->istats[s] = b->istats[s], a->rhs_evals[s] = b->rhs_evals[s];
    a->event_iter_max = umax(a->event_iter_max, b->event_iter_max);
    a->loop_iter_max = umax(a->loop_iter_max, b->loop_iter_max);
    a->loop_residual = b->loop_residual > a->loop_residual ? b->loop_residual : a->loop_residual;
}

/* ------------------------------------------------------------------ the step */

/* the first block of set s whose outputs are not finite, or -1 */
static int16_t nonfinite_block(const rt_sim *sim, uint8_t s)
{
    const uint16_t *off = sim->plan.y_off;
    for (uint16_t k = sim->plan.blk_of[s]; k < sim->plan.blk_of[s + 1]; k++) {
        uint16_t b = sim->plan.set_blk[k];
        if (!rt_all_finite(sim->state.y + off[b], off[b + 1] - off[b]))
            return (int16_t)b;
    }
    return -1;
}

/* the step itself, in whichever rt_sim it runs: states to the end of the macro step,
   then the outputs there (what the other sets will read), checked here rather than in
   the tick that publishes them */
static void run_step(const rt_scene *sc, rt_sim *ctx, uint8_t s)
{
    uint32_t ratio = sc->sets[s].ratio;
    uint64_t r0 = ctx->stats.rhs_evals[s];
    /* its sensitivity to the inputs it extrapolates, when due (here, not in the tick) */
    if (ctx->plan.set_flags[s] & RTI_SET_XPRED)
        rti_xset_gain(sc, ctx, s, rti_tick_time(ctx->state.set_tick[s], sc->dt), ctx->plan.set_h[s]);
    rti_tev_step(sc, ctx, s, ctx->state.set_tick[s], ratio); /* parts at time events */
    rti_step_witness(ctx, s, r0);
    real_t te = rti_tick_time(ctx->state.set_tick[s] + ratio, sc->dt);
    rti_outputs(sc, ctx, (rti_at){te, s, RTI_IN_STEP});
    ctx->state.bg_nonfinite = nonfinite_block(ctx, s);
    /* its recorded multibody signals (a residual): here, not in a tick */
    rti_hold_bg_signals(sc, ctx, s, ctx->state.set_tick[s] + ratio);
}

/* release at the set's communication point: inline, the step runs now and its result is
   swapped into bg_result (the trace keeps showing the state at release); with a context,
   the inputs are copied there and the step is handed to rt_background */
static void release(const rt_scene *sc, rt_sim *sim, uint8_t s)
{
    sim->state.bg_busy = 1;
    sim->state.bg_due = sim->state.set_tick[s] + sc->sets[s].ratio;
    /* the inputs it extrapolates against their prediction, from the tick's history
       (the context's copy is the same, rather than the other way round) */
    if (sim->plan.set_flags[s] & RTI_SET_XPRED)
        rti_xset_predict(sc, sim, s, rti_tick_time(sim->state.set_tick[s], sc->dt),
                         sim->plan.set_h[s]);
    if (!sim->bg) {
        move_result(sim, s, sim->state.x, sim->state.y, sim->state.bg_result, 0);
        run_step(sc, sim, s);
        move_result(sim, s, sim->state.x, sim->state.y, sim->state.bg_result, 2);
        return;
    }
    /* a parameter set since the last release: the context's step forms the Jacobian
       anew, the step this release runs, as the inline step does (rt/step.c); copy_inputs
       adds parameters that changed another way (a restored snapshot) */
    sim->bg->state.param_changed[s] = sim->state.param_changed[s];
    sim->state.param_changed[s] = 0;
    copy_inputs(sc, sim, sim->bg, s);
    /* the copies above become visible to the background context with the count */
    __atomic_store_n(&sim->bg_released, sim->bg_released + 1u, __ATOMIC_RELEASE);
}

/* the result becomes the set's state and outputs, and the newest point of its history */
static void publish(const rt_scene *sc, rt_sim *sim, uint8_t s)
{
    rt_sim *bg = sim->bg;
    if (bg) {
        copy_result(bg, sim, s);
        sim->state.bg_nonfinite = bg->state.bg_nonfinite;
        merge_stats(sim, bg, s);
        copy_gains(sc, bg, sim, s); /* its step's, for the tick's check at the next release */
    } else {
        move_result(sim, s, sim->state.x, sim->state.y, sim->state.bg_result, 1);
    }
    sim->state.set_tick[s] = sim->state.bg_due;
    sim->state.bg_busy = 0;
    rti_publish_signals(sim, bg ? bg : sim);
    if (sim->plan.set_xout[s])
        rti_xset_push(sc, sim, s, rti_tick_time(sim->state.bg_due, sc->dt));
}

static void release_due(const rt_scene *sc, rt_sim *sim)
{
    /* at the set's communication point, or at once after a late publication (its
       deadline stays on the set's schedule) */
    if (sim->plan.bg_set >= 0 && !sim->state.bg_busy &&
        sim->state.set_tick[sim->plan.bg_set] <= sim->state.tick)
        release(sc, sim, (uint8_t)sim->plan.bg_set);
}

static void publish_due(const rt_scene *sc, rt_sim *sim)
{
    if (sim->plan.bg_set < 0 || !sim->state.bg_busy || sim->state.tick < sim->state.bg_due)
        return;
    /* finished: the context's writes are visible with its count (acquire) */
    if (!sim->bg || __atomic_load_n(&sim->bg_finished, __ATOMIC_ACQUIRE) == sim->bg_released) {
        publish(sc, sim, (uint8_t)sim->plan.bg_set);
    } else if (sim->state.tick == sim->state.bg_due) {
        /* never wait (the step runs below this context): the other sets go on
           extrapolating its history, and it is published when it has finished */
        rti_count(sim, RT_CNT_OVERRUN, -1, RT_E_OVERRUN);
        sim->stats.bg_late++;
    }
}

const rt_bg_ops rt_bg = {
    .init = init,
    .release = release_due,
    .publish = publish_due,
};

/* ------------------------------------------------------------------ API */

/* the name in parentheses: rt_sim.h's rt_bg_attach macro does not expand here */
rt_status (rt_bg_attach)(const rt_scene *sc, rt_sim *sim, rt_sim *bg)
{
    return rt_bg_attach_checked(sc, sim, bg, RT_SIM_LAYOUT);
}

rt_status rt_bg_attach_checked(const rt_scene *sc, rt_sim *sim, rt_sim *bg,
                               uint32_t caller_layout)
{
    if (!sc || !sim || !bg || bg == sim)
        return RT_E_ARG;
    /* bg (the caller's) may be smaller than this build's rt_sim: copy nothing into it */
    rt_status st = rti_layout_check(sim, caller_layout);
    if (st != RT_OK)
        return st;
    if (sim->state.bg_busy)
        return RT_E_ARG;
    const unsigned char *from = (const unsigned char *)sim;
    unsigned char *to = (unsigned char *)bg;
    for (size_t i = 0; i < sizeof *sim; i++)
        to[i] = from[i];
    bg->bg = 0;
    rti_zero(bg->stats.count, sizeof bg->stats.count);
    rti_zero(bg->stats.loop_hist, sizeof bg->stats.loop_hist);
    rti_zero(bg->stats.errest, sizeof bg->stats.errest);
    bg->stats.status = RT_OK;
    sim->bg_released = sim->bg_finished = 0;
    sim->bg_counted = 0;
    sim->bg = bg;
    return RT_OK;
}

int rt_bg_pending(const rt_sim *sim)
{
    return sim->bg && __atomic_load_n(&sim->bg_released, __ATOMIC_ACQUIRE) !=
                          __atomic_load_n(&sim->bg_finished, __ATOMIC_ACQUIRE);
}

rt_status rt_background(const rt_scene *sc, rt_sim *sim)
{
    if (!sim->bg || sim->plan.bg_set < 0)
        return RT_E_ARG;
    /* the released count first (acquire: the tick's copies are visible), then the step */
    uint32_t n = __atomic_load_n(&sim->bg_released, __ATOMIC_ACQUIRE);
    if (n == __atomic_load_n(&sim->bg_finished, __ATOMIC_RELAXED))
        return RT_E_ARG;
    run_step(sc, sim->bg, (uint8_t)sim->plan.bg_set);
    sim->bg_counted = counted(&sim->bg->stats); /* visible with the count, as the step */
    __atomic_store_n(&sim->bg_finished, n, __ATOMIC_RELEASE);
    return RT_OK;
}

int rt_bg_set(const rt_sim *sim)
{
    return sim->plan.bg_set;
}
