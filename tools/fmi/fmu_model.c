/* fmu_model.c - one FMU file loaded (fmu_model_load): unpacked, described, its Model
 * Exchange binary for this platform opened and bound, and the interface a kind shows:
 * Float64 inputs, outputs and parameters by name, continuous states in the order of the
 * model structure's derivatives, the outputs' direct dependencies on inputs (throughput),
 * event indicators. Every disagreement is refused here, before a run, in one line. */
#define _XOPEN_SOURCE 700
#include <dirent.h>
#include <dlfcn.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "fmu_int.h"

static fmu_model *loaded; /* models of this process, so a file loaded twice is loaded once */

static int failf(char *err, size_t errlen, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err, errlen, fmt, ap);
    va_end(ap);
    return -1;
}

char *fmu_scene_name(const char *s)
{
    size_t n = strlen(s);
    char *o = malloc(n + 2), *d = o;
    if (!o)
        return NULL;
    if (*s >= '0' && *s <= '9')
        *d++ = '_';
    for (; *s; s++)
        *d++ = ((*s >= 'a' && *s <= 'z') || (*s >= 'A' && *s <= 'Z') ||
                (*s >= '0' && *s <= '9') || *s == '_') ? *s : '_';
    *d = 0;
    return o;
}

static int read_file(const char *path, char **buf, size_t *n)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return -1;
    size_t cap = 65536, len = 0, got;
    char *b = malloc(cap);
    while (b && (got = fread(b + len, 1, cap - len, f)) > 0) {
        len += got;
        if (len == cap && cap < FMU_MD_MAX_BYTES + 1u) {
            char *nb = realloc(b, cap * 2);
            if (!nb)
                free(b);
            b = nb, cap *= 2;
        } else if (len == cap) {
            break;
        }
    }
    fclose(f);
    *buf = b, *n = len;
    return b ? 0 : -1;
}

/* the platforms the FMU has binaries for, for the message that it lacks ours */
static void platforms(const char *dir, char *out, size_t n)
{
    char p[4200];
    snprintf(p, sizeof p, "%s/binaries", dir);
    DIR *d = opendir(p);
    struct dirent *e;
    out[0] = 0;
    while (d && (e = readdir(d)))
        if (e->d_name[0] != '.' && strlen(out) + strlen(e->d_name) + 3 < n)
            strcat(strcat(out, out[0] ? ", " : ""), e->d_name);
    if (d)
        closedir(d);
    snprintf(p, sizeof p, "%s/sources", dir);
    struct stat st;
    if (stat(p, &st) == 0 && strlen(out) + 12 < n)
        strcat(out, out[0] ? ", sources" : "sources");
    if (!out[0])
        snprintf(out, n, "none");
}

/* the functions of the version, by name (one list: fmu_int.h) */
static int bind(fmu_model *m, char *err, size_t errlen)
{
    typedef struct { const char *name; void **slot; } row;
#define FMU_X_ROW2(n) {#n, (void **)&m->f2.n},
#define FMU_X_ROW3(n) {#n, (void **)&m->f3.n},
    row r2[] = {FMU_FMI2_LIST(FMU_X_ROW2) {NULL, NULL}};
    row r3[] = {FMU_FMI3_LIST(FMU_X_ROW3) {NULL, NULL}};
    row s2[] = {FMU_FMI2_STATE_LIST(FMU_X_ROW2) {NULL, NULL}};
    row s3[] = {FMU_FMI3_STATE_LIST(FMU_X_ROW3) {NULL, NULL}};
#undef FMU_X_ROW2
#undef FMU_X_ROW3
    for (row *r = m->md.version == 2 ? r2 : r3; r->name; r++) {
        *r->slot = dlsym(m->so, r->name);
        if (!*r->slot)
            return failf(err, errlen, "%s: %s lacks %s (FMI %s Model Exchange calls it)",
                         m->path, m->lib + strlen(m->dir) + 1, r->name, m->md.fmi_version);
    }
    for (row *r = m->md.version == 2 ? s2 : s3; m->md.can_state && r->name; r++) {
        *r->slot = dlsym(m->so, r->name);
        if (!*r->slot)
            return failf(err, errlen, "%s: %s lacks %s (its modelDescription.xml says it can "
                         "get, set and serialize its FMU state)", m->path,
                         m->lib + strlen(m->dir) + 1, r->name);
    }
    const char *v = m->md.version == 2 ? m->f2.fmi2GetVersion() : m->f3.fmi3GetVersion();
    int ok = v && (m->md.version == 2 ? !strcmp(v, "2.0") : v[0] == '3' && v[1] == '.');
    if (!ok)
        return failf(err, errlen, "%s: the binary implements FMI '%s', its modelDescription.xml "
                     "says %s", m->path, v ? v : "(null)", m->md.fmi_version);
    if (m->md.version == 2 && strcmp(m->f2.fmi2GetTypesPlatform(), "default") != 0)
        return failf(err, errlen, "%s: the binary's types platform is '%s', not 'default'",
                     m->path, m->f2.fmi2GetTypesPlatform());
    m->ops = m->md.version == 2 ? &fmu_ops2 : &fmu_ops3;
    return 0;
}

static int open_binary(fmu_model *m, char *err, size_t errlen)
{
    const fmu_md *md = &m->md;
    if (!md->me_id)
        return failf(err, errlen, "%s: no <ModelExchange> in modelDescription.xml%s: modrt "
                     "imports Model Exchange FMUs", m->path, md->cs_id ? " (Co-Simulation only)" : "");
    const char *plat = md->version == 2 ? "linux64" : "x86_64-linux";
    size_t n = strlen(m->dir) + strlen(md->me_id) + 40;
    m->lib = malloc(n);
    if (!m->lib)
        return failf(err, errlen, "out of memory");
    snprintf(m->lib, n, "%s/binaries/%s/%s.so", m->dir, plat, md->me_id);
    struct stat st;
    char src[4200];
    snprintf(src, sizeof src, "%s/sources", m->dir);
    if (stat(m->lib, &st) != 0 && stat(src, &st) == 0) { /* a source FMU: built here once */
        if (fmu_build(m, m->lib, err, errlen) != 0)
            return -1;
    } else if (stat(m->lib, &st) != 0) {
        char have[256];
        platforms(m->dir, have, sizeof have);
        return failf(err, errlen, "%s: no binary for this platform (binaries/%s/%s.so); it "
                     "has: %s", m->path, plat, md->me_id, have);
    }
    m->so = dlopen(m->lib, RTLD_NOW | RTLD_LOCAL);
    if (!m->so)
        return failf(err, errlen, "%s: cannot load its binary: %s", m->path, dlerror());
    return bind(m, err, errlen);
}

/* ------------------------------------------------------------------ the interface */

/* variables of a causality modrt maps must be Float64 scalars */
static int check_types(const fmu_model *m, char *err, size_t errlen)
{
    for (uint32_t i = 0; i < m->md.nv; i++) {
        const fmu_var *v = &m->md.v[i];
        int mapped = v->causality == FMU_C_INPUT || v->causality == FMU_C_OUTPUT ||
                     v->causality == FMU_C_PARAMETER || v->causality == FMU_C_STRUCTURAL;
        if (mapped && (!v->float64 || v->array))
            return failf(err, errlen, "%s: variable '%s' (%s %s%s, modelDescription.xml:%u): "
                         "modrt imports Float64 scalars only", m->path, v->name,
                         fmu_md_causality_name(v->causality), v->type ? v->type : "?",
                         v->array ? " array" : "", (unsigned)v->line);
        if (v->causality == FMU_C_STRUCTURAL)
            return failf(err, errlen, "%s: structural parameter '%s': modrt does not "
                         "configure FMUs", m->path, v->name);
    }
    return 0;
}

static int collect(fmu_model *m, int causality, uint32_t **idx, uint32_t **vr,
                   const char ***names, uint32_t *n)
{
    uint32_t k = 0;
    for (uint32_t i = 0; i < m->md.nv; i++)
        k += m->md.v[i].causality == causality;
    *idx = calloc(k + 1, sizeof **idx), *vr = calloc(k + 1, sizeof **vr);
    *names = calloc(k + 1, sizeof **names);
    if (!*idx || !*vr || !*names)
        return -1;
    k = 0;
    for (uint32_t i = 0; i < m->md.nv; i++)
        if (m->md.v[i].causality == causality) {
            (*idx)[k] = i, (*vr)[k] = m->md.v[i].vr;
            (*names)[k++] = fmu_scene_name(m->md.v[i].name);
        }
    *n = k;
    return 0;
}

/* continuous states: the derivatives of the model structure, in order */
static int states(fmu_model *m, char *err, size_t errlen)
{
    const fmu_md *md = &m->md;
    m->nx = md->nder;
    m->ix = calloc(m->nx + 1, sizeof *m->ix), m->idx = calloc(m->nx + 1, sizeof *m->idx);
    m->vx = calloc(m->nx + 1, sizeof *m->vx), m->x_names = calloc(m->nx + 1, sizeof *m->x_names);
    m->x_def = calloc(m->nx + 1, sizeof *m->x_def);
    if (!m->ix || !m->idx || !m->vx || !m->x_names || !m->x_def)
        return failf(err, errlen, "out of memory");
    for (uint32_t i = 0; i < m->nx; i++) {
        int64_t d = fmu_md_find(md, md->der[i]);
        const fmu_var *dv = &md->v[d];
        int64_t s = dv->derivative >= 0 ? fmu_md_find(md, dv->derivative) : -1;
        if (s < 0 || !dv->float64 || !md->v[s].float64)
            return failf(err, errlen, "%s: derivative '%s' of the model structure is not the "
                         "Float64 derivative of a Float64 state", m->path, dv->name);
        m->ix[i] = (uint32_t)s, m->idx[i] = (uint32_t)d, m->vx[i] = md->v[s].vr;
        m->x_names[i] = fmu_scene_name(md->v[s].name);
        m->x_def[i] = (real_t)(md->v[s].has_start ? md->v[s].start : 0);
    }
    return 0;
}

/* does output variable y (md index) depend directly on input variable u (md index)? */
static int depends(const fmu_model *m, uint32_t y, uint32_t u)
{
    const fmu_md *md = &m->md;
    for (uint32_t k = 0; k < md->nout; k++) {
        if (fmu_md_find(md, md->out[k].ref) != (int64_t)y)
            continue;
        if (!md->out[k].has_deps)
            return 1;
        for (uint32_t j = 0; j < md->out[k].ndeps; j++)
            if (fmu_md_find(md, md->out[k].deps[j]) == (int64_t)u)
                return 1;
        return 0;
    }
    return 1; /* not in the model structure: assume it does */
}

static void feed(fmu_model *m)
{
    uint32_t any = 0, all = 1;
    m->feed = calloc((size_t)m->ny * m->nu + 1, 1);
    for (uint32_t i = 0; m->feed && i < m->ny; i++)
        for (uint32_t j = 0; j < m->nu; j++) {
            uint8_t f = (uint8_t)depends(m, m->iy[i], m->iu[j]);
            m->feed[i * m->nu + j] = f, any |= f, all &= f;
        }
    m->feed_class = !any ? RT_FEED_NONE : all ? RT_FEED_ALL : RT_FEED_TABLE;
}

/* "u.. y.. x.. p..": the units of the kind, '-' where none is given */
static void units(fmu_model *m)
{
    const uint32_t *lists[4] = {m->iu, m->iy, m->ix, m->ip};
    uint32_t ns[4] = {m->nu, m->ny, m->nx, m->np};
    size_t len = 1;
    for (int l = 0; l < 4; l++)
        for (uint32_t i = 0; i < ns[l]; i++) {
            const char *u = m->md.v[lists[l][i]].unit;
            len += (u && *u ? strlen(u) : 1) + 1;
        }
    char *s = calloc(len, 1);
    for (int l = 0; s && l < 4; l++)
        for (uint32_t i = 0; i < ns[l]; i++) {
            const char *u = m->md.v[lists[l][i]].unit;
            if (*s)
                strcat(s, " ");
            strcat(s, u && *u && !strchr(u, ' ') ? u : "-");
        }
    m->units = s;
}

/* two names of one list that the scene language cannot tell apart */
static int clash(const fmu_model *m, char *err, size_t errlen)
{
    const char *const *lists[4] = {m->u_names, m->y_names, m->x_names, m->p_names};
    uint32_t ns[4] = {m->nu, m->ny, m->nx, m->np};
    for (int l = 0; l < 4; l++)
        for (uint32_t i = 0; i < ns[l]; i++)
            for (uint32_t j = 0; j < i; j++)
                if (!strcmp(lists[l][i], lists[l][j]))
                    return failf(err, errlen, "%s: two variables are both '%s' in the scene "
                                 "language (characters outside [A-Za-z0-9_] read as '_')",
                                 m->path, lists[l][i]);
    return 0;
}

static int interface_of(fmu_model *m, char *err, size_t errlen)
{
    if (check_types(m, err, errlen) || states(m, err, errlen))
        return -1;
    if (collect(m, FMU_C_INPUT, &m->iu, &m->vu, &m->u_names, &m->nu) ||
        collect(m, FMU_C_OUTPUT, &m->iy, &m->vy, &m->y_names, &m->ny) ||
        collect(m, FMU_C_PARAMETER, &m->ip, &m->vp, &m->p_names, &m->np))
        return failf(err, errlen, "out of memory");
    m->p_def = calloc(m->np + 1, sizeof *m->p_def);
    for (uint32_t i = 0; m->p_def && i < m->np; i++)
        m->p_def[i] = (real_t)m->md.v[m->ip[i]].start;
    m->nz = m->md.n_indicators;
    m->u_disc = calloc(m->nu + 1, 1);
    for (uint32_t i = 0; m->u_disc && i < m->nu; i++) {
        m->u_disc[i] = m->md.v[m->iu[i]].variability != FMU_V_CONTINUOUS;
        m->instants |= m->u_disc[i];
    }
    for (uint32_t i = 0; i < m->np; i++)
        m->instants |= m->md.v[m->ip[i]].variability == FMU_V_TUNABLE;
    feed(m);
    units(m);
    return !m->p_def || !m->u_disc || !m->feed || !m->units ? failf(err, errlen, "out of memory")
                                              : clash(m, err, errlen);
}

fmu_model *fmu_model_load(const char *path, char *err, size_t errlen)
{
    char *real = realpath(path, NULL);
    if (!real) {
        failf(err, errlen, "%s: no such FMU file", path);
        return NULL;
    }
    for (fmu_model *m = loaded; m; m = m->next)
        if (!strcmp(m->path, real)) {
            free(real);
            return m;
        }
    fmu_model *m = calloc(1, sizeof *m);
    char *xml = NULL;
    size_t n = 0;
    if (!m) {
        free(real);
        failf(err, errlen, "out of memory");
        return NULL;
    }
    m->path = real;
    m->dir = fmu_unpack(real, err, errlen);
    int rc = m->dir ? 0 : -1;
    if (!rc) {
        size_t len = strlen(m->dir) + 32;
        char *p = malloc(len);
        snprintf(p, len, "%s/modelDescription.xml", m->dir);
        rc = read_file(p, &xml, &n) ? failf(err, errlen, "%s: cannot read %s", real, p) : 0;
        free(p);
    }
    if (!rc) {
        char msg[FMU_ERR_LEN];
        rc = fmu_md_parse(xml, n, &m->md, msg, sizeof msg);
        if (rc)
            failf(err, errlen, "%s: %s", real, msg);
    }
    free(xml);
    rc = rc || interface_of(m, err, errlen) || open_binary(m, err, errlen);
    if (rc)
        return NULL; /* (the partial model is left: the process ends on this error) */
    m->next = loaded, loaded = m;
    return m;
}

const fmu_md *fmu_model_md(const fmu_model *m) { return &m->md; }

int fmu_is_file(const char *arg)
{
    size_t n = strlen(arg);
    return n > 4 && strcmp(arg + n - 4, ".fmu") == 0;
}
