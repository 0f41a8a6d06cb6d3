/* link_wire.h - the controller link's wire format, version 1 (docs/link.md): encoding
 * and checked decoding of one datagram, and the CRC-32 it carries. Plain C without libc,
 * so the same code serves the POSIX UDP service, a UART or CAN driver on a board, the
 * fuzzer and the example controller.
 *
 *   offset  size  field
 *   0       4     magic "MRTL"
 *   4       1     version (1)
 *   5       1     type: 1 plant -> controller (exports), 2 controller -> plant (imports)
 *   6       2     n, the number of values
 *   8       16    scene name, NUL-padded (cut at 16 bytes)
 *   24      4     link id: hash of the scene name and the link layout
 *   28      4     sequence number (a reply repeats the one it answers)
 *   32      8     tick of the state the exports belong to
 *   40      8 n   values, IEEE-754 binary64
 *   40+8n   4     CRC-32 (IEEE 802.3, zlib's crc32) of bytes 0 .. 39+8n
 * All integers and values little-endian. */
#ifndef LINK_WIRE_H
#define LINK_WIRE_H

#include <stddef.h>
#include <stdint.h>

#define LINK_MAGIC "MRTL"
#define LINK_VERSION 1
#define LINK_TYPE_EXPORTS 1
#define LINK_TYPE_IMPORTS 2
#define LINK_NAME_LEN 16
#define LINK_HEADER 40
#define LINK_MAX_VALUES 64
#define LINK_SIZE(n) (LINK_HEADER + 8 * (size_t)(n) + 4)
#define LINK_MAX_PACKET LINK_SIZE(LINK_MAX_VALUES)

/* What a decoder found wrong, declared once: X(id, key for summaries, meaning). */
#define LINK_WIRE_ERRORS(X)                                                      \
    X(LINK_OK, "ok", "ok")                                                       \
    X(LINK_E_SIZE, "size", "truncated or oversized datagram")                   \
    X(LINK_E_FRAME, "frame", "a broken serial frame (COBS, length, framing version)") \
    X(LINK_E_MAGIC, "magic", "wrong magic")                                      \
    X(LINK_E_VERSION, "version", "unsupported protocol version")                 \
    X(LINK_E_TYPE, "type", "wrong packet type")                                  \
    X(LINK_E_CRC, "crc", "bad CRC")                                              \
    X(LINK_E_SCENE, "scene", "another scene (name or link id)")                  \
    X(LINK_E_COUNT, "count", "wrong number of values")                           \
    X(LINK_E_VALUE, "value", "a value is not finite")                            \
    X(LINK_E_SEQ, "seq", "answers a packet never sent")

typedef enum {
#define LINK_X_ENUM(id, key, text) id,
    LINK_WIRE_ERRORS(LINK_X_ENUM)
#undef LINK_X_ENUM
    LINK_E_COUNT_
} link_wire_error;

typedef struct link_packet {
    uint8_t type;
    uint16_t n;
    char name[LINK_NAME_LEN + 1];
    uint32_t id, seq;
    uint64_t tick;
    double v[LINK_MAX_VALUES];
} link_packet;

const char *link_wire_error_name(int e); /* its meaning */
const char *link_wire_error_key(int e);  /* one word, for key: value summaries */
uint32_t link_crc32(uint32_t crc, const uint8_t *p, size_t n);
/* The byte order of the wire and of the replay log (tools/modrt/mrlog.c): v into / from
   `bytes` little-endian bytes, and a binary64's bit pattern. */
void link_put_le(uint8_t *b, uint64_t v, int bytes);
uint64_t link_get_le(const uint8_t *b, int bytes);
uint64_t link_bits_of(double d);
double link_double_of(uint64_t u);
/* Writes packet p (p->n values) into buf (cap bytes); returns its size, or 0 if it
   does not fit or n exceeds LINK_MAX_VALUES. */
size_t link_encode(const link_packet *p, uint8_t *buf, size_t cap);
/* Decodes and checks a datagram against what the receiver expects (type, scene name, id,
   value count): fills p and returns LINK_OK, or the first problem found. p is written
   only as far as the datagram was read; never applied by the caller unless LINK_OK. */
link_wire_error link_decode(const uint8_t *buf, size_t len, uint8_t type, const char *name,
                            uint32_t id, uint16_t n, link_packet *p);

#endif /* LINK_WIRE_H */
