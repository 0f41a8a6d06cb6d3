/* link.h - the POSIX controller link of `modrt run --link udp:HOST:PORT` or
 * `serial:DEVICE[:BAUD]` (docs/link.md): a transport (link_udp.c, link_serial.c) read
 * by a receiver thread that never blocks the tick, the lock-step and soft real-time
 * exchanges, the checks of every answer against its request, the per-signal policies and
 * the counters. */
#ifndef MODRT_LINK_H
#define MODRT_LINK_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "common/link_wire.h"
#include "rt.h"

struct mrl_writer;

typedef struct link_counts {
    uint64_t sent, applied;   /* requests sent; answers applied */
    uint64_t bad, late, missing, dup;
    uint64_t resent;          /* lock-step: requests sent again for want of an answer */
    uint64_t bad_kind[LINK_E_COUNT_]; /* bad by link_wire_error */
    double rtt_us[3];         /* round trip: p50, p99, max [us] */
} link_counts;

/* A transport carries the datagrams of link_wire.h unchanged, one at a time, between the
   plant and the one peer its spec names; everything else (framing checks, CRC, tag, run,
   sequence) is the link's. Slots are never NULL. */
typedef struct link_transport {
    const char *prefix;       /* the --link specs it serves, e.g. "udp:" */
    const char *usage;        /* e.g. "udp:HOST:PORT" */
    /* Checks a spec's syntax and ranges without opening anything: 0, or -1 with a
       one-line reason in err (a usage error). */
    int (*check)(const char *spec, char *err, size_t n);
    /* Opens the transport: 0, or -1 with a one-line reason. */
    int (*open)(const char *spec, char *err, size_t n);
    /* Sends one datagram whole without waiting: 0, or -1. The tick's thread. */
    int (*send)(const uint8_t *buf, size_t len);
    /* Waits at most poll_ms for one datagram from the peer (anything from another sender
       is dropped unseen) into buf: its length, 0 when none came, LINK_RECV_BROKEN when
       what arrived was a broken frame (counted link_bad.frame), -1 when the transport
       failed for good. The receiver thread only. */
    long (*recv)(uint8_t *buf, size_t cap, int poll_ms);
    void (*close)(void);
    /* 1: lock-step sends an unanswered request again every timeout / LINK_TRIES (a byte
       stream that loses frames to line noise; its controllers answer a repeat from a
       copy). 0: once (a UDP controller need not recognise a repeat). */
    int resend;
} link_transport;

#define LINK_RECV_BROKEN (-2L)
extern const link_transport link_udp;    /* link_udp.c */
extern const link_transport link_serial; /* link_serial.c */

typedef struct link_opts {
    int realtime;             /* 1: soft real-time exchange, else lock-step */
    double timeout_s;         /* lock-step: the wait for an answer */
    uint64_t run;             /* this run's nonce (link_nonce) */
    const link_key *key;      /* NULL: unauthenticated */
} link_opts;

/* Checks a --link spec (none, or one of the transports'): 0, or -1 with the reason. */
int link_spec_check(const char *spec, char *err, size_t n);
/* A fresh random run nonce (the OS's entropy; never 0). */
uint64_t link_nonce(void);
/* Reads the shared key of the authenticated mode from a file (1 to LINK_MAX_KEY bytes,
   taken as they are; one trailing newline is dropped): 0, or -1 with the reason. */
int link_key_read(const char *path, link_key *key, char *err, size_t n);
/* Opens the link `spec` for scene sc. Returns 0, or -1 with a one-line reason in err. */
int link_open(const char *spec, const rt_scene *sc, const link_opts *o,
              struct mrl_writer *rec, char *err, size_t n);
/* The runner hook: exchanges at the link's ticks; returns 1 to stop the run (an import
   with policy stop went missing). ctx is ignored (one link per process). */
int link_exchange(void *ctx, const rt_scene *sc, rt_sim *sim);
/* Stops the receiver thread, closes the transport and returns the counts. */
void link_close(link_counts *out);
/* 1 when the counts show a fault (link_bad or link_missing above 0): status and exit
   code "controller link faults". */
int link_faulty(const link_counts *c);
/* Summary lines (link_sent: ..., link_bad: ...). */
void link_print(FILE *f, const link_counts *c);
/* Fault injection for tests: from now on, the real-time tick finds the mailbox busy
   (its trylock fails) while `busy` is 1. */
void link_test_busy(int busy);

#endif /* MODRT_LINK_H */
