/* liftoff.c - test FMU (tests/fmi/): the bouncing ball whose gravity is a relation set in
 * event mode only: h' = v, v' = contact ? 0 : -g, contact := (h <= 0) at every event, and
 * at an impact (h <= 0 falling) v := -e v. An impact leaves h just below 0 moving up, with
 * contact true: only the event at the return of h to h > 0 (the lift-off) sets it false
 * again, so the ball flies as the plain bouncing ball only if the importer reports that
 * sign change; without it the ball leaves the floor at constant speed. */
#include "fmi_model.h"

enum { H, DH, V, DV, G, E, Z, CONTACT };

void model_derivatives(model_data *m)
{
    m->v[DH] = m->v[V];
    m->v[DV] = m->v[CONTACT] != 0 ? 0 : -m->v[G];
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
    m->v[CONTACT] = m->v[H] <= 0;
    return 0;
}
