/* footprint_main.c - the one-scene image of `make footprint`: it links only the scene named
 * at compile time (-DFOOT_SCENE=mdl_scene_<name>) and the models that scene uses, paints
 * the stack, runs the scene to its end calling port_cycles() once before every tick (the
 * marker of the QEMU instruction-count plugin, tools/qemu/insn_count.c), and prints the
 * trace hash and the stack high-water mark. */
#include "harness.h"
#include "port.h"
#include "rt.h"

#define PAINT 0xA5C3E1F7u /* a word no real stack frame is likely to hold */
#define PAINT_MARGIN 256  /* bytes below the current stack pointer left unpainted */
#ifndef FOOT_TICKS
#define FOOT_TICKS 1000   /* ticks measured (or the whole scene if shorter) */
#endif

extern const rt_scene FOOT_SCENE;
extern uint32_t __stack_bottom[], __stack_top[];

static rt_sim sim;

/* fills the unused stack below this frame with the pattern */
static void paint(void)
{
    uint32_t here = 0, *sp = &here;
    for (uint32_t *p = __stack_bottom; p + PAINT_MARGIN / 4 < sp; p++)
        *p = PAINT;
}

/* bytes of stack ever used: from the top down to the lowest word that lost the pattern */
static uint32_t high_water(void)
{
    uint32_t *p = __stack_bottom;
    while (p < __stack_top && *p == PAINT)
        p++;
    return (uint32_t)((char *)__stack_top - (char *)p);
}

int app_main(void)
{
    const rt_scene *sc = &FOOT_SCENE;
    rt_status st = rt_init(sc, &sim);
    if (st != RT_OK) {
        th_put("init failed: ");
        th_put(rt_error_text(&sim));
        th_put("\n");
        return 1;
    }
    rt_record(sc, &sim, 0);
    paint(); /* after init: the mark measures ticks and recording only */
    do {
        (void)port_cycles(); /* marker: the plugin counts instructions between calls */
        st = rt_tick(sc, &sim);
        rt_record(sc, &sim, 0);
    } while (st != RT_E_DONE && sim.state.tick < FOOT_TICKS);
    (void)port_cycles();
    th_put("scene ");
    th_put(sc->name);
    th_put(" ticks ");
    th_put_int((long long)sim.state.tick);
    th_put(" hash ");
    th_put_hex64(sim.state.hash);
    th_put(" stack ");
    th_put_int(high_water());
    th_put("\n");
    return sim.stats.status == RT_OK ? 0 : 1;
}
