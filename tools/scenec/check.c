/* check.c - what a scene means: resolves every name against the model library
 * (mdl_kinds), the defines, the joint kinds (rt_joint_kinds) and the integrators
 * (rt_integrators); builds the kinds of defines; gives each block its values; checks
 * wiring (one source per input, none left open), sets, links, sample periods, recorded
 * signals and parameter ranges. Each problem is reported at the text that causes it.
 * It calls sets.c (sets, links, the rest); both look names up through lookup.c. */
#include "scn.h"

#include <math.h>
#include <string.h>

#include "models.h"

/* in the order of rt_interp, from its one list in rt/rt.h; "set" (RT_INTERP_SET) is what a
   connection without a clause gets, so it is not written in a scene */
#define SCN_X_NAME(id, name) name,
const char *const scn_interp_key[RT_INTERP_COUNT] = {RT_INTERP_LIST(SCN_X_NAME)};
#undef SCN_X_NAME

/* ------------------------------------------------------------------ the scene */

static int is_ident(const char *s, size_t n)
{
    if (n == 0 || n > SCN_MAX_NAME || (s[0] >= '0' && s[0] <= '9'))
        return 0;
    for (size_t i = 0; i < n; i++)
        if (!((s[i] >= 'a' && s[i] <= 'z') || (s[i] >= 'A' && s[i] <= 'Z') ||
              (s[i] >= '0' && s[i] <= '9') || s[i] == '_'))
            return 0;
    return 1;
}

/* scene name (from the file name if not given), base tick, end time */
static void header(scn_ctx *c)
{
    scn_scene *s = &c->sc;
    scn_pos top = {0, 1, 1};
    if (!s->has_name) {
        const char *path = c->files[0].path, *slash = strrchr(path, '/');
        const char *base = slash ? slash + 1 : path, *dot = strrchr(base, '.');
        size_t n = dot ? (size_t)(dot - base) : strlen(base);
        s->name.s = scn_strndup(c, base, n), s->name.pos = top;
        if (!is_ident(base, n))
            scn_fail(c, top, s->name.s, "the file name is not a scene name",
                     "scene (name); with a name of letters, digits and _");
    }
    if (!s->has_dt)
        scn_fail(c, top, s->name.s, "missing base tick", "base tick (<time>); in the scene");
    if (!s->has_end)
        scn_fail(c, top, s->name.s, "missing end time", "end time (<time>); in the scene");
    if (!s->has_dt || !s->has_end || !(s->dt > 0))
        return;
    double n = s->t_end / s->dt, k = floor(n + 0.5);
    if (!(n <= (double)RT_MAX_TICKS))
        scn_fail(c, s->end_pos, "end", "end time beyond the tick counter",
                 scn_fmt(c, "at most %.10g s with a base tick of %.10g s (2^53 ticks, "
                            "RT_MAX_TICKS)", (double)RT_MAX_TICKS * s->dt, s->dt));
    else if (fabs(n - k) > 1e-9 * (n > 1 ? n : 1))
        scn_fail(c, s->end_pos, "end", "end time is not a whole number of base ticks",
                 scn_fmt(c, "a multiple of the base tick, e.g. %.12g s or %.12g s",
                         floor(n) * s->dt, (floor(n) + 1) * s->dt));
}

/* ------------------------------------------------------------------ defines */

/* which inputs each output reads, directly or through let names (eq. 1 throughput) */
static void define_feed(scn_ctx *c, scn_define *d, rt_kind *k)
{
    uint64_t loc[SCN_MAX_LOCALS] = {0}, all = 0, any = 0;
    d->feed = scn_alloc(c, (size_t)d->ny * d->nu + 1);
    for (uint32_t si = d->st0; si < d->st1; si++) {
        const scn_stmt *st = &c->sc.st[si];
        uint64_t m = 0;
        for (uint32_t i = st->code0; i < st->code1; i++) {
            const scn_ins *in = &c->sc.code[i];
            m |= in->op == SCN_OP_IN ? (uint64_t)1 << in->a : in->op == SCN_OP_LOC ? loc[in->a] : 0;
        }
        if (st->kind == SCN_ST_LET)
            loc[st->index] = m;
        for (uint16_t j = 0; st->kind == SCN_ST_OUT && j < d->nu; j++)
            d->feed[st->index * d->nu + j] = (uint8_t)((m >> j) & 1);
    }
    for (size_t i = 0; i < (size_t)d->ny * d->nu; i++)
        any |= d->feed[i], all += d->feed[i];
    k->feed = !any ? RT_FEED_NONE : all == (uint64_t)d->ny * d->nu ? RT_FEED_ALL : RT_FEED_TABLE;
    k->feed_table = k->feed == RT_FEED_TABLE ? d->feed : NULL;
}

/* an LSS matrix has the size its define's ports give it */
static void lss_size(scn_ctx *c, scn_define *d, scn_matrix *m, char name, uint16_t rows,
                     uint16_t cols, int required)
{
    static const char *const dims[] = {"states x states", "states x inputs",
                                       "outputs x states", "outputs x inputs"};
    const char *dim = dims[name - 'A'];
    if (!m->given) {
        if (required && rows > 0 && cols > 0)
            scn_fail(c, d->name.pos, d->name.s, scn_fmt(c, "matrix %c missing", name),
                     scn_fmt(c, "%c = [...]; of %ux%u (%s) in the body", name, rows, cols, dim));
        return;
    }
    if (m->rows * m->cols == 0 && rows * cols == 0)
        return;
    if (m->rows != rows || m->cols != cols)
        scn_fail(c, m->pos, "[", scn_fmt(c, "size mismatch: %c is %ux%u", name, m->rows, m->cols),
                 scn_fmt(c, "%c of %ux%u (%s)", name, rows, cols, dim));
}

static void lss_feed(scn_ctx *c, scn_define *d, rt_kind *k)
{
    int any = 0, all = 1;
    d->feed = scn_alloc(c, (size_t)d->ny * d->nu + 1);
    for (size_t i = 0; d->D.given && i < (size_t)d->ny * d->nu; i++) {
        d->feed[i] = d->D.v[i] != 0;
        any |= d->feed[i], all &= d->feed[i];
    }
    k->feed = !any ? RT_FEED_NONE : all ? RT_FEED_ALL : RT_FEED_TABLE;
    k->feed_table = k->feed == RT_FEED_TABLE ? d->feed : NULL;
}

static const char **var_names(scn_ctx *c, const scn_var *v, uint16_t n)
{
    const char **out = scn_alloc(c, (n ? n : 1) * sizeof *out);
    for (uint16_t i = 0; i < n; i++)
        out[i] = v[i].name.s;
    return n ? out : NULL;
}

static real_t *var_values(scn_ctx *c, const scn_var *v, uint16_t n)
{
    real_t *out = scn_alloc(c, (n ? n : 1) * sizeof *out);
    for (uint16_t i = 0; i < n; i++)
        out[i] = (real_t)v[i].init;
    return n ? out : NULL;
}

const rt_kind *scn_library_kind(const char *name)
{
    for (const mdl_entry *e = mdl_kinds; e->name; e++)
        if (!strcmp(e->name, name))
            return e->kind;
    return NULL;
}

/* the discrete states of an ss_system's roots: t_last<k>, the time of the k-th when's
   last crossing (SCN_T_LAST0 before the first), which its rest clause reads */
static void when_times(scn_ctx *c, scn_define *d, rt_kind *k)
{
    const char **names = scn_alloc(c, d->nr * sizeof *names);
    real_t *t0 = scn_alloc(c, d->nr * sizeof *t0);
    for (uint16_t r = 0; r < d->nr && !c->err; r++) {
        names[r] = scn_fmt(c, "t_last%u", r + 1u), t0[r] = (real_t)SCN_T_LAST0;
        const scn_var *all[4] = {d->u, d->y, d->p, d->x};
        uint16_t cnt[4] = {d->nu, d->ny, d->np, d->nx};
        for (int j = 0; j < 4; j++)
            for (uint16_t i = 0; i < cnt[j] && !c->err; i++)
                if (!strcmp(all[j][i].name.s, names[r]))
                    scn_fail(c, all[j][i].name.pos, names[r],
                             "name of the discrete state of a when",
                             "a name other than t_last<k> (the time of the k-th when's "
                             "last crossing)");
    }
    k->nd = d->nr, k->d_names = names, k->d_default = t0;
}

/* the define's invariants with their states resolved to indices (rt_kind.inv) */
static void define_invariants(scn_ctx *c, const scn_define *d, rt_kind *k)
{
    if (d->ninv == 0)
        return;
    rt_invariant *inv = scn_alloc(c, d->ninv * sizeof *inv);
    for (uint8_t i = 0; i < d->ninv && !c->err; i++) {
        const scn_inv *v = &d->inv[i];
        uint16_t *x = scn_alloc(c, v->n * sizeof *x);
        for (uint8_t j = 0; j < v->n && !c->err; j++) {
            int at = -1;
            for (uint16_t q = 0; q < d->nx && at < 0; q++)
                at = strcmp(d->x[q].name.s, v->x[j].s) ? -1 : q;
            if (at < 0)
                scn_fail(c, v->x[j].pos, v->x[j].s, "an invariant reads a state",
                         scn_fmt(c, "a state of %s", d->name.s));
            x[j] = (uint16_t)(at < 0 ? 0 : at);
        }
        if (!c->err && !(v->tol >= 0))
            scn_fail(c, v->x[0].pos, v->x[0].s, "an invariant's tolerance is negative",
                     "within (a tolerance >= 0)");
        inv[i] = (rt_invariant){.type = v->type, .n = v->n, .x = x, .c = (real_t)v->c,
                                .tol = (real_t)v->tol};
    }
    k->inv = inv, k->ninv = d->ninv;
}

/* the kind a define describes: sizes, names, defaults, throughput (services: image.c) */
static void define_kind(scn_ctx *c, scn_define *d)
{
    rt_kind *k = scn_alloc(c, sizeof *k);
    int dss = d->type == SCN_DEF_DSS;
    k->name = d->name.s;
    k->type = d->type == SCN_DEF_LSS ? RT_KIND_LSS : dss ? RT_KIND_DSS
            : d->nx ? RT_KIND_NSS : RT_KIND_OUTPUT;
    k->nu = d->nu, k->ny = d->ny, k->np = d->np;
    k->u_names = var_names(c, d->u, d->nu);
    k->y_names = var_names(c, d->y, d->ny);
    k->p_names = var_names(c, d->p, d->np);
    k->p_default = var_values(c, d->p, d->np);
    if (dss) {
        k->nd = d->nx;
        k->d_names = var_names(c, d->x, d->nx), k->d_default = var_values(c, d->x, d->nx);
    } else {
        k->nx = d->nx;
        k->x_names = var_names(c, d->x, d->nx), k->x_default = var_values(c, d->x, d->nx);
    }
    if (d->nr) { /* state events: `when` statements */
        int8_t *dir = scn_alloc(c, d->nr);
        memcpy(dir, d->rdir, d->nr);
        k->nr = d->nr, k->root_dir = dir;
        when_times(c, d, k);
    }
    define_invariants(c, d, k);
    d->kind = k;
    if (d->type != SCN_DEF_LSS) {
        define_feed(c, d, k);
        return;
    }
    lss_size(c, d, &d->A, 'A', d->nx, d->nx, 1);
    lss_size(c, d, &d->B, 'B', d->nx, d->nu, 0);
    lss_size(c, d, &d->C, 'C', d->ny, d->nx, 1);
    lss_size(c, d, &d->D, 'D', d->ny, d->nu, 0);
    lss_feed(c, d, k);
}

/* each define on its own: one's error does not hide another's */
static void defines(scn_ctx *c)
{
    scn_scene *s = &c->sc;
    for (uint16_t i = 0; i < s->ndef; i++, scn_keep_error(c)) {
        scn_define *d = s->def[i];
        if (scn_library_kind(d->name.s))
            scn_fail(c, d->name.pos, d->name.s, "type name already used by the model library",
                     "a new name for the defined system");
        for (uint16_t j = 0; j < i && !c->err; j++)
            if (!strcmp(s->def[j]->name.s, d->name.s))
                scn_fail(c, d->name.pos, d->name.s, "system defined twice",
                         scn_fmt(c, "one define per name (first at %s)",
                                 scn_where(c, s->def[j]->name.pos)));
        if (!c->err)
            define_kind(c, d);
    }
}

/* ------------------------------------------------------------------ blocks and joints */

static const char *type_list(scn_ctx *c)
{
    const char *n[64 + SCN_MAX_DEFINES];
    size_t k = 0;
    for (const mdl_entry *e = mdl_kinds; e->name && k < 64; e++)
        n[k++] = e->name;
    for (uint16_t i = 0; i < c->sc.ndef; i++)
        n[k++] = c->sc.def[i]->name.s;
    return scn_list(c, n, k, 40);
}

static double *values(scn_ctx *c, const real_t *kind_def, const scn_var *def_vars,
                      uint16_t n)
{
    double *v = scn_alloc(c, (n ? n : 1) * sizeof *v);
    for (uint16_t i = 0; i < n; i++)
        v[i] = def_vars ? def_vars[i].init : kind_def ? (double)kind_def[i] : 0;
    return v;
}

static void block_kind(scn_ctx *c, scn_block *b)
{
    const scn_scene *s = &c->sc;
    const scn_define *d = NULL;
    for (uint16_t i = 0; i < s->ndef; i++)
        if (!strcmp(s->def[i]->name.s, b->type.s))
            b->def = (int16_t)i, d = s->def[i];
    b->kind = d ? d->kind : scn_library_kind(b->type.s);
    if (!d && !strcmp(b->type.s, "fmu") && !(b->kind = scn_fmu_kind(c, b)))
        return; /* (its error said why) */
    if (!b->kind) {
        scn_fail(c, b->type.pos, b->type.s, "unknown system type",
                 scn_fmt(c, "a model of the library or a defined system (%s)", type_list(c)));
        return;
    }
    const rt_kind *k = b->kind;
    int dss = d && d->type == SCN_DEF_DSS;
    b->p = values(c, k->p_default, d ? d->p : NULL, k->np);
    b->x0 = values(c, k->x_default, d && !dss ? d->x : NULL, k->nx);
    b->d0 = values(c, k->d_default, dss ? d->x : NULL, k->nd);
    b->p_at = scn_alloc(c, (k->np + 1u) * sizeof(uint16_t));
    b->x_at = scn_alloc(c, (k->nx + 1u) * sizeof(uint16_t));
    b->d_at = scn_alloc(c, (k->nd + 1u) * sizeof(uint16_t));
    b->u_at = scn_alloc(c, (k->nu + 1u) * sizeof(uint16_t));
    b->u_conn = scn_alloc(c, (k->nu + 1u) * sizeof(int16_t));
    for (uint16_t i = 0; i < k->nu; i++)
        b->u_conn[i] = -1;
}

static void joint_kind(scn_ctx *c, scn_joint *j)
{
    for (const rt_joint_entry *e = rt_joint_kinds; e->name && !j->kind; e++)
        if (!strcmp(e->name, j->type.s))
            j->kind = e->kind;
    if (!j->kind) {
        const char *n[16];
        size_t k = 0;
        for (const rt_joint_entry *e = rt_joint_kinds; e->name && k < 16; e++)
            n[k++] = e->name;
        scn_fail(c, j->type.pos, j->type.s, "unknown joint type", scn_list(c, n, k, 16));
        return;
    }
    j->p = scn_alloc(c, (j->kind->np + 1u) * sizeof(double));
    j->p_at = scn_alloc(c, (j->kind->np + 1u) * sizeof(uint16_t));
}

/* ------------------------------------------------------------------ assignments */

/* which value `name` of block b means: 0 parameter, 1 state, 2 discrete state, 3 input */
static int value_slot(scn_ctx *c, const scn_block *b, scn_name n, int *idx)
{
    const rt_kind *k = b->kind;
    const char *const *lists[4] = {k->p_names, k->x_names, k->d_names, k->u_names};
    uint16_t ns[4] = {k->np, k->nx, k->nd, k->nu};
    int slot = -1;
    for (int s = 0; s < 4; s++) {
        int i = scn_find_name(lists[s], ns[s], n.s);
        if (i >= 0 && slot >= 0) {
            scn_fail(c, n.pos, n.s, "ambiguous name: both a parameter, state or input",
                     "a kind whose parameter, state and input names differ");
            return -1;
        }
        if (i >= 0)
            slot = s, *idx = i;
    }
    if (slot < 0) {
        const char *all[4 * 256];
        size_t m = 0;
        for (int s = 0; s < 4; s++)
            for (uint16_t i = 0; i < ns[s] && m < 4 * 256; i++)
                all[m++] = lists[s][i];
        scn_fail(c, n.pos, n.s, scn_fmt(c, "unknown parameter, state or input of %s",
                                        scn_kind_desc(c, b)),
                 scn_list(c, all, m, 24));
    }
    return slot;
}

static void twice(scn_ctx *c, const scn_assign *a, uint16_t first)
{
    scn_fail(c, a->lhs.port.pos, a->lhs.port.s, "assigned twice",
             scn_fmt(c, "one value per name (first at %s)",
                     scn_where(c, c->sc.asg[first - 1].lhs.port.pos)));
}

static void assign_joint(scn_ctx *c, uint16_t ai, scn_joint *j)
{
    const scn_assign *a = &c->sc.asg[ai];
    if (!strcmp(a->lhs.port.s, "axis")) { /* the joint's axis: a direction */
        if (!a->is_vec)
            scn_fail(c, a->lhs.port.pos, a->lhs.port.s, "a joint's axis is a direction",
                     scn_fmt(c, "%s.axis = (x, y, z);", j->name.s));
        else if (j->axis_at)
            twice(c, a, j->axis_at);
        else
            memcpy(j->axis, a->vec, sizeof j->axis), j->axis_at = (uint16_t)(ai + 1);
        return;
    }
    if (a->is_vec) {
        scn_fail(c, a->lhs.port.pos, a->lhs.port.s, "a direction (x, y, z) is only for axis",
                 scn_fmt(c, "%s.%s = <value>;", j->name.s, a->lhs.port.s));
        return;
    }
    int i = scn_find_name(j->kind->p_names, j->kind->np, a->lhs.port.s);
    if (i < 0) {
        scn_fail(c, a->lhs.port.pos, a->lhs.port.s,
                 scn_fmt(c, "unknown parameter of joint %s (%s)", j->name.s, j->kind->name),
                 scn_list(c, (const char *const *)j->kind->p_names, j->kind->np, 16));
        return;
    }
    if (j->p_at[i])
        twice(c, a, j->p_at[i]);
    j->p[i] = a->v, j->p_at[i] = (uint16_t)(ai + 1);
}

static void assign_block(scn_ctx *c, uint16_t ai, scn_block *b)
{
    scn_scene *s = &c->sc;
    const scn_assign *a = &s->asg[ai];
    if (a->is_vec) {
        scn_fail(c, a->lhs.port.pos, a->lhs.port.s, "a direction (x, y, z) is only for a "
                 "joint's axis", scn_fmt(c, "%s.%s = <value>;", b->name.s, a->lhs.port.s));
        return;
    }
    int i = 0, slot = value_slot(c, b, a->lhs.port, &i);
    double *vals[3] = {b->p, b->x0, b->d0};
    uint16_t *at[4] = {b->p_at, b->x_at, b->d_at, b->u_at};
    uint8_t *given[3] = {&b->p_given, &b->x_given, &b->d_given};
    if (slot < 0)
        return;
    if (at[slot][i]) {
        twice(c, a, at[slot][i]);
        return;
    }
    at[slot][i] = (uint16_t)(ai + 1);
    if (slot < 3) {
        vals[slot][i] = a->v, *given[slot] = 1;
        return;
    }
    /* an input default (rt_default) */
    if (s->ndflt >= RT_MAX_U) {
        scn_fail(c, a->lhs.port.pos, a->lhs.port.s, "too many input defaults",
                 scn_limit(c, RT_LIM_U));
        return;
    }
    s->dflt[s->ndflt++] = (scn_default){(uint16_t)(b - s->blk), (uint16_t)i, a->v};
}

static void assigns(scn_ctx *c)
{
    scn_scene *s = &c->sc;
    for (uint16_t ai = 0; ai < s->nasg && !c->err; ai++) {
        const scn_ref *r = &s->asg[ai].lhs;
        int b = scn_find_block(s, r->block.s), j = scn_find_joint(s, r->block.s);
        if (b >= 0)
            assign_block(c, ai, &s->blk[b]);
        else if (j >= 0)
            assign_joint(c, ai, &s->jnt[j]);
        else
            scn_fail(c, r->block.pos, r->block.s, "unknown system or joint",
                     scn_fmt(c, "a loaded system or joint (%s)", scn_block_list(c, 1)));
    }
}

/* ------------------------------------------------------------------ wiring */

static int port_of(scn_ctx *c, const scn_block *b, scn_name n, int output)
{
    const rt_kind *k = b->kind;
    int i = output ? scn_find_name(k->y_names, k->ny, n.s) : scn_find_name(k->u_names, k->nu, n.s);
    if (i < 0)
        scn_fail(c, n.pos, n.s,
                 scn_fmt(c, "unknown %s of %s", output ? "output" : "input", scn_kind_desc(c, b)),
                 scn_fmt(c, "one of its %s: %s", output ? "outputs" : "inputs",
                         scn_list(c, output ? k->y_names : k->u_names,
                                  output ? k->ny : k->nu, 24)));
    return i;
}

static void connection(scn_ctx *c, uint16_t ci)
{
    scn_scene *s = &c->sc;
    scn_conn *cn = &s->conn[ci];
    int fb = scn_block_of(c, cn->from.block);
    int fy = fb < 0 ? -1 : port_of(c, &s->blk[fb], cn->from.port, 1);
    int tb = fy < 0 ? -1 : scn_block_of(c, cn->to.block);
    int tu = tb < 0 ? -1 : port_of(c, &s->blk[tb], cn->to.port, 0);
    if (tu < 0)
        return;
    scn_block *to = &s->blk[tb];
    const char *near = scn_fmt(c, "%s.%s", cn->to.block.s, cn->to.port.s);
    if (to->u_conn[tu] >= 0) {
        scn_fail(c, cn->to.block.pos, near, "duplicate connection: input already driven",
                 scn_fmt(c, "one connection per input (first at %s)",
                         scn_where(c, s->conn[to->u_conn[tu]].to.block.pos)));
        return;
    }
    if (to->u_at[tu]) {
        scn_fail(c, cn->to.block.pos, near, "input is both connected and given a default",
                 scn_fmt(c, "either the connection or the default (%s)",
                         scn_where(c, s->asg[to->u_at[tu] - 1].lhs.block.pos)));
        return;
    }
    to->u_conn[tu] = (int16_t)ci;
    cn->fb = (uint16_t)fb, cn->fy = (uint16_t)fy, cn->tb = (uint16_t)tb, cn->tu = (uint16_t)tu;
}

static void wiring(scn_ctx *c)
{
    scn_scene *s = &c->sc;
    for (uint16_t i = 0; i < s->nconn && !c->err; i++)
        connection(c, i);
    for (uint16_t b = 0; b < s->nblk && !c->err; b++) {
        const scn_block *bl = &s->blk[b];
        for (uint16_t u = 0; u < bl->kind->nu && !c->err; u++)
            if (bl->u_conn[u] < 0 && !bl->u_at[u])
                scn_fail(c, bl->name.pos, bl->name.s,
                         scn_fmt(c, "input %s.%s is not connected", bl->name.s,
                                 bl->kind->u_names[u]),
                         scn_fmt(c, "connect(<System>.<output>, %s.%s); or a default %s.%s = "
                                    "<value>;", bl->name.s, bl->kind->u_names[u], bl->name.s,
                                 bl->kind->u_names[u]));
    }
}

/* ------------------------------------------------------------------ entry */

/* Every independent error is reported (up to SCN_MAX_ERRORS), in the order of the file:
   the header, each define, each block's and joint's type, and the scene's systems are
   checked on their own; what builds on them (values, wiring, sets, links, the rest) only
   when they passed, and what counts in ticks only with a base tick, so that no error
   reported is a consequence of another. */
int scn_check(scn_ctx *c)
{
    scn_scene *s = &c->sc;
    header(c);
    int timed = s->has_dt && s->dt > 0;
    scn_keep_error(c);
    unsigned e0 = scn_error_count(c);
    defines(c);
    int typed = scn_error_count(c) == e0; /* the block types may name the defines */
    for (uint16_t i = 0; i < s->nblk && typed; i++)
        block_kind(c, &s->blk[i]), scn_keep_error(c);
    for (uint16_t i = 0; i < s->njnt && typed; i++)
        joint_kind(c, &s->jnt[i]), scn_keep_error(c);
    if (scn_error_count(c) == e0) {
        assigns(c);
        if (!c->err)
            wiring(c);
        if (!c->err && timed)
            scn_check_sets(c);
        if (!c->err && timed)
            scn_check_joint_links(c);
        if (!c->err && timed)
            scn_check_rest(c);
        if (!c->err && timed)
            scn_check_ctl_link(c);
    }
    scn_keep_error(c);
    if (s->nblk == 0 && scn_error_count(c) == 0) /* a file of defines: their errors alone */
        scn_fail(c, (scn_pos){0, 1, 1}, s->name.s, "scene without systems",
                 "at least one load system (...);");
    return scn_report_errors(c);
}

