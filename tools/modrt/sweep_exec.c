/* sweep_exec.c - one run of a campaign (`modrt sweep exec`): the scene with the run's
 * values, its metrics folded in tick by tick, and its result file DIR/runs/K.txt written
 * whole (temporary name, then rename). The run happens in a child process under a
 * supervisor that bounds its wall time and writes the result of a run that crashed or
 * timed out, so every engine (local, GNU parallel, Slurm) leaves a result for every run
 * it started. */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "mrlog.h"
#include "replay.h"
#include "runner.h"
#include "study.h"
#include "sweep.h"
#include "rt_sim.h" /* allocates the run */

static rt_sim sim;                       /* the run's storage */
static sweep_acc acc[SWEEP_MAX_METRICS];  /* its metrics */
static const sweep_campaign *cur;         /* the campaign of the observer below */

void sweep_result_path(char *buf, size_t n, const char *dir, uint64_t k)
{
    snprintf(buf, n, "%s/runs/%06llu.txt", dir, (unsigned long long)k);
}

/* a path of the campaign (scene file, log) relative to the campaign's directory */
static void rel_path(const sweep_campaign *c, const char *p, char *buf, size_t n)
{
    if (p[0] == '/' || strcmp(c->dir, ".") == 0)
        snprintf(buf, n, "%s", p);
    else
        snprintf(buf, n, "%s/%s", c->dir, p);
}

static mrl_header h; /* the replayed log's header */

/* the scene with every override of the run, initialised: a replay run's through
   replay.c, as `modrt replay` sets it up, with the campaign's overrides after the log's */
static int setup(const sweep_campaign *c, const sweep_exec_args *a, rt_scene *sc)
{
    static study_args sa;
    char path[SWEEP_PATH * 2], err[600];
    memset(&sa, 0, sizeof sa);
    for (int i = 0; i < a->nmethod; i++)
        if (study_add(&sa, "method", a->method[i]) != CLI_OK)
            return CLI_USAGE;
    for (int i = 0; i < a->nstep; i++)
        if (study_add(&sa, "step", a->step[i]) != CLI_OK)
            return CLI_USAGE;
    if (a->replay) {
        replay_more more = {c->t_end, &sa, a->sets, a->nsets};
        rel_path(c, a->replay, path, sizeof path);
        if (mrl_open(path, &h, err, sizeof err) != 0)
            return cli_fail("replay", err);
        return replay_scene(&h, path, &more, sc, &sim);
    }
    const char *scene = a->scene ? a->scene : c->scene; /* a grid's, else the campaign's */
    rel_path(c, scene, path, sizeof path);
    size_t n = strlen(scene); /* a scene file (FILE.scn), else a library name */
    int file = n > 4 && strcmp(scene + n - 4, ".scn") == 0;
    const rt_scene *base = cli_scene(file ? path : scene);
    if (!base)
        return CLI_USAGE;
    *sc = *base;
    if ((c->t_end >= 0 && cli_end_time(sc, c->t_end, c->path) != CLI_OK) ||
        study_apply(&sa, sc) != CLI_OK)
        return CLI_USAGE;
    rt_status st = rt_init(sc, &sim);
    if (st != RT_OK)
        return cli_fail(rt_status_name(st), rt_error_text(&sim));
    for (int i = 0; i < a->nsets; i++)
        if (cli_set_param(sc, &sim, a->sets[i]) != CLI_OK)
            return CLI_USAGE;
    if (a->nsets > 0) /* a refresh re-solves loops from the new values */
        return cli_refresh(sc, &sim);
    return CLI_OK;
}

static void observe(const rt_scene *sc, const rt_sim *s)
{
    sweep_metrics_sample(cur, sc, s, acc, (double)rt_time(sc, s));
}

/* the values the run was given, as result keys */
static void values(FILE *f, const sweep_exec_args *a)
{
    for (int i = 0; i < a->nsets; i++) {
        const char *eq = strchr(a->sets[i], '=');
        fprintf(f, "set.%.*s: %s\n", (int)(eq - a->sets[i]), a->sets[i], eq + 1);
    }
    for (int i = 0; i < a->nmethod; i++) {
        const char *eq = strchr(a->method[i], '=');
        fprintf(f, "method.%.*s: %s\n", (int)(eq - a->method[i]), a->method[i], eq + 1);
    }
    for (int i = 0; i < a->nstep; i++) {
        const char *eq = strchr(a->step[i], '=');
        fprintf(f, "step.%.*s: %s\n", (int)(eq - a->step[i]), a->step[i], eq + 1);
    }
    if (a->replay)
        fprintf(f, "replay: %s\n", a->replay);
    if (a->scene)
        fprintf(f, "scene_file: %s\n", a->scene);
}

/* the result of a run that completed (whatever its status) */
static int write_result(const sweep_campaign *c, const sweep_exec_args *a, const rt_scene *sc,
                        rt_status st, double wall, int sig, int code)
{
    char path[SWEEP_PATH + 40], tmp[SWEEP_PATH + 64], v[40];
    sweep_result_path(path, sizeof path, a->out, a->index);
    snprintf(tmp, sizeof tmp, "%s.%ld", path, (long)getpid());
    FILE *f = fopen(tmp, "w");
    if (!f)
        return cli_fail("cannot write the run's result", tmp);
    fprintf(f, "index: %llu\nstatus: %s\nexit: %d\nscene: %s\nticks: %llu\nwall_s: %.6f\n",
            (unsigned long long)a->index,
            sig                                  ? "interrupted"
            : rt_stats_of(&sim)->status == RT_OK ? (st == RT_E_DONE ? "ok" : rt_status_name(st))
                                                 : rt_status_name(rt_stats_of(&sim)->status),
            code, sc->name, (unsigned long long)rt_ticks_done(&sim), wall);
    fprintf(f, "hash: %016llx\ncampaign_hash: %016llx\n",
            (unsigned long long)rt_trace_hash(&sim), (unsigned long long)c->hash);
    for (int i = 0; i < RT_CNT_COUNT; i++)
        fprintf(f, "count.%s: %u\n", rt_counter_key((rt_counter)i), (unsigned)rt_stats_of(&sim)->count[i]);
    for (uint8_t k = 0; k < sc->nsets; k++) /* what the run cost, in right-hand sides */
        fprintf(f, "rhs_evals.%s: %llu\n", sc->sets[k].name,
                (unsigned long long)rt_stats_of(&sim)->rhs_evals[k]);
    values(f, a);
    for (int i = 0; i < c->nmetrics; i++)
        fprintf(f, "metric.%s: %s\n", c->metrics[i].name,
                cli_fmt(v, sizeof v, sweep_metric_value(c, acc, i)));
    if (fclose(f) != 0 || rename(tmp, path) != 0)
        return remove(tmp), cli_fail("cannot write the run's result", path);
    return CLI_OK;
}

/* the child: the run itself */
static int run_child(const sweep_campaign *c, const sweep_exec_args *a)
{
    rt_scene sc;
    if (setup(c, a, &sc) != CLI_OK || sweep_metrics_bind(c, &sc, acc) != 0)
        return CLI_USAGE;
    cur = c;
    FILE *csv = a->csv ? fopen(a->csv, "w") : NULL;
    if (a->csv && !csv)
        return cli_fail("cannot write the CSV file", a->csv);
    runner_opts o = {csv, 1, 0, a->replay ? mrl_replay_exchange : NULL, NULL, 0, NULL,
                     observe, a->replay ? replay_stop_tick(&h) : NULL};
    runner_result r;
    sweep_metrics_sample(c, &sc, &sim, acc, (double)rt_time(&sc, &sim)); /* tick 0 */
    rt_status st = runner_run(&sc, &sim, &o, &r);
    int sig = r.signal ? r.signal : a->replay ? replay_end(&h, &sim) : 0; /* as modrt replay */
    if (a->replay)
        mrl_close();
    if (csv && fclose(csv) != 0)
        return cli_fail("error writing the CSV file", a->csv);
    int code = sig ? CLI_INTERRUPTED : cli_exit_code(rt_status_severity(rt_stats_of(&sim)->status));
    return write_result(c, a, &sc, st, r.wall_s, sig, code) != CLI_OK ? CLI_USAGE : code;
}

/* B.p (at line:col of the campaign) set to v on the initialised scene, or one located
   error line */
static int check_param(const sweep_campaign *c, const rt_scene *sc, const char *name, double v,
                       int line, int col)
{
    char block[SWEEP_NAME];
    const char *dot = strchr(name, '.'), *why = NULL;
    snprintf(block, sizeof block, "%.*s", (int)(dot - name), name);
    rt_status st = RT_OK;
    if (rt_block_index(sc, block) < 0)
        why = "has no block";
    else if ((st = rt_set_param(sc, &sim, block, dot + 1, (real_t)v)) == RT_E_PARAM)
        why = "refuses the value";
    else if (st != RT_OK)
        why = "has no parameter or state";
    char val[40];
    if (why && st == RT_E_PARAM)
        fprintf(stderr, "%s:%d:%d: error: scene %s refuses %s = %s (out of the parameter's "
                "range)\n", c->path, line, col, sc->name, name, sweep_fmt(val, sizeof val, v));
    else if (why)
        fprintf(stderr, "%s:%d:%d: error: scene %s %s '%s'\n", c->path, line, col, sc->name,
                why, st == RT_OK ? block : name);
    return why ? CLI_USAGE : CLI_OK;
}

int sweep_check(const sweep_campaign *c, const sweep_exec_args *a)
{
    rt_scene sc;
    sweep_exec_args bare = *a;
    bare.nsets = 0; /* the scene first, then each varied name where the campaign names it */
    int rc = setup(c, &bare, &sc);
    /* every listed value, a range's ends, a draw's bounds: the scene accepts them all */
    for (int i = 0; i < c->ndims && rc == CLI_OK; i++) {
        const sweep_dim *d = &c->dims[i];
        for (uint32_t j = 0; d->kind == SWEEP_DIM_PARAM && j < d->n && rc == CLI_OK;
             j = d->is_range && j == 0 ? d->n - 1 : j + 1)
            rc = check_param(c, &sc, d->name, sweep_dim_num(c, i, j), d->line, d->col);
    }
    for (int i = 0; i < c->nvars && rc == CLI_OK; i++) {
        const sweep_var *v = &c->vars[i];
        rc = check_param(c, &sc, v->name, v->lo, v->line, v->col);
        if (rc == CLI_OK)
            rc = check_param(c, &sc, v->name, v->hi, v->line, v->col);
    }
    if (a->replay)
        mrl_close();
    if (rc == CLI_OK) /* all of run 0 together, as its task will */
        rc = setup(c, a, &sc) != CLI_OK || sweep_metrics_bind(c, &sc, acc) != 0 ? CLI_USAGE
                                                                                : CLI_OK;
    if (a->replay)
        mrl_close();
    return rc;
}

int sweep_write_status(const char *dir, uint64_t k, uint64_t hash, const char *status,
                       const char *why)
{
    char path[SWEEP_PATH + 40], tmp[SWEEP_PATH + 64];
    sweep_result_path(path, sizeof path, dir, k);
    snprintf(tmp, sizeof tmp, "%s.%ld", path, (long)getpid());
    FILE *f = fopen(tmp, "w");
    if (!f)
        return cli_fail("cannot write the run's result", tmp);
    fprintf(f, "index: %llu\nstatus: %s\nwhy: %s\ncampaign_hash: %016llx\n",
            (unsigned long long)k, status, why, (unsigned long long)hash);
    if (fclose(f) != 0 || rename(tmp, path) != 0)
        return remove(tmp), cli_fail("cannot write the run's result", path);
    return CLI_OK;
}

/* waits for the child at most timeout seconds (SIGCHLD blocked); 1 when it ended */
static int wait_child(pid_t pid, double timeout, int *wst)
{
    sigset_t set;
    struct timespec now, end;
    sigemptyset(&set), sigaddset(&set, SIGCHLD);
    clock_gettime(CLOCK_MONOTONIC, &end);
    end.tv_sec += (time_t)timeout;
    end.tv_nsec += (long)((timeout - sweep_floor(timeout)) * 1e9);
    if (end.tv_nsec >= 1000000000L)
        end.tv_sec++, end.tv_nsec -= 1000000000L;
    for (;;) {
        if (waitpid(pid, wst, WNOHANG) == pid)
            return 1;
        clock_gettime(CLOCK_MONOTONIC, &now);
        double left = (double)(end.tv_sec - now.tv_sec) + 1e-9 * (double)(end.tv_nsec - now.tv_nsec);
        if (left <= 0)
            return 0;
        struct timespec ts = {(time_t)left, (long)((left - sweep_floor(left)) * 1e9)};
        if (sigtimedwait(&set, NULL, &ts) < 0 && errno != EAGAIN && errno != EINTR)
            return waitpid(pid, wst, 0) == pid;
    }
}

int sweep_exec(const sweep_campaign *c, const sweep_exec_args *a)
{
    char why[160], path[SWEEP_PATH + 40];
    snprintf(path, sizeof path, "%s/runs", a->out); /* a plan printed without --out */
    if ((mkdir(a->out, 0777) != 0 && errno != EEXIST) || (mkdir(path, 0777) != 0 && errno != EEXIST))
        return cli_fail("cannot create the output directory", path);
    sigset_t set, old;
    sigemptyset(&set), sigaddset(&set, SIGCHLD);
    sigprocmask(SIG_BLOCK, &set, &old);
    fflush(NULL);
    pid_t pid = fork();
    if (pid < 0)
        return cli_fail("fork", strerror(errno));
    if (pid == 0) {
        sigprocmask(SIG_SETMASK, &old, NULL);
        exit(run_child(c, a));
    }
    int wst = 0;
    if (!wait_child(pid, c->timeout, &wst)) {
        kill(pid, SIGKILL);
        waitpid(pid, &wst, 0);
        snprintf(why, sizeof why, "no result after %g s (timeout)", c->timeout);
        sweep_write_status(a->out, a->index, c->hash, "timeout", why);
        return CLI_FAULTS;
    }
    if (WIFSIGNALED(wst)) {
        snprintf(why, sizeof why, "the run ended by signal %d (%s)", WTERMSIG(wst),
                 strsignal(WTERMSIG(wst)));
        sweep_write_status(a->out, a->index, c->hash, "crashed", why);
        return CLI_FAULTS;
    }
    int code = WEXITSTATUS(wst);
    sweep_result_path(path, sizeof path, a->out, a->index);
    if (code == CLI_USAGE || access(path, F_OK) != 0) { /* it said why on stderr */
        snprintf(why, sizeof why, "the run could not start (exit %d; its error is on its "
                 "stderr)", code);
        sweep_write_status(a->out, a->index, c->hash, "error", why);
        return CLI_USAGE;
    }
    return code;
}
