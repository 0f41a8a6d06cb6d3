/* xset.c - multirate: signals that cross from one set to another and the fixed schedule
 * of the sets (paper, section 3; Gear 1974); the monitor of the inputs a set
 * extrapolates is rt/xpred.c.
 *
 * A set steps when the tick count is a multiple of its ratio; within a tick the slowest
 * set steps first. After each step a set's outputs read by other sets are pushed into a
 * short history (RT_HIST points, newest first). An input from another set is never read
 * from the live output: it is reconstructed from that history at the time of the
 * evaluation, by the scheme of its connection (rt_interp). So each set's right-hand side
 * evaluates only its own blocks, and a cross-set edge is no algebraic dependency. */
#include "rti.h"

/* does input i of block b, in set st, read a sampled output (RT_SRC_HELD) whose block
   samples inside st's steps (its period not a whole number of them): st's stages then
   hold the value from the step's start while it moves on. A sampled reader reads it at
   its own instants */
static int held_inside(const rt_scene *sc, const rt_sim *sim, uint16_t i, uint16_t b, uint8_t st)
{
    if (sc->blocks[b].kind->type == RT_KIND_DSS)
        return 0;
    return sim->plan.period[rti_writer(sc, sim, sim->plan.src[i])] % sc->sets[st].ratio != 0;
}

/* how input i, of block b of set st, reads another set over st's step (RTI_XP_*): ahead,
   extrapolating its source's history (a source faster than st, or of st's ratio and
   behind it; the background set, however slow, and any set of its ratio it reads or that
   reads it: rt/bg.c; a set of the tick that steps after st), or between two points of it
   (a source slower than st, or of its ratio and ahead of it); a sampled output held over
   st's step while it moves inside it (held_inside). A sampled block's input is not
   monitored where it would be read between points or from a slower background set: it
   enters no derivative of the step (its sensitivity is 0) */
static int monitored(const rt_scene *sc, const rt_sim *sim, uint16_t i, uint16_t b, uint8_t st)
{
    if (sim->plan.src_kind[i] == RT_SRC_HELD)
        return held_inside(sc, sim, i, b, st) ? RTI_XP_HELD : RTI_XP_NONE;
    if (sim->plan.src_kind[i] != RT_SRC_XSET)
        return RTI_XP_NONE;
    uint8_t q = sim->plan.src_set[i];
    int sampled = sc->blocks[b].kind->type == RT_KIND_DSS;
    if (sc->sets[q].ratio != sc->sets[st].ratio)
        return sc->sets[q].ratio < sc->sets[st].ratio ? RTI_XP_AHEAD
               : sampled                              ? RTI_XP_NONE
               : sc->sets[q].background               ? RTI_XP_AHEAD /* however slow */
                                                      : RTI_XP_BRACKET;
    if (sc->sets[q].background || sc->sets[st].background)
        return RTI_XP_AHEAD;
    for (uint8_t k = 0; k < sc->nsets; k++) /* which of the two steps first */
        if (sim->plan.sched[k] == q || sim->plan.sched[k] == st)
            return sim->plan.sched[k] == st ? RTI_XP_AHEAD
                   : sampled                ? RTI_XP_NONE
                                            : RTI_XP_BRACKET;
    return RTI_XP_NONE;
}

uint16_t rti_xset_npred(const rt_scene *sc, const rt_sim *sim)
{
    uint16_t n = 0;
    for (uint16_t b = 0; b < sc->nblocks; b++)
        for (uint16_t i = sim->plan.u_off[b]; i < sim->plan.u_off[b + 1]; i++)
            n = (uint16_t)(n + (monitored(sc, sim, i, b, sc->blocks[b].set) != RTI_XP_NONE));
    return n;
}

/* the inputs read from another set's history, whose error is checked (rti_xset_predict) */
static rt_status collect_predicted(const rt_scene *sc, rt_sim *sim)
{
    if (rti_xset_npred(sc, sim) > RT_MAX_XPRED)
        return rti_capacity(sim, 0, 0, RT_LIM_XPRED);
#if RT_MAX_XPRED > 0
    sim->plan.nxpred = 0;
    for (uint8_t s = 0; s < sc->nsets; s++) { /* by set: each set's step walks its own */
        sim->plan.xpred_of[s] = sim->plan.nxpred;
        for (uint16_t b = 0; b < sc->nblocks; b++)
            for (uint16_t i = sim->plan.u_off[b]; sc->blocks[b].set == s && i < sim->plan.u_off[b + 1];
                 i++) {
                int how = monitored(sc, sim, i, b, s);
                if (how == RTI_XP_NONE)
                    continue;
                sim->plan.xpred_in[sim->plan.nxpred] = i;
                sim->plan.xpred_blk[sim->plan.nxpred] = b;
                sim->plan.xpred_how[sim->plan.nxpred++] = (uint8_t)how;
            }
    }
    sim->plan.xpred_of[sc->nsets] = sim->plan.nxpred;
#endif
    return RT_OK;
}

/* does a block of set r read an output of set q by source kind how: a sampled output
   (RT_SRC_HELD) or through q's history (RT_SRC_XSET)? */
static int reads(const rt_scene *sc, const rt_sim *sim, uint8_t r, uint8_t q, rt_src_kind how)
{
    for (uint16_t b = 0; b < sc->nblocks; b++)
        for (uint16_t i = sim->plan.u_off[b]; sc->blocks[b].set == r && i < sim->plan.u_off[b + 1];
             i++)
            if (sim->plan.src_kind[i] == how && sim->plan.src_set[i] == q)
                return 1;
    return 0;
}

/* a before b in byte order of their names */
static int name_before(const char *a, const char *b)
{
    while (*a && *a == *b)
        a++, b++;
    return (unsigned char)*a < (unsigned char)*b;
}

/* sets of one ratio step at the same instants: the one that steps first is read by the
   others at its new point, the others it extrapolates. So that this does not depend on
   the order the scene lists them in, a set steps after the sets of its ratio it reads
   (their history) and, in a cycle, by name. sched[lo .. hi) holds one ratio */
static void order_run(const rt_scene *sc, rt_sim *sim, uint8_t lo, uint8_t hi)
{
    uint8_t run[RT_MAX_SETS], placed[RT_MAX_SETS] = {0};
    for (uint8_t i = lo; i < hi; i++)
        run[i] = sim->plan.sched[i];
    for (uint8_t n = lo; n < hi; n++) {
        uint8_t pick = RT_MAX_SETS, low = RT_MAX_SETS;
        for (uint8_t i = lo; i < hi && pick == RT_MAX_SETS; i++) {
            uint8_t r = run[i];
            if (placed[r])
                continue;
            low = low < RT_MAX_SETS && name_before(sc->sets[low].name, sc->sets[r].name) ? low : r;
            int ready = 1;
            for (uint8_t k = lo; ready && k < hi; k++)
                ready = placed[run[k]] || run[k] == r || !reads(sc, sim, r, run[k], RT_SRC_XSET);
            pick = ready ? r : RT_MAX_SETS;
        }
        pick = pick < RT_MAX_SETS ? pick : low; /* a cycle: the first name of the rest */
        if (pick >= RT_MAX_SETS)
            return; /* not reached: a set of the run is unplaced */
        placed[pick] = 1;
        sim->plan.sched[n] = pick;
    }
}

static void equal_ratios(const rt_scene *sc, rt_sim *sim)
{
    for (uint8_t lo = 0, hi; lo < sc->nsets && lo < RT_MAX_SETS; lo = hi) {
        for (hi = (uint8_t)(lo + 1);
             hi < sc->nsets && hi < RT_MAX_SETS &&
             sc->sets[sim->plan.sched[hi]].ratio == sc->sets[sim->plan.sched[lo]].ratio;
             hi++)
            ;
        if (hi - lo > 1)
            order_run(sc, sim, lo, hi);
    }
}

/* rsched: sched's order, but a set's outputs refreshed before those of any set that reads
   its sampled outputs: at a sample instant a throughput block then shows this sample, not
   the last, whatever the order the scene lists its sets in. Each place takes the first set
   in sched's order none of whose sampled sources is still unplaced (in a cycle: the first) */
static void refresh_order(const rt_scene *sc, rt_sim *sim)
{
    uint8_t placed[RT_MAX_SETS] = {0};
    for (uint8_t n = 0; n < sc->nsets; n++) {
        uint8_t pick = RT_MAX_SETS, first = RT_MAX_SETS;
        for (uint8_t i = 0; i < sc->nsets && pick == RT_MAX_SETS; i++) {
            uint8_t r = sim->plan.sched[i];
            if (placed[r])
                continue;
            first = first < RT_MAX_SETS ? first : r;
            int ready = 1;
            for (uint8_t q = 0; ready && q < sc->nsets; q++)
                ready = placed[q] || q == r || !reads(sc, sim, r, q, RT_SRC_HELD);
            pick = ready ? r : RT_MAX_SETS;
        }
        pick = pick < RT_MAX_SETS ? pick : first; /* a cycle: sched's first unplaced */
        if (pick >= RT_MAX_SETS)
            return; /* not reached: n < nsets leaves a set unplaced */
        placed[pick] = 1;
        sim->plan.rsched[n] = pick;
    }
}

rt_status rti_xset_init(const rt_scene *sc, rt_sim *sim)
{
    for (uint16_t c = 0; c < sc->nconns; c++) {
        const rt_conn *cn = &sc->conns[c];
        uint8_t sf = sc->blocks[cn->from].set, st = sc->blocks[cn->to].set;
        uint8_t own = sc->conn_interp ? sc->conn_interp[c] : RT_INTERP_SET;
        uint8_t scheme = own ? own : sc->sets[st].interp;
        if (own >= RT_INTERP_COUNT || sc->sets[st].interp >= RT_INTERP_COUNT)
            return rti_fail(sim, RT_E_SCENE, "connection to ", sc->blocks[cn->to].name,
                            ": unknown interpolation scheme", (const char *)0);
        if (sf == st)
            continue;
        uint16_t gi = (uint16_t)(sim->plan.u_off[cn->to] + cn->u);
        /* a sampled output is piecewise constant by definition: computed at its sample
           instant (rt_refresh, before any set steps) and not again until the next, so the
           live value is its exact zero-order hold in every set; the history would label
           it with the end of its set's step and deliver it one step late */
        if (sc->blocks[cn->from].kind->type == RT_KIND_DSS) {
            sim->plan.src_kind[gi] = RT_SRC_HELD;
            sim->plan.src_set[gi] = sf; /* the refresh order (refresh_order) */
            sim->plan.interp[gi] = RT_INTERP_HOLD;
            continue;
        }
        if (sim->plan.src[gi] >= RT_MAX_HIST_Y)
            return rti_capacity(sim, 0, 0, RT_LIM_HIST_Y);
        sim->plan.src_kind[gi] = RT_SRC_XSET;
        sim->plan.src_set[gi] = sf;
        sim->plan.interp[gi] = scheme ? scheme : RT_INTERP_HOLD;
        sim->plan.xsrc[sim->plan.src[gi]] = 1;
        if (sim->plan.src[gi] >= sim->plan.set_xout[sf])
            sim->plan.set_xout[sf] = (uint16_t)(sim->plan.src[gi] + 1);
    }
    /* schedule: by ratio, largest first; equal ratios by dependency (equal_ratios) */
    for (uint8_t i = 0; i < sc->nsets && i < RT_MAX_SETS; i++) { /* init checked nsets */
        uint8_t j = i;
        for (; j > 0 && sc->sets[sim->plan.sched[j - 1]].ratio < sc->sets[i].ratio; j--)
            sim->plan.sched[j] = sim->plan.sched[j - 1];
        sim->plan.sched[j] = i;
    }
    equal_ratios(sc, sim);
    refresh_order(sc, sim);
    return collect_predicted(sc, sim);
}

/* the line through history points a and b of output v, at time t */
static real_t line(const rt_sim *sim, const real_t *T, uint16_t v, int a, int b, real_t t)
{
    return sim->state.hist_y[b][v] +
           (sim->state.hist_y[a][v] - sim->state.hist_y[b][v]) * (t - T[b]) / (T[a] - T[b]);
}

/* the parabola through the three points, at time t (Lagrange form): cubic Hermite with
   both end slopes taken from this parabola reproduces it exactly */
static real_t parabola(const rt_sim *sim, const real_t *T, uint16_t v, real_t t)
{
    real_t l0 = (t - T[1]) * (t - T[2]) / ((T[0] - T[1]) * (T[0] - T[2]));
    real_t l1 = (t - T[0]) * (t - T[2]) / ((T[1] - T[0]) * (T[1] - T[2]));
    real_t l2 = (t - T[0]) * (t - T[1]) / ((T[2] - T[0]) * (T[2] - T[1]));
    return l0 * sim->state.hist_y[0][v] + l1 * sim->state.hist_y[1][v] + l2 * sim->state.hist_y[2][v];
}

/* history slot 0 := the outputs of set s now; older points move down */
void rti_xset_push(const rt_scene *sc, rt_sim *sim, uint8_t s, real_t t)
{
    (void)sc; /* the plan's per-set lists say all it needs */
    if (!sim->plan.set_xout[s])
        return;
    real_t *T = sim->state.hist_t[s], *y = sim->state.y;
    real_t(*hy)[RT_MAX_HIST_Y] = sim->state.hist_y;
    const uint8_t *xsrc = sim->plan.xsrc;
    uint8_t n = sim->state.hist_n[s];
    int bg = s == sim->plan.bg_set;
    real_t err = sim->stats.xset_err[s];
    unsigned vend = sim->plan.set_xout[s]; /* <= RT_MAX_HIST_Y (rti_xset_init) */
    /* the set's blocks ascend, and so do their outputs: none past vend keeps history */
    for (unsigned i = sim->plan.blk_of[s], i1 = sim->plan.blk_of[s + 1];
         i < i1 && sim->plan.y_off[sim->plan.set_blk[i]] < vend; i++) {
        unsigned b = sim->plan.set_blk[i], v1 = sim->plan.y_off[b + 1];
        for (unsigned v = sim->plan.y_off[b]; v < v1 && v < vend; v++) {
            if (!xsrc[v])
                continue;
            /* monitor: how far the new point is from the line through the last two */
            if (n >= 2) {
                real_t e = hy[0][v] + (hy[0][v] - hy[1][v]) * (t - T[0]) / (T[0] - T[1]) - y[v];
                e = rt_fabs(e);
                err = e > err ? e : err;
            }
            /* quadratic readers of the background set were extrapolating to t by the
               parabola through the last three points: what it showed there, minus the new
               point, fades out over the next macro step (rti_xset_value) */
            if (bg)
                sim->state.bg_jump[v] = n == RT_HIST ? parabola(sim, T, v, t) - y[v] : 0;
            else /* (a set steps at a fixed interval: a plain difference is a divided one) */
                sim->state.hist_d2[v] = n == RT_HIST ? hy[0][v] - 2 * hy[1][v] + hy[2][v]
                                                     : (real_t)0 / (real_t)0;
            for (int k = RT_HIST - 1; k > 0; k--)
                hy[k][v] = hy[k - 1][v];
            hy[0][v] = y[v];
        }
    }
    sim->stats.xset_err[s] = err;
    for (int k = RT_HIST - 1; k > 0; k--)
        T[k] = T[k - 1];
    T[0] = t;
    sim->state.hist_n[s] = (uint8_t)(n < RT_HIST ? n + 1 : RT_HIST);
    /* the new interval holds an event if the step that reached it fired one */
    unsigned ev = sim->state.hist_ev[s];
    ev = (ev << 1) | (ev & RTI_HIST_EV_STEP ? 1u : 0u);
    sim->state.hist_ev[s] = (uint8_t)(ev & ((1u << (RT_HIST - 1)) - 1));
}

/* the line through points k + 1 and k at t (point k held if it is the only one), and
   ahead of the background set's history the jump the line made at the newest point,
   faded */
static real_t extrap(const rt_sim *sim, const real_t *T, uint16_t v, int n, int k, real_t t,
                     int ahead, real_t fade)
{
    real_t e = k + 1 < n ? line(sim, T, v, k, k + 1, t) : sim->state.hist_y[k][v];
    if (ahead)
        e += (line(sim, T, v, 1, 2, T[0]) - sim->state.hist_y[0][v]) * fade;
    return e;
}

/* is an evaluation of block reader's set at t one at the end of the step (or step part)
   it is integrating? There a hold, or a line through the points before, reads a point at
   t as the left end of the interval before it (a sampled output's hold gives the same,
   rt/held.c): a method's stage at the step's end would otherwise read the next
   interval's value one step early. Not in a set whose parts end at instants with services
   (rt/tev.c), which take the value at the instant */
static int ends_there(const rt_sim *sim, uint16_t reader, real_t t)
{
    if (reader >= sim->sc->nblocks)
        return 0;
    uint8_t s = sim->sc->blocks[reader].set;
    if (sim->plan.set_flags[s] & (RTI_SET_TEV_SERVE | RTI_SET_STEP_END | RTI_SET_INSTANT_IN))
        return 0;
    real_t from = rti_tick_time(sim->state.set_tick[s], sim->sc->dt);
#if RT_MAX_TEV > 0
    if (sim->work.t_piece > 0)
        from = sim->work.t_piece; /* a part: its midpoint */
#endif
    return t > from;
}

real_t rti_xset_value(const rt_sim *sim, uint16_t v, uint8_t q, uint8_t scheme, real_t t,
                      uint16_t reader)
{
    const real_t *T = sim->state.hist_t[q];
    int n = sim->state.hist_n[q], k = 0;
    /* the common case first: a slower source has stepped past t, which lies between its
       two newest points, and the scheme interpolates (what the general path below gives
       there: k = 1, a bracket, never ahead) */
    if (n >= 2 && T[1] <= t && t < T[0] &&
        (scheme == RT_INTERP_LINEAR || scheme == RT_INTERP_HERMITE || scheme == RT_INTERP_QUAD))
        return n == RT_HIST && scheme != RT_INTERP_LINEAR ? parabola(sim, T, v, t)
                                                          : line(sim, T, v, 0, 1, t);
    /* the newest point at or before t (the source may have stepped past t already) */
    while (k + 1 < n && T[k] > t)
        k++;
    if ((scheme == RT_INTERP_HOLD || scheme == RT_INTERP_EXTRAP) && T[k] == t && k + 1 < n &&
        ends_there(sim, reader, t))
        k++;
    int bracket = k > 0 && T[k] <= t; /* points k and k - 1 enclose t */
    /* the background set is always read ahead of its history (rt/bg.c): the jump its
       extrapolation makes at each new point fades out over the next macro step, so the
       value read stays continuous (a jump looks like a step of the signal to a sampled
       derivative: on pendulum10_actuated the error at 10 s is 4e-6 m with the fade and
       4.6e-4 m without, docs/multirate.md "Background sets") */
    int ahead = q == sim->plan.bg_set && scheme != RT_INTERP_HOLD && n == RT_HIST && !bracket;
    real_t fade = 0;
    if (ahead) {
        fade = 1 - (t - T[0]) / (T[0] - T[1]);
        fade = fade > 0 ? fade : 0;
        /* quadratic: the parabola through the last three points (third order), with the
           jump it made at the newest point (rti_xset_push) */
        if (scheme == RT_INTERP_QUAD)
            return parabola(sim, T, v, t) + sim->state.bg_jump[v] * fade;
    }
    switch (scheme) {
    case RT_INTERP_EXTRAP:
        break;
    case RT_INTERP_HERMITE:
        if (n == RT_HIST && bracket)
            return parabola(sim, T, v, t);
        return bracket ? line(sim, T, v, k - 1, k, t) : extrap(sim, T, v, n, k, t, ahead, fade);
    case RT_INTERP_QUAD: /* inside the points and ahead of them; with fewer, as linear */
    case RT_INTERP_LINEAR: /* without a newer point: extrapolate */
        if (scheme == RT_INTERP_QUAD && n == RT_HIST)
            return parabola(sim, T, v, t);
        if (bracket)
            return line(sim, T, v, k - 1, k, t);
        break;
    default:
        return sim->state.hist_y[k][v];
    }
    return extrap(sim, T, v, n, k, t, ahead, fade);
}

int rti_xset_monitors(const rt_scene *sc, const rt_sim *sim, uint8_t s)
{
    (void)sc;
#if RT_MAX_XPRED > 0
    return sim->plan.xpred_of[s + 1] > sim->plan.xpred_of[s];
#else
    (void)sim, (void)s;
    return 0;
#endif
}
