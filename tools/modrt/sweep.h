/* sweep.h - campaigns of runs of one scene (`modrt sweep`, docs/sweeps.md): the campaign
 * file, the plan that maps a run's index to its values and its command line, the metrics
 * a run computes over its recorded signals, and the engines (local cores, GNU parallel,
 * Slurm array jobs) that run the same task lines. Everything is sized by the limits below;
 * nothing is allocated, and nothing is as large as the campaign. */
#ifndef SWEEP_H
#define SWEEP_H

#include <stdint.h>
#include <stdio.h>

#include "cli.h"
#include "rt.h"

#define SWEEP_MAX_DIMS 16       /* grid dimensions: parameter, method, step, replay, scene lists */
#define SWEEP_MAX_VARS 32       /* Monte-Carlo variables */
#define SWEEP_MAX_VALUES 1024   /* listed grid values over all dimensions */
#define SWEEP_MAX_METRICS 32    /* metrics of one campaign */
#define SWEEP_NAME 64           /* bytes of a name: Block.param, set, metric, signal */
#define SWEEP_PATH 512          /* bytes of a path */
#define SWEEP_TEXT 65536        /* bytes of a campaign file */
#define SWEEP_ARENA 65536       /* bytes of the listed method names and replay paths */
#define SWEEP_MAX_RUNS 1000000000ull /* runs of one campaign */
#define SWEEP_DRAW_TRIES 4096   /* attempts of a bounded normal draw (rejection) */
#define SWEEP_NORMAL_MASS 0.01  /* least probability a normal's bounds may hold */
#define SWEEP_LINE 8192         /* bytes of a task line */
#define SWEEP_ARGS 128          /* words of a task line */
#define SWEEP_MAX_JOBS 256      /* local runs at once (--jobs) */
#define SWEEP_TIMEOUT_S 600.0   /* a run's wall-time limit unless the campaign sets one */
#define SWEEP_SLURM_TASKS 1000  /* array tasks of one Slurm job (Slurm's MaxArraySize 1001) */
#define SWEEP_HIST_BINS 40      /* bins of a metric's histogram (collect) */
#define SWEEP_SCATTER_MAX 100000 /* most runs plotted against a varied value (svgplot) */
#define SWEEP_REF_VALUES 262144 /* values of the reference tables of one campaign's metrics */
#define SWEEP_REF_COLS 64       /* signals of one reference table */
#define SWEEP_REF_LINE 8192     /* bytes of one line of a reference table */

/* what a grid dimension varies */
typedef enum {
    SWEEP_DIM_PARAM, SWEEP_DIM_METHOD, SWEEP_DIM_STEP, SWEEP_DIM_REPLAY, SWEEP_DIM_SCENE
} sweep_dim_kind;
/* how a Monte-Carlo variable is drawn */
typedef enum { SWEEP_UNIFORM, SWEEP_LOGUNIFORM, SWEEP_NORMAL } sweep_dist;
/* what a metric computes over the samples at or after its start time */
typedef enum {
    SWEEP_M_MAX, SWEEP_M_MIN, SWEEP_M_MAXABS, SWEEP_M_FINAL, SWEEP_M_RMS, SWEEP_M_MEAN,
    SWEEP_M_SETTLE, SWEEP_M_OVERSHOOT, SWEEP_M_ERROR
} sweep_metric_kind;

/* One grid dimension: a list of values (num or arena strings), or a range of n values. */
typedef struct sweep_dim {
    uint8_t kind;              /* sweep_dim_kind */
    uint8_t is_range;          /* 1: n values evenly from lo to hi */
    char name[SWEEP_NAME];     /* Block.param or set name; "" for replay */
    uint32_t first, n;         /* listed: values first..first+n-1 of the pools */
    double lo, hi;             /* range */
    int line, col;             /* where its name is (errors against the scene) */
} sweep_dim;

/* One Monte-Carlo variable (a parameter or initial state, Block.name). */
typedef struct sweep_var {
    char name[SWEEP_NAME];
    uint8_t dist;              /* sweep_dist */
    double a, b;               /* uniform, loguniform: bounds; normal: mean, sd */
    double lo, hi;             /* bounds of every draw */
    uint64_t key;              /* hash of the name: the draw does not depend on order */
    int line, col;             /* where its name is */
} sweep_var;

/* One metric over a recorded signal or the difference of two. */
typedef struct sweep_metric {
    char name[SWEEP_NAME];
    uint8_t kind;              /* sweep_metric_kind */
    char sig[2][SWEEP_NAME];   /* signal, and the one subtracted ("" none) */
    double p[2];               /* settle: band lo, hi; overshoot: target */
    double from;               /* samples before this time [s] are left out */
    uint32_t ref;              /* error: its reference table's path, an offset into arena */
    int line[2], col[2];        /* where its signals are named (errors against the scene) */
} sweep_metric;

/* A parsed campaign: small and fixed in size, whatever its number of runs. */
typedef struct sweep_campaign {
    char path[SWEEP_PATH];     /* as given */
    char dir[SWEEP_PATH];      /* its directory: relative scene and log paths start here */
    char name[SWEEP_NAME];
    char scene[SWEEP_PATH];    /* library scene name or scene file (as written) */
    uint64_t seed;
    uint64_t draws;            /* Monte-Carlo draws per grid point (1 without variables) */
    double t_end;              /* end time, or < 0: the scene's */
    double timeout;            /* a run's wall-time limit [s] */
    sweep_dim dims[SWEEP_MAX_DIMS];
    int ndims;
    sweep_var vars[SWEEP_MAX_VARS];
    int nvars;
    sweep_metric metrics[SWEEP_MAX_METRICS];
    int nmetrics;
    double num[SWEEP_MAX_VALUES];   /* listed numbers */
    uint32_t str[SWEEP_MAX_VALUES]; /* listed strings: offsets into arena */
    uint32_t nvalues;
    char arena[SWEEP_ARENA];
    uint32_t narena;
    uint64_t nruns;            /* product of the grid sizes times draws */
    uint64_t hash;             /* FNV-1a of the file: a result of another version is stale */
} sweep_campaign;

/* One run's values, computed from its index alone. */
typedef struct sweep_point {
    uint64_t index;
    uint64_t draw;                     /* Monte-Carlo draw number */
    uint32_t at[SWEEP_MAX_DIMS];       /* index into each grid dimension */
    double var[SWEEP_MAX_VARS];        /* drawn values */
} sweep_point;

/* ---- sweep_parse.c: the campaign language ---- */
/* Parses the campaign file at path into c; 0, or -1 after one line
   "FILE:LINE:COL: error: WHAT" on stderr. */
int sweep_parse(const char *path, sweep_campaign *c);

/* ---- sweep_draw.c: counter-based draws, the same bits on every machine ---- */
/* A 64-bit hash of (seed, draw, variable key, attempt): the only source of randomness. */
uint64_t sweep_hash(uint64_t seed, uint64_t draw, uint64_t key, uint64_t attempt);
/* The value of variable v at draw d of a campaign with this seed; NaN if a bounded normal
   found no value inside its bounds in SWEEP_DRAW_TRIES attempts. */
double sweep_draw(const sweep_var *v, uint64_t seed, uint64_t d);
/* The natural logarithm and the exponential with + - * / only (a few ulp; deterministic). */
double sweep_log(double x);
/* floor without libm (modrt links none) */
double sweep_floor(double x);
double sweep_exp(double x);

/* ---- sweep_plan.c: run index -> values -> task line ---- */
/* v in the shortest form that reads back the same (a whole number without exponent) */
const char *sweep_fmt(char *buf, size_t n, double v);
/* Fills p with run k's values (k < c->nruns). */
void sweep_point_of(const sweep_campaign *c, uint64_t k, sweep_point *p);
/* The number value of grid dimension i at position j (params and steps). */
double sweep_dim_num(const sweep_campaign *c, int i, uint32_t j);
/* The string value of grid dimension i at position j (methods and replay logs). */
const char *sweep_dim_str(const sweep_campaign *c, int i, uint32_t j);
/* Run k's command as argv (words in buf, NULL-terminated): the modrt binary modrt, the
   campaign and the output directory as given (absolute paths). Returns the word count,
   or -1 when it does not fit. */
int sweep_argv(const sweep_campaign *c, const sweep_point *p, const char *modrt,
               const char *campaign, const char *out, char *buf, size_t nbuf, char **argv);
/* The task line of run k: "K<TAB>COMMAND" with the words quoted for sh. */
int sweep_task_line(FILE *f, char **argv, uint64_t k);
/* The directory's sweep.info: the campaign, its run count, its columns. 0 or -1. */
int sweep_write_info(const sweep_campaign *c, const char *campaign, const char *out);

/* ---- sweep_metrics.c: metrics over a run's recorded signals ---- */
typedef struct sweep_acc {
    int16_t sig[2];            /* recorded signal indices (-1 none) */
    double v, aux, y0, t_prev, y_prev, span;
    uint8_t started, nan, pending;
    uint32_t row;              /* error: the next row of its reference table */
} sweep_acc;
/* Resolves every metric's signals against the scene's recorded ones and reads the
   reference tables of error metrics; 0, or -1 after one located error line (naming the
   signals the scene records, or the table's line). */
int sweep_metrics_bind(const sweep_campaign *c, const rt_scene *sc, sweep_acc *acc);
/* Folds in the recorded values at simulated time t (called at tick 0 and after each tick). */
void sweep_metrics_sample(const sweep_campaign *c, const rt_scene *sc, const rt_sim *sim,
                          sweep_acc *acc, double t);
/* Metric i's value (NaN when it has none: no sample, a NaN signal, never settled). */
double sweep_metric_value(const sweep_campaign *c, const sweep_acc *acc, int i);

/* ---- sweep_exec.c: one run under a supervisor that always leaves a result ---- */
typedef struct sweep_exec_args {
    const char *out;           /* output directory */
    uint64_t index;
    int has_index;
    const char *sets[SWEEP_MAX_DIMS + SWEEP_MAX_VARS]; /* Block.param=value */
    int nsets;
    const char *method[SWEEP_MAX_DIMS], *step[SWEEP_MAX_DIMS]; /* SET=value */
    int nmethod, nstep;
    const char *replay;        /* replay log, as written in the campaign */
    const char *scene;         /* scene file of a grid of scenes, as written */
    const char *csv;           /* the run's trace, or NULL */
} sweep_exec_args;
/* `modrt sweep exec`: runs the run in a child, writes DIR/runs/K.txt (always: a crash or
   a timeout is a result too); returns the run's exit code. */
int sweep_exec(const sweep_campaign *c, const sweep_exec_args *a);
/* Sets up run a (scene, overrides, metrics' signals) without running it: CLI_OK, or
   CLI_USAGE after one error line; what plan, run and slurm check before any task. */
int sweep_check(const sweep_campaign *c, const sweep_exec_args *a);
/* The result file of run k in dir. */
void sweep_result_path(char *buf, size_t n, const char *dir, uint64_t k);
/* Writes a result that says only why the run has none (crashed, timeout...), of the
   campaign version hash. */
int sweep_write_status(const char *dir, uint64_t k, uint64_t hash, const char *status,
                       const char *why);

/* ---- sweep_run.c: the local engine ---- */
/* Runs the campaign's task lines on jobs local processes; only_missing: only the runs
   without a result (or whose result says it crashed or timed out). */
int sweep_run_local(const sweep_campaign *c, const char *campaign, const char *out, int jobs,
                    int only_missing, const char *modrt);

/* ---- sweep_collect.c: one CSV and the figures ---- */
/* Merges DIR's results into DIR/results.csv (one row per run in index order, a missing
   result a row with status missing) and DIR/plots/ (a histogram of each metric, each
   metric against each varied number; by svgplot beside modrt). */
int sweep_collect(const char *dir, const char *svgplot);

/* ---- sweep.c: the subcommand ---- */
#define SWEEP_SBATCH_OPTS 16 /* --sbatch-opt options */
typedef struct sweep_cli_args {
    sweep_exec_args exec;      /* exec: the run's values; --out and --index for all */
    int jobs, only_missing;
    uint64_t count;            /* plan: lines from --index on (0: to the end) */
    uint64_t per_task;         /* slurm: runs per array task (0: as few tasks as fit) */
    const char *sbatch[SWEEP_SBATCH_OPTS];
    int nsbatch;
} sweep_cli_args;
/* `modrt sweep ACTION CAMPAIGN|DIR`: the options fill sweep_cli_ctx; sweep_cli_run runs
   the action and returns the exit code */
extern sweep_cli_args sweep_cli_ctx;
extern const cli_opt sweep_cli_opts[];
extern const char sweep_cli_help[];
int sweep_cli_run(void *ctx, int npos, char **pos);
/* rewrites the short option -j N (-jN) of `modrt sweep` into --jobs N */
void sweep_short_opts(int argc, char **argv);

#endif /* SWEEP_H */
