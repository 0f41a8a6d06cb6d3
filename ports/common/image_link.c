/* image_link.c - the controller link of a per-scene image (image_link.h): the plant side
 * of docs/link.md on a board. At an exchange tick the exports go out as one datagram
 * (link_wire.c) in one frame (linkframe.c) on the port's link UART; the answer is taken
 * byte by byte from the UART's receive buffer (filled by its interrupt) through the same
 * checks as on POSIX: a datagram of another scene or layout, a bad CRC, a broken frame
 * are counted and never applied. Lock-step waits for the answer to this very request
 * (sending it again every timeout / IMAGE_LINK_TRIES, as `modrt run` does); real time
 * looks between ticks and applies an answer at the first tick after it arrived. The
 * import policies (hold, default, stop) apply to an exchange without an answer. An answer
 * must echo its request's sequence number, tick and this run's nonce (image_link_nonce).
 * Unauthenticated (no shared key on the board). */
#include "image_link.h"

#include "common/link_wire.h"
#include "common/linkframe.h"
#include "port.h"

#define IMAGE_LINK_TRIES 10 /* lock-step: a request is sent again every timeout / TRIES */

static struct {
    uint64_t run;                /* this run's nonce */
    uint64_t tick;               /* the tick of the request awaiting its answer */
    uint32_t id, seq, waiting;   /* waiting: the seq awaiting its answer (0: none) */
    uint32_t answered;           /* the last seq answered */
    real_t cur[LINK_MAX_VALUES]; /* the imports in force */
    uint8_t frame[LINKFRAME_MAX_WIRE];
    uint32_t frame_len;
    linkframe_rx rx;
    uint64_t sent, applied, bad, late, missing, dup, resent;
    link_packet pkt;             /* the request being built, or the answer being checked */
} K;

static void transmit(void)
{
    port_link_write(K.frame, K.frame_len);
}

static void send_exports(const rt_scene *sc, const rt_sim *sim)
{
    link_packet *p = &K.pkt;
    uint8_t d[LINK_MAX_PACKET];
    const char *name = sc->name;
    p->type = LINK_TYPE_EXPORTS, p->n = sc->link->nexp, p->id = sc->link->id;
    p->seq = ++K.seq, p->tick = rt_ticks_done(sim), p->run = K.run;
    for (int i = 0; i < LINK_NAME_LEN; i++) { /* the scene's name, padded with zeros */
        p->name[i] = *name;
        name += *name != 0;
    }
    for (uint16_t i = 0; i < p->n; i++)
        p->v[i] = (double)rt_link_export(sc, sim, i);
    K.frame_len = (uint32_t)linkframe_encode(d, link_encode(p, 0, d, sizeof d), K.frame,
                                             sizeof K.frame);
    K.waiting = p->seq, K.tick = p->tick;
    transmit();
    K.sent++;
}

/* a checked datagram: the awaited answer (1, its values in K.cur), or counted */
static int receive(const rt_scene *sc, const uint8_t *d, size_t len)
{
    link_packet *p = &K.pkt;
    const rt_link *lk = sc->link;
    const link_expect x = {.type = LINK_TYPE_IMPORTS, .name = sc->name, .id = lk->id,
                           .n = lk->nimp, .check_run = 1, .run = K.run};
    link_wire_error e = link_decode(d, len, &x, p);
    if (e != LINK_OK) {
        K.bad++;
        return 0;
    }
    if (p->seq == K.waiting && p->tick != K.tick) {
        K.bad++; /* not its request's tick */
        return 0;
    }
    if (p->seq == K.answered) {
        K.dup++;
        return 0;
    }
    if (p->seq == 0 || p->seq != K.waiting) {
        if (p->seq < K.seq)
            K.late++; /* an answer to a request given up on */
        else
            K.bad++;  /* to a request never sent */
        return 0;
    }
    for (uint16_t i = 0; i < p->n; i++)
        K.cur[i] = (real_t)p->v[i];
    K.answered = K.waiting, K.waiting = 0;
    K.applied++;
    return 1;
}

/* drains the UART's buffer: 1 when the awaited answer came (the rest stays buffered) */
static int poll_answer(const rt_scene *sc)
{
    int b;
    while ((b = port_link_getc()) >= 0) {
        const uint8_t *d;
        size_t len;
        linkframe_verdict v = linkframe_rx_byte(&K.rx, (uint8_t)b, &d, &len);
        if (v == LINKFRAME_DATAGRAM) {
            if (receive(sc, d, len))
                return 1;
        } else if (v != LINKFRAME_MORE) {
            K.bad++;
        }
    }
    return 0;
}

/* no answer in time: each import's policy; 1 if one of them stops the run */
static int missing(const rt_scene *sc)
{
    int stop = 0;
    K.missing++, K.waiting = 0;
    for (uint16_t i = 0; i < sc->link->nimp; i++) {
        if (sc->link->policy[i] == RT_LINK_DEFAULT)
            K.cur[i] = sc->link->def[i];
        stop |= sc->link->policy[i] == RT_LINK_STOP;
    }
    return stop;
}

static int lockstep(const rt_scene *sc, rt_sim *sim)
{
    const uint64_t try_ns = (uint64_t)RT_IMAGE_LINK_TIMEOUT_US * 1000u / IMAGE_LINK_TRIES;
    int got = 0, stop = 0;
    send_exports(sc, sim);
    for (int k = 1; k <= IMAGE_LINK_TRIES && !got; k++) {
        uint64_t t0 = port_cycles();
        while (!(got = poll_answer(sc)) && port_cycles() - t0 < try_ns)
            port_link_wait(); /* woken by the next byte or the next timer tick */
        if (!got && k < IMAGE_LINK_TRIES)
            transmit(), K.resent++;
    }
    if (!got)
        stop = missing(sc);
    rt_link_apply(sc, sim, K.cur);
    return stop;
}

static int realtime(const rt_scene *sc, rt_sim *sim)
{
    int got = poll_answer(sc), stop = 0;
    if (rt_link_due(sc, sim) && !got && K.waiting != 0)
        stop = missing(sc), got = 1;
    if (got)
        rt_link_apply(sc, sim, K.cur);
    if (rt_link_due(sc, sim) && !stop)
        send_exports(sc, sim);
    return stop;
}

int image_link_exchange(const rt_scene *sc, rt_sim *sim)
{
    if (!sc->link)
        return 0;
    if (RT_IMAGE_LINK_REALTIME)
        return realtime(sc, sim);
    return rt_link_due(sc, sim) ? lockstep(sc, sim) : 0;
}

/* a run nonce from the time since reset, mixed (splitmix64); a board with a random number
   generator overrides this weak definition with a true random number */
__attribute__((weak)) uint64_t image_link_nonce(void)
{
    uint64_t z = port_cycles() + 0x9E3779B97F4A7C15ull;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return z ? z : 1;
}

int image_link_start(const rt_scene *sc, rt_sim *sim)
{
    if (!sc->link || sc->link->nexp > LINK_MAX_VALUES || sc->link->nimp > LINK_MAX_VALUES ||
        port_link_open(RT_IMAGE_LINK_BAUD) != 0)
        return -1;
    linkframe_rx_init(&K.rx);
    K.run = image_link_nonce();
    for (uint16_t i = 0; i < sc->link->nimp; i++)
        K.cur[i] = sc->link->def[i];
    (void)sim;
    return 0;
}

int image_link_report(void (*put)(const char *key, uint64_t v))
{
    put("sent", K.sent), put("applied", K.applied), put("bad", K.bad), put("late", K.late);
    put("missing", K.missing), put("dup", K.dup), put("resent", K.resent);
    put("lost", port_link_lost());
    return K.bad > 0 || K.missing > 0 || port_link_lost() > 0;
}
