/* runner.c - the POSIX tick loops: the simulated clock runs ticks back to back (the
 * deterministic replay used by CI), the real-time clock paces them (rtloop.c: absolute
 * deadlines, latency statistics, the trace ring) and counts overruns. Both record
 * through rt_record at the same ticks, so the hash and the CSV are the same. */
#define _POSIX_C_SOURCE 200809L
#include <signal.h>
#include <string.h>
#include <time.h>

#include "port.h"
#include "runner.h"
#include "trace.h"

static double now_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* records the current state into the hash and, if wanted, the CSV */
static void record(const rt_scene *sc, rt_sim *sim, const runner_opts *o)
{
    real_t vals[RT_MAX_REC];
    rt_record(sc, sim, vals);
    if (o->csv)
        trace_csv_row(o->csv, sc, sim, vals);
}


/* ------------------------------------------------------------------ signals */

/* SIGINT or SIGTERM: the run stops between ticks, so the CSV ends in a whole row and the
   caller still closes its files and prints the summary. The handler only sets a flag. */
static volatile sig_atomic_t stop_signal;
static struct sigaction old_int, old_term;
static struct timespec stop_at; /* when the first signal came */

#define STOP_AGAIN_S 1 /* a signal this long after the first ends the program at once */

static void on_stop(int sig)
{
    struct timespec now;
    clock_gettime(CLOCK_MONOTONIC, &now); /* async-signal-safe */
    if (!stop_signal) {
        stop_at = now, stop_signal = sig;
        return;
    }
    /* asked again: the default action, at once; but not for the copies of the first that
       come together (Ctrl-C reaches a wrapper and modrt alike, `timeout` passes it on to
       modrt and to its process group) */
    double since = (double)(now.tv_sec - stop_at.tv_sec) +
                   1e-9 * (double)(now.tv_nsec - stop_at.tv_nsec);
    if (since > STOP_AGAIN_S) {
        signal(sig, SIG_DFL);
        raise(sig);
    }
}

int runner_stop_signal(void) { return stop_signal; }

static void catch_stop(void)
{
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_stop;
    sa.sa_flags = SA_RESTART; /* a write under way completes: no half row */
    sigemptyset(&sa.sa_mask);
    stop_signal = 0;
    sigaction(SIGINT, &sa, &old_int);
    sigaction(SIGTERM, &sa, &old_term);
    if (old_int.sa_handler == SIG_IGN) /* a background job (nohup, sh's &) stays deaf */
        sigaction(SIGINT, &old_int, NULL);
}

/* after a stop signal the handler stays: a copy of it that comes once the loop has
   ended (timeout's second one) must not kill the program before it has written its
   summary and finished its files */
static void release_stop(void)
{
    if (stop_signal)
        return;
    sigaction(SIGINT, &old_int, NULL);
    sigaction(SIGTERM, &old_term, NULL);
}

/* ------------------------------------------------------------------ the loops */

static int running(rt_status st) { return st != RT_E_DONE && st != RT_E_LINK; }

/* the inputs from outside at this tick; RT_E_LINK (also the run's status) ends the run */
static rt_status exchange(const rt_scene *sc, rt_sim *sim, const runner_opts *o, rt_status st)
{
    /* the last tick too: a sampled controller samples at the end time as well */
    if (!o->exchange || !o->exchange(o->xctx, sc, sim))
        return st;
    rt_note_status(sim, RT_E_LINK);
    return RT_E_LINK;
}

/* one tick, the exchange, and the recording; the unit of work of both clocks */
static rt_status tick_and_record(const rt_scene *sc, rt_sim *sim, const runner_opts *o)
{
    rt_status st = exchange(sc, sim, o, rt_tick(sc, sim));
    if (o->observe)
        o->observe(sc, sim);
    if (rt_ticks_done(sim) % o->every == 0 || !running(st))
        record(sc, sim, o);
    return st;
}


/* one real-time tick: the model and the exchange (rtloop.c records the row) */
static rt_status rt_tick_exchange(const rt_scene *sc, rt_sim *sim, void *ctx)
{
    return exchange(sc, sim, (const runner_opts *)ctx, rt_tick(sc, sim));
}

/* the real-time clock: rtloop.c paces the ticks; misses are counted as overruns, and
   policy stop ends the run as failed */
static rt_status run_realtime(const rt_scene *sc, rt_sim *sim, const runner_opts *o,
                              runner_result *r)
{
    rt_status st = RT_E_DONE;
    if (rt_ticks_done(sim) < rt_tick_count(sim)) {
        if (o->csv)
            fflush(o->csv); /* the header and row 0, before the writer thread takes over */
        st = rtloop_run(sc, sim, rt_tick_exchange, (void *)o, runner_stop_signal, o->every,
                        (rtloop_policy)o->overrun, o->csv, o->rt_log, stderr, &r->rt);
    }
    r->overruns = r->rt.misses;
    rt_note_count(sim, RT_CNT_OVERRUN, (uint32_t)r->rt.misses, r->rt.first_miss, RT_E_OVERRUN);
    if (r->rt.stopped)
        rt_note_status(sim, RT_E_STOPPED);
    return st == RT_OK ? RT_E_STOPPED : st;
}

/* the tick a replay of an interrupted run stops at, reached */
static int stop_reached(const runner_opts *o, const rt_sim *sim)
{
    return o->stop_tick && rt_ticks_done(sim) >= *o->stop_tick;
}

rt_status runner_run(const rt_scene *sc, rt_sim *sim, const runner_opts *o, runner_result *r)
{
    rt_status st = RT_OK;
    memset(r, 0, sizeof *r);
    if (o->csv)
        trace_csv_header(o->csv, sc);
    st = exchange(sc, sim, o, st);
    record(sc, sim, o);
    double t0 = now_s();
    catch_stop();
    if (!running(st)) {
    } else if (!o->realtime) {
        while (running(st) && !stop_signal && !stop_reached(o, sim))
            st = tick_and_record(sc, sim, o);
    } else {
        st = run_realtime(sc, sim, o, r);
    }
    r->signal = stop_signal;
    release_stop();
    r->wall_s = now_s() - t0;
    return st;
}
