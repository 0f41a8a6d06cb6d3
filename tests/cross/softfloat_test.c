/* softfloat_test.c - cross-target check of binary64 arithmetic, conversions and
 * comparisons: every target must produce the same result bits as the host.
 *
 * Runs + - * / over a deterministic set of operand pairs in classes chosen to reach the
 * hard cases of rounding, plus the int<->double and float<->double conversions and the
 * comparisons, and prints one FNV-1a hash of the result bits per operation:
 *   "softfloat <op> n <count> hash <16 hex digits>"
 * followed by known-answer checks (TH_CHECK) and the harness summary. The hash lines must
 * equal the host's (x86-64 SSE2: correctly rounded) on every target; on ARM without double
 * hardware (M3, M4F) that holds only with ports/common/softfloat.c linked, which replaces
 * libgcc's not correctly rounded __aeabi_dadd/dsub.
 *
 * NaN results are hashed as one canonical NaN: payloads legitimately differ between
 * targets (RISC-V returns the canonical NaN 0x7ff8000000000000, x86 keeps the first
 * operand's payload, ARM prefers a signalling operand). Conversions to integers use only
 * in-range values (out of range is undefined in C and differs between targets).
 *
 * Operand classes for the binary operations (SF_TEST_N pairs each, from fixed seeds):
 *   random    uniformly random bit patterns (all exponents, rare inf/NaN)
 *   close     random signs and mantissas, exponents at most 64 apart
 *   binade    a = +-2^k (1 + a few low ulps), b 2..64 binades lower, either sign: a + b
 *             or a - b falls below 2^k; half the pairs 31..35 binades apart (libgcc's
 *             dadd/dsub fail at exactly 33: about 1% of this class, 0 elsewhere)
 *   ties      b a power of two at a's half ulp (exact ties of + -), odd integers whose
 *             product has 54 bits (exact ties of *), shifted into every exponent range
 *   subnormal subnormal inputs and results (tiny exponents; /, * by powers of two give
 *             subnormal ties)
 *   overflow  exponents near the top of the range
 *   special   all pairs of +-0, +-inf, NaNs, min/max subnormal and normal, 1, ...
 *
 * Built with -DMODRT_SOFTFLOAT_API (and, on ARM, -DMODRT_SOFTFLOAT_NO_AEABI so the C
 * operators keep libgcc's helpers) and linked with ports/common/softfloat.c, it also
 * compares every result with softfloat.c's modrt_sf_* functions and prints the number of
 * differences per operation and per class ("softfloat <op> differs-from-softfloat <count>
 * of <n>", "softfloat class <name> differs-from-softfloat add <n> sub <n> ..."): on the
 * host and on hardware-FPU targets that checks softfloat.c against the hardware, on M3/M4F
 * it counts the errors of libgcc's helpers. Such a build is expected to fail its
 * known-answer checks on M3/M4F (they exercise the C operators, i.e. libgcc). */
#include <stdint.h>

#include "harness.h"
#include "port.h"

#ifdef MODRT_SOFTFLOAT_API
#include "common/softfloat.h"
#endif

#ifndef SF_TEST_N
#define SF_TEST_N 3000
#endif

/* ------------------------------------------------------------------ bits and hashing */

static uint64_t bits_of(double d)
{
    union { double d; uint64_t u; } v;
    v.d = d;
    return v.u;
}
static double double_of(uint64_t u)
{
    union { double d; uint64_t u; } v;
    v.u = u;
    return v.d;
}
static uint32_t fbits_of(float f)
{
    union { float f; uint32_t u; } v;
    v.f = f;
    return v.u;
}
static float float_of(uint32_t u)
{
    union { float f; uint32_t u; } v;
    v.u = u;
    return v.f;
}

#define CANON_NAN 0x7FF8000000000000ull
static uint64_t canon(uint64_t x) { return (x & ~(1ull << 63)) > 0x7FF0000000000000ull ? CANON_NAN : x; }
static uint32_t fcanon(uint32_t x) { return (x & 0x7FFFFFFFu) > 0x7F800000u ? 0x7FC00000u : x; }

typedef struct {
    const char *name;
    uint64_t hash;
    uint32_t n;
    uint32_t diff; /* differences from softfloat.c (compare builds only) */
} op_stat;

static void fnv_add(op_stat *s, uint64_t v)
{
    uint64_t h = s->n ? s->hash : 0xCBF29CE484222325ull;
    for (int i = 0; i < 8; i++, v >>= 8) {
        h ^= v & 0xFF;
        h *= 0x100000001B3ull;
    }
    s->hash = h;
    s->n++;
}

enum { OP_ADD, OP_SUB, OP_MUL, OP_DIV, OP_I2D, OP_UI2D, OP_L2D, OP_UL2D, OP_F2D, OP_D2F,
       OP_D2I, OP_D2UI, OP_D2L, OP_D2UL, OP_CMP, OP_COUNT };
static op_stat stats[OP_COUNT] = {
    {"add", 0, 0, 0}, {"sub", 0, 0, 0}, {"mul", 0, 0, 0}, {"div", 0, 0, 0},
    {"i2d", 0, 0, 0}, {"ui2d", 0, 0, 0}, {"l2d", 0, 0, 0}, {"ul2d", 0, 0, 0},
    {"f2d", 0, 0, 0}, {"d2f", 0, 0, 0}, {"d2i", 0, 0, 0}, {"d2ui", 0, 0, 0},
    {"d2l", 0, 0, 0}, {"d2ul", 0, 0, 0}, {"cmp", 0, 0, 0},
};

/* Operand class of the current binary operation (compare builds count per class). */
enum { CL_RANDOM, CL_CLOSE, CL_BINADE, CL_TIES, CL_SUBNORMAL, CL_OVERFLOW, CL_SPECIAL, CL_COUNT };
static int cur_class;
#ifdef MODRT_SOFTFLOAT_API
static const char *const class_names[CL_COUNT] = {"random", "close", "binade", "ties",
                                                  "subnormal", "overflow", "special"};
static uint32_t class_diff[CL_COUNT][4]; /* add sub mul div */
#endif

/* Records a double result; in compare builds also checks it against softfloat.c. */
static void record(int op, uint64_t r, uint64_t ref)
{
    fnv_add(&stats[op], canon(r));
#ifdef MODRT_SOFTFLOAT_API
    if (canon(r) != canon(ref)) {
        stats[op].diff++;
        if (op <= OP_DIV) class_diff[cur_class][op]++;
    }
#else
    (void)ref;
#endif
}

/* ------------------------------------------------------------------ operand generation */

static uint64_t rng;
static uint64_t rnd(void) /* xorshift64* */
{
    rng ^= rng >> 12;
    rng ^= rng << 25;
    rng ^= rng >> 27;
    return rng * 0x2545F4914F6CDD1Dull;
}
static uint32_t rnd_below(uint32_t n) { return (uint32_t)((rnd() >> 32) % n); }

#define SIGN 0x8000000000000000ull
#define FRAC 0x000FFFFFFFFFFFFFull

static uint64_t make(uint64_t sign, int32_t e, uint64_t frac)
{
    if (e < 0) e = 0;
    if (e > 0x7FE) e = 0x7FE;
    return (sign & SIGN) | ((uint64_t)e << 52) | (frac & FRAC);
}
static int32_t expo(uint64_t x) { return (int32_t)((x >> 52) & 0x7FF); }

/* Random sign, biased exponent e, fraction = the low 52 bits of a random value shifted
   right by frac_shift (>= 12: a small fraction, its top frac_shift - 12 bits zero; 64: 0). (Every random draw is its own statement: the order of evaluation
   of function arguments differs between compilers, and the sequence must not.) */
static uint64_t rmake(int32_t e, uint32_t frac_shift)
{
    uint64_t sign = rnd();
    uint64_t frac = rnd();
    frac = frac_shift < 64 ? frac >> frac_shift : 0;
    return make(sign, e, frac);
}

/* An odd integer of exactly k bits (1 <= k <= 53) times 2^e_shift, random sign. */
static uint64_t odd_int(uint32_t k, int32_t e_shift)
{
    uint64_t m = (rnd() >> (64 - k)) | 1 | (1ull << (k - 1)); /* k bits, odd */
    uint64_t sign = rnd();
    /* m = 1.f * 2^(k-1): the fraction is m without its leading bit, aligned to 52 bits */
    return make(sign, (int32_t)(1023 + k - 1) + e_shift, (m << (53 - k)) & FRAC);
}

static void gen_pair(int cls, uint32_t i, uint64_t *pa, uint64_t *pb)
{
    uint64_t a, b;
    int32_t e;
    uint32_t sh;
    switch (cls) {
    case CL_RANDOM:
        a = rnd();
        b = rnd();
        break;
    case CL_CLOSE:
        e = 1 + (int32_t)rnd_below(0x7FE);
        a = rmake(e, 0);
        e = expo(a) + (int32_t)rnd_below(129) - 64;
        b = rmake(e, 0);
        break;
    case CL_BINADE:
        /* a = +-2^k * (1 + a few low ulps), b d binades lower, of either sign: a + b or
           a - b is a subtraction falling below 2^k. Half the pairs have d in 31..35,
           around the word boundary of 32-bit implementations (libgcc fails at d = 33). */
        e = 2 + (int32_t)rnd_below(0x7FC);
        sh = 12 + rnd_below(52);
        a = rmake(e, sh);
        if (rnd_below(2))
            e = expo(a) - 31 - (int32_t)rnd_below(5);
        else
            e = expo(a) - 2 - (int32_t)rnd_below(63);
        if (rnd_below(4) == 0) { /* b's fraction all ones but a few low bits */
            sh = 12 + rnd_below(52);
            uint64_t sign = rnd();
            b = make(sign, e, FRAC - (rnd() >> sh));
        } else {
            b = rmake(e, 0);
        }
        break;
    case CL_TIES:
        if (i & 1) { /* exact ties for * : odd integers with k and 54-k (or 55-k) bits */
            uint32_t k = 1 + rnd_below(53);
            uint32_t kb = (rnd_below(2) ? 54 : 55) - k;
            if (kb > 53) kb = 53;
            if (kb < 1) kb = 1;
            int32_t sa = (int32_t)rnd_below(2000) - 1000;
            a = odd_int(k, sa);
            int32_t sb = (int32_t)rnd_below(2000) - 1000 - sa / 2;
            b = odd_int(kb, sb);
        } else { /* exact ties (or binade crossings) for + - : b at a's half ulp */
            e = 60 + (int32_t)rnd_below(0x7FE - 60);
            sh = rnd_below(53);
            a = rmake(e, sh);
            e = expo(a) - 53 - (int32_t)rnd_below(2);
            if (rnd_below(2)) {
                b = rmake(e, 64); /* a power of two: frac_shift 64 gives 0 */
            } else {
                sh = 12 + rnd_below(52);
                b = rmake(e, sh);
            }
        }
        break;
    case CL_SUBNORMAL:
        e = (int32_t)rnd_below(60);
        sh = rnd_below(52);
        a = rmake(e, sh);
        switch (rnd_below(4)) {
        case 0: e = (int32_t)rnd_below(60); b = rmake(e, 0); break;              /* tiny */
        case 1: e = 1023 + (int32_t)rnd_below(80) - 40; b = rmake(e, 0); break;  /* ~1 */
        case 2: e = 1023 + (int32_t)rnd_below(60); b = rmake(e, 64); break;      /* 2^k */
        default: e = 1023 - (int32_t)rnd_below(60); b = rmake(e, 64); break;     /* 2^-k */
        }
        break;
    default: /* CL_OVERFLOW */
        e = 0x7FE - (int32_t)rnd_below(0x100);
        a = rmake(e, 0);
        if (rnd_below(2))
            e = 0x7FE - (int32_t)rnd_below(0x400);
        else
            e = 1 + (int32_t)rnd_below(0x300);
        b = rmake(e, 0);
        break;
    }
    if (rnd_below(2)) { /* either order */
        uint64_t t = a;
        a = b;
        b = t;
    }
    *pa = a;
    *pb = b;
}

static const uint64_t specials[] = {
    0x0000000000000000ull, 0x0000000000000001ull, 0x0000000000000003ull,
    0x000FFFFFFFFFFFFFull, 0x0008000000000000ull, 0x0010000000000000ull,
    0x0010000000000001ull, 0x001FFFFFFFFFFFFFull, 0x3CA0000000000000ull,
    0x3FE0000000000000ull, 0x3FEFFFFFFFFFFFFFull, 0x3FF0000000000000ull,
    0x3FF0000000000001ull, 0x4000000000000000ull, 0x4340000000000000ull,
    0x7FE0000000000000ull, 0x7FEFFFFFFFFFFFFFull, 0x7FF0000000000000ull,
    0x7FF8000000000000ull, 0x7FF4000000000000ull,
};
#define N_SPECIALS (2 * (uint32_t)(sizeof specials / sizeof specials[0]))
static uint64_t special(uint32_t i) { return specials[i / 2] | ((uint64_t)(i & 1) << 63); }

/* ------------------------------------------------------------------ operations */

static uint32_t cmp_bits(double x, double y)
{
    return (uint32_t)(x < y) | (uint32_t)(x <= y) << 1 | (uint32_t)(x == y) << 2 |
           (uint32_t)(x > y) << 3 | (uint32_t)(x >= y) << 4 | (uint32_t)(x != x || y != y) << 5;
}

static void binary_ops(uint64_t ua, uint64_t ub)
{
    double a = double_of(ua), b = double_of(ub);
#ifdef MODRT_SOFTFLOAT_API
    record(OP_ADD, bits_of(a + b), modrt_sf_add(ua, ub));
    record(OP_SUB, bits_of(a - b), modrt_sf_sub(ua, ub));
    record(OP_MUL, bits_of(a * b), modrt_sf_mul(ua, ub));
    record(OP_DIV, bits_of(a / b), modrt_sf_div(ua, ub));
#else
    record(OP_ADD, bits_of(a + b), 0);
    record(OP_SUB, bits_of(a - b), 0);
    record(OP_MUL, bits_of(a * b), 0);
    record(OP_DIV, bits_of(a / b), 0);
#endif
    fnv_add(&stats[OP_CMP], cmp_bits(a, b));
    fnv_add(&stats[OP_CMP], cmp_bits(a, a));
    /* double -> float (rounds; subnormal and overflowing floats included) */
    fnv_add(&stats[OP_D2F], fcanon(fbits_of((float)a)));
}

static void conversions(uint32_t i)
{
    uint64_t r = rnd();
    uint32_t sh = rnd_below(64);
    int64_t l = (int64_t)r >> sh; /* every bit length, both signs */
    uint64_t ul = r >> sh;
    int32_t n = (int32_t)(uint32_t)(r >> (sh & 31));
    uint32_t un = (uint32_t)(r >> 32) >> (sh & 31);
#ifdef MODRT_SOFTFLOAT_API
    record(OP_I2D, bits_of((double)n), modrt_sf_from_i32(n));
    record(OP_UI2D, bits_of((double)un), modrt_sf_from_u32(un));
    record(OP_L2D, bits_of((double)l), modrt_sf_from_i64(l));
    record(OP_UL2D, bits_of((double)ul), modrt_sf_from_u64(ul));
#else
    record(OP_I2D, bits_of((double)n), 0);
    record(OP_UI2D, bits_of((double)un), 0);
    record(OP_L2D, bits_of((double)l), 0);
    record(OP_UL2D, bits_of((double)ul), 0);
#endif
    /* float -> double: every float class (random bits include subnormals, inf, NaN) */
    uint32_t f = (uint32_t)rnd();
    if ((i & 3) == 0) f &= 0x807FFFFFu; /* subnormal floats */
#ifdef MODRT_SOFTFLOAT_API
    record(OP_F2D, bits_of((double)float_of(f)), modrt_sf_from_f32(f));
#else
    record(OP_F2D, bits_of((double)float_of(f)), 0);
#endif
    /* double -> integer, truncating, in range only: |x| < 2^(bits) */
    int32_t e = 1023 - 4 + (int32_t)rnd_below(35);
    double x = double_of(rmake(e, 0)); /* |x| < 2^31 */
    fnv_add(&stats[OP_D2I], (uint64_t)(uint32_t)(int32_t)x);
    x = x < 0 ? -x : x;
    fnv_add(&stats[OP_D2UI], (uint64_t)(uint32_t)(x * 2.0)); /* < 2^32 */
    e = 1023 - 4 + (int32_t)rnd_below(67);
    double y = double_of(rmake(e, 0)); /* |y| < 2^63 */
    fnv_add(&stats[OP_D2L], (uint64_t)(int64_t)y);
    y = y < 0 ? -y : y;
    fnv_add(&stats[OP_D2UL], (uint64_t)(y * 2.0)); /* < 2^64 */
}

/* ------------------------------------------------------------------ known answers */

static uint64_t add_bits(uint64_t a, uint64_t b) { return bits_of(double_of(a) + double_of(b)); }
static uint64_t sub_bits(uint64_t a, uint64_t b) { return bits_of(double_of(a) - double_of(b)); }
static uint64_t mul_bits(uint64_t a, uint64_t b) { return bits_of(double_of(a) * double_of(b)); }
static uint64_t div_bits(uint64_t a, uint64_t b) { return bits_of(double_of(a) / double_of(b)); }

/* Operands go through volatile so the compiler cannot fold the checks at compile time. */
static volatile uint64_t ka[] = {
    0xbfd00000000b746aull, 0x3dc6e90e92d8a537ull, /* libgcc dadd reproducer */
    0x3ff0000000000000ull, 0x3ca0000000000000ull, /* 1, 2^-53 */
    0x3ff0000000000001ull, 0x0000000000000001ull, /* 1 + 2^-52, min subnormal */
    0x0000000000000003ull, 0x3fe0000000000000ull, /* 3 * min subnormal, 0.5 */
    0x7fefffffffffffffull, 0x4008000000000000ull, /* DBL_MAX, 3 */
    0x8000000000000000ull, 0x0010000000000000ull, /* -0, DBL_MIN */
    0x7ff0000000000000ull, 0x4340000000000000ull, /* inf, 2^53 */
};

static void known_answers(void)
{
    uint64_t rep_a = ka[0], rep_b = ka[1], one = ka[2], half_ulp = ka[3], one_p = ka[4];
    uint64_t min_sub = ka[5], three_sub = ka[6], half = ka[7], dmax = ka[8], three = ka[9];
    uint64_t mzero = ka[10], dmin = ka[11], inf = ka[12], two53 = ka[13];

    TH_EQ_U64(add_bits(rep_a, rep_b), 0xbfcfffffffffffc5ull);
    TH_EQ_U64(add_bits(rep_b, rep_a), 0xbfcfffffffffffc5ull);
    TH_EQ_U64(sub_bits(rep_a, rep_b ^ SIGN), 0xbfcfffffffffffc5ull);
    TH_EQ_U64(sub_bits(rep_a ^ SIGN, rep_b), 0x3fcfffffffffffc5ull);    /* -(a + b) */
    TH_EQ_U64(add_bits(one, half_ulp), one);                        /* tie to even: down */
    TH_EQ_U64(add_bits(one_p, half_ulp), 0x3ff0000000000002ull);    /* tie to even: up */
    TH_EQ_U64(sub_bits(one, half_ulp), 0x3fefffffffffffffull);      /* exact below 1 */
    TH_EQ_U64(add_bits(two53, one), two53);                         /* 2^53 + 1: tie down */
    TH_EQ_U64(mul_bits(min_sub, half), 0);                          /* subnormal tie to 0 */
    TH_EQ_U64(mul_bits(three_sub, half), 2);                        /* 1.5 -> 2 */
    TH_EQ_U64(div_bits(three_sub, 0x4000000000000000ull), 2);       /* 1.5 -> 2 */
    TH_EQ_U64(div_bits(dmin, 0x4330000000000000ull), min_sub);      /* DBL_MIN / 2^52 */
    TH_EQ_U64(div_bits(one, three), 0x3fd5555555555555ull);
    TH_EQ_U64(mul_bits(dmax, 0x4000000000000000ull), inf);          /* overflow */
    TH_EQ_U64(add_bits(dmax, 0x7c90000000000000ull), inf);          /* DBL_MAX + half ulp */
    TH_EQ_U64(add_bits(dmax, 0x7c8fffffffffffffull), dmax);
    TH_EQ_U64(add_bits(three, three ^ SIGN), 0);                    /* x + -x = +0 */
    TH_EQ_U64(add_bits(mzero, mzero), mzero);                       /* -0 + -0 = -0 */
    TH_EQ_U64(sub_bits(mzero, 0), mzero);                           /* -0 - +0 = -0 */
    TH_EQ_U64(add_bits(dmin, dmin ^ SIGN ^ 1), 0x8000000000000001ull); /* subnormal diff */
    TH_CHECK(canon(sub_bits(inf, inf)) == CANON_NAN);
    TH_CHECK(canon(mul_bits(0, inf)) == CANON_NAN);
    TH_CHECK(canon(div_bits(mzero, 0)) == CANON_NAN);
    TH_EQ_U64(div_bits(one, mzero), inf | SIGN);
    volatile int64_t big = (int64_t)((1ull << 62) + (1ull << 9) + 1); /* just above a tie: up */
    TH_EQ_U64(bits_of((double)big), 0x43d0000000000001ull);
    volatile int64_t tie = (int64_t)((1ull << 62) + (1ull << 9)); /* tie: to even */
    TH_EQ_U64(bits_of((double)tie), 0x43d0000000000000ull);
}

/* ------------------------------------------------------------------ main */

int app_main(void)
{
    for (int cls = 0; cls < CL_SPECIAL; cls++) {
        cur_class = cls;
        rng = 0x9E3779B97F4A7C15ull * (uint64_t)(cls + 1);
        for (uint32_t i = 0; i < SF_TEST_N; i++) {
            uint64_t a, b;
            gen_pair(cls, i, &a, &b);
            binary_ops(a, b);
        }
    }
    cur_class = CL_SPECIAL;
    for (uint32_t i = 0; i < N_SPECIALS; i++)
        for (uint32_t j = 0; j < N_SPECIALS; j++) binary_ops(special(i), special(j));
    rng = 0x0123456789ABCDEFull;
    for (uint32_t i = 0; i < 4 * SF_TEST_N; i++) conversions(i);

    for (int op = 0; op < OP_COUNT; op++) {
        th_put("softfloat ");
        th_put(stats[op].name);
        th_put(" n ");
        th_put_int(stats[op].n);
        th_put(" hash ");
        th_put_hex64(stats[op].hash);
        th_put("\n");
    }
#ifdef MODRT_SOFTFLOAT_API
    for (int op = 0; op <= OP_F2D; op++) {
        th_put("softfloat ");
        th_put(stats[op].name);
        th_put(" differs-from-softfloat ");
        th_put_int(stats[op].diff);
        th_put(" of ");
        th_put_int(stats[op].n);
        th_put("\n");
    }
    for (int cls = 0; cls < CL_COUNT; cls++) {
        th_put("softfloat class ");
        th_put(class_names[cls]);
        th_put(" differs-from-softfloat add ");
        th_put_int(class_diff[cls][OP_ADD]);
        th_put(" sub ");
        th_put_int(class_diff[cls][OP_SUB]);
        th_put(" mul ");
        th_put_int(class_diff[cls][OP_MUL]);
        th_put(" div ");
        th_put_int(class_diff[cls][OP_DIV]);
        th_put("\n");
    }
#endif
    known_answers();
    return th_summary() != 0;
}
