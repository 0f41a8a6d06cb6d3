/* snap_image.c - tests/fmi/snap.c inside a per-scene image (tests/image.sh: `make image`
 * with IMAGE_MAIN naming this file): the scene RT_SCENE run straight to tick SNAP_N2; run
 * again from rt_init to SNAP_N1, snapshotted (rt_snapshot, an FMU block's state with it),
 * run on to SNAP_N2 across the FMU's events, restored (rt_restore) and run to SNAP_N2
 * again. One line: the statuses and the three trace hashes, which must all be the host's
 * straight run's (snap.c on the same scene): a restore that lost the FMU's own memory (the
 * stair's counter) gives another hash. Simulated time: no timer, the ticks back to back. */
#include "port.h"
#include "rt.h"
#include "rt_sim.h" /* allocates the run and its snapshot */

#ifndef SNAP_N1
#define SNAP_N1 10 /* the tick of the snapshot */
#endif
#ifndef SNAP_N2
#define SNAP_N2 24 /* the tick each run ends at */
#endif

extern const rt_scene RT_SCENE;

static rt_sim sim;
static rt_state snap;

static void put_hex(uint64_t v)
{
    char buf[17];
    for (int i = 15; i >= 0; i--, v >>= 4)
        buf[i] = "0123456789abcdef"[v & 15];
    buf[16] = 0;
    port_write(buf);
}

static void say(const char *key, const char *value)
{
    port_write(key);
    port_write(value);
}

static void run_to(uint64_t n)
{
    while (rt_ticks_done(&sim) < n && rt_tick(&RT_SCENE, &sim) != RT_E_ARG)
        rt_record(&RT_SCENE, &sim, 0);
}

/* rt_init (the second one resets the FMU instances) and the row at t = 0 */
static int start(void)
{
    rt_status st = rt_init(&RT_SCENE, &sim);
    if (st == RT_OK) {
        rt_record(&RT_SCENE, &sim, 0);
        return 0;
    }
    say("snap rt_init ", rt_status_name(st));
    say(": ", rt_error_text(&sim));
    port_write("\n");
    return 1;
}

int app_main(void)
{
    if (start())
        return 1;
    run_to(SNAP_N2);
    uint64_t straight = rt_trace_hash(&sim);
    if (start())
        return 1;
    run_to(SNAP_N1);
    rt_status s1 = rt_snapshot(&sim, &snap);
    run_to(SNAP_N2);
    uint64_t on = rt_trace_hash(&sim);
    rt_status s2 = rt_restore(&sim, &snap);
    run_to(SNAP_N2);
    say("snap scene ", RT_SCENE.name);
    say(" snapshot ", rt_status_name(s1));
    say(" restore ", rt_status_name(s2));
    port_write(" straight ");
    put_hex(straight);
    port_write(" on ");
    put_hex(on);
    port_write(" restored ");
    put_hex(rt_trace_hash(&sim));
    say(" status ", rt_status_name(rt_stats_of(&sim)->status));
    port_write("\n");
    return s1 == RT_OK && s2 == RT_OK && rt_stats_of(&sim)->status == RT_OK ? 0 : 1;
}
