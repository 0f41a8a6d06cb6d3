/* fmu_scn.c - the FMU loader the scene language calls (scn_fmu_ops, tools/scenec/scn.h):
 * a block's kind from an FMU file, its start once the scene's values are known, and its C
 * for a per-scene image; and the limits of a per-scene build with the FMU arena its FMU
 * blocks need (`scenec --sizes`, `modrt sizes`, `scenec --fmu`). */
#define _POSIX_C_SOURCE 200809L /* open_memstream */
#include "fmu_scn.h"

#include <stdlib.h>

#include "fmu_int.h"
#include "scn_host.h"

static const rt_kind *kind(const char *path, const char *block, char *err, size_t n)
{
    fmu_model *m = fmu_model_load(path, err, n);
    fmu_inst *in = m ? fmu_inst_new(m, block, err, n) : NULL;
    return in ? fmu_inst_kind(in) : NULL;
}

static int start(const rt_kind *k, const real_t *p, real_t *x0, const uint8_t *given,
                 char *err, size_t n)
{
    return fmu_inst_start((fmu_inst *)k->spec, p, x0, given, err, n);
}

static int emit(FILE *f, const rt_kind *k, char *err, size_t n)
{
    return fmu_emit((const fmu_inst *)k->spec, f, err, n);
}

const scn_fmu_ops fmu_scn_ops = {kind, start, emit};

long fmu_scn_sizes(FILE *f, FILE *note, const char *path, const rt_scene *sc, const rt_sim *sim)
{
    char *line = NULL;
    size_t n = 0;
    FILE *m = open_memstream(&line, &n);
    if (m) /* (the sizes take the first FMU state, which the arena serves too) */
        scn_host_sizes(m, sc, sim), fclose(m);
    long arena = fmu_arena_need();
    if (line && n && line[n - 1] == '\n')
        line[--n] = 0;
    if (f) {
        fprintf(f, "%s", line ? line : "");
        if (arena > 0)
            fprintf(f, " -DFMU_ARENA_BYTES=%ld", arena);
        fputc('\n', f);
    }
    free(line);
    if (arena < 0 && note)
        fprintf(note, "%s: note: the FMU arena's size is not known (an FMI 3.0 FMU not built "
                "here from its sources)\n", path);
    return arena;
}
