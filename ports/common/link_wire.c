/* link_wire.c - encoding and checked decoding of the controller link's datagrams (format:
 * link_wire.h, docs/link.md). No libc: byte-wise little-endian access, so the code is the
 * same on any host byte order and alignment. */
#include "link_wire.h"

#define LINK_X_NAME(id, key, text) text,
#define LINK_X_KEY(id, key, text) key,
static const char *const error_names[] = {LINK_WIRE_ERRORS(LINK_X_NAME)};
static const char *const error_keys[] = {LINK_WIRE_ERRORS(LINK_X_KEY)};
#undef LINK_X_NAME
#undef LINK_X_KEY

const char *link_wire_error_name(int e)
{
    return e >= 0 && e < LINK_E_COUNT_ ? error_names[e] : "?";
}

const char *link_wire_error_key(int e)
{
    return e >= 0 && e < LINK_E_COUNT_ ? error_keys[e] : "?";
}

/* bitwise CRC-32 (reflected, polynomial 0xEDB88320): a table would be 1 KB of flash */
uint32_t link_crc32(uint32_t crc, const uint8_t *p, size_t n)
{
    crc = ~crc;
    while (n--) {
        crc ^= *p++;
        for (int k = 0; k < 8; k++)
            crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
    }
    return ~crc;
}

void link_put_le(uint8_t *b, uint64_t v, int bytes)
{
    for (int i = 0; i < bytes; i++)
        b[i] = (uint8_t)(v >> (8 * i));
}

uint64_t link_get_le(const uint8_t *b, int bytes)
{
    uint64_t v = 0;
    for (int i = 0; i < bytes; i++)
        v |= (uint64_t)b[i] << (8 * i);
    return v;
}

uint64_t link_bits_of(double d)
{
    union { double d; uint64_t u; } c = {.d = d};
    return c.u;
}

double link_double_of(uint64_t u)
{
    union { uint64_t u; double d; } c = {.u = u};
    return c.d;
}

size_t link_encode(const link_packet *p, uint8_t *buf, size_t cap)
{
    if (p->n > LINK_MAX_VALUES || cap < LINK_SIZE(p->n))
        return 0;
    for (int i = 0; i < 4; i++)
        buf[i] = (uint8_t)LINK_MAGIC[i];
    buf[4] = LINK_VERSION, buf[5] = p->type;
    link_put_le(buf + 6, p->n, 2);
    int end = 0;
    for (int i = 0; i < LINK_NAME_LEN; i++) {
        end |= p->name[i] == 0;
        buf[8 + i] = end ? 0 : (uint8_t)p->name[i];
    }
    link_put_le(buf + 24, p->id, 4);
    link_put_le(buf + 28, p->seq, 4);
    link_put_le(buf + 32, p->tick, 8);
    for (uint16_t i = 0; i < p->n; i++)
        link_put_le(buf + LINK_HEADER + 8 * (size_t)i, link_bits_of(p->v[i]), 8);
    size_t body = LINK_HEADER + 8 * (size_t)p->n;
    link_put_le(buf + body, link_crc32(0, buf, body), 4);
    return body + 4;
}

static int same_name(const uint8_t *field, const char *name)
{
    for (int i = 0; i < LINK_NAME_LEN; i++) {
        if (field[i] != (uint8_t)name[i])
            return 0;
        if (name[i] == 0)
            return 1;
    }
    return 1; /* both cut at LINK_NAME_LEN */
}

link_wire_error link_decode(const uint8_t *buf, size_t len, uint8_t type, const char *name,
                            uint32_t id, uint16_t n, link_packet *p)
{
    if (len < LINK_SIZE(0) || len > LINK_MAX_PACKET)
        return LINK_E_SIZE;
    for (int i = 0; i < 4; i++)
        if (buf[i] != (uint8_t)LINK_MAGIC[i])
            return LINK_E_MAGIC;
    if (buf[4] != LINK_VERSION)
        return LINK_E_VERSION;
    p->n = (uint16_t)link_get_le(buf + 6, 2);
    if (p->n > LINK_MAX_VALUES || len != LINK_SIZE(p->n))
        return LINK_E_SIZE;
    size_t body = LINK_HEADER + 8 * (size_t)p->n;
    if (link_get_le(buf + body, 4) != link_crc32(0, buf, body))
        return LINK_E_CRC;
    p->type = buf[5];
    if (p->type != type)
        return LINK_E_TYPE;
    for (int i = 0; i < LINK_NAME_LEN; i++)
        p->name[i] = (char)buf[8 + i];
    p->name[LINK_NAME_LEN] = 0;
    p->id = (uint32_t)link_get_le(buf + 24, 4);
    if (!same_name(buf + 8, name) || p->id != id)
        return LINK_E_SCENE;
    if (p->n != n)
        return LINK_E_COUNT;
    p->seq = (uint32_t)link_get_le(buf + 28, 4);
    p->tick = link_get_le(buf + 32, 8);
    for (uint16_t i = 0; i < p->n; i++) {
        p->v[i] = link_double_of(link_get_le(buf + LINK_HEADER + 8 * (size_t)i, 8));
        if (!(p->v[i] - p->v[i] == 0))
            return LINK_E_VALUE;
    }
    return LINK_OK;
}
