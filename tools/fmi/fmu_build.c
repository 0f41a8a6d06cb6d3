/* fmu_build.c - source FMUs on the host: an FMU with sources/ but no binary for this
 * platform is compiled into one as the standard describes its build (FMI 3.0
 * sources/buildDescription.xml: the source files, preprocessor definitions, include
 * directories and libraries of the BuildConfiguration of its Model Exchange model
 * identifier; FMI 2.0: the files its <ModelExchange><SourceFiles> lists), by $CC (else
 * cc), into the FMU's cache directory beside its unpacked files, so it is built once.
 * Names that would leave sources/ are refused; the compiler's output goes to a log whose
 * path the one-line error names. */
#define _XOPEN_SOURCE 700
#include <errno.h>
#include <expat.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "fmu_int.h"

#define FMU_BUILD_MAX_ARGS 1024 /* words of one compiler command */
#ifndef MODRT_SRC_DIR
#define MODRT_SRC_DIR "." /* where tools/fmi/fmu_count.c is (the build passes its tree) */
#endif
#define FMU_STR_(x) #x
#define FMU_STR(x) FMU_STR_(x)
#define FMU_COUNT_ALIGN_DEF "-DFMU_COUNT_ALIGN=" FMU_STR(FMU_ARENA_ALIGN)

typedef struct bctx {
    const char *id;         /* the model identifier whose configuration is read */
    int in_conf, done, bad;
    const char *argv[FMU_BUILD_MAX_ARGS];
    int n;
    char *own[FMU_BUILD_MAX_ARGS]; /* the words allocated here */
    int nown;
} bctx;

static int failf(char *err, size_t errlen, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err, errlen, fmt, ap);
    va_end(ap);
    return -1;
}

/* a relative path that stays under sources/ */
static int inside(const char *s)
{
    if (!s || !*s || s[0] == '/' || strchr(s, '\\') || strstr(s, ".."))
        return 0;
    return 1;
}

static void word(bctx *b, const char *prefix, const char *s, const char *eq, const char *v)
{
    if (b->n >= FMU_BUILD_MAX_ARGS - 8) {
        b->bad = 1;
        return;
    }
    size_t len = strlen(prefix) + strlen(s) + (eq ? strlen(eq) + strlen(v) : 0) + 1;
    char *w = malloc(len);
    if (!w) {
        b->bad = 1;
        return;
    }
    snprintf(w, len, "%s%s%s%s", prefix, s, eq ? eq : "", eq ? v : "");
    b->argv[b->n++] = b->own[b->nown++] = w;
}

static const char *attr(const char **at, const char *name)
{
    for (; at[0]; at += 2)
        if (!strcmp(at[0], name))
            return at[1];
    return NULL;
}

static void XMLCALL on_start(void *ud, const char *name, const char **at)
{
    bctx *b = ud;
    if (!strcmp(name, "BuildConfiguration")) {
        const char *id = attr(at, "modelIdentifier");
        b->in_conf = !b->done && id && !strcmp(id, b->id);
        return;
    }
    if (!b->in_conf)
        return;
    const char *n = attr(at, "name");
    if (!strcmp(name, "SourceFile") || !strcmp(name, "IncludeDirectory")) {
        if (!inside(n)) {
            b->bad = 1;
            return;
        }
        word(b, !strcmp(name, "SourceFile") ? "" : "-I", n, NULL, NULL);
    } else if (!strcmp(name, "PreprocessorDefinition") && n) {
        const char *v = attr(at, "value");
        word(b, "-D", n, v ? "=" : NULL, v ? v : "");
    } else if (!strcmp(name, "Library") && n) {
        const char *ext = attr(at, "external");
        if (!ext || strcmp(ext, "true") != 0)
            word(b, "-l", n, NULL, NULL);
    }
}

static void XMLCALL on_end(void *ud, const char *name)
{
    bctx *b = ud;
    if (!strcmp(name, "BuildConfiguration") && b->in_conf)
        b->in_conf = 0, b->done = 1;
}

/* 3.0: the words of sources/buildDescription.xml's configuration for the model */
static int from_description(const fmu_model *m, bctx *b, char *err, size_t errlen)
{
    char p[4200];
    snprintf(p, sizeof p, "%s/sources/buildDescription.xml", m->dir);
    FILE *f = fopen(p, "rb");
    if (!f)
        return failf(err, errlen, "%s: no binary for this platform and no "
                     "sources/buildDescription.xml to build one", m->path);
    static char buf[1 << 20];
    size_t n = fread(buf, 1, sizeof buf, f);
    fclose(f);
    XML_Parser x = XML_ParserCreate(NULL);
    XML_SetUserData(x, b);
    XML_SetElementHandler(x, on_start, on_end);
    int ok = x && XML_Parse(x, buf, (int)n, XML_TRUE) == XML_STATUS_OK;
    if (x && !ok)
        failf(err, errlen, "%s: sources/buildDescription.xml:%lu: %s", m->path,
              (unsigned long)XML_GetCurrentLineNumber(x), XML_ErrorString(XML_GetErrorCode(x)));
    if (x)
        XML_ParserFree(x);
    if (!ok)
        return -1;
    if (b->bad)
        return failf(err, errlen, "%s: sources/buildDescription.xml names a file outside "
                     "sources/ or too many: refused", m->path);
    if (!b->done)
        return failf(err, errlen, "%s: sources/buildDescription.xml has no BuildConfiguration "
                     "for %s", m->path, m->md.me_id);
    return 0;
}

/* runs the compiler in sources/, its output into log */
static int run(const char *dir, const char *const *argv, const char *log)
{
    pid_t pid = fork();
    if (pid == 0) {
        FILE *l = fopen(log, "w");
        if (l) {
            dup2(fileno(l), 1);
            dup2(fileno(l), 2);
        }
        if (chdir(dir) == 0)
            execvp(argv[0], (char *const *)argv);
        _exit(127);
    }
    int st = 0;
    if (pid < 0 || waitpid(pid, &st, 0) < 0)
        return -1;
    return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

/* the words naming the sources, definitions and include directories (relative to
   sources/) of the FMU's build, appended to b */
static int source_words(const fmu_model *m, bctx *b, char *err, size_t errlen)
{
    int rc = 0;
    if (m->md.version == 3) {
        rc = from_description(m, b, err, errlen);
    } else if (m->md.nsources == 0) {
        rc = failf(err, errlen, "%s: no binary for this platform and no <SourceFiles> to "
                   "build one from", m->path);
    } else {
        for (uint32_t i = 0; i < m->md.nsources && !b->bad; i++)
            if (inside(m->md.sources[i]))
                word(b, "", m->md.sources[i], NULL, NULL);
            else
                b->bad = 1;
        if (b->bad)
            rc = failf(err, errlen, "%s: a source file outside sources/: refused", m->path);
    }
    return rc;
}

int fmu_source_words(const fmu_model *m, FILE *f, char *err, size_t errlen)
{
    bctx b = {.id = m->md.me_id};
    int rc = source_words(m, &b, err, errlen);
    for (int i = 0; rc == 0 && i < b.n; i++)
        fprintf(f, "%s%s", i ? " " : "", b.argv[i]);
    for (int i = 0; i < b.nown; i++)
        free(b.own[i]);
    return rc;
}

int fmu_build(const fmu_model *m, const char *lib, char *err, size_t errlen)
{
    bctx b = {.id = m->md.me_id};
    const char *cc = getenv("CC") && *getenv("CC") ? getenv("CC") : "cc";
    b.argv[b.n++] = cc;
    /* the arithmetic as written (no contraction into fused multiply-adds), as modrt's own */
    static const char *const flags[] = {"-shared", "-fPIC", "-O2", "-w", "-ffp-contract=off",
                                        "-I."};
    for (size_t i = 0; i < sizeof flags / sizeof *flags; i++)
        b.argv[b.n++] = flags[i];
    int rc = source_words(m, &b, err, errlen);
    /* FMI 3.0: its calloc, malloc and free counted as an image's arena would hand them out
       (fmu_count.c, fmu_arena_need) */
    static const char *const count[] = {"-Dcalloc=fmu_count_calloc", "-Dmalloc=fmu_count_malloc",
                                        "-Dfree=fmu_count_free", FMU_COUNT_ALIGN_DEF,
                                        MODRT_SRC_DIR "/tools/fmi/fmu_count.c"};
    for (size_t i = 0; rc == 0 && m->md.version == 3 && i < sizeof count / sizeof *count; i++)
        b.argv[b.n++] = count[i];
    char src[4200], tmp[4400], log[4400], dir[4400];
    snprintf(src, sizeof src, "%s/sources", m->dir);
    snprintf(tmp, sizeof tmp, "%s.tmp%ld", lib, (long)getpid());
    snprintf(log, sizeof log, "%s/build.log", m->dir);
    snprintf(dir, sizeof dir, "%s", lib);
    *strrchr(dir, '/') = 0;
    if (rc == 0) {
        b.argv[b.n++] = "-o", b.argv[b.n++] = tmp, b.argv[b.n++] = "-lm", b.argv[b.n] = NULL;
        char *parent = strrchr(dir, '/');
        *parent = 0;
        mkdir(dir, 0755); /* binaries/ */
        *parent = '/';
        mkdir(dir, 0755); /* binaries/<platform>/ */
        int x = run(src, b.argv, log);
        if (x != 0)
            rc = failf(err, errlen, "%s: building its sources failed (%s exit %d, log %s)",
                       m->path, cc, x, log);
        else if (rename(tmp, lib) != 0)
            rc = failf(err, errlen, "%s: cannot write %s: %s", m->path, lib, strerror(errno));
    }
    for (int i = 0; i < b.nown; i++)
        free(b.own[i]);
    return rc;
}
