/* code_run.c - one scene compiled by scenec, run with the code scenec writes out for it
 * (CODE_RUN_SCENE names its rt_scene) as `modrt run` runs a scene: a record at t = 0 and
 * after every tick, for the ticks given (or to the scene's end); prints its trace hash and
 * status. `make speedup` counts its instructions (tools/dev/bench/speedup.py, "compiled").
 * Usage: code_run [TICKS] */
#include <stdio.h>
#include <stdlib.h>

#include "models.h"
#include "rt_sim.h" /* allocates the run */

extern const rt_scene CODE_RUN_SCENE;

static rt_sim sim;

int main(int argc, char **argv)
{
    const rt_scene *sc = &CODE_RUN_SCENE;
    unsigned long ticks = argc > 1 ? strtoul(argv[1], NULL, 10) : 0, n = 0;
    rt_status st = rt_init(sc, &sim);
    if (st == RT_OK) {
        rt_record(sc, &sim, NULL);
        for (rt_status t = RT_OK; t != RT_E_DONE && (ticks == 0 || n++ < ticks);) {
            t = rt_tick(sc, &sim);
            rt_record(sc, &sim, NULL); /* the last tick's too, as modrt run records it */
        }
    }
    printf("hash: %016llx\nstatus: %s\n", (unsigned long long)rt_trace_hash(&sim),
           rt_status_name(st != RT_OK ? st : rt_stats_of(&sim)->status));
    return st == RT_OK ? 0 : 1;
}
