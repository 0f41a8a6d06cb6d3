/* run_compiled.c - runs every compiled scene, the library's (mdl_scenes) and the scene
 * language tests' (scn_test_scenes), as `modrt run` does (rt_init, a record at t = 0 and
 * after every tick) and prints "NAME HASH STATUS" per scene for
 * tests/scenec/hashes.sh. */
#include <stdio.h>

#include "models.h"
#include "rt_sim.h" /* allocates the run */

extern const rt_scene_entry scn_test_scenes[];

static rt_sim sim;

static void run(const rt_scene *sc)
{
    rt_status st = rt_init(sc, &sim);
    if (st == RT_OK) {
        rt_record(sc, &sim, NULL);
        while (rt_tick(sc, &sim) != RT_E_DONE)
            rt_record(sc, &sim, NULL);
        rt_record(sc, &sim, NULL);
    }
    printf("%s %016llx %s\n", sc->name, (unsigned long long)rt_trace_hash(&sim),
           rt_status_name(st != RT_OK ? st : rt_stats_of(&sim)->status));
}

int main(void)
{
    for (const rt_scene_entry *e = mdl_scenes; e->name; e++)
        run(e->scene);
    for (const rt_scene_entry *e = scn_test_scenes; e->name; e++)
        run(e->scene);
    return 0;
}
