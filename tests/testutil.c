/* testutil.c - helpers shared by the tests (see testutil.h). */
#include "testutil.h"

#include "rt_sim.h" /* allocates tu_sim and tu_spare */

rt_sim tu_sim, tu_spare;

int tu_init(const rt_scene *sc)
{
    rt_status st = rt_init(sc, &tu_sim);
    if (st != RT_OK) {
        th_put("  init: ");
        th_put(rt_status_name(st));
        th_put(": ");
        th_put(rt_error_text(&tu_sim));
        th_put("\n");
    }
    return TH_CHECK(st == RT_OK);
}

rt_status tu_run_to(const rt_scene *sc, real_t t)
{
    uint64_t n = (uint64_t)(t / sc->dt + (real_t)0.5);
    rt_status st = RT_OK;
    while (rt_ticks_done(&tu_sim) < n && st == RT_OK)
        st = rt_tick(sc, &tu_sim);
    return st;
}

real_t tu_y(const rt_scene *sc, const char *block, uint16_t j)
{
    int b = rt_block_index(sc, block);
    return b < 0 ? (real_t)0 / (real_t)0 : rt_output(&tu_sim, (uint16_t)b, j);
}
