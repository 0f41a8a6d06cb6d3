/* fmu_md.h - what modrt reads from an FMU's modelDescription.xml (FMI 2.0 and 3.0): the
 * model's identity, its Model Exchange interface, its variables and its model structure
 * (state derivatives, outputs and their dependencies, event indicators). Parsed by expat
 * (fmu_md.c); nothing here touches the file system, so the reader can be fuzzed alone. */
#ifndef FMU_MD_H
#define FMU_MD_H

#include <stddef.h>
#include <stdint.h>

#define FMU_MD_MAX_BYTES (64u << 20) /* largest modelDescription.xml read */
#define FMU_MD_MAX_VARS 100000u      /* variables of one model */
#define FMU_MD_MAX_DEPTH 32          /* element nesting */
#define FMU_ERR_LEN 512              /* characters of an error message */

/* causality and variability, as the standard names them (fmu_md_causality_name) */
typedef enum {
    FMU_C_LOCAL = 0, FMU_C_PARAMETER, FMU_C_CALCULATED, FMU_C_INPUT, FMU_C_OUTPUT,
    FMU_C_INDEPENDENT, FMU_C_STRUCTURAL, FMU_C_COUNT
} fmu_causality;
typedef enum {
    FMU_V_CONTINUOUS = 0, FMU_V_CONSTANT, FMU_V_FIXED, FMU_V_TUNABLE, FMU_V_DISCRETE,
    FMU_V_COUNT
} fmu_variability;

typedef struct fmu_var {
    const char *name, *desc, *unit; /* unit: its own, else its declared type's; or NULL */
    const char *type;       /* element of its type: Real, Integer ... (2.0), Float64 ... (3.0) */
    uint32_t vr;            /* value reference */
    uint8_t causality;      /* fmu_causality */
    uint8_t variability;    /* fmu_variability */
    uint8_t float64;        /* 1: an FMI 2.0 Real or FMI 3.0 Float64 scalar */
    uint8_t array;          /* 1: an FMI 3.0 array variable (has Dimension) */
    uint8_t has_start;
    double start;           /* start value (float64 variables with has_start) */
    int64_t derivative;     /* of which state it is the derivative: 2.0 the 1-based index of
                               that state's variable, 3.0 its value reference; -1 none */
    uint32_t line;          /* where it is declared in modelDescription.xml */
} fmu_var;

/* one <Unknown> (2.0) or <Output> (3.0) of ModelStructure/Outputs */
typedef struct fmu_out {
    int64_t ref;            /* 2.0: 1-based variable index; 3.0: value reference */
    int64_t *deps;          /* its dependencies, same kind of reference */
    uint32_t ndeps;
    uint8_t has_deps;       /* 0: the attribute is absent (depends on everything) */
} fmu_out;

typedef struct fmu_md {
    int version;                    /* 2 or 3 */
    const char *fmi_version, *model_name, *token; /* token: guid (2.0) or
                                                     instantiationToken (3.0) */
    const char *me_id;              /* modelIdentifier of <ModelExchange>, NULL: none */
    const char *cs_id;              /* modelIdentifier of <CoSimulation>, NULL: none */
    const char *tool;               /* generationTool, or NULL */
    const char **sources;           /* 2.0: <ModelExchange><SourceFiles><File name>: the C
                                       files of a source FMU, under sources/ */
    uint32_t nsources;
    uint8_t needs_step_done;        /* the FMU asks for CompletedIntegratorStep calls */
    uint8_t once_per_process;       /* canBeInstantiatedOnlyOncePerProcess */
    uint8_t can_state;              /* canGetAndSetFMUstate and canSerializeFMUstate (2.0),
                                       canGetAndSetFMUState and canSerializeFMUState (3.0) */
    uint32_t n_indicators;          /* 2.0: numberOfEventIndicators; 3.0: EventIndicator
                                       elements */
    fmu_var *v;
    uint32_t nv;
    int64_t *der;                   /* ModelStructure derivatives in state order (2.0:
                                       1-based variable index; 3.0: value reference) */
    uint32_t nder;
    fmu_out *out;
    uint32_t nout;
    void *arena;                    /* everything above is carved from here */
} fmu_md;

/* Parses the n bytes of a modelDescription.xml. Returns 0, or -1 with a one-line message
   in err ("modelDescription.xml:LINE: WHAT"). Free with fmu_md_free either way. */
int fmu_md_parse(const char *xml, size_t n, fmu_md *md, char *err, size_t errlen);
void fmu_md_free(fmu_md *md);
/* The variable a ModelStructure reference names (2.0 index, 3.0 value reference of a
   float64 variable first), or -1. */
int64_t fmu_md_find(const fmu_md *md, int64_t ref);
const char *fmu_md_causality_name(int c);
const char *fmu_md_variability_name(int v);

#endif /* FMU_MD_H */
