/* scn_host.h - scene files for hosts: what the modrt CLI calls so that `modrt run FILE.scn`
 * and `modrt info FILE.scn` compile a scene file in host memory and run it directly, its
 * defined systems evaluated by the scene compiler's bytecode interpreter. */
#ifndef SCN_HOST_H
#define SCN_HOST_H

#include <stdio.h>

#include "rt.h"

/* Does the command-line argument name a scene file (it ends in ".scn")? */
int scn_host_is_file(const char *arg);
struct scn_fmu_ops;
/* Compiles the scene file at path into host memory, its FMU systems read by fmu (NULL:
   none may appear); returns the scene (valid until the process ends), or NULL after
   printing "modrt: FILE:LINE:COL: error: ..." to stderr. */
const rt_scene *scn_host_load(const char *path, const struct scn_fmu_ops *fmu);
/* Writes the exact compile-time limits of a per-scene build of sc (initialised in sim)
   as -D flags on one line: what `scenec --sizes` and `modrt sizes` print. */
void scn_host_sizes(FILE *f, const rt_scene *sc, const rt_sim *sim);

/* v seconds as a whole number of base ticks of dt seconds (within RT_TICK_MATCH_REL of
   v), or 0: a set's step in the scene language and on modrt's command line, a sample
   period */
uint32_t scn_ticks(double v, double dt);

#endif /* SCN_HOST_H */
