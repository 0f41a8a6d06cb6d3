/* rt_math.h - elementary functions of modrt, written with + - * / only (and the hardware
 * square root where it is exact), so that every target computes bit-identical results.
 *
 * Models and the runtime call these, never libm: libm differs between glibc and newlib,
 * and identical traces on every target need identical elementary functions. Accuracy and
 * ranges are documented in rt/rmath.c and measured by tests/rt/test_rmath.c. */
#ifndef RT_MATH_H
#define RT_MATH_H

#include <stdint.h>

#include "rt_config.h"

#define RT_PI 3.14159265358979323846
#define RT_TWO_PI 6.28318530717958647693
#define RT_HALF_PI 1.57079632679489661923

real_t rt_sqrt(real_t x);           /* correctly rounded where hardware allows; NaN for x < 0 */
real_t rt_sin(real_t x);
real_t rt_cos(real_t x);
real_t rt_tan(real_t x);
real_t rt_atan(real_t x);
real_t rt_atan2(real_t y, real_t x);
real_t rt_asin(real_t x);
real_t rt_acos(real_t x);
real_t rt_exp(real_t x);
real_t rt_log(real_t x);
real_t rt_pow(real_t x, real_t y);
real_t rt_tanh(real_t x);
real_t rt_floor(real_t x);
/* Faithfully rounded (error below 1 ulp, deterministic on every target like the rest),
   a third to half the cost of the correctly rounded ones: for models that call them in
   every stage and need no last-bit accuracy (rt/rmath.c, "faithful functions"). */
real_t rt_atan_faithful(real_t x);
real_t rt_atan2_faithful(real_t y, real_t x);
real_t rt_asin_faithful(real_t x);
real_t rt_sin_faithful(real_t x);
real_t rt_fmin(real_t a, real_t b);
real_t rt_fmax(real_t a, real_t b);

/* |x| and finiteness from the bit pattern, inline: the steps call them for every state
   (a call each cost more than the operation, #14); exact, NaNs pass through rt_fabs */
#if RT_REAL_IS_FLOAT
typedef uint32_t rt_real_bits;
#define RT_SIGN_BIT 0x80000000u
#define RT_EXP_BITS 0x7f800000u
#else
typedef uint64_t rt_real_bits;
#define RT_SIGN_BIT 0x8000000000000000ull
#define RT_EXP_BITS 0x7ff0000000000000ull
#endif
typedef union rt_real_rep {
    real_t r;
    rt_real_bits u;
} rt_real_rep;

/* The hardware square root where it is a single exact instruction (-DRT_SOFT_SQRT forces
   the software one, so host tests can compare the two bit for bit). Without
   -fno-math-errno (__NO_MATH_ERRNO__) gcc would also emit a call to libm's sqrt. */
#if defined(RT_SOFT_SQRT) || !defined(__NO_MATH_ERRNO__)
#define RT_HW_SQRT_D 0
#define RT_HW_SQRT_F 0
#elif (defined(__x86_64__) && defined(__SSE2__)) || defined(__aarch64__)
#define RT_HW_SQRT_D 1
#define RT_HW_SQRT_F 1
#elif defined(__arm__) && defined(__ARM_FP)
#define RT_HW_SQRT_D ((__ARM_FP & 8) != 0)
#define RT_HW_SQRT_F ((__ARM_FP & 4) != 0)
#elif defined(__riscv) && defined(__riscv_fdiv) && defined(__riscv_flen)
#define RT_HW_SQRT_D (__riscv_flen >= 64)
#define RT_HW_SQRT_F (__riscv_flen >= 32)
#else
#define RT_HW_SQRT_D 0
#define RT_HW_SQRT_F 0
#endif
#if RT_REAL_IS_FLOAT
#define RT_HW_SQRT RT_HW_SQRT_F
#define RT_QNAN_BITS 0x7fc00000u
#else
#define RT_HW_SQRT RT_HW_SQRT_D
#define RT_QNAN_BITS 0x7ff8000000000000ull
#endif

#if RT_HW_SQRT
/* rt_sqrt inline where it is one instruction: the joints and norms call it in every
   stage, and the call cost more than the root. The same bits as rt/rmath.c's rt_sqrt
   (which stays, for a caller compiled without the macro or taking its address) */
static inline real_t rti_sqrt_hw(real_t x)
{
    if (!(x >= 0)) { /* x < 0 or NaN: the canonical quiet NaN; -0 passes */
        rt_real_rep v = {.u = RT_QNAN_BITS};
        return v.r;
    }
#if RT_REAL_IS_FLOAT
    return __builtin_sqrtf(x);
#else
    return __builtin_sqrt(x);
#endif
}
#define rt_sqrt(x) rti_sqrt_hw(x)
#endif

static inline real_t rt_fabs(real_t x)
{
#if defined(__GNUC__) && RT_REAL_IS_FLOAT /* gcc, clang: the sign bit cleared where the
                         value is (an FPU or vector register, not through an integer one),
                         never a call */
    return __builtin_fabsf(x);
#elif defined(__GNUC__)
    return __builtin_fabs(x);
#else
    rt_real_rep v = {.r = x};
    v.u &= ~RT_SIGN_BIT;
    return v.r;
#endif
}

static inline int rt_isfinite(real_t x) /* 0 for NaN and +-inf */
{
    rt_real_rep v = {.r = x};
    return (v.u & RT_EXP_BITS) != RT_EXP_BITS;
}

/* 1 if all n values are finite (a kind's parameter check, a new discrete state, a set's
   state after each step). A value is not finite when its exponent bits are all ones:
   adding the exponent's lowest bit to the masked exponent then carries into the sign
   bit's place, which stays clear for every other value: an and, an add and an or per
   value, no branch (a branch costs more than the tests). Four values per iteration: the
   loop's own count and test cost as much as a value's three operations (the tick checks
   every new output, the step every state) */
#ifdef __GNUC__ /* a one-value array of a build with exact limits, RT_MAX_D 1: GCC sees the
                  four-value body read past it, never run */
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Warray-bounds"
#endif
static inline int rt_all_finite(const real_t *v, int n)
{
    const rt_real_bits lsb = RT_EXP_BITS & (~RT_EXP_BITS + 1u);
    rt_real_bits bad = 0;
    int i = 0;
    for (; i + 4 <= n; i += 4) {
        rt_real_rep a = {.r = v[i]}, b = {.r = v[i + 1]}, c = {.r = v[i + 2]}, d = {.r = v[i + 3]};
        bad |= ((a.u & RT_EXP_BITS) + lsb) | ((b.u & RT_EXP_BITS) + lsb) |
               ((c.u & RT_EXP_BITS) + lsb) | ((d.u & RT_EXP_BITS) + lsb);
    }
    for (; i < n; i++) {
        rt_real_rep a = {.r = v[i]};
        bad |= (a.u & RT_EXP_BITS) + lsb;
    }
    return !(bad & RT_SIGN_BIT);
}
#ifdef __GNUC__
#pragma GCC diagnostic pop
#endif

#endif /* RT_MATH_H */
