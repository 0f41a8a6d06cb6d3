/* test_layout.c - an rt_sim allocated by a file compiled with other limits than the
 * runtime: this file is, with twice the runtime's RT_MAX_X (the Makefile's flags for it
 * alone), as an application's main compiled without the image's `scenec --sizes` flags
 * would be. rt_init refuses such an rt_sim with RT_E_SCENE and its text, writing nothing
 * into it but that text (table-driven or with the scene's written-out code, whose own
 * layout is the runtime's); rt_bg_attach refuses such a context untouched, and
 * rt_snapshot and rt_restore such a snapshot. White-box: allocates rt_sim and rt_state
 * (rt_sim.h, under this file's limits); the runtime's own rt_sim is testutil.c's, which
 * this file only passes by address. */
#ifndef RT_MAX_X
#error "compile with another RT_MAX_X than the runtime's (the Makefile's flags for this file)"
#endif
#include <string.h>

#include "harness.h"
#include "rt_sim.h"
#include "scenes/scenes.h"
#include "testutil.h"

#define FILL 0xa5 /* every byte of the caller's rt_sim before the call */

static rt_sim other, other_ctx; /* laid out under this file's limits */
static rt_state other_snap;

static const char *const TEXT = "rt_sim compiled with other limits than the runtime";

/* 1 when the n bytes at p all still hold FILL */
static int untouched(const void *p, size_t n)
{
    const unsigned char *b = p;
    for (size_t i = 0; i < n; i++)
        if (b[i] != FILL)
            return 0;
    return 1;
}

/* the scene with and without its written-out code: refused before anything is laid out,
   and only the text written (err, at offset 0 under every limit); the runtime's own
   rt_sim takes both, through the macro (testutil.c includes rt_sim.h) and through the
   plain function a file without rt_sim.h calls */
static void test_layout_init(void)
{
    rt_scene sc = mdl_scene_pi_loop;
    TH_CHECK(sc.code != 0); /* the second pass below is table-driven for a reason */
    for (int pass = 0; pass < 2; pass++) {
        if (pass == 1)
            sc.code = 0;
        memset(&other, FILL, sizeof other);
        TH_CHECK(rt_init(&sc, &other) == RT_E_SCENE);
        /* the text where this file's layout has it too */
        TH_CHECK(memchr(other.err, 0, sizeof other.err) && th_has(other.err, TEXT));
        TH_CHECK(rt_error_text(&other) == other.err);
        TH_CHECK(untouched((const unsigned char *)&other + sizeof other.err,
                           sizeof other - sizeof other.err));
        TH_CHECK(tu_init(&sc));
        TH_CHECK((rt_init)(&sc, &tu_sim) == RT_OK && rt_error_text(&tu_sim)[0] == 0);
    }
}

/* a background context of this file's layout: refused, nothing copied into it, nothing
   attached (the step runs inline: none waits for a context); the runtime's own attaches,
   and then its step waits for the context within the set's step of 4 ticks */
static void test_layout_bg(void)
{
    const rt_scene *sc = &mdl_scene_pendulum10_actuated;
    if (!tu_init(sc))
        return;
    memset(&other_ctx, FILL, sizeof other_ctx);
    TH_CHECK(rt_bg_attach(sc, &tu_sim, &other_ctx) == RT_E_SCENE);
    TH_CHECK(th_has(rt_error_text(&tu_sim), TEXT));
    TH_CHECK(untouched(&other_ctx, sizeof other_ctx));
    int pending = 0;
    for (int k = 0; k < 8; k++)
        pending |= rt_tick(sc, &tu_sim) != RT_OK || rt_bg_pending(&tu_sim);
    TH_CHECK(!pending);
    if (!tu_init(sc))
        return;
    TH_CHECK((rt_bg_attach)(sc, &tu_sim, &tu_spare) == RT_OK);
    for (int k = 0; k < 4 && !pending; k++)
        pending = rt_tick(sc, &tu_sim) == RT_OK && rt_bg_pending(&tu_sim);
    TH_CHECK(pending);
}

/* a snapshot of this file's layout: rt_snapshot writes nothing into it, rt_restore takes
   nothing from it, and the run goes on unchanged */
static void test_layout_snapshot(void)
{
    const rt_scene *sc = &mdl_scene_pi_loop;
    if (!tu_init(sc))
        return;
    for (int k = 0; k < 10; k++)
        rt_tick(sc, &tu_sim);
    uint64_t hash = rt_trace_hash(&tu_sim);
    memset(&other_snap, FILL, sizeof other_snap);
    TH_CHECK(rt_snapshot(&tu_sim, &other_snap) == RT_E_ARG);
    TH_CHECK(untouched(&other_snap, sizeof other_snap));
    TH_CHECK(rt_restore(&tu_sim, &other_snap) == RT_E_ARG);
    TH_CHECK(rt_ticks_done(&tu_sim) == 10 && rt_trace_hash(&tu_sim) == hash);
}

const th_test th_layout_tests[] = {
    {"layout_init", test_layout_init},
    {"layout_bg", test_layout_bg},
    {"layout_snapshot", test_layout_snapshot},
    {0, 0},
};
