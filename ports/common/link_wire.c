/* link_wire.c - encoding and checked decoding of the controller link's datagrams (format:
 * link_wire.h, docs/link.md). No libc: byte-wise little-endian access, so the code is the
 * same on any host byte order and alignment. */
#include "link_wire.h"

#include "link_hmac.h"

#define LINK_X_KEY(id, key, text) key,
static const char *const error_keys[] = {LINK_WIRE_ERRORS(LINK_X_KEY)};
#undef LINK_X_KEY

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

static int has_key(const link_key *key)
{
    return key && key->len > 0 && key->len <= LINK_MAX_KEY;
}

size_t link_encode(const link_packet *p, const link_key *key, uint8_t *buf, size_t cap)
{
    int auth = has_key(key);
    size_t size = LINK_SIZE(p->n) + (auth ? LINK_TAG_LEN : 0);
    if (p->n > LINK_MAX_VALUES || cap < size)
        return 0;
    for (int i = 0; i < 4; i++)
        buf[i] = (uint8_t)LINK_MAGIC[i];
    buf[4] = LINK_VERSION, buf[5] = p->type;
    buf[6] = auth ? LINK_FLAG_AUTH : 0, buf[7] = (uint8_t)p->n;
    int end = 0;
    for (int i = 0; i < LINK_NAME_LEN; i++) {
        end |= p->name[i] == 0;
        buf[8 + i] = end ? 0 : (uint8_t)p->name[i];
    }
    link_put_le(buf + 24, p->id, 4);
    link_put_le(buf + 28, p->seq, 4);
    link_put_le(buf + 32, p->tick, 8);
    link_put_le(buf + 40, p->run, 8);
    for (uint16_t i = 0; i < p->n; i++)
        link_put_le(buf + LINK_HEADER + 8 * (size_t)i, link_bits_of(p->v[i]), 8);
    size_t body = LINK_HEADER + 8 * (size_t)p->n;
    link_put_le(buf + body, link_crc32(0, buf, body), 4);
    if (auth)
        link_hmac_sha256(key->k, key->len, buf, body + 4, buf + body + 4);
    return size;
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

/* the tag, compared in time independent of where it differs */
static int tag_ok(const link_key *key, const uint8_t *buf, size_t signed_len)
{
    uint8_t want[LINK_TAG_LEN], diff = 0;
    link_hmac_sha256(key->k, key->len, buf, signed_len, want);
    for (int i = 0; i < LINK_TAG_LEN; i++)
        diff |= (uint8_t)(want[i] ^ buf[signed_len + i]);
    return diff == 0;
}

/* the framing: size, magic, version and flags, the size n implies, the CRC, the tag */
static link_wire_error check_frame(const uint8_t *buf, size_t len, const link_key *key,
                                   link_packet *p)
{
    if (len < LINK_SIZE(0) || len > LINK_MAX_PACKET)
        return LINK_E_SIZE;
    for (int i = 0; i < 4; i++)
        if (buf[i] != (uint8_t)LINK_MAGIC[i])
            return LINK_E_MAGIC;
    p->flags = buf[6];
    if (buf[4] != LINK_VERSION || (p->flags & ~LINK_FLAG_AUTH) != 0)
        return LINK_E_VERSION;
    p->n = buf[7];
    int tagged = (p->flags & LINK_FLAG_AUTH) != 0;
    if (p->n > LINK_MAX_VALUES || len != LINK_SIZE(p->n) + (tagged ? LINK_TAG_LEN : 0))
        return LINK_E_SIZE;
    size_t body = LINK_HEADER + 8 * (size_t)p->n;
    if (link_get_le(buf + body, 4) != link_crc32(0, buf, body))
        return LINK_E_CRC;
    if (tagged != has_key(key) || (tagged && !tag_ok(key, buf, body + 4)))
        return LINK_E_AUTH;
    return LINK_OK;
}

link_wire_error link_decode(const uint8_t *buf, size_t len, const link_expect *x,
                            link_packet *p)
{
    link_wire_error e = check_frame(buf, len, x->key, p);
    if (e != LINK_OK)
        return e;
    p->type = buf[5];
    if (p->type != x->type)
        return LINK_E_TYPE;
    for (int i = 0; i < LINK_NAME_LEN; i++)
        p->name[i] = (char)buf[8 + i];
    p->name[LINK_NAME_LEN] = 0;
    p->id = (uint32_t)link_get_le(buf + 24, 4);
    if (!same_name(buf + 8, x->name) || p->id != x->id)
        return LINK_E_SCENE;
    if (p->n != x->n)
        return LINK_E_COUNT;
    p->seq = (uint32_t)link_get_le(buf + 28, 4);
    p->tick = link_get_le(buf + 32, 8);
    p->run = link_get_le(buf + 40, 8);
    if (x->check_run && p->run != x->run)
        return LINK_E_RUN;
    for (uint16_t i = 0; i < p->n; i++) {
        p->v[i] = link_double_of(link_get_le(buf + LINK_HEADER + 8 * (size_t)i, 8));
        if (!(p->v[i] - p->v[i] == 0))
            return LINK_E_VALUE;
    }
    return LINK_OK;
}
