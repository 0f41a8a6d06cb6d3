/* joints.c - the library of joint kinds: each computes, from the states of its two
 * interaction nodes, the constraints g, their velocity coefficients C (g' = C [v1; w1;
 * v2; w2], eq. 7a) and the acceleration term c (g'' = C [r1''; w1'; r2''; w2'] + c,
 * eq. 7b). Joints never see block coordinates: rt/mbs_asm.c maps C through the nodes'
 * Jacobians into rows of W = G K (eq. 9c).
 *
 * Orientation conditions are written as perpendicularity of node axes, u . w = 0 with
 * u = S2 e_i and w = S1 e_j: their derivative is (u x w) . (w2 - w1), smooth everywhere. */
#include "rt.h"
#include "rti_joints.h"

static real_t dot3(const real_t *a, const real_t *b)
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void cross3(const real_t *a, const real_t *b, real_t *c)
{
    /* cppcheck's whole-program pass sizes real_t[3] as float and calls offset 16 (b[2] as
       double) out of bounds: a false positive (every caller passes three real_t) */
    // cppcheck-suppress ctuArrayIndex
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
}

/* column i of a row-major rotation: the node frame's axis i in the inertial frame */
static void axis(const real_t *S, int i, real_t *u)
{
    u[0] = S[i], u[1] = S[3 + i], u[2] = S[6 + i];
}

static void clear(rt_joint_eval *e, int nc)
{
    for (int i = 0; i < nc; i++) {
        e->g[i] = e->c[i] = 0;
        for (int j = 0; j < 12; j++)
            e->C[i][j] = 0;
    }
}

/* rows 0-2: r1 - r2 = 0; g' = v1 - v2, no acceleration term */
static void coincide(const rt_mbs_node *n1, const rt_mbs_node *n2, rt_joint_eval *e)
{
    for (int i = 0; i < 3; i++) {
        e->g[i] = n1->r[i] - n2->r[i];
        e->C[i][i] = 1;
        e->C[i][6 + i] = -1;
    }
}

/* row k: u . w = 0 with u = axis iu of node 2, w = axis iw of node 1;
   g' = (u x w) . (w2 - w1), c = ((w2 x u) x w + u x (w1 x w)) . (w2 - w1) */
static void perpendicular(const rt_mbs_node *n1, const rt_mbs_node *n2, int iu, int iw,
                          int k, rt_joint_eval *e)
{
    real_t u[3], w[3], n[3], ud[3], wd[3], t1[3], t2[3], dw[3];
    axis(n2->S, iu, u);
    axis(n1->S, iw, w);
    cross3(u, w, n);
    cross3(n2->w, u, ud);
    cross3(n1->w, w, wd);
    cross3(ud, w, t1);
    cross3(u, wd, t2);
    e->g[k] = dot3(u, w);
    for (int i = 0; i < 3; i++) {
        e->C[k][3 + i] = -n[i];
        e->C[k][9 + i] = n[i];
        dw[i] = n2->w[i] - n1->w[i];
        t1[i] += t2[i];
    }
    e->c[k] = dot3(t1, dw);
}

/* ---- spherical difference joint |r1 - r2| - l = 0 (eq. 8); p = {l} ----
   its point equations are rt/rti_joints.h's (written-out scene code inlines them) */
static void sphdiff_points(const real_t *p, const real_t *r1, const real_t *v1,
                           const real_t *r2, const real_t *v2, rt_joint_eval *e)
{
    rti_sphdiff_points(p, r1, v1, r2, v2, e);
}

static void sphdiff_g(const real_t *p, const real_t *r1, const real_t *r2, real_t *g)
{
    rti_sphdiff_g(p, r1, r2, g);
}

static void sphdiff_eval(const real_t *p, const rt_mbs_node *n1, const rt_mbs_node *n2,
                         rt_joint_eval *e)
{
    clear(e, 1);
    sphdiff_points(p, n1->r, n1->v, n2->r, n2->v, e);
}

static int sphdiff_check(const real_t *p)
{
    return p[0] > 0 && rt_isfinite(p[0]) ? 0 : 1;
}

/* ---- spherical joint r1 = r2 ---- */
static void spherical_eval(const real_t *p, const rt_mbs_node *n1, const rt_mbs_node *n2,
                           rt_joint_eval *e)
{
    (void)p;
    clear(e, 3);
    coincide(n1, n2, e);
}

/* ---- revolute joint: r1 = r2 and the nodes' z axes parallel (rotation about them
   free): (S2 e_z) . (S1 e_x) = 0, (S2 e_z) . (S1 e_y) = 0 ---- */
static void revolute_eval(const real_t *p, const rt_mbs_node *n1, const rt_mbs_node *n2,
                          rt_joint_eval *e)
{
    (void)p;
    clear(e, 5);
    coincide(n1, n2, e);
    perpendicular(n1, n2, 2, 0, 3, e);
    perpendicular(n1, n2, 2, 1, 4, e);
}

/* ---- fixed joint: r1 = r2 and S1 = S2 (with b2 = -1: a node clamped to the inertial
   frame); three perpendicularities pin the orientation ---- */
static void fixed_eval(const real_t *p, const rt_mbs_node *n1, const rt_mbs_node *n2,
                       rt_joint_eval *e)
{
    (void)p;
    clear(e, 6);
    coincide(n1, n2, e);
    perpendicular(n1, n2, 1, 2, 3, e);
    perpendicular(n1, n2, 2, 0, 4, e);
    perpendicular(n1, n2, 0, 1, 5, e);
}

/* ---- prismatic joint: S1 = S2 and node 2 on the z axis of node 1 (translation along
   it free). With a = S1 e_i (i = x, y) and d = r2 - r1: g = a . d,
   g' = -a . v1 + (a x d) . w1 + a . v2, c = w1 . ((w1 x a) x d + a x d') + (w1 x a) . d' ---- */
static void slide_row(const rt_mbs_node *n1, const rt_mbs_node *n2, int ia, int k,
                      rt_joint_eval *e)
{
    real_t a[3], d[3], dd[3], ad[3], axd[3], t1[3], t2[3];
    axis(n1->S, ia, a);
    for (int i = 0; i < 3; i++)
        d[i] = n2->r[i] - n1->r[i], dd[i] = n2->v[i] - n1->v[i];
    cross3(n1->w, a, ad);
    cross3(a, d, axd);
    cross3(ad, d, t1);
    cross3(a, dd, t2);
    e->g[k] = dot3(a, d);
    for (int i = 0; i < 3; i++) {
        e->C[k][i] = -a[i];
        e->C[k][3 + i] = axd[i];
        e->C[k][6 + i] = a[i];
        t1[i] += t2[i];
    }
    e->c[k] = dot3(n1->w, t1) + dot3(ad, dd);
}

static void prismatic_eval(const real_t *p, const rt_mbs_node *n1, const rt_mbs_node *n2,
                           rt_joint_eval *e)
{
    (void)p;
    clear(e, 5);
    slide_row(n1, n2, 0, 0, e);
    slide_row(n1, n2, 1, 1, e);
    perpendicular(n1, n2, 1, 2, 2, e);
    perpendicular(n1, n2, 2, 0, 3, e);
    perpendicular(n1, n2, 0, 1, 4, e);
}

static const char *const sphdiff_p[] = {"l"};

const rt_joint_kind rt_joint_sphdiff = {
    .name = "sphdiff", .nc = 1, .np = 1, .trans = 1, .anti = 1, .p_names = sphdiff_p,
    .check = sphdiff_check, .eval = sphdiff_eval, .eval_points = sphdiff_points,
    .g_points = sphdiff_g,
    .doc = RT_DOC("Rod of length l between two points (spherical difference, eq. (8)):\n"
                  "  g = |d| - l = 0,  d = r1 - r2 (node positions, inertial frame)\n"
                  "  g' = e.(v1 - v2), e = d/|d|; coincident nodes: e = +x"),
    .free = RT_DOC("5 of 6 relative directions: both rotations of the rod and the nodes' "
                   "rotations about their points; only the distance is held"),
};
const rt_joint_kind rt_joint_spherical = {
    .name = "spherical", .nc = 3, .trans = 1, .eval = spherical_eval,
    .doc = RT_DOC("Ball joint: the two nodes coincide.\n"
                  "  g = r1 - r2 = 0 (3 rows)"),
    .free = RT_DOC("the three relative rotations"),
};
const rt_joint_kind rt_joint_revolute = {
    .name = "revolute", .nc = 5, .eval = revolute_eval,
    .doc = RT_DOC("Hinge: the nodes coincide and their joint axes are parallel. With the\n"
                  "joint frame A (J.axis, default z) the node frames are S1 A, S2 A:\n"
                  "  g = r1 - r2 = 0 (3 rows)\n"
                  "  (S2 A ez).(S1 A ex) = 0,  (S2 A ez).(S1 A ey) = 0"),
    .free = RT_DOC("the rotation about the joint axis (S1 A ez)"),
};
const rt_joint_kind rt_joint_fixed = {
    .name = "fixed", .nc = 6, .eval = fixed_eval,
    .doc = RT_DOC("Clamp: the nodes coincide and their frames agree (node frames S1 A, S2 A):\n"
                  "  g = r1 - r2 = 0 (3 rows)\n"
                  "  (S2 A ey).(S1 A ez) = 0, (S2 A ez).(S1 A ex) = 0, (S2 A ex).(S1 A ey) = 0\n"
                  "On a mass point (no rotation) the three orientation rows restrain no\n"
                  "motion: dropped and counted redundant (a spherical joint says it)."),
    .free = RT_DOC("none"),
};

const rt_joint_kind rt_joint_prismatic = {
    .name = "prismatic", .nc = 5, .eval = prismatic_eval,
    .doc = RT_DOC("Slider: node 2 stays on the line through node 1 along the joint axis, and\n"
                  "the frames agree (node frames S1 A, S2 A; J.axis, default z):\n"
                  "  a.d = 0 for a = S1 A ex, S1 A ey, d = r2 - r1 (2 rows)\n"
                  "  the three orientation rows of fixed\n"
                  "A cart on a horizontal rail: J.axis = (1, 0, 0), bodies unturned."),
    .free = RT_DOC("the translation along the joint axis (S1 A ez)"),
};

const rt_joint_entry rt_joint_kinds[] = {
    {"sphdiff", &rt_joint_sphdiff},
    {"spherical", &rt_joint_spherical},
    {"revolute", &rt_joint_revolute},
    {"fixed", &rt_joint_fixed},
    {"prismatic", &rt_joint_prismatic},
    {0, 0},
};
