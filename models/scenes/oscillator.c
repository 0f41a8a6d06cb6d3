/* oscillator.c - scene `oscillator`: x'' = -(2 pi)^2 x, x(0) = 1, v(0) = 0, 10 s at 1 ms
 * with RK4; records Osc.x. Exact answer x = cos(2 pi t). Written in the form the scene
 * compiler generates. */
#include "scenes.h"

enum { OSC };

static const rt_block blocks[] = {
    [OSC] = {.name = "Osc", .kind = &mdl_oscillator_kind, .set = 0},
};
static const rt_set sets[] = {{.name = "main", .method = &rt_rk4, .ratio = 1}};
static const rt_rec recs[] = {{OSC, RT_SIG_Y, MDL_OSC_Y_X}};

const rt_scene mdl_scene_oscillator = {
    .name = "oscillator",
    .doc = "harmonic oscillator, 1 Hz, RK4 at 1 ms",
    .dt = (real_t)1e-3, .t_end = 10,
    .blocks = blocks, .nblocks = 1,
    .sets = sets, .nsets = 1,
    .recs = recs, .nrecs = 1,
};
