/* linkframe.h - the controller link's byte-stream framing, version 1 (docs/link.md, "Over
 * a serial line"): one datagram of link_wire.h per frame, COBS-encoded (Cheshire & Baker
 * 1999) so that a frame holds no zero byte, and a zero byte before and after it:
 *
 *   0x00  COBS( framing version (1) | datagram )  0x00
 *
 * The datagram keeps its own CRC-32; the framing adds none. A receiver decodes between two
 * zero bytes: garbage, a lost byte or a flipped bit spoils at most the frame it falls in
 * (the CRC or the COBS structure shows it) and the next zero resynchronises. Two zeros in
 * a row (the end of one frame, the start of the next) are an empty frame, skipped.
 * Plain C without libc or allocation: the POSIX serial link, the client library of a
 * controller's firmware and a plant image share it. */
#ifndef LINKFRAME_H
#define LINKFRAME_H

#include <stddef.h>
#include <stdint.h>

#include "link_wire.h"

#define LINKFRAME_VERSION 1
/* the largest payload: the version byte and the largest datagram */
#define LINKFRAME_MAX_PAYLOAD (1 + LINK_MAX_PACKET)
/* COBS adds one code byte per 254 payload bytes (and one at the start) */
#define LINKFRAME_MAX_CODED (LINKFRAME_MAX_PAYLOAD + LINKFRAME_MAX_PAYLOAD / 254 + 1)
/* a frame on the wire: the coded bytes and both delimiters */
#define LINKFRAME_MAX_WIRE (LINKFRAME_MAX_CODED + 2)
/* the wire size of a datagram of `len` bytes */
#define LINKFRAME_WIRE(len) ((size_t)(len) + 1 + ((size_t)(len) + 1) / 254 + 1 + 2)

/* What a frame decoder found wrong, declared once: X(id, key for summaries, meaning). */
#define LINKFRAME_FAULTS(X)                                                                \
    X(LINKFRAME_E_LONG, "long", "a frame longer than the largest one")     \
    X(LINKFRAME_E_COBS, "cobs", "a COBS code byte runs past the frame's end")               \
    X(LINKFRAME_E_VERSION, "version", "an empty payload or a framing version other than 1")

typedef enum {
    LINKFRAME_MORE = 0,  /* the byte was taken; no frame complete yet */
    LINKFRAME_DATAGRAM,  /* a frame ended: its datagram is ready */
#define LINKFRAME_X_ENUM(id, key, text) id,
    LINKFRAME_FAULTS(LINKFRAME_X_ENUM)
#undef LINKFRAME_X_ENUM
    LINKFRAME_E_COUNT_
} linkframe_verdict;

/* A receiver: the bytes since the last zero byte. The caller owns the storage (about
   LINKFRAME_MAX_CODED bytes); zero it, or call linkframe_rx_init, before the first byte. */
typedef struct linkframe_rx {
    uint8_t buf[LINKFRAME_MAX_CODED];
    uint16_t len;      /* bytes in buf */
    uint8_t skipping;  /* an overlong frame: bytes are dropped until the next zero */
    uint32_t fault[LINKFRAME_E_COUNT_]; /* frames refused, by linkframe_verdict */
} linkframe_rx;

void linkframe_rx_init(linkframe_rx *rx);
/* Takes one received byte. Returns LINKFRAME_DATAGRAM when it ended a frame whose datagram
   (without the version byte) is then at *dgram (inside rx, valid until the next call) with
   *len bytes; a fault (counted in rx->fault) when it ended a broken frame; else
   LINKFRAME_MORE. A frame too long for the buffer is reported once, at its first byte too
   many; one that fits but decodes to more than the largest payload, at its closing zero. */
linkframe_verdict linkframe_rx_byte(linkframe_rx *rx, uint8_t byte, const uint8_t **dgram,
                                    size_t *len);
/* Frames datagram d (len bytes) into out (cap bytes, LINKFRAME_WIRE(len) needed); returns
   the number of bytes to send, or 0 if it does not fit or len exceeds LINK_MAX_PACKET. */
size_t linkframe_encode(const uint8_t *d, size_t len, uint8_t *out, size_t cap);
/* The name and the summary key of a verdict. */
const char *linkframe_fault_name(int v);
const char *linkframe_fault_key(int v);

#endif /* LINKFRAME_H */
