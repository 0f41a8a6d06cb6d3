/* fmu.c - FMU systems in a scene (`load system (P) of type (fmu) from file ("p.fmu");`,
 * docs/fmi.md): the file is found relative to the scene file that names it, and the kind
 * and the start come from the host's loader (scn_ctx.fmu, tools/fmi/) that the tool
 * compiling the scene names; a tool without one (scenec, the fuzzer) reports the system as
 * one it cannot read. Each FMU block has a kind of its own (its services drive its own
 * instance), made at compile time like the kinds of defines. */
#include "scn.h"

#include <stdlib.h>
#include <string.h>

const rt_kind *scn_fmu_kind(scn_ctx *c, scn_block *b)
{
    if (!b->unit) {
        scn_fail(c, b->type.pos, b->type.s, "an FMU system needs its file",
                 "load system (...) of type (fmu) from file (\"model.fmu\");");
        return NULL;
    }
    if (!c->fmu) {
        scn_fail(c, b->type.pos, b->type.s, "FMU systems run on the host only",
                 "modrt run FILE.scn or modrt info FILE.scn (scenec compiles library kinds and "
                 "defines to C)");
        return NULL;
    }
    /* relative to the scene file that names it */
    const char *scene = scn_path(c, b->type.pos), *slash = strrchr(scene, '/');
    const char *path = b->unit[0] == '/' || !slash ? b->unit
                     : scn_fmt(c, "%.*s/%s", (int)(slash - scene), scene, b->unit);
    char err[SCN_MSG_LEN];
    const rt_kind *k = c->fmu->kind(path, b->name.s, err, sizeof err);
    if (!k)
        scn_fail(c, b->type.pos, b->type.s, scn_fmt(c, "FMU of %s: %s", b->name.s, err),
                 "an FMI 2.0 or 3.0 Model Exchange FMU with a binary for this platform");
    b->fmu = k != NULL;
    return k;
}

void scn_fmu_start(scn_ctx *c)
{
    scn_scene *s = &c->sc;
    for (uint16_t i = 0; i < s->nblk && !c->err; i++) {
        scn_block *b = &s->blk[i];
        const rt_kind *k = b->kind;
        if (!b->fmu)
            continue;
        real_t *p = scn_alloc(c, (k->np + 1u) * sizeof *p);
        real_t *x0 = scn_alloc(c, (k->nx + 1u) * sizeof *x0);
        uint8_t *given = scn_alloc(c, k->nx + 1u);
        for (uint16_t j = 0; j < k->np; j++)
            p[j] = (real_t)b->p[j];
        for (uint16_t j = 0; j < k->nx; j++)
            x0[j] = (real_t)b->x0[j], given[j] = b->x_at[j] != 0;
        char err[SCN_MSG_LEN];
        if (c->fmu->start(k, p, x0, given, err, sizeof err) != 0) {
            scn_fail(c, b->name.pos, b->name.s, scn_fmt(c, "FMU %s does not start: %s",
                                                        b->name.s, err),
                     "an FMU that initializes with these values");
            return;
        }
        for (uint16_t j = 0; j < k->nx; j++)
            b->x0[j] = (double)x0[j];
        b->x_given = k->nx > 0;
    }
}
