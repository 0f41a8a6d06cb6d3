/* tight_bench.c - modrt against the tightest hand-written program of pendulum10
 * (pendulum_tight.c): the trajectory check, and the runs tools/dev/bench/overhead.sh counts
 * with callgrind (docs/overhead.md, "Against the tight program").
 *
 * The modrt side is the library as an application runs it: rt_init, then rt_tick per base
 * tick of scene pendulum10 with its method replaced. The counted functions are
 * modrt_ticks and tight_steps; start-up is outside them.
 *
 * The same for lane_change_planar (lane_tight.c): its own scene as shipped (RK4 at 5 ms,
 * base tick 1 ms), the whole run of LANE_T seconds in the check.
 *
 * Usage: tight_bench check              both sides, every method, CHECK_T seconds: the
 *                                       largest position difference must be at most
 *                                       CHECK_TOL and the largest error estimate equal
 *                                       modrt's to EST_TOL (exit 1 otherwise); then
 *                                       lane_change_planar likewise over LANE_T seconds
 *        tight_bench count SIDE METHOD SECONDS
 *                                       SIDE modrt | modrt-tables (the table-driven
 *                                       path: without the scene's written-out code) |
 *                                       tight | tight-noest (without the error
 *                                       estimate); METHOD bs3 | rk4 | dopri5;
 *                                       SIDE lane-modrt | lane-modrt-tables | lane-tight |
 *                                       lane-tight-noest: lane_change_planar, METHOD rk4
 *                                       (the scene's) */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lane_tight.h"
#include "pendulum_tight.h"
#include "rt_sim.h" /* allocates the run */
#include "scenes/scenes.h"
#include "rt_sim.h" /* the simulator in static storage */

#define CHECK_T 2.0     /* simulated time of the check [s]: the chain is chaotic, rounding
                           differences grow from 1e-16 to 1e-14 m over it */
#define CHECK_TOL 1e-12 /* largest position difference accepted [m]; a formulation or
                           tableau error gives 1e-6 or more */
#define EST_TOL 1e-9    /* largest relative difference of the largest error estimates */
#define LANE_T 8.0      /* lane_change_planar's whole run [s] */

static rt_sim sim;

static const struct {
    const char *name;
    const rt_integrator *rt;
    int tight;
} methods[] = {
    {"bs3", &rt_bs3, TIGHT_BS3},
    {"rk4", &rt_rk4, TIGHT_RK4},
    {"dopri5", &rt_dopri5, TIGHT_DOPRI5},
};
#define NMETHODS (int)(sizeof methods / sizeof methods[0])

static int method_index(const char *name)
{
    for (int i = 0; i < NMETHODS; i++)
        if (strcmp(name, methods[i].name) == 0)
            return i;
    fprintf(stderr, "tight_bench: unknown method %s\n", name);
    exit(2);
}

/* pendulum10 with method i over t_end seconds (the scene's own step); no recorded
   signals: the tight program records nothing. tables: without the scene's written-out
   code (rt_scene_code), the table-driven path */
static void modrt_init(rt_scene *sc, rt_set *set, int i, double t_end, int tables)
{
    *sc = mdl_scene_pendulum10;
    if (tables)
        sc->code = 0;
    *set = sc->sets[0];
    set->method = methods[i].rt;
    sc->sets = set;
    sc->t_end = (real_t)t_end;
    sc->nrecs = 0;
    if (rt_init(sc, &sim) != RT_OK) {
        fprintf(stderr, "tight_bench: init: %s\n", rt_error_text(&sim));
        exit(1);
    }
}

__attribute__((noinline)) void modrt_ticks(const rt_scene *sc, rt_sim *s, long n)
{
    for (long i = 0; i < n; i++)
        rt_tick(sc, s);
}

/* the tight program started from modrt's state after init (outputs x, y, z, vx, vy, vz) */
static void tight_start(tight *m, int i, int estimate, const rt_scene *sc)
{
    double x0[6 * TIGHT_NB];
    for (uint16_t b = 0; b < TIGHT_NB; b++)
        for (uint16_t j = 0; j < 6; j++)
            x0[6 * b + j] = (double)rt_output(&sim, b, j);
    m->method = methods[i].tight, m->estimate = estimate;
    m->h = (double)sc->dt;
    tight_init(m, x0);
}

/* a tight program's run against modrt's (sim): positions within CHECK_TOL, the same
   largest error estimate within EST_TOL, status ok, constraint residual within 1e-9 m */
static int agrees(double worst, double err_max, double est, double res_max)
{
    return worst <= CHECK_TOL && fabs(err_max - est) / est <= EST_TOL &&
           rt_stats_of(&sim)->status == RT_OK && res_max <= 1e-9;
}

static int check(void)
{
    int bad = 0;
    for (int i = 0; i < NMETHODS; i++) {
        rt_scene sc;
        rt_set set;
        tight m;
        modrt_init(&sc, &set, i, CHECK_T, 0);
        tight_start(&m, i, 1, &sc);
        long n = lround(CHECK_T / (double)sc.dt);
        modrt_ticks(&sc, &sim, n);
        tight_steps(&m, n);
        double worst = 0;
        for (uint16_t b = 0; b < TIGHT_NB; b++)
            for (uint16_t j = 0; j < 3; j++) {
                double d = fabs((double)rt_output(&sim, b, j) - m.q[3 * b + j]);
                worst = d > worst || d != d ? d : worst;
            }
        double est = (double)rt_stats_of(&sim)->istats[0].err_max;
        int ok = agrees(worst, m.err_max, est, m.res_max);
        bad += !ok;
        printf("trajectory pendulum10 %s tight: largest position difference at %g s %.2e m "
               "(tolerance %.0e), largest error estimate %.6e (modrt %.6e), largest "
               "residual %.1e m %s\n", methods[i].name, CHECK_T, worst, CHECK_TOL, m.err_max,
               est, m.res_max, ok ? "ok" : "FAILED");
    }
    return bad ? 1 : 0;
}

/* ------------------------------------------------------------------ lane_change_planar */

/* lane_change_planar as shipped over t_end seconds, no recorded signals; tables: without
   its written-out code (the table-driven path) */
static void lane_modrt_init(rt_scene *sc, double t_end, int tables)
{
    const rt_scene_entry *e = mdl_scenes;
    while (e->name && strcmp(e->name, "lane_change_planar") != 0)
        e++;
    if (!e->name) {
        fprintf(stderr, "tight_bench: no scene lane_change_planar\n");
        exit(1);
    }
    *sc = *e->scene;
    sc->t_end = (real_t)t_end;
    sc->nrecs = 0;
    if (tables)
        sc->code = 0;
    if (rt_init(sc, &sim) != RT_OK) {
        fprintf(stderr, "tight_bench: init: %s\n", rt_error_text(&sim));
        exit(1);
    }
}

/* the tight program from modrt's state after init (blocks V1, V2 are the scene's first) */
static void lane_start(lane_tight *m, int estimate, const rt_scene *sc)
{
    double x0[LT_NX];
    for (uint16_t b = 0; b < 2; b++)
        for (uint16_t j = 0; j < 6; j++)
            x0[6 * b + j] = (double)rt_block_x(&sim, b, j);
    lane_tight_init(m, x0, (double)rt_set_step(sc, 0));
    m->estimate = estimate;
}

static int lane_check(void)
{
    rt_scene sc;
    lane_tight m;
    lane_modrt_init(&sc, LANE_T, 0);
    lane_start(&m, 1, &sc);
    long n = lround(LANE_T / (double)sc.dt), k = lround(LANE_T / m.h);
    modrt_ticks(&sc, &sim, n);
    lane_tight_steps(&m, k);
    double worst = 0;
    for (uint16_t b = 0; b < 2; b++)
        for (uint16_t j = 0; j < 2; j++) {
            double d = fabs((double)rt_block_x(&sim, b, j) - m.x[6 * b + j]);
            worst = d > worst || d != d ? d : worst;
        }
    double est = (double)rt_stats_of(&sim)->istats[0].err_max;
    int ok = agrees(worst, m.err_max, est, m.res_max);
    printf("trajectory lane_change_planar rk4 tight: largest position difference at %g s "
           "%.2e m (tolerance %.0e), largest error estimate %.6e (modrt %.6e), largest "
           "residual %.1e m %s\n", LANE_T, worst, CHECK_TOL, m.err_max, est, m.res_max,
           ok ? "ok" : "FAILED");
    return ok ? 0 : 1;
}

static int lane_count(const char *side, const char *method, double secs)
{
    rt_scene sc;
    if (strcmp(method, "rk4") != 0) {
        fprintf(stderr, "tight_bench: lane_change_planar is stepped by rk4, not %s\n", method);
        return 2;
    }
    int tables = strcmp(side, "lane-modrt-tables") == 0;
    lane_modrt_init(&sc, secs, tables);
    if (strcmp(side, "lane-modrt") == 0 || tables) {
        modrt_ticks(&sc, &sim, lround(secs / (double)sc.dt));
        return rt_stats_of(&sim)->status == RT_OK ? 0 : 1;
    }
    static lane_tight m;
    lane_start(&m, strcmp(side, "lane-tight") == 0, &sc);
    lane_tight_steps(&m, lround(secs / m.h));
    return 0;
}

int main(int argc, char **argv)
{
    if (argc == 2 && strcmp(argv[1], "check") == 0)
        return check() | lane_check();
    if (argc == 5 && strncmp(argv[2], "lane-", 5) == 0 && strcmp(argv[1], "count") == 0) {
        if (strcmp(argv[2], "lane-modrt") && strcmp(argv[2], "lane-modrt-tables") &&
            strcmp(argv[2], "lane-tight") &&
            strcmp(argv[2], "lane-tight-noest")) {
            fprintf(stderr, "tight_bench: unknown side %s\n", argv[2]);
            return 2;
        }
        return lane_count(argv[2], argv[3], atof(argv[4]));
    }
    if (argc != 5 || strcmp(argv[1], "count") != 0) {
        fprintf(stderr, "usage: tight_bench check | count SIDE METHOD SECONDS\n");
        return 2;
    }
    int i = method_index(argv[3]);
    double secs = atof(argv[4]);
    rt_scene sc;
    rt_set set;
    int tables = strcmp(argv[2], "modrt-tables") == 0;
    modrt_init(&sc, &set, i, secs, tables);
    long n = lround(secs / (double)sc.dt);
    if (strcmp(argv[2], "modrt") == 0 || tables) {
        modrt_ticks(&sc, &sim, n);
        return rt_stats_of(&sim)->status == RT_OK ? 0 : 1;
    }
    if (strcmp(argv[2], "tight") != 0 && strcmp(argv[2], "tight-noest") != 0) {
        fprintf(stderr, "tight_bench: unknown side %s\n", argv[2]);
        return 2;
    }
    static tight m;
    tight_start(&m, i, strcmp(argv[2], "tight") == 0, &sc);
    tight_steps(&m, n);
    return 0;
}
