/* rt_math.h - elementary functions of modrt, written with + - * / only (and the hardware
 * square root where it is exact), so that every target computes bit-identical results.
 *
 * Models and the runtime call these, never libm: libm differs between glibc and newlib,
 * and identical traces on every target need identical elementary functions. Accuracy and
 * ranges are documented in rt/rmath.c and measured by tests/rt/test_rmath.c. */
#ifndef RT_MATH_H
#define RT_MATH_H

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
real_t rt_fabs(real_t x);
real_t rt_floor(real_t x);
real_t rt_fmin(real_t a, real_t b);
real_t rt_fmax(real_t a, real_t b);
int rt_isfinite(real_t x);          /* 0 for NaN and +-inf */

#endif /* RT_MATH_H */
