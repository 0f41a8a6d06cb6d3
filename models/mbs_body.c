/* mbs_body.c - a spatial rigid body as a multibody module (eq. 6): coordinates
 * q = [r (3), p (4)] with p a unit quaternion (scalar first) of the body-to-inertial
 * rotation R(p), velocities z = [v (3, inertial), w (3, body frame)]. Free of
 * singularities: the quaternion enters only through K,
 *     r' = v,  p' = 1/2 p (x) (0, w)                      (eq. 6a, K(q) 7 x 6, b = 0)
 * and K keeps |p| constant up to the integrator's error; the projection renormalizes it.
 * M = diag(m I, J) is constant; k = [m g + f, -w x J w + tau] (eq. 6b).
 * Three interaction nodes with node frame = body frame: "cm" at the centre of mass, "n1"
 * and "n2" at body-frame offsets given as parameters.
 * Parameters: m [kg], the inertia tensor about the centre of mass in the body frame Jxx,
 * Jyy, Jzz, Jxy, Jyz, Jxz [kg m^2] (tensor entries), gravity gx, gy, gz [m/s^2], node
 * offsets n1x.. n2z [m]. Two kinds: mbs_body (gravity only) and mbs_bodyf (inputs: force
 * fx, fy, fz [N] at the centre of mass, inertial frame; torque tx, ty, tz [N m], body
 * frame). Outputs: position and velocity of the centre of mass, body angular velocity,
 * position and velocity of nodes n1 and n2. */
#include "models.h"
#include "rigid.h"

enum { P_M = 0, P_J = 1, P_G = 7, P_N1 = 10, P_N2 = 13, NP = 16 };

static const char *const x_names[] = {"x", "y", "z", "p0", "p1", "p2", "p3",
                                      "vx", "vy", "vz", "wx", "wy", "wz"};
static const char *const y_names[] = {"x", "y", "z", "vx", "vy", "vz", "wx", "wy", "wz",
                                      "n1x", "n1y", "n1z", "n1vx", "n1vy", "n1vz",
                                      "n2x", "n2y", "n2z", "n2vx", "n2vy", "n2vz"};
static const char *const p_names[] = {"m", "Jxx", "Jyy", "Jzz", "Jxy", "Jyz", "Jxz",
                                      "gx", "gy", "gz", "n1x", "n1y", "n1z",
                                      "n2x", "n2y", "n2z"};
static const char *const u_names[] = {"fx", "fy", "fz", "tx", "ty", "tz"};
static const char *const node_names[] = {"cm", "n1", "n2"};
static const real_t p_default[NP] = {1, (real_t)0.1, (real_t)0.1, (real_t)0.1, 0, 0, 0,
                                     0, 0, (real_t)-9.81, 0, 0, 0, 0, 0, 0};
static const real_t x_default[13] = {0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0};

/* the symmetric inertia tensor from its six parameters */
static void inertia(const real_t *p, real_t *J)
{
    const real_t *j = p + P_J;
    J[0] = j[0], J[4] = j[1], J[8] = j[2];
    J[1] = J[3] = j[3];
    J[5] = J[7] = j[4];
    J[2] = J[6] = j[5];
}

/* r' = v, p' = 1/2 p (x) (0, w): the K of eq. 6a applied to v = [v; w] */
static void kin(const rt_args *a, const real_t *v, real_t *qd) { mdl_rigid_kin(a->x, v, qd); }

/* M = diag(m I, J), 6 x 6 */
static void mass(const rt_args *a, real_t *M)
{
    real_t J[9];
    inertia(a->p, J);
    for (int i = 0; i < 36; i++)
        M[i] = 0;
    for (int i = 0; i < 3; i++) {
        M[7 * (size_t)i] = a->p[P_M];
        for (int k = 0; k < 3; k++)
            M[(3 + i) * 6 + 3 + k] = J[3 * i + k];
    }
}

/* k = [m g, -w x J w]: gravity and the gyroscopic torque (Euler's equations) */
static void force(const rt_args *a, real_t *k)
{
    const real_t *w = a->x + 10;
    real_t J[9], Jw[3];
    inertia(a->p, J);
    mdl_mul3(J, w, Jw);
    mdl_cross3(w, Jw, k + 3);
    for (int i = 0; i < 3; i++) {
        k[i] = a->p[P_M] * a->p[P_G + i];
        k[3 + i] = -k[3 + i];
    }
}

/* plus the inputs: force at the centre of mass (inertial), torque (body frame) */
static void force_u(const rt_args *a, real_t *k)
{
    force(a, k);
    for (int i = 0; i < 6; i++)
        k[i] += a->u[i];
}

/* node at body offset s (rigid.c): r = r0 + R s, v = v0 + R (w x s), w_I = R w,
   ar = R (w x (w x s)), aw = 0; Jr = [I, -R [s]x], Jw = [0, R] */
static void node(const rt_args *a, uint16_t i, rt_mbs_node *n, real_t *J)
{
    static const real_t zero[3] = {0, 0, 0};
    const real_t *s = i == 1 ? a->p + P_N1 : i == 2 ? a->p + P_N2 : zero;
    real_t R[9];
    mdl_rotation(a->x + 3, R);
    mdl_rigid_node(a->x, R, s, n, J);
}

/* T = m |v|^2 / 2 + w^T J w / 2, V = -m g . r */
static void energy(const rt_args *a, real_t *e)
{
    const real_t *x = a->x, *p = a->p, *w = x + 10;
    real_t J[9], Jw[3];
    inertia(p, J);
    mdl_mul3(J, w, Jw);
    e[0] = (real_t)0.5 * (p[P_M] * (x[7] * x[7] + x[8] * x[8] + x[9] * x[9]) +
                          (w[0] * Jw[0] + w[1] * Jw[1] + w[2] * Jw[2]));
    e[1] = -p[P_M] * (p[P_G] * x[0] + p[P_G + 1] * x[1] + p[P_G + 2] * x[2]);
}

/* centre of mass, body angular velocity, and nodes n1, n2 (position, velocity) */
static void output(const rt_args *a, real_t *y)
{
    rt_mbs_node n1, n2;
    node(a, 1, &n1, 0);
    node(a, 2, &n2, 0);
    for (int i = 0; i < 3; i++) {
        y[i] = a->x[i], y[3 + i] = a->x[7 + i], y[6 + i] = a->x[10 + i];
        y[9 + i] = n1.r[i], y[12 + i] = n1.v[i];
        y[15 + i] = n2.r[i], y[18 + i] = n2.v[i];
    }
}

/* m > 0 and J positive definite (leading minors), everything finite */
static rt_status check(const real_t *p, const void *spec)
{
    (void)spec;
    for (int i = 0; i < NP; i++)
        if (!rt_isfinite(p[i]))
            return RT_E_PARAM;
    real_t J[9];
    inertia(p, J);
    real_t m2 = J[0] * J[4] - J[1] * J[3];
    real_t det = J[0] * (J[4] * J[8] - J[5] * J[7]) - J[1] * (J[3] * J[8] - J[5] * J[6]) +
                 J[2] * (J[3] * J[7] - J[4] * J[6]);
    return p[P_M] > 0 && J[0] > 0 && m2 > 0 && det > 0 ? RT_OK : RT_E_PARAM;
}

static const rt_mbs_spec spec = {
    .nq = 7, .nz = 6, .nn = 3, .node_names = node_names, .kin = kin, .mass = mass,
    .force = force, .node = node, .energy = energy, .normalize = mdl_rigid_normalize,
};
static const rt_mbs_spec spec_u = {
    .nq = 7, .nz = 6, .nn = 3, .node_names = node_names, .kin = kin, .mass = mass,
    .force = force_u, .node = node, .energy = energy, .normalize = mdl_rigid_normalize,
};

const rt_kind mdl_mbs_body_kind = {
    .name = "mbs_body", .type = RT_KIND_MBS, .ny = 21, .nx = 13, .np = NP,
    .y_names = y_names, .x_names = x_names, .p_names = p_names, .p_default = p_default,
    .x_default = x_default, .feed = RT_FEED_NONE,
    .autonomous = 1, .check = check, .output = output,
    .spec = &spec,
    .doc = RT_DOC(
        "Spatial rigid body (eq. (6)): q = [r, p], p = (p0, p1, p2, p3) a unit quaternion\n"
        "(scalar first) of the body-to-inertial rotation R(p); z = [v inertial, w body].\n"
        "r' = v, p' = 1/2 p (x) (0, w) (6a); m v' = m g, J w' = -w x J w (6b).\n"
        "Nodes cm, n1, n2 [r|S], S = R, at body offsets 0, (n1x n1y n1z), (n2x n2y n2z).\n"
        "m > 0; J (Jxx Jyy Jzz Jxy Jyz Jxz, about cm, body frame) positive definite; all\n"
        "finite. Outputs: cm position and velocity, w, n1 and n2 position and velocity."),
    .units = RT_DOC(
        "m m m m/s m/s m/s rad/s rad/s rad/s m m m m/s m/s m/s m m m m/s m/s m/s m m m - - "
        "- - m/s m/s m/s rad/s rad/s rad/s kg kg*m^2 kg*m^2 kg*m^2 kg*m^2 kg*m^2 kg*m^2 "
        "m/s^2 m/s^2 m/s^2 m m m m m m"),
};
const rt_kind mdl_mbs_bodyf_kind = {
    .name = "mbs_bodyf", .type = RT_KIND_MBS, .nu = 6, .ny = 21, .nx = 13, .np = NP,
    .u_names = u_names, .y_names = y_names, .x_names = x_names, .p_names = p_names,
    .p_default = p_default, .x_default = x_default, .feed = RT_FEED_NONE,
    .autonomous = 1, .check = check,
    .output = output, .spec = &spec_u,
    .doc = RT_DOC(
        "Spatial rigid body with inputs (eq. (6)): q = [r, p], p a unit quaternion\n"
        "(scalar first) of R(p); z = [v inertial, w body]. r' = v, p' = 1/2 p (x) (0, w);\n"
        "m v' = m g + f (f inertial, at cm), J w' = -w x J w + tau (tau in body frame).\n"
        "Nodes cm, n1, n2 [r|S] at body offsets 0, n1, n2, S = R. m > 0; J (Jxx Jyy Jzz\n"
        "Jxy Jyz Jxz, about cm, body frame) positive definite; all finite.\n"
        "Outputs: cm position and velocity, w, n1 and n2 position and velocity."),
    .units = RT_DOC(
        "N N N N*m N*m N*m m m m m/s m/s m/s rad/s rad/s rad/s m m m m/s m/s m/s m m m m/s "
        "m/s m/s m m m - - - - m/s m/s m/s rad/s rad/s rad/s kg kg*m^2 kg*m^2 kg*m^2 "
        "kg*m^2 kg*m^2 kg*m^2 m/s^2 m/s^2 m/s^2 m m m m m m"),
};
