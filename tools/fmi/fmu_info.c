/* fmu_info.c - what modrt prints about FMUs: `modrt info FILE.fmu` (the model, how it maps
 * onto a block kind, every variable with causality, variability, type, unit and start) and
 * the FMU lines of a run summary (faults, the first one with its call, status, time and
 * the FMU's logged message; event iterations, CompletedIntegratorStep calls). */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fmu_int.h"

void fmu_summary(FILE *f)
{
    for (int i = 0; i < fmu_ninstances; i++) {
        const fmu_inst *in = fmu_instances[i];
        fprintf(f, "fmu.%s: %lu faults, %lu warnings, %lu events, event_iter_max %u",
                in->block, in->faults, in->warnings, in->events, (unsigned)in->iter_max);
        if (in->kind.step_end)
            fprintf(f, ", %lu completed integrator steps", in->steps_done);
        fputc('\n', f);
        if (in->faults)
            fprintf(f, "fmu.%s.first_fault: t = %.17g: %s\n", in->block, in->fault_t, in->fault);
    }
}

/* an instance's tally (fmu_inst's "what went wrong" fields) */
typedef struct tally {
    unsigned long faults, warnings, events, steps_done;
    uint32_t iter_max;
    double fault_t;
    char fault[FMU_ERR_LEN];
} tally;
static tally tallies[FMU_TALLY_RUNS][FMU_MAX_INSTANCES];

static void tally_copy(tally *to, const fmu_inst *in)
{
    to->faults = in->faults, to->warnings = in->warnings, to->events = in->events;
    to->steps_done = in->steps_done, to->iter_max = in->iter_max, to->fault_t = in->fault_t;
    memcpy(to->fault, in->fault, sizeof to->fault);
}

static void tally_put(fmu_inst *in, const tally *t)
{
    in->faults = t->faults, in->warnings = t->warnings, in->events = t->events;
    in->steps_done = t->steps_done, in->iter_max = t->iter_max, in->fault_t = t->fault_t;
    memcpy(in->fault, t->fault, sizeof in->fault);
}

void fmu_tally_keep(int run)
{
    for (int i = 0; i < fmu_ninstances && run >= 0 && run < FMU_TALLY_RUNS; i++)
        tally_copy(&tallies[run][i], fmu_instances[i]);
}

void fmu_tally_use(int run)
{
    for (int i = 0; i < fmu_ninstances && run >= 0 && run < FMU_TALLY_RUNS; i++)
        tally_put(fmu_instances[i], &tallies[run][i]);
}

void fmu_tally_use_since(int run, int since)
{
    for (int i = 0; i < fmu_ninstances && run >= 0 && run < FMU_TALLY_RUNS && since >= 0 &&
                    since < FMU_TALLY_RUNS; i++) {
        fmu_inst *in = fmu_instances[i];
        tally t = tallies[run][i];
        unsigned long met = in->faults - tallies[since][i].faults;
        if (t.faults == 0 && met > 0) /* (the instance's first since `since`'s, if it had none) */
            t.fault_t = in->fault_t, memcpy(t.fault, in->fault, sizeof t.fault);
        t.faults += met;
        tally_put(in, &t);
    }
}

void fmu_tally_zero(void)
{
    static const tally none;
    for (int i = 0; i < fmu_ninstances; i++)
        tally_put(fmu_instances[i], &none);
}

static int read_all(const char *path, char **buf, size_t *n)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return -1;
    fseek(f, 0, SEEK_END);
    long len = ftell(f);
    fseek(f, 0, SEEK_SET);
    *buf = len >= 0 && (unsigned long)len <= FMU_MD_MAX_BYTES ? malloc((size_t)len + 1) : NULL;
    *n = *buf ? fread(*buf, 1, (size_t)len, f) : 0;
    fclose(f);
    return *buf ? 0 : -1;
}

static void variables(FILE *f, const fmu_md *md)
{
    fprintf(f, "\n%-24s %-20s %-12s %-8s %-6s %-10s %s\n", "variable", "causality",
            "variability", "type", "vr", "unit", "start");
    for (uint32_t i = 0; i < md->nv; i++) {
        const fmu_var *v = &md->v[i];
        char start[40] = "";
        for (int prec = 1; v->has_start && prec <= 17; prec++) { /* shortest round trip */
            snprintf(start, sizeof start, "%.*g", prec, v->start);
            if (strtod(start, NULL) == v->start)
                break;
        }
        fprintf(f, "%-24s %-20s %-12s %-8s %-6u %-10s %s", v->name,
                fmu_md_causality_name(v->causality), fmu_md_variability_name(v->variability),
                v->type ? v->type : "?", (unsigned)v->vr, v->unit ? v->unit : "-", start);
        char *scene = fmu_scene_name(v->name);
        if (scene && strcmp(scene, v->name) != 0)
            fprintf(f, "  (scene name %s)", scene);
        free(scene);
        if (v->desc && *v->desc)
            fprintf(f, "  \"%s\"", v->desc);
        fputc('\n', f);
    }
}

int fmu_info(FILE *f, const char *path)
{
    char err[FMU_ERR_LEN], *xml = NULL;
    size_t n = 0;
    fmu_md md;
    char *dir = fmu_unpack(path, err, sizeof err);
    if (!dir) {
        fprintf(stderr, "modrt: %s\n", err);
        return -1;
    }
    size_t len = strlen(dir) + 32;
    char *p = malloc(len);
    snprintf(p, len, "%s/modelDescription.xml", dir);
    int rc = read_all(p, &xml, &n);
    free(p);
    free(dir);
    if (rc) {
        fprintf(stderr, "modrt: %s: cannot read its modelDescription.xml\n", path);
        return -1;
    }
    rc = fmu_md_parse(xml, n, &md, err, sizeof err);
    free(xml);
    if (rc) {
        fprintf(stderr, "modrt: %s: %s\n", path, err);
        fmu_md_free(&md);
        return -1;
    }
    uint32_t nc[FMU_C_COUNT] = {0};
    for (uint32_t i = 0; i < md.nv; i++)
        nc[md.v[i].causality]++;
    fprintf(f, "fmu: %s\nmodel: %s\nfmi_version: %s\ngeneration_tool: %s\n", path,
            md.model_name, md.fmi_version, md.tool ? md.tool : "-");
    fprintf(f, "model_exchange: %s\nco_simulation: %s\n", md.me_id ? md.me_id : "no",
            md.cs_id ? md.cs_id : "no");
    fprintf(f, "inputs: %u\noutputs: %u\nparameters: %u\nstates: %u\nevent_indicators: %u\n",
            (unsigned)nc[FMU_C_INPUT], (unsigned)nc[FMU_C_OUTPUT], (unsigned)nc[FMU_C_PARAMETER],
            (unsigned)md.nder, (unsigned)md.n_indicators);
    if (md.needs_step_done)
        fprintf(f, "note: the FMU asks for CompletedIntegratorStep: modrt calls it at the "
                   "end of every step of its set (docs/fmi.md)\n");
    variables(f, &md);
    fmu_md_free(&md);
    return 0;
}
