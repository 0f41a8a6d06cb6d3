/* fmu_emit.c - an FMU block in the C of a per-scene image (docs/fmi.md, "FMUs in images"):
 * what `scenec` writes for a block whose FMU ships sources. The model and the instance the
 * host built at load time become static tables (interface, names, start values, the
 * scene's state starts) and the FMU's functions are bound by their prefixed names
 * (<modelIdentifier>_fmi2GetReal ..., FMI*_FUNCTION_PREFIX), so the image links the FMU's
 * sources beside fmu_inst.c, fmu_call.c and fmu_arena.c built with FMU_TARGET: the same
 * calling sequence as on the host, no dlopen, no heap. One comment line per block,
 * "// fmu-build: BLOCK VERSION ID SOURCES_DIR WORDS...", tells tools/image.sh how to
 * compile the sources (their files, definitions and include directories). */
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#include "fmu_int.h"

static void cstr(FILE *f, const char *s)
{
    fputc('"', f);
    for (; s && *s; s++)
        if (*s == '"' || *s == '\\')
            fprintf(f, "\\%c", *s);
        else if ((unsigned char)*s < 32 || (unsigned char)*s > 126)
            fprintf(f, "\\%03o", (unsigned char)*s);
        else
            fputc(*s, f);
    fputc('"', f);
}

static void u32s(FILE *f, const char *pre, const char *what, const uint32_t *v, uint32_t n)
{
    fprintf(f, "static uint32_t %s_%s[] = {", pre, what);
    for (uint32_t i = 0; i < n; i++)
        fprintf(f, "%u, ", (unsigned)v[i]);
    fputs("0};\n", f);
}

static void names(FILE *f, const char *pre, const char *what, const char *const *v, uint32_t n)
{
    fprintf(f, "static const char *%s_%s[] = {", pre, what);
    for (uint32_t i = 0; i < n; i++)
        cstr(f, v[i]), fputs(", ", f);
    fputs("NULL};\n", f);
}

/* n values (double, or real_t when real), in 17 digits: read back, the same bits */
static void values(FILE *f, const char *pre, const char *what, const void *v, uint32_t n,
                   int real)
{
    fprintf(f, "static %s %s_%s[] = {", real ? "real_t" : "double", pre, what);
    for (uint32_t i = 0; v && i < n; i++)
        fprintf(f, "%.17g, ", real ? (double)((const real_t *)v)[i] : ((const double *)v)[i]);
    fputs("0};\n", f);
}

/* the model's variables: only what fmu_inst.c reads of them (name, causality,
   variability) */
static void variables(FILE *f, const char *pre, const fmu_md *md)
{
    fprintf(f, "static fmu_var %s_v[] = {\n", pre);
    for (uint32_t i = 0; i < md->nv; i++) {
        fputs("    {.name = ", f);
        cstr(f, md->v[i].name);
        fprintf(f, ", .vr = %u, .causality = %u, .variability = %u},\n", (unsigned)md->v[i].vr,
                md->v[i].causality, md->v[i].variability);
    }
    fputs("    {.name = NULL}};\n", f);
}

/* the FMU's functions by their prefixed names, declared and bound */
static void functions(FILE *f, const fmu_md *md, int decl)
{
#define FMU_X_NAME(n) #n,
    static const char *const f2[] = {FMU_FMI2_LIST(FMU_X_NAME) NULL,
                                     FMU_FMI2_STATE_LIST(FMU_X_NAME) NULL};
    static const char *const f3[] = {FMU_FMI3_LIST(FMU_X_NAME) NULL,
                                     FMU_FMI3_STATE_LIST(FMU_X_NAME) NULL};
#undef FMU_X_NAME
    /* the calls, then (an FMU that can save its state) the FMU state's */
    const char *const *n = md->version == 2 ? f2 : f3;
    for (int part = 0; part < 1 + md->can_state; part++, n++)
        for (; *n; n++)
            if (decl)
                fprintf(f, "extern %sTYPE %s_%s;\n", *n, md->me_id, *n);
            else
                fprintf(f, "        .%s = %s_%s,\n", *n, md->me_id, *n);
}

int fmu_emit(const fmu_inst *in, FILE *f, char *err, size_t errlen)
{
    const fmu_model *m = in->m;
    const fmu_md *md = &m->md;
    const rt_kind *k = &in->kind;
    char pre[80], src[4200];
    snprintf(src, sizeof src, "%s/sources", m->dir);
    struct stat st;
    if (stat(src, &st) != 0 || !S_ISDIR(st.st_mode)) {
        snprintf(err, errlen, "%s ships no sources (sources/): an image compiles an FMU from "
                 "its sources, a binary for the host cannot go into it", m->path);
        return -1;
    }
    snprintf(pre, sizeof pre, "fmu_%s", in->block);
    fprintf(f, "\n/* FMU block %s: %s, FMI %s, built from its sources */\n// fmu-build: %s %d "
               "%s %s/sources ", in->block, md->model_name, md->fmi_version, in->block,
            md->version, md->me_id, m->dir);
    if (fmu_source_words(m, f, err, errlen) != 0)
        return -1;
    fputc('\n', f);
    functions(f, md, 1);
    variables(f, pre, md);
    u32s(f, pre, "iu", m->iu, m->nu), u32s(f, pre, "iy", m->iy, m->ny);
    u32s(f, pre, "ip", m->ip, m->np), u32s(f, pre, "ix", m->ix, m->nx);
    u32s(f, pre, "idx", m->idx, m->nx), u32s(f, pre, "vu", m->vu, m->nu);
    u32s(f, pre, "vy", m->vy, m->ny), u32s(f, pre, "vp", m->vp, m->np);
    u32s(f, pre, "vx", m->vx, m->nx);
    names(f, pre, "un", m->u_names, m->nu), names(f, pre, "yn", m->y_names, m->ny);
    names(f, pre, "pn", m->p_names, m->np), names(f, pre, "xn", m->x_names, m->nx);
    values(f, pre, "pdef", m->p_def, m->np, 1), values(f, pre, "xdef", m->x_def, m->nx, 1);
    fprintf(f, "static uint8_t %s_ud[] = {", pre);
    for (uint32_t i = 0; i < m->nu; i++)
        fprintf(f, "%u, ", m->u_disc[i]);
    fputs("0};\n", f);
    fprintf(f, "static uint8_t %s_feed[] = {", pre);
    for (uint32_t i = 0; i < m->ny * m->nu; i++)
        fprintf(f, "%u, ", m->feed[i]);
    fputs("0};\n", f);
    fprintf(f, "static fmu_model %s_m = {\n    .path = ", pre);
    cstr(f, m->path);
    fprintf(f, ",\n    .md = {.version = %d, .fmi_version = ", md->version);
    cstr(f, md->fmi_version), fputs(", .model_name = ", f), cstr(f, md->model_name);
    fputs(", .token = ", f), cstr(f, md->token), fputs(", .me_id = ", f), cstr(f, md->me_id);
    fprintf(f, ",\n           .v = %s_v, .nv = %u, .n_indicators = %u, .can_state = %u},\n"
               "    .f%d = {\n", pre, (unsigned)md->nv, (unsigned)md->n_indicators,
            (unsigned)md->can_state, md->version);
    functions(f, md, 0);
    fprintf(f, "    },\n    .ops = &fmu_ops%d, .nu = %u, .ny = %u, .np = %u, .nx = %u, .nz = %u,\n",
            md->version, (unsigned)m->nu, (unsigned)m->ny, (unsigned)m->np, (unsigned)m->nx,
            (unsigned)m->nz);
    fprintf(f, "    .iu = %s_iu, .iy = %s_iy, .ip = %s_ip, .ix = %s_ix, .idx = %s_idx,\n"
               "    .vu = %s_vu, .vy = %s_vy, .vp = %s_vp, .vx = %s_vx,\n"
               "    .u_names = %s_un, .y_names = %s_yn, .p_names = %s_pn, .x_names = %s_xn,\n"
               "    .p_def = %s_pdef, .x_def = %s_xdef, .feed = %s_feed, .feed_class = %d,\n"
               "    .u_disc = %s_ud, .instants = %u, .units = ", pre, pre, pre, pre, pre, pre,
            pre, pre, pre, pre, pre, pre, pre, pre, pre, pre, (int)m->feed_class, pre,
            (unsigned)m->instants);
    cstr(f, m->units);
    fputs(", .ninst = 1};\n", f);
    /* the instance: its buffers, the scene's state starts, the root directions */
    uint32_t nb = m->nx > m->ny ? m->nx : m->ny;
    nb = nb > m->nz ? nb : m->nz;
    nb = nb > m->nu ? nb : m->nu;
    fprintf(f, "static double %s_x[%u], %s_u[%u], %s_p[%u], %s_buf[%u], %s_evx[%u];\n", pre,
            (unsigned)m->nx + 1, pre, (unsigned)m->nu + 1, pre, (unsigned)m->np + 1, pre,
            (unsigned)nb + 1, pre, (unsigned)m->nx + 1);
    values(f, pre, "xs", in->x_start, m->nx, 0);
    fprintf(f, "static uint8_t %s_xg[] = {", pre);
    for (uint32_t i = 0; i < m->nx; i++)
        fprintf(f, "%u, ", in->x_given[i]);
    fprintf(f, "0};\nstatic int8_t %s_rd[] = {", pre);
    for (uint32_t i = 0; i <= m->nz; i++)
        fprintf(f, "%d, ", in->root_dir[i]);
    fprintf(f, "0};\nstatic fmu_inst %s_i = {.m = &%s_m, .block = ", pre, pre);
    cstr(f, in->block);
    fprintf(f, ", .root_dir = %s_rd, .x = %s_x, .u = %s_u,\n    .p = %s_p, .buf = %s_buf, "
               ".ev_x = %s_evx, .x_start = %s_xs, .x_given = %s_xg};\n", pre, pre, pre, pre,
            pre, pre, pre, pre);
    /* the kind */
    char ft[96];
    snprintf(ft, sizeof ft, "%s_feed", pre);
    fprintf(f, "static const rt_kind %s_kind = {\n    .name = ", pre);
    cstr(f, k->name);
    fprintf(f, ", .type = %s, .nu = %u, .ny = %u, .nx = %u, .np = %u, .nr = %u,\n",
            k->type == RT_KIND_NSS ? "RT_KIND_NSS" : "RT_KIND_OUTPUT", k->nu, k->ny, k->nx,
            k->np, k->nr);
    fprintf(f, "    .u_names = %s_un, .y_names = %s_yn, .x_names = %s_xn, .p_names = %s_pn,\n"
               "    .p_default = %s_pdef, .x_default = %s_xdef, .feed = %d, .feed_table = %s,\n"
               "    .root_dir = %s_rd, .check = fmu_check, .output = %s, .deriv = %s,\n"
               "    .roots = %s, .event = %s, .save = fmu_save, .restore = fmu_restore,\n"
               "    .spec = &%s_i, .units = ",
            pre, pre, pre, pre, pre, pre, (int)k->feed,
            k->feed_table ? ft : "NULL", pre,
            k->output ? "fmu_output" : "NULL", k->deriv ? "fmu_deriv" : "NULL",
            k->roots ? "fmu_roots" : "NULL", k->event ? "fmu_event" : "NULL", pre);
    cstr(f, k->units);
    fputs(", .doc = ", f), cstr(f, k->doc);
    fprintf(f, ",\n    .next_event = fmu_next_event, .time_event = fmu_time_event, "
               ".step_end = %s, .roots_every_sign = %u,\n    .instant = %s, .u_discrete = %s_ud};\n",
            k->step_end ? "fmu_step_end" : "NULL", (unsigned)k->roots_every_sign,
            k->instant ? "fmu_instant" : "NULL", pre);
    return 0;
}
