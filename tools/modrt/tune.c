/* tune.c - owns `modrt tune`: offline error control of fixed multirate schedules (issue 6,
 * item 2; NUMERICS.md, "Choosing a fixed schedule offline"). The run-time side, the
 * monitor rt_sim.xset_err, lives in rt/xset.c; this file only reads it.
 *
 * 1. Reference: every set at the finest candidate ratio r_min on the base tick divided by
 *    ref_div. Its own error is estimated by a second run at half that resolution.
 * 2. Candidates: each set's ratio r_min 2^k, k = 0 .. K. Powers of two nest, so at every
 *    multiple of a schedule's largest ratio all its sets sit at a communication point;
 *    its recorded signals are compared with the reference there (the reference is kept
 *    every r_min ticks, or every power-of-two multiple of that which fits the limit).
 * 3. Search: candidates run in the order of a lower bound of their cost (stages per step
 *    times steps times states: exact for explicit methods, implicit ones evaluate more).
 *    A run stops at the first comparison above the tolerance; the search stops when the
 *    bound of the next candidate reaches the cheapest measured cost within tolerance, so
 *    the result is the cheapest candidate by measured cost, not by the bound.
 * 4. Check: a candidate within the tolerance of the reference meets it only when its own
 *    estimated global error does too (check.c: the schedule again at half its steps,
 *    Richardson): a reference of a first-order method at a quarter of the step carries a
 *    quarter of the candidate's error, so |y - y_ref| alone reads 3/4 of the true error.
 * Cost: right-hand-side evaluations times the states of the set, summed over sets, per
 * simulated second (rt_stats.rhs_evals, counted by the runtime). Deterministic, unlike
 * host time, which is printed beside it.
 *
 * Host only: libc and the POSIX CPU clock; no libm (modrt links without it). */
#define _POSIX_C_SOURCE 200809L
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "check.h"
#include "cli.h"
#include "tune.h"
#include "rt_sim.h" /* allocates the trial runs */

#define DEFAULT_DOUBLINGS 6 /* candidate ratios up to 64 r_min */
#define DEFAULT_REF_DIV 4   /* the reference's base tick: a quarter of the scene's */
#define SAMPLES_MIN 8       /* comparison instants a tuning wants at least */
#define NAME_LEN 96         /* "Block.signal" */
#define INF_ERR 1e300       /* the error of a run that produced a non-finite value */

static rt_sim sim; /* the runtime's storage, owned here */

/* ------------------------------------------------------------------ tuning state */

static struct {
    const rt_scene *sc;          /* the scene tuned */
    tune_opts o;                 /* options with defaults filled in */
    rt_scene trial;              /* the scene with the schedule under test */
    rt_set sets[RT_MAX_SETS];
    uint16_t sig[RT_MAX_REC];    /* recorded signals compared */
    uint16_t nsig;
    double w[RT_MAX_SETS];       /* cost weight of a set: its states (at least 1) */
    uint64_t n_ticks;            /* base ticks to the end */
    uint32_t grid;               /* interval of the reference's samples [base ticks] */
    uint32_t nsamp;              /* reference samples */
    real_t ref[TUNE_SAMPLES_MAX][RT_MAX_REC]; /* the reference every grid ticks */
} T;

static uint32_t cand[TUNE_CANDIDATES_MAX];   /* schedules as base-(K+1) digit strings */
static double cand_lb[TUNE_CANDIDATES_MAX];  /* their cost bounds */
static uint32_t order[TUNE_CANDIDATES_MAX];

static double cpu_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* the trial scene: sc with ratio[] on the base tick divided by div */
static void configure(const uint32_t *ratio, uint32_t div)
{
    const rt_scene *sc = T.sc;
    T.trial = *sc;
    T.trial.dt = sc->dt / (real_t)div;
    for (uint8_t s = 0; s < sc->nsets; s++) {
        T.sets[s] = sc->sets[s];
        T.sets[s].ratio = ratio[s];
    }
    T.trial.sets = T.sets;
}

/* largest |y - y_ref| at comparison instant j (INF_ERR for a non-finite value) */
static double compare(uint32_t j)
{
    double e = 0;
    for (uint16_t i = 0; i < T.nsig; i++) {
        double d = (double)rt_rec_value(&T.trial, &sim, T.sig[i]) - (double)T.ref[j][i];
        d = d < 0 ? -d : d;
        if (!(d <= INF_ERR))
            return INF_ERR;
        e = d > e ? d : e;
    }
    return e;
}

/* what the finished (or cut) run measured besides the error */
static void account(tune_sched *m, double t0)
{
    const rt_scene *sc = T.sc;
    const rt_stats *z = rt_stats_of(&sim);
    static const rt_counter faults[] = {RT_CNT_NAN, RT_CNT_EVENT_LIMIT, RT_CNT_EVENT_NOLOC,
                                        RT_CNT_NOCONV, RT_CNT_SINGULAR, RT_CNT_DEGRADED,
                                        RT_CNT_UNSTABLE};
    m->host_s = cpu_s() - t0;
    m->cost = 0;
    for (uint8_t s = 0; s < sc->nsets; s++) {
        m->ratio[s] = T.sets[s].ratio;
        m->evals[s] = (double)z->rhs_evals[s] / (double)sc->t_end; /* counted by rt/ */
        m->cost += m->evals[s] * T.w[s];
        m->xset_err[s] = (double)z->xset_err[s];
    }
    /* a step's error estimate above its accuracy (severity 1) is not a fault here: the
       tuner measures the error itself, against its reference */
    m->clean = rt_status_severity(z->status) < 2;
    for (unsigned i = 0; i < sizeof faults / sizeof faults[0]; i++)
        m->clean = m->clean && z->count[faults[i]] == 0;
}

typedef enum { RUN_REF, RUN_FULL, RUN_CUT } run_mode;

/* runs the schedule ratio[] on the base tick / div: RUN_REF stores the reference every
   T.grid ticks; the others compare at the reference's samples where every set is at a
   communication point (multiples of the largest ratio), RUN_CUT stops above tol */
static rt_status run(const uint32_t *ratio, uint32_t div, run_mode mode, tune_sched *m)
{
    configure(ratio, div);
    *m = (tune_sched){.complete = 1, .gerr = -1};
    double t0 = cpu_s();
    rt_status st = rt_init(&T.trial, &sim);
    if (st != RT_OK)
        return st;
    uint64_t grid = (uint64_t)T.grid * div, every = grid;
    for (uint8_t s = 0; s < T.sc->nsets && mode != RUN_REF; s++)
        every = ratio[s] > every ? ratio[s] : every; /* powers of two: a multiple of grid */
    for (rt_status ts = RT_OK; ts == RT_OK;) {
        ts = rt_tick(&T.trial, &sim);
        uint64_t j = rt_ticks_done(&sim) / grid - 1;
        if (rt_ticks_done(&sim) % every != 0 || j >= T.nsamp)
            continue;
        if (mode == RUN_REF) {
            for (uint16_t i = 0; i < T.nsig; i++)
                T.ref[j][i] = rt_rec_value(&T.trial, &sim, T.sig[i]);
            continue;
        }
        double e = compare((uint32_t)j);
        if (e > m->err || (e == m->err && m->t_err == 0))
            m->err = e, m->t_err = (double)rt_time(&T.trial, &sim);
        if (mode == RUN_CUT && e > T.o.tol) {
            m->complete = 0;
            break;
        }
    }
    account(m, t0);
    return RT_OK;
}

/* ------------------------------------------------------------------ setup */

/* options with defaults; the signals compared; the set weights */
static rt_status setup(const rt_scene *sc, const tune_opts *o)
{
    T.sc = sc;
    T.o = *o;
    if (!T.o.doublings)
        T.o.doublings = DEFAULT_DOUBLINGS;
    T.o.doublings = T.o.doublings > TUNE_DOUBLINGS_MAX ? TUNE_DOUBLINGS_MAX : T.o.doublings;
    if (!T.o.ref_div)
        T.o.ref_div = DEFAULT_REF_DIV;
    if (!(T.o.tol > 0) || T.o.ref_div < 2 || (T.o.ref_div & (T.o.ref_div - 1)) != 0)
        return RT_E_ARG;
    T.nsig = 0;
    for (uint16_t i = 0; i < sc->nrecs; i++) {
        char name[NAME_LEN];
        cli_rec_name(sc, i, name, sizeof name);
        if (cli_selected(name, T.o.only))
            T.sig[T.nsig++] = i;
    }
    if (T.nsig == 0)
        return RT_E_ARG;
    rt_status st = rt_init(sc, &sim);
    if (st != RT_OK)
        return st;
    for (uint8_t s = 0; s < sc->nsets; s++) {
        unsigned n = rt_set_nx(&sim, s);
        T.w[s] = n ? (double)n : 1;
    }
    T.n_ticks = rt_tick_count(&sim);
    return RT_OK;
}

/* the finest candidate ratio: the smallest the scene declares */
static uint32_t finest(const rt_scene *sc)
{
    uint32_t r = sc->sets[0].ratio;
    for (uint8_t s = 1; s < sc->nsets; s++)
        r = sc->sets[s].ratio < r ? sc->sets[s].ratio : r;
    return r;
}

/* doublings (the coarsest candidate still compares SAMPLES_MIN times) and the
   reference's sampling interval (every r_min ticks, or a power of two of it that fits) */
static void choose_grid(tune_result *r)
{
    uint64_t n = T.n_ticks;
    unsigned K = T.o.doublings;
    uint64_t count = 1;
    while (K > 0 && (uint64_t)r->r_min << K > n / SAMPLES_MIN)
        K--;
    for (;;) { /* (K+1)^nsets schedules */
        count = 1;
        for (uint8_t s = 0; s < T.sc->nsets; s++)
            count *= K + 1;
        if (count <= TUNE_CANDIDATES_MAX || K == 0)
            break;
        K--;
    }
    T.grid = r->r_min;
    while (n / T.grid > TUNE_SAMPLES_MAX)
        T.grid *= 2;
    T.nsamp = (uint32_t)(n / T.grid);
    r->doublings = K;
    r->ncand = (unsigned)count;
    r->grid_s = (double)T.sc->dt * T.grid;
}

/* ratios of candidate c (digits of base K+1, set 0 lowest) */
static void decode(uint32_t c, const tune_result *r, uint32_t *ratio)
{
    for (uint8_t s = 0; s < T.sc->nsets; s++) {
        ratio[s] = r->r_min << (c % (r->doublings + 1));
        c /= r->doublings + 1;
    }
}

/* lower bound of the cost: every stage evaluated once per step (an explicit method's
   error estimate included: it always takes its evaluations) */
static double bound(const uint32_t *ratio)
{
    double b = 0;
    for (uint8_t s = 0; s < T.sc->nsets; s++) {
        double steps = (double)((T.n_ticks + ratio[s] - 1) / ratio[s]);
        const rt_integrator *m = T.sc->sets[s].method;
        uint32_t per = m->implicit ? m->stages : rt_step_bound(T.sc, s, 1).rhs;
        b += per * steps * T.w[s];
    }
    return b / (double)T.sc->t_end;
}

/* a set cannot step past a sample of its discrete blocks (rt_init refuses it): a
   candidate is admissible when every DSS period is a whole number of its set's steps */
static int admissible(const uint32_t *ratio)
{
    const rt_scene *sc = T.sc;
    for (uint16_t b = 0; b < sc->nblocks; b++) {
        const rt_block *bl = &sc->blocks[b];
        if (bl->kind->type != RT_KIND_DSS)
            continue;
        double r = (double)bl->ts / (double)sc->dt; /* rt_init: a whole number of ticks */
        uint64_t n = r >= 0.5 && r < 1.8e19 ? (uint64_t)(r + 0.5) : 0;
        if (n == 0 || n % ratio[bl->set] != 0)
            return 0;
    }
    return 1;
}

static int by_bound(const void *a, const void *b)
{
    uint32_t i = *(const uint32_t *)a, j = *(const uint32_t *)b;
    if (cand_lb[i] != cand_lb[j])
        return cand_lb[i] < cand_lb[j] ? -1 : 1;
    return i < j ? -1 : i > j;
}

/* ------------------------------------------------------------------ search */

static void print_ratios(FILE *f, const tune_sched *m)
{
    for (uint8_t s = 0; s < T.sc->nsets; s++)
        fprintf(f, "%s%s %u", s ? " " : "", T.sc->sets[s].name, (unsigned)m->ratio[s]);
}

static void log_try(FILE *log, const tune_sched *m, double lb, int ok)
{
    if (!log)
        return;
    fprintf(log, "  try ");
    print_ratios(log, m);
    fprintf(log, ": bound %.3g, %s error %.3g at t = %.4g s, cost %.4g", lb,
            m->complete ? "" : "cut at", m->err, m->t_err, m->cost);
    if (m->gerr >= 0)
        fprintf(log, ", estimated global error %.3g at t = %.4g s", m->gerr, m->t_gerr);
    fputs(ok ? " (within)\n" : !m->clean ? " (faults)\n"
          : m->gerr >= 0 ? " (the estimate is not within)\n" : "\n", log);
}

/* the schedule in T.trial checked by its own half-step run against tol (absolute, on the
   compared signals): m->gerr, m->gok */
static rt_status global_check(tune_sched *m)
{
    static check_result cr;
    check_opts o = {T.o.tol, 0, T.o.only, NULL, 0};
    rt_status st = check_scene(&T.trial, &o, NULL, NULL, &cr);
    if (st != RT_OK)
        return st;
    m->gerr = 0, m->t_gerr = 0;
    for (uint16_t i = 0; i < T.sc->nrecs; i++)
        if (cr.sig[i].on && cr.sig[i].err > m->gerr)
            m->gerr = cr.sig[i].err, m->t_gerr = cr.sig[i].t;
    m->gok = cr.severity == 0;
    return RT_OK;
}

/* the reference and its self-check */
static rt_status reference(tune_result *r)
{
    uint32_t fine[RT_MAX_SETS];
    tune_sched half;
    for (uint8_t s = 0; s < T.sc->nsets; s++)
        fine[s] = r->r_min;
    rt_status st = run(fine, T.o.ref_div, RUN_REF, &half);
    if (st == RT_OK)
        st = run(fine, T.o.ref_div / 2, RUN_FULL, &half);
    r->ref_err = half.err;
    return st;
}

rt_status tune_scene(const rt_scene *sc, const tune_opts *o, tune_result *r, FILE *log)
{
    *r = (tune_result){0};
    rt_status st = setup(sc, o);
    if (st != RT_OK)
        return st;
    r->nsig = T.nsig;
    r->r_min = finest(sc);
    choose_grid(r);
    if (T.nsamp == 0 || (st = reference(r)) != RT_OK)
        return T.nsamp == 0 ? RT_E_ARG : st;
    uint32_t ratio[RT_MAX_SETS];
    for (uint32_t c = 0; c < r->ncand; c++) {
        decode(c, r, ratio);
        cand[c] = c, cand_lb[c] = bound(ratio), order[c] = c;
    }
    qsort(order, r->ncand, sizeof order[0], by_bound);
    for (uint32_t i = 0; i < r->ncand; i++) {
        uint32_t c = order[i];
        if (r->found && cand_lb[c] >= r->best.cost)
            break;
        tune_sched m;
        decode(cand[c], r, ratio);
        if (!admissible(ratio))
            continue;
        if ((st = run(ratio, 1, RUN_CUT, &m)) != RT_OK)
            return st;
        r->nrun++;
        int ok = m.complete && m.clean && m.err <= T.o.tol;
        if (ok && (st = global_check(&m)) != RT_OK)
            return st;
        ok = ok && m.gok;
        log_try(log, &m, cand_lb[c], ok);
        if (ok && (!r->found || m.cost < r->best.cost))
            r->best = m, r->found = 1;
    }
    for (uint8_t s = 0; s < sc->nsets; s++)
        ratio[s] = sc->sets[s].ratio;
    if ((st = run(ratio, 1, RUN_FULL, &r->declared)) != RT_OK)
        return st;
    return global_check(&r->declared);
}

rt_status tune_measure(const rt_scene *sc, const uint32_t *ratio, tune_sched *out)
{
    if (sc != T.sc)
        return RT_E_ARG;
    return run(ratio, 1, RUN_FULL, out);
}

/* ------------------------------------------------------------------ command line */

tune_cli_args tune_cli_ctx;

static int opt_tol(void *ctx, const char *v)
{
    double x;
    if (!cli_real(v, &x) || !(x > 0))
        return cli_fail("--tol expects a tolerance > 0, got", v);
    ((tune_cli_args *)ctx)->o.tol = x;
    return CLI_OK;
}

static int opt_only(void *ctx, const char *v)
{
    ((tune_cli_args *)ctx)->o.only = v;
    return CLI_OK;
}

static int opt_doublings(void *ctx, const char *v)
{
    unsigned long n;
    if (!cli_uint(v, 1, TUNE_DOUBLINGS_MAX, &n))
        return cli_fail("--doublings expects a whole number from 1 to 12, got", v);
    ((tune_cli_args *)ctx)->o.doublings = (unsigned)n;
    return CLI_OK;
}

static int opt_ref_div(void *ctx, const char *v)
{
    unsigned long n;
    if (!cli_uint(v, 2, TUNE_REF_DIV_MAX, &n) || (n & (n - 1)) != 0)
        return cli_fail("--ref-div expects a power of two from 2 to 1024, got", v);
    ((tune_cli_args *)ctx)->o.ref_div = (unsigned)n;
    return CLI_OK;
}

static int opt_verbose(void *ctx, const char *v)
{
    (void)v;
    ((tune_cli_args *)ctx)->verbose = 1;
    return CLI_OK;
}

const cli_opt tune_cli_opts[] = {
    {"tol", "E", "largest accepted |y - y_ref| over the compared signals (required)", opt_tol},
    {"only", "P,...", "compare only recorded signals starting with these prefixes", opt_only},
    {"doublings", "K", "candidate ratios r_min * 2^0..K (default 6, at most 12)",
     opt_doublings},
    {"ref-div", "N", "the reference steps at the base tick / N (power of two, default 4)",
     opt_ref_div},
    {"verbose", NULL, "print every schedule run", opt_verbose},
    {NULL, NULL, NULL, NULL},
};

static void print_sched(const char *what, const tune_sched *m)
{
    printf("%s: ", what);
    print_ratios(stdout, m);
    printf(": error %.3g at t = %.4g s, estimated global error %.3g at t = %.4g s, cost "
           "%.4g state derivatives per simulated s, host %.4g s%s\n", m->err, m->t_err,
           m->gerr, m->t_gerr, m->cost, m->host_s, m->clean ? "" : " (faults counted)");
}

/* the details of the chosen schedule: its evaluations, each set's step doubled, the
   run-time monitor */
static void print_details(const rt_scene *sc, const tune_result *r)
{
    const tune_sched *b = &r->best;
    printf("  rhs evaluations per simulated s:");
    for (uint8_t s = 0; s < sc->nsets; s++)
        printf(" %s %.4g (%s, %g s)", sc->sets[s].name, b->evals[s], sc->sets[s].method->name,
               (double)sc->dt * b->ratio[s]);
    printf("\n  one set's step doubled:");
    for (uint8_t s = 0; s < sc->nsets; s++) {
        uint32_t ratio[RT_MAX_SETS];
        tune_sched m;
        memcpy(ratio, b->ratio, sizeof ratio);
        if (ratio[s] >= r->r_min << r->doublings)
            continue;
        ratio[s] *= 2;
        if (tune_measure(sc, ratio, &m) == RT_OK)
            printf(" %s %u -> error %.3g%s;", sc->sets[s].name, (unsigned)ratio[s], m.err,
                   m.clean ? "" : " (faults)");
    }
    printf("\n  monitor xset_err (run time):");
    for (uint8_t s = 0; s < sc->nsets; s++)
        printf(" %s %.3g", sc->sets[s].name, b->xset_err[s]);
    printf("\nschedule:");
    for (uint8_t s = 0; s < sc->nsets; s++)
        printf(" %s=%u", sc->sets[s].name, (unsigned)b->ratio[s]);
    putchar('\n');
}

int tune_cli_run(void *ctx, int npos, char **pos)
{
    const tune_cli_args *a = ctx;
    tune_opts o = a->o;
    const rt_scene *sc = cli_scene(pos[0]);
    (void)npos;
    if (!sc)
        return CLI_USAGE;
    if (!(o.tol > 0))
        return cli_fail("tune needs --tol E", NULL);
    int verbose = a->verbose;
    static tune_result r;
    rt_status st = tune_scene(sc, &o, &r, verbose ? stdout : NULL);
    if (st == RT_E_ARG)
        return cli_fail(T.nsig == 0 ? "--only selects no recorded signal" : "end time shorter "
                    "than one step of the finest candidate", o.only);
    if (st != RT_OK)
        return cli_fail(rt_status_name(st), rt_error_text(&sim));
    printf("scene: %s\ntolerance: %g on %u of %u recorded signals%s%s\n", sc->name, o.tol,
           (unsigned)r.nsig, (unsigned)sc->nrecs, o.only ? " starting with " : "",
           o.only ? o.only : "");
    printf("reference: every set at %u tick(s) of %g s (base tick / %u); against base tick "
           "/ %u: %.3g\n", (unsigned)r.r_min, (double)sc->dt / T.o.ref_div, T.o.ref_div,
           T.o.ref_div / 2, r.ref_err);
    printf("candidates: ratios %u * 2^0..%u per set, %u schedules; compared where all sets "
           "meet, at most every %g s; %u run\n", (unsigned)r.r_min, r.doublings, r.ncand,
           r.grid_s, r.nrun);
    if (r.ref_err > o.tol / 4)
        printf("warning: the reference moves by %.3g at half its resolution, more than a "
               "quarter of the tolerance: errors below are uncertain by about that much "
               "(raise --ref-div)\n", r.ref_err);
    print_sched("declared", &r.declared);
    if (!r.found) {
        printf("cheapest: none of the candidates meets the tolerance (against the reference "
               "and by its estimated global error)\n");
        return 1;
    }
    print_sched("cheapest", &r.best);
    print_details(sc, &r);
    return 0;
}
