/* stepper.c - test FMU for CompletedIntegratorStep (tests/fmi/): x' = 1 from x = 0; n
 * counts the calls of CompletedIntegratorStep; the first call at which x >= at asks for
 * an event mode, which resets x := 0 and records its time in te. So n(t) = the steps of
 * its set completed by t, and x(t) = t up to the first step end at or past `at`, t - te
 * after it, with te that step end exactly. */
#include "fmi_model.h"

enum { X, DX, N, AT, TE, ASKED };

void model_derivatives(model_data *m) { m->v[DX] = 1; }

void model_outputs(model_data *m) { (void)m; }

void model_indicators(const model_data *m, double *z) { (void)m, (void)z; }

int model_event(model_data *m, int *x_changed, int *has_next, double *next)
{
    (void)has_next, (void)next;
    if (m->v[ASKED] == 1) { /* the event mode the step end asked for */
        m->v[ASKED] = 2;
        m->v[X] = 0, m->v[TE] = m->time;
        *x_changed = 1;
    }
    return 0;
}

int model_completed_step(model_data *m)
{
    m->v[N] += 1;
    if (m->v[ASKED] == 0 && m->v[X] >= m->v[AT]) {
        m->v[ASKED] = 1;
        return 1;
    }
    return 0;
}
