/* serial.c - the POSIX serial transport of the controller link (serial.h, docs/link.md):
 * opens a terminal device raw at a named baud rate (or creates a pty), writes each
 * datagram as one frame of ports/common/linkframe.c, and reads bytes into the framing
 * receiver until a frame ends. The receive side runs in the link's receiver thread only. */
#define _DEFAULT_SOURCE /* cfmakeraw, the B* rates above 38400 */
#define _XOPEN_SOURCE 600 /* posix_openpt, grantpt, unlockpt, ptsname */
#include "serial.h"

#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <termios.h>
#include <time.h>
#include <unistd.h>

#include "common/linkframe.h"

#define SERIAL_READ_CHUNK 512 /* bytes per read(): several frames at once */

/* the rates termios names (POSIX and Linux) */
static const struct { unsigned long baud; speed_t code; } rates[] = {
    {50, B50}, {75, B75}, {110, B110}, {134, B134}, {150, B150}, {200, B200}, {300, B300},
    {600, B600}, {1200, B1200}, {1800, B1800}, {2400, B2400}, {4800, B4800}, {9600, B9600},
    {19200, B19200}, {38400, B38400},
#ifdef B57600
    {57600, B57600}, {115200, B115200}, {230400, B230400},
#endif
#ifdef B460800
    {460800, B460800}, {500000, B500000}, {576000, B576000}, {921600, B921600},
    {1000000, B1000000}, {1152000, B1152000}, {1500000, B1500000}, {2000000, B2000000},
#endif
#ifdef B2500000
    {2500000, B2500000}, {3000000, B3000000}, {3500000, B3500000}, {4000000, B4000000},
#endif
};

static int speed_of(unsigned long baud, speed_t *code)
{
    for (size_t i = 0; i < sizeof rates / sizeof rates[0]; i++)
        if (rates[i].baud == baud)
            return *code = rates[i].code, 0;
    return -1;
}

/* raw 8N1, no flow control, reads never wait (poll does) */
static int make_raw(int fd, speed_t code)
{
    struct termios t;
    if (tcgetattr(fd, &t) != 0)
        return -1;
    cfmakeraw(&t);
    t.c_cflag |= CLOCAL | CREAD;
    t.c_cflag &= ~(tcflag_t)(CSTOPB | CRTSCTS);
    t.c_cc[VMIN] = 0, t.c_cc[VTIME] = 0;
    if (cfsetispeed(&t, code) != 0 || cfsetospeed(&t, code) != 0)
        return -1;
    if (tcsetattr(fd, TCSANOW, &t) != 0)
        return -1;
    tcflush(fd, TCIOFLUSH); /* whatever an earlier user left in the buffers */
    return 0;
}

/* a new pty: the master is ours, the slave stays open (raw) so that the master never
   reads end-of-file while the peer has not opened it yet */
static int open_pty(char *peer, size_t nk, char *err, size_t n)
{
    int m = posix_openpt(O_RDWR | O_NOCTTY);
    const char *name = m >= 0 && grantpt(m) == 0 && unlockpt(m) == 0 ? ptsname(m) : NULL;
    int s = name ? open(name, O_RDWR | O_NOCTTY) : -1;
    if (s < 0 || make_raw(s, B115200) != 0 || strlen(name) >= nk) {
        snprintf(err, n, "serial:pty: cannot create a pseudo-terminal: %s", strerror(errno));
        if (m >= 0)
            close(m);
        return -1;
    }
    strcpy(peer, name);
    fcntl(m, F_SETFL, fcntl(m, F_GETFL) | O_NONBLOCK);
    return m; /* s is kept open for the life of the process */
}

/* serial:DEVICE[:BAUD] into the device and its rate; -1 with the reason */
static int split(const char *spec, char *dev, size_t nd, speed_t *code, unsigned long *baud,
                 char *err, size_t n)
{
    *baud = SERIAL_DEFAULT_BAUD, *code = B115200; /* the same rate */
    if (strncmp(spec, SERIAL_PREFIX, strlen(SERIAL_PREFIX)) != 0)
        return snprintf(err, n, "expected serial:DEVICE[:BAUD], got '%s'", spec), -1;
    const char *d = spec + strlen(SERIAL_PREFIX), *colon = strrchr(d, ':');
    size_t dl = strlen(d);
    if (colon) {
        char *end;
        *baud = strtoul(colon + 1, &end, 10);
        if (colon[1] == 0 || *end != 0 || speed_of(*baud, code) != 0)
            return snprintf(err, n, "%s: the baud rate '%s' is none the system names "
                            "(e.g. 9600, 115200, 921600)", spec, colon + 1), -1;
        dl = (size_t)(colon - d);
    }
    if (dl == 0 || dl >= nd)
        return snprintf(err, n, "expected serial:DEVICE[:BAUD], got '%s'", spec), -1;
    memcpy(dev, d, dl), dev[dl] = 0;
    return 0;
}

int serial_check(const char *spec, char *err, size_t n)
{
    char dev[256];
    speed_t code;
    unsigned long baud;
    return split(spec, dev, sizeof dev, &code, &baud, err, n);
}

int serial_open(const char *spec, char *peer, size_t nk, char *err, size_t n)
{
    char dev[256];
    unsigned long baud;
    speed_t code;
    if (strcmp(spec, SERIAL_PREFIX "pty") == 0)
        return open_pty(peer, nk, err, n);
    if (split(spec, dev, sizeof dev, &code, &baud, err, n) != 0)
        return -1;
    int fd = open(dev, O_RDWR | O_NOCTTY | O_NONBLOCK);
    if (fd < 0)
        return snprintf(err, n, "%s: cannot open %s: %s", spec, dev, strerror(errno)), -1;
    if (make_raw(fd, code) != 0) {
        snprintf(err, n, "%s: %s is not a terminal that takes %lu baud: %s", spec, dev, baud,
                 strerror(errno));
        close(fd);
        return -1;
    }
    return fd;
}

/* the receiver's bytes read but not yet framed */
static struct {
    uint8_t buf[SERIAL_READ_CHUNK];
    size_t len, pos;
    linkframe_rx rx;
} R;

ssize_t serial_recv(int fd, uint8_t *out, size_t cap, int poll_ms, int *fault)
{
    for (;;) {
        while (R.pos < R.len) {
            const uint8_t *d;
            size_t len;
            linkframe_verdict v = linkframe_rx_byte(&R.rx, R.buf[R.pos++], &d, &len);
            if (v == LINKFRAME_DATAGRAM) {
                size_t m = len < cap ? len : cap; /* a longer one fails the size check */
                memcpy(out, d, m);
                return (ssize_t)(len <= cap ? len : cap);
            }
            if (v != LINKFRAME_MORE)
                return *fault = (int)v, -2;
        }
        struct pollfd p = {.fd = fd, .events = POLLIN};
        int r = poll(&p, 1, poll_ms);
        if (r == 0)
            return errno = EAGAIN, -1;
        if (r < 0)
            return -1;
        ssize_t k = read(fd, R.buf, sizeof R.buf);
        if (k == 0 || (k < 0 && errno == EIO)) /* a pty whose peer is gone */
            return errno = EAGAIN, usleep((useconds_t)poll_ms * 1000), -1;
        if (k < 0)
            return -1;
        R.len = (size_t)k, R.pos = 0;
    }
}

ssize_t serial_send(int fd, const uint8_t *d, size_t len, int wait_ms)
{
    uint8_t frame[LINKFRAME_MAX_WIRE];
    size_t n = linkframe_encode(d, len, frame, sizeof frame), done = 0;
    if (n == 0)
        return errno = EMSGSIZE, -1;
    while (done < n) {
        ssize_t k = write(fd, frame + done, n - done);
        if (k > 0) {
            done += (size_t)k;
            continue;
        }
        if (k < 0 && errno != EAGAIN && errno != EINTR)
            return -1;
        struct pollfd p = {.fd = fd, .events = POLLOUT};
        if (poll(&p, 1, wait_ms) <= 0)
            return errno = ETIMEDOUT, -1;
    }
    return (ssize_t)len;
}
