/* math.h - what FMU code in an image may use of <math.h> on a target whose toolchain has no C
 * library (tools/image.sh adds tools/fmi/libc to the include path there; docs/fmi.md, "FMUs
 * in images"): the classification macros and constants, by the compiler's builtins. No
 * function of libm: an FMU that calls one does not build. */
#ifndef FMU_LIBC_MATH_H
#define FMU_LIBC_MATH_H

#define NAN (__builtin_nanf(""))
#define INFINITY (__builtin_inff())
#define HUGE_VAL (__builtin_huge_val())
#define isfinite(x) __builtin_isfinite(x)
#define isnan(x) __builtin_isnan(x)
#define isinf(x) __builtin_isinf(x)

#endif
