/* vehicle_st.c - a planar single-track car with linear tires as a multibody module
 * (eq. 6: K = I, M = diag(m, m, Iz)), with hitch nodes for a tow bar (docs/vehicles.md).
 *
 * Coordinates q = (x, y, psi): the centre of mass in the ground frame (x along the track,
 * y to the left) and the yaw angle; velocities z = (vx, vy, r) in the ground frame, so
 * q' = z. In the body frame the speeds are u = vx cos psi + vy sin psi (forward) and
 * v = -vx sin psi + vy cos psi (left). The linear single-track tires (NUMERICS.md,
 * "Vehicle models"):
 *   F_yf = C_f (delta - (v + l_f r) / u),  F_yr = -C_r (v - l_r r) / u,
 * with u bounded below by u_min (the slip is undefined at rest); in the body frame
 * F_x = Fx (the drive input), F_y = F_yf + F_yr, M_z = l_f F_yf - l_r F_yr, so
 * m (v' + u r) = F_yf + F_yr and I_z r' = l_f F_yf - l_r F_yr, as in the textbook model.
 * Nodes "front" and "rear": the hitch points d_f ahead of and d_r behind the centre of
 * mass, at height 0, their frame turned by psi about z. */
#include "models.h"

enum { P_M, P_IZ, P_LF, P_LR, P_CF, P_CR, P_DF, P_DR, P_UMIN, P_COUNT };
/* st_car_mf adds the Magic Formula's friction, shape, curvature and gravity */
enum { P_MU = P_COUNT, P_SHAPE, P_CURV, P_G, P_COUNT_MF };
enum { U_DELTA, U_FX };

static const char *const x_names[] = {"x", "y", "psi", "vx", "vy", "r"};
static const char *const y_names[] = {"x", "y", "psi", "u", "v", "r", "ay"};
static const char *const u_names[] = {"delta", "Fx"};
static const char *const p_names[] = {"m", "Iz", "lf", "lr", "Cf", "Cr", "df", "dr", "umin",
                                      "mu", "C", "E", "g"};
static const char *const node_names[] = {"front", "rear"};
/* CommonRoad vehicle 1 (NUMERICS.md): m, Iz, lf, lr; C_f 158 kN/rad and C_r 170 kN/rad
   (mildly understeering); hitches 2 m ahead of and behind the centre of mass */
static const real_t p_default[P_COUNT] = {(real_t)1225.887, (real_t)1538.853, (real_t)0.88392,
                                          (real_t)1.50876, (real_t)158000, (real_t)170000, 2, 2,
                                          1};
/* the same car, and a dry road: mu 1, lateral shape 1.3, curvature -0.5 (Pacejka,
   Tire and Vehicle Dynamics, ch. 4: typical lateral values), g 9.81 m/s^2 */
static const real_t p_default_mf[P_COUNT_MF] = {
    (real_t)1225.887, (real_t)1538.853, (real_t)0.88392, (real_t)1.50876, (real_t)158000,
    (real_t)170000, 2, 2, 1, 1, (real_t)1.3, (real_t)-0.5, (real_t)9.81};
static const real_t x_default[6] = {0, 0, 0, 20, 0, 0};
/* ay depends on delta directly (the front tire force); nothing else feeds through */
static const uint8_t feed[7 * 2] = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0};

/* Magic Formula F = D sin(C atan(B a - E (B a - atan(B a)))), D = mu Fz, with
   B C D = the cornering stiffness, so that F = Ca a for small slip angles a */
static real_t magic(real_t alpha, real_t ca, real_t fz, const real_t *p)
{
    real_t d = p[P_MU] * fz, b = ca / (p[P_SHAPE] * d), ba = b * alpha;
    return d * rt_sin(p[P_SHAPE] * rt_atan(ba - p[P_CURV] * (ba - rt_atan(ba))));
}

/* body-frame speeds: u (forward, at least umin: us), v (left), the yaw rate r */
typedef struct speeds {
    real_t u, v, r, us;
} speeds;

/* cos and sin of the yaw: taken once in each kind function, which hands them on */
typedef struct yaw {
    real_t c, s;
} yaw;

static yaw yaw_of(const rt_args *a)
{
    yaw w = {rt_cos(a->x[2]), rt_sin(a->x[2])};
    return w;
}

static speeds body_speeds(const rt_args *a, yaw w)
{
    const real_t *x = a->x;
    real_t c = w.c, s = w.s;
    speeds b = {c * x[3] + s * x[4], -s * x[3] + c * x[4], x[5], 0};
    b.us = b.u > a->p[P_UMIN] ? b.u : a->p[P_UMIN];
    return b;
}

/* body-frame tire resultants fb = (F_x, F_y, M_z) from the axles' lateral forces */
static void resultants(const rt_args *a, real_t fyf, real_t fyr, real_t *fb)
{
    const real_t *p = a->p;
    fb[0] = a->u[U_FX];
    fb[1] = fyf + fyr;
    fb[2] = p[P_LF] * fyf - p[P_LR] * fyr;
}

/* linear tires (st_car). Each kind has its own tire function, so that an image of a
   scene with linear tires links no Magic-Formula code */
static void tires(const rt_args *a, speeds b, real_t *fb)
{
    const real_t *p = a->p;
    resultants(a, p[P_CF] * (a->u[U_DELTA] - (b.v + p[P_LF] * b.r) / b.us),
               -p[P_CR] * (b.v - p[P_LR] * b.r) / b.us, fb);
}

/* the Magic Formula with exact slip angles and static axle loads (st_car_mf) */
static void tires_mf(const rt_args *a, speeds b, real_t *fb)
{
    const real_t *p = a->p;
    real_t l = p[P_LF] + p[P_LR], w = p[P_M] * p[P_G];
    resultants(a,
               magic(a->u[U_DELTA] - rt_atan((b.v + p[P_LF] * b.r) / b.us), p[P_CF],
                     w * p[P_LR] / l, p),
               magic(-rt_atan((b.v - p[P_LR] * b.r) / b.us), p[P_CR], w * p[P_LF] / l, p), fb);
}

static void kin(const rt_args *a, const real_t *v, real_t *qd)
{
    (void)a;
    qd[0] = v[0], qd[1] = v[1], qd[2] = v[2];
}

static void mass(const rt_args *a, real_t *M)
{
    M[0] = M[1] = a->p[P_M];
    M[2] = a->p[P_IZ];
}

/* the body-frame resultants fb turned into the ground frame */
static void to_ground(yaw w, const real_t *fb, real_t *k)
{
    real_t c = w.c, s = w.s;
    k[0] = c * fb[0] - s * fb[1];
    k[1] = s * fb[0] + c * fb[1];
    k[2] = fb[2];
}

static void force(const rt_args *a, real_t *k)
{
    real_t fb[3];
    yaw w = yaw_of(a);
    tires(a, body_speeds(a, w), fb);
    to_ground(w, fb, k);
}

static void force_mf(const rt_args *a, real_t *k)
{
    real_t fb[3];
    yaw w = yaw_of(a);
    tires_mf(a, body_speeds(a, w), fb);
    to_ground(w, fb, k);
}

/* hitch i at d ahead of the centre of mass (d < 0: behind) */
static void node(const rt_args *a, uint16_t i, rt_mbs_node *n, real_t *J)
{
    const real_t *x = a->x;
    real_t d = i == 0 ? a->p[P_DF] : -a->p[P_DR];
    yaw w = yaw_of(a);
    real_t c = w.c, s = w.s, r = x[5];
    n->r[0] = x[0] + d * c, n->r[1] = x[1] + d * s, n->r[2] = 0;
    n->v[0] = x[3] - d * s * r, n->v[1] = x[4] + d * c * r, n->v[2] = 0;
    n->w[0] = n->w[1] = 0, n->w[2] = r;
    n->ar[0] = -d * c * r * r, n->ar[1] = -d * s * r * r, n->ar[2] = 0;
    n->aw[0] = n->aw[1] = n->aw[2] = 0;
    /* stored entry by entry: through a local table and a loop it took twice the time */
    n->S[0] = c, n->S[1] = -s, n->S[2] = 0;
    n->S[3] = s, n->S[4] = c, n->S[5] = 0;
    n->S[6] = 0, n->S[7] = 0, n->S[8] = 1;
    if (!J)
        return;
    /* 6 x 3: Jr = [1 0 -d s; 0 1 d c; 0 0 0], Jw = [0 0 0; 0 0 0; 0 0 1] */
    J[0] = 1, J[1] = 0, J[2] = -d * s;
    J[3] = 0, J[4] = 1, J[5] = d * c;
    J[6] = J[7] = J[8] = J[9] = J[10] = J[11] = 0;
    J[12] = J[13] = J[14] = J[15] = J[16] = 0, J[17] = 1;
}

static void energy(const rt_args *a, real_t *e)
{
    const real_t *x = a->x;
    e[0] = (real_t)0.5 * (a->p[P_M] * (x[3] * x[3] + x[4] * x[4]) + a->p[P_IZ] * x[5] * x[5]);
    e[1] = 0;
}

/* outputs from the state and the body-frame resultants fb */
static void outputs(const rt_args *a, speeds b, const real_t *fb, real_t *y)
{
    const real_t *x = a->x;
    y[0] = x[0], y[1] = x[1], y[2] = x[2];
    y[3] = b.u, y[4] = b.v, y[5] = x[5];
    y[6] = fb[1] / a->p[P_M]; /* v' + u r: the lateral acceleration in the body frame */
}

static void output(const rt_args *a, real_t *y)
{
    real_t fb[3];
    speeds b = body_speeds(a, yaw_of(a));
    tires(a, b, fb);
    outputs(a, b, fb, y);
}

static void output_mf(const rt_args *a, real_t *y)
{
    real_t fb[3];
    speeds b = body_speeds(a, yaw_of(a));
    tires_mf(a, b, fb);
    outputs(a, b, fb, y);
}

static rt_status check_n(const real_t *p, int n)
{
    int ok = rt_all_finite(p, n) && p[P_M] > 0 && p[P_IZ] > 0 && p[P_LF] > 0 && p[P_LR] > 0 &&
             p[P_CF] > 0 && p[P_CR] > 0 && p[P_DF] >= 0 && p[P_DR] >= 0 && p[P_UMIN] > 0;
    return ok ? RT_OK : RT_E_PARAM;
}

static rt_status check(const real_t *p, const void *spec)
{
    (void)spec;
    return check_n(p, P_COUNT);
}

/* the Magic Formula also needs mu > 0, C in (0, 2) (a peak), E <= 1, g > 0 */
static rt_status check_mf(const real_t *p, const void *spec)
{
    (void)spec;
    return check_n(p, P_COUNT_MF) == RT_OK && p[P_MU] > 0 && p[P_SHAPE] > 0 &&
                   p[P_SHAPE] < 2 && p[P_CURV] <= 1 && p[P_G] > 0
               ? RT_OK
               : RT_E_PARAM;
}

static const rt_mbs_spec spec = {
    .nq = 3, .nz = 3, .nn = 2, .flags = RT_MBS_M_DIAG | RT_MBS_M_CONST | RT_MBS_K_CONST,
    .node_names = node_names,
    .kin = kin, .mass = mass, .force = force, .node = node, .energy = energy,
};

const rt_kind mdl_st_car_kind = {
    .name = "st_car", .type = RT_KIND_MBS, .nu = 2, .ny = 7, .nx = 6, .np = P_COUNT,
    .u_names = u_names, .y_names = y_names, .x_names = x_names, .p_names = p_names,
    .p_default = p_default, .x_default = x_default, .feed = RT_FEED_TABLE,
    .autonomous = 1, .feed_table = feed,
    .check = check, .output = output, .spec = &spec,
    .doc = RT_DOC(
        "Planar single-track car with linear tires as a multibody module (eq. (6)):\n"
        "q = (x, y, psi), z = (vx, vy, r) in the ground frame, q' = z,\n"
        "M = diag(m, m, Iz). Body speeds u (forward), v (left). Tires:\n"
        "F_yf = Cf (delta - (v + lf r)/u), F_yr = -Cr (v - lr r)/u (u >= umin);\n"
        "m (v' + u r) = F_yf + F_yr, Iz r' = lf F_yf - lr F_yr, m (u' - v r) = Fx.\n"
        "Nodes front and rear: hitch points df ahead of and dr behind the centre of mass.\n"
        "Outputs x, y, psi, u, v, r and the lateral acceleration ay = v' + u r.\n"
        "Defaults: CommonRoad vehicle 1 (m, Iz, lf, lr), Cf 158 kN/rad, Cr 170 kN/rad."),
    .units = RT_DOC("rad N m m rad m/s m/s rad/s m/s^2 m m rad m/s m/s rad/s "
                    "kg kg*m^2 m m N/rad N/rad m m m/s"),
};

static const rt_mbs_spec spec_mf = {
    .nq = 3, .nz = 3, .nn = 2, .flags = RT_MBS_M_DIAG | RT_MBS_M_CONST | RT_MBS_K_CONST,
    .node_names = node_names,
    .kin = kin, .mass = mass, .force = force_mf, .node = node, .energy = energy,
};

const rt_kind mdl_st_car_mf_kind = {
    .name = "st_car_mf", .type = RT_KIND_MBS, .nu = 2, .ny = 7, .nx = 6, .np = P_COUNT_MF,
    .u_names = u_names, .y_names = y_names, .x_names = x_names, .p_names = p_names,
    .p_default = p_default_mf, .x_default = x_default, .feed = RT_FEED_TABLE, .autonomous = 1,
    .feed_table = feed, .check = check_mf, .output = output_mf, .spec = &spec_mf,
    .doc = RT_DOC(
        "Planar single-track car with Magic-Formula tires (the same ports, states and\n"
        "nodes as st_car): slip angles a_f = delta - atan((v + lf r)/u),\n"
        "a_r = -atan((v - lr r)/u) (u >= umin); F = D sin(C atan(B a - E (B a - atan(B a))))\n"
        "with D = mu Fz on the static axle loads Fz_f = m g lr/L, Fz_r = m g lf/L and\n"
        "B C D = Cf (front), Cr (rear), so small slips give the linear tires' forces.\n"
        "mu: friction, > 0; C: shape, 0 < C < 2; E: curvature, <= 1; g: gravity."),
    .units = RT_DOC("rad N m m rad m/s m/s rad/s m/s^2 m m rad m/s m/s rad/s "
                    "kg kg*m^2 m m N/rad N/rad m m m/s - - - m/s^2"),
};
