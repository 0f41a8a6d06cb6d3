/* pendulum10_actuated.c - scene `pendulum10_actuated` (paper, section 5, Fig. 4 right): the
 * ten-body pendulum of scene pendulum10 (mass points B1..B10 of 1 kg, spherical difference
 * joints of 1 m, B1 on a fixed anchor at the origin, gravity 9.81 m/s^2 along -z), starting
 * at rest hanging straight down (Bk at (0, 0, -k) m). A motor at the anchor turns the
 * first link as a massless arm (arm_motor: the torque acts on B1 perpendicular to the
 * link); the torque comes from a stiff servo of natural frequency 1 kHz (servo2: omega =
 * 2 pi 1000 rad/s, zeta = 0.7) commanded by a digital computed-torque PD controller
 * sampled every TS (arm_pd) that raises the first link from hanging (-90 deg) to
 * horizontal (0 deg) along a quintic over 6 s and holds it there; models/actuator.c and
 * docs/multirate.md give the equations and parameters. 10 s.
 *
 * Multirate: the chain and the motor in set "chain" (Bogacki-Shampine, explicit, every
 * CHAIN_RATIO base ticks), the controller and the servo in set "servo" (ROS2, linearly
 * implicit, every base tick = the sample period). The chain steps first; the servo set
 * interpolates B1's position (cubic Hermite), the chain extrapolates the servo's torque
 * linearly. This is the cheapest configuration the benchmark
 * (tools/bench/multirate_bench.c) found that keeps every position at 10 s within 1e-4 m
 * of a fine reference (with beuler in the servo set within the timing noise);
 * `modrt tune pendulum10_actuated --tol 1e-4` confirms the schedule. The scene file
 * pendulum10_actuated.scn describes the same scene and must agree with this one.
 *
 * Records B1.x, B1.z .. B10.x, B10.z [m], the link angle Ctrl.theta (the last measured)
 * and its reference Ctrl.thr [rad], and the largest constraint residual of the chain
 * B1.residual [m]. */
#include "scenes.h"

enum { B1, B2, B3, B4, B5, B6, B7, B8, B9, B10, MOTOR, CTRL, SERVO, NB };
enum { CHAIN, FAST };

#define TS 1e-3        /* sample period of the controller [s] */
#define BASE_TICK 1e-3 /* [s]: the servo set's step */
#define CHAIN_RATIO 16 /* the chain's step in base ticks */
#define JAC_EVERY 64   /* servo steps between Jacobian refreshes (the servo is linear) */

/* initial states x y z vx vy vz: hanging straight down, at rest */
static const real_t x0[10][6] = {
    {0, 0, -1, 0, 0, 0}, {0, 0, -2, 0, 0, 0}, {0, 0, -3, 0, 0, 0}, {0, 0, -4, 0, 0, 0},
    {0, 0, -5, 0, 0, 0}, {0, 0, -6, 0, 0, 0}, {0, 0, -7, 0, 0, 0}, {0, 0, -8, 0, 0, 0},
    {0, 0, -9, 0, 0, 0}, {0, 0, -10, 0, 0, 0},
};

/* mass 1 kg, gravity (0, 0, -9.81) m/s^2: the kinds' defaults; servo and controller
   parameters: the kinds' defaults too (models/actuator.c) */
#define POINT(n, k) {.name = n, .kind = &mdl_mbs_point_kind, .x0 = x0[k], .set = CHAIN}
static const rt_block blocks[NB] = {
    {.name = "B1", .kind = &mdl_mbs_pointf_kind, .x0 = x0[B1], .set = CHAIN},
    POINT("B2", B2), POINT("B3", B3), POINT("B4", B4), POINT("B5", B5),
    POINT("B6", B6), POINT("B7", B7), POINT("B8", B8), POINT("B9", B9), POINT("B10", B10),
    [MOTOR] = {.name = "Motor", .kind = &mdl_arm_motor_kind, .set = CHAIN},
    [CTRL] = {.name = "Ctrl", .kind = &mdl_arm_pd_kind, .set = FAST, .ts = (real_t)TS},
    [SERVO] = {.name = "Servo", .kind = &mdl_servo2_kind, .set = FAST},
};

/* B1 -> controller (across sets), controller -> servo -> motor (across sets) -> B1 */
static const rt_conn conns[] = {
    {B1, MDL_MBS_POINT_X, CTRL, MDL_ARM_PD_U_X},
    {B1, MDL_MBS_POINT_Z, CTRL, MDL_ARM_PD_U_Z},
    {CTRL, MDL_ARM_PD_Y_U, SERVO, 0},
    {SERVO, MDL_SERVO2_Y, MOTOR, MDL_ARM_MOTOR_U_TAU},
    {B1, MDL_MBS_POINT_X, MOTOR, MDL_ARM_MOTOR_U_X},
    {B1, MDL_MBS_POINT_Z, MOTOR, MDL_ARM_MOTOR_U_Z},
    {MOTOR, 0, B1, 0}, {MOTOR, 1, B1, 1}, {MOTOR, 2, B1, 2},
};

static const real_t len[] = {1}; /* l [m] */
#define LINK(n, b, to) {.name = n, .kind = &rt_joint_sphdiff, .b1 = b, .b2 = to, .p = len}
static const rt_joint joints[10] = {
    LINK("J1", B1, -1), LINK("J2", B2, B1), LINK("J3", B3, B2), LINK("J4", B4, B3),
    LINK("J5", B5, B4), LINK("J6", B6, B5), LINK("J7", B7, B6), LINK("J8", B8, B7),
    LINK("J9", B9, B8), LINK("J10", B10, B9),
};

static const rt_set sets[] = {
    [CHAIN] = {.name = "chain", .method = &rt_bs3, .ratio = CHAIN_RATIO,
               .interp = RT_INTERP_EXTRAP},
    [FAST] = {.name = "servo", .method = &rt_ros2, .ratio = 1, .interp = RT_INTERP_HERMITE,
              .implicit = {.jac_every = JAC_EVERY}},
};

#define XZ(b) {b, RT_SIG_Y, MDL_MBS_POINT_X}, {b, RT_SIG_Y, MDL_MBS_POINT_Z}
static const rt_rec recs[] = {
    XZ(B1), XZ(B2), XZ(B3), XZ(B4), XZ(B5), XZ(B6), XZ(B7), XZ(B8), XZ(B9), XZ(B10),
    {CTRL, RT_SIG_Y, MDL_ARM_PD_Y_THETA}, {CTRL, RT_SIG_Y, MDL_ARM_PD_Y_THR},
    {B1, RT_SIG_MBS, RT_MBS_SIG_RESIDUAL},
};

const rt_scene mdl_scene_pendulum10_actuated = {
    .name = "pendulum10_actuated",
    .doc = "pendulum10 hanging, first link raised by a 1 kHz servo; multirate",
    .dt = (real_t)BASE_TICK, .t_end = 10,
    .blocks = blocks, .nblocks = NB,
    .conns = conns, .nconns = sizeof conns / sizeof conns[0],
    .sets = sets, .nsets = 2,
    .recs = recs, .nrecs = sizeof recs / sizeof recs[0],
    .joints = joints, .njoints = 10,
    .mbs = &rt_mbs, .stab = RT_STAB_PROJECT,
};
