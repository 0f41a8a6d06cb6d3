/* footprint_main.c - the one-scene image of `make footprint`: it links only the scene named
 * at compile time (-DFOOT_SCENE=mdl_scene_<name>) and the models that scene uses, paints
 * the stack, runs the scene to its end calling port_cycles() before every tick and
 * foot_tick_end() after it (the markers of the QEMU instruction-count plugin,
 * tools/dev/qemu/insn_count.c: the tick context), and prints the trace hash and the stack
 * high-water mark. A scene with a background set gets a background context
 * (rt_bg_attach): its step runs between ticks at the port's background level (PendSV on
 * Cortex-M, else called from here), between foot_bg_begin() and foot_bg_end() (the
 * background context's markers). */
#include "harness.h"
#include "port.h"
#include "rt.h"
#include "rt_sim.h" /* allocates the run */

#define PAINT 0xA5C3E1F7u /* a word no real stack frame is likely to hold */
#define PAINT_MARGIN 256  /* bytes below the current stack pointer left unpainted */
#ifndef FOOT_TICKS
#define FOOT_TICKS 1000   /* ticks measured (or the whole scene if shorter) */
#endif

extern const rt_scene FOOT_SCENE;
extern uint32_t __stack_bottom[], __stack_top[];

static rt_sim sim;
#ifndef FOOT_BG
#define FOOT_BG 0 /* 1: the scene has a background set (the build asks modrt info) */
#endif
#if FOOT_BG
static rt_sim bg; /* the background context */
#endif

/* markers for the plugin: never inlined, so each is one address the image executes */
__attribute__((noinline)) void foot_tick_end(void) { __asm__ volatile("" ::: "memory"); }
__attribute__((noinline)) void foot_bg_begin(void) { __asm__ volatile("" ::: "memory"); }
__attribute__((noinline)) void foot_bg_end(void) { __asm__ volatile("" ::: "memory"); }

/* the background level's work: the released step, between its markers */
static void background(void *ctx)
{
    (void)ctx;
    if (!rt_bg_pending(&sim))
        return;
    foot_bg_begin();
    rt_background(&FOOT_SCENE, &sim);
    foot_bg_end();
}

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
    int own_level = 0;
#if FOOT_BG
    rt_bg_attach(sc, &sim, &bg);
    own_level = port_bg_start(background, 0) == 0;
#endif
    paint(); /* after init: the mark measures ticks and recording only */
    do {
        (void)port_cycles(); /* marker: the plugin counts instructions between calls */
        st = rt_tick(sc, &sim);
        rt_record(sc, &sim, 0);
        foot_tick_end();
        if (FOOT_BG && rt_bg_pending(&sim)) {
            if (own_level)
                port_bg_request(); /* PendSV runs it now, before the next tick */
            else
                background(0);
        }
    } while (st != RT_E_DONE && rt_ticks_done(&sim) < FOOT_TICKS);
    (void)port_cycles();
    th_put("scene ");
    th_put(sc->name);
    th_put(" ticks ");
    th_put_int((long long)rt_ticks_done(&sim));
    th_put(" hash ");
    th_put_hex64(rt_trace_hash(&sim));
    th_put(" stack ");
    th_put_int(high_water());
    th_put("\n");
    return rt_stats_of(&sim)->status == RT_OK ? 0 : 1;
}
