/* test_joints.c - tests of rt/joints.c: for every joint kind, the velocity coefficients
 * C and the acceleration term c against central differences of g and g' along smooth
 * node motions (uniformly accelerated translation, rotation about a fixed axis with
 * constant angular acceleration), and the residuals of satisfied joints. */
#include "testutil.h"

static double absd(double v) { return v < 0 ? -v : v; }

/* a node's motion: r(t) = r0 + v0 t + a t^2 / 2, S(t) = Rot(n, w0 t + al t^2 / 2) S0 */
typedef struct motion {
    real_t r0[3], v0[3], a[3];
    real_t S0[9];
    real_t n[3];      /* unit axis of the rotation, inertial */
    real_t w0, al;    /* angular velocity [rad/s] and acceleration [rad/s^2] about n */
} motion;

/* Rodrigues: Rot(n, th) = I + sin th [n]x + (1 - cos th) [n]x^2 */
static void rot(const real_t *n, real_t th, real_t *R)
{
    real_t K[9] = {0, -n[2], n[1], n[2], 0, -n[0], -n[1], n[0], 0}, s = rt_sin(th);
    real_t c = 1 - rt_cos(th);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            real_t k2 = 0;
            for (int k = 0; k < 3; k++)
                k2 += K[3 * i + k] * K[3 * k + j];
            R[3 * i + j] = (i == j ? 1 : 0) + s * K[3 * i + j] + c * k2;
        }
}

/* the node at time t, with its full accelerations as ar and aw (no Jacobian part) */
static void node_at(const motion *m, real_t t, rt_mbs_node *n)
{
    real_t R[9], th = m->w0 * t + m->al * t * t / 2, w = m->w0 + m->al * t;
    rot(m->n, th, R);
    for (int i = 0; i < 3; i++) {
        n->r[i] = m->r0[i] + m->v0[i] * t + m->a[i] * t * t / 2;
        n->v[i] = m->v0[i] + m->a[i] * t;
        n->ar[i] = m->a[i];
        n->w[i] = w * m->n[i];
        n->aw[i] = m->al * m->n[i];
        for (int j = 0; j < 3; j++)
            n->S[3 * i + j] = R[3 * i] * m->S0[j] + R[3 * i + 1] * m->S0[3 + j] +
                              R[3 * i + 2] * m->S0[6 + j];
    }
}

/* g' (acc = 0) or g'' (acc = 1) of row i from the joint's C and c */
static double rate(const rt_joint_eval *e, int i, const rt_mbs_node *n1,
                   const rt_mbs_node *n2, int acc)
{
    double s = acc ? (double)e->c[i] : 0;
    for (int k = 0; k < 3; k++)
        s += (double)e->C[i][k] * (acc ? n1->ar[k] : n1->v[k]) +
             (double)e->C[i][3 + k] * (acc ? n1->aw[k] : n1->w[k]) +
             (double)e->C[i][6 + k] * (acc ? n2->ar[k] : n2->v[k]) +
             (double)e->C[i][9 + k] * (acc ? n2->aw[k] : n2->w[k]);
    return s;
}

/* worst relative mismatch of g' and g'' against central differences at t = 0 */
static double fd_check(const rt_joint_kind *k, const real_t *p, const motion *m1,
                       const motion *m2)
{
    real_t eps = RT_REAL_IS_FLOAT ? (real_t)1e-2 : (real_t)1e-4;
    rt_mbs_node a1, a2, b1, b2, c1, c2;
    rt_joint_eval ea, eb, ec;
    node_at(m1, -eps, &a1), node_at(m2, -eps, &a2);
    node_at(m1, 0, &b1), node_at(m2, 0, &b2);
    node_at(m1, eps, &c1), node_at(m2, eps, &c2);
    k->eval(p, &a1, &a2, &ea);
    k->eval(p, &b1, &b2, &eb);
    k->eval(p, &c1, &c2, &ec);
    double worst = 0;
    for (int i = 0; i < k->nc; i++) {
        double gd = ((double)ec.g[i] - (double)ea.g[i]) / (2 * (double)eps);
        double gdd = (rate(&ec, i, &c1, &c2, 0) - rate(&ea, i, &a1, &a2, 0)) / (2 * (double)eps);
        double e1 = absd(rate(&eb, i, &b1, &b2, 0) - gd) / (1 + absd(gd));
        double e2 = absd(rate(&eb, i, &b1, &b2, 1) - gdd) / (1 + absd(gdd));
        worst = e1 > worst ? e1 : worst;
        worst = e2 > worst ? e2 : worst;
    }
    return worst;
}

/* two general motions: offset nodes, different axes, rotations and accelerations */
static const motion m1 = {
    {(real_t)0.3, (real_t)-0.2, (real_t)1.1}, {(real_t)0.7, (real_t)0.1, (real_t)-0.4},
    {(real_t)-1.3, (real_t)0.8, (real_t)2.1}, {1, 0, 0, 0, 1, 0, 0, 0, 1},
    {(real_t)0.6, 0, (real_t)0.8}, (real_t)2.5, (real_t)-1.5,
};
static const motion m2 = {
    {(real_t)-0.4, (real_t)0.5, (real_t)0.2}, {(real_t)-0.3, (real_t)0.9, (real_t)0.2},
    {(real_t)0.4, (real_t)-0.6, (real_t)1.2}, {0, -1, 0, 1, 0, 0, 0, 0, 1},
    {0, (real_t)0.28, (real_t)0.96}, (real_t)-1.2, (real_t)0.7,
};

static void test_derivatives(void)
{
    static const real_t len[] = {(real_t)1.8};
    double tol = RT_REAL_IS_FLOAT ? 5e-3 : 1e-7;
    for (const rt_joint_entry *e = rt_joint_kinds; e->name; e++) {
        double w = fd_check(e->kind, len, &m1, &m2);
        th_note(e->name, w);
        TH_CHECK(w < tol);
        /* a node against an inertial one (the anchor case): node 2 at rest */
        motion still = m2;
        for (int i = 0; i < 3; i++)
            still.v0[i] = still.a[i] = 0;
        still.w0 = still.al = 0;
        TH_CHECK(fd_check(e->kind, len, &m1, &still) < tol);
    }
}

/* coincident nodes rotating together about their common z axis satisfy every joint;
   a relative rotation about z violates only the fixed joint */
static void test_satisfied(void)
{
    motion a = m1, b = m1;
    a.n[0] = a.n[1] = b.n[0] = b.n[1] = 0;
    a.n[2] = b.n[2] = 1;
    b.w0 = a.w0 + 1; /* b turns faster about z */
    rt_mbs_node n1, n2;
    rt_joint_eval e;
    node_at(&a, 0, &n1), node_at(&a, 0, &n2);
    static const real_t zero[] = {(real_t)1e-3};
    for (const rt_joint_entry *j = rt_joint_kinds; j->name; j++) {
        if (j->kind == &rt_joint_sphdiff)
            continue; /* needs a distance */
        j->kind->eval(zero, &n1, &n2, &e);
        for (int i = 0; i < j->kind->nc; i++)
            TH_NEAR(e.g[i], 0, 1e-6);
    }
    node_at(&a, (real_t)0.5, &n1), node_at(&b, (real_t)0.5, &n2);
    rt_joint_revolute.eval(0, &n1, &n2, &e);
    for (int i = 0; i < 5; i++)
        TH_NEAR(e.g[i], 0, 1e-6);
    rt_joint_fixed.eval(0, &n1, &n2, &e);
    TH_CHECK(absd((double)e.g[5]) > 0.1); /* sin(0.5 rad) of relative turn */
    /* sphdiff: g = |r1 - r2| - l, and coincident nodes stay finite */
    static const real_t l[] = {2};
    n2 = n1;
    n2.r[0] += 3;
    rt_joint_sphdiff.eval(l, &n1, &n2, &e);
    TH_NEAR(e.g[0], 1, 1e-6);
    TH_NEAR(e.C[0][0], -1, 1e-6);
    rt_joint_sphdiff.eval(l, &n1, &n1, &e);
    TH_CHECK(rt_isfinite(e.g[0]) && rt_isfinite(e.c[0]) && e.C[0][0] == 1);
}

/* the kinds' shortcuts between two points give eval's bits: eval_points' g, C, c, and
   g_points' g (the recorded residual), at scattered points, also coincident ones */
static void test_points_paths(void)
{
    static const real_t l[] = {(real_t)1.3};
    uint32_t seed = 12345;
    int differ = 0;
    for (int n = 0; n < 200; n++) {
        real_t r1[3], r2[3], v1[3], v2[3];
        for (int i = 0; i < 3; i++) {
            seed = seed * 1664525u + 1013904223u, r1[i] = (real_t)(seed >> 8) / (1 << 22) - 2;
            seed = seed * 1664525u + 1013904223u, r2[i] = (real_t)(seed >> 8) / (1 << 22) - 2;
            seed = seed * 1664525u + 1013904223u, v1[i] = (real_t)(seed >> 8) / (1 << 22) - 2;
            seed = seed * 1664525u + 1013904223u, v2[i] = (real_t)(seed >> 8) / (1 << 22) - 2;
        }
        if (n == 0)
            for (int i = 0; i < 3; i++)
                r2[i] = r1[i];
        rt_mbs_node n1 = {.r = {r1[0], r1[1], r1[2]}, .v = {v1[0], v1[1], v1[2]},
                          .S = {1, 0, 0, 0, 1, 0, 0, 0, 1}};
        rt_mbs_node n2 = {.r = {r2[0], r2[1], r2[2]}, .v = {v2[0], v2[1], v2[2]},
                          .S = {1, 0, 0, 0, 1, 0, 0, 0, 1}};
        rt_joint_eval e, ep;
        real_t g;
        rt_joint_sphdiff.eval(l, &n1, &n2, &e);
        rt_joint_sphdiff.eval_points(l, r1, v1, r2, v2, &ep);
        rt_joint_sphdiff.g_points(l, r1, r2, &g);
        int same = ep.g[0] == e.g[0] && g == e.g[0] && ep.c[0] == e.c[0];
        for (int i = 0; i < 3; i++)
            same = same && ep.C[0][i] == e.C[0][i] && ep.C[0][6 + i] == e.C[0][6 + i];
        differ += !same;
    }
    TH_CHECK(differ == 0);
}

const th_test th_joint_tests[] = {
    {"joints_derivatives", test_derivatives},
    {"joints_satisfied", test_satisfied},
    {"joints_points_paths", test_points_paths},
    {0, 0},
};
