/* svgplot.c - owns the svgplot host tool: modrt trace CSVs and work-precision tables -> SVG plots.
 *
 * Trace mode plots signals against t; xy mode plots series,x,y tables (error vs cost).
 * Host-only, C11 + libc + libm, no malloc: every size is bounded by a named limit below and
 * exceeding one is a clear error, never a silent truncation of data. Trace files are read
 * twice (ranges, then per-pixel-column min/max decimation) so a million-row trace needs no
 * more memory than a short one. Errors print one line "svgplot: FILE:LINE: what" on stderr
 * and exit with status 1; the output file is only opened once all input has been checked.
 *
 * Build: gcc -std=c11 -Wall -Wextra -Werror -O2 -ffp-contract=off tools/svgplot.c -lm */

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ------------------------------------------------------------------ limits */

#define MAX_LINE 16384       /* bytes in one CSV line, newline included */
#define MAX_COLS 256         /* columns in a trace CSV header */
#define MAX_SERIES 32        /* curves in one plot (trace signals or xy series) */
#define MAX_NAME 128         /* bytes in a column or series name */
#define MAX_XY_POINTS 100000 /* data rows in an xy table (kept in memory) */
#define MAX_TRACE_VERTICES 80000 /* path vertices over all trace curves: keeps the SVG near 1 MB */
#define MIN_IMAGE_PX 200     /* smallest -W / -H */
#define MAX_IMAGE_PX 4096    /* largest -W / -H; also bounds the decimation bins */
#define MIN_PLOT_PX 80       /* smallest plot area left after margins and legend */
#define MAX_TICKS 64         /* labelled ticks per axis */
#define MAX_TICK_TARGET 25   /* linear axes aim for at most this many intervals (<= MAX_TICKS ticks) */
#define MAX_MINOR 512        /* unlabelled ticks per axis */
#define MAX_LABEL 40         /* bytes in one tick label */
#define MAX_LEGEND_CHARS 28  /* legend names longer than this are shortened with "..." */
#define MAX_TITLE_CHARS 120  /* titles longer than this are shortened with "..." */

#define DEFAULT_W 800
#define DEFAULT_H 500

/* ------------------------------------------------------------------ look */

/* No font metrics on the host: widths are estimated from an average glyph advance. */
#define CHAR_EM 0.6
#define FONT_TICK 11.0
#define FONT_TEXT 12.0
#define FONT_TITLE 15.0
#define FONT_EXP 8.5 /* exponent of a 10^k log label */
#define TICK_LEN 5.0
#define GAP 10.0       /* generic spacing between layout elements */
#define LEG_ROW 18.0   /* legend row height */
#define LEG_SWATCH 26.0
#define LEG_PAD 7.0
#define Y_TICK_PX 48.0 /* aim for one linear y tick per this many pixels */
#define X_TICK_PX 90.0
#define PAD_TRACE_Y 0.04 /* fraction of the data span left free above and below curves */
#define PAD_XY 0.05
#define MARKER_R 3.5

static const char *const PALETTE[] = {
    "#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b", "#e377c2",
    "#7f7f7f", "#bcbd22", "#17becf", "#393b79", "#637939", "#8c6d31", "#843c39",
    "#7b4173", "#3182bd", "#e6550d", "#31a354", "#756bb1", "#636363",
};
#define NPALETTE ((int)(sizeof PALETTE / sizeof PALETTE[0]))
#define NMARKERS 6 /* circle, square, triangle up, diamond, triangle down, cross */

/* ------------------------------------------------------------------ diagnostics */

static const char *g_out_path; /* removed on a late failure so no half-written file remains */

/* One diagnostic line: "svgplot: [warning: ][FILE:LINE: ]text". */
static void vreport(const char *kind, const char *path, long line, const char *fmt, va_list ap)
{
    fprintf(stderr, "svgplot: %s", kind);
    if (path) fprintf(stderr, "%s:%ld: ", path, line);
    vfprintf(stderr, fmt, ap);
    fputc('\n', stderr);
}

static void die(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vreport("", NULL, 0, fmt, ap);
    va_end(ap);
    exit(1);
}

static void warn(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vreport("warning: ", NULL, 0, fmt, ap);
    va_end(ap);
}

/* ------------------------------------------------------------------ CSV reading */

struct csv {
    FILE *f;
    const char *path;
    long line; /* 1-based number of the line now in buf */
    char buf[MAX_LINE];
    char *field[MAX_COLS];
    int nf;
};

static void csv_die(const struct csv *c, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vreport("", c->path, c->line, fmt, ap);
    va_end(ap);
    exit(1);
}

static int is_space(char ch) { return ch == ' ' || ch == '\t' || ch == '\r' || ch == '\n'; }

static char *trim(char *s)
{
    while (is_space(*s)) s++;
    size_t n = strlen(s);
    while (n > 0 && is_space(s[n - 1])) s[--n] = '\0';
    return s;
}

/* Quoted fields are unquoted so spreadsheet exports work; commas inside quotes are not supported. */
static char *unquote(char *s)
{
    size_t n = strlen(s);
    if (n >= 2 && s[0] == '"' && s[n - 1] == '"') {
        s[n - 1] = '\0';
        return trim(s + 1);
    }
    return s;
}

static void csv_split(struct csv *c, char *s)
{
    c->nf = 0;
    for (;;) {
        char *comma = strchr(s, ',');
        if (comma) *comma = '\0';
        if (c->nf == MAX_COLS) csv_die(c, "more than %d columns (MAX_COLS)", MAX_COLS);
        c->field[c->nf++] = unquote(trim(s));
        if (!comma) return;
        s = comma + 1;
    }
}

static FILE *open_input(const char *path)
{
    FILE *f = fopen(path, "r");
    if (!f) die("cannot open '%s': %s", path, strerror(errno));
    return f;
}

/* Reads the next line that is neither blank nor a '#' comment and splits it; 0 at end of file. */
static int csv_next(struct csv *c)
{
    for (;;) {
        if (!fgets(c->buf, sizeof c->buf, c->f)) {
            if (ferror(c->f)) die("%s: read error after line %ld: %s", c->path, c->line, strerror(errno));
            return 0;
        }
        c->line++;
        size_t len = strlen(c->buf);
        if (len == sizeof c->buf - 1 && c->buf[len - 1] != '\n' && getc(c->f) != EOF)
            csv_die(c, "line longer than %d bytes (MAX_LINE)", MAX_LINE - 2);
        char *s = trim(c->buf);
        if (*s == '\0' || *s == '#') continue;
        csv_split(c, s);
        return 1;
    }
}

/* An empty field is a missing sample (NaN), as pandas writes it; anything else must be a full number. */
static int parse_num(const char *s, double *v)
{
    if (*s == '\0') {
        *v = NAN;
        return 1;
    }
    char *end;
    *v = strtod(s, &end);
    return end != s && *end == '\0';
}

static double field_num(const struct csv *c, int i, const char *colname)
{
    double v;
    if (!parse_num(c->field[i], &v))
        csv_die(c, "non-numeric value '%.40s' in column '%s'", c->field[i], colname);
    return v;
}

/* A header starts with a name; a first line starting with a number means the header is missing. */
static void csv_header(struct csv *c, const char *example)
{
    if (!csv_next(c)) die("%s: empty file: no header row (expected e.g. '%s')", c->path, example);
    double v;
    if (c->field[0][0] != '\0' && parse_num(c->field[0], &v))
        csv_die(c, "no header row: first line starts with the number '%.40s' (expected e.g. '%s')",
                c->field[0], example);
    for (int i = 0; i < c->nf; i++) {
        if (c->field[i][0] == '\0') csv_die(c, "empty column name in header (column %d)", i + 1);
        if (strlen(c->field[i]) > MAX_NAME)
            csv_die(c, "column name longer than %d bytes (MAX_NAME) in header (column %d)", MAX_NAME, i + 1);
    }
}

static void csv_fields(const struct csv *c, int expect, const char *what)
{
    if (c->nf != expect) csv_die(c, "expected %d fields (%s), got %d", expect, what, c->nf);
}

/* ------------------------------------------------------------------ text and XML */

/* Length of one valid UTF-8 sequence that is also an XML Char, or 0: names come from files
   and must not make the SVG ill-formed. */
static int utf8_char(const unsigned char *s, unsigned *cp)
{
    unsigned c = s[0], min;
    int n;
    if (c < 0x80) {
        *cp = c;
        return (c >= 0x20 || c == '\t') ? 1 : 0;
    }
    if ((c & 0xE0) == 0xC0) { n = 2; *cp = c & 0x1F; min = 0x80; }
    else if ((c & 0xF0) == 0xE0) { n = 3; *cp = c & 0x0F; min = 0x800; }
    else if ((c & 0xF8) == 0xF0) { n = 4; *cp = c & 0x07; min = 0x10000; }
    else return 0;
    for (int i = 1; i < n; i++) {
        if ((s[i] & 0xC0) != 0x80) return 0; /* also stops at the terminating NUL */
        *cp = (*cp << 6) | (s[i] & 0x3F);
    }
    if (*cp < min || *cp > 0x10FFFF || (*cp >= 0xD800 && *cp <= 0xDFFF) || *cp == 0xFFFE || *cp == 0xFFFF)
        return 0;
    return n;
}

static int text_chars(const char *s)
{
    int n = 0;
    for (const unsigned char *p = (const unsigned char *)s; *p; p++) n += (*p & 0xC0) != 0x80;
    return n;
}

static double text_w(const char *s, double font, int maxchars)
{
    int n = text_chars(s);
    return (n > maxchars ? maxchars + 3 : n) * font * CHAR_EM;
}

/* Writes s as XML character data, at most maxchars characters then "..."; bad bytes become '?'. */
static void put_xml(FILE *out, const char *s, int maxchars)
{
    const unsigned char *p = (const unsigned char *)s;
    for (int k = 0; *p; k++) {
        if (k == maxchars) {
            fputs("...", out);
            return;
        }
        unsigned cp;
        int n = utf8_char(p, &cp);
        if (n == 0) { fputc('?', out); p++; continue; }
        switch (cp) {
        case '&': fputs("&amp;", out); break;
        case '<': fputs("&lt;", out); break;
        case '>': fputs("&gt;", out); break;
        case '"': fputs("&quot;", out); break;
        default: fwrite(p, 1, (size_t)n, out);
        }
        p += n;
    }
}

static const char *basename_of(const char *path)
{
    const char *slash = strrchr(path, '/');
    return slash ? slash + 1 : path;
}

/* ------------------------------------------------------------------ axes and ticks */

struct axis {
    int log;           /* lo, hi and ticks are log10 of data values */
    double lo, hi;     /* limits in axis space */
    double p0, p1;     /* pixel positions of lo and hi */
    int nmaj, nmin;
    double maj[MAX_TICKS], min[MAX_MINOR]; /* in axis space */
    char lab[MAX_TICKS][MAX_LABEL];        /* on a log axis: just the exponent k of 10^k */
};

static double axis_px(const struct axis *a, double u) { return a->p0 + (u - a->lo) / (a->hi - a->lo) * (a->p1 - a->p0); }

static double data_px(const struct axis *a, double v) { return axis_px(a, a->log ? log10(v) : v); }

/* A degenerate span (constant signal, single sample) is widened so the mapping stays finite. */
static void axis_range_linear(struct axis *a, double dmin, double dmax, int have, double pad)
{
    if (!have) { dmin = 0.0; dmax = 1.0; }
    double mag = fmax(fabs(dmin), fabs(dmax));
    if (dmax - dmin <= mag * 1e-9) {
        double h = mag > 0.0 ? mag * 0.05 : 0.5;
        dmin -= h;
        dmax += h;
    }
    double span = dmax - dmin;
    a->log = 0;
    a->lo = dmin - pad * span;
    a->hi = dmax + pad * span;
    if (!isfinite(a->hi - a->lo)) die("data range %g .. %g is too wide to plot", dmin, dmax);
}

/* Log axes get the same relative padding as linear ones (in decades) so no point sits on the
   frame; if that leaves fewer than two decades to label, the axis widens to whole decades. */
static void axis_range_log(struct axis *a, double dmin, double dmax, int have, double pad)
{
    double l0 = have ? log10(dmin) : 0.0, l1 = have ? log10(dmax) : 1.0;
    double span = fmax(l1 - l0, 1.0);
    a->log = 1;
    a->lo = l0 - pad * span;
    a->hi = l1 + pad * span;
    if (floor(a->hi) - ceil(a->lo) < 1.0) {
        a->lo = floor(l0);
        a->hi = ceil(l1) > a->lo ? ceil(l1) : a->lo + 1.0;
    }
}

/* The step of the form {1,2,5} x 10^k nearest (by ratio) to span/target. */
static double nice_step(double span, int target)
{
    double rough = span / target;
    double p = pow(10.0, floor(log10(rough)));
    double m = rough / p;
    double f = m < 1.4142 ? 1.0 : m < 3.1623 ? 2.0 : m < 7.0711 ? 5.0 : 10.0;
    return f * p;
}

/* Next value of the sequence 1, 2, 5, 10, 20, 50, ... */
static int next_125(int v)
{
    int p = 1;
    while (v >= 10 * p) p *= 10;
    int m = v / p;
    return (m < 2 ? 2 : m < 5 ? 5 : 10) * p;
}

/* "1.5e-05" -> "1.5e-5": shorter labels, same value. */
static void tidy_exponent(char *s)
{
    char *e = strchr(s, 'e');
    if (!e) return;
    char *d = e + 1, *src = e + 1;
    if (*src == '+') src++;
    else if (*src == '-') *d++ = *src++;
    while (*src == '0' && src[1] != '\0') src++;
    memmove(d, src, strlen(src) + 1);
}

/* Fixed notation with just enough decimals for the step; %g when numbers are huge or tiny. */
static void format_linear(char *buf, double v, double step, double maxabs)
{
    int e = (int)floor(log10(step) + 1e-9);
    if (maxabs < 1e6 && e >= -4) {
        snprintf(buf, MAX_LABEL, "%.*f", e < 0 ? -e : 0, v);
        return;
    }
    int sig = maxabs > 0 ? (int)floor(log10(maxabs)) - e + 1 : 1; /* log10(0): no int */
    sig = sig < 1 ? 1 : sig > 15 ? 15 : sig;
    snprintf(buf, MAX_LABEL, "%.*g", sig, v);
    tidy_exponent(buf);
}

static double label_w(const struct axis *a, int i)
{
    if (a->log) return 2 * FONT_TICK * CHAR_EM + text_chars(a->lab[i]) * FONT_EXP * CHAR_EM;
    return text_chars(a->lab[i]) * FONT_TICK * CHAR_EM;
}

static void ticks_linear_step(struct axis *a, double step)
{
    double k0 = ceil(a->lo / step - 1e-9), k1 = floor(a->hi / step + 1e-9);
    double maxabs = fmax(fabs(k0 * step), fabs(k1 * step));
    a->nmaj = a->nmin = 0;
    /* the count bound also ends the loop if k is so large that k + 1 == k */
    for (double k = k0; k <= k1 && a->nmaj < MAX_TICKS; k += 1.0) {
        double v = k == 0.0 ? 0.0 : k * step; /* exact zero: no "-0" or 1e-17 labels */
        a->maj[a->nmaj] = v;
        format_linear(a->lab[a->nmaj], v, step, maxabs);
        a->nmaj++;
    }
}

/* min_gap > 0 (horizontal axes): fewer ticks until neighbouring labels keep that gap. */
static void ticks_linear(struct axis *a, double px_len, double px_per_tick, double min_gap)
{
    int target = (int)(px_len / px_per_tick);
    target = target > MAX_TICK_TARGET ? MAX_TICK_TARGET : target;
    for (target = target < 2 ? 2 : target;; target--) {
        double step = nice_step(a->hi - a->lo, target);
        ticks_linear_step(a, step);
        double px_step = step / (a->hi - a->lo) * px_len, widest = 0.0;
        for (int i = 0; i < a->nmaj; i++) widest = fmax(widest, label_w(a, i));
        if (min_gap <= 0.0 || target <= 2 || px_step >= widest + min_gap) return;
    }
}

static void add_minor(struct axis *a, double u)
{
    if (a->nmin < MAX_MINOR) a->min[a->nmin++] = u;
}

/* Decades get labels as long as they stay min_gap pixels apart; 2..9 minors when decades are roomy. */
static void ticks_log(struct axis *a, double px_len, double min_gap)
{
    double px_dec = px_len / (a->hi - a->lo);
    int every = 1;
    while (px_dec * every < min_gap || (a->hi - a->lo) / every + 2 > MAX_TICKS) every = next_125(every);
    a->nmaj = a->nmin = 0;
    for (int d = (int)floor(a->lo); d <= (int)ceil(a->hi); d++) {
        int in = d >= a->lo - 1e-9 && d <= a->hi + 1e-9;
        if (in && ((d % every) + every) % every == 0 && a->nmaj < MAX_TICKS) {
            a->maj[a->nmaj] = d;
            snprintf(a->lab[a->nmaj], MAX_LABEL, "%d", d);
            a->nmaj++;
        } else if (in && px_dec >= 6.0) {
            add_minor(a, d);
        }
        for (int m = 2; m <= 9 && px_dec >= 40.0; m++) {
            double u = d + log10((double)m);
            if (u > a->lo && u < a->hi) add_minor(a, u);
        }
    }
}

/* ------------------------------------------------------------------ plot layout */

struct plot {
    int W, H;
    const char *title, *xlabel, *ylabel;
    int n;
    const char *name[MAX_SERIES];
    int markers;               /* xy mode: point markers on curves and in the legend */
    double x0, x1, y0, y1;     /* plot area: left, right, top, bottom pixel */
    struct axis ax, ay;
    int leg_cols, leg_rows;
    double leg_x, leg_colw;
};

struct ranges {
    double xmin, xmax, ymin, ymax;
    int have_x, have_y;
};

static void extend(double *lo, double *hi, int *have, double v)
{
    if (!*have || v < *lo) *lo = v;
    if (!*have || v > *hi) *hi = v;
    *have = 1;
}

static void ranges_add(struct ranges *r, double x, double y)
{
    extend(&r->xmin, &r->xmax, &r->have_x, x);
    extend(&r->ymin, &r->ymax, &r->have_y, y);
}

static void layout_y(struct plot *p, const struct ranges *r, int logy, double pad)
{
    p->y0 = (p->title[0] ? 2.6 * FONT_TITLE : GAP) + 4.0;
    p->y1 = p->H - (TICK_LEN + 2.6 * FONT_TICK + (p->xlabel[0] ? 1.6 * FONT_TEXT : 0.0));
    if (p->y1 - p->y0 < MIN_PLOT_PX) die("image height %d leaves no room for the plot (raise -H)", p->H);
    if (logy) axis_range_log(&p->ay, r->ymin, r->ymax, r->have_y, pad);
    else axis_range_linear(&p->ay, r->ymin, r->ymax, r->have_y, pad);
    p->ay.p0 = p->y1;
    p->ay.p1 = p->y0;
    if (logy) ticks_log(&p->ay, p->y1 - p->y0, 2.2 * FONT_TICK);
    else ticks_linear(&p->ay, p->y1 - p->y0, Y_TICK_PX, 0.0);
}

/* The legend sits right of the plot area so it can never hide a curve; it wraps into columns. */
static double layout_legend(struct plot *p)
{
    double maxw = 0.0;
    for (int i = 0; i < p->n; i++) maxw = fmax(maxw, text_w(p->name[i], FONT_TEXT, MAX_LEGEND_CHARS));
    int fit = (int)((p->y1 - p->y0 - 2 * LEG_PAD) / LEG_ROW);
    if (fit < 1) fit = 1;
    p->leg_cols = (p->n + fit - 1) / fit;
    p->leg_rows = (p->n + p->leg_cols - 1) / p->leg_cols;
    p->leg_colw = LEG_SWATCH + 6.0 + maxw + GAP;
    return p->leg_cols * p->leg_colw + 2 * LEG_PAD;
}

static void layout_x(struct plot *p, const struct ranges *r, int logx, double pad)
{
    double lw = 0.0;
    for (int i = 0; i < p->ay.nmaj; i++) lw = fmax(lw, label_w(&p->ay, i));
    p->x0 = GAP + (p->ylabel[0] ? 1.8 * FONT_TEXT : 0.0) + lw + TICK_LEN + 4.0;
    double legw = layout_legend(p);
    p->x1 = p->W - GAP - legw - 1.5 * GAP;
    p->leg_x = p->x1 + 1.5 * GAP;
    if (p->x1 - p->x0 < MIN_PLOT_PX)
        die("image width %d leaves no room for the plot beside the legend (raise -W or plot fewer series)", p->W);
    if (logx) axis_range_log(&p->ax, r->xmin, r->xmax, r->have_x, pad);
    else axis_range_linear(&p->ax, r->xmin, r->xmax, r->have_x, pad);
    p->ax.p0 = p->x0;
    p->ax.p1 = p->x1;
    if (logx) ticks_log(&p->ax, p->x1 - p->x0, 4.5 * FONT_TICK);
    else ticks_linear(&p->ax, p->x1 - p->x0, X_TICK_PX, 2 * GAP);
}

/* ------------------------------------------------------------------ SVG output */

static void svg_begin(FILE *out, const struct plot *p)
{
    fprintf(out, "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
                 "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%d\" height=\"%d\" viewBox=\"0 0 %d %d\" "
                 "font-family=\"DejaVu Sans, Helvetica, Arial, sans-serif\" font-size=\"%.0f\">\n",
            p->W, p->H, p->W, p->H, FONT_TEXT);
    fprintf(out, "<rect width=\"%d\" height=\"%d\" fill=\"white\"/>\n", p->W, p->H);
    fprintf(out, "<defs><clipPath id=\"plotarea\"><rect x=\"%.1f\" y=\"%.1f\" width=\"%.1f\" height=\"%.1f\"/>"
                 "</clipPath></defs>\n",
            p->x0, p->y0, p->x1 - p->x0, p->y1 - p->y0);
}

/* Full-height (vertical) or full-width lines at axis-space positions u[0..n-1]. */
static void svg_gridlines(FILE *out, const struct plot *p, const struct axis *a, const double *u, int n, int vertical)
{
    for (int i = 0; i < n; i++) {
        double q = axis_px(a, u[i]);
        if (vertical) fprintf(out, "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\"/>\n", q, p->y0, q, p->y1);
        else fprintf(out, "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\"/>\n", p->x0, q, p->x1, q);
    }
}

static void svg_grid(FILE *out, const struct plot *p)
{
    fputs("<g stroke=\"#f0f0f0\" stroke-width=\"1\">\n", out);
    svg_gridlines(out, p, &p->ax, p->ax.min, p->ax.nmin, 1);
    svg_gridlines(out, p, &p->ay, p->ay.min, p->ay.nmin, 0);
    fputs("</g>\n<g stroke=\"#dcdcdc\" stroke-width=\"1\">\n", out);
    svg_gridlines(out, p, &p->ax, p->ax.maj, p->ax.nmaj, 1);
    svg_gridlines(out, p, &p->ay, p->ay.maj, p->ay.nmaj, 0);
    fputs("</g>\n", out);
}

static void svg_tick_label(FILE *out, const struct axis *a, int i, double x, double y, const char *anchor)
{
    fprintf(out, "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"%s\">", x, y, anchor);
    if (a->log) fprintf(out, "10<tspan dy=\"-%.0f\" font-size=\"%.1f\">%s</tspan>", FONT_TICK * 0.45, FONT_EXP, a->lab[i]);
    else fputs(a->lab[i], out);
    fputs("</text>\n", out);
}

static void svg_axes(FILE *out, const struct plot *p)
{
    fprintf(out, "<rect x=\"%.1f\" y=\"%.1f\" width=\"%.1f\" height=\"%.1f\" fill=\"none\" stroke=\"#333\"/>\n",
            p->x0, p->y0, p->x1 - p->x0, p->y1 - p->y0);
    fputs("<g stroke=\"#333\">\n", out);
    for (int i = 0; i < p->ax.nmaj; i++) {
        double x = axis_px(&p->ax, p->ax.maj[i]);
        fprintf(out, "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\"/>\n", x, p->y1, x, p->y1 + TICK_LEN);
    }
    for (int i = 0; i < p->ay.nmaj; i++) {
        double y = axis_px(&p->ay, p->ay.maj[i]);
        fprintf(out, "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\"/>\n", p->x0 - TICK_LEN, y, p->x0, y);
    }
    fprintf(out, "</g>\n<g font-size=\"%.0f\" fill=\"#222\">\n", FONT_TICK);
    for (int i = 0; i < p->ax.nmaj; i++)
        svg_tick_label(out, &p->ax, i, axis_px(&p->ax, p->ax.maj[i]), p->y1 + TICK_LEN + 1.2 * FONT_TICK, "middle");
    for (int i = 0; i < p->ay.nmaj; i++)
        svg_tick_label(out, &p->ay, i, p->x0 - TICK_LEN - 3.0, axis_px(&p->ay, p->ay.maj[i]) + 0.35 * FONT_TICK, "end");
    fputs("</g>\n", out);
}

static void svg_labels(FILE *out, const struct plot *p)
{
    double cx = 0.5 * (p->x0 + p->x1), cy = 0.5 * (p->y0 + p->y1);
    if (p->title[0]) {
        fprintf(out, "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"middle\" font-size=\"%.0f\" font-weight=\"bold\">",
                cx, 1.5 * FONT_TITLE, FONT_TITLE);
        put_xml(out, p->title, MAX_TITLE_CHARS);
        fputs("</text>\n", out);
    }
    if (p->xlabel[0]) {
        fprintf(out, "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"middle\">", cx, p->H - 0.6 * FONT_TEXT);
        put_xml(out, p->xlabel, MAX_TITLE_CHARS);
        fputs("</text>\n", out);
    }
    if (p->ylabel[0]) {
        double x = GAP + FONT_TEXT;
        fprintf(out, "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"middle\" transform=\"rotate(-90 %.1f %.1f)\">",
                x, cy, x, cy);
        put_xml(out, p->ylabel, MAX_TITLE_CHARS);
        fputs("</text>\n", out);
    }
}

/* Past the palette, colours repeat with a dash pattern so curves stay distinguishable. */
static void svg_stroke_attrs(FILE *out, int i)
{
    fprintf(out, "stroke=\"%s\"", PALETTE[i % NPALETTE]);
    if (i >= NPALETTE) fputs(" stroke-dasharray=\"6,3\"", out);
}

static void svg_marker(FILE *out, int shape, double x, double y)
{
    double r = MARKER_R;
    switch (shape % NMARKERS) {
    case 0: fprintf(out, "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"%.1f\"/>\n", x, y, r); break;
    case 1: fprintf(out, "<rect x=\"%.1f\" y=\"%.1f\" width=\"%.1f\" height=\"%.1f\"/>\n", x - r, y - r, 2 * r, 2 * r); break;
    case 2: fprintf(out, "<path d=\"M%.1f,%.1fl%.1f,%.1fh%.1fz\"/>\n", x, y - 1.2 * r, 1.2 * r, 2.1 * r, -2.4 * r); break;
    case 3: fprintf(out, "<path d=\"M%.1f,%.1fl%.1f,%.1fl%.1f,%.1fl%.1f,%.1fz\"/>\n", x, y - 1.3 * r, 1.3 * r, 1.3 * r,
                    -1.3 * r, 1.3 * r, -1.3 * r, -1.3 * r); break;
    case 4: fprintf(out, "<path d=\"M%.1f,%.1fl%.1f,%.1fh%.1fz\"/>\n", x, y + 1.2 * r, 1.2 * r, -2.1 * r, -2.4 * r); break;
    default: fprintf(out, "<path fill=\"none\" stroke-width=\"1.8\" d=\"M%.1f,%.1fl%.1f,%.1fm0,%.1fl%.1f,%.1f\"/>\n",
                     x - r, y - r, 2 * r, 2 * r, -2 * r, -2 * r, 2 * r); break;
    }
}

static void svg_legend(FILE *out, const struct plot *p)
{
    double w = p->leg_cols * p->leg_colw + 2 * LEG_PAD - GAP, h = p->leg_rows * LEG_ROW + 2 * LEG_PAD;
    fprintf(out, "<rect x=\"%.1f\" y=\"%.1f\" width=\"%.1f\" height=\"%.1f\" fill=\"white\" stroke=\"#bbb\"/>\n",
            p->leg_x, p->y0, w, h);
    for (int i = 0; i < p->n; i++) {
        double x = p->leg_x + LEG_PAD + (i / p->leg_rows) * p->leg_colw;
        double y = p->y0 + LEG_PAD + (i % p->leg_rows + 0.5) * LEG_ROW;
        fprintf(out, "<g fill=\"%s\">\n<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke-width=\"2\" ",
                PALETTE[i % NPALETTE], x, y, x + LEG_SWATCH, y);
        svg_stroke_attrs(out, i);
        fputs("/>\n", out);
        if (p->markers) {
            fprintf(out, "<g stroke=\"%s\">", PALETTE[i % NPALETTE]);
            svg_marker(out, i, x + 0.5 * LEG_SWATCH, y);
            fputs("</g>", out);
        }
        fprintf(out, "<text x=\"%.1f\" y=\"%.1f\" fill=\"#222\">", x + LEG_SWATCH + 6.0, y + 0.35 * FONT_TEXT);
        put_xml(out, p->name[i], MAX_LEGEND_CHARS);
        fputs("</text>\n</g>\n", out);
    }
}

static void svg_series_begin(FILE *out, int i)
{
    fputs("<path fill=\"none\" ", out);
    svg_stroke_attrs(out, i);
    fputs(" d=\"", out);
}

/* Emits one vertex of a path; drops vertices that land on the previous one at 0.1 px resolution. */
struct pen {
    FILE *out;
    long seg_pts;   /* vertices in the current subpath; 0: next vertex starts one */
    long lx, ly;    /* last vertex in tenths of a pixel */
};

static void pen_break(struct pen *pn)
{
    /* a lone sample between gaps would draw nothing as a line: mark it with a small plus */
    if (pn->seg_pts == 1) fputs("m-2,0h4m-2,-2v4", pn->out);
    pn->seg_pts = 0;
}

static void pen_to(struct pen *pn, double x, double y)
{
    long ix = lround(x * 10.0), iy = lround(y * 10.0);
    if (pn->seg_pts > 0 && ix == pn->lx && iy == pn->ly) return;
    fprintf(pn->out, "%s%.1f,%.1f", pn->seg_pts ? " " : "M", x, y);
    pn->seg_pts++;
    pn->lx = ix;
    pn->ly = iy;
}

static void svg_end(FILE *out)
{
    fputs("</svg>\n", out);
}

/* ------------------------------------------------------------------ options */

struct opts {
    const char *in, *out, *title, *cols, *xlabel, *ylabel;
    int xy, logx, logy, width, height;
    int lines;                 /* xy mode: curves without point markers (paths) */
};

static void usage(FILE *f)
{
    fputs("usage: svgplot [-o OUT.svg] [-t TITLE] [-c COLS] [-x XLABEL] [-y YLABEL] [-W WIDTH] [-H HEIGHT] TRACE.csv\n"
          "       svgplot --xy [--logx] [--logy] [--lines] [-c SERIES] [-x XLABEL] [-y YLABEL] [-o OUT.svg] [-t TITLE]\n"
          "               [-W WIDTH] [-H HEIGHT] TABLE.csv\n"
          "Trace mode: header 't,NAME,...'; plots every column (or the comma-separated -c names) against t;\n"
          "  -c NAME=LABEL,... gives a series its legend text.\n"
          "XY mode: header 'series,x,y'; one marked curve per series, in order of first appearance\n"
          "  (--lines: no markers, for paths; a 'nan,nan' row is a gap in a path).\n"
          "Writes SVG to stdout unless -o is given. Empty fields, nan and inf are gaps.\n",
          f);
}

static int parse_px(const char *opt, const char *s)
{
    char *end;
    long v = strtol(s, &end, 10);
    if (end == s || *end != '\0' || v < MIN_IMAGE_PX || v > MAX_IMAGE_PX)
        die("%s wants a whole number of pixels in %d..%d, got '%s'", opt, MIN_IMAGE_PX, MAX_IMAGE_PX, s);
    return (int)v;
}

static const char *opt_value(int argc, char **argv, int *i)
{
    if (*i + 1 >= argc) die("option %s needs a value (see svgplot --help)", argv[*i]);
    return argv[++*i];
}

static int parse_flag(struct opts *o, const char *a)
{
    if (!strcmp(a, "--xy")) o->xy = 1;
    else if (!strcmp(a, "--logx")) o->logx = 1;
    else if (!strcmp(a, "--logy")) o->logy = 1;
    else if (!strcmp(a, "--lines")) o->lines = 1;
    else if (!strcmp(a, "-h") || !strcmp(a, "--help")) { usage(stdout); exit(0); }
    else return 0;
    return 1;
}

static void parse_opts(struct opts *o, int argc, char **argv)
{
    *o = (struct opts){.width = DEFAULT_W, .height = DEFAULT_H};
    int only_files = 0;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (only_files || a[0] != '-' || a[1] == '\0') {
            if (o->in) die("more than one input file ('%s' and '%s')", o->in, a);
            o->in = a;
        } else if (!strcmp(a, "--")) only_files = 1;
        else if (parse_flag(o, a)) continue;
        else if (!strcmp(a, "-o")) o->out = opt_value(argc, argv, &i);
        else if (!strcmp(a, "-t")) o->title = opt_value(argc, argv, &i);
        else if (!strcmp(a, "-c")) o->cols = opt_value(argc, argv, &i);
        else if (!strcmp(a, "-x")) o->xlabel = opt_value(argc, argv, &i);
        else if (!strcmp(a, "-y")) o->ylabel = opt_value(argc, argv, &i);
        else if (!strcmp(a, "-W")) o->width = parse_px("-W", opt_value(argc, argv, &i));
        else if (!strcmp(a, "-H")) o->height = parse_px("-H", opt_value(argc, argv, &i));
        else die("unknown option '%s' (see svgplot --help)", a);
    }
    if (!o->in) die("no input file (see svgplot --help)");
    if (!strcmp(o->in, "-")) die("reading stdin is not supported: pass a file name");
    if (!o->xy && (o->logx || o->logy)) die("--logx/--logy only apply with --xy");
    if (!o->title) o->title = basename_of(o->in);
}

/* Splits the -c list into names (in a caller buffer); returns their count. */
static int split_names(const char *list, char *buf, size_t bufsize, char **names)
{
    if (strlen(list) >= bufsize) die("-c list longer than %zu bytes", bufsize - 1);
    strcpy(buf, list);
    int n = 0;
    for (char *s = buf;;) {
        char *comma = strchr(s, ',');
        if (comma) *comma = '\0';
        char *name = trim(s);
        if (*name) {
            if (n == MAX_SERIES) die("-c names more than %d series (MAX_SERIES)", MAX_SERIES);
            names[n++] = name;
        }
        if (!comma) break;
        s = comma + 1;
    }
    if (n == 0) die("-c list '%s' names no column", list);
    return n;
}

/* ------------------------------------------------------------------ output file */

static FILE *open_output(const struct opts *o)
{
    if (!o->out) return stdout;
    FILE *f = fopen(o->out, "w");
    if (!f) die("cannot create '%s': %s", o->out, strerror(errno));
    g_out_path = o->out;
    return f;
}

static void close_output(FILE *out)
{
    int bad = fflush(out) != 0 || ferror(out);
    if (out != stdout) bad |= fclose(out) != 0;
    if (bad) {
        if (g_out_path) remove(g_out_path);
        die("write error on %s", g_out_path ? g_out_path : "stdout");
    }
}

/* ------------------------------------------------------------------ trace mode */

/* One pixel column of one signal, kept as M4 aggregation (first, min, max, last sample):
   drawing those four in order reproduces the column exactly, peaks included. */
struct sample {
    double t, y;
    long row;
};

struct bin {
    long n;
    struct sample first, lo, hi, last;
    unsigned char brk_before; /* a gap lies between the previous finite sample and this column */
    unsigned char inner_gap;  /* a gap lies inside the column: isolate it from both neighbours */
};

struct trace {
    int ncols;
    char colname[MAX_COLS][MAX_NAME + 1];
    int nsel, sel[MAX_SERIES];   /* plotted column indices */
    const char *label[MAX_SERIES]; /* legend text from -c NAME=LABEL, or NULL */
    long nrows, bad_t, nonmono_line;
    struct ranges r;
    long nfinite[MAX_SERIES];
    int pending_gap[MAX_SERIES]; /* a non-finite sample was seen since the last finite one */
};

static struct trace g_tr;
static struct bin g_bins[MAX_SERIES][MAX_IMAGE_PX];

static int find_col(const struct trace *tr, const char *name)
{
    for (int i = 1; i < tr->ncols; i++)
        if (!strcmp(tr->colname[i], name)) return i;
    return -1;
}

static void die_unknown_col(const struct trace *tr, const char *path, const char *name)
{
    char list[200] = "";
    size_t used = 0;
    for (int i = 1; i < tr->ncols && used + 8 < sizeof list; i++) {
        int w = snprintf(list + used, sizeof list - used, "%s%s", i > 1 ? ", " : "", tr->colname[i]);
        used += (w > 0) ? (size_t)w : 0;
    }
    if (used >= sizeof list - 1) strcpy(list + sizeof list - 5, "...");
    die("-c: no column '%s' in %s (it has: %s)", name, path, list);
}

static void trace_select(struct trace *tr, const struct opts *o)
{
    static char buf[MAX_LINE];
    char *names[MAX_SERIES];
    if (!o->cols) {
        if (tr->ncols - 1 > MAX_SERIES)
            die("%s has %d signal columns, more than %d (MAX_SERIES): pick some with -c", o->in, tr->ncols - 1,
                MAX_SERIES);
        tr->nsel = tr->ncols - 1;
        for (int i = 0; i < tr->nsel; i++) tr->sel[i] = i + 1;
        return;
    }
    tr->nsel = split_names(o->cols, buf, sizeof buf, names);
    for (int i = 0; i < tr->nsel; i++) {
        char *eq = strchr(names[i], '=');
        tr->label[i] = eq ? eq + 1 : NULL; /* NAME=LABEL: the legend says what it means */
        if (eq) *eq = 0;
        tr->sel[i] = find_col(tr, names[i]);
        if (tr->sel[i] < 0) die_unknown_col(tr, o->in, names[i]);
    }
}

static void trace_header(struct csv *c, struct trace *tr, const struct opts *o)
{
    csv_header(c, "t,Osc.x,Osc.v");
    if (c->nf == 3 && !strcmp(c->field[0], "series") && !strcmp(c->field[1], "x") && !strcmp(c->field[2], "y"))
        csv_die(c, "header 'series,x,y' is an xy table: use --xy");
    if (c->nf < 2) csv_die(c, "header has no signal column after '%s'", c->field[0]);
    tr->ncols = c->nf;
    for (int i = 0; i < c->nf; i++) strcpy(tr->colname[i], c->field[i]);
    trace_select(tr, o);
}

/* Checks a row and returns its t; NaN t (row skipped) is returned as is. */
static double trace_row_t(const struct csv *c, const struct trace *tr)
{
    csv_fields(c, tr->ncols, "as many as the header");
    return field_num(c, 0, tr->colname[0]);
}

static void trace_pass1(struct csv *c, struct trace *tr)
{
    double prev_t = -INFINITY;
    while (csv_next(c)) {
        double t = trace_row_t(c, tr);
        tr->nrows++;
        for (int s = 0; s < tr->nsel; s++) {
            double y = field_num(c, tr->sel[s], tr->colname[tr->sel[s]]);
            if (!isfinite(t) || !isfinite(y)) continue;
            tr->nfinite[s]++;
            extend(&tr->r.ymin, &tr->r.ymax, &tr->r.have_y, y);
        }
        if (!isfinite(t)) { tr->bad_t++; continue; }
        if (t < prev_t && !tr->nonmono_line) tr->nonmono_line = c->line;
        prev_t = t;
        extend(&tr->r.xmin, &tr->r.xmax, &tr->r.have_x, t);
    }
}

static void trace_warnings(const struct trace *tr, const char *path)
{
    if (tr->nrows == 0) die("%s: no data rows after the header", path);
    if (!tr->r.have_x) die("%s: no row has a finite t", path);
    if (tr->bad_t) warn("%s: %ld row(s) with non-finite t skipped", path, tr->bad_t);
    if (tr->nonmono_line)
        warn("%s:%ld: t decreases; curves are drawn in t order, not row order", path, tr->nonmono_line);
    for (int s = 0; s < tr->nsel; s++)
        if (tr->nfinite[s] == 0) warn("%s: column '%s' has no finite value", path, tr->colname[tr->sel[s]]);
}

static void bin_add(struct bin *b, double t, double y, long row, int *pending)
{
    struct sample smp = {t, y, row};
    if (b->n == 0) {
        b->first = b->lo = b->hi = b->last = smp;
        b->brk_before = (unsigned char)*pending;
    } else {
        if (*pending) b->inner_gap = 1;
        if (y < b->lo.y) b->lo = smp;
        if (y > b->hi.y) b->hi = smp;
        b->last = smp;
    }
    b->n++;
    *pending = 0;
}

static int bin_index(const struct axis *ax, double t, int nbins)
{
    double u = (t - ax->lo) / (ax->hi - ax->lo) * nbins;
    int b = !(u >= 0.0) ? 0 : u >= nbins ? nbins - 1 : (int)u; /* NaN: bin 0, never cast */
    return b;
}

static void trace_pass2(struct csv *c, struct trace *tr, const struct axis *ax, int nbins)
{
    while (csv_next(c)) {
        double t = trace_row_t(c, tr);
        for (int s = 0; s < tr->nsel; s++) {
            double y = field_num(c, tr->sel[s], tr->colname[tr->sel[s]]);
            if (!isfinite(t) || !isfinite(y)) {
                tr->pending_gap[s] = 1;
                continue;
            }
            bin_add(&g_bins[s][bin_index(ax, t, nbins)], t, y, c->line, &tr->pending_gap[s]);
        }
    }
}

/* The column's distinct samples in row order (at most four). */
static int bin_samples(const struct bin *b, struct sample out[4])
{
    const struct sample *cand[4] = {&b->first, &b->lo, &b->hi, &b->last};
    int n = 0;
    for (int i = 0; i < 4; i++) {
        int dup = 0;
        for (int j = 0; j < n; j++) dup |= out[j].row == cand[i]->row;
        if (!dup) out[n++] = *cand[i];
    }
    for (int i = 1; i < n; i++) /* insertion sort by row */
        for (int j = i; j > 0 && out[j].row < out[j - 1].row; j--) {
            struct sample tmp = out[j];
            out[j] = out[j - 1];
            out[j - 1] = tmp;
        }
    return n;
}

static void trace_series(FILE *out, const struct plot *p, int s, int nbins)
{
    struct pen pn = {out, 0, 0, 0};
    int prev_inner = 0;
    svg_series_begin(out, s);
    for (int b = 0; b < nbins; b++) {
        const struct bin *bn = &g_bins[s][b];
        if (bn->n == 0) continue;
        if (bn->brk_before || bn->inner_gap || prev_inner) pen_break(&pn);
        struct sample smp[4];
        int n = bin_samples(bn, smp);
        for (int i = 0; i < n; i++) pen_to(&pn, data_px(&p->ax, smp[i].t), data_px(&p->ay, smp[i].y));
        prev_inner = bn->inner_gap;
    }
    pen_break(&pn);
    fputs("\"/>\n", out);
}

static void run_trace(const struct opts *o)
{
    static struct csv c;
    struct trace *tr = &g_tr;
    c.f = open_input(o->in);
    c.path = o->in;
    trace_header(&c, tr, o);
    trace_pass1(&c, tr);
    trace_warnings(tr, o->in);

    struct plot p = {.W = o->width, .H = o->height, .title = o->title, .n = tr->nsel};
    p.xlabel = o->xlabel ? o->xlabel : !strcmp(tr->colname[0], "t") ? "t [s]" : tr->colname[0];
    p.ylabel = o->ylabel ? o->ylabel : "";
    for (int s = 0; s < tr->nsel; s++) p.name[s] = tr->label[s] ? tr->label[s] : tr->colname[tr->sel[s]];
    layout_y(&p, &tr->r, 0, PAD_TRACE_Y);
    layout_x(&p, &tr->r, 0, 0.0);

    /* second pass: one bin per pixel column of the plot area, fewer if that would exceed the
       vertex budget (each bin draws up to four vertices per curve) */
    int nbins = (int)(p.x1 - p.x0);
    if (nbins > MAX_TRACE_VERTICES / (4 * tr->nsel)) nbins = MAX_TRACE_VERTICES / (4 * tr->nsel);
    if (nbins > MAX_IMAGE_PX) nbins = MAX_IMAGE_PX;
    if (fseek(c.f, 0L, SEEK_SET) != 0) die("%s: cannot re-read the file (trace mode needs a regular file)", o->in);
    c.line = 0;
    if (!csv_next(&c)) die("%s: file changed while reading", o->in);
    trace_pass2(&c, tr, &p.ax, nbins);
    fclose(c.f);

    FILE *out = open_output(o);
    svg_begin(out, &p);
    svg_grid(out, &p);
    fputs("<g clip-path=\"url(#plotarea)\" stroke-width=\"1.5\" stroke-linejoin=\"round\" stroke-linecap=\"round\">\n",
          out);
    for (int s = 0; s < tr->nsel; s++) trace_series(out, &p, s, nbins);
    fputs("</g>\n", out);
    svg_axes(out, &p);
    svg_labels(out, &p);
    svg_legend(out, &p);
    svg_end(out);
    close_output(out);
}

/* ------------------------------------------------------------------ xy mode */

struct xy {
    int n;
    char name[MAX_SERIES][MAX_NAME + 1];
    long npts;
    char *want[MAX_SERIES]; /* -c filter, or none */
    int nwant;
    long skipped[MAX_SERIES], skip_line[MAX_SERIES];
};

static struct xy g_xy;
static double g_px[MAX_XY_POINTS], g_py[MAX_XY_POINTS];
static int g_ps[MAX_XY_POINTS];
static long g_pline[MAX_XY_POINTS];

static int xy_wanted(const struct xy *d, const char *name)
{
    if (d->nwant == 0) return 1;
    for (int i = 0; i < d->nwant; i++)
        if (!strcmp(d->want[i], name)) return 1;
    return 0;
}

static int xy_series(struct xy *d, const struct csv *c, const char *name)
{
    for (int i = 0; i < d->n; i++)
        if (!strcmp(d->name[i], name)) return i;
    if (d->n == MAX_SERIES) csv_die(c, "more than %d series (MAX_SERIES)", MAX_SERIES);
    if (strlen(name) > MAX_NAME) csv_die(c, "series name longer than %d bytes (MAX_NAME)", MAX_NAME);
    strcpy(d->name[d->n], name);
    return d->n++;
}

static int lower_eq(const char *a, const char *b)
{
    for (; *a && *b; a++, b++)
        if ((*a | 0x20) != *b) return 0;
    return *a == *b;
}

static void xy_read(struct csv *c, struct xy *d)
{
    csv_header(c, "series,x,y");
    if (c->nf != 3 || !lower_eq(c->field[0], "series") || !lower_eq(c->field[1], "x") || !lower_eq(c->field[2], "y"))
        csv_die(c, "expected header 'series,x,y', got %d column(s) starting '%.40s'", c->nf, c->field[0]);
    while (csv_next(c)) {
        csv_fields(c, 3, "series,x,y");
        if (c->field[0][0] == '\0') csv_die(c, "empty series name");
        double x = field_num(c, 1, "x"), y = field_num(c, 2, "y");
        if (!xy_wanted(d, c->field[0])) continue;
        if (d->npts == MAX_XY_POINTS) csv_die(c, "more than %d data rows (MAX_XY_POINTS)", MAX_XY_POINTS);
        g_ps[d->npts] = xy_series(d, c, c->field[0]);
        g_px[d->npts] = x;
        g_py[d->npts] = y;
        g_pline[d->npts] = c->line;
        d->npts++;
    }
}

static int xy_ok(const struct opts *o, long i)
{
    double x = g_px[i], y = g_py[i];
    return isfinite(x) && isfinite(y) && (!o->logx || x > 0.0) && (!o->logy || y > 0.0);
}

static void xy_ranges(const struct opts *o, struct xy *d, struct ranges *r)
{
    for (long i = 0; i < d->npts; i++) {
        if (xy_ok(o, i)) {
            ranges_add(r, g_px[i], g_py[i]);
            continue;
        }
        int s = g_ps[i];
        if (o->lines && isnan(g_px[i]) && isnan(g_py[i]))
            continue; /* a "nan,nan" row: a deliberate gap in a path */
        if (d->skipped[s]++ == 0) d->skip_line[s] = g_pline[i];
    }
    for (int s = 0; s < d->n; s++)
        if (d->skipped[s])
            warn("%s:%ld: skipped %ld point(s) of series '%s' that are not finite%s", o->in, d->skip_line[s],
                 d->skipped[s], d->name[s], (o->logx || o->logy) ? " or not positive on a log axis" : "");
    if (!r->have_x) warn("%s: no plottable point", o->in);
}

static void xy_check_wanted(const struct opts *o, const struct xy *d)
{
    for (int i = 0; i < d->nwant; i++) {
        int found = 0;
        for (int s = 0; s < d->n; s++) found |= !strcmp(d->name[s], d->want[i]);
        if (!found) die("-c: no series '%s' in %s", d->want[i], o->in);
    }
}

static void xy_series_out(FILE *out, const struct opts *o, const struct plot *p, const struct xy *d, int s)
{
    struct pen pn = {out, 0, 0, 0};
    svg_series_begin(out, s);
    for (long i = 0; i < d->npts; i++) {
        if (g_ps[i] != s)
            continue;
        if (xy_ok(o, i))
            pen_to(&pn, data_px(&p->ax, g_px[i]), data_px(&p->ay, g_py[i]));
        else if (o->lines)
            pen_break(&pn); /* a gap: the path does not join across it */
    }
    fputs("\"/>\n", out); /* no pen_break: the markers already show lone points */
    if (!p->markers)
        return;
    fprintf(out, "<g fill=\"%s\" stroke=\"%s\">\n", PALETTE[s % NPALETTE], PALETTE[s % NPALETTE]);
    for (long i = 0; i < d->npts; i++)
        if (g_ps[i] == s && xy_ok(o, i)) svg_marker(out, s, data_px(&p->ax, g_px[i]), data_px(&p->ay, g_py[i]));
    fputs("</g>\n", out);
}

static void run_xy(const struct opts *o)
{
    static struct csv c;
    static char wantbuf[MAX_LINE];
    struct xy *d = &g_xy;
    if (o->cols) d->nwant = split_names(o->cols, wantbuf, sizeof wantbuf, d->want);
    c.f = open_input(o->in);
    c.path = o->in;
    xy_read(&c, d);
    fclose(c.f);
    xy_check_wanted(o, d);
    if (d->npts == 0) die("%s: no data rows after the header", o->in);
    struct ranges r = {0};
    xy_ranges(o, d, &r);

    struct plot p = {.W = o->width, .H = o->height, .title = o->title, .n = d->n,
                     .markers = !o->lines};
    p.xlabel = o->xlabel ? o->xlabel : "x";
    p.ylabel = o->ylabel ? o->ylabel : "y";
    for (int s = 0; s < d->n; s++) p.name[s] = d->name[s];
    layout_y(&p, &r, o->logy, PAD_XY);
    layout_x(&p, &r, o->logx, PAD_XY);

    FILE *out = open_output(o);
    svg_begin(out, &p);
    svg_grid(out, &p);
    /* not clipped: every point lies inside the axis range, and markers on the frame stay whole */
    fputs("<g stroke-width=\"1.5\" stroke-linejoin=\"round\">\n", out);
    for (int s = 0; s < d->n; s++) xy_series_out(out, o, &p, d, s);
    fputs("</g>\n", out);
    svg_axes(out, &p);
    svg_labels(out, &p);
    svg_legend(out, &p);
    svg_end(out);
    close_output(out);
}

int main(int argc, char **argv)
{
    struct opts o;
    parse_opts(&o, argc, argv);
    if (o.xy) run_xy(&o);
    else run_trace(&o);
    return 0;
}
