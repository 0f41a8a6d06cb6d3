/* link_hmac.h - SHA-256 (FIPS 180-4) and HMAC-SHA-256 (RFC 2104) for the controller link's
 * authenticated mode (docs/link.md, "On an untrusted network"): plain C without libc, no
 * allocation, a few hundred bytes of stack, so a controller firmware can use it too. */
#ifndef LINK_HMAC_H
#define LINK_HMAC_H

#include <stddef.h>
#include <stdint.h>

#define LINK_SHA256_LEN 32    /* digest bytes */
#define LINK_SHA256_BLOCK 64  /* message block bytes */

typedef struct link_sha256 {
    uint32_t h[8];                     /* the hash value H(i) */
    uint8_t buf[LINK_SHA256_BLOCK];    /* the block being filled */
    uint64_t len;                      /* message bytes so far */
} link_sha256;

void link_sha256_init(link_sha256 *s);
void link_sha256_update(link_sha256 *s, const uint8_t *p, size_t n);
void link_sha256_final(link_sha256 *s, uint8_t out[LINK_SHA256_LEN]);
/* HMAC-SHA-256 of msg (n bytes) under key (klen bytes, any length: a key longer than a
   block is hashed first, RFC 2104 section 2) into tag. */
void link_hmac_sha256(const uint8_t *key, size_t klen, const uint8_t *msg, size_t n,
                      uint8_t tag[LINK_SHA256_LEN]);

#endif /* LINK_HMAC_H */
