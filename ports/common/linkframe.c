/* linkframe.c - the controller link's byte-stream framing (format: linkframe.h,
 * docs/link.md): COBS encoding of one datagram between zero bytes, and a receiver that
 * takes one byte at a time (from a UART interrupt, a polling loop or a read() buffer) and
 * decodes a frame in place when its closing zero arrives. No libc. */
#include "linkframe.h"

#define COBS_RUN 0xFFu /* a code byte for 254 data bytes and no zero after them */

#define LINKFRAME_X_NAME(id, key, text) text,
#define LINKFRAME_X_KEY(id, key, text) key,
static const char *const fault_names[] = {"more", "datagram",
                                          LINKFRAME_FAULTS(LINKFRAME_X_NAME)};
static const char *const fault_keys[] = {"more", "datagram", LINKFRAME_FAULTS(LINKFRAME_X_KEY)};
#undef LINKFRAME_X_NAME
#undef LINKFRAME_X_KEY

const char *linkframe_fault_name(int v)
{
    return v >= 0 && v < LINKFRAME_E_COUNT_ ? fault_names[v] : "?";
}

const char *linkframe_fault_key(int v)
{
    return v >= 0 && v < LINKFRAME_E_COUNT_ ? fault_keys[v] : "?";
}

void linkframe_rx_init(linkframe_rx *rx)
{
    rx->len = 0, rx->skipping = 0;
    for (int i = 0; i < LINKFRAME_E_COUNT_; i++)
        rx->fault[i] = 0;
}

/* COBS: each code byte c is followed by c - 1 data bytes and stands for a zero after them,
   except c = 0xFF (a full run) and the last block (the frame's end is no zero) */
size_t linkframe_encode(const uint8_t *d, size_t len, uint8_t *out, size_t cap)
{
    if (len > LINK_MAX_PACKET || cap < LINKFRAME_WIRE(len))
        return 0;
    size_t o = 0, code_at;
    uint8_t code = 1;
    out[o++] = 0;
    code_at = o++;
    for (size_t i = 0; i <= len; i++) {
        uint8_t b = i == 0 ? (uint8_t)LINKFRAME_VERSION : d[i - 1];
        if (b != 0) {
            out[o++] = b;
            code++;
        }
        /* a full run closes its block only when more bytes follow (the minimal coding) */
        if (b == 0 || (code == COBS_RUN && i < len)) {
            out[code_at] = code;
            code_at = o++;
            code = 1;
        }
    }
    out[code_at] = code;
    out[o++] = 0;
    return o;
}

/* decodes rx->buf in place (the output never overtakes the input); the payload's length,
   or -1 when a code byte points past the end */
static long cobs_decode(uint8_t *buf, size_t len)
{
    size_t i = 0, o = 0;
    while (i < len) {
        uint8_t code = buf[i++];
        if ((size_t)code - 1 > len - i)
            return -1;
        for (uint8_t k = 1; k < code; k++)
            buf[o++] = buf[i++];
        if (code != COBS_RUN && i < len)
            buf[o++] = 0;
    }
    return (long)o;
}

static linkframe_verdict fault(linkframe_rx *rx, linkframe_verdict v)
{
    rx->fault[v]++;
    return v;
}

/* a zero byte ended the frame in rx->buf: its datagram, a fault, or nothing (empty) */
static linkframe_verdict close_frame(linkframe_rx *rx, const uint8_t **dgram, size_t *len)
{
    size_t n = rx->len;
    int skipped = rx->skipping;
    rx->len = 0, rx->skipping = 0;
    if (skipped || n == 0) /* an overlong frame was counted when it overflowed */
        return LINKFRAME_MORE;
    long m = cobs_decode(rx->buf, n);
    if (m < 0)
        return fault(rx, LINKFRAME_E_COBS);
    /* COBS codes a frame of blocks without zeros more densely than the encoder's worst
       case the buffer is sized for: a frame that fits can still hold too much */
    if ((size_t)m > LINKFRAME_MAX_PAYLOAD)
        return fault(rx, LINKFRAME_E_LONG);
    if (m < 1 || rx->buf[0] != LINKFRAME_VERSION)
        return fault(rx, LINKFRAME_E_VERSION);
    *dgram = rx->buf + 1, *len = (size_t)m - 1;
    return LINKFRAME_DATAGRAM;
}

linkframe_verdict linkframe_rx_byte(linkframe_rx *rx, uint8_t byte, const uint8_t **dgram,
                                    size_t *len)
{
    if (byte == 0)
        return close_frame(rx, dgram, len);
    if (rx->skipping)
        return LINKFRAME_MORE;
    if (rx->len >= sizeof rx->buf) {
        rx->skipping = 1;
        return fault(rx, LINKFRAME_E_LONG);
    }
    rx->buf[rx->len++] = byte;
    return LINKFRAME_MORE;
}
