/* mbs_bench.c - what accuracy costs: scene pendulum10 run by every explicit integrator
 * over a range of steps; for each run the position error at t = 2 s against a fine
 * reference, and the host CPU time per simulated second (best of a few repetitions).
 *
 * The reference is independent of the runtime: the same chain in minimal coordinates
 * (ten link angles, Lagrange's equations, a dense solve per evaluation) integrated by the
 * classic Runge-Kutta method at 1e-5 s in double; its own error is estimated by halving
 * that step and printed. Host program (libc, libm, POSIX clock).
 *
 * Usage: mbs_bench [--csv FILE] [--md FILE] [--doc FILE] [--reps N] [--commit ID] [--quick]
 *   --csv  work-precision table "series,x,y" (x: host CPU s per simulated s, y: error [m])
 *          for `svgplot --xy --logx --logy`
 *   --md   the table as Markdown
 *   --doc  replaces the text between the lines "<!-- bench:begin -->" and
 *          "<!-- bench:end -->" of FILE (docs/mbs.md) with that Markdown
 *   --reps repetitions per run, the fastest counts (default 3)
 *   --commit the source's commit, named in the Markdown with the date (CPU times are
 *          figures of one machine and day)
 *   --quick fewer, coarser runs (a smoke test) */
#define _POSIX_C_SOURCE 200809L
#include "bench_doc.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "scenes/scenes.h"
#include "rt_sim.h" /* allocates the run */

#define NB 10            /* bodies of pendulum10 */
#define T_CHECK 2.0      /* time of the error measurement [s] */
#define REF_STEPS 200000 /* reference steps over T_CHECK */
#define MAX_ROWS 128     /* table rows */
#define RUN_CAP_S 0.5    /* a method stops refining once one run takes longer [s] */
#define ERR_FLOOR 1e-11  /* ... or once its error is this close to roundoff [m] */
#define ROUND_S 0.05     /* shortest timed round of repeated runs [s] */

static rt_sim sim;
static double ref_xz[2 * NB]; /* reference positions (x, z) of B1..B10 at T_CHECK [m] */

/* ------------------------------------------------------------------ reference */

/* Lagrange's equations of the planar chain, angles phi_i from +x towards +z:
   sum_j M_ij phi_j'' = -sum_j l_i l_j mu_max(i,j) sin(phi_i - phi_j) w_j^2 - g mu_i l_i cos phi_i,
   M_ij = l_i l_j mu_max(i,j) cos(phi_i - phi_j), mu_i = sum_{k >= i} m_k (m = l = 1) */
static void chain_rhs(const double *y, double *dy)
{
    const double *ph = y, *w = y + NB;
    double M[NB][NB + 1];
    for (int i = 0; i < NB; i++) {
        double b = -9.81 * (NB - i) * cos(ph[i]);
        for (int j = 0; j < NB; j++) {
            double mu = NB - (i > j ? i : j);
            M[i][j] = mu * cos(ph[i] - ph[j]);
            b -= mu * sin(ph[i] - ph[j]) * w[j] * w[j];
        }
        M[i][NB] = b;
    }
    for (int k = 0; k < NB; k++) { /* Gauss with partial pivoting */
        int p = k;
        for (int i = k + 1; i < NB; i++)
            if (fabs(M[i][k]) > fabs(M[p][k]))
                p = i;
        for (int j = 0; j <= NB; j++) {
            double t = M[k][j];
            M[k][j] = M[p][j], M[p][j] = t;
        }
        for (int i = k + 1; i < NB; i++) {
            double f = M[i][k] / M[k][k];
            for (int j = k; j <= NB; j++)
                M[i][j] -= f * M[k][j];
        }
    }
    for (int i = NB - 1; i >= 0; i--) {
        double s = M[i][NB];
        for (int j = i + 1; j < NB; j++)
            s -= M[i][j] * dy[NB + j];
        dy[NB + i] = s / M[i][i];
    }
    for (int i = 0; i < NB; i++)
        dy[i] = w[i];
}

/* positions (x, z) of the bodies at T_CHECK with n RK4 steps */
static void chain_ref(long n, double *xz)
{
    double y[2 * NB] = {0}, k[4][2 * NB], t[2 * NB], h = T_CHECK / (double)n;
    static const double c[4] = {0, 0.5, 0.5, 1};
    for (long s = 0; s < n; s++) {
        for (int st = 0; st < 4; st++) {
            for (int i = 0; i < 2 * NB; i++)
                t[i] = y[i] + (st ? c[st] * h * k[st - 1][i] : 0);
            chain_rhs(t, k[st]);
        }
        for (int i = 0; i < 2 * NB; i++)
            y[i] += h / 6 * (k[0][i] + 2 * k[1][i] + 2 * k[2][i] + k[3][i]);
    }
    double x = 0, z = 0;
    for (int i = 0; i < NB; i++) {
        x += cos(y[i]), z += sin(y[i]);
        xz[2 * i] = x, xz[2 * i + 1] = z;
    }
}

/* ------------------------------------------------------------------ runs */

static double now_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t); /* CPU time: other load matters less */
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

typedef struct row {
    const char *method;
    int project;
    double h, err, cost, rhs; /* step [s], error [m], CPU s per sim s, RHS per sim s */
    unsigned status;
} row;

/* pendulum10 with method m at n steps over T_CHECK; returns the position error and the
   host time of init and run in *secs */
static double run(const rt_integrator *m, long n, int project, double *secs, unsigned *status)
{
    rt_scene sc = mdl_scene_pendulum10;
    rt_set set = sc.sets[0];
    set.method = m, set.ratio = 1;
    sc.sets = &set;
    sc.dt = (real_t)(T_CHECK / (double)n);
    sc.t_end = (real_t)T_CHECK;
    sc.stab = project ? RT_STAB_PROJECT : RT_STAB_NONE;
    double t0 = now_s();
    if (rt_init(&sc, &sim) != RT_OK) {
        fprintf(stderr, "mbs_bench: init: %s\n", rt_error_text(&sim));
        exit(1);
    }
    while (rt_tick(&sc, &sim) == RT_OK)
        ;
    *secs = now_s() - t0;
    *status = (unsigned)rt_stats_of(&sim)->status;
    double worst = 0;
    for (int b = 0; b < NB; b++) {
        uint16_t bb = (uint16_t)b;
        double e[3] = {(double)rt_output(&sim, bb, 0) - ref_xz[2 * b],
                       (double)rt_output(&sim, bb, 1),
                       (double)rt_output(&sim, bb, 2) - ref_xz[2 * b + 1]};
        for (int i = 0; i < 3; i++)
            worst = fabs(e[i]) > worst || e[i] != e[i] ? fabs(e[i]) : worst;
    }
    return worst;
}

/* one method over its steps (n = n0, 2 n0, ...) until nmax or the run cap */
static int sweep(const rt_integrator *m, long n0, long nmax, int project, int reps, row *rows,
                 int nrows)
{
    for (long n = n0; n <= nmax && nrows < MAX_ROWS; n *= 2) {
        double best = 1e300, secs = 0, err = 0;
        unsigned st = 0;
        /* each repetition averages over enough runs to last ROUND_S; the fastest counts */
        for (int r = 0; r < reps; r++) {
            double sum = 0;
            int k = 0;
            do {
                err = run(m, n, project, &secs, &st);
                sum += secs, k++;
            } while (sum < ROUND_S);
            best = sum / k < best ? sum / k : best;
        }
        rows[nrows++] = (row){m->name, project, T_CHECK / (double)n, err, best / T_CHECK,
                              (double)n * m->stages / T_CHECK, st};
        if (best > RUN_CAP_S || err < ERR_FLOOR)
            break;
    }
    return nrows;
}

/* the cheapest run of each method within 1e-6 m: the choice issue 4 asks for */
static void print_cheapest(FILE *f, const row *rows, int n, int md)
{
    for (int i = 0; i < n; i++) {
        if (!rows[i].project || (i > 0 && rows[i - 1].method == rows[i].method))
            continue;
        const row *best = 0;
        for (int k = i; k < n && rows[k].method == rows[i].method && rows[k].project; k++)
            if (rows[k].err <= 1e-6 && (!best || rows[k].cost < best->cost))
                best = &rows[k];
        if (best)
            fprintf(f, md ? "- %s: h = %.3g s, error %.2e m, %.3g host CPU s per simulated s\n"
                          : "cheapest within 1e-6 m: %-8s h = %.3g s, error %.2e m, "
                            "%.3g CPU s/sim s\n",
                    best->method, best->h, best->err, best->cost);
        else
            fprintf(f, md ? "- %s: not within 1e-6 m in the steps tried\n"
                          : "cheapest within 1e-6 m: %-8s none in the steps tried\n",
                    rows[i].method);
    }
}

static void print_table(FILE *f, const row *rows, int n, int md)
{
    if (md) {
        fprintf(f, "| method | step h [s] | max position error at 2 s [m] | host CPU s per "
                   "simulated s | RHS per simulated s | status |\n");
        fprintf(f, "|---|---:|---:|---:|---:|---|\n");
    } else {
        fprintf(f, "%-19s %10s %12s %14s %12s  %s\n", "method", "h [s]", "error [m]",
                "CPU s/sim s", "RHS/sim s", "status");
    }
    for (int i = 0; i < n; i++) {
        const row *r = &rows[i];
        char name[32];
        snprintf(name, sizeof name, "%s%s", r->method, r->project ? "" : " (no projection)");
        const char *st = rt_status_name((rt_status)r->status);
        if (md)
            fprintf(f, "| %s | %.3g | %.2e | %.3g | %.3g | %s |\n", name, r->h, r->err,
                    r->cost, r->rhs, st);
        else
            fprintf(f, "%-19s %10.3g %12.2e %14.3g %12.3g  %s\n", name, r->h, r->err, r->cost,
                    r->rhs, st);
    }
}

/* ------------------------------------------------------------------ output files */

/* a FILE writing into buf (at most n - 1 characters, always terminated) */
static FILE *text_stream(char *buf, size_t n)
{
    FILE *f = fmemopen(buf, n, "w");
    if (!f) {
        perror("fmemopen");
        exit(1);
    }
    return f;
}

int main(int argc, char **argv)
{
    const char *csv = 0, *md = 0, *doc = 0, *commit = "unknown";
    int reps = 3, quick = 0;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--csv") && i + 1 < argc)
            csv = argv[++i];
        else if (!strcmp(argv[i], "--md") && i + 1 < argc)
            md = argv[++i];
        else if (!strcmp(argv[i], "--doc") && i + 1 < argc)
            doc = argv[++i];
        else if (!strcmp(argv[i], "--reps") && i + 1 < argc)
            reps = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--commit") && i + 1 < argc)
            commit = argv[++i];
        else if (!strcmp(argv[i], "--quick"))
            quick = 1;
        else {
            fprintf(stderr, "usage: mbs_bench [--csv FILE] [--md FILE] [--doc FILE] [--reps N] "
                            "[--commit ID] [--quick]\n");
            return 2;
        }
    }
    if (reps < 1)
        reps = 1;

    /* the reference, and its own error from halving the step */
    double half[2 * NB], dref = 0;
    chain_ref(REF_STEPS, ref_xz);
    chain_ref(REF_STEPS / 2, half);
    for (int i = 0; i < 2 * NB; i++)
        dref = fabs(half[i] - ref_xz[i]) > dref ? fabs(half[i] - ref_xz[i]) : dref;
    printf("reference: angle formulation, RK4 at %.1e s; |ref(h) - ref(2h)| = %.2e m\n",
           T_CHECK / REF_STEPS, dref);

    static row rows[MAX_ROWS];
    int n = 0;
    long top = quick ? 2000 : 1L << 22;
    n = sweep(&rt_euler, quick ? 1000 : 4000, top, 1, reps, rows, n);
    n = sweep(&rt_heun, 500, top, 1, reps, rows, n);
    n = sweep(&rt_bs3, 250, top, 1, reps, rows, n);
    n = sweep(&rt_rk4, 250, top, 1, reps, rows, n);
    n = sweep(&rt_dopri5, 125, quick ? 2000 : 32000, 1, reps, rows, n);
    n = sweep(&rt_rk4, 250, quick ? 1000 : 16000, 0, reps, rows, n);

    print_table(stdout, rows, n, 0);
    print_cheapest(stdout, rows, n, 0);
    if (md || doc) {
        static char text[MAX_DOC];
        char cpu[128], day[32];
        bench_cpu_name(cpu, sizeof cpu);
        time_t now = time(NULL);
        strftime(day, sizeof day, "%Y-%m-%d", gmtime(&now));
        FILE *f = text_stream(text, sizeof text);
        fprintf(f, "Figures of commit `%s`, measured %s on %s. The errors and the "
                   "right-hand sides are exact, the same on every machine; the host CPU time "
                   "is the best of %d timed rounds per row, a figure of that machine and day. "
                   "Reference: the chain in minimal coordinates, RK4 at %.1e s (halving its "
                   "step changes it by %.1e m).\n\n", commit, day, cpu, reps,
                T_CHECK / REF_STEPS, dref);
        print_table(f, rows, n, 1);
        fprintf(f, "\nCheapest step of each method within 1e-6 m at 2 s:\n\n");
        print_cheapest(f, rows, n, 1);
        fclose(f);
        if (md && bench_write_file(md, text) != 0)
            return 1;
        if (doc && bench_splice_doc("mbs_bench", doc, text) != 0)
            return 1;
    }
    if (csv) {
        FILE *f = fopen(csv, "w");
        if (!f) {
            perror(csv);
            return 1;
        }
        fprintf(f, "series,x,y\n");
        for (int i = 0; i < n; i++)
            fprintf(f, "%s%s,%.6g,%.6g\n", rows[i].method, rows[i].project ? "" : " no proj",
                    rows[i].cost, rows[i].err);
        fclose(f);
    }
    return 0;
}
