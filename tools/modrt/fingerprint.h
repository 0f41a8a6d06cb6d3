/* fingerprint.h - a 64-bit hash of everything in a compiled scene that determines a run
 * (its tables, parameter values, initial states, schedule, link and the programs of its
 * interpreted defines): the replay log names its scene by it (mrlog.h), so a log is not
 * replayed against a scene that changed since it was recorded. */
#ifndef FINGERPRINT_H
#define FINGERPRINT_H

#include <stdint.h>

#include "rt.h"

/* FNV-1a 64 over the scene's contents in a fixed order (fingerprint.c lists them); the
   same scene in any process, on any host, gives the same value. */
uint64_t fp_scene(const rt_scene *sc);

#endif /* FINGERPRINT_H */
