/* bouncing.c - test FMU: a ball dropped from h = 1 m onto a floor (tests/fmi/): h' = v,
 * v' = -g; the event indicator h, and at its crossing with the ball falling v := -e v.
 * The same arithmetic as tests/fmi/scenes/ball_scn.scn, so both give the same bits. */
#include "fmi_model.h"

enum { H, DH, V, DV, G, E, Z };

void model_derivatives(model_data *m)
{
    m->v[DH] = m->v[V];
    m->v[DV] = -m->v[G];
}

void model_outputs(model_data *m) { m->v[Z] = m->v[H]; }

void model_indicators(const model_data *m, double *z) { z[0] = m->v[H]; }

int model_event(model_data *m, int *x_changed, int *has_next, double *next)
{
    (void)has_next, (void)next;
    if (m->v[H] <= 0 && m->v[V] < 0) {
        m->v[V] = -m->v[E] * m->v[V];
        *x_changed = 1;
    }
    return 0;
}
