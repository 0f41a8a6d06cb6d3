/* link_udp.c - the UDP transport of the controller link (link.h, docs/link.md): a socket
 * connected to the controller's address (IPv4, [IPv6] or a host name; the port a number
 * 1..65535 or a service name), so the kernel delivers only datagrams from that address
 * and port; anything another process sends to the plant's port is dropped unseen. */
#define _POSIX_C_SOURCE 200809L
#include "link.h"

#include <errno.h>
#include <netdb.h>
#include <poll.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <unistd.h>

#define UDP_MAX_PORT 65535

static int fd = -1;

/* udp:HOST:PORT into host and port; -1 with the reason */
static int split(const char *spec, char *host, size_t nh, char *port, size_t np, char *err,
                 size_t n)
{
    const char *h = spec + 4, *colon = strrchr(h, ':');
    if (strncmp(spec, "udp:", 4) != 0 || !colon || colon == h || !colon[1]) {
        snprintf(err, n, "--link expects udp:HOST:PORT, got '%s'", spec);
        return -1;
    }
    size_t hl = (size_t)(colon - h);
    if (h[0] == '[' && hl >= 2 && h[hl - 1] == ']') /* [::1]:port */
        h++, hl -= 2;
    if (hl >= nh || strlen(colon + 1) >= np) {
        snprintf(err, n, "--link %s: host or port too long", spec);
        return -1;
    }
    memcpy(host, h, hl), host[hl] = 0;
    strcpy(port, colon + 1);
    return 0;
}

/* a port is 1..65535 in decimal, or the name of a UDP service (/etc/services) */
static int port_ok(const char *port, const char *spec, char *err, size_t n)
{
    if (strspn(port, "0123456789") == strlen(port)) {
        char *end;
        errno = 0;
        unsigned long v = strtoul(port, &end, 10);
        if (errno == 0 && v >= 1 && v <= UDP_MAX_PORT)
            return 0;
        snprintf(err, n, "--link %s: port %s is not in 1..%d", spec, port, UDP_MAX_PORT);
        return -1;
    }
    if (getservbyname(port, "udp"))
        return 0;
    snprintf(err, n, "--link %s: '%s' is neither a port number (1..%d) nor a UDP service "
                     "name", spec, port, UDP_MAX_PORT);
    return -1;
}

static int udp_check(const char *spec, char *err, size_t n)
{
    char host[256], port[64];
    if (split(spec, host, sizeof host, port, sizeof port, err, n) != 0)
        return -1;
    return port_ok(port, spec, err, n);
}

static int udp_open(const char *spec, char *err, size_t n)
{
    char host[256], port[64];
    struct addrinfo hints = {.ai_socktype = SOCK_DGRAM}, *ai = NULL;
    if (split(spec, host, sizeof host, port, sizeof port, err, n) != 0 ||
        port_ok(port, spec, err, n) != 0)
        return -1;
    int g = getaddrinfo(host, port, &hints, &ai);
    if (g != 0) {
        snprintf(err, n, "--link %s: %s", spec, gai_strerror(g));
        return -1;
    }
    fd = socket(ai->ai_family, SOCK_DGRAM, 0);
    if (fd < 0 || connect(fd, ai->ai_addr, ai->ai_addrlen) != 0) {
        snprintf(err, n, "--link %s: %s", spec, strerror(errno));
        freeaddrinfo(ai);
        if (fd >= 0)
            close(fd), fd = -1;
        return -1;
    }
    freeaddrinfo(ai);
    return 0;
}

static int udp_send(const uint8_t *buf, size_t len)
{
    return send(fd, buf, len, MSG_DONTWAIT) == (ssize_t)len ? 0 : -1;
}

static long udp_recv(uint8_t *buf, size_t cap, int poll_ms)
{
    struct pollfd p = {.fd = fd, .events = POLLIN};
    int r = poll(&p, 1, poll_ms);
    if (r < 0)
        return errno == EINTR ? 0 : -1;
    if (r == 0)
        return 0;
    ssize_t got = recv(fd, buf, cap, MSG_DONTWAIT);
    if (got >= 0)
        return (long)got;
    /* no controller listening yet (an ICMP port unreachable) is no failure */
    return errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR || errno == ECONNREFUSED
               ? 0 : -1;
}

static void udp_close(void)
{
    if (fd >= 0)
        close(fd), fd = -1;
}

const link_transport link_udp = {
    .prefix = "udp:",
    .usage = "udp:HOST:PORT",
    .check = udp_check,
    .open = udp_open,
    .send = udp_send,
    .recv = udp_recv,
    .close = udp_close,
};
