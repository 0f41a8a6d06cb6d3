/* study.c - per-set overrides of a run for studies: --method, --step and the settings of
 * RT_SET_CFG_LIST (--newton, --tol, ... SET=VALUE), checked by the runtime's own check of
 * a set (rt_set_check), as the scene language's clauses are. The scene stays const; its
 * sets are copied. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "cli.h"
#include "study.h"
#include "scn_host.h"

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
    uint32_t k = scn_ticks(s, (double)sc->dt); /* as the scene language's step (...) */
    if (!k)
        return bad(opt, "must be a whole number of base ticks; got", v);
    st->ratio = k;
    return CLI_OK;
}

/* a value onto setting id: an explicit 0 is no default, so it is kept as NaN for the
   check to name (rt_set_check) */
static void put(rt_set *st, int id, double v)
{
    rt_set_cfg_put(&st->cfg, (rt_cfg_id)id, v == 0 ? (real_t)NAN : (real_t)v);
}

/* --OPT SET=N or SET=E (SET=R,A where the next row is its second value, RT_CFG_PAIR):
   parsed here, judged by rt_set_check as the scene's clause is */
static int set_setting(rt_set *st, int id, const char *opt, const char *v)
{
    const rt_set_opt *o = &rt_set_opts[id];
    if (o->kind == RT_CFG_COUNT || o->kind == RT_CFG_POW2) {
        unsigned long n;
        if (!cli_uint(v, 1, o->max, &n)) {
            char b[80];
            snprintf(b, sizeof b, "expects SET=N with N from 1 to %u, got", (unsigned)o->max);
            return bad(opt, b, v);
        }
        put(st, id, (double)n);
        return CLI_OK;
    }
    int pair = id + 1 < RT_CFG_N && rt_set_opts[id + 1].kind == RT_CFG_PAIR;
    const char *comma = pair ? strchr(v, ',') : NULL;
    double e, a = 0;
    char rel[64];
    if (comma) {
        size_t n = (size_t)(comma - v);
        if (n >= sizeof rel || !cli_real(comma + 1, &a))
            return bad(opt, "expects SET=E or SET=R,A, got", v);
        memcpy(rel, v, n), rel[n] = 0, v = rel;
    }
    if (!cli_real(v, &e))
        return bad(opt, pair ? "expects SET=E or SET=R,A, got" : "expects SET=E, got", v);
    put(st, id, e);
    if (pair) /* SET=E alone: no second value, as the scene's accuracy (E) */
        rt_set_cfg_put(&st->cfg, (rt_cfg_id)(id + 1), 0);
    if (comma)
        put(st, id + 1, a);
    return CLI_OK;
}

/* the setting modrt's option opt sets (RT_SET_CFG_LIST), or -1 */
static int setting_of(const char *opt)
{
    for (int id = 0; id < RT_CFG_N; id++)
        if (rt_set_opts[id].opt && strcmp(rt_set_opts[id].opt, opt) == 0)
            return id;
    return -1;
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
    int id = setting_of(opt);
    if (id < 0)
        return bad(opt, "is no per-set option:", arg);
    return set_setting(st, id, opt, v);
}

/* a method given on the command line that does not iterate: the scene's settings for
   one that does no longer apply (the options after it are still checked) */
static void drop_iter_settings(rt_set *st)
{
    if (rt_method_iterates(st->method))
        return;
    for (int id = 0; id < RT_CFG_N; id++)
        if (rt_set_opts[id].scope == RT_CFG_ITER)
            rt_set_cfg_put(&st->cfg, (rt_cfg_id)id, 0);
}

int study_apply(const study_args *a, rt_scene *sc)
{
    if (a->n == 0)
        return CLI_OK;
    const rt_set *scene = sc->sets;
    memcpy(sets, scene, sc->nsets * sizeof sets[0]);
    sc->sets = sets;
    for (int i = 0; i < a->n; i++) /* the methods first: the settings then meet theirs */
        if (strcmp(a->opt[i], "method") == 0 && apply_one(sc, a->opt[i], a->val[i]) != CLI_OK)
            return CLI_USAGE;
    for (uint8_t s = 0; s < sc->nsets; s++)
        if (sets[s].method != scene[s].method)
            drop_iter_settings(&sets[s]);
    for (int i = 0; i < a->n; i++)
        if (strcmp(a->opt[i], "method") != 0 && apply_one(sc, a->opt[i], a->val[i]) != CLI_OK)
            return CLI_USAGE;
    for (uint8_t s = 0; s < sc->nsets; s++) { /* as the scene's clauses: rt_set_check */
        rt_cfg_id id;
        const char *msg = rt_set_check(&sets[s], &id);
        if (!msg)
            continue;
        const char *o = id < RT_CFG_N && rt_set_opts[id].opt ? rt_set_opts[id].opt : "step";
        int scope = id < RT_CFG_N && rt_set_opts[id].scope == RT_CFG_ITER &&
                    !rt_method_iterates(sets[s].method);
        char b[200];
        snprintf(b, sizeof b, "--%s: set %s: %s%s%s", o, sets[s].name, msg,
                 scope ? "; its method is " : "", scope ? sets[s].method->name : "");
        return cli_fail(b, NULL);
    }
    return CLI_OK;
}
