/* fmu_scn.h - the FMU loader for the scene language (tools/fmi/fmu_scn.c): what a tool that
 * reads FMU systems passes to the scene compiler (scn_ctx.fmu). */
#ifndef FMU_SCN_H
#define FMU_SCN_H

#include "scn.h"

extern const scn_fmu_ops fmu_scn_ops;

#endif /* FMU_SCN_H */
