/* trace.c - the CSV rows of a run's trace, and the trace ring of a real-time run
 * (trace.h): the tick thread owns `head`, the writer thread owns `tail`; each publishes
 * its index with release ordering and reads the other's with acquire, so a row is
 * complete before the writer sees it and free before the tick reuses it. The writer
 * sleeps 1 ms when the ring is empty. */
#define _POSIX_C_SOURCE 200809L
#include <pthread.h>
#include <stdatomic.h>
#include <time.h>

#include "trace.h"

static trace_row ring[TRACE_ROWS];
static _Atomic uint64_t head, tail; /* rows written by the tick, rows drained */
static atomic_int done;
static uint64_t dropped;
static pthread_t writer;
static const rt_scene *scene;
static FILE *csv_out, *log_out;

trace_row *trace_claim(void)
{
    uint64_t h = atomic_load_explicit(&head, memory_order_relaxed);
    if (h - atomic_load_explicit(&tail, memory_order_acquire) >= TRACE_ROWS) {
        dropped++;
        return NULL;
    }
    return &ring[h % TRACE_ROWS];
}

void trace_publish(void)
{
    atomic_fetch_add_explicit(&head, 1, memory_order_release);
}

/* ------------------------------------------------------------------ CSV rows */

void trace_csv_header(FILE *f, const rt_scene *sc)
{
    fputs("t", f);
    for (uint16_t i = 0; i < sc->nrecs; i++)
        fprintf(f, ",%s.%s", sc->blocks[sc->recs[i].block].name, rt_rec_signal(sc, i));
    fputc('\n', f);
}

void trace_csv_row(FILE *f, const rt_scene *sc, const rt_sim *sim, const real_t *vals)
{
    trace_csv_row_at(f, sc, (double)rt_time(sc, sim), vals);
}

void trace_csv_row_at(FILE *f, const rt_scene *sc, double t, const real_t *vals)
{
    /* 17 significant digits round-trip a double; 9 a float */
    const char *fmt = RT_REAL_IS_FLOAT ? ",%.9g" : ",%.17g";
    fprintf(f, RT_REAL_IS_FLOAT ? "%.9g" : "%.17g", t);
    for (uint16_t i = 0; i < sc->nrecs; i++)
        fprintf(f, fmt, (double)vals[i]);
    fputc('\n', f);
}

/* ------------------------------------------------------------------ the ring */

static void write_row(const trace_row *r)
{
    if (csv_out && r->record)
        trace_csv_row_at(csv_out, scene, r->t, r->vals);
    if (log_out)
        fprintf(log_out, "%llu,%.3f,%.3f,%u\n", (unsigned long long)r->tick,
                1e-3 * (double)r->latency_ns, 1e-3 * (double)r->exec_ns, (unsigned)r->late);
}

static void *drain(void *arg)
{
    (void)arg;
    const struct timespec nap = {0, 1000000};
    for (;;) {
        uint64_t t = atomic_load_explicit(&tail, memory_order_relaxed);
        uint64_t h = atomic_load_explicit(&head, memory_order_acquire);
        if (t == h) {
            if (atomic_load(&done))
                break;
            nanosleep(&nap, NULL);
            continue;
        }
        for (; t != h; t++)
            write_row(&ring[t % TRACE_ROWS]);
        atomic_store_explicit(&tail, t, memory_order_release);
    }
    return NULL;
}

int trace_start(const rt_scene *sc, FILE *csv, FILE *log)
{
    scene = sc, csv_out = csv, log_out = log, dropped = 0;
    atomic_store(&head, 0), atomic_store(&tail, 0), atomic_store(&done, 0);
    if (log)
        fputs("tick,wake_latency_us,exec_us,late\n", log);
    return pthread_create(&writer, NULL, drain, NULL) == 0 ? 0 : -1;
}

uint64_t trace_stop(void)
{
    atomic_store(&done, 1);
    pthread_join(writer, NULL);
    return dropped;
}
