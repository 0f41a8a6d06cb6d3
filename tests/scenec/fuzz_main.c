/* fuzz_main.c - a deterministic mutation fuzzer for hosts without libFuzzer: starts from
 * the seed files, mutates them (byte flips, insertions of bytes and language words,
 * deletions, duplications, splices of two seeds) with a fixed-seed generator, and calls
 * LLVMFuzzerTestOneInput on each; built with ASan and UBSan, a crash stops the run.
 * Usage: scenec-fuzz SECONDS SEED_FILE... */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define MAX_SEEDS 512
#define MAX_LEN 65536 /* bytes of one input (the libFuzzer runs use -max_len=65536 too) */

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static const char *const words[] = {
    "define", "ss_system", "lss_system", "dss_system", "with", "inputs", "outputs",
    "parameters", "states", "period", "by", "load", "system", "joint", "of", "type",
    "from", "file", "connect", "link", "ground", "at", "set", "method", "step", "members",
    "interpolation", "record", "scene", "base", "tick", "end", "time", "include", "solve",
    "loops", "stabilization", "let", "der", "next", "y[0]", "xdot[0]", "xnext[0]", "(", ")",
    "{", "}", "[", "]", ";", ",", ".", "=", "/*", "*/", "//", "\"", "1e308", "0", "-1",
    "ms", "ticks", "rk4", "sdirk2", "pi", "sphdiff", "mbs_point", "oscillator", "x", "^",
};

static uint64_t rng = 0x9E3779B97F4A7C15ull;

static uint32_t rnd(uint32_t n)
{
    rng ^= rng << 13, rng ^= rng >> 7, rng ^= rng << 17;
    return n ? (uint32_t)(rng % n) : 0;
}

typedef struct buf {
    uint8_t b[MAX_LEN];
    size_t n;
} buf;

static void insert(buf *x, size_t at, const void *s, size_t k)
{
    if (x->n + k > MAX_LEN || at > x->n)
        return;
    memmove(x->b + at + k, x->b + at, x->n - at);
    memcpy(x->b + at, s, k);
    x->n += k;
}

/* one random edit of x; other is a second seed for splicing */
static void mutate(buf *x, const buf *other)
{
    size_t at = rnd((uint32_t)x->n + 1), k = 1 + rnd(16);
    const char *w = words[rnd(sizeof words / sizeof words[0])];
    uint8_t byte = (uint8_t)rnd(256);
    switch (rnd(6)) {
    case 0: if (x->n) x->b[rnd((uint32_t)x->n)] ^= (uint8_t)(1u << rnd(8)); break;
    case 1: insert(x, at, &byte, 1); break;
    case 2: insert(x, at, w, strlen(w)); break;
    case 3: /* delete k bytes */
        if (at + k <= x->n)
            memmove(x->b + at, x->b + at + k, x->n - at - k), x->n -= k;
        break;
    case 4: /* duplicate k bytes elsewhere (through a copy: the ranges may overlap) */
        if (at + k <= x->n) {
            uint8_t tmp[16];
            memcpy(tmp, x->b + at, k);
            insert(x, rnd((uint32_t)x->n + 1), tmp, k);
        }
        break;
    default: /* splice: the head of x, the tail of other */
        if (other->n) {
            size_t from = rnd((uint32_t)other->n), take = other->n - from;
            if (at + take > MAX_LEN)
                take = MAX_LEN - at;
            memcpy(x->b + at, other->b + from, take), x->n = at + take;
        }
    }
}

static int load(const char *path, buf *x)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return -1;
    x->n = fread(x->b, 1, MAX_LEN, f);
    fclose(f);
    return 0;
}

int main(int argc, char **argv)
{
    static buf seeds[MAX_SEEDS], cur;
    int n = 0;
    double secs = argc > 1 ? atof(argv[1]) : 10;
    for (int i = 2; i < argc && n < MAX_SEEDS; i++)
        if (load(argv[i], &seeds[n]) == 0)
            n++;
    if (n == 0)
        seeds[n++].n = 0;
    clock_t end = clock() + (clock_t)(secs * CLOCKS_PER_SEC);
    unsigned long runs = 0;
    for (int i = 0; i < n; i++, runs++)
        LLVMFuzzerTestOneInput(seeds[i].b, seeds[i].n);
    while (clock() < end) {
        cur = seeds[rnd((uint32_t)n)];
        for (uint32_t m = 1 + rnd(8); m > 0; m--)
            mutate(&cur, &seeds[rnd((uint32_t)n)]);
        LLVMFuzzerTestOneInput(cur.b, cur.n);
        runs++;
    }
    printf("fuzz: %lu inputs in %.0f s from %d seeds, no crash\n", runs, secs, n);
    return 0;
}
