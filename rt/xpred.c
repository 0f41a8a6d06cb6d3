/* xpred.c - the communication-error monitor: the inputs a set extrapolates from another
 * set over its step, checked against the source's point at the next step's start, and
 * the reader's sensitivity to them (paper, section 3; docs/multirate.md).
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
 * estimate (doubtful above it). */
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
static real_t gain(const rt_scene *sc, rt_sim *sim, uint8_t s, uint16_t v, real_t t, real_t h,
                   real_t d)
{
    uint16_t x0 = sim->plan.set_x[s], n = (uint16_t)(sim->plan.set_x[s + 1] - x0);
    real_t *f1 = sim->work.w.k[0], *f0 = sim->work.w.k[1], keep[RT_HIST], g = 0;
    rti_rhs_ctx c = {sc, sim, s, h};
    for (int i = 0; i < RT_HIST; i++)
        keep[i] = sim->state.hist_y[i][v], sim->state.hist_y[i][v] += d;
    rti_rhs(&c, t, f1);
    for (int i = 0; i < RT_HIST; i++)
        sim->state.hist_y[i][v] = keep[i];
    rti_rhs(&c, t, f0);
    for (uint16_t i = 0; i < n; i++) {
        real_t e = rt_fabs(f1[i] - f0[i]) / (1 + rt_fabs(sim->state.x[x0 + i]));
        if (!(e <= g))
            g = e; /* (a NaN stays) */
    }
    return g / d;
}
#endif

#if RT_MAX_XPRED > 0
/* input k's sensitivity, measured now (set s at its step's start t, step h) */
static void measure(const rt_scene *sc, rt_sim *sim, uint8_t s, uint16_t k, real_t t, real_t h)
{
    /* a set without states (sampled blocks alone) takes no error from it */
    real_t d = RT_XSET_FD * (1 + sim->state.xscale[k]);
    uint16_t v = sim->plan.src[sim->plan.xpred_in[k]];
    sim->state.xgain[k] = rti_set_nx(sim, s) ? gain(sc, sim, s, v, t, h, d) : 0;
}
#endif

void rti_xset_gain(const rt_scene *sc, rt_sim *sim, uint8_t s, real_t t, real_t h)
{
#if RT_MAX_XPRED > 0
    uint64_t step = sim->state.set_tick[s] / sc->sets[s].ratio;
    for (uint16_t k = 0; k < sim->plan.nxpred; k++)
        if (sc->blocks[sim->plan.xpred_blk[k]].set == s &&
            (step % RT_XSET_GAIN_EVERY == 0 || sim->state.xgain[k] != sim->state.xgain[k]))
            measure(sc, sim, s, k, t, h);
#else
    (void)sc, (void)sim, (void)s, (void)t, (void)h;
#endif
}

#if RT_MAX_XPRED > 0
/* input k of set s (block b) missed its prediction over the set's last step h by e: the
   local error it put into the set's state, at most e h / 2 times the set's sensitivity
   (the miss grows from 0 at the step's start to e at its end, no faster than linearly
   for a hold and slower for the schemes that extrapolate a slope), against the set's
   accuracy; above it the step is counted as one whose estimate exceeds its accuracy. Near
   the accuracy (RT_XSET_FRESH) the sensitivity, measured up to RT_XSET_GAIN_EVERY steps
   ago, is measured afresh first: now for a set of the tick (t: this step's start), by its
   next step for the background set (which never evaluates in the tick) */
static void judge(const rt_scene *sc, rt_sim *sim, uint8_t s, uint16_t b, uint16_t k,
                  real_t e, real_t t, real_t h)
{
    real_t acc = rti_accuracy(&sc->sets[s].cfg);
    real_t est = (real_t)0.5 * h * sim->state.xgain[k] * e;
    if (!(est <= RT_XSET_FRESH * acc)) {
        if (!sc->sets[s].background) {
            measure(sc, sim, s, k, t, h);
            est = (real_t)0.5 * h * sim->state.xgain[k] * e;
        } else {
            sim->state.xgain[k] = (real_t)0 / (real_t)0;
        }
    }
    if (!(est == est))
        return; /* no sensitivity measured (its right-hand side was not finite) */
    if (est > sim->stats.xset_est[s])
        sim->stats.xset_est[s] = est;
    if (est > acc) {
        rti_count(sim, RT_CNT_ERREST, (int)b, RT_E_ACCURACY);
        sim->stats.errest[s]++;
    }
}
#endif

void rti_xset_predict(const rt_scene *sc, rt_sim *sim, uint8_t s, real_t t, real_t h)
{
#if RT_MAX_XPRED > 0
    for (uint16_t k = 0; k < sim->plan.nxpred; k++) {
        uint16_t b = sim->plan.xpred_blk[k], i = sim->plan.xpred_in[k];
        if (sc->blocks[b].set != s)
            continue;
        uint16_t v = sim->plan.src[i];
        uint8_t q = sim->plan.src_set[i];
        real_t p = sim->state.xpred[k], y = sim->state.hist_y[0][v];
        /* where the source has a point at this step's start (at every common multiple of
           the two sets' steps): how far the prediction made at the last start was off,
           against the largest size the input has had there */
        if (rt_isfinite(y) && sim->state.hist_n[q] > 0 && sim->state.hist_t[q][0] == t) {
            real_t e = rt_fabs(y - p), a = rt_fabs(y);
            sim->state.xscale[k] = a > sim->state.xscale[k] ? a : sim->state.xscale[k];
            if (p == p) { /* (y is finite: e is NaN only without a prediction) */
                if (!(e <= sim->stats.xset_err[q]))
                    sim->stats.xset_err[q] = e;
                if (!(e <= RT_XSET_LOST * (1 + sim->state.xscale[k]))) {
                    rti_count(sim, RT_CNT_ERREST, (int)b, RT_E_COUPLING);
                    sim->stats.errest[s]++;
                } else {
                    judge(sc, sim, s, b, k, e, t, h);
                }
            }
        }
        sim->state.xpred[k] = rti_xset_value(sim, v, q, sim->plan.interp[i], t + h);
    }
    /* the background set's sensitivity is measured by its step, in the context that runs
       it (rt/bg.c): not in the tick */
    if (!sc->sets[s].background)
        rti_xset_gain(sc, sim, s, t, h);
#else
    (void)sc, (void)sim, (void)s, (void)t, (void)h;
#endif
}
