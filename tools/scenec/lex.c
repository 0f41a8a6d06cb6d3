/* lex.c - sources and tokens of the scene language: the arena every part allocates from,
 * the one error report (file:line:col: error: what near 'text'; expected what), the main
 * file and its includes, and the tokenizer with comments, strings and numbers. */
#define _XOPEN_SOURCE 700
#include "scn.h"

#include <errno.h>
#include <limits.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

/* ------------------------------------------------------------------ arena */

struct scn_chunk {
    scn_chunk *next;
    size_t used, cap;           /* bytes of data */
    max_align_t data[];
};

#define CHUNK_BYTES 65536 /* one arena chunk; larger requests get their own */

void *scn_alloc(scn_ctx *c, size_t n)
{
    size_t a = sizeof(max_align_t);
    n = n ? (n + a - 1) / a * a : a;
    scn_chunk *k = c->chunks;
    if (!k || k->cap - k->used < n) {
        size_t cap = n > CHUNK_BYTES ? n : CHUNK_BYTES;
        scn_chunk *fresh = malloc(sizeof *fresh + cap);
        if (!fresh) { /* a host tool with bounded inputs: nothing sensible is left */
            fputs("scenec: out of memory\n", stderr);
            abort();
        }
        fresh->cap = cap, fresh->used = 0;
        /* a big one-off request goes behind the current chunk, which keeps serving */
        if (k && cap > CHUNK_BYTES) {
            fresh->next = k->next, k->next = fresh;
        } else {
            fresh->next = k, c->chunks = fresh;
        }
        k = fresh;
    }
    void *p = (char *)k->data + k->used;
    k->used += n;
    memset(p, 0, n);
    return p;
}

char *scn_strndup(scn_ctx *c, const char *s, size_t n)
{
    char *d = scn_alloc(c, n + 1);
    memcpy(d, s, n);
    d[n] = 0;
    return d;
}

char *scn_fmt(scn_ctx *c, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(NULL, 0, fmt, ap);
    va_end(ap);
    char *d = scn_alloc(c, n > 0 ? (size_t)n + 1 : 1);
    va_start(ap, fmt);
    vsnprintf(d, n > 0 ? (size_t)n + 1 : 1, fmt, ap);
    va_end(ap);
    return d;
}

char *scn_limit(scn_ctx *c, rt_limit lim)
{
    char text[RT_ERR_LEN];
    return scn_fmt(c, "fewer: %s, the host CLI's limit (a per-scene build, make image, sizes "
                      "it from the scene)", rt_limit_text(text, sizeof text, lim));
}

char *scn_list(scn_ctx *c, const char *const *names, size_t n, size_t max)
{
    char *out = scn_fmt(c, "%s", n ? "" : "(none)");
    for (size_t i = 0; i < n && i < max; i++)
        out = scn_fmt(c, "%s%s%s", out, i ? ", " : "", names[i]);
    return n > max ? scn_fmt(c, "%s, ...", out) : out;
}

scn_ctx *scn_new(void)
{
    return calloc(1, sizeof(scn_ctx));
}

void scn_free(scn_ctx *c)
{
    if (!c)
        return;
    for (scn_chunk *k = c->chunks, *next; k; k = next)
        next = k->next, free(k);
    free(c);
}

/* ------------------------------------------------------------------ errors */

const char *scn_path(const scn_ctx *c, scn_pos pos)
{
    return pos.file < c->nfiles ? c->files[pos.file].path : "?";
}

#define NEAR_MAX 40 /* characters of the text a message quotes */

static int printable(char ch) { return ch >= 32 && ch < 127; }

/* text for a message: at most NEAR_MAX characters, a byte that is not printable ASCII
   written as \xHH (a NUL byte, a tab, a UTF-8 byte: the user sees which one it is) */
static const char *sanitize(scn_ctx *c, const char *s, size_t n)
{
    char *d = scn_alloc(c, NEAR_MAX + 4);
    size_t i = 0, m = 0;
    for (; i < n; i++) {
        size_t w = printable(s[i]) ? 1 : 4;
        if (m + w > NEAR_MAX)
            break;
        if (w == 1)
            d[m] = s[i];
        else
            snprintf(d + m, 5, "\\x%02x", (unsigned)(unsigned char)s[i]);
        m += w;
    }
    if (i < n)
        memcpy(d + m, "...", 3);
    return d;
}

/* already what sanitize makes of it: printable, within NEAR_MAX (and a "..." it added) */
static int sanitized(const char *s)
{
    size_t n = strlen(s);
    for (size_t i = 0; i < n; i++)
        if (!printable(s[i]))
            return 0;
    return n <= NEAR_MAX || (n <= NEAR_MAX + 3 && strcmp(s + n - 3, "...") == 0);
}

const char *scn_near(scn_ctx *c, const scn_tok *t)
{
    return t->kind == SCN_T_EOF ? "end of file" : sanitize(c, t->raw, t->rawlen);
}

void scn_fail(scn_ctx *c, scn_pos pos, const char *near, const char *what,
              const char *expected)
{
    if (c->err)
        return;
    c->err = 1;
    c->err_pos = pos;
    snprintf(c->msg, SCN_MSG_LEN, "%s:%u:%u: error: %s near '%s'; expected %s",
             scn_path(c, pos), (unsigned)pos.line, (unsigned)pos.col, what,
             sanitized(near) ? near : sanitize(c, near, strlen(near)), expected);
}

void scn_fail_tok(scn_ctx *c, const char *what, const char *expected)
{
    scn_fail(c, c->tok.pos, scn_near(c, &c->tok), what, expected);
}

void scn_keep_error(scn_ctx *c)
{
    if (!c->err)
        return;
    if (c->nkept < SCN_MAX_ERRORS) {
        memcpy(c->kept[c->nkept], c->msg, SCN_MSG_LEN);
        c->kept[c->nkept][SCN_MSG_LEN - 1] = 0;
        c->kept_pos[c->nkept++] = c->err_pos;
    } else {
        c->nlost++;
    }
    c->err = 0, c->msg[0] = 0;
}

unsigned scn_error_count(const scn_ctx *c)
{
    return (unsigned)c->nkept + c->nlost + (c->err != 0);
}

static int before(scn_pos a, scn_pos b)
{
    return a.file != b.file ? a.file < b.file : a.line != b.line ? a.line < b.line : a.col < b.col;
}

int scn_report_errors(scn_ctx *c)
{
    scn_keep_error(c);
    if (c->nkept == 0)
        return 0;
    uint16_t order[SCN_MAX_ERRORS];
    for (uint16_t i = 0; i < c->nkept; i++) { /* stable insertion sort by position */
        uint16_t j = i;
        for (; j > 0 && before(c->kept_pos[i], c->kept_pos[order[j - 1]]); j--)
            order[j] = order[j - 1];
        order[j] = i;
    }
    size_t n = 0;
    for (uint16_t i = 0; i < c->nkept; i++)
        n += (size_t)snprintf(c->msg + n, sizeof c->msg - n, "%s%s", i ? "\n" : "",
                              c->kept[order[i]]);
    if (c->nlost)
        snprintf(c->msg + n, sizeof c->msg - n, "\n(%u more errors not shown)", (unsigned)c->nlost);
    c->err = 1;
    return -1;
}

/* ------------------------------------------------------------------ files */

/* what path is when it is not a regular file (opening a FIFO or a terminal to read it
   would wait for a writer forever), or NULL */
static const char *not_regular(const char *path)
{
    struct stat st;
    if (stat(path, &st) != 0 || S_ISREG(st.st_mode))
        return NULL; /* a missing file is reported by fopen, with errno */
    return S_ISDIR(st.st_mode)    ? "a directory"
           : S_ISFIFO(st.st_mode) ? "a FIFO"
           : S_ISCHR(st.st_mode)  ? "a character device"
           : S_ISBLK(st.st_mode)  ? "a block device"
           : S_ISSOCK(st.st_mode) ? "a socket"
                                  : "not a regular file";
}

/* reads a whole file into the arena; -1 if it cannot (errno), -2 if it is too large, -3
   if it is not a regular file (*why says what it is) */
static int read_file(scn_ctx *c, const char *path, const char **text, size_t *len,
                     const char **why)
{
    if ((*why = not_regular(path)) != NULL)
        return -3;
    FILE *f = fopen(path, "rb");
    if (!f)
        return -1;
    char *buf = malloc(SCN_MAX_SRC + 1);
    size_t n = buf ? fread(buf, 1, SCN_MAX_SRC + 1, f) : 0;
    int bad = !buf || ferror(f);
    fclose(f);
    if (bad || n > SCN_MAX_SRC) {
        free(buf);
        return bad ? -1 : -2;
    }
    *text = scn_strndup(c, buf, n);
    *len = n;
    free(buf);
    return 0;
}

/* registers a source and starts reading it at its first character */
static int add_file(scn_ctx *c, const char *path, const char *real, const char *text,
                    size_t len)
{
    scn_file *f = &c->files[c->nfiles];
    f->path = path, f->real = real, f->text = text, f->len = len, f->generated = 0;
    scn_lexer *l = &c->lx[c->depth];
    l->file = c->nfiles++, l->off = 0, l->line = 1, l->col = 1;
    return 0;
}

static const char *resolve(scn_ctx *c, const char *path)
{
    char *r = realpath(path, NULL);
    const char *out = scn_strndup(c, r ? r : path, strlen(r ? r : path));
    free(r);
    return out;
}

int scn_open_main(scn_ctx *c, const char *path, const char *text, size_t len)
{
    scn_pos at = {0, 1, 1};
    c->depth = 0;
    if (!text) {
        errno = 0;
        const char *why;
        int r = read_file(c, path, &text, &len, &why);
        if (r == -1 || r == -3) { /* no position in a file never read: the reason */
            c->err = 1;
            snprintf(c->msg, SCN_MSG_LEN, "%s: error: cannot read the scene file: %s", path,
                     r == -3 ? scn_fmt(c, "%s, not a regular file", why)
                     : errno ? strerror(errno) : "read error");
            return -1;
        }
        if (r == -2) {
            c->files[0].path = path, c->nfiles = 1; /* for the message */
            scn_fail(c, at, path, "scene file too large", scn_fmt(c, "at most %u bytes", SCN_MAX_SRC));
            return -1;
        }
    } else if (len > SCN_MAX_SRC) {
        c->files[0].path = path, c->nfiles = 1;
        scn_fail(c, at, path, "scene file too large", scn_fmt(c, "at most %u bytes", SCN_MAX_SRC));
        return -1;
    }
    add_file(c, path, c->sandbox ? path : resolve(c, path), text, len);
    scn_next(c);
    return c->err ? -1 : 0;
}

/* the includer's directory joined with name (name as is when absolute) */
static const char *beside(scn_ctx *c, const char *includer, const char *name)
{
    const char *slash = strrchr(includer, '/');
    if (name[0] == '/' || !slash)
        return name;
    return scn_fmt(c, "%.*s/%s", (int)(slash - includer), includer, name);
}

/* the first existing file among: beside the includer, then the -I directories (looked
   at, not opened: opening a FIFO would block) */
static const char *find_include(scn_ctx *c, const char *name)
{
    const char *p = beside(c, c->files[c->lx[c->depth].file].path, name);
    struct stat st;
    for (int i = -1; i < (int)c->nincdirs; i++) {
        if (i >= 0 && name[0] != '/')
            p = scn_fmt(c, "%s/%s", c->incdirs[i], name);
        if (stat(p, &st) == 0)
            return p;
    }
    return NULL;
}

int scn_push_include(scn_ctx *c, const char *name, scn_pos pos)
{
    const char *near = scn_fmt(c, "\"%s\"", name);
    if (c->depth >= SCN_MAX_DEPTH || c->nfiles >= SCN_MAX_FILES) {
        scn_fail(c, pos, near, "includes nested too deeply or too many files",
                 scn_fmt(c, "at most %u levels and %u files", SCN_MAX_DEPTH, SCN_MAX_FILES));
        return -1;
    }
    const char *path = c->sandbox || !name[0] ? NULL : find_include(c, name);
    if (!path) {
        scn_fail(c, pos, near, "include file not found",
                 "a file beside the including file or in a -I directory");
        return -1;
    }
    const char *real = resolve(c, path);
    for (int d = 0; d <= c->depth; d++)
        if (strcmp(c->files[c->lx[d].file].real, real) == 0) {
            scn_fail(c, pos, near, "recursive include",
                     scn_fmt(c, "a file not already open in the chain of includes (%s is)",
                             c->files[c->lx[d].file].path));
            return -1;
        }
    const char *text, *why;
    size_t len;
    int r = read_file(c, path, &text, &len, &why);
    if (r == -3) {
        scn_fail(c, pos, near, scn_fmt(c, "include is %s (%s), not a regular file", why, path),
                 "a regular file");
        return -1;
    }
    if (r < 0) {
        scn_fail(c, pos, near, r == -2 ? "include file too large" : "cannot read include file",
                 r == -2 ? scn_fmt(c, "at most %u bytes", SCN_MAX_SRC) : "a readable file");
        return -1;
    }
    c->depth++;
    add_file(c, path, real, text, len);
    scn_next(c);
    return c->err ? -1 : 0;
}

int scn_push_text(scn_ctx *c, const char *label, const char *text, scn_pos pos)
{
    if (c->depth >= SCN_MAX_DEPTH || c->nfiles >= SCN_MAX_FILES) {
        scn_fail(c, pos, label, "includes nested too deeply or too many files",
                 scn_fmt(c, "at most %u levels and %u files", SCN_MAX_DEPTH, SCN_MAX_FILES));
        return -1;
    }
    c->depth++;
    add_file(c, label, label, text, strlen(text));
    c->files[c->nfiles - 1].generated = 1;
    scn_next(c);
    return c->err ? -1 : 0;
}

void scn_pop_include(scn_ctx *c)
{
    if (c->depth > 0)
        c->depth--;
    scn_next(c);
}

/* ------------------------------------------------------------------ characters */

static int at(const scn_ctx *c, size_t k)
{
    const scn_lexer *l = &c->lx[c->depth];
    const scn_file *f = &c->files[l->file];
    return l->off + k < f->len ? (unsigned char)f->text[l->off + k] : -1;
}

static void adv(scn_ctx *c)
{
    scn_lexer *l = &c->lx[c->depth];
    if (at(c, 0) == '\n')
        l->line++, l->col = 1;
    else
        l->col++;
    l->off++;
}

static scn_pos here(const scn_ctx *c)
{
    const scn_lexer *l = &c->lx[c->depth];
    return (scn_pos){l->file, l->line, l->col};
}

static const char *cur(const scn_ctx *c)
{
    const scn_lexer *l = &c->lx[c->depth];
    return c->files[l->file].text + l->off;
}

static int is_alpha(int ch)
{
    return (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') || ch == '_';
}
static int is_digit(int ch) { return ch >= '0' && ch <= '9'; }

/* blanks and comments; an unterminated block comment is an error at its start */
static void skip_blank(scn_ctx *c)
{
    for (;;) {
        int ch = at(c, 0);
        if (ch == ' ' || ch == '\t' || ch == '\n' || ch == '\r' || ch == '\f' || ch == '\v') {
            adv(c);
        } else if (ch == '/' && at(c, 1) == '/') {
            while (at(c, 0) >= 0 && at(c, 0) != '\n')
                adv(c);
        } else if (ch == '/' && at(c, 1) == '*') {
            scn_pos start = here(c);
            adv(c), adv(c);
            while (at(c, 0) >= 0 && !(at(c, 0) == '*' && at(c, 1) == '/'))
                adv(c);
            if (at(c, 0) < 0) {
                scn_fail(c, start, "/*", "unterminated comment", "'*/' before the end of the file");
                return;
            }
            adv(c), adv(c);
        } else {
            return;
        }
    }
}

/* ------------------------------------------------------------------ tokens */

static void lex_name(scn_ctx *c, scn_tok *t)
{
    while (is_alpha(at(c, 0)) || is_digit(at(c, 0)))
        adv(c);
    t->kind = SCN_T_ID;
    t->rawlen = (uint32_t)(cur(c) - t->raw);
    t->s = scn_strndup(c, t->raw, t->rawlen);
    if (t->rawlen > SCN_MAX_NAME)
        scn_fail(c, t->pos, t->s, "name too long",
                 scn_fmt(c, "at most %u characters", SCN_MAX_NAME));
}

/* digits [. digits] [e [+-] digits], not followed by a letter, digit or '.' */
static void lex_number(scn_ctx *c, scn_tok *t)
{
    int bad = 0;
    while (is_digit(at(c, 0)))
        adv(c);
    if (at(c, 0) == '.') {
        adv(c);
        while (is_digit(at(c, 0)))
            adv(c);
    }
    if (at(c, 0) == 'e' || at(c, 0) == 'E') {
        int k = (at(c, 1) == '+' || at(c, 1) == '-') ? 2 : 1;
        if (is_digit(at(c, k))) {
            for (int i = 0; i < k; i++)
                adv(c);
            while (is_digit(at(c, 0)))
                adv(c);
        }
    }
    while (is_alpha(at(c, 0)) || is_digit(at(c, 0)) || at(c, 0) == '.')
        adv(c), bad = 1;
    t->kind = SCN_T_NUM;
    t->rawlen = (uint32_t)(cur(c) - t->raw);
    const char *text = scn_strndup(c, t->raw, t->rawlen);
    if (bad || t->rawlen > 400) {
        scn_fail(c, t->pos, text, "bad number",
                 "a decimal number such as 2, 0.5 or 1e-3 (a unit follows after a space)");
        return;
    }
    errno = 0;
    t->num = strtod(text, NULL);
    if (errno == ERANGE && (t->num > 1 || t->num < -1))
        scn_fail(c, t->pos, text, "number out of range", "a finite double");
    else if (errno == ERANGE) /* 1e-999 would silently be 0 (or lose its digits) */
        scn_fail(c, t->pos, text, "number too small: it underflows",
                 "0, or a magnitude of at least 2.2250738585072014e-308 (the smallest normal "
                 "double)");
}

/* "text" with the escapes \" and \\ */
static void lex_string(scn_ctx *c, scn_tok *t)
{
    adv(c);
    size_t n = 0;
    char *buf = scn_alloc(c, 256);
    for (;;) {
        int ch = at(c, 0);
        if (ch < 0 || ch == '\n') {
            scn_fail(c, t->pos, "\"", "unterminated string", "a closing '\"' on the same line");
            return;
        }
        if ((ch < 32 && ch != '\t') || ch == 127) { /* a NUL byte would end it early */
            scn_fail(c, here(c), sanitize(c, cur(c), 1), "control character in string",
                     "printable text (a tab is allowed)");
            return;
        }
        adv(c);
        if (ch == '"')
            break;
        if (ch == '\\') {
            ch = at(c, 0);
            if (ch != '"' && ch != '\\') {
                scn_fail(c, here(c), "\\", "bad escape in string", "\\\" or \\\\");
                return;
            }
            adv(c);
        }
        if (n >= 255) {
            scn_fail(c, t->pos, "\"", "string too long", "at most 255 characters");
            return;
        }
        buf[n++] = (char)ch;
    }
    t->kind = SCN_T_STR;
    t->s = buf;
    t->rawlen = (uint32_t)(cur(c) - t->raw);
}

static void lex_op(scn_ctx *c, scn_tok *t)
{
    static const char *const two[] = {"<=", ">=", "==", "!=", "&&", "||"};
    static const char one[] = "(){}[],;.=+-*/^<>!?:";
    int a = at(c, 0), b = at(c, 1);
    for (size_t i = 0; i < sizeof two / sizeof two[0]; i++)
        if (a == two[i][0] && b == two[i][1]) {
            t->op[0] = (char)a, t->op[1] = (char)b;
            adv(c), adv(c);
            t->kind = SCN_T_OP, t->rawlen = 2;
            return;
        }
    if (a > 0 && strchr(one, a)) {
        t->op[0] = (char)a;
        adv(c);
        t->kind = SCN_T_OP, t->rawlen = 1;
        return;
    }
    t->rawlen = 1;
    scn_fail(c, t->pos, sanitize(c, t->raw, 1), "unexpected character",
             "a name, a number, a string or one of ( ) { } [ ] , ; . = + - * / ^ < > ! ? :");
}

void scn_next(scn_ctx *c)
{
    scn_tok *t = &c->tok;
    memset(t, 0, sizeof *t);
    if (c->err || c->nfiles == 0) {
        t->raw = "";
        return; /* after an error the stream ends, so every loop terminates */
    }
    skip_blank(c);
    t->pos = here(c);
    t->raw = cur(c);
    if (c->err)
        return;
    int ch = at(c, 0);
    if (ch < 0)
        t->kind = SCN_T_EOF;
    else if (is_alpha(ch))
        lex_name(c, t);
    else if (is_digit(ch) || (ch == '.' && is_digit(at(c, 1))))
        lex_number(c, t);
    else if (ch == '"')
        lex_string(c, t);
    else
        lex_op(c, t);
    if (c->err)
        t->kind = SCN_T_EOF;
}
