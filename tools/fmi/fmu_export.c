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

#ifndef MODRT_SRC_DIR
#define MODRT_SRC_DIR "."
#endif

typedef struct ex {
    scn_ctx *c;
    const rt_scene *sc;
    int version;            /* FMI 2 or 3 */
    char dir[4096];         /* the FMU's tree before zipping */
    char *err;
    size_t errlen;
    char token[96];
    const char *srcs[256];  /* the files of sources/ */
    int nsrcs;
} ex;

static int fail(ex *e, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(e->err, e->errlen, fmt, ap);
    va_end(ap);
    return -1;
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
    char from[4200], to[4300];
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
        if (c && rc == 0 && e->nsrcs < 250)
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

static int sources(ex *e)
{
    char p[4300];
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
    snprintf(p, sizeof p, "%s/sources/scene.c", e->dir);
    FILE *f = fopen(p, "w");
    if (!f || scn_emit(e->c, f) != 0 || fclose(f) != 0)
        return fail(e, "cannot write %s", p);
    e->srcs[e->nsrcs++] = "scene.c";
    snprintf(e->token, sizeof e->token, "{modrt-%s-%016llx}", e->sc->name, hash_file(p));
    /* which scene the FMI functions serve, under which token and names */
    snprintf(p, sizeof p, "%s/sources/fmu_cs_id.h", e->dir);
    f = fopen(p, "w");
    if (!f)
        return fail(e, "cannot write %s", p);
    fprintf(f, "/* fmu_cs_id.h - written by scenec --fmu: the scene this FMU serves */\n"
               "#define FMU_CS_SCENE %s%s\n#define FMU_CS_TOKEN \"%s\"\n"
               "#define FMI%d_FUNCTION_PREFIX %s_\n",
            SCN_SYMBOL_PREFIX, e->sc->name, e->token, e->version, e->sc->name);
    return fclose(f) == 0 ? 0 : fail(e, "cannot write %s", p);
}

static int build_description(ex *e)
{
    char p[4300];
    snprintf(p, sizeof p, "%s/sources/buildDescription.xml", e->dir);
    FILE *f = fopen(p, "w");
    if (!f)
        return fail(e, "cannot write %s", p);
    fprintf(f, "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<fmiBuildDescription fmiVersion=\"3.0\">\n"
               "  <BuildConfiguration modelIdentifier=\"%s\">\n"
               "    <SourceFileSet language=\"C11\" compilerOptions=\"-ffp-contract=off "
               "-fno-math-errno\">\n", e->sc->name);
    for (int i = 0; i < e->nsrcs; i++)
        fprintf(f, "      <SourceFile name=\"%s\"/>\n", e->srcs[i]);
    fputs("      <IncludeDirectory name=\".\"/>\n      <IncludeDirectory name=\"rt\"/>\n"
          "      <IncludeDirectory name=\"models\"/>\n    </SourceFileSet>\n"
          "    <Library name=\"m\"/>\n  </BuildConfiguration>\n</fmiBuildDescription>\n", f);
    return fclose(f) == 0 ? 0 : fail(e, "cannot write %s", p);
}

/* the binary for this host from the sources just written */
static int compile(ex *e)
{
    char out[4300];
    const char *plat = e->version == 2 ? "linux64" : "x86_64-linux";
    snprintf(out, sizeof out, "%s/binaries/%s", e->dir, plat);
    char *mk = scn_fmt(e->c, "%s/binaries", e->dir);
    if (mkdir(mk, 0755) != 0 || mkdir(out, 0755) != 0)
        return fail(e, "cannot create %s", out);
    snprintf(out, sizeof out, "%s/binaries/%s/%s.so", e->dir, plat, e->sc->name);
    const char *cc = getenv("CC") && *getenv("CC") ? getenv("CC") : "cc";
    const char *argv[300];
    int n = 0;
    argv[n++] = cc;
    const char *flags[] = {"-std=c11", "-O2", "-fPIC", "-shared", "-ffp-contract=off",
                           "-fno-math-errno", "-fvisibility=hidden", "-w", "-I.", "-Irt",
                           "-Imodels"};
    for (size_t i = 0; i < sizeof flags / sizeof *flags; i++)
        argv[n++] = flags[i];
    /* a shared object: the functions' plain names */
    argv[n++] = e->version == 2 ? "-DFMI2_OVERRIDE_FUNCTION_PREFIX" : "-DFMI3_OVERRIDE_FUNCTION_PREFIX";
    for (int i = 0; i < e->nsrcs; i++)
        argv[n++] = e->srcs[i];
    argv[n++] = "-o", argv[n++] = out, argv[n++] = "-lm", argv[n] = NULL;
    pid_t pid = fork();
    if (pid == 0) {
        char src[4300];
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
               "canGetAndSetFMUState=\"true\" canSerializeFMUState=\"true\" "
               "hasEventMode=\"false\" providesIntermediateUpdate=\"false\" "
               "mightReturnEarlyFromDoStep=\"false\"/>\n", sc->name, real(b1, (double)sc->dt));
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
               "maxOutputDerivativeOrder=\"0\" canGetAndSetFMUstate=\"true\" "
               "canSerializeFMUstate=\"true\" canNotUseMemoryManagementFunctions=\"false\" "
               "providesDirectionalDerivative=\"false\">\n    <SourceFiles>\n", sc->name);
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
    char p[4300];
    snprintf(p, sizeof p, "%s/modelDescription.xml", e->dir);
    FILE *f = fopen(p, "w");
    if (!f)
        return fail(e, "cannot write %s", p);
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
