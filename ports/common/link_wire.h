/* link_wire.h - the controller link's wire format, version 2 (docs/link.md): encoding
 * and checked decoding of one datagram, and the CRC-32 it carries. Plain C without libc,
 * so the same code serves the POSIX UDP service, a UART or CAN driver on a board, the
 * fuzzer and the example controller. A transport (UDP, a serial framing) carries the
 * datagram's bytes unchanged; everything it means is checked here and in the exchange.
 *
 *   offset  size  field
 *   0       4     magic "MRTL"
 *   4       1     version (2)
 *   5       1     type: 1 plant -> controller (exports), 2 controller -> plant (imports)
 *   6       1     flags: bit 0 (LINK_FLAG_AUTH) an HMAC-SHA-256 tag follows the CRC;
 *                 the other bits are 0
 *   7       1     n, the number of values (at most 64)
 *   8       16    scene name, NUL-padded (cut at 16 bytes)
 *   24      4     link id: hash of the scene name and the link layout
 *   28      4     sequence number (an answer repeats the one it answers)
 *   32      8     tick of the state the exports belong to (an answer repeats it)
 *   40      8     run nonce: random, drawn by the plant at the start of each run (an
 *                 answer repeats it)
 *   48      8 n   values, IEEE-754 binary64
 *   48+8n   4     CRC-32 (IEEE 802.3, zlib's crc32) of bytes 0 .. 47+8n
 *   52+8n   32    only with LINK_FLAG_AUTH: HMAC-SHA-256 under the shared key of bytes
 *                 0 .. 51+8n
 * All integers and values little-endian. */
#ifndef LINK_WIRE_H
#define LINK_WIRE_H

#include <stddef.h>
#include <stdint.h>

#define LINK_MAGIC "MRTL"
#define LINK_VERSION 2
#define LINK_TYPE_EXPORTS 1
#define LINK_TYPE_IMPORTS 2
#define LINK_FLAG_AUTH 1u
#define LINK_NAME_LEN 16
#define LINK_HEADER 48
#define LINK_TAG_LEN 32
#define LINK_MAX_VALUES 64
#define LINK_MAX_KEY 64          /* shared key bytes (HMAC-SHA-256's block) */
#define LINK_SIZE(n) (LINK_HEADER + 8 * (size_t)(n) + 4)   /* without a tag */
#define LINK_MAX_PACKET (LINK_SIZE(LINK_MAX_VALUES) + LINK_TAG_LEN)

/* What a receiver found wrong, in the order the checks run, declared once:
   X(id, key for summaries, meaning: documentation only). A serial line's framing (linkframe.c) finds frame;
   the decoder all the others but the last two; the plant's exchange (tools/modrt/link.c)
   finds seq and tick against its requests. */
#define LINK_WIRE_ERRORS(X)                                                      \
    X(LINK_OK, "ok", "ok")                                                       \
    X(LINK_E_FRAME, "frame", "a broken frame of a serial line")                  \
    X(LINK_E_SIZE, "size", "truncated or oversized datagram")                   \
    X(LINK_E_MAGIC, "magic", "wrong magic")                                      \
    X(LINK_E_VERSION, "version", "unsupported protocol version or flag")        \
    X(LINK_E_CRC, "crc", "bad CRC")                                              \
    X(LINK_E_AUTH, "auth", "authentication tag missing, unexpected or wrong")   \
    X(LINK_E_TYPE, "type", "wrong packet type")                                  \
    X(LINK_E_SCENE, "scene", "another scene (name or link id)")                  \
    X(LINK_E_COUNT, "count", "wrong number of values")                           \
    X(LINK_E_RUN, "run", "another run's nonce (a stray or replayed answer)")    \
    X(LINK_E_VALUE, "value", "a value is not finite")                            \
    X(LINK_E_SEQ, "seq", "answers a request never sent")                         \
    X(LINK_E_TICK, "tick", "a tick other than its request's")

typedef enum {
#define LINK_X_ENUM(id, key, text) id,
    LINK_WIRE_ERRORS(LINK_X_ENUM)
#undef LINK_X_ENUM
    LINK_E_COUNT_
} link_wire_error;

typedef struct link_packet {
    uint8_t type, flags;
    uint16_t n;
    char name[LINK_NAME_LEN + 1];
    uint32_t id, seq;
    uint64_t tick, run;
    double v[LINK_MAX_VALUES];
} link_packet;

/* The shared key of the authenticated mode; len 0: unauthenticated. */
typedef struct link_key {
    uint8_t k[LINK_MAX_KEY];
    size_t len;
} link_key;

/* What a receiver accepts. */
typedef struct link_expect {
    uint8_t type;            /* LINK_TYPE_* */
    const char *name;        /* scene name (compared over LINK_NAME_LEN bytes) */
    uint32_t id;             /* link id */
    uint16_t n;              /* value count */
    int check_run;           /* 1: the run nonce must equal `run` (the plant) */
    uint64_t run;
    const link_key *key;     /* NULL or len 0: tags refused; else a tag is required */
} link_expect;

const char *link_wire_error_key(int e);  /* one word, for key: value summaries */
uint32_t link_crc32(uint32_t crc, const uint8_t *p, size_t n);
/* The byte order of the wire and of the replay log (tools/modrt/mrlog.c): v into / from
   `bytes` little-endian bytes, and a binary64's bit pattern. */
void link_put_le(uint8_t *b, uint64_t v, int bytes);
uint64_t link_get_le(const uint8_t *b, int bytes);
uint64_t link_bits_of(double d);
double link_double_of(uint64_t u);
/* Writes packet p (p->n values; p->flags is ignored) into buf (cap bytes), with a tag
   when key is given (non-NULL, len > 0); returns its size, or 0 if it does not fit or n
   exceeds LINK_MAX_VALUES. */
size_t link_encode(const link_packet *p, const link_key *key, uint8_t *buf, size_t cap);
/* Decodes and checks a datagram against what the receiver expects, in the order of
   LINK_WIRE_ERRORS (size, magic, version and flags, size for n, CRC, tag, type, scene,
   count, run, values): fills p and returns LINK_OK, or the first problem found. p is
   written only as far as the datagram was read; never applied by the caller unless
   LINK_OK. */
link_wire_error link_decode(const uint8_t *buf, size_t len, const link_expect *x,
                            link_packet *p);

#endif /* LINK_WIRE_H */
