/* expr.c - expressions of the scene language: constant expressions (evaluated in double
 * while parsing), define bodies compiled to the bytecode of vm.c, and LSS matrices.
 * Also the token tests every parser uses.
 *
 * Body expressions keep the order they are written in: a + b + c is (a + b) + c, and
 * emit.c prints the same tree fully parenthesized, so the VM and the generated C do the
 * same operations in the same order (the build uses -ffp-contract=off). */
#include "scn.h"

#include "rt_expr.h"

#include <string.h>

const scn_fn scn_fns[] = {
    {"sqrt", 1, rt_sqrt, 0, "rt_sqrt"},     {"sin", 1, rt_sin, 0, "rt_sin"},
    {"cos", 1, rt_cos, 0, "rt_cos"},        {"tan", 1, rt_tan, 0, "rt_tan"},
    {"asin", 1, rt_asin, 0, "rt_asin"},     {"acos", 1, rt_acos, 0, "rt_acos"},
    {"atan", 1, rt_atan, 0, "rt_atan"},     {"atan2", 2, 0, rt_atan2, "rt_atan2"},
    {"exp", 1, rt_exp, 0, "rt_exp"},        {"log", 1, rt_log, 0, "rt_log"},
    {"pow", 2, 0, rt_pow, "rt_pow"},        {"tanh", 1, rt_tanh, 0, "rt_tanh"},
    {"abs", 1, rt_fabs, 0, "rt_fabs"},      {"floor", 1, rt_floor, 0, "rt_floor"},
    {"min", 2, 0, rt_x_min, "rt_x_min"},    {"max", 2, 0, rt_x_max, "rt_x_max"},
    /* a switch's root for <, <=, > and >= (finish_switches): no name a scene can write */
    {"#swlt", 2, 0, rt_x_swlt, "rt_x_swlt"}, {"#swle", 2, 0, rt_x_swle, "rt_x_swle"},
    {"#swgt", 2, 0, rt_x_swgt, "rt_x_swgt"}, {"#swge", 2, 0, rt_x_swge, "rt_x_swge"},
    /* the time to a floor's next jump (floor_time, flush_tev) */
    {"#floor_next", 2, 0, rt_x_floor_next, "rt_x_floor_next"},
    {"#floor_snap", 2, 0, rt_x_floor_snap, "rt_x_floor_snap"},
    {0, 0, 0, 0, 0},
};

/* ------------------------------------------------------------------ tokens */

int scn_is_op(const scn_ctx *c, const char *op)
{
    return c->tok.kind == SCN_T_OP && strcmp(c->tok.op, op) == 0;
}

int scn_is_word(const scn_ctx *c, const char *w)
{
    return c->tok.kind == SCN_T_ID && strcmp(c->tok.s, w) == 0;
}

int scn_accept_op(scn_ctx *c, const char *op)
{
    if (!scn_is_op(c, op))
        return 0;
    scn_next(c);
    return 1;
}

void scn_expect_op(scn_ctx *c, const char *op)
{
    if (!scn_accept_op(c, op))
        scn_fail_tok(c, "syntax error", scn_fmt(c, "'%s'", op));
}

void scn_expect_word(scn_ctx *c, const char *w)
{
    if (scn_is_word(c, w))
        scn_next(c);
    else
        scn_fail_tok(c, "syntax error", scn_fmt(c, "'%s'", w));
}

scn_name scn_expect_name(scn_ctx *c, const char *what)
{
    scn_name n = {"", c->tok.pos};
    if (c->tok.kind != SCN_T_ID) {
        scn_fail_tok(c, "syntax error", what);
        return n;
    }
    n.s = c->tok.s;
    scn_next(c);
    return n;
}

/* nesting guard of the recursive descent, taken at each parenthesis, call, prefix
   operator, power and conditional: 0 when too deep (and the error is set); the caller
   that got 1 decrements c->edepth when it returns */
static int enter(scn_ctx *c)
{
    if (++c->edepth <= SCN_MAX_EXPR_DEPTH)
        return 1;
    c->edepth--;
    scn_fail_tok(c, "expression nested too deeply",
                 scn_fmt(c, "at most %u nested parentheses, calls and operators",
                         SCN_MAX_EXPR_DEPTH));
    return 0;
}

/* ------------------------------------------------------------------ constants */

static double c_sum(scn_ctx *c);

static const scn_fn *find_fn(const char *name)
{
    for (const scn_fn *f = scn_fns; f->name; f++)
        if (strcmp(f->name, name) == 0)
            return f;
    return 0;
}

/* fn(a) or fn(a, b) with constant arguments, evaluated by the same rt_ function the VM
   and the generated C call, so a constant means the same everywhere */
static double c_call(scn_ctx *c, const scn_fn *f)
{
    double a[2] = {0, 0};
    scn_next(c);
    scn_expect_op(c, "(");
    for (int i = 0; i < f->nargs && !c->err; i++) {
        if (i)
            scn_expect_op(c, ",");
        a[i] = c_sum(c);
    }
    scn_expect_op(c, ")");
    return f->nargs == 1 ? (double)f->f1((real_t)a[0]) : (double)f->f2((real_t)a[0], (real_t)a[1]);
}

static double c_primary(scn_ctx *c)
{
    double v = 0;
    const scn_fn *f = c->tok.kind == SCN_T_ID ? find_fn(c->tok.s) : 0;
    if (f && enter(c)) {
        v = c_call(c, f);
        c->edepth--;
    } else if (c->tok.kind == SCN_T_NUM) {
        v = c->tok.num;
        scn_next(c);
    } else if (scn_is_word(c, "pi")) {
        v = RT_PI;
        scn_next(c);
    } else if (scn_is_op(c, "(") && enter(c)) {
        scn_next(c);
        v = c_sum(c);
        scn_expect_op(c, ")");
        c->edepth--;
    } else if (!c->err) {
        scn_fail_tok(c, "not a constant",
                     "a number, pi, + - * /, parentheses or a function such as sin( ) (a "
                     "constant expression)");
    }
    return v;
}

static double c_unary(scn_ctx *c)
{
    double v = 0;
    int neg = scn_is_op(c, "-");
    if (!(neg || scn_is_op(c, "+")))
        return c_primary(c);
    if (!enter(c))
        return 0;
    scn_next(c);
    v = c_unary(c);
    c->edepth--;
    return neg ? -v : v;
}

static double c_product(scn_ctx *c)
{
    double v = c_unary(c);
    while (!c->err && (scn_is_op(c, "*") || scn_is_op(c, "/"))) {
        int mul = scn_is_op(c, "*");
        scn_next(c);
        double w = c_unary(c);
        v = mul ? v * w : v / w;
    }
    return v;
}

static double c_sum(scn_ctx *c)
{
    double v = c_product(c);
    while (!c->err && (scn_is_op(c, "+") || scn_is_op(c, "-"))) {
        int add = scn_is_op(c, "+");
        scn_next(c);
        double w = c_product(c);
        v = add ? v + w : v - w;
    }
    return v;
}

double scn_const_expr(scn_ctx *c)
{
    scn_tok start = c->tok;
    double v = c_sum(c);
    if (!c->err && !(v - v == 0))
        scn_fail(c, start.pos, scn_near(c, &start), "value is not finite",
                 "a constant expression with a finite value");
    return v;
}

void scn_parse_matrix(scn_ctx *c, scn_matrix *m)
{
    double v[SCN_MAX_MATRIX];
    uint32_t n = 0, cols = 0, rows = 0, in_row = 0;
    m->pos = c->tok.pos;
    scn_expect_op(c, "[");
    while (!c->err && !scn_is_op(c, "]")) {
        if (n >= SCN_MAX_MATRIX) {
            scn_fail_tok(c, "matrix too large", scn_fmt(c, "at most %u entries", SCN_MAX_MATRIX));
            return;
        }
        v[n++] = scn_const_expr(c), in_row++;
        if (scn_accept_op(c, ","))
            continue;
        if (rows > 0 && in_row != cols)
            scn_fail(c, m->pos, "[", "matrix rows of different lengths",
                     scn_fmt(c, "%u entries in every row", (unsigned)cols));
        cols = in_row, in_row = 0, rows++;
        if (!scn_accept_op(c, ";") && !scn_is_op(c, "]"))
            scn_fail_tok(c, "syntax error", "',' between entries, ';' between rows or ']'");
    }
    scn_expect_op(c, "]");
    m->rows = (uint16_t)rows, m->cols = (uint16_t)cols, m->given = 1;
    m->v = scn_alloc(c, (n ? n : 1) * sizeof(double));
    memcpy(m->v, v, n * sizeof(double));
}

/* ------------------------------------------------------------------ bytecode */

static void emit(scn_ctx *c, uint8_t op, uint16_t a, int push)
{
    scn_scene *s = &c->sc;
    if (c->err)
        return;
    if (s->ncode >= SCN_MAX_CODE) {
        scn_fail_tok(c, "define bodies too large",
                     scn_fmt(c, "at most %u operations in all bodies", SCN_MAX_CODE));
        return;
    }
    s->code[s->ncode++] = (scn_ins){op, a};
    c->sdepth = (uint32_t)((int)c->sdepth + push);
    if (c->sdepth > c->smax)
        c->smax = c->sdepth;
    if (c->sdepth > SCN_MAX_STACK)
        scn_fail_tok(c, "expression too complex",
                     scn_fmt(c, "at most %u pending operands", SCN_MAX_STACK));
}

static void emit_const(scn_ctx *c, double v)
{
    scn_scene *s = &c->sc;
    uint32_t i = 0;
    while (i < s->nk && memcmp(&s->k[i], &v, sizeof v) != 0)
        i++;
    if (i == s->nk) {
        if (s->nk >= SCN_MAX_CONST) {
            scn_fail_tok(c, "too many constants",
                         scn_fmt(c, "at most %u constants in all bodies", SCN_MAX_CONST));
            return;
        }
        s->k[s->nk++] = v;
    }
    emit(c, SCN_OP_CONST, (uint16_t)i, 1);
}

/* ------------------------------------------------------------------ body expressions */


static int find_var(const scn_var *v, uint16_t n, const char *name)
{
    for (uint16_t i = 0; i < n; i++)
        if (strcmp(v[i].name.s, name) == 0)
            return i;
    return -1;
}

static int find_local(const scn_define *d, const char *name)
{
    for (uint16_t i = 0; i < d->nloc; i++)
        if (strcmp(d->loc[i].s, name) == 0)
            return i;
    return -1;
}

static void expr(scn_ctx *c);

/* a constant index in [0, n) inside brackets */
static uint16_t index_in(scn_ctx *c, uint16_t n, const char *vec)
{
    uint16_t i = 0;
    scn_expect_op(c, "[");
    if (c->tok.kind != SCN_T_NUM || !(c->tok.num >= 0 && c->tok.num < n) ||
        c->tok.num != (double)(uint16_t)c->tok.num)
        scn_fail_tok(c, "index out of range",
                     n ? scn_fmt(c, "a whole number from 0 to %u for the %s", n - 1u, vec)
                       : scn_fmt(c, "no index: the define has no %s", vec));
    else
        i = (uint16_t)c->tok.num;
    scn_next(c);
    scn_expect_op(c, "]");
    return i;
}

static const char *names_of(scn_ctx *c, const scn_define *d)
{
    const char *all[4 * SCN_MAX_PORTS + SCN_MAX_LOCALS];
    size_t n = 0;
    for (uint16_t i = 0; i < d->nu; i++)
        all[n++] = d->u[i].name.s;
    for (uint16_t i = 0; i < d->np; i++)
        all[n++] = d->p[i].name.s;
    for (uint16_t i = 0; i < d->nx; i++)
        all[n++] = d->x[i].name.s;
    for (uint16_t i = 0; i < d->nloc; i++)
        all[n++] = d->loc[i].s;
    return scn_list(c, all, n, 12);
}

/* a name in an expression: local, input, parameter, state, t, h or pi */
static void name_ref(scn_ctx *c, scn_name n)
{
    const scn_define *d = c->def;
    uint8_t state_op = d->type == SCN_DEF_DSS ? SCN_OP_DSTATE : SCN_OP_STATE;
    int i;
    if ((i = find_local(d, n.s)) >= 0)
        emit(c, SCN_OP_LOC, (uint16_t)i, 1);
    else if ((i = find_var(d->u, d->nu, n.s)) >= 0)
        emit(c, SCN_OP_IN, (uint16_t)i, 1);
    else if ((i = find_var(d->p, d->np, n.s)) >= 0)
        emit(c, SCN_OP_PAR, (uint16_t)i, 1);
    else if ((i = find_var(d->x, d->nx, n.s)) >= 0)
        emit(c, state_op, (uint16_t)i, 1);
    else if (strcmp(n.s, "t") == 0)
        emit(c, SCN_OP_TIME, 0, 1);
    else if (strcmp(n.s, "h") == 0)
        emit(c, SCN_OP_STEP, 0, 1);
    else if (strcmp(n.s, "pi") == 0)
        emit_const(c, RT_PI);
    else if (c->when && strcmp(n.s, "t_last") == 0) /* the root's discrete t_last<k> */
        emit(c, SCN_OP_DSTATE, (uint16_t)(c->when - 1), 1);
    else if (find_var(d->y, d->ny, n.s) >= 0)
        scn_fail(c, n.pos, n.s, "an output cannot be read in a body",
                 "an input, parameter, state or let name");
    else
        scn_fail(c, n.pos, n.s, "unknown name",
                 scn_fmt(c, "t, h, pi or a name of %s (%s)", d->name.s, names_of(c, d)));
}

/* u[i], p[i], x[i] */
static int indexed_ref(scn_ctx *c, scn_name n)
{
    const scn_define *d = c->def;
    uint8_t state_op = d->type == SCN_DEF_DSS ? SCN_OP_DSTATE : SCN_OP_STATE;
    if (strcmp(n.s, "u") == 0)
        emit(c, SCN_OP_IN, index_in(c, d->nu, "inputs"), 1);
    else if (strcmp(n.s, "p") == 0)
        emit(c, SCN_OP_PAR, index_in(c, d->np, "parameters"), 1);
    else if (strcmp(n.s, "x") == 0)
        emit(c, state_op, index_in(c, d->nx, "states"), 1);
    else
        return 0;
    return 1;
}

/* what code [i0, i1) is as a function of `t` (band_arg); d: a define whose fixed lets
   (lets of constants and parameters) count as fixed, or NULL */
typedef enum { IN_T_FIXED, IN_T_AFFINE, IN_T_OTHER } in_t;

static in_t affine_in_t(const scn_define *d, const scn_ins *code, uint32_t i0, uint32_t i1)
{
    uint8_t st[SCN_MAX_STACK + 1];
    int sp = 0;
    for (uint32_t i = i0; i < i1; i++) {
        uint8_t op = code[i].op, a, b;
        if (op == SCN_OP_CONST || op == SCN_OP_PAR || op == SCN_OP_TIME ||
            (op == SCN_OP_LOC && d && d->loc_fixed[code[i].a])) {
            if (sp > SCN_MAX_STACK)
                return IN_T_OTHER;
            st[sp++] = op == SCN_OP_TIME ? IN_T_AFFINE : IN_T_FIXED;
        } else if (op <= SCN_OP_LOC) {
            return IN_T_OTHER; /* an input, a state, a let, the step: not t alone */
        } else if (op == SCN_OP_NEG) {
            continue;
        } else if (op >= SCN_OP_ADD && op <= SCN_OP_DIV && sp >= 2) {
            b = st[--sp], a = st[sp - 1];
            if (a == IN_T_OTHER || b == IN_T_OTHER || (op >= SCN_OP_MUL && a + b > 1) ||
                (op == SCN_OP_DIV && b != IN_T_FIXED))
                return IN_T_OTHER;
            st[sp - 1] = a > b ? a : b;
        } else {
            return IN_T_OTHER; /* a function, a condition: not affine */
        }
    }
    return sp == 1 ? (in_t)st[0] : IN_T_OTHER;
}

/* a sin or cos of an argument affine in `t` (code [a0, a1): w t + phi, w and phi fixed)
   in an output, derivative, let or root of a continuous define: its |w| is the kind's band
   (rt_kind.band), so rt_init refuses a set that samples the signal at w h >= pi, as a sine
   source's (an alias no estimate can tell: 1 - cos(w t) read where cos is 1 is 0). The
   argument becomes an SCN_ST_BAND statement after the one compiled (flush_tev) */
static void band_arg(scn_ctx *c, int f, uint32_t a0, uint32_t a1)
{
    if (c->err || !c->def || c->def->type != SCN_DEF_SS ||
        (c->st_kind != SCN_ST_OUT && c->st_kind != SCN_ST_DER && c->st_kind != SCN_ST_LET &&
         c->st_kind != SCN_ST_ROOT) ||
        (strcmp(scn_fns[f].name, "sin") != 0 && strcmp(scn_fns[f].name, "cos") != 0) ||
        affine_in_t(0, c->sc.code, a0, a1) != IN_T_AFFINE)
        return;
    if (c->def->nband + c->ntev >= SCN_MAX_BAND)
        return; /* (more than the bound: the first SCN_MAX_BAND say the band) */
    c->tev[c->ntev][0] = a0, c->tev[c->ntev][1] = a1, c->tev[c->ntev][2] = SCN_ST_BAND;
    c->tev[c->ntev][3] = c->tev[c->ntev][4] = 0;
    c->ntev++;
}

/* floor(a t + b) (a, b fixed: constants, parameters, lets of them) in a derivative or let
   of a continuous define: a staircase of t whose jumps, where a t + b is an integer, no
   step's error estimate sees (every stage past a jump reads the next stair, and so does
   the companion: dopri5's estimate of a jump in the first 0.3 of its step is 1/170 of
   its error). Each jump is a time
   event known at run time, as a comparison of t with an instant (time_switch): two
   instants of the kind's next_event, t + rt_x_floor_next(a t + b, a) and one stair
   further (the first may be now's to rounding), so a step of its set ends a part there,
   and the argument's `t` reads t_piece (inside a part its midpoint: every stage reads
   one stair). In an output it stays a plain floor: a counter of samples recorded, its
   stairs finer than a step, is no staircase integrated, and its instants would pass
   RT_TEV_PARTS_MAX. The argument is code [a0, a1); past the define's SCN_MAX_TEV
   instants, or past the VM's stack, it stays plain */
static uint32_t code_depth(const scn_ins *code, uint32_t i0, uint32_t i1);

static void floor_time(scn_ctx *c, int f, uint32_t a0, uint32_t a1)
{
    scn_ins *code = c->sc.code;
    if (c->err || !c->def || c->def->type != SCN_DEF_SS ||
        (c->st_kind != SCN_ST_DER && c->st_kind != SCN_ST_LET) ||
        strcmp(scn_fns[f].name, "floor") != 0 ||
        affine_in_t(c->def, code, a0, a1) != IN_T_AFFINE ||
        code_depth(code, a0, a1) + 4 > SCN_MAX_STACK ||
        c->def->ntev + c->ntev + 1 >= SCN_MAX_TEV)
        return;
    for (uint32_t i = a0; i < a1; i++)
        if (code[i].op == SCN_OP_TIME)
            code[i].op = SCN_OP_TPIECE;
    for (uint16_t k = 0; k < 2; k++) { /* (i0 = i1: a floor's; k: stairs after the next) */
        c->tev[c->ntev][0] = c->tev[c->ntev][1] = k, c->tev[c->ntev][2] = SCN_ST_TEV;
        c->tev[c->ntev][3] = a0, c->tev[c->ntev][4] = a1;
        c->ntev++;
    }
}

/* f(args): an elementary function, or if(c, a, b) */
static void call(scn_ctx *c, scn_name n)
{
    int f = -1, nargs = 0;
    for (int i = 0; scn_fns[i].name; i++)
        if (strcmp(scn_fns[i].name, n.s) == 0)
            f = i;
    int want = strcmp(n.s, "if") == 0 ? 3 : f >= 0 ? scn_fns[f].nargs : -1;
    if (want < 0) {
        const char *fn[32];
        size_t k = 0;
        for (int i = 0; scn_fns[i].name; i++)
            if (scn_fns[i].name[0] != '#')
                fn[k++] = scn_fns[i].name;
        fn[k++] = "if";
        scn_fail(c, n.pos, n.s, "unknown function", scn_list(c, fn, k, 32));
        return;
    }
    scn_expect_op(c, "(");
    uint32_t a0 = c->sc.ncode;
    while (!c->err && !scn_is_op(c, ")")) {
        expr(c), nargs++;
        if (!scn_accept_op(c, ","))
            break;
    }
    if (!c->err && nargs != want)
        scn_fail(c, n.pos, n.s, "wrong number of arguments",
                 scn_fmt(c, "%d argument%s for %s", want, want == 1 ? "" : "s", n.s));
    scn_expect_op(c, ")");
    if (want == 3)
        emit(c, SCN_OP_SEL, 0, -2);
    else if (!c->err) {
        if (want == 1)
            band_arg(c, f, a0, c->sc.ncode), floor_time(c, f, a0, c->sc.ncode);
        emit(c, SCN_OP_CALL, (uint16_t)f, 1 - want);
    }
}

static void primary(scn_ctx *c)
{
    if (c->tok.kind == SCN_T_NUM) {
        emit_const(c, c->tok.num);
        scn_next(c);
    } else if (c->tok.kind == SCN_T_ID) {
        scn_name n = {c->tok.s, c->tok.pos};
        scn_next(c);
        if (scn_is_op(c, "(") && enter(c)) {
            call(c, n);
            c->edepth--;
        } else if (!(scn_is_op(c, "[") && indexed_ref(c, n))) {
            name_ref(c, n);
        }
    } else if (scn_is_op(c, "(") && enter(c)) {
        scn_next(c);
        expr(c);
        scn_expect_op(c, ")");
        c->edepth--;
    } else if (!c->err) {
        scn_fail_tok(c, "syntax error", "a number, a name, a function call or '('");
    }
}

static void unary(scn_ctx *c);

/* a ^ b, right-associative, binding tighter than unary minus: -x^2 = -(x^2) */
static void power(scn_ctx *c)
{
    primary(c);
    if (!c->err && scn_is_op(c, "^") && enter(c)) {
        scn_next(c);
        unary(c);
        c->edepth--;
        uint16_t f = 0;
        while (strcmp(scn_fns[f].name, "pow") != 0) /* ^ means pow */
            f++;
        emit(c, SCN_OP_CALL, f, -1);
    }
}

static void unary(scn_ctx *c)
{
    int neg = scn_is_op(c, "-"), not = scn_is_op(c, "!");
    if (!(neg || not || scn_is_op(c, "+"))) {
        power(c);
        return;
    }
    if (!enter(c))
        return;
    scn_next(c);
    unary(c);
    if (neg || not)
        emit(c, neg ? SCN_OP_NEG : SCN_OP_NOT, 0, 0);
    c->edepth--;
}

/* binary levels, loosest first; each row: operators and their operations */
typedef struct level {
    const char *ops[4];
    uint8_t code[4];
} level;
static const level levels[] = {
    {{"||"}, {SCN_OP_OR}},
    {{"&&"}, {SCN_OP_AND}},
    {{"==", "!="}, {SCN_OP_EQ, SCN_OP_NE}},
    {{"<", "<=", ">", ">="}, {SCN_OP_LT, SCN_OP_LE, SCN_OP_GT, SCN_OP_GE}},
    {{"+", "-"}, {SCN_OP_ADD, SCN_OP_SUB}},
    {{"*", "/"}, {SCN_OP_MUL, SCN_OP_DIV}},
};
#define NLEVELS (sizeof levels / sizeof levels[0])

static int level_op(const scn_ctx *c, size_t lv)
{
    for (int i = 0; i < 4 && levels[lv].ops[i]; i++)
        if (scn_is_op(c, levels[lv].ops[i]))
            return i;
    return -1;
}

/* code [i0, i1) reads nothing that changes during a run: constants, parameters and
   operations on them */
static int fixed_code(const scn_ins *code, uint32_t i0, uint32_t i1)
{
    for (uint32_t i = i0; i < i1; i++) {
        uint8_t op = code[i].op;
        if (op != SCN_OP_CONST && op != SCN_OP_PAR && op < SCN_OP_NEG)
            return 0;
    }
    return i1 > i0;
}

static int pushes(scn_ins in);

/* the most operands code [i0, i1) pushes at once */
static uint32_t code_depth(const scn_ins *code, uint32_t i0, uint32_t i1)
{
    int d = 0, most = 0;
    for (uint32_t i = i0; i < i1; i++) {
        d += pushes(code[i]);
        most = d > most ? d : most;
    }
    return (uint32_t)most;
}

/* an order comparison of `t` alone with an expression fixed during the run (`t < t1`,
   `2 * T <= t`) in an output, derivative or let of a continuous define: a time event
   known at run time (rt_kind.next_event with time_event: the instant may lie anywhere,
   and follows the parameters), so a step of its set ends a part at the instant and
   every method keeps its order across the switch, as across a step source's. Its `t`
   reads t_piece through rt_x_at (the part ending at the instant sees the left limit
   there, the part from it the right, a tick at the instant the operator's own value),
   and the instant becomes an SCN_ST_TEV statement after the one compiled (flush_tev).
   A side affine in `t`, a t + b (`t - ts > 0`, `2 * t >= T`), against a fixed one r is the
   same switch at (r - b) / a: its `t` reads t_piece (inside a part the midpoint, clear of
   the instant; at a tick the tick's time, the comparison's own value there to the grid's
   rounding), the instant computed from the side at t = 0 and 1 (a = 0: no instant).
   lhs is code [a0, a1), rhs [a1, b1). Returns the comparison's SCN_TSIDE_*, 0 if none */
static uint16_t time_switch(scn_ctx *c, uint32_t a0, uint32_t a1, uint32_t b1)
{
    scn_ins *code = c->sc.code;
    uint32_t t = 0, i0, i1, s0 = 0, s1 = 0;
    uint16_t side = 0;
    if (c->err || !c->def || c->def->type != SCN_DEF_SS ||
        (c->st_kind != SCN_ST_OUT && c->st_kind != SCN_ST_DER && c->st_kind != SCN_ST_LET))
        return 0;
    if (a1 == a0 + 1 && code[a0].op == SCN_OP_TIME && fixed_code(code, a1, b1))
        t = a0, i0 = a1, i1 = b1, side = SCN_TSIDE_LEFT;
    else if (b1 == a1 + 1 && code[a1].op == SCN_OP_TIME && fixed_code(code, a0, a1))
        t = a1, i0 = a0, i1 = a1, side = SCN_TSIDE_RIGHT;
    else if (affine_in_t(0, code, a0, a1) == IN_T_AFFINE && fixed_code(code, a1, b1))
        s0 = a0, s1 = a1, i0 = a1, i1 = b1;
    else if (affine_in_t(0, code, a1, b1) == IN_T_AFFINE && fixed_code(code, a0, a1))
        s0 = a1, s1 = b1, i0 = a0, i1 = a1;
    else
        return 0;
    if (s1 > s0 && (code_depth(code, s0, s1) + 2 > SCN_MAX_STACK ||
                    c->def->ntev + c->ntev >= SCN_MAX_TEV))
        return 0; /* (its instant, (r - b) / a, would not fit the VM's stack, or the define
                     has SCN_MAX_TEV instants: the plain comparison, as before there was
                     one for an affine side) */
    if (c->def->ntev + c->ntev >= SCN_MAX_TEV) {
        scn_fail_tok(c, "too many comparisons of t",
                     scn_fmt(c, "at most %u in one define's body", SCN_MAX_TEV));
        return 0;
    }
    if (side)
        code[t].op = SCN_OP_TPIECE;
    for (uint32_t i = s0; i < s1; i++)
        if (code[i].op == SCN_OP_TIME)
            code[i].op = SCN_OP_TPIECE;
    c->tev[c->ntev][0] = i0, c->tev[c->ntev][1] = i1, c->tev[c->ntev][2] = SCN_ST_TEV;
    c->tev[c->ntev][3] = s0, c->tev[c->ntev][4] = s1;
    c->ntev++;
    return side;
}

/* is the value of code [i0, i1) a truth value: its last operation (the code is postfix)
   a comparison, !, && or ||, or a let that holds one (a side that is one switches only
   where those do: no switch of its own, state_switch). A truth value inside a side that
   is no truth value itself (`if(s > 0, s, -s) > 0.5`) leaves the side's own switch */
static int logic_code(const scn_define *d, const scn_ins *code, uint32_t i0, uint32_t i1)
{
    if (i1 <= i0)
        return 0;
    uint8_t op = code[i1 - 1].op;
    return (op >= SCN_OP_LT && op <= SCN_OP_OR) || op == SCN_OP_NOT ||
           (op == SCN_OP_LOC && d->loc_logic[code[i1 - 1].a]);
}

/* is code [i0, i1) fixed during the run: constants, parameters, operators on them and
   lets that are (state_switch: no switch of states) */
static int fixed_side(const scn_define *d, const scn_ins *code, uint32_t i0, uint32_t i1)
{
    for (uint32_t i = i0; i < i1; i++) {
        uint8_t op = code[i].op;
        if (op != SCN_OP_CONST && op != SCN_OP_PAR && op < SCN_OP_NEG &&
            !(op == SCN_OP_LOC && d->loc_fixed[code[i].a]))
            return 0;
    }
    return i1 > i0;
}

/* does code [i0, i1) read h, itself or through a let (the call's step: 0 at an instant,
   where a switch's mode is taken, state_switch) */
static int step_code(const scn_define *d, const scn_ins *code, uint32_t i0, uint32_t i1)
{
    for (uint32_t i = i0; i < i1; i++)
        if (code[i].op == SCN_OP_STEP || (code[i].op == SCN_OP_LOC && d->loc_step[code[i].a]))
            return 1;
    return 0;
}

/* an order comparison in an output, a derivative or a let of an ss_system, its sides not
   both fixed, no truth values, no h and no time event (time_switch): a switch of the
   dynamics where its sides meet (in an output, of the block that integrates it). Inside a
   step no estimate sees it (the stages after the crossing read the other branch, and the
   method's companion does too), so it becomes a located switch (finish_switches, at the
   body's end, for a let only if an output or a derivative reads it; in a system without
   states its mode makes it a continuous one): two roots, the sides' difference rising and
   falling, located and handled as a `when`'s, whose handlers set a hidden state, the switch's mode, to the comparison's
   value past the crossing; the kind takes the modes at each instant (rt_kind.instant)
   and the comparison reads its mode (rt_x_swc) once it has one. Registers the comparison
   about to be emitted at code index c->sc.ncode, its operator `op` at `pos`; its `a` is
   set by finish_switches. Past the define's SCN_MAX_PORTS comparisons, one is noted
   (sw_over): finish_switches refuses it where an output or a derivative reads it, since
   plain it would cross its switch unseen */
static void state_switch(scn_ctx *c, uint32_t a0, uint32_t a1, uint32_t b1, scn_pos pos,
                         const char *op)
{
    scn_define *d = c->def;
    const scn_ins *code = c->sc.code;
    if (c->err || !d || d->type != SCN_DEF_SS ||
        (c->st_kind != SCN_ST_DER && c->st_kind != SCN_ST_OUT && c->st_kind != SCN_ST_LET) ||
        (fixed_side(d, code, a0, a1) && fixed_side(d, code, a1, b1)) ||
        logic_code(d, code, a0, a1) || logic_code(d, code, a1, b1) ||
        step_code(d, code, a0, b1)) /* (truth values change where their sides meet) */
        return;
    if (d->nsw >= SCN_MAX_PORTS) {
        int16_t at = c->st_kind == SCN_ST_LET ? (int16_t)d->nloc : -1;
        if (at < 0 ? !d->sw_over_der : !d->sw_over[at]) /* (the first one, to name) */
            d->sw_over_pos[at < 0 ? SCN_MAX_LOCALS : at] = pos,
            d->sw_over_op[at < 0 ? SCN_MAX_LOCALS : at] = op;
        if (at < 0)
            d->sw_over_der = 1;
        else
            d->sw_over[at] = 1;
        return;
    }
    d->sw[d->nsw][0] = a0, d->sw[d->nsw][1] = a1, d->sw[d->nsw][2] = b1;
    d->sw_let[d->nsw] = c->st_kind == SCN_ST_LET ? (int16_t)d->nloc : -1; /* (its let) */
    d->sw_op[d->nsw] = op;
    d->sw_pos[d->nsw++] = pos;
}

/* the comparison op of the sides code [a0, a1) and [a1, ncode): a time event, a located
   switch or a plain comparison (time_switch, state_switch) */
static void comparison(scn_ctx *c, uint32_t a0, uint32_t a1, uint8_t op, scn_pos pos,
                       const char *name)
{
    uint16_t side = 0; /* (t == c holds at an instant alone: no time event) */
    if (op >= SCN_OP_LT && op <= SCN_OP_GE) {
        uint16_t ntev = c->ntev; /* (a time event is no switch of states) */
        side = time_switch(c, a0, a1, c->sc.ncode);
        if (c->ntev == ntev)
            state_switch(c, a0, a1, c->sc.ncode, pos, name);
    }
    emit(c, op, side, -1);
}

/* the kink function code [i0, i1) ends in: abs (1), max (2), min (3), or 0 if none (or
   its argument is empty) */
static int kink_code(const scn_ins *code, uint32_t i0, uint32_t i1)
{
    if (i1 < i0 + 2 || code[i1 - 1].op != SCN_OP_CALL)
        return 0;
    const char *f = scn_fns[code[i1 - 1].a].name;
    return strcmp(f, "abs") == 0 ? 1 : strcmp(f, "max") == 0 ? 2 : strcmp(f, "min") == 0 ? 3 : 0;
}

/* the operands instruction in pushes (+1), pops (a binary operator: -1) or leaves */
static int pushes(scn_ins in)
{
    if (in.op <= SCN_OP_LOC)
        return 1;
    if (in.op == SCN_OP_NEG || in.op == SCN_OP_NOT)
        return 0;
    if (in.op == SCN_OP_SEL)
        return -2;
    return in.op == SCN_OP_CALL ? 1 - scn_fns[in.a].nargs : -1;
}

/* the n instructions at from emitted again, with their stack effect */
static void emit_copy(scn_ctx *c, const scn_ins *from, uint32_t n)
{
    for (uint32_t i = 0; i < n; i++)
        emit(c, from[i].op, from[i].a, pushes(from[i]));
}

/* where the second argument of a two-argument call ending code [i0, i1) begins: the
   shortest suffix before the call that is a whole expression */
static uint32_t second_arg(const scn_ins *code, uint32_t i0, uint32_t i1)
{
    int need = 1;
    uint32_t i = i1 - 1; /* (the call) */
    while (i > i0 && need > 0)
        need -= pushes(code[--i]);
    return i;
}

/* is code [i0, i1) a constant, c or -c: its value in *v */
static int const_value(const scn_scene *s, uint32_t i0, uint32_t i1, double *v)
{
    if (i1 == i0 + 1 && s->code[i0].op == SCN_OP_CONST)
        return *v = s->k[s->code[i0].a], 1;
    if (i1 == i0 + 2 && s->code[i0].op == SCN_OP_CONST && s->code[i0 + 1].op == SCN_OP_NEG)
        return *v = -s->k[s->code[i0].a], 1;
    return 0;
}

/* order comparison op with its sides swapped: a < b is b > a */
static uint8_t mirrored(uint8_t op)
{
    return op == SCN_OP_LT ? SCN_OP_GT : op == SCN_OP_LE ? SCN_OP_GE
         : op == SCN_OP_GT ? SCN_OP_LT : SCN_OP_LE;
}

/* an order comparison with a kink on one side, abs(e), max(p, q) or min(p, q), and r on
   the other, nothing registered inside either (no instant, band or switch whose code
   would move): abs(e) < r is e < r && -e < r, max(p, q) < r is p < r && q < r, min(p, q)
   < r is p < r || q < r, and > swaps && and || (<= and >= alike, r op f(...) mirrored).
   As one comparison its root is a tent that a step crosses through and back unseen (a
   thin layer |z - zl| < w passed in one step: 140 times the tolerance off, a pulse
   max(t - ts, ts - t) < w inside a step: 0 for 0.4, run and check ok); as two, each
   half's root is as smooth as its argument, and each is a time event or a located switch
   of its own. Returns 0 (nothing done) if it is no such comparison */
static int split_kink(scn_ctx *c, uint32_t a0, uint32_t a1, uint8_t op, scn_pos pos,
                      const char *name)
{
    static scn_ins h1[SCN_MAX_CODE], h2[SCN_MAX_CODE], r[SCN_MAX_CODE];
    scn_scene *s = &c->sc;
    uint32_t b1 = s->ncode;
    int kl = kink_code(s->code, a0, a1), kr = kink_code(s->code, a1, b1);
    if (c->err || !c->def || op < SCN_OP_LT || op > SCN_OP_GE || (kl != 0) == (kr != 0) ||
        c->def->ntev + c->ntev + 2 > SCN_MAX_TEV) /* (halves of t: two instants more) */
        return 0;
    int kind = kl ? kl : kr;
    uint32_t f0 = kl ? a0 : a1, f1 = (kl ? a1 : b1) - 1; /* the arguments: [f0, f1) */
    uint32_t r0 = kl ? a1 : a0, nr = (kl ? b1 : a1) - r0;
    uint32_t m = kind == 1 ? f1 : second_arg(s->code, f0, f1 + 1);
    if (kind != 1 && !(m > f0 && m < f1))
        return 0;
    uint32_t n1 = m - f0, n2 = kind == 1 ? n1 + 1 : f1 - m;
    uint32_t d1 = code_depth(s->code, f0, m), d2 = kind == 1 ? d1 : code_depth(s->code, m, f1);
    uint32_t dr = code_depth(s->code, r0, r0 + nr), dh = d1 > d2 ? d1 : d2;
    if (c->sdepth + (dh > dr ? dh : dr) > SCN_MAX_STACK) /* (a half op r on one's value) */
        return 0;
    double rv;
    if (kind == 1 && const_value(s, r0, r0 + nr, &rv) && !(rv > 0))
        return 0; /* abs(e) < 0 never holds, abs(e) > 0 wherever e is not 0: split, the
                     halves would switch where the whole does not */
    memcpy(h1, &s->code[f0], n1 * sizeof *h1);
    if (kind == 1)
        memcpy(h2, h1, n1 * sizeof *h2), h2[n1] = (scn_ins){SCN_OP_NEG, 0};
    else
        memcpy(h2, &s->code[m], n2 * sizeof *h2);
    memcpy(r, &s->code[r0], nr * sizeof *r);
    if (kr) /* r op f(...): f(...) op' r */
        op = mirrored(op);
    int below = op == SCN_OP_LT || op == SCN_OP_LE; /* max below r: both halves are */
    s->ncode = a0, c->sdepth -= 2; /* (both sides' values gone) */
    emit_copy(c, h1, n1);
    emit_copy(c, r, nr);
    comparison(c, a0, a0 + n1, op, pos, name);
    uint32_t p = s->ncode;
    emit_copy(c, h2, n2);
    emit_copy(c, r, nr);
    comparison(c, p, p + n2, op, pos, name);
    emit(c, (kind == 3) != below ? SCN_OP_AND : SCN_OP_OR, 0, -1);
    return 1;
}

/* is code [s0, s1) a kink wrapped once by a fixed operand: K + C, C + K, K - C, C - K, and
   K * C, C * K, K / C with C a constant above 0 (K a kink, kink_code; C fixed code). Sets
   the kink's range [*k0, *k1), the operand's [*c0, *c1), the operation and whether K
   comes first */
static int wrapped_kink(const scn_scene *s, uint32_t s0, uint32_t s1, uint32_t *k0,
                        uint32_t *k1, uint32_t *c0, uint32_t *c1, uint8_t *aop, int *kfirst)
{
    if (s1 < s0 + 3)
        return 0;
    uint8_t o = s->code[s1 - 1].op;
    if (o < SCN_OP_ADD || o > SCN_OP_DIV)
        return 0;
    uint32_t m = second_arg(s->code, s0, s1);
    if (!(m > s0 && m < s1 - 1))
        return 0;
    int first = kink_code(s->code, s0, m) != 0 && fixed_code(s->code, m, s1 - 1);
    int second = !first && kink_code(s->code, m, s1 - 1) != 0 && fixed_code(s->code, s0, m);
    if (!first && !second)
        return 0;
    *k0 = first ? s0 : m, *k1 = first ? m : s1 - 1;
    *c0 = first ? m : s0, *c1 = first ? s1 - 1 : m;
    if ((o == SCN_OP_MUL || o == SCN_OP_DIV) &&
        !(*c1 == *c0 + 1 && s->code[*c0].op == SCN_OP_CONST && s->k[s->code[*c0].a] > 0))
        return 0; /* (a factor of unknown sign would turn the comparison) */
    if (o == SCN_OP_DIV && !first)
        return 0; /* (C / K is no kink of K's kind) */
    *aop = o, *kfirst = first;
    return 1;
}

/* a comparison of a kink wrapped once by a fixed operand (wrapped_kink: abs(e) - w < 0,
   2 * abs(x) < 2 * w) as the bare kink against the other side undone: K + C op r is
   K op r - C, C - K op r is K op' C - r, K * C op r is K op r / C, so the kink is split
   (split_kink) as when written bare (a pulse abs(t - ts) - w < 0 inside a step: 0 for 0.4,
   run and check ok). Returns 1 if it compiled the comparison */
static int unwrap_kink(scn_ctx *c, uint32_t a0, uint32_t a1, uint8_t op, scn_pos pos,
                       const char *name)
{
    static scn_ins kk[SCN_MAX_CODE], cc[SCN_MAX_CODE], r[SCN_MAX_CODE];
    scn_scene *s = &c->sc;
    uint32_t b1 = s->ncode, k0, k1, c0, c1;
    uint8_t aop;
    int kfirst;
    if (c->err || !c->def || c->def->type != SCN_DEF_SS || op < SCN_OP_LT || op > SCN_OP_GE ||
        (c->st_kind != SCN_ST_OUT && c->st_kind != SCN_ST_DER && c->st_kind != SCN_ST_LET) ||
        kink_code(s->code, a0, a1) || kink_code(s->code, a1, b1))
        return 0; /* (only where a split locates something: moving C across rounds, which a
                     sampled system's tie or a handler's test would see) */
    int left = wrapped_kink(s, a0, a1, &k0, &k1, &c0, &c1, &aop, &kfirst);
    if (!left && !wrapped_kink(s, a1, b1, &k0, &k1, &c0, &c1, &aop, &kfirst))
        return 0;
    uint32_t r0 = left ? a1 : a0, nr = (left ? b1 : a1) - r0, nk = k1 - k0, nc = c1 - c0;
    double rv, cv;
    if (kink_code(s->code, k0, k1) == 1 && const_value(s, r0, r0 + nr, &rv) &&
        const_value(s, c0, c1, &cv)) {
        double v = aop == SCN_OP_ADD ? rv - cv : aop == SCN_OP_SUB ? (kfirst ? rv + cv : cv - rv)
                 : aop == SCN_OP_MUL ? rv / cv : rv * cv;
        if (!(v > 0))
            return 0; /* (abs against a value not above 0: split_kink's own exception) */
    }
    uint32_t dk = code_depth(s->code, k0, k1), dc = code_depth(s->code, c0, c1);
    uint32_t dr = code_depth(s->code, r0, r0 + nr), d = dk > dr ? dk : dr;
    d = d > dc + 1 ? d : dc + 1;
    if (c->sdepth + d + 1 > SCN_MAX_STACK)
        return 0;
    memcpy(kk, &s->code[k0], nk * sizeof *kk);
    memcpy(cc, &s->code[c0], nc * sizeof *cc);
    memcpy(r, &s->code[r0], nr * sizeof *r);
    if (!left) /* r op W: W op' r */
        op = mirrored(op);
    s->ncode = a0, c->sdepth -= 2; /* (both sides' values gone) */
    emit_copy(c, kk, nk);
    uint32_t a1n = s->ncode;
    if (aop == SCN_OP_SUB && !kfirst) { /* C - K op r: K op' C - r */
        emit_copy(c, cc, nc);
        emit_copy(c, r, nr);
        emit(c, SCN_OP_SUB, 0, -1);
        op = mirrored(op);
    } else { /* K + C: r - C; K - C: r + C; K * C: r / C; K / C: r * C */
        emit_copy(c, r, nr);
        emit_copy(c, cc, nc);
        emit(c, aop == SCN_OP_ADD ? SCN_OP_SUB : aop == SCN_OP_SUB ? SCN_OP_ADD
              : aop == SCN_OP_MUL ? SCN_OP_DIV : SCN_OP_MUL, 0, -1);
    }
    if (!split_kink(c, a0, a1n, op, pos, name))
        comparison(c, a0, a1n, op, pos, name);
    return 1;
}

static void binary(scn_ctx *c, size_t lv)
{
    if (lv == NLEVELS) {
        unary(c);
        return;
    }
    uint32_t a0 = c->sc.ncode;
    uint16_t ntev = c->ntev, nsw = c->def ? c->def->nsw : 0; /* (registered before it) */
    binary(c, lv + 1);
    int i;
    while (!c->err && (i = level_op(c, lv)) >= 0) {
        uint32_t a1 = c->sc.ncode;
        scn_pos op_pos = c->tok.pos;
        scn_next(c);
        binary(c, lv + 1);
        uint8_t op = levels[lv].code[i];
        int moved = c->ntev != ntev || (c->def && c->def->nsw != nsw);
        if (moved || (!split_kink(c, a0, a1, op, op_pos, levels[lv].ops[i]) &&
                      !unwrap_kink(c, a0, a1, op, op_pos, levels[lv].ops[i])))
            comparison(c, a0, a1, op, op_pos, levels[lv].ops[i]);
    }
}

/* cond ? a : b, right-associative */
static void expr(scn_ctx *c)
{
    binary(c, 0);
    if (!c->err && scn_is_op(c, "?") && enter(c)) {
        scn_next(c);
        expr(c);
        scn_expect_op(c, ":");
        expr(c);
        emit(c, SCN_OP_SEL, 0, -2);
        c->edepth--;
    }
}

/* ------------------------------------------------------------------ body statements */

/* a copy of code [i0, i1), a side a t + b of a comparison (time_switch: its `t` reads
   t_piece), with t = v */
static void side_at(scn_ctx *c, uint32_t i0, uint32_t i1, double v)
{
    for (uint32_t i = i0; i < i1 && !c->err; i++) {
        scn_ins in = c->sc.code[i];
        if (in.op == SCN_OP_TPIECE) {
            emit_const(c, v);
            c->sdepth--; /* (an instant's statement counts no depth: flush_tev) */
        } else {
            emit(c, in.op, in.a, 0);
        }
    }
}

/* the index of function `name` in scn_fns */
static int fn_index(const char *name)
{
    int f = 0;
    while (scn_fns[f].name && strcmp(scn_fns[f].name, name) != 0)
        f++;
    return f;
}


/* a copy of code [i0, i1), the argument a t + b of a floor (floor_time: its `t` reads
   t_piece), reading `t` itself: the argument now */
static void arg_now(scn_ctx *c, uint32_t i0, uint32_t i1)
{
    for (uint32_t i = i0; i < i1 && !c->err; i++) {
        scn_ins in = c->sc.code[i];
        emit(c, in.op == SCN_OP_TPIECE ? SCN_OP_TIME : in.op, in.a, 0);
    }
}

/* the instants the statement just compiled compares `t` with (time_switch), and its sin
   and cos arguments affine in `t` (band_arg): each an SCN_ST_TEV or SCN_ST_BAND statement
   of its own, a copy of its code stored into the next one */
static void flush_tev(scn_ctx *c, scn_pos pos)
{
    scn_scene *s = &c->sc;
    for (uint16_t k = 0; k < c->ntev && !c->err; k++) {
        if (s->nst >= SCN_MAX_STMTS) {
            scn_fail(c, pos, "t", "too many body statements",
                     scn_fmt(c, "at most %u in all bodies", SCN_MAX_STMTS));
            return;
        }
        uint8_t kind = (uint8_t)c->tev[k][2];
        uint16_t *n = kind == SCN_ST_TEV ? &c->def->ntev : &c->def->nband;
        uint32_t code0 = s->ncode;
        for (uint32_t i = c->tev[k][0]; i < c->tev[k][1]; i++)
            emit(c, s->code[i].op, s->code[i].a, 0);
        if (c->tev[k][1] == c->tev[k][0]) { /* floor(a t + b): t + its next jump's time */
            uint32_t s0 = c->tev[k][3], s1 = c->tev[k][4];
            emit(c, SCN_OP_TIME, 0, 0);
            arg_now(c, s0, s1);
            side_at(c, s0, s1, 0);
            emit(c, SCN_OP_CALL, (uint16_t)fn_index("abs"), 0);
            emit(c, SCN_OP_CALL, (uint16_t)fn_index("#floor_snap"), 0);
            side_at(c, s0, s1, 1);
            side_at(c, s0, s1, 0);
            emit(c, SCN_OP_SUB, 0, 0);
            emit(c, SCN_OP_CALL, (uint16_t)fn_index("#floor_next"), 0);
            emit(c, SCN_OP_ADD, 0, 0);
            if (c->tev[k][0] == 1) { /* one stair further: + 1 / |a| */
                emit_const(c, 1);
                c->sdepth--; /* (an instant's statement counts no depth) */
                side_at(c, s0, s1, 1);
                side_at(c, s0, s1, 0);
                emit(c, SCN_OP_SUB, 0, 0);
                emit(c, SCN_OP_CALL, (uint16_t)fn_index("abs"), 0);
                emit(c, SCN_OP_DIV, 0, 0);
                emit(c, SCN_OP_ADD, 0, 0);
            }
        } else if (c->tev[k][4] > c->tev[k][3]) { /* r, a t + b: (r - b) / a */
            side_at(c, c->tev[k][3], c->tev[k][4], 0);
            emit(c, SCN_OP_SUB, 0, 0);
            side_at(c, c->tev[k][3], c->tev[k][4], 1);
            side_at(c, c->tev[k][3], c->tev[k][4], 0);
            emit(c, SCN_OP_SUB, 0, 0);
            emit(c, SCN_OP_DIV, 0, 0);
        }
        emit(c, SCN_OP_OUT, *n, 0);
        s->st[s->nst++] = (scn_stmt){kind, (*n)++, code0, s->ncode, pos, 0};
    }
    c->ntev = 0;
}

/* one statement: its expression, stored into index, ended by the operator term */
static void add_stmt_to(scn_ctx *c, uint8_t kind, uint16_t index, uint16_t root, scn_pos pos,
                        const char *term)
{
    scn_scene *s = &c->sc;
    if (s->nst >= SCN_MAX_STMTS) {
        scn_fail(c, pos, "=", "too many body statements",
                 scn_fmt(c, "at most %u in all bodies", SCN_MAX_STMTS));
        return;
    }
    uint32_t code0 = s->ncode;
    c->sdepth = 0;
    c->st_kind = kind, c->ntev = 0;
    expr(c);
    emit(c, kind == SCN_ST_LET ? SCN_OP_SETLOC : SCN_OP_OUT, index, -1);
    scn_expect_op(c, term);
    s->st[s->nst++] = (scn_stmt){kind, index, code0, s->ncode, pos, root};
    flush_tev(c, pos);
}

static void add_stmt(scn_ctx *c, uint8_t kind, uint16_t index, scn_pos pos)
{
    add_stmt_to(c, kind, index, 0, pos, ";");
}

/* the target of `name = ...`: an output */
static int target_output(scn_ctx *c, scn_name n)
{
    int i = find_var(c->def->y, c->def->ny, n.s);
    if (i < 0)
        scn_fail(c, n.pos, n.s, "not an output of the define",
                 "y[i], xdot[i], xnext[i], der(state), next(state), let name or an output "
                 "name on the left of '='");
    return i;
}

/* the state inside der( ) or next( ) */
static int target_state(scn_ctx *c)
{
    scn_expect_op(c, "(");
    scn_name n = scn_expect_name(c, "a state name");
    scn_expect_op(c, ")");
    int i = c->err ? -1 : find_var(c->def->x, c->def->nx, n.s);
    if (!c->err && i < 0)
        scn_fail(c, n.pos, n.s, "unknown state",
                 scn_fmt(c, "a state of %s", c->def->name.s));
    return i;
}

static void let_stmt(scn_ctx *c)
{
    scn_define *d = c->def;
    scn_name n = scn_expect_name(c, "a name after let");
    if (c->err)
        return;
    if (find_local(d, n.s) >= 0 || find_var(d->u, d->nu, n.s) >= 0 ||
        find_var(d->y, d->ny, n.s) >= 0 || find_var(d->p, d->np, n.s) >= 0 ||
        find_var(d->x, d->nx, n.s) >= 0 || !strcmp(n.s, "t") || !strcmp(n.s, "h") ||
        !strcmp(n.s, "pi")) {
        scn_fail(c, n.pos, n.s, "name already used in the define", "a new name after let");
        return;
    }
    if (d->nloc >= SCN_MAX_LOCALS) {
        scn_fail(c, n.pos, n.s, "too many let names",
                 scn_fmt(c, "at most %u per define", SCN_MAX_LOCALS));
        return;
    }
    scn_pos pos = c->tok.pos;
    scn_expect_op(c, "=");
    /* the name is visible only after its own expression */
    uint16_t i = d->nloc;
    uint32_t code0 = c->sc.ncode;
    add_stmt(c, SCN_ST_LET, i, pos);
    /* its expression: code0 up to its SETLOC (time events add statements after it) */
    uint32_t code1 = code0;
    while (code1 < c->sc.ncode && c->sc.code[code1].op != SCN_OP_SETLOC)
        code1++;
    d->loc_logic[i] = (uint8_t)logic_code(d, c->sc.code, code0, code1);
    d->loc_step[i] = (uint8_t)step_code(d, c->sc.code, code0, code1);
    d->loc_fixed[i] = (uint8_t)fixed_side(d, c->sc.code, code0, code1);
    d->loc[d->nloc++] = n;
}

/* one assignment of a `when` handler (kind SCN_ST_EVENT) or of its rest clause
   (SCN_ST_REST): state = e; or x[i] = e; each state once */
static void handler_stmt(scn_ctx *c, uint16_t r, uint8_t kind)
{
    scn_define *d = c->def;
    scn_name n = scn_expect_name(c, "a state assignment (state = ...; or x[i] = ...;) or '}'");
    if (c->err)
        return;
    int i = scn_is_op(c, "[") && !strcmp(n.s, "x") ? index_in(c, d->nx, "states")
                                                   : find_var(d->x, d->nx, n.s);
    if (i < 0 && !c->err)
        scn_fail(c, n.pos, n.s, "not a state of the define",
                 "a state name or x[i]: an event handler sets states");
    for (uint32_t s = d->st0; !c->err && s < c->sc.nst; s++)
        if (c->sc.st[s].kind == kind && c->sc.st[s].root == r && c->sc.st[s].index == i)
            scn_fail(c, n.pos, n.s, "assigned twice in the handler", "one value per state");
    if (c->err)
        return;
    scn_pos pos = c->tok.pos;
    scn_expect_op(c, "=");
    add_stmt_to(c, kind, (uint16_t)i, r, pos, ";");
}

/* { state = ...; ... } of root r's handler or rest clause, t_last readable inside */
static void handler_block(scn_ctx *c, uint16_t r, uint8_t kind)
{
    scn_expect_op(c, "{");
    c->when = (uint16_t)(r + 1);
    while (!c->err && !scn_is_op(c, "}") && c->tok.kind != SCN_T_EOF)
        handler_stmt(c, r, kind);
    c->when = 0;
    scn_expect_op(c, "}");
}

/* rest (T) { state = ...; ... } after a `when`: a crossing that comes less than T seconds
   after the root's previous one (its t_last) runs this handler instead of the when's:
   how contact comes to rest (docs/scene-language.md) */
static void rest_clause(scn_ctx *c, scn_name at)
{
    scn_define *d = c->def;
    if (!c->after_when) {
        scn_fail(c, at.pos, at.s, "a rest clause belongs to a when",
                 "when (...) { ... } rest (time) { ... }");
        return;
    }
    uint16_t r = (uint16_t)(c->after_when - 1);
    c->after_when = 0; /* one rest clause per when */
    d->rest[r] = 1;
    scn_pos pos = c->tok.pos;
    scn_expect_op(c, "(");
    c->when = (uint16_t)(r + 1);
    add_stmt_to(c, SCN_ST_REST_T, r, r, pos, ")");
    c->when = 0;
    handler_block(c, r, SCN_ST_REST);
}

/* when [falling|rising] (e) { state = ...; ... }: a root function of an ss_system (a state
   event where e crosses 0 in that direction) and what happens to the states there */
static void when_stmt(scn_ctx *c, scn_name at)
{
    scn_define *d = c->def;
    if (d->type != SCN_DEF_SS || d->nx == 0) {
        scn_fail(c, at.pos, at.s, "state events belong to an ss_system with states",
                 "when (...) { ... } in the body of an ss_system");
        return;
    }
    if (d->nr >= SCN_MAX_PORTS) {
        scn_fail(c, at.pos, at.s, "too many roots",
                 scn_fmt(c, "at most %u per define", SCN_MAX_PORTS));
        return;
    }
    int8_t dir = 0;
    if (scn_is_word(c, "falling") || scn_is_word(c, "rising")) {
        dir = scn_is_word(c, "falling") ? -1 : 1;
        scn_next(c);
    }
    uint16_t r = d->nr++;
    d->rdir[r] = dir;
    scn_pos pos = c->tok.pos;
    scn_expect_op(c, "(");
    add_stmt_to(c, SCN_ST_ROOT, r, 0, pos, ")");
    handler_block(c, r, SCN_ST_EVENT);
    c->after_when = (uint16_t)(r + 1);
}

/* which kind of assignment a body statement is and to which index */
static void body_stmt(scn_ctx *c)
{
    scn_define *d = c->def;
    int dss = d->type == SCN_DEF_DSS;
    scn_name n = scn_expect_name(c, "a body statement: y[i] = ..., xdot[i] = ..., "
                                    "xnext[i] = ..., der(x) = ..., let v = ..., "
                                    "when (...) { ... } or '}'");
    if (c->err)
        return;
    uint8_t kind = SCN_ST_OUT;
    int i = -1;
    if (strcmp(n.s, "rest") == 0 && scn_is_op(c, "(")) {
        rest_clause(c, n);
        return;
    }
    c->after_when = 0;
    if (strcmp(n.s, "let") == 0 && c->tok.kind == SCN_T_ID) {
        let_stmt(c);
        return;
    }
    if (strcmp(n.s, "when") == 0 && (scn_is_op(c, "(") || c->tok.kind == SCN_T_ID)) {
        when_stmt(c, n);
        return;
    }
    if (scn_is_op(c, "[") && !strcmp(n.s, "y")) {
        i = index_in(c, d->ny, "outputs");
    } else if (scn_is_op(c, "[") && (!strcmp(n.s, "xdot") || !strcmp(n.s, "xnext"))) {
        kind = n.s[1] == 'd' ? SCN_ST_DER : SCN_ST_NEXT;
        i = index_in(c, d->nx, "states");
    } else if (scn_is_op(c, "(") && (!strcmp(n.s, "der") || !strcmp(n.s, "next"))) {
        kind = n.s[0] == 'd' ? SCN_ST_DER : SCN_ST_NEXT;
        i = target_state(c);
    } else {
        i = target_output(c, n);
    }
    if (c->err)
        return;
    if ((kind == SCN_ST_DER && dss) || (kind == SCN_ST_NEXT && !dss)) {
        scn_fail(c, n.pos, n.s, dss ? "a dss_system has next states, not derivatives"
                                    : "an ss_system has derivatives, not next states",
                 dss ? "xnext[i] = ... or next(state) = ..." : "xdot[i] = ... or der(state) = ...");
        return;
    }
    for (uint32_t s = d->st0; s < c->sc.nst; s++)
        if (c->sc.st[s].kind == kind && c->sc.st[s].index == i) {
            scn_fail(c, n.pos, n.s, "assigned twice in the body",
                     "one equation per output and per state");
            return;
        }
    scn_pos pos = c->tok.pos;
    scn_expect_op(c, "=");
    add_stmt(c, kind, (uint16_t)i, pos);
}

/* after the body: every output and every state has its equation */
static void body_complete(scn_ctx *c, scn_define *d, scn_pos end)
{
    uint8_t xk = d->type == SCN_DEF_DSS ? SCN_ST_NEXT : SCN_ST_DER;
    for (int pass = 0; pass < 2 && !c->err; pass++) {
        uint8_t kind = pass ? xk : SCN_ST_OUT;
        uint16_t n = pass ? d->nx : d->ny;
        for (uint16_t i = 0; i < n && !c->err; i++) {
            uint32_t s = d->st0;
            while (s < c->sc.nst && !(c->sc.st[s].kind == kind && c->sc.st[s].index == i))
                s++;
            if (s < c->sc.nst)
                continue;
            const char *name = pass ? d->x[i].name.s : d->y[i].name.s;
            scn_fail(c, end, "}", pass ? "state has no equation" : "output not assigned",
                     pass ? scn_fmt(c, "%s(%s) = ... in the body",
                                    xk == SCN_ST_NEXT ? "next" : "der", name)
                          : scn_fmt(c, "y[%u] = ... (%s) in the body", (unsigned)i, name));
        }
    }
}

/* a statement of kind `kind` into index (root `root` for a handler) whose code is the
   root of the comparison op of the sides [a0, a1) and [a1, b1) (rt_x_swgt ...), or with
   a0 = a1 the constant v: the statements a switch adds (finish_switches) */
static void added_stmt(scn_ctx *c, uint8_t kind, uint16_t index, uint16_t root, scn_pos pos,
                       uint32_t a0, uint32_t a1, uint32_t b1, double v, uint8_t op)
{
    scn_scene *s = &c->sc;
    if (c->err || s->nst >= SCN_MAX_STMTS) {
        if (!c->err)
            scn_fail(c, pos, "", "too many body statements",
                     scn_fmt(c, "at most %u in all bodies", SCN_MAX_STMTS));
        return;
    }
    uint32_t code0 = s->ncode;
    c->sdepth = 0; /* (a statement of its own, as add_stmt_to's) */
    if (a0 == a1)
        emit_const(c, v);
    for (uint32_t i = a0; i < b1; i++) /* (the sides in a row: [a0, a1), then [a1, b1)) */
        emit(c, s->code[i].op, s->code[i].a, 0);
    static const char *const root_fn[] = {"#swlt", "#swle", "#swgt", "#swge"};
    uint16_t f = 0; /* its row of scn_fns */
    while (b1 > a1 && strcmp(scn_fns[f].name, root_fn[op - SCN_OP_LT]) != 0)
        f++;
    if (b1 > a1)
        emit(c, SCN_OP_CALL, f, 0);
    emit(c, SCN_OP_OUT, index, 0);
    s->st[s->nst++] = (scn_stmt){kind, index, code0, s->ncode, pos, root};
}

/* the body's located switches (state_switch), after its own statements: for each its
   mode, a hidden state #switch<k> (0.5: no value yet; its derivative 0), and two roots
   after the body's `when`s, both its root (rt_x_swgt ...: positive where the comparison
   holds, never 0), rising and falling, whose handlers set the mode to 1 and 0. A comparison in a
   let no output or derivative reads stays a plain comparison; one past the define's SCN_MAX_PORTS
   states or roots is refused (plain, its switch would pass unseen inside a step) */
static void finish_switches(scn_ctx *c, scn_define *d)
{
    uint8_t need[SCN_MAX_LOCALS] = {0}; /* the lets an output or derivative reads (also
                                           through lets) */
    for (uint32_t s = c->sc.nst; s-- > d->st0;) {
        const scn_stmt *st = &c->sc.st[s];
        if (st->kind == SCN_ST_DER || st->kind == SCN_ST_OUT ||
            (st->kind == SCN_ST_LET && need[st->index]))
            for (uint32_t i = st->code0; i < st->code1; i++)
                if (c->sc.code[i].op == SCN_OP_LOC)
                    need[c->sc.code[i].a] = 1;
    }
    for (int16_t at = -1; at < (int16_t)d->nloc && !c->err; at++) {
        if (at < 0 ? !d->sw_over_der : !(d->sw_over[at] && need[at]))
            continue; /* (no comparison past the limit that is read) */
        uint16_t j = at < 0 ? SCN_MAX_LOCALS : (uint16_t)at;
        scn_fail(c, d->sw_over_pos[j], d->sw_over_op[j], "too many comparisons of states",
                 scn_fmt(c, "at most %u in one define's body, counting those in lets (a "
                         "comparison an output or a derivative reads is a located switch)",
                         SCN_MAX_PORTS));
        return;
    }
    for (uint16_t k = 0; k < d->nsw && !c->err; k++) {
        uint32_t a0 = d->sw[k][0], a1 = d->sw[k][1], b1 = d->sw[k][2];
        scn_ins *cmp = &c->sc.code[b1];
        if (d->sw_let[k] >= 0 && !need[d->sw_let[k]])
            continue; /* (a plain comparison: no derivative reads it) */
        if (d->nx >= SCN_MAX_PORTS || d->nr + 2 > SCN_MAX_PORTS) {
            scn_fail(c, d->sw_pos[k], d->sw_op[k], "too many states and roots for a located switch",
                     scn_fmt(c, "at most %u states and %u roots in one define, with a "
                             "state and two roots for each comparison of states",
                             SCN_MAX_PORTS, SCN_MAX_PORTS));
            return;
        }
        /* (a name the language cannot write: the mode is no state a scene refers to) */
        const char *name = scn_fmt(c, "#switch%u", d->nswm + 1u);
        uint16_t q = d->nx++;
        d->x[q] = (scn_var){{name, d->sw_pos[k]}, 0.5};
        cmp->a = (uint16_t)(SCN_SW_BASE + q);
        d->swm[d->nswm][0] = q, d->swm[d->nswm++][1] = d->nr;
        added_stmt(c, SCN_ST_DER, q, 0, d->sw_pos[k], 0, 0, 0, 0, 0);
        for (int dir = 1; dir >= -1 && !c->err; dir -= 2) {
            uint16_t r = d->nr++;
            d->rdir[r] = (int8_t)dir, d->rest[r] = 0;
            added_stmt(c, SCN_ST_ROOT, r, 0, d->sw_pos[k], a0, a1, b1, 0, cmp->op);
            /* (the root is positive where the comparison holds: rising, it holds) */
            added_stmt(c, SCN_ST_EVENT, q, r, d->sw_pos[k], 0, 0, 0, dir > 0, 0);
        }
    }
}

void scn_parse_body(scn_ctx *c, scn_define *d)
{
    c->def = d;
    c->after_when = 0;
    d->st0 = c->sc.nst;
    scn_expect_op(c, "{");
    while (!c->err && !scn_is_op(c, "}") && c->tok.kind != SCN_T_EOF)
        body_stmt(c);
    scn_pos end = c->tok.pos;
    scn_expect_op(c, "}");
    finish_switches(c, d);
    d->st1 = c->sc.nst;
    body_complete(c, d, end);
}
