/* link_hmac.c - SHA-256 written from FIPS 180-4 (sections 4.1.2, 4.2.2, 5.1.1, 5.3.3, 6.2)
 * and HMAC from RFC 2104; checked against the standards' test vectors in
 * tests/whitebox/host/test_link.c (FIPS 180-4 examples "abc" and the 448-bit message, RFC 4231). */
#include "link_hmac.h"

/* the first 32 bits of the fractional parts of the cube roots of the first 64 primes
   (FIPS 180-4, 4.2.2) */
static const uint32_t K[64] = {
    0x428a2f98, 0x71374491, 0xb5c0fbcf, 0xe9b5dba5, 0x3956c25b, 0x59f111f1, 0x923f82a4,
    0xab1c5ed5, 0xd807aa98, 0x12835b01, 0x243185be, 0x550c7dc3, 0x72be5d74, 0x80deb1fe,
    0x9bdc06a7, 0xc19bf174, 0xe49b69c1, 0xefbe4786, 0x0fc19dc6, 0x240ca1cc, 0x2de92c6f,
    0x4a7484aa, 0x5cb0a9dc, 0x76f988da, 0x983e5152, 0xa831c66d, 0xb00327c8, 0xbf597fc7,
    0xc6e00bf3, 0xd5a79147, 0x06ca6351, 0x14292967, 0x27b70a85, 0x2e1b2138, 0x4d2c6dfc,
    0x53380d13, 0x650a7354, 0x766a0abb, 0x81c2c92e, 0x92722c85, 0xa2bfe8a1, 0xa81a664b,
    0xc24b8b70, 0xc76c51a3, 0xd192e819, 0xd6990624, 0xf40e3585, 0x106aa070, 0x19a4c116,
    0x1e376c08, 0x2748774c, 0x34b0bcb5, 0x391c0cb3, 0x4ed8aa4a, 0x5b9cca4f, 0x682e6ff3,
    0x748f82ee, 0x78a5636f, 0x84c87814, 0x8cc70208, 0x90befffa, 0xa4506ceb, 0xbef9a3f7,
    0xc67178f2};

/* the initial hash value: fractional parts of the square roots of the first 8 primes
   (5.3.3) */
static const uint32_t H0[8] = {0x6a09e667, 0xbb67ae85, 0x3c6ef372, 0xa54ff53a,
                               0x510e527f, 0x9b05688c, 0x1f83d9ab, 0x5be0cd19};

static uint32_t rotr(uint32_t x, int n) { return (x >> n) | (x << (32 - n)); }

/* one 512-bit block (6.2.2: message schedule, eight working variables, 64 rounds) */
static void compress(uint32_t h[8], const uint8_t *blk)
{
    uint32_t w[64], v[8];
    for (int t = 0; t < 16; t++) {
        const uint8_t *q = blk + (size_t)4 * (size_t)t;
        w[t] = (uint32_t)q[0] << 24 | (uint32_t)q[1] << 16 | (uint32_t)q[2] << 8 | q[3];
    }
    for (int t = 16; t < 64; t++) {
        uint32_t s0 = rotr(w[t - 15], 7) ^ rotr(w[t - 15], 18) ^ (w[t - 15] >> 3);
        uint32_t s1 = rotr(w[t - 2], 17) ^ rotr(w[t - 2], 19) ^ (w[t - 2] >> 10);
        w[t] = s1 + w[t - 7] + s0 + w[t - 16];
    }
    for (int i = 0; i < 8; i++)
        v[i] = h[i];
    for (int t = 0; t < 64; t++) {
        uint32_t e = v[4], a = v[0];
        uint32_t t1 = v[7] + (rotr(e, 6) ^ rotr(e, 11) ^ rotr(e, 25)) + ((e & v[5]) ^ (~e & v[6])) +
                      K[t] + w[t];
        uint32_t t2 = (rotr(a, 2) ^ rotr(a, 13) ^ rotr(a, 22)) +
                      ((a & v[1]) ^ (a & v[2]) ^ (v[1] & v[2]));
        for (int i = 7; i > 0; i--)
            v[i] = v[i - 1];
        v[4] += t1, v[0] = t1 + t2;
    }
    for (int i = 0; i < 8; i++)
        h[i] += v[i];
}

void link_sha256_init(link_sha256 *s)
{
    for (int i = 0; i < 8; i++)
        s->h[i] = H0[i];
    s->len = 0;
}

void link_sha256_update(link_sha256 *s, const uint8_t *p, size_t n)
{
    while (n--) {
        s->buf[s->len++ % LINK_SHA256_BLOCK] = *p++;
        if (s->len % LINK_SHA256_BLOCK == 0)
            compress(s->h, s->buf);
    }
}

/* padding (5.1.1): a 1 bit, zeros to 448 mod 512, the message length in bits */
void link_sha256_final(link_sha256 *s, uint8_t out[LINK_SHA256_LEN])
{
    uint64_t bits = s->len * 8;
    uint8_t one = 0x80, zero = 0, len[8];
    link_sha256_update(s, &one, 1);
    while (s->len % LINK_SHA256_BLOCK != 56)
        link_sha256_update(s, &zero, 1);
    for (int i = 0; i < 8; i++)
        len[i] = (uint8_t)(bits >> (56 - 8 * i));
    link_sha256_update(s, len, 8);
    for (int i = 0; i < 32; i++)
        out[i] = (uint8_t)(s->h[i / 4] >> (24 - 8 * (i % 4)));
}

/* H((K ^ opad) || H((K ^ ipad) || text)) with K zero-padded to the block (RFC 2104) */
void link_hmac_sha256(const uint8_t *key, size_t klen, const uint8_t *msg, size_t n,
                      uint8_t tag[LINK_SHA256_LEN])
{
    uint8_t k[LINK_SHA256_BLOCK] = {0}, pad[LINK_SHA256_BLOCK], inner[LINK_SHA256_LEN];
    link_sha256 s;
    if (klen > LINK_SHA256_BLOCK) {
        link_sha256_init(&s);
        link_sha256_update(&s, key, klen);
        link_sha256_final(&s, k);
    } else {
        for (size_t i = 0; i < klen; i++)
            k[i] = key[i];
    }
    for (int i = 0; i < LINK_SHA256_BLOCK; i++)
        pad[i] = k[i] ^ 0x36;
    link_sha256_init(&s);
    link_sha256_update(&s, pad, LINK_SHA256_BLOCK);
    link_sha256_update(&s, msg, n);
    link_sha256_final(&s, inner);
    for (int i = 0; i < LINK_SHA256_BLOCK; i++)
        pad[i] = k[i] ^ 0x5c;
    link_sha256_init(&s);
    link_sha256_update(&s, pad, LINK_SHA256_BLOCK);
    link_sha256_update(&s, inner, LINK_SHA256_LEN);
    link_sha256_final(&s, tag);
}
