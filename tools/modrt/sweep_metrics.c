/* sweep_metrics.c - the metrics a campaign asks of each run, folded in tick by tick from
 * the recorded signals (every tick, whatever --every the trace would use), in constant
 * memory: extremes, final value, RMS and mean (trapezoidal, over time, so they do not
 * depend on the tick), settling time into a band and overshoot past a target. A NaN
 * sample makes the metric NaN: a run that blew up never reports a fine maximum. An error
 * metric compares the run with a reference table (a CSV of t and signals: an independent
 * solution, or a run at a much finer step) at the table's instants where every set of the
 * run has completed a step (between its steps a slower set's outputs are extrapolated, not
 * integrated): the largest absolute difference over the instants and signals. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
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

/* the reference tables of the error metrics, read once per run: metric i's rows are
   ref_val[ref_first[i] ...], each a time and ref_ncol[i] values of the recorded signals
   ref_sig[i][...] */
static double ref_val[SWEEP_REF_VALUES];
static uint32_t ref_first[SWEEP_MAX_METRICS], ref_nrows[SWEEP_MAX_METRICS], ref_used;
static int16_t ref_sig[SWEEP_MAX_METRICS][SWEEP_REF_COLS];
static uint8_t ref_ncol[SWEEP_MAX_METRICS];

static int ref_fail(const char *path, int line, const char *what, const char *detail)
{
    fprintf(stderr, "%s:%d: error: %s%s%s\n", path, line, what, detail ? ": " : "",
            detail ? detail : "");
    return -1;
}

/* the header "t,SIG,..." of metric i's table: each a signal the scene records */
static int ref_header(const char *path, char *line, const rt_scene *sc, int i)
{
    char *save = NULL, *tok = strtok_r(line, ",\r\n", &save);
    if (!tok || strcmp(tok, "t") != 0)
        return ref_fail(path, 1, "a reference table starts with the column t", tok);
    ref_ncol[i] = 0;
    while ((tok = strtok_r(NULL, ",\r\n", &save))) {
        if (ref_ncol[i] >= SWEEP_REF_COLS)
            return ref_fail(path, 1, "more signals than SWEEP_REF_COLS", tok);
        int r = find_rec(sc, tok);
        if (r < 0) {
            char what[200];
            snprintf(what, sizeof what, "scene %s records no signal", sc->name);
            return ref_fail(path, 1, what, tok);
        }
        ref_sig[i][ref_ncol[i]++] = (int16_t)r;
    }
    return ref_ncol[i] ? 0 : ref_fail(path, 1, "a reference table names no signal", NULL);
}

/* metric i's reference table (its path relative to the campaign's directory) */
static int ref_read(const sweep_campaign *c, const rt_scene *sc, int i)
{
    static char line[SWEEP_REF_LINE];
    char path[2 * SWEEP_PATH];
    const char *p = c->arena + c->metrics[i].ref;
    snprintf(path, sizeof path, "%s%s%s", p[0] == '/' ? "" : c->dir, p[0] == '/' ? "" : "/", p);
    FILE *f = fopen(path, "r");
    if (!f) {
        fprintf(stderr, "%s:%d:%d: error: cannot read the reference table %s\n", c->path,
                c->metrics[i].line[0], c->metrics[i].col[0], path);
        return -1;
    }
    int rc = fgets(line, sizeof line, f) ? ref_header(path, line, sc, i)
                                        : ref_fail(path, 1, "empty", NULL);
    ref_first[i] = ref_used, ref_nrows[i] = 0;
    for (int ln = 2; rc == 0 && fgets(line, sizeof line, f); ln++) {
        char *s = line, *end;
        if (ref_used + 1u + ref_ncol[i] > SWEEP_REF_VALUES)
            rc = ref_fail(path, ln, "more values than SWEEP_REF_VALUES", NULL);
        for (int k = 0; rc == 0 && k <= ref_ncol[i]; k++, s = end + 1) {
            ref_val[ref_used + k] = strtod(s, &end);
            if (end == s || *end != (k < ref_ncol[i] ? ',' : *end) ||
                (k == ref_ncol[i] && *end && *end != '\n' && *end != '\r') ||
                !isfinite(ref_val[ref_used + k]))
                rc = ref_fail(path, ln, "expected a row of finite numbers, one per column", NULL);
        }
        if (rc == 0 && ref_nrows[i] > 0 && !(ref_val[ref_used] > ref_val[ref_used - 1 - ref_ncol[i]]))
            rc = ref_fail(path, ln, "the times must increase", NULL);
        if (rc == 0)
            ref_used += 1u + ref_ncol[i], ref_nrows[i]++;
    }
    fclose(f);
    return rc;
}

int sweep_metrics_bind(const sweep_campaign *c, const rt_scene *sc, sweep_acc *acc)
{
    ref_used = 0;
    for (int i = 0; i < c->nmetrics; i++) {
        const sweep_metric *m = &c->metrics[i];
        memset(&acc[i], 0, sizeof acc[i]);
        if (m->kind == SWEEP_M_ERROR) {
            acc[i].sig[0] = acc[i].sig[1] = -1;
            if (ref_read(c, sc, i) != 0)
                return -1;
            continue;
        }
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

/* 1 when every set of the scene has completed a step at this tick */
static int all_stepped(const rt_scene *sc, const rt_sim *sim)
{
    for (uint8_t k = 0; k < sc->nsets; k++)
        if (rt_ticks_done(sim) % (sc->sets[k].ratio ? sc->sets[k].ratio : 1) != 0)
            return 0;
    return 1;
}

/* metric i against its table's row at time t (within half a tick), if any */
static void error_sample(int i, const rt_scene *sc, const rt_sim *sim, sweep_acc *a, double t)
{
    double half = 0.5 * (double)sc->dt;
    uint32_t w = 1u + ref_ncol[i];
    while (a->row < ref_nrows[i] && ref_val[ref_first[i] + a->row * w] < t - half)
        a->row++; /* an instant the run stepped over: none of its ticks is near it */
    if (a->row >= ref_nrows[i] || ref_val[ref_first[i] + a->row * w] > t + half)
        return;
    const double *r = &ref_val[ref_first[i] + a->row++ * w];
    if (!all_stepped(sc, sim))
        return;
    double e = a->started ? a->v : 0;
    for (int k = 0; k < ref_ncol[i]; k++) {
        double d = fabs((double)rt_rec_value(sc, sim, (uint16_t)ref_sig[i][k]) - r[1 + k]);
        if (d != d)
            a->nan = 1;
        e = d > e ? d : e;
    }
    a->v = e, a->started = 1, a->span += 1; /* span: the instants compared */
}

void sweep_metrics_sample(const sweep_campaign *c, const rt_scene *sc, const rt_sim *sim,
                          sweep_acc *acc, double t)
{
    for (int i = 0; i < c->nmetrics; i++) {
        const sweep_metric *m = &c->metrics[i];
        double dt = (double)sc->dt, slack = (double)RT_TICK_SLACK * (m->from > dt ? m->from : dt);
        if (t + slack < m->from) /* before its start, beyond the rounding of a tick's time */
            continue;
        if (m->kind == SWEEP_M_ERROR) {
            error_sample(i, sc, sim, &acc[i], t);
            continue;
        }
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
