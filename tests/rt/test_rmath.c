/* test_rmath.c - portable tests of rt/rmath.c: known values, special values, identities
 * over many points, and a golden hash of results that must be the same on every target.
 *
 * No libm, no stdio: the same file runs on the host and on bare metal under QEMU.
 * Tolerances are in units of RT_EPS, so they hold for real_t = double and float. The
 * accuracy against a reference libm is measured by tests/host/test_rmath_libm.c. */
#include <stdint.h>

#include "harness.h"
#include "rt_math.h"

#define EPS ((double)RT_EPS)

typedef union {
    real_t f;
#if RT_REAL_IS_FLOAT
    uint32_t u;
#else
    uint64_t u;
#endif
} bits_u;

static uint64_t bits(real_t x)
{
    bits_u b;
    b.f = x;
    return b.u;
}

static real_t from_bits(uint64_t u)
{
    bits_u b;
    b.u = u;
    return b.f;
}

#if RT_REAL_IS_FLOAT
#define SIGN_BIT 0x80000000ull
#define QNAN_BITS 0x7fc00000ull
#define INF_BITS 0x7f800000ull
#else
#define SIGN_BIT 0x8000000000000000ull
#define QNAN_BITS 0x7ff8000000000000ull
#define INF_BITS 0x7ff0000000000000ull
#endif

static int is_nan(real_t x) { return x != x; }
static int is_neg(real_t x) { return (bits(x) & SIGN_BIT) != 0; }
static double dabs(double x) { return x < 0 ? -x : x; }

/* relative closeness: |a - b| <= k EPS |b| (absolute k EPS when b == 0) */
#define REL(a, b, k) TH_NEAR((a), (b), (k) * EPS * ((b) != 0 ? dabs((double)(b)) : 1.0))

/* deterministic inputs, identical on every target (integer LCG, exact conversions) */
static uint64_t lcg_state;

static void lcg_seed(uint64_t s) { lcg_state = s; }

static uint32_t lcg(void)
{
    lcg_state = lcg_state * 6364136223846793005ull + 1442695040888963407ull;
    return (uint32_t)(lcg_state >> 32);
}

static real_t uni(double a, double b) /* in [a, b), rounded to real_t */
{
    return (real_t)(a + (b - a) * ((double)lcg() * (1.0 / 4294967296.0)));
}

/* ------------------------------------------------------------------ values */

static void check_known_values(void)
{
    const real_t pi = (real_t)RT_PI;
    REL(rt_sin(pi / 6), 0.5, 2);
    REL(rt_cos(pi / 3), 0.5, 2);
    REL(rt_sin((real_t)RT_HALF_PI), 1.0, 1);
    REL(rt_tan(pi / 4), 1.0, 2);
    REL(rt_sin(1), 0.84147098480789650665, 1);
    REL(rt_cos(1), 0.54030230586813971740, 1);
    REL(rt_tan(1), 1.5574077246549022305, 1);
    REL(rt_sin(100), -0.50636564110975879366, 1);
    REL(rt_cos(1e5), -0.99936080743821245189, 1);
    TH_CHECK(rt_cos(0) == 1 && rt_sin(0) == 0);

    REL(rt_atan(1), RT_PI / 4, 1);
    REL(rt_atan(-1e30), -RT_HALF_PI, 1);
    REL(rt_asin((real_t)0.5), RT_PI / 6, 1);
    REL(rt_acos((real_t)0.5), RT_PI / 3, 1);
    REL(rt_asin(1), RT_HALF_PI, 1);
    REL(rt_acos(-1), RT_PI, 1);
    TH_CHECK(rt_acos(1) == 0 && !is_neg(rt_acos(1)));
    /* atan2 in all four quadrants and on the axes */
    REL(rt_atan2(1, 1), RT_PI / 4, 1);
    REL(rt_atan2(1, -1), 3 * RT_PI / 4, 1);
    REL(rt_atan2(-1, -1), -3 * RT_PI / 4, 1);
    REL(rt_atan2(-1, 1), -RT_PI / 4, 1);
    REL(rt_atan2(2, 0), RT_HALF_PI, 1);
    REL(rt_atan2(-2, 0), -RT_HALF_PI, 1);
    REL(rt_atan2(0, -3), RT_PI, 1);
    REL(rt_atan2(-(real_t)0, -3), -RT_PI, 1);
    REL(rt_atan2(1, (real_t)1.7320508075688772935), RT_PI / 6, 2);

    TH_CHECK(rt_exp(0) == 1);
    REL(rt_exp(1), 2.7182818284590452354, 1);
    REL(rt_exp(-1), 0.36787944117144232160, 1);
    REL(rt_exp(10), 22026.465794806716517, 1);
    REL(rt_exp(-20), 2.0611536224385578280e-9, 1);
    TH_CHECK(rt_log(1) == 0);
    REL(rt_log(10), 2.3025850929940456840, 1);
    REL(rt_log(2), 0.69314718055994530942, 1);
    REL(rt_log((real_t)0.5), -0.69314718055994530942, 1);
    REL(rt_log((real_t)1e-30), -69.077552789821370437, 1);
    REL(rt_log((real_t)2.7182818284590452354), 1.0, 2);

    REL(rt_pow(2, (real_t)0.5), 1.4142135623730950488, 1);
    TH_CHECK(rt_pow(2, 10) == 1024);
    TH_CHECK(rt_pow(10, 2) == 100);
    TH_CHECK(rt_pow(3, 13) == 1594323);
    TH_CHECK(rt_pow(-2, 3) == -8);
    TH_CHECK(rt_pow(-2, -2) == (real_t)0.25);
    TH_CHECK(rt_pow(2, -3) == (real_t)0.125);
    TH_CHECK(rt_pow(9, (real_t)0.5) == 3);
    TH_CHECK(rt_pow(16, (real_t)0.25) == 2);
    REL(rt_pow(10, -3), 1e-3, 1);
    REL(rt_pow(8, (real_t)(1.0 / 3.0)), 2.0, 2);
    REL(rt_pow((real_t)1.5, (real_t)2.5), 2.7556759606310753604, 1);

    TH_CHECK(rt_tanh(0) == 0);
    REL(rt_tanh((real_t)0.5), 0.46211715726000975850, 1);
    REL(rt_tanh(-3), -0.99505475368673045133, 1);
    REL(rt_tanh((real_t)0.01), 0.0099996666799994603393, 2);
    TH_CHECK(rt_tanh(30) == 1 && rt_tanh(-30) == -1);

    /* square roots are correctly rounded: exact bits */
#if RT_REAL_IS_FLOAT
    TH_EQ_U64(bits(rt_sqrt(2)), 0x3fb504f3u);
    TH_EQ_U64(bits(rt_sqrt(3)), 0x3fddb3d7u);
    TH_EQ_U64(bits(rt_sqrt(from_bits(1))), 0x1a3504f3u); /* smallest subnormal */
#else
    TH_EQ_U64(bits(rt_sqrt(2)), 0x3ff6a09e667f3bcdull);
    TH_EQ_U64(bits(rt_sqrt(3)), 0x3ffbb67ae8584caaull);
    TH_EQ_U64(bits(rt_sqrt(from_bits(1))), 0x1e60000000000000ull); /* sqrt(2^-1074) = 2^-537 */
#endif
    TH_CHECK(rt_sqrt(4) == 2 && rt_sqrt((real_t)0.25) == (real_t)0.5);

    /* the exact helpers */
    TH_CHECK(rt_floor((real_t)2.5) == 2 && rt_floor((real_t)-2.5) == -3);
    TH_CHECK(rt_floor((real_t)-0.5) == -1 && rt_floor((real_t)0.5) == 0);
    TH_CHECK(rt_floor(-3) == -3 && rt_floor((real_t)1e30) == (real_t)1e30);
    TH_CHECK(rt_floor(-(real_t)0) == 0 && is_neg(rt_floor(-(real_t)0)));
    TH_CHECK(rt_fabs(-3) == 3 && !is_neg(rt_fabs(-(real_t)0)));
    TH_CHECK(rt_fmin(1, 2) == 1 && rt_fmax(1, 2) == 2);
    TH_CHECK(rt_fmin(-(real_t)0, 0) == 0 && is_neg(rt_fmin(0, -(real_t)0)));
    TH_CHECK(!is_neg(rt_fmax(-(real_t)0, 0)));
}

static void check_special_values(void)
{
    const real_t inf = from_bits(INF_BITS), nan = from_bits(QNAN_BITS), z = 0;
    real_t (*const unary[])(real_t) = {rt_sqrt, rt_sin, rt_cos, rt_tan, rt_atan, rt_asin,
                                       rt_acos, rt_exp, rt_log, rt_tanh};
    for (unsigned i = 0; i < sizeof unary / sizeof unary[0]; i++) {
        /* NaN in, canonical NaN out (bit-identical on every FPU) */
        TH_EQ_U64(bits(unary[i](nan)), QNAN_BITS);
        TH_EQ_U64(bits(unary[i](-nan)), QNAN_BITS);
    }
    TH_EQ_U64(bits(rt_atan2(nan, 1)), QNAN_BITS);
    TH_EQ_U64(bits(rt_pow(nan, 2)), QNAN_BITS);
    TH_CHECK(is_nan(rt_sqrt(-1)) && is_nan(rt_sqrt(-inf)));
    TH_CHECK(rt_sqrt(inf) == inf && rt_sqrt(-z) == 0 && is_neg(rt_sqrt(-z)));
    TH_CHECK(is_nan(rt_sin(inf)) && is_nan(rt_cos(-inf)) && is_nan(rt_tan(inf)));
    TH_CHECK(is_neg(rt_sin(-z)) && is_neg(rt_tan(-z)) && is_neg(rt_atan(-z)));
    TH_CHECK(is_neg(rt_asin(-z)) && is_neg(rt_tanh(-z)));
    TH_CHECK(is_nan(rt_asin((real_t)1.5)) && is_nan(rt_acos((real_t)-1.0000001)));
    TH_CHECK(rt_exp(inf) == inf && rt_exp(-inf) == 0 && rt_exp(-z) == 1);
    TH_CHECK(rt_exp(1000) == inf && rt_exp(-1000) == 0 && !is_neg(rt_exp(-1000)));
    TH_CHECK(rt_log(z) == -inf && rt_log(-z) == -inf && rt_log(inf) == inf);
    TH_CHECK(is_nan(rt_log(-1)) && is_nan(rt_log(-inf)));
    REL(rt_atan(inf), RT_HALF_PI, 1);
    REL(rt_atan(-inf), -RT_HALF_PI, 1);
    TH_CHECK(rt_tanh(inf) == 1 && rt_tanh(-inf) == -1);

    /* atan2 with zeros and infinities (C99 Annex F) */
    TH_CHECK(rt_atan2(z, z) == 0 && !is_neg(rt_atan2(z, z)));
    TH_CHECK(rt_atan2(-z, z) == 0 && is_neg(rt_atan2(-z, z)));
    REL(rt_atan2(z, -z), RT_PI, 1);
    REL(rt_atan2(-z, -z), -RT_PI, 1);
    REL(rt_atan2(inf, inf), RT_PI / 4, 1);
    REL(rt_atan2(-inf, -inf), -3 * RT_PI / 4, 1);
    REL(rt_atan2(1, -inf), RT_PI, 1);
    TH_CHECK(rt_atan2(-1, inf) == 0 && is_neg(rt_atan2(-1, inf)));
    REL(rt_atan2(inf, -1), RT_HALF_PI, 1);

    /* pow special cases (C99 Annex F) */
    TH_CHECK(rt_pow(nan, 0) == 1 && rt_pow(1, nan) == 1 && rt_pow(inf, -z) == 1);
    TH_CHECK(rt_pow(-1, inf) == 1 && rt_pow(-1, -inf) == 1);
    TH_CHECK(rt_pow(z, -1) == inf && rt_pow(-z, -1) == -inf && rt_pow(-z, -2) == inf);
    TH_CHECK(rt_pow(-z, 3) == 0 && is_neg(rt_pow(-z, 3)) && !is_neg(rt_pow(-z, 2)));
    TH_CHECK(rt_pow(-z, (real_t)0.5) == 0 && !is_neg(rt_pow(-z, (real_t)0.5)));
    TH_CHECK(rt_pow((real_t)0.5, inf) == 0 && rt_pow((real_t)0.5, -inf) == inf);
    TH_CHECK(rt_pow(2, -inf) == 0 && rt_pow(-2, inf) == inf);
    TH_CHECK(rt_pow(-inf, 3) == -inf && rt_pow(-inf, 2) == inf);
    TH_CHECK(rt_pow(-inf, -3) == 0 && is_neg(rt_pow(-inf, -3)));
    TH_CHECK(rt_pow(inf, -2) == 0 && rt_pow(inf, (real_t)0.5) == inf);
    TH_CHECK(is_nan(rt_pow(-8, (real_t)(1.0 / 3.0))) && is_nan(rt_pow(-2, (real_t)0.5)));
    TH_CHECK(rt_pow(2, 1000000) == inf && rt_pow(2, -1000000) == 0);
    TH_CHECK(rt_pow(-2, 1000001) == -inf && rt_pow(-2, -1000001) == 0);

    TH_CHECK(rt_isfinite(1) && rt_isfinite(-z) && !rt_isfinite(inf) && !rt_isfinite(nan));
    /* rt_all_finite: the largest finite, the smallest subnormal, -0 and 1 pass; inf, -inf
       and a NaN of either sign are found at every place of arrays of 1 to 7 */
    const real_t edge[] = {from_bits(INF_BITS - 1), from_bits(1), -z, 1};
    const real_t bad[] = {inf, -inf, nan, -nan};
    for (int n = 1; n <= 7; n++) {
        real_t v[7];
        for (int i = 0; i < n; i++)
            v[i] = edge[i % 4];
        TH_CHECK(rt_all_finite(v, n));
        for (int i = 0; i < n; i++)
            for (int k = 0; k < 4; k++) {
                real_t keep = v[i];
                v[i] = bad[k];
                TH_CHECK(!rt_all_finite(v, n));
                v[i] = keep;
            }
    }
    TH_CHECK(rt_all_finite(bad, 0));
    TH_CHECK(rt_fmin(nan, 1) == 1 && rt_fmin(1, nan) == 1 && rt_fmax(nan, -1) == -1);
    TH_CHECK(is_nan(rt_fmax(nan, nan)) && is_nan(rt_floor(nan)));
    TH_CHECK(rt_floor(-inf) == -inf && rt_fabs(-inf) == inf);
}

/* FNV-1a over the result bits of every function at fixed inputs. The same value on every
   target is the bit-identity promise of rt_math.h; a deliberate change to rmath.c must
   update GOLDEN (the failing check prints the new value). */
#if RT_REAL_IS_FLOAT
#define GOLDEN 0x4e88bdd7d02f8b58ull
#else
#define GOLDEN 0xb4046b27b7b8fca3ull
#endif

static uint64_t fnv;

static void mix(real_t v)
{
    uint64_t u = bits(v);
    for (int i = 0; i < 8; i++) {
        fnv ^= (u >> (8 * i)) & 0xffu;
        fnv *= 0x100000001b3ull;
    }
}

static void check_golden_hash(void)
{
    fnv = 0xcbf29ce484222325ull;
    lcg_seed(12345);
    for (int i = 0; i < 300; i++) {
        real_t a = uni(-10, 10), b = uni(0, 3), w = uni(-1, 1);
        real_t big = uni(-1e6, 1e6); /* scaled below: reaches Payne-Hanek */
        big *= (real_t)(1u << (lcg() % 24u)); /* own statement: argument order is unspecified */
        mix(rt_sqrt(b * b * b));
        mix(rt_sin(a));
        mix(rt_cos(a));
        mix(rt_tan(a));
        mix(rt_sin(big));
        mix(rt_cos(big));
        mix(rt_atan(a * a * a));
        mix(rt_atan2(a, w));
        mix(rt_asin(w));
        mix(rt_acos(w));
        mix(rt_exp(a * 8));
        mix(rt_log(b * b * b * b));
        mix(rt_pow(b, a));
        mix(rt_pow(a, (real_t)(int)(lcg() % 9u)));
        mix(rt_tanh(a));
        mix(rt_floor(a));
        mix(rt_atan_faithful(a * a * a));
        mix(rt_atan2_faithful(a, w));
        mix(rt_asin_faithful(w));
        mix(rt_sin_faithful(a));
    }
    mix(rt_exp(-740)); /* subnormal results (0 in float) */
    mix(rt_pow(2, (real_t)-1070.5));
    if (!TH_EQ_U64(fnv, GOLDEN)) {
        th_put("  rmath golden hash now: 0x");
        th_put_hex64(fnv);
        th_put("\n");
    }
}

void test_rmath_values(void)
{
    check_known_values();
    check_special_values();
    check_golden_hash();
}

/* ------------------------------------------------------------------ identities */

/* Each identity is checked over many points with a bound derived from how rounding
   errors of the inputs propagate; fails count once per identity, not once per point. */
static void check_symmetry_and_pythagoras(void)
{
    int bad_sym = 0, bad_pyth = 0, bad_tan = 0, bad_shift = 0;
    lcg_seed(1);
    for (int i = 0; i < 1000; i++) {
        real_t x = i < 500 ? uni(-20, 20) : uni(-1e5, 1e5);
        real_t s = rt_sin(x), c = rt_cos(x), t = rt_tan(x);
        if (rt_sin(-x) != -s || rt_cos(-x) != c || rt_tan(-x) != -t) bad_sym++;
        if (dabs((double)s * s + (double)c * c - 1.0) > 3 * EPS) bad_pyth++;
        if (dabs((double)c) > 0.1 && dabs((double)t - (double)s / c) > 3 * EPS * dabs((double)t))
            bad_tan++;
        /* cos x = sin(x + pi/2) at small x, where x + pi/2 rounds by at most one ulp */
        if (i < 500) {
            real_t y = x + (real_t)RT_HALF_PI;
            double tol = 2 * EPS + 16 * EPS; /* ulp(y) <= 16 EPS for |y| < 32 */
            if (dabs((double)rt_sin(y) - (double)rt_cos(x)) > tol) bad_shift++;
        }
    }
    TH_CHECK(bad_sym == 0);
    TH_CHECK(bad_pyth == 0);
    TH_CHECK(bad_tan == 0);
    TH_CHECK(bad_shift == 0);
}

static void check_inverses(void)
{
    int bad_asin = 0, bad_acos = 0, bad_atan = 0, bad_atan2 = 0, bad_sym = 0;
    lcg_seed(2);
    for (int i = 0; i < 1000; i++) {
        real_t x = uni(-1.0, 1.0), ax = rt_fabs(x);
        if (dabs((double)rt_asin(rt_sin(x)) - x) > 3 * EPS * ax) bad_asin++;
        real_t y = uni(0.1, 3.0); /* acos'(cos y) = -1/sin y */
        if (dabs((double)rt_acos(rt_cos(y)) - y) > (1 / (double)rt_sin(y) + 2 * y) * EPS)
            bad_acos++;
        real_t u = uni(-1.5, 1.5);
        if (dabs((double)rt_atan(rt_tan(u)) - u) > 3 * EPS * dabs((double)u)) bad_atan++;
        real_t th = uni(-3.1, 3.1), r = uni(0.001, 1000);
        real_t a2 = rt_atan2(r * rt_sin(th), r * rt_cos(th));
        if (dabs((double)a2 - th) > 4 * EPS * (dabs((double)th) + 1)) bad_atan2++;
        if (rt_asin(-x) != -rt_asin(x) || rt_atan(-u) != -rt_atan(u)) bad_sym++;
    }
    TH_CHECK(bad_asin == 0);
    TH_CHECK(bad_acos == 0);
    TH_CHECK(bad_atan == 0);
    TH_CHECK(bad_atan2 == 0);
    TH_CHECK(bad_sym == 0);
}

static void check_exp_log_pow(void)
{
    int bad_el = 0, bad_le = 0, bad_add = 0, bad_pow = 0, bad_int = 0, bad_recip = 0;
    int bad_tanh = 0;
    const double emax = RT_REAL_IS_FLOAT ? 80 : 700;
    lcg_seed(3);
    for (int i = 0; i < 1000; i++) {
        /* exp(log x) = x: log x is off by half an ulp of |log x|, which exp magnifies */
        real_t x = rt_exp(uni(-emax, emax)), l = rt_log(x);
        if (dabs((double)rt_exp(l) - x) > (2 + dabs((double)l)) * EPS * x) bad_el++;
        real_t e = uni(-emax, emax);
        if (dabs((double)rt_log(rt_exp(e)) - e) > 2 * EPS * (1 + dabs((double)e))) bad_le++;
        real_t a = uni(-20, 20), b = uni(-20, 20);
        double ab = (double)rt_exp(a) * rt_exp(b), sum = (double)a + b;
        if (dabs(ab - rt_exp(a + b)) > (3 + dabs(sum)) * EPS * ab) bad_add++;
        real_t px = uni(0.01, 100), py = uni(-5, 5);
        if (dabs((double)rt_pow(px, py) * rt_pow(px, -py) - 1) > 3 * EPS) bad_pow++;
        if (rt_pow(px, 2) != px * px || rt_pow(px, -1) != 1 / px ||
            rt_pow(px, (real_t)0.5) != rt_sqrt(px))
            bad_int++;
        real_t p3 = px * px * px; /* two roundings: within 1.5 ulp of x^3 */
        if (dabs((double)rt_pow(-px, 3) + p3) > 2 * EPS * p3) bad_recip++;
        real_t h = uni(0.5, 10), e2 = rt_exp(2 * h);
        double tref = ((double)e2 - 1) / ((double)e2 + 1);
        if (dabs((double)rt_tanh(h) - tref) > 4 * EPS || rt_tanh(-h) != -rt_tanh(h)) bad_tanh++;
    }
    TH_CHECK(bad_el == 0);
    TH_CHECK(bad_le == 0);
    TH_CHECK(bad_add == 0);
    TH_CHECK(bad_pow == 0);
    TH_CHECK(bad_int == 0);
    TH_CHECK(bad_recip == 0);
    TH_CHECK(bad_tanh == 0);
}

/* monotone functions stay monotone between neighbouring arguments, and floor brackets */
static void check_monotonic_and_floor(void)
{
    int bad_mono = 0, bad_floor = 0;
    real_t (*const inc[])(real_t) = {rt_exp, rt_log, rt_atan, rt_tanh, rt_sqrt, rt_asin};
    for (unsigned f = 0; f < sizeof inc / sizeof inc[0]; f++) {
        lcg_seed(4 + f);
        for (int i = 0; i < 200; i++) {
            real_t x = uni(0.001, 0.999);
            real_t x1 = from_bits(bits(x) + 1 + lcg() % 3u);
            if (inc[f](x1) < inc[f](x)) bad_mono++;
        }
    }
    lcg_seed(9);
    for (int i = 0; i < 1000; i++) {
        real_t x = uni(-1e6, 1e6), fl;
        x /= (real_t)(1u << (lcg() % 20u));
        fl = rt_floor(x);
        if (!(fl <= x && x < fl + 1) || rt_floor(fl) != fl) bad_floor++;
    }
    TH_CHECK(bad_mono == 0);
    TH_CHECK(bad_floor == 0);
}

void test_rmath_identities(void)
{
    check_symmetry_and_pythagoras();
    check_inverses();
    check_exp_log_pow();
    check_monotonic_and_floor();
}
