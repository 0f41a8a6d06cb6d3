/* sweep_collect.c - `modrt sweep collect DIR`: the per-run results of a campaign merged
 * into one CSV, one row per run in index order whatever engine ran them and in whatever
 * order (a run without a result is a row with status missing), and the figures: each
 * metric's histogram and each metric against each varied number (svgplot). The same
 * results give the same bytes: nothing time-dependent goes into the CSV. */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "sweep.h"

#define KV_MAX 160    /* keys of one run's record */
#define KV_LEN 256    /* bytes of a key or a value */
#define COLS_MAX (SWEEP_MAX_DIMS + SWEEP_MAX_VARS)

typedef struct record {
    char key[KV_MAX][KV_LEN], val[KV_MAX][KV_LEN];
    int n;
} record;

typedef struct info {
    char campaign[SWEEP_PATH], name[SWEEP_NAME], hash[24];
    uint64_t runs;
    char col[COLS_MAX][SWEEP_NAME + 8];
    int ncols;
    char metric[SWEEP_MAX_METRICS][SWEEP_NAME];
    int nmetrics;
} info;

static sweep_campaign camp;
static record rec;
static info inf;
static char argbuf[SWEEP_LINE];

static void put(record *r, const char *k, const char *v)
{
    for (int i = 0; i < r->n; i++)
        if (strcmp(r->key[i], k) == 0)
            return; /* the run's own value wins over the plan's */
    if (r->n >= KV_MAX)
        return;
    snprintf(r->key[r->n], KV_LEN, "%s", k);
    snprintf(r->val[r->n], KV_LEN, "%s", v);
    r->n++;
}

static const char *get(const record *r, const char *k)
{
    for (int i = 0; i < r->n; i++)
        if (strcmp(r->key[i], k) == 0)
            return r->val[i];
    return NULL;
}

/* the run's result file (if any), then its values from the plan */
static void load(const char *dir, uint64_t k)
{
    char path[SWEEP_PATH + 40], line[2 * KV_LEN];
    char *argv[SWEEP_ARGS];
    sweep_point p;
    rec.n = 0;
    sweep_result_path(path, sizeof path, dir, k);
    FILE *f = fopen(path, "r");
    while (f && fgets(line, sizeof line, f)) {
        char *sep = strstr(line, ": ");
        if (!sep)
            continue;
        *sep = 0, sep[2 + strcspn(sep + 2, "\n")] = 0;
        put(&rec, line, sep + 2);
    }
    if (f)
        fclose(f);
    const char *h = get(&rec, "campaign_hash");
    if (h && strcmp(h, inf.hash) != 0) { /* a result of an earlier version of the campaign */
        rec.n = 0;
        put(&rec, "status", "stale");
    }
    put(&rec, "status", "missing");
    if (k >= camp.nruns)
        return;
    sweep_point_of(&camp, k, &p);
    int n = sweep_argv(&camp, &p, "modrt", "c", "o", argbuf, sizeof argbuf, argv);
    for (int i = 8; i + 1 < n; i += 2) { /* after modrt sweep exec C --out O --index K */
        const char *opt = argv[i] + 2, *w = argv[i + 1], *eq = strchr(w, '=');
        char key[KV_LEN];
        if (!eq) {
            put(&rec, opt, w);
            continue;
        }
        snprintf(key, sizeof key, "%s.%.*s", opt, (int)(eq - w), w);
        put(&rec, key, eq + 1);
    }
}

static int read_info(const char *dir)
{
    char path[SWEEP_PATH + 16], line[SWEEP_PATH + 32];
    snprintf(path, sizeof path, "%s/sweep.info", dir);
    FILE *f = fopen(path, "r");
    if (!f)
        return cli_fail("collect: no campaign here (no sweep.info; `modrt sweep run`, "
                        "`plan --out` or `slurm` writes it)", path), -1;
    memset(&inf, 0, sizeof inf);
    while (fgets(line, sizeof line, f)) {
        line[strcspn(line, "\n")] = 0;
        if (!strncmp(line, "campaign: ", 10))
            snprintf(inf.campaign, sizeof inf.campaign, "%.*s", SWEEP_PATH - 1, line + 10);
        else if (!strncmp(line, "name: ", 6))
            snprintf(inf.name, sizeof inf.name, "%.*s", SWEEP_NAME - 1, line + 6);
        else if (!strncmp(line, "campaign_hash: ", 15))
            snprintf(inf.hash, sizeof inf.hash, "%.16s", line + 15);
        else if (!strncmp(line, "runs: ", 6))
            inf.runs = strtoull(line + 6, NULL, 10);
        else if (!strncmp(line, "column: ", 8) && inf.ncols < COLS_MAX)
            snprintf(inf.col[inf.ncols++], sizeof inf.col[0], "%.*s", SWEEP_NAME + 7, line + 8);
        else if (!strncmp(line, "metric: ", 8) && inf.nmetrics < SWEEP_MAX_METRICS)
            snprintf(inf.metric[inf.nmetrics++], sizeof inf.metric[0], "%.*s", SWEEP_NAME - 1,
                     line + 8);
    }
    fclose(f);
    if (sweep_parse(inf.campaign, &camp) != 0)
        return cli_fail("collect: cannot read the campaign named in", path), -1;
    char now[24];
    snprintf(now, sizeof now, "%016llx", (unsigned long long)camp.hash);
    if (camp.nruns != inf.runs || strcmp(now, inf.hash) != 0)
        return cli_fail("collect: the campaign file has changed since sweep.info was written "
                        "(modrt sweep run --only-missing runs what the new version needs)",
                        inf.campaign), -1;
    return 0;
}

/* a CSV field: quoted when it holds a comma, a quote or a space */
static void field(FILE *f, const char *v)
{
    fputc(',', f);
    if (!strpbrk(v, ",\" ")) {
        fputs(v, f);
        return;
    }
    fputc('"', f);
    for (; *v; v++)
        *v == '"' ? fputs("\"\"", f) : fputc(*v, f);
    fputc('"', f);
}

static void header(FILE *f)
{
    fputs("run,status", f);
    for (int i = 0; i < inf.ncols; i++)
        fprintf(f, ",%s", inf.col[i]);
    for (int i = 0; i < inf.nmetrics; i++)
        fprintf(f, ",%s", inf.metric[i]);
    fputs(",ticks,hash", f);
    for (int i = 0; i < RT_CNT_COUNT; i++)
        fprintf(f, ",%s", rt_counter_key((rt_counter)i));
    fputc('\n', f);
}

static void row(FILE *f, uint64_t k)
{
    char mkey[SWEEP_NAME + 8], ckey[SWEEP_NAME + 8];
    const char *v;
    fprintf(f, "%llu", (unsigned long long)k);
    field(f, get(&rec, "status"));
    for (int i = 0; i < inf.ncols; i++)
        field(f, (v = get(&rec, inf.col[i])) ? v : "");
    for (int i = 0; i < inf.nmetrics; i++) {
        snprintf(mkey, sizeof mkey, "metric.%s", inf.metric[i]);
        field(f, (v = get(&rec, mkey)) ? v : "");
    }
    field(f, (v = get(&rec, "ticks")) ? v : "");
    field(f, (v = get(&rec, "hash")) ? v : "");
    for (int i = 0; i < RT_CNT_COUNT; i++) {
        snprintf(ckey, sizeof ckey, "count.%s", rt_counter_key((rt_counter)i));
        field(f, (v = get(&rec, ckey)) ? v : "");
    }
    fputc('\n', f);
}

/* metric i of the loaded run, or NaN: none, or the run failed (its values are not
   answers: the figures leave them out, the CSV has them with the run's status) */
static double metric_of(int i)
{
    char key[SWEEP_NAME + 8];
    const char *code = get(&rec, "exit");
    if (!code || (strcmp(code, "0") != 0 && strcmp(code, "3") != 0))
        return NAN;
    snprintf(key, sizeof key, "metric.%s", inf.metric[i]);
    const char *v = get(&rec, key);
    return v ? strtod(v, NULL) : NAN;
}

static int plot(const char *svgplot, char *const *argv)
{
    pid_t pid = fork();
    if (pid == 0) {
        execv(svgplot, argv);
        _exit(127);
    }
    int wst;
    return pid > 0 && waitpid(pid, &wst, 0) == pid && WIFEXITED(wst) && WEXITSTATUS(wst) == 0
               ? 0 : -1;
}

/* metric i's histogram over the runs that have it */
static int histogram(const char *dir, const char *svgplot, int i)
{
    double lo = INFINITY, hi = -INFINITY, w;
    uint64_t bins[SWEEP_HIST_BINS] = {0}, have = 0;
    char data[SWEEP_PATH + 80], svg[SWEEP_PATH + 80], title[200], ylab[64];
    for (int pass = 0; pass < 2; pass++)
        for (uint64_t k = 0; k < inf.runs; k++) {
            load(dir, k);
            double v = metric_of(i);
            if (!isfinite(v))
                continue;
            if (pass == 0) {
                lo = v < lo ? v : lo, hi = v > hi ? v : hi, have++;
                continue;
            }
            w = hi > lo ? (hi - lo) / SWEEP_HIST_BINS : 1;
            int b = (int)((v - lo) / w);
            bins[b < 0 ? 0 : b >= SWEEP_HIST_BINS ? SWEEP_HIST_BINS - 1 : b]++;
        }
    if (have == 0)
        return 0;
    w = hi > lo ? (hi - lo) / SWEEP_HIST_BINS : 1;
    snprintf(data, sizeof data, "%s/plots/%s-hist.csv", dir, inf.metric[i]);
    FILE *f = fopen(data, "w");
    if (!f)
        return cli_fail("cannot write", data), -1;
    fprintf(f, "series,x,y\n%s,%.17g,0\n", inf.metric[i], lo);
    for (int b = 0; b < SWEEP_HIST_BINS; b++)
        fprintf(f, "%s,%.17g,%llu\n%s,%.17g,%llu\n", inf.metric[i], lo + b * w,
                (unsigned long long)bins[b], inf.metric[i], lo + (b + 1) * w,
                (unsigned long long)bins[b]);
    fprintf(f, "%s,%.17g,0\n", inf.metric[i], lo + SWEEP_HIST_BINS * w);
    fclose(f);
    snprintf(svg, sizeof svg, "%s/plots/%s-hist.svg", dir, inf.metric[i]);
    snprintf(title, sizeof title, "%s: %s over %llu runs (%llu failed or without a value)", inf.name,
             inf.metric[i], (unsigned long long)have, (unsigned long long)(inf.runs - have));
    snprintf(ylab, sizeof ylab, "runs per bin of %.3g", w);
    char *argv[] = {(char *)svgplot, "--xy", "--lines", "-t", title, "-x", inf.metric[i], "-y",
                    ylab, "-o", svg, data, NULL};
    return plot(svgplot, argv);
}

/* metric i against numeric column j (set.* and step.*), one series per method or log */
static int scatter(const char *dir, const char *svgplot, int i, int j)
{
    char data[SWEEP_PATH + 160], svg[SWEEP_PATH + 160], title[240], series[KV_LEN];
    snprintf(data, sizeof data, "%s/plots/%s-vs-%s.csv", dir, inf.metric[i], inf.col[j]);
    FILE *f = fopen(data, "w");
    if (!f)
        return cli_fail("cannot write", data), -1;
    fputs("series,x,y\n", f);
    for (uint64_t k = 0; k < inf.runs; k++) {
        load(dir, k);
        const char *x = get(&rec, inf.col[j]);
        series[0] = 0;
        for (int c = 0; c < inf.ncols; c++)
            if (!strncmp(inf.col[c], "method.", 7) || !strcmp(inf.col[c], "replay") ||
                !strcmp(inf.col[c], "scene_file"))
                snprintf(series + strlen(series), sizeof series - strlen(series), "%s%s",
                         series[0] ? " " : "", get(&rec, inf.col[c]));
        for (char *s = series; *s; s++)
            *s = *s == ',' ? ';' : *s;
        double y = metric_of(i);
        if (x && isfinite(y)) /* a gap would only make svgplot warn */
            fprintf(f, "%s,%s,%.17g\n", series[0] ? series : "runs", x, y);
    }
    fclose(f);
    snprintf(svg, sizeof svg, "%s/plots/%s-vs-%s.svg", dir, inf.metric[i], inf.col[j]);
    snprintf(title, sizeof title, "%s: %s against %s", inf.name, inf.metric[i], inf.col[j] + 4);
    char *argv[] = {(char *)svgplot, "--xy", "-t", title, "-x", inf.col[j] + 4, "-y",
                    inf.metric[i], "-o", svg, data, NULL};
    return plot(svgplot, argv);
}

static int figures(const char *dir, const char *svgplot)
{
    char path[SWEEP_PATH + 16];
    snprintf(path, sizeof path, "%s/plots", dir);
    if (mkdir(path, 0777) != 0 && errno != EEXIST)
        return cli_fail("cannot create", path), -1;
    if (access(svgplot, X_OK) != 0) {
        fprintf(stderr, "sweep: collect: no figures: svgplot not found at %s (make builds it)\n",
                svgplot);
        return 0;
    }
    int bad = 0, nfig = 0;
    for (int i = 0; i < inf.nmetrics; i++) {
        bad |= histogram(dir, svgplot, i), nfig++;
        for (int j = 0; j < inf.ncols && inf.runs <= SWEEP_SCATTER_MAX; j++)
            if (!strncmp(inf.col[j], "set.", 4) || !strncmp(inf.col[j], "step.", 5))
                bad |= scatter(dir, svgplot, i, j), nfig++;
    }
    fprintf(stderr, "sweep: collect: %d figures in %s/plots%s\n", nfig, dir,
            bad ? " (svgplot failed on some)" : "");
    return bad;
}

int sweep_collect(const char *dir, const char *svgplot)
{
    char path[SWEEP_PATH + 16], tmp[SWEEP_PATH + 24];
    uint64_t ok = 0, missing = 0;
    double wall = 0;
    if (read_info(dir) != 0)
        return CLI_USAGE;
    snprintf(path, sizeof path, "%s/results.csv", dir);
    snprintf(tmp, sizeof tmp, "%s.tmp", path);
    FILE *f = fopen(tmp, "w");
    if (!f)
        return cli_fail("cannot write", tmp);
    header(f);
    for (uint64_t k = 0; k < inf.runs; k++) {
        load(dir, k);
        const char *st = get(&rec, "status"), *w = get(&rec, "wall_s");
        ok += strcmp(st, "ok") == 0;
        missing += strcmp(st, "missing") == 0 || strcmp(st, "stale") == 0;
        wall += w ? strtod(w, NULL) : 0;
        row(f, k);
    }
    if (fclose(f) != 0 || rename(tmp, path) != 0)
        return cli_fail("cannot write", path);
    printf("runs: %llu\nok: %llu\nnot_ok: %llu\nmissing_or_stale: %llu\nrun_wall_s_sum: %.6f\n"
           "csv: %s\n", (unsigned long long)inf.runs, (unsigned long long)ok,
           (unsigned long long)(inf.runs - ok - missing), (unsigned long long)missing, wall,
           path);
    return figures(dir, svgplot) != 0 || missing > 0 ? CLI_FAULTS : CLI_OK;
}
