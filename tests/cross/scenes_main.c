/* scenes_main.c - the scene image for cross targets: runs library scenes as `modrt run`
 * does (a record at t = 0 and after every tick), each over its whole run to its end time,
 * and prints one line per scene, "scene NAME ticks N status S hash H", for comparison
 * with the host (whose image runs them all). A part (-DSC_PART=k -DSC_PARTS=n) runs every
 * n-th scene from the k-th on, so that no one emulated run is long on the soft-float
 * targets. */
#include "harness.h"
#include "models.h"
#include "port.h"
#include "rt_sim.h" /* allocates the run */

#ifndef SC_PART
#define SC_PART 0
#define SC_PARTS 1
#endif

static rt_sim sim;

static void run_scene(const rt_scene *sc)
{
    rt_status st = rt_init(sc, &sim);
    th_put("scene ");
    th_put(sc->name);
    if (st != RT_OK) {
        th_put(" init ");
        th_put(rt_status_name(st));
        th_put("\n");
        return;
    }
    rt_record(sc, &sim, 0);
    rt_status t;
    do {
        t = rt_tick(sc, &sim);
        rt_record(sc, &sim, 0);
    } while (t != RT_E_DONE);
    th_put(" ticks ");
    th_put_int((long long)rt_ticks_done(&sim));
    th_put(" status ");
    if (rt_stats_of(&sim)->status == RT_OK) /* one word, so scripts can split the line */
        th_put("ok");
    else
        th_put("fault"), th_put_int(rt_stats_of(&sim)->status);
    th_put(" hash ");
    th_put_hex64(rt_trace_hash(&sim));
    th_put("\n");
}

int app_main(void)
{
    unsigned i = 0;
    for (const rt_scene_entry *e = mdl_scenes; e->name; e++, i++)
        if (i % (unsigned)SC_PARTS == (unsigned)SC_PART)
            run_scene(e->scene);
    return 0;
}
