/* multirate_bench.c - what the multirate schedule saves (issue 6, item 4): the cheapest
 * configuration of scene pendulum10_actuated_single (one set: method, step, Jacobian
 * refresh interval) and of scene pendulum10_actuated (per-set methods and the chain's step
 * ratio) that keep every position at t = 10 s within 1e-4 m of a fine reference, their host
 * CPU times measured side by side, and the speedup.
 *
 * Reference: the single-set model integrated by Dormand-Prince at 1e-4 s (explicit and
 * stable there: the servo's eigenvalues times the step stay within its stability region);
 * its own error is estimated by doubling that step and printed. Both variants are the same
 * model (same blocks, parameters and wiring), so both converge to it.
 *
 * Single rate: the step may not exceed the controller's sample period (1 ms: a set that
 * stepped over a sample would read the held command of the sample before), so the sweep
 * halves the step from 1 ms. Multirate: the servo set steps every base tick of 1 ms, the
 * chain every r ticks. A configuration counts when its run is clean (no fault counted)
 * and its error at 10 s is within the bound (issue 6); a stricter bound also asks it of
 * the positions every 0.128 s of the run. The cheapest of each variant under each bound
 * are then timed again in turn, best of --final rounds; the last line printed is the
 * speedup under the bound of issue 6.
 *
 * `make bench` does not run this CPU-time sweep: the speedup it reports comes from
 * deterministic instruction counts (tools/dev/bench/speedup.py, `make speedup`,
 * docs/multirate.md "The benchmark"). This program gives the table of rate transitions
 * (--transition, docs/multirate.md "Background sets") and a quick check.
 *
 * Host program (libc, libm, POSIX CPU clock). Usage: multirate_bench [--csv FILE]
 * [--md FILE] [--doc FILE] [--reps N] [--final N] [--quick]
 *   --csv   work-precision table "series,x,y" (x: host CPU s per run of 10 s, y: largest
 *           position error at 10 s [m]) for `svgplot --xy --logx --logy`
 *   --md    the summary and table as Markdown; --doc replaces the text between the lines
 *           "<!-- bench:begin -->" and "<!-- bench:end -->" of FILE with it
 *   --reps  timed rounds per sweep point, the fastest counts (default 2)
 *   --final rounds of the side-by-side timing of the winners (default 9)
 *   --quick fewer configurations (a smoke test) */
#define _POSIX_C_SOURCE 200809L
#include "bench_doc.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "scenes/scenes.h"
#include "rt_sim.h" /* allocates the run */

#define NB 10              /* bodies of the chain */
#define TOL 1e-4           /* accuracy every configuration must reach [m] */
#define REF_STEP 1e-4      /* reference step [s] */
#define TS 1e-3            /* the controller's sample period: the largest single step [s] */
#define T_SAMPLE 0.128     /* positions are also compared every T_SAMPLE (a multiple of every
                              step and macro step of the sweeps) [s] */
#define NSAMPLE 78         /* samples in 10 s */
#define ROUND_S 0.05       /* shortest timed round of repeated runs [s] */
#define SLOW_S 1.0         /* a sweep point slower than this is timed once [s] */
#define MAX_ROWS 512       /* sweep points */

static rt_sim sim;
static double ref_pos[3 * NB]; /* reference positions of B1..B10 at 10 s [m] */
static double ref_run[NSAMPLE][3 * NB]; /* ... every T_SAMPLE [m] */
static double run_pos[NSAMPLE][3 * NB]; /* those of the last run */

/* one configuration of either variant */
typedef struct config {
    int multi;                     /* 0: pendulum10_actuated_single, 1: pendulum10_actuated */
    const rt_integrator *m[2];     /* single: m[0]; multirate: chain m[0], servo m[1] */
    double h;                      /* single: step; multirate: base tick (servo step) [s] */
    uint32_t ratio;                /* multirate: the chain's step in base ticks */
    uint16_t jac_every;            /* Jacobian refresh interval of the implicit set */
    uint8_t in_chain, in_servo;    /* multirate: interpolation schemes (0: the scene's) */
    uint8_t bg;                    /* multirate: 1 the chain steps in the background
                                      (rt/bg.c), 0 in the tick (the sweeps) */
} config;

typedef struct row {
    config c;
    double err;                    /* largest position error at 10 s [m] */
    double err_run;                /* largest position error every T_SAMPLE s [m] */
    double cpu;                    /* host CPU s per run (best of the rounds) */
    int clean;                     /* no fault counted */
} row;

/* ------------------------------------------------------------------ runs */

static double cpu_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t); /* CPU time: other load matters less */
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* the scene of configuration c (its sets in *sets) */
static rt_scene make_scene(const config *c, rt_set *sets)
{
    rt_scene sc = c->multi ? mdl_scene_pendulum10_actuated : mdl_scene_pendulum10_actuated_single;
    for (uint8_t s = 0; s < sc.nsets; s++)
        sets[s] = sc.sets[s];
    sc.sets = sets;
    sc.dt = (real_t)c->h;
    sets[0].method = c->m[0];
    if (!c->multi) {
        sets[0].ratio = 1;
        sets[0].cfg.jac_every = rt_method_iterates(c->m[0]) ? c->jac_every : 0;
        return sc;
    }
    /* set 0 is the chain, set 1 the servo (models/scenes/pendulum10_actuated.c) */
    sets[0].ratio = c->ratio;
    sets[1].method = c->m[1];
    sets[1].ratio = 1;
    sets[1].cfg.jac_every = rt_method_iterates(c->m[1]) ? c->jac_every : 0;
    sets[0].background = c->bg;
    if (c->in_chain)
        sets[0].interp = c->in_chain;
    if (c->in_servo)
        sets[1].interp = c->in_servo;
    return sc;
}

/* positions of B1..B10 (blocks 0..9 of both scenes) now */
static void positions(double *p)
{
    for (int b = 0; b < NB; b++)
        for (int k = 0; k < 3; k++)
            p[3 * b + k] = (double)rt_output(&sim, (uint16_t)b, (uint16_t)k);
}

/* runs c to 10 s; positions into p (if not NULL), returns the CPU time */
static double run(const config *c, double *p, int *clean)
{
    rt_set sets[RT_MAX_SETS];
    rt_scene sc = make_scene(c, sets);
    double t0 = cpu_s();
    if (rt_init(&sc, &sim) != RT_OK) {
        fprintf(stderr, "multirate_bench: init: %s\n", rt_error_text(&sim));
        exit(1);
    }
    uint64_t every = (uint64_t)(T_SAMPLE / c->h + 0.5);
    for (rt_status st = RT_OK; st == RT_OK;) {
        st = rt_tick(&sc, &sim);
        uint64_t k = rt_ticks_done(&sim);
        if (p && k % every == 0 && k / every <= NSAMPLE)
            positions(run_pos[k / every - 1]);
    }
    double secs = cpu_s() - t0;
    if (p)
        positions(p);
    if (clean) {
        *clean = rt_stats_of(&sim)->status == RT_OK;
        for (int k = 0; k < RT_CNT_COUNT; k++)
            *clean = *clean && (k == RT_CNT_EVENTS || rt_stats_of(&sim)->count[k] == 0);
    }
    return secs;
}

static double max_diff(const double *a, const double *b)
{
    double e = 0;
    for (int i = 0; i < 3 * NB; i++) {
        double d = fabs(a[i] - b[i]);
        e = d > e || d != d ? d : e;
    }
    return e;
}

/* CPU time per run: rounds of at least ROUND_S, the fastest of reps (first: the time of
   a run already made, which counts as a round when it lasted ROUND_S) */
static double timed(const config *c, int reps, double first)
{
    double best = first >= ROUND_S ? first : 1e300;
    for (int r = first >= ROUND_S; r < reps; r++) {
        double sum = 0;
        int k = 0;
        do {
            sum += run(c, NULL, NULL), k++;
        } while (sum < ROUND_S);
        best = sum / k < best ? sum / k : best;
    }
    return best;
}

/* one sweep point: error, cleanliness, time (a run of over SLOW_S is timed once: such a
   configuration is out of the race, and repeating it would only lengthen the benchmark) */
static row measure(const config *c, int reps)
{
    row r = {.c = *c};
    double p[3 * NB];
    double first = run(c, p, &r.clean);
    r.err = max_diff(p, ref_pos);
    for (int k = 0; k < NSAMPLE; k++) {
        double e = max_diff(run_pos[k], ref_run[k]);
        r.err_run = e > r.err_run || e != e ? e : r.err_run;
    }
    r.cpu = r.clean && r.err < 1 && first < SLOW_S ? timed(c, reps, first) : first;
    return r;
}

/* ------------------------------------------------------------------ names */

static const char *interp_name(uint8_t i)
{
    return rt_interp_name((rt_interp)i);
}

/* the series a row belongs to, e.g. "single sdirk2 J64" or "multirate rk4+beuler" */
static void series(const row *r, char *buf, size_t n)
{
    const config *c = &r->c;
    if (!c->multi)
        snprintf(buf, n, c->m[0]->implicit ? "single %s J%u" : "single %s", c->m[0]->name,
                 (unsigned)c->jac_every);
    else
        snprintf(buf, n, "multirate %s+%s%s%s", c->m[0]->name, c->m[1]->name,
                 c->in_chain ? " " : "", c->in_chain ? interp_name(c->in_chain) : "");
}

static void describe(FILE *f, const config *c)
{
    const rt_scene *ms = &mdl_scene_pendulum10_actuated;
    if (!c->multi) {
        fprintf(f, "one set: %s, h = %g ms", c->m[0]->name, c->h * 1e3);
        if (c->m[0]->implicit)
            fprintf(f, ", Jacobian every %u steps", (unsigned)c->jac_every);
        return;
    }
    fprintf(f, "chain: %s, H = %g ms (%u ticks, inputs by %s); servo: %s, h = %g ms "
               "(inputs by %s), Jacobian every %u steps",
            c->m[0]->name, c->h * c->ratio * 1e3, (unsigned)c->ratio,
            interp_name(c->in_chain ? c->in_chain : ms->sets[0].interp), c->m[1]->name,
            c->h * 1e3, interp_name(c->in_servo ? c->in_servo : ms->sets[1].interp),
            (unsigned)c->jac_every);
}

/* ------------------------------------------------------------------ sweeps */

static row rows[MAX_ROWS];
static int nrows;

static void add(const config *c, int reps)
{
    if (nrows < MAX_ROWS)
        rows[nrows++] = measure(c, reps);
}

/* single rate: every stiff method and Jacobian interval, the step halved from the sample
   period until the bound is met (and once more, for the plot); the explicit methods from
   0.5 ms, where the servo's eigenvalues already leave their stability regions */
static void sweep_single(int reps, int quick)
{
    static const rt_integrator *const imp[] = {&rt_beuler, &rt_trap, &rt_sdirk2, &rt_sdirk3,
                                               &rt_ros2};
    static const rt_integrator *const expl[] = {&rt_heun, &rt_bs3, &rt_rk4, &rt_dopri5};
    static const uint16_t jac[] = {1, 32, 1024};
    for (unsigned i = 0; i < sizeof imp / sizeof imp[0]; i++)
        for (unsigned j = quick ? 1 : 0; j < sizeof jac / sizeof jac[0]; j++)
            /* a fresh Jacobian every step (n = 62 evaluations) only at the largest step */
            for (int k = 0, met = 0; k < (quick ? 2 : jac[j] == 1 ? 1 : 3) && met < 2; k++) {
                config c = {.m = {imp[i]}, .h = TS / (1 << k), .jac_every = jac[j]};
                add(&c, reps);
                met += rows[nrows - 1].clean && rows[nrows - 1].err <= TOL;
            }
    for (unsigned i = quick ? 2 : 0; i < sizeof expl / sizeof expl[0]; i++)
        for (int k = 1, met = 0; k < (quick ? 3 : 4) && met < 2; k++) {
            config c = {.m = {expl[i]}, .h = TS / (1 << k)};
            add(&c, reps);
            met += rows[nrows - 1].clean && rows[nrows - 1].err <= TOL;
        }
}

/* multirate: chain method x servo method, the chain's ratio from coarse to fine until
   the bound is met (and one finer), base tick = the sample period */
static void sweep_multi(int reps, int quick)
{
    static const rt_integrator *const chain[] = {&rt_heun, &rt_bs3, &rt_rk4, &rt_dopri5};
    static const rt_integrator *const servo[] = {&rt_beuler, &rt_trap, &rt_sdirk2,
                                                 &rt_sdirk3, &rt_ros2};
    for (unsigned i = quick ? 2 : 0; i < sizeof chain / sizeof chain[0]; i++)
        for (unsigned j = 0; j < sizeof servo / sizeof servo[0]; j++)
            for (uint32_t r = 64, met = 0; r >= 2 && met < 2; r /= 2) {
                config c = {.multi = 1, .m = {chain[i], servo[j]}, .h = TS, .ratio = r,
                            .jac_every = 64};
                add(&c, reps);
                met += rows[nrows - 1].clean && rows[nrows - 1].err <= TOL;
            }
    /* the chain holding the servo's torque instead of extrapolating it */
    for (uint32_t r = 64, met = 0; r >= 1 && met < 2; r /= 2) {
        config c = {.multi = 1, .m = {&rt_rk4, &rt_beuler}, .h = TS, .ratio = r,
                    .jac_every = 64, .in_chain = RT_INTERP_HOLD};
        add(&c, reps);
        met += rows[nrows - 1].clean && rows[nrows - 1].err <= TOL;
    }
}

/* the cheapest clean row of a variant within the bound at 10 s (strict: also at every
   sample of the run), or NULL */
static const row *cheapest(int multi, int strict)
{
    const row *best = 0;
    for (int i = 0; i < nrows; i++)
        if (rows[i].c.multi == multi && rows[i].clean && rows[i].err <= TOL &&
            (!strict || rows[i].err_run <= TOL) && (!best || rows[i].cpu < best->cpu))
            best = &rows[i];
    return best;
}

/* ------------------------------------------------------------------ output */

static void print_rows(FILE *f, int md)
{
    if (md)
        fprintf(f, "| variant | configuration | error at 10 s [m] | largest error over the run "
                   "[m] | host CPU s per run | clean |\n|---|---|---:|---:|---:|---|\n");
    for (int i = 0; i < nrows; i++) {
        const row *r = &rows[i];
        fprintf(f, md ? "| %s | " : "%-9s ", r->c.multi ? "multirate" : "single");
        describe(f, &r->c);
        fprintf(f, md ? " | %.2e | %.2e | %.4g | %s |\n"
                      : "  error %.2e m (over the run %.2e m)  cpu %.4g s%s\n",
                r->err, r->err_run, r->cpu,
                md ? (r->clean ? "yes" : "no") : (r->clean ? "" : "  (faults)"));
    }
}

/* do rows a and b belong to one series (same configuration but the step)? */
static int same_series(const row *a, const row *b)
{
    const config *x = &a->c, *y = &b->c;
    return x->multi == y->multi && x->m[0] == y->m[0] && x->m[1] == y->m[1] &&
           x->jac_every == y->jac_every && x->in_chain == y->in_chain &&
           x->in_servo == y->in_servo;
}

/* is row i plotted? For each single-rate method (each multirate chain method and scheme)
   the series of its cheapest row within the bound, else of its cheapest row */
static int plotted(int i)
{
    const row *best = 0;
    for (int k = 0; k < nrows; k++) {
        const config *x = &rows[k].c, *y = &rows[i].c;
        if (x->multi != y->multi || x->m[0] != y->m[0] || x->in_chain != y->in_chain)
            continue;
        int ok = rows[k].clean && rows[k].err <= TOL;
        int best_ok = best && best->clean && best->err <= TOL;
        if (!best || ok > best_ok || (ok == best_ok && rows[k].cpu < best->cpu))
            best = &rows[k];
    }
    return best && same_series(best, &rows[i]);
}

/* x = CPU s, y = error; clean points of the plotted series */
static int write_csv(const char *path)
{
    FILE *f = fopen(path, "w");
    if (!f) {
        perror(path);
        return 1;
    }
    fprintf(f, "series,x,y\n");
    for (int i = 0; i < nrows; i++) {
        char name[64];
        if (!rows[i].clean || !(rows[i].err < 1) || !plotted(i))
            continue;
        series(&rows[i], name, sizeof name);
        fprintf(f, "%s,%.6g,%.6g\n", name, rows[i].cpu, rows[i].err > 1e-14 ? rows[i].err : 1e-14);
    }
    return fclose(f) != 0;
}

/* a winner's configuration, error and time */
static void winner(FILE *f, const char *what, const row *r, double t)
{
    fprintf(f, "%s", what);
    describe(f, &r->c);
    fprintf(f, "; error at 10 s %.2e m (over the run %.2e m); %.4g s host CPU per run\n",
            r->err, r->err_run, t);
}

/* the summary: the winners of the stricter bound, then those of issue 6 (at 10 s) and
   their speedup, the last line */
static void summary(FILE *f, const row *const *w, const double *t, int md)
{
    const char *li = md ? "- " : "";
    fprintf(f, "%sbound also on every position every %g s of the run:\n", li, T_SAMPLE);
    winner(f, md ? "  - cheapest single rate: " : "  cheapest single rate: ", w[2], t[2]);
    winner(f, md ? "  - cheapest multirate: " : "  cheapest multirate:   ", w[3], t[3]);
    fprintf(f, "%sspeedup %.3g\n", md ? "  - " : "  ", t[2] / t[3]);
    fprintf(f, "%sbound on every position at 10 s (issue 6):\n", li);
    winner(f, md ? "  - cheapest single rate: " : "cheapest single rate: ", w[0], t[0]);
    winner(f, md ? "  - cheapest multirate: " : "cheapest multirate:   ", w[1], t[1]);
    fprintf(f, "%spendulum10_actuated speedup at equal accuracy: %.3g\n", md ? "  - " : "",
            t[0] / t[1]);
}

/* the library scenes as declared, against the reference */
static void check_scenes(FILE *f)
{
    static const rt_scene *const sc[] = {&mdl_scene_pendulum10_actuated,
                                         &mdl_scene_pendulum10_actuated_single};
    for (int i = 0; i < 2; i++) {
        double p[3 * NB];
        if (rt_init(sc[i], &sim) != RT_OK)
            continue;
        double t0 = cpu_s();
        while (rt_tick(sc[i], &sim) == RT_OK)
            ;
        double secs = cpu_s() - t0;
        positions(p);
        fprintf(f, "scene %s as declared: error %.2e m, %.4g s host CPU, status %s\n",
                sc[i]->name, max_diff(p, ref_pos), secs, rt_status_name(rt_stats_of(&sim)->status));
    }
}

/* the rate transitions: the chain stepped in the tick (the classic schedule) or in the
   background (rt/bg.c), against the reference at 10 s and over the run */
static void check_transition(FILE *f, int md)
{
    static const struct {
        uint8_t bg;
        uint32_t ratio;
        const char *how;
    } t[] = {
        {0, 16, "chain in the tick every 16 ms (it steps first, the servo set interpolates it)"},
        {1, 16, "chain in the background every 16 ms (each set extrapolates the other)"},
        {1, 8, "chain in the background every 8 ms"},
        {1, 4, "chain in the background every 4 ms (pendulum10_actuated)"},
    };
    for (size_t i = 0; i < sizeof t / sizeof t[0]; i++) {
        config c = {.multi = 1, .m = {&rt_bs3, &rt_ros2}, .h = TS, .ratio = t[i].ratio,
                    .jac_every = 64, .bg = t[i].bg};
        row r = {.c = c};
        double p[3 * NB];
        run(&c, p, &r.clean);
        r.err = max_diff(p, ref_pos);
        for (int k = 0; k < NSAMPLE; k++) {
            double e = max_diff(run_pos[k], ref_run[k]);
            r.err_run = e > r.err_run || e != e ? e : r.err_run;
        }
        fprintf(f, "%sbs3 + ros2 every 1 ms, %s: error at 10 s %.2e m, over the run %.2e m, "
                   "status %s\n", md ? "- " : "transition: ", t[i].how, r.err, r.err_run,
                rt_status_name(rt_stats_of(&sim)->status));
    }
}

int main(int argc, char **argv)
{
    const char *csv = 0, *md = 0, *doc = 0;
    int reps = 2, final = 9, quick = 0, transition = 0;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--csv") && i + 1 < argc)
            csv = argv[++i];
        else if (!strcmp(argv[i], "--md") && i + 1 < argc)
            md = argv[++i];
        else if (!strcmp(argv[i], "--doc") && i + 1 < argc)
            doc = argv[++i];
        else if (!strcmp(argv[i], "--reps") && i + 1 < argc)
            reps = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--final") && i + 1 < argc)
            final = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--quick"))
            quick = 1;
        else if (!strcmp(argv[i], "--transition"))
            transition = 1;
        else {
            fprintf(stderr, "usage: multirate_bench [--csv FILE] [--md FILE] [--doc FILE] "
                            "[--reps N] [--final N] [--quick]\n");
            return 2;
        }
    }
    reps = reps < 1 ? 1 : reps;
    final = final < 1 ? 1 : final;

    /* the reference and its own error from doubling the step */
    double coarse[3 * NB];
    config rc = {.m = {&rt_dopri5}, .h = REF_STEP};
    run(&rc, ref_pos, NULL);
    memcpy(ref_run, run_pos, sizeof ref_run);
    rc.h = 2 * REF_STEP;
    run(&rc, coarse, NULL);
    double dref = max_diff(ref_pos, coarse);
    printf("reference: one set, dopri5 at %.1e s; |ref(h) - ref(2h)| = %.2e m\n", REF_STEP,
           dref);
    check_transition(stdout, 0);
    if (transition)
        return 0;

    sweep_single(reps, quick);
    sweep_multi(reps, quick);
    print_rows(stdout, 0);
    check_scenes(stdout);
    /* winners: single and multirate at 10 s, then under the stricter bound */
    const row *w[4] = {cheapest(0, 0), cheapest(1, 0), cheapest(0, 1), cheapest(1, 1)};
    for (int i = 0; i < 4; i++)
        if (!w[i]) {
            printf("no %s configuration within %g m%s\n", i % 2 ? "multirate" : "single-rate",
                   TOL, i > 1 ? " over the run" : " at 10 s");
            return 1;
        }

    /* side by side: the winners in turn, the fastest round of each */
    double t[4] = {1e300, 1e300, 1e300, 1e300};
    for (int k = 0; k < final; k++)
        for (int i = 0; i < 4; i++) {
            double x = timed(&w[i]->c, 1, 0);
            t[i] = x < t[i] ? x : t[i];
        }
    summary(stdout, w, t, 0);

    if (csv && write_csv(csv) != 0)
        return 1;
    if (md || doc) {
        static char text[MAX_DOC];
        char cpu[128];
        bench_cpu_name(cpu, sizeof cpu);
        FILE *f = fmemopen(text, sizeof text, "w");
        if (!f) {
            perror("fmemopen");
            return 1;
        }
        fprintf(f, "Host: %s; host CPU time per 10 s run, best of %d timed rounds per "
                   "sweep point, the winners in turn best of %d. Reference: one set, "
                   "dopri5 at %.0e s (doubling its step changes it by %.1e m).\n\n",
                cpu, reps, final, REF_STEP, dref);
        summary(f, w, t, 1);
        fprintf(f, "\nThe rate transitions of the declared schedule (\"Background sets\" "
                   "above), against the reference:\n\n");
        check_transition(f, 1);
        fprintf(f, "\n");
        print_rows(f, 1);
        fclose(f);
        if (md && bench_write_file(md, text) != 0)
            return 1;
        if (doc && bench_splice_doc("multirate_bench", doc, text) != 0)
            return 1;
    }
    return 0;
}
