/* emit.c - the checked scene as C: const tables in the form of the hand-written scenes
 * (rt_block, rt_conn, rt_default, rt_set, rt_rec, rt_joint, rt_scene) and, for defined
 * systems, a const rt_kind with C services. Values are printed as (real_t)<shortest
 * double literal>, so the compiled scene holds exactly what image.c builds in host
 * memory; define bodies are printed from the VM's bytecode, operation by operation.
 * The file declares only the model kinds it names, so an image links only those. */
#include "scn.h"

#include <stdlib.h>
#include <string.h>

void scn_real_literal(double v, char *buf, size_t n)
{
    if (v > -1e15 && v < 1e15 && v == (double)(long long)v) {
        snprintf(buf, n, "%.0f", v); /* whole numbers as written: 10, -2, 0 */
        return;
    }
    for (int prec = 1; prec <= 17; prec++) {
        snprintf(buf, n, "%.*g", prec, v);
        if (strtod(buf, NULL) == v)
            return;
    }
}

/* "(real_t)<literal>" in a static buffer ring, for one printf */
static const char *R(double v)
{
    static char ring[8][40];
    static unsigned k;
    char *b = ring[k++ % 8];
    memcpy(b, "(real_t)", 8);
    scn_real_literal(v, b + 8, sizeof ring[0] - 8);
    return b;
}

/* a C string literal's body: quotes, backslashes and '?' escaped (no trigraphs) */
static void cstring(FILE *f, const char *s)
{
    for (; *s; s++) {
        if (*s == '"' || *s == '\\' || *s == '?')
            fputc('\\', f);
        fputc(*s, f);
    }
}

/* text inside a comment: no comment end */
static void ctext(FILE *f, const char *s)
{
    for (; *s; s++)
        fputc(*s == '/' && s[1] == '*' ? '|' : *s == '*' && s[1] == '/' ? '+' : *s, f);
}

/* ------------------------------------------------------------------ expressions */

/* one node of a statement's expression tree, rebuilt from its postfix code */
typedef struct node {
    const scn_ins *in;
    int kid[3];
    int depth;                  /* longest path to a leaf */
    int temp;                   /* >= 0: printed once into const real_t t<temp> */
} node;

#define TEMP_DEPTH 12 /* a subtree this deep gets its own temporary: bounded nesting */

static int arity(const scn_ins *in)
{
    if (in->op <= SCN_OP_LOC)
        return 0;
    if (in->op == SCN_OP_NEG || in->op == SCN_OP_NOT)
        return 1;
    if (in->op == SCN_OP_SEL)
        return 3;
    if (in->op == SCN_OP_CALL)
        return scn_fns[in->a].nargs;
    return 2;
}

/* the tree of code [i0, i1) (without the final OUT/SETLOC); returns the root */
static int build_tree(const scn_ins *code, uint32_t i0, uint32_t i1, node *nd, int *ntemp)
{
    int st[SCN_MAX_STACK + 1], sp = 0, n = 0;
    for (uint32_t i = i0; i < i1; i++, n++) {
        node *x = &nd[n];
        int k = arity(&code[i]);
        x->in = &code[i], x->depth = 1, x->temp = -1;
        for (int j = k - 1; j >= 0; j--) {
            x->kid[j] = st[--sp];
            if (nd[x->kid[j]].depth + 1 > x->depth)
                x->depth = nd[x->kid[j]].depth + 1;
        }
        if (x->depth >= TEMP_DEPTH)
            x->temp = (*ntemp)++, x->depth = 1;
        st[sp++] = n;
    }
    return sp ? st[sp - 1] : -1;
}

static void expr(FILE *f, const scn_ctx *c, const node *nd, int i, int top);

static void kids(FILE *f, const scn_ctx *c, const node *nd, const node *x, const char *sep)
{
    expr(f, c, nd, x->kid[0], 0);
    fputs(sep, f);
    expr(f, c, nd, x->kid[1], 0);
}

static void expr(FILE *f, const scn_ctx *c, const node *nd, int i, int top)
{
    static const char *const bin[] = {" + ", " - ", " * ", " / "};
    static const char *const cond[] = {"rt_x_lt", "rt_x_le", "rt_x_gt", "rt_x_ge",
                                       "rt_x_eq", "rt_x_ne", "rt_x_and", "rt_x_or"};
    const node *x = &nd[i];
    const scn_ins *in = x->in;
    if (x->temp >= 0 && !top) {
        fprintf(f, "t%d", x->temp);
        return;
    }
    switch (in->op) {
    case SCN_OP_CONST: fputs(R(c->sc.k[in->a]), f); return;
    case SCN_OP_TIME: fputs("a->t", f); return;
    case SCN_OP_TPIECE: fputs("a->t_piece", f); return;
    case SCN_OP_STEP: fputs("a->h", f); return;
    case SCN_OP_IN: fprintf(f, "a->u[%u]", in->a); return;
    case SCN_OP_PAR: fprintf(f, "a->p[%u]", in->a); return;
    case SCN_OP_STATE: fprintf(f, "a->x[%u]", in->a); return;
    case SCN_OP_DSTATE: fprintf(f, "a->d[%u]", in->a); return;
    case SCN_OP_LOC: fprintf(f, "l%u", in->a); return;
    case SCN_OP_NEG: fputs("(-", f), expr(f, c, nd, x->kid[0], 0), fputs(")", f); return;
    case SCN_OP_NOT:
        fputs("rt_x_not(", f), expr(f, c, nd, x->kid[0], 0), fputs(")", f);
        return;
    case SCN_OP_SEL:
        fputs("rt_x_if(", f), expr(f, c, nd, x->kid[0], 0), fputs(", ", f);
        kids(f, c, nd, &(node){.kid = {x->kid[1], x->kid[2]}}, ", "), fputs(")", f);
        return;
    case SCN_OP_CALL:
        fprintf(f, "%s(", scn_fns[in->a].c), expr(f, c, nd, x->kid[0], 0);
        if (scn_fns[in->a].nargs == 2)
            fputs(", ", f), expr(f, c, nd, x->kid[1], 0);
        fputs(")", f);
        return;
    default:
        if (in->op >= SCN_OP_LT && in->a >= SCN_SW_BASE) { /* a located switch, as the VM */
            fputs("rt_x_swc(", f), kids(f, c, nd, x, ", ");
            fprintf(f, ", a->x[%u], %d)", in->a - SCN_SW_BASE, in->op - SCN_OP_LT);
            return;
        }
        if (in->op >= SCN_OP_LT && in->a) { /* t with an instant: rt_x_at, as the VM */
            int tk = x->kid[in->a == SCN_TSIDE_LEFT ? 0 : 1], ck = x->kid[in->a == SCN_TSIDE_LEFT];
            fprintf(f, "%s(", cond[in->op - SCN_OP_LT]);
            if (in->a == SCN_TSIDE_RIGHT)
                expr(f, c, nd, ck, 0), fputs(", ", f);
            fputs("rt_x_at(a->t, ", f), expr(f, c, nd, tk, 0), fputs(", ", f);
            expr(f, c, nd, ck, 0), fputs(")", f);
            if (in->a == SCN_TSIDE_LEFT)
                fputs(", ", f), expr(f, c, nd, ck, 0);
            fputs(")", f);
            return;
        }
        if (in->op >= SCN_OP_LT) { /* comparisons, and, or: rt/rt_expr.h, as the VM */
            fprintf(f, "%s(", cond[in->op - SCN_OP_LT]), kids(f, c, nd, x, ", ");
            fputs(")", f);
            return;
        }
        fputs("(", f), kids(f, c, nd, x, bin[in->op - SCN_OP_ADD]), fputs(")", f);
    }
}

/* one body statement: its temporaries, then `const real_t l<i> = ...;` or `out[i] = ...;` */
static void statement(FILE *f, const scn_ctx *c, const scn_stmt *st, const char *out, int *ntemp)
{
    uint32_t n = st->code1 - st->code0 - 1;
    node *nd = malloc((n ? n : 1) * sizeof *nd);
    if (!nd)
        return;
    int root = build_tree(c->sc.code, st->code0, st->code1 - 1, nd, ntemp);
    for (uint32_t i = 0; i < n; i++)
        if (nd[i].temp >= 0 && (int)i != root) {
            fprintf(f, "    const real_t t%d = ", nd[i].temp);
            expr(f, c, nd, (int)i, 1);
            fputs(";\n", f);
        }
    if (st->kind == SCN_ST_LET)
        fprintf(f, "    const real_t l%u = ", st->index);
    else
        fprintf(f, "    %s[%u] = ", out, st->index);
    expr(f, c, nd, root, 1);
    fputs(";\n", f);
    free(nd);
}

/* ------------------------------------------------------------------ defines */

static void names(FILE *f, const char *id, const char *what, const scn_var *v, uint16_t n)
{
    if (n == 0)
        return;
    fprintf(f, "static const char *const %s_%s[] = {", id, what);
    for (uint16_t i = 0; i < n; i++)
        fprintf(f, "%s\"%s\"", i ? ", " : "", v[i].name.s);
    fputs("};\n", f);
}

static void reals(FILE *f, const char *id, const char *what, const double *v, size_t n)
{
    if (n == 0)
        return;
    fprintf(f, "static const real_t %s_%s[] = {", id, what);
    for (size_t i = 0; i < n; i++)
        fprintf(f, "%s%s", i ? ", " : "", R(v[i]));
    fputs("};\n", f);
}

static void var_reals(FILE *f, const char *id, const char *what, const scn_var *v, uint16_t n)
{
    double d[SCN_MAX_PORTS];
    for (uint16_t i = 0; i < n; i++)
        d[i] = v[i].init;
    reals(f, id, what, d, n);
}

/* the statements of d's service `kind` (scn_service: with the lets they read), each
   stored into out[] */
static void statements(FILE *f, const scn_ctx *c, const scn_define *d, uint8_t kind,
                       const char *out, int *ntemp)
{
    uint8_t in[SCN_MAX_STMTS];
    scn_service(c, d, kind, in);
    for (uint32_t s = d->st0; s < d->st1; s++)
        if (in[s - d->st0])
            statement(f, c, &c->sc.st[s], out, ntemp);
}

static void service(FILE *f, const scn_ctx *c, const scn_define *d, const char *id,
                    uint8_t kind)
{
    static const char *const fn[] = {"", "output", "deriv", "update"};
    static const char *const out[] = {"", "y", "xdot", "dnext"};
    int ntemp = 0;
    fprintf(f, "\nstatic void %s_%s(const rt_args *a, real_t *%s)\n{\n    (void)a;\n", id,
            fn[kind], out[kind]);
    statements(f, c, d, kind, out[kind], &ntemp);
    fputs("}\n", f);
}

/* the instants the body compares t with, and the kind's next_event over them */
static void instants(FILE *f, const scn_ctx *c, const scn_define *d, const char *id)
{
    int ntemp = 0;
    fprintf(f, "\nstatic real_t %s_next(const rt_args *a)\n{\n    real_t v[%u];\n", id,
            (unsigned)d->ntev);
    statements(f, c, d, SCN_ST_TEV, "v", &ntemp);
    fprintf(f, "    return rt_x_next(a->t, v, %u);\n}\n", (unsigned)d->ntev);
}

/* the sin and cos arguments affine in t, and the kind's band over them */
static void bands(FILE *f, const scn_ctx *c, const scn_define *d, const char *id)
{
    int ntemp = 0;
    fprintf(f, "\nstatic void %s_band_at(const rt_args *a, real_t *v)\n{\n", id);
    statements(f, c, d, SCN_ST_BAND, "v", &ntemp);
    fprintf(f, "}\n\nstatic real_t %s_band(const rt_args *a)\n{\n"
               "    rt_args b = *a;\n    real_t v0[%u], v1[%u];\n"
               "    b.t = 0, %s_band_at(&b, v0);\n    b.t = 1, %s_band_at(&b, v1);\n"
               "    return rt_x_band(v0, v1, %u);\n}\n", id, (unsigned)d->nband,
            (unsigned)d->nband, id, id, (unsigned)d->nband);
}

/* the statements of root r's service kind (handler, rest time or rest handler) */
static void handler(FILE *f, const scn_ctx *c, const scn_define *d, uint8_t kind, uint16_t r,
                    const char *out, int *ntemp)
{
    uint8_t in[SCN_MAX_STMTS];
    scn_service_root(c, d, kind, r, in);
    fputs("    {\n", f);
    for (uint32_t s = d->st0; s < d->st1; s++)
        if (in[s - d->st0])
            statement(f, c, &c->sc.st[s], out, ntemp);
    fputs("    }\n", f);
}

/* roots and the event handlers, one case per root */
static void event_services(FILE *f, const scn_ctx *c, const scn_define *d, const char *id)
{
    int ntemp = 0;
    fprintf(f, "\nstatic void %s_roots(const rt_args *a, real_t *r)\n{\n    (void)a;\n", id);
    statements(f, c, d, SCN_ST_ROOT, "r", &ntemp);
    fprintf(f, "}\n\nstatic const int8_t %s_rdir[] = {", id);
    for (uint16_t r = 0; r < d->nr; r++)
        fprintf(f, "%s%d", r ? ", " : "", d->rdir[r]);
    fprintf(f, "};\n\nstatic void %s_event(const rt_args *a, uint16_t which, real_t *x, "
               "real_t *d)\n{\n    switch (which) {\n", id);
    for (uint16_t r = 0; r < d->nr; r++) {
        fprintf(f, "    case %u: {\n", (unsigned)r);
        if (d->rest[r]) { /* as scn_vm_event: the rest clause's time, then one handler */
            fprintf(f, "    real_t tq[%u];\n", r + 1u);
            handler(f, c, d, SCN_ST_REST_T, r, "tq", &ntemp);
            fprintf(f, "    if (a->t - d[%u] < tq[%u]) {\n", r, r);
            handler(f, c, d, SCN_ST_REST, r, "x", &ntemp);
            fputs("    } else {\n", f);
        }
        handler(f, c, d, SCN_ST_EVENT, r, "x", &ntemp);
        if (d->rest[r])
            fputs("    }\n", f);
        fprintf(f, "        d[%u] = a->t;\n        break;\n    }\n", r);
    }
    fputs("    default:\n        break;\n    }\n}\n", f);
    if (d->nswm == 0)
        return;
    /* scn_vm_instant: the located switches' modes at the start of a step part */
    fprintf(f, "\nstatic int %s_instant(const rt_args *a, real_t *x, real_t *d)\n{\n"
               "    real_t r[%u], m, v;\n    int changed = 0;\n    (void)d;\n"
               "    %s_roots(a, r);\n", id, (unsigned)d->nr, id);
    for (uint16_t k = 0; k < d->nswm; k++)
        fprintf(f, "    m = x[%u], v = rt_x_sw_mode(r[%u], m);\n"
                   "    changed |= (m == 0 || m == 1) && v != m;\n    x[%u] = v;\n",
                d->swm[k][0], d->swm[k][1], d->swm[k][0]);
    fputs("    return changed;\n}\n", f);
}

static void lss_spec(FILE *f, const scn_define *d, const char *id)
{
    const scn_matrix *m[4] = {&d->A, &d->B, &d->C, &d->D};
    static const char *const mn[4] = {"A", "B", "C", "D"};
    for (int i = 0; i < 4; i++)
        reals(f, id, mn[i], m[i]->v, (size_t)m[i]->rows * m[i]->cols);
    fprintf(f, "static const rt_lss_spec %s_lss = {\n    .nx = %u, .nu = %u, .ny = %u,", id,
            d->nx, d->nu, d->ny);
    for (int i = 0; i < 4; i++)
        if ((size_t)m[i]->rows * m[i]->cols > 0)
            fprintf(f, " .%s = %s_%s,", mn[i], id, mn[i]);
    fputs("\n};\n", f);
}

static const char *const type_id[] = {"RT_KIND_OUTPUT", "RT_KIND_NSS", "RT_KIND_LSS",
                                      "RT_KIND_DSS", "RT_KIND_MBS"};
static const char *const feed_id[] = {"RT_FEED_NONE", "RT_FEED_ALL", "RT_FEED_TABLE"};

/* the kind's invariants (rt_kind.inv) and the state indices they read */
static void invariants(FILE *f, const rt_kind *k, const char *pre)
{
#define SCN_X_ID(id, name, text) #id,
    static const char *const inv_id[] = {RT_INV_LIST(SCN_X_ID)};
#undef SCN_X_ID
    for (uint8_t i = 0; i < k->ninv; i++) {
        fprintf(f, "static const uint16_t %s_inv%u[] = {", pre, i);
        for (uint8_t j = 0; j < k->inv[i].n; j++)
            fprintf(f, "%s%u", j ? ", " : "", k->inv[i].x[j]);
        fputs("};\n", f);
    }
    if (k->ninv)
        fprintf(f, "static const rt_invariant %s_inv[] = {\n", pre);
    for (uint8_t i = 0; i < k->ninv; i++) {
        const rt_invariant *v = &k->inv[i];
        fprintf(f, "    {.type = %s, .n = %u, .x = %s_inv%u, .c = %s,", inv_id[v->type], v->n,
                pre, i, R((double)v->c));
        fprintf(f, " .tol = %s},\n", R((double)v->tol));
    }
    if (k->ninv)
        fputs("};\n", f);
}

static void define_kind(FILE *f, const scn_ctx *c, const scn_define *d)
{
    static const char *const dtype[] = {"ss_system", "lss_system", "dss_system"};
    const rt_kind *k = d->kind;
    const char *id = d->name.s;
    char pre[SCN_MAX_NAME + 4];
    int dss = d->type == SCN_DEF_DSS;
    snprintf(pre, sizeof pre, "d_%s", id);
    fprintf(f, "\n/* ---- define %s (%s), %s:%u */\n", dtype[d->type], id,
            scn_path(c, d->name.pos), (unsigned)d->name.pos.line);
    names(f, pre, "u", d->u, d->nu), names(f, pre, "y", d->y, d->ny);
    names(f, pre, "p", d->p, d->np), names(f, pre, "x", d->x, d->nx);
    var_reals(f, pre, "pdef", d->p, d->np), var_reals(f, pre, "xdef", d->x, d->nx);
    if (!dss && d->nr) {
        scn_var t_last[SCN_MAX_PORTS];
        for (uint16_t r = 0; r < d->nr; r++)
            t_last[r] = (scn_var){{k->d_names[r], d->name.pos}, SCN_T_LAST0};
        names(f, pre, "d", t_last, d->nr), var_reals(f, pre, "ddef", t_last, d->nr);
    }
    if (k->feed == RT_FEED_TABLE) {
        fprintf(f, "static const uint8_t %s_feed[] = {", pre);
        for (size_t i = 0; i < (size_t)d->ny * d->nu; i++)
            fprintf(f, "%s%u", i ? ", " : "", d->feed[i]);
        fputs("};\n", f);
    }
    if (d->type == SCN_DEF_LSS) {
        lss_spec(f, d, pre);
    } else {
        if (d->ny)
            service(f, c, d, pre, SCN_ST_OUT);
        if (d->nx && !dss)
            service(f, c, d, pre, SCN_ST_DER);
        if (dss)
            service(f, c, d, pre, SCN_ST_NEXT);
        if (d->nr)
            event_services(f, c, d, pre);
        if (d->ntev)
            instants(f, c, d, pre);
        if (d->nband)
            bands(f, c, d, pre);
    }
    invariants(f, k, pre);
    fprintf(f, "\nstatic const rt_kind %s_kind = {\n    .name = \"%s\", .type = %s,\n", pre, id,
            type_id[k->type]);
    fprintf(f, "    .nu = %u, .ny = %u, .nx = %u, .nd = %u, .np = %u, .nr = %u,\n", k->nu,
            k->ny, k->nx, k->nd, k->np, k->nr);
    const char *slot[] = {d->nu ? "u" : 0, d->ny ? "y" : 0, d->np ? "p" : 0,
                          d->nx ? "x" : 0};
    const char *field[] = {"u_names", "y_names", "p_names", dss ? "d_names" : "x_names"};
    for (int i = 0; i < 4; i++)
        if (slot[i])
            fprintf(f, "    .%s = %s_%s,\n", field[i], pre, slot[i]);
    if (d->np)
        fprintf(f, "    .p_default = %s_pdef,\n", pre);
    if (!dss && d->nr) /* the roots' t_last */
        fprintf(f, "    .d_names = %s_d, .d_default = %s_ddef,\n", pre, pre);
    if (d->nx)
        fprintf(f, "    .%s = %s_xdef,\n", dss ? "d_default" : "x_default", pre);
    fprintf(f, "    .feed = %s,", feed_id[k->feed]);
    if (k->feed == RT_FEED_TABLE)
        fprintf(f, " .feed_table = %s_feed,", pre);
    fputs("\n   ", f);
    if (d->type == SCN_DEF_LSS)
        fprintf(f, "%s .deriv = rt_lss_deriv, .spec = &%s_lss,",
                d->ny ? " .output = rt_lss_output," : "", pre);
    if (d->type != SCN_DEF_LSS && d->ny)
        fprintf(f, " .output = %s_output,", pre);
    if (d->type != SCN_DEF_LSS && d->nx && !dss)
        fprintf(f, " .deriv = %s_deriv,", pre);
    if (dss)
        fprintf(f, " .update = %s_update,", pre);
    if (d->nr)
        fprintf(f, " .roots = %s_roots, .event = %s_event, .root_dir = %s_rdir,", pre, pre, pre);
    if (d->nswm)
        fprintf(f, " .instant = %s_instant, .instant_own = 1,", pre);
    if (d->ntev)
        fprintf(f, " .next_event = %s_next, .time_event = rt_tev_none,", pre);
    if (d->nband)
        fprintf(f, " .band = %s_band,", pre);
    if (k->ninv)
        fprintf(f, " .inv = %s_inv, .ninv = %u,", pre, k->ninv);
    fputs("\n};\n", f);
}

/* ------------------------------------------------------------------ the scene */

static int used_define(const scn_scene *s, uint16_t d)
{
    for (uint16_t b = 0; b < s->nblk; b++)
        if (s->blk[b].def == d)
            return 1;
    return 0;
}

/* FMU blocks: each its own kind, model and instance, written by the FMU loader
   (tools/fmi/fmu_emit.c); an FMU without sources stops the compilation */
static void fmu_kinds(FILE *f, scn_ctx *c)
{
    const scn_scene *s = &c->sc;
    int any = 0;
    for (uint16_t b = 0; b < s->nblk && !c->err; b++) {
        const scn_block *bl = &s->blk[b];
        char err[SCN_MSG_LEN];
        if (!bl->fmu)
            continue;
        if (!any++)
            fputs("\n/* the FMU blocks: the FMI calls of the host's loader, bound statically "
                  "(docs/fmi.md) */\n#include \"fmu_int.h\"\n", f);
        if (c->fmu->emit(f, bl->kind, err, sizeof err) != 0)
            scn_fail(c, bl->type.pos, bl->type.s, scn_fmt(c, "FMU of %s: %s", bl->name.s, err),
                     "a source FMU (sources/) for a per-scene image or an exported FMU");
    }
}

static void header(FILE *f, scn_ctx *c)
{
    const scn_scene *s = &c->sc;
    fprintf(f, "/* %s.c - scene `%s`", s->name.s, s->name.s);
    if (s->doc && *s->doc)
        fputs(": ", f), ctext(f, s->doc);
    fputs(".\n * Generated by scenec from ", f);
    ctext(f, c->files[0].path);
    fputs(": edit that file, not this one.", f);
    const char *units = "";
    for (uint16_t b = 0; b < s->nblk; b++)
        if (s->blk[b].unit && !strstr(units, s->blk[b].unit))
            units = scn_fmt(c, "%s%s%s", units, *units ? ", " : "", s->blk[b].unit);
    if (*units)
        fputs("\n * Units named by `from file`: ", f), ctext(f, units), fputs(".", f);
    fputs(" */\n#include \"rt.h\"\n#include \"rt_expr.h\"\n\n"
          "/* the model kinds this scene names, and only those */\n", f);
    for (uint16_t b = 0; b < s->nblk; b++) {
        int first = 1;
        for (uint16_t e = 0; e < b; e++)
            first &= s->blk[e].kind != s->blk[b].kind;
        if (first && s->blk[b].def < 0 && !s->blk[b].fmu)
            fprintf(f, "extern const rt_kind mdl_%s_kind;\n", s->blk[b].type.s);
    }
    for (uint16_t d = 0; d < s->ndef; d++)
        if (used_define(s, d))
            define_kind(f, c, s->def[d]);
    fmu_kinds(f, c);
}

static void block_values(FILE *f, const scn_block *b)
{
    char id[SCN_MAX_NAME + 4];
    snprintf(id, sizeof id, "b_%s", b->name.s);
    if (b->p_given)
        reals(f, id, "p", b->p, b->kind->np);
    if (b->x_given)
        reals(f, id, "x0", b->x0, b->kind->nx);
    if (b->d_given)
        reals(f, id, "d0", b->d0, b->kind->nd);
}

static void blocks(FILE *f, const scn_scene *s)
{
    fputs("\nenum {", f);
    for (uint16_t b = 0; b < s->nblk; b++)
        fprintf(f, "%s B_%s", b ? "," : "", s->blk[b].name.s);
    fputs(" };\n\n", f);
    for (uint16_t b = 0; b < s->nblk; b++)
        block_values(f, &s->blk[b]);
    fputs("static const rt_block blocks[] = {\n", f);
    for (uint16_t i = 0; i < s->nblk; i++) {
        const scn_block *b = &s->blk[i];
        const char *n = b->name.s;
        fprintf(f, "    [B_%s] = {.name = \"%s\", .kind = &", n, n);
        if (b->fmu)
            fprintf(f, "fmu_%s_kind", n);
        else
            fprintf(f, b->def >= 0 ? "d_%s_kind" : "mdl_%s_kind", b->type.s);
        if (b->p_given)
            fprintf(f, ", .p = b_%s_p", n);
        if (b->x_given)
            fprintf(f, ", .x0 = b_%s_x0", n);
        if (b->d_given)
            fprintf(f, ", .d0 = b_%s_d0", n);
        if (b->set)
            fprintf(f, ", .set = %d", b->set);
        if (b->ts > 0)
            fprintf(f, ", .ts = %s", R(b->ts));
        fputs("},\n", f);
    }
    fputs("};\n", f);
}

#define SCN_X_ID(id, name) #id,
static const char *const interp_id[] = {RT_INTERP_LIST(SCN_X_ID)};
#undef SCN_X_ID

static int any_conn_interp(const scn_scene *s)
{
    for (uint16_t i = 0; i < s->nconn; i++)
        if (s->conn[i].interp)
            return 1;
    return 0;
}

static void wiring(FILE *f, const scn_scene *s)
{
    if (any_conn_interp(s)) {
        fputs("static const uint8_t conn_interp[] = {", f);
        for (uint16_t i = 0; i < s->nconn; i++)
            fprintf(f, "%s%s", i ? ", " : "", interp_id[s->conn[i].interp]);
        fputs("};\n", f);
    }
    if (s->nconn)
        fputs("static const rt_conn conns[] = {\n", f);
    for (uint16_t i = 0; i < s->nconn; i++) {
        const scn_conn *cn = &s->conn[i];
        fprintf(f, "    {B_%s, %u, B_%s, %u}, /* %s.%s -> %s.%s */\n", s->blk[cn->fb].name.s,
                cn->fy, s->blk[cn->tb].name.s, cn->tu, cn->from.block.s, cn->from.port.s,
                cn->to.block.s, cn->to.port.s);
    }
    if (s->nconn)
        fputs("};\n", f);
    if (s->ndflt)
        fputs("static const rt_default defaults[] = {\n", f);
    for (uint16_t i = 0; i < s->ndflt; i++) {
        const scn_default *d = &s->dflt[i];
        const scn_block *b = &s->blk[d->b];
        fprintf(f, "    {B_%s, %u, %s}, /* %s.%s */\n", b->name.s, d->u, R(d->v), b->name.s,
                b->kind->u_names[d->u]);
    }
    if (s->ndflt)
        fputs("};\n", f);
}

/* the settings a clause gave (RT_SET_CFG_LIST; the others stay 0, their defaults) */
static void set_cfg(FILE *f, const scn_set *st)
{
    static const char *const field[RT_CFG_N] = {
#define RT_X_FIELD(id, word, opt, field, kind, max, scope, dflt, help) #field,
        RT_SET_CFG_LIST(RT_X_FIELD)
#undef RT_X_FIELD
    };
    const char *sep = ",\n     .cfg = {";
    for (int id = 0; id < RT_CFG_N; id++) {
        if (!st->has_cfg[id])
            continue;
        double v = (double)rt_set_cfg_get(&st->cfg, (rt_cfg_id)id);
        uint8_t kind = rt_set_opts[id].kind;
        if (kind == RT_CFG_COUNT || kind == RT_CFG_POW2)
            fprintf(f, "%s.%s = %u", sep, field[id], (unsigned)v);
        else
            fprintf(f, "%s.%s = %s", sep, field[id], R(v));
        sep = ", ";
    }
    if (sep[0] == ',' && sep[1] == ' ')
        fputs("}", f);
}

static void sets(FILE *f, const scn_scene *s)
{
    fputs("static const rt_set sets[] = {\n", f);
    for (uint16_t i = 0; i < s->nset; i++) {
        const scn_set *st = &s->set[i];
        fprintf(f, "    {.name = \"%s\", .method = &rt_%s, .ratio = %u", st->name.s, st->m->name,
                (unsigned)st->ratio);
        if (st->interp)
            fprintf(f, ", .interp = %s", interp_id[st->interp]);
        set_cfg(f, st);
        if (st->background)
            fputs(", .background = 1", f);
        fputs("},\n", f);
    }
    fputs("};\n", f);
}

static void recs(FILE *f, const scn_scene *s)
{
    static const char *const what[] = {"RT_SIG_Y", "RT_SIG_X", "RT_SIG_D", "RT_SIG_MBS"};
    if (!s->nrec)
        return;
    fputs("static const rt_rec recs[] = {\n", f);
    for (uint16_t i = 0; i < s->nrec; i++) {
        const scn_rec *r = &s->rec[i];
        fprintf(f, "    {B_%s, %s, %u}, /* %s.%s */\n", s->blk[r->r.block].name.s, what[r->r.what],
                r->r.index, r->sig.block.s, r->sig.port.s);
    }
    fputs("};\n", f);
}

/* the controller link: exports like recorded signals, the import block, defaults,
   policies, and the layout's identity (docs/link.md) */
static void link(FILE *f, const scn_scene *s)
{
    static const char *const what[] = {"RT_SIG_Y", "RT_SIG_X", "RT_SIG_D", "RT_SIG_MBS"};
#define SCN_X_ID(id, name) #id,
    static const char *const pol[] = {RT_LINK_POLICY_LIST(SCN_X_ID)};
#undef SCN_X_ID
    const rt_link *l = &s->link;
    if (!l->name)
        return;
    if (l->nexp) {
        fputs("static const rt_rec link_exp[] = {\n", f);
        for (uint16_t i = 0; i < l->nexp; i++)
            fprintf(f, "    {B_%s, %s, %u}, /* %s.%s */\n", s->blk[l->exp[i].block].name.s,
                    what[l->exp[i].what], l->exp[i].index, s->lexp[i].sig.block.s,
                    s->lexp[i].sig.port.s);
        fputs("};\n", f);
    }
    if (l->nimp) {
        fputs("static const real_t link_def[] = {", f);
        for (uint16_t i = 0; i < l->nimp; i++)
            fprintf(f, "%s%s", i ? ", " : "", R(l->def[i]));
        fputs("};\nstatic const uint8_t link_policy[] = {", f);
        for (uint16_t i = 0; i < l->nimp; i++)
            fprintf(f, "%s%s", i ? ", " : "", pol[l->policy[i]]);
        fputs("};\n", f);
    }
    fprintf(f, "static const rt_link link = {\n    .name = \"%s\", .period = %u, .id = 0x%08xu,\n",
            l->name, (unsigned)l->period, (unsigned)l->id);
    if (l->nexp)
        fprintf(f, "    .exp = link_exp, .nexp = %u,\n", l->nexp);
    if (l->nimp)
        fprintf(f, "    .block = B_%s, .nimp = %u, .def = link_def, .policy = link_policy,\n",
                s->blk[l->block].name.s, l->nimp);
    fputs("};\n", f);
}

static void joints(FILE *f, const scn_scene *s)
{
    char id[SCN_MAX_NAME + 4];
    for (uint16_t i = 0; i < s->njnt; i++) {
        const scn_joint *j = &s->jnt[i];
        snprintf(id, sizeof id, "j_%s", j->name.s);
        reals(f, id, "p", j->p, j->kind->np);
        if (s->lnk[j->link].has_at)
            reals(f, id, "at", s->lnk[j->link].at, 3);
        if (s->lnk[j->link].has_turn)
            reals(f, id, "at_S", s->lnk[j->link].at_S, 9);
        if (j->axis_at)
            reals(f, id, "axis_S", j->axis_S, 9);
    }
    if (s->njnt)
        fputs("static const rt_joint joints[] = {\n", f);
    for (uint16_t i = 0; i < s->njnt; i++) {
        const scn_joint *j = &s->jnt[i];
        const scn_link *l = &s->lnk[j->link];
        fprintf(f, "    {.name = \"%s\", .kind = &rt_joint_%s, .b1 = B_%s, .n1 = %d, ", j->name.s,
                j->kind->name, s->blk[l->b1].name.s, l->n1);
        if (l->b2 >= 0)
            fprintf(f, ".b2 = B_%s, .n2 = %d", s->blk[l->b2].name.s, l->n2);
        else
            fputs(".b2 = -1", f);
        if (j->kind->np)
            fprintf(f, ", .p = j_%s_p", j->name.s);
        if (l->has_at)
            fprintf(f, ", .at = j_%s_at", j->name.s);
        if (l->has_turn)
            fprintf(f, ", .at_S = j_%s_at_S", j->name.s);
        if (j->axis_at)
            fprintf(f, ", .axis_S = j_%s_axis_S", j->name.s);
        fputs("},\n", f);
    }
    if (s->njnt)
        fputs("};\n", f);
}

static void scene(FILE *f, const scn_ctx *c, int code)
{
#define SCN_X_ID(id, name) #id,
    static const char *const stab[] = {RT_STAB_LIST(SCN_X_ID)};
#undef SCN_X_ID
    const scn_scene *s = &c->sc;
    const rt_scene *im = &c->image;
    fprintf(f, "\nconst rt_scene " SCN_SYMBOL_PREFIX "%s = {\n    .name = \"%s\",\n    .doc = \"",
            s->name.s, s->name.s);
    cstring(f, s->doc ? s->doc : "");
    fprintf(f, "\",\n    .dt = %s,", R(s->dt));
    fprintf(f, " .t_end = %s,\n", R(s->t_end));
    fprintf(f, "    .blocks = blocks, .nblocks = %u,\n", s->nblk);
    if (s->nconn)
        fprintf(f, "    .conns = conns, .nconns = %u,\n", s->nconn);
    if (any_conn_interp(s))
        fputs("    .conn_interp = conn_interp,\n", f);
    if (s->ndflt)
        fprintf(f, "    .defaults = defaults, .ndefaults = %u,\n", s->ndflt);
    fprintf(f, "    .sets = sets, .nsets = %u,\n", s->nset);
    if (s->nrec)
        fprintf(f, "    .recs = recs, .nrecs = %u,\n", s->nrec);
    if (s->njnt)
        fprintf(f, "    .joints = joints, .njoints = %u,\n", s->njnt);
    if (im->mbs)
        fprintf(f, "    .mbs = &rt_mbs, .stab = %s,\n", stab[im->stab]);
    if (im->mbs && (s->alpha != 0 || s->beta != 0))
        fprintf(f, "    .baumgarte = {%s, %s},\n", R(s->alpha), R(s->beta));
    if (s->solver.s)
        fprintf(f, "    .loop_solver = &rt_broyden,\n");
    if (s->loop_iter)
        fprintf(f, "    .loop_iter_max = %u,\n", (unsigned)s->loop_iter);
    if (s->loop_tol != 0)
        fprintf(f, "    .loop_tol = %s,\n", R(s->loop_tol));
    if (s->link.name)
        fputs("    .link = &link,\n", f);
    for (uint16_t i = 0; i < s->nset; i++)
        if (s->set[i].background) {
            fputs("    .bg = &rt_bg,\n", f);
            break;
        }
    if (code)
        fputs("#if RT_SCENE_CODE\n    .code = &scene_code,\n#endif\n", f);
    fputs("};\n", f);
}

int scn_emit(scn_ctx *c, FILE *f)
{
    if (c->err)
        return -1;
    header(f, c);
    if (c->err)
        return -1;
    blocks(f, &c->sc);
    wiring(f, &c->sc);
    sets(f, &c->sc);
    recs(f, &c->sc);
    link(f, &c->sc);
    joints(f, &c->sc);
    scene(f, c, scn_emit_code(f, c));
    return ferror(f) ? -1 : 0;
}
