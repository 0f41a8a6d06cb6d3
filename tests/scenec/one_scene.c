/* one_scene.c - the one-scene image of tests/scenec/effects.sh: only the scene named at
 * compile time (-DSCN_ONE=mdl_scene_<name>) and what it references; runs it to its end
 * and prints its hash, so the image is a real, working program. */
#include <stdio.h>

#include "rt.h"
#include "rt_sim.h" /* allocates the run */

extern const rt_scene SCN_ONE;

static rt_sim sim;

int main(void)
{
    const rt_scene *sc = &SCN_ONE;
    if (rt_init(sc, &sim) != RT_OK)
        return 1;
    rt_record(sc, &sim, NULL);
    while (rt_tick(sc, &sim) != RT_E_DONE)
        rt_record(sc, &sim, NULL);
    rt_record(sc, &sim, NULL);
    printf("%s %016llx\n", sc->name, (unsigned long long)rt_trace_hash(&sim));
    return 0;
}
