/* feedthrough.c - test FMU: outputs that depend directly on inputs (tests/fmi/):
 * y = gain u1 + offset, y2 = u2; no states. */
#include "fmi_model.h"

enum { U1, U2, Y, Y2, GAIN, OFFSET };

void model_derivatives(model_data *m) { (void)m; }

void model_outputs(model_data *m)
{
    m->v[Y] = m->v[GAIN] * m->v[U1] + m->v[OFFSET];
    m->v[Y2] = m->v[U2];
}

void model_indicators(const model_data *m, double *z) { (void)m, (void)z; }

int model_event(model_data *m, int *x_changed, int *has_next, double *next)
{
    (void)m, (void)x_changed, (void)has_next, (void)next;
    return 0;
}
