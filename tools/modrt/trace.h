/* trace.h - the CSV trace of a run (its header and rows, for both clocks), and the ring
 * of a real-time run: a lock-free single-producer single-consumer ring of recorded rows
 * (and each tick's timing) that the tick fills without a syscall, drained to the CSV and
 * the timing log by a writer thread. Nothing is dropped unless the ring is full, and a
 * full ring is counted. */
#ifndef TRACE_H
#define TRACE_H

#include <stdint.h>
#include <stdio.h>

#include "rt.h"

#define TRACE_ROWS 8192 /* rows the ring holds: 8 s of a 1 kHz scene if the disk stalls */

/* One row: what the tick recorded and how long it took. */
typedef struct trace_row {
    double t;                /* simulated time of the row */
    uint64_t tick;
    uint32_t latency_ns;     /* wake-up after the deadline */
    uint32_t exec_ns;        /* the tick's work */
    uint8_t record;          /* 1: vals go to the CSV (every N-th tick and the last) */
    uint8_t late;            /* the tick ended after the next deadline */
    real_t vals[RT_MAX_REC];
} trace_row;

/* Writes the CSV header: t, then Block.signal for each recorded signal. */
void trace_csv_header(FILE *f, const rt_scene *sc);
/* Writes one CSV row of the current state (values as recorded, full precision). */
void trace_csv_row(FILE *f, const rt_scene *sc, const rt_sim *sim, const real_t *vals);
/* The same for a row recorded at simulated time t (the real-time trace's writer). */
void trace_csv_row_at(FILE *f, const rt_scene *sc, double t, const real_t *vals);

/* Starts the writer thread; csv and log may be NULL. 0 on success. */
int trace_start(const rt_scene *sc, FILE *csv, FILE *log);
/* The tick side: the next free row, or NULL when the ring is full (counted). */
trace_row *trace_claim(void);
/* Publishes the row trace_claim returned. */
void trace_publish(void);
/* Drains what is left, stops the writer; returns the rows dropped on a full ring. */
uint64_t trace_stop(void);

#endif /* TRACE_H */
