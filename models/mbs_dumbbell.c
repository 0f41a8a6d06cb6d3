/* mbs_dumbbell.c - a module of two mass points joined by a massless rod: a multibody block
 * with several bodies and one internal constraint (eq. 6c inside the module),
 * g = |r1 - r2| - l = 0, written with the spherical difference joint kind of eq. 8.
 * Coordinates q = [r1, r2] [m], velocities z = [v1, v2] [m/s]; parameters m1, m2 [kg],
 * l [m], gravity gx, gy, gz [m/s^2]; nodes "p1", "p2" at the points; outputs both
 * positions. */
#include "models.h"

enum { P_M1 = 0, P_M2, P_L, P_G, NP = 6 };

static const char *const x_names[] = {"x1", "y1", "z1", "x2", "y2", "z2",
                                      "vx1", "vy1", "vz1", "vx2", "vy2", "vz2"};
static const char *const p_names[] = {"m1", "m2", "l", "gx", "gy", "gz"};
static const char *const node_names[] = {"p1", "p2"};
static const real_t p_default[NP] = {1, 1, 1, 0, 0, (real_t)-9.81};

static void kin(const rt_args *a, const real_t *v, real_t *qd)
{
    (void)a;
    for (int i = 0; i < 6; i++)
        qd[i] = v[i];
}

/* M = diag(m1 I, m2 I) (RT_MBS_M_DIAG) */
static void mass(const rt_args *a, real_t *M)
{
    for (int i = 0; i < 6; i++)
        M[i] = a->p[i < 3 ? P_M1 : P_M2];
}

static void force(const rt_args *a, real_t *k)
{
    for (int i = 0; i < 6; i++)
        k[i] = a->p[i < 3 ? P_M1 : P_M2] * a->p[P_G + i % 3];
}

/* point i: r, v from the state; no rotation, Jr selects its three velocities */
static void node(const rt_args *a, uint16_t i, rt_mbs_node *n, real_t *J)
{
    for (int k = 0; k < 3; k++) {
        n->r[k] = a->x[3 * i + k];
        n->v[k] = a->x[6 + 3 * i + k];
        n->w[k] = n->ar[k] = n->aw[k] = 0;
    }
    for (int k = 0; k < 9; k++)
        n->S[k] = k % 4 == 0 ? 1 : 0;
    for (int k = 0; J && k < 36; k++)
        J[k] = k < 18 && k % 6 == k / 6 + 3 * i ? 1 : 0;
}

/* the rod: g, g' and, on request, W = [e^T, -e^T] and gam from the joint kind */
static void constr(const rt_args *a, real_t *g, real_t *gd, real_t *W, uint16_t ld,
                   real_t *gam)
{
    rt_mbs_node n1, n2;
    rt_joint_eval e;
    node(a, 0, &n1, 0);
    node(a, 1, &n2, 0);
    rt_joint_sphdiff.eval(a->p + P_L, &n1, &n2, &e);
    g[0] = e.g[0];
    gd[0] = 0;
    for (int k = 0; k < 3; k++)
        gd[0] += e.C[0][k] * n1.v[k] + e.C[0][6 + k] * n2.v[k];
    if (!W)
        return;
    (void)ld;
    for (int k = 0; k < 3; k++)
        W[k] = e.C[0][k], W[3 + k] = e.C[0][6 + k];
    gam[0] = e.c[0];
}

static void energy(const rt_args *a, real_t *e)
{
    const real_t *x = a->x, *p = a->p;
    e[0] = e[1] = 0;
    for (int i = 0; i < 6; i++) {
        real_t m = p[i < 3 ? P_M1 : P_M2];
        e[0] += (real_t)0.5 * m * x[6 + i] * x[6 + i];
        e[1] -= m * p[P_G + i % 3] * x[i];
    }
}

static void output(const rt_args *a, real_t *y)
{
    for (int i = 0; i < 6; i++)
        y[i] = a->x[i];
}

static rt_status check(const real_t *p, const void *spec)
{
    (void)spec;
    for (int i = 0; i < NP; i++)
        if (!rt_isfinite(p[i]))
            return RT_E_PARAM;
    return p[P_M1] > 0 && p[P_M2] > 0 && p[P_L] > 0 ? RT_OK : RT_E_PARAM;
}

static const rt_mbs_spec spec = {
    .nq = 6, .nz = 6, .nc = 1, .nn = 2, .flags = RT_MBS_M_DIAG | RT_MBS_M_CONST | RT_MBS_K_CONST | RT_MBS_F_PARAM,
    .node_names = node_names,
    .kin = kin, .mass = mass, .force = force, .constr = constr, .node = node, .energy = energy,
};

const rt_kind mdl_mbs_dumbbell_kind = {
    .name = "mbs_dumbbell", .type = RT_KIND_MBS, .ny = 6, .nx = 12, .np = NP,
    .y_names = x_names, .x_names = x_names, .p_names = p_names, .p_default = p_default,
    .feed = RT_FEED_NONE, .autonomous = 1, .check = check, .output = output, .spec = &spec,
    .doc = RT_DOC(
        "Two mass points joined by a massless rod: eq. (6) with one internal constraint\n"
        "g = |r1 - r2| - l = 0 (6c), the spherical difference joint of eq. (8).\n"
        "q = [r1, r2], z = [v1, v2]; q' = z, mi vi' = mi g + rod force.\n"
        "Nodes p1, p2 [r|S] at the points, S = I. Outputs both positions.\n"
        "m1, m2: masses, > 0; l: rod length, > 0; gx, gy, gz: gravity; all finite."),
    .units = RT_DOC(
        "m m m m m m m m m m m m m/s m/s m/s m/s m/s m/s kg kg m m/s^2 m/s^2 m/s^2"),
};
