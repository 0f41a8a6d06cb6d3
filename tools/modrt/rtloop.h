/* rtloop.h - the soft real-time tick loop on Linux (`modrt run --realtime`): absolute
 * deadlines on CLOCK_MONOTONIC, SCHED_FIFO and locked memory when permitted, no stdio and
 * no allocation in the tick path (the trace goes through trace.c), wake-up latency and
 * execution time per tick, and an overrun policy. */
#ifndef RTLOOP_H
#define RTLOOP_H

#include <stdint.h>
#include <stdio.h>

#include "rt.h"

/* What a missed deadline does (--overrun). Declared once: the enum and the names. */
#define RTLOOP_POLICY_LIST(X)                                                        \
    X(RTLOOP_CATCHUP, "catchup") /* run the missed ticks back to back (default) */ \
    X(RTLOOP_SKIP, "skip")       /* drop the missed deadlines: wait for the next */ \
    X(RTLOOP_STOP, "stop")       /* end the run at the first miss (failed) */

typedef enum {
#define RTLOOP_X_ENUM(id, name) id,
    RTLOOP_POLICY_LIST(RTLOOP_X_ENUM)
#undef RTLOOP_X_ENUM
    RTLOOP_POLICY_COUNT
} rtloop_policy;

/* The policy called name, or -1. */
int rtloop_policy_find(const char *name);
const char *rtloop_policy_name(rtloop_policy p);

/* min / p50 / p99 / max of one per-tick quantity [us] */
typedef struct rtloop_dist {
    double min, p50, p99, max;
} rtloop_dist;

typedef struct rtloop_stats {
    rtloop_dist latency;  /* wake-up after the deadline */
    rtloop_dist exec;     /* the tick's work, exchange and recording included */
    uint64_t misses;      /* ticks that ended after the next deadline */
    uint64_t first_miss;  /* the tick of the first miss */
    uint64_t skipped;     /* deadlines dropped (policy skip) */
    uint64_t dropped;     /* trace rows lost on a full ring */
    int fifo;             /* 1: ran under SCHED_FIFO */
    int locked;           /* 1: memory locked (mlockall) */
    int stopped;          /* 1: policy stop ended the run */
} rtloop_stats;

/* One tick of the run: ticks, exchanges, and returns the status (running while it is
   RT_OK); the loop records the row itself. */
typedef rt_status (*rtloop_tick_fn)(const rt_scene *sc, rt_sim *sim, void *ctx);

/* Runs the scene from its current tick to the end in real time, one tick per base step.
   stop: polled before each tick, nonzero ends the run (a signal, runner.c); csv/log may
   be NULL; every: record every N-th tick. Warnings (no SCHED_FIFO, no mlockall) go to
   warn once, before the first tick. */
rt_status rtloop_run(const rt_scene *sc, rt_sim *sim, rtloop_tick_fn tick, void *ctx,
                     int (*stop)(void), unsigned every, rtloop_policy policy, FILE *csv, FILE *log, FILE *warn,
                     rtloop_stats *out);
/* Prints the statistics as summary lines (key: value). */
void rtloop_print(FILE *f, rtloop_policy policy, const rtloop_stats *s);

#endif /* RTLOOP_H */
