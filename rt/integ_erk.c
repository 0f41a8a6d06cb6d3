/* integ_erk.c - explicit fixed-step Runge-Kutta methods as const Butcher tableaus, one
 * generic stepper, and the registry of integrators.
 *
 * Each method is a const rt_integrator whose tab points to its tableau. The stepper
 * writes every stage state into the set's slice of x, so the right-hand side always
 * reads the state where the blocks expect it (no copies per block). Sums run in a fixed
 * order: the same inputs give the same bits on every target. */
#include "rti.h"

/* Butcher tableau of an s-stage explicit method: a is s*s row-major (strictly lower) */
typedef struct erk_tab {
    uint8_t s;
    const real_t *a, *b, *c;
} erk_tab;

/* x = x0 + h * sum_{j<i} a_ij k_j, the state of stage i */
static void stage_state(const erk_tab *t, uint8_t i, real_t h, real_t *x, uint16_t n,
                        const rt_iwork *w)
{
    for (uint16_t m = 0; m < n; m++) {
        real_t acc = 0;
        for (uint8_t j = 0; j < i; j++)
            acc += t->a[i * t->s + j] * w->k[j][m];
        x[m] = w->x0[m] + h * acc;
    }
}

static rt_status erk_step(const rt_integrator *m, const rt_rhs *f, real_t t, real_t h,
                          real_t *x, uint16_t n, const rt_iwork *w)
{
    const erk_tab *tab = m->tab;
    rt_status st = RT_OK;
    for (uint16_t i = 0; i < n; i++)
        w->x0[i] = x[i];
    for (uint8_t i = 0; i < tab->s; i++) {
        if (i > 0)
            stage_state(tab, i, h, x, n, w);
        rt_status si = f->eval(f->ctx, t + tab->c[i] * h, w->k[i]);
        if (st == RT_OK)
            st = si;
    }
    for (uint16_t i = 0; i < n; i++) {
        real_t acc = 0;
        for (uint8_t j = 0; j < tab->s; j++)
            acc += tab->b[j] * w->k[j][i];
        x[i] = w->x0[i] + h * acc;
    }
    return st;
}

#define R(v) ((real_t)(v))

/* explicit Euler, order 1 */
static const real_t euler_a[] = {0};
static const real_t euler_b[] = {1};
static const real_t euler_c[] = {0};
static const erk_tab euler_tab = {1, euler_a, euler_b, euler_c};

/* Heun's method (explicit trapezoidal), order 2 */
static const real_t heun_a[] = {0, 0, 1, 0};
static const real_t heun_b[] = {R(0.5), R(0.5)};
static const real_t heun_c[] = {0, 1};
static const erk_tab heun_tab = {2, heun_a, heun_b, heun_c};

/* Bogacki-Shampine, order 3 (its fourth, FSAL stage only serves error estimates) */
static const real_t bs3_a[] = {0, 0, 0, R(0.5), 0, 0, 0, R(0.75), 0};
static const real_t bs3_b[] = {R(2.0 / 9.0), R(1.0 / 3.0), R(4.0 / 9.0)};
static const real_t bs3_c[] = {0, R(0.5), R(0.75)};
static const erk_tab bs3_tab = {3, bs3_a, bs3_b, bs3_c};

/* the classic Runge-Kutta method, order 4 */
static const real_t rk4_a[] = {0, 0, 0, 0, R(0.5), 0, 0, 0, 0, R(0.5), 0, 0, 0, 0, 1, 0};
static const real_t rk4_b[] = {R(1.0 / 6.0), R(1.0 / 3.0), R(1.0 / 3.0), R(1.0 / 6.0)};
static const real_t rk4_c[] = {0, R(0.5), R(0.5), 1};
static const erk_tab rk4_tab = {4, rk4_a, rk4_b, rk4_c};

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
static const erk_tab dp5_tab = {6, dp5_a, dp5_b, dp5_c};

const rt_integrator rt_euler = {.name = "euler", .order = 1, .stages = 1, .step = erk_step,
                                .tab = &euler_tab};
const rt_integrator rt_heun = {.name = "heun", .order = 2, .stages = 2, .step = erk_step,
                               .tab = &heun_tab};
const rt_integrator rt_bs3 = {.name = "bs3", .order = 3, .stages = 3, .step = erk_step,
                              .tab = &bs3_tab};
const rt_integrator rt_rk4 = {.name = "rk4", .order = 4, .stages = 4, .step = erk_step,
                              .tab = &rk4_tab};
const rt_integrator rt_dopri5 = {.name = "dopri5", .order = 5, .stages = 6, .step = erk_step,
                                 .tab = &dp5_tab};
