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
 * give what C gives: 1 or 0, the selected branch, the smaller or larger value.
 *
 * Also a defined system's comparisons of `t` with a parameter, which tools/scenec makes
 * time events known at run time (rt_kind.time_event): rt_x_next gives the next instant,
 * rt_x_at the time the comparison reads. */
#ifndef RT_EXPR_H
#define RT_EXPR_H

#include "rt.h"

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

/* a comparison that is a located switch (a defined system's comparison of states,
   docs/scene-language.md): its mode m, the value it took at the start of the step part
   or at the crossing located since (1 or 0), held through the part; the comparison's own
   value v before it has one (m = 0.5) and where a side is NaN (v is NaN then) */
static inline real_t rt_x_sw(real_t a, real_t b, real_t m, real_t v)
{
    return a == a && b == b && (m == 0 || m == 1) ? m : v;
}

/* a located switch's sides' difference a - b; where that is NaN from two infinities of
   one sign, 0, and from sides that are not NaN its sign */
static inline real_t rt_x_side(real_t a, real_t b)
{
    real_t d = a - b;
    if (d == d || a != a || b != b)
        return d;
    return a > b ? (real_t)1 : a < b ? (real_t)-1 : (real_t)0;
}

/* the smallest normal real_t: how far a switch's root stands off 0 where its sides are
   equal */
#define RT_X_SW_OFF (RT_REAL_IS_FLOAT ? (real_t)1.17549435e-38f : (real_t)2.2250738585072014e-308)

/* a located switch's root for its comparison of a and b: positive exactly where the
   comparison holds, negative where it does not, never 0 (at equality RT_X_SW_OFF on the
   side the operator gives it): a side that rests on the other and then leaves it is a
   crossing (a root from exactly 0 would not be one), and elsewhere it is the sides'
   difference itself (d - RT_X_SW_OFF rounds to d) */
static inline real_t rt_x_swgt(real_t a, real_t b)
{
    real_t d = rt_x_side(a, b);
    return d > 0 ? d : d - RT_X_SW_OFF;
}
static inline real_t rt_x_swge(real_t a, real_t b)
{
    real_t d = rt_x_side(a, b);
    return d >= 0 ? d + RT_X_SW_OFF : d;
}
static inline real_t rt_x_swlt(real_t a, real_t b) { return rt_x_swgt(b, a); }
static inline real_t rt_x_swle(real_t a, real_t b) { return rt_x_swge(b, a); }

/* rt_x_sw of the comparison op (0 <, 1 <=, 2 >, 3 >=) of a and b: its sides once */
static inline real_t rt_x_swc(real_t a, real_t b, real_t m, int op)
{
    real_t v = op == 0 ? rt_x_lt(a, b) : op == 1 ? rt_x_le(a, b) : op == 2 ? rt_x_gt(a, b)
                                                                        : rt_x_ge(a, b);
    return rt_x_sw(a, b, m, v);
}

/* the mode a located switch takes from its root r (rt_x_swgt ...) at an instant (the
   start or end of a step part, a tick): 1 where the comparison holds (r > 0), 0 where it
   does not; NaN keeps the mode */
static inline real_t rt_x_sw_mode(real_t r, real_t m)
{
    return r != r ? m : r > 0 ? (real_t)1 : (real_t)0;
}

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

/* the first of the n instants v after t, RT_TEV_NEVER if none: a defined system's
   rt_kind.next_event over the values it compares `t` with. An instant t names to rounding
   (rt_same_instant) is t's, not a next one: a tick of 3 * 0.1 s has passed 0.3 s, and no
   step part of one rounding's length follows it. A NaN is no instant */
static inline real_t rt_x_next(real_t t, const real_t *v, unsigned n)
{
    real_t best = RT_TEV_NEVER;
    for (unsigned i = 0; i < n; i++)
        best = v[i] > t && v[i] < best && !rt_same_instant(v[i], t) ? v[i] : best;
    return best;
}

/* how long after now the value u = a t + b of a `floor`'s argument, moving at rate a,
   reaches the next integer past u (a defined system's floor of t, tools/scenec: an
   instant of its next_event, where the floor jumps; the integer after it is another, so
   that one of them follows now when the first is now's to rounding, rt_x_next).
   RT_TEV_NEVER where a is 0 or either is NaN */
static inline real_t rt_x_floor_next(real_t u, real_t a)
{
    if (!(a != 0) || u != u)
        return RT_TEV_NEVER;
    real_t n = a > 0 ? rt_floor(u) + 1 : -rt_floor(-u) - 1; /* the next integer past u */
    return (n - u) / a;
}

/* u = a t + b taken as the integer it lies on to its rounding (RT_TICK_SLACK of the
   larger of |u|, m = |b| and 1: a t + b rounds by that much, however small u is), so a
   jump of the floor that is now's (a part ending at it) is not found again a rounding
   later as a next one (rt_x_floor_next) */
static inline real_t rt_x_floor_snap(real_t u, real_t m)
{
    real_t n = rt_floor(u + (real_t)0.5), au = rt_fabs(u);
    real_t big = au > m ? au : m;
    big = big > 1 ? big : 1;
    return rt_fabs(u - n) <= (real_t)RT_TICK_SLACK * big ? n : u;
}

/* a defined system's rt_kind.band: the largest |v1_i - v0_i| over its n sin and cos
   arguments w t + phi taken at t = 1 (v1) and t = 0 (v0), |w| each (a NaN stays) */
static inline real_t rt_x_band(const real_t *v0, const real_t *v1, unsigned n)
{
    real_t w = 0;
    for (unsigned i = 0; i < n; i++) {
        real_t d = rt_fabs(v1[i] - v0[i]);
        w = d > w || d != d ? d : w;
    }
    return w;
}

/* the time a comparison of `t` with the instant c reads, t_piece tp given: inside a step
   part (tp != t) the part's midpoint, whose side of c is the whole part's, as a step
   source's (the part ending at c sees the left limit at its end, rt/tev.c); at t itself
   (a tick) t, or c where t is c to rounding: t <= c then holds at the instant, t < c
   not, as the operators say */
static inline real_t rt_x_at(real_t t, real_t tp, real_t c)
{
    if (tp != t)
        return tp;
    return rt_same_instant(t, c) ? c : t;
}

#endif /* RT_EXPR_H */
