/* pendulum10.c - scene `pendulum10` (paper, section 5, Fig. 4 left): ten mass points of
 * 1 kg, blocks B1..B10; B1 hangs from a fixed anchor at the origin and Bk from B(k-1), each
 * by a spherical difference joint |r1 - r2| - l = 0 (eq. 8) of l = 1 m. Gravity 9.81 m/s^2
 * along -z; released at rest straight along +x (Bk at (k, 0, 0) m). Post-stabilizing
 * projection after every step (eq. 10). Records B1.x, B1.z .. B10.x, B10.z [m], the total
 * energy [J] and the largest constraint residual |g| [m]; 10 s.
 *
 * Integrator and step: DEFAULT_METHOD at DEFAULT_STEP keep the positions at t = 2 s
 * within 1e-6 m of a fine reference (see docs/mbs.md, "pendulum10", for the check). */
#include "scenes.h"

enum { B1, B2, B3, B4, B5, B6, B7, B8, B9, B10, NB };

#define DEFAULT_METHOD rt_dopri5
#define DEFAULT_STEP 5e-3 /* [s] */

/* initial states x y z vx vy vz: straight along +x, at rest */
static const real_t x0[NB][6] = {
    {1, 0, 0, 0, 0, 0}, {2, 0, 0, 0, 0, 0}, {3, 0, 0, 0, 0, 0}, {4, 0, 0, 0, 0, 0},
    {5, 0, 0, 0, 0, 0}, {6, 0, 0, 0, 0, 0}, {7, 0, 0, 0, 0, 0}, {8, 0, 0, 0, 0, 0},
    {9, 0, 0, 0, 0, 0}, {10, 0, 0, 0, 0, 0},
};

/* mass 1 kg, gravity (0, 0, -9.81) m/s^2: the kind's defaults */
#define POINT(n, k) {.name = n, .kind = &mdl_mbs_point_kind, .x0 = x0[k]}
static const rt_block blocks[NB] = {
    POINT("B1", B1), POINT("B2", B2), POINT("B3", B3), POINT("B4", B4), POINT("B5", B5),
    POINT("B6", B6), POINT("B7", B7), POINT("B8", B8), POINT("B9", B9), POINT("B10", B10),
};

static const real_t len[] = {1}; /* l [m] */
#define LINK(n, b, to) {.name = n, .kind = &rt_joint_sphdiff, .b1 = b, .b2 = to, .p = len}
static const rt_joint joints[NB] = {
    LINK("J1", B1, -1), LINK("J2", B2, B1), LINK("J3", B3, B2), LINK("J4", B4, B3),
    LINK("J5", B5, B4), LINK("J6", B6, B5), LINK("J7", B7, B6), LINK("J8", B8, B7),
    LINK("J9", B9, B8), LINK("J10", B10, B9),
};

static const rt_set sets[] = {{.name = "mbs", .method = &DEFAULT_METHOD, .ratio = 1}};

#define XZ(b) {b, RT_SIG_Y, MDL_MBS_POINT_X}, {b, RT_SIG_Y, MDL_MBS_POINT_Z}
static const rt_rec recs[] = {
    XZ(B1), XZ(B2), XZ(B3), XZ(B4), XZ(B5), XZ(B6), XZ(B7), XZ(B8), XZ(B9), XZ(B10),
    {B1, RT_SIG_MBS, RT_MBS_SIG_ENERGY}, {B1, RT_SIG_MBS, RT_MBS_SIG_RESIDUAL},
};

const rt_scene mdl_scene_pendulum10 = {
    .name = "pendulum10",
    .doc = "ten-body pendulum of mass points and spherical difference joints, projected",
    .dt = (real_t)DEFAULT_STEP, .t_end = 10,
    .blocks = blocks, .nblocks = NB,
    .sets = sets, .nsets = 1,
    .recs = recs, .nrecs = sizeof recs / sizeof recs[0],
    .joints = joints, .njoints = NB,
    .mbs = &rt_mbs, .stab = RT_STAB_PROJECT,
};
