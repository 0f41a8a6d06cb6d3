/* info.c - `modrt info SCENE|KIND`, `modrt kinds` and the block reference docs/blocks.md,
 * all printed from the const tables (rt_scene, rt_kind) and an initialised rt_sim. */
#include <string.h>

#include "cli.h"
#include "info.h"
#include "models.h"

/* ------------------------------------------------------------------ small helpers */

const rt_kind *info_find_kind(const char *name)
{
    for (const mdl_entry *e = mdl_kinds; e->name; e++)
        if (strcmp(e->name, name) == 0)
            return e->kind;
    return NULL;
}

/* the shortest round-trip text of v */
static const char *num(char *buf, double v)
{
    return cli_fmt(buf, 32, v);
}

/* a JSON string (names and reference text are ASCII or UTF-8) */
static void jstr(FILE *f, const char *s)
{
    fputc('"', f);
    for (; s && *s; s++) {
        if (*s == '"' || *s == '\\')
            fprintf(f, "\\%c", *s);
        else if (*s == '\n')
            fputs("\\n", f);
        else if ((unsigned char)*s < 0x20)
            fprintf(f, "\\u%04x", (unsigned)(unsigned char)*s);
        else
            fputc(*s, f);
    }
    fputc('"', f);
}

/* unit number i of a kind's units string into buf ("" when the kind gives none) */
static const char *unit(const rt_kind *k, unsigned i, char *buf, size_t n)
{
    const char *s = k->units;
    buf[0] = 0;
    while (s && *s && i > 0) { /* skip i tokens */
        while (*s && *s != ' ')
            s++;
        while (*s == ' ')
            s++;
        i--;
    }
    size_t len = 0;
    while (s && s[len] && s[len] != ' ' && len + 1 < n)
        len++;
    if (s)
        memcpy(buf, s, len), buf[len] = 0;
    return buf;
}

static const char *feed_name(rt_feed f)
{
    static const char *const names[] = {"none", "all", "table"};
    return (unsigned)f < 3 ? names[f] : "?";
}

/* ------------------------------------------------------------------ kinds */

/* the ports and values of one group: inputs, outputs, states, discrete states, params */
typedef struct group {
    const char *title;
    uint16_t n;
    const char *const *names;
    const real_t *defaults; /* NULL: none shown (ports), or all zero (states) */
    int has_default;
} group;

static void kind_groups(const rt_kind *k, group g[5])
{
    g[0] = (group){"inputs", k->nu, k->u_names, NULL, 0};
    g[1] = (group){"outputs", k->ny, k->y_names, NULL, 0};
    g[2] = (group){"states", k->nx, k->x_names, k->x_default, 1};
    g[3] = (group){"discrete states", k->nd, k->d_names, k->d_default, 1};
    g[4] = (group){"parameters", k->np, k->p_names, k->p_default, 1};
}

static void kind_text(FILE *f, const rt_kind *k)
{
    group g[5];
    char b[32], u[32];
    unsigned ui = 0;
    kind_groups(k, g);
    fprintf(f, "kind: %s\ntype: %s\nthroughput: %s\nroots: %u\n", k->name,
            rt_kind_type_name(k->type), feed_name(k->feed), k->nr);
    if (k->doc)
        fprintf(f, "%s\n", k->doc);
    for (int i = 0; i < 5; i++) {
        fprintf(f, "%s: %u\n", g[i].title, g[i].n);
        for (uint16_t j = 0; j < g[i].n; j++, ui++) {
            const char *name = g[i].names ? g[i].names[j] : "?";
            fprintf(f, "  %-14s [%s]", name, unit(k, ui, u, sizeof u)[0] ? u : "?");
            if (g[i].has_default)
                fprintf(f, "  default %s", num(b, g[i].defaults ? (double)g[i].defaults[j] : 0));
            fputc('\n', f);
        }
    }
}

static void kind_json(FILE *f, const rt_kind *k)
{
    group g[5];
    char b[32], u[32];
    unsigned ui = 0;
    static const char *const keys[] = {"inputs", "outputs", "states", "dstates", "parameters"};
    kind_groups(k, g);
    fputs("{\"kind\": ", f);
    jstr(f, k->name);
    fprintf(f, ", \"type\": \"%s\", \"throughput\": \"%s\", \"roots\": %u, \"doc\": ",
            rt_kind_type_name(k->type), feed_name(k->feed), k->nr);
    jstr(f, k->doc);
    for (int i = 0; i < 5; i++) {
        fprintf(f, ", \"%s\": [", keys[i]);
        for (uint16_t j = 0; j < g[i].n; j++, ui++) {
            fputs(j ? ", {\"name\": " : "{\"name\": ", f);
            jstr(f, g[i].names ? g[i].names[j] : "?");
            fputs(", \"unit\": ", f);
            jstr(f, unit(k, ui, u, sizeof u));
            if (g[i].has_default)
                fprintf(f, ", \"default\": %s",
                        num(b, g[i].defaults ? (double)g[i].defaults[j] : 0));
            fputc('}', f);
        }
        fputc(']', f);
    }
    fputs("}\n", f);
}

void info_kind(FILE *f, const rt_kind *k, int json)
{
    if (json)
        kind_json(f, k);
    else
        kind_text(f, k);
}

/* the first sentence (up to the first newline) of a kind's text, for listings */
static void first_line(FILE *f, const char *doc)
{
    size_t n = doc ? strcspn(doc, "\n") : 0;
    fprintf(f, "%.*s", (int)n, doc ? doc : "");
}

void info_kinds(FILE *f)
{
    for (const mdl_entry *e = mdl_kinds; e->name; e++) {
        fprintf(f, "%-16s %-6s ", e->name, rt_kind_type_name(e->kind->type));
        first_line(f, e->kind->doc);
        fputc('\n', f);
    }
}

const rt_joint_kind *info_find_joint(const char *name)
{
    for (const rt_joint_entry *e = rt_joint_kinds; e->name; e++)
        if (strcmp(e->name, name) == 0)
            return e->kind;
    return NULL;
}

void info_joint(FILE *f, const rt_joint_kind *k)
{
    fprintf(f, "joint kind %s: %u constraint equations\n", k->name, k->nc);
    fputs("nodes: node 1 = the first of link(A.node, B.node | ground ...), node 2 = the "
          "second (ground: an anchor at `at`, turned by `rotated`)\n", f);
    fputs("parameters:", f);
    for (uint8_t i = 0; i < k->np; i++)
        fprintf(f, " %s", k->p_names[i]);
    fprintf(f, "%s; axis = (x, y, z) (the joint axis in both node frames, default z)\n",
            k->np ? "" : " none");
    fprintf(f, "%s\nfree: %s\n", k->doc ? k->doc : "", k->free ? k->free : "?");
}

/* a cart on a horizontal rail and a slider on an incline, as a newcomer writes them:
   tests/cli.sh checks that it is tests/scenec/scenes/lang_rail.scn, which
   tests/scenec/test_scenec.c holds to the closed form */
static const char rail_example[] =
    "// lang_rail.scn - a cart on a horizontal rail and a slider on a 30-degree incline: prismatic\n"
    "// joints given their axis (J.axis), no quaternion worked out by hand (docs/blocks.md,\n"
    "// Joints; tests/scenec/test_scenec.c checks it against the closed form).\n"
    "scene (lang_rail) doc (\"a cart on a horizontal rail, a slider on a 30-degree incline\");\n"
    "base tick (1 ms);\n"
    "end time (1 s);\n"
    "load system (Cart, Slider) of type (mbs_body) from file (\"mbs_body\");\n"
    "Cart.m = 2;  Cart.z = 0.5;  Cart.vx = 1.5;   // rolls along x at 1.5 m/s, 0.5 m up\n"
    "load joint (Rail, Incline) of type (prismatic);\n"
    "Rail.axis = (1, 0, 0);                        // slides along x\n"
    "Incline.axis = (0.8660254037844386, 0, 0.5);  // along (cos 30, 0, sin 30)\n"
    "link(Cart.cm, ground at (0, 0, 0.5)) by (Rail);\n"
    "link(Slider.cm, ground) by (Incline);\n"
    "set (mbs) method (rk4) step (1 tick);\n"
    "stabilization (project);\n"
    "record (Cart.x, Cart.z, Slider.x, Slider.z, Rail.fz);\n"
;

static void joints_md(FILE *f)
{
    fputs("\n# Joint kinds\n\nGenerated from the joint tables (`rt/joints.c`, fields `doc` and "
          "`free`); `modrt info JOINT` prints one. A joint links node 1 (the first node of "
          "`link(...)`) with node 2 or an anchor (`ground at (x, y, z) rotated (a deg about "
          "(x, y, z))`); `J.axis = (x, y, z)` turns the joint frame in both node frames so that "
          "its z axis is the given direction.\n\n| joint | equations | parameters | free |\n"
          "|---|---|---|---|\n", f);
    for (const rt_joint_entry *e = rt_joint_kinds; e->name; e++) {
        fprintf(f, "| [`%s`](#joint-%s) | %u | ", e->name, e->name, e->kind->nc);
        for (uint8_t i = 0; i < e->kind->np; i++)
            fprintf(f, "%s`%s`", i ? ", " : "", e->kind->p_names[i]);
        fprintf(f, "%s`axis` | %s |\n", e->kind->np ? ", " : "",
                e->kind->free ? e->kind->free : "?");
    }
    for (const rt_joint_entry *e = rt_joint_kinds; e->name; e++) {
        fprintf(f, "\n## joint %s\n\n```\n", e->name);
        info_joint(f, e->kind);
        fputs("```\n", f);
    }
    fprintf(f, "\n## Example: a cart on a rail\n\nA body on a prismatic joint to an anchor "
               "slides along the joint axis; `J.axis` points it, no quaternion needed. "
               "`modrt run` this file (`tests/scenec/scenes/lang_rail.scn`): the cart keeps "
               "z = 0.5 m and 1.5 m/s with the reaction `Rail.fz` = m g = 19.62 N, the slider "
               "moves g sin 30 t^2 / 2 down its incline.\n\n```\n%s```\n", rail_example);
}

void info_blocks_md(FILE *f)
{
    fputs("# Block reference\n\nGenerated by `modrt docs-blocks` from the kinds' const tables "
          "(`models/*.c`, fields `doc` and `units`), so it cannot drift from the code. "
          "`modrt info KIND` prints the same for one kind; `modrt kinds` lists them.\n\n"
          "A kind that switches (its right-hand side or outputs jump: contact, dry friction, "
          "a relay) declares each switching function as a root, so the runtime locates the "
          "switch as a state event and no step, and no finite-difference Jacobian, spans "
          "both laws (rt/step.c, docs/solvers.md); column *switches* gives their number.\n\n"
          "| kind | type | switches | what |\n|---|---|---|---|\n", f);
    for (const mdl_entry *e = mdl_kinds; e->name; e++) {
        fprintf(f, "| [`%s`](#%s) | %s | ", e->name, e->name, rt_kind_type_name(e->kind->type));
        if (e->kind->nr)
            fprintf(f, "%u root%s ", (unsigned)e->kind->nr, e->kind->nr > 1 ? "s" : "");
        fputs("| ", f);
        first_line(f, e->kind->doc);
        fputs(" |\n", f);
    }
    for (const mdl_entry *e = mdl_kinds; e->name; e++) {
        fprintf(f, "\n## %s\n\n```\n", e->name);
        kind_text(f, e->kind);
        fputs("```\n", f);
    }
    joints_md(f);
}

/* ------------------------------------------------------------------ scenes */

/* parameter p of block b as the scene gives it (its value, or the kind's default) */
static double param(const rt_block *bl, uint16_t p)
{
    const real_t *v = bl->p ? bl->p : bl->kind->p_default;
    return v ? (double)v[p] : 0;
}

static void scene_blocks(FILE *f, const rt_scene *sc)
{
    char b[32];
    fprintf(f, "blocks: %u\n", sc->nblocks);
    for (uint16_t i = 0; i < sc->nblocks; i++) {
        const rt_block *bl = &sc->blocks[i];
        const rt_kind *k = bl->kind;
        fprintf(f, "  %-10s %-12s %-6s set %s  nu %u ny %u nx %u nd %u np %u nr %u",
                bl->name, k->name, rt_kind_type_name(k->type), sc->sets[bl->set].name, k->nu,
                k->ny, k->nx, k->nd, k->np, k->nr);
        if (k->type == RT_KIND_DSS)
            fprintf(f, "  period %s s", num(b, (double)bl->ts));
        fputc('\n', f);
        if (k->np == 0)
            continue;
        fputs("             ", f);
        for (uint16_t p = 0; p < k->np; p++)
            fprintf(f, " %s=%s", k->p_names[p], num(b, param(bl, p)));
        fputc('\n', f);
    }
}

/* the settings that apply to a set's method with their values (RT_SET_CFG_LIST, its
   defaults filled in), after the accuracy: "absolute" for its second value */
static void set_settings(FILE *f, const rt_set *st)
{
    char a[32];
    rt_set_cfg d = rt_set_cfg_of(&st->cfg);
    for (int id = 0; id < RT_CFG_N; id++) {
        const rt_set_opt *o = &rt_set_opts[id];
        real_t v = rt_set_cfg_get(&d, (rt_cfg_id)id);
        if (id == RT_CFG_ACCURACY || (o->scope == RT_CFG_ITER && !rt_method_iterates(st->method)))
            continue;
        if (o->kind == RT_CFG_PAIR) {
            if (v > 0) /* |e_i| <= atol + accuracy |x_i| (docs/solvers.md) */
                fprintf(f, ", absolute %s", num(a, (double)v));
            continue;
        }
        fprintf(f, ", %s %s", o->word, num(a, (double)v));
    }
}

/* one set: method, step, and the most work one of its steps can take (the implicit
   methods' retries and substeps included: docs/solvers.md, "Bounded work") */
static void scene_set(FILE *f, const rt_scene *sc, uint8_t s)
{
    char b[32], t[32], a[32];
    const rt_set *st = &sc->sets[s];
    uint16_t n = 0;
    for (uint16_t i = 0; i < sc->nblocks; i++)
        n = (uint16_t)(n + (sc->blocks[i].set == s ? sc->blocks[i].kind->nx : 0));
    rt_step_work w = rt_step_bound(sc, s, n);
    fprintf(f, "  %-10s %-8s step %s s (%u ticks of %s s); %u states; worst step %u "
               "right-hand sides, %u factorizations; accuracy %s",
            st->name, st->method->name, num(b, (double)rt_set_step(sc, s)),
            (unsigned)st->ratio, num(t, (double)sc->dt), (unsigned)n, (unsigned)w.rhs,
            (unsigned)w.lu,
            num(a, (double)rt_set_cfg_of(&st->cfg).accuracy));
    set_settings(f, st);
    fputc('\n', f);
    if (st->background)
        fprintf(f, "  %-10s background: each step released at its communication point, "
                   "published at the next (rt/bg.c)\n", "");
}

static void scene_wiring(FILE *f, const rt_scene *sc)
{
    char b[32];
    fprintf(f, "connections: %u\n", sc->nconns);
    for (uint16_t c = 0; c < sc->nconns; c++) {
        const rt_conn *cn = &sc->conns[c];
        const rt_block *from = &sc->blocks[cn->from], *to = &sc->blocks[cn->to];
        fprintf(f, "  %s.%s -> %s.%s\n", from->name, from->kind->y_names[cn->y], to->name,
                to->kind->u_names[cn->u]);
    }
    for (uint16_t j = 0; j < sc->njoints; j++) {
        const rt_joint *jt = &sc->joints[j];
        fprintf(f, "  joint %s: %s -- %s\n", jt->name, sc->blocks[jt->b1].name,
                jt->b2 >= 0 ? sc->blocks[jt->b2].name : "inertial point");
    }
    for (uint16_t i = 0; i < sc->ndefaults; i++) {
        const rt_default *d = &sc->defaults[i];
        fprintf(f, "  %s -> %s.%s\n", num(b, (double)d->value), sc->blocks[d->block].name,
                sc->blocks[d->block].kind->u_names[d->u]);
    }
    fprintf(f, "sets: %u\n", sc->nsets);
    for (uint8_t s = 0; s < sc->nsets; s++)
        scene_set(f, sc, s);
}

static uint32_t gcd(uint32_t a, uint32_t b)
{
    while (b) {
        uint32_t r = a % b;
        a = b, b = r;
    }
    return a;
}

#define INFO_SCHED_TICKS 24 /* ticks of the schedule's period shown */

/* the fixed schedule: step order within a tick, which sets step at which tick over one
   period of the ratios, and the signals that cross sets with their reconstruction */
static void scene_schedule(FILE *f, const rt_scene *sc, const rt_sim *s)
{
    uint32_t period = 1; /* least common multiple of the ratios */
    for (uint8_t i = 0; i < sc->nsets; i++)
        period = period / gcd(period, sc->sets[i].ratio) * sc->sets[i].ratio;
    fprintf(f, "schedule: slowest first:");
    for (uint8_t i = 0; i < sc->nsets; i++)
        fprintf(f, " %s", sc->sets[rt_set_at(s, i)].name);
    fprintf(f, "; period %u ticks\n", (unsigned)period);
    for (uint32_t k = 0; k < period && k < INFO_SCHED_TICKS; k++) {
        fprintf(f, "  tick %2u:", (unsigned)k);
        for (uint8_t i = 0; i < sc->nsets; i++)
            if (k % sc->sets[rt_set_at(s, i)].ratio == 0)
                fprintf(f, " %s", sc->sets[rt_set_at(s, i)].name);
        fputc('\n', f);
    }
    /* a tick's worst case: the method's bound for every re-step of event location and
       every part at a known time event, with the probes and coupling checks */
    for (uint8_t i = 0; i < sc->nsets; i++) {
        rt_step_work w = rt_set_step_bound(sc, s, i);
        fprintf(f, "  %s: a whole step at most %u right-hand sides, %u factorizations "
                   "(events, time-event parts, coupling checks)\n",
                sc->sets[i].name, (unsigned)w.rhs, (unsigned)w.lu);
    }
    for (uint16_t c = 0; c < sc->nconns; c++) {
        const rt_conn *cn = &sc->conns[c];
        rt_interp how;
        rt_src_kind src = rt_input_source(s, cn->to, cn->u, &how);
        if (src != RT_SRC_XSET && src != RT_SRC_HELD)
            continue;
        fprintf(f, "  across sets: %s.%s -> %s.%s by %s\n", sc->blocks[cn->from].name,
                sc->blocks[cn->from].kind->y_names[cn->y], sc->blocks[cn->to].name,
                sc->blocks[cn->to].kind->u_names[cn->u],
                src == RT_SRC_HELD ? "zero-order hold from its sample instant (a sampled "
                                     "output is piecewise constant; no delay where its "
                                     "period is a whole number of the reader's steps)"
                : sc->sets[sc->blocks[cn->from].set].background && how != RT_INTERP_HOLD
                    ? "extrapolation of the background set's history (its jumps faded)"
                    : rt_interp_name(how));
    }
}

/* a torn input as "From.y -> To.u" */
static void print_torn(FILE *f, const rt_scene *sc, const rt_sim *s, uint16_t k)
{
    rt_torn e = rt_torn_at(sc, s, k);
    fprintf(f, " %s.%s -> %s.%s;", sc->blocks[e.from].name, sc->blocks[e.from].kind->y_names[e.y],
            sc->blocks[e.to].name, sc->blocks[e.to].kind->u_names[e.u]);
}

static void scene_order(FILE *f, const rt_scene *sc, const rt_sim *s)
{
    fprintf(f, "evaluation order:");
    for (uint16_t i = 0; i < rt_seq_count(s); i++) {
        rt_seq_step st = rt_seq_at(s, i);
        if (st.kind == RT_SEQ_LOOP)
            fprintf(f, " [loop %u:", (unsigned)st.index);
        else
            fprintf(f, " %s", sc->blocks[st.index].name);
        for (uint8_t l = 0; l < rt_loop_count(s); l++)
            if (rt_loop_at(s, l)->actual && rt_loop_at(s, l)->seq1 == i + 1)
                fprintf(f, " ]");
    }
    fprintf(f, "\nloops: %u\n", rt_loop_count(s));
    for (uint8_t l = 0; l < rt_loop_count(s); l++) {
        const rt_loop *lp = rt_loop_at(s, l);
        fprintf(f, "  %u %s:", (unsigned)l, lp->actual ? "actual" : "potential");
        for (uint16_t i = 0; i < lp->nblocks; i++)
            fprintf(f, " %s", sc->blocks[rt_loop_block(s, l, i)].name);
        if (lp->actual) {
            fprintf(f, "; torn:");
            for (uint16_t k = lp->torn0; k < lp->torn0 + lp->ntorn; k++)
                print_torn(f, sc, s, k);
        } else {
            fprintf(f, "; solved by ordering");
        }
        fputc('\n', f);
    }
}

/* the controller link: what is sent and received, how often, and its identity */
static void scene_link(FILE *f, const rt_scene *sc)
{
    const rt_link *l = sc->link;
    if (!l)
        return;
    fprintf(f, "link: controller %s, every %u ticks, id 0x%08x (docs/link.md)\n  exports:",
            l->name, (unsigned)l->period, (unsigned)l->id);
    for (uint16_t i = 0; i < l->nexp; i++) /* an export reads like a recorded signal */
        fprintf(f, " %s.%s", sc->blocks[l->exp[i].block].name,
                l->exp[i].what == RT_SIG_Y ? sc->blocks[l->exp[i].block].kind->y_names[l->exp[i].index]
                : l->exp[i].what == RT_SIG_X ? sc->blocks[l->exp[i].block].kind->x_names[l->exp[i].index]
                : l->exp[i].what == RT_SIG_D ? sc->blocks[l->exp[i].block].kind->d_names[l->exp[i].index]
                                             : "(multibody)");
    fprintf(f, "\n  imports:");
    for (uint16_t i = 0; i < l->nimp; i++)
        fprintf(f, " %s.%s = %.17g %s", l->name, sc->blocks[l->block].kind->y_names[i],
                (double)l->def[i], rt_link_policy_name(l->policy[i]));
    fputc('\n', f);
}

static void scene_text(FILE *f, const rt_scene *sc, const rt_sim *sim, rt_status init)
{
    char b[32], e[32];
    fprintf(f, "scene: %s\n%s\nbase tick: %s s\nend time: %s s\n", sc->name,
            sc->doc ? sc->doc : "", num(b, (double)sc->dt), num(e, (double)sc->t_end));
    scene_blocks(f, sc);
    scene_wiring(f, sc);
    if (init == RT_OK) { /* the plan exists only after a successful init */
        scene_schedule(f, sc, sim);
        scene_order(f, sc, sim);
    }
    scene_link(f, sc);
    fprintf(f, "recorded:");
    for (uint16_t i = 0; i < sc->nrecs; i++)
        fprintf(f, " %s.%s", sc->blocks[sc->recs[i].block].name, rt_rec_signal(sc, i));
    const char *text = rt_error_text(sim); /* after ok: what rt_init moved or found */
    fprintf(f, "\ninit: %s%s%s%s\n", rt_status_name(init),
            init ? ": " : text[0] ? " (reported: " : "", text, !init && text[0] ? ")" : "");
}

static void json_blocks(FILE *f, const rt_scene *sc)
{
    char b[32];
    fputs(", \"blocks\": [", f);
    for (uint16_t i = 0; i < sc->nblocks; i++) {
        const rt_block *bl = &sc->blocks[i];
        fputs(i ? ", {\"name\": " : "{\"name\": ", f);
        jstr(f, bl->name);
        fputs(", \"kind\": ", f);
        jstr(f, bl->kind->name);
        fprintf(f, ", \"type\": \"%s\", \"set\": ", rt_kind_type_name(bl->kind->type));
        jstr(f, sc->sets[bl->set].name);
        if (bl->kind->type == RT_KIND_DSS)
            fprintf(f, ", \"period\": %s", num(b, (double)bl->ts));
        fputs(", \"parameters\": {", f);
        for (uint16_t p = 0; p < bl->kind->np; p++) {
            fputs(p ? ", " : "", f);
            jstr(f, bl->kind->p_names[p]);
            fprintf(f, ": %s", num(b, param(bl, p)));
        }
        fputs("}}", f);
    }
    fputc(']', f);
}

static void json_sets_wiring(FILE *f, const rt_scene *sc)
{
    char b[32];
    fputs(", \"sets\": [", f);
    for (uint8_t s = 0; s < sc->nsets; s++) {
        fputs(s ? ", {\"name\": " : "{\"name\": ", f);
        jstr(f, sc->sets[s].name);
        fputs(", \"method\": ", f);
        jstr(f, sc->sets[s].method->name);
        fprintf(f, ", \"step\": %s, \"ratio\": %u, \"background\": %s}",
                num(b, (double)rt_set_step(sc, s)), (unsigned)sc->sets[s].ratio,
                sc->sets[s].background ? "true" : "false");
    }
    fputs("], \"connections\": [", f);
    for (uint16_t c = 0; c < sc->nconns; c++) {
        const rt_conn *cn = &sc->conns[c];
        fprintf(f, "%s[\"%s.%s\", \"%s.%s\"]", c ? ", " : "", sc->blocks[cn->from].name,
                sc->blocks[cn->from].kind->y_names[cn->y], sc->blocks[cn->to].name,
                sc->blocks[cn->to].kind->u_names[cn->u]);
    }
    fputs("], \"recorded\": [", f);
    for (uint16_t i = 0; i < sc->nrecs; i++)
        fprintf(f, "%s\"%s.%s\"", i ? ", " : "", sc->blocks[sc->recs[i].block].name,
                rt_rec_signal(sc, i));
    fputc(']', f);
}

static void scene_json(FILE *f, const rt_scene *sc, const rt_sim *sim, rt_status init)
{
    char b[32];
    fputs("{\"scene\": ", f);
    jstr(f, sc->name);
    fputs(", \"doc\": ", f);
    jstr(f, sc->doc);
    fprintf(f, ", \"base_tick\": %s", num(b, (double)sc->dt));
    fprintf(f, ", \"end_time\": %s", num(b, (double)sc->t_end));
    json_blocks(f, sc);
    json_sets_wiring(f, sc);
    fprintf(f, ", \"loops\": %u, \"init\": ", init == RT_OK ? (unsigned)rt_loop_count(sim) : 0u);
    jstr(f, init ? rt_error_text(sim) : "ok");
    fputs("}\n", f);
}

void info_scene(FILE *f, const rt_scene *sc, const rt_sim *sim, rt_status init, int json)
{
    if (json)
        scene_json(f, sc, sim, init);
    else
        scene_text(f, sc, sim, init);
}
