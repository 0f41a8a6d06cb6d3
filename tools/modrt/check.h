/* check.h - `modrt check SCENE` and `modrt run SCENE --check`: an estimate of the global
 * error of every recorded signal, from the run at the scene's steps and a second run at
 * half the steps of every set (Richardson extrapolation with the methods' order). What a
 * status of ok guarantees, and what this adds, is in docs/solvers.md ("What status: ok
 * guarantees"). Host only (libc, stdio; no libm). */
#ifndef CHECK_H
#define CHECK_H

#include <stdio.h>

#include "rt.h"

#define CHECK_WHY_LEN 256 /* the text saying where the order comes from */
#define CHECK_Q_SLACK 0.5 /* an observed order this far below p replaces it */
#define CHECK_Q_MIN 0.3   /* below this observed order the runs do not converge */

/* What the check compares against (negative tolerances select the defaults). */
typedef struct check_opts {
    double atol, rtol;    /* a signal's estimate must stay below atol + rtol * its range
                             (max |y| over the run); < 0: each from the accuracy of the
                             signal's set (the runtime's |e| / (1 + |x|) <= accuracy) */
    const char *only;     /* comma-separated prefixes of "Block.signal" names to check;
                             NULL: every recorded signal */
    FILE *csv;            /* the estimate of every checked signal at every compared
                             instant (t, then one column per signal), or NULL */
    int observe;          /* 1: a third run at a quarter of the steps gives each signal's
                             observed order; below p it takes p's place */
} check_opts;

/* Applies a run's --set overrides to sim, just initialised for sc, and refreshes it (as
   `modrt run` does); 0 on success, else nonzero after one error line. */
typedef int (*check_setup)(void *ctx, const rt_scene *sc, rt_sim *sim);

/* One recorded signal. */
typedef struct check_sig {
    int on;               /* 1: checked (selected by only) */
    double err, t;        /* largest estimated global error and its time [s] */
    double range;         /* largest |y| of the run at the compared instants */
    double tol;           /* atol + rtol * range */
    double err_ev, t_ev;  /* largest |difference| where the runs had handled different
                             numbers of events (a shifted event: not an estimate) */
    double d1, d2;        /* observe: largest |y_h - y_h/2| and |y_h/2 - y_h/4| */
    double q;             /* observe: the observed order log2(d1 / d2) (0: none, the
                             differences at rounding level) */
    int q_used;           /* observe: q below p - CHECK_Q_SLACK took p's place */
    int q_none;           /* observe: no convergence (q below CHECK_Q_MIN): no estimate */
} check_sig;

typedef struct check_result {
    uint8_t order;        /* order p of the Richardson estimate (0: nothing integrated) */
    char why[CHECK_WHY_LEN]; /* the sets and couplings p is the lowest of */
    double atol, rtol;    /* as given; < 0: the sets' accuracies */
    uint64_t every;       /* base ticks between compared instants (all sets meet) */
    double every_s, dt_half; /* the same in seconds; the half run's base tick */
    uint64_t ncmp;        /* instants compared (estimated) */
    uint64_t nshift;      /* instants left out: the runs' event counts differed */
    double shift_s;       /* longest such stretch [s] */
    uint32_t events, events_half; /* events handled by each run */
    uint32_t substeps, substeps_half; /* steps that split into substeps in each run: their
                             steps were not h and h/2 (no estimate, severity 1) */
    rt_status status_half;/* the half run's status */
    int observe;          /* 1: the quarter run took place */
    rt_status status_quarter;
    uint32_t events_quarter, substeps_quarter;
    uint8_t kstate_lost;  /* 1: a block's internal state (an FMU's) could not be kept apart
                             between the runs: no estimate from then (severity 2); 2: nor
                             put back into the run, which went on from another's */
    char skip[CHECK_WHY_LEN]; /* a set reading a sampled output of another set whose
                             half step still spans several of its samples, or "" (then
                             no estimate of that coupling: severity 1, find_skips) */
    uint16_t nsig;
    check_sig sig[RT_MAX_REC];
    int severity;         /* 0 within the tolerance; 1 above it, the event sequence not
                             resolved, or a step split into substeps; 2 no correct digit (above RT_ERR_LOST (1 + range)),
                             or the half run failed (no estimate) */
} check_result;

/* Starts a check beside a run of sc (overrides applied) from sim, initialised as the run
   starts: initialises the half run (setup applies the same --set overrides). RT_OK, or a
   status with check_error() saying what cannot be checked. */
rt_status check_begin(const rt_scene *sc, const rt_sim *sim, const check_opts *o,
                      check_setup setup, void *ctx);
/* After every tick of the run: the half run takes its two ticks; compares where every set
   of both runs is at a communication point. */
void check_tick(const rt_scene *sc, const rt_sim *sim);
/* The result, once the run has ended. */
void check_end(const rt_scene *sc, const rt_sim *sim, check_result *r);
/* The whole check without a caller's run (modrt tune): runs sc and its half in step. */
rt_status check_scene(const rt_scene *sc, const check_opts *o, check_setup setup, void *ctx,
                      check_result *r);
/* What check_begin or check_scene refused, or "". */
const char *check_error(void);
/* The result as key: value lines (docs/solvers.md). */
void check_print(FILE *f, const rt_scene *sc, const check_result *r);

#endif /* CHECK_H */
