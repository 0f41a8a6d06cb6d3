/* sweep.c - the `modrt sweep` subcommand: its options and its actions (plan, run, exec,
 * collect, slurm). Every engine runs the same task lines: `plan` prints them, `run`
 * starts them on the local cores, GNU parallel reads them, and the Slurm script that
 * `slurm` writes has each array task print and run its own. */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "sweep.h"

sweep_cli_args sweep_cli_ctx = {.jobs = 0};
static sweep_campaign camp;
static char modrt_path[PATH_MAX], camp_path[PATH_MAX], out_path[PATH_MAX];

const char sweep_cli_help[] =
    "Actions:\n"
    "  plan CAMPAIGN     print the task list: one line per run, its index, a tab and the\n"
    "                    complete command of the run (--index K --count M: lines K..K+M-1)\n"
    "  run CAMPAIGN      run the task list on the local cores (--jobs N, default: all)\n"
    "  exec CAMPAIGN     one run, as a task line says (its result: DIR/runs/K.txt)\n"
    "  collect DIR       merge the results into DIR/results.csv and DIR/plots/*.svg\n"
    "  slurm CAMPAIGN    write DIR/sweep.sbatch, an array job whose tasks run the lines\n"
    "\n"
    "The results go to --out DIR (default ./sweep-NAME, NAME the campaign's). Run k's values\n"
    "depend on k and the campaign alone: every engine, in any order, on any machine, gives\n"
    "the same results. A run that fails, crashes or times out leaves a result saying so;\n"
    "collect writes a row for every run (status missing when a run left nothing).\n"
    "Exit status of exec: the run's (0 ok, 3 doubtful, 1 failed, 2 could not start);\n"
    "of collect: 0 when every run has a result. The campaign language: docs/sweeps.md.";

static int opt_out(void *ctx, const char *v)
{
    ((sweep_cli_args *)ctx)->exec.out = v;
    return CLI_OK;
}

static int opt_jobs(void *ctx, const char *v)
{
    unsigned long n;
    if (!cli_uint(v, 1, SWEEP_MAX_JOBS, &n))
        return cli_fail("--jobs expects a whole number in [1, 256], got", v);
    ((sweep_cli_args *)ctx)->jobs = (int)n;
    return CLI_OK;
}

static int opt_index(void *ctx, const char *v)
{
    unsigned long n;
    if (!cli_uint(v, 0, ULONG_MAX, &n))
        return cli_fail("--index expects a run index (a whole number), got", v);
    ((sweep_cli_args *)ctx)->exec.index = n, ((sweep_cli_args *)ctx)->exec.has_index = 1;
    return CLI_OK;
}

static int opt_count(void *ctx, const char *v)
{
    unsigned long n;
    if (!cli_uint(v, 1, ULONG_MAX, &n))
        return cli_fail("--count expects a whole number >= 1, got", v);
    ((sweep_cli_args *)ctx)->count = n;
    return CLI_OK;
}

static int opt_per_task(void *ctx, const char *v)
{
    unsigned long n;
    if (!cli_uint(v, 1, ULONG_MAX, &n))
        return cli_fail("--per-task expects a whole number >= 1, got", v);
    ((sweep_cli_args *)ctx)->per_task = n;
    return CLI_OK;
}

static int opt_only_missing(void *ctx, const char *v)
{
    (void)v;
    ((sweep_cli_args *)ctx)->only_missing = 1;
    return CLI_OK;
}

static int opt_sbatch(void *ctx, const char *v)
{
    sweep_cli_args *a = ctx;
    if (a->nsbatch >= SWEEP_SBATCH_OPTS)
        return cli_fail("too many --sbatch-opt options", v);
    a->sbatch[a->nsbatch++] = v;
    return CLI_OK;
}

/* --set, --method, --step SET=VALUE of an exec */
static int add_kv(const char **list, int *n, int max, const char *opt, const char *v)
{
    char msg[64];
    if (!strchr(v, '=')) {
        snprintf(msg, sizeof msg, "--%s expects NAME=VALUE, got", opt);
        return cli_fail(msg, v);
    }
    if (*n >= max) {
        snprintf(msg, sizeof msg, "too many --%s options", opt);
        return cli_fail(msg, v);
    }
    list[(*n)++] = v;
    return CLI_OK;
}

static int opt_set(void *ctx, const char *v)
{
    sweep_exec_args *e = &((sweep_cli_args *)ctx)->exec;
    return add_kv(e->sets, &e->nsets, SWEEP_MAX_DIMS + SWEEP_MAX_VARS, "set", v);
}

static int opt_method(void *ctx, const char *v)
{
    sweep_exec_args *e = &((sweep_cli_args *)ctx)->exec;
    return add_kv(e->method, &e->nmethod, SWEEP_MAX_DIMS, "method", v);
}

static int opt_step(void *ctx, const char *v)
{
    sweep_exec_args *e = &((sweep_cli_args *)ctx)->exec;
    return add_kv(e->step, &e->nstep, SWEEP_MAX_DIMS, "step", v);
}

static int opt_replay(void *ctx, const char *v)
{
    ((sweep_cli_args *)ctx)->exec.replay = v;
    return CLI_OK;
}

static int opt_scene(void *ctx, const char *v)
{
    ((sweep_cli_args *)ctx)->exec.scene = v;
    return CLI_OK;
}

static int opt_csv(void *ctx, const char *v)
{
    ((sweep_cli_args *)ctx)->exec.csv = v;
    return CLI_OK;
}

const cli_opt sweep_cli_opts[] = {
    {"out", "DIR", "the campaign's directory of results (default ./sweep-NAME)", opt_out},
    {"jobs", "N", "run: runs at once on this machine (also -j N; default: its cores)",
     opt_jobs},
    {"only-missing", NULL, "run: only the runs without a result, or whose result says it "
     "crashed, timed out or could not start", opt_only_missing},
    {"index", "K", "plan: start at run K; exec: the run's index", opt_index},
    {"count", "M", "plan: print M lines (default: to the last run)", opt_count},
    {"per-task", "M", "slurm: runs per array task (default: as few tasks as fit in 1000)",
     opt_per_task},
    {"sbatch-opt", "OPT", "slurm: one more #SBATCH line, e.g. --sbatch-opt=--partition=short; "
     "repeatable", opt_sbatch},
    {"set", "BLOCK.PARAM=VALUE", "exec: a parameter or initial state of the run; repeatable",
     opt_set},
    {"method", "SET=NAME", "exec: the method of a set; repeatable", opt_method},
    {"step", "SET=TIME", "exec: the step of a set; repeatable", opt_step},
    {"replay", "FILE.mrl", "exec: replay this log (its path as the campaign writes it)",
     opt_replay},
    {"scene", "FILE.scn", "exec: run this scene file (its path as the campaign writes it)",
     opt_scene},
    {"csv", "FILE", "exec: also write the run's recorded signals as CSV to FILE", opt_csv},
    {NULL, NULL, NULL, NULL},
};

void sweep_short_opts(int argc, char **argv)
{
    static char jobs[32];
    for (int i = 2; i < argc && strcmp(argv[i], "--") != 0; i++)
        if (strcmp(argv[i], "-j") == 0)
            argv[i] = "--jobs";
        else if (strncmp(argv[i], "-j", 2) == 0 && strlen(argv[i]) < sizeof jobs - 7)
            snprintf(jobs, sizeof jobs, "--jobs=%s", argv[i] + 2), argv[i] = jobs;
}

/* p as an absolute path (without resolving links: the same text on every node) */
static int absolute(const char *p, char *buf, size_t n)
{
    char cwd[PATH_MAX];
    if (p[0] == '/')
        return snprintf(buf, n, "%s", p) < (int)n ? 0 : -1;
    if (!getcwd(cwd, sizeof cwd))
        return -1;
    if (strncmp(p, "./", 2) == 0)
        p += 2;
    return snprintf(buf, n, "%s/%s", cwd, p) < (int)n ? 0 : -1;
}

/* the campaign, this modrt and the output directory, as the task lines name them */
static int paths(sweep_cli_args *a, const char *campaign)
{
    char out[PATH_MAX];
    ssize_t n = readlink("/proc/self/exe", modrt_path, sizeof modrt_path - 1);
    if (n <= 0)
        return cli_fail("sweep: cannot find this program's path (/proc/self/exe)", NULL);
    modrt_path[n] = 0;
    if (absolute(campaign, camp_path, sizeof camp_path) != 0)
        return cli_fail("sweep: path too long", campaign);
    snprintf(out, sizeof out, "sweep-%s", camp.name);
    if (absolute(a->exec.out ? a->exec.out : out, out_path, sizeof out_path) != 0)
        return cli_fail("sweep: path too long", a->exec.out);
    return CLI_OK;
}

static int plan(const sweep_cli_args *a)
{
    static char buf[SWEEP_LINE];
    char *argv[SWEEP_ARGS];
    sweep_point p;
    uint64_t k0 = a->exec.has_index ? a->exec.index : 0, k1 = camp.nruns;
    if (a->count && a->count < k1 - (k0 < k1 ? k0 : k1))
        k1 = k0 + a->count;
    /* only when asked: printing a plan leaves no trace by default */
    if (a->exec.out && !a->exec.has_index && sweep_write_info(&camp, camp_path, out_path) != 0)
        return CLI_USAGE;
    for (uint64_t k = k0; k < k1; k++) {
        sweep_point_of(&camp, k, &p);
        if (sweep_argv(&camp, &p, modrt_path, camp_path, out_path, buf, sizeof buf, argv) < 0)
            return cli_fail("sweep: a task line longer than SWEEP_LINE", NULL);
        if (sweep_task_line(stdout, argv, k) != 0)
            return CLI_FAULTS; /* the reader went away */
    }
    return fflush(stdout) == 0 ? CLI_OK : CLI_FAULTS;
}

/* DIR/sweep.sbatch: an array job; task t runs lines t*M .. t*M+M-1, printed by plan */
static int slurm(const sweep_cli_args *a)
{
    char path[PATH_MAX + 32];
    uint64_t per = a->per_task ? a->per_task
                               : (camp.nruns + SWEEP_SLURM_TASKS - 1) / SWEEP_SLURM_TASKS;
    uint64_t tasks = (camp.nruns + per - 1) / per;
    if (sweep_write_info(&camp, camp_path, out_path) != 0)
        return CLI_USAGE;
    snprintf(path, sizeof path, "%s/slurm", out_path);
    if (mkdir(path, 0777) != 0 && errno != EEXIST)
        return cli_fail("cannot create", path);
    snprintf(path, sizeof path, "%s/sweep.sbatch", out_path);
    FILE *f = fopen(path, "w");
    if (!f)
        return cli_fail("cannot write", path);
    fprintf(f, "#!/bin/sh\n#SBATCH --job-name=sweep-%s\n#SBATCH --array=0-%llu\n"
            "#SBATCH --ntasks=1\n#SBATCH --cpus-per-task=1\n#SBATCH --output=%s/slurm/%%a.log\n",
            camp.name, (unsigned long long)(tasks - 1), out_path);
    for (int i = 0; i < a->nsbatch; i++)
        fprintf(f, "#SBATCH %s\n", a->sbatch[i]);
    fprintf(f, "# written by modrt sweep slurm: %llu runs of %s, %llu per array task.\n"
            "# Each task prints its lines of the task list and runs them unchanged; then\n"
            "#   modrt sweep collect %s\n# merges the results.\n"
            "'%s' sweep plan '%s' --out '%s' --index $((SLURM_ARRAY_TASK_ID * %llu)) "
            "--count %llu | cut -f2- | sh\n",
            (unsigned long long)camp.nruns, camp_path, (unsigned long long)per, out_path,
            modrt_path, camp_path, out_path, (unsigned long long)per, (unsigned long long)per);
    if (fclose(f) != 0)
        return cli_fail("cannot write", path);
    printf("%s\n", path);
    fprintf(stderr, "sweep: %llu runs in %llu array tasks; submit with: sbatch %s\n",
            (unsigned long long)camp.nruns, (unsigned long long)tasks, path);
    return CLI_OK;
}

/* svgplot beside this modrt (make builds both into the same directory) */
static void svgplot_path(char *buf, size_t n)
{
    ssize_t len = readlink("/proc/self/exe", buf, n - 16);
    buf[len > 0 ? len : 0] = 0;
    char *slash = strrchr(buf, '/');
    snprintf(slash ? slash + 1 : buf, 16, "svgplot");
}

/* run 0 set up as its task line says: a wrong name fails here, not in every task */
static int check_first(void)
{
    static char buf[SWEEP_LINE];
    static sweep_exec_args e;
    char *argv[SWEEP_ARGS];
    sweep_point p;
    sweep_point_of(&camp, 0, &p);
    int n = sweep_argv(&camp, &p, "modrt", "c", "o", buf, sizeof buf, argv);
    if (n < 0)
        return cli_fail("sweep: a task line longer than SWEEP_LINE", NULL);
    for (int i = 8; i + 1 < n; i += 2) { /* after modrt sweep exec C --out O --index K */
        if (!strcmp(argv[i], "--set"))
            e.sets[e.nsets++] = argv[i + 1];
        else if (!strcmp(argv[i], "--method"))
            e.method[e.nmethod++] = argv[i + 1];
        else if (!strcmp(argv[i], "--step"))
            e.step[e.nstep++] = argv[i + 1];
        else if (!strcmp(argv[i], "--scene"))
            e.scene = argv[i + 1];
        else
            e.replay = argv[i + 1];
    }
    return sweep_check(&camp, &e);
}

int sweep_cli_run(void *ctx, int npos, char **pos)
{
    sweep_cli_args *a = ctx;
    const char *act = pos[0];
    (void)npos;
    if (strcmp(act, "collect") == 0) {
        char svg[PATH_MAX];
        svgplot_path(svg, sizeof svg);
        return sweep_collect(pos[1], svg);
    }
    if (strcmp(act, "plan") && strcmp(act, "run") && strcmp(act, "exec") &&
        strcmp(act, "slurm"))
        return cli_fail("sweep: unknown action (plan, run, exec, collect, slurm)", act);
    if (sweep_parse(pos[1], &camp) != 0)
        return CLI_USAGE;
    if (strcmp(act, "exec") == 0) {
        if (!a->exec.out || !a->exec.has_index)
            return cli_fail("sweep exec needs --out DIR and --index K (as its task line "
                            "gives them)", NULL);
        return sweep_exec(&camp, &a->exec);
    }
    if (paths(a, pos[1]) != CLI_OK || check_first() != CLI_OK)
        return CLI_USAGE;
    if (strcmp(act, "plan") == 0)
        return plan(a);
    if (strcmp(act, "slurm") == 0)
        return slurm(a);
    int jobs = a->jobs ? a->jobs : (int)sysconf(_SC_NPROCESSORS_ONLN);
    return sweep_run_local(&camp, camp_path, out_path, jobs < 1 ? 1 : jobs, a->only_missing,
                           modrt_path);
}
