/* fmi_model.h - what one test model (tests/fmi/models/<m>.c) provides to the FMI glue
 * (tests/fmi/fmi_glue.c), which turns it into an FMI 2.0 or FMI 3.0 Model Exchange FMU.
 * The model's values live in one array indexed by value reference; model_gen.h (written by
 * tests/fmi/mkfmu.py from models/<m>.json) gives their number, the start values, the value
 * references of the states and derivatives, the number of event indicators and the
 * instantiation token, so the C code and modelDescription.xml come from one description. */
#ifndef FMI_MODEL_H
#define FMI_MODEL_H

#include "model_gen.h" /* MODEL_NV, MODEL_NX, MODEL_NZ, MODEL_TOKEN, model_start[], ... */

typedef struct model_data {
    double v[MODEL_NV + 1];     /* every variable, by value reference */
    double time;                /* [s] */
} model_data;

/* the derivatives of the states (vr model_state[i]) into v[model_der[i]] */
void model_derivatives(model_data *m);
/* outputs (and other dependent values) from states, inputs, parameters and time */
void model_outputs(model_data *m);
/* the event indicators (MODEL_NZ values) */
void model_indicators(const model_data *m, double *z);
/* one discrete-state update in event mode (also the first, right after initialization):
   returns 1 when another is needed; sets *x_changed when it re-initialized a state, and
   *has_next with *next when a time event is pending */
int model_event(model_data *m, int *x_changed, int *has_next, double *next);
#ifdef MODEL_NEEDS_STEP
/* a model that needs CompletedIntegratorStep (its description says so): called at each;
   returns 1 to ask for an event mode there */
int model_completed_step(model_data *m);
#endif

#endif /* FMI_MODEL_H */
