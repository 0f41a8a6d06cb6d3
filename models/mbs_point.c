/* mbs_point.c - a mass point as a multibody module (eq. 6 with K = I, b = 0, M = m I and
 * no internal constraints) with one interaction node "c" at the point, S = I.
 * States x, y, z [m], vx, vy, vz [m/s]; parameters m [kg] and gravity gx, gy, gz
 * [m/s^2]; outputs the position and velocity. Two kinds: mbs_point (gravity only) and
 * mbs_pointf (plus an applied force fx, fy, fz [N] as inputs). */
#include "models.h"

static const char *const x_names[] = {"x", "y", "z", "vx", "vy", "vz"};
static const char *const p_names[] = {"m", "gx", "gy", "gz"};
static const char *const u_names[] = {"fx", "fy", "fz"};
static const char *const node_names[] = {"c"};
static const real_t p_default[] = {1, 0, 0, (real_t)-9.81};

/* q' = z (eq. 6a) */
static void kin(const rt_args *a, const real_t *v, real_t *qd)
{
    (void)a;
    for (int i = 0; i < 3; i++)
        qd[i] = v[i];
}

/* M = m I, diagonal and constant (RT_MBS_M_DIAG, RT_MBS_M_ISO, RT_MBS_M_CONST) */
static void mass(const rt_args *a, real_t *M)
{
    M[0] = M[1] = M[2] = a->p[0];
}

/* k = m g (eq. 6b): parameters only (RT_MBS_F_PARAM) */
static void force(const rt_args *a, real_t *k)
{
    for (int i = 0; i < 3; i++)
        k[i] = a->p[0] * a->p[1 + i];
}

/* k = m g + f */
static void force_u(const rt_args *a, real_t *k)
{
    for (int i = 0; i < 3; i++)
        k[i] = a->p[0] * a->p[1 + i] + a->u[i];
}

/* node "c": r = q, v = z, Jr = I, no rotation, no acceleration terms (the kind says
   RT_MBS_NODE_POINT, so the assembly needs no J; it is written when asked for) */
static void node(const rt_args *a, uint16_t i, rt_mbs_node *n, real_t *J)
{
    static const real_t unit[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    (void)i;
    for (int k = 0; k < 3; k++) {
        n->r[k] = a->x[k];
        n->v[k] = a->x[3 + k];
        n->w[k] = n->ar[k] = n->aw[k] = 0;
    }
    for (int k = 0; k < 9; k++)
        n->S[k] = unit[k];
    if (!J)
        return;
    for (int k = 0; k < 9; k++) /* 6 x 3: Jr = I, Jw = 0 */
        J[k] = unit[k], J[9 + k] = 0;
}

/* T = m |v|^2 / 2, V = -m g . r */
static void energy(const rt_args *a, real_t *e)
{
    const real_t *x = a->x, *p = a->p;
    e[0] = (real_t)0.5 * p[0] * (x[3] * x[3] + x[4] * x[4] + x[5] * x[5]);
    e[1] = -p[0] * (p[1] * x[0] + p[2] * x[1] + p[3] * x[2]);
}

static void output(const rt_args *a, real_t *y)
{
    for (int i = 0; i < 6; i++)
        y[i] = a->x[i];
}

static rt_status check(const real_t *p, const void *spec)
{
    (void)spec;
    return p[0] > 0 && rt_isfinite(p[0]) && rt_isfinite(p[1]) && rt_isfinite(p[2]) &&
                   rt_isfinite(p[3])
               ? RT_OK
               : RT_E_PARAM;
}

static const rt_mbs_spec spec = {
    .nq = 3, .nz = 3, .nn = 1, 
    .flags = RT_MBS_M_DIAG | RT_MBS_M_CONST | RT_MBS_K_CONST | RT_MBS_F_PARAM |
             RT_MBS_NODE_POINT | RT_MBS_M_ISO | RT_MBS_Y_STATE,
    .node_names = node_names,
    .kin = kin, .mass = mass, .force = force, .node = node, .energy = energy,
};
static const rt_mbs_spec spec_u = {
    .nq = 3, .nz = 3, .nn = 1, 
    .flags = RT_MBS_M_DIAG | RT_MBS_M_CONST | RT_MBS_K_CONST | RT_MBS_NODE_POINT |
             RT_MBS_M_ISO | RT_MBS_Y_STATE,
    .node_names = node_names,
    .kin = kin, .mass = mass, .force = force_u, .node = node, .energy = energy,
};

const rt_kind mdl_mbs_point_kind = {
    .name = "mbs_point", .type = RT_KIND_MBS, .ny = 6, .nx = 6, .np = 4,
    .y_names = x_names, .x_names = x_names, .p_names = p_names, .p_default = p_default,
    .feed = RT_FEED_NONE, .autonomous = 1, .check = check, .output = output, .spec = &spec,
    .doc = RT_DOC(
        "Mass point as a multibody module (eq. (6): K = I, b = 0, M = m I, no internal\n"
        "constraints): coordinates q = r = (x, y, z), velocities z = v = (vx, vy, vz);\n"
        "q' = v, m v' = m g. One node c [r|S] at the point, S = I.\n"
        "Outputs position and velocity. m: mass, > 0; gx, gy, gz: gravity; all finite."),
    .units = RT_DOC("m m m m/s m/s m/s m m m m/s m/s m/s kg m/s^2 m/s^2 m/s^2"),
};
const rt_kind mdl_mbs_pointf_kind = {
    .name = "mbs_pointf", .type = RT_KIND_MBS, .nu = 3, .ny = 6, .nx = 6, .np = 4,
    .u_names = u_names, .y_names = x_names, .x_names = x_names, .p_names = p_names,
    .p_default = p_default, .feed = RT_FEED_NONE,
    .autonomous = 1, .check = check, .output = output,
    .spec = &spec_u,
    .doc = RT_DOC(
        "Mass point with an applied force as a multibody module (eq. (6): K = I, b = 0,\n"
        "M = m I, no internal constraints): coordinates q = r = (x, y, z), velocities\n"
        "z = v = (vx, vy, vz); q' = v, m v' = m g + f, f = (fx, fy, fz) inertial.\n"
        "One node c [r|S] at the point, S = I. Outputs position and velocity.\n"
        "m: mass, > 0; gx, gy, gz: gravity; all finite."),
    .units = RT_DOC("N N N m m m m/s m/s m/s m m m m/s m/s m/s kg m/s^2 m/s^2 m/s^2"),
};
