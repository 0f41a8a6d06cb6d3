/* pi_loop.c - scene `pi_loop`: a PI controller sampled at 10 ms closes a loop around a
 * continuous first-order plant (K = 2, T = 0.5 s); a unit step of the reference at
 * t = 0.1 s. Base tick 1 ms, RK4; 3 s. Records Ref.y, PI.c and Plant.y. */
#include "scenes.h"

enum { REF, PI, PLANT };

static const real_t ref_p[] = {(real_t)0.1, 0, 1};
static const real_t pi_p[] = {(real_t)0.8, 3};
static const real_t plant_p[] = {2, (real_t)0.5};
static const rt_block blocks[] = {
    [REF] = {.name = "Ref", .kind = &mdl_step_kind, .p = ref_p},
    [PI] = {.name = "PI", .kind = &mdl_pi_kind, .p = pi_p, .ts = (real_t)0.01},
    [PLANT] = {.name = "Plant", .kind = &mdl_pt1_kind, .p = plant_p},
};
static const rt_conn conns[] = {
    {REF, 0, PI, MDL_PI_U_R},
    {PLANT, MDL_PT1_Y, PI, MDL_PI_U_M},
    {PI, MDL_PI_Y_C, PLANT, MDL_PT1_U},
};
static const rt_set sets[] = {{.name = "main", .method = &rt_rk4, .ratio = 1}};
static const rt_rec recs[] = {
    {REF, RT_SIG_Y, 0}, {PI, RT_SIG_Y, MDL_PI_Y_C}, {PLANT, RT_SIG_Y, MDL_PT1_Y},
};

const rt_scene mdl_scene_pi_loop = {
    .name = "pi_loop",
    .doc = "sampled PI (10 ms) around a first-order plant, step response",
    .dt = (real_t)1e-3, .t_end = 3,
    .blocks = blocks, .nblocks = 3,
    .conns = conns, .nconns = 3,
    .sets = sets, .nsets = 1,
    .recs = recs, .nrecs = 3,
};
