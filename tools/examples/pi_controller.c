/* pi_controller.c - the PI controller of scene pi_link in C, outside the plant, over the
 * modrt controller link (docs/link.md), with the freestanding codec of
 * ports/common/link_wire.c. Binds 127.0.0.1:PORT (0: any, printed as "port N"), answers
 * every valid packet of pi_link with c = Kp e + I, I += Ki Ts e (models/pi.c's law), and
 * exits after IDLE seconds without packets.
 * Usage: pi_controller [PORT [IDLE_S]] */
#define _POSIX_C_SOURCE 200809L
#include <arpa/inet.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/time.h>

#include "common/link_wire.h"

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

int main(int argc, char **argv)
{
    static const char *const layout[] = {"pi_link", "Ctrl", "Ref", "y", "Plant", "y", ">", "c"};
    const uint32_t id = link_id(layout, 8);
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
        double e = in.v[0] - in.v[1];
        out.v[0] = KP * e + integral;
        integral = integral + KI * TS * e;
        strcpy(out.name, "pi_link");
        out.seq = in.seq, out.tick = in.tick;
        size_t m = link_encode(&out, buf, sizeof buf);
        sendto(fd, buf, m, 0, (struct sockaddr *)&peer, plen);
        answered++;
    }
    printf("answered %lu refused %lu\n", answered, refused);
    return 0;
}
