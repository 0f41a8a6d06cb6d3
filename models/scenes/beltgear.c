/* beltgear.c - scene `beltgear` (the paper's Fig. 6): two pulleys joined by an elastic
 * belt with inertia, driven by a motor whose current loop follows a step command, and
 * braked by a constant load torque. The current loop (Ctl, Motor) is a potential loop,
 * solved by ordering; the drive train (P1, Belt, P2) is an actual loop, torn and solved
 * by Broyden's method. Base tick 0.1 ms, RK4, 0.5 s. */
#include "scenes.h"

enum { REF, CTL, MOTOR, KT, P1, P2, R1, R2, BELT };

static const real_t ref_p[] = {(real_t)0.01, 0, 2};          /* 2 A from 10 ms on */
static const real_t ctl_p[] = {10, -10};                      /* v = Kc (i_ref - i) */
static const real_t motor_p[] = {1, (real_t)0.005};           /* T i' = v - i */
static const real_t kt_p[] = {(real_t)0.5};                   /* torque constant [N m/A] */
static const real_t p1_p[] = {(real_t)0.01, (real_t)0.05, -1}; /* J1, r1: a1 = (M - r1 F)/J1 */
static const real_t p2_p[] = {(real_t)0.04, (real_t)0.1, 1};   /* J2, r2: a2 = (M + r2 F)/J2 */

static const rt_block blocks[] = {
    [REF] = {.name = "Ref", .kind = &mdl_step_kind, .p = ref_p},
    [CTL] = {.name = "Ctl", .kind = &mdl_sum_kind, .p = ctl_p},
    [MOTOR] = {.name = "Motor", .kind = &mdl_pt1_kind, .p = motor_p},
    [KT] = {.name = "Kt", .kind = &mdl_gain_kind, .p = kt_p},
    [P1] = {.name = "P1", .kind = &mdl_pulley_kind, .p = p1_p},
    [P2] = {.name = "P2", .kind = &mdl_pulley_kind, .p = p2_p},
    [R1] = {.name = "R1", .kind = &mdl_rotor_kind},
    [R2] = {.name = "R2", .kind = &mdl_rotor_kind},
    [BELT] = {.name = "Belt", .kind = &mdl_belt_kind},
};
static const rt_conn conns[] = {
    {REF, 0, CTL, 0}, {MOTOR, 0, CTL, 1}, {CTL, 0, MOTOR, 0}, {MOTOR, 0, KT, 0},
    {KT, 0, P1, 0}, {BELT, 0, P1, 1}, {BELT, 0, P2, 1},
    {P1, 0, R1, 0}, {P2, 0, R2, 0},
    {R1, 0, BELT, 0}, {R1, 1, BELT, 1}, {R2, 0, BELT, 2}, {R2, 1, BELT, 3},
    {P1, 0, BELT, 4}, {P2, 0, BELT, 5},
};
static const rt_default defaults[] = {{P2, 0, (real_t)-0.2}}; /* load torque 0.2 N m */
static const rt_set sets[] = {{.name = "main", .method = &rt_rk4, .ratio = 1}};
static const rt_rec recs[] = {
    {MOTOR, RT_SIG_Y, 0}, {R1, RT_SIG_Y, 1}, {R2, RT_SIG_Y, 1}, {BELT, RT_SIG_Y, 0},
};

const rt_scene mdl_scene_beltgear = {
    .name = "beltgear",
    .doc = "belt gear with a potential and an actual algebraic loop (paper Fig. 6)",
    .dt = (real_t)1e-4, .t_end = (real_t)0.5,
    .blocks = blocks, .nblocks = 9,
    .conns = conns, .nconns = 15,
    .defaults = defaults, .ndefaults = 1,
    .sets = sets, .nsets = 1,
    .recs = recs, .nrecs = 4,
    .loop_solver = &rt_broyden,
};
