/* softfloat.h - modrt's correctly rounded IEEE-754 binary64 arithmetic in integer C
 * (ports/common/softfloat.c).
 *
 * On ARM without double-precision hardware (Cortex-M3 soft-float, Cortex-M4F with
 * fpv4-sp-d16) softfloat.c defines the run-time helpers GCC calls for double arithmetic
 * (__aeabi_dadd, __aeabi_dsub, __aeabi_dmul, __aeabi_ddiv, ... see softfloat.c), replacing
 * libgcc's hand-written ARM assembly, which does not round correctly in every case. Nothing
 * includes this header for that: the compiler calls the helpers by name.
 *
 * The functions below are the same operations on IEEE bit patterns under portable names.
 * They exist only when softfloat.c is compiled with -DMODRT_SOFTFLOAT_API (on any target,
 * the host included): for testing the implementation against hardware on the host, and
 * against libgcc in one image on a target (add -DMODRT_SOFTFLOAT_NO_AEABI there, so the
 * C operators keep calling libgcc's helpers). */
#ifndef MODRT_SOFTFLOAT_H
#define MODRT_SOFTFLOAT_H

#include <stdint.h>

#ifdef MODRT_SOFTFLOAT_API
/* Binary64 arithmetic, round to nearest even, arguments and results as bit patterns. */
uint64_t modrt_sf_add(uint64_t a, uint64_t b);
uint64_t modrt_sf_sub(uint64_t a, uint64_t b);
uint64_t modrt_sf_mul(uint64_t a, uint64_t b);
uint64_t modrt_sf_div(uint64_t a, uint64_t b);
/* Conversions to binary64 (exact, except 64-bit integers: rounded to nearest even). */
uint64_t modrt_sf_from_i32(int32_t x);
uint64_t modrt_sf_from_u32(uint32_t x);
uint64_t modrt_sf_from_i64(int64_t x);
uint64_t modrt_sf_from_u64(uint64_t x);
uint64_t modrt_sf_from_f32(uint32_t f); /* binary32 bit pattern -> binary64 (exact) */
#endif

#endif /* MODRT_SOFTFLOAT_H */
