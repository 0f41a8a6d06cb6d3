/* integ_erk.c - explicit fixed-step Runge-Kutta methods as const Butcher tableaus, one
 * generic stepper, and the registry of integrators.
 *
 * Each method is a const rt_integrator whose tab points to its tableau. The stepper
 * writes every stage state into the set's slice of x, so the right-hand side always
 * reads the state where the blocks expect it (no copies per block). Sums run in a fixed
 * order: the same inputs give the same bits on every target.
 *
 * Every method carries an embedded solution of one order less (e: the weights b - bhat)
 * and reports the scaled norm of the difference as the step's local error estimate
 * (stats->last_err; rt/step.c counts it against the set's accuracy). All but Heun's
 * need one evaluation more per step for it, which erk_bound counts: f(t + h, x1) (FSAL),
 * or for the classic Runge-Kutta method a fifth stage at t + 3h/4. The companion's
 * quadrature rule differs from the method's: when f depends on t alone (y' = g(t), an
 * input driving a lag) the estimate still sees the error. A companion built on the
 * method's own nodes would not: rk4's nodes 0, 1/2, 1 carry one rule exact to degree
 * two, Simpson's, so any third-order companion on them is Simpson's again on a
 * quadrature and the difference is 0 however wrong the step is. */
#include "rti.h"

/* Butcher tableau of an s-stage explicit method: a is s*s row-major (strictly lower) */
typedef struct erk_tab {
    uint8_t s;
    const real_t *a, *b, *c;
    const real_t *e;    /* b - bhat against an embedded solution of one order less:
                           s weights, plus one for the estimate's own stage if any */
    uint8_t fsal;       /* the estimate's stage is f(t + h, x1), the step's end */
    const real_t *ae;   /* else, if not NULL: it is f(t + ce h, x0 + h sum_j ae_j k_j),
                           a stage that only serves the estimate (s weights) */
    real_t ce;
} erk_tab;

/* out[m] = base[m] + h acc (base NULL: acc) for the one state m, summed as combine_k does */
static void combine_one(real_t *out, const real_t *base, real_t h, const real_t *c,
                        const rt_iwork *w, uint32_t m, uint8_t nk)
{
    real_t acc = 0;
    for (uint8_t j = 0; j < nk; j++)
        acc += c[j] * w->k[j][m];
    out[m] = base ? base[m] + h * acc : acc;
}

/* out = base + h acc (base NULL: out = acc), acc = sum_{j<nk} c_j k_j summed from j = 0:
   a stage's state, the new state, the estimate's sum. Two states per iteration, over a
   pair count the compiler can compute, with the stage buffers as restrict pointers (out,
   base and the k_j are distinct buffers of rt_sim.work and the set's state): a target
   with vector registers then takes both states in one, each lane the same scalar sum term
   by term, so the bits are those of one state at a time. The coefficients are read once
   into locals; nk is a constant where combine calls this (terms past it fold away). */
#define ERK_TERM(j, kj)                                                                      if (nk > (j))                                                                            a0 += c[j] * (kj)[m], a1 += c[j] * (kj)[m + 1u]
#define ERK_SUMS                                                                         \
    real_t a0 = 0, a1 = 0;                                                               \
    ERK_TERM(0, k0);                                                                     \
    ERK_TERM(1, k1);                                                                     \
    ERK_TERM(2, k2);                                                                     \
    ERK_TERM(3, k3);                                                                     \
    ERK_TERM(4, k4);                                                                     \
    ERK_TERM(5, k5)
static RTI_INLINE void combine_k(real_t *restrict out, const real_t *restrict base, real_t h,
                                 const real_t *cs, const rt_iwork *w, uint16_t n, uint8_t nk)
{
    real_t c[RT_MAX_STAGES];
    for (uint8_t j = 0; j < nk; j++)
        c[j] = cs[j];
    const real_t *restrict k0 = w->k[0], *restrict k1 = w->k[1], *restrict k2 = w->k[2];
    const real_t *restrict k3 = w->k[3], *restrict k4 = w->k[4], *restrict k5 = w->k[5];
    uint32_t pairs = (uint32_t)n / 2u;
    if (base)
        for (uint32_t p = 0; p < pairs; p++) {
            uint32_t m = 2u * p;
            ERK_SUMS;
            out[m] = base[m] + h * a0, out[m + 1u] = base[m + 1u] + h * a1;
        }
    else
        for (uint32_t p = 0; p < pairs; p++) {
            uint32_t m = 2u * p;
            ERK_SUMS;
            out[m] = a0, out[m + 1u] = a1;
        }
    if (n & 1u) /* the last state of an odd count, alone */
        combine_one(out, base, h, c, w, n - 1u, nk);
}
#undef ERK_TERM
#undef ERK_SUMS

static void combine(real_t *out, const real_t *base, real_t h, const real_t *c, uint8_t nk,
                    const rt_iwork *w, uint16_t n)
{
    switch (nk) { /* every stage count of the tableaus: 1 to 6 */
    case 1: combine_k(out, base, h, c, w, n, 1); break;
    case 2: combine_k(out, base, h, c, w, n, 2); break;
    case 3: combine_k(out, base, h, c, w, n, 3); break;
    case 4: combine_k(out, base, h, c, w, n, 4); break;
    case 5: combine_k(out, base, h, c, w, n, 5); break;
    case 6: combine_k(out, base, h, c, w, n, 6); break;
    default: /* no tableau has more stages; the same sums, one state at a time */
        for (uint16_t m = 0; m < n; m++)
            combine_one(out, base, h, c, w, m, nk);
        break;
    }
}

/* max_i |h sum_j e_j k_ij| / (sa + |x_i|) (rti_err_floor): the local error of the
   embedded solution of one order less, which bounds the method's own from above. The
   pairs whose estimate needs a stage of its own pay one more right-hand side for it
   (erk_extra_stage): the FSAL pairs' f(t + h, x1) cannot be the next step's first stage
   at a fixed step, which sees the state after projection, events and the other sets' new
   outputs. The sum over the s stages goes into x0 (dead once x1 is formed; scratch when
   the start is the caller's, rt_iwork.xs), the extra stage's derivative is in k[s] (an
   estimate stage) or k[0] (FSAL: no buffer of its own, so Dormand-Prince needs six stage
   buffers, not seven, RT_MAX_STAGES, #14), and its term is added last, in the order one
   sum would take (the same bits). */
/* |h (x0_i + es kx_i)| / (sa + |x_i|) (with_kx 0: without the term), the scaled error
   of state i: a ratio >= 0, or NaN */
static RTI_INLINE real_t err_ratio(const real_t *restrict x0, const real_t *restrict kx,
                                   real_t es, real_t h, real_t sa, const real_t *x,
                                   uint32_t i, int with_kx)
{
    real_t acc = with_kx ? x0[i] + es * kx[i] : x0[i];
    return rt_fabs(h * acc) / (sa + rt_fabs(x[i]));
}

/* the largest err_ratio over the n states, NaN if one is. Taken on the bits, as the
   state's norm (rt/step.c): a ratio's bits with the sign cleared order as the ratios do,
   a NaN's above them all, so an integer maximum keeps the largest or the NaN with no
   compare of reals and no branch per state; two states per iteration, each into a
   maximum of its own. with_kx is a constant where erk_estimate calls this */
static RTI_INLINE real_t err_norm(const real_t *restrict x0, const real_t *restrict kx,
                                  real_t es, real_t h, real_t sa, const real_t *x, uint16_t n,
                                  int with_kx)
{
    rt_real_bits m0 = 0, m1 = 0;
    uint32_t i = 0;
    for (; i + 2u <= n; i += 2u) {
        rt_real_rep r0 = {.r = err_ratio(x0, kx, es, h, sa, x, i, with_kx)};
        rt_real_rep r1 = {.r = err_ratio(x0, kx, es, h, sa, x, i + 1u, with_kx)};
        rt_real_bits a0 = r0.u & ~RT_SIGN_BIT, a1 = r1.u & ~RT_SIGN_BIT;
        m0 = a0 > m0 ? a0 : m0, m1 = a1 > m1 ? a1 : m1;
    }
    if (i < n) { /* the last state of an odd count, alone */
        rt_real_rep r = {.r = err_ratio(x0, kx, es, h, sa, x, i, with_kx)};
        rt_real_bits a = r.u & ~RT_SIGN_BIT;
        m0 = a > m0 ? a : m0;
    }
    rt_real_rep m = {.u = m1 > m0 ? m1 : m0};
    return m.r; /* (a NaN with its sign cleared: the same bits on every target) */
}

static real_t erk_estimate(const rt_integrator *m, const rt_rhs *f, real_t t, real_t h,
                           const real_t *x, uint16_t n, const rt_iwork *w)
{
    const erk_tab *tab = m->tab;
    uint8_t s = tab->s;
    const real_t *kx = tab->fsal ? w->k[0] : tab->ae ? w->k[s] : 0;
    combine(w->x0, 0, 0, tab->e, s, w, n);
    if (tab->fsal) {
        rt_status st = f->eval(f->ctx, t + h, w->k[0]);
        if (st != RT_OK) /* no derivative at the end: nothing to vouch for the step */
            return (real_t)1 / (real_t)0;
    }
    real_t sa = rti_err_floor(w->cfg);
    return kx ? err_norm(w->x0, kx, tab->e[s], h, sa, x, n, 1)
              : err_norm(w->x0, 0, 0, h, sa, x, n, 0);
}

/* the stage that serves only the estimate (erk_tab.ae), into k[s], evaluated with the
   step's stages before the new state is formed (its state is written where the blocks
   read it, x; x0 the step's start); a failed evaluation makes the estimate infinite */
static int erk_extra_stage(const erk_tab *tab, const rt_rhs *f, real_t t, real_t h, real_t *x,
                           const real_t *x0, uint16_t n, const rt_iwork *w)
{
    combine(x, x0, h, tab->ae, tab->s, w, n);
    return f->eval(f->ctx, t + tab->ce * h, w->k[tab->s]) == RT_OK;
}

static rt_status erk_step(const rt_integrator *m, const rt_rhs *f, real_t t, real_t h,
                          real_t *x, uint16_t n, const rt_iwork *w)
{
    const erk_tab *tab = m->tab;
    rt_status st = RT_OK;
    /* the start: where the caller keeps it (rt/step.c), else a copy in x0 */
    const real_t *x0 = w->xs;
    if (!x0) {
        for (uint16_t i = 0; i < n; i++)
            w->x0[i] = x[i];
        x0 = w->x0;
    }
    for (uint8_t i = 0; i < tab->s; i++) {
        if (i > 0) /* x = x0 + h sum_{j<i} a_ij k_j, the state of stage i */
            combine(x, x0, h, tab->a + (size_t)i * tab->s, i, w, n);
        rt_status si = f->eval(f->ctx, t + tab->c[i] * h, w->k[i]);
        if (st == RT_OK)
            st = si;
    }
    /* no statistics (a bare step): no estimate, no extra evaluation */
    int extra = w->stats && tab->ae ? erk_extra_stage(tab, f, t, h, x, x0, n, w) : 1;
    combine(x, x0, h, tab->b, tab->s, w, n);
    if (w->stats) {
        real_t e = extra ? erk_estimate(m, f, t, h, x, n, w) : (real_t)1 / (real_t)0;
        w->stats->last_err = e;
        if (e != e || e > w->stats->err_max)
            w->stats->err_max = e;
    }
    return st;
}

/* stages, plus the end-point derivative of the error estimate */
static void erk_bound(const rt_integrator *m, const rt_set_cfg *cfg, uint16_t n,
                      rt_step_work *w)
{
    const erk_tab *tab = m->tab;
    (void)cfg, (void)n;
    w->rhs = (uint32_t)tab->s + (tab->fsal || tab->ae), w->lu = 0;
}

#define R(v) ((real_t)(v))

/* explicit Euler, order 1 */
static const real_t euler_a[] = {0};
static const real_t euler_b[] = {1};
static const real_t euler_c[] = {0};
static const real_t euler_e[] = {R(0.5), R(-0.5)}; /* against Heun's method */
static const erk_tab euler_tab = {1, euler_a, euler_b, euler_c, euler_e, 1, 0, 0};

/* Heun's method (explicit trapezoidal), order 2 */
static const real_t heun_a[] = {0, 0, 1, 0};
static const real_t heun_b[] = {R(0.5), R(0.5)};
static const real_t heun_c[] = {0, 1};
static const real_t heun_e[] = {R(-0.5), R(0.5)}; /* against explicit Euler */
static const erk_tab heun_tab = {2, heun_a, heun_b, heun_c, heun_e, 0, 0, 0};

/* Bogacki-Shampine 3(2); its fourth (FSAL) stage only serves the error estimate */
static const real_t bs3_a[] = {0, 0, 0, R(0.5), 0, 0, 0, R(0.75), 0};
static const real_t bs3_b[] = {R(2.0 / 9.0), R(1.0 / 3.0), R(4.0 / 9.0)};
static const real_t bs3_c[] = {0, R(0.5), R(0.75)};
/* b - bhat, bhat = (7/24, 1/4, 1/3, 1/8) (Bogacki & Shampine 1989) */
static const real_t bs3_e[] = {R(-5.0 / 72.0), R(1.0 / 12.0), R(1.0 / 9.0), R(-1.0 / 8.0)};
static const erk_tab bs3_tab = {3, bs3_a, bs3_b, bs3_c, bs3_e, 1, 0, 0};

/* the classic Runge-Kutta method, order 4 */
static const real_t rk4_a[] = {0, 0, 0, 0, R(0.5), 0, 0, 0, 0, R(0.5), 0, 0, 0, 0, 1, 0};
static const real_t rk4_b[] = {R(1.0 / 6.0), R(1.0 / 3.0), R(1.0 / 3.0), R(1.0 / 6.0)};
static const real_t rk4_c[] = {0, R(0.5), R(0.5), 1};
/* a fifth stage at c = 3/4, only for the estimate, as in Zonneveld's 4(3) pair (Hairer,
   Norsett & Wanner I, II.4), whose difference b - bhat = (2/3, -2, -2, -2, 16/3) every
   third-order companion on these nodes shares up to a factor: it is the one direction
   that annihilates the conditions of order <= 3 (weights summing to 0 against 1, c, c^2
   and A c). On a quadrature it is off at degree three, where b (Simpson's rule) is exact.
   The stage's row (3/16, 0, 9/16, 0) (second-order stage, like Zonneveld's) leaves the
   estimate on y' = lambda y a pure (h lambda)^4 term; Zonneveld's row
   (5/32, 7/32, 13/32, -1/32) gives (h lambda)^4 (1 + h lambda), blind at h lambda = -1.
   The factor is the smallest simple one at which the estimate exceeds rk4's own local
   error on y' = lambda y for every |h lambda| <= 1 (it needs 0.21): 1/4 of the
   direction above, bhat = (13/96, 41/96, 41/96, 25/96, -1/4), 21 times less pessimistic
   than Zonneveld's weights (tests/whitebox/test_integ.c) */
static const real_t rk4_ae[] = {R(3.0 / 16.0), 0, R(9.0 / 16.0), 0};
static const real_t rk4_e[] = {R(1.0 / 32.0), R(-3.0 / 32.0), R(-3.0 / 32.0), R(-3.0 / 32.0),
                               R(1.0 / 4.0)};
static const erk_tab rk4_tab = {4, rk4_a, rk4_b, rk4_c, rk4_e, 0, rk4_ae, R(0.75)};

/* Dormand-Prince 5(4), fifth-order solution; b7 = 0, so six stages suffice at fixed step */
static const real_t dp5_a[] = {
    0, 0, 0, 0, 0, 0,
    R(1.0 / 5.0), 0, 0, 0, 0, 0,
    R(3.0 / 40.0), R(9.0 / 40.0), 0, 0, 0, 0,
    R(44.0 / 45.0), R(-56.0 / 15.0), R(32.0 / 9.0), 0, 0, 0,
    R(19372.0 / 6561.0), R(-25360.0 / 2187.0), R(64448.0 / 6561.0), R(-212.0 / 729.0), 0, 0,
    R(9017.0 / 3168.0), R(-355.0 / 33.0), R(46732.0 / 5247.0), R(49.0 / 176.0),
    R(-5103.0 / 18656.0), 0,
};
static const real_t dp5_b[] = {R(35.0 / 384.0), 0, R(500.0 / 1113.0), R(125.0 / 192.0),
                               R(-2187.0 / 6784.0), R(11.0 / 84.0)};
static const real_t dp5_c[] = {0, R(1.0 / 5.0), R(3.0 / 10.0), R(4.0 / 5.0), R(8.0 / 9.0), 1};
/* b - bhat against the fourth-order companion, whose seventh (FSAL) stage is f(t + h, x1)
   (Dormand & Prince 1980; Hairer, Norsett & Wanner I, II.5) */
static const real_t dp5_e[] = {R(71.0 / 57600.0), 0, R(-71.0 / 16695.0), R(71.0 / 1920.0),
                               R(-17253.0 / 339200.0), R(22.0 / 525.0), R(-1.0 / 40.0)};
static const erk_tab dp5_tab = {6, dp5_a, dp5_b, dp5_c, dp5_e, 1, 0, 0};

const rt_integrator rt_euler = {.name = "euler", .order = 1, .stages = 1, .step = erk_step, .bound = erk_bound,
                                .tab = &euler_tab};
const rt_integrator rt_heun = {.name = "heun", .order = 2, .stages = 2, .step = erk_step, .bound = erk_bound,
                               .tab = &heun_tab};
const rt_integrator rt_bs3 = {.name = "bs3", .order = 3, .stages = 3, .step = erk_step, .bound = erk_bound,
                              .tab = &bs3_tab};
const rt_integrator rt_rk4 = {.name = "rk4", .order = 4, .stages = 4, .step = erk_step, .bound = erk_bound,
                              .tab = &rk4_tab};
const rt_integrator rt_dopri5 = {.name = "dopri5", .order = 5, .stages = 6, .step = erk_step, .bound = erk_bound,
                                 .tab = &dp5_tab};
