/* test_linkframe.c - tests of the link's byte-stream framing (ports/common/linkframe.c)
 * against COBS codings worked out by hand from Cheshire & Baker's definition and two of
 * the published examples, round trips of every datagram length, resynchronisation after
 * garbage, a lost byte, a flipped bit and an overlong frame; and of the controller's
 * client library (ports/common/linkclient.c) on an in-memory byte stream: a request is
 * handed over once, a repeated request is answered from the kept copy without advancing
 * the controller, bad input is counted. */
#include <string.h>

#include "common/linkclient.h"
#include "common/linkframe.h"
#include "testutil.h"

/* feeds bytes one by one; returns the verdicts that were not LINKFRAME_MORE, in order,
   and the last datagram */
typedef struct feed_out {
    int verdict[16], n;
    uint8_t d[LINK_MAX_PACKET];
    size_t len;
} feed_out;

static void feed(linkframe_rx *rx, const uint8_t *b, size_t n, feed_out *o)
{
    o->n = 0;
    for (size_t i = 0; i < n; i++) {
        const uint8_t *d;
        size_t len;
        linkframe_verdict v = linkframe_rx_byte(rx, b[i], &d, &len);
        if (v == LINKFRAME_MORE)
            continue;
        if (o->n < 16)
            o->verdict[o->n++] = v;
        if (v == LINKFRAME_DATAGRAM)
            memcpy(o->d, d, len), o->len = len;
    }
}

/* the coded frame of payload "01 d..." must be `want` (delimiters included) */
static int codes_as(const uint8_t *d, size_t n, const uint8_t *want, size_t nw)
{
    uint8_t out[LINKFRAME_MAX_WIRE];
    size_t m = linkframe_encode(d, n, out, sizeof out);
    return m == nw && memcmp(out, want, nw) == 0 && m <= LINKFRAME_WIRE(n);
}

static void test_cobs_vectors(void)
{
    /* by hand: the payload is the version byte 01 followed by the datagram */
    static const uint8_t z[] = {0x00}, zw[] = {0, 0x02, 0x01, 0x01, 0};
    static const uint8_t a[] = {0x11, 0x22, 0x00, 0x33},
                         aw[] = {0, 0x04, 0x01, 0x11, 0x22, 0x02, 0x33, 0};
    static const uint8_t e[1] = {0}, ew[] = {0, 0x02, 0x01, 0};
    TH_CHECK(codes_as(z, 1, zw, sizeof zw));
    TH_CHECK(codes_as(a, sizeof a, aw, sizeof aw));
    TH_CHECK(codes_as(e, 0, ew, sizeof ew));
    /* Cheshire & Baker's (Wikipedia's) examples that start with 01: 01 02 .. FE encodes
       to FF 01 .. FE (no code byte after a full run at the end); 01 .. FF to FF 01 .. FE
       02 FF */
    uint8_t d[255], w[262];
    for (int i = 0; i < 254; i++)
        d[i] = (uint8_t)(i + 2); /* 02 .. FF */
    w[0] = 0, w[1] = 0xFF;
    for (int i = 0; i < 254; i++)
        w[2 + i] = (uint8_t)(i + 1); /* 01 .. FE */
    w[256] = 0;
    TH_CHECK(codes_as(d, 253, w, 257));
    w[256] = 0x02, w[257] = 0xFF, w[258] = 0;
    TH_CHECK(codes_as(d, 254, w, 259));
}

static void test_frame_round_trip(void)
{
    static linkframe_rx rx;
    uint8_t d[LINK_MAX_PACKET], w[LINKFRAME_MAX_WIRE];
    feed_out o;
    uint32_t s = 12345;
    linkframe_rx_init(&rx);
    int all = 1;
    for (size_t n = 0; n <= LINK_MAX_PACKET; n++) {
        for (size_t i = 0; i < n; i++) /* many zeros and runs: every third byte is 0 */
            s = s * 1103515245u + 12345u, d[i] = i % 3 == 1 ? 0 : (uint8_t)(s >> 16);
        size_t m = linkframe_encode(d, n, w, sizeof w);
        feed(&rx, w, m, &o);
        all &= m > 0 && m <= LINKFRAME_WIRE(n) && memchr(w + 1, 0, m - 2) == NULL &&
               o.n == 1 && o.verdict[0] == LINKFRAME_DATAGRAM && o.len == n &&
               memcmp(o.d, d, n) == 0;
    }
    TH_CHECK(all);
    /* a run of nonzero bytes as long as the largest datagram */
    memset(d, 0xA5, sizeof d);
    size_t m = linkframe_encode(d, sizeof d, w, sizeof w);
    feed(&rx, w, m, &o);
    TH_CHECK(o.n == 1 && o.verdict[0] == LINKFRAME_DATAGRAM && o.len == sizeof d);
    TH_CHECK(linkframe_encode(d, LINK_MAX_PACKET + 1, w, sizeof w) == 0);
    TH_CHECK(linkframe_encode(d, 10, w, LINKFRAME_WIRE(10) - 1) == 0);
}

static void test_frame_resync(void)
{
    static linkframe_rx rx;
    uint8_t d[40], w[64], s[256];
    feed_out o;
    for (int i = 0; i < 40; i++)
        d[i] = (uint8_t)(i * 7);
    size_t m = linkframe_encode(d, sizeof d, w, sizeof w), n;
    linkframe_rx_init(&rx);
    /* garbage without a zero before a frame: its own (broken) frame, then the datagram */
    static const uint8_t junk[] = {0x55, 0xAA, 0x13};
    memcpy(s, junk, 3), memcpy(s + 3, w, m);
    feed(&rx, s, 3 + m, &o);
    TH_CHECK(o.n == 2 && o.verdict[0] != LINKFRAME_DATAGRAM && o.verdict[1] == LINKFRAME_DATAGRAM);
    /* a byte lost inside: the frame decodes to something the datagram check refuses, or
       breaks (it never yields the original); the next frame is whole */
    memcpy(s, w, 10), memcpy(s + 10, w + 11, m - 11), memcpy(s + m - 1, w, m);
    feed(&rx, s, 2 * m - 1, &o);
    TH_CHECK(o.n == 2 && o.verdict[1] == LINKFRAME_DATAGRAM && o.len == sizeof d);
    TH_CHECK(o.verdict[0] != LINKFRAME_DATAGRAM || o.len != sizeof d);
    /* a code byte that points past the end: COBS fault */
    static const uint8_t past[] = {0, 0x05, 0x11, 0x22, 0};
    feed(&rx, past, sizeof past, &o);
    TH_CHECK(o.n == 1 && o.verdict[0] == LINKFRAME_E_COBS && rx.fault[LINKFRAME_E_COBS] >= 1);
    /* another framing version */
    static const uint8_t v2[] = {0, 0x03, 0x02, 0x11, 0};
    feed(&rx, v2, sizeof v2, &o);
    TH_CHECK(o.n == 1 && o.verdict[0] == LINKFRAME_E_VERSION);
    /* an overlong frame: one fault when it overflows, nothing at its end, then in sync */
    n = 0;
    for (size_t i = 0; i < LINKFRAME_MAX_CODED + 50; i++)
        s[n++ % sizeof s] = 0x77, feed(&rx, s, 1, &o), n = 0;
    TH_CHECK(rx.fault[LINKFRAME_E_LONG] == 1);
    feed(&rx, w, m, &o);
    TH_CHECK(o.n == 1 && o.verdict[0] == LINKFRAME_DATAGRAM && rx.fault[LINKFRAME_E_LONG] == 1);
    /* a frame that fits the coded buffer but decodes to more than the largest datagram:
       code 2 blocks expand each two coded bytes to two payload bytes (no COBS overhead),
       so LINKFRAME_MAX_CODED coded bytes give LINKFRAME_MAX_CODED - 1 payload bytes */
    static uint8_t big[LINKFRAME_MAX_CODED + 2];
    n = 0, big[n++] = 0, big[n++] = 0x02, big[n++] = LINKFRAME_VERSION;
    while (n + 2 <= LINKFRAME_MAX_CODED + 1)
        big[n++] = 0x02, big[n++] = 0x33;
    big[n++] = 0;
    feed(&rx, big, n, &o);
    TH_CHECK(o.n == 1 && o.verdict[0] == LINKFRAME_E_LONG && rx.fault[LINKFRAME_E_LONG] == 2);
    feed(&rx, w, m, &o);
    TH_CHECK(o.n == 1 && o.verdict[0] == LINKFRAME_DATAGRAM && o.len == sizeof d);
}

/* ------------------------------------------------------------------ client library */

typedef struct pipe_io {
    uint8_t in[4096];
    size_t in_len, in_pos;
    uint8_t out[4096];
    size_t out_len;
} pipe_io;

static int p_read(void *ctx)
{
    pipe_io *p = ctx;
    return p->in_pos < p->in_len ? p->in[p->in_pos++] : -1;
}

static void p_write(void *ctx, const uint8_t *b, size_t n)
{
    pipe_io *p = ctx;
    memcpy(p->out + p->out_len, b, n), p->out_len += n;
}

/* the plant's request seq/tick with values r, m, framed onto the controller's input;
   flip: a bit of the first value flipped after the CRC was computed */
static void plant_sends(pipe_io *p, uint32_t id, uint32_t seq, uint64_t tick, double r, double m,
                        int flip)
{
    link_packet q = {.type = LINK_TYPE_EXPORTS, .n = 2, .id = id, .seq = seq, .tick = tick,
                     .run = 0x0123456789abcdefull + (seq > 100), .v = {r, m}};
    uint8_t d[LINK_MAX_PACKET];
    strcpy(q.name, "pi_link");
    size_t n = link_encode(&q, NULL, d, sizeof d);
    d[LINK_HEADER] ^= (uint8_t)(flip ? 0x04 : 0);
    p->in_len += linkframe_encode(d, n, p->in + p->in_len, sizeof p->in - p->in_len);
}

/* the answer the plant would decode from the controller's output */
static int plant_gets(pipe_io *p, uint32_t id, link_packet *a)
{
    static linkframe_rx rx;
    feed_out o;
    linkframe_rx_init(&rx);
    feed(&rx, p->out, p->out_len, &o);
    p->out_len = 0;
    const link_expect x = {.type = LINK_TYPE_IMPORTS, .name = "pi_link", .id = id, .n = 1,
                           .check_run = 1, .run = 0x0123456789abcdefull};
    return o.n == 1 && o.verdict[0] == LINKFRAME_DATAGRAM &&
           link_decode(o.d, o.len, &x, a) == LINK_OK;
}

static void test_client(void)
{
    static const char *const layout[] = {"pi_link", "Ctrl", "Ref", "y", "Plant", "y", ">", "c"};
    static pipe_io p;
    static linkclient c;
    const linkclient_io io = {p_read, p_write, &p};
    uint32_t id = linkclient_layout_id(layout, 8);
    link_packet a;
    double integral = 0;
    TH_CHECK(linkclient_init(&c, "pi_link", id, 2, 1, &io) == 0);
    TH_CHECK(linkclient_poll(&c) == 0);
    TH_CHECK(linkclient_answer(&c, &integral) == -1); /* nothing to answer */
    /* a request: handed over once, answered with its seq and tick */
    plant_sends(&p, id, 1, 0, 1.0, 0.25, 0);
    TH_CHECK(linkclient_poll(&c) == 1 && c.req.v[0] == 1.0 && c.req.v[1] == 0.25 && c.new_run);
    double u = 0.5;
    TH_CHECK(linkclient_answer(&c, &u) == 0 && linkclient_poll(&c) == 0);
    TH_CHECK(plant_gets(&p, id, &a) && a.seq == 1 && a.tick == 0 && a.v[0] == 0.5);
    /* the same request again (its answer was lost): the same answer, not handed over */
    plant_sends(&p, id, 1, 0, 1.0, 0.25, 0);
    TH_CHECK(linkclient_poll(&c) == 0 && c.repeats == 1 && c.requests == 1);
    TH_CHECK(plant_gets(&p, id, &a) && a.seq == 1 && a.v[0] == 0.5);
    /* a bad CRC and another scene's request: counted, dropped; then the next request */
    plant_sends(&p, id, 2, 10, 1.0, 0.5, 1);
    plant_sends(&p, id ^ 1, 2, 10, 1.0, 0.5, 0);
    plant_sends(&p, id, 2, 10, 1.0, 0.5, 0);
    TH_CHECK(linkclient_poll(&c) == 1 && c.req.seq == 2 && c.req.tick == 10 && !c.new_run);
    TH_CHECK(c.bad[LINK_E_SCENE] == 1 && c.bad[LINK_E_CRC] == 1 && linkclient_faults(&c) == 2);
    /* a value that is not finite is not sent */
    u = 0.0 / 0.0;
    TH_CHECK(linkclient_answer(&c, &u) == -1 && p.out_len == 0 && c.pending);
    u = 0.75;
    TH_CHECK(linkclient_answer(&c, &u) == 0 && plant_gets(&p, id, &a) && a.seq == 2);
    TH_CHECK(c.requests == 2 && c.repeats == 1);
    /* a new run of the plant (another nonce): handed over as the first of a run */
    plant_sends(&p, id, 101, 0, 1.0, 0.5, 0);
    TH_CHECK(linkclient_poll(&c) == 1 && c.new_run && c.req.run == 0x0123456789abcdf0ull);
}

const th_test th_linkframe_tests[] = {
    {"linkframe_cobs_vectors", test_cobs_vectors},
    {"linkframe_round_trip", test_frame_round_trip},
    {"linkframe_resync", test_frame_resync},
    {"linkclient", test_client},
    {0, 0},
};
