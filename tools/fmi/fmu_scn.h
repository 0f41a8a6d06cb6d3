/* fmu_scn.h - the FMU loader for the scene language (tools/fmi/fmu_scn.c): what a tool that
 * reads FMU systems passes to the scene compiler (scn_ctx.fmu). */
#ifndef FMU_SCN_H
#define FMU_SCN_H

#include "scn.h"

extern const scn_fmu_ops fmu_scn_ops;

/* The exact limits of a per-scene build of sc (initialised in sim) as -D flags on one
   line of f (scn_host_sizes), then the static arena its FMU blocks need
   (-DFMU_ARENA_BYTES=N, fmu_arena_need, after the sizes: they take the first FMU state);
   f NULL: measured only. Returns the arena's bytes, 0 without FMU blocks, -1 when an FMU's
   is not known, which a note on note (if not NULL) says for the scene file path. */
long fmu_scn_sizes(FILE *f, FILE *note, const char *path, const rt_scene *sc,
                   const rt_sim *sim);

#endif /* FMU_SCN_H */
