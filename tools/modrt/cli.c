/* cli.c - option parsing and the shared helpers of the modrt subcommands (cli.h). */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "fmu_scn.h"
#include "models.h"
#include "scn_host.h"

int cli_fail(const char *what, const char *detail)
{
    fprintf(stderr, "modrt: %s%s%s\n", what, detail ? ": " : "", detail ? detail : "");
    return CLI_USAGE;
}

int cli_real(const char *s, double *v)
{
    char *end;
    errno = 0;
    *v = strtod(s, &end);
    /* an underflow (ERANGE with a result of at most DBL_MIN: a subnormal, or 0 below
       it) is the nearest value there is; an overflow is infinite and refused */
    return *s && !*end && (errno == 0 || (errno == ERANGE && fabs(*v) <= DBL_MIN)) &&
           *v == *v && *v - *v == 0;
}

int cli_uint(const char *s, unsigned long lo, unsigned long hi, unsigned long *v)
{
    char *end;
    if (*s < '0' || *s > '9')
        return 0;
    errno = 0;
    *v = strtoul(s, &end, 10);
    return !*end && errno == 0 && *v >= lo && *v <= hi;
}

const char *cli_fmt(char *buf, size_t n, double v)
{
    for (int prec = 1; prec <= 17; prec++) { /* the first precision that round-trips */
        snprintf(buf, n, "%.*g", prec, v);
        if (strtod(buf, NULL) == v)
            break;
    }
    return buf;
}

int cli_exit_code(int sev)
{
    return sev == 0 ? CLI_OK : sev == 1 ? CLI_DOUBTFUL : CLI_FAULTS;
}

int cli_set_param(const rt_scene *sc, rt_sim *sim, const char *arg)
{
    char buf[128];
    double v;
    if (strlen(arg) >= sizeof buf)
        return cli_fail("--set argument too long", arg);
    strcpy(buf, arg);
    char *dot = strchr(buf, '.'), *eq = strchr(buf, '=');
    if (!dot || !eq || eq < dot)
        return cli_fail("--set expects BLOCK.PARAM=VALUE, got", arg);
    *dot = 0, *eq = 0;
    if (!cli_real(eq + 1, &v))
        return cli_fail("--set value is not a finite number", arg);
    if (rt_block_index(sc, buf) < 0)
        return cli_fail("--set: unknown block", buf);
    rt_status st = rt_set_param(sc, sim, buf, dot + 1, (real_t)v);
    if (st == RT_E_PARAM) /* the runtime may say why (a time event off the grid) */
        return cli_fail(rt_error_text(sim)[0] ? rt_error_text(sim)
                                              : "--set: value out of range for the parameter",
                        arg);
    if (st != RT_OK)
        return cli_fail("--set: block has no parameter or state named", dot + 1);
    return CLI_OK;
}

int cli_refresh(const rt_scene *sc, rt_sim *sim)
{
    rt_status st = rt_refresh(sc, sim);
    return st == RT_OK ? CLI_OK : cli_fail("--set: the initial state is refused",
                                           rt_error_text(sim));
}

void cli_rec_name(const rt_scene *sc, uint16_t i, char *buf, size_t n)
{
    snprintf(buf, n, "%s.%s", sc->blocks[sc->recs[i].block].name, rt_rec_signal(sc, i));
}

int cli_selected(const char *name, const char *list)
{
    if (!list)
        return 1;
    for (const char *p = list; *p;) {
        size_t len = strcspn(p, ",");
        if (len > 0 && strncmp(name, p, len) == 0)
            return 1;
        p += len + (p[len] == ',');
    }
    return 0;
}

const rt_scene *cli_scene(const char *name)
{
    if (scn_host_is_file(name)) /* the scene compiler says what is wrong with a file */
        return scn_host_load(name, &fmu_scn_ops);
    for (const rt_scene_entry *e = mdl_scenes; e->name; e++)
        if (strcmp(e->name, name) == 0)
            return e->scene;
    cli_fail("unknown scene (modrt list names them)", name);
    return NULL;
}

static void help(const cli_cmd *c)
{
    printf("usage: modrt %s%s%s%s\n%s\n", c->name, c->args ? " " : "", c->args ? c->args : "",
           c->opts ? " [options]" : "", c->summary);
    if (c->help)
        printf("\n%s\n", c->help);
    printf("\noptions:\n");
    for (const cli_opt *o = c->opts; o && o->name; o++) {
        char lhs[80];
        snprintf(lhs, sizeof lhs, "--%s%s%s", o->name, o->arg ? "=" : "", o->arg ? o->arg : "");
        printf("  %-24s %s\n", lhs, o->help);
    }
    printf("  %-24s %s\n", "-h, --help", "this text");
}

static const cli_opt *find_opt(const cli_cmd *c, const char *name, size_t len)
{
    for (const cli_opt *o = c->opts; o && o->name; o++)
        if (strlen(o->name) == len && strncmp(o->name, name, len) == 0)
            return o;
    return NULL;
}

/* one option word at argv[*i] (and its value at argv[*i + 1] when not given with '=') */
static int option(const cli_cmd *c, int argc, char **argv, int *i)
{
    const char *w = argv[*i] + 2, *eq = strchr(w, '=');
    const cli_opt *o = find_opt(c, w, eq ? (size_t)(eq - w) : strlen(w));
    char msg[96];
    snprintf(msg, sizeof msg, "%s: unknown option (modrt %s --help lists them)", c->name,
             c->name);
    if (!o)
        return cli_fail(msg, argv[*i]);
    if (!o->arg) {
        if (eq)
            return cli_fail("option takes no value", argv[*i]);
        return o->set(c->ctx, NULL);
    }
    if (eq)
        return o->set(c->ctx, eq + 1);
    if (*i + 1 >= argc) {
        snprintf(msg, sizeof msg, "option needs a value (--%s=%s)", o->name, o->arg);
        return cli_fail(msg, argv[*i]);
    }
    return o->set(c->ctx, argv[++*i]);
}

int cli_dispatch(const cli_cmd *c, int argc, char **argv)
{
    char *pos[CLI_POS_MAX];
    int npos = 0, opts_done = 0;
    for (int i = 0; i < argc && strcmp(argv[i], "--") != 0; i++) {
        const char *w = argv[i];
        if (strcmp(w, "--help") == 0 || strcmp(w, "-h") == 0) {
            help(c);
            return CLI_OK;
        }
    }
    for (int i = 0; i < argc; i++) {
        const char *w = argv[i];
        int st;
        if (!opts_done && strcmp(w, "--") == 0) {
            opts_done = 1;
        } else if (!opts_done && w[0] == '-' && w[1] == '-' && w[2]) {
            if ((st = option(c, argc, argv, &i)) != CLI_OK)
                return st;
        } else if (!opts_done && w[0] == '-' && w[1]) {
            return cli_fail("options are long (--name); unknown option", w);
        } else if (npos < c->npos_max && npos < CLI_POS_MAX) {
            pos[npos++] = argv[i];
        } else {
            char msg[64];
            snprintf(msg, sizeof msg, "%s: unexpected argument", c->name);
            return cli_fail(msg, w);
        }
    }
    if (npos < c->npos_min) {
        char msg[96];
        snprintf(msg, sizeof msg, "%s needs %s (modrt %s --help)", c->name, c->args, c->name);
        return cli_fail(msg, NULL);
    }
    return c->run(c->ctx, npos, pos);
}

int cli_end_time(rt_scene *sc, double t_end, const char *what)
{
    double n = t_end / (double)sc->dt;
    char b[200], v[32];
    snprintf(v, sizeof v, "%.10g", t_end);
    if (!(n >= 0 && n <= (double)RT_MAX_TICKS)) {
        snprintf(b, sizeof b, "%s: at most %.10g s with the scene's base tick of %.10g s "
                 "(2^53 ticks), got", what, (double)RT_MAX_TICKS * (double)sc->dt,
                 (double)sc->dt);
        return cli_fail(b, v);
    }
    /* the same slack as rt_init: the rounding of real_t, at most a quarter tick */
    double slack = (double)RT_TICK_SLACK * (n > 1 ? n : 1), off = n - (double)(uint64_t)(n + 0.5);
    if ((off < 0 ? -off : off) > (slack < 0.25 ? slack : 0.25)) {
        snprintf(b, sizeof b, "%s must be a whole number of base ticks (%.10g s), got", what,
                 (double)sc->dt);
        return cli_fail(b, v);
    }
    sc->t_end = (real_t)t_end;
    return CLI_OK;
}
