/* link_serial.c - the serial-line transport of the controller link (link.h, docs/link.md
 * "Over a serial line"): `serial:DEVICE[:BAUD]` (or serial:pty, whose peer's path is
 * printed) through serial.c, each datagram one COBS frame of ports/common/linkframe.c.
 * A frame that arrives broken is reported as such (link_bad.frame); lock-step sends an
 * unanswered request again, since a byte stream loses frames to line noise. */
#define _POSIX_C_SOURCE 200809L
#include "link.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "serial.h"

static int fd = -1;

static int ser_check(const char *spec, char *err, size_t n)
{
    char why[400];
    if (serial_check(spec, why, sizeof why) != 0 && strcmp(spec, SERIAL_PREFIX "pty") != 0)
        return snprintf(err, n, "--link %s", why), -1;
    return 0;
}

static int ser_open(const char *spec, char *err, size_t n)
{
    char peer[64], why[400];
    fd = serial_open(spec, peer, sizeof peer, why, sizeof why);
    if (fd < 0)
        return snprintf(err, n, "%s", why), -1;
    if (strcmp(spec, SERIAL_PREFIX "pty") == 0)
        fprintf(stderr, "link: the controller's end of the pty is %s\n", peer);
    return 0;
}

/* never waits for the device: a frame it cannot take at once is not sent whole (the next
   frame's opening zero resynchronises the receiver) */
static int ser_send(const uint8_t *buf, size_t len)
{
    return serial_send(fd, buf, len, 0) == (ssize_t)len ? 0 : -1;
}

static long ser_recv(uint8_t *buf, size_t cap, int poll_ms)
{
    int fault = 0;
    ssize_t r = serial_recv(fd, buf, cap, poll_ms, &fault);
    if (r > 0)
        return (long)r;
    if (r == 0 || r == -2) /* a frame without a datagram, or broken */
        return LINK_RECV_BROKEN;
    return errno == EAGAIN || errno == EINTR ? 0 : -1;
}

static void ser_close(void)
{
    if (fd >= 0)
        close(fd), fd = -1;
}

const link_transport link_serial = {
    .prefix = SERIAL_PREFIX,
    .usage = "serial:DEVICE[:BAUD]",
    .check = ser_check,
    .open = ser_open,
    .send = ser_send,
    .recv = ser_recv,
    .close = ser_close,
    .resend = 1,
};
