/* sets.c - the checks after wiring: sets (method, step as a whole number of base ticks,
 * members), joints and their links (nodes of multibody systems, one set per joint),
 * sample periods of discrete systems, recorded signals, parameter ranges and the loop
 * and stabilization options; and the statements of each service of a define. */
#include "scn.h"
#include "scn_host.h"

#include <string.h>

#include "models.h"

/* a step or period in seconds as a whole number of base ticks dt (RT_TICK_MATCH_REL), or 0 */
uint32_t scn_ticks(double v, double dt)
{
    double r = v / dt;
    if (!(r >= 0.5 && r < 4e9))
        return 0;
    uint32_t n = (uint32_t)(r + 0.5);
    double err = (double)n * dt - v;
    return (err < 0 ? -err : err) <= RT_TICK_MATCH_REL * v ? n : 0;
}

/* ------------------------------------------------------------------ sets */

static const char *method_list(scn_ctx *c)
{
    const char *n[32];
    size_t k = 0;
    for (const rt_integrator_entry *e = rt_integrators; e->name && k < 32; e++)
        n[k++] = e->name;
    return scn_list(c, n, k, 32);
}

/* the methods a setting of scope RT_CFG_ITER applies to */
static const char *iterating_list(scn_ctx *c)
{
    const char *n[32];
    size_t k = 0;
    for (const rt_integrator_entry *e = rt_integrators; e->name && k < 32; e++)
        if (rt_method_iterates(e->method))
            n[k++] = e->name;
    return scn_list(c, n, k, 32);
}

/* the settings' clauses, by the runtime's own check (rt_set_check) */
static void set_settings(scn_ctx *c, scn_set *st)
{
    rt_set tmp = {.name = st->name.s, .method = st->m, .ratio = 1, .cfg = st->cfg};
    rt_cfg_id id;
    const char *msg = rt_set_check(&tmp, &id);
    if (!msg || id >= RT_CFG_N)
        return;
    const rt_set_opt *o = &rt_set_opts[id];
    const char *want =
        o->scope == RT_CFG_ITER && !rt_method_iterates(st->m)
            ? scn_fmt(c, "a method that iterates (%s) or no %s clause", iterating_list(c), o->word)
        : o->kind == RT_CFG_PAIR ? scn_fmt(c, "%s (relative, absolute) with both above 0", o->word)
        : o->kind == RT_CFG_REAL ? "a value above 0"
        : o->kind == RT_CFG_POW2 ? scn_fmt(c, "a power of two from 1 to %u", (unsigned)o->max)
                                 : scn_fmt(c, "a whole number from 1 to %u", (unsigned)o->max);
    scn_fail(c, st->cfg_pos[id], o->word, msg, want);
}

static void set_method(scn_ctx *c, scn_set *st)
{
    if (!st->method.s) {
        scn_fail(c, st->name.pos, st->name.s, "set has no method",
                 scn_fmt(c, "method (<name>) with one of %s", method_list(c)));
        return;
    }
    st->m = rt_integrator_find(st->method.s);
    if (!st->m) {
        scn_fail(c, st->method.pos, st->method.s, "unknown integration method", method_list(c));
        return;
    }
    set_settings(c, st);
}

static void set_ratio(scn_ctx *c, scn_set *st)
{
    const scn_scene *s = &c->sc;
    st->ratio = 1;
    if (!st->has_step)
        return;
    if (st->step_ticks) {
        st->ratio = (uint32_t)st->step;
        return;
    }
    st->ratio = scn_ticks(st->step, s->dt);
    if (!st->ratio)
        scn_fail(c, st->step_pos, scn_fmt(c, "%g s", st->step),
                 "step is not a whole multiple of the base tick",
                 scn_fmt(c, "a multiple of %g s, or a step in ticks such as (2 ticks)", s->dt));
}

static void members(scn_ctx *c)
{
    scn_scene *s = &c->sc;
    int dflt = -1;
    for (uint16_t i = 0; i < s->nset && !c->err; i++) {
        const scn_set *st = &s->set[i];
        if (!st->has_members && dflt >= 0)
            scn_fail(c, st->name.pos, st->name.s, "two sets without members",
                     scn_fmt(c, "members (...) for all sets but one (%s has none)",
                             s->set[dflt].name.s));
        if (!st->has_members)
            dflt = i;
        for (uint16_t m = st->m0; m < st->m1 && !c->err; m++) {
            int b = scn_block_of(c, s->members[m]);
            if (b >= 0 && s->blk[b].set >= 0)
                scn_fail(c, s->members[m].pos, s->members[m].s, "system in two sets",
                         scn_fmt(c, "each system in one set (already in %s)",
                                 s->set[s->blk[b].set].name.s));
            else if (b >= 0)
                s->blk[b].set = (int16_t)i;
        }
    }
    for (uint16_t b = 0; b < s->nblk && !c->err; b++) {
        if (s->blk[b].set < 0 && dflt < 0)
            scn_fail(c, s->blk[b].name.pos, s->blk[b].name.s, "system belongs to no set",
                     "its name in the members (...) of a set");
        else if (s->blk[b].set < 0)
            s->blk[b].set = (int16_t)dflt;
    }
}

void scn_check_sets(scn_ctx *c)
{
    scn_scene *s = &c->sc;
    if (s->nset == 0) { /* no set statement: one set "main", RK4 at the base tick */
        memset(&s->set[0], 0, sizeof s->set[0]);
        s->set[0].name.s = "main", s->set[0].method.s = "rk4";
        s->nset = 1;
    }
    for (uint16_t i = 0; i < s->nset && !c->err; i++) {
        scn_set *st = &s->set[i];
        for (uint16_t j = 0; j < i && !c->err; j++)
            if (!strcmp(s->set[j].name.s, st->name.s))
                scn_fail(c, st->name.pos, st->name.s, "duplicate set name",
                         scn_fmt(c, "a name not used by another set (first at %s)",
                                 scn_where(c, s->set[j].name.pos)));
        set_method(c, st);
        if (!c->err)
            set_ratio(c, st);
    }
    members(c);
}

/* ------------------------------------------------------------------ links and joints */

static const char *mbs_kinds(scn_ctx *c)
{
    const char *n[64];
    size_t k = 0;
    for (const mdl_entry *e = mdl_kinds; e->name && k < 64; e++)
        if (e->kind->type == RT_KIND_MBS)
            n[k++] = e->name;
    return scn_list(c, n, k, 16);
}

/* node `node` of block `block`: its index, or -1 with an error */
static int node_of(scn_ctx *c, scn_ref r, int16_t *blk)
{
    int b = scn_block_of(c, r.block);
    if (b < 0)
        return -1;
    const scn_block *bl = &c->sc.blk[b];
    if (bl->kind->type != RT_KIND_MBS || !bl->kind->spec) {
        scn_fail(c, r.block.pos, r.block.s, "not a multibody system",
                 scn_fmt(c, "a system of a multibody kind (%s)", mbs_kinds(c)));
        return -1;
    }
    const rt_mbs_spec *sp = bl->kind->spec;
    int n = scn_find_name(sp->node_names, sp->nn, r.port.s);
    if (n < 0)
        scn_fail(c, r.port.pos, r.port.s, scn_fmt(c, "unknown node of %s", scn_kind_desc(c, bl)),
                 scn_fmt(c, "one of its nodes: %s", scn_list(c, sp->node_names, sp->nn, 16)));
    *blk = (int16_t)b;
    return n;
}

static void link_joint(scn_ctx *c, uint16_t li)
{
    scn_scene *s = &c->sc;
    scn_link *l = &s->lnk[li];
    int j = scn_find_joint(s, l->joint.s);
    if (j < 0) {
        scn_fail(c, l->joint.pos, l->joint.s, "unknown joint",
                 "a joint loaded with load joint (<name>) of type (<type>);");
        return;
    }
    scn_joint *jt = &s->jnt[j];
    if (jt->link >= 0) {
        scn_fail(c, l->joint.pos, l->joint.s, "joint linked twice",
                 scn_fmt(c, "one link per joint (first at %s)",
                         scn_where(c, s->lnk[jt->link].joint.pos)));
        return;
    }
    jt->link = (int16_t)li;
    l->n1 = (int16_t)node_of(c, l->a, &l->b1);
    l->b2 = -1, l->n2 = 0;
    if (!l->ground && !c->err)
        l->n2 = (int16_t)node_of(c, l->b, &l->b2);
    if (c->err || l->b2 < 0 || s->blk[l->b1].set == s->blk[l->b2].set)
        return;
    scn_fail(c, l->joint.pos, l->joint.s, "joint across sets",
             scn_fmt(c, "both systems in one set (%s is in %s, %s in %s)", l->a.block.s,
                     s->set[s->blk[l->b1].set].name.s, l->b.block.s,
                     s->set[s->blk[l->b2].set].name.s));
}

/* R (row-major) of the turn by angle a [rad] about the unit vector k (Rodrigues) */
static void axis_angle(double a, const double *k, double *R)
{
    double co = (double)rt_cos((real_t)a), si = (double)rt_sin((real_t)a), v = 1 - co; /* no libm here */
    for (int r = 0; r < 3; r++)
        for (int q = 0; q < 3; q++)
            R[3 * r + q] = v * k[r] * k[q] + (r == q ? co : 0);
    R[1] -= si * k[2], R[2] += si * k[1], R[3] += si * k[2];
    R[5] -= si * k[0], R[6] -= si * k[1], R[7] += si * k[0];
}

/* v / |v| into u; 0 when v has no direction */
static int unit3(const double *v, double *u)
{
    double n = (double)rt_sqrt((real_t)(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]));
    if (!(n > 0) || !rt_isfinite((real_t)n))
        return 0;
    u[0] = v[0] / n, u[1] = v[1] / n, u[2] = v[2] / n;
    return 1;
}

/* the joint frame A: the shortest turn taking z to the axis a, so A's third column is a
   (a = -z: half a turn about x) */
static void axis_frame(const double *a, double *A)
{
    double k[3] = {-a[1], a[0], 0}, kn = (double)rt_sqrt((real_t)(a[0] * a[0] + a[1] * a[1]));
    if (kn == 0) {
        const double x[3] = {1, 0, 0};
        axis_angle(a[2] > 0 ? 0 : 3.14159265358979323846, x, A);
        return;
    }
    k[0] /= kn, k[1] /= kn;
    axis_angle((double)rt_atan2((real_t)kn, (real_t)a[2]), k, A);
}

/* a joint's axis and its anchor's turn, as rotation matrices */
static void joint_frames(scn_ctx *c, scn_joint *j)
{
    scn_scene *s = &c->sc;
    scn_link *l = &s->lnk[j->link];
    double u[3];
    if (j->axis_at && !unit3(j->axis, u))
        scn_fail(c, s->asg[j->axis_at - 1].lhs.port.pos, "axis", "the joint's axis has no "
                 "direction", "a non-zero direction (x, y, z)");
    else if (j->axis_at)
        axis_frame(u, j->axis_S);
    if (!c->err && l->has_turn && !unit3(l->turn + 1, u))
        scn_fail(c, l->turn_pos, "rotated", "the anchor's rotation axis has no direction",
                 "rotated (angle deg about (x, y, z)) with a non-zero (x, y, z)");
    else if (l->has_turn)
        axis_angle(l->turn[0], u, l->at_S);
}

static void joint_params(scn_ctx *c, scn_joint *j)
{
    joint_frames(c, j);
    const rt_joint_kind *k = j->kind;
    real_t p[256];
    for (uint16_t i = 0; i < k->np && !c->err; i++) {
        if (!j->p_at[i])
            scn_fail(c, j->name.pos, j->name.s,
                     scn_fmt(c, "joint parameter %s not set", k->p_names[i]),
                     scn_fmt(c, "%s.%s = <value>;", j->name.s, k->p_names[i]));
        p[i] = (real_t)j->p[i];
    }
    if (!c->err && k->check && k->check(p) != 0)
        scn_fail(c, j->name.pos, j->name.s, scn_fmt(c, "parameters out of range for joint type %s",
                                                    k->name),
                 "values the joint type accepts (e.g. a length above 0)");
}

void scn_check_joint_links(scn_ctx *c)
{
    scn_scene *s = &c->sc;
    for (uint16_t i = 0; i < s->nlnk && !c->err; i++)
        link_joint(c, i);
    for (uint16_t i = 0; i < s->njnt && !c->err; i++) {
        if (s->jnt[i].link < 0)
            scn_fail(c, s->jnt[i].name.pos, s->jnt[i].name.s, "joint not linked",
                     scn_fmt(c, "link(<System>.<node>, <System>.<node> or ground) by (%s);",
                             s->jnt[i].name.s));
        else
            joint_params(c, &s->jnt[i]);
    }
}

/* ------------------------------------------------------------------ periods, ranges */

static void period(scn_ctx *c, scn_block *b)
{
    const scn_scene *s = &c->sc;
    int dss = b->kind->type == RT_KIND_DSS;
    scn_pos at = b->ts_pos;
    if (!dss && b->ts > 0) {
        scn_fail(c, at, scn_fmt(c, "%g s", b->ts), "period given for a system that is not discrete",
                 "period (...) only for discrete (dss) systems");
        return;
    }
    if (!dss)
        return;
    if (!(b->ts > 0) && b->def >= 0)
        b->ts = s->def[b->def]->period, at = s->def[b->def]->period_pos;
    if (!(b->ts > 0))
        scn_fail(c, b->name.pos, b->name.s, "sample period missing",
                 "period (<time>) in its load statement or its define");
    else if (!scn_ticks(b->ts, s->dt))
        scn_fail(c, at, scn_fmt(c, "%g s", b->ts), "sample period is not a whole multiple of the "
                                                 "base tick",
                 scn_fmt(c, "a multiple of %g s", s->dt));
    else if (b->set >= 0 && scn_ticks(b->ts, s->dt) % s->set[b->set].ratio)
        /* the set only runs every ratio ticks: a sample between its steps would be missed */
        scn_fail(c, at, scn_fmt(c, "%g s", b->ts), "sample period is not a whole multiple of "
                                                 "its set's step",
                 scn_fmt(c, "a multiple of %g s (the step of set %s)",
                         s->set[b->set].ratio * s->dt, s->set[b->set].name.s));
}

static void param_range(scn_ctx *c, const scn_block *b)
{
    const rt_kind *k = b->kind;
    real_t p[1024];
    if (!k->check || k->np > 1024)
        return;
    for (uint16_t i = 0; i < k->np; i++)
        p[i] = (real_t)b->p[i];
    if (k->check(p, k->spec) == RT_OK)
        return;
    scn_pos at = b->name.pos;
    const char *near = b->name.s;
    for (uint16_t i = 0; i < k->np; i++)
        if (b->p_at[i])
            at = c->sc.asg[b->p_at[i] - 1].lhs.port.pos, near = k->p_names[i];
    scn_fail(c, at, near, scn_fmt(c, "parameters of %s out of range", scn_kind_desc(c, b)),
             scn_fmt(c, "values %s accepts for %s", k->name,
                     scn_list(c, k->p_names, k->np, 16)));
}

/* ------------------------------------------------------------------ recorded signals */

static const char *mbs_signal(uint16_t index)
{
    static const rt_scene none; /* the service names signals without reading the scene */
    return rt_mbs.signal_name(&none, 0, index);
}

/* "a, b or c": the names of MBS signals first .. first + n - 1 (rt/mbs.c's list) */
static const char *mbs_names(scn_ctx *c, uint16_t first, uint16_t n)
{
    const char *names[RT_MBS_JSIG_COUNT + RT_MBS_SIG_NSET];
    for (uint16_t i = 0; i < n; i++)
        names[i] = mbs_signal((uint16_t)(first + i));
    return scn_list(c, names, n, n);
}

static int joint_signal(scn_ctx *c, scn_rec *r, int j)
{
    const scn_joint *jt = &c->sc.jnt[j];
    for (uint16_t k = 0; k < RT_MBS_JSIG_COUNT; k++) {
        if (k >= RT_MBS_JSIG_LAMBDA + jt->kind->nc)
            break;
        if (!strcmp(mbs_signal(RT_MBS_SIG_JOINT_AT(j, k)), r->sig.port.s) && r->want < 0) {
            r->r = (rt_rec){(uint16_t)c->sc.lnk[jt->link].b1, RT_SIG_MBS,
                            RT_MBS_SIG_JOINT_AT(j, k)};
            return 1;
        }
    }
    return 0;
}

static int block_signal(scn_ctx *c, scn_rec *r, int b)
{
    const rt_kind *k = c->sc.blk[b].kind;
    const char *const *lists[3] = {k->y_names, k->x_names, k->d_names};
    uint16_t ns[3] = {k->ny, k->nx, k->nd};
    for (int q = 0; q < 3; q++) {
        int i = scn_find_name(lists[q], ns[q], r->sig.port.s);
        if (i >= 0 && (r->want < 0 || r->want == q)) {
            r->r = (rt_rec){(uint16_t)b, (uint8_t)q, (uint16_t)i};
            return 1;
        }
    }
    for (uint16_t i = 0; k->type == RT_KIND_MBS && r->want < 0 && i < RT_MBS_SIG_NSET; i++)
        if (!strcmp(mbs_signal(i), r->sig.port.s)) {
            r->r = (rt_rec){(uint16_t)b, RT_SIG_MBS, i};
            return 1;
        }
    return 0;
}

static void record(scn_ctx *c, scn_rec *r)
{
    const scn_scene *s = &c->sc;
    int b = scn_find_block(s, r->sig.block.s), j = scn_find_joint(s, r->sig.block.s);
    if (b < 0 && j < 0) {
        scn_fail(c, r->sig.block.pos, r->sig.block.s, "unknown system or joint",
                 scn_fmt(c, "a loaded system or joint (%s)", scn_block_list(c, 1)));
        return;
    }
    if (b >= 0 ? block_signal(c, r, b) : joint_signal(c, r, j))
        return;
    const char *what = b >= 0 ? scn_kind_desc(c, &s->blk[b])
                              : scn_fmt(c, "joint %s (%s)", s->jnt[j].name.s, s->jnt[j].kind->name);
    scn_fail(c, r->sig.port.pos, r->sig.port.s, scn_fmt(c, "unknown signal of %s", what),
             b >= 0 ? scn_fmt(c, "one of its outputs, states or discrete states (or %s of a "
                                 "multibody system)", mbs_names(c, 0, RT_MBS_SIG_NSET))
                    : scn_fmt(c, "%s or lambda1.. of its constraint rows",
                              mbs_names(c, RT_MBS_SIG_JOINT, RT_MBS_JSIG_LAMBDA)));
}

/* ------------------------------------------------------------------ options */

static void options(scn_ctx *c)
{
    scn_scene *s = &c->sc;
    int mbs = 0;
    for (uint16_t b = 0; b < s->nblk; b++)
        mbs |= s->blk[b].kind->type == RT_KIND_MBS;
    if (s->solver.s && strcmp(s->solver.s, "broyden") != 0)
        scn_fail(c, s->solver.pos, s->solver.s, "unknown loop solver", "broyden");
    if (s->solver.s && !(s->loop_tol >= 0))
        scn_fail(c, s->solver.pos, s->solver.s, "loop tolerance must not be negative",
                 "a tolerance of 0 (the default) or above");
    s->stab_kind = RT_STAB_PROJECT;
    if (!s->stab.s || c->err)
        return;
    if (!mbs)
        scn_fail(c, s->stab.pos, s->stab.s, "stabilization applies to multibody scenes only",
                 "no stabilization statement without multibody systems");
    else if (rt_stab_find(s->stab.s) >= 0)
        s->stab_kind = (uint8_t)rt_stab_find(s->stab.s);
    else
        scn_fail(c, s->stab.pos, s->stab.s, "unknown stabilization", "project, none or baumgarte");
    if (!c->err && s->stab_kind != RT_STAB_BAUMGARTE && (s->alpha != 0 || s->beta != 0))
        scn_fail(c, s->stab.pos, s->stab.s, "alpha and beta apply to baumgarte only",
                 "stabilization (baumgarte) alpha (...) beta (...);");
    if (!c->err && s->stab_kind == RT_STAB_BAUMGARTE && s->alpha == 0 && s->beta == 0)
        scn_fail(c, s->stab.pos, s->stab.s, "baumgarte with alpha = beta = 0 stabilizes nothing",
                 "stabilization (baumgarte) alpha (...) beta (...); or stabilization (none);");
}

void scn_resolve_rec(scn_ctx *c, scn_rec *r)
{
    record(c, r);
}

void scn_check_rest(scn_ctx *c)
{
    scn_scene *s = &c->sc;
    for (uint16_t b = 0; b < s->nblk && !c->err; b++)
        period(c, &s->blk[b]);
    for (uint16_t b = 0; b < s->nblk && !c->err; b++)
        param_range(c, &s->blk[b]);
    for (uint16_t i = 0; i < s->nrec && !c->err; i++)
        record(c, &s->rec[i]);
    if (!c->err)
        options(c);
}

/* ------------------------------------------------------------------ services */

/* marks the statements of one service: kind, and for SCN_ST_EVENT root r's handler */
static void service(const scn_ctx *c, const scn_define *d, uint8_t kind, uint16_t r,
                    uint8_t *in)
{
    uint8_t need[SCN_MAX_LOCALS] = {0};
    for (uint32_t s = d->st1; s-- > d->st0;) {
        const scn_stmt *st = &c->sc.st[s];
        int per_root = kind == SCN_ST_EVENT || kind == SCN_ST_REST;
        int mine = (st->kind == kind && (!per_root || st->root == r) &&
                    (kind != SCN_ST_REST_T || st->index == r)) ||
                   (st->kind == SCN_ST_LET && need[st->index]);
        in[s - d->st0] = (uint8_t)mine;
        for (uint32_t i = st->code0; mine && i < st->code1; i++)
            if (c->sc.code[i].op == SCN_OP_LOC)
                need[c->sc.code[i].a] = 1;
    }
}

void scn_service(const scn_ctx *c, const scn_define *d, uint8_t kind, uint8_t *in)
{
    service(c, d, kind, 0, in);
}

void scn_service_event(const scn_ctx *c, const scn_define *d, uint16_t r, uint8_t *in)
{
    service(c, d, SCN_ST_EVENT, r, in);
}

void scn_service_root(const scn_ctx *c, const scn_define *d, uint8_t kind, uint16_t r,
                      uint8_t *in)
{
    service(c, d, kind, r, in);
}
