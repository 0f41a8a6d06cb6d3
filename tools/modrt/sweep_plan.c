/* sweep_plan.c - the plan of a campaign: run k's values from k alone (mixed-radix digits
 * over the grid, the draw number innermost, each drawn value from sweep_draw), its
 * command line, and the directory's sweep.info that tells `collect` what to expect. Run k
 * costs the same whatever the campaign's size: the task list streams. */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "sweep.h"

void sweep_point_of(const sweep_campaign *c, uint64_t k, sweep_point *p)
{
    p->index = k;
    p->draw = k % c->draws;
    uint64_t rest = k / c->draws;
    for (int i = c->ndims - 1; i >= 0; i--) {
        p->at[i] = (uint32_t)(rest % c->dims[i].n);
        rest /= c->dims[i].n;
    }
    /* draw d of every grid point sees the same values: grid points compare on common
       random numbers */
    for (int v = 0; v < c->nvars; v++)
        p->var[v] = sweep_draw(&c->vars[v], c->seed, p->draw);
}

double sweep_dim_num(const sweep_campaign *c, int i, uint32_t j)
{
    const sweep_dim *d = &c->dims[i];
    if (!d->is_range)
        return c->num[d->first + j];
    /* the ends exactly: lo at j = 0, hi at j = n - 1 */
    return j + 1 == d->n ? d->hi : d->lo + (d->hi - d->lo) * ((double)j / (double)(d->n - 1));
}

const char *sweep_dim_str(const sweep_campaign *c, int i, uint32_t j)
{
    return c->arena + c->str[c->dims[i].first + j];
}

const char *sweep_fmt(char *buf, size_t n, double v)
{
    if (v == sweep_floor(v) && v > -1e15 && v < 1e15) { /* whole: 50, not 5e+01 */
        snprintf(buf, n, "%.0f", v);
        return buf;
    }
    if (v != v || v - v != 0)
        return cli_fmt(buf, n, v);
    /* the fewest digits that read back v; random draws need 16 or 17, listed values few:
       try 15, then bisect below it or step above it (a plan prints millions of values) */
    int lo = 1, hi = 15;
    snprintf(buf, n, "%.15g", v);
    if (strtod(buf, NULL) != v)
        lo = hi = 16 + (snprintf(buf, n, "%.16g", v), strtod(buf, NULL) != v);
    while (lo < hi) { /* round-tripping is monotone in the precision */
        int mid = (lo + hi) / 2;
        snprintf(buf, n, "%.*g", mid, v);
        if (strtod(buf, NULL) == v)
            hi = mid;
        else
            lo = mid + 1;
    }
    snprintf(buf, n, "%.*g", lo, v);
    return buf;
}

/* appends the word a (fmt "%s%s") or a=b (fmt "%s=%s") to buf at *used; its start into
   argv[*n] */
static int word(char *buf, size_t nbuf, size_t *used, char **argv, int *n, const char *fmt,
                const char *a, const char *b)
{
    size_t la = strlen(a), lb = strlen(b), eq = fmt[2] == '=';
    if (*n + 1 >= SWEEP_ARGS || la + eq + lb + 1 > nbuf - *used)
        return -1;
    char *w = buf + *used;
    memcpy(w, a, la);
    if (eq)
        w[la] = '=';
    memcpy(w + la + eq, b, lb + 1);
    argv[(*n)++] = w;
    *used += la + eq + lb + 1;
    return 0;
}

int sweep_argv(const sweep_campaign *c, const sweep_point *p, const char *modrt,
               const char *campaign, const char *out, char *buf, size_t nbuf, char **argv)
{
    static const char *const opt[] = {"--set", "--method", "--step", "--replay", "--scene"};
    char k[24], v[40];
    size_t used = 0;
    int n = 0, bad = 0;
    snprintf(k, sizeof k, "%llu", (unsigned long long)p->index);
    bad |= word(buf, nbuf, &used, argv, &n, "%s%s", modrt, "");
    bad |= word(buf, nbuf, &used, argv, &n, "%s%s", "sweep", "");
    bad |= word(buf, nbuf, &used, argv, &n, "%s%s", "exec", "");
    bad |= word(buf, nbuf, &used, argv, &n, "%s%s", campaign, "");
    bad |= word(buf, nbuf, &used, argv, &n, "%s%s", "--out", "");
    bad |= word(buf, nbuf, &used, argv, &n, "%s%s", out, "");
    bad |= word(buf, nbuf, &used, argv, &n, "%s%s", "--index", "");
    bad |= word(buf, nbuf, &used, argv, &n, "%s%s", k, "");
    for (int i = 0; i < c->ndims && !bad; i++) {
        const sweep_dim *d = &c->dims[i];
        bad |= word(buf, nbuf, &used, argv, &n, "%s%s", opt[d->kind], "");
        if (d->kind == SWEEP_DIM_REPLAY || d->kind == SWEEP_DIM_SCENE)
            bad |= word(buf, nbuf, &used, argv, &n, "%s%s", sweep_dim_str(c, i, p->at[i]), "");
        else if (d->kind == SWEEP_DIM_METHOD)
            bad |= word(buf, nbuf, &used, argv, &n, "%s=%s", d->name,
                        sweep_dim_str(c, i, p->at[i]));
        else
            bad |= word(buf, nbuf, &used, argv, &n, "%s=%s", d->name,
                        sweep_fmt(v, sizeof v, sweep_dim_num(c, i, p->at[i])));
    }
    for (int i = 0; i < c->nvars && !bad; i++) {
        bad |= word(buf, nbuf, &used, argv, &n, "%s%s", "--set", "");
        bad |= word(buf, nbuf, &used, argv, &n, "%s=%s", c->vars[i].name,
                    sweep_fmt(v, sizeof v, p->var[i]));
    }
    argv[n] = NULL;
    return bad ? -1 : n;
}

/* may a character stand bare in a word for sh? */
static int safe(char ch)
{
    return (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') || (ch >= '0' && ch <= '9') ||
           (ch && strchr("_./=:,+-@%", ch));
}

/* one word for sh: bare when it has only safe characters, else in single quotes */
static void quoted(FILE *f, const char *w)
{
    const char *p = w;
    while (safe(*p))
        p++;
    if (*w && !*p) {
        fputs(w, f);
        return;
    }
    fputc('\'', f);
    for (; *w; w++)
        *w == '\'' ? fputs("'\\''", f) : fputc(*w, f);
    fputc('\'', f);
}

int sweep_task_line(FILE *f, char **argv, uint64_t k)
{
    fprintf(f, "%llu\t", (unsigned long long)k);
    for (int i = 0; argv[i]; i++) {
        if (i)
            fputc(' ', f);
        quoted(f, argv[i]);
    }
    fputc('\n', f);
    return ferror(f) ? -1 : 0;
}

/* the result key of grid dimension d (the exec writes the same) */
static void column(FILE *f, const sweep_dim *d)
{
    static const char *const key[] = {"set.", "method.", "step.", "replay", "scene_file"};
    fprintf(f, "column: %s%s\n", key[d->kind], d->name);
}

int sweep_write_info(const sweep_campaign *c, const char *campaign, const char *out)
{
    char path[SWEEP_PATH + 32], tmp[SWEEP_PATH + 40];
    snprintf(path, sizeof path, "%s/runs", out);
    if ((mkdir(out, 0777) != 0 && errno != EEXIST) || (mkdir(path, 0777) != 0 && errno != EEXIST))
        return cli_fail("cannot create the output directory", path), -1;
    snprintf(path, sizeof path, "%s/sweep.info", out);
    snprintf(tmp, sizeof tmp, "%s.tmp", path);
    FILE *f = fopen(tmp, "w");
    if (!f)
        return cli_fail("cannot write", tmp), -1;
    fprintf(f, "campaign: %s\nname: %s\nruns: %llu\ncampaign_hash: %016llx\n", campaign,
            c->name, (unsigned long long)c->nruns, (unsigned long long)c->hash);
    for (int i = 0; i < c->ndims; i++)
        column(f, &c->dims[i]);
    for (int i = 0; i < c->nvars; i++)
        fprintf(f, "column: set.%s\n", c->vars[i].name);
    for (int i = 0; i < c->nmetrics; i++)
        fprintf(f, "metric: %s\n", c->metrics[i].name);
    if (fclose(f) != 0 || rename(tmp, path) != 0)
        return cli_fail("cannot write", path), -1;
    return 0;
}
