/* test_limits.c - every numeric input of a hand-written scene (the C API) at its limit and
 * one past it (docs/reliability.md): rt_init accepts the one and refuses the other with a
 * status and a message, and leaves no run that could say "ok" about it. */
#include "models.h"
#include "testutil.h"

static const real_t ball_p[] = {(real_t)9.81, (real_t)0.8, (real_t)1e-3};

/* a one-block scene to vary: the ball (parameters with a range), one set */
typedef struct variant {
    rt_block blk[RT_MAX_BLOCKS + 1];
    rt_set set[RT_MAX_SETS + 1];
    real_t p[3];
    rt_scene sc;
} variant;

static variant v;

static rt_scene *base(void)
{
    /* one ball (roots count against RT_MAX_ROOTS), the rest oscillators */
    v.blk[0] = (rt_block){.name = "B", .kind = &mdl_ball_kind, .p = v.p};
    for (int i = 1; i < RT_MAX_BLOCKS + 1; i++)
        v.blk[i] = (rt_block){.name = "O", .kind = &mdl_oscillator_kind};
    for (int i = 0; i < RT_MAX_SETS + 1; i++)
        v.set[i] = (rt_set){.name = "s", .method = &rt_rk4, .ratio = 1};
    for (int i = 0; i < 3; i++)
        v.p[i] = ball_p[i];
    v.sc = (rt_scene){.name = "limits", .dt = (real_t)1e-3, .t_end = 1, .blocks = v.blk,
                      .nblocks = 1, .sets = v.set, .nsets = 1};
    return &v.sc;
}

/* rt_init's status for the scene as varied */
static rt_status init(void)
{
    return rt_init(&v.sc, &tu_sim);
}

/* the variant is accepted (at the limit) */
#define AT(expr) (base(), (expr), init() == RT_OK)
/* the variant is refused with status st (one past) */
#define PAST(expr, st) (base(), (expr), init() == (st))

static void test_times(void)
{
    real_t two53 = (real_t)9007199254740992.0;
    TH_CHECK(PAST(v.sc.dt = 0, RT_E_SCENE) && PAST(v.sc.dt = -1, RT_E_SCENE));
    TH_CHECK(AT(v.sc.t_end = 0) && PAST(v.sc.t_end = (real_t)-1e-3, RT_E_SCENE));
    TH_CHECK(PAST(v.sc.t_end = (real_t)0 / (real_t)0, RT_E_SCENE));
    TH_CHECK(PAST(v.sc.t_end = (real_t)1.0005, RT_E_SCENE)); /* not whole ticks */
    if (!RT_REAL_IS_FLOAT) { /* 2^53 ticks: exact in double only */
        TH_CHECK(AT(v.sc.t_end = two53 * v.sc.dt));
        TH_CHECK(PAST(v.sc.t_end = 2 * two53 * v.sc.dt, RT_E_SCENE));
    }
    TH_CHECK(PAST(v.sc.t_end = (real_t)1e300 * (real_t)1e300, RT_E_SCENE)); /* inf */
}

static void test_counts(void)
{
    TH_CHECK(AT(v.sc.nblocks = RT_MAX_BLOCKS) && PAST(v.sc.nblocks = RT_MAX_BLOCKS + 1, RT_E_CAPACITY));
    TH_CHECK(AT(v.sc.nsets = RT_MAX_SETS) && PAST(v.sc.nsets = RT_MAX_SETS + 1, RT_E_CAPACITY));
    TH_CHECK(PAST(v.sc.nsets = 0, RT_E_CAPACITY));
    TH_CHECK(AT(v.set[0].ratio = 1) && PAST(v.set[0].ratio = 0, RT_E_SCENE));
    TH_CHECK(PAST(v.blk[0].set = 1, RT_E_SCENE)); /* a set that does not exist */
}

static void test_settings(void)
{
    real_t nan = (real_t)0 / (real_t)0;
    const rt_integrator *imp = &rt_sdirk2; /* the Newton settings apply to it */
    TH_CHECK(AT((v.set[0].method = imp, v.set[0].cfg.tol = 0)) &&
             PAST((v.set[0].method = imp, v.set[0].cfg.tol = -1), RT_E_PARAM));
    TH_CHECK(PAST((v.set[0].method = imp, v.set[0].cfg.tol = nan), RT_E_PARAM));
    TH_CHECK(AT(v.set[0].cfg.accuracy = (real_t)1e-12) &&
             PAST(v.set[0].cfg.accuracy = -1, RT_E_PARAM));
    TH_CHECK(AT((v.set[0].method = imp, v.set[0].cfg.substeps = 128)) &&
             PAST((v.set[0].method = imp, v.set[0].cfg.substeps = 129), RT_E_PARAM));
    TH_CHECK(AT((v.set[0].method = imp, v.set[0].cfg.substeps = 1)) &&
             PAST((v.set[0].method = imp, v.set[0].cfg.substeps = 3), RT_E_PARAM));
    /* a Newton setting on a method that does not iterate is no silent no-op (as the scene
       compiler and modrt's options) */
    TH_CHECK(AT((v.set[0].method = imp, v.set[0].cfg.newton_max = 2)) &&
             PAST(v.set[0].cfg.newton_max = 2, RT_E_PARAM) &&
             PAST((v.set[0].method = &rt_transition, v.set[0].cfg.jac_every = 4), RT_E_PARAM));
    TH_CHECK(AT(v.sc.loop_iter_max = RT_LOOP_ITER_LIMIT) &&
             PAST(v.sc.loop_iter_max = RT_LOOP_ITER_LIMIT + 1, RT_E_PARAM));
    TH_CHECK(PAST(v.sc.loop_tol = nan, RT_E_PARAM) && AT(v.sc.loop_tol = (real_t)1e-300));
}

/* parameter values through the kind's range check (the ball: 0 <= e <= 1, g > 0) */
static void test_parameters(void)
{
    TH_CHECK(AT(v.p[1] = 1) && PAST(v.p[1] = (real_t)1.0000001, RT_E_PARAM));
    TH_CHECK(AT(v.p[1] = 0) && PAST(v.p[1] = (real_t)-1e-30, RT_E_PARAM));
    TH_CHECK(PAST(v.p[0] = 0, RT_E_PARAM) && PAST(v.p[2] = -1, RT_E_PARAM));
    TH_CHECK(th_has(rt_error_text(&tu_sim), "B")); /* the message names the block */
}

/* s1 + s2 + s3 into out (cap RT_ERR_LEN) */
static const char *join(char *out, const char *s1, const char *s2, const char *s3)
{
    size_t n = 0;
    for (const char *const *s = (const char *const[]){s1, s2, s3, 0}; *s; s++)
        for (const char *c = *s; *c && n + 1 < RT_ERR_LEN; c++)
            out[n++] = *c;
    out[n] = 0;
    return out;
}

/* v in decimal, digits kept from the front */
static const char *decimal(char *out, uint32_t v)
{
    uint32_t div = 1;
    size_t n = 0;
    while (v / div >= 10)
        div *= 10;
    for (; div > 0; div /= 10)
        out[n++] = (char)('0' + v / div % 10);
    out[n] = 0;
    return out;
}

/* a capacity fault says which limit (its macro and value, what it counts) and where: the
   block at which the roots outgrew RT_MAX_ROOTS, not "states or roots" */
static void test_messages(void)
{
    char want[RT_ERR_LEN], num[12], tail[RT_ERR_LEN], text[RT_ERR_LEN];
    join(tail, " (", decimal(num, RT_MAX_BLOCKS), " in rt_config.h)");
    TH_CHECK(rt_streq(rt_limit_text(text, sizeof text, RT_LIM_BLOCKS),
                      join(want, "blocks exceed RT_MAX_BLOCKS", tail, "")));
    TH_CHECK(PAST(v.sc.nblocks = RT_MAX_BLOCKS + 1, RT_E_CAPACITY) &&
             rt_streq(rt_error_text(&tu_sim), want));
    /* truncated to its buffer, terminated */
    TH_CHECK(rt_streq(rt_limit_text(text, 7, RT_LIM_BLOCKS), "blocks") &&
             rt_limit_text(text, sizeof text, RT_LIM_COUNT)[0] == 0);
    for (int k = 0; k < RT_LIM_COUNT; k++) /* every row: its words, its macro */
        TH_CHECK(th_has(rt_limit_text(text, sizeof text, (rt_limit)k), " exceed RT_MAX_") &&
                 text[0] != ' ' && th_has(text, " in rt_config.h)"));
#if RT_MAX_ROOTS < RT_MAX_BLOCKS
    base();
    for (int i = 0; i <= RT_MAX_ROOTS; i++)
        v.blk[i] = (rt_block){.name = i < RT_MAX_ROOTS ? "O" : "Last", .kind = &mdl_ball_kind,
                              .p = v.p};
    v.sc.nblocks = RT_MAX_ROOTS + 1;
    join(tail, " (", decimal(num, RT_MAX_ROOTS), " in rt_config.h)");
    TH_CHECK(init() == RT_E_CAPACITY &&
             rt_streq(rt_error_text(&tu_sim),
                      join(want, "block Last: state-event root functions (a when: one, a located "
                                 "switch: two) exceed RT_MAX_ROOTS",
                           tail, "")));
#endif
}

const th_test th_limits_tests[] = {
    {"limits_times", test_times},
    {"limits_counts", test_counts},
    {"limits_settings", test_settings},
    {"limits_parameters", test_parameters},
    {"limits_messages", test_messages},
    {0, 0},
};
