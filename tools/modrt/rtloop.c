/* rtloop.c - the soft real-time tick loop on Linux (rtloop.h).
 *
 * Deadlines are absolute: d_k = start + k P on CLOCK_MONOTONIC, slept to with
 * clock_nanosleep(TIMER_ABSTIME), so a late tick does not shift the later ones. The tick
 * thread asks for SCHED_FIFO and locks its memory when permitted (root or CAP_SYS_NICE /
 * CAP_IPC_LOCK), else says so once and runs soft real time. In the tick path: the clock,
 * the model, the exchange, and a row into the trace ring; no stdio, no allocation. Wake-up
 * latency and execution time go into fixed 1 us histograms for the percentiles.
 *
 * A scene with a background set (docs/multirate.md, "Background sets") gets a second
 * rt_sim as its background context and a thread one priority below the tick's (or a
 * normal thread without SCHED_FIFO) that runs each released step, woken by the tick
 * that released it: the tick then does only its own sets' work, and the trace is the
 * simulated clock's whatever the preemption (a step late at its deadline is counted). */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <pthread.h>
#include <sched.h>
#include <string.h>
#include <sys/mman.h>
#include <time.h>

#include "rtloop.h"
#include "trace.h"
#include "rt_sim.h" /* allocates the background context */

#define NS_PER_S 1000000000LL
#define HIST_US 100000     /* 1 us bins up to 100 ms; beyond: the last bin (max is exact) */
/* SCHED_FIFO priority of the tick: below the interrupt threads of a PREEMPT_RT kernel
   (50), which the link's network I/O needs, above every normal thread */
#define RT_FIFO_PRIO 49

static const char *const policy_names[] = {
#define RTLOOP_X_NAME(id, name) name,
    RTLOOP_POLICY_LIST(RTLOOP_X_NAME)
#undef RTLOOP_X_NAME
};

int rtloop_policy_find(const char *name)
{
    for (int i = 0; i < RTLOOP_POLICY_COUNT; i++)
        if (strcmp(policy_names[i], name) == 0)
            return i;
    return -1;
}

const char *rtloop_policy_name(rtloop_policy p)
{
    return (unsigned)p < RTLOOP_POLICY_COUNT ? policy_names[p] : "?";
}

/* ------------------------------------------------------------------ histograms */

typedef struct hist {
    uint32_t bin[HIST_US + 1];
    uint64_t n, min_ns, max_ns;
} hist;

static hist lat_hist, exec_hist;

static void hist_add(hist *h, int64_t ns)
{
    uint64_t v = ns > 0 ? (uint64_t)ns : 0, us = v / 1000;
    h->bin[us < HIST_US ? us : HIST_US]++;
    h->min_ns = h->n == 0 || v < h->min_ns ? v : h->min_ns;
    h->max_ns = v > h->max_ns ? v : h->max_ns;
    h->n++;
}

/* the smallest bin below which a fraction q of the samples lie, in us */
static double hist_quantile(const hist *h, double q)
{
    uint64_t want = (uint64_t)(q * (double)h->n + 0.5), seen = 0;
    for (uint32_t i = 0; i <= HIST_US; i++) {
        seen += h->bin[i];
        if (seen >= want && seen > 0)
            return (double)i;
    }
    return (double)HIST_US;
}

static rtloop_dist hist_dist(const hist *h)
{
    rtloop_dist d = {0, 0, 0, 0};
    if (h->n == 0)
        return d;
    d.min = 1e-3 * (double)h->min_ns, d.max = 1e-3 * (double)h->max_ns;
    d.p50 = hist_quantile(h, 0.50), d.p99 = hist_quantile(h, 0.99);
    return d;
}

/* ------------------------------------------------------------------ clock */

static int64_t ns_of(const struct timespec *t)
{
    return (int64_t)t->tv_sec * NS_PER_S + t->tv_nsec;
}

static struct timespec ts_of(int64_t ns)
{
    struct timespec t = {(time_t)(ns / NS_PER_S), (long)(ns % NS_PER_S)};
    return t;
}

static int64_t now_ns(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return ns_of(&t);
}

static void sleep_until(int64_t deadline)
{
    struct timespec d = ts_of(deadline);
    while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &d, NULL) == EINTR)
        ;
}

/* SCHED_FIFO and locked memory for this thread when permitted; one warning otherwise */
static void go_realtime(FILE *warn, rtloop_stats *s)
{
    struct sched_param sp = {.sched_priority = RT_FIFO_PRIO};
    int e = pthread_setschedparam(pthread_self(), SCHED_FIFO, &sp);
    s->fifo = e == 0;
    s->locked = mlockall(MCL_CURRENT | MCL_FUTURE) == 0;
    if (warn && (!s->fifo || !s->locked))
        fprintf(warn, "modrt: warning: %s%s%s: soft real time only (run as root, or grant "
                      "CAP_SYS_NICE and CAP_IPC_LOCK)\n",
                s->fifo ? "" : "no SCHED_FIFO", !s->fifo && !s->locked ? ", " : "",
                s->locked ? "" : "memory not locked");
}

static void go_normal(const rtloop_stats *s)
{
    struct sched_param sp = {.sched_priority = 0};
    if (s->fifo)
        pthread_setschedparam(pthread_self(), SCHED_OTHER, &sp);
    if (s->locked)
        munlockall();
}

/* ------------------------------------------------------------------ background thread */

static rt_sim bg_ctx; /* the background context (rt_bg_attach) */
static struct {
    pthread_mutex_t mu;
    pthread_cond_t cv;
    pthread_t th;
    int on, quit;
    const rt_scene *sc;
    rt_sim *sim;
} bgt = {.mu = PTHREAD_MUTEX_INITIALIZER, .cv = PTHREAD_COND_INITIALIZER};

static void *bg_main(void *arg)
{
    (void)arg;
    for (;;) {
        pthread_mutex_lock(&bgt.mu);
        while (!bgt.quit && !rt_bg_pending(bgt.sim))
            pthread_cond_wait(&bgt.cv, &bgt.mu);
        int quit = bgt.quit;
        pthread_mutex_unlock(&bgt.mu);
        if (quit)
            return NULL;
        rt_background(bgt.sc, bgt.sim);
    }
}

/* the background context and its thread, for a scene with a background set */
static void bg_start(const rt_scene *sc, rt_sim *sim, int fifo)
{
    bgt.on = 0, bgt.quit = 0, bgt.sc = sc, bgt.sim = sim;
    if (!sc->bg || rt_bg_attach(sc, sim, &bg_ctx) != RT_OK)
        return;
    pthread_attr_t at;
    pthread_attr_init(&at);
    struct sched_param sp = {.sched_priority = RT_FIFO_PRIO - 1};
    if (fifo && pthread_attr_setinheritsched(&at, PTHREAD_EXPLICIT_SCHED) == 0 &&
        pthread_attr_setschedpolicy(&at, SCHED_FIFO) == 0)
        pthread_attr_setschedparam(&at, &sp);
    bgt.on = pthread_create(&bgt.th, &at, bg_main, NULL) == 0 ||
             pthread_create(&bgt.th, NULL, bg_main, NULL) == 0;
    pthread_attr_destroy(&at);
}

/* after a tick: wake the thread for a step just released */
static void bg_kick(void)
{
    if (!bgt.on)
        return;
    pthread_mutex_lock(&bgt.mu);
    pthread_cond_signal(&bgt.cv);
    pthread_mutex_unlock(&bgt.mu);
}

static void bg_stop(void)
{
    if (!bgt.on)
        return;
    pthread_mutex_lock(&bgt.mu);
    bgt.quit = 1;
    pthread_cond_signal(&bgt.cv);
    pthread_mutex_unlock(&bgt.mu);
    pthread_join(bgt.th, NULL);
    bgt.on = 0;
}

/* ------------------------------------------------------------------ the loop */

static int running(rt_status st) { return st == RT_OK; }

/* the row of this tick: records (and hashes) every N-th tick and the last, like the
   simulated clock, into the ring or, when it is full, a scratch row */
static trace_row *fill_row(const rt_scene *sc, rt_sim *sim, unsigned every, rt_status st,
                           int *in_ring)
{
    static trace_row scratch;
    trace_row *r = trace_claim();
    *in_ring = r != NULL;
    r = r ? r : &scratch;
    r->tick = rt_ticks_done(sim);
    r->t = (double)rt_time(sc, sim);
    r->record = rt_ticks_done(sim) % every == 0 || !running(st);
    if (r->record)
        rt_record(sc, sim, r->vals);
    return r;
}

/* the next deadline after a tick that ended at `end`; counts a miss, applies the policy */
static int64_t next_deadline(int64_t d, int64_t period, int64_t end, rtloop_policy policy,
                             rtloop_stats *s, trace_row *r)
{
    int64_t next = d + period;
    r->late = end > next;
    if (!r->late)
        return next;
    if (s->misses++ == 0)
        s->first_miss = r->tick;
    if (policy == RTLOOP_STOP)
        s->stopped = 1;
    if (policy != RTLOOP_SKIP)
        return next;
    int64_t n = (end - next) / period + 1; /* deadlines already past */
    s->skipped += (uint64_t)n;
    return next + n * period;
}

rt_status rtloop_run(const rt_scene *sc, rt_sim *sim, rtloop_tick_fn tick, void *ctx,
                     int (*stop)(void), unsigned every, rtloop_policy policy, FILE *csv, FILE *log, FILE *warn,
                     rtloop_stats *out)
{
    rtloop_stats s;
    memset(&s, 0, sizeof s);
    memset(&lat_hist, 0, sizeof lat_hist), memset(&exec_hist, 0, sizeof exec_hist);
    rt_status st = RT_OK;
    double period_ns = (double)sc->dt * 1e9; /* in int64_t's range before the cast */
    if (!(period_ns < 9e18) || trace_start(sc, csv, log) != 0)
        return RT_E_ARG;
    go_realtime(warn, &s);
    bg_start(sc, sim, s.fifo);
    int64_t period = (int64_t)(period_ns + 0.5), d = now_ns() + period;
    while (running(st) && !s.stopped && !stop()) {
        sleep_until(d);
        int64_t wake = now_ns();
        st = tick(sc, sim, ctx);
        int in_ring;
        trace_row *r = fill_row(sc, sim, every, st, &in_ring);
        int64_t end = now_ns();
        r->latency_ns = (uint32_t)(wake > d ? wake - d : 0);
        r->exec_ns = (uint32_t)(end - wake);
        hist_add(&lat_hist, wake - d), hist_add(&exec_hist, end - wake);
        d = next_deadline(d, period, end, policy, &s, r);
        if (in_ring)
            trace_publish();
        bg_kick();
    }
    bg_stop();
    go_normal(&s);
    s.dropped = trace_stop();
    s.latency = hist_dist(&lat_hist), s.exec = hist_dist(&exec_hist);
    *out = s;
    return st;
}

void rtloop_print(FILE *f, rtloop_policy policy, const rtloop_stats *s)
{
    fprintf(f, "rt_sched: %s, memory %s; overrun policy %s\n",
            s->fifo ? "SCHED_FIFO" : "SCHED_OTHER (no permission for SCHED_FIFO)",
            s->locked ? "locked" : "not locked", rtloop_policy_name(policy));
    fprintf(f, "latency_us: min %.1f p50 %.0f p99 %.0f max %.1f\n", s->latency.min,
            s->latency.p50, s->latency.p99, s->latency.max);
    fprintf(f, "exec_us: min %.1f p50 %.0f p99 %.0f max %.1f\n", s->exec.min, s->exec.p50,
            s->exec.p99, s->exec.max);
    fprintf(f, "deadline_misses: %llu\nskipped_deadlines: %llu\ntrace_dropped: %llu\n",
            (unsigned long long)s->misses, (unsigned long long)s->skipped,
            (unsigned long long)s->dropped);
}
