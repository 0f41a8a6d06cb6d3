/* study.c - per-set overrides of a run for studies: --method, --step, --tol, --accuracy,
 * --substeps, --newton SET=VALUE, checked as strictly as the scene language checks the
 * same clauses (tools/scenec/sets.c). The scene stays const; its sets are copied. */
#include <stdio.h>
#include <string.h>

#include "cli.h"
#include "study.h"

static rt_set sets[RT_MAX_SETS]; /* the overridden copy of the scene's sets */

int study_add(study_args *a, const char *opt, const char *val)
{
    if (a->n >= STUDY_MAX)
        return cli_fail("too many per-set overrides (at most 32)", val);
    a->opt[a->n] = opt, a->val[a->n] = val, a->n++;
    return CLI_OK;
}

/* "--OPT SET=VALUE" for the error lines */
static int bad(const char *opt, const char *what, const char *val)
{
    char b[160];
    snprintf(b, sizeof b, "--%s %s", opt, what);
    return cli_fail(b, val);
}

static int set_step(rt_scene *sc, rt_set *st, const char *opt, const char *v)
{
    double s;
    if (!cli_real(v, &s) || !(s > 0))
        return bad(opt, "expects SET=TIME, a step in seconds > 0, got", v);
    /* in range before the cast: a double out of uint32_t's range is undefined behaviour */
    double r = s / (double)sc->dt, k = r >= 0.5 && r <= 1e9 ? (double)(uint32_t)(r + 0.5) : 0;
    if (!(k >= 1 && k <= 1e9) || !(k * (double)sc->dt <= s * (1 + 1e-12) &&
                                   k * (double)sc->dt >= s * (1 - 1e-12)))
        return bad(opt, "must be a whole number of base ticks; got", v);
    st->ratio = (uint32_t)k;
    return CLI_OK;
}

static int set_count(rt_set *st, const char *opt, const char *v)
{
    unsigned long n;
    if (strcmp(opt, "newton") == 0) {
        if (!cli_uint(v, 1, 255, &n))
            return bad(opt, "expects SET=N with N from 1 to 255, got", v);
        st->implicit.newton_max = (uint8_t)n;
    } else {
        if (!cli_uint(v, 1, 128, &n) || (n & (n - 1)) != 0)
            return bad(opt, "expects SET=N, a power of two from 1 to 128, got", v);
        st->implicit.substeps = (uint8_t)n;
    }
    return CLI_OK;
}

static int set_real(rt_set *st, const char *opt, const char *v)
{
    double e, a = 0;
    const char *comma = strcmp(opt, "accuracy") == 0 ? strchr(v, ',') : NULL;
    char rel[64];
    if (comma) { /* accuracy SET=R,A: relative and absolute, as the scene's clause */
        size_t n = (size_t)(comma - v);
        if (n >= sizeof rel || !cli_real(comma + 1, &a) || !(a > 0))
            return bad(opt, "expects SET=E or SET=R,A with both above 0, got", v);
        memcpy(rel, v, n), rel[n] = 0, v = rel;
    }
    if (!cli_real(v, &e) || !(e > 0))
        return bad(opt, "expects SET=E with E > 0, got", v);
    if (strcmp(opt, "tol") == 0)
        st->implicit.tol = (real_t)e;
    else
        st->implicit.accuracy = (real_t)e, st->implicit.atol = (real_t)a;
    return CLI_OK;
}

/* one override onto the copy */
static int apply_one(rt_scene *sc, const char *opt, const char *arg)
{
    const char *eq = strchr(arg, '=');
    char name[64];
    if (!eq || eq == arg || (size_t)(eq - arg) >= sizeof name)
        return bad(opt, "expects SET=VALUE, got", arg);
    memcpy(name, arg, (size_t)(eq - arg)), name[eq - arg] = 0;
    rt_set *st = NULL;
    for (uint8_t s = 0; s < sc->nsets; s++)
        if (strcmp(sets[s].name, name) == 0)
            st = &sets[s];
    if (!st)
        return bad(opt, "names no set of the scene:", name);
    const char *v = eq + 1;
    if (strcmp(opt, "method") == 0) {
        const rt_integrator *m = rt_integrator_find(v);
        if (!m) {
            char list[160] = "";
            for (const rt_integrator_entry *e = rt_integrators; e->name; e++)
                snprintf(list + strlen(list), sizeof list - strlen(list), "%s%s",
                         e == rt_integrators ? "" : ", ", e->name);
            fprintf(stderr, "modrt: --method: unknown integration method '%s' (one of %s)\n",
                    v, list);
            return CLI_USAGE;
        }
        st->method = m;
        return CLI_OK;
    }
    if (strcmp(opt, "step") == 0)
        return set_step(sc, st, opt, v);
    if (strcmp(opt, "newton") == 0 || strcmp(opt, "substeps") == 0)
        return set_count(st, opt, v);
    return set_real(st, opt, v);
}

int study_apply(const study_args *a, rt_scene *sc)
{
    if (a->n == 0)
        return CLI_OK;
    memcpy(sets, sc->sets, sc->nsets * sizeof sets[0]);
    sc->sets = sets;
    for (int i = 0; i < a->n; i++)
        if (apply_one(sc, a->opt[i], a->val[i]) != CLI_OK)
            return CLI_USAGE;
    for (int i = 0; i < a->n; i++) { /* as tools/scenec/sets.c: no silent no-op */
        const char *o = a->opt[i];
        size_t len = strcspn(a->val[i], "=");
        for (uint8_t s = 0; s < sc->nsets; s++)
            if (strncmp(sets[s].name, a->val[i], len) == 0 && sets[s].name[len] == 0 &&
                (!sets[s].method->implicit || sets[s].method->linear) &&
                (strcmp(o, "tol") == 0 || strcmp(o, "newton") == 0 ||
                 strcmp(o, "substeps") == 0))
                return bad(o, "applies to iterating implicit methods only; the set's method is",
                           sets[s].method->name);
    }
    return CLI_OK;
}
