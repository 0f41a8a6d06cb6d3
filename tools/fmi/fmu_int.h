/* fmu_int.h - the internals shared by the files of tools/fmi/ (fmu.h says which does what):
 * a loaded model with its bound functions and its interface, an instance, and the
 * version adapters that make FMI 2.0 and 3.0 one calling sequence. */
#ifndef FMU_INT_H
#define FMU_INT_H

#include "fmi_api.h"
#include "fmu.h"

/* the functions of each version modrt binds, as X(name): one list, expanded into the
   struct of pointers and the table of names dlsym looks up */
#define FMU_FMI2_LIST(X)                                                          \
    X(fmi2GetTypesPlatform) X(fmi2GetVersion) X(fmi2Instantiate) X(fmi2FreeInstance) \
    X(fmi2SetupExperiment) X(fmi2EnterInitializationMode) X(fmi2ExitInitializationMode) \
    X(fmi2Terminate) X(fmi2Reset) X(fmi2GetReal) X(fmi2SetReal) X(fmi2EnterEventMode) \
    X(fmi2NewDiscreteStates) X(fmi2EnterContinuousTimeMode) X(fmi2SetTime)          \
    X(fmi2SetContinuousStates) X(fmi2GetDerivatives) X(fmi2GetEventIndicators)      \
    X(fmi2GetContinuousStates) X(fmi2CompletedIntegratorStep)
#define FMU_FMI3_LIST(X)                                                          \
    X(fmi3GetVersion) X(fmi3InstantiateModelExchange) X(fmi3FreeInstance)          \
    X(fmi3EnterInitializationMode) X(fmi3ExitInitializationMode) X(fmi3EnterEventMode) \
    X(fmi3Terminate) X(fmi3Reset) X(fmi3GetFloat64) X(fmi3SetFloat64)              \
    X(fmi3UpdateDiscreteStates) X(fmi3EnterContinuousTimeMode) X(fmi3SetTime)      \
    X(fmi3SetContinuousStates) X(fmi3GetContinuousStateDerivatives)                \
    X(fmi3GetEventIndicators) X(fmi3GetContinuousStates)                           \
    X(fmi3GetNumberOfEventIndicators) X(fmi3GetNumberOfContinuousStates)            \
    X(fmi3CompletedIntegratorStep)

/* the FMU state's functions, bound only when the description says it has them
   (fmu_md.can_state): what a snapshot of a run calls (fmu_state.c) */
#define FMU_FMI2_STATE_LIST(X)                                                    \
    X(fmi2GetFMUstate) X(fmi2SetFMUstate) X(fmi2FreeFMUstate)                     \
    X(fmi2SerializedFMUstateSize) X(fmi2SerializeFMUstate) X(fmi2DeSerializeFMUstate)
#define FMU_FMI3_STATE_LIST(X)                                                    \
    X(fmi3GetFMUState) X(fmi3SetFMUState) X(fmi3FreeFMUState)                     \
    X(fmi3SerializedFMUStateSize) X(fmi3SerializeFMUState) X(fmi3DeserializeFMUState)

typedef struct fmu_fns2 {
#define FMU_X_PTR(n) n##TYPE *n;
    FMU_FMI2_LIST(FMU_X_PTR)
    FMU_FMI2_STATE_LIST(FMU_X_PTR)
} fmu_fns2;
typedef struct fmu_fns3 {
    FMU_FMI3_LIST(FMU_X_PTR)
    FMU_FMI3_STATE_LIST(FMU_X_PTR)
#undef FMU_X_PTR
} fmu_fns3;

/* the result of one discrete-state update (fmi2NewDiscreteStates / fmi3UpdateDiscreteStates) */
typedef struct fmu_update {
    int again;              /* newDiscreteStatesNeeded / discreteStatesNeedUpdate */
    int terminate;
    int x_changed;          /* valuesOfContinuousStatesChanged */
    int has_next;           /* nextEventTimeDefined */
    double next;            /* nextEventTime [s] */
} fmu_update;

/* One calling sequence over both versions: each returns the FMI status (fmi2Status and
   fmi3Status number OK .. Fatal alike). */
typedef struct fmu_ops {
    const char *prefix;     /* "fmi2" or "fmi3": names the calls in messages */
    int (*instantiate)(fmu_inst *in);                 /* 0 or -1 (NULL instance) */
    int (*enter_init)(fmu_inst *in, double t0);       /* 2.0: with fmi2SetupExperiment */
    int (*exit_init)(fmu_inst *in);
    int (*update)(fmu_inst *in, fmu_update *u);
    int (*enter_ct)(fmu_inst *in);
    int (*enter_event)(fmu_inst *in);
    int (*set_time)(fmu_inst *in, double t);
    int (*set_x)(fmu_inst *in, const double *x, size_t n);
    int (*get_x)(fmu_inst *in, double *x, size_t n);
    int (*get_dx)(fmu_inst *in, double *dx, size_t n);
    int (*get_z)(fmu_inst *in, double *z, size_t n);
    /* CompletedIntegratorStep (noSetFMUStatePriorToCurrentPoint true unless the FMU can
       save its state: a snapshot may be restored): its two flags */
    int (*completed)(fmu_inst *in, int *enter_event, int *terminate);
    int (*get)(fmu_inst *in, const uint32_t *vr, size_t n, double *v);
    int (*set)(fmu_inst *in, const uint32_t *vr, size_t n, const double *v);
    int (*reset)(fmu_inst *in);
    int (*terminate)(fmu_inst *in);
    void (*free)(fmu_inst *in);
} fmu_ops;
extern const fmu_ops fmu_ops2, fmu_ops3;

struct fmu_model {
    char *path, *dir, *lib;     /* the file, where it is unpacked, its binary */
    fmu_md md;
    void *so;                   /* dlopen handle */
    fmu_fns2 f2;
    fmu_fns3 f3;
    const fmu_ops *ops;
    /* the interface: variable indices (into md.v) and value references, in kind order */
    uint32_t nu, ny, np, nx, nz;
    uint32_t *iu, *iy, *ip, *ix, *idx;  /* ix: the states, idx: their derivatives */
    uint32_t *vu, *vy, *vp, *vx;
    const char **u_names, **y_names, **p_names, **x_names; /* scene-language names */
    real_t *p_def, *x_def;
    uint8_t *feed;              /* ny*nu */
    uint8_t *u_disc;            /* nu: 1 for an input of discrete variability (taken only
                                   in event mode, at an instant: rt_kind.u_discrete) */
    uint8_t instants;           /* a discrete input or a tunable parameter: the kind's
                                   rt_kind.instant */
    rt_feed feed_class;
    const char *units;          /* rt_kind.units */
    int ninst;
    fmu_model *next;
};

/* an instance's life: modrt calls only what the mode allows */
typedef enum { FMU_M_NONE = 0, FMU_M_CT, FMU_M_EVENT, FMU_M_DEAD } fmu_mode;

struct fmu_inst {
    fmu_model *m;
    char *block;                /* the block's name: the instance name */
    void *c;                    /* fmi2Component or fmi3Instance */
    fmi2CallbackFunctions cb2;  /* FMI 2.0: the callbacks the FMU keeps a pointer to */
    rt_kind kind;               /* this block's kind; spec points here */
    int8_t *root_dir;
    uint8_t mode;               /* fmu_mode */
    uint8_t fresh;              /* initialized, no event since: a restart may reuse it */
    uint8_t t_valid, x_valid, u_valid;
    double t;                   /* what the FMU holds now */
    double *x, *u, *p;          /* nx, nu, np */
    double *buf;                /* scratch of max(nx, ny, nz, nu) */
    uint8_t has_next;           /* a time event is pending at t_next */
    double t_next;
    double ev_t;                /* the last event: its time and the states after it */
    double *ev_x;
    uint8_t ev_valid;
    uint8_t fatal;              /* a call returned Fatal: no further call at all */
    double *x_start;            /* the scene's state starts (where x_given), set before every
                                   initialization */
    uint8_t *x_given;
    /* what went wrong */
    unsigned long faults, warnings, events;
    unsigned long steps_done;   /* CompletedIntegratorStep calls */
    uint32_t iter_max;          /* most discrete-state updates of one event iteration */
    double fault_t;
    char fault[FMU_ERR_LEN];    /* the first fault: call, status, logged message */
    char log[FMU_ERR_LEN];      /* the message the FMU logged last */
    void *fstate;               /* the FMU state a snapshot goes through (fmu_state.c):
                                   made by the first, reused by every later one */
};

/* fmu_inst.c: the services of an FMU block's kind (rt_kind.spec is its fmu_inst) */
void fmu_output(const rt_args *a, real_t *y);
void fmu_deriv(const rt_args *a, real_t *xdot);
void fmu_roots(const rt_args *a, real_t *r);
void fmu_event(const rt_args *a, uint16_t which, real_t *x, real_t *d);
real_t fmu_next_event(const rt_args *a);
void fmu_time_event(const rt_args *a, real_t *x, real_t *d);
int fmu_step_end(const rt_args *a, real_t *x, real_t *d);
int fmu_instant(const rt_args *a, real_t *x, real_t *d);
rt_status fmu_check(const real_t *p, const void *spec);
/* the status of an FMI call the instance made: 0 to go on, -1 after the fault is counted
   (Discard, Error, Fatal: the instance is dead after Error and Fatal) */
int fmu_status(fmu_inst *in, int s, const char *what, double t);

/* fmu_state.c: the block's internal state in a snapshot (rt_kind.save, rt_kind.restore):
   the importer's view of the instance and the FMU's serialized FMU state */
rt_status fmu_save(const void *spec, uint8_t *buf, uint32_t cap, uint32_t *n);
rt_status fmu_restore(const void *spec, const uint8_t *buf, uint32_t n);

/* fmu_arena.c: the memory an FMU in an image gets (FMI 2.0 allocateMemory, FMI 3.0's
   calloc compiled as fmu_arena_calloc): FMU_ARENA_BYTES, used only while instantiating */
void *fmu_arena_calloc(size_t n, size_t size);
void *fmu_arena_malloc(size_t size);
void fmu_arena_free(void *p);
size_t fmu_arena_used(void);    /* bytes handed out so far */

/* fmu_call.c: the bytes the FMI 2.0 FMUs of this process took, as the arena hands them out */
extern size_t fmu_alloc2_used;

/* fmu_build.c: the sources, definitions and include directories of a source FMU's build
   (relative to its sources/), written to f as words; 0, or -1 with a message in err */
int fmu_source_words(const fmu_model *m, FILE *f, char *err, size_t errlen);

/* fmu_emit.c: the C of FMU block `in` for a per-scene image (its model, instance and kind
   as static tables, fmu_<block>_kind); 0, or -1 with a message in err */
int fmu_emit(const fmu_inst *in, FILE *f, char *err, size_t errlen);

/* fmu_model.c: the scene-language name of an FMI name (every character outside
   [A-Za-z0-9_] becomes '_'; a leading digit gets a '_'); malloc'd */
char *fmu_scene_name(const char *fmi_name);
/* fmu_build.c: a source FMU's binary for this host built from its sources/ into lib;
   0, or -1 with a one-line message in err */
int fmu_build(const fmu_model *m, const char *lib, char *err, size_t errlen);
/* fmu_inst.c: the instances of the process, for the summary */
extern fmu_inst *fmu_instances[FMU_MAX_INSTANCES];
extern int fmu_ninstances;

#endif /* FMU_INT_H */
