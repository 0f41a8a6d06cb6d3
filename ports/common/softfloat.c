/* softfloat.c - correctly rounded IEEE-754 binary64 arithmetic in portable integer C, as
 * the double-precision run-time helpers of ARM targets without double hardware.
 *
 * Why: GCC 12's libgcc for ARM soft-float implements __aeabi_dadd/__aeabi_dsub in
 * hand-written assembly (ieee754-df.S) that is not correctly rounded. Observed failure
 * (tests/cross/softfloat_test.c, compare build): an effective subtraction whose operands'
 * exponents differ by exactly 33 and whose result falls into the next lower binade comes
 * out 1 ulp off in about 1 of 5 such cases, e.g. a = 0xbfd00000000b746a,
 * b = 0x3dc6e90e92d8a537: a + b must be 0xbfcfffffffffffc5, Cortex-M3/M4F give ...c6.
 * (No error was found for other exponent differences, in dmul, ddiv, the conversions,
 * the comparisons, or the single-precision helpers.) x86-64, AArch64, M7 (fpv5-d16) and
 * RISC-V (hardware, or libgcc's C soft-fp on rv32imac) round correctly, so modrt's traces
 * differed on M3/M4F. Linking this object replaces libgcc's helpers: the linker pulls an
 * archive member only for a symbol still undefined, and objects come before -lgcc.
 *
 * Where: only on ARM without double-precision floating-point hardware, i.e. __arm__ and
 * not (__ARM_FP & 8): Cortex-M3 (-mfloat-abi=soft) and Cortex-M4F (fpv4-sp-d16, single
 * precision only). Elsewhere (M7 fpv5-d16, AArch64, RISC-V, x86-64) this file compiles to
 * nothing. -DMODRT_SOFTFLOAT_API additionally exports the operations as modrt_sf_* on any
 * target (softfloat.h) for tests; -DMODRT_SOFTFLOAT_NO_AEABI suppresses the __aeabi_*
 * definitions (to compare against libgcc in one image).
 *
 * Helpers defined (with the GNU alias names libgcc gives them in the same archive members):
 *   __aeabi_dadd __aeabi_dsub __aeabi_drsub       (__adddf3 __subdf3)
 *   __aeabi_dmul __aeabi_ddiv __aeabi_drdiv       (__muldf3 __divdf3)
 *   __aeabi_i2d __aeabi_ui2d __aeabi_l2d __aeabi_ul2d __aeabi_f2d
 *                                  (__floatsidf __floatunsidf __floatdidf __floatundidf
 *                                   __extendsfdf2)
 * dmul and ddiv are correct in libgcc; they are replaced so that all binary64 arithmetic
 * comes from one implementation (libgcc's dmul takes 0.8x, its ddiv 3.4x the instructions
 * of the versions here; see below). The conversions are correct in libgcc too;
 * they are here because libgcc's _arm_addsubdf3.o defines them together with
 * __aeabi_dadd: a reference to __aeabi_i2d would pull that member in, and its
 * __aeabi_dadd would clash with ours ("multiple definition"). So every global symbol of
 * _arm_addsubdf3.o and _arm_muldivdf3.o is defined here and neither member is ever
 * linked. Comparisons (__aeabi_dcmp*), double->integer conversions (__aeabi_d2iz, d2uiz,
 * d2lz, d2ulz) and __aeabi_d2f were checked bit-exact against x86-64 and stay libgcc's.
 * (On the M7, libgcc's __aeabi_l2d/ul2d, the only double helpers it still needs, are
 * checked by the same test.)
 *
 * Calling convention: the __aeabi_d* helpers use the base AAPCS (doubles in r0:r1 and
 * r2:r3, result in r0:r1, a float argument in r0) also under -mfloat-abi=hard, as GCC
 * calls them on the M4F. They are defined here on uint64_t/uint32_t/int bit patterns,
 * which the base and the VFP variant of the AAPCS both pass in core registers, and are
 * marked pcs("aapcs") as well.
 *
 * Semantics: IEEE-754 binary64, round to nearest, ties to even; subnormal inputs and
 * results in full (no flush to zero); overflow gives +-inf; x + (-x) = +0, -0 + -0 = -0.
 * No exception flags. NaNs: an operation with a NaN operand returns that NaN quieted (the
 * first signalling NaN of a, b, else the first quiet NaN: the ARM VFP rule with
 * FPSCR.DN = 0); an invalid operation (inf - inf, 0 * inf, 0 / 0, inf / inf) returns the
 * default NaN 0x7ff8000000000000 (ARM, AArch64 and RISC-V's value; x86 SSE returns
 * 0xfff8000000000000). NaN payloads therefore differ between targets anyway (RISC-V
 * hardware always returns 0x7ff8000000000000): compare NaN results as "a NaN".
 *
 * Method (the classic one of Berkeley SoftFloat, written anew): operands are unpacked to
 * a 53-bit significand (subnormals normalised, with a correspondingly smaller exponent),
 * the significand is placed at bit 62 of a uint64_t, leaving 10 bits below the result's
 * last bit; bits shifted out to the right are OR-ed into bit 0 ("shift right jamming"), so
 * the working value is the exact result rounded to odd at a precision 10 bits finer than
 * binary64, and one final round to nearest even is then correct. Multiplication takes the
 * full 128-bit product; division computes the exact quotient digit by digit (11 bits per
 * step, estimated with one 32-bit division and corrected against the exact remainder) and
 * the remainder's non-zeroness as the sticky bit. No floating-point type is used. add and
 * mul have inline fast paths for two normal operands and for a zero operand; the other
 * cases (subnormals, inf, NaN, results out of the normal range) take the general code. Shifts are written
 * on 32-bit halves where that saves instructions on the 32-bit targets; there is one code
 * path for every target, so the host tests check the code the targets run.
 *
 * Cost on Cortex-M3 (instructions per operation incl. call, normal operands, QEMU count):
 * add 73 (libgcc 67), sub 80 (67), mul 62 (51), div 169 (577); a zero operand of + - *
 * takes a short path too (zeros are frequent in modrt's scenes, which run about 2% fewer
 * instructions in total than with libgcc). Code: 4.0 KB (libgcc's two members: 1.9 KB). */
#include <stdint.h>

#include "softfloat.h"

#if defined(__arm__) && (!defined(__ARM_FP) || !(__ARM_FP & 8)) && \
    !defined(MODRT_SOFTFLOAT_NO_AEABI)
#define SF_AEABI 1
#endif

#if defined(SF_AEABI) || defined(MODRT_SOFTFLOAT_API)

#define SF_SIGN 0x8000000000000000ull
#define SF_INF 0x7FF0000000000000ull
#define SF_FRAC 0x000FFFFFFFFFFFFFull
#define SF_QUIET 0x0008000000000000ull
#define SF_DEFAULT_NAN 0x7FF8000000000000ull
#define SF_HIDDEN 0x0010000000000000ull /* the implicit bit, 2^52 */

/* Leading zeros of a non-zero 64-bit value. */
static inline int sf_clz64(uint64_t x)
{
#if defined(__GNUC__)
    uint32_t hi = (uint32_t)(x >> 32);
    return hi ? __builtin_clz(hi) : 32 + __builtin_clz((uint32_t)x);
#else
    int n = 0;
    while (!(x & SF_SIGN)) x <<= 1, n++;
    return n;
#endif
}

/* x >> n with every bit shifted out OR-ed into bit 0 ("jamming"); any n >= 0. Written
   on 32-bit halves: this is the code the 32-bit targets run (and the host tests). */
static inline uint64_t sf_shift_right_jam(uint64_t x, uint32_t n)
{
    uint32_t hi = (uint32_t)(x >> 32), lo = (uint32_t)x, sticky;
    if (n == 0) return x;
    if (n < 32) {
        sticky = lo << (32 - n);
        lo = (lo >> n) | (hi << (32 - n));
        hi >>= n;
    } else if (n < 64) {
        sticky = n > 32 ? lo | (hi << (64 - n)) : lo;
        lo = hi >> (n - 32);
        hi = 0;
    } else {
        return x != 0;
    }
    return ((uint64_t)hi << 32) | lo | (sticky != 0);
}

static inline int sf_is_nan(uint64_t x) { return (x & ~SF_SIGN) > SF_INF; }

/* At least one of a, b is a NaN: the first signalling NaN, else the first quiet NaN,
   returned quiet. */
static uint64_t sf_propagate_nan(uint64_t a, uint64_t b)
{
    int a_nan = sf_is_nan(a), b_nan = sf_is_nan(b);
    if (a_nan && !(a & SF_QUIET)) return a | SF_QUIET;
    if (b_nan && !(b & SF_QUIET)) return b | SF_QUIET;
    return (a_nan ? a : b) | SF_QUIET;
}

/* The significand of a finite non-zero x in [2^52, 2^53) (subnormals normalised);
   returns the biased exponent, < 1 for subnormals: x = *sig * 2^(e - 1023 - 52). */
static inline int32_t sf_unpack(uint64_t x, uint64_t *sig)
{
    int32_t e = (int32_t)((x >> 52) & 0x7FF);
    uint64_t f = x & SF_FRAC;
    if (e == 0) {
        int s = sf_clz64(f) - 11;
        f <<= s;
        e = 1 - s;
    } else {
        f |= SF_HIDDEN;
    }
    *sig = f;
    return e;
}

#if defined(__GNUC__)
#define SF_INLINE static inline __attribute__((always_inline))
#define SF_NOINLINE static __attribute__((noinline))
#else
#define SF_INLINE static inline
#define SF_NOINLINE static
#endif

/* Rounds sign * sig * 2^(e - 1023 - 62) to nearest even and packs it. sig is normalised
   (bit 62 is its leading bit) and its bit 0 is sticky (set if anything non-zero was
   shifted out below it). Handles overflow to inf and subnormal / zero results. */
SF_NOINLINE uint64_t sf_round_pack_slow(uint64_t sign, int32_t e, uint64_t sig)
{
    uint32_t low;
    uint64_t m;
    if (e <= 0) {
        /* below the normal range: denormalise to the subnormal exponent (-1022) */
        sig = sf_shift_right_jam(sig, (uint32_t)(1 - e));
        low = (uint32_t)sig & 0x3FF;
        m = (sig + 0x200) >> 10;
        if (low == 0x200) m &= ~(uint64_t)1; /* tie: to even */
        return sign | m; /* a carry into bit 52 gives the smallest normal: right */
    }
    if (e >= 0x7FF) return sign | SF_INF;
    low = (uint32_t)sig & 0x3FF;
    m = (sig + 0x200) >> 10; /* in [2^52, 2^53] */
    if (low == 0x200) m &= ~(uint64_t)1;
    /* the hidden bit of m adds 1 to the exponent field; a carry to 2^53 adds 2 */
    m += (uint64_t)(e - 1) << 52;
    if (m >= SF_INF) return sign | SF_INF;
    return sign | m;
}

/* The same; the common case (1 <= e <= 0x7FD: normal, cannot overflow) inline. */
SF_INLINE uint64_t sf_round_pack(uint64_t sign, int32_t e, uint64_t sig)
{
    if ((uint32_t)(e - 1) >= 0x7FDu) return sf_round_pack_slow(sign, e, sig);
    uint64_t m = (sig + 0x200) >> 10; /* in [2^52, 2^53] */
    if (((uint32_t)sig & 0x3FF) == 0x200) m &= ~(uint64_t)1; /* tie: to even */
    return sign | (m + ((uint64_t)(uint32_t)(e - 1) << 52));
}

/* a + b for the general case: any operand class. */
SF_NOINLINE uint64_t sf_add_slow(uint64_t a, uint64_t b)
{
    uint64_t ma = a & ~SF_SIGN, mb = b & ~SF_SIGN;
    if (ma > SF_INF || mb > SF_INF) return sf_propagate_nan(a, b);
    if (ma == SF_INF) {
        if (mb == SF_INF && ((a ^ b) & SF_SIGN)) return SF_DEFAULT_NAN; /* inf - inf */
        return a;
    }
    if (mb == SF_INF) return b;
    if (mb == 0) return ma == 0 ? a & b : a; /* -0 only for -0 + -0 */
    if (ma == 0) return b;
    if (ma < mb) { /* make |a| >= |b|: the result has a's sign */
        uint64_t t = a;
        a = b;
        b = t;
        t = ma;
        ma = mb;
        mb = t;
    }
    uint64_t sign = a & SF_SIGN, sa, sb, sig;
    int32_t ea = sf_unpack(a, &sa), eb = sf_unpack(b, &sb), e = ea;
    uint32_t d = (uint32_t)(ea - eb);
    sa <<= 10;
    sb = sf_shift_right_jam(sb << 10, d);
    if (!((a ^ b) & SF_SIGN)) {
        sig = sa + sb; /* < 2^64 */
        if (sig & SF_SIGN) {
            sig = sf_shift_right_jam(sig, 1);
            e++;
        }
    } else {
        if (ma == mb) return 0; /* x - x = +0 when rounding to nearest */
        /* d <= 1: exact; d >= 2: sig >= 2^61, so at most one bit of cancellation and
           the sticky bit stays below the rounding position */
        sig = sa - sb;
        int s = sf_clz64(sig) - 1;
        sig <<= s;
        e -= s;
    }
    return sf_round_pack(sign, e, sig);
}

/* a + b for two normal operands with |a| >= |b| (ea, eb: their exponent fields). */
SF_INLINE uint64_t sf_add_normal(uint64_t a, uint64_t b, uint32_t ea, uint32_t eb)
{
    uint64_t sa = ((a & SF_FRAC) | SF_HIDDEN) << 10;
    uint64_t sb = sf_shift_right_jam(((b & SF_FRAC) | SF_HIDDEN) << 10, ea - eb);
    uint64_t sig;
    int32_t e = (int32_t)ea;
    if (!((a ^ b) & SF_SIGN)) {
        sig = sa + sb;
        if (sig & SF_SIGN) {
            sig = (sig >> 1) | (sig & 1);
            e++;
        }
    } else {
        sig = sa - sb;
        if (sig < ((uint64_t)1 << 62)) { /* cancellation */
            if (sig == 0) return 0;       /* x - x = +0 */
            int s = sf_clz64(sig) - 1;
            sig <<= s;
            e -= s;
        }
    }
    return sf_round_pack(a & SF_SIGN, e, sig);
}

static inline int sf_is_zero(uint64_t x) { return (x << 1) == 0; }

/* a + b: sf_add_slow's computation, with fast paths for two normal operands and for a
   zero operand (frequent in practice: a + 0 = a unless a is a NaN, -0 + -0 = -0). */
static uint64_t sf_add(uint64_t a, uint64_t b)
{
    uint32_t ea = (uint32_t)(a >> 52) & 0x7FF, eb = (uint32_t)(b >> 52) & 0x7FF;
    if (ea - 1 >= 0x7FEu || eb - 1 >= 0x7FEu) {
        if (sf_is_zero(b) && ea != 0x7FF) return sf_is_zero(a) ? a & b : a;
        if (sf_is_zero(a) && eb != 0x7FF) return b;
        return sf_add_slow(a, b);
    }
    if ((a & ~SF_SIGN) >= (b & ~SF_SIGN)) return sf_add_normal(a, b, ea, eb);
    return sf_add_normal(b, a, eb, ea);
}

static uint64_t sf_sub(uint64_t a, uint64_t b)
{
    /* b inf or NaN: keep a NaN b's sign (propagated as it is); otherwise a + -b */
    if (((uint32_t)(b >> 32) & 0x7FFFFFFFu) >= 0x7FF00000u && sf_is_nan(b))
        return sf_propagate_nan(a, b);
    return sf_add(a, b ^ SF_SIGN);
}

/* The 128-bit product of two 64-bit values (each partial product plus a 32-bit
   addend fits in 64 bits: multiply-accumulate instructions where there are any). */
SF_INLINE void sf_mul64x64(uint64_t a, uint64_t b, uint64_t *hi, uint64_t *lo)
{
    uint32_t a0 = (uint32_t)a, a1 = (uint32_t)(a >> 32);
    uint32_t b0 = (uint32_t)b, b1 = (uint32_t)(b >> 32);
    uint64_t p00 = (uint64_t)a0 * b0;
    uint64_t p01 = (uint64_t)a0 * b1 + (p00 >> 32);
    uint64_t p10 = (uint64_t)a1 * b0 + (uint32_t)p01;
    *lo = (p10 << 32) | (uint32_t)p00;
    *hi = (uint64_t)a1 * b1 + (p01 >> 32) + (p10 >> 32);
}

/* Rounds and packs sign * sa * sb: sa, sb significands in [2^52, 2^53) of operands with
   biased exponents ea, eb (< 1 for normalised subnormals), e = ea + eb - 1022. */
SF_INLINE uint64_t sf_mul_sigs(uint64_t sign, int32_t e, uint64_t sa, uint64_t sb)
{
    uint64_t hi, lo;
    /* (sa << 10) * (sb << 11) is in [2^125, 2^127): its high half in [2^61, 2^63) */
    sf_mul64x64(sa << 10, sb << 11, &hi, &lo);
    hi |= (lo != 0);
    if (hi < ((uint64_t)1 << 62)) {
        hi <<= 1; /* the sticky bit moves to bit 1: still below the rounding position */
        e--;
    }
    return sf_round_pack(sign, e, hi);
}

SF_NOINLINE uint64_t sf_mul_slow(uint64_t a, uint64_t b)
{
    uint64_t ma = a & ~SF_SIGN, mb = b & ~SF_SIGN, sign = (a ^ b) & SF_SIGN;
    if (ma > SF_INF || mb > SF_INF) return sf_propagate_nan(a, b);
    if (ma == SF_INF || mb == SF_INF) {
        if (ma == 0 || mb == 0) return SF_DEFAULT_NAN; /* 0 * inf */
        return sign | SF_INF;
    }
    if (ma == 0 || mb == 0) return sign;
    uint64_t sa, sb;
    int32_t e = sf_unpack(a, &sa) + sf_unpack(b, &sb) - 1022;
    return sf_mul_sigs(sign, e, sa, sb);
}

/* a * b: sf_mul_slow's computation, with fast paths for two normal operands and for a
   zero times a finite number (a signed zero). */
static uint64_t sf_mul(uint64_t a, uint64_t b)
{
    uint32_t ea = (uint32_t)(a >> 52) & 0x7FF, eb = (uint32_t)(b >> 52) & 0x7FF;
    if (ea - 1 >= 0x7FEu || eb - 1 >= 0x7FEu) {
        if ((sf_is_zero(a) && eb != 0x7FF) || (sf_is_zero(b) && ea != 0x7FF))
            return (a ^ b) & SF_SIGN;
        return sf_mul_slow(a, b);
    }
    return sf_mul_sigs((a ^ b) & SF_SIGN, (int32_t)(ea + eb) - 1022, (a & SF_FRAC) | SF_HIDDEN,
                       (b & SF_FRAC) | SF_HIDDEN);
}

static uint64_t sf_div(uint64_t a, uint64_t b)
{
    uint64_t ma = a & ~SF_SIGN, mb = b & ~SF_SIGN, sign = (a ^ b) & SF_SIGN;
    if (ma > SF_INF || mb > SF_INF) return sf_propagate_nan(a, b);
    if (ma == SF_INF) return mb == SF_INF ? SF_DEFAULT_NAN : sign | SF_INF;
    if (mb == SF_INF) return sign;
    if (mb == 0) return ma == 0 ? SF_DEFAULT_NAN : sign | SF_INF;
    if (ma == 0) return sign;
    uint64_t sa, sb;
    int32_t ea = sf_unpack(a, &sa), eb = sf_unpack(b, &sb);
    int32_t e = ea - eb + 1023;
    if (sa < sb) { /* make sa / sb in [1, 2) */
        sa <<= 1;
        e--;
    }
    /* Long division, 11 quotient bits per step. Invariant: r < sb < 2^53, so r << 11 < 2^64
       and a digit is < 2^11. The digit estimate divides the top 32 bits of r << 11 by the top
       bits of sb rounded up: never too large, and at most 1 too small (the loop corrects it;
       correctness does not depend on the estimate, only the speed does). */
    uint64_t q = 1, r = sa - sb;
    uint32_t d = (uint32_t)(sb >> 32) + 1; /* in [2^20 + 1, 2^21] */
    for (int i = 0; i < 5; i++) {
        r <<= 11;
        uint32_t digit = (uint32_t)(r >> 32) / d;
        r -= (uint64_t)digit * sb;
        while (r >= sb) {
            r -= sb;
            digit++;
        }
        q = (q << 11) | digit;
    }
    /* q = floor(2^55 * sa / sb) in [2^55, 2^56): place it at bit 62, r != 0 is sticky */
    return sf_round_pack(sign, e, (q << 7) | (r != 0));
}

/* sign * mag (mag < 2^64) rounded to binary64. */
static uint64_t sf_from_mag(uint64_t sign, uint64_t mag)
{
    if (mag == 0) return 0; /* integer zero converts to +0 */
    int s = sf_clz64(mag); /* leading bit at 63 - s */
    uint64_t sig = s ? mag << (s - 1) : sf_shift_right_jam(mag, 1);
    return sf_round_pack(sign, 1086 - s, sig);
}

static uint64_t sf_from_f32(uint32_t f)
{
    uint64_t sign = (uint64_t)(f & 0x80000000u) << 32;
    uint32_t e = (f >> 23) & 0xFF, m = f & 0x7FFFFF;
    if (e == 0xFF) /* inf, or NaN: quieted, payload kept in the top fraction bits */
        return m ? sign | SF_INF | SF_QUIET | ((uint64_t)m << 29) : sign | SF_INF;
    if (e == 0) {
        if (m == 0) return sign;
        int s = sf_clz64(m) - 40; /* normalise the subnormal: leading bit to bit 23 */
        m = (m << s) & 0x7FFFFF;
        return sign | ((uint64_t)(1 - s + 1023 - 127) << 52) | ((uint64_t)m << 29);
    }
    return sign | ((uint64_t)(e + 1023 - 127) << 52) | ((uint64_t)m << 29);
}

#endif /* SF_AEABI || MODRT_SOFTFLOAT_API */

#ifdef MODRT_SOFTFLOAT_API
uint64_t modrt_sf_add(uint64_t a, uint64_t b) { return sf_add(a, b); }
uint64_t modrt_sf_sub(uint64_t a, uint64_t b) { return sf_sub(a, b); }
uint64_t modrt_sf_mul(uint64_t a, uint64_t b) { return sf_mul(a, b); }
uint64_t modrt_sf_div(uint64_t a, uint64_t b) { return sf_div(a, b); }
uint64_t modrt_sf_from_i32(int32_t x)
{
    return sf_from_mag(x < 0 ? SF_SIGN : 0, x < 0 ? 0u - (uint32_t)x : (uint32_t)x);
}
uint64_t modrt_sf_from_u32(uint32_t x) { return sf_from_mag(0, x); }
uint64_t modrt_sf_from_i64(int64_t x)
{
    return sf_from_mag(x < 0 ? SF_SIGN : 0, x < 0 ? 0u - (uint64_t)x : (uint64_t)x);
}
uint64_t modrt_sf_from_u64(uint64_t x) { return sf_from_mag(0, x); }
uint64_t modrt_sf_from_f32(uint32_t f) { return sf_from_f32(f); }
#endif

#ifdef SF_AEABI
/* Base-standard AAPCS (core registers) whatever -mfloat-abi says; with integer
   parameters this is what the compiler does anyway. */
#define SF_HELPER __attribute__((pcs("aapcs")))

/* Prototypes (nothing else declares these: the compiler calls them by name). */
SF_HELPER uint64_t __aeabi_dadd(uint64_t a, uint64_t b);
SF_HELPER uint64_t __aeabi_dsub(uint64_t a, uint64_t b);
SF_HELPER uint64_t __aeabi_drsub(uint64_t a, uint64_t b);
SF_HELPER uint64_t __aeabi_dmul(uint64_t a, uint64_t b);
SF_HELPER uint64_t __aeabi_ddiv(uint64_t a, uint64_t b);
SF_HELPER uint64_t __aeabi_drdiv(uint64_t a, uint64_t b);
SF_HELPER uint64_t __aeabi_i2d(int32_t x);
SF_HELPER uint64_t __aeabi_ui2d(uint32_t x);
SF_HELPER uint64_t __aeabi_l2d(int64_t x);
SF_HELPER uint64_t __aeabi_ul2d(uint64_t x);
SF_HELPER uint64_t __aeabi_f2d(uint32_t f);

SF_HELPER uint64_t __aeabi_dadd(uint64_t a, uint64_t b) { return sf_add(a, b); }
SF_HELPER uint64_t __aeabi_dsub(uint64_t a, uint64_t b) { return sf_sub(a, b); }
SF_HELPER uint64_t __aeabi_drsub(uint64_t a, uint64_t b) { return sf_sub(b, a); }
SF_HELPER uint64_t __aeabi_dmul(uint64_t a, uint64_t b) { return sf_mul(a, b); }
SF_HELPER uint64_t __aeabi_ddiv(uint64_t a, uint64_t b) { return sf_div(a, b); }
SF_HELPER uint64_t __aeabi_drdiv(uint64_t a, uint64_t b) { return sf_div(b, a); }
SF_HELPER uint64_t __aeabi_i2d(int32_t x)
{
    return sf_from_mag(x < 0 ? SF_SIGN : 0, x < 0 ? 0u - (uint32_t)x : (uint32_t)x);
}
SF_HELPER uint64_t __aeabi_ui2d(uint32_t x) { return sf_from_mag(0, x); }
SF_HELPER uint64_t __aeabi_l2d(int64_t x)
{
    return sf_from_mag(x < 0 ? SF_SIGN : 0, x < 0 ? 0u - (uint64_t)x : (uint64_t)x);
}
SF_HELPER uint64_t __aeabi_ul2d(uint64_t x) { return sf_from_mag(0, x); }
SF_HELPER uint64_t __aeabi_f2d(uint32_t f) { return sf_from_f32(f); }

/* libgcc's GNU names for the same functions, defined in the same archive members. */
SF_HELPER uint64_t __adddf3(uint64_t a, uint64_t b) __attribute__((alias("__aeabi_dadd")));
SF_HELPER uint64_t __subdf3(uint64_t a, uint64_t b) __attribute__((alias("__aeabi_dsub")));
SF_HELPER uint64_t __muldf3(uint64_t a, uint64_t b) __attribute__((alias("__aeabi_dmul")));
SF_HELPER uint64_t __divdf3(uint64_t a, uint64_t b) __attribute__((alias("__aeabi_ddiv")));
SF_HELPER uint64_t __floatsidf(int32_t x) __attribute__((alias("__aeabi_i2d")));
SF_HELPER uint64_t __floatunsidf(uint32_t x) __attribute__((alias("__aeabi_ui2d")));
SF_HELPER uint64_t __floatdidf(int64_t x) __attribute__((alias("__aeabi_l2d")));
SF_HELPER uint64_t __floatundidf(uint64_t x) __attribute__((alias("__aeabi_ul2d")));
SF_HELPER uint64_t __extendsfdf2(uint32_t f) __attribute__((alias("__aeabi_f2d")));
#endif /* SF_AEABI */

#if !defined(SF_AEABI) && !defined(MODRT_SOFTFLOAT_API)
typedef int modrt_softfloat_empty; /* nothing to provide here; ISO C wants a declaration */
#endif
