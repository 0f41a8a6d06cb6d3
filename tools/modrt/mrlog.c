/* mrlog.c - the replay log (format in mrlog.h and docs/link.md): writing during a live
 * run, checking the whole file before a replay, and applying its records at their ticks.
 *
 *   header  "MRTR" u16 version=2 u16 header_size u32 link_id u16 nimp u8 real_size
 *           u8 realtime f64 t_end u32 every u16 nsets u16 0  u64 scene_fingerprint
 *           u64 run_nonce  char scene[256]  nsets x char set[128]
 *           u32 CRC-32 of everything before it
 *           (version 1, still read: without scene_fingerprint and run_nonce)
 *   record  u64 tick  nimp x f64  u32 CRC-32 of the record's tick and values
 *   end     "MRTE" u64 records  u32 CRC-32 of the marker and count
 * little-endian throughout (the CRC is link_crc32, ports/common/link_wire.c). */
#define _XOPEN_SOURCE 700 /* realpath, PATH_MAX */
#include "mrlog.h"

#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "common/link_wire.h"

#define MRL_VERSION 2
#define MRL_FIXED_V1 32 /* header bytes before the scene name, version 1 */
#define MRL_FIXED 48    /* version 2 */
#define MRL_MAX_RECORD (8 + 8 * LINK_MAX_VALUES + 4)

struct mrl_writer {
    FILE *f;
    uint64_t count;
    uint16_t nimp;
    int failed;
};

static mrl_writer writer;

static size_t fixed_size(unsigned version)
{
    return version == 1 ? MRL_FIXED_V1 : MRL_FIXED;
}

static size_t header_size(unsigned version, uint16_t nsets)
{
    return fixed_size(version) + (MRL_SCENE_LEN + 1) + (size_t)nsets * (MRL_SET_LEN + 1) + 4;
}

static size_t encode_header(const mrl_header *h, uint8_t *b)
{
    size_t n = header_size(MRL_VERSION, h->nsets);
    memset(b, 0, n);
    memcpy(b, "MRTR", 4);
    link_put_le(b + 4, MRL_VERSION, 2);
    link_put_le(b + 6, n, 2);
    link_put_le(b + 8, h->id, 4);
    link_put_le(b + 12, h->nimp, 2);
    b[14] = h->real_size, b[15] = h->realtime;
    link_put_le(b + 16, link_bits_of(h->t_end), 8);
    link_put_le(b + 24, h->every, 4);
    link_put_le(b + 28, h->nsets, 2);
    link_put_le(b + 32, h->scene_fp, 8);
    link_put_le(b + 40, h->run, 8);
    memcpy(b + MRL_FIXED, h->scene, strlen(h->scene));
    uint8_t *p = b + MRL_FIXED + MRL_SCENE_LEN + 1;
    for (uint16_t i = 0; i < h->nsets; i++, p += MRL_SET_LEN + 1)
        memcpy(p, h->sets[i], strlen(h->sets[i]));
    link_put_le(b + n - 4, link_crc32(0, b, n - 4), 4);
    return n;
}

mrl_writer *mrl_create(const char *path, const mrl_header *h, char *err, size_t n)
{
    static uint8_t b[MRL_FIXED + MRL_SCENE_LEN + 1 + MRL_MAX_SETS * (MRL_SET_LEN + 1) + 4];
    if (h->nimp > LINK_MAX_VALUES || h->nsets > MRL_MAX_SETS) {
        snprintf(err, n, "%s: too many values or --set options for a replay log", path);
        return NULL;
    }
    writer = (mrl_writer){.nimp = h->nimp};
    if (!(writer.f = fopen(path, "wb"))) {
        snprintf(err, n, "%s: cannot create the replay log: %s", path, strerror(errno));
        return NULL;
    }
    size_t sz = encode_header(h, b);
    if (fwrite(b, 1, sz, writer.f) != sz)
        writer.failed = 1;
    return &writer;
}

int mrl_append(mrl_writer *w, uint64_t tick, const real_t *v)
{
    uint8_t b[MRL_MAX_RECORD];
    size_t n = 8 + 8 * (size_t)w->nimp;
    link_put_le(b, tick, 8);
    for (uint16_t i = 0; i < w->nimp; i++)
        link_put_le(b + 8 + 8 * i, link_bits_of((double)v[i]), 8);
    link_put_le(b + n, link_crc32(0, b, n), 4);
    if (fwrite(b, 1, n + 4, w->f) != n + 4)
        w->failed = 1;
    w->count++;
    return w->failed ? -1 : 0;
}

int mrl_finish(mrl_writer *w, char *err, size_t n)
{
    uint8_t b[16];
    memcpy(b, "MRTE", 4);
    link_put_le(b + 4, w->count, 8);
    link_put_le(b + 12, link_crc32(0, b, 12), 4);
    if (fwrite(b, 1, 16, w->f) != 16)
        w->failed = 1;
    if (fclose(w->f) != 0)
        w->failed = 1;
    if (w->failed)
        snprintf(err, n, "error writing the replay log: %s", strerror(errno));
    return w->failed ? -1 : 0;
}

/* ------------------------------------------------------------------ reading */

static struct {
    FILE *f;
    const char *path;
    uint16_t nimp;
    long first;       /* offset of the first record */
    uint64_t count;   /* records, from the end marker */
    uint64_t next;    /* records read */
    uint64_t tick;    /* the next record's tick (valid when have) */
    real_t v[LINK_MAX_VALUES];
    int have;
} rd;

static int fail(char *err, size_t n, const char *what, long at)
{
    snprintf(err, n, "%s: %s at byte %ld", rd.path, what, at);
    if (rd.f)
        fclose(rd.f), rd.f = NULL;
    return -1;
}

static int read_header(mrl_header *h, char *err, size_t n)
{
    static uint8_t b[MRL_FIXED + MRL_SCENE_LEN + 1 + MRL_MAX_SETS * (MRL_SET_LEN + 1) + 4];
    size_t got = fread(b, 1, MRL_FIXED_V1, rd.f);
    if (got < 4 || memcmp(b, "MRTR", 4) != 0)
        return fail(err, n, "not a modrt replay log (it does not begin with MRTR)", 0);
    if (got != MRL_FIXED_V1)
        return fail(err, n, "truncated header", (long)got);
    h->version = (uint16_t)link_get_le(b + 4, 2);
    if (h->version < 1 || h->version > MRL_VERSION)
        return fail(err, n, "unsupported replay log version", 4);
    size_t fixed = fixed_size(h->version);
    h->nsets = (uint16_t)link_get_le(b + 28, 2);
    size_t sz = link_get_le(b + 6, 2);
    if (h->nsets > MRL_MAX_SETS || sz != header_size(h->version, h->nsets))
        return fail(err, n, "bad header size or --set count", 6);
    if (fread(b + MRL_FIXED_V1, 1, sz - MRL_FIXED_V1, rd.f) != sz - MRL_FIXED_V1)
        return fail(err, n, "truncated header", MRL_FIXED_V1);
    if (link_get_le(b + sz - 4, 4) != link_crc32(0, b, sz - 4))
        return fail(err, n, "header CRC mismatch (corrupt header)", (long)sz - 4);
    h->id = (uint32_t)link_get_le(b + 8, 4);
    h->nimp = (uint16_t)link_get_le(b + 12, 2);
    h->real_size = b[14], h->realtime = b[15];
    h->t_end = link_double_of(link_get_le(b + 16, 8));
    h->every = (uint32_t)link_get_le(b + 24, 4);
    h->scene_fp = h->version >= 2 ? link_get_le(b + 32, 8) : 0;
    h->run = h->version >= 2 ? link_get_le(b + 40, 8) : 0;
    if (h->nimp > LINK_MAX_VALUES || h->every == 0)
        return fail(err, n, "bad value count or --every in the header", 12);
    memcpy(h->scene, b + fixed, MRL_SCENE_LEN + 1);
    h->scene[MRL_SCENE_LEN] = 0;
    for (uint16_t i = 0; i < h->nsets; i++) {
        memcpy(h->sets[i], b + fixed + MRL_SCENE_LEN + 1 + i * (MRL_SET_LEN + 1),
               MRL_SET_LEN + 1);
        h->sets[i][MRL_SET_LEN] = 0;
    }
    rd.first = (long)sz;
    return 0;
}

/* one record at the current position: 1 read, 0 the end marker, -1 an error */
static int read_record(char *err, size_t n, uint64_t prev, int check_order)
{
    uint8_t b[MRL_MAX_RECORD];
    long at = ftell(rd.f);
    size_t rec = 8 + 8 * (size_t)rd.nimp;
    size_t got = fread(b, 1, 4, rd.f);
    if (got == 4 && memcmp(b, "MRTE", 4) == 0) {
        if (fread(b + 4, 1, 12, rd.f) != 12)
            return fail(err, n, "truncated end marker", at);
        if (link_get_le(b + 12, 4) != link_crc32(0, b, 12))
            return fail(err, n, "end marker CRC mismatch", at);
        rd.count = link_get_le(b + 4, 8);
        return 0;
    }
    if (got != 4 || fread(b + 4, 1, rec, rd.f) != rec)
        return fail(err, n, got == 0 ? "truncated: no end marker after the last record"
                                     : "truncated record", at);
    if (link_get_le(b + rec, 4) != link_crc32(0, b, rec))
        return fail(err, n, "record CRC mismatch (corrupt record)", at);
    rd.tick = link_get_le(b, 8);
    if (check_order && rd.next > 0 && rd.tick <= prev)
        return fail(err, n, "record ticks not increasing", at);
    for (uint16_t i = 0; i < rd.nimp; i++) {
        double d = link_double_of(link_get_le(b + 8 + 8 * i, 8));
        if (!(d - d == 0))
            return fail(err, n, "non-finite value in a record", at + 8 + 8 * i);
        rd.v[i] = (real_t)d;
    }
    return 1;
}

int mrl_open(const char *path, mrl_header *h, char *err, size_t n)
{
    rd.path = path, rd.next = 0, rd.have = 0;
    if (!(rd.f = fopen(path, "rb"))) {
        snprintf(err, n, "%s: cannot read the replay log: %s", path, strerror(errno));
        return -1;
    }
    if (read_header(h, err, n) != 0)
        return -1;
    rd.nimp = h->nimp;
    uint64_t prev = 0;
    int r;
    while ((r = read_record(err, n, prev, 1)) == 1)
        prev = rd.tick, rd.next++;
    if (r < 0)
        return -1;
    if (rd.count != rd.next)
        return fail(err, n, "end marker counts another number of records", ftell(rd.f) - 16);
    uint8_t extra;
    if (fread(&extra, 1, 1, rd.f) == 1)
        return fail(err, n, "data after the end marker", ftell(rd.f) - 1);
    fseek(rd.f, rd.first, SEEK_SET);
    rd.next = 0;
    return 0;
}

int mrl_check_schedule(uint64_t last, uint32_t period, int realtime, char *err, size_t n)
{
    uint64_t tick, bad = 0, first = 0;
    long at = 0, first_at = 0;
    real_t v[LINK_MAX_VALUES];
    for (;;) {
        at = ftell(rd.f);
        if (!mrl_next(&tick, v))
            break;
        if (tick > last || (!realtime && period && tick % period != 0)) {
            if (bad++ == 0)
                first = tick, first_at = at;
        }
    }
    fseek(rd.f, rd.first, SEEK_SET);
    rd.next = 0;
    if (bad == 0)
        return 0;
    char what[200];
    snprintf(what, sizeof what, "%llu record(s) a replay would never apply, the first at "
             "tick %llu (%s; the run ends at tick %llu, exchanges every %lu ticks)",
             (unsigned long long)bad, (unsigned long long)first,
             first > last ? "past the end" : "not an exchange tick of a lock-step run",
             (unsigned long long)last, (unsigned long)period);
    return fail(err, n, what, first_at);
}

int mrl_scene_name(const char *scene, char *out, size_t n, char *err, size_t en)
{
    static char abs[PATH_MAX];
    size_t len = strlen(scene);
    if (len > 4 && strcmp(scene + len - 4, ".scn") == 0) {
        if (!realpath(scene, abs)) {
            snprintf(err, en, "%s: %s", scene, strerror(errno));
            return -1;
        }
        scene = abs, len = strlen(abs);
    }
    if (len >= n) {
        snprintf(err, en, "%s: longer than the %u bytes a replay log holds", scene,
                 (unsigned)(n - 1));
        return -1;
    }
    memcpy(out, scene, len + 1);
    return 0;
}

int mrl_next(uint64_t *tick, real_t *v)
{
    char err[8];
    if (!rd.f || rd.next >= rd.count || read_record(err, sizeof err, 0, 0) != 1)
        return 0;
    rd.next++;
    *tick = rd.tick;
    memcpy(v, rd.v, rd.nimp * sizeof *v);
    return 1;
}

void mrl_close(void)
{
    if (rd.f)
        fclose(rd.f), rd.f = NULL;
}

int mrl_replay_exchange(void *ctx, const rt_scene *sc, rt_sim *sim)
{
    static uint64_t tick;
    static real_t v[LINK_MAX_VALUES];
    (void)ctx;
    if (!rd.have)
        rd.have = mrl_next(&tick, v) ? 1 : -1;
    if (rd.have == 1 && tick == rt_ticks_done(sim)) {
        rt_link_apply(sc, sim, v);
        rd.have = 0;
    }
    return 0;
}
