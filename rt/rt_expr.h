/* rt_expr.h - the conditions and limits of the scene language's expressions: what a
 * defined system's comparisons, not, and, or, if, min and max compute (tools/scenec: the
 * interpreter's VM calls these, and the C it writes for a compiled scene calls the same,
 * so both give the same bits).
 *
 * Why not C's own operators: they drop a NaN. NaN < 0 is false and fmin ignores a NaN, so
 * a model guarded by a condition or a limit (a tank's outflow min(sqrt(z), q) once z
 * dips below zero) gets a finite derivative from an invalid state, and the run goes on
 * wrong with status ok. Here a NaN operand makes a comparison NaN, a NaN condition makes
 * not, and, or and if NaN, and min and max of a NaN are NaN: the NaN reaches the state or
 * output, where the step's finite check counts it. Finite operands (infinities included)
 * give what C gives: 1 or 0, the selected branch, the smaller or larger value. */
#ifndef RT_EXPR_H
#define RT_EXPR_H

#include "rt_math.h"

/* NaN if a or b is (a's own NaN first), else the truth value c as 1 or 0 */
static inline real_t rt_x_truth(real_t a, real_t b, int c)
{
    return a != a ? a : b != b ? b : c ? (real_t)1 : (real_t)0;
}

static inline real_t rt_x_lt(real_t a, real_t b) { return rt_x_truth(a, b, a < b); }
static inline real_t rt_x_le(real_t a, real_t b) { return rt_x_truth(a, b, a <= b); }
static inline real_t rt_x_gt(real_t a, real_t b) { return rt_x_truth(a, b, a > b); }
static inline real_t rt_x_ge(real_t a, real_t b) { return rt_x_truth(a, b, a >= b); }
static inline real_t rt_x_eq(real_t a, real_t b) { return rt_x_truth(a, b, a == b); }
static inline real_t rt_x_ne(real_t a, real_t b) { return rt_x_truth(a, b, a != b); }
static inline real_t rt_x_and(real_t a, real_t b) { return rt_x_truth(a, b, a != 0 && b != 0); }
static inline real_t rt_x_or(real_t a, real_t b) { return rt_x_truth(a, b, a != 0 || b != 0); }
static inline real_t rt_x_not(real_t a) { return rt_x_truth(a, 0, a == 0); }

/* if(c, a, b): a where c is nonzero, b where it is 0, NaN where it is NaN */
static inline real_t rt_x_if(real_t c, real_t a, real_t b) { return c != c ? c : c != 0 ? a : b; }

/* the smaller and the larger of a and b, NaN if either is (rt_fmin and rt_fmax, as C's
   fmin and fmax, return the other); of finite ones rt_fmin's and rt_fmax's (-0 < +0) */
static inline real_t rt_x_min(real_t a, real_t b)
{
    return a != a ? a : b != b ? b : rt_fmin(a, b);
}

static inline real_t rt_x_max(real_t a, real_t b)
{
    return a != a ? a : b != b ? b : rt_fmax(a, b);
}

#endif /* RT_EXPR_H */
