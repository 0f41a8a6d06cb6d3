/* test_link.c - tests of the controller link's pieces that need no network: the wire
 * codec (ports/common/link_wire.c) against the standard CRC-32 check value and every kind
 * of bad datagram, the replay log (tools/modrt/mrlog.c) round trip and its refusals of
 * corrupt, truncated and foreign files with the byte they name, rt_link_apply's effect on
 * the import block, the runtime's check of a link, and snapshots: a run restored from a
 * snapshot continues bit-identically. */
#define _POSIX_C_SOURCE 200809L
#include <arpa/inet.h>
#include <stdio.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <string.h>
#include <unistd.h>

#include "common/link_hmac.h"
#include "common/link_wire.h"
#include "fingerprint.h"
#include "link.h"
#include "models.h"
#include "mrlog.h"
#include "testutil.h"
#include "rt_sim.h" /* white box: reads rt_sim's parts (plan, state, work) */

extern const rt_scene mdl_scene_pi_link, mdl_scene_pi_loop;

#define RUN 0x0123456789abcdefull /* the run nonce of the test packets */

static size_t good_packet(uint8_t *buf, uint32_t seq)
{
    link_packet p = {.type = LINK_TYPE_IMPORTS, .n = 1, .id = mdl_scene_pi_link.link->id,
                     .seq = seq, .tick = 10, .run = RUN, .v = {0.25}};
    strcpy(p.name, "pi_link");
    return link_encode(&p, NULL, buf, LINK_MAX_PACKET);
}

static link_wire_error decode_as(const uint8_t *b, size_t n, uint16_t nval, const link_key *k,
                                 link_packet *p)
{
    link_expect x = {.type = LINK_TYPE_IMPORTS, .name = "pi_link",
                     .id = mdl_scene_pi_link.link->id, .n = nval, .check_run = 1, .run = RUN,
                     .key = k};
    return link_decode(b, n, &x, p);
}

static link_wire_error decode(const uint8_t *b, size_t n, link_packet *p)
{
    return decode_as(b, n, 1, NULL, p);
}

/* re-seals a modified packet so that only the intended field is wrong */
static void reseal(uint8_t *b, size_t n)
{
    uint32_t c = link_crc32(0, b, n - 4);
    for (int i = 0; i < 4; i++)
        b[n - 4 + i] = (uint8_t)(c >> (8 * i));
}

static void test_codec(void)
{
    /* the CRC-32 check value of the standard (IEEE 802.3, zlib): "123456789" */
    TH_CHECK(link_crc32(0, (const uint8_t *)"123456789", 9) == 0xCBF43926u);
    uint8_t b[LINK_MAX_PACKET + 8], t[LINK_MAX_PACKET + 8];
    link_packet p;
    size_t n = good_packet(b, 7);
    TH_CHECK(n == LINK_SIZE(1) && n == 60);
    TH_CHECK(decode(b, n, &p) == LINK_OK && p.seq == 7 && p.tick == 10 && p.run == RUN &&
             p.v[0] == 0.25);
    /* the layout of docs/link.md, byte by byte where it matters */
    TH_CHECK(b[4] == 2 && b[5] == 2 && b[6] == 0 && b[7] == 1 && link_get_le(b + 40, 8) == RUN);
    TH_CHECK(link_get_le(b + 48, 8) == link_bits_of(0.25));
    TH_CHECK(decode(b, n - 1, &p) == LINK_E_SIZE); /* truncated */
    memcpy(t, b, n), t[n] = 0;
    TH_CHECK(decode(t, n + 1, &p) == LINK_E_SIZE); /* a byte too many */
    TH_CHECK(decode(b, LINK_MAX_PACKET + 1, &p) == LINK_E_SIZE); /* oversized */
    memcpy(t, b, n), t[0] = 'X';
    TH_CHECK(decode(t, n, &p) == LINK_E_MAGIC);
    memcpy(t, b, n), t[4] = 1, reseal(t, n);
    TH_CHECK(decode(t, n, &p) == LINK_E_VERSION);
    memcpy(t, b, n), t[6] = 4, reseal(t, n); /* an unknown flag */
    TH_CHECK(decode(t, n, &p) == LINK_E_VERSION);
    memcpy(t, b, n), t[5] = LINK_TYPE_EXPORTS, reseal(t, n);
    TH_CHECK(decode(t, n, &p) == LINK_E_TYPE);
    memcpy(t, b, n), t[53] ^= 1; /* a value bit, CRC not resealed */
    TH_CHECK(decode(t, n, &p) == LINK_E_CRC);
    memcpy(t, b, n), t[8] = 'q', reseal(t, n); /* scene name */
    TH_CHECK(decode(t, n, &p) == LINK_E_SCENE);
    memcpy(t, b, n), t[24] ^= 1, reseal(t, n); /* link id */
    TH_CHECK(decode(t, n, &p) == LINK_E_SCENE);
    memcpy(t, b, n), t[41] ^= 1, reseal(t, n); /* another run's nonce */
    TH_CHECK(decode(t, n, &p) == LINK_E_RUN);
    TH_CHECK(decode_as(b, n, 2, NULL, &p) == LINK_E_COUNT);
    link_packet q = {.type = LINK_TYPE_IMPORTS, .n = 1, .id = mdl_scene_pi_link.link->id,
                     .run = RUN, .v = {0.0 / 0.0}};
    strcpy(q.name, "pi_link");
    n = link_encode(&q, NULL, t, sizeof t);
    TH_CHECK(decode(t, n, &p) == LINK_E_VALUE);
    q.n = LINK_MAX_VALUES + 1;
    TH_CHECK(link_encode(&q, NULL, t, sizeof t) == 0);
}

static void hex(const char *h, uint8_t *out)
{
    for (int i = 0; h[2 * i]; i++) {
        unsigned v;
        sscanf(h + 2 * i, "%2x", &v);
        out[i] = (uint8_t)v;
    }
}

static int digest_is(const uint8_t *d, const char *want)
{
    uint8_t w[LINK_SHA256_LEN];
    hex(want, w);
    return memcmp(d, w, LINK_SHA256_LEN) == 0;
}

/* SHA-256 against FIPS 180-4's examples (one block, two blocks, a million 'a'), HMAC
   against RFC 4231's test cases 1, 2 and 6 (a key longer than a block) */
static void test_hmac(void)
{
    uint8_t d[LINK_SHA256_LEN], key[131];
    link_sha256 s;
    static const char *const two = "abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq";
    link_sha256_init(&s), link_sha256_update(&s, (const uint8_t *)"abc", 3);
    link_sha256_final(&s, d);
    TH_CHECK(digest_is(d, "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad"));
    link_sha256_init(&s), link_sha256_update(&s, (const uint8_t *)two, strlen(two));
    link_sha256_final(&s, d);
    TH_CHECK(digest_is(d, "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1"));
    link_sha256_init(&s);
    for (int i = 0; i < 1000000; i++)
        link_sha256_update(&s, (const uint8_t *)"a", 1);
    link_sha256_final(&s, d);
    TH_CHECK(digest_is(d, "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0"));
    memset(key, 0x0b, 20);
    link_hmac_sha256(key, 20, (const uint8_t *)"Hi There", 8, d);
    TH_CHECK(digest_is(d, "b0344c61d8db38535ca8afceaf0bf12b881dc200c9833da726e9376c2e32cff7"));
    link_hmac_sha256((const uint8_t *)"Jefe", 4, (const uint8_t *)"what do ya want for nothing?",
                     28, d);
    TH_CHECK(digest_is(d, "5bdcc146bf60754e6a042426089575c75a003f089d2739839dec58b964ec3843"));
    static const char *const big = "Test Using Larger Than Block-Size Key - Hash Key First";
    memset(key, 0xaa, 131);
    link_hmac_sha256(key, 131, (const uint8_t *)big, strlen(big), d);
    TH_CHECK(digest_is(d, "60e431591ee0b67f0d8a26aacbf5b77f8e0bc6213728c5140546040f0ee37f54"));
}

/* the authenticated mode: a tag under the key is accepted; no tag, a tag where none is
   expected, another key, a flipped tag or body bit (CRC resealed) are refused as auth */
static void test_auth(void)
{
    link_key k = {.k = "shared secret", .len = 13}, other = {.k = "shared secreT", .len = 13};
    link_packet p = {.type = LINK_TYPE_IMPORTS, .n = 1, .id = mdl_scene_pi_link.link->id,
                     .seq = 3, .tick = 20, .run = RUN, .v = {-1.5}}, q;
    uint8_t b[LINK_MAX_PACKET], t[LINK_MAX_PACKET], plain[LINK_MAX_PACKET];
    strcpy(p.name, "pi_link");
    size_t n = link_encode(&p, &k, b, sizeof b), m = link_encode(&p, NULL, plain, sizeof plain);
    TH_CHECK(n == LINK_SIZE(1) + LINK_TAG_LEN && b[6] == LINK_FLAG_AUTH);
    /* the tag is HMAC-SHA-256 of the datagram up to its CRC */
    uint8_t want[LINK_TAG_LEN];
    link_hmac_sha256(k.k, k.len, b, n - LINK_TAG_LEN, want);
    TH_CHECK(memcmp(want, b + n - LINK_TAG_LEN, LINK_TAG_LEN) == 0);
    TH_CHECK(decode_as(b, n, 1, &k, &q) == LINK_OK && q.v[0] == -1.5 && q.seq == 3);
    TH_CHECK(decode_as(plain, m, 1, &k, &q) == LINK_E_AUTH);  /* no tag */
    TH_CHECK(decode_as(b, n, 1, NULL, &q) == LINK_E_AUTH);    /* a tag, no key */
    TH_CHECK(decode_as(b, n, 1, &other, &q) == LINK_E_AUTH);  /* another key */
    memcpy(t, b, n), t[n - 1] ^= 0x80;
    TH_CHECK(decode_as(t, n, 1, &k, &q) == LINK_E_AUTH);
    memcpy(t, b, n), t[50] ^= 1, reseal(t, n - LINK_TAG_LEN); /* forged value, CRC fixed */
    TH_CHECK(decode_as(t, n, 1, &k, &q) == LINK_E_AUTH);
}

static const char *tmp_path(const char *name)
{
    static char p[256];
    snprintf(p, sizeof p, "build/test-link-%s.mrl", name);
    return p;
}

/* a log of nrec records (ticks 0, 10, ...) whose run ended as `ended` at tick `last` */
static void write_log_end(const char *path, uint16_t nrec, mrl_end ended, uint64_t last)
{
    char err[256];
    mrl_header h = {.id = 0x1234, .nimp = 2, .real_size = sizeof(real_t), .t_end = 3,
                    .every = 1, .nsets = 1, .scene_fp = 0x8877665544332211ull, .run = RUN};
    strcpy(h.scene, "pi_link");
    strcpy(h.sets[0], "Plant.K=2");
    mrl_writer *w = mrl_create(path, &h, err, sizeof err);
    TH_CHECK(w != NULL);
    if (!w)
        return;
    for (uint16_t i = 0; i < nrec; i++) {
        real_t v[2] = {(real_t)i, (real_t)(0.5 * i)};
        mrl_append(w, 10u * i, v);
    }
    TH_CHECK(mrl_finish(w, ended, last, err, sizeof err) == 0);
}

static void write_log(const char *path, uint16_t nrec)
{
    write_log_end(path, nrec, MRL_END_DONE, 3000);
}

static long file_size(const char *path)
{
    FILE *f = fopen(path, "rb");
    long n = -1;
    if (f && fseek(f, 0, SEEK_END) == 0)
        n = ftell(f);
    if (f)
        fclose(f);
    return n;
}

static void patch(const char *path, long at, uint8_t xor_with)
{
    FILE *f = fopen(path, "r+b");
    int c;
    if (!f)
        return;
    fseek(f, at, SEEK_SET);
    c = fgetc(f);
    fseek(f, at, SEEK_SET);
    fputc(c ^ xor_with, f);
    fclose(f);
}

static int refused(const char *path, const char *what)
{
    mrl_header h;
    char err[512];
    int r = mrl_open(path, &h, err, sizeof err);
    mrl_close();
    th_note(err, 0);
    return r != 0 && strstr(err, what) != NULL && strstr(err, "at byte ") != NULL;
}

static void test_log(void)
{
    const char *p = tmp_path("ok");
    mrl_header h;
    char err[512];
    write_log(p, 3);
    TH_CHECK(mrl_open(p, &h, err, sizeof err) == 0);
    TH_CHECK(h.id == 0x1234 && h.nimp == 2 && h.nsets == 1 && strcmp(h.sets[0], "Plant.K=2") == 0);
    TH_CHECK(strcmp(h.scene, "pi_link") == 0 && h.t_end == 3 && h.every == 1);
    TH_CHECK(h.version == 3 && h.scene_fp == 0x8877665544332211ull && h.run == RUN);
    TH_CHECK(h.ended == MRL_END_DONE && h.last_tick == 3000);
    uint64_t tick;
    real_t v[LINK_MAX_VALUES];
    int n = 0;
    while (mrl_next(&tick, v))
        TH_CHECK(tick == 10u * (unsigned)n && v[1] == (real_t)(0.5 * n)), n++;
    TH_CHECK(n == 3);
    mrl_close();
    long size = file_size(p), hdr = size - 28 - 3 * (8 + 16 + 4);
    /* a flipped bit in record 1, in the header, a cut file, data after the end */
    write_log(p, 3);
    patch(p, hdr + 28 + 9, 0x10);
    TH_CHECK(refused(p, "record CRC mismatch"));
    write_log(p, 3);
    patch(p, 40, 0x01);
    TH_CHECK(refused(p, "header CRC mismatch"));
    write_log(p, 3);
    TH_CHECK(truncate(p, size - 20) == 0 && refused(p, "truncated"));
    write_log(p, 3);
    FILE *f = fopen(p, "ab");
    if (f)
        fputc(0, f), fclose(f);
    TH_CHECK(refused(p, "after the end marker"));
    f = fopen(p, "wb");
    if (f)
        fputs("t,Ref.y\n0,0\n", f), fclose(f);
    TH_CHECK(refused(p, "not a modrt replay log"));
    /* the end marker: how the run ended and its last tick, read back; a record past that
       tick is one a replay would never apply; an unknown way to end or a flipped bit in
       the tick are refused */
    write_log_end(p, 3, MRL_END_SIGINT, 25);
    TH_CHECK(mrl_open(p, &h, err, sizeof err) == 0 && h.ended == MRL_END_SIGINT &&
             h.last_tick == 25);
    mrl_close();
    TH_CHECK(strcmp(mrl_end_name(MRL_END_SIGTERM), "SIGTERM") == 0);
    write_log_end(p, 3, MRL_END_LINK, 19);
    TH_CHECK(mrl_open(p, &h, err, sizeof err) == 0 && mrl_check_end(3000, err, sizeof err) == 0);
    TH_CHECK(mrl_check_schedule(3000, 10, 0, err, sizeof err) != 0 &&
             th_has(err, "1 record(s) a replay would never apply, the first at tick 20 (past "
                         "the end; the run ends at tick 19"));
    mrl_close();
    write_log_end(p, 3, MRL_END_DONE, 2999); /* ran to its end: tick 3000 */
    TH_CHECK(mrl_open(p, &h, err, sizeof err) == 0 && mrl_check_end(3000, err, sizeof err) != 0 &&
             th_has(err, "the end marker says the run ended at tick 2999 (end time), but the "
                         "scene's run ends at tick 3000"));
    mrl_close();
    write_log_end(p, 3, MRL_END_SIGINT, 3001);
    TH_CHECK(mrl_open(p, &h, err, sizeof err) == 0 && mrl_check_end(3000, err, sizeof err) != 0);
    mrl_close();
    write_log_end(p, 3, MRL_END_COUNT_, 30);
    TH_CHECK(refused(p, "unknown end of the run in the end marker"));
    write_log_end(p, 3, MRL_END_DONE, 30);
    patch(p, size - 28 + 12, 0x01);
    TH_CHECK(refused(p, "end marker CRC mismatch"));
}

static void test_apply_and_check(void)
{
    if (!tu_init(&mdl_scene_pi_link))
        return;
    const rt_link *l = mdl_scene_pi_link.link;
    TH_CHECK(l->nexp == 2 && l->nimp == 1 && l->period == 10);
    real_t v[1] = {(real_t)0.75};
    rt_link_apply(&mdl_scene_pi_link, &tu_sim, v);
    rt_tick(&mdl_scene_pi_link, &tu_sim);
    TH_CHECK(rt_rec_value(&mdl_scene_pi_link, &tu_sim, 1) == (real_t)0.75); /* Ctrl.c held */
    /* the plant's input is the applied command: T y' = K u - y from 0, y(h) = K u (1 - e^-h/T) */
    TH_NEAR(rt_rec_value(&mdl_scene_pi_link, &tu_sim, 2), 2.99700199900033e-3, /* 1.5 (1 - e^-0.002) */
            RT_REAL_IS_FLOAT ? 1e-9 : 1e-13);
    TH_CHECK(rt_link_due(&mdl_scene_pi_link, &tu_sim) == 0);
    /* a link naming a block that is not its import block is refused by rt_init */
    rt_link bad = *l;
    bad.block = 0; /* Ref: an output block */
    rt_scene sc = mdl_scene_pi_link;
    sc.link = &bad;
    TH_CHECK(rt_init(&sc, &tu_sim) == RT_E_SCENE && th_has(rt_error_text(&tu_sim), "import block"));
    bad = *l, bad.period = 0;
    TH_CHECK(rt_init(&sc, &tu_sim) == RT_E_SCENE);
}

/* snapshot at 1.2 s, run to the end; restore, run again: the same hash as the straight run */
static void test_snapshot(void)
{
    static rt_state snap;
    const rt_scene *sc = &mdl_scene_pi_loop;
    if (!tu_init(sc))
        return;
    while (rt_tick(sc, &tu_sim) != RT_E_DONE)
        rt_record(sc, &tu_sim, 0);
    rt_record(sc, &tu_sim, 0);
    uint64_t straight = rt_trace_hash(&tu_sim);
    if (!tu_init(sc))
        return;
    while (rt_ticks_done(&tu_sim) < 1200) {
        rt_tick(sc, &tu_sim);
        rt_record(sc, &tu_sim, 0);
    }
    rt_snapshot(&tu_sim, &snap);
    while (rt_tick(sc, &tu_sim) != RT_E_DONE)
        rt_record(sc, &tu_sim, 0);
    rt_record(sc, &tu_sim, 0);
    TH_CHECK(rt_trace_hash(&tu_sim) == straight);
    if (!tu_init(sc)) /* a fresh simulator of the same scene, then the snapshot */
        return;
    TH_CHECK(rt_restore(&tu_sim, &snap) == RT_OK);
    TH_CHECK(rt_ticks_done(&tu_sim) == 1200);
    while (rt_tick(sc, &tu_sim) != RT_E_DONE)
        rt_record(sc, &tu_sim, 0);
    rt_record(sc, &tu_sim, 0);
    TH_CHECK(rt_trace_hash(&tu_sim) == straight);
}

/* a real-time exchange tick that cannot take the mailbox (its trylock fails: injected)
   counts the outstanding request missing and applies the policy; before, it did neither.
   The controller is this test, on a loopback socket it owns (bounded waits). */
static void test_busy_mailbox(void)
{
    const rt_scene *sc = &mdl_scene_pi_link;
    int fd = socket(AF_INET, SOCK_DGRAM, 0);
    struct sockaddr_in me = {.sin_family = AF_INET, .sin_addr.s_addr = htonl(INADDR_LOOPBACK)}, peer;
    socklen_t len = sizeof me, plen = sizeof peer;
    struct timeval tv = {2, 0};
    char spec[64], err[256];
    if (!TH_CHECK(fd >= 0 && bind(fd, (struct sockaddr *)&me, sizeof me) == 0 &&
                  getsockname(fd, (struct sockaddr *)&me, &len) == 0) || !tu_init(sc))
        return;
    setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);
    snprintf(spec, sizeof spec, "udp:127.0.0.1:%d", ntohs(me.sin_port));
    link_opts o = {.realtime = 1, .timeout_s = 1, .run = RUN};
    if (!TH_CHECK(link_open(spec, sc, &o, NULL, err, sizeof err) == 0))
        return;
    uint8_t b[LINK_MAX_PACKET];
    TH_CHECK(link_exchange(NULL, sc, &tu_sim) == 0); /* tick 0: request 1 */
    ssize_t n = recvfrom(fd, b, sizeof b, 0, (struct sockaddr *)&peer, &plen);
    link_packet req, ans = {.type = LINK_TYPE_IMPORTS, .n = 1, .id = sc->link->id, .v = {5}};
    link_expect x = {.type = LINK_TYPE_EXPORTS, .name = "pi_link", .id = sc->link->id, .n = 2};
    TH_CHECK(n > 0 && link_decode(b, (size_t)n, &x, &req) == LINK_OK && req.seq == 1 &&
             req.run == RUN && req.tick == 0);
    strcpy(ans.name, "pi_link");
    ans.seq = req.seq, ans.tick = req.tick, ans.run = req.run;
    size_t m = link_encode(&ans, NULL, b, sizeof b);
    sendto(fd, b, m, 0, (struct sockaddr *)&peer, plen);
    link_test_busy(1);
    for (uint64_t k = 1; k <= sc->link->period; k++) {
        tu_sim.state.tick = k;
        TH_CHECK(link_exchange(NULL, sc, &tu_sim) == 0);
    }
    link_test_busy(0);
    link_counts c;
    link_close(&c);
    close(fd);
    TH_CHECK(c.missing == 1 && c.applied == 0 && c.sent == 2 && c.bad == 0);
    TH_CHECK(link_faulty(&c));
    /* the policy (hold): Ctrl.c keeps its default 0 */
    TH_CHECK(rt_rec_value(sc, &tu_sim, 1) == 0);
}

/* the scene fingerprint of the replay log: equal for a copy, different after a change of
   one parameter value, an initial state, the end time, a set's method or the link */
static void test_fingerprint(void)
{
    static rt_block blocks[RT_MAX_BLOCKS];
    static real_t p[16];
    const rt_scene *base = &mdl_scene_pi_link;
    rt_scene sc = *base;
    uint64_t f0 = fp_scene(base);
    TH_CHECK(fp_scene(&sc) == f0);
    int k = rt_block_index(base, "Plant");
    if (!TH_CHECK(k >= 0 && base->nblocks <= RT_MAX_BLOCKS && base->blocks[k].kind->np <= 16))
        return;
    memcpy(blocks, base->blocks, base->nblocks * sizeof *blocks);
    const rt_kind *kd = blocks[k].kind;
    for (uint16_t i = 0; i < kd->np; i++)
        p[i] = blocks[k].p ? blocks[k].p[i] : kd->p_default ? kd->p_default[i] : 0;
    blocks[k].p = p, sc.blocks = blocks;
    TH_CHECK(fp_scene(&sc) == f0); /* the same values, spelled out */
    p[0] = p[0] + (real_t)0.5;
    TH_CHECK(fp_scene(&sc) != f0);
    sc = *base, sc.t_end = base->t_end + base->dt;
    TH_CHECK(fp_scene(&sc) != f0);
    rt_set set = base->sets[0];
    set.ratio = 2;
    sc = *base, sc.sets = &set;
    TH_CHECK(fp_scene(&sc) != f0);
    rt_link l = *base->link;
    l.period = 20;
    sc = *base, sc.link = &l;
    TH_CHECK(fp_scene(&sc) != f0);
    TH_CHECK(fp_scene(&mdl_scene_pi_loop) != f0);
}

/* a version 1 log (before the fingerprint and the nonce), written byte by byte from its
   layout (mrlog.c), is still read: its header fields and its one record */
static void test_log_v1(void)
{
    uint8_t b[400] = {0};
    const char *p = tmp_path("v1");
    size_t hs = 32 + 256 + 4, n = 0;
    memcpy(b, "MRTR", 4);
    link_put_le(b + 4, 1, 2), link_put_le(b + 6, hs, 2), link_put_le(b + 8, 0xabcd, 4);
    link_put_le(b + 12, 1, 2), b[14] = (uint8_t)sizeof(real_t);
    link_put_le(b + 16, link_bits_of(0.5), 8), link_put_le(b + 24, 2, 4);
    memcpy(b + 32, "pi_link", 7);
    link_put_le(b + hs - 4, link_crc32(0, b, hs - 4), 4);
    n = hs;
    link_put_le(b + n, 40, 8), link_put_le(b + n + 8, link_bits_of(-0.25), 8);
    link_put_le(b + n + 16, link_crc32(0, b + n, 16), 4);
    n += 20;
    memcpy(b + n, "MRTE", 4), link_put_le(b + n + 4, 1, 8);
    link_put_le(b + n + 12, link_crc32(0, b + n, 12), 4);
    n += 16;
    FILE *f = fopen(p, "wb");
    if (!TH_CHECK(f != NULL))
        return;
    fwrite(b, 1, n, f), fclose(f);
    mrl_header h;
    char err[512];
    uint64_t tick;
    real_t v[LINK_MAX_VALUES];
    TH_CHECK(mrl_open(p, &h, err, sizeof err) == 0);
    TH_CHECK(h.version == 1 && h.id == 0xabcd && h.nimp == 1 && h.t_end == 0.5 && h.every == 2);
    TH_CHECK(h.scene_fp == 0 && h.run == 0 && strcmp(h.scene, "pi_link") == 0);
    TH_CHECK(h.ended == MRL_END_UNKNOWN && h.last_tick == 0); /* it does not say */
    TH_CHECK(mrl_next(&tick, v) == 1 && tick == 40 && v[0] == (real_t)-0.25);
    TH_CHECK(mrl_next(&tick, v) == 0);
    mrl_close();
}

const th_test th_link_tests[] = {
    {"link_codec", test_codec},
    {"link_hmac", test_hmac},
    {"link_auth", test_auth},
    {"link_log", test_log},
    {"link_log_v1", test_log_v1},
    {"link_apply_check", test_apply_and_check},
    {"link_snapshot", test_snapshot},
    {"link_busy_mailbox", test_busy_mailbox},
    {"link_fingerprint", test_fingerprint},
    {0, 0},
};
