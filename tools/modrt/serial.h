/* serial.h - the POSIX serial transport of the controller link (`--link serial:DEV:BAUD`,
 * docs/link.md "Over a serial line"): a terminal device (a UART, a USB-CDC port, a pty) in
 * raw mode carrying the link's datagrams in the frames of ports/common/linkframe.h.
 * One serial link per process (the receive side keeps its buffer and framing state). */
#ifndef MODRT_SERIAL_H
#define MODRT_SERIAL_H

#include <stddef.h>
#include <stdint.h>
#include <sys/types.h>

#define SERIAL_PREFIX "serial:"
#define SERIAL_DEFAULT_BAUD 115200

/* Opens `spec`: serial:DEVICE[:BAUD] (raw 8N1, no flow control, BAUD one of the rates
   termios names, default 115200), or serial:pty (a new pseudo-terminal: its peer's path is
   written to `peer`, nk bytes; the returned fd is its master side). Returns the fd, or -1
   with a one-line reason in err. */
int serial_open(const char *spec, char *peer, size_t nk, char *err, size_t n);
/* Checks the syntax and the rate of a spec without opening anything: 0, or -1. */
int serial_check(const char *spec, char *err, size_t n);
/* Waits at most poll_ms for input and returns the next datagram (its length; the bytes in
   buf, cap of them); -1 with errno EAGAIN when no frame ended in time, another errno on a
   read error; -2 when a broken frame ended, with *fault its linkframe_verdict. */
ssize_t serial_recv(int fd, uint8_t *buf, size_t cap, int poll_ms, int *fault);
/* Frames datagram d (len bytes) and writes it whole, waiting at most wait_ms for the
   device to take it; returns len, or -1. */
ssize_t serial_send(int fd, const uint8_t *d, size_t len, int wait_ms);

#endif /* MODRT_SERIAL_H */
