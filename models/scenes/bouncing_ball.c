/* bouncing_ball.c - scene `bouncing_ball`: a ball dropped from 1 m, restitution 0.8,
 * g = 9.81 m/s^2; impacts are state events. 1 ms, RK4, 3.5 s. Records Ball.h, Ball.v and
 * the impact count. */
#include "scenes.h"

enum { BALL };

static const rt_block blocks[] = {
    [BALL] = {.name = "Ball", .kind = &mdl_ball_kind},
};
static const rt_set sets[] = {{.name = "main", .method = &rt_rk4, .ratio = 1}};
static const rt_rec recs[] = {
    {BALL, RT_SIG_Y, 0}, {BALL, RT_SIG_Y, 1}, {BALL, RT_SIG_D, MDL_BALL_D_N},
};

const rt_scene mdl_scene_bouncing_ball = {
    .name = "bouncing_ball",
    .doc = "ball dropped from 1 m, restitution 0.8, impacts as state events",
    .dt = (real_t)1e-3, .t_end = (real_t)3.5,
    .blocks = blocks, .nblocks = 1,
    .sets = sets, .nsets = 1,
    .recs = recs, .nrecs = 3,
};
