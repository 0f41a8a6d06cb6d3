/* runner.c - the POSIX tick loops: the simulated clock runs ticks back to back (the
 * deterministic replay used by CI), the real-time clock paces them with port_timer_*
 * and counts overruns. Both record through rt_record, so the hash is the same. */
#define _POSIX_C_SOURCE 200809L
#include <time.h>

#include "port.h"
#include "runner.h"

static double now_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

void port_csv_header(FILE *f, const rt_scene *sc)
{
    fputs("t", f);
    for (uint16_t i = 0; i < sc->nrecs; i++)
        fprintf(f, ",%s.%s", sc->blocks[sc->recs[i].block].name, rt_rec_signal(sc, i));
    fputc('\n', f);
}

void port_csv_row(FILE *f, const rt_scene *sc, const rt_sim *sim, const real_t *vals)
{
    /* 17 significant digits round-trip a double; 9 a float */
    const char *fmt = RT_REAL_IS_FLOAT ? ",%.9g" : ",%.17g";
    fprintf(f, RT_REAL_IS_FLOAT ? "%.9g" : "%.17g", (double)rt_time(sc, sim));
    for (uint16_t i = 0; i < sc->nrecs; i++)
        fprintf(f, fmt, (double)vals[i]);
    fputc('\n', f);
}

/* records the current state into the hash and, if wanted, the CSV */
static void record(const rt_scene *sc, rt_sim *sim, const port_run_opts *o)
{
    real_t vals[RT_MAX_REC];
    rt_record(sc, sim, vals);
    if (o->csv)
        port_csv_row(o->csv, sc, sim, vals);
}


static int running(rt_status st) { return st != RT_E_DONE && st != RT_E_LINK; }

/* the inputs from outside at this tick; RT_E_LINK (also the run's status) ends the run */
static rt_status exchange(const rt_scene *sc, rt_sim *sim, const port_run_opts *o, rt_status st)
{
    /* the last tick too: a sampled controller samples at the end time as well */
    if (!o->exchange || !o->exchange(o->xctx, sc, sim))
        return st;
    if (rt_status_severity(RT_E_LINK) > rt_status_severity(sim->stats.status))
        sim->stats.status = RT_E_LINK;
    return RT_E_LINK;
}

/* one tick, the exchange, and the recording; the unit of work of both clocks */
static rt_status tick_and_record(const rt_scene *sc, rt_sim *sim, const port_run_opts *o)
{
    rt_status st = exchange(sc, sim, o, rt_tick(sc, sim));
    if (sim->state.tick % o->every == 0 || !running(st))
        record(sc, sim, o);
    return st;
}


/* the real-time clock calls this from port_timer_wait */
static const rt_scene *rt_scene_now;
static rt_sim *rt_sim_now;
static const port_run_opts *rt_opts_now;
static rt_status rt_last = RT_OK;
static uint64_t rt_overruns;

static void on_tick(void)
{
    if (!running(rt_last))
        return;
    rt_last = tick_and_record(rt_scene_now, rt_sim_now, rt_opts_now);
    if (port_timer_late())
        rt_overruns++;
}

rt_status port_run(const rt_scene *sc, rt_sim *sim, const port_run_opts *o, port_run_result *r)
{
    rt_status st = RT_OK;
    if (o->csv)
        port_csv_header(o->csv, sc);
    st = exchange(sc, sim, o, st);
    record(sc, sim, o);
    double t0 = now_s();
    if (!running(st)) {
    } else if (!o->realtime) {
        while (running(st))
            st = tick_and_record(sc, sim, o);
    } else {
        rt_scene_now = sc, rt_sim_now = sim, rt_opts_now = o, rt_last = RT_OK;
        rt_overruns = 0;
        uint32_t us = (uint32_t)(sc->dt * 1e6 + 0.5);
        if (sim->state.tick < sim->plan.n_ticks && port_timer_start(us, on_tick) == 0) {
            while (running(rt_last))
                port_timer_wait();
            port_timer_stop();
        }
        st = rt_last == RT_E_LINK ? RT_E_LINK : RT_E_DONE;
        sim->stats.count[RT_CNT_OVERRUN] += (uint32_t)rt_overruns;
    }
    r->wall_s = now_s() - t0;
    r->overruns = o->realtime ? rt_overruns : 0;
    return st;
}
