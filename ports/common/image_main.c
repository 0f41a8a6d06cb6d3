/* image_main.c - the application of a per-scene image (`make image`, docs/porting.md)
 * and of the cross tests' real-time run: ticks the scene RT_SCENE (default pi_loop) from
 * the port's periodic timer (SysTick on Cortex-M, the CLINT timer on RISC-V,
 * clock_nanosleep on POSIX) at its base step, counts the ticks that finished after their
 * deadline, and prints one line with the trace hash, which must equal the simulated-clock
 * run's: pacing changes when a tick runs, never what it computes. Needs only rt.h and
 * port.h: the scene's generated C brings its models. */
#include "port.h"
#include "rt.h"

#ifndef RT_SCENE
#define RT_SCENE mdl_scene_pi_loop
#endif
extern const rt_scene RT_SCENE;

static rt_sim sim;

/* the timer callback's context: ticks it has counted */
typedef struct timer_count {
    volatile uint32_t ticks;
} timer_count;

static void on_timer(void *ctx) { ((timer_count *)ctx)->ticks++; }

static void put_u64(uint64_t v, unsigned base, int width)
{
    char buf[24];
    int n = 23;
    buf[n] = 0;
    do {
        buf[--n] = "0123456789abcdef"[v % base];
        v /= base;
    } while (v || 23 - n < width);
    port_write(buf + n);
}

int app_main(void)
{
    const rt_scene *sc = &RT_SCENE;
    uint32_t overruns = 0;
    static timer_count count; /* the timer interrupt keeps a pointer to it */
    if (rt_init(sc, &sim) != RT_OK)
        return 1;
    rt_record(sc, &sim, 0);
    uint32_t us = (uint32_t)(sc->dt * (real_t)1e6 + (real_t)0.5);
    if (port_timer_start(us, on_timer, &count) != 0) {
        port_write("rt: the port cannot tick at this period\n");
        return 1;
    }
    rt_status st;
    do {
        port_timer_wait(); /* the work runs in the main loop, not in the interrupt */
        st = rt_tick(sc, &sim);
        rt_record(sc, &sim, 0);
        overruns += (uint32_t)port_timer_late();
    } while (st != RT_E_DONE);
    port_timer_stop();
    port_write("rt scene ");
    port_write(sc->name);
    port_write(" ticks ");
    put_u64(sim.state.tick, 10, 1);
    port_write(" timer ");
    put_u64(count.ticks, 10, 1);
    port_write(" overruns ");
    put_u64(overruns, 10, 1);
    port_write(" hash ");
    put_u64(sim.state.hash, 16, 16);
    port_write(" status ");
    port_write(rt_status_name(sim.stats.status));
    port_write("\n");
    /* overruns are judged by the caller: zero is required only where the port's time is
       virtual and deterministic (bare metal under QEMU -icount), not on a shared host */
    return sim.stats.status == RT_OK ? 0 : 1;
}
