/* vanderpol.c - scene `vanderpol`: van der Pol with mu = 1 from (2, 0), 20 s at 1 ms with
 * RK4; records VdP.x and VdP.v. Its limit cycle has period 6.6632868593 s. */
#include "scenes.h"

enum { VDP };

static const real_t p[] = {1};
static const real_t x0[] = {2, 0};
static const rt_block blocks[] = {
    [VDP] = {.name = "VdP", .kind = &mdl_vanderpol_kind, .p = p, .x0 = x0, .set = 0},
};
static const rt_set sets[] = {{.name = "main", .method = &rt_rk4, .ratio = 1}};
static const rt_rec recs[] = {{VDP, RT_SIG_Y, 0}, {VDP, RT_SIG_Y, 1}};

const rt_scene mdl_scene_vanderpol = {
    .name = "vanderpol",
    .doc = "van der Pol oscillator, mu = 1, RK4 at 1 ms",
    .dt = (real_t)1e-3, .t_end = 20,
    .blocks = blocks, .nblocks = 1,
    .sets = sets, .nsets = 1,
    .recs = recs, .nrecs = 2,
};
