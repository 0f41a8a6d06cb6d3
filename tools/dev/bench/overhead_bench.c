/* overhead_bench.c - modrt against the hand-written monolith of the same formulation
 * (pendulum_mono.c, actuated_mono.c, actuated_mr_mono.c): the trajectory checks, and the
 * runs that tools/dev/bench/overhead.sh counts with callgrind to print the modular overhead
 * (docs/overhead.md).
 *
 * The modrt side is the library as an application runs it: rt_init, then rt_tick per
 * base tick (scene pendulum10 with its method replaced; with METHOD ros2 scene
 * pendulum10_actuated_single as it is, with METHOD bs3+ros2 the multirate scene
 * pendulum10_actuated as it is, its background set stepped inline). The counted
 * functions are modrt_ticks and mono_steps, amono_steps or amr_steps; start-up (init, the
 * first projection) is outside them.
 *
 * Usage: overhead_bench check            both sides, every method, 2 s (pendulum10), and
 *                                        pendulum10_actuated_single and
 *                                        pendulum10_actuated over their 10 s: the
 *                                        largest position difference must be below
 *                                        CHECK_TOL, ACT_TOL (exit 1 otherwise)
 *        overhead_bench count SIDE METHOD SECONDS
 *                                        SIDE modrt | mono | mono-noest | thomas;
 *                                        METHOD bs3 | rk4 | dopri5 (pendulum10), ros2
 *                                        (pendulum10_actuated_single; mono-noest is mono
 *                                        there: neither side evaluates f(t + h, x0) for
 *                                        the f_t term of the autonomous model) or
 *                                        bs3+ros2 (pendulum10_actuated; mono-noest: without
 *                                        bs3's error estimate and the history monitors) */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "actuated_mono.h"
#include "actuated_mr_mono.h"
#include "pendulum_mono.h"
#include "scenes/scenes.h"
#include "rt_sim.h" /* allocates the run */

#define CHECK_T 2.0     /* simulated time of the trajectory check [s] */
#define CHECK_TOL 1e-11 /* largest position difference accepted [m]: rounding grows in the
                           chaotic chain, a formulation error gives 1e-3 or more */
#define ACT_T 10.0      /* pendulum10_actuated(_single): the whole scene [s] */
#define ACT_TOL 1e-9    /* and its bound [m] */
#define TIGHT_TOL 1e-12 /* the multirate scene's tight program (MONO_TIGHT) [m] */

static rt_sim sim;

static const struct {
    const char *name;
    const rt_integrator *rt;
    int mono;
} methods[] = {
    {"bs3", &rt_bs3, MONO_BS3},
    {"rk4", &rt_rk4, MONO_RK4},
    {"dopri5", &rt_dopri5, MONO_DOPRI5},
};
#define NMETHODS (int)(sizeof methods / sizeof methods[0])

static int method_index(const char *name)
{
    for (int i = 0; i < NMETHODS; i++)
        if (strcmp(name, methods[i].name) == 0)
            return i;
    fprintf(stderr, "overhead_bench: unknown method %s\n", name);
    exit(2);
}

/* pendulum10 with method i over t_end seconds (the scene's own step) */
static void modrt_init(rt_scene *sc, rt_set *set, int i, double t_end)
{
    *sc = mdl_scene_pendulum10;
    *set = sc->sets[0];
    set->method = methods[i].rt;
    sc->sets = set;
    sc->t_end = (real_t)t_end;
    if (rt_init(sc, &sim) != RT_OK) {
        fprintf(stderr, "overhead_bench: init: %s\n", rt_error_text(&sim));
        exit(1);
    }
}

__attribute__((noinline)) void modrt_ticks(const rt_scene *sc, rt_sim *s, long n)
{
    for (long i = 0; i < n; i++)
        rt_tick(sc, s);
}

/* the monolith started from modrt's initial state (outputs x, y, z, vx, vy, vz) */
static void mono_start(mono *m, int i, int solver, int estimate, const rt_scene *sc)
{
    double x0[6 * MONO_NB];
    for (uint16_t b = 0; b < MONO_NB; b++)
        for (uint16_t j = 0; j < 6; j++)
            x0[6 * b + j] = (double)rt_output(&sim, b, j);
    m->method = methods[i].mono, m->solver = solver, m->estimate = estimate;
    m->h = (double)sc->dt;
    mono_init(m, x0);
}

/* ------------------------------------------------------------ pendulum10_actuated_single */

static void act_init(rt_scene *sc, const rt_scene *scene, double t_end)
{
    *sc = *scene;
    sc->t_end = (real_t)t_end;
    /* no recorded signals: the monoliths record nothing, and the multirate scene's
       background step computes its recorded residual (held until its publication) */
    sc->nrecs = 0;
    if (rt_init(sc, &sim) != RT_OK) {
        fprintf(stderr, "overhead_bench: init: %s\n", rt_error_text(&sim));
        exit(1);
    }
}

/* the servo's two states in modrt now */
static void servo_states(const rt_scene *sc, double *s)
{
    int sv = rt_block_index(sc, "Servo");
    for (int j = 0; j < 2; j++)
        s[j] = (double)rt_block_x(&sim, (uint16_t)sv, (uint16_t)j);
}

/* the largest position difference of the chain between modrt's outputs and the
   monolith's states x (per body x, y, z, vx, vy, vz) */
static double chain_diff(const double *x)
{
    double worst = 0;
    for (uint16_t b = 0; b < MONO_NB; b++)
        for (uint16_t j = 0; j < 3; j++) {
            double d = fabs((double)rt_output(&sim, b, j) - x[6 * b + j]);
            worst = d > worst || d != d ? d : worst;
        }
    return worst;
}

/* the monolith from modrt's initial state: the chain's outputs, the servo's states */
static void act_start(amono *m, int solver, const rt_scene *sc)
{
    double x0[AMONO_NX];
    for (uint16_t b = 0; b < MONO_NB; b++)
        for (uint16_t j = 0; j < 6; j++)
            x0[6 * b + j] = (double)rt_output(&sim, b, j);
    servo_states(sc, x0 + 6 * MONO_NB);
    m->solver = solver;
    m->h = (double)sc->dt;
    amono_init(m, x0);
}

/* largest position difference of the chain; the servo's torque difference in *dy */
static double act_diff(const amono *m, const rt_scene *sc, double *dy)
{
    double s[2];
    servo_states(sc, s);
    *dy = fabs(s[0] - m->x[6 * MONO_NB]);
    return chain_diff(m->x);
}

/* both sides over the whole scene; positions compared at 1, 2, 5 and 10 s */
static int act_check(void)
{
    static const double at[] = {1, 2, 5, ACT_T};
    int bad = 0;
    for (int v = 0; v < 2; v++) { /* dense and Thomas */
        int solver = v == 1 ? MONO_THOMAS : MONO_DENSE;
        const char *name = v == 0 ? "dense" : "thomas";
        rt_scene sc;
        static amono m;
        act_init(&sc, &mdl_scene_pendulum10_actuated_single, ACT_T);
        act_start(&m, solver, &sc);
        long done = 0;
        double worst = 0;
        for (int i = 0; i < (int)(sizeof at / sizeof at[0]); i++) {
            long n = lround(at[i] / (double)sc.dt) - done;
            modrt_ticks(&sc, &sim, n);
            amono_steps(&m, n);
            done += n;
            double dy, d = act_diff(&m, &sc, &dy);
            worst = d > worst || d != d ? d : worst;
            printf("trajectory pendulum10_actuated_single ros2 %s at %g s: largest position "
                   "difference %.2e m, servo torque %.2e N m\n",
                   name, at[i], d, dy);
        }
        int ok = worst <= ACT_TOL && m.over == 0 && rt_stats_of(&sim)->status == RT_OK;
        bad += !ok;
        printf("trajectory pendulum10_actuated_single ros2 %s: largest %.2e m (tolerance "
               "%.0e), %ld Jacobians, largest estimate %.3g, %ld steps above the accuracy "
               "%s\n", name, worst, ACT_TOL,
               m.jac_evals, m.err_max, m.over, ok ? "ok" : "FAILED");
    }
    return bad;
}

/* ------------------------------------------------------------ pendulum10_actuated */

/* the multirate monolith from modrt's state after init: the chain's states (projected at
   init), the servo's states */
static void mr_start(amr *m, int solver, int estimate, const rt_scene *sc)
{
    double x0[6 * MONO_NB], s0[2];
    for (uint16_t b = 0; b < MONO_NB; b++)
        for (uint16_t j = 0; j < 6; j++)
            x0[6 * b + j] = (double)rt_block_x(&sim, b, j);
    servo_states(sc, s0);
    m->solver = solver, m->estimate = estimate;
    m->dt = (double)sc->dt;
    amr_init(m, x0, s0);
}

/* largest position difference of the chain (modrt's published state against the
   monolith's, both at the chain's communication point now); servo torque and the
   controller's command in dy, dc */
static double mr_diff(const amr *m, const rt_scene *sc, double *dy, double *dc)
{
    double s[2];
    servo_states(sc, s);
    *dy = fabs(s[0] - m->s[0]);
    *dc = fabs((double)rt_block_d(&sim, (uint16_t)rt_block_index(sc, "Ctrl"), 0) - m->c);
    return chain_diff(m->x);
}

/* both sides over the whole scene; positions compared at 1, 2, 5 and 10 s (multiples of
   the chain's ratio: its state is at the tick there on both sides) */
static int mr_check(void)
{
    static const double at[] = {1, 2, 5, ACT_T};
    int bad = 0;
    for (int v = 0; v < 5; v++) {
        int solver = v == 1 ? MONO_THOMAS : v >= 3 ? MONO_TIGHT : MONO_DENSE, est = v != 2 && v != 4;
        const char *name = (const char *[]){"dense", "thomas", "dense-noest", "tight",
                                            "tight-noest"}[v];
        rt_scene sc;
        static amr m;
        act_init(&sc, &mdl_scene_pendulum10_actuated, ACT_T);
        mr_start(&m, solver, est, &sc);
        long done = 0;
        double worst = 0;
        for (int i = 0; i < (int)(sizeof at / sizeof at[0]); i++) {
            long n = lround(at[i] / (double)sc.dt) - done;
            modrt_ticks(&sc, &sim, n);
            amr_steps(&m, n);
            done += n;
            double dy, dc, d = mr_diff(&m, &sc, &dy, &dc);
            worst = d > worst || d != d ? d : worst;
            printf("trajectory pendulum10_actuated bs3+ros2 %s at %g s: largest position "
                   "difference %.2e m, servo torque %.2e N m, command %.2e N m\n",
                   name, at[i], d, dy, dc);
        }
        int sv = rt_block_index(&sc, "Servo"), ch = sc.blocks[0].set;
        uint8_t ss = sc.blocks[sv].set;
        long jac = (long)rt_stats_of(&sim)->istats[ss].jac_evals;
        double tol = solver == MONO_TIGHT ? TIGHT_TOL : ACT_TOL;
        int ok = worst <= tol && m.over == 0 && rt_stats_of(&sim)->status == RT_OK &&
                 m.jac_evals == jac;
        bad += !ok;
        printf("trajectory pendulum10_actuated bs3+ros2 %s: largest %.2e m (tolerance %.0e), "
               "Jacobians %ld (modrt %ld), largest estimate servo %.6g (modrt %.6g), %ld "
               "steps above the accuracy %s\n", name, worst, tol, m.jac_evals, jac,
               m.err_servo, (double)rt_stats_of(&sim)->istats[ss].err_max, m.over, ok ? "ok" : "FAILED");
        if (est)
            printf("  chain estimate %.6g (modrt %.6g), history monitors chain %.6g (modrt "
                   "%.6g), servo %.6g (modrt %.6g)\n", m.err_chain,
                   (double)rt_stats_of(&sim)->istats[ch].err_max, m.xerr_chain,
                   (double)rt_stats_of(&sim)->xset_err[ch], m.xerr_servo, (double)rt_stats_of(&sim)->xset_err[ss]);
    }
    return bad;
}

static int check(void)
{
    int bad = 0;
    for (int i = 0; i < NMETHODS; i++) {
        rt_scene sc;
        rt_set set;
        modrt_init(&sc, &set, i, CHECK_T);
        long n = lround(CHECK_T / (double)sc.dt);
        for (int solver = MONO_DENSE; solver <= MONO_THOMAS; solver++) {
            mono m;
            modrt_init(&sc, &set, i, CHECK_T);
            mono_start(&m, i, solver, 1, &sc);
            modrt_ticks(&sc, &sim, n);
            mono_steps(&m, n);
            double worst = 0;
            for (uint16_t b = 0; b < MONO_NB; b++)
                for (uint16_t j = 0; j < 3; j++) {
                    double d = fabs((double)rt_output(&sim, b, j) - m.x[6 * b + j]);
                    worst = d > worst || d != d ? d : worst;
                }
            int ok = worst <= CHECK_TOL;
            bad += !ok;
            printf("trajectory pendulum10 %s %s: largest position difference at %g s "
                   "%.2e m (tolerance %.0e) %s\n", methods[i].name,
                   solver == MONO_DENSE ? "dense" : "thomas", CHECK_T, worst, CHECK_TOL,
                   ok ? "ok" : "FAILED");
        }
    }
    bad += act_check();
    bad += mr_check();
    return bad ? 1 : 0;
}

int main(int argc, char **argv)
{
    if (argc == 2 && strcmp(argv[1], "check") == 0)
        return check();
    if (argc != 5 || strcmp(argv[1], "count") != 0) {
        fprintf(stderr, "usage: overhead_bench check | count SIDE METHOD SECONDS\n");
        return 2;
    }
    double secs = atof(argv[4]);
    rt_scene sc;
    if (strcmp(argv[3], "ros2") == 0) {
        act_init(&sc, &mdl_scene_pendulum10_actuated_single, secs);
        long n = lround(secs / (double)sc.dt);
        if (strcmp(argv[2], "modrt") == 0) {
            modrt_ticks(&sc, &sim, n);
            return rt_stats_of(&sim)->status == RT_OK ? 0 : 1;
        }
        static amono m;
        act_start(&m, strcmp(argv[2], "thomas") == 0 ? MONO_THOMAS : MONO_DENSE, &sc);
        amono_steps(&m, n);
        return 0;
    }
    if (strcmp(argv[3], "bs3+ros2") == 0) {
        act_init(&sc, &mdl_scene_pendulum10_actuated, secs);
        long n = lround(secs / (double)sc.dt);
        if (strcmp(argv[2], "modrt") == 0) {
            modrt_ticks(&sc, &sim, n);
            return rt_stats_of(&sim)->status == RT_OK ? 0 : 1;
        }
        static amr m;
        mr_start(&m, strcmp(argv[2], "thomas") == 0                            ? MONO_THOMAS
                     : strncmp(argv[2], "tight", 5) == 0 ? MONO_TIGHT
                                                         : MONO_DENSE,
                 strcmp(argv[2], "mono-noest") != 0 && strcmp(argv[2], "tight-noest") != 0, &sc);
        amr_steps(&m, n);
        return 0;
    }
    int i = method_index(argv[3]);
    rt_set set;
    modrt_init(&sc, &set, i, secs);
    long n = lround(secs / (double)sc.dt);
    if (strcmp(argv[2], "modrt") == 0) {
        modrt_ticks(&sc, &sim, n);
        return rt_stats_of(&sim)->status == RT_OK ? 0 : 1;
    }
    static mono m;
    int solver = strcmp(argv[2], "thomas") == 0 ? MONO_THOMAS : MONO_DENSE;
    mono_start(&m, i, solver, strcmp(argv[2], "mono-noest") != 0, &sc);
    mono_steps(&m, n);
    return 0;
}
