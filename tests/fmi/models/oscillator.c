/* oscillator.c - test FMU: a damped oscillator driven by its input (tests/fmi/), a linear
 * state space with parameters: x1' = x2, x2' = -k x1 - c x2 + b u, y = x1. The same
 * arithmetic as tests/fmi/scenes/osc_scn.scn. */
#include "fmi_model.h"

enum { U, Y, X1, DX1, X2, DX2, K, C, B };

void model_derivatives(model_data *m)
{
    m->v[DX1] = m->v[X2];
    m->v[DX2] = -m->v[K] * m->v[X1] - m->v[C] * m->v[X2] + m->v[B] * m->v[U];
}

void model_outputs(model_data *m) { m->v[Y] = m->v[X1]; }

void model_indicators(const model_data *m, double *z) { (void)m, (void)z; }

int model_event(model_data *m, int *x_changed, int *has_next, double *next)
{
    (void)m, (void)x_changed, (void)has_next, (void)next;
    return 0;
}
