/* pendulum10_actuated_single.c - scene `pendulum10_actuated_single`: the model of scene
 * pendulum10_actuated (the hanging ten-body pendulum whose first link a 1 kHz servo raises
 * to horizontal; see models/scenes/pendulum10_actuated.c) in one set, integrated by a stiff
 * method: the servo's eigenvalues (6283 rad/s from the origin) bound the step of every
 * explicit method below 0.5 ms, and the step may not exceed the controller's sample
 * period TS (a set stepping over a sample would read the command of the sample before).
 * The blocks, parameters, initial states and wiring equal pendulum10_actuated's
 * (tests/models/test_actuated.c compares them). Method, step and Jacobian interval are the
 * cheapest the benchmark (tools/bench/multirate_bench.c) found that keep every position
 * at 10 s within 1e-4 m of a fine reference; docs/multirate.md. The scene file
 * pendulum10_actuated_single.scn describes the same scene and must agree with this one.
 *
 * Records what pendulum10_actuated records. 10 s. */
#include "scenes.h"

enum { B1, B2, B3, B4, B5, B6, B7, B8, B9, B10, MOTOR, CTRL, SERVO, NB };

#define TS 1e-3        /* sample period of the controller [s] */
#define STEP 1e-3      /* [s] */
#define JAC_EVERY 1024 /* steps between Jacobian refreshes (the chain moves slowly) */

/* initial states x y z vx vy vz: hanging straight down, at rest */
static const real_t x0[10][6] = {
    {0, 0, -1, 0, 0, 0}, {0, 0, -2, 0, 0, 0}, {0, 0, -3, 0, 0, 0}, {0, 0, -4, 0, 0, 0},
    {0, 0, -5, 0, 0, 0}, {0, 0, -6, 0, 0, 0}, {0, 0, -7, 0, 0, 0}, {0, 0, -8, 0, 0, 0},
    {0, 0, -9, 0, 0, 0}, {0, 0, -10, 0, 0, 0},
};

#define POINT(n, k) {.name = n, .kind = &mdl_mbs_point_kind, .x0 = x0[k]}
static const rt_block blocks[NB] = {
    {.name = "B1", .kind = &mdl_mbs_pointf_kind, .x0 = x0[B1]},
    POINT("B2", B2), POINT("B3", B3), POINT("B4", B4), POINT("B5", B5),
    POINT("B6", B6), POINT("B7", B7), POINT("B8", B8), POINT("B9", B9), POINT("B10", B10),
    [MOTOR] = {.name = "Motor", .kind = &mdl_arm_motor_kind},
    [CTRL] = {.name = "Ctrl", .kind = &mdl_arm_pd_kind, .ts = (real_t)TS},
    [SERVO] = {.name = "Servo", .kind = &mdl_servo2_kind},
};

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
    {.name = "all", .method = &rt_ros2, .ratio = 1, .implicit = {.jac_every = JAC_EVERY}},
};

#define XZ(b) {b, RT_SIG_Y, MDL_MBS_POINT_X}, {b, RT_SIG_Y, MDL_MBS_POINT_Z}
static const rt_rec recs[] = {
    XZ(B1), XZ(B2), XZ(B3), XZ(B4), XZ(B5), XZ(B6), XZ(B7), XZ(B8), XZ(B9), XZ(B10),
    {CTRL, RT_SIG_Y, MDL_ARM_PD_Y_THETA}, {CTRL, RT_SIG_Y, MDL_ARM_PD_Y_THR},
    {B1, RT_SIG_MBS, RT_MBS_SIG_RESIDUAL},
};

const rt_scene mdl_scene_pendulum10_actuated_single = {
    .name = "pendulum10_actuated_single",
    .doc = "pendulum10_actuated in one set with a stiff method (single-rate)",
    .dt = (real_t)STEP, .t_end = 10,
    .blocks = blocks, .nblocks = NB,
    .conns = conns, .nconns = sizeof conns / sizeof conns[0],
    .sets = sets, .nsets = 1,
    .recs = recs, .nrecs = sizeof recs / sizeof recs[0],
    .joints = joints, .njoints = 10,
    .mbs = &rt_mbs, .stab = RT_STAB_PROJECT,
};
