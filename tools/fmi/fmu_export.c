/* fmu_export.c - `scenec --fmu OUT.fmu [--fmi-version 2] FILE.scn`: a scene as an FMI 3.0
 * or 2.0 Co-Simulation FMU (docs/fmi.md, "Export"). The FMU holds its sources (the runtime,
 * the model library, the scene as scenec writes it, fmu_cs_id.h naming it, the slave of
 * tools/fmi/cs/cs_slave.c with the FMI functions of fmi3cs.c or fmi2cs.c, and
 * buildDescription.xml naming them) and a binary for this host built from exactly those
 * sources, and a modelDescription.xml whose variables follow fmu_cs_vars.h, the numbering
 * the FMU's code serves. Written under a temporary name, renamed when whole. */
#define _XOPEN_SOURCE 700
#include "fmu_export.h"

#include <dirent.h>
#include <errno.h>
#include <ftw.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>
#include <zip.h>

#include "fmu_cs_vars.h"
#include "fmu_int.h" /* the scene's FMU blocks: their models' descriptions */
#include "fmu_scn.h"

#ifndef MODRT_SRC_DIR
#define MODRT_SRC_DIR "."
#endif

#define EX_MAX_SRCS 400    /* source files of an exported FMU */
#define EX_MAX_INCS 64     /* include directories of its FMU blocks' sources */
#define EX_MAX_FMUS 16     /* distinct FMUs (model identifiers) of its FMU blocks */
#define EX_PATH 4300       /* characters of a path in the FMU's tree */

typedef struct ex {
    scn_ctx *c;
    const rt_scene *sc;
    int version;            /* FMI 2 or 3 */
    char dir[4096];         /* the FMU's tree before zipping */
    char *err;
    size_t errlen;
    char token[96];
    const char *srcs[EX_MAX_SRCS]; /* the files of sources/ */
    int nsrcs;
    const char *incs[EX_MAX_INCS]; /* include directories of the FMU blocks' sources */
    int nincs;
    int nfmu;               /* FMU blocks (their sources compiled in, "inner" below) */
    int can_state;          /* every FMU block can save its state */
} ex;

static int fail(ex *e, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(e->err, e->errlen, fmt, ap);
    va_end(ap);
    return -1;
}

/* creates file `rel` of the FMU's tree for writing, its path into p[EX_PATH]; NULL with the
   message in e->err */
static FILE *create(ex *e, char *p, const char *rel)
{
    snprintf(p, EX_PATH, "%s/%s", e->dir, rel);
    FILE *f = fopen(p, "w");
    if (!f)
        fail(e, "cannot write %s", p);
    return f;
}

static int copy(ex *e, const char *from, const char *to)
{
    FILE *in = fopen(from, "rb"), *out = in ? fopen(to, "wb") : NULL;
    char buf[65536];
    size_t n;
    int rc = in && out ? 0 : -1;
    while (rc == 0 && (n = fread(buf, 1, sizeof buf, in)) > 0)
        rc = fwrite(buf, 1, n, out) == n ? 0 : -1;
    if (in)
        fclose(in);
    if (out && fclose(out) != 0)
        rc = -1;
    return rc ? fail(e, "cannot copy %s to %s: %s", from, to, strerror(errno)) : 0;
}

/* the .c and .h files of one source directory into sources/ */
static int copy_dir(ex *e, const char *sub)
{
    char from[4200], to[EX_PATH];
    snprintf(from, sizeof from, "%s/%s", MODRT_SRC_DIR, sub);
    DIR *d = opendir(from);
    struct dirent *de;
    if (!d)
        return fail(e, "cannot read %s (the modrt sources the FMU is built from)", from);
    snprintf(to, sizeof to, "%s/sources/%s", e->dir, sub);
    int rc = mkdir(to, 0755) == 0 ? 0 : fail(e, "cannot create %s: %s", to, strerror(errno));
    while (rc == 0 && (de = readdir(d))) {
        size_t n = strlen(de->d_name);
        int c = n > 2 && !strcmp(de->d_name + n - 2, ".c");
        if (!c && !(n > 2 && !strcmp(de->d_name + n - 2, ".h")))
            continue;
        snprintf(from, sizeof from, "%s/%s/%s", MODRT_SRC_DIR, sub, de->d_name);
        snprintf(to, sizeof to, "%s/sources/%s/%s", e->dir, sub, de->d_name);
        rc = copy(e, from, to);
        if (c && rc == 0 && e->nsrcs >= EX_MAX_SRCS - 16)
            rc = fail(e, "more than %d source files in %s", EX_MAX_SRCS - 16, sub);
        else if (c && rc == 0)
            e->srcs[e->nsrcs++] = scn_fmt(e->c, "%s/%s", sub, de->d_name);
    }
    closedir(d);
    return rc;
}

/* FNV-1a 64 over a file: the instantiation token ties the description to the binary */
static unsigned long long hash_file(const char *path)
{
    FILE *f = fopen(path, "rb");
    unsigned long long h = 0xcbf29ce484222325ull;
    int ch;
    while (f && (ch = fgetc(f)) != EOF)
        h = (h ^ (unsigned char)ch) * 0x100000001b3ull;
    if (f)
        fclose(f);
    return h;
}

/* ------------------------------------------------------------------ FMU blocks */

/* a directory tree (regular files and directories) copied */
static int copy_tree(ex *e, const char *from, const char *to)
{
    DIR *d = opendir(from);
    struct dirent *de;
    if (!d)
        return fail(e, "cannot read %s", from);
    int rc = mkdir(to, 0755) == 0 ? 0 : fail(e, "cannot create %s: %s", to, strerror(errno));
    while (rc == 0 && (de = readdir(d))) {
        if (!strcmp(de->d_name, ".") || !strcmp(de->d_name, ".."))
            continue;
        char *f = scn_fmt(e->c, "%s/%s", from, de->d_name), *t = scn_fmt(e->c, "%s/%s", to, de->d_name);
        struct stat st;
        if (lstat(f, &st) != 0)
            rc = fail(e, "cannot stat %s", f);
        else if (S_ISDIR(st.st_mode))
            rc = copy_tree(e, f, t);
        else if (S_ISREG(st.st_mode))
            rc = copy(e, f, t);
    }
    closedir(d);
    return rc;
}

/* the importer's calling sequence (fmu_inst.c, fmu_state.c, fmu_call.c, fmu_arena.c)
   under sources/fmi/, each compiled through a unit at the root that builds it as an image
   does (FMU_TARGET: the FMU's functions bound statically, its memory the static arena of
   FMU_ARENA_BYTES bytes scenec measured), whatever the importer defines */
static int importer(ex *e)
{
    static const char *const c[] = {"fmu_inst.c", "fmu_state.c", "fmu_call.c", "fmu_arena.c"};
    static const char *const h[] = {"fmu_int.h", "fmu.h", "fmu_md.h"};
    char from[4200], to[EX_PATH];
    snprintf(to, sizeof to, "%s/sources/fmi", e->dir);
    if (mkdir(to, 0755) != 0)
        return fail(e, "cannot create %s: %s", to, strerror(errno));
    long arena = fmu_scn_sizes(NULL, NULL, NULL, e->sc, e->c->sim); /* as scenec --sizes */
    for (int i = 0; i < 7; i++) {
        const char *n = i < 4 ? c[i] : h[i - 4];
        snprintf(from, sizeof from, "%s/tools/fmi/%s", MODRT_SRC_DIR, n);
        snprintf(to, sizeof to, "%s/sources/%s%s", e->dir, i < 4 ? "fmi/" : "", n);
        if (copy(e, from, to))
            return -1;
        if (i >= 4)
            continue;
        const char *unit = scn_fmt(e->c, "fmu_blocks_%s", n + 4);
        snprintf(to, sizeof to, "%s/sources/%s", e->dir, unit);
        FILE *f = fopen(to, "w");
        if (!f)
            return fail(e, "cannot write %s", to);
        fprintf(f, "/* %s - written by scenec --fmu: fmi/%s for the FMU blocks, built as an "
                   "image builds it */\n#define FMU_TARGET 1\n", unit, n);
        if (arena > 0)
            fprintf(f, "#define FMU_ARENA_BYTES %ld\n", arena);
        fprintf(f, "#include \"fmi/%s\"\n", n);
        if (fclose(f) != 0)
            return fail(e, "cannot write %s", to);
        e->srcs[e->nsrcs++] = unit;
    }
    return 0;
}

/* one source file of an FMU block's FMU, compiled through a unit of its own that fixes
   what its FMI functions are named (<ID>_fmi3GetFloat64 ...: FMI*_FUNCTION_PREFIX, never
   the plain names the exported FMU's own functions have, whatever the importer of the
   exported FMU defines), its definitions and (FMI 3.0) its calloc, malloc and free: the
   static arena */
static int inner_unit(ex *e, int ver, const char *id, int k, const char *file, const char *defs)
{
    const char *unit = scn_fmt(e->c, "fmu_%s_%d.c", id, k);
    char p[EX_PATH];
    FILE *f = create(e, p, scn_fmt(e->c, "sources/%s", unit));
    if (!f)
        return -1;
    fprintf(f, "/* %s - written by scenec --fmu: %s of the FMU %s, its functions named "
               "%s_fmi%d... */\n#undef FMI2_OVERRIDE_FUNCTION_PREFIX\n"
               "#undef FMI3_OVERRIDE_FUNCTION_PREFIX\n#undef FMI3_ACTUAL_FUNCTION_PREFIX\n"
               "#define FMI%d_FUNCTION_PREFIX %s_\n", unit, file, id, id, ver, ver, id);
    if (ver == 3)
        fputs("#define calloc fmu_arena_calloc\n#define malloc fmu_arena_malloc\n"
              "#define free fmu_arena_free\n", f);
    fputs(defs, f);
    fprintf(f, "#include \"fmu_%s/%s\"\n", id, file);
    if (fclose(f) != 0)
        return fail(e, "cannot write %s", p);
    if (e->nsrcs >= EX_MAX_SRCS)
        return fail(e, "more than %d source files", EX_MAX_SRCS);
    e->srcs[e->nsrcs++] = unit;
    return 0;
}

/* one "// fmu-build: BLOCK VERSION ID SOURCES WORDS..." line of scene.c (fmu_emit.c):
   the FMU's sources copied to sources/fmu_ID/ once per model identifier, each file
   compiled through its unit (inner_unit) */
static int inner_block(ex *e, char *line, char ids[][128], char dirs[][4096], int *nids)
{
    char blk[128], id[128], src[4096];
    int ver, at = 0;
    if (sscanf(line, "// fmu-build: %127s %d %127s %4095s %n", blk, &ver, id, src, &at) != 4 || !at)
        return fail(e, "scene.c: an fmu-build line scenec cannot read: %s", line);
    for (int i = 0; i < *nids; i++)
        if (!strcmp(ids[i], id))
            return strcmp(dirs[i], src) == 0 ? 0 /* the same FMU in another block */
                 : fail(e, "FMU block %s: another FMU of the scene has its model identifier %s "
                        "(the functions of both would have one name)", blk, id);
    if (*nids >= EX_MAX_FMUS)
        return fail(e, "FMU block %s: more than %d distinct FMUs", blk, EX_MAX_FMUS);
    snprintf(ids[*nids], 128, "%s", id), snprintf(dirs[*nids], 4096, "%s", src), ++*nids;
    char to[EX_PATH];
    snprintf(to, sizeof to, "%s/sources/fmu_%s", e->dir, id);
    if (copy_tree(e, src, to))
        return -1;
    char defs[2048] = "", *w, *save = NULL, files[16384];
    size_t nd = 0;
    snprintf(files, sizeof files, "%s", line + at); /* (strtok_r cuts the line) */
    for (w = strtok_r(line + at, " \n", &save); w; w = strtok_r(NULL, " \n", &save))
        if (!strncmp(w, "-D", 2)) {
            char *eq = strchr(w, '=');
            nd += (size_t)snprintf(defs + nd, sizeof defs - (nd < sizeof defs ? nd : sizeof defs),
                                   "#define %.*s %s\n", eq ? (int)(eq - w - 2) : (int)strlen(w + 2),
                                   w + 2, eq ? eq + 1 : "1");
        } else if (!strncmp(w, "-I", 2) && e->nincs < EX_MAX_INCS)
            e->incs[e->nincs++] = scn_fmt(e->c, "fmu_%s/%s", id, w + 2);
    if (nd >= sizeof defs)
        return fail(e, "FMU block %s: too many definitions", blk);
    if (e->nincs >= EX_MAX_INCS)
        return fail(e, "FMU block %s: more than %d include directories", blk, EX_MAX_INCS - 1);
    e->incs[e->nincs++] = scn_fmt(e->c, "fmu_%s", id);
    save = NULL;
    int k = 0;
    for (w = strtok_r(files, " \n", &save); w; w = strtok_r(NULL, " \n", &save))
        if (w[0] != '-' && inner_unit(e, ver, id, ++k, w, defs))
            return -1;
    return 0;
}

/* the scene's FMU blocks (docs/fmi.md, "FMU blocks in an exported FMU"): fmu_emit.c wrote
   them into scene.c with their build lines, which are read back here as tools/image.sh
   reads them; whether every one can save its state decides the FMU's capability flags */
static int inner(ex *e, const char *scene_c)
{
    e->can_state = 1;
    for (uint16_t i = 0; i < e->c->sc.nblk; i++)
        if (e->c->sc.blk[i].fmu) {
            const fmu_inst *in = e->c->sc.blk[i].kind->spec;
            e->nfmu++, e->can_state &= in->m->md.can_state;
        }
    if (!e->nfmu)
        return 0;
    FILE *f = fopen(scene_c, "r");
    if (!f)
        return fail(e, "cannot read %s", scene_c);
    static char line[16384], ids[EX_MAX_FMUS][128], dirs[EX_MAX_FMUS][4096];
    int nids = 0, rc = importer(e);
    while (rc == 0 && fgets(line, sizeof line, f))
        if (!strncmp(line, "// fmu-build: ", 14))
            rc = inner_block(e, line, ids, dirs, &nids);
    fclose(f);
    return rc;
}

static int sources(ex *e)
{
    char p[EX_PATH];
    snprintf(p, sizeof p, "%s/sources", e->dir);
    if (mkdir(p, 0755) != 0)
        return fail(e, "cannot create %s: %s", p, strerror(errno));
    if (copy_dir(e, "rt") || copy_dir(e, "models"))
        return -1;
    const char *fmi = e->version == 2 ? "fmi2cs.c" : "fmi3cs.c";
    const char *own[] = {fmi, "cs_slave.c", "cs_slave.h", "fmu_cs_vars.h", "../fmi_api.h"};
    for (int i = 0; i < 5; i++) {
        char from[4200];
        snprintf(from, sizeof from, "%s/tools/fmi/cs/%s", MODRT_SRC_DIR, own[i]);
        const char *name = strrchr(own[i], '/') ? strrchr(own[i], '/') + 1 : own[i];
        snprintf(p, sizeof p, "%s/sources/%s", e->dir, name);
        if (copy(e, from, p))
            return -1;
    }
    e->srcs[e->nsrcs++] = fmi, e->srcs[e->nsrcs++] = "cs_slave.c";
    FILE *f = create(e, p, "sources/scene.c");
    int emitted = f && scn_emit(e->c, f) == 0;
    if (f)
        emitted = fclose(f) == 0 && emitted;
    if (!emitted) /* what stopped the C (an FMU block without sources), else the file */
        return e->c->err ? fail(e, "%s", e->c->msg) : fail(e, "cannot write %s", p);
    e->srcs[e->nsrcs++] = "scene.c";
    if (inner(e, p) != 0)
        return -1;
    snprintf(e->token, sizeof e->token, "{modrt-%s-%016llx}", e->sc->name, hash_file(p));
    /* which scene the FMI functions serve, under which token and names */
    f = create(e, p, "sources/fmu_cs_id.h");
    if (!f)
        return -1;
    fprintf(f, "/* fmu_cs_id.h - written by scenec --fmu: the scene this FMU serves */\n"
               "#define FMU_CS_SCENE %s%s\n#define FMU_CS_TOKEN \"%s\"\n"
               "#define FMI%d_FUNCTION_PREFIX %s_\n",
            SCN_SYMBOL_PREFIX, e->sc->name, e->token, e->version, e->sc->name);
    if (e->nfmu) /* its FMU blocks are static instances (cs_claim) */
        fputs("#define FMU_CS_ONCE 1\n", f);
    return fclose(f) == 0 ? 0 : fail(e, "cannot write %s", p);
}

static int build_description(ex *e)
{
    char p[EX_PATH];
    FILE *f = create(e, p, "sources/buildDescription.xml");
    if (!f)
        return -1;
    fprintf(f, "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<fmiBuildDescription fmiVersion=\"3.0\">\n"
               "  <BuildConfiguration modelIdentifier=\"%s\">\n"
               "    <SourceFileSet language=\"C11\" compilerOptions=\"-ffp-contract=off "
               "-fno-math-errno\">\n", e->sc->name);
    for (int i = 0; i < e->nsrcs; i++)
        fprintf(f, "      <SourceFile name=\"%s\"/>\n", e->srcs[i]);
    fputs("      <IncludeDirectory name=\".\"/>\n      <IncludeDirectory name=\"rt\"/>\n"
          "      <IncludeDirectory name=\"models\"/>\n", f);
    for (int i = 0; i < e->nincs; i++)
        fprintf(f, "      <IncludeDirectory name=\"%s\"/>\n", e->incs[i]);
    fputs("    </SourceFileSet>\n"
          "    <Library name=\"m\"/>\n  </BuildConfiguration>\n</fmiBuildDescription>\n", f);
    return fclose(f) == 0 ? 0 : fail(e, "cannot write %s", p);
}

/* the binary for this host from the sources just written */
static int compile(ex *e)
{
    char out[EX_PATH];
    const char *plat = e->version == 2 ? "linux64" : "x86_64-linux";
    snprintf(out, sizeof out, "%s/binaries/%s", e->dir, plat);
    char *mk = scn_fmt(e->c, "%s/binaries", e->dir);
    if (mkdir(mk, 0755) != 0 || mkdir(out, 0755) != 0)
        return fail(e, "cannot create %s", out);
    snprintf(out, sizeof out, "%s/binaries/%s/%s.so", e->dir, plat, e->sc->name);
    const char *cc = getenv("CC") && *getenv("CC") ? getenv("CC") : "cc";
    const char *argv[EX_MAX_SRCS + EX_MAX_INCS + 32];
    int n = 0;
    argv[n++] = cc;
    const char *flags[] = {"-std=c11", "-O2", "-fPIC", "-shared", "-ffp-contract=off",
                           "-fno-math-errno", "-fvisibility=hidden", "-w", "-I.", "-Irt",
                           "-Imodels"};
    for (size_t i = 0; i < sizeof flags / sizeof *flags; i++)
        argv[n++] = flags[i];
    /* a shared object: the functions' plain names */
    argv[n++] = e->version == 2 ? "-DFMI2_OVERRIDE_FUNCTION_PREFIX" : "-DFMI3_OVERRIDE_FUNCTION_PREFIX";
    for (int i = 0; i < e->nincs; i++)
        argv[n++] = scn_fmt(e->c, "-I%s", e->incs[i]);
    for (int i = 0; i < e->nsrcs; i++)
        argv[n++] = e->srcs[i];
    argv[n++] = "-o", argv[n++] = out, argv[n++] = "-lm", argv[n] = NULL;
    pid_t pid = fork();
    if (pid == 0) {
        char src[EX_PATH];
        snprintf(src, sizeof src, "%s/sources", e->dir);
        if (chdir(src) == 0)
            execvp(cc, (char *const *)argv);
        _exit(127);
    }
    int st = 0;
    if (pid < 0 || waitpid(pid, &st, 0) < 0 || !WIFEXITED(st) || WEXITSTATUS(st) != 0)
        return fail(e, "%s failed building the FMU's binary from its sources (exit %d)", cc,
                    WIFEXITED(st) ? WEXITSTATUS(st) : -1);
    return 0;
}

/* ------------------------------------------------------------------ modelDescription.xml */

static void xml_text(FILE *f, const char *s)
{
    for (; *s; s++)
        if (*s == '&' || *s == '<' || *s == '>' || *s == '"')
            fputs(*s == '&' ? "&amp;" : *s == '<' ? "&lt;" : *s == '>' ? "&gt;" : "&quot;", f);
        else
            fputc(*s, f);
}

static const char *real(char *buf, double v)
{
    for (int prec = 1; prec <= 17; prec++) { /* the shortest text that reads back as v */
        snprintf(buf, 32, "%.*g", prec, v);
        if (strtod(buf, NULL) == v)
            break;
    }
    return buf;
}

/* the unit of port `index` of a kind's units string (inputs, outputs, states, discrete
   states, parameters), or NULL for none or "-" */
static const char *unit_of(scn_ctx *c, const rt_kind *k, unsigned index)
{
    const char *s = k->units;
    for (unsigned i = 0; s && *s; i++) {
        while (*s == ' ')
            s++;
        size_t n = strcspn(s, " ");
        if (i == index)
            return n == 0 || (n == 1 && *s == '-') ? NULL : scn_strndup(c, s, n);
        s += n;
    }
    return NULL;
}

static unsigned sig_index(const rt_kind *k, const rt_rec *r)
{
    return r->what == RT_SIG_X ? k->nu + k->ny + r->index
         : r->what == RT_SIG_D ? k->nu + k->ny + k->nx + r->index : k->nu + r->index;
}

/* name, unit and the attributes of variable vr */
typedef struct xvar {
    const char *name, *unit, *causality, *variability;
    int has_start;
    double start;
} xvar;

static xvar describe(scn_ctx *c, const rt_scene *sc, uint32_t vr)
{
    fmu_cs_var v = fmu_cs_at(sc, vr);
    xvar x = {"time", "s", "independent", "continuous", 0, 0};
    const rt_rec *r = NULL;
    if (v.kind == FMU_CS_REC)
        r = &sc->recs[v.a];
    else if (v.kind == FMU_CS_EXP)
        r = &sc->link->exp[v.a];
    if (r) {
        const rt_kind *k = sc->blocks[r->block].kind;
        x.name = scn_fmt(c, "%s%s.%s", v.kind == FMU_CS_EXP ? "export." : "",
                         sc->blocks[r->block].name, fmu_cs_signal(sc, r));
        x.unit = r->what == RT_SIG_MBS ? NULL : unit_of(c, k, sig_index(k, r));
        x.causality = "output";
        x.variability = r->what == RT_SIG_D || k->type == RT_KIND_DSS ? "discrete" : "continuous";
    } else if (v.kind == FMU_CS_IMP) {
        x.name = c->sc.limp[v.a].name.s, x.unit = NULL;
        x.causality = "input", x.variability = "continuous";
        x.has_start = 1, x.start = (double)sc->link->def[v.a];
    } else if (v.kind == FMU_CS_PAR) {
        const rt_kind *k = sc->blocks[v.a].kind;
        x.name = scn_fmt(c, "%s.%s", sc->blocks[v.a].name, k->p_names[v.b]);
        x.unit = unit_of(c, k, k->nu + k->ny + k->nx + k->nd + v.b);
        x.causality = "parameter", x.variability = "tunable";
        x.has_start = 1, x.start = (double)fmu_cs_param0(sc, v.a, v.b);
    }
    return x;
}

/* every unit of the variables once, into units[]; their number */
static int units_of(ex *e, const char **units, int max)
{
    int nu = 0;
    for (uint32_t vr = 0; vr < fmu_cs_count(e->sc); vr++) {
        xvar x = describe(e->c, e->sc, vr);
        int seen = !x.unit;
        for (int i = 0; !seen && i < nu; i++)
            seen = !strcmp(units[i], x.unit);
        if (!seen && nu < max)
            units[nu++] = x.unit;
    }
    return nu;
}

static void unit_definitions(ex *e, FILE *f)
{
    const char *units[1024];
    int nu = units_of(e, units, 1024);
    fputs("  <UnitDefinitions>\n", f);
    for (int i = 0; i < nu; i++) {
        fputs("    <Unit name=\"", f);
        xml_text(f, units[i]);
        fputs("\"/>\n", f);
    }
    fputs("  </UnitDefinitions>\n", f);
}

static void default_experiment(ex *e, FILE *f)
{
    char b1[32], b2[32];
    fprintf(f, "  <DefaultExperiment startTime=\"0\" stopTime=\"%s\" stepSize=\"%s\"/>\n",
            real(b1, (double)e->sc->t_end), real(b2, (double)e->sc->dt));
}

/* the attributes a variable's type element carries: start and unit */
static void start_unit(FILE *f, const xvar *x)
{
    char b[32];
    if (x->has_start)
        fprintf(f, " start=\"%s\"", real(b, x->start));
    if (x->unit) {
        fputs(" unit=\"", f);
        xml_text(f, x->unit);
        fputc('"', f);
    }
}

static const char *flag(int on) { return on ? "true" : "false"; }

static void md3(ex *e, FILE *f)
{
    const rt_scene *sc = e->sc;
    char b1[32];
    fprintf(f, "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<fmiModelDescription "
               "fmiVersion=\"3.0\" modelName=\"%s\" instantiationToken=\"%s\" description=\"",
            sc->name, e->token);
    xml_text(f, sc->doc ? sc->doc : "");
    fprintf(f, "\" generationTool=\"modrt scenec --fmu\">\n  <CoSimulation modelIdentifier=\"%s\" "
               "canHandleVariableCommunicationStepSize=\"true\" fixedInternalStepSize=\"%s\" "
               "canBeInstantiatedOnlyOncePerProcess=\"%s\" "
               "canGetAndSetFMUState=\"%s\" canSerializeFMUState=\"%s\" "
               "hasEventMode=\"false\" providesIntermediateUpdate=\"false\" "
               "mightReturnEarlyFromDoStep=\"false\"/>\n", sc->name, real(b1, (double)sc->dt),
            flag(e->nfmu > 0), flag(e->can_state), flag(e->can_state));
    unit_definitions(e, f);
    default_experiment(e, f);
    fputs("  <ModelVariables>\n", f);
    for (uint32_t vr = 0; vr < fmu_cs_count(sc); vr++) {
        xvar x = describe(e->c, sc, vr);
        fputs("    <Float64 name=\"", f);
        xml_text(f, x.name);
        fprintf(f, "\" valueReference=\"%u\" causality=\"%s\" variability=\"%s\"", (unsigned)vr,
                x.causality, x.variability);
        start_unit(f, &x);
        fputs("/>\n", f);
    }
    fputs("  </ModelVariables>\n  <ModelStructure>\n", f);
    for (uint32_t vr = 1; vr <= sc->nrecs + fmu_cs_nexp(sc); vr++)
        fprintf(f, "    <Output valueReference=\"%u\"/>\n", (unsigned)vr);
    for (uint32_t vr = 1; vr <= sc->nrecs + fmu_cs_nexp(sc); vr++)
        fprintf(f, "    <InitialUnknown valueReference=\"%u\"/>\n", (unsigned)vr);
    fputs("  </ModelStructure>\n</fmiModelDescription>\n", f);
}

/* FMI 2.0: variables are ScalarVariable elements in value-reference order, so variable
   vr is ModelStructure's index vr + 1; the outputs (calculated) are also the initial
   unknowns; the sources are listed in <SourceFiles> and, with their include directories,
   in sources/buildDescription.xml (which FMI 2.0.4 lets take precedence) */
static void md2(ex *e, FILE *f)
{
    const rt_scene *sc = e->sc;
    uint32_t nout = sc->nrecs + fmu_cs_nexp(sc);
    fprintf(f, "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<fmiModelDescription "
               "fmiVersion=\"2.0\" modelName=\"%s\" guid=\"%s\" description=\"", sc->name, e->token);
    xml_text(f, sc->doc ? sc->doc : "");
    fprintf(f, "\" generationTool=\"modrt scenec --fmu\" variableNamingConvention=\"flat\" "
               "numberOfEventIndicators=\"0\">\n  <CoSimulation modelIdentifier=\"%s\" "
               "canHandleVariableCommunicationStepSize=\"true\" canInterpolateInputs=\"false\" "
               "maxOutputDerivativeOrder=\"0\" canBeInstantiatedOnlyOncePerProcess=\"%s\" "
               "canGetAndSetFMUstate=\"%s\" canSerializeFMUstate=\"%s\" "
               "canNotUseMemoryManagementFunctions=\"false\" "
               "providesDirectionalDerivative=\"false\">\n    <SourceFiles>\n", sc->name,
            flag(e->nfmu > 0), flag(e->can_state), flag(e->can_state));
    for (int i = 0; i < e->nsrcs; i++)
        fprintf(f, "      <File name=\"%s\"/>\n", e->srcs[i]);
    fputs("    </SourceFiles>\n  </CoSimulation>\n", f);
    unit_definitions(e, f);
    fputs("  <LogCategories>\n    <Category name=\"logStatusWarning\" description=\"a step the "
          "runtime doubts\"/>\n    <Category name=\"logStatusError\" description=\"a call "
          "refused or a step failed\"/>\n  </LogCategories>\n", f);
    default_experiment(e, f);
    fputs("  <ModelVariables>\n", f);
    for (uint32_t vr = 0; vr < fmu_cs_count(sc); vr++) {
        xvar x = describe(e->c, sc, vr);
        fputs("    <ScalarVariable name=\"", f);
        xml_text(f, x.name);
        fprintf(f, "\" valueReference=\"%u\" causality=\"%s\" variability=\"%s\">\n      <Real",
                (unsigned)vr, x.causality, x.variability);
        start_unit(f, &x);
        fputs("/>\n    </ScalarVariable>\n", f);
    }
    fputs("  </ModelVariables>\n  <ModelStructure>\n", f);
    for (int list = 0; list < 2 && nout > 0; list++) {
        fprintf(f, "    <%s>\n", list ? "InitialUnknowns" : "Outputs");
        for (uint32_t vr = 1; vr <= nout; vr++)
            fprintf(f, "      <Unknown index=\"%u\"/>\n", (unsigned)vr + 1);
        fprintf(f, "    </%s>\n", list ? "InitialUnknowns" : "Outputs");
    }
    fputs("  </ModelStructure>\n</fmiModelDescription>\n", f);
}

static int model_description(ex *e)
{
    char p[EX_PATH];
    FILE *f = create(e, p, "modelDescription.xml");
    if (!f)
        return -1;
    if (e->version == 2)
        md2(e, f);
    else
        md3(e, f);
    return fclose(f) == 0 ? 0 : fail(e, "cannot write %s", p);
}

/* ------------------------------------------------------------------ the archive */

static int zip_tree(ex *e, zip_t *z, const char *rel)
{
    char p[4400];
    snprintf(p, sizeof p, "%s%s%s", e->dir, *rel ? "/" : "", rel);
    DIR *d = opendir(p);
    struct dirent *de;
    int rc = d ? 0 : fail(e, "cannot read %s", p);
    while (rc == 0 && d && (de = readdir(d))) {
        if (de->d_name[0] == '.')
            continue;
        char *r = scn_fmt(e->c, "%s%s%s", rel, *rel ? "/" : "", de->d_name);
        char *full = scn_fmt(e->c, "%s/%s", e->dir, r);
        struct stat st;
        if (stat(full, &st) != 0)
            rc = fail(e, "cannot stat %s", full);
        else if (S_ISDIR(st.st_mode))
            rc = zip_dir_add(z, r, ZIP_FL_ENC_UTF_8) < 0 ? fail(e, "zip: %s", zip_strerror(z))
                                                         : zip_tree(e, z, r);
        else {
            zip_source_t *s = zip_source_file(z, full, 0, -1);
            if (!s || zip_file_add(z, r, s, ZIP_FL_ENC_UTF_8) < 0) {
                zip_source_free(s);
                rc = fail(e, "zip: %s", zip_strerror(z));
            }
        }
    }
    if (d)
        closedir(d);
    return rc;
}

static int archive(ex *e, const char *out)
{
    char *tmp = scn_fmt(e->c, "%s.tmp%ld", out, (long)getpid());
    int ze = 0;
    remove(tmp);
    zip_t *z = zip_open(tmp, ZIP_CREATE | ZIP_EXCL, &ze);
    if (!z)
        return fail(e, "cannot create %s", tmp);
    if (zip_tree(e, z, "") != 0) {
        zip_discard(z);
        return -1;
    }
    if (zip_close(z) != 0) {
        fail(e, "cannot write %s: %s", tmp, zip_strerror(z));
        zip_discard(z);
        return -1;
    }
    return rename(tmp, out) == 0 ? 0 : fail(e, "cannot rename %s to %s", tmp, out);
}

static int rm_one(const char *p, const struct stat *sb, int flag, struct FTW *ftw)
{
    (void)sb, (void)flag, (void)ftw;
    return remove(p);
}

int fmu_export(scn_ctx *c, const char *out, int version, char *err, size_t errlen)
{
    ex e = {.c = c, .sc = &c->image, .version = version, .err = err, .errlen = errlen};
    if (version != 2 && version != 3)
        return fail(&e, "FMI version %d: 2 or 3", version);
    const char *t = getenv("TMPDIR");
    snprintf(e.dir, sizeof e.dir, "%s/modrt-fmu-XXXXXX", t && *t ? t : "/tmp");
    if (!mkdtemp(e.dir))
        return fail(&e, "cannot create a temporary directory: %s", strerror(errno));
    int rc = sources(&e) || build_description(&e) || model_description(&e) || compile(&e) ||
             archive(&e, out);
    nftw(e.dir, rm_one, 16, FTW_DEPTH | FTW_PHYS);
    return rc ? -1 : 0;
}
