/* modrt.c - the host command line: list and describe the registered scenes and kinds,
 * run a scene or a scene file (FILE.scn, compiled in host memory by tools/scenec) on the
 * POSIX port, size a per-scene build, tune a multirate schedule. The conventions (GNU-style
 * options, --help per subcommand, exit codes 0 ok / 1 failed / 2 usage / 3 doubtful) are in
 * cli.h; each subcommand is a row of the table at the end of this file. */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "check.h"
#include "cli.h"
#include "fingerprint.h"
#include "fmu.h"
#include "fmu_scn.h"
#include "info.h"
#include "link.h"
#include "models.h"
#include "mrlog.h"
#include "replay.h"
#include "scn_host.h"
#include "study.h"
#include "sweep.h"
#include "runner.h"
#include "tune.h"
#include "version.h"
#include "rt_sim.h" /* allocates the run */

#define MAX_SETS_ARGS 32 /* --set options on one command line */

static rt_sim sim; /* the caller owns the runtime's storage */

/* ------------------------------------------------------------------ list, kinds, info */

static int cmd_list(void *ctx, int npos, char **pos)
{
    (void)ctx, (void)npos, (void)pos;
    for (const rt_scene_entry *e = mdl_scenes; e->name; e++)
        printf("%-28s %s\n", e->name, e->scene->doc ? e->scene->doc : "");
    return CLI_OK;
}

static int cmd_kinds(void *ctx, int npos, char **pos)
{
    (void)ctx, (void)npos, (void)pos;
    info_kinds(stdout);
    return CLI_OK;
}

static int cmd_docs_blocks(void *ctx, int npos, char **pos)
{
    (void)ctx, (void)npos, (void)pos;
    info_blocks_md(stdout);
    return CLI_OK;
}

typedef struct info_args {
    int json;
} info_args;

static int opt_json(void *ctx, const char *v)
{
    (void)v;
    ((info_args *)ctx)->json = 1;
    return CLI_OK;
}

static int is_scene_name(const char *name)
{
    for (const rt_scene_entry *e = mdl_scenes; e->name; e++)
        if (strcmp(e->name, name) == 0)
            return 1;
    return scn_host_is_file(name);
}

/* a kind's reference, or a scene as initialised */
static int cmd_info(void *ctx, int npos, char **pos)
{
    const info_args *a = ctx;
    const rt_kind *k = info_find_kind(pos[0]);
    (void)npos;
    if (fmu_is_file(pos[0])) /* an FMU file: its variables */
        return fmu_info(stdout, pos[0]) == 0 ? CLI_OK : CLI_USAGE;
    if (k && !is_scene_name(pos[0])) { /* a scene of the same name wins */
        info_kind(stdout, k, a->json);
        return CLI_OK;
    }
    const rt_joint_kind *j = info_find_joint(pos[0]);
    if (j && !is_scene_name(pos[0])) {
        info_joint(stdout, j);
        return CLI_OK;
    }
    const rt_scene *sc = cli_scene(pos[0]);
    if (!sc)
        return CLI_USAGE;
    rt_status st = rt_init(sc, &sim);
    info_scene(stdout, sc, &sim, st, a->json);
    return st == RT_OK ? CLI_OK : CLI_FAULTS;
}

/* a set whose last step does not end where the run did: its outputs in the last record
   are held from the step's start, and its states are the step's end, past the end of
   the run (a background set's, its start: its step is not published yet);
   docs/multirate.md, "Held outputs". Said in the summary, not left to be found */
static void held_at_end(FILE *f, const rt_scene *sc, const rt_sim *s)
{
    uint64_t n = rt_ticks_done(s);
    for (uint8_t k = 0; k < sc->nsets; k++) {
        uint64_t r = sc->sets[k].ratio, k0 = n / r * r;
        if (r <= 1 || n % r == 0 || rt_set_nx(s, k) == 0)
            continue;
        fprintf(f, "held_at_end.%s: outputs from %.17g s, states at %.17g s\n",
                sc->sets[k].name, (double)k0 * (double)sc->dt,
                (double)(sc->sets[k].background ? k0 : k0 + r) * (double)sc->dt);
    }
}

/* the summary of a run; sig: the signal that ended it early (its status then says so, the
   counters say what happened until then) */
static void summary(FILE *f, const rt_scene *sc, const rt_sim *s, rt_status st, double wall,
                    int sig)
{
    const rt_stats *z = rt_stats_of(s);
    fprintf(f, "scene: %s\nticks: %llu\nsim_time: %.17g\nwall_s: %.6f\n", sc->name,
            (unsigned long long)rt_ticks_done(s), (double)rt_time(sc, s), wall);
    if (sig)
        fprintf(f, "status: interrupted\ninterrupted: %s at tick %llu of %llu\n",
                sig == SIGINT ? "SIGINT" : "SIGTERM", (unsigned long long)rt_ticks_done(s),
                (unsigned long long)rt_tick_count(s));
    else
        fprintf(f, "status: %s\n", z->status == RT_OK
                                       ? (st == RT_E_DONE ? "ok" : rt_status_name(st))
                                       : rt_status_name(z->status));
    for (int c = 0; c < RT_CNT_COUNT; c++) {
        fprintf(f, "%s: %u", rt_counter_key((rt_counter)c), (unsigned)z->count[c]);
        if (z->last_block[c] >= 0 && c != RT_CNT_EVENTS)
            fprintf(f, " (last %s)", sc->blocks[z->last_block[c]].name);
        if (z->count[c] > 0 && c != RT_CNT_EVENTS)
            fprintf(f, " (first at tick %u)", (unsigned)z->first_tick[c]);
        fputc('\n', f);
    }
    fprintf(f, "event_iter_max: %u\n", (unsigned)z->event_iter_max);
    for (uint8_t k = 0; k < sc->nsets; k++)
        fprintf(f, "rhs_evals.%s: %llu\n", sc->sets[k].name,
                (unsigned long long)z->rhs_evals[k]);
    for (uint8_t k = 0; k < sc->nsets; k++) /* the most one step took, and its bound */
        fprintf(f, "rhs_step_max.%s: %u (bound %u)\n", sc->sets[k].name,
                (unsigned)z->istats[k].rhs_step_max,
                (unsigned)rt_step_bound(sc, k, rt_set_nx(s, k)).rhs);
    for (uint8_t k = 0; k < sc->nsets; k++) /* a whole step: events, parts, couplings */
        fprintf(f, "rhs_set_step_max.%s: %u (bound %u)\n", sc->sets[k].name,
                (unsigned)z->istats[k].rhs_set_step_max,
                (unsigned)rt_set_step_bound(sc, s, k).rhs);
    for (uint8_t k = 0; k < sc->nsets; k++) {
        rt_set_cfg c = rt_set_cfg_of(&sc->sets[k].cfg);
        fprintf(f, "err_max.%s: %g (accuracy %g", sc->sets[k].name,
                (double)z->istats[k].err_max, (double)c.accuracy);
        fprintf(f, c.atol > 0 ? ", absolute %g)\n" : ")\n", (double)c.atol);
        if (z->errest[k] || z->unstable[k])
            fprintf(f, "errest.%s: %u\nunstable.%s: %u\n", sc->sets[k].name,
                    (unsigned)z->errest[k], sc->sets[k].name,
                    (unsigned)z->unstable[k]);
    }
    held_at_end(f, sc, s);
    for (uint8_t k = 0; k < sc->nsets; k++)
        if (rt_set_is_source(s, k))
            fprintf(f, "xset_err.%s: %g\n", sc->sets[k].name, (double)z->xset_err[k]);
#if RT_MAX_XPRED > 0
    for (uint8_t k = 0; k < sc->nsets; k++) /* a reader's coupling error (rt/xset.c) */
        if (z->xset_est[k] > 0)
            fprintf(f, "xset_est.%s: %g\n", sc->sets[k].name, (double)z->xset_est[k]);
#endif
    if (rt_torn_count(s) > 0) {
        fprintf(f, "loop_iter_max: %u\nloop_iter_hist:", (unsigned)z->loop_iter_max);
        for (uint32_t i = 0; i <= z->loop_iter_max; i++)
            fprintf(f, " %u", (unsigned)z->loop_hist[i]);
        fprintf(f, "\nloop_residual: %g\n", (double)z->loop_residual);
    }
    fmu_summary(f); /* FMU blocks: their faults with the FMU's own account */
    fprintf(f, "hash: %016llx\n", (unsigned long long)rt_trace_hash(s));
}

/* ------------------------------------------------------------------ output files */

/* one line with the system's reason; CLI_IO */
static int io_fail(const char *what, const char *path, int err)
{
    fprintf(stderr, "modrt: %s %s: %s\n", what, path, err ? strerror(err) : "write error");
    return CLI_IO;
}

/* an output file of a run, opened before the run so that a directory, a missing
   directory or a missing permission is reported before any tick; NULL after one line */
static FILE *open_out(const char *path, const char *what)
{
    struct stat st;
    if (stat(path, &st) == 0 && S_ISDIR(st.st_mode)) {
        io_fail(what, path, EISDIR);
        return NULL;
    }
    FILE *f = fopen(path, "w");
    if (!f)
        io_fail(what, path, errno);
    return f;
}

/* flushes f and closes it (not stdout): CLI_OK, or CLI_IO after one line with the reason
   (a full disk shows here: the rows were buffered) */
static int close_out(FILE *f, int is_stdout, const char *what, const char *path)
{
    if (!f)
        return CLI_OK;
    errno = 0;
    int bad = fflush(f) != 0, err = errno;
    bad |= ferror(f) != 0;
    errno = 0;
    if (!is_stdout && fclose(f) != 0)
        bad = 1, err = err ? err : errno;
    return bad ? io_fail(what, path, err) : CLI_OK;
}

/* the exit status of a run: interrupted, then an output lost, then the worst severity
   of the run (and of its check) */
static int run_exit(int sig, int io, int sev)
{
    return sig ? CLI_INTERRUPTED : io ? CLI_IO : cli_exit_code(sev);
}

/* ------------------------------------------------------------------ run */

typedef struct run_args {
    const char *csv;
    double t_end;
    int has_t_end, realtime;
    unsigned every;
    const char *sets[MAX_SETS_ARGS];
    int nsets;
    const char *link, *record, *link_key;
    double link_timeout;
    study_args study; /* per-set overrides */
    int overrun;      /* rtloop_policy */
    const char *rt_log;
    int check;        /* 1: estimate the global error (check.h) */
    const char *check_csv; /* its estimates at every compared instant, or NULL */
    check_opts global; /* its tolerance and signals */
} run_args;

/* 1: the run talks to a controller over --link (`--link none`: the imports hold their
   defaults) */
static int live_link(const run_args *a)
{
    return a->link && strcmp(a->link, "none") != 0;
}

static int opt_t_end(void *ctx, const char *v)
{
    run_args *a = ctx;
    if (!cli_real(v, &a->t_end) || a->t_end < 0)
        return cli_fail("--t-end expects a time >= 0 in seconds, got", v);
    a->has_t_end = 1;
    return CLI_OK;
}

static int opt_csv(void *ctx, const char *v)
{
    ((run_args *)ctx)->csv = v;
    return CLI_OK;
}

static int opt_every(void *ctx, const char *v)
{
    unsigned long n;
    if (!cli_uint(v, 1, 1000000000ul, &n))
        return cli_fail("--every expects a whole number >= 1, got", v);
    ((run_args *)ctx)->every = (unsigned)n;
    return CLI_OK;
}

static int opt_set(void *ctx, const char *v)
{
    run_args *a = ctx;
    if (a->nsets >= MAX_SETS_ARGS)
        return cli_fail("too many --set options", v);
    a->sets[a->nsets++] = v;
    return CLI_OK;
}

static int opt_realtime(void *ctx, const char *v)
{
    (void)v;
    ((run_args *)ctx)->realtime = 1;
    return CLI_OK;
}

static int opt_link(void *ctx, const char *v)
{
    char err[512];
    if (link_spec_check(v, err, sizeof err) != 0)
        return cli_fail(err, NULL);
    ((run_args *)ctx)->link = v;
    return CLI_OK;
}

static int opt_link_key(void *ctx, const char *v)
{
    ((run_args *)ctx)->link_key = v;
    return CLI_OK;
}

static int opt_link_timeout(void *ctx, const char *v)
{
    run_args *a = ctx;
    if (!cli_real(v, &a->link_timeout) || !(a->link_timeout > 0 && a->link_timeout <= 3600))
        return cli_fail("--link-timeout expects seconds in (0, 3600], got", v);
    return CLI_OK;
}

static int opt_method(void *ctx, const char *v)
{
    return study_add(&((run_args *)ctx)->study, "method", v);
}

static int opt_step(void *ctx, const char *v)
{
    return study_add(&((run_args *)ctx)->study, "step", v);
}

/* one handler per set setting (RT_SET_CFG_LIST), each recording its own option */
#define STUDY_OPT(id, w_, o_, f_, k_, m_, s_, d_, h_)                        \
    static int opt_##id(void *ctx, const char *v)                                           \
    {                                                                                       \
        return study_add(&((run_args *)ctx)->study, rt_set_opts[id].opt, v);                \
    }
RT_SET_CFG_LIST(STUDY_OPT)
#undef STUDY_OPT
static int (*const opt_setting[RT_CFG_N])(void *, const char *) = {
#define STUDY_OPT_FN(id, w_, o_, f_, k_, m_, s_, d_, h_) opt_##id,
    RT_SET_CFG_LIST(STUDY_OPT_FN)
#undef STUDY_OPT_FN
};

static int opt_overrun(void *ctx, const char *v)
{
    int p = rtloop_policy_find(v);
    if (p < 0)
        return cli_fail("--overrun expects catchup, skip or stop, got", v);
    ((run_args *)ctx)->overrun = p;
    return CLI_OK;
}

static int opt_rt_log(void *ctx, const char *v)
{
    ((run_args *)ctx)->rt_log = v;
    return CLI_OK;
}

static int opt_record(void *ctx, const char *v)
{
    ((run_args *)ctx)->record = v;
    return CLI_OK;
}

static int opt_check(void *ctx, const char *v)
{
    (void)v;
    ((run_args *)ctx)->check = 1;
    return CLI_OK;
}

/* E (atol = rtol = E) or A,R */
static int opt_global_tol(void *ctx, const char *v)
{
    check_opts *o = &((run_args *)ctx)->global;
    char buf[64];
    const char *comma = strchr(v, ',');
    size_t n = comma ? (size_t)(comma - v) : strlen(v);
    if (n >= sizeof buf)
        return cli_fail("--global-tol expects E or ATOL,RTOL, got", v);
    memcpy(buf, v, n), buf[n] = 0;
    if (!cli_real(buf, &o->atol) || !(o->atol >= 0) ||
        !cli_real(comma ? comma + 1 : buf, &o->rtol) || !(o->rtol >= 0) ||
        !(o->atol > 0 || o->rtol > 0))
        return cli_fail("--global-tol expects E or ATOL,RTOL (numbers >= 0, not both 0), got",
                        v);
    return CLI_OK;
}

static int opt_only(void *ctx, const char *v)
{
    ((run_args *)ctx)->global.only = v;
    return CLI_OK;
}

static int opt_observe(void *ctx, const char *v)
{
    (void)v;
    ((run_args *)ctx)->global.observe = 1;
    return CLI_OK;
}

static int opt_check_csv(void *ctx, const char *v)
{
    ((run_args *)ctx)->check_csv = v;
    return CLI_OK;
}

#define CHECK_OPTS                                                                          \
    {"global-tol", "E|ATOL,RTOL", "with the check: a signal's estimated global error must "  \
     "stay below ATOL + RTOL * its largest |y| (E: both; default: the accuracy of the "       \
     "signal's set)", opt_global_tol},                                                      \
    {"only", "P,...", "with the check: check only recorded signals starting with these "    \
     "prefixes", opt_only},                                                                 \
    {"check-csv", "FILE", "with the check: write the estimate of every checked signal at "  \
     "every compared instant as CSV to FILE", opt_check_csv},                               \
    {"observe", NULL, "with the check: a third run at a quarter of the steps measures each " \
     "signal's order of convergence; an order below the methods' replaces theirs",         \
     opt_observe}

static const cli_opt run_opts_fixed[] = {
    {"t-end", "S", "end time [s] instead of the scene's", opt_t_end},
    {"csv", "FILE", "write the recorded signals as CSV to FILE (- : stdout, summary to stderr)",
     opt_csv},
    {"every", "N", "record every N-th tick (default 1)", opt_every},
    {"set", "BLOCK.PARAM=VALUE", "set parameter (or initial state) P of block B to V; repeatable", opt_set},
    {"realtime", NULL, "pace the ticks by the wall clock (default: simulated clock); "
     "SCHED_FIFO and locked memory when permitted; latency statistics in the summary",
     opt_realtime},
    {"overrun", "catchup|skip|stop", "real time: a missed deadline runs the missed ticks back "
     "to back (catchup, default), drops them (skip), or ends the run (stop)", opt_overrun},
    {"rt-log", "FILE", "real time: write each tick's wake-up latency and execution time "
     "[us] to FILE (CSV)", opt_rt_log},
    {"link", "udp:HOST:PORT|serial:DEV[:BAUD]|none", "exchange the scene's export/import "
     "signals with a controller over UDP or a serial line (docs/link.md); lock-step, or soft "
     "real time with --realtime", opt_link},
    {"link-timeout", "S", "lock-step: wait at most S seconds per exchange (a serial line: "
     "sending the request again every S/10; default 1)",
     opt_link_timeout},
    {"link-key", "FILE", "authenticate every datagram with HMAC-SHA-256 under the shared "
     "key in FILE (1 to 64 bytes; docs/link.md)", opt_link_key},
    {"record", "FILE", "write every imported vector and its tick to a replay log "
     "(modrt replay FILE)", opt_record},
    {"method", "SET=NAME", "integrate set SET by method NAME instead of the scene's; repeatable "
     "(as are the per-set options below)", opt_method},
    {"step", "SET=TIME", "set SET's step [s], a whole number of base ticks", opt_step},
    {"check", NULL, "estimate the global error of every recorded signal: the scene again at "
     "half the steps (as `modrt check`)", opt_check},
    CHECK_OPTS,
    {NULL, NULL, NULL, NULL},
};

/* `modrt check`: the options of a run that make sense beside a second run */
static const cli_opt check_opts_tab_fixed[] = {
    {"t-end", "S", "end time [s] instead of the scene's", opt_t_end},
    {"csv", "FILE", "write the recorded signals of the run (at the scene's steps) as CSV to "
     "FILE (- : stdout, summary to stderr)", opt_csv},
    {"every", "N", "record every N-th tick (default 1)", opt_every},
    {"set", "BLOCK.PARAM=VALUE", "set parameter (or initial state) P of block B to V, in "
     "both runs; repeatable", opt_set},
    {"method", "SET=NAME", "integrate set SET by method NAME instead of the scene's; "
     "repeatable (as are the per-set options below)", opt_method},
    {"step", "SET=TIME", "set SET's step [s], a whole number of base ticks (the check "
     "halves it)", opt_step},
    CHECK_OPTS,
    {NULL, NULL, NULL, NULL},
};

/* the options of run and check: the fixed ones, and after --step modrt's option of each
   set setting (RT_SET_CFG_LIST: its help, "SET=N" or "SET=E", ",A" for a second value) */
static cli_opt run_opts[sizeof run_opts_fixed / sizeof run_opts_fixed[0] + RT_CFG_N];
static cli_opt check_opts_tab[sizeof check_opts_tab_fixed / sizeof check_opts_tab_fixed[0] +
                              RT_CFG_N];
static void with_settings(cli_opt *out, const cli_opt *fixed)
{
    for (;; fixed++) {
        *out++ = *fixed;
        if (!fixed->name)
            return;
        if (strcmp(fixed->name, "step") != 0)
            continue;
        for (int id = 0; id < RT_CFG_N; id++) {
            const rt_set_opt *o = &rt_set_opts[id];
            int pair = id + 1 < RT_CFG_N && rt_set_opts[id + 1].kind == RT_CFG_PAIR;
            if (o->opt)
                *out++ = (cli_opt){o->opt, o->kind == RT_CFG_REAL ? (pair ? "SET=E[,A]" : "SET=E")
                                                                   : "SET=N",
                                   o->help, opt_setting[id]};
        }
    }
}

/* the options that change the numbers, as the log lists them */
static int record_options(const run_args *a, mrl_header *h)
{
    char b[MRL_SET_LEN + 2];
    if (a->nsets + a->study.n > MRL_MAX_SETS)
        return cli_fail("--record: too many --set and per-set options for the log", NULL);
    for (int i = 0; i < a->nsets + a->study.n; i++) {
        int s = i - a->nsets;
        int k = i < a->nsets ? snprintf(b, sizeof b, "%s", a->sets[i])
                             : snprintf(b, sizeof b, "--%s %s", a->study.opt[s], a->study.val[s]);
        if (k < 0 || k > MRL_SET_LEN)
            return cli_fail("--record: option too long for the log", b);
        strcpy(h->sets[h->nsets++], b);
    }
    return 0;
}

/* the replay log's header of this run */
static int record_header(const run_args *a, const char *scene, const rt_scene *sc,
                         uint64_t run, mrl_header *h)
{
    char err[600];
    memset(h, 0, sizeof *h);
    if (mrl_scene_name(scene, h->scene, sizeof h->scene, err, sizeof err) != 0)
        return cli_fail("--record", err);
    h->id = sc->link ? sc->link->id : 0, h->nimp = sc->link ? sc->link->nimp : 0;
    h->real_size = (uint8_t)sizeof(real_t), h->realtime = (uint8_t)a->realtime;
    h->t_end = (double)sc->t_end, h->every = a->every;
    h->scene_fp = fp_scene(sc), h->run = run;
    return record_options(a, h);
}

/* the inputs of a run: the controller link (and the log it writes), or nothing */
static int start_inputs(const run_args *a, const char *scene, const rt_scene *sc,
                        runner_opts *o, mrl_writer **rec)
{
    static link_key key;
    char err[512];
    mrl_header h;
    int live = live_link(a);
    link_opts lo = {a->realtime, a->link_timeout > 0 ? a->link_timeout : 1,
                    live ? link_nonce() : 0, NULL};
    *rec = NULL;
    if (a->link_key && !live)
        return cli_fail("--link-key authenticates a link: it needs --link", a->link_key);
    if (a->link_key) {
        if (link_key_read(a->link_key, &key, err, sizeof err) != 0)
            return cli_fail(err, NULL);
        lo.key = &key;
    }
    if (a->record) {
        if (record_header(a, scene, sc, lo.run, &h))
            return CLI_USAGE;
        if (!(*rec = mrl_create(a->record, &h, err, sizeof err)))
            return cli_fail("--record", err), CLI_IO;
    }
    if (!live)
        return CLI_OK;
    if (link_open(a->link, sc, &lo, *rec, err, sizeof err) != 0)
        return cli_fail("--link", err);
    o->exchange = link_exchange;
    return CLI_OK;
}

/* closes the link before the summary, so its faults set the status the summary shows
   and the exit code follows: RT_E_LINK_FAULT (failed) */
static int stop_link(const run_args *a, rt_sim *s, link_counts *c)
{
    if (!live_link(a))
        return 0;
    link_close(c);
    if (link_faulty(c))
        rt_note_status(s, RT_E_LINK_FAULT);
    return 1;
}

/* how the run ended, as its replay log says it */
static mrl_end run_end(const rt_sim *s, rt_status st, const runner_result *r)
{
    if (r->signal)
        return r->signal == SIGINT ? MRL_END_SIGINT : MRL_END_SIGTERM;
    if (st == RT_E_LINK)
        return MRL_END_LINK;
    return rt_ticks_done(s) < rt_tick_count(s) ? MRL_END_STOPPED : MRL_END_DONE;
}

/* finishes the log (its end marker written: how the run ended, the tick it reached);
   CLI_IO if it could not be written */
static int stop_record(mrl_writer *rec, const rt_sim *s, rt_status st, const runner_result *r)
{
    char err[512];
    if (rec && mrl_finish(rec, run_end(s, st, r), rt_ticks_done(s), err, sizeof err) != 0)
        return cli_fail("--record", err), CLI_IO;
    return CLI_OK;
}

/* the run's --set overrides onto a freshly initialised sim (the check's half run too) */
static int setup_sets(void *ctx, const rt_scene *sc, rt_sim *s)
{
    const run_args *a = ctx;
    for (int i = 0; i < a->nsets; i++)
        if (cli_set_param(sc, s, a->sets[i]))
            return CLI_USAGE;
    if (a->nsets > 0) /* only then: a refresh re-solves loops from a new warm start */
        return cli_refresh(sc, s);
    return CLI_OK;
}

/* what a second run at half the steps cannot reproduce */
static int check_refused(const run_args *a)
{
    if (!a->check)
        return a->global.only || a->global.atol >= 0 || a->check_csv || a->global.observe
                   ? cli_fail("--global-tol, --only, --check-csv and --observe apply with --check", NULL)
                   : CLI_OK;
    if (a->realtime)
        return cli_fail("--check", "a run paced by the wall clock cannot be run again at half "
                        "the steps; check without --realtime");
    if (live_link(a))
        return cli_fail("--check", "a live --link run cannot be checked: its controller "
                        "answers one run, not a second at half the steps; check the scene "
                        "without --link (its imports hold their defaults)");
    if (a->record)
        return cli_fail("--check", "--record logs a live link's imports; there is none to "
                        "check");
    return CLI_OK;
}

static void check_observe(const rt_scene *sc, const rt_sim *s)
{
    check_tick(sc, s);
}

static int cmd_run(void *ctx, int npos, char **pos)
{
    run_args *a = ctx;
    const rt_scene *base = cli_scene(pos[0]);
    (void)npos;
    if (!base)
        return CLI_USAGE;
    rt_scene sc = *base; /* the const scene, with the end time the user asked for */
    if (a->has_t_end && cli_end_time(&sc, a->t_end, "--t-end") != CLI_OK)
        return CLI_USAGE;
    if (study_apply(&a->study, &sc) != CLI_OK || check_refused(a) != CLI_OK)
        return CLI_USAGE;
    if (a->realtime && !((double)sc.dt * 1e9 < 9e18)) { /* the clock counts int64_t ns */
        char v[32];
        snprintf(v, sizeof v, "%.10g s", (double)sc.dt);
        return cli_fail("--realtime: the scene's base tick too long for the real-time clock "
                        "(at most 9e9 s), got", v);
    }
    rt_status st = rt_init(&sc, &sim);
    if (st != RT_OK)
        return cli_fail(rt_status_name(st), rt_error_text(&sim));
    if (rt_error_text(&sim)[0]) /* what rt_init moved or found redundant */
        fprintf(stderr, "modrt: %s: %s\n", sc.name, rt_error_text(&sim));
    if (setup_sets(a, &sc, &sim) != CLI_OK)
        return CLI_USAGE;
    if (a->check_csv && !(a->global.csv = fopen(a->check_csv, "w")))
        return cli_fail("cannot write the --check-csv file", a->check_csv);
    if (a->check && check_begin(&sc, &sim, &a->global, setup_sets, a) != RT_OK)
        return cli_fail("--check", check_error());
    FILE *csv = NULL;
    int to_stdout = a->csv && strcmp(a->csv, "-") == 0;
    if (a->csv && !(csv = to_stdout ? stdout : open_out(a->csv, "cannot write the CSV file")))
        return CLI_IO;
    FILE *rt_log = NULL;
    if (a->rt_log && !(rt_log = open_out(a->rt_log, "cannot write the --rt-log file")))
        return CLI_IO;
    runner_opts o = {csv, a->every, a->realtime, NULL, NULL, a->overrun, rt_log,
                     a->check ? check_observe : NULL, NULL};
    runner_result r;
    mrl_writer *rec;
    int rc = start_inputs(a, pos[0], &sc, &o, &rec);
    if (rc != CLI_OK)
        return rc;
    st = runner_run(&sc, &sim, &o, &r);
    /* whatever was lost, the summary is printed and the replay log finished */
    int io = close_out(csv, to_stdout, "error writing the CSV file", a->csv);
    io |= close_out(rt_log, 0, "error writing the --rt-log file", a->rt_log);
    FILE *out = to_stdout ? stderr : stdout;
    link_counts lc;
    int linked = stop_link(a, &sim, &lc);
    summary(out, &sc, &sim, st, r.wall_s, r.signal);
    if (a->realtime)
        rtloop_print(out, (rtloop_policy)a->overrun, &r.rt);
    if (linked)
        link_print(out, &lc);
    io |= stop_record(rec, &sim, st, &r);
    int sev = rt_status_severity(rt_stats_of(&sim)->status);
    if (a->check && !r.signal) { /* an interrupted run has no whole run to check */
        static check_result cr;
        check_end(&sc, &sim, &cr);
        io |= close_out(a->global.csv, 0, "error writing the --check-csv file", a->check_csv);
        check_print(out, &sc, &cr);
        sev = cr.severity > sev ? cr.severity : sev;
    }
    io |= close_out(out, 1, "error writing the summary to", to_stdout ? "stderr" : "stdout");
    return run_exit(r.signal, io, sev);
}

/* `modrt check`: a run with the check */
static int cmd_check(void *ctx, int npos, char **pos)
{
    ((run_args *)ctx)->check = 1;
    return cmd_run(ctx, npos, pos);
}

/* ------------------------------------------------------------------ replay */

typedef struct replay_args {
    const char *csv;
} replay_args;

static int opt_replay_csv(void *ctx, const char *v)
{
    ((replay_args *)ctx)->csv = v;
    return CLI_OK;
}

static const cli_opt replay_opts[] = {
    {"csv", "FILE", "write the recorded signals as CSV to FILE (- : stdout, summary to stderr)",
     opt_replay_csv},
    {NULL, NULL, NULL, NULL},
};

static int cmd_replay(void *ctx, int npos, char **pos)
{
    static mrl_header h;
    const replay_args *a = ctx;
    char err[600];
    rt_scene sc;
    struct stat fs;
    (void)npos;
    if (stat(pos[0], &fs) == 0 && !S_ISREG(fs.st_mode)) /* not read: a FIFO would block */
        return cli_fail(S_ISDIR(fs.st_mode) ? "replay: a directory, not a replay log"
                                            : "replay: not a regular file, not a replay log",
                        pos[0]);
    if (mrl_open(pos[0], &h, err, sizeof err) != 0)
        return cli_fail("replay", err);
    int rc = replay_scene(&h, pos[0], NULL, &sc, &sim);
    if (rc == CLI_OK && mrl_check_end(rt_tick_count(&sim), err, sizeof err) != 0)
        rc = cli_fail("replay", err);
    if (rc != CLI_OK)
        return mrl_close(), rc;
    FILE *csv = NULL;
    int to_stdout = a->csv && strcmp(a->csv, "-") == 0;
    if (a->csv && !(csv = to_stdout ? stdout : open_out(a->csv, "cannot write the CSV file")))
        return mrl_close(), CLI_IO;
    runner_opts o = {csv, h.every, 0, mrl_replay_exchange, NULL, 0, NULL, NULL,
                     replay_stop_tick(&h)};
    runner_result r;
    rt_status st = runner_run(&sc, &sim, &o, &r);
    mrl_close();
    int io = close_out(csv, to_stdout, "error writing the CSV file", a->csv);
    FILE *out = to_stdout ? stderr : stdout;
    int sig = r.signal ? r.signal : replay_end(&h, &sim);
    summary(out, &sc, &sim, st, r.wall_s, sig);
    if (!r.signal && h.version >= 3 && h.ended != MRL_END_DONE)
        fprintf(out, "replayed: to tick %llu of %llu, where the recorded run ended (%s)\n",
                (unsigned long long)rt_ticks_done(&sim), (unsigned long long)rt_tick_count(&sim),
                mrl_end_name((mrl_end)h.ended));
    io |= close_out(out, 1, "error writing the summary to", to_stdout ? "stderr" : "stdout");
    return run_exit(sig, io, rt_status_severity(rt_stats_of(&sim)->status));
}

/* the compile-time limits that fit this scene exactly, as -D flags for a per-scene build
   (the same as `scenec --sizes`, tools/scenec/host.c) */
static int cmd_sizes(void *ctx, int npos, char **pos)
{
    const rt_scene *sc = cli_scene(pos[0]);
    (void)ctx, (void)npos;
    if (!sc)
        return CLI_USAGE;
    rt_status st = rt_init(sc, &sim);
    if (st != RT_OK)
        return cli_fail(rt_status_name(st), rt_error_text(&sim));
    fmu_scn_sizes(stdout, stderr, pos[0], sc, &sim); /* with an FMU block's arena */
    return 0;
}

/* ------------------------------------------------------------------ subcommands */

static info_args info_ctx;
static run_args run_ctx = {.every = 1, .global = {-1, -1, NULL, NULL, 0}};
static run_args check_ctx = {.every = 1, .global = {-1, -1, NULL, NULL, 0}};
static replay_args replay_ctx;
static const cli_opt info_opts[] = {
    {"json", NULL, "print JSON (one object) for scripts", opt_json},
    {NULL, NULL, NULL, NULL},
};

static const cli_cmd commands[] = {
    {"list", "", "list the registered scenes", NULL, NULL, 0, 0, NULL, cmd_list},
    {"kinds", "", "list the block kinds of the model library", NULL, NULL, 0, 0, NULL,
     cmd_kinds},
    {"info", "SCENE|FILE.scn|FILE.fmu|KIND",
     "describe a scene as initialised, a block kind, or an FMU file",
     "A scene: blocks with parameter values, wiring, sets, schedule, evaluation order, loops.\n"
     "A kind: inputs, outputs, states and parameters with defaults and units, equations.\n"
     "An FMU: its interfaces and every variable with causality, variability, type, unit and\n"
     "start value (docs/fmi.md).", info_opts, 1, 1, &info_ctx, cmd_info},
    {"run", "SCENE|FILE.scn", "run a scene to its end time; prints a key: value summary",
     "Exit status 0 when no fault was counted; 1 when the answer failed (NaN, instability,\n"
     "a degraded step, a lost link...); 3 when it completed but a step's error estimate\n"
     "exceeded its set's accuracy, an implicit step damped a growing mode (damped) or a\n"
     "tick missed its deadline; 2 for bad arguments; 4 when an\n"
     "output file could not be written (the summary says how far the run got); 5 when\n"
     "SIGINT or SIGTERM ended it early (status: interrupted; the CSV ends in a whole row).\n"
     "\n"
     "status: ok says, of every step of every set: its local error estimate (the step\n"
     "against its embedded companion, scaled by 1 + |x|) stayed within the set's accuracy;\n"
     "every Newton iteration and algebraic loop converged within its bound, without a\n"
     "singular matrix; no state, output or derivative was NaN or infinite; no state grew\n"
     "without bound, and no implicit step damped a mode growing past its pole (damped);\n"
     "every state event was located within its bound, at most\n"
     "RT_EVENTS_PER_STEP_MAX per step, and no guard root was tunnelled; the error an\n"
     "input read from another set put into its reader (extrapolated or interpolated)\n"
     "stayed within the reader's accuracy; no multibody set without projection drifted\n"
     "off its joints by more than its accuracy; no link import or deadline was missed.\n"
     "It says nothing about the global error: local errors accumulate (and grow with an\n"
     "unstable solution) over the run. --check estimates it (modrt check --help;\n"
     "docs/solvers.md, \"What status: ok guarantees\").\n"
     "\n"
     "The summary's hash is a 64-bit FNV-1a over the bit patterns of every recorded value:\n"
     "the same scene gives the same hash on every run and every target.",
     run_opts, 1, 1, &run_ctx, cmd_run},
    {"check", "SCENE|FILE.scn", "run a scene and estimate the global error of every "
     "recorded signal",
     "Runs the scene as `modrt run` does (its summary first), and beside it the scene again\n"
     "with the base tick halved and every set's ratio kept: every step halves, sampled\n"
     "blocks, sources and the end time keep their times. Where all sets of both runs meet,\n"
     "each recorded signal's global error is estimated by Richardson extrapolation,\n"
     "|y_h - y_h/2| / (1 - 2^-p), p the lowest order among the sets that integrate and\n"
     "the couplings between sets (hold 1, extrapolate and linear 2, hermite and quadratic\n"
     "3). Prints the largest estimate per signal, its time, and its tolerance (--global-tol:\n"
     "ATOL + RTOL * the signal's largest |y|; default ATOL = RTOL = the accuracy of the\n"
     "signal's set). Instants between the two runs' event times (their event counts\n"
     "differ) are left out and printed apart. global_status: ok within every tolerance;\n"
     "doubtful above one, when the runs end with different numbers of events, or when a\n"
     "step split into substeps (the runs then did not take h and h/2); failed\n"
     "when an estimate leaves no correct digit (above 1 + |y|) or the half run failed.\n"
     "Exit status: the worse of the run's status and global_status (0, 3, 1; 2 for bad\n"
     "arguments, or a scene that cannot be checked). The estimate holds where the error\n"
     "behaves like C h^p: a right-hand side that is not smooth lowers the order, and\n"
     "--observe (a third run at a quarter of the steps) measures it per signal and uses\n"
     "it where it is below p (docs/solvers.md).",
     check_opts_tab, 1, 1, &check_ctx, cmd_check},
    {"replay", "FILE.mrl", "re-run a recorded live run from its log, without the controller",
     "Applies every recorded import at its tick on the simulated clock: the summary and its\n"
     "hash equal the live run's bit for bit. A corrupt, truncated or mismatched log is\n"
     "refused with one line saying what and where (docs/link.md).",
     replay_opts, 1, 1, &replay_ctx, cmd_replay},
    {"tune", "SCENE|FILE.scn", "find the cheapest fixed multirate schedule within a tolerance",
     "Runs a fine reference, then candidate schedules (nested power-of-two step ratios),\n"
     "and prints the cheapest that stays within --tol of it and whose own estimated global\n"
     "error (modrt check: the schedule again at half its steps) is within --tol too\n"
     "(docs/multirate.md).",
     tune_cli_opts, 1, 1, &tune_cli_ctx, tune_cli_run},
    {"sweep", "plan|run|exec|slurm CAMPAIGN, or collect DIR", "parameter sweeps and "
     "Monte-Carlo campaigns of a scene: local cores, GNU parallel, Slurm (docs/sweeps.md)",
     sweep_cli_help, sweep_cli_opts, 2, 2, &sweep_cli_ctx, sweep_cli_run},
    {"sizes", "SCENE|FILE.scn", "print the exact compile-time limits of a per-scene build "
     "as -D flags", NULL, NULL, 1, 1, NULL, cmd_sizes},
    {"docs-blocks", "", "print the block reference (docs/blocks.md) of every kind", NULL,
     NULL, 0, 0, NULL, cmd_docs_blocks},
    {NULL, NULL, NULL, NULL, NULL, 0, 0, NULL, NULL},
};

static void usage(FILE *f)
{
    fputs("usage: modrt COMMAND [ARGS] [options]   (modrt COMMAND --help for its options)\n"
          "commands:\n", f);
    for (const cli_cmd *c = commands; c->name; c++)
        fprintf(f, "  %-12s %s\n", c->name, c->summary);
    fputs("  --version    print the version\n  --help       this text\n", f);
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        usage(stderr);
        return CLI_USAGE;
    }
    if (strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0) {
        usage(stdout);
        return CLI_OK;
    }
    if (strcmp(argv[1], "--version") == 0) {
        printf("modrt %s (%s)\n", MODRT_VERSION, RT_REAL_IS_FLOAT ? "float" : "double");
        return CLI_OK;
    }
    if (strcmp(argv[1], "sweep") == 0)
        sweep_short_opts(argc, argv);
    with_settings(run_opts, run_opts_fixed);
    with_settings(check_opts_tab, check_opts_tab_fixed);
    for (const cli_cmd *c = commands; c->name; c++)
        if (strcmp(argv[1], c->name) == 0)
            return cli_dispatch(c, argc - 2, argv + 2);
    return cli_fail("unknown command (modrt --help lists them)", argv[1]);
}
