/* parse.c - the statements of the scene language (grammar in docs/scene-language.md):
 * one function per statement, dispatched from a {word, function} table. Parsing only
 * records what is written, with positions; names are resolved by check.c, so statements
 * may come in any order. */
#include "scn.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ------------------------------------------------------------------ pieces */

static scn_ref ref(scn_ctx *c, const char *what)
{
    scn_ref r;
    r.block = scn_expect_name(c, what);
    scn_expect_op(c, ".");
    r.port = scn_expect_name(c, what);
    return r;
}

/* ( name {, name} ) */
static uint16_t name_list(scn_ctx *c, scn_name *out, uint16_t max, const char *what)
{
    uint16_t n = 0;
    scn_expect_op(c, "(");
    do {
        scn_name nm = scn_expect_name(c, what);
        if (!c->err && n >= max)
            scn_fail(c, nm.pos, nm.s, "too many names in the list",
                     scn_fmt(c, "at most %u", (unsigned)max));
        if (!c->err)
            out[n++] = nm;
    } while (!c->err && scn_accept_op(c, ","));
    scn_expect_op(c, ")");
    return n;
}

/* ( name ) */
static scn_name paren_name(scn_ctx *c, const char *what)
{
    scn_expect_op(c, "(");
    scn_name n = scn_expect_name(c, what);
    scn_expect_op(c, ")");
    return n;
}

static const char *paren_string(scn_ctx *c, const char *what)
{
    const char *s = "";
    scn_expect_op(c, "(");
    if (c->tok.kind == SCN_T_STR)
        s = c->tok.s, scn_next(c);
    else
        scn_fail_tok(c, "syntax error", what);
    scn_expect_op(c, ")");
    return s;
}

static double paren_const(scn_ctx *c)
{
    scn_expect_op(c, "(");
    double v = scn_const_expr(c);
    scn_expect_op(c, ")");
    return v;
}

/* ( whole number from 1 to max ) */
static uint32_t paren_count(scn_ctx *c, uint32_t max)
{
    uint32_t v = 0;
    scn_expect_op(c, "(");
    if (c->tok.kind != SCN_T_NUM || !(c->tok.num >= 1 && c->tok.num <= max) ||
        c->tok.num != (double)(uint32_t)c->tok.num)
        scn_fail_tok(c, "bad count", scn_fmt(c, "a whole number from 1 to %u", (unsigned)max));
    else
        v = (uint32_t)c->tok.num;
    scn_next(c);
    scn_expect_op(c, ")");
    return v;
}

/* the literal scaled by 10^shift, rounded once (so "10 ms" is exactly the double 0.01) */
static double scaled(scn_ctx *c, const scn_tok *t, int shift)
{
    const char *raw = scn_strndup(c, t->raw, t->rawlen);
    const char *e = strpbrk(raw, "eE");
    long ex = e ? strtol(e + 1, NULL, 10) : 0;
    if (ex > 100000 || ex < -100000)
        ex = ex > 0 ? 100000 : -100000;
    int mant = e ? (int)(e - raw) : (int)strlen(raw);
    return strtod(scn_fmt(c, "%.*se%ld", mant, raw, ex + shift), NULL);
}

/* ( number [unit] ): seconds, or base ticks if allowed and written so */
static double paren_time(scn_ctx *c, int allow_ticks, uint8_t *ticks, scn_pos *pos)
{
    static const struct { const char *unit; int shift; } units[] = {
        {"s", 0}, {"ms", -3}, {"us", -6}, {"ns", -9}, {0, 0},
    };
    double v = 0;
    scn_expect_op(c, "(");
    scn_tok num = c->tok;
    if (pos)
        *pos = num.pos;
    if (num.kind != SCN_T_NUM) {
        scn_fail_tok(c, "syntax error", allow_ticks ? "a time such as 1 ms, 0.5 s or 2 ticks"
                                                    : "a time such as 1 ms or 0.5 s");
        return 0;
    }
    scn_next(c);
    int shift = 0, is_ticks = 0, found = c->tok.kind != SCN_T_ID;
    for (int i = 0; !found && units[i].unit; i++)
        if (scn_is_word(c, units[i].unit))
            shift = units[i].shift, found = 1;
    if (!found && allow_ticks && (scn_is_word(c, "tick") || scn_is_word(c, "ticks")))
        is_ticks = found = 1;
    if (!found) {
        scn_fail_tok(c, "unknown time unit",
                     allow_ticks ? "s, ms, us, ns or ticks" : "s, ms, us or ns");
        return 0;
    }
    if (c->tok.kind == SCN_T_ID)
        scn_next(c);
    v = scaled(c, &num, shift);
    if (!(v - v == 0) || (is_ticks && !(v >= 1 && v <= 4e9 && v == (double)(uint32_t)v)))
        scn_fail(c, num.pos, scn_near(c, &num), is_ticks ? "bad tick count" : "time out of range",
                 is_ticks ? "a whole number of ticks from 1" : "a finite time");
    if (ticks)
        *ticks = (uint8_t)is_ticks;
    scn_expect_op(c, ")");
    return v;
}

static int interp_of(scn_ctx *c, scn_name n)
{
    for (int i = RT_INTERP_HOLD; i < RT_INTERP_COUNT; i++)
        if (strcmp(scn_interp_key[i], n.s) == 0)
            return i;
    scn_fail(c, n.pos, n.s, "unknown interpolation",
             scn_list(c, scn_interp_key + RT_INTERP_HOLD, RT_INTERP_COUNT - RT_INTERP_HOLD, 8));
    return 0;
}

/* a second clause of the same kind in one statement */
static int once(scn_ctx *c, uint8_t *seen)
{
    if (*seen) {
        scn_fail_tok(c, "clause given twice", "each clause at most once per statement");
        return 0;
    }
    *seen = 1;
    return 1;
}

/* ------------------------------------------------------------------ statements */

/* scene (name) [doc ("text")]; */
static void st_scene(scn_ctx *c, scn_pos at)
{
    scn_scene *s = &c->sc;
    if (s->has_name) {
        scn_fail(c, at, "scene", "second scene statement", "one scene statement per scene");
        return;
    }
    s->name = paren_name(c, "the scene name");
    s->has_name = 1;
    if (scn_is_word(c, "doc")) {
        scn_next(c);
        s->doc = paren_string(c, "the description as a string");
    }
    scn_expect_op(c, ";");
}

/* base tick (time); */
static void st_base(scn_ctx *c, scn_pos at)
{
    scn_scene *s = &c->sc;
    scn_expect_word(c, "tick");
    if (!c->err && s->has_dt) {
        scn_fail(c, at, "base", "base tick given twice", "one base tick per scene");
        return;
    }
    s->dt = paren_time(c, 0, NULL, &s->dt_pos);
    if (!c->err && !(s->dt > 0))
        scn_fail(c, s->dt_pos, "0", "base tick must be positive", "a time above 0 s");
    s->has_dt = 1;
    scn_expect_op(c, ";");
}

/* end time (time); */
static void st_end(scn_ctx *c, scn_pos at)
{
    scn_scene *s = &c->sc;
    scn_expect_word(c, "time");
    if (!c->err && s->has_end) {
        scn_fail(c, at, "end", "end time given twice", "one end time per scene");
        return;
    }
    s->t_end = paren_time(c, 0, NULL, &s->end_pos);
    s->has_end = 1;
    scn_expect_op(c, ";");
}

/* include "file"; -- reading goes on in the file, then after the ';' */
static void st_include(scn_ctx *c, scn_pos at)
{
    (void)at;
    scn_pos pos = c->tok.pos;
    if (c->tok.kind != SCN_T_STR) {
        scn_fail_tok(c, "syntax error", "the file name as a string: include \"file\";");
        return;
    }
    const char *name = c->tok.s;
    scn_next(c);
    if (!scn_is_op(c, ";")) {
        scn_fail_tok(c, "syntax error", "';'");
        return;
    }
    scn_push_include(c, name, pos);
}

/* ( name [= const] {, ...} ) of a define */
static uint16_t var_list(scn_ctx *c, scn_var *v, int with_init, const char *what)
{
    uint16_t n = 0;
    scn_expect_op(c, "(");
    while (!c->err && !scn_is_op(c, ")")) {
        scn_name nm = scn_expect_name(c, what);
        if (!c->err && n >= SCN_MAX_PORTS)
            scn_fail(c, nm.pos, nm.s, "too many names in the list",
                     scn_fmt(c, "at most %u", SCN_MAX_PORTS));
        if (c->err)
            break;
        v[n].name = nm, v[n].init = 0;
        if (scn_is_op(c, "=") && !with_init)
            scn_fail_tok(c, "a default value is not allowed here",
                         "defaults only for parameters and states");
        if (scn_accept_op(c, "="))
            v[n].init = scn_const_expr(c);
        n++;
        if (!scn_accept_op(c, ","))
            break;
    }
    scn_expect_op(c, ")");
    return n;
}

/* names of a define are unique and not t, h or pi */
static void define_names(scn_ctx *c, scn_define *d)
{
    const scn_var *lists[4] = {d->u, d->y, d->p, d->x};
    uint16_t ns[4] = {d->nu, d->ny, d->np, d->nx};
    for (int a = 0; a < 4 && !c->err; a++)
        for (uint16_t i = 0; i < ns[a] && !c->err; i++) {
            const scn_name *n = &lists[a][i].name;
            if (!strcmp(n->s, "t") || !strcmp(n->s, "h") || !strcmp(n->s, "pi"))
                scn_fail(c, n->pos, n->s, "reserved name", "a name other than t, h and pi");
            for (int b = 0; b <= a && !c->err; b++)
                for (uint16_t j = 0; j < (b == a ? i : ns[b]) && !c->err; j++)
                    if (!strcmp(lists[b][j].name.s, n->s))
                        scn_fail(c, n->pos, n->s, "duplicate name in the define",
                                 "names unique among inputs, outputs, parameters and states");
        }
}

/* with inputs (...) outputs (...) parameters (...) states (...) period (...) */
/* one invariant: nonnegative (names) | sum (names) = c | norm (names) <= c,
   then within (tol) */
static void inv_item(scn_ctx *c, scn_inv *v)
{
    static const char *const kinds[] = {"nonnegative", "sum", "norm"};
    scn_var names[SCN_MAX_PORTS];
    int k = 0;
    while (k < 3 && !scn_is_word(c, kinds[k]))
        k++;
    if (k == 3) {
        scn_fail_tok(c, "syntax error", "nonnegative (...), sum (...) = c or norm (...) <= c");
        return;
    }
    scn_next(c);
    uint16_t n = var_list(c, names, 0, "a state name");
    if (!c->err && (n == 0 || n > SCN_MAX_INV_N))
        scn_fail_tok(c, "an invariant reads 1 to 16 states", "a shorter list of states");
    for (uint16_t i = 0; i < n && !c->err; i++)
        v->x[i] = names[i].name;
    v->type = (uint8_t)k, v->n = (uint8_t)n, v->c = 0, v->tol = 0;
    if (k == RT_INV_SUM)
        scn_expect_op(c, "="), v->c = scn_const_expr(c);
    if (k == RT_INV_NORM)
        scn_expect_op(c, "<="), v->c = scn_const_expr(c);
    if (!c->err && scn_is_word(c, "within"))
        scn_next(c), v->tol = paren_const(c);
}

/* invariants (item, item, ...): what the states keep (rt/invariant.c) */
static void inv_list(scn_ctx *c, scn_define *d)
{
    scn_expect_op(c, "(");
    while (!c->err) {
        if (d->ninv >= SCN_MAX_INV) {
            scn_fail_tok(c, "too many invariants", scn_fmt(c, "at most %u", SCN_MAX_INV));
            return;
        }
        inv_item(c, &d->inv[d->ninv++]);
        if (!scn_accept_op(c, ","))
            break;
    }
    scn_expect_op(c, ")");
}

static void define_clauses(scn_ctx *c, scn_define *d)
{
    uint8_t seen[5] = {0};
    if (scn_is_word(c, "with"))
        scn_next(c);
    while (!c->err && !scn_is_word(c, "by")) {
        if (scn_is_word(c, "inputs") && once(c, &seen[0]))
            scn_next(c), d->nu = var_list(c, d->u, 0, "an input name");
        else if (scn_is_word(c, "outputs") && once(c, &seen[1]))
            scn_next(c), d->ny = var_list(c, d->y, 0, "an output name");
        else if (scn_is_word(c, "parameters") && once(c, &seen[2]))
            scn_next(c), d->np = var_list(c, d->p, 1, "a parameter name");
        else if (scn_is_word(c, "states") && once(c, &seen[3]))
            scn_next(c), d->nx = var_list(c, d->x, 1, "a state name");
        else if (scn_is_word(c, "period") && d->type == SCN_DEF_DSS && once(c, &seen[4])) {
            scn_next(c);
            d->period = paren_time(c, 0, NULL, &d->period_pos);
            if (!c->err && !(d->period > 0)) /* 0 would read as "no period given" */
                scn_fail(c, d->period_pos, scn_fmt(c, "%g s", d->period),
                         "sample period must be positive", "a time above 0 s");
        } else if (scn_is_word(c, "invariants") && d->type == SCN_DEF_SS && !d->ninv) {
            scn_next(c);
            inv_list(c, d);
        } else if (!c->err)
            scn_fail_tok(c, "syntax error",
                         d->type == SCN_DEF_DSS
                             ? "inputs, outputs, parameters, states, period (...) or by { ... }"
                             : "inputs, outputs, parameters, states, invariants (...) or by { ... }");
    }
    if (!c->err && d->type == SCN_DEF_LSS && d->np > 0)
        scn_fail(c, d->p[0].name.pos, d->p[0].name.s, "an lss_system has no parameters",
                 "the matrices A, B, C, D with constant entries");
    define_names(c, d);
}

/* { A = [...]; B = [...]; C = [...]; D = [...]; } of an lss_system */
static void lss_body(scn_ctx *c, scn_define *d)
{
    scn_matrix *m[4] = {&d->A, &d->B, &d->C, &d->D};
    scn_expect_op(c, "{");
    while (!c->err && !scn_is_op(c, "}")) {
        int i = -1;
        if (c->tok.kind == SCN_T_ID && strlen(c->tok.s) == 1 && c->tok.s[0] >= 'A' &&
            c->tok.s[0] <= 'D')
            i = c->tok.s[0] - 'A';
        if (i < 0) {
            scn_fail_tok(c, "syntax error", "A = [...]; B = [...]; C = [...]; D = [...]; or '}'");
            return;
        }
        if (m[i]->given) {
            scn_fail_tok(c, "matrix given twice", "each of A, B, C, D at most once");
            return;
        }
        scn_next(c);
        scn_expect_op(c, "=");
        scn_parse_matrix(c, m[i]);
        scn_expect_op(c, ";");
    }
    scn_expect_op(c, "}");
}

/* define ss_system|lss_system|dss_system (Name) [with] clauses by { body } [;] */
static void st_define(scn_ctx *c, scn_pos at)
{
    static const char *const types[] = {"ss_system", "lss_system", "dss_system"};
    scn_scene *s = &c->sc;
    int type = -1;
    for (int i = 0; i < 3; i++)
        if (scn_is_word(c, types[i]))
            type = i;
    if (type < 0) {
        scn_fail_tok(c, "syntax error", "ss_system, lss_system or dss_system after define");
        return;
    }
    if (s->ndef >= SCN_MAX_DEFINES) {
        scn_fail(c, at, "define", "too many defines",
                 scn_fmt(c, "at most %u per scene", SCN_MAX_DEFINES));
        return;
    }
    scn_next(c);
    scn_define *d = s->def[s->ndef] = scn_alloc(c, sizeof *d);
    d->type = (uint8_t)type;
    d->name = paren_name(c, "the name of the defined system");
    define_clauses(c, d);
    scn_expect_word(c, "by");
    if (type == SCN_DEF_LSS)
        lss_body(c, d);
    else
        scn_parse_body(c, d);
    scn_accept_op(c, ";");
    if (!c->err)
        s->ndef++;
}

static int is_statement_word(const char *w);

/* a block or joint name not used before, and not a word that begins a statement */
static int fresh_name(scn_ctx *c, scn_name n)
{
    const scn_scene *s = &c->sc;
    const scn_name *old = NULL;
    if (is_statement_word(n.s)) {
        scn_fail(c, n.pos, n.s, "reserved word",
                 "a name that does not begin a statement (Block.name = ... would not parse)");
        return 0;
    }
    for (uint16_t i = 0; i < s->nblk && !old; i++)
        if (!strcmp(s->blk[i].name.s, n.s))
            old = &s->blk[i].name;
    for (uint16_t i = 0; i < s->njnt && !old; i++)
        if (!strcmp(s->jnt[i].name.s, n.s))
            old = &s->jnt[i].name;
    if (old)
        scn_fail(c, n.pos, n.s, "duplicate name",
                 scn_fmt(c, "a name not used by another system or joint (first at %s:%u:%u)",
                         scn_path(c, old->pos), (unsigned)old->pos.line, (unsigned)old->pos.col));
    return !old;
}

/* load system (N, ...) of type (T) [from file ("unit")] [period (time)];
   load joint (N, ...) of type (T) [from file ("unit")]; */
static void st_load(scn_ctx *c, scn_pos at)
{
    scn_scene *s = &c->sc;
    scn_name names[RT_MAX_BLOCKS];
    int joint = scn_is_word(c, "joint");
    (void)at;
    if (!joint && !scn_is_word(c, "system")) {
        scn_fail_tok(c, "syntax error", "system or joint after load");
        return;
    }
    scn_next(c);
    uint16_t n = name_list(c, names, RT_MAX_BLOCKS, joint ? "a joint name" : "a system name");
    scn_expect_word(c, "of");
    scn_expect_word(c, "type");
    scn_name type = paren_name(c, joint ? "a joint type" : "a system type");
    const char *unit = NULL;
    double ts = 0;
    scn_pos ts_pos = {0, 0, 0};
    if (scn_is_word(c, "from")) {
        scn_next(c);
        scn_expect_word(c, "file");
        unit = paren_string(c, "the unit as a string: from file (\"unit\")");
    }
    if (!joint && scn_is_word(c, "period")) {
        scn_next(c);
        ts = paren_time(c, 0, NULL, &ts_pos);
        if (!c->err && !(ts > 0))
            scn_fail(c, ts_pos, "0", "sample period must be positive", "a time above 0 s");
    }
    scn_expect_op(c, ";");
    for (uint16_t i = 0; i < n && !c->err; i++) {
        if (!fresh_name(c, names[i]))
            return;
        if ((joint ? s->njnt >= RT_MAX_JOINTS : s->nblk >= RT_MAX_BLOCKS)) {
            scn_fail(c, names[i].pos, names[i].s, joint ? "too many joints" : "too many systems",
                     scn_limit(c, joint ? RT_LIM_JOINTS : RT_LIM_BLOCKS));
            return;
        }
        if (joint) {
            scn_joint *j = &s->jnt[s->njnt++];
            j->name = names[i], j->type = type, j->unit = unit, j->link = -1;
        } else {
            scn_block *b = &s->blk[s->nblk++];
            b->name = names[i], b->type = type, b->unit = unit;
            b->ts = ts, b->ts_pos = ts_pos, b->def = -1, b->set = -1;
        }
    }
}

/* connect(A.y, B.u) [interpolation (scheme)]; */
static void st_connect(scn_ctx *c, scn_pos at)
{
    scn_scene *s = &c->sc;
    scn_conn cn;
    memset(&cn, 0, sizeof cn);
    scn_expect_op(c, "(");
    cn.from = ref(c, "an output as Block.output");
    scn_expect_op(c, ",");
    cn.to = ref(c, "an input as Block.input");
    scn_expect_op(c, ")");
    if (scn_is_word(c, "interpolation")) {
        scn_next(c);
        cn.interp = (uint8_t)interp_of(c, paren_name(c, "an interpolation scheme"));
    }
    scn_expect_op(c, ";");
    if (!c->err && s->nconn >= RT_MAX_U)
        scn_fail(c, at, "connect", "too many connections",
                 scn_limit(c, RT_LIM_U));
    if (!c->err)
        s->conn[s->nconn++] = cn;
}

/* ( x, y, z ) of constants */
static void paren_vec3(scn_ctx *c, double *v)
{
    scn_expect_op(c, "(");
    for (int i = 0; i < 3 && !c->err; i++) {
        v[i] = scn_const_expr(c);
        if (i < 2)
            scn_expect_op(c, ",");
    }
    scn_expect_op(c, ")");
}

/* the anchor's orientation by axis and angle: rotated (angle deg|rad about (x, y, z)) */
static void anchor_turn(scn_ctx *c, scn_link *l)
{
    l->turn_pos = c->tok.pos, l->has_turn = 1;
    scn_next(c);
    scn_expect_op(c, "(");
    double a = scn_const_expr(c);
    if (scn_is_word(c, "deg"))
        a *= 3.14159265358979323846 / 180;
    else if (!scn_is_word(c, "rad") && !c->err) {
        scn_fail_tok(c, "angle without its unit", "deg or rad");
        return;
    }
    scn_next(c);
    scn_expect_word(c, "about");
    l->turn[0] = a;
    paren_vec3(c, l->turn + 1);
    scn_expect_op(c, ")");
}

/* link(A.node, B.node | ground [at (x, y, z)] [rotated (angle deg about (x, y, z))])
   by (Joint); */
static void st_link(scn_ctx *c, scn_pos at)
{
    scn_scene *s = &c->sc;
    scn_link l;
    memset(&l, 0, sizeof l);
    scn_expect_op(c, "(");
    l.a = ref(c, "a node as Block.node");
    scn_expect_op(c, ",");
    if (scn_is_word(c, "ground")) {
        l.b.block.s = "ground", l.b.block.pos = c->tok.pos, l.ground = 1;
        scn_next(c);
        if (scn_is_word(c, "at")) {
            scn_next(c);
            scn_expect_op(c, "(");
            for (int i = 0; i < 3 && !c->err; i++) {
                l.at[i] = scn_const_expr(c);
                if (i < 2)
                    scn_expect_op(c, ",");
            }
            scn_expect_op(c, ")");
            l.has_at = 1;
        }
        if (scn_is_word(c, "rotated")) /* rotated (angle deg|rad about (x, y, z)) */
            anchor_turn(c, &l);
    } else {
        l.b = ref(c, "a node as Block.node, or ground");
    }
    scn_expect_op(c, ")");
    scn_expect_word(c, "by");
    l.joint = paren_name(c, "a joint name");
    scn_expect_op(c, ";");
    if (!c->err && s->nlnk >= RT_MAX_JOINTS)
        scn_fail(c, at, "link", "too many links", scn_limit(c, RT_LIM_JOINTS));
    if (!c->err)
        s->lnk[s->nlnk++] = l;
}

/* the setting (RT_SET_CFG_LIST) whose clause the current word is, or -1 */
static int setting_of(scn_ctx *c)
{
    for (int id = 0; id < RT_CFG_N; id++)
        if (rt_set_opts[id].kind != RT_CFG_PAIR && scn_is_word(c, rt_set_opts[id].word))
            return id;
    return -1;
}

/* a setting's value: an explicit 0 is no default, so it is kept as NaN for the check to
   name (rt_set_check) */
static void put_setting(scn_ctx *c, scn_set *st, int id, double v)
{
    rt_set_cfg_put(&st->cfg, (rt_cfg_id)id, v == 0 ? (real_t)NAN : (real_t)v);
    st->has_cfg[id] = 1;
    (void)c;
}

/* newton (n), tolerance (e), accuracy (rtol [, atol]), ...: a count or a constant, and
   the optional second value of the row after it (RT_CFG_PAIR) */
static void setting(scn_ctx *c, scn_set *st, int id)
{
    const rt_set_opt *o = &rt_set_opts[id];
    st->cfg_pos[id] = c->tok.pos;
    scn_next(c);
    if (o->kind == RT_CFG_COUNT || o->kind == RT_CFG_POW2) {
        put_setting(c, st, id, paren_count(c, o->max));
        return;
    }
    scn_expect_op(c, "(");
    put_setting(c, st, id, scn_const_expr(c));
    if (!c->err && id + 1 < RT_CFG_N && rt_set_opts[id + 1].kind == RT_CFG_PAIR &&
        scn_is_op(c, ",")) {
        scn_next(c), st->cfg_pos[id + 1] = c->tok.pos;
        put_setting(c, st, id + 1, scn_const_expr(c));
    }
    scn_expect_op(c, ")");
}

/* one clause of a set statement */
static void set_clause(scn_ctx *c, scn_set *st, uint8_t *seen)
{
    scn_scene *s = &c->sc;
    int id;
    if (scn_is_word(c, "method") && once(c, &seen[0])) {
        scn_next(c), st->method = paren_name(c, "an integration method");
    } else if (scn_is_word(c, "step") && once(c, &seen[1])) {
        scn_next(c);
        st->step = paren_time(c, 1, &st->step_ticks, &st->step_pos), st->has_step = 1;
    } else if (scn_is_word(c, "interpolation") && once(c, &seen[2])) {
        scn_next(c), st->interp = (uint8_t)interp_of(c, paren_name(c, "an interpolation scheme"));
    } else if (scn_is_word(c, "members") && once(c, &seen[3])) {
        scn_next(c);
        st->m0 = s->nmembers;
        s->nmembers += name_list(c, s->members + s->nmembers,
                                 (uint16_t)(SCN_MAX_MEMBERS - s->nmembers), "a system name");
        st->m1 = s->nmembers, st->has_members = 1;
    } else if (scn_is_word(c, "background") && once(c, &seen[4])) {
        scn_next(c), st->background = 1; /* no argument: steps below the tick (rt/bg.c) */
    } else if ((id = setting_of(c)) >= 0 && once(c, &seen[5 + id])) {
        setting(c, st, id);
    } else if (!c->err) {
        char words[160] = "method, step, interpolation, members, background";
        for (int k = 0; k < RT_CFG_N; k++)
            if (rt_set_opts[k].kind != RT_CFG_PAIR)
                snprintf(words + strlen(words), sizeof words - strlen(words), ", %s",
                         rt_set_opts[k].word);
        scn_fail_tok(c, "syntax error", scn_fmt(c, "%s or ';'", words));
    }
}

/* set (name) method (m) step (time|ticks) [interpolation (i)] [members (...)] ...; */
static void st_set(scn_ctx *c, scn_pos at)
{
    scn_scene *s = &c->sc;
    uint8_t seen[5 + RT_CFG_N] = {0};
    if (s->nset >= RT_MAX_SETS) {
        scn_fail(c, at, "set", "too many sets", scn_limit(c, RT_LIM_SETS));
        return;
    }
    scn_set *st = &s->set[s->nset];
    memset(st, 0, sizeof *st);
    st->name = paren_name(c, "the set name");
    while (!c->err && !scn_is_op(c, ";"))
        set_clause(c, st, seen);
    scn_expect_op(c, ";");
    if (!c->err)
        s->nset++;
}

/* [output|state|discrete] Block.signal (a qualifier only where `qualified`) */
static scn_rec signal_ref(scn_ctx *c, int qualified)
{
    static const char *const quals[] = {"output", "state", "discrete"};
    scn_rec r;
    memset(&r, 0, sizeof r);
    r.want = -1;
    r.sig.block = scn_expect_name(c, "a signal as Block.signal");
    for (int q = 0; qualified && q < 3 && !c->err && !scn_is_op(c, "."); q++)
        if (!strcmp(r.sig.block.s, quals[q])) {
            r.want = (int8_t)q; /* RT_SIG_Y, RT_SIG_X, RT_SIG_D in this order */
            r.sig.block = scn_expect_name(c, "a signal as Block.signal");
        }
    scn_expect_op(c, ".");
    r.sig.port = scn_expect_name(c, "a signal name");
    return r;
}

/* record ([output|state|discrete] Block.signal, ...); */
static void st_record(scn_ctx *c, scn_pos at)
{
    scn_scene *s = &c->sc;
    (void)at;
    scn_expect_op(c, "(");
    do {
        scn_rec r = signal_ref(c, 1);
        if (!c->err && s->nrec >= SCN_MAX_RECS)
            scn_fail(c, r.sig.block.pos, r.sig.block.s, "too many recorded signals",
                     scn_limit(c, RT_LIM_REC));
        if (!c->err)
            s->rec[s->nrec++] = r;
    } while (!c->err && scn_accept_op(c, ","));
    scn_expect_op(c, ")");
    scn_expect_op(c, ";");
}

/* ------------------------------------------------------------------ controller link */

/* (C): the controller's name; both statements must name the same one */
static void controller(scn_ctx *c, scn_name *slot, const char *word, const char *stmt)
{
    scn_expect_word(c, word);
    scn_name n = paren_name(c, "the controller's name");
    if (!c->err && slot->s)
        scn_fail(c, n.pos, n.s, scn_fmt(c, "a second %s statement", stmt),
                 "one export and one import statement per scene (one controller)");
    *slot = n;
}

/* export (Block.signal, ...) to (C); */
static void st_export(scn_ctx *c, scn_pos at)
{
    scn_scene *s = &c->sc;
    (void)at;
    scn_expect_op(c, "(");
    do {
        scn_rec r = signal_ref(c, 0);
        if (!c->err && s->nlexp >= SCN_MAX_RECS)
            scn_fail(c, r.sig.block.pos, r.sig.block.s, "too many exported signals",
                     scn_fmt(c, "at most %u", SCN_MAX_RECS));
        if (!c->err)
            s->lexp[s->nlexp++] = r;
    } while (!c->err && scn_accept_op(c, ","));
    scn_expect_op(c, ")");
    controller(c, &s->ctl_exp, "to", "export");
    scn_expect_op(c, ";");
}

/* name [= constant] [hold|default|stop] */
static void import_item(scn_ctx *c, scn_scene *s)
{
    scn_name n = scn_expect_name(c, "an imported signal's name");
    if (!c->err && s->nlimp >= SCN_MAX_PORTS)
        scn_fail(c, n.pos, n.s, "too many imported signals", scn_fmt(c, "at most %u", SCN_MAX_PORTS));
    if (c->err)
        return;
    scn_var *v = &s->limp[s->nlimp];
    v->name = n, v->init = 0;
    if (scn_accept_op(c, "="))
        v->init = scn_const_expr(c);
    s->lpol[s->nlimp] = RT_LINK_HOLD;
    if (c->tok.kind == SCN_T_ID && rt_link_policy_find(c->tok.s) >= 0) {
        s->lpol[s->nlimp] = (uint8_t)rt_link_policy_find(c->tok.s);
        scn_next(c);
    }
    s->nlimp++;
}

/* the define and the load an import stands for: a DSS block named after the controller,
   one held discrete state and output per import (rt_link_apply writes both) */
static void import_expand(scn_ctx *c, scn_scene *s, scn_pos at)
{
    const char *C = s->ctl_imp.s;
    char *out = scn_fmt(c, "define dss_system (%s__import) with outputs (", C);
    for (uint16_t i = 0; i < s->nlimp; i++)
        out = scn_fmt(c, "%s%s%s", out, i ? ", " : "", s->limp[i].name.s);
    out = scn_fmt(c, "%s) states (", out);
    for (uint16_t i = 0; i < s->nlimp; i++)
        out = scn_fmt(c, "%s%s%s__in = %.17g", out, i ? ", " : "", s->limp[i].name.s,
                      s->limp[i].init);
    out = scn_fmt(c, "%s) period (%.17g s) by {", out, s->lperiod);
    for (uint16_t i = 0; i < s->nlimp; i++)
        out = scn_fmt(c, "%s %s = %s__in; next(%s__in) = %s__in;", out, s->limp[i].name.s,
                      s->limp[i].name.s, s->limp[i].name.s, s->limp[i].name.s);
    out = scn_fmt(c, "%s };\nload system (%s) of type (%s__import);\n", out, C, C);
    scn_push_text(c, scn_fmt(c, "<import from %s>", C), out, at);
}

/* import (name [= v] [hold|default|stop], ...) from (C) [every (time)]; */
static void st_import(scn_ctx *c, scn_pos at)
{
    scn_scene *s = &c->sc;
    scn_expect_op(c, "(");
    do
        import_item(c, s);
    while (!c->err && scn_accept_op(c, ","));
    scn_expect_op(c, ")");
    controller(c, &s->ctl_imp, "from", "import");
    scn_pos every = at;
    s->lperiod = s->dt;
    if (!c->err && scn_is_word(c, "every")) {
        scn_next(c);
        s->lperiod = paren_time(c, 0, NULL, &every);
    }
    /* r is range-checked before it is rounded: a cast of a double out of range is undefined */
    double r = s->dt > 0 ? s->lperiod / s->dt : 0;
    double n = r >= 0.5 && r < 4e9 ? (double)(uint32_t)(r + 0.5) : 0;
    if (!c->err && !(s->lperiod > 0 && s->dt > 0))
        scn_fail(c, at, "import", "no exchange period",
                 "base tick (...) before the import, and every (<time>) if not every tick");
    else if (!c->err && !(n >= 1 && (n - r) * (n - r) <= RT_TICK_MATCH_REL * RT_TICK_MATCH_REL * r * r))
        scn_fail(c, every, scn_fmt(c, "%g s", s->lperiod),
                 "exchange period is not a whole number of base ticks",
                 scn_fmt(c, "a multiple of %g s", s->dt));
    if (!c->err && !scn_is_op(c, ";"))
        scn_fail_tok(c, "syntax error", "every (<time>) or ';'");
    if (!c->err)
        import_expand(c, s, at);
}

/* solve loops by (broyden) [iterations (n)] [tolerance (v)]; */
static void st_solve(scn_ctx *c, scn_pos at)
{
    scn_scene *s = &c->sc;
    uint8_t seen[2] = {0};
    if (s->solver.s) {
        scn_fail(c, at, "solve", "loop solver given twice", "one solve statement per scene");
        return;
    }
    scn_expect_word(c, "loops");
    scn_expect_word(c, "by");
    s->solver = paren_name(c, "a loop solver (broyden)");
    while (!c->err && !scn_is_op(c, ";")) {
        if (scn_is_word(c, "iterations") && once(c, &seen[0]))
            scn_next(c), s->loop_iter = paren_count(c, RT_LOOP_ITER_LIMIT);
        else if (scn_is_word(c, "tolerance") && once(c, &seen[1]))
            scn_next(c), s->loop_tol = paren_const(c);
        else if (!c->err)
            scn_fail_tok(c, "syntax error", "iterations (...), tolerance (...) or ';'");
    }
    scn_expect_op(c, ";");
}

/* stabilization (project|none|baumgarte) [alpha (v)] [beta (v)]; */
static void st_stab(scn_ctx *c, scn_pos at)
{
    scn_scene *s = &c->sc;
    uint8_t seen[2] = {0};
    if (s->stab.s) {
        scn_fail(c, at, "stabilization", "stabilization given twice", "one per scene");
        return;
    }
    s->stab = paren_name(c, "project, none or baumgarte");
    while (!c->err && !scn_is_op(c, ";")) {
        if (scn_is_word(c, "alpha") && once(c, &seen[0]))
            scn_next(c), s->alpha = paren_const(c);
        else if (scn_is_word(c, "beta") && once(c, &seen[1]))
            scn_next(c), s->beta = paren_const(c);
        else if (!c->err)
            scn_fail_tok(c, "syntax error", "alpha (...), beta (...) or ';'");
    }
    scn_expect_op(c, ";");
}

/* Block.name = constant;  Joint.axis = (x, y, z); */
static void st_assign(scn_ctx *c)
{
    scn_scene *s = &c->sc;
    scn_assign a;
    memset(&a, 0, sizeof a);
    a.lhs = ref(c, "a statement or Block.name = value;");
    scn_expect_op(c, "=");
    if (!c->err && !strcmp(a.lhs.port.s, "axis") && scn_is_op(c, "("))
        paren_vec3(c, a.vec), a.is_vec = 1; /* a direction, checked with the joint */
    else
        a.v = scn_const_expr(c);
    scn_expect_op(c, ";");
    if (!c->err && s->nasg >= SCN_MAX_ASSIGN)
        scn_fail(c, a.lhs.block.pos, a.lhs.block.s, "too many assignments",
                 scn_fmt(c, "at most %u", SCN_MAX_ASSIGN));
    if (!c->err)
        s->asg[s->nasg++] = a;
}

typedef struct stmt_entry {
    const char *word;
    void (*fn)(scn_ctx *c, scn_pos at);
} stmt_entry;

static const stmt_entry stmts[] = {
    {"scene", st_scene},     {"base", st_base},       {"end", st_end},
    {"include", st_include}, {"define", st_define},   {"load", st_load},
    {"connect", st_connect}, {"link", st_link},       {"set", st_set},
    {"record", st_record},   {"solve", st_solve},     {"stabilization", st_stab},
    {"export", st_export},   {"import", st_import},
    {0, 0},
};

static int is_statement_word(const char *w)
{
    for (const stmt_entry *e = stmts; e->word; e++)
        if (!strcmp(e->word, w))
            return 1;
    return 0;
}

static void statement(scn_ctx *c)
{
    if (c->tok.kind == SCN_T_ID) {
        scn_pos at = c->tok.pos;
        for (const stmt_entry *e = stmts; e->word; e++)
            if (scn_is_word(c, e->word)) {
                scn_next(c);
                e->fn(c, at);
                return;
            }
        st_assign(c);
        return;
    }
    scn_fail_tok(c, "syntax error", "a statement: scene, base tick, end time, include, define, "
                                    "load, connect, link, set, record, solve, stabilization, "
                                    "export, import or "
                                    "Block.name = value;");
}

int scn_parse(scn_ctx *c)
{
    while (!c->err) {
        if (c->tok.kind == SCN_T_EOF) {
            if (c->depth == 0)
                break;
            scn_pop_include(c);
            continue;
        }
        statement(c);
    }
    return c->err ? -1 : 0;
}
