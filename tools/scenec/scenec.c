/* scenec.c - the scene compiler's command line: compiles a scene file to C const tables,
 * checks it, runs it in host memory (the interpreter `modrt run FILE.scn` uses), writes
 * it as an FMI 3.0 or 2.0 Co-Simulation FMU, or writes the registry of several scenes.
 * Errors go to stderr as one line
 * "FILE:LINE:COL: error: WHAT near 'TEXT'; expected WHAT", exit status 1; usage errors
 * exit with 2. Output files are written whole or not at all. */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fmu.h"
#include "fmu_export.h"
#include "fmu_scn.h"
#include "scn.h"
#include "scn_host.h"
#include "rt_sim.h" /* sizes the rt_sim it runs a scene in */

#define MAX_INPUTS 256 /* scene files of one --registry call */

typedef struct opts {
    const char *out, *deps, *symbol;
    const char *inc[8];
    int ninc;
    int fmi_version;            /* --fmu: 3, or 2 with --fmi-version 2 */
    int mode;                   /* 'c' compile, 'k' check, 'r' run, 'g' registry */
    const char *in[MAX_INPUTS];
    int nin;
} opts;

static int usage(void)
{
    fputs("usage: scenec [-I DIR]... [-o OUT.c] [-M OUT.d] FILE.scn   compile to C\n"
          "       scenec --check [-I DIR]... FILE.scn                 check only\n"
          "       scenec --run [-I DIR]... FILE.scn                   run in host memory\n"
          "       scenec --sizes [-I DIR]... FILE.scn                 the exact limits of a\n"
          "                                                           per-scene build (-D flags)\n"
          "       scenec --fmu OUT.fmu [--fmi-version 2|3] [-I DIR]... FILE.scn\n"
          "                                                           an FMI 3.0 (default) or\n"
          "                                                           2.0 Co-Simulation FMU\n"
          "                                                           (docs/fmi.md)\n"
          "       scenec --registry [--symbol NAME] -o OUT.c FILE.scn...\n",
          stderr);
    return 2;
}

static int parse_args(int argc, char **argv, opts *o)
{
    o->mode = 'c', o->symbol = "mdl_scenes", o->fmi_version = 3;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        int more = i + 1 < argc;
        if (!strcmp(a, "--check") || !strcmp(a, "--run") || !strcmp(a, "--registry"))
            o->mode = a[2] == 'c' ? 'k' : a[3] == 'u' ? 'r' : 'g';
        else if (!strcmp(a, "--sizes"))
            o->mode = 's';
        else if (!strcmp(a, "--fmu") && more)
            o->mode = 'f', o->out = argv[++i];
        else if (!strcmp(a, "--fmi-version") && more &&
                 (!strcmp(argv[i + 1], "2") || !strcmp(argv[i + 1], "3")))
            o->fmi_version = argv[++i][0] - '0';
        else if (!strcmp(a, "-o") && more)
            o->out = argv[++i];
        else if (!strcmp(a, "-M") && more)
            o->deps = argv[++i];
        else if (!strcmp(a, "--symbol") && more)
            o->symbol = argv[++i];
        else if (!strcmp(a, "-I") && more && o->ninc < 8)
            o->inc[o->ninc++] = argv[++i];
        else if (a[0] != '-' && o->nin < MAX_INPUTS)
            o->in[o->nin++] = a;
        else
            return usage();
    }
    if (o->nin == 0 || (o->mode != 'g' && o->nin != 1) || (o->mode == 'g' && !o->out))
        return usage();
    return 0;
}

static scn_ctx *compile(const opts *o, const char *path)
{
    scn_ctx *c = scn_new();
    if (!c) {
        fputs("scenec: out of memory\n", stderr);
        return NULL;
    }
    for (int i = 0; i < o->ninc; i++)
        c->incdirs[c->nincdirs++] = o->inc[i];
    /* FMU systems: loaded on the host; their C for an image or an exported FMU needs
       their sources. A registry holds library kinds and defines only */
    c->fmu = o->mode == 'g' ? NULL : &fmu_scn_ops;
    if (scn_compile(c, path, NULL, 0) == 0)
        return c;
    fprintf(stderr, "%s\n", c->msg);
    scn_free(c);
    return NULL;
}

/* opens path.tmp for writing; commit renames it over path */
static FILE *open_out(const char *path, char *tmp, size_t n)
{
    snprintf(tmp, n, "%s.tmp", path);
    FILE *f = fopen(tmp, "w");
    if (!f)
        fprintf(stderr, "scenec: cannot write %s\n", tmp);
    return f;
}

static int commit(FILE *f, int ok, const char *tmp, const char *path)
{
    ok = fclose(f) == 0 && ok;
    if (ok && rename(tmp, path) == 0)
        return 0;
    fprintf(stderr, "scenec: cannot write %s\n", path);
    remove(tmp);
    return 1;
}

/* make rules: the C file depends on the scene file and every file it includes (not on
   the text the compiler generates, such as the import block of a link: no file is there,
   so make would remake the target every time) */
static int write_deps(const scn_ctx *c, const char *deps, const char *target)
{
    char tmp[4096];
    FILE *f = open_out(deps, tmp, sizeof tmp);
    if (!f)
        return 1;
    fprintf(f, "%s:", target);
    for (uint16_t i = 0; i < c->nfiles; i++)
        if (!c->files[i].generated)
            fprintf(f, " %s", c->files[i].path);
    fputs("\n", f);
    for (uint16_t i = 1; i < c->nfiles; i++)
        if (!c->files[i].generated)
            fprintf(f, "%s:\n", c->files[i].path);
    return commit(f, !ferror(f), tmp, deps);
}

static int cmd_compile(const opts *o)
{
    char tmp[4096];
    scn_ctx *c = compile(o, o->in[0]);
    if (!c)
        return 1;
    int rc = 0;
    if (o->mode == 'c' && !o->out) {
        rc = scn_emit(c, stdout) != 0;
    } else if (o->mode == 'c') {
        FILE *f = open_out(o->out, tmp, sizeof tmp);
        int ok = f && scn_emit(c, f) == 0;
        if (f && !ok && c->err) /* what stopped the C (an FMU without sources): not written */
            fprintf(stderr, "%s\n", c->msg), fclose(f), remove(tmp), rc = 1;
        else
            rc = !f || commit(f, ok, tmp, o->out);
        if (!rc && o->deps)
            rc = write_deps(c, o->deps, o->out);
    }
    if (rc && c->err && !o->out)
        fprintf(stderr, "%s\n", c->msg);
    scn_free(c);
    return rc;
}

/* as `modrt run` does: rt_init, a record at t = 0 and after every tick, the summary */
static int cmd_run(const opts *o)
{
    scn_ctx *c = compile(o, o->in[0]);
    if (!c)
        return 1;
    rt_scene *sc = &c->image;
    rt_sim *sim = scn_alloc(c, sizeof *sim); /* a fresh one, as modrt's static storage */
    rt_status st = rt_init(sc, sim);
    if (st == RT_OK) {
        rt_record(sc, sim, NULL);
        while (rt_tick(sc, sim) != RT_E_DONE)
            rt_record(sc, sim, NULL);
        rt_record(sc, sim, NULL);
    }
    printf("scene: %s\nticks: %llu\nstatus: %s\nhash: %016llx\n", sc->name,
           (unsigned long long)rt_ticks_done(sim),
           rt_status_name(st != RT_OK ? st : rt_stats_of(sim)->status),
           (unsigned long long)rt_trace_hash(sim));
    int rc = st != RT_OK || rt_stats_of(sim)->status != RT_OK;
    scn_free(c);
    return rc;
}

/* the scene as an FMI 3.0 or 2.0 Co-Simulation FMU (tools/fmi/fmu_export.c) */
static int cmd_fmu(const opts *o)
{
    char err[SCN_MSG_LEN];
    scn_ctx *c = compile(o, o->in[0]);
    if (!c)
        return 1;
    int rc = fmu_export(c, o->out, o->fmi_version, err, sizeof err);
    if (rc)
        fprintf(stderr, "scenec: %s: %s\n", o->out, err);
    scn_free(c);
    return rc ? 1 : 0;
}

/* the exact compile-time limits of a per-scene build, as -D flags (docs/porting.md) */
static int cmd_sizes(const opts *o)
{
    scn_ctx *c = compile(o, o->in[0]);
    if (!c)
        return 1;
    rt_sim *sim = scn_alloc(c, sizeof *sim);
    rt_status st = rt_init(&c->image, sim);
    if (st == RT_OK) /* the limits, then an image's FMU arena (docs/fmi.md) */
        fmu_scn_sizes(stdout, stderr, o->in[0], &c->image, sim);
    else
        fprintf(stderr, "%s: error: %s: %s\n", o->in[0], rt_status_name(st), rt_error_text(sim));
    scn_free(c);
    return st != RT_OK;
}

static int cmd_registry(const opts *o)
{
    char tmp[4096], names[MAX_INPUTS][SCN_MAX_NAME + 1];
    for (int n = 0; n < o->nin; n++) {
        scn_ctx *c = compile(o, o->in[n]);
        if (!c)
            return 1;
        snprintf(names[n], sizeof names[n], "%s", c->sc.name.s);
        scn_free(c);
        for (int i = 0; i < n; i++)
            if (!strcmp(names[i], names[n])) {
                fprintf(stderr, "%s:1:1: error: scene name used twice near '%s'; expected "
                        "one scene file per name (also %s)\n", o->in[n], names[n], o->in[i]);
                return 1;
            }
    }
    FILE *f = open_out(o->out, tmp, sizeof tmp);
    if (!f)
        return 1;
    fputs("/* registry.c - the scenes compiled by scenec, one row per scene file; "
          "generated. */\n#include \"models.h\"\n\n", f);
    for (int i = 0; i < o->nin; i++)
        fprintf(f, "extern const rt_scene " SCN_SYMBOL_PREFIX "%s;\n", names[i]);
    fprintf(f, "\nconst rt_scene_entry %s[] = {\n", o->symbol);
    for (int i = 0; i < o->nin; i++)
        fprintf(f, "    {\"%s\", &" SCN_SYMBOL_PREFIX "%s},\n", names[i], names[i]);
    fputs("    {0, 0},\n};\n", f);
    return commit(f, !ferror(f), tmp, o->out);
}

int main(int argc, char **argv)
{
    opts o;
    memset(&o, 0, sizeof o);
    if (parse_args(argc, argv, &o))
        return 2;
    if (o.mode == 'r')
        return cmd_run(&o);
    if (o.mode == 'g')
        return cmd_registry(&o);
    if (o.mode == 's')
        return cmd_sizes(&o);
    if (o.mode == 'f')
        return cmd_fmu(&o);
    return cmd_compile(&o);
}
