/* pi_controller.c - the PI controller of scene pi_link in C, outside the plant, over the
 * modrt controller link (docs/link.md, wire format version 2), with the freestanding codec
 * of ports/common/link_wire.c. Binds 127.0.0.1:PORT (0: any, printed as "port N") and
 * serves one plant: the address and run nonce of the first valid request that starts a
 * run (sequence 1 at tick 0; the same address may start a new run); requests from any
 * other sender, of another run or not newer than the last answered are ignored and
 * counted. It answers
 * with models/pi.c's law in its order of arithmetic: e = r - m; c = Kp e + I; then
 * I = I + Ki Ts e. Exits after IDLE seconds without packets. With KEYFILE every datagram
 * carries an HMAC-SHA-256 tag under the shared key (modrt run --link-key KEYFILE).
 * Serial mode: the same over a terminal device (serial:DEVICE[:BAUD]) or a new pty
 * (serial:pty, its path printed as "pty PATH"), with the client library of
 * ports/common/linkclient.c that a firmware controller uses; one plant on the line, its
 * integrator reset when a new run starts, a repeated request answered from the copy.
 * Usage: pi_controller [PORT [IDLE_S [KEYFILE]]]
 *        pi_controller serial:DEVICE[:BAUD]|serial:pty [IDLE_S [KEYFILE]] */
#define _POSIX_C_SOURCE 200809L
#include <arpa/inet.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <unistd.h>

#include "common/link_wire.h"
#include "common/linkclient.h"
#include "serial.h"

#define KP 0.8
#define KI 3.0
#define TS 0.01

static int read_key(const char *path, link_key *key)
{
    uint8_t b[LINK_MAX_KEY + 2];
    FILE *f = fopen(path, "rb");
    if (!f)
        return -1;
    size_t n = fread(b, 1, sizeof b, f);
    fclose(f);
    if (n > 0 && b[n - 1] == '\n')
        n--;
    if (n < 1 || n > LINK_MAX_KEY)
        return -1;
    memcpy(key->k, b, n), key->len = n;
    return 0;
}

/* the plant served: its address and run */
typedef struct plant {
    int known;
    struct sockaddr_in addr;
    uint64_t run;
    uint32_t last;             /* the last sequence number answered */
    double integral;
} plant;

static int same_addr(const struct sockaddr_in *a, const struct sockaddr_in *b)
{
    return a->sin_addr.s_addr == b->sin_addr.s_addr && a->sin_port == b->sin_port;
}

/* 1 if the request is the served plant's next one (taking on a first or new run) */
static int accept_request(plant *p, const struct sockaddr_in *from, const link_packet *in)
{
    int same = p->known && same_addr(&p->addr, from);
    if (in->seq == 1 && in->tick == 0 && (!p->known || same) && in->run != p->run) {
        *p = (plant){.known = 1, .addr = *from, .run = in->run};
        same = 1;
    }
    if (!same || in->run != p->run || in->seq <= p->last)
        return 0;
    p->last = in->seq;
    return 1;
}

/* the PI law and the order of its arithmetic (bit for bit models/pi.c's in pi_loop) */
static double pi_step(double *integral, double r, double m)
{
    double e = r - m;
    double c = KP * e + *integral;
    *integral = *integral + KI * TS * e;
    return c;
}

/* serial mode: the byte stream of the client library is a terminal device */
typedef struct tty {
    int fd;
    uint8_t buf[512];
    size_t len, pos;
} tty;

static int tty_read(void *ctx)
{
    tty *t = ctx;
    if (t->pos == t->len) {
        ssize_t k = read(t->fd, t->buf, sizeof t->buf);
        if (k <= 0)
            return -1;
        t->len = (size_t)k, t->pos = 0;
    }
    return t->buf[t->pos++];
}

static void tty_write(void *ctx, const uint8_t *b, size_t n)
{
    tty *t = ctx;
    while (n > 0) {
        ssize_t k = write(t->fd, b, n);
        if (k > 0) {
            b += k, n -= (size_t)k;
        } else {
            struct pollfd p = {.fd = t->fd, .events = POLLOUT};
            if (poll(&p, 1, 1000) <= 0)
                return; /* the line is stuck: the plant counts the answer missing */
        }
    }
}

static int serial_main(const char *spec, int idle_s, uint32_t id, const link_key *key)
{
    static tty t;
    static linkclient c;
    char peer[64], err[512];
    const linkclient_io io = {tty_read, tty_write, &t};
    t.fd = serial_open(spec, peer, sizeof peer, err, sizeof err);
    if (t.fd < 0 || linkclient_init(&c, "pi_link", id, 2, 1, &io) != 0) {
        fprintf(stderr, "pi_controller: %s\n", err);
        return 1;
    }
    c.key = key->len ? key : NULL;
    if (strcmp(spec, "serial:pty") == 0)
        printf("pty %s\n", peer);
    fflush(stdout);
    double integral = 0;
    struct pollfd p = {.fd = t.fd, .events = POLLIN};
    while (poll(&p, 1, idle_s * 1000) > 0) {
        if (linkclient_poll(&c)) {
            if (c.new_run)
                integral = 0;
            double u = pi_step(&integral, c.req.v[0], c.req.v[1]);
            linkclient_answer(&c, &u);
        }
        if (p.revents & (POLLHUP | POLLERR))
            break; /* the other end is gone (a pty whose master closed) */
    }
    printf("answered %lu repeats %lu refused %lu (frame", (unsigned long)c.requests,
           (unsigned long)c.repeats, (unsigned long)linkclient_faults(&c));
    for (int v = LINKFRAME_E_LONG; v < LINKFRAME_E_COUNT_; v++)
        printf(" %s %lu", linkframe_fault_key(v), (unsigned long)c.rx.fault[v]);
    printf(", datagram");
    for (int e = 1; e < LINK_E_COUNT_; e++)
        printf(" %s %lu", link_wire_error_key(e), (unsigned long)c.bad[e]);
    printf(")\n");
    return 0;
}

int main(int argc, char **argv)
{
    static const char *const layout[] = {"pi_link", "Ctrl", "Ref", "y", "Plant", "y", ">", "c"};
    static link_key key;
    struct sockaddr_in me = {.sin_family = AF_INET, .sin_port = htons(argc > 1 ? atoi(argv[1]) : 0)};
    struct timeval idle = {argc > 2 ? atoi(argv[2]) : 5, 0};
    if (argc > 3 && read_key(argv[3], &key) != 0) {
      fprintf(stderr, "pi_controller: %s: cannot read a key of 1 to %d bytes\n",
              argv[3], LINK_MAX_KEY);
      return 1;
    }
    link_expect want = {.type = LINK_TYPE_EXPORTS,
                        .name = "pi_link",
                        .id = linkclient_layout_id(layout, 8),
                        .n = 2,
                        .key = &key};
    if (argc > 1 && strncmp(argv[1], SERIAL_PREFIX, strlen(SERIAL_PREFIX)) == 0)
      return serial_main(argv[1], argc > 2 ? atoi(argv[2]) : 5, want.id, &key);
    int fd = socket(AF_INET, SOCK_DGRAM, 0);
    me.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    socklen_t len = sizeof me;
    if (fd < 0 || bind(fd, (struct sockaddr *)&me, sizeof me) != 0 ||
        getsockname(fd, (struct sockaddr *)&me, &len) != 0) {
        perror("pi_controller");
        return 1;
    }
    setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &idle, sizeof idle);
    printf("port %d\n", ntohs(me.sin_port));
    fflush(stdout);
    plant pl = {0};
    unsigned long answered = 0, refused = 0, ignored = 0;
    for (;;) {
        uint8_t buf[LINK_MAX_PACKET + 1];
        struct sockaddr_in peer;
        socklen_t plen = sizeof peer;
        ssize_t n = recvfrom(fd, buf, sizeof buf, 0, (struct sockaddr *)&peer, &plen);
        if (n < 0)
            break; /* idle */
        link_packet in, out = {.type = LINK_TYPE_IMPORTS, .n = 1, .id = want.id};
        if (link_decode(buf, (size_t)n, &want, &in) != LINK_OK) {
            refused++;
            continue;
        }
        if (plen != sizeof peer || !accept_request(&pl, &peer, &in)) {
            ignored++;
            continue;
        }
        out.v[0] = pi_step(&pl.integral, in.v[0], in.v[1]);
        strcpy(out.name, "pi_link");
        out.seq = in.seq, out.tick = in.tick, out.run = in.run;
        size_t m = link_encode(&out, &key, buf, sizeof buf);
        sendto(fd, buf, m, 0, (struct sockaddr *)&pl.addr, sizeof pl.addr);
        answered++;
    }
    printf("answered %lu refused %lu ignored %lu\n", answered, refused, ignored);
    return 0;
}
