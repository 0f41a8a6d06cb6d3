/* link.h - the POSIX controller link of `modrt run --link udp:HOST:PORT` or
 * `serial:DEVICE:BAUD` (docs/link.md): a UDP socket or a serial line with a receiver thread that never blocks the tick, the lock-step and soft
 * real-time exchanges, the per-signal policies and the counters; and the input sources
 * of a run (live link, or a replay log) as one runner hook. */
#ifndef MODRT_LINK_H
#define MODRT_LINK_H

#include <stdint.h>
#include <stdio.h>

#include "rt.h"

struct mrl_writer;

typedef struct link_counts {
    uint64_t sent, applied;   /* exports sent; replies applied */
    uint64_t bad, late, missing, dup;
    uint64_t resent;          /* lock-step: requests sent again for want of an answer */
    uint64_t bad_kind[16];    /* bad by link_wire_error */
    double rtt_us[3];         /* round trip: p50, p99, max [us] */
} link_counts;

/* Opens the link `spec` (udp:HOST:PORT, IPv4 or [IPv6] or a name; serial:DEVICE[:BAUD],
   serial.h) for scene sc; realtime
   selects the soft real-time exchange, else lock-step with `timeout_s` per exchange.
   Returns 0, or -1 with a one-line reason in err. */
int link_open(const char *spec, const rt_scene *sc, int realtime, double timeout_s,
              struct mrl_writer *rec, char *err, size_t n);
/* The runner hook: exchanges at the link's ticks; returns 1 to stop the run (an import
   with policy stop went missing). ctx is ignored (one link per process). */
int link_exchange(void *ctx, const rt_scene *sc, rt_sim *sim);
/* Stops the receiver thread, closes the socket and returns the counts. */
void link_close(link_counts *out);
/* Summary lines (link_sent: ..., link_bad: ...). */
void link_print(FILE *f, const link_counts *c);

#endif /* MODRT_LINK_H */
