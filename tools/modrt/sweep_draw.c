/* sweep_draw.c - the Monte-Carlo draws of a campaign: counter-based, so the value of a
 * variable at draw d is a function of (seed, d, the variable's name) alone: no generator
 * state, the same value whichever run, process or machine asks, in any order. The
 * arithmetic is + - * / and the IEEE square root only (the log and exp below instead of
 * libm's, which differ between C libraries), so the bits are the same everywhere. */
#include <math.h> /* NAN, HUGE_VAL; sqrt is the IEEE instruction */
#include <stdint.h>
#include <string.h>

#include "sweep.h"

#define LN2_HI 6.93147180369123816490e-01 /* ln 2 in two parts: k * LN2_HI is exact */
#define LN2_LO 1.90821492927058770002e-10
#define SQRT2 1.41421356237309504880
#define LOG_TERMS 14 /* s^2 <= 0.0295: 14 terms of the atanh series reach 1e-21 */
#define EXP_TERMS 20 /* |r| <= 0.35: 20 Taylor terms reach 1e-25 */

/* SplitMix64's finaliser: a bijection of 64-bit words that mixes every bit */
static uint64_t mix(uint64_t z)
{
    z += 0x9e3779b97f4a7c15ull;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

uint64_t sweep_hash(uint64_t seed, uint64_t draw, uint64_t key, uint64_t attempt)
{
    return mix(mix(mix(mix(seed) ^ draw) ^ key) ^ attempt);
}

/* a uniform number in (0, 1): 53 bits, never 0 or 1 */
static double unit(uint64_t h)
{
    return ((double)(h >> 11) + 0.5) * (1.0 / 9007199254740992.0);
}

double sweep_floor(double x)
{
    if (!(x > -4503599627370496.0 && x < 4503599627370496.0)) /* |x| >= 2^52: whole */
        return x;
    double t = (double)(int64_t)x; /* toward zero */
    return t > x ? t - 1 : t;
}

/* x 2^k for |k| <= 1023 + 52, exactly (the result may be subnormal) */
static double scale2(double x, int k)
{
    while (k > 0) {
        int s = k > 1000 ? 1000 : k;
        uint64_t b = (uint64_t)(1023 + s) << 52;
        double f;
        memcpy(&f, &b, sizeof f);
        x *= f, k -= s;
    }
    while (k < 0) {
        int s = k < -1000 ? 1000 : -k;
        uint64_t b = (uint64_t)(1023 - s) << 52;
        double f;
        memcpy(&f, &b, sizeof f);
        x *= f, k += s;
    }
    return x;
}

double sweep_log(double x)
{
    if (!(x > 0) || x != x || x > 1.7976931348623157e308)
        return x == 0 ? -HUGE_VAL : x > 0 ? x : NAN;
    int e = 0;
    if (x < 2.2250738585072014e-308) /* subnormal: scale into the normal range */
        x *= 18014398509481984.0, e = -54;
    uint64_t b;
    memcpy(&b, &x, sizeof b);
    e += (int)((b >> 52) & 0x7ff) - 1023;
    b = (b & 0x000fffffffffffffull) | 0x3ff0000000000000ull; /* m in [1, 2) */
    double m;
    memcpy(&m, &b, sizeof m);
    if (m > SQRT2)
        m *= 0.5, e++;
    /* ln m = 2 atanh(s), s = (m - 1) / (m + 1), |s| < 0.172 */
    double s = (m - 1) / (m + 1), s2 = s * s, term = s, sum = 0;
    for (int k = 0; k < LOG_TERMS; k++) {
        sum += term / (2 * k + 1);
        term *= s2;
    }
    return (double)e * LN2_HI + ((double)e * LN2_LO + 2 * sum);
}

double sweep_exp(double x)
{
    if (x != x)
        return x;
    if (x > 709.782712893384)
        return HUGE_VAL;
    if (x < -745.2)
        return 0;
    /* x = k ln 2 + r, |r| <= ln2 / 2 */
    double k = sweep_floor(x * 1.4426950408889634 + 0.5);
    double r = (x - k * LN2_HI) - k * LN2_LO, term = 1, sum = 1;
    for (int i = 1; i <= EXP_TERMS; i++) {
        term *= r / i;
        sum += term;
    }
    return scale2(sum, (int)k); /* exact but for a subnormal result */
}

/* a standard normal by Marsaglia's polar method from attempt pair j; 0 with *ok = 0
   when the pair falls outside the unit disc */
static double polar(uint64_t seed, uint64_t d, uint64_t key, uint64_t j, int *ok)
{
    double u = 2 * unit(sweep_hash(seed, d, key, 2 * j)) - 1;
    double v = 2 * unit(sweep_hash(seed, d, key, 2 * j + 1)) - 1;
    double s = u * u + v * v;
    *ok = s < 1 && s > 0;
    return *ok ? u * sqrt(-2 * sweep_log(s) / s) : 0;
}

double sweep_draw(const sweep_var *v, uint64_t seed, uint64_t d)
{
    double x;
    switch (v->dist) {
    case SWEEP_UNIFORM:
        x = v->lo + unit(sweep_hash(seed, d, v->key, 0)) * (v->hi - v->lo);
        break;
    case SWEEP_LOGUNIFORM: {
        double a = sweep_log(v->lo), b = sweep_log(v->hi);
        x = sweep_exp(a + unit(sweep_hash(seed, d, v->key, 0)) * (b - a));
        break;
    }
    default: /* normal, by rejection within the bounds (they hold >= SWEEP_NORMAL_MASS) */
        for (uint64_t j = 0; j < SWEEP_DRAW_TRIES; j++) {
            int ok;
            x = v->a + v->b * polar(seed, d, v->key, j, &ok);
            if (ok && x >= v->lo && x <= v->hi)
                return x;
        }
        return NAN;
    }
    /* the rounding of lo + u (hi - lo) or of exp may land a last bit outside */
    return x < v->lo ? v->lo : x > v->hi ? v->hi : x;
}
