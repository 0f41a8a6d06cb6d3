/* linkclient.h - the controller side of the modrt link over a byte stream, for firmware
 * (docs/link.md, "A controller on a microcontroller"): takes the plant's requests from a
 * UART (or any byte source) through the framing of linkframe.h, checks them with the codec
 * of link_wire.h, hands the application each request's values once, and sends its answer.
 * Freestanding C: no allocation, no stdio, no libm; the application owns the storage and
 * gives two functions, one that reads a byte and one that writes bytes.
 *
 *   static linkclient c;
 *   linkclient_init(&c, "pi_link", id, 2, 1, &io);
 *   for (;;)
 *       if (linkclient_poll(&c)) {             // a new request: c.req.v[0 .. nexp-1]
 *           if (c.new_run)                     // the plant started a run: start afresh
 *               reset();
 *           double u[1] = {law(c.req.v)};
 *           linkclient_answer(&c, u);
 *       }
 *
 * A lost answer is recovered by the plant sending the same request again: linkclient_poll
 * answers such a repeat from the copy of the answer it kept, without returning it, so the
 * controller's state (an integrator) advances exactly once per request. An answer echoes
 * its request's sequence number, tick and run nonce (wire format 2); with c.key set, every
 * datagram carries and needs the HMAC-SHA-256 tag of the authenticated mode. */
#ifndef LINKCLIENT_H
#define LINKCLIENT_H

#include <stddef.h>
#include <stdint.h>

#include "link_wire.h"
#include "linkframe.h"

/* The byte stream: read returns the next received byte (0 .. 255) or -1 when none is
   waiting (it must not block); write sends n bytes (it may wait until they are taken). */
typedef struct linkclient_io {
    int (*read)(void *ctx);
    void (*write)(void *ctx, const uint8_t *b, size_t n);
    void *ctx;
} linkclient_io;

typedef struct linkclient {
    /* what the controller answers (linkclient_init) */
    const char *scene;           /* the scene's name */
    uint32_t id;                 /* its link id (linkclient_layout_id) */
    uint16_t nexp, nimp;         /* values per request, per answer */
    linkclient_io io;
    const link_key *key;         /* NULL (set by init): unauthenticated; else the shared key */
    /* the request waiting for its answer: valid after linkclient_poll returned 1 */
    link_packet req;
    int pending;                 /* 1: req waits for linkclient_answer */
    int new_run;                 /* 1: req is the first of a run (a new run nonce) */
    uint64_t run;                /* the run nonce of the last request handed over */
    uint32_t req_crc;            /* the CRC field of req's datagram */
    /* the last answer as sent, and the request it answers (seq, tick, the request's CRC) */
    uint8_t answer[LINKFRAME_MAX_WIRE];
    size_t answer_len;
    uint32_t last_seq, last_crc;
    uint64_t last_tick;
    int answered;                /* 1: answer holds an answer */
    linkframe_rx rx;             /* the framing receiver; its fault[] counts broken frames */
    /* counts */
    uint32_t requests;           /* new requests handed to the application */
    uint32_t repeats;            /* repeated requests answered again from the copy */
    uint32_t overtaken;          /* requests a newer one replaced before they were answered */
    uint32_t bad[LINK_E_COUNT_]; /* datagrams refused, by link_wire_error */
} linkclient;

/* The link id of a layout (docs/link.md, "link id"): FNV-1a over each word and a '|'. */
uint32_t linkclient_layout_id(const char *const *words, int n);
/* Sets up c for scene `scene` (kept by pointer), link id `id`, nexp values per request and
   nimp per answer (each at most LINK_MAX_VALUES); io is copied. Returns 0, or -1. */
int linkclient_init(linkclient *c, const char *scene, uint32_t id, uint16_t nexp,
                    uint16_t nimp, const linkclient_io *io);
/* Reads every byte waiting. Returns 1 when a new request waits for its answer (values in
   c->req.v, its tick in c->req.tick), else 0. Broken frames and bad datagrams are
   counted and dropped; a repeat of the request answered last is answered again here. */
int linkclient_poll(linkclient *c);
/* Answers the waiting request with c->nimp values v. Returns 0, or -1 if no request
   waits or a value is not finite (nothing is sent: the plant will count it missing). */
int linkclient_answer(linkclient *c, const double *v);
/* All refused input: broken frames and bad datagrams. */
uint32_t linkclient_faults(const linkclient *c);

#endif /* LINKCLIENT_H */
