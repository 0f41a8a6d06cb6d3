/* info.h - what `modrt info` and `modrt kinds` print: a scene as initialised (blocks with
 * their parameter values, wiring, sets by name, schedule, order, loops), or a block kind
 * from its const table (ports, states and parameters with defaults and units, equations),
 * as text or as JSON for scripts; and docs/blocks.md from the same tables. */
#ifndef INFO_H
#define INFO_H

#include <stdio.h>

#include "rt.h"

/* The registered kind called name, or NULL. */
const rt_kind *info_find_kind(const char *name);
/* Prints a scene initialised in sim; init is rt_init's status. */
void info_scene(FILE *f, const rt_scene *sc, const rt_sim *sim, rt_status init, int json);
/* Prints a kind's reference. */
void info_kind(FILE *f, const rt_kind *k, int json);
/* Prints one line per registered kind: name, type, one-line summary. */
void info_kinds(FILE *f);
/* The joint kind of that name (rt_joint_kinds), or NULL; its reference text. */
const rt_joint_kind *info_find_joint(const char *name);
void info_joint(FILE *f, const rt_joint_kind *k);
/* Writes the block reference (docs/blocks.md) of every registered kind. */
void info_blocks_md(FILE *f);

#endif /* INFO_H */
