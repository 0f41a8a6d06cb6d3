/* scale_bench.c - how modrt's cost grows with the model (docs/overhead.md, "Scaling"): a
 * chain of SCALE_N mass points hanging from the origin (pendulum10's chain made longer),
 * or a tree, a spine of SCALE_N / 2 points with one point hanging from each; distance
 * joints of 1 m, dopri5 at 5 ms, the projection of eq. 10. The scene is built here, not by
 * scenec (whose statement limits hold hand-written scenes); tools/dev/bench/scale.sh first
 * builds this file with generous limits to print the scene's exact sizes, then with them.
 *
 * Usage: scale_bench sizes            the scene's -DRT_MAX_... flags (as scenec --sizes)
 *        scale_bench modrt STEPS [METHOD H]
 *                                     STEPS ticks of modrt (modrt_ticks is counted), by
 *                                     dopri5 at 5 ms or METHOD (euler | heun | bs3 | rk4 |
 *                                     dopri5) at step H
 *        scale_bench tight STEPS      the chain's tight program (tight_steps), same start
 *        scale_bench run METHOD H T   modrt by METHOD at step H up to T seconds: prints
 *                                     every body's position "x y z", one line each
 *        scale_bench ref H T          the same from the chain's tight program, dopri5 at
 *                                     step H (the reference of mujoco_scale.py) */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <valgrind/callgrind.h>

#include "pendulum_tight.h"
#include "rt.h"
#include "rt_mbs.h"
#include "rt_sim.h" /* allocates the run */

#ifndef SCALE_N
#define SCALE_N 10
#endif
#ifndef SCALE_TREE
#define SCALE_TREE 0 /* 1: a spine of N / 2 points, each with a point hanging from it */
#endif

extern const rt_kind mdl_mbs_point_kind;

static char names[2 * SCALE_N][12];
static real_t x0[SCALE_N][6];
static rt_block blocks[SCALE_N];
static rt_joint joints[SCALE_N];
static const real_t one[] = {1};
static rt_set sets[] = {{.name = "mbs", .method = &rt_dopri5, .ratio = 1}};
static rt_scene scene = {.name = "scale", .doc = "a chain or tree of mass points",
                         .dt = (real_t)0.005, .t_end = 1e6, .sets = sets, .nsets = 1,
                         .mbs = &rt_mbs, .stab = RT_STAB_PROJECT};
static rt_sim sim;

/* body k at (x, 0, z) linked to body `to` (-1: the anchor at the origin) */
static void body(int k, double x, double z, int to)
{
    snprintf(names[k], sizeof names[k], "B%d", k + 1);
    snprintf(names[SCALE_N + k], sizeof names[k], "J%d", k + 1);
    x0[k][0] = (real_t)x, x0[k][2] = (real_t)z;
    blocks[k] = (rt_block){.name = names[k], .kind = &mdl_mbs_point_kind, .x0 = x0[k]};
    joints[k] = (rt_joint){.name = names[SCALE_N + k], .kind = &rt_joint_sphdiff,
                           .b1 = (int16_t)k, .b2 = (int16_t)to, .p = one};
}

static void build(void)
{
    if (SCALE_TREE) /* spine point s at (s + 1, 0, 0), its branch point below it */
        for (int s = 0; s < SCALE_N / 2; s++) {
            body(2 * s, s + 1, 0, s ? 2 * (s - 1) : -1);
            body(2 * s + 1, s + 1, -1, 2 * s);
        }
    else
        for (int k = 0; k < SCALE_N; k++)
            body(k, k + 1, 0, k - 1);
    scene.blocks = blocks, scene.nblocks = SCALE_N;
    scene.joints = joints, scene.njoints = SCALE_N;
    if (rt_init(&scene, &sim) != RT_OK) {
        fprintf(stderr, "scale_bench: init: %s\n", rt_error_text(&sim));
        exit(1);
    }
}

static const struct {
    const char *name;
    const rt_integrator *method;
} methods[] = {{"euler", &rt_euler}, {"heun", &rt_heun}, {"bs3", &rt_bs3}, {"rk4", &rt_rk4},
               {"dopri5", &rt_dopri5}};

/* the scene's method and step from the command line, before build() */
static void set_method(const char *name, const char *h)
{
    sets[0].method = NULL;
    for (size_t i = 0; i < sizeof methods / sizeof methods[0]; i++)
        if (strcmp(name, methods[i].name) == 0)
            sets[0].method = methods[i].method;
    scene.dt = (real_t)atof(h);
    scene.t_end = scene.dt * (real_t)(1 << 20); /* a whole number of ticks, past any run */
    /* the error estimate's check off in effect (accuracy 1: a user after 1e-3 m asks no
       more): the sweep of mujoco_scale.py measures the error against its reference; every
       other fault (the projection's residual, non-finite states) still stops a run */
    sets[0].cfg.accuracy = 1;
    if (!sets[0].method || !(scene.dt > 0)) {
        fprintf(stderr, "scale_bench: bad method %s or step %s\n", name, h);
        exit(2);
    }
}

static void print_positions(const double *q, int stride)
{
    for (int k = 0; k < SCALE_N; k++)
        printf("%.17g %.17g %.17g\n", q[stride * k], q[stride * k + 1], q[stride * k + 2]);
}

static unsigned one_at_least(unsigned v)
{
    return v ? v : 1;
}

static void sizes(void)
{
    rt_sizes z;
    rt_sizes_of(&scene, &sim, &z);
#define F(name, v) printf(" -D" name "=%u", one_at_least(v))
    F("RT_MAX_BLOCKS", z.blocks), F("RT_MAX_X", z.x), F("RT_MAX_D", z.d), F("RT_MAX_U", z.u);
    F("RT_MAX_Y", z.y), F("RT_MAX_P", z.p), F("RT_MAX_ROOTS", z.roots);
    F("RT_MAX_SETS", z.sets), F("RT_MAX_REC", z.recs), F("RT_MAX_LOOPS", z.loops);
    F("RT_MAX_TORN", z.torn), F("RT_MAX_IMPLICIT_N", z.implicit_n);
    F("RT_MAX_HIST_Y", z.hist_y), F("RT_MAX_EVENT_X", z.event_x), F("RT_MAX_SEQ", z.seq);
    F("RT_MAX_LOOP_HIST", z.loop_hist), F("RT_MAX_BG", z.bg);
    F("RT_MAX_JOINTS", scene.njoints), F("RT_MAX_MBS_Z", z.mbs_z), F("RT_MAX_MBS_Q", z.mbs_q);
    F("RT_MAX_MBS_C", z.mbs_c), F("RT_MAX_MBS_BZ", z.mbs_bz), F("RT_MAX_MBS_ROWS", z.mbs_rows);
    F("RT_MAX_MBS_TOUCH", z.mbs_touch), F("RT_MAX_MBS_TW", z.mbs_tw);
    F("RT_MAX_MBS_QT", z.mbs_qt), F("RT_MAX_MBS_TY", z.mbs_ty);
    F("RT_MAX_MBS_PAIRS", z.mbs_pairs), F("RT_MAX_MBS_LNZ", z.mbs_lnz);
    F("RT_MAX_MBS_M", z.mbs_m), F("RT_MAX_MBS_JROWS", z.mbs_jrows), F("RT_MAX_MBS_JZ", z.mbs_jz);
#undef F
    printf(" -DRT_MAX_TRANSITION_N=%u -DRT_MAX_HELD_Y=%u -DRT_MAX_HELD_SIG=%u -DRT_MAX_XPRED=%u"
           " -DRT_MAX_TEV=%u\n", z.transition_n, z.held_y, z.held_sig, z.xpred, z.tev);
}

__attribute__((noinline)) void modrt_ticks(rt_sim *s, long n)
{
    for (long i = 0; i < n; i++)
        rt_tick(&scene, s);
}

int main(int argc, char **argv)
{
    int run = argc == 5 && strcmp(argv[1], "run") == 0;
    int ref = argc == 4 && strcmp(argv[1], "ref") == 0;
    if (run || (argc == 5 && strcmp(argv[1], "modrt") == 0))
        set_method(argv[2 + !run], argv[3 + !run]);
    if (ref)
        set_method("dopri5", argv[2]);
    build();
    if (argc == 2 && strcmp(argv[1], "sizes") == 0) {
        sizes();
        return 0;
    }
    static double xs[6 * SCALE_N];
    for (uint16_t b = 0; b < SCALE_N; b++)
        for (uint16_t j = 0; j < 6; j++)
            xs[6 * b + j] = (double)rt_output(&sim, b, j);
    if (run) {
        modrt_ticks(&sim, lround(atof(argv[4]) / (double)scene.dt));
        for (uint16_t b = 0; b < SCALE_N; b++)
            for (uint16_t j = 0; j < 3; j++)
                xs[3 * b + j] = (double)rt_output(&sim, b, j);
        print_positions(xs, 3);
        if (rt_stats_of(&sim)->status == RT_OK)
            return 0;
        fprintf(stderr, "scale_bench: %s at %g s: %s\n",
                rt_status_name(rt_stats_of(&sim)->status), (double)rt_time(&scene, &sim),
                rt_error_text(&sim));
        return 1;
    }
    if ((argc != 3 && argc != 5 && !ref) ||
        (strcmp(argv[1], "modrt") != 0 && strcmp(argv[1], "tight") != 0 && !ref)) {
        fprintf(stderr, "usage: scale_bench sizes | modrt STEPS [METHOD H] | tight STEPS | "
                        "run METHOD H T | ref H T\n");
        return 2;
    }
    if (strcmp(argv[1], "modrt") == 0) {
        CALLGRIND_START_INSTRUMENTATION; /* callgrind --instr-atstart=no: rt_init uncounted */
        modrt_ticks(&sim, atol(argv[2]));
        return rt_stats_of(&sim)->status == RT_OK ? 0 : 1;
    }
    if (SCALE_TREE || TIGHT_NB != SCALE_N) {
        fprintf(stderr, "scale_bench: the tight program is the chain's of TIGHT_NB points\n");
        return 2;
    }
    static tight m;
    m.method = TIGHT_DOPRI5, m.estimate = !ref, m.h = (double)scene.dt;
    tight_init(&m, xs);
    if (ref) {
        tight_steps(&m, lround(atof(argv[3]) / m.h));
        print_positions(m.q, 3);
        return 0;
    }
    tight_steps(&m, atol(argv[2]));
    return 0;
}
