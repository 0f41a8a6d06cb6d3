/* rt_main.c - the real-time image of the cross tests: ticks the scene RT_SCENE (default
 * pi_loop) from the port's periodic timer (SysTick on Cortex-M, the CLINT timer on
 * RISC-V, clock_nanosleep on POSIX) at its base step, counts the ticks that finished
 * after their deadline, and prints the trace hash, which must equal the simulated-clock
 * run's: pacing changes when a tick runs, never what it computes. */
#include "harness.h"
#include "models.h"
#include "port.h"

#ifndef RT_SCENE
#define RT_SCENE mdl_scene_pi_loop
#endif
extern const rt_scene RT_SCENE;

static rt_sim sim;
static volatile uint32_t timer_ticks; /* counted by the timer callback */

static void on_timer(void) { timer_ticks++; }

int app_main(void)
{
    const rt_scene *sc = &RT_SCENE;
    uint32_t overruns = 0;
    if (rt_init(sc, &sim) != RT_OK)
        return 1;
    rt_record(sc, &sim, 0);
    uint32_t us = (uint32_t)(sc->dt * (real_t)1e6 + (real_t)0.5);
    if (port_timer_start(us, on_timer) != 0) {
        th_put("rt: the port cannot tick at this period\n");
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
    th_put("rt scene ");
    th_put(sc->name);
    th_put(" ticks ");
    th_put_int((long long)sim.state.tick);
    th_put(" timer ");
    th_put_int(timer_ticks);
    th_put(" overruns ");
    th_put_int(overruns);
    th_put(" hash ");
    th_put_hex64(sim.state.hash);
    th_put("\n");
    /* overruns are judged by the caller: zero is required only where the port's time is
       virtual and deterministic (bare metal under QEMU -icount), not on a shared host */
    return sim.stats.status == RT_OK ? 0 : 1;
}
