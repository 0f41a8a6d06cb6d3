/* fmu_cs_vars.h - the variables of a scene exported as an FMI 3.0 or 2.0 Co-Simulation FMU
 * (docs/fmi.md, "Export"), in value-reference order. One enumeration for both sides: the
 * exporter writes modelDescription.xml from it (tools/fmi/fmu_export.c) and the FMU's own
 * code (cs_slave.c) serves the values by it, so the two cannot number them differently.
 *
 *   vr 0                       time (independent)
 *   1 .. nrecs                 the recorded signals, in record order (outputs)
 *   then nexp                  the controller link's exports (outputs)
 *   then nimp                  the controller link's imports (inputs)
 *   then every block parameter (tunable parameters), block by block */
#ifndef FMU_CS_VARS_H
#define FMU_CS_VARS_H

#include "rt.h"

typedef enum { FMU_CS_TIME = 0, FMU_CS_REC, FMU_CS_EXP, FMU_CS_IMP, FMU_CS_PAR } fmu_cs_kind;

typedef struct fmu_cs_var {
    uint8_t kind;   /* fmu_cs_kind */
    uint16_t a;     /* REC: record index; EXP: export; IMP: import; PAR: block */
    uint16_t b;     /* PAR: parameter index */
} fmu_cs_var;

static inline uint32_t fmu_cs_nexp(const rt_scene *sc) { return sc->link ? sc->link->nexp : 0; }
static inline uint32_t fmu_cs_nimp(const rt_scene *sc) { return sc->link ? sc->link->nimp : 0; }

/* the number of variables (value references 0 .. n - 1) */
static inline uint32_t fmu_cs_count(const rt_scene *sc)
{
    uint32_t n = 1u + sc->nrecs + fmu_cs_nexp(sc) + fmu_cs_nimp(sc);
    for (uint16_t b = 0; b < sc->nblocks; b++)
        n += sc->blocks[b].kind->np;
    return n;
}

/* what value reference vr (< fmu_cs_count) stands for */
static inline fmu_cs_var fmu_cs_at(const rt_scene *sc, uint32_t vr)
{
    fmu_cs_var v = {FMU_CS_TIME, 0, 0};
    if (vr == 0)
        return v;
    vr -= 1;
    if (vr < sc->nrecs)
        return (fmu_cs_var){FMU_CS_REC, (uint16_t)vr, 0};
    vr -= sc->nrecs;
    if (vr < fmu_cs_nexp(sc))
        return (fmu_cs_var){FMU_CS_EXP, (uint16_t)vr, 0};
    vr -= fmu_cs_nexp(sc);
    if (vr < fmu_cs_nimp(sc))
        return (fmu_cs_var){FMU_CS_IMP, (uint16_t)vr, 0};
    vr -= fmu_cs_nimp(sc);
    for (uint16_t b = 0; b < sc->nblocks; b++) {
        if (vr < sc->blocks[b].kind->np)
            return (fmu_cs_var){FMU_CS_PAR, b, (uint16_t)vr};
        vr -= sc->blocks[b].kind->np;
    }
    return v;
}

/* the name of signal r's port (output, state or discrete state) */
static inline const char *fmu_cs_signal(const rt_scene *sc, const rt_rec *r)
{
    const rt_kind *k = sc->blocks[r->block].kind;
    const char *const *n = r->what == RT_SIG_X ? k->x_names
                         : r->what == RT_SIG_D ? k->d_names : k->y_names;
    return r->what == RT_SIG_MBS && sc->mbs ? sc->mbs->signal_name(sc, r->block, r->index)
         : n ? n[r->index] : "?";
}

/* a parameter's value as the scene gives it (the block's, else the kind's default) */
static inline real_t fmu_cs_param0(const rt_scene *sc, uint16_t b, uint16_t j)
{
    const rt_block *bl = &sc->blocks[b];
    return bl->p ? bl->p[j] : bl->kind->p_default ? bl->kind->p_default[j] : 0;
}

#endif /* FMU_CS_VARS_H */
