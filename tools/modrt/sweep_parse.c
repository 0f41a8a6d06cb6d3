/* sweep_parse.c - the campaign language (docs/sweeps.md): statements of words and
 * parenthesised lists ending in ';', `//` comments, like the scene language. Every error
 * is one line "FILE:LINE:COL: error: WHAT near 'TEXT'" and the parse stops at the first. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sweep.h"

typedef enum { T_END, T_WORD, T_NUM, T_STR, T_PUNCT } tok_kind;

typedef struct lexer {
    const char *path, *s; /* the file, its text */
    size_t i;             /* position of the next character */
    int line, col;
    /* the current token */
    tok_kind k;
    char text[SWEEP_PATH];
    double num;
    int tline, tcol;
} lexer;

static char src[SWEEP_TEXT + 1];

static int fail(lexer *L, const char *fmt, ...)
{
    char what[400];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(what, sizeof what, fmt, ap);
    va_end(ap);
    fprintf(stderr, "%s:%d:%d: error: %s near '%s'\n", L->path, L->tline, L->tcol, what,
            L->k == T_END ? "end of file" : L->text);
    return -1;
}

/* fail at an earlier position (line, col) of the statement */
static int fail_at(lexer *L, int line, int col, const char *what, const char *near)
{
    fprintf(stderr, "%s:%d:%d: error: %s near '%s'\n", L->path, line, col, what, near);
    return -1;
}

static void adv(lexer *L)
{
    if (L->s[L->i] == '\n')
        L->line++, L->col = 1;
    else
        L->col++;
    L->i++;
}

static void skip_space(lexer *L)
{
    for (;;) {
        char ch = L->s[L->i];
        if (ch == ' ' || ch == '\t' || ch == '\r' || ch == '\n')
            adv(L);
        else if (ch == '/' && L->s[L->i + 1] == '/')
            while (L->s[L->i] && L->s[L->i] != '\n')
                adv(L);
        else
            return;
    }
}

static int is_word(char ch, int first)
{
    return (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') || ch == '_' ||
           (!first && ((ch >= '0' && ch <= '9') || ch == '.'));
}

/* the next token into L; -1 on a bad character or an unterminated string */
static int next(lexer *L)
{
    skip_space(L);
    L->tline = L->line, L->tcol = L->col;
    size_t n = 0, start = L->i;
    char ch = L->s[L->i];
    L->text[0] = 0;
    if (!ch) {
        L->k = T_END;
        return 0;
    }
    if (ch == '"') {
        adv(L);
        while (L->s[L->i] && L->s[L->i] != '"' && L->s[L->i] != '\n') {
            if (n + 1 < sizeof L->text)
                L->text[n++] = L->s[L->i];
            adv(L);
        }
        L->text[n] = 0;
        L->k = T_STR;
        if (L->s[L->i] != '"')
            return fail(L, "string without its closing quote");
        adv(L);
        if (n + 1 >= sizeof L->text)
            return fail(L, "string longer than %d bytes", SWEEP_PATH - 1);
        return 0;
    }
    if (is_word(ch, 1)) {
        L->k = T_WORD;
        while (is_word(L->s[L->i], 0))
            adv(L);
    } else if ((ch >= '0' && ch <= '9') || ((ch == '.' || ch == '+') && L->s[L->i + 1] >= '0' &&
                                            L->s[L->i + 1] <= '9')) {
        char *end;
        L->k = T_NUM;
        L->num = strtod(L->s + L->i, &end);
        while (L->s + L->i < end)
            adv(L);
    } else {
        L->k = T_PUNCT;
        adv(L);
    }
    n = L->i - start < sizeof L->text - 1 ? L->i - start : sizeof L->text - 1;
    memcpy(L->text, L->s + start, n), L->text[n] = 0;
    if (L->k == T_PUNCT && !strchr("(),;-", ch))
        return fail(L, "unexpected character");
    return 0;
}

static int is_punct(const lexer *L, char ch)
{
    return L->k == T_PUNCT && L->text[0] == ch;
}

static int is_kw(const lexer *L, const char *w)
{
    return L->k == T_WORD && strcmp(L->text, w) == 0;
}

static int expect(lexer *L, char ch)
{
    if (!is_punct(L, ch))
        return fail(L, "expected '%c'", ch);
    return next(L);
}

/* a word or a string into buf (at most n - 1 bytes) */
static int name_tok(lexer *L, char *buf, size_t n, const char *what)
{
    if (L->k != T_WORD && L->k != T_STR)
        return fail(L, "expected %s", what);
    if (strlen(L->text) >= n)
        return fail(L, "%s longer than %zu bytes", what, n - 1);
    strcpy(buf, L->text);
    return next(L);
}

/* "(NAME)" */
static int paren_name(lexer *L, char *buf, size_t n, const char *what)
{
    if (expect(L, '(') || name_tok(L, buf, n, what))
        return -1;
    return expect(L, ')');
}

/* a number, optionally negative, with an optional time unit (s, ms, us) when time */
static int number(lexer *L, double *v, int time)
{
    int neg = 0;
    if (is_punct(L, '-')) {
        neg = 1;
        if (next(L))
            return -1;
    }
    if (L->k != T_NUM || !isfinite(L->num))
        return fail(L, "expected a finite number");
    *v = neg ? -L->num : L->num;
    if (next(L))
        return -1;
    if (time && L->k == T_WORD) {
        double scale = is_kw(L, "s") ? 1 : is_kw(L, "ms") ? 1e-3 : is_kw(L, "us") ? 1e-6 : 0;
        if (scale == 0)
            return fail(L, "expected a time unit (s, ms, us)");
        *v *= scale;
        return next(L);
    }
    return 0;
}

/* "(A, B, ...)" of exactly n numbers */
static int numbers(lexer *L, double *v, int n, int time)
{
    if (expect(L, '('))
        return -1;
    for (int i = 0; i < n; i++)
        if ((i > 0 && expect(L, ',')) || number(L, &v[i], time))
            return -1;
    return expect(L, ')');
}

static int strdup_arena(lexer *L, sweep_campaign *c, const char *s, uint32_t *off)
{
    size_t n = strlen(s) + 1;
    if (c->narena + n > SWEEP_ARENA)
        return fail(L, "listed names longer than %d bytes in all (SWEEP_ARENA)", SWEEP_ARENA);
    memcpy(c->arena + c->narena, s, n);
    *off = c->narena;
    c->narena += (uint32_t)n;
    return 0;
}

/* "(v, v, ...)" into the pools: numbers (time: with units) or names */
static int value_list(lexer *L, sweep_campaign *c, sweep_dim *d, int strings, int time)
{
    d->first = c->nvalues, d->n = 0;
    if (expect(L, '('))
        return -1;
    do {
        if (d->n > 0 && next(L))
            return -1;
        if (c->nvalues >= SWEEP_MAX_VALUES)
            return fail(L, "more than %d listed values (SWEEP_MAX_VALUES)", SWEEP_MAX_VALUES);
        if (strings) {
            char buf[SWEEP_PATH];
            if (name_tok(L, buf, sizeof buf, d->kind == SWEEP_DIM_REPLAY  ? "a log path"
                                             : d->kind == SWEEP_DIM_SCENE ? "a scene file"
                                                                          : "a method name") ||
                strdup_arena(L, c, buf, &c->str[c->nvalues]))
                return -1;
        } else if (number(L, &c->num[c->nvalues], time)) {
            return -1;
        } else if (time && !(c->num[c->nvalues] > 0)) {
            return fail(L, "a step must be > 0");
        }
        c->nvalues++, d->n++;
    } while (is_punct(L, ','));
    return expect(L, ')');
}

static int new_dim(lexer *L, sweep_campaign *c, sweep_dim **d)
{
    if (c->ndims >= SWEEP_MAX_DIMS)
        return fail(L, "more than %d grid dimensions (SWEEP_MAX_DIMS)", SWEEP_MAX_DIMS);
    *d = &c->dims[c->ndims++];
    memset(*d, 0, sizeof **d);
    return 0;
}

/* grid scene values ("a.scn", ...): a grid dimension of scene files, in place of scene */
static int st_grid_scene(lexer *L, sweep_campaign *c)
{
    sweep_dim *d = NULL;
    for (int i = 0; i < c->ndims; i++)
        if (c->dims[i].kind == SWEEP_DIM_SCENE)
            return fail(L, "a second grid of scenes (put every scene in one)");
    if (next(L) || new_dim(L, c, &d))
        return -1;
    d->kind = SWEEP_DIM_SCENE;
    if (!is_kw(L, "values"))
        return fail(L, "expected values (\"FILE.scn\", ...)");
    if (next(L) || value_list(L, c, d, 1, 0))
        return -1;
    for (uint32_t j = 0; j < d->n; j++) {
        const char *s = c->arena + c->str[d->first + j];
        size_t n = strlen(s);
        if (n <= 4 || strcmp(s + n - 4, ".scn") != 0)
            return fail(L, "a grid of scenes lists scene files (FILE.scn), got '%s'", s);
    }
    return 0;
}

/* grid (B.p) values (...) | range (lo, hi, n); grid method|step (SET) values (...);
   grid scene values (...) */
static int st_grid(lexer *L, sweep_campaign *c)
{
    sweep_dim *d = NULL;
    if (is_kw(L, "scene"))
        return st_grid_scene(L, c);
    if (new_dim(L, c, &d))
        return -1;
    d->kind = is_kw(L, "method") ? SWEEP_DIM_METHOD : is_kw(L, "step") ? SWEEP_DIM_STEP
                                                                        : SWEEP_DIM_PARAM;
    if (d->kind != SWEEP_DIM_PARAM && next(L))
        return -1;
    d->line = L->tline, d->col = L->tcol + 1; /* the name after '(' */
    if (paren_name(L, d->name, sizeof d->name, d->kind == SWEEP_DIM_PARAM ? "Block.param"
                                                                           : "a set name"))
        return -1;
    if (d->kind == SWEEP_DIM_PARAM && !strchr(d->name, '.'))
        return fail(L, "a grid parameter is Block.param, got '%s'", d->name);
    if (d->kind == SWEEP_DIM_PARAM && is_kw(L, "range")) {
        double v[3];
        int line = L->tline, col = L->tcol;
        if (next(L) || numbers(L, v, 3, 0))
            return -1;
        if (!(v[2] >= 2 && v[2] <= 1e9 && v[2] == sweep_floor(v[2])))
            return fail_at(L, line, col, "range (lo, hi, n) needs a whole n >= 2", "range");
        d->is_range = 1, d->lo = v[0], d->hi = v[1], d->n = (uint32_t)v[2];
        return 0;
    }
    if (!is_kw(L, "values"))
        return fail(L, d->kind == SWEEP_DIM_PARAM ? "expected values (...) or range (lo, hi, n)"
                                                  : "expected values (...)");
    if (next(L))
        return -1;
    return value_list(L, c, d, d->kind == SWEEP_DIM_METHOD, d->kind == SWEEP_DIM_STEP);
}

#define MASS_STEPS 2000 /* Simpson intervals of the check below: far finer than needed */

/* P(lo < X < hi) of a normal (mean m, sd s), by Simpson's rule over the bounds within
   ten sd: the bounds must hold some of it for rejection to find a value */
static double normal_mass(double m, double s, double lo, double hi)
{
    double a = lo > m - 10 * s ? lo : m - 10 * s, b = hi < m + 10 * s ? hi : m + 10 * s;
    if (!(a < b))
        return 0;
    double h = (b - a) / MASS_STEPS, sum = 0;
    for (int i = 0; i <= MASS_STEPS; i++) {
        double z = (a + i * h - m) / s, w = i == 0 || i == MASS_STEPS ? 1 : i % 2 ? 4 : 2;
        sum += w * sweep_exp(-0.5 * z * z);
    }
    return sum * h / 3 / (s * 2.5066282746310002); /* sqrt(2 pi) */
}

/* draw (B.p) uniform (lo, hi) | loguniform (lo, hi) | normal (m, sd) within (lo, hi) */
static int st_draw(lexer *L, sweep_campaign *c)
{
    if (c->nvars >= SWEEP_MAX_VARS)
        return fail(L, "more than %d drawn variables (SWEEP_MAX_VARS)", SWEEP_MAX_VARS);
    sweep_var *v = &c->vars[c->nvars];
    memset(v, 0, sizeof *v);
    v->line = L->tline, v->col = L->tcol + 1;
    if (paren_name(L, v->name, sizeof v->name, "Block.param"))
        return -1;
    if (!strchr(v->name, '.'))
        return fail(L, "a drawn variable is Block.param, got '%s'", v->name);
    for (int i = 0; i < c->nvars; i++)
        if (strcmp(c->vars[i].name, v->name) == 0)
            return fail(L, "'%s' is drawn twice", v->name);
    double p[2];
    int uni = is_kw(L, "uniform"), logu = is_kw(L, "loguniform"), nor = is_kw(L, "normal");
    if (!uni && !logu && !nor)
        return fail(L, "expected uniform, loguniform or normal");
    if (next(L) || numbers(L, p, 2, 0))
        return -1;
    v->dist = uni ? SWEEP_UNIFORM : logu ? SWEEP_LOGUNIFORM : SWEEP_NORMAL;
    v->a = v->lo = p[0], v->b = v->hi = p[1];
    int line = L->tline, col = L->tcol;
    if (nor) {
        if (!is_kw(L, "within"))
            return fail(L, "a normal draw needs its bounds: within (lo, hi)");
        if (next(L) || numbers(L, p, 2, 0))
            return -1;
        v->lo = p[0], v->hi = p[1];
        if (!(v->b > 0))
            return fail(L, "the standard deviation must be > 0");
    }
    if (!(v->lo < v->hi))
        return fail(L, "the bounds must have lo < hi");
    if (logu && !(v->lo > 0))
        return fail(L, "loguniform bounds must be > 0");
    if (nor && !(normal_mass(v->a, v->b, v->lo, v->hi) >= SWEEP_NORMAL_MASS)) {
        char what[96];
        snprintf(what, sizeof what, "the bounds hold less than %g of the normal's probability",
                 SWEEP_NORMAL_MASS);
        return fail_at(L, line, col, what, "within");
    }
    uint64_t h = 1469598103934665603ull; /* FNV-1a of the name */
    for (const char *s = v->name; *s; s++)
        h = (h ^ (uint8_t)*s) * 1099511628211ull;
    v->key = h;
    c->nvars++;
    return 0;
}

/* SIG [- SIG] */
static int signal_expr(lexer *L, sweep_metric *m)
{
    if (L->k != T_WORD || !strchr(L->text, '.'))
        return fail(L, "expected a recorded signal Block.signal");
    m->line[0] = L->tline, m->col[0] = L->tcol;
    if (name_tok(L, m->sig[0], sizeof m->sig[0], "a signal"))
        return -1;
    if (is_punct(L, '-')) {
        if (next(L))
            return -1;
        if (L->k != T_WORD || !strchr(L->text, '.'))
            return fail(L, "expected the recorded signal Block.signal to subtract");
        m->line[1] = L->tline, m->col[1] = L->tcol;
        return name_tok(L, m->sig[1], sizeof m->sig[1], "a signal");
    }
    return 0;
}

static const char *const metric_kw[] = {"max", "min", "maxabs", "final", "rms", "mean",
                                        "settle", "overshoot", "error", NULL};

/* metric (NAME) KIND (SIG [- SIG]) [band (lo, hi) | to (V)] [from (T)];
   metric (NAME) error against ("REF.csv") [from (T)] */
static int st_metric(lexer *L, sweep_campaign *c)
{
    if (c->nmetrics >= SWEEP_MAX_METRICS)
        return fail(L, "more than %d metrics (SWEEP_MAX_METRICS)", SWEEP_MAX_METRICS);
    sweep_metric *m = &c->metrics[c->nmetrics];
    memset(m, 0, sizeof *m);
    if (paren_name(L, m->name, sizeof m->name, "a metric name"))
        return -1;
    for (int i = 0; i < c->nmetrics; i++)
        if (strcmp(c->metrics[i].name, m->name) == 0)
            return fail(L, "a second metric named '%s'", m->name);
    int k = 0;
    while (metric_kw[k] && !is_kw(L, metric_kw[k]))
        k++;
    if (!metric_kw[k])
        return fail(L, "expected max, min, maxabs, final, rms, mean, settle, overshoot or error");
    m->kind = (uint8_t)k;
    if (next(L))
        return -1;
    if (k == SWEEP_M_ERROR) {
        char path[SWEEP_PATH];
        if (!is_kw(L, "against"))
            return fail(L, "error needs its reference: against (\"REF.csv\")");
        m->line[0] = L->tline, m->col[0] = L->tcol;
        if (next(L) || paren_name(L, path, sizeof path, "a reference table (CSV)") ||
            strdup_arena(L, c, path, &m->ref))
            return -1;
    } else if (expect(L, '(') || signal_expr(L, m) || expect(L, ')')) {
        return -1;
    }
    if (k == SWEEP_M_SETTLE) {
        if (!is_kw(L, "band"))
            return fail(L, "settle needs its band: band (lo, hi)");
        if (next(L) || numbers(L, m->p, 2, 0))
            return -1;
        if (!(m->p[0] < m->p[1]))
            return fail(L, "the band must have lo < hi");
    } else if (k == SWEEP_M_OVERSHOOT) {
        if (!is_kw(L, "to"))
            return fail(L, "overshoot needs its target: to (V)");
        if (next(L) || numbers(L, m->p, 1, 0))
            return -1;
    }
    if (is_kw(L, "from") && (next(L) || numbers(L, &m->from, 1, 1)))
        return -1;
    c->nmetrics++;
    return 0;
}

/* replay ("a.mrl", ...): a grid dimension of logs */
static int st_replay(lexer *L, sweep_campaign *c)
{
    sweep_dim *d = NULL;
    for (int i = 0; i < c->ndims; i++)
        if (c->dims[i].kind == SWEEP_DIM_REPLAY)
            return fail(L, "a second replay list (put every log in one)");
    if (new_dim(L, c, &d))
        return -1;
    d->kind = SWEEP_DIM_REPLAY;
    return value_list(L, c, d, 1, 0);
}

static int whole(lexer *L, uint64_t *v, double max, const char *what)
{
    double x;
    if (expect(L, '(') || number(L, &x, 0))
        return -1;
    if (!(x >= 0 && x <= max && x == sweep_floor(x)))
        return fail(L, "%s must be a whole number in [0, %.0f]", what, max);
    *v = (uint64_t)x;
    return expect(L, ')');
}

static int statement(lexer *L, sweep_campaign *c)
{
    if (L->k != T_WORD)
        return fail(L, "expected a statement (campaign, scene, seed, draws, end time, "
                       "timeout, grid, draw, replay, metric)");
    char kw[SWEEP_NAME];
    int line = L->tline, col = L->tcol;
    snprintf(kw, sizeof kw, "%.*s", SWEEP_NAME - 1, L->text);
    if (next(L))
        return -1;
    if (!strcmp(kw, "campaign"))
        return paren_name(L, c->name, sizeof c->name, "a campaign name");
    if (!strcmp(kw, "scene"))
        return paren_name(L, c->scene, sizeof c->scene, "a scene name or file");
    if (!strcmp(kw, "seed"))
        return whole(L, &c->seed, 9007199254740992.0, "the seed");
    if (!strcmp(kw, "draws")) {
        if (whole(L, &c->draws, (double)SWEEP_MAX_RUNS, "draws"))
            return -1;
        return c->draws < 1 ? fail(L, "draws must be >= 1") : 0;
    }
    if (!strcmp(kw, "end")) {
        if (!is_kw(L, "time"))
            return fail(L, "expected end time (S)");
        if (next(L) || numbers(L, &c->t_end, 1, 1))
            return -1;
        return c->t_end >= 0 ? 0 : fail(L, "the end time must be >= 0");
    }
    if (!strcmp(kw, "timeout")) {
        if (numbers(L, &c->timeout, 1, 1))
            return -1;
        return c->timeout > 0 && c->timeout <= 86400 ? 0
                                                      : fail(L, "timeout must be in (0, 1 day]");
    }
    if (!strcmp(kw, "grid"))
        return st_grid(L, c);
    if (!strcmp(kw, "draw"))
        return st_draw(L, c);
    if (!strcmp(kw, "replay"))
        return st_replay(L, c);
    if (!strcmp(kw, "metric"))
        return st_metric(L, c);
    return fail_at(L, line, col, "unknown statement", kw);
}

/* the product of the grid sizes and the draws, within SWEEP_MAX_RUNS */
static int count_runs(lexer *L, sweep_campaign *c)
{
    uint64_t n = c->draws;
    for (int i = 0; i < c->ndims; i++) {
        if (c->dims[i].n == 0 || n > SWEEP_MAX_RUNS / c->dims[i].n)
            return fail(L, "the campaign has more than %llu runs (SWEEP_MAX_RUNS)",
                        (unsigned long long)SWEEP_MAX_RUNS);
        n *= c->dims[i].n;
    }
    c->nruns = n;
    return 0;
}

static int read_text(const char *path)
{
    FILE *f = fopen(path, "r");
    if (!f) {
        fprintf(stderr, "%s: error: cannot read the campaign file\n", path);
        return -1;
    }
    size_t n = fread(src, 1, SWEEP_TEXT + 1, f);
    int err = ferror(f);
    fclose(f);
    if (err || n > SWEEP_TEXT) {
        fprintf(stderr, "%s: error: %s\n", path, err ? "cannot read the campaign file"
                                                    : "longer than SWEEP_TEXT bytes");
        return -1;
    }
    src[n] = 0;
    if (strlen(src) != n) {
        fprintf(stderr, "%s: error: a NUL byte: not a text file\n", path);
        return -1;
    }
    return 0;
}

int sweep_parse(const char *path, sweep_campaign *c)
{
    memset(c, 0, sizeof *c);
    c->draws = 1, c->t_end = -1, c->timeout = SWEEP_TIMEOUT_S;
    if (strlen(path) >= sizeof c->path || read_text(path))
        return strlen(path) >= sizeof c->path ? fprintf(stderr, "campaign path too long\n"), -1
                                              : -1;
    strcpy(c->path, path);
    c->hash = 1469598103934665603ull; /* FNV-1a of the text */
    for (const char *s = src; *s; s++)
        c->hash = (c->hash ^ (uint8_t)*s) * 1099511628211ull;
    const char *slash = strrchr(path, '/');
    snprintf(c->dir, sizeof c->dir, "%.*s", slash ? (int)(slash - path) : 1,
             slash ? path : ".");
    lexer L = {path, src, 0, 1, 1, T_END, "", 0, 1, 1};
    int draws_set = 0;
    if (next(&L))
        return -1;
    while (L.k != T_END) {
        draws_set |= is_kw(&L, "draws");
        if (statement(&L, c) || expect(&L, ';'))
            return -1;
    }
    int replays = 0, scenes = 0;
    for (int i = 0; i < c->ndims; i++)
        replays |= c->dims[i].kind == SWEEP_DIM_REPLAY, scenes |= c->dims[i].kind == SWEEP_DIM_SCENE;
    if (!c->scene[0] && !replays && !scenes)
        return fail(&L, "the campaign names no scene: scene (NAME or \"FILE.scn\");");
    if (c->scene[0] && replays)
        return fail(&L, "a replay log names its scene: leave out scene (...) or replay (...)");
    if ((c->scene[0] || replays) && scenes)
        return fail(&L, "a grid of scenes names the scenes: leave out scene (...) and replay (...)");
    if (c->nvars > 0 && !draws_set)
        return fail(&L, "variables are drawn but the campaign says not how often: draws (N);");
    if (!c->name[0]) {
        const char *b = slash ? slash + 1 : path;
        snprintf(c->name, sizeof c->name, "%.*s", (int)strcspn(b, "."), b);
    }
    return count_runs(&L, c);
}
