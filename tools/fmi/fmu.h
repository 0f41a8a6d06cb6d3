/* fmu.h - FMUs on the host (docs/fmi.md): an FMI 2.0 or 3.0 Model Exchange FMU file becomes
 * a block kind made at run time, like a define of the scene language. The parts:
 *
 *   fmu_zip.c    the archive: unpacked by libzip into a cache directory, entries that would
 *                leave it refused
 *   fmu_md.c     modelDescription.xml, read by expat (fmu_md.h)
 *   fmu_model.c  one FMU file: its description, its binary (dlopen), the interface modrt
 *                maps onto a kind (inputs, outputs, parameters, states, event indicators)
 *   fmu_build.c  a source FMU's binary for the host, built from its sources/
 *   fmu_inst.c   one block: the FMU instance, its initialization and the rt_kind services
 *                (output, deriv, roots, event, check) that drive it
 *   fmu_state.c  one block's internal state in a snapshot of the run (rt_kind.save,
 *                rt_kind.restore): the FMU's serialized FMU state
 *   fmu_info.c   `modrt info FILE.fmu` and the run summary's FMU lines
 *
 * The runtime (rt/) sees only an rt_kind; whatever an FMU does wrong at run time is a NaN
 * the runtime counts with the block (nan), and the FMU's own account (the call, its status
 * and the message it logged) is kept here for the summary. */
#ifndef FMU_H
#define FMU_H

#include <stdio.h>

#include "fmu_md.h"
#include "rt.h"

#define FMU_MAX_INSTANCES 64          /* FMU blocks of one process */
#define FMU_EVENT_ITER_MAX 64         /* discrete-state updates of one event iteration */
#define FMU_MAX_ENTRIES 65536u        /* entries of one FMU archive */
#define FMU_MAX_UNPACKED (1ull << 30) /* bytes of one FMU unpacked */
#define FMU_ARENA_ALIGN 8u            /* of every block the arena hands out: the strictest
                                         alignment of the targets' scalars */
#ifndef FMU_ARENA_BYTES
#define FMU_ARENA_BYTES 16384         /* an image's static memory for its FMUs' instances */
#endif

typedef struct fmu_model fmu_model;
typedef struct fmu_inst fmu_inst;

/* Unpacks the FMU at path into the cache (MODRT_FMU_CACHE, else $XDG_CACHE_HOME/modrt/fmu,
   else $HOME/.cache/modrt/fmu) under the hash of its bytes, or finds it there. Returns the
   directory (malloc'd), or NULL with a one-line message in err. */
char *fmu_unpack(const char *path, char *err, size_t errlen);

/* Loads an FMU file: unpacks it, reads its description, opens its binary and checks both
   agree. NULL with a one-line message in err. A file loaded twice is loaded once. */
fmu_model *fmu_model_load(const char *path, char *err, size_t errlen);
const fmu_md *fmu_model_md(const fmu_model *m);

/* A block of kind FMU: its own kind (names and sizes from the model; services that drive an
   instance of it named `block`). NULL with a message in err. */
fmu_inst *fmu_inst_new(fmu_model *m, const char *block, char *err, size_t errlen);
const rt_kind *fmu_inst_kind(const fmu_inst *in);
/* What identifies the code an FMU block's kind runs: the hash of its FMU file's bytes (the
   name of its cache directory), for the replay log's scene fingerprint; NULL for a kind
   that is not an FMU's. */
const char *fmu_kind_file_id(const rt_kind *k);
/* Instantiates and initializes the FMU with parameters p and, where given[i], initial
   state x0[i] (its variable's start value); writes the states it starts from into x0.
   0, or -1 with a one-line message in err. */
int fmu_inst_start(fmu_inst *in, const real_t *p, real_t *x0, const uint8_t *given,
                   char *err, size_t errlen);

/* The bytes of FMU_ARENA_BYTES an image of this process's FMU blocks needs: what their
   instantiation, initialization and one FMU state (the first snapshot's) took here, as
   the arena hands it out (FMI 2.0: through allocateMemory; 3.0 source FMUs: their calloc,
   counted by fmu_count.c); 0 without FMU blocks; -1 when an FMU's is not known (a 3.0
   binary, not built here from its sources). Measured on this host: an upper bound on a
   target whose pointers and longs are narrower (the 32-bit ones). */
long fmu_arena_need(void);

/* The FMU lines of a run summary: per FMU block its faults, the first with its time, the
   call, its status and the message the FMU logged. Nothing without FMU blocks. */
void fmu_summary(FILE *f);
/* Each FMU block's tally, what fmu_summary prints (faults, warnings, events, event
   iterations, completed integrator steps, the first fault), for `modrt check`, whose runs
   share the instances: fmu_tally_keep copies every instance's into slot `run` (0 ..
   FMU_TALLY_RUNS - 1), fmu_tally_use puts slot `run`'s in place, fmu_tally_use_since
   slot `run`'s with the faults met since slot `since` was kept added (the first of them
   where `run` had none), fmu_tally_zero starts every instance's afresh. */
#define FMU_TALLY_RUNS 3
void fmu_tally_keep(int run);
void fmu_tally_use(int run);
void fmu_tally_use_since(int run, int since);
void fmu_tally_zero(void);
/* `modrt info FILE.fmu`: the model, its interface and every variable (causality,
   variability, type, unit, start). 0, or -1 with the message on stderr. */
int fmu_info(FILE *f, const char *path);
/* Does the argument name an FMU file (it ends in ".fmu")? */
int fmu_is_file(const char *arg);

#endif /* FMU_H */
