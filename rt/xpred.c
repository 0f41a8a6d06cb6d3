/* xpred.c - the communication-error monitor: the inputs a set reads from another set's
 * history, the error their schemes make, and the reader's sensitivity to them (paper,
 * section 3; docs/multirate.md).
 *
 * A set reading a faster one (or one of its own rate that steps after it, or the
 * background set) extrapolates it over its whole step. At each step's start
 * the value its scheme gives for the step's end is kept, and at the next start compared
 * with the source's point there (a predictor-corrector indicator, kept in the monitor
 * xset_err of the source). Off by more than the input's range (RT_XSET_LOST), the input
 * is counted like a step whose own estimate lost every digit: the coupling is past its
 * stability limit (RT_E_COUPLING). Below that, the miss times the reader's sensitivity to
 * the input (its derivatives' change per unit of it, measured every RT_XSET_GAIN_EVERY
 * steps and afresh near the accuracy) and half its step estimates the local error the
 * coupling put into its state, which is held to the reader's accuracy like its own
 * estimate (doubtful above it). A sensitivity found next to none is measured again at
 * every step while the miss would matter at a strong one (RT_XSET_NOGAIN).
 *
 * A set reading a slower one (or one of its ratio that steps before it) reads it between
 * two points of its history: a hold, a line or a parabola over the source's step. Once
 * per such interval the scheme's error over it is estimated by the next higher difference
 * of the points, and its integral over the interval times the reader's sensitivity is
 * held to the reader's accuracy in the same way: the source's step is the coupling's. */
#include "rti.h"

void rti_xset_predict_reset(rt_sim *sim)
{
#if RT_MAX_XPRED > 0
    for (uint16_t k = 0; k < sim->plan.nxpred; k++)
        sim->state.xpred[k] = sim->state.xgain[k] = (real_t)0 / (real_t)0,
        sim->state.xscale[k] = 0;
#else
    (void)sim;
#endif
}

#if RT_MAX_XPRED > 0
/* the sensitivity of set s's derivatives at (t, its state) to source output v (read
   through the history of set q): max_i |df_i/dv| / (1 + |x_i|), by one difference of
   size d. Every scheme reproduces a constant shift of all the history's points, so the
   points of v move by d for one right-hand side and are restored bit for bit; the second
   one, unshifted, leaves the set's outputs as they were at t. NaN if f is not finite */
/* the modes of set s's located switches (rt_kind.instant with instant_own: a defined
   system's, which reads its mode between instants) taken anew at t from the inputs as
   they read now, after the set's outputs: a switch on an input's level (`if(u > 0.5, 1,
   0)`) then answers a moved input as the set's next instant would, where its kept mode
   would not. Such an instant changes the kind's states alone (its modes): the set's
   state is kept in work.xb (free at a step's start) and put back by restore_modes */
static int own_instants(const rt_scene *sc, rt_sim *sim, uint8_t s, real_t t)
{
    uint16_t x0 = sim->plan.set_x[s], n = (uint16_t)(sim->plan.set_x[s + 1] - x0);
    if (!(sim->plan.set_flags[s] & RTI_SET_INSTANT))
        return 0;
    for (uint16_t i = 0; i < n; i++)
        sim->work.xb[i] = sim->state.x[x0 + i];
    rti_outputs(sc, sim, (rti_at){t, s, RTI_IN_STEP});
    for (uint16_t j = sim->plan.blk_of[s]; j < sim->plan.blk_of[s + 1]; j++) {
        uint16_t b = sim->plan.set_blk[j];
        const rt_kind *kd = sc->blocks[b].kind;
        if (!kd->instant || !kd->instant_own)
            continue;
        rt_args a;
        rti_gather(sim, b, t);
        rti_args(sc, sim, b, t, 0, &a);
        a.t_piece = rti_piece(sc, sim, kd, t);
        kd->instant(&a, sim->state.x + sim->plan.x_off[b], sim->state.d + sim->plan.d_off[b]);
    }
    return 1;
}

static void restore_modes(rt_sim *sim, uint8_t s)
{
    uint16_t x0 = sim->plan.set_x[s], n = (uint16_t)(sim->plan.set_x[s + 1] - x0);
    for (uint16_t i = 0; i < n; i++)
        sim->state.x[x0 + i] = sim->work.xb[i];
}

static real_t gain(const rt_scene *sc, rt_sim *sim, uint8_t s, uint16_t v, int held, real_t t,
                   real_t h, real_t d)
{
    uint16_t x0 = sim->plan.set_x[s], n = (uint16_t)(sim->plan.set_x[s + 1] - x0);
    real_t *f1 = sim->work.w.k[0], *f0 = sim->work.w.k[1], keep[RT_HIST], g = 0;
    rti_rhs_ctx c = {sc, sim, s, h};
#if RT_MAX_TEV > 0
    /* on the side of t the step integrates: the midpoint of its first part, before the
       set's next instant known at run time. At a tick that is an instant, t itself reads
       the left side of a strict comparison (t > ts is 0 there): a gain switched on at ts
       on the reader's grid was measured off, 1000 times small, and 8 times its accuracy
       went unreported */
    real_t tb = t + h, keep_piece = sim->work.t_piece;
    if (sim->plan.set_flags[s] & RTI_SET_TEV_DYN) {
        real_t td = rti_tev_dyn_next(sc, sim, s, t);
        tb = td < tb ? td : tb;
    }
    sim->work.t_piece = (real_t)0.5 * (t + tb);
#endif
    if (held) { /* a sampled output: its live value, which no evaluation of s writes */
        keep[0] = sim->state.y[v], sim->state.y[v] += d;
        int modes = own_instants(sc, sim, s, t);
        rti_rhs(&c, t, f1);
        sim->state.y[v] = keep[0];
        if (modes)
            restore_modes(sim, s);
    } else {
        for (int i = 0; i < RT_HIST; i++)
            keep[i] = sim->state.hist_y[i][v], sim->state.hist_y[i][v] += d;
        int modes = own_instants(sc, sim, s, t);
        rti_rhs(&c, t, f1);
        for (int i = 0; i < RT_HIST; i++)
            sim->state.hist_y[i][v] = keep[i];
        if (modes)
            restore_modes(sim, s);
    }
    rti_rhs(&c, t, f0);
#if RT_MAX_TEV > 0
    sim->work.t_piece = keep_piece;
#endif
    real_t sa = rti_err_floor(&sc->sets[s].cfg); /* scaled as the set's steps scale errors */
    for (uint16_t i = 0; i < n; i++) {
        real_t e = rt_fabs(f1[i] - f0[i]) / (sa + rt_fabs(sim->state.x[x0 + i]));
        if (!(e <= g))
            g = e; /* (a NaN stays) */
    }
    return g / rt_fabs(d);
}
#endif

#if RT_MAX_XPRED > 0
/* input k's sensitivity, measured now (set s at its step's start t, step h): by a small
   difference, or over `miss` where that is larger, the change of the input the set
   missed (signed: from the input's value now to the one the set read instead). Over the
   miss the difference sees what a small one cannot: a switch on the input's level
   (`if(u > 0.5, 1, 0)`, 0 slope on either side) that the miss crossed */
static void measure(const rt_scene *sc, rt_sim *sim, uint8_t s, uint16_t k, real_t t, real_t h,
                    real_t miss)
{
    /* a set without states (sampled blocks alone) takes no error from it */
    real_t d = RT_XSET_FD * (1 + sim->state.xscale[k]);
    d = rt_fabs(miss) > d ? miss : d;
    uint16_t v = sim->plan.src[sim->plan.xpred_in[k]];
    int held = sim->plan.xpred_how[k] == RTI_XP_HELD;
    sim->state.xgain[k] = rti_set_nx(sim, s) ? gain(sc, sim, s, v, held, t, h, d) : 0;
}
#endif

#if RT_MAX_XPRED > 0
/* is set s at a step whose count is a multiple of every */
static int steps_at(const rt_scene *sc, const rt_sim *sim, uint8_t s, uint32_t every)
{
    uint64_t st = sim->state.set_tick[s];
    uint32_t ratio = sc->sets[s].ratio; /* (in 32 bits while it fits: rti_tick_mod) */
    uint64_t steps = st <= UINT32_MAX ? (uint32_t)st / ratio : st / ratio;
    return rti_tick_mod(steps, every) == 0;
}
#endif

void rti_xset_gain(const rt_scene *sc, rt_sim *sim, uint8_t s, real_t t, real_t h)
{
#if RT_MAX_XPRED > 0
    int due = steps_at(sc, sim, s, RT_XSET_GAIN_EVERY);
    for (uint16_t k = sim->plan.xpred_of[s]; k < sim->plan.xpred_of[s + 1]; k++)
        if (due || sim->state.xgain[k] != sim->state.xgain[k])
            measure(sc, sim, s, k, t, h, 0);
#else
    (void)sc, (void)sim, (void)s, (void)t, (void)h;
#endif
}

#if RT_MAX_XPRED > 0
/* input k of set s (block b) put an error into the set's state of w times the set's
   sensitivity to it: against the set's accuracy; above it the step is counted as one
   whose estimate exceeds its accuracy. Near the accuracy (RT_XSET_FRESH), after one
   found next to none (RT_XSET_NOGAIN), or for a miss above RT_XSET_BIGMISS of the input's
   range at every RT_XSET_BIGMISS_EVERY-th step, the sensitivity, measured up to
   RT_XSET_GAIN_EVERY steps ago, is measured afresh first: now for a set of
   the tick (t: this step's start, h its step), by its next step for the background set
   (which never evaluates in the tick) */
static void judge(const rt_scene *sc, rt_sim *sim, uint8_t s, uint16_t b, uint16_t k,
                  real_t w, real_t miss, real_t t, real_t h)
{
    real_t g = sim->state.xgain[k], fresh = RT_XSET_FRESH * rti_accuracy(&sc->sets[s].cfg);
    real_t strong = 1 / ((1 + sim->state.xscale[k]) * h), est = w * g; /* RT_XSET_NOGAIN */
    if (!(est <= fresh) || (g <= RT_XSET_NOGAIN * strong && w * strong > fresh) ||
        (2 * w * strong > RT_XSET_BIGMISS && steps_at(sc, sim, s, RT_XSET_BIGMISS_EVERY))) {
        if (!sc->sets[s].background) {
            measure(sc, sim, s, k, t, h, miss);
            est = w * sim->state.xgain[k];
        } else {
            sim->state.xgain[k] = (real_t)0 / (real_t)0;
        }
    }
    rti_xset_judge(sc, sim, s, b, est);
}
#endif

real_t rti_xset_late(const rt_scene *sc, rt_sim *sim, uint8_t s)
{
    real_t late = 0;
#if RT_MAX_XPRED > 0
    real_t now = rti_tick_time(sim->state.set_tick[s], sc->dt);
    for (uint16_t k = sim->plan.xpred_of[s]; k < sim->plan.xpred_of[s + 1]; k++) {
        uint8_t q = sim->plan.src_set[sim->plan.xpred_in[k]];
        const real_t *T = sim->state.hist_t[q];
        if (sim->plan.xpred_how[k] == RTI_XP_HELD)
            continue; /* (a sampled output's jump is at its instant) */
        int j = 0, n = sim->state.hist_n[q];
        while (j < n && T[j] > now)
            j++;
        if (j >= n || T[j] != now || rti_tev_was(sc, sim, q, sim->state.set_tick[s]))
            continue; /* no new point here, or a jump at a known instant */
        real_t d = sim->plan.xpred_how[k] == RTI_XP_AHEAD ? (real_t)sc->sets[s].ratio * sc->dt
                 : j + 1 < n ? T[j] - T[j + 1] : 0;
        late = d > late ? d : late;
    }
#else
    (void)sc, (void)sim, (void)s;
#endif
    return late;
}

#if RT_MAX_XPRED > 0

/* an input extrapolated over set s's step [t, t + h] (block b, input i, source output v
   of set q): how far the prediction made at the last start was off at this start,
   against the largest size the input has had there. Where the source has a point here
   (at every common multiple of the two sets' steps) against that point; where it has
   stepped past this start since (a source of 7 ms read by a set of 30 ms, which steps
   first only at their common multiples), against its points around it, interpolated
   (a line, or the parabola through three): judged at the common multiples alone, a
   narrow pulse between them was read 6 times its size with status ok. The miss grows from 0
   at the step's start to e at its end, no faster than linearly for a hold and slower
   for the schemes that extrapolate a slope: the error it put into the state is at most
   e h / 2 times the set's sensitivity. Then the prediction for t + h */
static void check_ahead(const rt_scene *sc, rt_sim *sim, uint8_t s, uint16_t k, real_t t,
                        real_t h)
{
    uint16_t b = sim->plan.xpred_blk[k], i = sim->plan.xpred_in[k];
    uint16_t v = sim->plan.src[i];
    uint8_t q = sim->plan.src_set[i];
    const real_t *T = sim->state.hist_t[q];
    int n = sim->state.hist_n[q], here = n > 0 && T[0] == t;
    int past = n >= 2 && T[1] <= t && t < T[0];
    real_t p = sim->state.xpred[k], y = sim->state.hist_y[0][v];
    if (past)
        y = rti_xset_value(sim, v, q, RT_INTERP_HERMITE, t, b);
    /* a jump of the output's own block at a known instant (rt/tev.c) here, the end of
       the step judged: the point is its right side, the step rightly read the left one
       (a step source at 0.06 s read by steps of 30 ms is exact: no miss to judge).
       The block's, not its set's: a pulse beside it whose edges meet the reader's grid
       says nothing of a sine read (mr_tev_beside) */
    if (here && rti_tev_was(sc, sim, q, sim->state.set_tick[s]) &&
        rti_tev_block_was(sc, sim, rti_writer(sc, sim, v), sim->state.set_tick[s]))
        p = (real_t)0 / (real_t)0;
    if (rt_isfinite(y) && (here || past)) {
        real_t e = rt_fabs(y - p), a = rt_fabs(y);
        sim->state.xscale[k] = a > sim->state.xscale[k] ? a : sim->state.xscale[k];
        if (p == p) { /* (y is finite: e is NaN only without a prediction) */
            if (!(e <= sim->stats.xset_err[q]))
                sim->stats.xset_err[q] = e;
            if (!(e <= RT_XSET_LOST * (1 + sim->state.xscale[k]))) {
                rti_count(sim, RT_CNT_ERREST, (int)b, RT_E_COUPLING);
                sim->stats.errest[s]++;
            } else {
                judge(sc, sim, s, b, k, (real_t)0.5 * h * e, p - y, t, h);
            }
        }
    }
    sim->state.xpred[k] = rti_xset_value(sim, v, q, sim->plan.interp[i], t + h, b);
}

/* a sampled output held over set s's step [t, t + h] (block b): its value at this
   step's start against the one the last step held, the change it made inside that step,
   which the step read as constant (a hold's miss, judged as check_ahead's); then the
   value this step holds */
static void check_held(const rt_scene *sc, rt_sim *sim, uint8_t s, uint16_t k, real_t t,
                       real_t h)
{
    uint16_t b = sim->plan.xpred_blk[k], v = sim->plan.src[sim->plan.xpred_in[k]];
    real_t p = sim->state.xpred[k], y = sim->state.y[v], a = rt_fabs(y);
    sim->state.xscale[k] = a > sim->state.xscale[k] ? a : sim->state.xscale[k];
    if (p == p && rt_isfinite(y))
        judge(sc, sim, s, b, k, (real_t)0.5 * h * rt_fabs(y - p), p - y, t, h);
    sim->state.xpred[k] = y;
}

/* an input read ahead of the background set's history by set s (block b): the background
   publishes a point late, at its deadline, never at a step start of s, so check_ahead
   never sees one. Once per new point T0: what the points before it extrapolated to T0 (a
   line through the two before where there are two, else the one before held: the
   schemes read the background set ahead, rti_xset_value) against the point, a miss
   grown over the whole interval T1..T0 the reader read ahead: half that interval times
   it, judged as check_ahead's */
static void check_bg(const rt_scene *sc, rt_sim *sim, uint8_t s, uint16_t k, real_t t, real_t h)
{
    uint16_t b = sim->plan.xpred_blk[k], i = sim->plan.xpred_in[k], v = sim->plan.src[i];
    uint8_t q = sim->plan.src_set[i];
    const real_t *T = sim->state.hist_t[q];
    int n = sim->state.hist_n[q];
    if (n < 2 || T[0] == sim->state.xpred[k])
        return; /* no interval yet, or this point judged */
    sim->state.xpred[k] = T[0];
    real_t y0 = sim->state.hist_y[0][v], y1 = sim->state.hist_y[1][v], p = y1;
    if (n >= 3 && sim->plan.interp[i] != RT_INTERP_HOLD)
        p = y1 + (y1 - sim->state.hist_y[2][v]) * (T[0] - T[1]) / (T[1] - T[2]);
    real_t e = rt_fabs(y0 - p), a = rt_fabs(y0);
    sim->state.xscale[k] = a > sim->state.xscale[k] ? a : sim->state.xscale[k];
    if (rt_isfinite(e))
        judge(sc, sim, s, b, k, (real_t)0.5 * (T[0] - T[1]) * e, p - y0, t, h);
}

/* the mean over [T1, T0] of the difference between what scheme reads of output v there
   (from its history of n points) and the signal, by the difference of the order the
   scheme leaves out: a hold, half the change; a line, a twelfth of the second difference;
   a parabola, a twenty-fourth of the third; the line through the two points before
   (extrapolated), five twelfths of the second. NaN where too few points say it */
static real_t bracket_miss(const rt_sim *sim, uint16_t v, int n, uint8_t scheme)
{
    const real_t nan = (real_t)0 / (real_t)0;
    real_t y0 = sim->state.hist_y[0][v], y1 = sim->state.hist_y[1][v];
    real_t d2 = n >= 3 ? y0 - 2 * y1 + sim->state.hist_y[2][v] : nan;
    switch (scheme) {
    case RT_INTERP_HOLD:
        return (real_t)0.5 * rt_fabs(y0 - y1);
    case RT_INTERP_LINEAR:
        return rt_fabs(d2) / 12;
    case RT_INTERP_HERMITE: /* a parabola through three points, a line through two */
    case RT_INTERP_QUAD:
        return n == RT_HIST ? rt_fabs(d2 - sim->state.hist_d2[v]) / 24 : nan;
    case RT_INTERP_EXTRAP:
        return n >= 3 ? (real_t)5 / 12 * rt_fabs(d2) : (real_t)0.5 * rt_fabs(y0 - y1);
    default:
        return nan;
    }
}

/* does a switch of source set q at a known instant (rt/tev.c) fall where the difference
   bracket_miss takes for scheme's error is not one: a hold's at the interval's end (its
   points, left of it and right, differ by the jump the hold is right to leave out), a
   line's at its start (the second difference reaches past the jump the line does not) */
static int jumps_past(const rt_scene *sc, rt_sim *sim, uint8_t q, uint8_t scheme)
{
    if (!(sim->plan.set_flags[q] & RTI_SET_TEV))
        return 0;
    real_t at = scheme == RT_INTERP_HOLD ? sim->state.hist_t[q][0]
              : scheme == RT_INTERP_LINEAR ? sim->state.hist_t[q][1] : -1;
    return at >= 0 && rti_tev_was(sc, sim, q, (uint64_t)(at / sc->dt + (real_t)0.5));
}

/* an input read between the two newest points of its source's history by set s at its
   step's start t (step h): once per interval, at the first step of s in it, the error
   its scheme makes over the interval, integrated: its length times the mean miss, times
   the set's sensitivity. A source read this way has stepped to (or past) the end of s's
   step before it (the schedule: slower first, rt/xset.c) */
static void check_bracket(const rt_scene *sc, rt_sim *sim, uint8_t s, uint16_t k, real_t t,
                          real_t h)
{
    uint16_t i = sim->plan.xpred_in[k];
    uint8_t q = sim->plan.src_set[i];
    const real_t *T = sim->state.hist_t[q];
    if (T[0] == sim->state.xpred[k]) /* (the common case, every step but the first) */
        return;                       /* this interval judged already */
    uint16_t b = sim->plan.xpred_blk[k], v = sim->plan.src[i];
    int n = sim->state.hist_n[q];
    if (n < 2 || !(T[1] <= t && t < T[0]))
        return; /* no interval */
    sim->state.xpred[k] = T[0];
    uint8_t scheme = sim->plan.interp[i];
    if (jumps_past(sc, sim, q, scheme))
        return;
    if (sim->state.hist_ev[q] & 1u)
        scheme = RT_INTERP_HOLD; /* a jump anywhere inside: any scheme misses as a hold */
    real_t m = bracket_miss(sim, v, n, scheme), a = rt_fabs(sim->state.hist_y[0][v]);
    if (!rt_isfinite(m))
        return;
    sim->state.xscale[k] = a > sim->state.xscale[k] ? a : sim->state.xscale[k];
    /* a hold read the older point where the signal went to the newer: the miss's
       direction (a switch on the input's level between them, mr_threshold_slow); a
       scheme that interpolates misses by a mean with no direction */
    real_t dir = scheme == RT_INTERP_HOLD ? sim->state.hist_y[0][v] - sim->state.hist_y[1][v] : 0;
    judge(sc, sim, s, b, k, (T[0] - T[1]) * m, dir, t, h);
}
#endif

void rti_xset_predict(const rt_scene *sc, rt_sim *sim, uint8_t s, real_t t, real_t h)
{
#if RT_MAX_XPRED > 0
    for (uint16_t k = sim->plan.xpred_of[s]; k < sim->plan.xpred_of[s + 1]; k++) {
        if (sim->plan.xpred_how[k] == RTI_XP_AHEAD &&
            sim->plan.src_set[sim->plan.xpred_in[k]] == sim->plan.bg_set && !sc->sets[s].background)
            check_bg(sc, sim, s, k, t, h);
        else if (sim->plan.xpred_how[k] == RTI_XP_AHEAD)
            check_ahead(sc, sim, s, k, t, h);
        else if (sim->plan.xpred_how[k] == RTI_XP_HELD)
            check_held(sc, sim, s, k, t, h);
        else
            check_bracket(sc, sim, s, k, t, h);
    }
    /* the background set's sensitivity is measured by its step, in the context that runs
       it (rt/bg.c): not in the tick */
    if (!sc->sets[s].background)
        rti_xset_gain(sc, sim, s, t, h);
#else
    (void)sc, (void)sim, (void)s, (void)t, (void)h;
#endif
}
