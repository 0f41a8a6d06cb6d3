/* fmu_export.h - a compiled scene written as an FMI 3.0 or 2.0 Co-Simulation FMU
 * (fmu_export.c), what `scenec --fmu OUT.fmu [--fmi-version 2] FILE.scn` calls. */
#ifndef FMU_EXPORT_H
#define FMU_EXPORT_H

#include <stddef.h>

#include "scn.h"

/* Writes the FMI `version` (2 or 3) FMU of the scene compiled in c to out (sources, a binary
   for this host built by $CC, else cc, modelDescription.xml). 0, or -1 with a one-line
   message in err. */
int fmu_export(scn_ctx *c, const char *out, int version, char *err, size_t errlen);

#endif /* FMU_EXPORT_H */
