/* test_link.c - tests of the controller link's pieces that need no network: the wire
 * codec (ports/common/link_wire.c) against the standard CRC-32 check value and every kind
 * of bad datagram, the replay log (tools/modrt/mrlog.c) round trip and its refusals of
 * corrupt, truncated and foreign files with the byte they name, rt_link_apply's effect on
 * the import block, the runtime's check of a link, and snapshots: a run restored from a
 * snapshot continues bit-identically. */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "common/link_wire.h"
#include "models.h"
#include "mrlog.h"
#include "testutil.h"

extern const rt_scene mdl_scene_pi_link, mdl_scene_pi_loop;

static size_t good_packet(uint8_t *buf, uint32_t seq)
{
    link_packet p = {.type = LINK_TYPE_IMPORTS, .n = 1, .id = mdl_scene_pi_link.link->id,
                     .seq = seq, .tick = 10, .v = {0.25}};
    strcpy(p.name, "pi_link");
    return link_encode(&p, buf, LINK_MAX_PACKET);
}

static link_wire_error decode(const uint8_t *b, size_t n, link_packet *p)
{
    return link_decode(b, n, LINK_TYPE_IMPORTS, "pi_link", mdl_scene_pi_link.link->id, 1, p);
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
    TH_CHECK(n == LINK_SIZE(1) && n == 52);
    TH_CHECK(decode(b, n, &p) == LINK_OK && p.seq == 7 && p.tick == 10 && p.v[0] == 0.25);
    TH_CHECK(decode(b, n - 1, &p) == LINK_E_SIZE); /* truncated */
    memcpy(t, b, n), t[n] = 0;
    TH_CHECK(decode(t, n + 1, &p) == LINK_E_SIZE); /* a byte too many */
    TH_CHECK(decode(b, LINK_MAX_PACKET + 1, &p) == LINK_E_SIZE); /* oversized */
    memcpy(t, b, n), t[0] = 'X';
    TH_CHECK(decode(t, n, &p) == LINK_E_MAGIC);
    memcpy(t, b, n), t[4] = 2, reseal(t, n);
    TH_CHECK(decode(t, n, &p) == LINK_E_VERSION);
    memcpy(t, b, n), t[5] = LINK_TYPE_EXPORTS, reseal(t, n);
    TH_CHECK(decode(t, n, &p) == LINK_E_TYPE);
    memcpy(t, b, n), t[45] ^= 1; /* a value bit, CRC not resealed */
    TH_CHECK(decode(t, n, &p) == LINK_E_CRC);
    memcpy(t, b, n), t[8] = 'q', reseal(t, n); /* scene name */
    TH_CHECK(decode(t, n, &p) == LINK_E_SCENE);
    memcpy(t, b, n), t[24] ^= 1, reseal(t, n); /* link id */
    TH_CHECK(decode(t, n, &p) == LINK_E_SCENE);
    TH_CHECK(link_decode(b, n, LINK_TYPE_IMPORTS, "pi_link", mdl_scene_pi_link.link->id, 2, &p) ==
             LINK_E_COUNT);
    link_packet q = {.type = LINK_TYPE_IMPORTS, .n = 1, .id = mdl_scene_pi_link.link->id,
                     .v = {0.0 / 0.0}};
    strcpy(q.name, "pi_link");
    n = link_encode(&q, t, sizeof t);
    TH_CHECK(decode(t, n, &p) == LINK_E_VALUE);
    q.n = LINK_MAX_VALUES + 1;
    TH_CHECK(link_encode(&q, t, sizeof t) == 0);
}

static const char *tmp_path(const char *name)
{
    static char p[256];
    snprintf(p, sizeof p, "build/test-link-%s.mrl", name);
    return p;
}

static void write_log(const char *path, uint16_t nrec)
{
    char err[256];
    mrl_header h = {.id = 0x1234, .nimp = 2, .real_size = sizeof(real_t), .t_end = 3,
                    .every = 1, .nsets = 1};
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
    TH_CHECK(mrl_finish(w, err, sizeof err) == 0);
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
    uint64_t tick;
    real_t v[LINK_MAX_VALUES];
    int n = 0;
    while (mrl_next(&tick, v))
        TH_CHECK(tick == 10u * (unsigned)n && v[1] == (real_t)(0.5 * n)), n++;
    TH_CHECK(n == 3);
    mrl_close();
    long size = file_size(p), hdr = size - 16 - 3 * (8 + 16 + 4);
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
    uint64_t straight = tu_sim.state.hash;
    if (!tu_init(sc))
        return;
    while (tu_sim.state.tick < 1200) {
        rt_tick(sc, &tu_sim);
        rt_record(sc, &tu_sim, 0);
    }
    rt_snapshot(&tu_sim, &snap);
    while (rt_tick(sc, &tu_sim) != RT_E_DONE)
        rt_record(sc, &tu_sim, 0);
    rt_record(sc, &tu_sim, 0);
    TH_CHECK(tu_sim.state.hash == straight);
    if (!tu_init(sc)) /* a fresh simulator of the same scene, then the snapshot */
        return;
    TH_CHECK(rt_restore(&tu_sim, &snap) == RT_OK);
    TH_CHECK(tu_sim.state.tick == 1200);
    while (rt_tick(sc, &tu_sim) != RT_E_DONE)
        rt_record(sc, &tu_sim, 0);
    rt_record(sc, &tu_sim, 0);
    TH_CHECK(tu_sim.state.hash == straight);
}

const th_test th_link_tests[] = {
    {"link_codec", test_codec},
    {"link_log", test_log},
    {"link_apply_check", test_apply_and_check},
    {"link_snapshot", test_snapshot},
    {0, 0},
};
