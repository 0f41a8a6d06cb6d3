/* image_main.c - the application of a per-scene image (`make image`, docs/porting.md)
 * and of the cross tests' real-time run: ticks the scene RT_SCENE (default pi_loop) from
 * the port's periodic timer (SysTick on Cortex-M, the CLINT timer on RISC-V,
 * clock_nanosleep on POSIX) at its base step, counts the ticks that finished after their
 * deadline, and prints one line with the trace hash, which must equal the simulated-clock
 * run's: pacing changes when a tick runs, never what it computes. Needs only rt.h and
 * port.h: the scene's generated C brings its models.
 *
 * A scene with a background set (docs/multirate.md, "Background sets") on a port with a
 * level below the timer (PendSV on Cortex-M): the ticks run in the timer interrupt and
 * the set's steps at that lower level, in a second rt_sim, preempted by every tick that
 * falls while they run (the line reports how many did). Elsewhere the ticks run in the
 * main loop and the steps inline. RT_IMAGE_TICKS ends the run early, RT_IMAGE_PERIOD_US
 * ticks faster than the scene's base tick (the cross test: more preemptions).
 *
 * A scene with a controller link (RT_IMAGE_LINK, docs/link.md "The plant on a board")
 * exchanges its exports and imports over the port's link UART after each tick
 * (image_link.c), as `modrt run --link` does: in lock-step the controller paces the run
 * (the ticks run back to back; the timer only wakes the wait for an answer), in real time
 * the timer does. */
#include "port.h"
#include "rt.h"
#include "rt_sim.h" /* allocates the run and its background context */

#ifndef RT_SCENE
#define RT_SCENE mdl_scene_pi_loop
#endif
extern const rt_scene RT_SCENE;

#ifndef RT_IMAGE_TICKS
#define RT_IMAGE_TICKS 0 /* ticks to run (0: to the scene's end) */
#endif
#ifndef RT_IMAGE_PERIOD_US
#define RT_IMAGE_PERIOD_US 0 /* timer period [us] (0: the scene's base tick) */
#endif

#ifndef RT_IMAGE_BG
#define RT_IMAGE_BG 0 /* 1: the scene has a background set (tools/image.sh finds out) */
#endif

#ifndef RT_IMAGE_LINK
#define RT_IMAGE_LINK 0 /* 1: the scene has a controller link (tools/image.sh finds out) */
#endif
#if RT_IMAGE_LINK
#include "image_link.h"
#if RT_IMAGE_BG
#error "A scene with a controller link and a background set: the image runs one or the other."
#endif
#define RT_IMAGE_PACED RT_IMAGE_LINK_REALTIME /* lock-step: the controller paces the run */
#else
#define RT_IMAGE_PACED 1
#endif

static rt_sim sim;
#if RT_IMAGE_BG
static rt_sim bg; /* the background context */
#endif

/* the timer callback's context: ticks it has counted, and with a background set the
   ticking itself (the run's state, its end, the ticks that preempted a step) */
typedef struct timer_count {
    volatile uint32_t ticks;
    int in_irq;                 /* the scene ticks here, not in the main loop */
    volatile int done;
    volatile rt_status st;
    volatile uint32_t overruns, preempted;
    volatile int bg_running;    /* the background level is inside a step */
} timer_count;

/* the scene's end, or RT_IMAGE_TICKS */
static int finished(rt_status st)
{
#if RT_IMAGE_TICKS > 0
    if (rt_ticks_done(&sim) >= RT_IMAGE_TICKS)
        return 1;
#endif
    return st == RT_E_DONE || st == RT_E_LINK;
}

/* the exchange with the controller after a tick (and at tick 0); an import with policy
   stop that went missing ends the run with status RT_E_LINK */
static rt_status exchange(const rt_scene *sc, rt_status st)
{
#if RT_IMAGE_LINK
    if (image_link_exchange(sc, &sim)) {
        rt_note_status(&sim, RT_E_LINK);
        return RT_E_LINK;
    }
#else
    (void)sc;
#endif
    return st;
}

static void on_timer(void *ctx)
{
    timer_count *c = ctx;
    c->ticks++;
    if (!c->in_irq || c->done)
        return;
    c->preempted += (uint32_t)c->bg_running;
    c->st = rt_tick(&RT_SCENE, &sim);
    rt_record(&RT_SCENE, &sim, 0);
    c->overruns += (uint32_t)port_timer_late();
    if (rt_bg_pending(&sim))
        port_bg_request();
    c->done = finished(c->st);
}

/* the background level: the released step of the background set */
#if RT_IMAGE_BG
static void on_background(void *ctx)
{
    timer_count *c = ctx;
    if (!rt_bg_pending(&sim)) /* pended again by a tick while it ran: done already */
        return;
    c->bg_running = 1;
    rt_background(&RT_SCENE, &sim);
    c->bg_running = 0;
}
#endif

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

#if RT_IMAGE_LINK
/* one count of the link on the image's line: " link_KEY N" */
static void put_count(const char *key, uint64_t v)
{
    port_write(" link_");
    port_write(key);
    port_write(" ");
    put_u64(v, 10, 1);
}
#endif

int app_main(void)
{
    const rt_scene *sc = &RT_SCENE;
    uint32_t overruns = 0;
    static timer_count count; /* the timer interrupt keeps a pointer to it */
    rt_status init = rt_init(sc, &sim);
    if (init != RT_OK) { /* one line saying why: the run never starts */
        port_write("rt scene ");
        port_write(sc->name);
        port_write(" init ");
        port_write(rt_status_name(init));
        port_write(": ");
        port_write(rt_error_text(&sim));
        port_write("\n");
        return 1;
    }
    uint32_t us = RT_IMAGE_PERIOD_US ? RT_IMAGE_PERIOD_US
                                     : (uint32_t)(sc->dt * (real_t)1e6 + (real_t)0.5);
    rt_status st = RT_OK;
#if RT_IMAGE_LINK
    /* the timer runs before the first exchange: in lock-step its tick is what ends the
       wait for an answer that does not come (port_link_wait) */
    if (image_link_start(sc, &sim) != 0) {
        port_write("rt: the port has no link UART at this rate\n");
        return 1;
    }
    if (port_timer_start(us, on_timer, &count) != 0) {
        port_write("rt: the port cannot tick at this period\n");
        return 1;
    }
    st = exchange(sc, st);
#endif
    rt_record(sc, &sim, 0);
#if RT_IMAGE_BG
    if (sc->bg && port_bg_start(on_background, &count) == 0)
        count.in_irq = rt_bg_attach(sc, &sim, &bg) == RT_OK;
#endif
    if (!RT_IMAGE_LINK && port_timer_start(us, on_timer, &count) != 0) {
        port_write("rt: the port cannot tick at this period\n");
        return 1;
    }
    if (count.in_irq) {
        while (!count.done)
            port_timer_wait(); /* the ticks run in the interrupt, the steps below it */
        overruns = count.overruns;
    } else {
        while (!finished(st)) {
            if (RT_IMAGE_PACED)
                port_timer_wait(); /* the work runs in the main loop, not in the interrupt */
            st = exchange(sc, rt_tick(sc, &sim));
            rt_record(sc, &sim, 0);
            overruns += RT_IMAGE_PACED ? (uint32_t)port_timer_late() : 0;
        }
    }
    port_timer_stop();
    port_write("rt scene ");
    port_write(sc->name);
    port_write(" ticks ");
    put_u64(rt_ticks_done(&sim), 10, 1);
    port_write(" timer ");
    put_u64(count.ticks, 10, 1);
    port_write(" overruns ");
    put_u64(overruns, 10, 1);
    if (count.in_irq) {
        port_write(" preempted ");
        put_u64(count.preempted, 10, 1);
        port_write(" late ");
        put_u64(rt_stats_of(&sim)->bg_late, 10, 1);
    }
#if RT_IMAGE_LINK
    int link_bad = image_link_report(put_count);
#else
    int link_bad = 0;
#endif
    port_write(" hash ");
    put_u64(rt_trace_hash(&sim), 16, 16);
    port_write(" status ");
    port_write(rt_status_name(rt_stats_of(&sim)->status));
    port_write("\n");
    /* overruns are judged by the caller: zero is required only where the port's time is
       virtual and deterministic (bare metal under QEMU -icount), not on a shared host */
    return rt_stats_of(&sim)->status == RT_OK && !link_bad ? 0 : 1;
}
