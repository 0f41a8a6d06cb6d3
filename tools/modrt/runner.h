/* runner.h - running a scene on the POSIX port: the simulated clock (as fast as possible,
 * deterministic) or the real-time clock (one tick per base step of wall time), with the
 * CSV trace and the run summary. */
#ifndef RUNNER_H
#define RUNNER_H

#include <stdio.h>

#include "rt.h"
#include "rtloop.h"

typedef struct runner_opts {
    FILE *csv;          /* trace destination, or NULL */
    unsigned every;     /* record every N ticks (>= 1) */
    int realtime;       /* 1: pace ticks by the wall clock */
    /* the scene's inputs from outside (a controller link, a replay log), or NULL: called
       at tick 0 and after every tick before it is recorded; returns 1 to end the run */
    int (*exchange)(void *ctx, const rt_scene *sc, rt_sim *sim);
    void *xctx;
    int overrun;        /* real time: rtloop_policy of a missed deadline */
    FILE *rt_log;       /* real time: per-tick latency and execution time, or NULL */
    /* simulated clock: called after every tick (the global-error check, check.h), or
       NULL */
    void (*observe)(const rt_scene *sc, const rt_sim *sim);
} runner_opts;

typedef struct runner_result {
    double wall_s;      /* wall-clock time of the tick loop [s] */
    int signal;         /* SIGINT or SIGTERM that ended the run early, 0: none */
    uint64_t overruns;  /* real-time ticks that missed their deadline */
    rtloop_stats rt;    /* real time: latency, execution time, misses */
} runner_result;

/* Runs an initialised scene to its end; returns the last tick status (RT_E_LINK when the
   exchange ended it, also set as the run's status). SIGINT or SIGTERM during the run ends
   it after the tick under way and its CSV row (r->signal says which); another one a
   second or more later ends the program at once. */
rt_status runner_run(const rt_scene *sc, rt_sim *sim, const runner_opts *o, runner_result *r);
/* The signal that asked the run under way to stop, 0: none (the tick loops poll it). */
int runner_stop_signal(void);

#endif /* RUNNER_H */
