/* study.h - per-set overrides of a run for studies (--method, --step, --tol, --accuracy,
 * --substeps, --newton SET=VALUE), so a study needs no generated scene files. */
#ifndef STUDY_H
#define STUDY_H

#include "rt.h"

#define STUDY_MAX 32 /* overrides on one command line */

typedef struct study_args {
    const char *opt[STUDY_MAX]; /* option name of each override, e.g. "method" */
    const char *val[STUDY_MAX]; /* its SET=VALUE */
    int n;
} study_args;

/* records one override; CLI_USAGE after one error line when there are too many */
int study_add(study_args *a, const char *opt, const char *val);
/* applies the overrides to a copy of sc's sets (sc->sets then points at the copy, which
   lives until the next call); CLI_OK, or CLI_USAGE after one line naming the bad value */
int study_apply(const study_args *a, rt_scene *sc);

#endif /* STUDY_H */
