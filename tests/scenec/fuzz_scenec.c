/* fuzz_scenec.c - the fuzz target of the scene compiler: any bytes as a scene file, with
 * includes that never touch the file system. What compiles is also written as C (to
 * /dev/null) and run for a few ticks in host memory, so the checker, the emitter, the VM
 * and rt_init see everything the parser lets through. Nothing may crash, leak, read out
 * of bounds or hit undefined behaviour (libFuzzer with ASan and UBSan, or fuzz_main.c). */
#include <stdio.h>

#include "scn.h"

#define FUZZ_TICKS 64 /* base ticks a compiled input runs */

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    scn_ctx *c = scn_new();
    if (!c)
        return 0;
    c->sandbox = 1;
    if (scn_compile(c, "fuzz.scn", (const char *)data, size) == 0) {
        FILE *f = fopen("/dev/null", "w");
        if (f) {
            scn_emit(c, f);
            fclose(f);
        }
        rt_scene sc = c->image;
        if (sc.t_end > sc.dt * FUZZ_TICKS)
            sc.t_end = sc.dt * FUZZ_TICKS;
        if (rt_init(&sc, c->sim) == RT_OK)
            while (rt_tick(&sc, c->sim) != RT_E_DONE)
                rt_record(&sc, c->sim, NULL);
    }
    scn_free(c);
    return 0;
}
