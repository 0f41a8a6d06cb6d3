/* xmiss.c - what a signal read from another set's history misses by at a place (its
 * scheme's remainder, by the next difference of the points), and the error a coupling
 * put into a set, held to the set's accuracy: the services of the communication-error
 * monitor (rt/xpred.c) and of the judgement of events that read other sets (rt/step.c,
 * docs/multirate.md). */
#include "rti.h"

void rti_xset_judge(const rt_scene *sc, rt_sim *sim, uint8_t s, uint16_t b, real_t est)
{
    if (!(est == est))
        return; /* no sensitivity measured (its right-hand side was not finite) */
#if RT_MAX_XPRED > 0
    if (est > sim->stats.xset_est[s])
        sim->stats.xset_est[s] = est;
#endif
    if (est > rti_accuracy(&sc->sets[s].cfg)) {
        rti_count(sim, RT_CNT_ERREST, (int)b, RT_E_ACCURACY);
        sim->stats.errest[s]++;
    }
}

#if RT_MAX_XPRED > 0
/* the difference between what scheme reads of output v at time t (from its history of n
   points at times T) and the signal, by the difference the scheme leaves out, as
   bracket_miss, at t's place: a fraction th of the newest interval past its older point,
   or rho of it past the newest (ahead: the remainder of extrapolating the points'
   polynomial that far). As rti_xset_value reads: ahead, a line through the two newest
   (extrapolate, linear, hermite) or the parabola through three (quadratic); between
   points a line (linear), a parabola (hermite, quadratic), or the line through the two
   before (extrapolate); a hold the older point. jumped: the interval holds a state event
   (state.hist_ev), a jump anywhere in it, missed by as much as its points differ.
   d2_prev: the previous second difference (state.hist_d2; NaN for the background set's,
   whose slot holds bg_jump). NaN where too few points say it */
static real_t read_miss(const rt_sim *sim, uint16_t v, int n, uint8_t scheme, const real_t *T,
                        real_t t, real_t d2_prev, int jumped)
{
    const real_t nan = (real_t)0 / (real_t)0;
    real_t y0 = sim->state.hist_y[0][v], y1 = sim->state.hist_y[1][v];
    real_t d2 = n >= 3 ? rt_fabs(y0 - 2 * y1 + sim->state.hist_y[2][v]) : nan;
    real_t d3 = n == RT_HIST ? rt_fabs(y0 - 2 * y1 + sim->state.hist_y[2][v] - d2_prev) : nan;
    real_t rho = (t - T[0]) / (T[0] - T[1]), th = (t - T[1]) / (T[0] - T[1]);
    th = th > 0 ? th < 1 ? th : 1 : 0;
    if (jumped)
        return rt_fabs(y0 - y1) * (rho > 1 ? rho : 1);
    if (rho > 0) /* ahead */
        return scheme == RT_INTERP_HOLD ? rt_fabs(y0 - y1) * rho
             : scheme == RT_INTERP_QUAD ? d3 * rho * (rho + 1) * (rho + 2) / 6
                                        : d2 * rho * (rho + 1) / 2;
    switch (scheme) {
    case RT_INTERP_HOLD:
        return rt_fabs(y0 - y1) * th;
    case RT_INTERP_LINEAR:
        return d2 * th * (1 - th) / 2;
    case RT_INTERP_HERMITE:
    case RT_INTERP_QUAD:
        return d3 * th * (1 - th) * (1 + th) / 6;
    case RT_INTERP_EXTRAP:
        return d2 * th * (th + 1) / 2;
    default:
        return nan;
    }
}
#endif

void rti_xset_shifted(const rt_scene *sc, rt_sim *sim, uint8_t s, real_t t, real_t h,
                      rti_xset_effect fn, void *ctx)
{
#if RT_MAX_XPRED > 0
    real_t keep[RT_HIST];
    for (uint16_t k = sim->plan.xpred_of[s]; k < sim->plan.xpred_of[s + 1]; k++) {
        uint16_t i = sim->plan.xpred_in[k], v = sim->plan.src[i];
        uint8_t q = sim->plan.src_set[i];
        int n = sim->state.hist_n[q];
        const real_t *T = sim->state.hist_t[q];
        if (n < 2 || sim->plan.xpred_how[k] == RTI_XP_HELD)
            continue; /* (a sampled output held: no history) */
        real_t d2p = sc->sets[q].background ? (real_t)0 / (real_t)0 : sim->state.hist_d2[v];
        real_t m = read_miss(sim, v, n, sim->plan.interp[i], T, t, d2p,
                             (sim->state.hist_ev[q] & 1u) != 0);
        if (!(m > 0))
            continue; /* (NaN: too few points yet) */
        real_t d = RT_XSET_FD * (1 + sim->state.xscale[k]);
        for (int j = 0; j < RT_HIST; j++) /* a shift every scheme reproduces (gain) */
            keep[j] = sim->state.hist_y[j][v], sim->state.hist_y[j][v] += d;
        fn(ctx, m / d, sim->plan.xpred_how[k] == RTI_XP_AHEAD ? h : T[0] - T[1]);
        for (int j = 0; j < RT_HIST; j++)
            sim->state.hist_y[j][v] = keep[j];
    }
#else
    (void)sc, (void)sim, (void)s, (void)t, (void)h, (void)fn, (void)ctx;
#endif
}
