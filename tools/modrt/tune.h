/* tune.h - `modrt tune`: offline multirate error control (issue 6, item 2). Finds the
 * cheapest fixed schedule of a scene (the step ratio of every set) whose recorded signals
 * stay within a tolerance of a fine reference run. Host only (libc, stdio, CPU clock);
 * docs/multirate.md describes the method. */
#ifndef PORT_TUNE_H
#define PORT_TUNE_H

#include <stdio.h>

#include "cli.h"
#include "rt.h"

#define TUNE_SAMPLES_MAX 4096 /* comparison instants kept from the reference */
#define TUNE_DOUBLINGS_MAX 12 /* candidate ratios go up to r_min * 2^12 */
#define TUNE_REF_DIV_MAX 1024 /* finest reference: base tick / 1024 */
#define TUNE_CANDIDATES_MAX 32768 /* schedules enumerated (doublings shrink to fit) */

/* What to tune for (zeros select the defaults). */
typedef struct tune_opts {
    double tol;           /* largest accepted |y - y_ref| over the compared signals */
    const char *only;     /* comma-separated prefixes of "Block.signal" names to compare
                             (e.g. "B" or "B1.x,Ctrl"); NULL: every recorded signal */
    unsigned doublings;   /* candidate ratios r_min * 2^k, k = 0 .. doublings (default 6;
                             r_min: the smallest ratio the scene declares) */
    unsigned ref_div;     /* the reference runs every set at r_min on the base tick divided
                             by ref_div (default 4, a power of two >= 2) */
} tune_opts;

/* One schedule and what a run of it measured. */
typedef struct tune_sched {
    uint32_t ratio[RT_MAX_SETS]; /* step of each set in base ticks */
    double err;           /* largest |y - y_ref| over the compared signals at the instants
                             where all sets meet (the first one above tol when the run
                             was cut short) */
    double t_err;         /* time of that difference [s] */
    double evals[RT_MAX_SETS]; /* right-hand-side evaluations per simulated second */
    double cost;          /* the cost measure: sum over sets of evals * states (state
                             derivatives evaluated per simulated second) */
    double host_s;        /* host CPU time of the run [s] */
    double xset_err[RT_MAX_SETS]; /* the run-time monitor (rt_sim.xset_err) at the end */
    double gerr, t_gerr;  /* its estimated global error (check.h: the schedule again at
                             half the steps), largest over the compared signals, and where;
                             -1: not checked (the reference comparison failed first) */
    int gok;              /* 1: the check found every estimate within tol, the events
                             resolved and no substep */
    int complete;         /* 1: ran to the end (not cut short at an error above tol) */
    int clean;            /* 1: no fault counted (NaN, degraded step, singular, ...) */
} tune_sched;

/* What tune_scene found. */
typedef struct tune_result {
    int found;            /* 1: best meets the tolerance, against the reference and by its
                             estimated global error */
    tune_sched best;      /* the cheapest schedule within tol (meaningful when found) */
    tune_sched declared;  /* the scene's own schedule, measured the same way */
    double ref_err;       /* |reference - reference at half its resolution| */
    double grid_s;        /* sampling interval of the reference [s]: a schedule is compared
                             at the multiples of this and of its largest ratio */
    uint32_t r_min;       /* the finest candidate ratio */
    unsigned doublings;   /* candidate ratios r_min * 2^0 .. 2^doublings */
    unsigned ncand, nrun; /* schedules enumerated, schedules run */
    uint16_t nsig;        /* signals compared */
} tune_result;

/* Tunes scene sc: runs the reference, then candidate schedules in the order of a lower
   bound of their cost, until no remaining one can be cheaper than the cheapest found
   within o->tol. Progress goes to log (NULL: quiet). Returns RT_OK, RT_E_ARG for bad
   options (no signal selected, tol <= 0), or the status of a failed rt_init. */
rt_status tune_scene(const rt_scene *sc, const tune_opts *o, tune_result *r, FILE *log);

/* Runs sc with the given ratios to its end and measures it against the reference of the
   last tune_scene call (same scene and options). Returns RT_OK or rt_init's status. */
rt_status tune_measure(const rt_scene *sc, const uint32_t *ratio, tune_sched *out);

/* `modrt tune SCENE --tol E [--only P,...] [--doublings K] [--ref-div N] [--verbose]`:
   the options fill tune_cli_ctx; tune_cli_run prints the cheapest schedule and returns
   the exit status: 0, 1 when no candidate meets the tolerance, 2 for bad arguments. */
typedef struct tune_cli_args {
    tune_opts o;
    int verbose;
} tune_cli_args;
extern tune_cli_args tune_cli_ctx;
extern const cli_opt tune_cli_opts[];
int tune_cli_run(void *ctx, int npos, char **pos);

#endif /* PORT_TUNE_H */
