/* link.c - the POSIX controller link (docs/link.md): a connected UDP socket (IPv4 or IPv6)
 * to the controller, a receiver thread that decodes and sorts every datagram into a
 * one-slot mailbox or a counter, and the exchange the runner calls at every tick:
 *   lock-step (simulated clock): at each exchange tick send the exports and wait (at most
 *     the timeout) for the answer to this very packet, then apply it at this tick;
 *     deterministic, for CI;
 *   soft real time (--realtime): never wait. An answer is applied at the first tick after
 *     it arrived; an exchange tick whose previous packet got no answer counts it missing
 *     and applies each import's policy (hold, default, stop).
 * Every applied vector goes to the replay log with its tick (mrlog.c), so a replay
 * reproduces the live run bit for bit whatever the network did. The transport is UDP, or
 * a serial line carrying the same datagrams in frames (serial.c, `serial:DEV:BAUD`). */
#define _POSIX_C_SOURCE 200809L
#include "link.h"

#include <errno.h>
#include <netdb.h>
#include <pthread.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <time.h>
#include <unistd.h>

#include "common/link_wire.h"
#include "mrlog.h"
#include "serial.h"

#define LINK_RECV_POLL_MS 50   /* the receiver thread checks for shutdown this often */
#define LINK_RTT_FINE 4096     /* round-trip histogram: 1 us bins up to 4.096 ms, */
#define LINK_RTT_STEP 64       /* then 64 us bins (a serial line's 10 ms round trips) */
#define LINK_RTT_BINS (LINK_RTT_FINE + 4096) /* up to 266 ms, then one */
#define LINK_TRIES 10          /* lock-step on a serial line: a request is sent again every
                                  timeout / TRIES (UDP: once; docs/link.md, "Lost frames") */
#define LINK_SEND_WAIT_MS 100  /* serial: the longest wait for the device to take a frame */

static struct {
    int fd, realtime;
    int serial;                /* the transport: 0 UDP, 1 a serial line (serial.c) */
    double timeout_s;
    const rt_scene *sc;
    mrl_writer *rec;
    pthread_t thread;
    int running;
    pthread_mutex_t mu;
    pthread_cond_t cv;
    /* under mu */
    uint32_t waiting;          /* seq of the packet whose answer is awaited (0: none) */
    uint32_t answered;         /* last seq answered (applied or in the mailbox) */
    int full;                  /* the mailbox holds the answer to `waiting` */
    link_packet box;
    link_counts n;
    struct timespec sent_at;   /* when `waiting` was sent */
    uint32_t rtt_hist[LINK_RTT_BINS + 1];
    double rtt_max;            /* [us] */
    /* main thread only */
    uint32_t seq;
    uint8_t out[LINK_MAX_PACKET]; /* the last request, for sending it again */
    size_t out_len;
    real_t cur[LINK_MAX_VALUES];
} L;

static double since_us(const struct timespec *t0)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return 1e6 * (double)(t.tv_sec - t0->tv_sec) + 1e-3 * (double)(t.tv_nsec - t0->tv_nsec);
}

static int rtt_bin(double us)
{
    if (us < LINK_RTT_FINE)
        return (int)us;
    double k = LINK_RTT_FINE + (us - LINK_RTT_FINE) / LINK_RTT_STEP;
    return k < LINK_RTT_BINS ? (int)k : LINK_RTT_BINS;
}

/* the middle of bin i [us] */
static double rtt_mid(int i)
{
    return i < LINK_RTT_FINE ? i + 0.5 : LINK_RTT_FINE + (i - LINK_RTT_FINE + 0.5) * LINK_RTT_STEP;
}

/* the receiver: every datagram is either the awaited answer, or counted */
static void receive(const uint8_t *buf, size_t len)
{
    link_packet p;
    const rt_link *lk = L.sc->link;
    link_wire_error e = link_decode(buf, len, LINK_TYPE_IMPORTS, L.sc->name, lk->id, lk->nimp, &p);
    pthread_mutex_lock(&L.mu);
    if (e != LINK_OK) {
        L.n.bad++, L.n.bad_kind[e]++;
    } else if (p.seq == L.answered || (p.seq == L.waiting && L.full)) {
        L.n.dup++;
    } else if (p.seq != L.waiting || p.seq == 0) {
        if (p.seq < L.waiting) /* an answer to a packet given up on */
            L.n.late++;
        else
            L.n.bad++, L.n.bad_kind[LINK_E_SEQ]++; /* a packet never sent */
    } else {
        L.box = p, L.full = 1;
        double us = since_us(&L.sent_at); /* the round trip, whenever it is applied */
        L.rtt_hist[rtt_bin(us)]++;
        L.rtt_max = us > L.rtt_max ? us : L.rtt_max;
        pthread_cond_signal(&L.cv);
    }
    pthread_mutex_unlock(&L.mu);
}

static void broken_frame(void)
{
    pthread_mutex_lock(&L.mu);
    L.n.bad++, L.n.bad_kind[LINK_E_FRAME]++;
    pthread_mutex_unlock(&L.mu);
}

static void *receiver(void *arg)
{
    static uint8_t buf[LINK_MAX_PACKET + 1]; /* one byte more: an oversized datagram shows */
    (void)arg;
    while (__atomic_load_n(&L.running, __ATOMIC_ACQUIRE)) {
        int fault = 0;
        ssize_t r = L.serial ? serial_recv(L.fd, buf, sizeof buf, LINK_RECV_POLL_MS, &fault)
                             : recv(L.fd, buf, sizeof buf, 0);
        if (r >= 0)
            receive(buf, (size_t)r);
        else if (r == -2) /* a broken frame: counted like a bad datagram */
            broken_frame();
        else if (errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR &&
                 errno != ECONNREFUSED)
            break;
    }
    return NULL;
}

static int parse_spec(const char *spec, char *host, size_t nh, char *port, size_t np)
{
    if (strncmp(spec, "udp:", 4) != 0)
        return -1;
    const char *h = spec + 4, *colon = strrchr(h, ':');
    if (!colon || colon == h || !colon[1])
        return -1;
    size_t hl = (size_t)(colon - h);
    if (h[0] == '[' && hl >= 2 && h[hl - 1] == ']') /* [::1]:port */
        h++, hl -= 2;
    if (hl >= nh || strlen(colon + 1) >= np)
        return -1;
    memcpy(host, h, hl), host[hl] = 0;
    strcpy(port, colon + 1);
    return 0;
}

/* a connected UDP socket with a receive timeout (the receiver checks for shutdown) */
static int open_udp(const char *spec, char *err, size_t n)
{
    char host[256], port[32];
    struct addrinfo hints = {.ai_socktype = SOCK_DGRAM}, *ai = NULL;
    if (parse_spec(spec, host, sizeof host, port, sizeof port) != 0) {
        snprintf(err, n, "--link expects udp:HOST:PORT, serial:DEVICE[:BAUD] or none, got '%s'",
                 spec);
        return -1;
    }
    int g = getaddrinfo(host, port, &hints, &ai);
    if (g != 0) {
        snprintf(err, n, "--link %s: %s", spec, gai_strerror(g));
        return -1;
    }
    L.fd = socket(ai->ai_family, SOCK_DGRAM, 0);
    if (L.fd < 0 || connect(L.fd, ai->ai_addr, ai->ai_addrlen) != 0) {
        snprintf(err, n, "--link %s: %s", spec, strerror(errno));
        freeaddrinfo(ai);
        return -1;
    }
    freeaddrinfo(ai);
    struct timeval tv = {0, LINK_RECV_POLL_MS * 1000};
    setsockopt(L.fd, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);
    return 0;
}

/* a serial line (the receiver polls it) */
static int open_serial(const char *spec, char *err, size_t n)
{
    char peer[64], why[400];
    L.fd = serial_open(spec, peer, sizeof peer, why, sizeof why);
    if (L.fd < 0)
        snprintf(err, n, "--link %s", why);
    return L.fd < 0 ? -1 : 0;
}

int link_open(const char *spec, const rt_scene *sc, int realtime, double timeout_s,
              mrl_writer *rec, char *err, size_t n)
{
    if (!sc->link) {
        snprintf(err, n, "scene %s has no link (export/import statements)", sc->name);
        return -1;
    }
    if (sc->link->nexp > LINK_MAX_VALUES || sc->link->nimp > LINK_MAX_VALUES) {
        snprintf(err, n, "the link carries more than %d values one way", LINK_MAX_VALUES);
        return -1;
    }
    L.serial = strncmp(spec, SERIAL_PREFIX, strlen(SERIAL_PREFIX)) == 0;
    if ((L.serial ? open_serial : open_udp)(spec, err, n) != 0)
        return -1;
    L.sc = sc, L.realtime = realtime, L.timeout_s = timeout_s, L.rec = rec;
    L.seq = 0, L.waiting = L.answered = 0, L.full = 0;
    memset(&L.n, 0, sizeof L.n);
    memset(L.rtt_hist, 0, sizeof L.rtt_hist);
    L.rtt_max = 0;
    for (uint16_t i = 0; i < sc->link->nimp; i++)
        L.cur[i] = sc->link->def[i];
    pthread_mutex_init(&L.mu, NULL);
    pthread_condattr_t ca;
    pthread_condattr_init(&ca);
    pthread_condattr_setclock(&ca, CLOCK_MONOTONIC);
    pthread_cond_init(&L.cv, &ca);
    L.running = 1;
    if (pthread_create(&L.thread, NULL, receiver, NULL) != 0) {
        snprintf(err, n, "--link: cannot start the receiver thread");
        close(L.fd);
        return -1;
    }
    return 0;
}

/* one datagram on the transport; 1 if it went out whole */
static int transmit(const uint8_t *buf, size_t len)
{
    /* real time never waits for the device: a frame it cannot take is not sent whole
       (not counted as sent; the next frame's opening zero resynchronises the receiver) */
    if (L.serial)
        return serial_send(L.fd, buf, len, L.realtime ? 0 : LINK_SEND_WAIT_MS) == (ssize_t)len;
    return send(L.fd, buf, len, 0) == (ssize_t)len;
}

static void send_exports(const rt_scene *sc, const rt_sim *sim)
{
    link_packet p = {.type = LINK_TYPE_EXPORTS, .n = sc->link->nexp, .id = sc->link->id,
                     .seq = ++L.seq, .tick = sim->state.tick};
    uint8_t buf[LINK_MAX_PACKET];
    strncpy(p.name, sc->name, LINK_NAME_LEN);
    for (uint16_t i = 0; i < p.n; i++)
        p.v[i] = (double)rt_link_export(sc, sim, i);
    size_t len = link_encode(&p, buf, sizeof buf);
    pthread_mutex_lock(&L.mu);
    L.waiting = p.seq, L.full = 0;
    clock_gettime(CLOCK_MONOTONIC, &L.sent_at);
    pthread_mutex_unlock(&L.mu);
    memcpy(L.out, buf, len), L.out_len = len;
    if (transmit(L.out, L.out_len))
        L.n.sent++;
}

static void apply(const rt_scene *sc, rt_sim *sim)
{
    rt_link_apply(sc, sim, L.cur);
    if (L.rec)
        mrl_append(L.rec, sim->state.tick, L.cur);
}

/* takes the answer from the mailbox (under mu): 1 if there was one */
static int take(void)
{
    if (!L.full)
        return 0;
    for (uint16_t i = 0; i < L.box.n; i++)
        L.cur[i] = (real_t)L.box.v[i];
    L.answered = L.waiting, L.full = 0, L.waiting = 0;
    L.n.applied++;
    return 1;
}

/* no answer in time: each import's policy; 1 if one of them stops the run */
static int missing(const rt_scene *sc)
{
    int stop = 0;
    L.n.missing++;
    for (uint16_t i = 0; i < sc->link->nimp; i++) {
        if (sc->link->policy[i] == RT_LINK_DEFAULT)
            L.cur[i] = sc->link->def[i];
        stop |= sc->link->policy[i] == RT_LINK_STOP;
    }
    return stop;
}

static void add_s(struct timespec *t, double s)
{
    t->tv_sec += (time_t)s;
    t->tv_nsec += (long)((s - (double)(time_t)s) * 1e9);
    if (t->tv_nsec >= 1000000000L)
        t->tv_sec++, t->tv_nsec -= 1000000000L;
}

/* waits for the answer; on a serial line it sends the request again every timeout /
   LINK_TRIES (a frame lost to line noise; the controller answers a repeat from its copy,
   docs/link.md "Lost frames"). Over UDP the request goes once: a UDP controller need not
   recognise a repeat (the Python example does not, and would step its integrator twice). */
static int lockstep(const rt_scene *sc, rt_sim *sim)
{
    struct timespec until;
    int tries = L.serial ? LINK_TRIES : 1;
    clock_gettime(CLOCK_MONOTONIC, &until);
    send_exports(sc, sim);
    pthread_mutex_lock(&L.mu);
    for (int k = 1; k <= tries && !L.full; k++) {
        struct timespec try_until = until;
        add_s(&try_until, L.timeout_s * k / tries);
        while (!L.full && pthread_cond_timedwait(&L.cv, &L.mu, &try_until) != ETIMEDOUT)
            ;
        if (!L.full && k < tries) {
            pthread_mutex_unlock(&L.mu); /* the receiver may deliver meanwhile */
            L.n.resent += (uint64_t)transmit(L.out, L.out_len);
            pthread_mutex_lock(&L.mu);
        }
    }
    int got = take(), stop = 0;
    if (!got)
        L.waiting = 0; /* a later answer to it is late */
    pthread_mutex_unlock(&L.mu);
    if (!got)
        stop = missing(sc);
    apply(sc, sim);
    return stop;
}

/* soft real time: never blocks (trylock; a busy mailbox is looked at next tick) */
static int realtime(const rt_scene *sc, rt_sim *sim)
{
    int got = 0, stop = 0, due = rt_link_due(sc, sim);
    if (pthread_mutex_trylock(&L.mu) == 0) {
        got = take();
        if (due && !got && L.waiting != 0)
            L.waiting = 0, stop = -1; /* the previous packet went unanswered */
        pthread_mutex_unlock(&L.mu);
    }
    if (stop < 0)
        stop = missing(sc), got = 1;
    if (got)
        apply(sc, sim);
    if (due && !stop)
        send_exports(sc, sim);
    return stop;
}

int link_exchange(void *ctx, const rt_scene *sc, rt_sim *sim)
{
    (void)ctx;
    if (L.realtime)
        return realtime(sc, sim);
    return rt_link_due(sc, sim) ? lockstep(sc, sim) : 0;
}

static double percentile(double q)
{
    uint64_t total = 0, acc = 0;
    for (int i = 0; i <= LINK_RTT_BINS; i++)
        total += L.rtt_hist[i];
    for (int i = 0; i <= LINK_RTT_BINS && total; i++)
        if ((acc += L.rtt_hist[i]) >= (uint64_t)(q * (double)total + 0.5))
            return rtt_mid(i);
    return 0;
}

void link_close(link_counts *out)
{
    __atomic_store_n(&L.running, 0, __ATOMIC_RELEASE);
    pthread_join(L.thread, NULL);
    close(L.fd);
    L.n.rtt_us[0] = percentile(0.5), L.n.rtt_us[1] = percentile(0.99);
    L.n.rtt_us[2] = L.rtt_max;
    *out = L.n;
}

void link_print(FILE *f, const link_counts *c)
{
    fprintf(f, "link_sent: %llu\nlink_applied: %llu\nlink_bad: %llu\nlink_late: %llu\n"
               "link_missing: %llu\nlink_dup: %llu\n",
            (unsigned long long)c->sent, (unsigned long long)c->applied,
            (unsigned long long)c->bad, (unsigned long long)c->late,
            (unsigned long long)c->missing, (unsigned long long)c->dup);
    if (c->resent)
        fprintf(f, "link_resent: %llu\n", (unsigned long long)c->resent);
    for (int e = 1; e < LINK_E_COUNT_; e++)
        if (c->bad_kind[e])
            fprintf(f, "link_bad.%s: %llu\n", link_wire_error_key(e),
                    (unsigned long long)c->bad_kind[e]);
    if (c->applied)
        fprintf(f, "link_rtt_us: p50 %.1f p99 %.1f max %.1f\n", c->rtt_us[0], c->rtt_us[1],
                c->rtt_us[2]);
}
