/* rmath.c - owns modrt's elementary functions (rt_math.h): sqrt, trig, exp/log/pow, tanh.
 *
 * Why not libm: glibc, newlib and the compiler runtimes differ in the last bit, and modrt
 * promises bit-identical traces on every target. Everything here is + - * / on IEEE
 * binary64 (round to nearest), integer and bit operations, and the hardware square root
 * only where it is an exact IEEE instruction. Those are correctly rounded on x86-64 (SSE2),
 * AArch64, Cortex-M3/M4F/M7 (VFP or libgcc soft-float) and RISC-V (F/D or soft-float),
 * so every target computes the same bits (checked: one hash of results over ~50k inputs
 * is equal on x86-64, AArch64, M3, M4F, M7, rv32imac and rv64gc, double and float).
 * Requirements on the build and the target:
 *   - no contraction into FMA (-ffp-contract=off; the pragmas below cover gcc and clang
 *     builds without it), no -ffast-math, FLT_EVAL_METHOD == 0 (no x87): checked below;
 *   - round-to-nearest and no flush-to-zero (the reset state of every listed FPU).
 * NaN results are the canonical quiet NaN (0x7ff8000000000000 / 0x7fc00000), never an
 * FPU-dependent payload; rt_fabs, rt_floor, rt_fmin and rt_fmax pass input NaNs through.
 *
 * With real_t = float (-DRT_REAL_FLOAT) every function computes in double and rounds
 * once to float (so float results are correctly rounded but for rare double roundings),
 * except rt_sqrt, which uses the hardware float square root where there is one. On a
 * single-precision FPU (M4F) that means soft-float double arithmetic: exact but slow.
 *
 * Methods (dd = double-double, an unevaluated sum hi + lo carrying ~106 bits):
 *   sqrt       hardware where exact, else bit-by-bit integer root, correctly rounded.
 *   sin cos    x = n pi/2 + r: Cody-Waite with a 3-part pi/2 for |x| < 2^20, Payne-Hanek
 *              (integer product with the bits of 2/pi) above, so no range limit;
 *              minimax polynomials for sin and cos on [-pi/4, pi/4].
 *   tan        the same sin and cos kernels as dd, then a compensated division.
 *   atan atan2 asin acos   one dd core: atan(v) = atan(i/16) + atan(t), |t| <= 1/32
 *              (table + Taylor); ratios, 1 - x^2 and its square root carried as dd.
 *   exp        x = (32k + j) ln2/32 + r, 2^(j/32) table in dd, degree-7 polynomial.
 *   log        log(2^k m) = k ln2 + log F + log1p((m - F)/F), F = i/128, all in dd.
 *   pow        integer |y| <= 64: dd repeated squaring; else exp(y log x) with log x and
 *              y log x in dd, so a product up to 745 costs no accuracy.
 *   tanh       Taylor below 1/16, else (e^2x - 1)/(e^2x + 1) in dd.
 *   *_faithful sin, atan, atan2, asin rounded faithfully (< 1 ulp) in plain double where
 *              the error analysis allows: the cars' tire law calls them in every stage
 *              (section "faithful functions").
 *
 * Max error in ulp measured against the long double libm (tests/host/test_rmath_libm.c,
 * 20M points per function over the whole range incl. subnormals, huge trig arguments,
 * arguments next to multiples of pi/2; resolution 2^-11 ulp). Float: every function
 * measures <= 0.5 ulp (+ 2^-29 from double rounding); rt_sqrt exactly 0.5.
 *   sqrt        0.5     correctly rounded; hardware and software path bit-identical
 *   sin cos     0.67    whole range (bound checked by the host test: 0.75)
 *   tan         0.79    whole range (0.9)
 *   atan atan2  0.501   whole range, all quadrants; atan2(+-0, +0) = +-0,
 *                       atan2(+-0, -0) = +-pi (C99 Annex F)               (0.51)
 *   asin acos   0.501   [-1, 1]; NaN outside                                (0.51)
 *   exp         0.5005  e^x > DBL_MAX -> +inf, e^x < 2^-1075 -> +0; subnormal
 *                       results are rounded once                           (0.51)
 *   log         0.5005  subnormals included; log(+-0) = -inf, log(x < 0) = NaN (0.51)
 *   pow         0.504   exact when the result is representable (pow(2, 10) = 1024);
 *                       x < 0 needs an integer y, else NaN; C99 Annex F special
 *                       cases; |y| > 2^64 over/underflows directly          (0.51)
 *   tanh        0.503   (0.51)
 *   sin_faithful                 0.79    (0.85)
 *   atan_faithful atan2_faithful 0.525   (0.6)
 *   asin_faithful                0.547   (0.6)
 *   fabs isfinite (inline in rt_math.h) floor fmin fmax: exact. fmin(-0, +0) = -0, fmax(-0, +0) = +0; a NaN
 *   argument of fmin/fmax is ignored unless both are NaN.
 * Cost, QEMU instruction counts per call (M3 soft-float / M7 double FPU): sqrt 1.8k/15,
 * sin 2.8k/120 (4k/520 beyond 2^20), exp 4.4k/120, log 6.3k/150, atan 8.9k/170,
 * pow 12.5k/360 (integer y 5.8k/230), asin 13.7k/210. */
#include <stddef.h>
#include <stdint.h>

#include "rt_math.h"

#if defined(__FAST_MATH__)
#error "rmath.c needs exact IEEE arithmetic: do not build it with -ffast-math"
#endif
#if defined(__FLT_EVAL_METHOD__) && __FLT_EVAL_METHOD__ != 0
#error "rmath.c needs FLT_EVAL_METHOD == 0 (e.g. SSE2, not the x87 FPU)"
#endif
/* No a*b+c fused into an FMA: that changes roundings on the targets that have one. The
   build passes -ffp-contract=off; these keep a build without it (gnu11 defaults to
   "fast") correct. */
#if defined(__clang__)
#pragma STDC FP_CONTRACT OFF
#elif defined(__GNUC__)
#pragma GCC optimize("fp-contract=off")
#endif

/* ------------------------------------------------------------------ bits */

typedef union {
    double f;
    uint64_t u;
} rmath_b64;

static inline uint64_t bits_of(double x)
{
    rmath_b64 b;
    b.f = x;
    return b.u;
}

static inline double from_bits(uint64_t u)
{
    rmath_b64 b;
    b.u = u;
    return b.f;
}

#define ABS_MASK 0x7fffffffffffffffull
#define EXP_MASK 0x7ff0000000000000ull
#define MANT_MASK 0x000fffffffffffffull
#define HIDDEN_BIT 0x0010000000000000ull
#define NAN_BITS 0x7ff8000000000000ull
#define INF_D from_bits(EXP_MASK)
#define NAN_D from_bits(NAN_BITS)

/* 2^k for -1022 <= k <= 1023, exact. */
static inline double pow2(int32_t k)
{
    return from_bits((uint64_t)(k + 1023) << 52);
}

/* Biased exponent field, used to measure cancellation without arithmetic. */
static inline int32_t exp_field(double x)
{
    return (int32_t)((bits_of(x) >> 52) & 0x7ff);
}

static inline double abs_d(double x)
{
    return from_bits(bits_of(x) & ABS_MASK);
}

/* ------------------------------------------------------------------ double-double */

/* s + e == a + b exactly (Knuth), for any a, b. */
static inline void two_sum(double a, double b, double *s, double *e)
{
    double t = a + b, bb = t - a;
    *e = (a - (t - bb)) + (b - bb);
    *s = t;
}

/* s + e == a + b exactly when |a| >= |b| or a == 0 (Dekker). */
static inline void fast_two_sum(double a, double b, double *s, double *e)
{
    double t = a + b;
    *e = b - (t - a);
    *s = t;
}

/* p + e == a * b exactly (Dekker/Veltkamp; no FMA on purpose). Needs |a|, |b| < 2^996
   and a product far enough from the subnormal range; callers keep to that. */
static inline void two_prod(double a, double b, double *p, double *e)
{
    double ca = 134217729.0 * a, cb = 134217729.0 * b; /* 2^27 + 1 */
    double ah = ca - (ca - a), al = a - ah;
    double bh = cb - (cb - b), bl = b - bh;
    double t = a * b;
    *e = ((ah * bh - t) + ah * bl + al * bh) + al * bl;
    *p = t;
}

/* (ah + al) / (bh + bl) rounded to double; error ~0.5 ulp + 2^-100. */
static double dd_div(double ah, double al, double bh, double bl)
{
    double q = ah / bh, p, e;
    two_prod(q, bh, &p, &e);
    return q + ((((ah - p) - e) + al) - q * bl) / bh; /* ah - p is exact (Sterbenz) */
}

/* ------------------------------------------------------------------ square root */

double rti_sqrt_soft(double x); /* internal; exposed so host tests compare it with libm */

/* Correctly rounded square root without FPU support. x = m * 2^E with m in [2^52, 2^54),
   E even; the integer root q of m * 2^54 has 54 bits, the last one the rounding bit.
   Ties cannot occur (an odd q with zero remainder would make m * 2^52 = (q/2)^2 a
   non-integer), so round-to-nearest is simply (q + 1) >> 1. */
double rti_sqrt_soft(double x)
{
    uint64_t ix = bits_of(x);
    if (x != x || (ix >> 63 && x != 0.0)) return NAN_D;
    if (x == 0.0 || ix == EXP_MASK) return x; /* +-0, +inf */
    int32_t e = (int32_t)(ix >> 52);
    uint64_t m = ix & MANT_MASK;
    if (e == 0) { /* subnormal: normalise */
        e = 1;
        while (!(m & HIDDEN_BIT)) {
            m <<= 1;
            e--;
        }
    } else {
        m |= HIDDEN_BIT;
    }
    int32_t E = e - 1023;
    if ((uint32_t)E & 1u) { /* make the exponent even */
        m <<= 1;
        E--;
    }
    uint64_t q = 0, r = 0;
    for (int i = 53; i >= 0; i--) { /* bit pair i of m * 2^54, from the top */
        r = (r << 2) | (i >= 27 ? (m >> (2 * i - 54)) & 3u : 0u);
        uint64_t t = (q << 2) | 1u;
        q <<= 1;
        if (r >= t) {
            r -= t;
            q |= 1u;
        }
    }
    /* the hidden bit of (q + 1) >> 1 carries into the exponent field */
    return from_bits(((uint64_t)(E / 2 + 1022) << 52) + ((q + 1u) >> 1));
}

/* Square root of a non-negative double, for the inverse trig functions. */
static inline double sqrt_d(double x)
{
#if RT_HW_SQRT_D
    return __builtin_sqrt(x);
#else
    return rti_sqrt_soft(x);
#endif
}

/* ------------------------------------------------------------------ sin, cos, tan */

/* Minimax on |x| <= pi/4 (Remez, coefficients rounded one at a time and the rest
   refitted): |sin x / x - (1 + S1 z + ... + S6 z^6)| < 2^-57.9, z = x^2, and
   |cos x - (1 - z/2 + z^2 (C1 + ... + C6 z^5))| / cos x < 2^-63. */
static const double S1 = -0x1.5555555555548p-3, S2 = 0x1.111111110f730p-7,
                    S3 = -0x1.a01a019be9217p-13, S4 = 0x1.71de35552b52cp-19,
                    S5 = -0x1.ae5e4b83e4697p-26, S6 = 0x1.5d8b55948ffc8p-33;
static const double C1 = 0x1.5555555555553p-5, C2 = -0x1.6c16c16c15eb1p-10,
                    C3 = 0x1.a01a019dcd0dep-16, C4 = -0x1.27e4f8be13944p-22,
                    C5 = 0x1.1eea59a5fc571p-29, C6 = -0x1.8fe23ef93c3d2p-37;

/* sin(x + y) as *hi + *lo for |x| <= pi/4, |y| <= ulp(x)/2: x + x^3 S1 summed exactly
   (saves ~0.06 ulp), the rest is small; the y terms are the first-order correction
   sin' = cos ~ 1 - z/2. */
static void ksin(double x, double y, double *hi, double *lo)
{
    double z = x * x, w = z * z, v = z * x, e;
    double r = S2 + z * (S3 + z * S4) + z * w * (S5 + z * S6);
    fast_two_sum(x, v * S1, hi, &e);
    *lo = e + ((v * z) * r + (y - (z * 0.5) * y));
}

/* cos(x + y) as *hi + *lo: hi = 1 - z/2 rounded, lo collects its rounding error and
   that of z = x^2 (both exact: a rounded z alone would cost 0.25 ulp near pi/4), the
   polynomial and the first-order y term -x*y. */
static void kcos(double x, double y, double *hi, double *lo)
{
    double z, zl, w, r, hz, h;
    two_prod(x, x, &z, &zl);
    w = z * z;
    r = z * (C1 + z * (C2 + z * C3)) + w * w * (C4 + z * (C5 + z * C6));
    hz = 0.5 * z;
    h = 1.0 - hz;
    *lo = ((1.0 - h) - hz) + ((z * r - x * y) - 0.5 * zl);
    *hi = h;
}

/* pi/2 in three 33-bit parts plus tails (fn * part is exact for fn < 2^20). */
static const double PIO2_1 = 0x1.921fb54400000p+0, PIO2_1T = 0x1.0b4611a626331p-34;
static const double PIO2_2 = 0x1.0b4611a600000p-34, PIO2_2T = 0x1.3198a2e037073p-69;
static const double PIO2_3 = 0x1.3198a2e000000p-69, PIO2_3T = 0x1.b839a252049c1p-104;
static const double INV_PIO2 = 0x1.45f306dc9c883p-1;
static const double PIO2_H = 0x1.921fb54442d18p+0, PIO2_L = 0x1.1a62633145c07p-54;
static const double PI_H = 0x1.921fb54442d18p+1, PI_L = 0x1.1a62633145c07p-53;
static const double RND = 0x1.8p52; /* (v + RND) - RND rounds v to an integer, |v| < 2^51 */

/* 2/pi in binary, 32 bits per word, most significant first (1280 bits: enough for the
   largest double, whose exponent skips the first ~970 bits). */
static const uint32_t TWO_OVER_PI[40] = {
    0xA2F9836Eu, 0x4E441529u, 0xFC2757D1u, 0xF534DDC0u, 0xDB629599u, 0x3C439041u,
    0xFE5163ABu, 0xDEBBC561u, 0xB7246E3Au, 0x424DD2E0u, 0x06492EEAu, 0x09D1921Cu,
    0xFE1DEB1Cu, 0xB129A73Eu, 0xE88235F5u, 0x2EBB4484u, 0xE99C7026u, 0xB45F7E41u,
    0x3991D639u, 0x835339F4u, 0x9C845F8Bu, 0xBDF9283Bu, 0x1FF897FFu, 0xDE05980Fu,
    0xEF2F118Bu, 0x5A0A6D1Fu, 0x6D367ECFu, 0x27CB09B7u, 0x4F463F66u, 0x9E5FEA2Du,
    0x7527BAC7u, 0xEBE5F17Bu, 0x3D0739F7u, 0x8A5292EAu, 0x6BFB5FB1u, 0x1F8D5D08u,
    0x56033046u, 0xFC7B6BABu, 0xF0CFBC20u, 0x9AF4361Du
};

/* 64 bits of the little-endian 32-bit-limb number p, from bit pos up. */
static uint64_t limb_bits(const uint32_t *p, int32_t pos)
{
    int32_t w = pos >> 5, sh = pos & 31;
    uint64_t lo = (uint64_t)p[w] | ((uint64_t)p[w + 1] << 32);
    uint64_t hi = p[w + 2];
    return sh ? (lo >> sh) | (hi << (64 - sh)) : lo;
}

/* Payne-Hanek for ax >= 2^20: ax = m 2^e; ax * 2/pi mod 4 from the integer product of
   m with 192 bits of 2/pi starting where the bits stop mattering mod 4. The fraction
   keeps 128 bits; the worst case double (~2^-62 from a multiple of pi/2) keeps > 64. */
static int32_t rem_pio2_large(double ax, double *y0, double *y1)
{
    uint64_t ix = bits_of(ax);
    int32_t e = (int32_t)(ix >> 52) - 1075;
    uint64_t m = (ix & MANT_MASK) | HIDDEN_BIT;
    int32_t i0 = e - 1 > 1 ? e - 1 : 1; /* bits i < e-1 of 2/pi only add multiples of 4 */
    int32_t wi = (i0 - 1) >> 5, sh = (i0 - 1) & 31;
    uint32_t w[6], p[10]; /* no "= {0}": that may become a call to memset */
    uint64_t m0 = m & 0xffffffffu, m1 = m >> 32, carry = 0, t;
    for (int32_t k = 0; k < 6; k++) { /* w little-endian: w[5] holds bits i0..i0+31 */
        uint32_t a = TWO_OVER_PI[wi + k], b = TWO_OVER_PI[wi + k + 1];
        w[5 - k] = sh ? (a << sh) | (b >> (32 - sh)) : a;
    }
    for (int32_t j = 0; j < 6; j++) { /* p = m * w on 32-bit limbs, m = m1 2^32 + m0 */
        t = m0 * w[j] + carry;
        p[j] = (uint32_t)t;
        carry = t >> 32;
    }
    p[6] = (uint32_t)carry;
    carry = 0;
    for (int32_t j = 0; j < 6; j++) {
        t = m1 * w[j] + p[j + 1] + carry; /* < 2^64: (2^32-1)^2 + 2 (2^32-1) */
        p[j + 1] = (uint32_t)t;
        carry = t >> 32;
    }
    p[7] = (uint32_t)carry;
    p[8] = p[9] = 0;
    int32_t s = i0 + 191 - e; /* ax * 2/pi = p * 2^-s, 190 <= s <= 224 */
    uint32_t q = (uint32_t)limb_bits(p, s) & 3u;
    uint64_t fh = limb_bits(p, s - 64), fl = limb_bits(p, s - 128);
    int neg = (int)(fh >> 63); /* fraction >= 1/2: next quadrant, fraction - 1 */
    if (neg) {
        q = (q + 1u) & 3u;
        fl = ~fl + 1u;
        fh = ~fh + (fl == 0 ? 1u : 0u);
    }
    int32_t z = 0; /* normalise the 128-bit magnitude */
    while (!(fh >> 63) && z < 120) {
        fh = (fh << 1) | (fl >> 63);
        fl <<= 1;
        z++;
    }
    double fhi = (double)(int64_t)(fh >> 11) * pow2(-53 - z);
    double flo = (double)(int64_t)(((fh & 0x7ffu) << 42) | (fl >> 22)) * pow2(-106 - z);
    double rh, rl;
    two_prod(fhi, PIO2_H, &rh, &rl); /* r = fraction * pi/2 in dd */
    rl += fhi * PIO2_L + flo * PIO2_H;
    fast_two_sum(rh, rl, y0, y1);
    if (neg) {
        *y0 = -*y0;
        *y1 = -*y1;
    }
    return (int32_t)q;
}

/* x = n pi/2 + (*y0 + *y1), |y0| <= ~pi/4, x finite. Returns n (only n mod 4 is used).
   Cody-Waite: r = x - fn*PIO2_1 is exact; further parts are used only when the result
   has cancelled more than 16 (then 49) bits, which keeps ~118 (151) bits of pi/2. */
static int32_t rem_pio2(double x, double *y0, double *y1)
{
    if ((bits_of(x) & ABS_MASK) >= 0x4130000000000000ull) { /* |x| >= 2^20 */
        int32_t n = rem_pio2_large(abs_d(x), y0, y1);
        if (x < 0) {
            *y0 = -*y0;
            *y1 = -*y1;
            n = -n;
        }
        return n;
    }
    double fn = (x * INV_PIO2 + RND) - RND;
    double r = x - fn * PIO2_1, w = fn * PIO2_1T, y = r - w, t;
    int32_t ex = exp_field(x);
    if (ex - exp_field(y) > 16) {
        t = r;
        w = fn * PIO2_2;
        r = t - w;
        w = fn * PIO2_2T - ((t - r) - w);
        y = r - w;
        if (ex - exp_field(y) > 49) {
            t = r;
            w = fn * PIO2_3;
            r = t - w;
            w = fn * PIO2_3T - ((t - r) - w);
            y = r - w;
        }
    }
    *y0 = y;
    *y1 = (r - y) - w;
    return (int32_t)fn;
}

#define PIO4_BITS 0x3fe921fb54442d18ull
#define TINY_BITS 0x3e40000000000000ull /* 2^-27: below it sin x = tan x = x */

static double sin_cos_d(double x, int32_t shift) /* shift 0: sin, 1: cos */
{
    uint64_t ix = bits_of(x) & ABS_MASK;
    double y0 = x, y1 = 0.0, h, l;
    uint32_t n = 0;
    if (ix >= EXP_MASK) return NAN_D;
    if (ix < TINY_BITS) return shift ? 1.0 : x;
    if (ix > PIO4_BITS) n = (uint32_t)rem_pio2(x, &y0, &y1);
    n += (uint32_t)shift; /* cos x = sin(x + pi/2) */
    if (n & 1u)
        kcos(y0, y1, &h, &l);
    else
        ksin(y0, y1, &h, &l);
    h += l;
    return (n & 2u) ? -h : h;
}

static double tan_d(double x)
{
    uint64_t ix = bits_of(x) & ABS_MASK;
    double y0 = x, y1 = 0.0, sh, sl, ch, cl;
    int32_t n = 0;
    if (ix >= EXP_MASK) return NAN_D;
    if (ix < TINY_BITS) return x;
    if (ix > PIO4_BITS) n = rem_pio2(x, &y0, &y1);
    /* sin and cos of the reduced argument as dd, then one compensated division */
    ksin(y0, y1, &sh, &sl);
    fast_two_sum(sh, sl, &sh, &sl);
    kcos(y0, y1, &ch, &cl);
    fast_two_sum(ch, cl, &ch, &cl);
    return ((uint32_t)n & 1u) ? -dd_div(ch, cl, sh, sl) : dd_div(sh, sl, ch, cl);
}

/* ------------------------------------------------------------------ exp */

static const double INV_LN2_32 = 0x1.71547652b82fep+5;
static const double LN2_32_HI = 0x1.62e42fefa0000p-6; /* 36 bits: fn * it is exact */
static const double LN2_32_LO = 0x1.cf79abc9e3b3ap-45;

/* 2^(j/32), j = 0..31, as dd */
static const double EXP2_T[32][2] = {
    {0x1.0000000000000p+0, 0x0.0p+0}, {0x1.059b0d3158574p+0, 0x1.d73e2a475b465p-55},
    {0x1.0b5586cf9890fp+0, 0x1.8a62e4adc610bp-54}, {0x1.11301d0125b51p+0, -0x1.6c51039449b3ap-54},
    {0x1.172b83c7d517bp+0, -0x1.19041b9d78a76p-55}, {0x1.1d4873168b9aap+0, 0x1.e016e00a2643cp-54},
    {0x1.2387a6e756238p+0, 0x1.9b07eb6c70573p-54}, {0x1.29e9df51fdee1p+0, 0x1.612e8afad1255p-55},
    {0x1.306fe0a31b715p+0, 0x1.6f46ad23182e4p-55}, {0x1.371a7373aa9cbp+0, -0x1.63aeabf42eae2p-54},
    {0x1.3dea64c123422p+0, 0x1.ada0911f09ebcp-55}, {0x1.44e086061892dp+0, 0x1.89b7a04ef80d0p-59},
    {0x1.4bfdad5362a27p+0, 0x1.d4397afec42e2p-56}, {0x1.5342b569d4f82p+0, -0x1.07abe1db13cadp-55},
    {0x1.5ab07dd485429p+0, 0x1.6324c054647adp-54}, {0x1.6247eb03a5585p+0, -0x1.383c17e40b497p-54},
    {0x1.6a09e667f3bcdp+0, -0x1.bdd3413b26456p-54}, {0x1.71f75e8ec5f74p+0, -0x1.16e4786887a99p-55},
    {0x1.7a11473eb0187p+0, -0x1.41577ee04992fp-55}, {0x1.82589994cce13p+0, -0x1.d4c1dd41532d8p-54},
    {0x1.8ace5422aa0dbp+0, 0x1.6e9f156864b27p-54}, {0x1.93737b0cdc5e5p+0, -0x1.75fc781b57ebcp-57},
    {0x1.9c49182a3f090p+0, 0x1.c7c46b071f2bep-56}, {0x1.a5503b23e255dp+0, -0x1.d2f6edb8d41e1p-54},
    {0x1.ae89f995ad3adp+0, 0x1.7a1cd345dcc81p-54}, {0x1.b7f76f2fb5e47p+0, -0x1.5584f7e54ac3bp-56},
    {0x1.c199bdd85529cp+0, 0x1.11065895048ddp-55}, {0x1.cb720dcef9069p+0, 0x1.503cbd1e949dbp-56},
    {0x1.d5818dcfba487p+0, 0x1.2ed02d75b3707p-55}, {0x1.dfc97337b9b5fp+0, -0x1.1a5cd4f184b5cp-54},
    {0x1.ea4afa2a490dap+0, -0x1.e9c23179c2893p-54}, {0x1.f50765b6e4540p+0, 0x1.9d3e12dd8a18bp-54},
};

/* e^(hi + lo) = 2^k (*a + *b) with k returned, for |hi| <= 746, |lo| <= ulp(hi):
   hi + lo = (32k + j) ln2/32 + r, |r| <= ln2/64, r in dd; 2^(j/32) e^r as a normalised
   dd with relative error < 2^-65 (tanh and pow need more than a double). */
static int32_t exp_core(double hi, double lo, double *a, double *b)
{
    double fn = (hi * INV_LN2_32 + RND) - RND, rh, rl, ph, pe, s, e;
    int32_t n = (int32_t)fn;
    two_sum(hi - fn * LN2_32_HI, -(fn * LN2_32_LO), &rh, &rl); /* first difference exact */
    two_sum(rh, rl + lo, &rh, &rl); /* fold in lo (pow's tail can exceed ulp(rh)) */
    int32_t j = (int32_t)((uint32_t)n & 31u), k = (n - j) / 32;
    /* e^rh - 1 - rh, Taylor to degree 7: the next term is below 2^-67 */
    double q = rh * rh * (0.5 + rh * (1.0 / 6 + rh * (1.0 / 24 + rh * (1.0 / 120
                        + rh * (1.0 / 720 + rh * (1.0 / 5040))))));
    double th = EXP2_T[j][0], tl = EXP2_T[j][1];
    /* T e^(rh + rl) = T (1 + rh + q + rl (1 + rh)), T rh exact, small terms summed last */
    two_prod(th, rh, &ph, &pe);
    fast_two_sum(th, ph, &s, &e);
    fast_two_sum(s, e + (pe + (tl + (th * (q + (rl + rl * rh)) + tl * rh))), a, b);
    return k;
}

/* (a + b) 2^k rounded once, including overflow and the subnormal range, where the sum
   is first rounded at the subnormal quantum by adding and removing 1.0. */
static double exp_scale(double a, double b, int32_t k)
{
    if (k > 1020) return ((a + b) * pow2(k - 1)) * 2.0;
    if (k >= -1021) return (a + b) * pow2(k);
    double s = pow2(k + 1022); /* k >= -1076 here */
    double zh = a * s, zl = b * s, y = zh + zl;
    if (y < 1.0) {
        double lo = (zh - y) + zl, hi = 1.0 + y;
        lo = ((1.0 - hi) + y) + lo;
        y = (hi + lo) - 1.0;
    }
    return y * 0x1p-1022;
}

static double exp_d(double x)
{
    double a, b;
    if (x != x) return NAN_D;
    if (x > 709.8) return INF_D;
    if (x < -745.2) return 0.0;
    int32_t k = exp_core(x, 0.0, &a, &b);
    return exp_scale(a, b, k);
}

/* ------------------------------------------------------------------ log */

static const double LN2_HI = 0x1.62e42fefa3800p-1; /* 42 bits: k * it is exact */
static const double LN2_LO = 0x1.ef35793c76730p-45;

/* log(i/128), i = 91..181, as dd */
static const double LOG_T[91][2] = {
    {-0x1.5d5bddf595f30p-2, 0x1.6541148cbb8a2p-56}, {-0x1.522ae0738a3d8p-2, 0x1.8f7e9b38a6979p-57},
    {-0x1.4718dc271c41bp-2, -0x1.8fb4c14c56eefp-60}, {-0x1.3c25277333184p-2, 0x1.2ad27e50a8ec6p-56},
    {-0x1.314f1e1d35ce4p-2, 0x1.3d69909e5c3dcp-56}, {-0x1.269621134db92p-2, -0x1.e0efadd9db02bp-56},
    {-0x1.1bf99635a6b95p-2, 0x1.12aeb84249223p-57}, {-0x1.1178e8227e47cp-2, 0x1.0e63a5f01c691p-57},
    {-0x1.07138604d5862p-2, -0x1.cdb16ed4e9138p-56}, {-0x1.f991c6cb3b379p-3, -0x1.f665066f980a2p-57},
    {-0x1.e530effe71012p-3, -0x1.2276041f43042p-59}, {-0x1.d1037f2655e7bp-3, -0x1.60629242471a2p-57},
    {-0x1.bd087383bd8adp-3, -0x1.dd355f6a516d7p-60}, {-0x1.a93ed3c8ad9e3p-3, -0x1.bcafa9de97203p-57},
    {-0x1.95a5adcf7017fp-3, -0x1.142c507fb7a3dp-58}, {-0x1.823c16551a3c2p-3, 0x1.1232ce70be781p-57},
    {-0x1.6f0128b756abcp-3, 0x1.8de59c21e166cp-57}, {-0x1.5bf406b543db2p-3, 0x1.1f5b44c0df7e7p-61},
    {-0x1.4913d8333b561p-3, 0x1.0d5604930f135p-58}, {-0x1.365fcb0159016p-3, -0x1.7d411a5b944adp-58},
    {-0x1.23d712a49c202p-3, 0x1.6e38161051d69p-57}, {-0x1.1178e8227e47cp-3, 0x1.0e63a5f01c691p-58},
    {-0x1.fe89139dbd566p-4, 0x1.ac9f4215f9393p-58}, {-0x1.da727638446a2p-4, -0x1.401fa71733019p-58},
    {-0x1.b6ac88dad5b1cp-4, 0x1.0057eed1ca59fp-59}, {-0x1.9335e5d594989p-4, 0x1.478a85704ccb7p-58},
    {-0x1.700d30aeac0e1p-4, 0x1.72566212cdd05p-61}, {-0x1.4d3115d207eacp-4, -0x1.769f42c7842ccp-58},
    {-0x1.2aa04a44717a5p-4, 0x1.d15d38d2fa3f7p-58}, {-0x1.08598b59e3a07p-4, 0x1.dd7009902bf32p-58},
    {-0x1.ccb73cdddb2ccp-5, 0x1.e48fb0500efd4p-59}, {-0x1.894aa149fb343p-5, -0x1.a8be97660a23dp-60},
    {-0x1.466aed42de3eap-5, 0x1.cdd6f7f4a137ep-59}, {-0x1.0415d89e74444p-5, -0x1.c05cf1d753622p-59},
    {-0x1.8492528c8cabfp-6, 0x1.d192d0619fa67p-60}, {-0x1.0205658935847p-6, -0x1.27c8e8416e71fp-60},
    {-0x1.010157588de71p-7, -0x1.46662d417ced0p-62}, {0x0.0p+0, 0x0.0p+0},
    {0x1.fe02a6b106789p-8, -0x1.e44b7e3711ebfp-67}, {0x1.fc0a8b0fc03e4p-7, -0x1.83092c59642a1p-62},
    {0x1.7b91b07d5b11bp-6, -0x1.5b602ace3a510p-60}, {0x1.f829b0e783300p-6, 0x1.33e3f04f1ef23p-60},
    {0x1.39e87b9febd60p-5, -0x1.5bfa937f551bbp-59}, {0x1.77458f632dcfcp-5, 0x1.18d3ca87b9296p-59},
    {0x1.b42dd711971bfp-5, -0x1.eb9759c130499p-60}, {0x1.f0a30c01162a6p-5, 0x1.85f325c5bbacdp-59},
    {0x1.16536eea37ae1p-4, -0x1.79da3e8c22cdap-60}, {0x1.341d7961bd1d1p-4, -0x1.b599f227becbbp-58},
    {0x1.51b073f06183fp-4, 0x1.a49e39a1a8be4p-58}, {0x1.6f0d28ae56b4cp-4, -0x1.906d99184b992p-58},
    {0x1.8c345d6319b21p-4, -0x1.4a697ab3424a9p-61}, {0x1.a926d3a4ad563p-4, 0x1.942f48aa70ea9p-58},
    {0x1.c5e548f5bc743p-4, 0x1.5d617ef8161b1p-60}, {0x1.e27076e2af2e6p-4, -0x1.61578001e0162p-60},
    {0x1.fec9131dbeabbp-4, -0x1.5746b9981b36cp-58}, {0x1.0d77e7cd08e59p-3, 0x1.9a5dc5e9030acp-57},
    {0x1.1b72ad52f67a0p-3, 0x1.483023472cd74p-58}, {0x1.29552f81ff523p-3, 0x1.301771c407dbfp-57},
    {0x1.371fc201e8f74p-3, 0x1.de6cb62af18a0p-58}, {0x1.44d2b6ccb7d1ep-3, 0x1.9f4f6543e1f88p-57},
    {0x1.526e5e3a1b438p-3, -0x1.746ff8a470d3ap-57}, {0x1.5ff3070a793d4p-3, -0x1.bc60efafc6f6ep-58},
    {0x1.6d60fe719d21dp-3, -0x1.caae268ecd179p-57}, {0x1.7ab890210d909p-3, 0x1.be36b2d6a0608p-59},
    {0x1.87fa06520c911p-3, -0x1.bf7fdbfa08d9ap-57}, {0x1.9525a9cf456b4p-3, 0x1.d904c1d4e2e26p-57},
    {0x1.a23bc1fe2b563p-3, 0x1.93711b07a998cp-59}, {0x1.af3c94e80bff3p-3, -0x1.398cff3641985p-58},
    {0x1.bc286742d8cd6p-3, 0x1.4fce744870f55p-58}, {0x1.c8ff7c79a9a22p-3, -0x1.4f689f8434012p-57},
    {0x1.d5c216b4fbb91p-3, 0x1.6e443597e4d40p-57}, {0x1.e27076e2af2e6p-3, -0x1.61578001e0162p-59},
    {0x1.ef0adcbdc5936p-3, 0x1.48637950dc20dp-57}, {0x1.fb9186d5e3e2bp-3, -0x1.caaae64f21acbp-57},
    {0x1.0402594b4d041p-2, -0x1.28ec217a5022dp-57}, {0x1.0a324e27390e3p-2, 0x1.7dcfde8061c03p-56},
    {0x1.1058bf9ae4ad5p-2, 0x1.89fa0ab4cb31dp-58}, {0x1.1675cababa60ep-2, 0x1.ce63eab883717p-61},
    {0x1.1c898c16999fbp-2, -0x1.0e5c62aff1c44p-60}, {0x1.22941fbcf7966p-2, -0x1.76f5eb09628afp-56},
    {0x1.2895a13de86a3p-2, 0x1.7ad24c13f040ep-56}, {0x1.2e8e2bae11d31p-2, -0x1.8f4cdb95ebdf9p-56},
    {0x1.347dd9a987d55p-2, -0x1.4dd4c580919f8p-57}, {0x1.3a64c556945eap-2, -0x1.c68651945f97cp-57},
    {0x1.404308686a7e4p-2, -0x1.0bcfb6082ce6dp-56}, {0x1.4618bc21c5ec2p-2, 0x1.f42decdeccf1dp-56},
    {0x1.4be5f957778a1p-2, -0x1.259b35b04813dp-57}, {0x1.51aad872df82dp-2, 0x1.3927ac19f55e3p-59},
    {0x1.5767717455a6cp-2, 0x1.526adb283660cp-56}, {0x1.5d1bdbf5809cap-2, 0x1.4236383dc7fe1p-56},
    {0x1.62c82f2b9c795p-2, 0x1.7b7af915300e5p-57},
};

/* log x as *hi + *lo, relative error < 2^-68, for finite x > 0 (subnormals too).
   x = 2^k m, m in [sqrt(1/2), sqrt(2)] so k ln2 and log m never cancel; F = i/128
   nearest m; u = (m - F)/F in dd, |u| < 0.0056; log1p(u) by Taylor to u^10. */
static void log_dd(double x, double *hi, double *lo)
{
    uint64_t ix = bits_of(x);
    int32_t k = 0;
    if (ix < HIDDEN_BIT) { /* subnormal */
        ix = bits_of(x * 0x1p54);
        k = -54;
    }
    k += (int32_t)(ix >> 52) - 1023;
    ix = (ix & MANT_MASK) | 0x3ff0000000000000ull;
    if (ix > 0x3ff6a09e667f3bcdull) { /* m > sqrt(2): use m/2 */
        ix -= HIDDEN_BIT;
        k++;
    }
    double m = from_bits(ix);
    int32_t i = (int32_t)(m * 128.0 + 0.5);
    double F = (double)i * 0x1p-7, f = m - F; /* both exact */
    double uh = f / F, p, pe, q, qe;
    two_prod(uh, F, &p, &pe);
    double ul = ((f - p) - pe) / F;
    two_prod(uh, uh, &q, &qe);
    double poly = uh * q * (1.0 / 3 - uh * (0.25 - uh * (0.2 - uh * (1.0 / 6
                            - uh * (1.0 / 7 - uh * (0.125 - uh * (1.0 / 9 - uh * 0.1)))))));
    /* sum the large terms exactly, collect every error term in l */
    double s, e1, e2, e3;
    two_sum((double)k * LN2_HI, LOG_T[i - 91][0], &s, &e1);
    two_sum(s, uh, &s, &e2);
    two_sum(s, -0.5 * q, &s, &e3);
    double l = (double)k * LN2_LO + LOG_T[i - 91][1] + (ul - ul * uh) - 0.5 * qe + poly;
    fast_two_sum(s, ((e1 + e2) + e3) + l, hi, lo);
}

static double log_d(double x)
{
    double h, l;
    if (x != x || x < 0.0) return NAN_D;
    if (x == 0.0) return -INF_D;
    if (x == INF_D) return x;
    log_dd(x, &h, &l);
    return h;
}

/* ------------------------------------------------------------------ pow */

/* y is: 0 not an integer, 1 an odd integer, 2 an even integer (finite y), from bits. */
static int int_kind(double y)
{
    uint64_t u = bits_of(y) & ABS_MASK;
    int32_t e = (int32_t)(u >> 52) - 1023;
    if (e > 52) return 2;
    if (e < 0) return u == 0 ? 2 : 0;
    uint64_t m = (u & MANT_MASK) | HIDDEN_BIT;
    if (m & (MANT_MASK >> e)) return 0; /* fraction bits set */
    return ((m >> (52 - e)) & 1u) ? 1 : 2;
}

/* x^n for 2 <= n <= 64 by repeated squaring in dd: relative error < 2^-98, so rounding
   it to double is correct unless x^n lies within 2^-45 ulp of a midpoint. The caller
   keeps every power of x within 2^+-900 (no overflow, split limit or subnormals). */
static void pow_int_dd(double x, int32_t n, double *hi, double *lo)
{
    double rh = 1.0, rl = 0.0, bh = x, bl = 0.0, p, e;
    for (;;) {
        if (n & 1) {
            two_prod(rh, bh, &p, &e);
            fast_two_sum(p, e + (rh * bl + rl * bh), &rh, &rl);
        }
        n >>= 1;
        if (!n) break;
        two_prod(bh, bh, &p, &e);
        fast_two_sum(p, e + 2.0 * (bh * bl), &bh, &bl);
    }
    *hi = rh;
    *lo = rl;
}

static double pow_d(double x, double y)
{
    if (y == 0.0 || x == 1.0) return 1.0; /* even for NaN x (resp. y): C99 F.9.4.4 */
    if (x != x || y != y) return NAN_D;
    double ax = abs_d(x), ay = abs_d(y);
    if (ay == INF_D) {
        if (ax == 1.0) return 1.0;
        return ((ax > 1.0) == (y > 0.0)) ? INF_D : 0.0;
    }
    int kind = int_kind(y);
    int neg = x < 0.0 || (x == 0.0 && bits_of(x) >> 63);
    double sign = (neg && kind == 1) ? -1.0 : 1.0;
    if (ax == 0.0 || ax == INF_D) { /* (+-0)^y and (+-inf)^y: 0 or inf, sign if y odd */
        double r = ((ax == 0.0) == (y < 0.0)) ? INF_D : 0.0;
        return sign * r;
    }
    if (neg && kind == 0) return NAN_D;
    if (y == 1.0) return x;
    if (y == 2.0) return x * x;
    if (y == -1.0) return 1.0 / x;
    if (y == 0.5) return sqrt_d(ax); /* x > 0 here */
    if (ay > 0x1p64) /* |y log x| > 2^11 for every x != 1: over/underflow */
        return ((ax < 1.0) == (y > 0.0)) ? 0.0 : INF_D;
    int32_t ex = exp_field(ax) - 1023; /* ax in [2^ex, 2^(ex+1)) for normal ax */
    if (kind && ay <= 64.0 && exp_field(ax) != 0) {
        int32_t n = (int32_t)ay, em = ex < 0 ? -ex : ex + 1;
        if (em * n <= 900) {
            double h, l;
            pow_int_dd(ax, n, &h, &l);
            return sign * (y > 0.0 ? h : dd_div(1.0, 0.0, h, l));
        }
    }
    double lh, ll, th, tl, a, b;
    log_dd(ax, &lh, &ll);
    two_prod(y, lh, &th, &tl); /* y log x in dd */
    tl += y * ll;
    if (th > 709.8) return sign * INF_D;
    if (th < -745.2) return sign * 0.0;
    int32_t k = exp_core(th, tl, &a, &b);
    return sign * exp_scale(a, b, k);
}

/* ------------------------------------------------------------------ atan family */

/* atan(i/16), i = 0..16, as dd */
static const double ATAN_T[17][2] = {
    {0x0.0p+0, 0x0.0p+0}, {0x1.ff55bb72cfdeap-5, -0x1.c934d86d23f1dp-60},
    {0x1.fd5ba9aac2f6ep-4, -0x1.cd37686760c17p-59}, {0x1.7b97b4bce5b02p-3, 0x1.347b0b4f881cap-58},
    {0x1.f5b75f92c80ddp-3, 0x1.8ab6e3cf7afbdp-57}, {0x1.362773707ebccp-2, -0x1.963a544b672d8p-57},
    {0x1.6f61941e4def1p-2, -0x1.c63aae6f6e918p-56}, {0x1.a64eec3cc23fdp-2, -0x1.24dec1b50b7ffp-56},
    {0x1.dac670561bb4fp-2, 0x1.a2b7f222f65e2p-56}, {0x1.0657e94db30d0p-1, -0x1.d5b495f6349e6p-56},
    {0x1.1e00babdefeb4p-1, -0x1.928df287a668fp-58}, {0x1.345f01cce37bbp-1, 0x1.1021137c71102p-55},
    {0x1.4978fa3269ee1p-1, 0x1.2419a87f2a458p-56}, {0x1.5d58987169b18p-1, 0x1.0028e4bc5e7cap-57},
    {0x1.700a7c5784634p-1, -0x1.8c34d25aadef6p-56}, {0x1.819d0b7158a4dp-1, -0x1.bf76229d3b917p-56},
    {0x1.921fb54442d18p-1, 0x1.1a62633145c07p-55},
};

/* atan(vh + vl) as *hi + *lo for 0 <= v <= 1 (+tiny): atan v = atan c + atan t with
   c = i/16 nearest v, t = (v - c)/(1 + c v) in dd, |t| <= 1/32, Taylor to t^11 (the
   next term is below 2^-63 t). */
static void atan_core(double vh, double vl, double *hi, double *lo)
{
    int32_t i = (int32_t)(vh * 16.0 + 0.5);
    double c = (double)i * 0.0625, nh, nl, p, pe, dh, dl;
    two_sum(vh - c, vl, &nh, &nl); /* vh - c is exact */
    two_prod(c, vh, &p, &pe);
    fast_two_sum(1.0, p, &dh, &dl);
    dl += pe + c * vl;
    double th = nh / dh, q, qe;
    two_prod(th, dh, &q, &qe);
    double tl = (((nh - q) - qe) + nl - th * dl) / dh;
    double z = th * th;
    double poly = th * z * (1.0 / 3 - z * (0.2 - z * (1.0 / 7 - z * (1.0 / 9
                            - z * (1.0 / 11)))));
    double s, e;
    two_sum(ATAN_T[i][0], th, &s, &e);
    fast_two_sum(s, e + ATAN_T[i][1] + ((tl - tl * z) - poly), hi, lo);
}

/* atan2 of dd y >= 0, x >= 0 (not both 0) as *hi + *lo in [0, pi/2]: the smaller over
   the larger in dd, and pi/2 - atan(x/y) when y > x. Operands below 2^960. */
static void atan2_pos(double yh, double yl, double xh, double xl, double *hi, double *lo)
{
    int swap = yh > xh;
    double nh = swap ? xh : yh, nl = swap ? xl : yl;
    double dh = swap ? yh : xh, dl = swap ? yl : xl;
    double vh = nh / dh, p, pe, h, l;
    two_prod(vh, dh, &p, &pe);
    double vl = (((nh - p) - pe) + nl - vh * dl) / dh;
    atan_core(vh, vl, &h, &l);
    if (swap) {
        double s, e;
        two_sum(PIO2_H, -h, &s, &e);
        fast_two_sum(s, e + (PIO2_L - l), &h, &l);
    }
    *hi = h;
    *lo = l;
}

/* fa_pos, the faithful core of atan2_fa (below) */
static void fa_pos(double y, double x, double *hi, double *lo);

/* atan2 around a core for y >= 0, x >= 0: the special values, the scaling by 2^k (exact
   when it matters: keeps two_prod from overflowing and the dd remainders of a ratio >=
   2^-30 out of the subnormal range), the extreme ratios and the quadrants, shared by the
   correctly rounded atan2_d (atan2_pos) and the faithful atan2_fa (fa_pos) */
static double atan2_frame(double y, double x, int faithful)
{
    if (x != x || y != y) return NAN_D;
    double ax = abs_d(x), ay = abs_d(y), h = 0.0, l = 0.0;
    if (ax == INF_D && ay == INF_D) {
        h = 0.5 * PIO2_H;
        l = 0.5 * PIO2_L;
    } else if (ay == INF_D) {
        h = PIO2_H;
        l = PIO2_L;
    } else if (ax != INF_D && ay != 0.0) {
        double mx = ax > ay ? ax : ay;
        if (mx > 0x1p960) {
            ax *= 0x1p-128;
            ay *= 0x1p-128;
        } else if (mx < 0x1p-900) {
            ax *= 0x1p200;
            ay *= 0x1p200;
        }
        if (ay < ax * 0x1p-30) {
            h = ay / ax; /* atan v = v (1 - v^2/3): one rounding, right even if subnormal */
        } else if (ax < ay * 0x1p-30) {
            fast_two_sum(PIO2_H, PIO2_L - ax / ay, &h, &l);
        } else if (faithful) {
            fa_pos(ay, ax, &h, &l);
        } else {
            atan2_pos(ay, 0.0, ax, 0.0, &h, &l);
        }
    } /* else y == 0 or x == inf: angle 0 */
    if (bits_of(x) >> 63) { /* left half-plane: pi - angle */
        double s, e;
        two_sum(PI_H, -h, &s, &e);
        fast_two_sum(s, e + (PI_L - l), &h, &l);
    }
    h += l;
    return (bits_of(y) >> 63) ? -h : h;
}

static double atan2_d(double y, double x)
{
    return atan2_frame(y, x, 0);
}

/* sqrt(1 - x^2) as *hi + *lo for |x| <= 1: 1 - x^2 exactly in dd, one Newton correction
   on the rounded root. */
static void sqrt_1mx2(double ax, double *hi, double *lo)
{
    double p, pe, dh, dl, s, q, qe;
    two_prod(ax, ax, &p, &pe);
    two_sum(1.0, -p, &dh, &dl);
    fast_two_sum(dh, dl - pe, &dh, &dl);
    s = sqrt_d(dh);
    *hi = s;
    *lo = 0.0;
    if (s == 0.0) return;
    two_prod(s, s, &q, &qe);
    *lo = (((dh - q) - qe) + dl) / (2.0 * s);
}

static double asin_d(double x)
{
    double ax = abs_d(x), ch, cl, h, l;
    if (!(ax <= 1.0)) return NAN_D;
    if (ax < 0x1p-27) return x;
    sqrt_1mx2(ax, &ch, &cl);
    atan2_pos(ax, 0.0, ch, cl, &h, &l);
    h += l;
    return x < 0.0 ? -h : h;
}

static double acos_d(double x)
{
    double ax = abs_d(x), ch, cl, h, l;
    if (!(ax <= 1.0)) return NAN_D;
    sqrt_1mx2(ax, &ch, &cl);
    atan2_pos(ch, cl, ax, 0.0, &h, &l);
    if (x < 0.0) {
        double s, e;
        two_sum(PI_H, -h, &s, &e);
        fast_two_sum(s, e + (PI_L - l), &h, &l);
    }
    return h + l;
}

/* ------------------------------------------------------------------ faithful functions */

/* rt_atan_faithful, rt_atan2_faithful, rt_asin_faithful: faithfully rounded (the result
   is one of the two doubles around the exact value), for models whose results need no
   last-bit accuracy but call these in every stage (the tire law of a car, #13). The
   same table reduction as atan_core, but carried in plain double wherever the error
   analysis allows, so that no Dekker product is needed on the common paths:
   - |v| < 1/8: the odd Taylor series to v^19 (the next term is below 2^-57 v);
   - 1/8 <= v <= 1: atan v = atan c + atan t, c = i/64 nearest v, t = (n - c d)/(d + c n)
     for v = n/d. c d is exact with d's last 6 bits split off (c has at most 6
     significant bits), n - c d exact by Sterbenz (n/(c d) is within 1/16 of 1), so t
     carries at most 4 roundings: |dt| <= 2^-51 |t| <= 2^-55 atan v (|t| <= 1/128,
     atan v >= 1/8), below half an ulp with the table's 106 bits and one final rounding.
   The errors measured against the long double libm are in tests/host/test_rmath_libm.c. */

#define FA_SMALL 0.125        /* below: Taylor series in v */
#define FA_STEPS 64.0         /* table spacing 1/64 */
#define FA_FIRST 8            /* the first table entry, atan(8/64) */
#define FA_SPLIT 0xffffffffffffffc0ull /* clears a double's last 6 mantissa bits */

/* atan(i/64), i = 8..64, as dd */
static const double ATAN64_T[57][2] = {
    {0x1.fd5ba9aac2f6ep-4, -0x1.cd37686760c17p-59}, {0x1.1e1fafb043727p-3, -0x1.b485914dacf8cp-59},
    {0x1.3d6eee8c6626cp-3, 0x1.61a3b0ce9281bp-57}, {0x1.5c9811e3ec26ap-3, -0x1.054ab2c010f3dp-58},
    {0x1.7b97b4bce5b02p-3, 0x1.347b0b4f881cap-58}, {0x1.9a6a8e96c8626p-3, 0x1.cf601e7b4348ep-59},
    {0x1.b90d7529260a2p-3, 0x1.17b10d2e0e5abp-61}, {0x1.d77d5df205736p-3, 0x1.c648d1534597ep-57},
    {0x1.f5b75f92c80ddp-3, 0x1.8ab6e3cf7afbdp-57}, {0x1.09dc597d86362p-2, 0x1.62e47390cb865p-56},
    {0x1.18bf5a30bf178p-2, 0x1.30ca4748b1bf9p-57}, {0x1.278372057ef46p-2, -0x1.077cdd36dfc81p-56},
    {0x1.362773707ebccp-2, -0x1.963a544b672d8p-57}, {0x1.44aa436c2af0ap-2, -0x1.5d5e43c55b3bap-56},
    {0x1.530ad9951cd4ap-2, -0x1.2566480884082p-57}, {0x1.614840309cfe2p-2, -0x1.a725715711f00p-56},
    {0x1.6f61941e4def1p-2, -0x1.c63aae6f6e918p-56}, {0x1.7d5604b63b3f7p-2, 0x1.69c885c2b249ap-56},
    {0x1.8b24d394a1b25p-2, 0x1.b6d0ba3748fa8p-56}, {0x1.98cd5454d6b18p-2, 0x1.9e6c988fd0a77p-56},
    {0x1.a64eec3cc23fdp-2, -0x1.24dec1b50b7ffp-56}, {0x1.b3a911da65c6cp-2, 0x1.ae187b1ca5040p-56},
    {0x1.c0db4c94ec9f0p-2, -0x1.cc1ce70934c34p-56}, {0x1.cde53432c1351p-2, -0x1.a2cfa4418f1adp-56},
    {0x1.dac670561bb4fp-2, 0x1.a2b7f222f65e2p-56}, {0x1.e77eb7f175a34p-2, 0x1.0e53dc1bf3435p-56},
    {0x1.f40dd0b541418p-2, -0x1.a3992dc382a23p-57}, {0x1.0039c73c1a40cp-1, -0x1.b32c949c9d593p-55},
    {0x1.0657e94db30d0p-1, -0x1.d5b495f6349e6p-56}, {0x1.0c6145b5b43dap-1, 0x1.974fa13b5404fp-58},
    {0x1.1255d9bfbd2a9p-1, -0x1.2bdaee1c0ee35p-58}, {0x1.1835a88be7c13p-1, 0x1.c621cec00c301p-55},
    {0x1.1e00babdefeb4p-1, -0x1.928df287a668fp-58}, {0x1.23b71e2cc9e6ap-1, 0x1.c421c9f38224ep-57},
    {0x1.2958e59308e31p-1, -0x1.09e73b0c6c087p-56}, {0x1.2ee628406cbcap-1, 0x1.c5d5e9ff0cf8dp-55},
    {0x1.345f01cce37bbp-1, 0x1.1021137c71102p-55}, {0x1.39c391cd4171ap-1, -0x1.2304331d8bf46p-55},
    {0x1.3f13fb89e96f4p-1, 0x1.ecf8b492644f0p-56}, {0x1.445065b795b56p-1, -0x1.f76d0163f79c8p-56},
    {0x1.4978fa3269ee1p-1, 0x1.2419a87f2a458p-56}, {0x1.4e8de5bb6ec04p-1, 0x1.4a33dbeb3796cp-55},
    {0x1.538f57b89061fp-1, -0x1.1bb74abda520cp-55}, {0x1.587d81f732fbbp-1, -0x1.5e5c9d8c5a950p-56},
    {0x1.5d58987169b18p-1, 0x1.0028e4bc5e7cap-57}, {0x1.6220d115d7b8ep-1, -0x1.2b785350ee8c1p-57},
    {0x1.66d663923e087p-1, -0x1.6ea6febe8bbbap-56}, {0x1.6b798920b3d99p-1, -0x1.a80386188c50ep-55},
    {0x1.700a7c5784634p-1, -0x1.8c34d25aadef6p-56}, {0x1.748978fba8e0fp-1, 0x1.7b2a6165884a1p-59},
    {0x1.78f6bbd5d315ep-1, 0x1.406a089803740p-55}, {0x1.7d528289fa093p-1, 0x1.560821e2f3aa9p-55},
    {0x1.819d0b7158a4dp-1, -0x1.bf76229d3b917p-56}, {0x1.85d69576cc2c5p-1, 0x1.6b66e7fc8b8c3p-57},
    {0x1.89ff5ff57f1f8p-1, -0x1.55b9a5e177a1bp-55}, {0x1.8e17aa99cc05ep-1, -0x1.ec182ab042f61p-56},
    {0x1.921fb54442d18p-1, 0x1.1a62633145c07p-55}
};

/* atan(vh + vl) - vh for |vh| < 1/8, |vl| <= ulp(vh): the odd Taylor series (-1)^k
   v^(2k+1)/(2k+1) from k = 1 to 9, plus the tail vl (its products are below 2^-58 vl) */
static double fa_series(double vh, double vl)
{
    double z = vh * vh;
    double p = -1.0 / 3 + z * (1.0 / 5 + z * (-1.0 / 7 + z * (1.0 / 9 + z * (-1.0 / 11
               + z * (1.0 / 13 + z * (-1.0 / 15 + z * (1.0 / 17 + z * (-1.0 / 19))))))));
    return vl + vh * z * p;
}

/* atan(n / (d + dl)) as *hi + *lo for 0 < n <= d, |dl| <= ulp(d), q = n/d rounded and
   1/8 <= q <= 1: the table path above (dl, asin's root in dd, enters t to first order) */
static void fa_table(double n, double d, double dl, double q, double *hi, double *lo)
{
    int32_t i = (int32_t)(q * FA_STEPS + 0.5);
    double c = (double)i * (1.0 / FA_STEPS);
    double dh = from_bits(bits_of(d) & FA_SPLIT), e;
    double t = (((n - c * dh) - c * (d - dh)) - c * dl) / ((d + c * n) + dl);
    double z = t * t;
    double p = t * z * (-1.0 / 3 + z * (1.0 / 5 + z * (-1.0 / 7 + z * (1.0 / 9))));
    fast_two_sum(ATAN64_T[i - FA_FIRST][0], t, hi, &e);
    *lo = e + (ATAN64_T[i - FA_FIRST][1] + p);
}

/* atan(n / (d + dl)) as *hi + *lo for 0 <= n <= d (d > 0, |dl| <= ulp(d), operands
   scaled as atan2_frame does): the series with the quotient's remainder, or the table */
static void fa_ratio(double n, double d, double dl, double *hi, double *lo)
{
    double q = n / d;
    if (q >= FA_SMALL) {
        fa_table(n, d, dl, q, hi, lo);
        return;
    }
    double p, pe;
    two_prod(q, d, &p, &pe); /* q's remainder: the series' result is as large as q */
    *hi = q;
    *lo = fa_series(q, (((n - p) - pe) - q * dl) / d);
}

/* pi/2 - (hi + lo) as *hi + *lo, for 0 <= hi + lo <= pi/4 */
static void fa_complement(double *hi, double *lo)
{
    double s, e;
    two_sum(PIO2_H, -*hi, &s, &e);
    *lo = e + (PIO2_L - *lo);
    *hi = s;
}

/* atan2 of y >= 0, x >= 0 (not both 0), scaled as in atan2_frame, as *hi + *lo */
static void fa_pos(double y, double x, double *hi, double *lo)
{
    if (y > x) {
        fa_ratio(x, y, 0.0, hi, lo);
        fa_complement(hi, lo);
    } else {
        fa_ratio(y, x, 0.0, hi, lo);
    }
}

/* atan of 2^-27 <= ax <= 2^60, faithfully, as *h + *l: the series, the table, or
   pi/2 - atan(1/ax) */
static void atan_fa_core(double ax, double *h, double *l)
{
    if (ax < FA_SMALL) {
        *h = ax, *l = fa_series(ax, 0.0);
    } else if (ax <= 1.0) {
        fa_table(ax, 1.0, 0.0, ax, h, l);
    } else {
        /* pi/2 - atan(1/x): the error of 1/x moves the result by < 2^-56 of pi/2 */
        double q = 1.0 / ax;
        if (q < FA_SMALL) {
            *h = q, *l = fa_series(q, 0.0);
        } else {
            fa_table(1.0, ax, 0.0, q, h, l);
        }
        fa_complement(h, l);
    }
}

/* atan(x), correctly rounded or faithfully: one frame (NaN, tiny and huge arguments, the
   sign) around either core, as atan2_frame */
static double atan_frame(double x, int faithful)
{
    double ax = abs_d(x), h, l = 0.0;
    if (x != x) return NAN_D;
    if (ax < 0x1p-27) return x;
    if (ax > 0x1p60) {
        h = PIO2_H; /* pi/2 - 1/x rounds to PIO2_H */
    } else if (faithful) {
        atan_fa_core(ax, &h, &l);
    } else {
        atan2_pos(ax, 0.0, 1.0, 0.0, &h, &l);
    }
    h += l;
    return x < 0.0 ? -h : h;
}

static double atan_d(double x)
{
    return atan_frame(x, 0);
}

static double atan_fa(double x)
{
    return atan_frame(x, 1);
}

static double atan2_fa(double y, double x)
{
    return atan2_frame(y, x, 1);
}

/* asin x: below 1/8 its odd Taylor series to x^17 (the next term is below 2^-61 x);
   above, atan2(x, sqrt(1 - x^2)) with the root in dd */
static double asin_fa(double x)
{
    double ax = abs_d(x), h, l;
    if (!(ax <= 1.0)) return NAN_D;
    if (ax < 0x1p-27) return x;
    if (ax < FA_SMALL) {
        double z = ax * ax;
        double p = 1.0 / 6 + z * (3.0 / 40 + z * (5.0 / 112 + z * (35.0 / 1152 + z * (63.0 / 2816
                   + z * (231.0 / 13312 + z * (143.0 / 10240 + z * (6435.0 / 557056)))))));
        h = ax + ax * z * p;
    } else {
        double ch, cl;
        sqrt_1mx2(ax, &ch, &cl);
        if (ax > ch) {
            /* pi/2 - atan(c/x) with the root's tail cl to first order: on the unit
               circle x^2 + c^2 = 1, d atan(c/x) / dc = x / (x^2 + c^2) = x */
            fa_ratio(ch, ax, 0.0, &h, &l);
            l += ax * cl;
            fa_complement(&h, &l);
        } else {
            fa_ratio(ax, ch, cl, &h, &l);
        }
        h += l;
    }
    return x < 0.0 ? -h : h;
}

/* rt_sin_faithful: faithfully rounded sine, for the same models (the Magic Formula takes
   the sine of C atan(...), |C atan| < pi for its C < 2). Below 3 pi/4 it needs no general
   reduction: sin x by the minimax kernel in plain double up to pi/4, and cos(|x| - pi/2)
   above, with |x| - pi/2 in two parts (|x| - PIO2_1 is exact by Sterbenz) and z = r^2
   rounded: |error| < 0.31 ulp from z, the rest < 0.05 ulp, before the final rounding.
   Beyond 3 pi/4 (and for inf, NaN) it is rt_sin. */
#define SF_FAST_BITS 0x4002d97c7f3321d2ull /* 3 pi/4 */

static double sin_fa(double x)
{
    uint64_t ix = bits_of(x) & ABS_MASK;
    double ax = abs_d(x), h;
    if (ix >= SF_FAST_BITS) return sin_cos_d(x, 0);
    if (ix < TINY_BITS) return x;
    if (ix <= PIO4_BITS) {
        double z = ax * ax, w = z * z;
        double r = S2 + z * (S3 + z * S4) + z * w * (S5 + z * S6);
        h = ax + ax * z * (S1 + z * r);
    } else {
        double r0 = ax - PIO2_1, y0 = r0 - PIO2_1T, y1 = (r0 - y0) - PIO2_1T;
        double z = y0 * y0, w = z * z, hz = 0.5 * z, c = 1.0 - hz;
        double r = z * (C1 + z * (C2 + z * C3)) + w * w * (C4 + z * (C5 + z * C6));
        h = c + (((1.0 - c) - hz) + (z * r - y0 * y1));
    }
    return x < 0.0 ? -h : h;
}

/* ------------------------------------------------------------------ tanh */

static double tanh_d(double x)
{
    double ax = abs_d(x), h;
    if (x != x) return NAN_D;
    if (ax > 22.0) {
        h = 1.0; /* 1 - tanh(22) < 2^-60 */
    } else if (ax < 0x1p-28) {
        return x;
    } else if (ax < 0.0625) {
        /* Taylor to x^13, the next term is below 2^-65 x */
        double z = x * x;
        h = ax + ax * z * (-1.0 / 3 + z * (2.0 / 15 + z * (-17.0 / 315 + z * (62.0 / 2835
                           + z * (-1382.0 / 155925 + z * (21844.0 / 6081075))))));
    } else {
        /* E = e^2|x| in dd, then (E - 1) / (E + 1): no cancellation left for |x| >= 1/16 */
        double a, b, eh, el, nh, nl, dh, dl;
        int32_t k = exp_core(2.0 * ax, 0.0, &a, &b);
        fast_two_sum(a * pow2(k), b * pow2(k), &eh, &el);
        two_sum(eh, -1.0, &nh, &nl);
        two_sum(eh, 1.0, &dh, &dl);
        h = dd_div(nh, nl + el, dh, dl + el);
    }
    return x < 0.0 ? -h : h;
}

/* ------------------------------------------------------------------ public API */

#if RT_REAL_IS_FLOAT

typedef union {
    float f;
    uint32_t u;
} rmath_b32;

static inline uint32_t bits_f(float x)
{
    rmath_b32 b;
    b.f = x;
    return b.u;
}

static inline float from_bits_f(uint32_t u)
{
    rmath_b32 b;
    b.u = u;
    return b.f;
}

/* Rounds a double result to float; NaN becomes the canonical float NaN, because some
   FPUs (RISC-V) canonicalise NaNs on conversion and others keep the payload. */
static inline real_t R(double v)
{
    return v != v ? from_bits_f(0x7fc00000u) : (float)v;
}

real_t(rt_sqrt)(real_t x) /* the name in parentheses: not rt_math.h's inline macro */
{
    if (!(x >= 0.0f)) return from_bits_f(0x7fc00000u); /* x < 0 or NaN; -0 passes */
#if RT_HW_SQRT_F
    return __builtin_sqrtf(x);
#else
    return (float)rti_sqrt_soft((double)x); /* 53 >= 2*24 + 2: double rounding is exact */
#endif
}

/* floor by clearing the fraction bits; NaN, inf and integers come back unchanged. */
real_t rt_floor(real_t x)
{
    uint32_t u = bits_f(x);
    int32_t e = (int32_t)((u >> 23) & 0xff) - 127;
    if (e >= 23) return x;
    if (e < 0) return (u >> 31) ? (x == 0.0f ? x : -1.0f) : 0.0f;
    uint32_t frac = 0x007fffffu >> e;
    if (!(u & frac)) return x;
    float t = from_bits_f(u & ~frac);
    return (u >> 31) ? t - 1.0f : t;
}

#define RT_SIGNBIT(v) (bits_f(v) >> 31)

#else /* double */

#define R(v) (v)

real_t(rt_sqrt)(real_t x) /* the name in parentheses: not rt_math.h's inline macro */
{
    if (!(x >= 0.0)) return NAN_D; /* x < 0 or NaN; -0 passes */
#if RT_HW_SQRT_D
    return __builtin_sqrt(x);
#else
    return rti_sqrt_soft(x);
#endif
}

/* floor by clearing the fraction bits; NaN, inf and integers come back unchanged. */
real_t rt_floor(real_t x)
{
    uint64_t u = bits_of(x);
    int32_t e = (int32_t)((u >> 52) & 0x7ff) - 1023;
    if (e >= 52) return x;
    if (e < 0) return (u >> 63) ? (x == 0.0 ? x : -1.0) : 0.0;
    uint64_t frac = MANT_MASK >> e;
    if (!(u & frac)) return x;
    double t = from_bits(u & ~frac);
    return (u >> 63) ? t - 1.0 : t;
}

#define RT_SIGNBIT(v) (bits_of(v) >> 63)

#endif

/* fmin/fmax return one of their arguments unchanged: a NaN loses to a number, and of two
   equal values (+0 and -0) fmin picks the negative one, fmax the positive one. */
real_t rt_fmin(real_t a, real_t b)
{
    if (a != a) return b;
    if (b != b) return a;
    if (a < b) return a;
    if (b < a) return b;
    return RT_SIGNBIT(a) ? a : b;
}

real_t rt_fmax(real_t a, real_t b)
{
    if (a != a) return b;
    if (b != b) return a;
    if (a > b) return a;
    if (b > a) return b;
    return RT_SIGNBIT(a) ? b : a;
}

real_t rt_sin(real_t x) { return R(sin_cos_d((double)x, 0)); }
real_t rt_cos(real_t x) { return R(sin_cos_d((double)x, 1)); }
real_t rt_tan(real_t x) { return R(tan_d((double)x)); }
real_t rt_atan(real_t x) { return R(atan_d((double)x)); }
real_t rt_atan2(real_t y, real_t x) { return R(atan2_d((double)y, (double)x)); }
real_t rt_asin(real_t x) { return R(asin_d((double)x)); }
real_t rt_acos(real_t x) { return R(acos_d((double)x)); }
real_t rt_exp(real_t x) { return R(exp_d((double)x)); }
real_t rt_log(real_t x) { return R(log_d((double)x)); }
real_t rt_pow(real_t x, real_t y) { return R(pow_d((double)x, (double)y)); }
real_t rt_tanh(real_t x) { return R(tanh_d((double)x)); }
real_t rt_atan_faithful(real_t x) { return R(atan_fa((double)x)); }
real_t rt_atan2_faithful(real_t y, real_t x) { return R(atan2_fa((double)y, (double)x)); }
real_t rt_asin_faithful(real_t x) { return R(asin_fa((double)x)); }
real_t rt_sin_faithful(real_t x) { return R(sin_fa((double)x)); }
