/* fmu_scn.c - the FMU loader the scene language calls (scn_fmu_ops, tools/scenec/scn.h):
 * a block's kind from an FMU file, its start once the scene's values are known, and its C
 * for a per-scene image. */
#include "fmu_scn.h"

#include "fmu_int.h"

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
