/* sweep_run.c - the local engine of `modrt sweep run`: the campaign's task lines, each
 * started as its own process (the argv of its line, no shell), at most --jobs at once.
 * The plan streams: one run's line is built when a slot frees, so a campaign of any size
 * needs --jobs slots of memory. A task that dies without its supervisor's result (killed
 * from outside) is a row too ("lost"). */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "sweep.h"

typedef struct slot {
    pid_t pid;      /* 0: free */
    uint64_t k;     /* its run */
} slot;

static slot slots[SWEEP_MAX_JOBS];

static double now_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* does run k need running: no result, one of another version of the campaign, or one
   that says nothing about the scene? */
static int missing(const sweep_campaign *c, const char *out, uint64_t k)
{
    char path[SWEEP_PATH + 40], line[128], want[40];
    snprintf(want, sizeof want, "campaign_hash: %016llx\n", (unsigned long long)c->hash);
    sweep_result_path(path, sizeof path, out, k);
    FILE *f = fopen(path, "r");
    if (!f)
        return 1;
    int need = 0, same = 0;
    while (fgets(line, sizeof line, f)) {
        same |= strcmp(line, want) == 0;
        if (strncmp(line, "status: ", 8) == 0) {
            line[strcspn(line, "\n")] = 0;
            need = !strcmp(line + 8, "timeout") || !strcmp(line + 8, "crashed") ||
                   !strcmp(line + 8, "error") || !strcmp(line + 8, "lost");
        }
    }
    fclose(f);
    return need || !same;
}

/* reaps one ended task; a task without a result leaves a "lost" row */
static void reap(const sweep_campaign *c, const char *out, int *active)
{
    int wst;
    pid_t pid = wait(&wst);
    if (pid < 0)
        return;
    for (int i = 0; i < SWEEP_MAX_JOBS; i++) {
        if (slots[i].pid != pid)
            continue;
        char path[SWEEP_PATH + 40], why[96];
        sweep_result_path(path, sizeof path, out, slots[i].k);
        if (access(path, F_OK) != 0) {
            snprintf(why, sizeof why, "its task ended without a result (%s %d)",
                     WIFSIGNALED(wst) ? "signal" : "exit",
                     WIFSIGNALED(wst) ? WTERMSIG(wst) : WEXITSTATUS(wst));
            sweep_write_status(out, slots[i].k, c->hash, "lost", why);
        }
        slots[i].pid = 0;
        (*active)--;
        return;
    }
}

static int start(char **argv, uint64_t k)
{
    for (int i = 0; i < SWEEP_MAX_JOBS; i++) {
        if (slots[i].pid)
            continue;
        fflush(NULL);
        pid_t pid = fork();
        if (pid < 0)
            return cli_fail("fork", strerror(errno)), -1;
        if (pid == 0) {
            execv(argv[0], argv);
            fprintf(stderr, "modrt: sweep: cannot run %s: %s\n", argv[0], strerror(errno));
            _exit(127);
        }
        slots[i].pid = pid, slots[i].k = k;
        return 0;
    }
    return -1;
}

int sweep_run_local(const sweep_campaign *c, const char *campaign, const char *out, int jobs,
                    int only_missing, const char *modrt)
{
    static char buf[SWEEP_LINE];
    char *argv[SWEEP_ARGS];
    sweep_point p;
    uint64_t started = 0;
    int active = 0;
    double t0 = now_s();
    if (sweep_write_info(c, campaign, out) != 0)
        return CLI_USAGE;
    for (uint64_t k = 0; k < c->nruns; k++) {
        if (only_missing && !missing(c, out, k))
            continue;
        sweep_point_of(c, k, &p);
        if (sweep_argv(c, &p, modrt, campaign, out, buf, sizeof buf, argv) < 0)
            return cli_fail("sweep: a task line longer than SWEEP_LINE", NULL);
        while (active >= jobs)
            reap(c, out, &active);
        if (start(argv, k) != 0)
            break;
        active++, started++;
    }
    while (active > 0)
        reap(c, out, &active);
    double wall = now_s() - t0;
    fprintf(stderr, "sweep: %llu of %llu runs in %.3f s on %d jobs (%.1f runs/s); "
            "modrt sweep collect %s merges them\n", (unsigned long long)started,
            (unsigned long long)c->nruns, wall, jobs, wall > 0 ? (double)started / wall : 0.0,
            out);
    return CLI_OK;
}
