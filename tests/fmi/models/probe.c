/* probe.c - test FMU for discrete inputs and tunable parameters changed during a run
 * (tests/fmi/): x' = ud integrates the discrete input, w' = q the tunable parameter. In
 * event mode (the only mode in which FMI lets either change) each new value of ud is
 * counted in n with its time in tu, each new value of q in nq with its time in tq; nev
 * counts the discrete-state updates after the start (a continuous input, uc, needs none:
 * yc = uc). The glue counts in wrong every SetReal / SetFloat64 that gives ud or q a new
 * value in continuous-time mode, which FMI forbids (fmi_glue.c, MODEL_WRONG). */
#include "fmi_model.h"

enum { UD, UC, Q, X, DX, W, DW, N, TU, NQ, TQ, NEV, WRONG, YC, USEEN, QSEEN };

void model_derivatives(model_data *m) { m->v[DX] = m->v[UD], m->v[DW] = m->v[Q]; }

void model_outputs(model_data *m) { m->v[YC] = m->v[UC]; }

void model_indicators(const model_data *m, double *z) { (void)m, (void)z; }

int model_event(model_data *m, int *x_changed, int *has_next, double *next)
{
    (void)x_changed, (void)has_next, (void)next;
    if (m->v[UD] != m->v[USEEN])
        m->v[N] += 1, m->v[TU] = m->time, m->v[USEEN] = m->v[UD];
    if (m->v[Q] != m->v[QSEEN])
        m->v[NQ] += 1, m->v[TQ] = m->time, m->v[QSEEN] = m->v[Q];
    if (m->time > 0)
        m->v[NEV] += 1;
    return 0;
}
