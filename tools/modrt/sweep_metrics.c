/* sweep_metrics.c - the metrics a campaign asks of each run, folded in tick by tick from
 * the recorded signals (every tick, whatever --every the trace would use), in constant
 * memory: extremes, final value, RMS and mean (trapezoidal, over time, so they do not
 * depend on the tick), settling time into a band and overshoot past a target. A NaN
 * sample makes the metric NaN: a run that blew up never reports a fine maximum. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "sweep.h"

/* the recorded signal named Block.signal, or -1 */
static int find_rec(const rt_scene *sc, const char *name)
{
    char buf[2 * SWEEP_NAME];
    for (uint16_t i = 0; i < sc->nrecs; i++) {
        cli_rec_name(sc, i, buf, sizeof buf);
        if (strcmp(buf, name) == 0)
            return i;
    }
    return -1;
}

static void list_recs(const rt_scene *sc, char *buf, size_t n)
{
    size_t used = 0;
    buf[0] = 0;
    for (uint16_t i = 0; i < sc->nrecs && used + 1 < n; i++) {
        int w = snprintf(buf + used, n - used, "%s%s.%s", i ? ", " : "",
                         sc->blocks[sc->recs[i].block].name, rt_rec_signal(sc, i));
        used += w > 0 ? (size_t)w : 0;
    }
}

int sweep_metrics_bind(const sweep_campaign *c, const rt_scene *sc, sweep_acc *acc)
{
    for (int i = 0; i < c->nmetrics; i++) {
        const sweep_metric *m = &c->metrics[i];
        memset(&acc[i], 0, sizeof acc[i]);
        for (int j = 0; j < 2; j++) {
            acc[i].sig[j] = m->sig[j][0] ? (int16_t)find_rec(sc, m->sig[j]) : -1;
            if (m->sig[j][0] && acc[i].sig[j] < 0) {
                char recs[600];
                list_recs(sc, recs, sizeof recs);
                fprintf(stderr, "%s:%d:%d: error: scene %s records no signal '%s' (it "
                        "records: %s)\n", c->path, m->line[j], m->col[j], sc->name, m->sig[j], recs);
                return -1;
            }
        }
    }
    return 0;
}

/* one sample y at time t into metric m's accumulator */
static void fold(const sweep_metric *m, sweep_acc *a, double t, double y)
{
    int first = !a->started;
    if (y != y)
        a->nan = 1;
    if (first)
        a->y0 = y, a->v = y, a->aux = t, a->pending = 0, a->started = 1;
    switch (m->kind) {
    case SWEEP_M_MAX: a->v = y > a->v ? y : a->v; break;
    case SWEEP_M_MIN: a->v = y < a->v ? y : a->v; break;
    case SWEEP_M_MAXABS: a->v = first || fabs(y) > a->v ? fabs(y) : a->v; break;
    case SWEEP_M_FINAL: a->v = y; break;
    case SWEEP_M_RMS:
    case SWEEP_M_MEAN: {
        double f = m->kind == SWEEP_M_RMS ? y * y : y, fp = m->kind == SWEEP_M_RMS
                                                               ? a->y_prev * a->y_prev
                                                               : a->y_prev;
        if (first)
            a->v = 0, a->span = 0;
        else
            a->v += 0.5 * (f + fp) * (t - a->t_prev), a->span += t - a->t_prev;
        break;
    }
    case SWEEP_M_SETTLE: {
        int inside = y >= m->p[0] && y <= m->p[1];
        if (!inside)
            a->pending = 1;
        else if (a->pending)
            a->pending = 0, a->aux = t; /* entered again: the band holds from here on */
        break;
    }
    default: { /* overshoot past the target, in the direction from the start */
        double dir = m->p[0] >= a->y0 ? 1 : -1, e = (y - m->p[0]) * dir;
        a->v = first || e > a->v ? e : a->v;
        break;
    }
    }
    a->t_prev = t, a->y_prev = y;
}

void sweep_metrics_sample(const sweep_campaign *c, const rt_scene *sc, const rt_sim *sim,
                          sweep_acc *acc, double t)
{
    for (int i = 0; i < c->nmetrics; i++) {
        const sweep_metric *m = &c->metrics[i];
        if (t < m->from - 0.5 * (double)sc->dt) /* before its start (within half a tick) */
            continue;
        double y = (double)rt_rec_value(sc, sim, (uint16_t)acc[i].sig[0]);
        if (acc[i].sig[1] >= 0)
            y -= (double)rt_rec_value(sc, sim, (uint16_t)acc[i].sig[1]);
        fold(m, &acc[i], t, y);
    }
}

double sweep_metric_value(const sweep_campaign *c, const sweep_acc *acc, int i)
{
    const sweep_metric *m = &c->metrics[i];
    const sweep_acc *a = &acc[i];
    if (!a->started || a->nan)
        return NAN;
    switch (m->kind) {
    case SWEEP_M_RMS: return a->span > 0 ? sqrt(a->v / a->span) : fabs(a->y0);
    case SWEEP_M_MEAN: return a->span > 0 ? a->v / a->span : a->y0;
    case SWEEP_M_SETTLE: return a->pending ? NAN : a->aux - m->from;
    case SWEEP_M_OVERSHOOT:
        return m->p[0] == a->y0 ? NAN : (a->v > 0 ? a->v : 0) / fabs(m->p[0] - a->y0);
    default: return a->v;
    }
}
