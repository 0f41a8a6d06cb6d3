/* test_scenec.c - tests of the scene language (tools/scenec/) on the in-house harness:
 * expression semantics on the VM against values worked out by hand, the kinds of
 * defines (type, sizes, throughput), times and steps, sets and interpolation, includes
 * in the sandbox, and what the generated C names. Error texts: tests/scenec/errors.sh. */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "harness.h"
#include "scn.h"

/* compiles text as scene file t.scn without touching the file system */
static scn_ctx *compile(const char *text)
{
    scn_ctx *c = scn_new();
    c->sandbox = 1;
    scn_compile(c, "t.scn", text, strlen(text));
    return c;
}

/* v as the runtime's real_t: exact comparisons hold in float builds too */
#define R(v) ((double)(real_t)(v))

/* y = expr of a define with inputs a, b, parameter k = 3 and state s = 0.5, at t = 0 */
static double eval(const char *expr, double a, double b)
{
    char text[1024];
    snprintf(text, sizeof text,
             "base tick (1 ms); end time (0 s);\n"
             "define ss_system (E) with inputs (a, b) outputs (y) parameters (k = 3)\n"
             "    states (s = 0.5) by { y[0] = %s; der(s) = 0; }\n"
             "load system (X) of type (E); X.a = %.17g; X.b = %.17g;\n", expr, a, b);
    scn_ctx *c = compile(text);
    double v = c->err ? -999 : (double)rt_output(c->sim, 0, 0);
    scn_free(c);
    return v;
}

static void test_precedence(void)
{
    TH_CHECK(eval("1 + 2 * 3", 0, 0) == R(7));
    TH_CHECK(eval("(1 + 2) * 3", 0, 0) == R(9));
    TH_CHECK(eval("10 - 4 - 3", 0, 0) == R(3));
    TH_CHECK(eval("8 / 4 / 2", 0, 0) == R(1));
    TH_CHECK(eval("2 ^ 3 ^ 2", 0, 0) == R(512));     /* right-associative */
    TH_CHECK(eval("-2 ^ 2", 0, 0) == R(-4));         /* ^ binds tighter than unary minus */
    TH_CHECK(eval("2 ^ -1", 0, 0) == R(0.5));
    TH_CHECK(eval("- -a", 5, 0) == R(5));
    TH_CHECK(eval("+a * -b", 2, 3) == R(-6));
}

static void test_logic(void)
{
    TH_CHECK(eval("a < b", 1, 2) == R(1));
    TH_CHECK(eval("a >= b", 1, 2) == R(0));
    TH_CHECK(eval("a == 1 && b == 2", 1, 2) == R(1));
    TH_CHECK(eval("a > 1 || b > 1", 1, 2) == R(1));
    TH_CHECK(eval("a > 1 || b > 2", 1, 2) == R(0));
    TH_CHECK(eval("!a", 1, 0) == R(0));
    TH_CHECK(eval("!a", 0, 0) == R(1));
    TH_CHECK(eval("a != b", 1, 1) == R(0));
    TH_CHECK(eval("a <= b", 1, 1) == R(1));
    TH_CHECK(eval("a < b ? 10 : 20", 1, 2) == R(10));
    TH_CHECK(eval("a > 5 ? 1 : a > 0 ? 2 : 3", 1, 0) == R(2)); /* right-associative */
    TH_CHECK(eval("if(a - 1, 5, 6)", 1, 0) == R(6));
    TH_CHECK(eval("1 + 2 < 4", 0, 0) == R(1));      /* arithmetic before comparison */
}

/* a NaN operand (sqrt(a), a = -1) reaches the result of every condition and limit
   (rt/rt_expr.h): C's < and fmin would drop it */
static void test_nan_kept(void)
{
    static const char *const ex[] = {
        "sqrt(a) < b",     "sqrt(a) >= b",       "sqrt(a) == sqrt(a)", "b != sqrt(a)",
        "!sqrt(a)",        "sqrt(a) && b",       "b || sqrt(a)",       "0 && sqrt(a)",
        "if(sqrt(a), 1, 2)", "sqrt(a) ? 1 : 2",  "min(sqrt(a), b)",    "max(b, sqrt(a))",
        "b + (sqrt(a) > 0 ? 1 : 0)"};
    for (unsigned i = 0; i < sizeof ex / sizeof ex[0]; i++) {
        double v = eval(ex[i], -1, 2);
        TH_CHECK(v != v);
        if (v == v)
            th_note(ex[i], v);
    }
    /* finite operands as before: infinities compare, -0 is the smaller zero */
    TH_CHECK(eval("a * 1e308 < b", -10, 0) == R(1) && eval("a * 1e308 > b", 10, 1e308) == R(1));
    TH_CHECK(eval("1 / min(a, b)", 0, -0.0) < 0 && eval("1 / max(a, b)", -0.0, 0) > 0);
    TH_CHECK(eval("if(a, b, 3)", 1e-300, 2) == R(2));
}

static void test_names_and_functions(void)
{
    TH_CHECK(eval("k * a", 2, 0) == R(6));          /* parameter default */
    TH_CHECK(eval("s + u[1] + p[0] + x[0]", 0, 1) == R(5));
    TH_CHECK(eval("t + h", 0, 0) == R(0));           /* t = 0; h of an output call is 0 */
    TH_CHECK(eval("pi", 0, 0) == R(RT_PI));
    TH_CHECK(eval("sqrt(b * 8)", 0, 2) == R(4));
    TH_CHECK(eval("pow(2, 10)", 0, 0) == R(1024));
    TH_CHECK(eval("min(a, b) + max(a, b)", 3, 4) == R(7));
    TH_CHECK(eval("abs(-3) + floor(2.7)", 0, 0) == R(5));
    TH_CHECK(eval("atan2(a, b)", 0, -1) == (double)rt_atan2(0, -1));
    TH_CHECK(eval("exp(a) * cos(b)", 1, 0) == (double)(rt_exp(1) * rt_cos(0)));
    TH_CHECK(eval("let_not_a_let", 0, 0) == -999); /* unknown name: an error */
}

/* the kind a define becomes: type, sizes, throughput */
static void test_define_kinds(void)
{
    scn_ctx *c = compile(
        "base tick (1 ms); end time (1 s);\n"
        "define ss_system (S) with inputs (m1, m2) outputs (d, e) parameters (K1, K2)\n"
        "    by { y[0] = K1 * m1 + K2 * m2; y[1] = 0; }\n"
        "define ss_system (N) with inputs (f) outputs (x) states (q) by { x = q; der(q) = f; }\n"
        "define dss_system (D) with inputs (u) outputs (c) states (I) period (5 ms)\n"
        "    by { let e = u; c = I + e; next(I) = I + h * e; }\n"
        "define lss_system (L) with inputs (u) outputs (y) states (z) by { A = [-1]; B = [1];"
        " C = [2]; D = [0.5]; }\n"
        "load system (s) of type (S); load system (n) of type (N);\n"
        "load system (d) of type (D); load system (l) of type (L);\n"
        "s.m1 = 1; s.m2 = 2; connect(s.d, n.f); connect(n.x, d.u); connect(d.c, l.u);\n");
    TH_CHECK(!c->err);
    if (!c->err) {
        const rt_block *b = c->image.blocks;
        TH_CHECK(b[0].kind->type == RT_KIND_OUTPUT && b[0].kind->feed == RT_FEED_TABLE);
        TH_CHECK(b[0].kind->feed_table[0] == 1 && b[0].kind->feed_table[3] == 0);
        TH_CHECK(b[1].kind->type == RT_KIND_NSS && b[1].kind->feed == RT_FEED_NONE);
        TH_CHECK(b[2].kind->type == RT_KIND_DSS && b[2].kind->nd == 1 && b[2].kind->nx == 0);
        TH_CHECK(b[2].ts == (real_t)0.005 && b[2].kind->feed == RT_FEED_ALL);
        TH_CHECK(b[3].kind->type == RT_KIND_LSS && b[3].kind->feed == RT_FEED_ALL);
    }
    scn_free(c);
}

/* a DSS define advances at its sample hits: I += h e with e = 1 every 10 ms */
static void test_dss_runs(void)
{
    scn_ctx *c = compile("base tick (1 ms); end time (100 ms);\n"
                         "define dss_system (Acc) with inputs (e) outputs (c) states (I)\n"
                         "    by { c = I; next(I) = I + h * e; }\n"
                         "load system (A) of type (Acc) period (10 ms); A.e = 1;\n");
    TH_CHECK(!c->err);
    if (!c->err) {
        rt_sim *sim = c->sim;
        rt_init(&c->image, sim);
        while (rt_tick(&c->image, sim) != RT_E_DONE)
            ;
        TH_NEAR(rt_block_d(sim, 0, 0), 0.1, 10 * RT_EPS); /* ten hits of 0.01 each */
    }
    scn_free(c);
}

/* a body's joint point moved by rt_set_param during the run: the next projection moves
   the body 0.5 m at once, counted (init_moved) with the block and named; a mass change
   moves no node and counts nothing. Before the first tick the same move is refused
   (rt_refresh). */
static void test_mbs_param_moves(void)
{
    scn_ctx *c = compile("base tick (1 ms); end time (1 s);\n"
                         "load system (B) of type (mbs_body);\n"
                         "B.m = 2; B.Jxx = 0.2; B.Jyy = 0.3; B.Jzz = 0.4; B.x = 0.5; B.n1x = -0.5;\n"
                         "load joint (H) of type (revolute); H.axis = (0, 1, 0);\n"
                         "link(B.n1, ground) by (H);\n"
                         "set (mbs) method (rk4) step (10 ticks); stabilization (project);\n");
    TH_CHECK(!c->err);
    if (!c->err) {
        rt_sim *sim = c->sim;
        const rt_scene *sc = &c->image;
        TH_CHECK(rt_init(sc, sim) == RT_OK);
        TH_CHECK(rt_set_param(sc, sim, "B", "n1x", 0) == RT_OK);
        TH_CHECK(rt_refresh(sc, sim) == RT_E_INCONSISTENT);
        TH_CHECK(rt_init(sc, sim) == RT_OK && rt_refresh(sc, sim) == RT_OK);
        for (int i = 0; i < 50; i++)
            rt_tick(sc, sim);
        TH_CHECK(rt_stats_of(sim)->count[RT_CNT_INIT_MOVED] == 0);
        TH_CHECK(rt_set_param(sc, sim, "B", "m", 3) == RT_OK);
        TH_CHECK(rt_stats_of(sim)->count[RT_CNT_INIT_MOVED] == 0);
        TH_CHECK(rt_set_param(sc, sim, "B", "n1x", 0) == RT_OK);
        TH_CHECK(rt_stats_of(sim)->count[RT_CNT_INIT_MOVED] == 1);
        TH_CHECK(th_has(rt_error_text(sim), "a parameter of B put its set"));
    }
    scn_free(c);
}

/* times round once: 10 ms is the double 0.01; steps in seconds become tick ratios */
static void test_times_and_sets(void)
{
    scn_ctx *c = compile(
        "scene (ts) doc (\"times\"); base tick (0.5 ms); end time (2 s);\n"
        "define ss_system (I) with inputs (u) outputs (y) states (x) by { y[0] = x; der(x) = u; }\n"
        "load system (A, B) of type (I); connect(A.y, B.u) interpolation (linear); A.u = 1;\n"
        "set (f) method (sdirk2) step (1 tick) newton (6) jacobian (4) tolerance (1e-10)\n"
        "    interpolation (hermite) members (A);\n"
        "set (s) method (rk4) step (2.5 ms) interpolation (extrapolate);\n");
    TH_CHECK(!c->err);
    if (!c->err) {
        const rt_scene *sc = &c->image;
        TH_CHECK(sc->dt == (real_t)0.0005 && c->sc.dt == 0.5e-3);
        TH_CHECK(sc->nsets == 2 && sc->sets[0].ratio == 1 && sc->sets[1].ratio == 5);
        TH_CHECK(sc->sets[0].cfg.newton_max == 6 && sc->sets[0].cfg.jac_every == 4);
        TH_CHECK(sc->blocks[0].set == 0 && sc->blocks[1].set == 1);
        TH_CHECK(sc->sets[0].interp == RT_INTERP_HERMITE);
        TH_CHECK(sc->sets[1].interp == RT_INTERP_EXTRAP);
        TH_CHECK(sc->conn_interp && sc->conn_interp[0] == RT_INTERP_LINEAR);
    }
    scn_free(c);
    c = compile("base tick (10 ms); end time (1 s); load system (O) of type (oscillator);");
    TH_CHECK(!c->err && c->image.dt == (real_t)0.01 && strcmp(c->image.name, "t") == 0);
    scn_free(c);
    /* functions in constant expressions: 2 sqrt(4) + 4 atan2(1, 1) = 4 + pi, and sin(0.1)
       against the correctly rounded value */
    c = compile("base tick (10 ms); end time (1 s); load system (O, P) of type (oscillator);"
                "O.omega = 2 * sqrt(4) + 4 * atan2(1, 1); P.omega = sin(0.1);");
    TH_CHECK(!c->err);
    if (!c->err) {
        TH_NEAR(c->image.blocks[0].p[0], 7.141592653589793, 1e-15);
        TH_NEAR(c->image.blocks[1].p[0], 0.09983341664682815, 1e-16);
    }
    scn_free(c);
}

/* includes never reach the file system in the sandbox (the fuzzer's mode) */
static void test_sandbox_include(void)
{
    scn_ctx *c = compile("include \"/etc/passwd\";");
    TH_CHECK(c->err && th_has(c->msg, "include file not found"));
    scn_free(c);
}

/* the generated C declares only the kinds the scene uses */
static void test_emit_names(void)
{
    scn_ctx *c = compile("base tick (1 ms); end time (1 s);\n"
                         "load system (P) of type (pt1); load system (S) of type (step);\n"
                         "connect(S.y, P.u);\n");
    FILE *f = tmpfile();
    char buf[8192] = {0};
    TH_CHECK(!c->err && f && scn_emit(c, f) == 0);
    if (f) {
        rewind(f);
        buf[fread(buf, 1, sizeof buf - 1, f)] = 0;
        fclose(f);
    }
    TH_CHECK(th_has(buf, "extern const rt_kind mdl_pt1_kind;"));
    TH_CHECK(th_has(buf, "extern const rt_kind mdl_step_kind;"));
    TH_CHECK(!th_has(buf, "mdl_sine_kind") && !th_has(buf, "models.h"));
    TH_CHECK(th_has(buf, "const rt_scene mdl_scene_t = {"));
    scn_free(c);
}

/* shortest literals that read back as the same double */
static void test_literals(void)
{
    char b[40];
    double v[] = {0.1, 1e-3, -0.2, 10, 6.283185307179586, 1e300, 5e-324, -0.0};
    for (size_t i = 0; i < sizeof v / sizeof v[0]; i++) {
        scn_real_literal(v[i], b, sizeof b);
        TH_CHECK(strtod(b, NULL) == v[i]);
    }
    scn_real_literal(0.1, b, sizeof b);
    TH_CHECK(strcmp(b, "0.1") == 0);
    scn_real_literal(10, b, sizeof b);
    TH_CHECK(strcmp(b, "10") == 0);
}

/* lang_rail.scn, the example of docs/blocks.md: the cart keeps its height and speed with
   the reaction m g, the slider slides down its 30-degree incline by g sin 30 t^2 / 2 */
static void test_rail(void)
{
    static char text[4096];
    FILE *f = fopen("tests/scenec/scenes/lang_rail.scn", "r");
    size_t n = f ? fread(text, 1, sizeof text - 1, f) : 0;
    if (f)
        fclose(f);
    text[n] = 0;
    scn_ctx *c = compile(text);
    TH_CHECK(n > 0 && !c->err);
    if (n > 0 && !c->err) {
        rt_sim *sim = c->sim;
        TH_CHECK(rt_init(&c->image, sim) == RT_OK);
        while (rt_tick(&c->image, sim) == RT_OK)
            ;
        double g = 9.81, s = -g * 0.5 / 2, tol = RT_REAL_IS_FLOAT ? 1e-3 : 1e-9;
        double v[5];
        for (int i = 0; i < 5; i++)
            v[i] = (double)rt_rec_value(&c->image, sim, (uint16_t)i);
        TH_NEAR(v[0], 1.5, tol);                 /* Cart.x = vx t */
        TH_NEAR(v[1], 0.5, tol);                 /* Cart.z */
        TH_NEAR(v[2], s * 0.8660254037844386, tol); /* Slider.x */
        TH_NEAR(v[3], s * 0.5, tol);             /* Slider.z */
        TH_NEAR(v[4], 2 * g, tol * 100);         /* Rail.fz = m g */
        TH_CHECK(rt_stats_of(sim)->status == RT_OK &&
                 rt_stats_of(sim)->count[RT_CNT_INIT_MOVED] == 0);
    }
    scn_free(c);
}

/* an anchor turned by axis and angle: its rotation matrix; axes without a direction and
   angles without a unit are errors */
static void test_joint_frames(void)
{
    const char *base = "base tick (1 ms); end time (0 s);\n"
                       "load system (B) of type (mbs_body) from file (\"mbs_body\");\n"
                       "load joint (J) of type (revolute);\n";
    char text[1024];
    snprintf(text, sizeof text, "%slink(B.cm, ground rotated (90 deg about (0, 0, 2))) by (J);"
             "\nJ.axis = (0, 0, 1);\n", base);
    scn_ctx *c = compile(text);
    TH_CHECK(!c->err);
    if (!c->err) {
        const real_t *S = c->image.joints[0].at_S, *A = c->image.joints[0].axis_S;
        const double Rz[9] = {0, -1, 0, 1, 0, 0, 0, 0, 1}, I[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
        TH_CHECK(S && A);
        for (int i = 0; S && A && i < 9; i++) {
            TH_NEAR((double)S[i], Rz[i], 1e-6);
            TH_NEAR((double)A[i], I[i], 1e-6);
        }
    }
    scn_free(c);
    static const char *const bad[] = {
        "link(B.cm, ground) by (J); J.axis = (0, 0, 0);\n",
        "link(B.cm, ground) by (J); B.axis = (1, 0, 0);\n",
        "link(B.cm, ground) by (J); J.axis = 1;\n",
        "link(B.cm, ground rotated (90 about (0, 0, 1))) by (J);\n",
        "link(B.cm, ground rotated (90 deg about (0, 0, 0))) by (J);\n",
    };
    static const char *const why[] = {
        "the joint's axis has no direction", "a direction (x, y, z) is only for a joint's axis",
        "a joint's axis is a direction", "angle without its unit",
        "the anchor's rotation axis has no direction",
    };
    for (int i = 0; i < 5; i++) {
        snprintf(text, sizeof text, "%s%s", base, bad[i]);
        c = compile(text);
        TH_CHECK(c->err && th_has(c->msg, why[i]));
        scn_free(c);
    }
}

static const th_test tests[] = {
    {"scenec_rail", test_rail},
    {"scenec_joint_frames", test_joint_frames},
    {"scenec_precedence", test_precedence},
    {"scenec_logic", test_logic},
    {"scenec_nan_kept", test_nan_kept},
    {"scenec_names_functions", test_names_and_functions},
    {"scenec_define_kinds", test_define_kinds},
    {"scenec_dss_runs", test_dss_runs},
    {"scenec_mbs_param_moves", test_mbs_param_moves},
    {"scenec_times_sets", test_times_and_sets},
    {"scenec_sandbox_include", test_sandbox_include},
    {"scenec_emit_names", test_emit_names},
    {"scenec_literals", test_literals},
    {0, 0},
};

int main(int argc, char **argv)
{
    const th_test *const tables[] = {tests, 0};
    th_run(tables, argc > 1 ? argv[1] : 0);
    return th_summary() ? 1 : 0;
}
