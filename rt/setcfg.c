/* setcfg.c - a set's settings by name (RT_SET_CFG_LIST): their table for the tools, reading
 * and writing one by id, the defaults, the one check of a set's method, step and settings
 * that the scene compiler, modrt's per-set options and rt_init share, and the set's step. */
#include "rti.h"

const rt_set_opt rt_set_opts[RT_CFG_N] = {
#define RT_X_ROW(id, word, opt, field, kind, max, scope, dflt, help)                         \
    {word, opt, kind, scope, max, help},
    RT_SET_CFG_LIST(RT_X_ROW)
#undef RT_X_ROW
};

real_t rt_set_cfg_get(const rt_set_cfg *c, rt_cfg_id id)
{
    switch (id) {
#define RT_X_GET(id, word, opt, field, kind, max, scope, dflt, help)                         \
    case id:                                                                                \
        return (real_t)c->field;
        RT_SET_CFG_LIST(RT_X_GET)
#undef RT_X_GET
    default:
        return 0;
    }
}

/* a count as its field holds it: NaN (an explicit 0) or a value outside 0..max, which its
   field could not hold, is stored as 0, the default; the parsers refuse such counts first */
static real_t count_of(real_t v, uint32_t max)
{
    return v >= 0 && v <= (real_t)max ? v : 0;
}

void rt_set_cfg_put(rt_set_cfg *c, rt_cfg_id id, real_t v)
{
    switch (id) {
#define RT_X_PUT(id, word, opt, field, kind, max, scope, dflt, help)                         \
    case id:                                                                                \
        c->field = (kind) == RT_CFG_REAL || (kind) == RT_CFG_PAIR ? v : count_of(v, max);   \
        break;
        RT_SET_CFG_LIST(RT_X_PUT)
#undef RT_X_PUT
    default:
        break;
    }
}

rt_set_cfg rt_set_cfg_of(const rt_set_cfg *c)
{
    return rti_set_cfg_of(c);
}

int rt_method_iterates(const rt_integrator *m)
{
    return m && m->implicit && !m->linear;
}

/* what is wrong with value v of a setting of this kind up to max, or 0 (0: the default) */
static int bad_value(real_t v, uint8_t kind, uint32_t max)
{
    if (v == 0)
        return 0;
    if (kind == RT_CFG_COUNT || kind == RT_CFG_POW2) {
        uint32_t n = (uint32_t)v; /* the fields are whole numbers of their type */
        return n > max || (kind == RT_CFG_POW2 && (n & (n - 1)) != 0);
    }
    return !(v > 0 && rt_isfinite(v));
}

const char *rt_set_check(const rt_set *st, rt_cfg_id *bad)
{
    *bad = RT_CFG_N;
    if (!st->method || st->method->stages > RT_MAX_STAGES)
        return "set needs an integration method";
    if (st->ratio == 0)
        return "step must be a whole number of base ticks, at least one";
#define RT_X_CHECK(id, word, opt, field, kind, max, scope, dflt, help)                       \
    *bad = id;                                                                               \
    if (bad_value((real_t)st->cfg.field, kind, max))                                         \
        return (kind) == RT_CFG_COUNT  ? word " must be a whole number from 1 to " #max      \
               : (kind) == RT_CFG_POW2 ? word " must be a power of two from 1 to " #max      \
               : (kind) == RT_CFG_PAIR ? "the absolute " word " must be positive and finite" \
                                     : word " must be positive and finite";                  \
    if ((scope) == RT_CFG_ITER && st->cfg.field != 0 && !rt_method_iterates(st->method))     \
        return word " applies to the implicit methods that iterate only";
    RT_SET_CFG_LIST(RT_X_CHECK)
#undef RT_X_CHECK
    *bad = RT_CFG_N;
    return 0;
}

real_t rt_set_step(const rt_scene *sc, uint8_t s)
{
    return sc->dt * (real_t)sc->sets[s].ratio;
}
