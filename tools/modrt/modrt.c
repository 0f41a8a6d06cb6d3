/* modrt.c - the host command line: list and describe the registered scenes and kinds,
 * run a scene or a scene file (FILE.scn, compiled in host memory by tools/scenec) on the
 * POSIX port, size a per-scene build, tune a multirate schedule. The conventions (GNU-style
 * options, --help per subcommand, exit codes 0 ok / 1 faults counted / 2 usage) are in
 * cli.h; each subcommand is a row of the table at the end of this file. */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "info.h"
#include "models.h"
#include "runner.h"
#include "tune.h"
#include "version.h"

#define MAX_SETS_ARGS 32 /* --set options on one command line */

static rt_sim sim; /* the caller owns the runtime's storage */

static int cmd_list(void)
{
    for (const rt_scene_entry *e = mdl_scenes; e->name; e++)
        printf("%-28s %s\n", e->name, e->scene->doc ? e->scene->doc : "");
    return 0;
}

static const char *type_name(rt_kind_type t)
{
    static const char *const names[] = {"output", "nss", "lss", "dss", "mbs"};
    return (unsigned)t < sizeof names / sizeof names[0] ? names[t] : "?";
}

static void info_blocks(const rt_scene *sc)
{
    printf("blocks: %u\n", sc->nblocks);
    for (uint16_t b = 0; b < sc->nblocks; b++) {
        const rt_block *bl = &sc->blocks[b];
        const rt_kind *k = bl->kind;
        printf("  %-10s %-12s %-6s set %u  nu %u ny %u nx %u nd %u np %u nr %u", bl->name,
               k->name, type_name(k->type), bl->set, k->nu, k->ny, k->nx, k->nd, k->np, k->nr);
        if (k->type == RT_KIND_DSS)
            printf("  ts %g s", (double)bl->ts);
        putchar('\n');
    }
}

static void info_wiring(const rt_scene *sc)
{
    printf("connections: %u\n", sc->nconns);
    for (uint16_t c = 0; c < sc->nconns; c++) {
        const rt_conn *cn = &sc->conns[c];
        const rt_block *f = &sc->blocks[cn->from], *t = &sc->blocks[cn->to];
        printf("  %s.%s -> %s.%s\n", f->name, f->kind->y_names[cn->y], t->name,
               t->kind->u_names[cn->u]);
    }
    for (uint16_t j = 0; j < sc->njoints; j++) {
        const rt_joint *jt = &sc->joints[j];
        printf("  joint %s: %s", jt->name, sc->blocks[jt->b1].name);
        if (jt->b2 >= 0)
            printf(" -- %s\n", sc->blocks[jt->b2].name);
        else
            printf(" -- inertial point\n");
    }
    for (uint16_t i = 0; i < sc->ndefaults; i++) {
        const rt_default *d = &sc->defaults[i];
        printf("  %g -> %s.%s\n", (double)d->value, sc->blocks[d->block].name,
               sc->blocks[d->block].kind->u_names[d->u]);
    }
    printf("sets: %u\n", sc->nsets);
    for (uint8_t s = 0; s < sc->nsets; s++)
        printf("  %-10s %-8s step %g s (%u ticks of %g s)\n", sc->sets[s].name,
               sc->sets[s].method->name, (double)(sc->dt * (real_t)sc->sets[s].ratio),
               (unsigned)sc->sets[s].ratio, (double)sc->dt);
}

static const char *interp_name(uint8_t i)
{
    static const char *const names[] = {"set", "hold", "extrap", "linear", "hermite"};
    return i < RT_INTERP_COUNT ? names[i] : "?";
}

static uint32_t gcd(uint32_t a, uint32_t b)
{
    while (b) {
        uint32_t r = a % b;
        a = b, b = r;
    }
    return a;
}

/* the fixed schedule: step order within a tick, which sets step at which tick over one
   period of the ratios (shown up to 24 ticks), and the signals that cross sets */
static void info_schedule(const rt_scene *sc, const rt_sim *s)
{
    uint32_t period = 1; /* least common multiple of the ratios */
    for (uint8_t i = 0; i < sc->nsets; i++)
        period = period / gcd(period, sc->sets[i].ratio) * sc->sets[i].ratio;
    printf("schedule: slowest first:");
    for (uint8_t i = 0; i < sc->nsets; i++)
        printf(" %s", sc->sets[s->plan.sched[i]].name);
    printf("; period %u ticks\n", (unsigned)period);
    for (uint32_t k = 0; k < period && k < 24; k++) {
        printf("  tick %2u:", (unsigned)k);
        for (uint8_t i = 0; i < sc->nsets; i++)
            if (k % sc->sets[s->plan.sched[i]].ratio == 0)
                printf(" %s", sc->sets[s->plan.sched[i]].name);
        putchar('\n');
    }
    for (uint16_t c = 0; c < sc->nconns; c++) {
        const rt_conn *cn = &sc->conns[c];
        uint16_t gi = (uint16_t)(s->plan.u_off[cn->to] + cn->u);
        if (s->plan.src_kind[gi] != RT_SRC_XSET)
            continue;
        printf("  across sets: %s.%s -> %s.%s by %s\n", sc->blocks[cn->from].name,
               sc->blocks[cn->from].kind->y_names[cn->y], sc->blocks[cn->to].name,
               sc->blocks[cn->to].kind->u_names[cn->u], interp_name(s->plan.interp[gi]));
    }
}

/* a torn input as "From.y -> To.u" */
static void print_torn(const rt_scene *sc, const rt_sim *s, uint16_t k)
{
    uint16_t gi = s->plan.torn_in[k], src = s->plan.torn_src[k], b = 0, f = 0;
    while (b + 1 < sc->nblocks && s->plan.u_off[b + 1] <= gi)
        b++;
    while (f + 1 < sc->nblocks && s->plan.y_off[f + 1] <= src)
        f++;
    printf(" %s.%s -> %s.%s;", sc->blocks[f].name, sc->blocks[f].kind->y_names[src - s->plan.y_off[f]],
           sc->blocks[b].name, sc->blocks[b].kind->u_names[gi - s->plan.u_off[b]]);
}

static void info_order(const rt_scene *sc, const rt_sim *s)
{
    printf("evaluation order:");
    for (uint16_t i = 0; i < s->plan.nseq; i++) {
        const rt_seq_step *st = &s->plan.seq[i];
        if (st->kind == RT_SEQ_LOOP)
            printf(" [loop %u:", (unsigned)st->index);
        else
            printf(" %s", sc->blocks[st->index].name);
        for (uint8_t l = 0; l < s->plan.nloops; l++)
            if (s->plan.loops[l].actual && s->plan.loops[l].seq1 == i + 1)
                printf(" ]");
    }
    printf("\nloops: %u\n", s->plan.nloops);
    for (uint8_t l = 0; l < s->plan.nloops; l++) {
        const rt_loop *lp = &s->plan.loops[l];
        printf("  %u %s:", (unsigned)l, lp->actual ? "actual" : "potential");
        for (uint16_t i = 0; i < lp->nblocks; i++)
            printf(" %s", sc->blocks[s->plan.loop_blocks[lp->first + i]].name);
        if (lp->actual) {
            printf("; torn:");
            for (uint16_t k = lp->torn0; k < lp->torn0 + lp->ntorn; k++)
                print_torn(sc, s, k);
        } else {
            printf("; solved by ordering");
        }
        putchar('\n');
    }
}

static int cmd_info(const char *name)
{
    const rt_scene *sc = find_scene(name);
    if (!sc)
        return no_scene(name);
    rt_status st = rt_init(sc, &sim);
    printf("scene: %s\n%s\nbase tick: %g s\nend time: %g s\n", sc->name, sc->doc,
           (double)sc->dt, (double)sc->t_end);
    info_blocks(sc);
    info_wiring(sc);
    info_schedule(sc, &sim);
    info_order(sc, &sim);
    printf("recorded:");
    for (uint16_t i = 0; i < sc->nrecs; i++)
        printf(" %s.%s", sc->blocks[sc->recs[i].block].name, rt_rec_signal(sc, i));
    printf("\ninit: %s%s%s\n", rt_status_name(st), st ? ": " : "", st ? rt_error_text(&sim) : "");
    return st == RT_OK ? 0 : 1;
}

/* BLOCK.PARAM=VALUE */
static int apply_set(const rt_scene *sc, const char *arg)
{
    char buf[128];
    double v;
    if (strlen(arg) >= sizeof buf)
        return fail("--set argument too long", arg);
    strcpy(buf, arg);
    char *dot = strchr(buf, '.'), *eq = strchr(buf, '=');
    if (!dot || !eq || eq < dot)
        return fail("--set expects BLOCK.PARAM=VALUE, got", arg);
    *dot = 0, *eq = 0;
    if (!parse_real(eq + 1, &v))
        return fail("--set value is not a finite number", arg);
    if (rt_block_index(sc, buf) < 0)
        return fail("--set: unknown block", buf);
    rt_status st = rt_set_param(sc, &sim, buf, dot + 1, (real_t)v);
    if (st == RT_E_PARAM)
        return fail("--set: value out of range for the parameter", arg);
    if (st != RT_OK)
        return fail("--set: block has no parameter or state named", dot + 1);
    return 0;
}

static void summary(FILE *f, const rt_scene *sc, const rt_sim *s, rt_status st, double wall)
{
    fprintf(f, "scene: %s\nticks: %llu\nsim_time: %.17g\nwall_s: %.6f\n", sc->name,
            (unsigned long long)s->state.tick, (double)rt_time(sc, s), wall);
    fprintf(f, "status: %s\n", s->stats.status == RT_OK ? (st == RT_E_DONE ? "ok" : rt_status_name(st))
                                                  : rt_status_name(s->stats.status));
    for (int c = 0; c < RT_CNT_COUNT; c++) {
        fprintf(f, "%s: %u", rt_counter_key((rt_counter)c), (unsigned)s->stats.count[c]);
        if (s->stats.last_block[c] >= 0 && c != RT_CNT_EVENTS)
            fprintf(f, " (last %s)", sc->blocks[s->stats.last_block[c]].name);
        fputc('\n', f);
    }
    fprintf(f, "event_iter_max: %u\n", (unsigned)s->stats.event_iter_max);
    for (uint8_t k = 0; k < sc->nsets; k++)
        if (s->plan.set_xout[k])
            fprintf(f, "xset_err.%s: %g\n", sc->sets[k].name, (double)s->stats.xset_err[k]);
    if (s->plan.ntorn > 0) {
        fprintf(f, "loop_iter_max: %u\nloop_iter_hist:", (unsigned)s->stats.loop_iter_max);
        for (uint32_t i = 0; i <= s->stats.loop_iter_max; i++)
            fprintf(f, " %u", (unsigned)s->stats.loop_hist[i]);
        fprintf(f, "\nloop_residual: %g\n", (double)s->stats.loop_residual);
    }
    fprintf(f, "hash: %016llx\n", (unsigned long long)s->state.hash);
}

typedef struct run_args {
    const char *csv;
    double t_end;
    int has_t_end, realtime;
    unsigned every;
    const char *sets[MAX_SETS_ARGS];
    int nsets;
} run_args;

static int parse_run(int argc, char **argv, run_args *a)
{
    a->every = 1;
    for (int i = 3; i < argc; i++) {
        const char *o = argv[i];
        double v;
        int more = i + 1 < argc;
        if (strcmp(o, "--realtime") == 0) {
            a->realtime = 1;
        } else if (strcmp(o, "--t-end") == 0 && more) {
            if (!parse_real(argv[++i], &v) || v < 0)
                return fail("--t-end expects a time >= 0 in seconds, got", argv[i]);
            a->t_end = v, a->has_t_end = 1;
        } else if (strcmp(o, "--csv") == 0 && more) {
            a->csv = argv[++i];
        } else if (strcmp(o, "--every") == 0 && more) {
            if (!parse_real(argv[++i], &v) || v < 1 || v > 1e9 || v != (double)(unsigned)v)
                return fail("--every expects a whole number >= 1, got", argv[i]);
            a->every = (unsigned)v;
        } else if (strcmp(o, "--set") == 0 && more) {
            if (a->nsets >= MAX_SETS_ARGS)
                return fail("too many --set options", argv[i]);
            a->sets[a->nsets++] = argv[++i];
        } else {
            return fail("unknown or incomplete option", o);
        }
    }
    return 0;
}

static int cmd_run(int argc, char **argv)
{
    run_args a = {0};
    const rt_scene *base = find_scene(argv[2]);
    if (!base)
        return no_scene(argv[2]);
    if (parse_run(argc, argv, &a))
        return 2;
    rt_scene sc = *base; /* the const scene, with the end time the user asked for */
    if (a.has_t_end)
        sc.t_end = (real_t)a.t_end;
    rt_status st = rt_init(&sc, &sim);
    if (st != RT_OK)
        return fail(rt_status_name(st), rt_error_text(&sim));
    for (int i = 0; i < a.nsets; i++)
        if (apply_set(&sc, a.sets[i]))
            return 2;
    if (a.nsets > 0) /* only then: a refresh re-solves loops from a new warm start */
        rt_refresh(&sc, &sim);
    FILE *csv = NULL;
    int to_stdout = a.csv && strcmp(a.csv, "-") == 0;
    if (a.csv && !(csv = to_stdout ? stdout : fopen(a.csv, "w")))
        return fail("cannot write the CSV file", a.csv);
    port_run_opts o = {csv, a.every, a.realtime};
    port_run_result r;
    st = port_run(&sc, &sim, &o, &r);
    if (csv && !to_stdout && fclose(csv) != 0)
        return fail("error writing the CSV file", a.csv);
    summary(to_stdout ? stderr : stdout, &sc, &sim, st, r.wall_s);
    return sim.stats.status == RT_OK ? 0 : 1;
}

static unsigned at_least_1(unsigned n) { return n ? n : 1; }

/* the compile-time limits that fit this scene exactly, as -D flags for a per-scene build
   (multibody limits stay at their defaults: their workspace is sized per set) */
static int cmd_sizes(const char *name)
{
    const rt_scene *sc = find_scene(name);
    if (!sc)
        return no_scene(name);
    rt_status st = rt_init(sc, &sim);
    if (st != RT_OK)
        return fail(rt_status_name(st), rt_error_text(&sim));
    unsigned implicit = 1;
    for (uint8_t s = 0; s < sc->nsets; s++)
        if (sc->sets[s].method->implicit && (unsigned)(sim.plan.set_x[s + 1] - sim.plan.set_x[s]) > implicit)
            implicit = sim.plan.set_x[s + 1] - sim.plan.set_x[s];
    uint16_t nb = sc->nblocks;
    printf("-DRT_MAX_BLOCKS=%u -DRT_MAX_X=%u -DRT_MAX_D=%u -DRT_MAX_U=%u -DRT_MAX_Y=%u "
           "-DRT_MAX_P=%u -DRT_MAX_ROOTS=%u -DRT_MAX_SETS=%u -DRT_MAX_REC=%u "
           "-DRT_MAX_LOOPS=%u -DRT_MAX_TORN=%u -DRT_MAX_IMPLICIT_N=%u",
           at_least_1(nb), at_least_1(sim.plan.x_off[nb]), at_least_1(sim.plan.d_off[nb]),
           at_least_1(sim.plan.u_off[nb]), at_least_1(sim.plan.y_off[nb]), at_least_1(sim.plan.p_off[nb]),
           at_least_1(sim.plan.set_r[sc->nsets]), at_least_1(sc->nsets), at_least_1(sc->nrecs),
           at_least_1(sim.plan.nloops), at_least_1(sim.plan.ntorn), implicit);
    /* multibody workspace: per set, the largest velocities, coordinates, constraint rows;
       per block, the largest velocity count */
    unsigned nz = 1, nq = 1, nc = 1, bz = 1;
    for (uint8_t s = 0; sc->mbs && s < sc->nsets; s++) {
        nz = sim.work.mbs.nz[s] > nz ? sim.work.mbs.nz[s] : nz;
        nq = sim.work.mbs.nq[s] > nq ? sim.work.mbs.nq[s] : nq;
        nc = sim.work.mbs.nc[s] > nc ? sim.work.mbs.nc[s] : nc;
    }
    for (uint16_t b = 0; b < nb; b++) {
        const rt_kind *k = sc->blocks[b].kind;
        if (k->type == RT_KIND_MBS) {
            const rt_mbs_spec *m = k->spec;
            bz = m->nz > bz ? m->nz : bz;
        }
    }
    printf(" -DRT_MAX_JOINTS=%u -DRT_MAX_MBS_Z=%u -DRT_MAX_MBS_Q=%u -DRT_MAX_MBS_C=%u "
           "-DRT_MAX_MBS_BZ=%u\n", at_least_1(sc->njoints), nz, nq, nc, bz);
    return 0;
}

int main(int argc, char **argv)
{
    if (argc == 3 && strcmp(argv[1], "sizes") == 0)
        return cmd_sizes(argv[2]);
    if (argc >= 2 && strcmp(argv[1], "list") == 0 && argc == 2)
        return cmd_list();
    if (argc == 3 && strcmp(argv[1], "info") == 0)
        return cmd_info(argv[2]);
    if (argc >= 3 && strcmp(argv[1], "run") == 0)
        return cmd_run(argc, argv);
    if (argc >= 3 && strcmp(argv[1], "tune") == 0) /* tools/modrt/tune.c */
        return tune_main(find_scene(argv[2]), argc, argv);
    return usage();
}
