/* check.c - owns the global-error check (`modrt check`, `modrt run --check`): the scene
 * runs again at half the steps of every set, in step with the run, and at every instant
 * where all sets of both runs are at a communication point the difference of each
 * recorded signal is scaled by Richardson's factor 1 / (1 - 2^-p):
 *
 *     y_h - y = C h^p + ...,  y_h/2 - y = C (h/2)^p + ...
 *     =>  |y_h - y| ~ |y_h - y_h/2| / (1 - 2^-p)
 *
 * p is the lowest order among the sets that integrate states and the couplings between
 * sets (hold 1, extrapolate and linear 2, hermite and quadratic 3): the error of the
 * slowest-converging part dominates as h shrinks.
 *
 * Halving: the base tick is halved and every set keeps its ratio, so every step halves
 * and stays a whole number of ticks. What is physics keeps its time: sampled (DSS)
 * blocks keep their periods in seconds, sources and time events their instants, the end
 * time stays; the controller link's period (in base ticks) doubles, though no exchange
 * takes place (a live link cannot run twice: the imports hold their defaults, as in a
 * run without --link).
 *
 * Events: a state event is located in each run to its own accuracy, so its time differs
 * a little between them. An instant where the two runs have handled different numbers of
 * events lies between the two event times: the difference there is the jump of the
 * signal, not an error estimate. It is left out of the estimate and reported apart
 * (err_ev, the stretch's length shift_s); runs that end with different numbers of events
 * have not resolved the event sequence, and the check says so (severity 1).
 *
 * Substeps: an implicit step that fails its Newton iteration, or a ROS2 step above its
 * accuracy, splits itself into substeps (docs/solvers.md). Then the two runs did not take
 * steps h and h/2 (at h = 4 h' and h/2 = 2 h' split into 4 and 2 substeps they compute
 * the same thing, and the difference is 0): a run with substeps has no estimate, and the
 * check says so (severity 1).
 *
 * Observed order (--observe): a third run at a quarter of the steps gives each signal's
 * q = log2(max |y_h - y_h/2| / max |y_h/2 - y_h/4|). A discontinuity inside a step, a
 * source read one step early, a step size outside the asymptotic range lower it below
 * the methods' p, and the formula with p then reads the error too small (by up to
 * (1 - 2^-p) / (1 - 2^-q): 1.9 for p = 4, q = 1); q below p - CHECK_Q_SLACK takes p's
 * place, and q below CHECK_Q_MIN (the differences do not shrink) leaves no estimate.
 *
 * Internal states: a block whose kind keeps state outside x, d and p (rt_kind.save: an
 * FMU's instance) is one object every run shares, since the half scene is a copy of the
 * run's tables. Each run's such state is kept apart here and put in place around that
 * run's ticks (swap_in), so no run steps another's FMU; a kind that cannot save its state
 * (an FMU without canGetAndSetFMUState) leaves the check refused, the run untouched.
 *
 * Host only: libc, no libm (rt_log, rt_exp of the runtime). */
#include <float.h>
#include <math.h> /* HUGE_VAL only: modrt links without libm */
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "cli.h"
#include "fmu.h" /* each run's FMU tallies */
#include "rt_sim.h" /* allocates the runs it compares with */

static rt_sim half;  /* the run at half the steps */
static rt_sim quarter; /* --observe: the run at a quarter of the steps */
static rt_sim own;   /* the run at the scene's steps, for check_scene */

enum { RUN_MAIN, RUN_HALF, RUN_QUARTER, RUNS };
_Static_assert(RUNS == FMU_TALLY_RUNS, "a tally slot per run (fmu.h)");
static uint8_t kst[RUNS][RT_MAX_KSTATE]; /* each run's blocks' internal states, in block
                                            order, each after its 4-byte size */

static struct {
    rt_scene sc;          /* the half scene */
    rt_link link;         /* its link, with the period doubled */
    rt_scene sc4;         /* the quarter scene */
    rt_link link4;
    check_opts o;
    check_result r;
    int kinds;            /* 1: a block keeps internal state (swap_in) */
    int differ;           /* the event counts differ since shift_from */
    uint64_t shift_from;
    char err[400];
} C;

const char *check_error(void)
{
    return C.err;
}

static rt_status refuse(rt_status st, const char *what, const char *detail)
{
    snprintf(C.err, sizeof C.err, "%s%s%s", what, detail ? ": " : "", detail ? detail : "");
    return st;
}

/* the blocks' internal states (rt_kind.save) into kst[run], or back from it (restore) */
static rt_status kstate(const rt_scene *sc, int run, int restore)
{
    return restore ? rt_kinds_restore(sc, kst[run], RT_MAX_KSTATE)
                   : rt_kinds_save(sc, kst[run], RT_MAX_KSTATE);
}

/* run `to`'s internal states in place of run `from`'s, which are kept first: 1 if done.
   0: the check has no estimate from here on (r.kstate_lost 1), and the run's own states
   are in place again: still there (its save failed), or put back from this tick's copy
   (else r.kstate_lost 2: the run goes on from another run's) */
static int swap_in(const rt_scene *sc, int from, int to)
{
    if (!C.kinds)
        return 1;
    if (C.r.kstate_lost)
        return 0; /* (the run's own are in place since the failure) */
    fmu_tally_keep(from); /* (what each FMU block met in each run: its own summary) */
    int saved = kstate(sc, from, 0) == RT_OK;
    if (saved && kstate(sc, to, 1) == RT_OK) {
        fmu_tally_use(to);
        return 1;
    }
    /* the run's tally, and the faults the failed calls met: they may have ended an FMU the
       run goes on with */
    fmu_tally_use_since(RUN_MAIN, from);
    C.r.kstate_lost = 1;
    if ((from != RUN_MAIN || saved) && kstate(sc, RUN_MAIN, 1) != RT_OK)
        C.r.kstate_lost = 2;
    return 0;
}

static double fabs_(double v)
{
    return v < 0 ? -v : v;
}

/* The global tolerance of recorded signal i, absolute and relative to its range: the
   options', or the set's own of the signal's block: `accuracy (R, A)`'s A and R (the
   runtime's scaled norm |e| / (A / R + |x|) <= R, rti_err_floor), `accuracy (E)` read as
   A = R = E. The one place it is read. */
static void sig_tol(const rt_scene *sc, uint16_t i, const check_opts *o, double *atol,
                    double *rtol)
{
    const rt_set *st = &sc->sets[sc->blocks[sc->recs[i].block].set];
    rt_set_cfg c = rt_set_cfg_of(&st->cfg);
    double acc = (double)c.accuracy, a = c.atol > 0 ? (double)c.atol : acc;
    *atol = o->atol >= 0 ? o->atol : a;
    *rtol = o->rtol >= 0 ? o->rtol : acc;
}

/* the order of convergence of a coupling scheme (rt/rt.h, RT_INTERP_LIST) */
static uint8_t interp_order(uint8_t i)
{
    static const uint8_t order[RT_INTERP_COUNT] = {
        [RT_INTERP_SET] = 1, [RT_INTERP_HOLD] = 1, [RT_INTERP_EXTRAP] = 2,
        [RT_INTERP_LINEAR] = 2, [RT_INTERP_HERMITE] = 3, [RT_INTERP_QUAD] = 3};
    return i < RT_INTERP_COUNT ? order[i] : 1;
}

static void why_add(const char *fmt, const char *a, const char *b, unsigned p)
{
    size_t n = strlen(C.r.why);
    if (n + 1 < sizeof C.r.why)
        snprintf(C.r.why + n, sizeof C.r.why - n, fmt, n ? ", " : "", a, b, p);
}

/* is connection c a sampled output of another set held by a set with states
   (RT_SRC_HELD): then the sample period and the reader's step, in base ticks */
static int held_reader(const rt_scene *sc, const rt_sim *sim, const rt_conn *c,
                       uint64_t *period, uint64_t *ratio)
{
    rt_interp in;
    uint8_t s = sc->blocks[c->to].set;
    *period = (uint64_t)((double)sc->blocks[c->from].ts / (double)sc->dt + 0.5);
    *ratio = sc->sets[s].ratio;
    return rt_input_source(sim, c->to, c->u, &in) == RT_SRC_HELD && rt_set_nx(sim, s) > 0 &&
           *period > 0;
}

/* the lowest order among the sets with states and the couplings between sets */
static void find_order(const rt_scene *sc, const rt_sim *sim)
{
    uint8_t p = 0, seen[RT_INTERP_COUNT] = {0};
    C.r.why[0] = 0;
    for (uint8_t s = 0; s < sc->nsets; s++) {
        if (rt_set_nx(sim, s) == 0)
            continue;
        uint8_t q = sc->sets[s].method->order;
        p = p == 0 || q < p ? q : p;
        why_add("%sset %s %s %u", sc->sets[s].name, sc->sets[s].method->name, q);
    }
    for (uint16_t b = 0; b < sc->nblocks; b++)
        for (uint16_t u = 0; u < sc->blocks[b].kind->nu; u++) {
            rt_interp in;
            if (rt_input_source(sim, b, u, &in) != RT_SRC_XSET || seen[in])
                continue;
            seen[in] = 1;
            uint8_t q = interp_order((uint8_t)in);
            p = p == 0 || q < p ? q : p;
            why_add("%s%s%s couplings %u", rt_interp_name(in), "", q);
        }
    /* a sampled output of another set read over a step that spans its samples or ends
       between them: the reader holds a sample where the staircase moves on, first order
       in its step (a 5 ms integrator reading a 2 ms hold) */
    for (uint16_t i = 0; i < sc->nconns && p > 1; i++) {
        uint64_t period, ratio;
        if (!held_reader(sc, sim, &sc->conns[i], &period, &ratio) || period % ratio == 0)
            continue;
        p = 1;
        why_add("%s%s%s couplings %u", "held samples", "", 1);
    }
    C.r.order = p;
}

/* a set with states reading a sampled output of another set (RT_SRC_HELD) whose half
   step spans more than one sample period and is no multiple of it: at h and at h/2 it
   reads one sample a step, and the half run's extra reads fall between the samples taken
   at its own step points, on samples the run read too (a plant of 30 ms holding a 10 ms
   controller that reads the plant held: at 15 ms it reads the sample of 10 ms, made from
   the plant at 0; the runs agree at every compared instant, 4 times the tolerance off).
   A half step that is a multiple of the period reads a sample made at its own start,
   which the run did not: the difference shows the coupling (20 and 60 ms there). Only
   where the sampled block reads the reader's set (a loop): a sample made of other sets'
   signals differs between the runs' reads, and the difference shows it. The first such
   coupling, into r.skip */
static int reads_set(const rt_scene *sc, uint16_t b, uint8_t s)
{
    for (uint16_t i = 0; i < sc->nconns; i++)
        if (sc->conns[i].to == b && sc->blocks[sc->conns[i].from].set == s)
            return 1;
    return 0;
}

static void find_skips(const rt_scene *sc, const rt_sim *sim)
{
    C.r.skip[0] = 0;
    for (uint16_t i = 0; i < sc->nconns && !C.r.skip[0]; i++) {
        const rt_conn *c = &sc->conns[i];
        uint8_t s = sc->blocks[c->to].set;
        uint64_t period, ratio;
        if (!held_reader(sc, sim, c, &period, &ratio) || ratio <= 2 * period ||
            ratio % (2 * period) == 0 || !reads_set(sc, c->from, s))
            continue;
        snprintf(C.r.skip, sizeof C.r.skip, "set %s steps %g s over samples of %s every %g s",
                 sc->sets[s].name, (double)ratio * sc->dt, sc->blocks[c->from].name,
                 (double)sc->blocks[c->from].ts);
    }
}

/* base ticks between instants where every set is at a communication point: the least
   common multiple of the ratios (0 if it passes n) */
static uint64_t meet_every(const rt_scene *sc, uint64_t n)
{
    uint64_t l = 1;
    for (uint8_t s = 0; s < sc->nsets; s++) {
        uint64_t a = l, b = sc->sets[s].ratio;
        while (b) {
            uint64_t t = a % b;
            a = b, b = t;
        }
        l = l / a * sc->sets[s].ratio;
        if (l > n)
            return 0;
    }
    return l;
}

rt_status check_begin(const rt_scene *sc, const rt_sim *sim, const check_opts *o,
                      check_setup setup, void *ctx)
{
    char b[160];
    memset(&C.r, 0, sizeof C.r);
    C.err[0] = 0, C.o = *o, C.differ = 0, C.kinds = 0;
    C.r.atol = o->atol, C.r.rtol = o->rtol;
    uint64_t n = rt_tick_count(sim);
    if (n > RT_MAX_TICKS / 2) {
        snprintf(b, sizeof b, "%.10g s at half the base tick", (double)sc->t_end);
        return refuse(RT_E_CAPACITY, "the check's run exceeds RT_MAX_TICKS (2^53 ticks)", b);
    }
    C.r.every = meet_every(sc, n);
    if (C.r.every == 0)
        return refuse(RT_E_ARG, "the sets' steps meet no instant before the end time (the "
                      "least common multiple of their ratios): nothing to compare", NULL);
    C.r.every_s = (double)C.r.every * (double)sc->dt;
    for (uint16_t i = 0; i < sc->nrecs; i++) {
        char name[96];
        cli_rec_name(sc, i, name, sizeof name);
        C.r.sig[i].on = cli_selected(name, o->only);
        C.r.nsig += (uint16_t)C.r.sig[i].on;
    }
    if (C.r.nsig == 0)
        return refuse(RT_E_ARG, "no recorded signal to check", o->only);
    find_order(sc, sim);
    find_skips(sc, sim);
    if (o->csv) {
        fputs("t", o->csv);
        for (uint16_t i = 0; i < sc->nrecs; i++) {
            char name[96];
            cli_rec_name(sc, i, name, sizeof name);
            if (C.r.sig[i].on)
                fprintf(o->csv, ",%s", name);
        }
        fputc('\n', o->csv);
    }
    C.sc = *sc;
    C.sc.dt = sc->dt / 2; /* every set keeps its ratio: its step halves */
    if (sc->link) {
        C.link = *sc->link;
        C.link.period *= 2; /* the same exchange instants (none takes place) */
        C.sc.link = &C.link;
    }
    C.r.dt_half = (double)C.sc.dt;
    for (uint16_t b = 0; b < sc->nblocks; b++)
        C.kinds |= sc->blocks[b].kind->save != NULL;
    rt_status st = C.kinds ? kstate(sc, RUN_MAIN, 0) : RT_OK;
    if (st != RT_OK)
        return refuse(st, "a block's internal state (an FMU's) cannot be saved, so the run "
                      "at half the steps cannot have its own", rt_status_name(st));
    fmu_tally_keep(RUN_MAIN), fmu_tally_zero();
    if ((st = rt_init(&C.sc, &half)) != RT_OK)
        return refuse(st, "the scene at half the steps", rt_error_text(&half));
    if (setup && setup(ctx, &C.sc, &half) != 0)
        return refuse(RT_E_ARG, "the scene at half the steps: an override failed", NULL);
    if (C.kinds && kstate(sc, RUN_HALF, 0) != RT_OK)
        return refuse(RT_E_SNAPSHOT, "the half run's internal states", NULL);
    fmu_tally_keep(RUN_HALF);
    C.r.observe = o->observe;
    if (!o->observe) {
        fmu_tally_use(RUN_MAIN);
        return C.kinds && kstate(sc, RUN_MAIN, 1) != RT_OK
                   ? refuse(RT_E_SNAPSHOT, "the run's internal states back", NULL) : RT_OK;
    }
    if (n > RT_MAX_TICKS / 4)
        return refuse(RT_E_CAPACITY, "the check's quarter run exceeds RT_MAX_TICKS", NULL);
    C.sc4 = C.sc;
    C.sc4.dt = C.sc.dt / 2;
    fmu_tally_zero();
    if (sc->link) {
        C.link4 = C.link;
        C.link4.period *= 2;
        C.sc4.link = &C.link4;
    }
    if ((st = rt_init(&C.sc4, &quarter)) != RT_OK)
        return refuse(st, "the scene at a quarter of the steps", rt_error_text(&quarter));
    if (setup && setup(ctx, &C.sc4, &quarter) != 0)
        return refuse(RT_E_ARG, "the scene at a quarter of the steps: an override failed",
                      NULL);
    if (C.kinds && (kstate(sc, RUN_QUARTER, 0) != RT_OK || kstate(sc, RUN_MAIN, 1) != RT_OK))
        return refuse(RT_E_SNAPSHOT, "the quarter run's internal states", NULL);
    fmu_tally_keep(RUN_QUARTER), fmu_tally_use(RUN_MAIN);
    return RT_OK;
}

/* the estimate at the current instant (both runs at time t) */
static void compare(const rt_scene *sc, const rt_sim *sim)
{
    static const double two[] = {1, 2, 4, 8, 16, 32, 64, 128, 256};
    uint8_t p = C.r.order < 8 ? C.r.order : 8;
    double factor = p ? 1 / (1 - 1 / two[p]) : 1; /* nothing integrated: exact difference */
    double t = (double)rt_time(sc, sim);
    uint32_t ev = rt_stats_of(sim)->count[RT_CNT_EVENTS];
    int differ = ev != rt_stats_of(&half)->count[RT_CNT_EVENTS] ||
                 (C.r.observe && ev != rt_stats_of(&quarter)->count[RT_CNT_EVENTS]);
    if (differ && !C.differ)
        C.shift_from = rt_ticks_done(sim);
    if (differ || C.differ) { /* the stretch ends at the first instant they agree again */
        double len = (double)(rt_ticks_done(sim) - C.shift_from) * (double)sc->dt;
        C.r.shift_s = len > C.r.shift_s ? len : C.r.shift_s;
    }
    C.differ = differ;
    C.r.nshift += (uint64_t)differ;
    C.r.ncmp += (uint64_t)!differ;
    if (C.o.csv && !differ)
        fprintf(C.o.csv, "%.17g", t);
    for (uint16_t i = 0; i < sc->nrecs; i++) {
        check_sig *g = &C.r.sig[i];
        if (!g->on)
            continue;
        double y = (double)rt_rec_value(sc, sim, i), yh = (double)rt_rec_value(&C.sc, &half, i);
        double d = fabs_(y - yh), a = fabs_(y);
        if (!(d <= DBL_MAX)) /* not finite in one of the runs */
            d = HUGE_VAL;
        g->range = a <= DBL_MAX && a > g->range ? a : g->range;
        if (differ) {
            if (d > g->err_ev)
                g->err_ev = d, g->t_ev = t;
        } else {
            if (factor * d > g->err)
                g->err = factor * d, g->t = t;
            if (C.r.observe) {
                double d2 = fabs_(yh - (double)rt_rec_value(&C.sc4, &quarter, i));
                g->d1 = d > g->d1 ? d : g->d1;
                g->d2 = d2 > g->d2 || !(d2 <= DBL_MAX) ? d2 : g->d2;
            }
            if (C.o.csv)
                fprintf(C.o.csv, ",%.3e", factor * d);
        }
    }
    if (C.o.csv && !differ)
        fputc('\n', C.o.csv);
}

void check_tick(const rt_scene *sc, const rt_sim *sim)
{
    if (rt_ticks_done(sim) == 0) /* the initial state: the same in both runs */
        return;
    if (!swap_in(sc, RUN_MAIN, RUN_HALF))
        return; /* (no estimate: the half run stops) */
    for (int k = 0; k < 2 && rt_ticks_done(&half) < rt_tick_count(&half); k++)
        rt_tick(&C.sc, &half);
    int last = RUN_HALF;
    if (C.r.observe && swap_in(sc, RUN_HALF, RUN_QUARTER)) {
        last = RUN_QUARTER;
        for (int k = 0; k < 4 && rt_ticks_done(&quarter) < rt_tick_count(&quarter); k++)
            rt_tick(&C.sc4, &quarter);
    }
    swap_in(sc, last, RUN_MAIN);
    if (rt_ticks_done(sim) % C.r.every == 0)
        compare(sc, sim);
}

/* observe: the observed order of signal g, and the estimate by it where it is below p.
   Differences within a few thousand roundings of the signal's size carry no order. */
static void observed(check_sig *g)
{
    double noise = 1e3 * (double)RT_EPS * (1 + g->range);
    if (!(g->d1 > noise) && g->d2 > noise) { /* h and h/2 agree, h/4 does not: aliased */
        g->q_none = 1;
        return;
    }
    if (!(g->d1 > noise && g->d2 > noise) || !(g->d1 <= DBL_MAX && g->d2 <= DBL_MAX))
        return;
    g->q = (double)(rt_log((real_t)(g->d1 / g->d2)) / rt_log((real_t)2));
    if (g->q < CHECK_Q_MIN) {
        g->q_none = 1;
        return;
    }
    if (g->q < C.r.order - CHECK_Q_SLACK) {
        /* the largest difference over (1 - 2^-q): d1 is max |y_h - y_h/2| */
        g->err = g->d1 / (1 - (double)rt_exp((real_t)(-g->q) * rt_log((real_t)2)));
        g->q_used = 1;
    }
}

void check_end(const rt_scene *sc, const rt_sim *sim, check_result *r)
{
    C.r.events = rt_stats_of(sim)->count[RT_CNT_EVENTS];
    C.r.events_half = rt_stats_of(&half)->count[RT_CNT_EVENTS];
    C.r.status_half = rt_stats_of(&half)->status;
    C.r.substeps = rt_stats_of(sim)->count[RT_CNT_SUBSTEP];
    C.r.substeps_half = rt_stats_of(&half)->count[RT_CNT_SUBSTEP];
    if (C.r.observe) {
        C.r.status_quarter = rt_stats_of(&quarter)->status;
        C.r.events_quarter = rt_stats_of(&quarter)->count[RT_CNT_EVENTS];
        C.r.substeps_quarter = rt_stats_of(&quarter)->count[RT_CNT_SUBSTEP];
    }
    int sev = 0;
    for (uint16_t i = 0; i < sc->nrecs; i++) {
        check_sig *g = &C.r.sig[i];
        double atol, rtol;
        if (!g->on)
            continue;
        sig_tol(sc, i, &C.o, &atol, &rtol);
        g->tol = atol + rtol * g->range;
        if (C.r.observe)
            observed(g);
        int s = g->err > (double)RT_ERR_LOST * (1 + g->range) ? 2
                : g->err > g->tol || g->q_none;
        sev = s > sev ? s : sev;
    }
    if ((C.r.events != C.r.events_half || C.r.substeps || C.r.substeps_half ||
         C.r.skip[0]) && sev < 1)
        sev = 1;
    if (C.r.observe && (C.r.events != C.r.events_quarter || C.r.substeps_quarter) && sev < 1)
        sev = 1;
    if (rt_status_severity(C.r.status_half) >= 2 || C.r.kstate_lost ||
        (C.r.observe && rt_status_severity(C.r.status_quarter) >= 2))
        sev = 2;
    /* a run at a finer step that doubts its own answer where the run does not: the two
       do not tell the run's error (a signal aliased at h and h/2 alike reads 0) */
    if ((rt_status_severity(C.r.status_half) >= 1 ||
         (C.r.observe && rt_status_severity(C.r.status_quarter) >= 1)) && sev < 1)
        sev = 1;
    C.r.severity = sev;
    *r = C.r;
}

rt_status check_scene(const rt_scene *sc, const check_opts *o, check_setup setup, void *ctx,
                      check_result *r)
{
    rt_status st = rt_init(sc, &own);
    if (st != RT_OK)
        return refuse(st, "the scene", rt_error_text(&own));
    if (setup && setup(ctx, sc, &own) != 0)
        return refuse(RT_E_ARG, "an override failed", NULL);
    if ((st = check_begin(sc, &own, o, setup, ctx)) != RT_OK)
        return st;
    while (rt_ticks_done(&own) < rt_tick_count(&own)) {
        rt_tick(sc, &own);
        check_tick(sc, &own);
    }
    check_end(sc, &own, r);
    return RT_OK;
}

/* ------------------------------------------------------------------ printing */

static const char *verdict(const check_result *r, const check_sig *g)
{
    return r->substeps || r->substeps_half ? "no estimate (substeps)"
           : g->q_none                       ? "no estimate (the runs do not converge)"
           : g->err > (double)RT_ERR_LOST * (1 + g->range) ? "no correct digit"
           : g->err > g->tol                             ? "above tolerance"
                                                          : "ok";
}

void check_print(FILE *f, const rt_scene *sc, const check_result *r)
{
    static const char *sev[] = {"ok", "doubtful", "failed"};
    fprintf(f, "check: every set again at half its step (base tick %g s, ratios kept); "
               "Richardson estimate |y_h - y_h/2| / (1 - 2^-p)\n", r->dt_half);
    if (r->order)
        fprintf(f, "check_order: %u (the lowest of: %s)\n", (unsigned)r->order, r->why);
    else
        fprintf(f, "check_order: none (no set integrates a state: the difference itself)\n");
    if (r->atol >= 0)
        fprintf(f, "global_tol: atol %g", r->atol);
    else
        fputs("global_tol: atol = the absolute accuracy of the signal's set (its accuracy's A, "
              "else its accuracy)", f);
    if (r->rtol >= 0)
        fprintf(f, ", rtol %g", r->rtol);
    else
        fputs(", rtol = its accuracy", f);
    fputs(" (a signal's tolerance: atol + rtol * its largest |y|)\n", f);
    fprintf(f, "check_compared: %llu instants every %g s\n", (unsigned long long)r->ncmp,
            r->every_s);
    fprintf(f, "check_half_status: %s\n", rt_status_name(r->status_half));
    if (r->observe)
        fprintf(f, "check_quarter_status: %s (base tick %g s: each signal's observed order "
                   "log2(max |y_h - y_h/2| / max |y_h/2 - y_h/4|))\n",
                rt_status_name(r->status_quarter), r->dt_half / 2);
    if (r->events || r->events_half)
        fprintf(f, "check_events: %u, at half the steps %u%s; %llu instants between the "
                   "runs' event times left out (longest stretch %g s)\n",
                (unsigned)r->events, (unsigned)r->events_half,
                r->events != r->events_half ? " (different: the event sequence is not "
                                              "resolved)" : "",
                (unsigned long long)r->nshift, r->shift_s);
    if (r->kstate_lost)
        fprintf(f, "check_kstate: a block's internal state (an FMU's) could not be swapped "
                   "between the runs: no estimate%s\n", r->kstate_lost > 1
                   ? "; the run went on from another run's state, its answer is not the "
                     "scene's" : "");
    if (r->substeps || r->substeps_half)
        fprintf(f, "check_substeps: %u, at half the steps %u (steps split into substeps did "
                   "not take h and h/2: the estimates below are no estimates)\n",
                (unsigned)r->substeps, (unsigned)r->substeps_half);
    if (r->skip[0])
        fprintf(f, "check_skipped_samples: %s, at half the steps too (it reads one sample a "
                   "step and skips the others in both runs: their difference need not show "
                   "that coupling's error; a step of at most twice the period, or an even "
                   "multiple of it, is checked)\n",
                r->skip);
    for (uint16_t i = 0; i < sc->nrecs; i++) {
        const check_sig *g = &r->sig[i];
        char name[96];
        if (!g->on)
            continue;
        cli_rec_name(sc, i, name, sizeof name);
        fprintf(f, "global_err.%s: %.3g at t = %.6g s (tol %.3g): %s", name, g->err, g->t,
                g->tol, verdict(r, g));
        if (r->observe && g->q > 0)
            fprintf(f, "; observed order %.2f%s", g->q,
                    g->q_used ? ", below p: the estimate takes it" : "");
        fputc('\n', f);
        if (g->err_ev > 0)
            fprintf(f, "event_shift_diff.%s: %.3g at t = %.6g s (between the runs' events: "
                       "not an estimate)\n", name, g->err_ev, g->t_ev);
    }
    fprintf(f, "global_status: %s\n", sev[r->severity]);
}
