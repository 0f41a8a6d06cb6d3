/* link.c - the POSIX controller link (docs/link.md): a transport to the controller (UDP,
 * link_udp.c, or a serial line, link_serial.c), a receiver thread that checks every datagram against the request it claims
 * to answer and sorts it into a one-slot mailbox or a counter, and the exchange the
 * runner calls at every tick:
 *   lock-step (simulated clock): at each exchange tick send the exports and wait (at most
 *     the timeout) for the answer to this very request, then apply it at this tick;
 *     deterministic, for CI;
 *   soft real time (--realtime): never wait. An answer is applied at the first tick after
 *     it arrived; an exchange tick whose previous request got no answer, or that cannot
 *     take the mailbox, counts it missing and applies each import's policy.
 * An answer is taken only if it repeats its request's sequence number, tick and this
 * run's nonce (and carries a valid tag in the authenticated mode). Every applied vector
 * goes to the replay log with its tick (mrlog.c), so a replay reproduces the live run bit
 * for bit whatever the network did. */
#define _POSIX_C_SOURCE 200809L
#include "link.h"

#include <errno.h>
#include <fcntl.h>
#include <pthread.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "mrlog.h"

#define LINK_RECV_POLL_MS 50   /* the receiver thread checks for shutdown this often */
#define LINK_RTT_FINE 4096     /* round-trip histogram: 1 us bins up to 4.096 ms, */
#define LINK_RTT_STEP 64       /* then 64 us bins (a serial line's 10 ms round trips) */
#define LINK_RTT_BINS (LINK_RTT_FINE + 4096) /* up to 266 ms, then one */
#define LINK_WINDOW 64         /* requests remembered (tick, answered) for the checks */
#define LINK_TRIES 10          /* lock-step over a transport that resends: every timeout/10 */

static const link_transport *const transports[] = {&link_udp, &link_serial, NULL};

/* what the plant remembers of a request it sent */
typedef struct sent_req {
    uint32_t seq;
    uint64_t tick;
    int answered;              /* an answer was boxed or applied (a further one is dup) */
} sent_req;

static struct {
    const link_transport *tr;
    link_opts o;
    const rt_scene *sc;
    mrl_writer *rec;
    pthread_t thread;
    int running, test_busy;
    pthread_mutex_t mu;
    pthread_cond_t cv;
    /* under mu */
    uint32_t last;             /* the newest seq sent */
    uint32_t waiting;          /* seq of the request whose answer is awaited (0: none) */
    int full;                  /* the mailbox holds the answer to `waiting` */
    link_packet box;
    sent_req win[LINK_WINDOW]; /* by seq % LINK_WINDOW */
    link_counts n;
    struct timespec sent_at;   /* when `waiting` was sent */
    uint32_t rtt_hist[LINK_RTT_BINS + 1];
    double rtt_max;            /* [us] */
    /* main thread only */
    uint32_t outstanding;      /* the request sent and neither answered nor given up */
    real_t cur[LINK_MAX_VALUES];
    uint8_t out[LINK_MAX_PACKET]; /* the last request as sent, for sending it again */
    size_t out_len;
} L;

static double since_us(const struct timespec *t0)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return 1e6 * (double)(t.tv_sec - t0->tv_sec) + 1e-3 * (double)(t.tv_nsec - t0->tv_nsec);
}

static void count_bad(link_wire_error e)
{
    L.n.bad++, L.n.bad_kind[e]++;
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
    return i < LINK_RTT_FINE ? i + 0.5
                             : LINK_RTT_FINE + (i - LINK_RTT_FINE + 0.5) * LINK_RTT_STEP;
}

/* a checked answer against the request it names (under mu): boxed, or counted */
static void sort(const link_packet *p)
{
    sent_req *r = &L.win[p->seq % LINK_WINDOW];
    int known = r->seq == p->seq && p->seq != 0;
    if (p->seq == 0 || p->seq > L.last)
        count_bad(LINK_E_SEQ);             /* a request never sent */
    else if (known && p->tick != r->tick)
        count_bad(LINK_E_TICK);            /* not its request's tick */
    else if (known && r->answered)
        L.n.dup++;                         /* a second answer */
    else if (p->seq != L.waiting)
        L.n.late++;                        /* after its deadline: given up on */
    else {
        L.box = *p, L.full = 1, r->answered = 1;
        double us = since_us(&L.sent_at); /* the round trip, whenever it is applied */
        L.rtt_hist[rtt_bin(us)]++;
        L.rtt_max = us > L.rtt_max ? us : L.rtt_max;
        pthread_cond_signal(&L.cv);
    }
}

/* the receiver: every datagram is either the awaited answer, or counted */
static void receive(const uint8_t *buf, size_t len)
{
    link_packet p;
    const rt_link *lk = L.sc->link;
    link_expect x = {.type = LINK_TYPE_IMPORTS, .name = L.sc->name, .id = lk->id,
                     .n = lk->nimp, .check_run = 1, .run = L.o.run, .key = L.o.key};
    link_wire_error e = link_decode(buf, len, &x, &p);
    pthread_mutex_lock(&L.mu);
    if (e != LINK_OK)
        count_bad(e);
    else
        sort(&p);
    pthread_mutex_unlock(&L.mu);
}

static void *receiver(void *arg)
{
    static uint8_t buf[LINK_MAX_PACKET + 1]; /* one byte more: an oversized datagram shows */
    (void)arg;
    while (__atomic_load_n(&L.running, __ATOMIC_ACQUIRE)) {
        long r = L.tr->recv(buf, sizeof buf, LINK_RECV_POLL_MS);
        if (r > 0) {
            receive(buf, (size_t)r);
        } else if (r == LINK_RECV_BROKEN) {
            pthread_mutex_lock(&L.mu);
            count_bad(LINK_E_FRAME);
            pthread_mutex_unlock(&L.mu);
        } else if (r < 0) {
            break;
        }
    }
    return NULL;
}

static const link_transport *transport_of(const char *spec)
{
    for (int i = 0; transports[i]; i++)
        if (strncmp(spec, transports[i]->prefix, strlen(transports[i]->prefix)) == 0)
            return transports[i];
    return NULL;
}

int link_spec_check(const char *spec, char *err, size_t n)
{
    if (strcmp(spec, "none") == 0)
        return 0;
    const link_transport *t = transport_of(spec);
    if (!t) {
        int k = snprintf(err, n, "--link expects");
        for (int i = 0; transports[i] && k >= 0 && (size_t)k < n; i++)
            k += snprintf(err + k, n - (size_t)k, " %s or", transports[i]->usage);
        if (k >= 0 && (size_t)k < n)
            snprintf(err + k, n - (size_t)k, " none, got '%s'", spec);
        return -1;
    }
    return t->check(spec, err, n);
}

uint64_t link_nonce(void)
{
    uint64_t v = 0;
    int fd = open("/dev/urandom", O_RDONLY);
    if (fd >= 0) {
        if (read(fd, &v, sizeof v) != (ssize_t)sizeof v)
            v = 0;
        close(fd);
    }
    if (v == 0) { /* no entropy device: the clock and the process, still once per run */
        struct timespec t;
        clock_gettime(CLOCK_REALTIME, &t);
        v = ((uint64_t)t.tv_sec * 1000000007u) ^ (uint64_t)t.tv_nsec ^
            ((uint64_t)getpid() << 40);
    }
    return v ? v : 1;
}

int link_key_read(const char *path, link_key *key, char *err, size_t n)
{
    uint8_t b[LINK_MAX_KEY + 2];
    FILE *f = fopen(path, "rb");
    if (!f) {
        snprintf(err, n, "--link-key %s: %s", path, strerror(errno));
        return -1;
    }
    size_t got = fread(b, 1, sizeof b, f);
    fclose(f);
    if (got > 0 && b[got - 1] == '\n')
        got--;
    if (got == 0 || got > LINK_MAX_KEY) {
        snprintf(err, n, "--link-key %s: the key must be 1 to %d bytes", path, LINK_MAX_KEY);
        return -1;
    }
    memcpy(key->k, b, got), key->len = got;
    return 0;
}

int link_open(const char *spec, const rt_scene *sc, const link_opts *o, mrl_writer *rec,
              char *err, size_t n)
{
    if (!sc->link) {
        snprintf(err, n, "scene %s has no link (export/import statements)", sc->name);
        return -1;
    }
    if (sc->link->nexp > LINK_MAX_VALUES || sc->link->nimp > LINK_MAX_VALUES) {
        snprintf(err, n, "the link carries more than %d values one way", LINK_MAX_VALUES);
        return -1;
    }
    if (link_spec_check(spec, err, n) != 0)
        return -1;
    memset(&L, 0, sizeof L);
    L.tr = transport_of(spec);
    if (L.tr->open(spec, err, n) != 0)
        return -1;
    L.sc = sc, L.o = *o, L.rec = rec;
    for (uint16_t i = 0; i < sc->link->nimp; i++)
        L.cur[i] = sc->link->def[i];
    /* priority inheritance: the real-time tick never waits behind a preempted receiver */
    pthread_mutexattr_t ma;
    pthread_mutexattr_init(&ma);
    pthread_mutexattr_setprotocol(&ma, PTHREAD_PRIO_INHERIT);
    pthread_mutex_init(&L.mu, &ma);
    pthread_condattr_t ca;
    pthread_condattr_init(&ca);
    pthread_condattr_setclock(&ca, CLOCK_MONOTONIC);
    pthread_cond_init(&L.cv, &ca);
    L.running = 1;
    if (pthread_create(&L.thread, NULL, receiver, NULL) != 0) {
        snprintf(err, n, "--link: cannot start the receiver thread");
        L.tr->close();
        return -1;
    }
    return 0;
}

/* sends the exports as the next request; an answer still boxed for the previous one
   came after its deadline (the tick gave it up without reading it): late */
static void send_exports(const rt_scene *sc, const rt_sim *sim)
{
    link_packet p = {.type = LINK_TYPE_EXPORTS, .n = sc->link->nexp, .id = sc->link->id,
                     .tick = rt_ticks_done(sim), .run = L.o.run};
    uint8_t buf[LINK_MAX_PACKET];
    strncpy(p.name, sc->name, LINK_NAME_LEN);
    for (uint16_t i = 0; i < p.n; i++)
        p.v[i] = (double)rt_link_export(sc, sim, i);
    pthread_mutex_lock(&L.mu);
    p.seq = ++L.last;
    if (L.full)
        L.n.late++;
    L.win[p.seq % LINK_WINDOW] = (sent_req){.seq = p.seq, .tick = p.tick};
    L.waiting = p.seq, L.full = 0;
    clock_gettime(CLOCK_MONOTONIC, &L.sent_at);
    pthread_mutex_unlock(&L.mu);
    L.outstanding = p.seq;
    size_t len = link_encode(&p, L.o.key, buf, sizeof buf);
    memcpy(L.out, buf, len), L.out_len = len;
    if (len && L.tr->send(buf, len) == 0)
        L.n.sent++;
}

static void apply(const rt_scene *sc, rt_sim *sim)
{
    rt_link_apply(sc, sim, L.cur);
    if (L.rec)
        mrl_append(L.rec, rt_ticks_done(sim), L.cur);
}

/* takes the answer from the mailbox (under mu): 1 if there was one */
static int take(void)
{
    if (!L.full)
        return 0;
    for (uint16_t i = 0; i < L.box.n; i++)
        L.cur[i] = (real_t)L.box.v[i];
    L.full = 0, L.waiting = 0, L.outstanding = 0;
    L.n.applied++;
    return 1;
}

/* no answer in time: each import's policy; 1 if one of them stops the run. The caller
   has told the receiver (waiting = 0, or the next request) that a later answer is late. */
static int missing(const rt_scene *sc)
{
    int stop = 0;
    L.n.missing++, L.outstanding = 0;
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

/* waits for the answer; over a transport that resends (a serial line) the request goes
   again every timeout / LINK_TRIES: a frame lost to line noise costs a retry, not the
   exchange (docs/link.md, "Lost frames"); the controller answers a repeat from its copy */
static int lockstep(const rt_scene *sc, rt_sim *sim)
{
    struct timespec start;
    int tries = L.tr->resend ? LINK_TRIES : 1;
    clock_gettime(CLOCK_MONOTONIC, &start);
    send_exports(sc, sim);
    pthread_mutex_lock(&L.mu);
    for (int k = 1; k <= tries && !L.full; k++) {
        struct timespec until = start;
        add_s(&until, L.o.timeout_s * k / tries);
        while (!L.full && pthread_cond_timedwait(&L.cv, &L.mu, &until) != ETIMEDOUT)
            ;
        if (!L.full && k < tries) {
            pthread_mutex_unlock(&L.mu); /* the receiver may box the answer meanwhile */
            L.n.resent += (uint64_t)(L.tr->send(L.out, L.out_len) == 0);
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

/* soft real time: the mailbox is looked at with a trylock, never waited for. On an
   exchange tick the request still outstanding (unanswered, or its answer out of reach
   behind a busy mailbox) is missing; send_exports then retires it (a boxed answer is
   late) and sends the next. */
static int realtime(const rt_scene *sc, rt_sim *sim)
{
    int got = 0, stop = 0, due = rt_link_due(sc, sim);
    if (!L.test_busy && pthread_mutex_trylock(&L.mu) == 0) {
        got = take();
        if (due && !got)
            L.waiting = 0;
        pthread_mutex_unlock(&L.mu);
    }
    if (due && !got && L.outstanding != 0)
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
    if (L.o.realtime)
        return realtime(sc, sim);
    return rt_link_due(sc, sim) ? lockstep(sc, sim) : 0;
}

void link_test_busy(int busy)
{
    L.test_busy = busy;
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
    L.tr->close();
    L.n.rtt_us[0] = percentile(0.5), L.n.rtt_us[1] = percentile(0.99);
    L.n.rtt_us[2] = L.rtt_max;
    *out = L.n;
}

int link_faulty(const link_counts *c)
{
    return c->bad > 0 || c->missing > 0;
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
