/* link.c - the scene's controller link (export ... to (C); import ... from (C);): checks
 * that both statements name one controller, resolves the exported signals like recorded
 * ones, finds the import block the import statement expanded to (parse.c), and computes
 * the link identity: a hash of the scene name and the link layout, which every packet
 * and every replay log carries (docs/link.md). */
#include "scn.h"

#include <string.h>

/* FNV-1a, 32 bits, over a string and a separator byte */
static uint32_t fnv(uint32_t h, const char *s)
{
    for (; *s; s++)
        h = (h ^ (uint8_t)*s) * 16777619u;
    return (h ^ (uint8_t)'|') * 16777619u;
}

static uint32_t link_id(const scn_scene *s)
{
    uint32_t h = fnv(2166136261u, s->name.s);
    h = fnv(h, s->ctl_imp.s ? s->ctl_imp.s : s->ctl_exp.s);
    for (uint16_t i = 0; i < s->nlexp; i++)
        h = fnv(fnv(h, s->lexp[i].sig.block.s), s->lexp[i].sig.port.s);
    h = fnv(h, ">");
    for (uint16_t i = 0; i < s->nlimp; i++)
        h = fnv(h, s->limp[i].name.s);
    return h;
}

static uint32_t period_ticks(scn_ctx *c, const scn_scene *s)
{
    double r = s->lperiod / s->dt;
    uint32_t n = r >= 0.5 && r < 4e9 ? (uint32_t)(r + 0.5) : 0; /* in range before the cast */
    if (n >= 1 && (double)n * s->dt - s->lperiod <= RT_TICK_MATCH_REL * s->lperiod &&
        s->lperiod - (double)n * s->dt <= RT_TICK_MATCH_REL * s->lperiod)
        return n;
    scn_fail(c, s->ctl_imp.pos, s->ctl_imp.s, "exchange period is not a whole number of base ticks",
             scn_fmt(c, "every (...) a multiple of %g s", s->dt));
    return 0;
}

void scn_check_ctl_link(scn_ctx *c)
{
    scn_scene *s = &c->sc;
    rt_link *l = &s->link;
    memset(l, 0, sizeof *l);
    if (!s->ctl_exp.s && !s->ctl_imp.s)
        return;
    if (s->ctl_exp.s && s->ctl_imp.s && strcmp(s->ctl_exp.s, s->ctl_imp.s) != 0) {
        scn_fail(c, s->ctl_imp.pos, s->ctl_imp.s, "import names another controller than export",
                 scn_fmt(c, "from (%s), the controller of the export", s->ctl_exp.s));
        return;
    }
    if (!s->ctl_imp.s)
        s->lperiod = s->dt; /* exports only: every tick */
    for (uint16_t i = 0; i < s->nlexp && !c->err; i++) {
        scn_resolve_rec(c, &s->lexp[i]);
        s->lexp_r[i] = s->lexp[i].r;
    }
    for (uint16_t i = 0; i < s->nlimp; i++)
        s->ldef[i] = (real_t)s->limp[i].init;
    l->period = c->err ? 0 : period_ticks(c, s);
    if (c->err)
        return;
    l->name = s->ctl_imp.s ? s->ctl_imp.s : s->ctl_exp.s;
    l->exp = s->nlexp ? s->lexp_r : NULL, l->nexp = s->nlexp;
    l->nimp = s->nlimp;
    l->block = s->nlimp ? (uint16_t)scn_find_block(s, s->ctl_imp.s) : 0;
    l->def = s->nlimp ? s->ldef : NULL;
    l->policy = s->nlimp ? s->lpol : NULL;
    l->id = link_id(s);
}
