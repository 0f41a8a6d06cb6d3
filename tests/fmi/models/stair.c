/* stair.c - test FMU: a counter stepped by time events (tests/fmi/): y = k; the first
 * update after initialization schedules t = period; each time event at t >= next adds one
 * to k and schedules the next, so y(t) = floor(t / period). The output late counts the
 * times the importer set in continuous time past the announced event (fmi_glue.c). */
#include "fmi_model.h"

enum { Y, PERIOD, K, NEXT, LATE };

void model_derivatives(model_data *m) { (void)m; }

void model_outputs(model_data *m) { m->v[Y] = m->v[K]; }

void model_indicators(const model_data *m, double *z) { (void)m, (void)z; }

int model_event(model_data *m, int *x_changed, int *has_next, double *next)
{
    (void)x_changed;
    if (m->v[NEXT] == 0) { /* right after initialization */
        m->v[NEXT] = m->v[PERIOD];
    } else if (m->time >= m->v[NEXT]) {
        m->v[K] += 1;
        m->v[NEXT] = (m->v[K] + 1) * m->v[PERIOD];
    }
    *has_next = 1, *next = m->v[NEXT];
    return 0;
}
