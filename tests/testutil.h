/* testutil.h - helpers shared by the tests: run a scene to a time, read a recorded
 * signal, and one static simulator (the runtime's storage is the caller's). */
#ifndef TU_TESTUTIL_H
#define TU_TESTUTIL_H

#include "harness.h"
#include "rt.h"

/* TU_FULL: 1 where the long tests run their full span, the host's own builds; 0 in the
   cross-test images (CROSS_TEST_DEFS defines TU_CROSS) and other bare-metal builds, which
   run under QEMU, where binary64 in software (m3, m4f, rv32) or user-mode emulation
   (aarch64) makes a second of host work minutes: those tests run a shorter span there
   that still shows what they check (each says how) */
#ifdef TU_CROSS
#define TU_FULL 0
#else
#define TU_FULL __STDC_HOSTED__
#endif

/* one simulator for all tests (large: it holds every static limit), and a second one a
   test may use for anything (a copy, a background context): the cross targets' RAM
   holds few. Declared without the layout: a test that reads rt_sim's parts includes
   rt_sim.h (or rti.h) itself, and so says it is a white-box test */
extern rt_sim tu_sim, tu_spare;

/* Initialises sc into tu_sim and checks it returned RT_OK. */
int tu_init(const rt_scene *sc);
/* Ticks until time t (rounded to ticks) or the end; returns the last status. */
rt_status tu_run_to(const rt_scene *sc, real_t t);
/* Value of output j of the named block at the current state. */
real_t tu_y(const rt_scene *sc, const char *block, uint16_t j);

#endif /* TU_TESTUTIL_H */
