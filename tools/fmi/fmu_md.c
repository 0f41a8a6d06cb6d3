/* fmu_md.c - the modelDescription.xml reader (fmu_md.h): expat's callbacks fill an fmu_md
 * element by element, knowing where each element may stand (FMI 2.0 and 3.0 schemas);
 * attribute values are checked as they are read and every problem is one line naming the
 * line of the file. Elements modrt does not need (units, log categories, annotations,
 * terminals) are skipped whole. */
#define _POSIX_C_SOURCE 200809L
#include "fmu_md.h"

#include <errno.h>
#include <expat.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* where the parser stands: the element kinds whose children it reads */
typedef enum {
    E_SKIP = 0, E_ROOT, E_MODEL_VARS, E_SCALAR2, E_VAR3, E_TYPEDEFS, E_SIMPLETYPE2,
    E_STRUCT, E_OUTPUTS2, E_DERIVS2, E_OTHER2, E_LEAF, E_ME2, E_FILES2
} elem;

typedef struct tdef {
    const char *name, *unit;
} tdef;

/* growable arrays and strings of one model description, freed together */
typedef struct arena {
    char **str;
    size_t nstr, capstr;
    const char **declared;  /* per variable: its declaredType, or NULL */
    tdef *td;
    size_t ntd, captd;
    size_t capv, capder, capout, capsrc;
} arena;

typedef struct ctx {
    XML_Parser p;
    fmu_md *md;
    arena *a;
    elem st[FMU_MD_MAX_DEPTH + 1];
    int depth;              /* elements open */
    int seen_root;
    int bad_start;          /* the open 3.0 variable's start is not one number (an array's
                               may be a list: decided when the variable closes) */
    char *err;
    size_t errlen;
    int failed;
} ctx;

static const char *const causality_names[FMU_C_COUNT] = {
    "local", "parameter", "calculatedParameter", "input", "output", "independent",
    "structuralParameter"};
static const char *const variability_names[FMU_V_COUNT] = {
    "continuous", "constant", "fixed", "tunable", "discrete"};

const char *fmu_md_causality_name(int c)
{
    return c >= 0 && c < FMU_C_COUNT ? causality_names[c] : "?";
}

const char *fmu_md_variability_name(int v)
{
    return v >= 0 && v < FMU_V_COUNT ? variability_names[v] : "?";
}

/* the first error wins; the parser stops at once */
static void fail(ctx *c, const char *fmt, ...)
{
    if (c->failed)
        return;
    c->failed = 1;
    int n = snprintf(c->err, c->errlen, "modelDescription.xml:%lu: ",
                     (unsigned long)XML_GetCurrentLineNumber(c->p));
    va_list ap;
    va_start(ap, fmt);
    if (n >= 0 && (size_t)n < c->errlen)
        vsnprintf(c->err + n, c->errlen - (size_t)n, fmt, ap);
    va_end(ap);
    XML_StopParser(c->p, XML_FALSE);
}

/* grows *p (of *cap elements of size sz) to hold n + 1; 0 or -1 */
static int grow(ctx *c, void **p, size_t *cap, size_t n, size_t sz)
{
    if (n < *cap)
        return 0;
    size_t nc = *cap ? 2 * *cap : 16;
    void *q = realloc(*p, nc * sz);
    if (!q) {
        fail(c, "out of memory");
        return -1;
    }
    *p = q, *cap = nc;
    return 0;
}

static const char *keep(ctx *c, const char *s)
{
    arena *a = c->a;
    if (!s || grow(c, (void **)&a->str, &a->capstr, a->nstr, sizeof *a->str))
        return NULL;
    char *d = strdup(s);
    if (!d) {
        fail(c, "out of memory");
        return NULL;
    }
    return a->str[a->nstr++] = d;
}

static const char *attr(const char **at, const char *name)
{
    for (; at[0]; at += 2)
        if (!strcmp(at[0], name))
            return at[1];
    return NULL;
}

/* a whole decimal number in [0, max]; -1 with an error otherwise */
static int64_t uint_attr(ctx *c, const char *s, const char *what, uint64_t max)
{
    char *end;
    errno = 0;
    if (!s || !*s || *s == '-' || *s == '+' || *s == ' ') {
        fail(c, "%s '%s' is not a whole number >= 0", what, s ? s : "(missing)");
        return -1;
    }
    unsigned long long v = strtoull(s, &end, 10);
    if (*end || errno || v > max) {
        fail(c, "%s '%s' is not a whole number in [0, %llu]", what, s, (unsigned long long)max);
        return -1;
    }
    return (int64_t)v;
}

static int bool_attr(ctx *c, const char *s, const char *what)
{
    if (!s)
        return 0;
    if (!strcmp(s, "true") || !strcmp(s, "1"))
        return 1;
    if (!strcmp(s, "false") || !strcmp(s, "0"))
        return 0;
    fail(c, "%s '%s' is not true or false", what, s);
    return 0;
}

static int lookup(ctx *c, const char *s, const char *const *names, int n, int def,
                  const char *what)
{
    if (!s)
        return def;
    for (int i = 0; i < n; i++)
        if (!strcmp(s, names[i]))
            return i;
    fail(c, "unknown %s '%s'", what, s);
    return def;
}

/* ------------------------------------------------------------------ elements */

static void root(ctx *c, const char *name, const char **at)
{
    fmu_md *md = c->md;
    if (strcmp(name, "fmiModelDescription") != 0) {
        fail(c, "the root element is <%s>, not <fmiModelDescription>", name);
        return;
    }
    const char *v = attr(at, "fmiVersion");
    md->fmi_version = keep(c, v ? v : "");
    if (v && !strcmp(v, "2.0"))
        md->version = 2;
    else if (v && v[0] == '3' && v[1] == '.')
        md->version = 3;
    else {
        fail(c, "FMI version '%s' is not supported (modrt reads 2.0 and 3.x)", v ? v : "");
        return;
    }
    md->model_name = keep(c, attr(at, "modelName"));
    md->token = keep(c, attr(at, md->version == 2 ? "guid" : "instantiationToken"));
    md->tool = keep(c, attr(at, "generationTool"));
    if (!md->model_name || !md->token)
        fail(c, "<fmiModelDescription> lacks modelName or %s",
             md->version == 2 ? "guid" : "instantiationToken");
    if (md->version == 2)
        md->n_indicators = (uint32_t)uint_attr(c, attr(at, "numberOfEventIndicators")
                                                   ? attr(at, "numberOfEventIndicators") : "0",
                                               "numberOfEventIndicators", FMU_MD_MAX_VARS);
}

/* <ModelExchange> / <CoSimulation> */
static void interface(ctx *c, const char *name, const char **at)
{
    fmu_md *md = c->md;
    const char *id = attr(at, "modelIdentifier");
    if (!id || !*id) {
        fail(c, "<%s> lacks modelIdentifier", name);
        return;
    }
    for (const char *s = id; *s; s++)
        if (!((*s >= 'a' && *s <= 'z') || (*s >= 'A' && *s <= 'Z') ||
              (*s >= '0' && *s <= '9') || *s == '_')) {
            fail(c, "modelIdentifier '%s' is not a C name", id);
            return;
        }
    if (!strcmp(name, "CoSimulation")) {
        md->cs_id = keep(c, id);
        return;
    }
    md->me_id = keep(c, id);
    if (md->version == 2)
        md->needs_step_done = !bool_attr(c, attr(at, "completedIntegratorStepNotNeeded"),
                                         "completedIntegratorStepNotNeeded");
    else
        md->needs_step_done = (uint8_t)bool_attr(c, attr(at, "needsCompletedIntegratorStep"),
                                                 "needsCompletedIntegratorStep");
    md->once_per_process = (uint8_t)bool_attr(c, attr(at, "canBeInstantiatedOnlyOncePerProcess"),
                                              "canBeInstantiatedOnlyOncePerProcess");
    const char *gs = md->version == 2 ? "canGetAndSetFMUstate" : "canGetAndSetFMUState";
    const char *se = md->version == 2 ? "canSerializeFMUstate" : "canSerializeFMUState";
    md->can_state = (uint8_t)(bool_attr(c, attr(at, gs), gs) && bool_attr(c, attr(at, se), se));
}

/* the attributes common to a 2.0 ScalarVariable and a 3.0 typed variable */
static fmu_var *new_var(ctx *c, const char **at)
{
    fmu_md *md = c->md;
    arena *a = c->a;
    if (md->nv >= FMU_MD_MAX_VARS) {
        fail(c, "more than %u variables", FMU_MD_MAX_VARS);
        return NULL;
    }
    size_t capv = a->capv;
    if (grow(c, (void **)&md->v, &a->capv, md->nv, sizeof *md->v) ||
        grow(c, (void **)&a->declared, &capv, md->nv, sizeof *a->declared))
        return NULL;
    fmu_var *v = &md->v[md->nv];
    memset(v, 0, sizeof *v);
    a->declared[md->nv] = NULL;
    md->nv++;
    v->derivative = -1;
    v->line = (uint32_t)XML_GetCurrentLineNumber(c->p);
    v->name = keep(c, attr(at, "name"));
    if (!v->name || !*v->name) {
        fail(c, "a variable without a name");
        return NULL;
    }
    v->desc = keep(c, attr(at, "description"));
    int64_t vr = uint_attr(c, attr(at, "valueReference"), "valueReference", UINT32_MAX);
    v->vr = vr < 0 ? 0 : (uint32_t)vr;
    v->causality = (uint8_t)lookup(c, attr(at, "causality"), causality_names, FMU_C_COUNT,
                                   FMU_C_LOCAL, "causality");
    v->variability = (uint8_t)lookup(c, attr(at, "variability"), variability_names, FMU_V_COUNT,
                                     FMU_V_CONTINUOUS, "variability");
    if (md->version == 2 && v->causality == FMU_C_STRUCTURAL)
        fail(c, "causality structuralParameter is FMI 3.0, not 2.0");
    return v;
}

/* the typed part: start, unit, declaredType, derivative (a 2.0 <Real> or a 3.0 <Float64>) */
static void typed(ctx *c, fmu_var *v, const char *type, const char **at)
{
    v->type = keep(c, type);
    v->float64 = !strcmp(type, c->md->version == 2 ? "Real" : "Float64");
    const char *s = attr(at, "start");
    if (s && v->float64 && !v->array) {
        char *end;
        v->start = strtod(s, &end);
        while (*end == ' ')
            end++;
        if (end == s || *end) {
            if (c->md->version == 3)
                c->bad_start = 1;
            else
                fail(c, "start '%s' of %s is not a number", s, v->name);
        } else {
            v->has_start = 1;
        }
    }
    v->unit = keep(c, attr(at, "unit"));
    c->a->declared[v - c->md->v] = keep(c, attr(at, "declaredType"));
    const char *d = attr(at, "derivative");
    if (d)
        v->derivative = uint_attr(c, d, "derivative", UINT32_MAX);
}

static const char *const types3[] = {
    "Float32", "Float64", "Int8", "UInt8", "Int16", "UInt16", "Int32", "UInt32", "Int64",
    "UInt64", "Boolean", "String", "Binary", "Enumeration", "Clock", NULL};
static const char *const types2[] = {"Real", "Integer", "Boolean", "String", "Enumeration", NULL};

static int is_type(const char *const *list, const char *name)
{
    for (; *list; list++)
        if (!strcmp(*list, name))
            return 1;
    return 0;
}

static elem model_var(ctx *c, const char *name, const char **at)
{
    if (c->md->version == 2) {
        if (strcmp(name, "ScalarVariable") != 0)
            return E_SKIP;
        return new_var(c, at) ? E_SCALAR2 : E_SKIP;
    }
    if (!is_type(types3, name))
        return E_SKIP;
    fmu_var *v = new_var(c, at);
    if (v)
        typed(c, v, name, at);
    return E_VAR3;
}

/* a list of whole numbers (dependencies) */
static void ref_list(ctx *c, const char *s, fmu_out *o)
{
    size_t cap = 0;
    o->has_deps = 1;
    for (;;) {
        while (*s == ' ' || *s == '\t' || *s == '\n' || *s == '\r')
            s++;
        if (!*s)
            return;
        char *end;
        errno = 0;
        unsigned long long v = *s >= '0' && *s <= '9' ? strtoull(s, &end, 10) : (end = (char *)s, 0);
        if (end == s || errno || v > UINT32_MAX) {
            fail(c, "dependencies '%s' is not a list of whole numbers", s);
            return;
        }
        if (o->ndeps >= FMU_MD_MAX_VARS) {
            fail(c, "more than %u dependencies", FMU_MD_MAX_VARS);
            return;
        }
        if (grow(c, (void **)&o->deps, &cap, o->ndeps, sizeof *o->deps))
            return;
        o->deps[o->ndeps++] = (int64_t)v;
        s = end;
    }
}

static void structure_entry(ctx *c, int output, int deriv, int indicator, const char **at)
{
    fmu_md *md = c->md;
    arena *a = c->a;
    const char *key = md->version == 2 ? "index" : "valueReference";
    int64_t ref = uint_attr(c, attr(at, key), key, UINT32_MAX);
    if (ref < 0)
        return;
    if (indicator) {
        md->n_indicators++;
    } else if (deriv) {
        if (md->nder >= FMU_MD_MAX_VARS) {
            fail(c, "more than %u derivatives", FMU_MD_MAX_VARS);
            return;
        }
        if (!grow(c, (void **)&md->der, &a->capder, md->nder, sizeof *md->der))
            md->der[md->nder++] = ref;
    } else if (output) {
        if (md->nout >= FMU_MD_MAX_VARS) {
            fail(c, "more than %u outputs", FMU_MD_MAX_VARS);
            return;
        }
        if (grow(c, (void **)&md->out, &a->capout, md->nout, sizeof *md->out))
            return;
        fmu_out *o = &md->out[md->nout++];
        memset(o, 0, sizeof *o);
        o->ref = ref;
        const char *d = attr(at, "dependencies");
        if (d)
            ref_list(c, d, o);
    }
}

static elem structure(ctx *c, const char *name, const char **at)
{
    if (c->md->version == 2) {
        if (!strcmp(name, "Outputs"))
            return E_OUTPUTS2;
        if (!strcmp(name, "Derivatives"))
            return E_DERIVS2;
        return E_OTHER2;
    }
    int o = !strcmp(name, "Output"), d = !strcmp(name, "ContinuousStateDerivative");
    int e = !strcmp(name, "EventIndicator");
    if (o || d || e)
        structure_entry(c, o, d, e, at);
    return E_LEAF;
}

static void type_def(ctx *c, const char *name, const char **at, int v2_child)
{
    arena *a = c->a;
    if (v2_child) { /* 2.0 <SimpleType name><Real unit/> */
        if (!strcmp(name, "Real") && a->ntd > 0 && !a->td[a->ntd - 1].unit)
            a->td[a->ntd - 1].unit = keep(c, attr(at, "unit"));
        return;
    }
    if (grow(c, (void **)&a->td, &a->captd, a->ntd, sizeof *a->td))
        return;
    a->td[a->ntd].name = keep(c, attr(at, "name"));
    a->td[a->ntd].unit = c->md->version == 3 && !strcmp(name, "Float64Type")
                       ? keep(c, attr(at, "unit")) : NULL;
    a->ntd++;
}

/* 2.0: a C file of a source FMU (<ModelExchange><SourceFiles><File name=...>) */
static void source_file(ctx *c, const char **at)
{
    fmu_md *md = c->md;
    const char *n = attr(at, "name");
    if (!n || !*n) {
        fail(c, "<File> without a name");
        return;
    }
    if (md->nsources >= FMU_MD_MAX_VARS) {
        fail(c, "more than %u source files", FMU_MD_MAX_VARS);
        return;
    }
    if (!grow(c, (void **)&md->sources, &c->a->capsrc, md->nsources, sizeof *md->sources))
        md->sources[md->nsources++] = keep(c, n);
}

/* the kind of a child element `name` of an element of kind `parent` */
static elem child(ctx *c, elem parent, const char *name, const char **at)
{
    switch (parent) {
    case E_ROOT:
        if (!strcmp(name, "ModelExchange") || !strcmp(name, "CoSimulation")) {
            interface(c, name, at);
            return c->md->version == 2 && !strcmp(name, "ModelExchange") ? E_ME2 : E_SKIP;
        }
        return !strcmp(name, "ModelVariables") ? E_MODEL_VARS
             : !strcmp(name, "ModelStructure") ? E_STRUCT
             : !strcmp(name, "TypeDefinitions") ? E_TYPEDEFS : E_SKIP;
    case E_MODEL_VARS:
        return model_var(c, name, at);
    case E_SCALAR2:
        if (is_type(types2, name))
            typed(c, &c->md->v[c->md->nv - 1], name, at);
        return E_SKIP;
    case E_VAR3:
        if (!strcmp(name, "Dimension"))
            c->md->v[c->md->nv - 1].array = 1;
        return E_SKIP;
    case E_TYPEDEFS:
        type_def(c, name, at, 0);
        return c->md->version == 2 ? E_SIMPLETYPE2 : E_SKIP;
    case E_SIMPLETYPE2:
        type_def(c, name, at, 1);
        return E_SKIP;
    case E_ME2:
        return !strcmp(name, "SourceFiles") ? E_FILES2 : E_SKIP;
    case E_FILES2:
        if (!strcmp(name, "File"))
            source_file(c, at);
        return E_SKIP;
    case E_STRUCT:
        return structure(c, name, at);
    case E_OUTPUTS2:
    case E_DERIVS2:
        if (!strcmp(name, "Unknown"))
            structure_entry(c, parent == E_OUTPUTS2, parent == E_DERIVS2, 0, at);
        return E_SKIP;
    default:
        return E_SKIP;
    }
}

static void XMLCALL on_start(void *ud, const char *name, const char **at)
{
    ctx *c = ud;
    if (c->failed)
        return;
    if (c->depth >= FMU_MD_MAX_DEPTH) {
        fail(c, "elements nested deeper than %d", FMU_MD_MAX_DEPTH);
        return;
    }
    elem e;
    if (c->depth == 0) {
        root(c, name, at);
        c->seen_root = 1;
        e = E_ROOT;
    } else {
        e = child(c, c->st[c->depth - 1], name, at);
    }
    c->st[c->depth++] = e;
}

static void XMLCALL on_end(void *ud, const char *name)
{
    ctx *c = ud;
    (void)name;
    if (c->depth > 0 && c->st[--c->depth] == E_VAR3 && c->bad_start) {
        const fmu_var *v = &c->md->v[c->md->nv - 1];
        c->bad_start = 0;
        if (!v->array)
            fail(c, "start of %s is not a number", v->name);
    }
}

/* ------------------------------------------------------------------ after the parse */

static void resolve_units(fmu_md *md, const arena *a)
{
    for (uint32_t i = 0; i < md->nv; i++) {
        if (md->v[i].unit || !a->declared[i])
            continue;
        for (size_t k = 0; k < a->ntd; k++)
            if (a->td[k].name && !strcmp(a->td[k].name, a->declared[i]))
                md->v[i].unit = a->td[k].unit;
    }
}

int64_t fmu_md_find(const fmu_md *md, int64_t ref)
{
    if (md->version == 2)
        return ref >= 1 && ref <= (int64_t)md->nv ? ref - 1 : -1;
    for (uint32_t i = 0; i < md->nv; i++) /* a float64 variable first: aliases share vr */
        if (md->v[i].vr == ref && md->v[i].float64)
            return i;
    for (uint32_t i = 0; i < md->nv; i++)
        if (md->v[i].vr == ref)
            return i;
    return -1;
}

/* references of the model structure name variables that exist */
static int check_refs(fmu_md *md, char *err, size_t errlen)
{
    for (uint32_t i = 0; i < md->nder; i++)
        if (fmu_md_find(md, md->der[i]) < 0) {
            snprintf(err, errlen, "modelDescription.xml: derivative %lld of ModelStructure "
                     "names no variable", (long long)md->der[i]);
            return -1;
        }
    for (uint32_t i = 0; i < md->nout; i++)
        if (fmu_md_find(md, md->out[i].ref) < 0) {
            snprintf(err, errlen, "modelDescription.xml: output %lld of ModelStructure "
                     "names no variable", (long long)md->out[i].ref);
            return -1;
        }
    for (uint32_t i = 0; i < md->nv; i++)
        if (md->v[i].derivative >= 0 && fmu_md_find(md, md->v[i].derivative) < 0) {
            snprintf(err, errlen, "modelDescription.xml:%u: derivative=\"%lld\" of %s names "
                     "no variable", (unsigned)md->v[i].line, (long long)md->v[i].derivative,
                     md->v[i].name);
            return -1;
        }
    return 0;
}

int fmu_md_parse(const char *xml, size_t n, fmu_md *md, char *err, size_t errlen)
{
    memset(md, 0, sizeof *md);
    arena *a = calloc(1, sizeof *a);
    if (!a) {
        snprintf(err, errlen, "modelDescription.xml: out of memory");
        return -1;
    }
    md->arena = a;
    if (n > FMU_MD_MAX_BYTES) {
        snprintf(err, errlen, "modelDescription.xml: larger than %u bytes", FMU_MD_MAX_BYTES);
        return -1;
    }
    ctx c = {0};
    c.md = md, c.a = a, c.err = err, c.errlen = errlen;
    c.p = XML_ParserCreate(NULL);
    if (!c.p) {
        snprintf(err, errlen, "modelDescription.xml: out of memory");
        return -1;
    }
    XML_SetUserData(c.p, &c);
    XML_SetElementHandler(c.p, on_start, on_end);
    enum XML_Status st = XML_Parse(c.p, xml, (int)n, XML_TRUE);
    if (st == XML_STATUS_ERROR && !c.failed) {
        snprintf(err, errlen, "modelDescription.xml:%lu: %s", (unsigned long)XML_GetCurrentLineNumber(c.p),
                 XML_ErrorString(XML_GetErrorCode(c.p)));
        c.failed = 1;
    }
    XML_ParserFree(c.p);
    if (c.failed)
        return -1;
    if (!c.seen_root) {
        snprintf(err, errlen, "modelDescription.xml: no <fmiModelDescription> element");
        return -1;
    }
    resolve_units(md, a);
    return check_refs(md, err, errlen);
}

void fmu_md_free(fmu_md *md)
{
    arena *a = md->arena;
    if (a) {
        for (size_t i = 0; i < a->nstr; i++)
            free(a->str[i]);
        free(a->str);
        free(a->declared);
        free(a->td);
        free(a);
    }
    for (uint32_t i = 0; i < md->nout; i++)
        free(md->out[i].deps);
    free(md->v);
    free(md->sources);
    free(md->der);
    free(md->out);
    memset(md, 0, sizeof *md);
}
