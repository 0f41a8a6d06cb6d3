/* lookup.c - name look-ups over the scene being checked (systems, joints, a kind's port
 * names) and the location and list texts of error messages. Shared by check.c and sets.c,
 * so neither calls the other's helpers: check.c calls sets.c, both call this file. */
#include "scn.h"

#include <string.h>

int scn_find_block(const scn_scene *s, const char *name)
{
    for (uint16_t i = 0; i < s->nblk; i++)
        if (!strcmp(s->blk[i].name.s, name))
            return i;
    return -1;
}

int scn_find_joint(const scn_scene *s, const char *name)
{
    for (uint16_t i = 0; i < s->njnt; i++)
        if (!strcmp(s->jnt[i].name.s, name))
            return i;
    return -1;
}

int scn_find_name(const char *const *names, uint16_t n, const char *name)
{
    for (uint16_t i = 0; names && i < n; i++)
        if (!strcmp(names[i], name))
            return i;
    return -1;
}

const char *scn_where(scn_ctx *c, scn_pos p)
{
    return scn_fmt(c, "%s:%u:%u", scn_path(c, p), (unsigned)p.line, (unsigned)p.col);
}

const char *scn_block_list(scn_ctx *c, int joints)
{
    const scn_scene *s = &c->sc;
    const char *n[RT_MAX_BLOCKS + RT_MAX_JOINTS];
    size_t k = 0;
    for (uint16_t i = 0; i < s->nblk; i++)
        n[k++] = s->blk[i].name.s;
    for (uint16_t i = 0; joints && i < s->njnt; i++)
        n[k++] = s->jnt[i].name.s;
    return scn_list(c, n, k, 16);
}

/* block of a reference, or -1 with an error */
int scn_block_of(scn_ctx *c, scn_name n)
{
    int b = scn_find_block(&c->sc, n.s);
    if (b < 0 && !c->err)
        scn_fail(c, n.pos, n.s, "unknown system",
                 scn_fmt(c, "a loaded system (%s)", scn_block_list(c, 0)));
    return b;
}

const char *scn_kind_desc(scn_ctx *c, const scn_block *b)
{
    return scn_fmt(c, "%s (%s)", b->name.s, b->kind->name);
}

