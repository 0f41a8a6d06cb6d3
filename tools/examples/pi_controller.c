/* pi_controller.c - the PI controller of scene pi_link in C, outside the plant, over the
 * modrt controller link (docs/link.md), with the freestanding codec of
 * ports/common/link_wire.c. Binds 127.0.0.1:PORT (0: any, printed as "port N"), answers
 * every valid packet of pi_link with c = Kp e + I, I += Ki Ts e (models/pi.c's law), and
 * exits after IDLE seconds without packets. Serial mode: the same over a terminal device
 * (serial:DEVICE[:BAUD]) or a new pty (serial:pty, its path printed as "pty PATH"), with
 * the client library of ports/common/linkclient.c that a firmware controller uses.
 * Usage: pi_controller [PORT [IDLE_S]]
 *        pi_controller serial:DEVICE[:BAUD]|serial:pty [IDLE_S] */
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

/* FNV-1a over the scene's link layout (docs/link.md, "link id") */
static uint32_t link_id(const char *const *words, int n)
{
    uint32_t h = 2166136261u;
    for (int i = 0; i < n; i++) {
        for (const char *s = words[i]; *s; s++)
            h = (h ^ (uint8_t)*s) * 16777619u;
        h = (h ^ (uint8_t)'|') * 16777619u;
    }
    return h;
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

static int serial_main(const char *spec, int idle_s, uint32_t id)
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
    if (strcmp(spec, "serial:pty") == 0)
        printf("pty %s\n", peer);
    fflush(stdout);
    double integral = 0;
    struct pollfd p = {.fd = t.fd, .events = POLLIN};
    while (poll(&p, 1, idle_s * 1000) > 0) {
        if (linkclient_poll(&c)) {
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
    const uint32_t id = link_id(layout, 8);
    if (argc > 1 && strncmp(argv[1], SERIAL_PREFIX, strlen(SERIAL_PREFIX)) == 0)
        return serial_main(argv[1], argc > 2 ? atoi(argv[2]) : 5, id);
    struct sockaddr_in me = {.sin_family = AF_INET, .sin_port = htons(argc > 1 ? atoi(argv[1]) : 0)};
    struct timeval idle = {argc > 2 ? atoi(argv[2]) : 5, 0};
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
    double integral = 0;
    unsigned long answered = 0, refused = 0;
    for (;;) {
        uint8_t buf[LINK_MAX_PACKET + 1];
        struct sockaddr_storage peer;
        socklen_t plen = sizeof peer;
        ssize_t n = recvfrom(fd, buf, sizeof buf, 0, (struct sockaddr *)&peer, &plen);
        if (n < 0)
            break; /* idle */
        link_packet in, out = {.type = LINK_TYPE_IMPORTS, .n = 1, .id = id};
        if (link_decode(buf, (size_t)n, LINK_TYPE_EXPORTS, "pi_link", id, 2, &in) != LINK_OK) {
            refused++;
            continue;
        }
        out.v[0] = pi_step(&integral, in.v[0], in.v[1]);
        strcpy(out.name, "pi_link");
        out.seq = in.seq, out.tick = in.tick;
        size_t m = link_encode(&out, buf, sizeof buf);
        sendto(fd, buf, m, 0, (struct sockaddr *)&peer, plen);
        answered++;
    }
    printf("answered %lu refused %lu\n", answered, refused);
    return 0;
}
