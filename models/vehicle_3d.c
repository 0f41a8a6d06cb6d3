/* vehicle_3d.c - a spatial car as a multibody module (eq. 6): the chassis a rigid body
 * with six degrees of freedom and a unit quaternion (rigid.h, as mbs_body), standing on
 * four corners with vertical spring-dampers and tires, with the hitch nodes and ports of
 * the single-track car (vehicle_st.c) so that a scene can swap the kinds
 * (docs/vehicles.md, "The spatial car").
 *
 * Coordinates q = [r, p] (centre of mass, quaternion of the body-to-ground rotation R),
 * velocities z = [v (ground frame), w (body frame)], M = diag(m, m, m, Ixx, Iyy, Izz)
 * (principal axes: RT_MBS_M_DIAG). Body frame x forward, y left, z up; ground z up.
 * Corner i (fl, fr, rl, rr) is the body point s_i = (l_f or -l_r, +-t/2, -h): the contact
 * point when the car stands at its design height h. Its height z_i and vertical speed
 * give the vertical load (suspension spring in series with the tire, damper; unsprung
 * masses neglected)
 *     F_z,i = max(0, pre F0_i - k z_i - c z_i' - (K_b / t^2) (z_i - z_o)),
 *     F0 = m g l_r / (2 L) front, m g l_f / (2 L) rear,
 * so that with pre = 1 the car starts at rest in static equilibrium; z_o is the height of
 * the other wheel on the axle, K_b the axle's anti-roll bar (roll stiffness kbf, kbr,
 * acting at the contacts). The tire forces act at the corner point in the ground plane,
 * from the slip of the point's velocity in the wheel frame (the body x axis projected on
 * the ground, turned by delta at the front):
 *     tan a = -V_y / V_x  (V_x >= u_min; the slip angle of vehicle_st.c for small angles).
 * car3d: linear tires whose cornering stiffness is proportional to the load,
 *     F_y = (C/2) (F_z / F0) tan a,
 * F_x as demanded (no friction limit). car3d_mf: the Magic Formula with D = mu F_z and a
 * degressive cornering stiffness C_a(F_z) = c1 sin(2 atan(F_z / c2)), c2 = fzpk F0,
 * C_a(F0) = C/2 (Pacejka, Tire and Vehicle Dynamics, ch. 4), combined with the
 * longitudinal force by the friction circle: F_x = the demand limited to mu F_z,
 * F_y = F_y0 sqrt(1 - (F_x / (mu F_z))^2).
 * The longitudinal force is quasi-static: the drive input Fx is split on the axles
 * (share `drive` in front) and on the two wheels; no wheel spin states (their slip time
 * constant of about 2 ms at 20 m/s would bound the vehicles' step near 1 ms). Fa is a
 * force along the heading at the centre of mass (aerodynamic drag). */
#include "models.h"
#include "rigid.h"

enum {
    P_M, P_IXX, P_IYY, P_IZZ, P_LF, P_LR, P_TF, P_TR, P_H, P_CF, P_CR, P_FZPK, P_MU,
    P_SHAPE, P_CURV, P_KF, P_KR, P_CDF, P_CDR, P_PRE, P_DRIVE, P_DF, P_DR, P_UMIN, P_G,
    P_KBF, P_KBR, P_COUNT
};
enum { U_DELTA, U_FX, U_FA, NU };
enum { Y_X, Y_Y, Y_PSI, Y_U, Y_V, Y_R, Y_AY, Y_Z, Y_ROLL, Y_PITCH, Y_FZ, NY = Y_FZ + 4 };
enum { NCORNER = 4, NX = MDL_RB_NQ + MDL_RB_NZ };

static const char *const x_names[] = {"x", "y", "z", "p0", "p1", "p2", "p3",
                                      "vx", "vy", "vz", "wx", "wy", "wz"};
static const char *const y_names[] = {"x", "y", "psi", "u", "v", "r", "ay",
                                      "z", "roll", "pitch", "Fz_fl", "Fz_fr", "Fz_rl", "Fz_rr"};
static const char *const u_names[] = {"delta", "Fx", "Fa"};
static const char *const p_names[] = {"m", "Ixx", "Iyy", "Izz", "lf", "lr", "tf", "tr", "h",
                                      "Cf", "Cr", "fzpk", "mu", "C", "E", "kf", "kr", "cf",
                                      "cr", "pre", "drive", "df", "dr", "umin", "g", "kbf", "kbr"};
static const char *const node_names[] = {"front", "rear"};
/* CommonRoad vehicle 1 (docs/vehicles.md): m, Ixx = I_Phi_s, Iyy = I_y_s, Izz, lf, lr,
   tracks T_f, T_r, h = h_cg; corner stiffness K_sf in series with the tire's K_zt,
   damping K_sdf. Cf, Cr, mu, C, E as st_car_mf; fzpk, drive, df, dr, umin: our choice;
   anti-roll bars kbf, kbr for a roll gradient of 5 deg/g with 68 % of the roll stiffness
   at the front (docs/vehicles.md, "Anti-roll bars") */
static const real_t p_default[P_COUNT] = {
    (real_t)1225.887, (real_t)244.047, (real_t)1342.260, (real_t)1538.853, (real_t)0.88392,
    (real_t)1.50876, (real_t)1.389888, (real_t)1.423416, (real_t)0.557784, 158000, 170000,
    2, 1, (real_t)1.3, (real_t)-0.5, (real_t)19632.988, (real_t)19632.988,
    (real_t)1459.390, (real_t)1459.390, 1, 1, 2, 2, 1, (real_t)9.81, 37900, 6900};
static const real_t x_default[NX] = {0, 0, (real_t)0.557784, 1, 0, 0, 0, 20, 0, 0, 0, 0, 0};
/* ay depends directly on delta and Fx (the tire forces); nothing else feeds through */
static const uint8_t feed[NY * NU] = {[Y_AY * NU + U_DELTA] = 1, [Y_AY * NU + U_FX] = 1};

/* what the two wheels of an axle share, from the parameters and inputs (computed once per
   evaluation, so that a corner divides only where its own state enters) */
typedef struct axle {
    real_t f0;     /* static load of each wheel: the statics of the axles [N] */
    real_t k, c;   /* corner stiffness [N/m], damping [N s/m] */
    real_t kb;     /* anti-roll bar at the contacts: its roll stiffness / t^2 [N/m] */
    real_t ca0;    /* cornering stiffness of each wheel at f0 [N/rad] */
    real_t ic2;    /* 1 / c2 = 1 / (fzpk f0) [1/N] */
    real_t bk;     /* B (1 + x^2) = 2 c1 / (c2 C mu), 0 when mu = 0 [1/rad] */
    real_t fxd;    /* longitudinal force demanded of each wheel [N] */
    real_t cd, sd; /* cos, sin of the wheels' angle */
    real_t ex, ey; /* the wheels' forward axis in the ground frame (the heading turned by
                      the wheels' angle), unit length */
} axle;

/* what every force evaluation needs: the rotation, the heading, the axles */
typedef struct chassis {
    real_t R[9];    /* body to ground, row-major */
    real_t wg[3];   /* angular velocity in the ground frame, R w [rad/s] */
    real_t hx, hy;  /* heading: the body x axis projected on the ground, unit length */
    axle ax[2];     /* front, rear */
} chassis;

/* a corner's contact point: its offset from the centre of mass and its velocity, both in
   the ground frame, and its height */
typedef struct contact {
    real_t r[3], v[3], z;
} contact;

/* the sum of the corner forces: ground-frame force, ground-frame moment about the centre
   of mass, and the vertical loads */
typedef struct wrench {
    real_t f[3], t[3], fz[NCORNER];
} wrench;

/* axle j (0 front, 1 rear) with wheel angle delta and its share of the drive force.
   c1 = ca0 (1 + x0^2) / (2 x0) with x0 = f0 / c2 = 1 / fzpk makes C_a(f0) = ca0. The
   wheels' cosine from the sine (|delta| <= pi/2, as a road wheel turns): one sine, not
   two reductions */
static void axle_of(const rt_args *a, int j, real_t delta, real_t share, axle *x)
{
    const real_t *p = a->p;
    real_t fzpk = p[P_FZPK], c1, t = p[j ? P_TR : P_TF];
    x->f0 = p[P_M] * p[P_G] * p[j ? P_LF : P_LR] / (2 * (p[P_LF] + p[P_LR]));
    x->k = p[j ? P_KR : P_KF], x->c = p[j ? P_CDR : P_CDF];
    x->kb = p[j ? P_KBR : P_KBF] / (t * t);
    x->ca0 = (real_t)0.5 * p[j ? P_CR : P_CF];
    x->ic2 = 1 / (fzpk * x->f0);
    c1 = x->ca0 * (fzpk * fzpk + 1) / (2 * fzpk);
    x->bk = p[P_MU] > 0 ? 2 * c1 * x->ic2 / (p[P_SHAPE] * p[P_MU]) : 0;
    x->fxd = (real_t)0.5 * share * a->u[U_FX];
    if (delta == 0) {
        x->cd = 1, x->sd = 0;
    } else if (delta <= (real_t)RT_HALF_PI && delta >= (real_t)-RT_HALF_PI) {
        x->sd = rt_sin(delta), x->cd = rt_sqrt(1 - x->sd * x->sd);
    } else {
        x->sd = rt_sin(delta), x->cd = rt_cos(delta);
    }
}

/* the rotation and the heading */
static void pose(const rt_args *a, chassis *c)
{
    mdl_rotation(a->x + MDL_RB_P, c->R);
    real_t n = rt_sqrt(c->R[0] * c->R[0] + c->R[3] * c->R[3]);
    /* a car standing on its nose has no heading: keep the ground x axis (finite) */
    c->hx = n > 0 ? c->R[0] / n : 1, c->hy = n > 0 ? c->R[3] / n : 0;
}

/* the pose, the angular velocity in the ground frame and both axles, once per
   evaluation */
static void frame(const rt_args *a, chassis *c)
{
    pose(a, c);
    mdl_mul3(c->R, a->x + MDL_RB_W, c->wg);
    for (int j = 0; j < 2; j++) {
        axle *x = &c->ax[j];
        axle_of(a, j, j ? 0 : a->u[U_DELTA], j ? 1 - a->p[P_DRIVE] : a->p[P_DRIVE], x);
        x->ex = c->hx * x->cd - c->hy * x->sd, x->ey = c->hy * x->cd + c->hx * x->sd;
    }
}

/* corner i = fl, fr, rl, rr at body offset s (y to the left) */
static void corner_offset(const real_t *p, int i, real_t *s)
{
    int front = i < 2;
    s[0] = front ? p[P_LF] : -p[P_LR];
    s[1] = (i & 1 ? (real_t)-0.5 : (real_t)0.5) * (front ? p[P_TF] : p[P_TR]);
    s[2] = -p[P_H];
}

/* corner i's contact point: r = R s, v = v_cm + (R w) x r, z = z_cm + r_z */
static void contact_of(const rt_args *a, const chassis *c, int i, contact *k)
{
    const real_t *x = a->x;
    real_t s[3], t[3];
    corner_offset(a->p, i, s);
    mdl_mul3(c->R, s, k->r);
    mdl_cross3(c->wg, k->r, t);
    for (int j = 0; j < 3; j++)
        k->v[j] = x[MDL_RB_V + j] + t[j];
    k->z = x[2] + k->r[2];
}

/* vertical load from the corner's height z, vertical speed zd and the height zo of the
   other corner on its axle (the anti-roll bar pushes against the difference); a wheel
   off the ground carries nothing (no adhesion) */
static real_t vertical(const real_t *p, const axle *x, real_t z, real_t zd, real_t zo)
{
    real_t fz = p[P_PRE] * x->f0 - x->k * z - x->c * zd - x->kb * (z - zo);
    return fz > 0 ? fz : 0;
}

/* Magic Formula F = D sin(C atan(B a - E (B a - atan(B a)))), D = mu fz, with
   B C D = C_a(fz) = c1 sin(2 atan(fz / c2)) = c1 2 x / (1 + x^2), x = fz / c2:
   B = 2 c1 / (c2 (1 + x^2) C mu) stays finite as fz goes to zero. The sine and inverse
   tangents are the faithfully rounded ones: every stage calls them twelve times per car,
   and a last-bit difference in a tire force is far below the law's own fidelity */
static real_t magic(const real_t *p, const axle *x, real_t alpha, real_t fz)
{
    real_t d = p[P_MU] * fz;
    if (d <= 0)
        return 0;
    real_t r = fz * x->ic2, ba = x->bk / (1 + r * r) * alpha;
    real_t inner = rt_atan_faithful(ba);
    return d * rt_sin_faithful(p[P_SHAPE] * rt_atan_faithful(ba - p[P_CURV] * (ba - inner)));
}

/* friction circle: the longitudinal demand limited to fmax = mu fz, the pure lateral
   force scaled so that |(fx, fy)| <= fmax (|fy0| <= fmax by the Magic Formula) */
static void combine(real_t fmax, real_t fxd, real_t *fx, real_t *fy)
{
    if (fmax <= 0 || fxd == 0) {
        *fx = 0, *fy = fmax > 0 ? *fy : 0;
        return;
    }
    real_t f = fxd > fmax ? fmax : fxd < -fmax ? -fmax : fxd, q = f / fmax;
    *fx = f;
    *fy *= rt_sqrt(1 - q * q);
}

/* a wheel for its tire law: its axle, its vertical load and the slip tan(a) = -vy / vx
   of its contact point in the wheel frame (vx >= umin), as the Magic Formula of Pacejka
   (ch. 4.3) takes it, which needs no inverse tangent; the law writes the forces */
typedef struct wheel {
    const axle *ax;
    real_t fz, slip; /* vertical load [N], tan of the slip angle */
    real_t fx, fy;   /* wheel-frame forces, along and across the wheel [N] */
} wheel;

/* A tire law: the forces of the four wheels. Each kind names its own law, so a scene of
   linear tires links no Magic Formula; it takes all four wheels in one call, so that
   the corners' state stays in registers across a single indirect call, not four. */
typedef void tire_law(const real_t *p, wheel *w);

/* car3d: cornering stiffness proportional to the load, fx as demanded */
static void tire_linear(const real_t *p, wheel *w)
{
    (void)p;
    for (int i = 0; i < NCORNER; i++) {
        const axle *x = w[i].ax;
        w[i].fx = x->fxd;
        w[i].fy = x->ca0 * w[i].fz / x->f0 * w[i].slip;
    }
}

/* car3d_mf: the Magic Formula, combined with fx by the friction circle */
static void tire_mf(const real_t *p, wheel *w)
{
    for (int i = 0; i < NCORNER; i++) {
        w[i].fy = magic(p, w[i].ax, w[i].slip, w[i].fz);
        combine(p[P_MU] * w[i].fz, w[i].ax->fxd, &w[i].fx, &w[i].fy);
    }
}

/* corner i at contact k, with the height zo of the other wheel on its axle: its wheel's
   vertical load and slip */
static void wheel_of(const rt_args *a, const chassis *c, int i, const contact *k, real_t zo,
                     wheel *wh)
{
    const real_t *p = a->p, *vp = k->v;
    const axle *ax = &c->ax[i < 2 ? 0 : 1];
    /* the contact point's velocity in the wheel frame (along and across the wheel) */
    real_t ex = ax->ex, ey = ax->ey;
    real_t vxw = ex * vp[0] + ey * vp[1], vyw = -ey * vp[0] + ex * vp[1];
    wh->ax = ax;
    wh->fz = vertical(p, ax, k->z, vp[2], zo);
    wh->slip = -vyw / (vxw > p[P_UMIN] ? vxw : p[P_UMIN]);
}

/* wheel i's forces at its contact point k, added to w (the moment about the centre of
   mass, r x F in the ground frame, only if torque is set: outputs need none) */
static void apply(const contact *k, const wheel *wh, int i, int torque, wrench *w)
{
    real_t ex = wh->ax->ex, ey = wh->ax->ey, F[3], tg[3];
    /* wheel frame -> ground */
    F[0] = ex * wh->fx - ey * wh->fy, F[1] = ey * wh->fx + ex * wh->fy, F[2] = wh->fz;
    for (int j = 0; j < 3; j++)
        w->f[j] += F[j];
    if (torque) {
        mdl_cross3(k->r, F, tg);
        for (int j = 0; j < 3; j++)
            w->t[j] += tg[j];
    }
    w->fz[i] = wh->fz;
}

/* the four corners with the kind's tire law: contacts first (each wheel's load needs the
   other wheel's height on its axle, for the anti-roll bar), then the law for all four */
static void corners(const rt_args *a, const chassis *c, tire_law *law, int torque, wrench *w)
{
    contact k[NCORNER];
    wheel wh[NCORNER];
    for (int j = 0; j < 3; j++)
        w->f[j] = w->t[j] = 0;
    for (int i = 0; i < NCORNER; i++)
        contact_of(a, c, i, &k[i]);
    for (int i = 0; i < NCORNER; i++)
        wheel_of(a, c, i, &k[i], k[i ^ 1].z, &wh[i]);
    law(a->p, wh);
    for (int i = 0; i < NCORNER; i++)
        apply(&k[i], &wh[i], i, torque, w);
}

static void kin(const rt_args *a, const real_t *v, real_t *qd) { mdl_rigid_kin(a->x, v, qd); }

static void mass(const rt_args *a, real_t *M)
{
    M[0] = M[1] = M[2] = a->p[P_M];
    M[3] = a->p[P_IXX], M[4] = a->p[P_IYY], M[5] = a->p[P_IZZ];
}

/* k = [sum F_i + Fa heading - m g e_z, R^T sum (R s_i) x F_i - w x J w] (eq. 6b) */
static void force(const rt_args *a, tire_law *law, real_t *k)
{
    const real_t *p = a->p, *w = a->x + MDL_RB_W;
    chassis c;
    wrench t;
    frame(a, &c);
    corners(a, &c, law, 1, &t);
    real_t Jw[3] = {p[P_IXX] * w[0], p[P_IYY] * w[1], p[P_IZZ] * w[2]}, gyro[3], tb[3];
    mdl_cross3(w, Jw, gyro);
    mdl_mul3t(c.R, t.t, tb);
    k[0] = t.f[0] + a->u[U_FA] * c.hx;
    k[1] = t.f[1] + a->u[U_FA] * c.hy;
    k[2] = t.f[2] - p[P_M] * p[P_G];
    for (int i = 0; i < 3; i++)
        k[3 + i] = tb[i] - gyro[i];
}

/* hitch i at d ahead of the centre of mass (d < 0: behind), at its height: a node on the
   body x axis */
static void node(const rt_args *a, uint16_t i, rt_mbs_node *n, real_t *J)
{
    real_t R[9];
    mdl_rotation(a->x + MDL_RB_P, R);
    mdl_rigid_node_x(a->x, R, i == 0 ? a->p[P_DF] : -a->p[P_DR], n, J);
}

/* T = m |v|^2 / 2 + w^T J w / 2; V = m g z + sum (k z_i^2 / 2 - pre F0_i z_i)
   + sum over the axles kb (z_left - z_right)^2 / 2, the potential of gravity, of the
   corner springs and of the anti-roll bars while every wheel touches the ground */
static void energy(const rt_args *a, real_t *e)
{
    const real_t *x = a->x, *p = a->p, *v = x + MDL_RB_V, *w = x + MDL_RB_W;
    real_t R[9], s[3], t[3], z[NCORNER];
    axle ax[2];
    axle_of(a, 0, 0, 0, &ax[0]);
    axle_of(a, 1, 0, 0, &ax[1]);
    e[0] = (real_t)0.5 * (p[P_M] * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) +
                          p[P_IXX] * w[0] * w[0] + p[P_IYY] * w[1] * w[1] +
                          p[P_IZZ] * w[2] * w[2]);
    e[1] = p[P_M] * p[P_G] * x[2];
    mdl_rotation(x + MDL_RB_P, R);
    for (int i = 0; i < NCORNER; i++) {
        corner_offset(p, i, s);
        mdl_mul3(R, s, t);
        z[i] = x[2] + t[2];
        const axle *xi = &ax[i < 2 ? 0 : 1];
        e[1] += (real_t)0.5 * xi->k * z[i] * z[i] - p[P_PRE] * xi->f0 * z[i];
    }
    for (size_t j = 0; j < 2; j++) {
        real_t dz = z[2 * j] - z[2 * j + 1];
        e[1] += (real_t)0.5 * ax[j].kb * dz * dz;
    }
}

/* the position, yaw (z-y-x angle of R), the yaw rate psi' = (wy sin(roll) + wz cos(roll))
   / cos(pitch) and the speeds in the heading frame: what a right-hand side reads (the
   driver, the drag, the tow bar). Faithfully rounded yaw: every stage computes it */
static void motion(const rt_args *a, const chassis *c, real_t *y)
{
    const real_t *x = a->x, *w = x + MDL_RB_W, *R = c->R;
    real_t cc = R[7] * R[7] + R[8] * R[8];
    y[Y_X] = x[0], y[Y_Y] = x[1], y[Y_Z] = x[2];
    y[Y_PSI] = rt_atan2_faithful(R[3], R[0]);
    y[Y_U] = c->hx * x[MDL_RB_V] + c->hy * x[MDL_RB_V + 1];
    y[Y_V] = -c->hy * x[MDL_RB_V] + c->hx * x[MDL_RB_V + 1];
    y[Y_R] = cc > 0 ? (w[1] * R[7] + w[2] * R[8]) / cc : 0;
}

/* the motion, roll and pitch (z-y-x angles of R), a_y and the corner loads from the tire
   forces */
static void output(const rt_args *a, tire_law *law, real_t *y)
{
    chassis c;
    wrench t;
    frame(a, &c);
    corners(a, &c, law, 0, &t);
    const real_t *R = c.R;
    real_t sp = -R[6] > 1 ? 1 : -R[6] < -1 ? -1 : -R[6];
    motion(a, &c, y);
    y[Y_ROLL] = rt_atan2_faithful(R[7], R[8]);
    y[Y_PITCH] = rt_asin_faithful(sp);
    y[Y_AY] = (-c.hy * t.f[0] + c.hx * t.f[1]) / a->p[P_M];
    for (int i = 0; i < NCORNER; i++)
        y[Y_FZ + i] = t.fz[i];
}

/* a right-hand side's outputs: the motion alone, without the tires (rt_kind.output_lean;
   the others are recorded at the ticks) */
static void output_lean(const rt_args *a, real_t *y)
{
    chassis c;
    pose(a, &c);
    motion(a, &c, y);
}
static const uint8_t lean_skip[NY] = {[Y_AY] = 1, [Y_ROLL] = 1, [Y_PITCH] = 1, [Y_FZ] = 1,
                                      [Y_FZ + 1] = 1, [Y_FZ + 2] = 1, [Y_FZ + 3] = 1};

/* the hooks of each kind with its tire law */
static void force_linear(const rt_args *a, real_t *k) { force(a, tire_linear, k); }
static void force_mf(const rt_args *a, real_t *k) { force(a, tire_mf, k); }
static void output_linear(const rt_args *a, real_t *y) { output(a, tire_linear, y); }
static void output_mf(const rt_args *a, real_t *y) { output(a, tire_mf, y); }

/* every parameter finite; masses, inertias, lengths, stiffnesses, fzpk, umin and g
   positive; dampers, anti-roll bars, pre, hitch offsets and mu not negative; drive in
   [0, 1]; C in (0, 2) (a peak) and E <= 1 */
static rt_status check(const real_t *p, const void *spec)
{
    (void)spec;
    static const uint8_t positive[] = {P_M, P_IXX, P_IYY, P_IZZ, P_LF, P_LR, P_TF, P_TR, P_H,
                                       P_CF, P_CR, P_FZPK, P_SHAPE, P_KF, P_KR, P_UMIN, P_G};
    static const uint8_t nonneg[] = {P_MU, P_CDF, P_CDR, P_PRE, P_DF, P_DR, P_KBF, P_KBR};
    int ok = rt_all_finite(p, P_COUNT);
    for (unsigned i = 0; i < sizeof positive; i++)
        ok = ok && p[positive[i]] > 0;
    for (unsigned i = 0; i < sizeof nonneg; i++)
        ok = ok && p[nonneg[i]] >= 0;
    return ok && p[P_DRIVE] <= 1 && p[P_SHAPE] < 2 && p[P_CURV] <= 1 ? RT_OK : RT_E_PARAM;
}

static const rt_mbs_spec spec = {
    .nq = MDL_RB_NQ, .nz = MDL_RB_NZ, .nn = 2, .flags = RT_MBS_M_DIAG,
    .node_names = node_names, .kin = kin, .mass = mass, .force = force_linear, .node = node,
    .energy = energy, .normalize = mdl_rigid_normalize,
};
static const rt_mbs_spec spec_mf = {
    .nq = MDL_RB_NQ, .nz = MDL_RB_NZ, .nn = 2, .flags = RT_MBS_M_DIAG,
    .node_names = node_names, .kin = kin, .mass = mass, .force = force_mf, .node = node,
    .energy = energy, .normalize = mdl_rigid_normalize,
};

#define CAR3D_UNITS                                                                        \
    "rad N N m m rad m/s m/s rad/s m/s^2 m rad rad N N N N m m m - - - - m/s m/s m/s "     \
    "rad/s rad/s rad/s kg kg*m^2 kg*m^2 kg*m^2 m m m m m N/rad N/rad - - - - N/m N/m "     \
    "N*s/m N*s/m - - m m m/s m/s^2 N*m/rad N*m/rad"

const rt_kind mdl_car3d_kind = {
    .name = "car3d", .type = RT_KIND_MBS, .nu = NU, .ny = NY, .nx = NX, .np = P_COUNT,
    .u_names = u_names, .y_names = y_names, .x_names = x_names, .p_names = p_names,
    .p_default = p_default, .x_default = x_default, .feed = RT_FEED_TABLE,
    .autonomous = 1, .feed_table = feed,
    .check = check, .output = output_linear, .output_lean = output_lean,
    .lean_skip = lean_skip, .spec = &spec,
    .doc = RT_DOC(
        "Spatial car (eq. (6)): chassis a rigid body, q = [r, p] (unit quaternion), z =\n"
        "[v ground, w body], M = diag(m, m, m, Ixx, Iyy, Izz); corners (lf|-lr, +-t/2, -h)\n"
        "on vertical spring-dampers: Fz = max(0, pre F0 - k z_i - c z_i' - kb/t^2 (z_i -\n"
        "z_o)), F0 the static loads, kb the axle's anti-roll bar (roll stiffness), z_o the\n"
        "other wheel's height. Linear tires F_y = (C/2)(Fz/F0) tan a, tan a = -V_y/V_x in\n"
        "the wheel frame (V_x >= umin), at each corner; Fx split on the axles (drive:\n"
        "front share), Fa along the heading at the centre of mass.\n"
        "Nodes front, rear: df ahead, dr behind the centre of mass. Outputs as st_car\n"
        "plus z, roll, pitch, the corner loads. Defaults: CommonRoad vehicle 1."),
    .units = RT_DOC(CAR3D_UNITS),
};

const rt_kind mdl_car3d_mf_kind = {
    .name = "car3d_mf", .type = RT_KIND_MBS, .nu = NU, .ny = NY, .nx = NX, .np = P_COUNT,
    .u_names = u_names, .y_names = y_names, .x_names = x_names, .p_names = p_names,
    .p_default = p_default, .x_default = x_default, .feed = RT_FEED_TABLE,
    .autonomous = 1, .feed_table = feed,
    .check = check, .output = output_mf, .output_lean = output_lean,
    .lean_skip = lean_skip, .spec = &spec_mf,
    .doc = RT_DOC(
        "Spatial car with Magic-Formula tires (the ports, states and nodes of car3d):\n"
        "F_y0 = D sin(C atan(B a - E (B a - atan(B a)))), a = tan(slip) = -V_y/V_x,\n"
        "D = mu Fz, B C D = c1 sin(2 atan(Fz/c2)), c2 = fzpk F0, equal to C/2 at F0;\n"
        "combined slip by the friction circle: F_x = Fx share/2 limited to mu Fz,\n"
        "F_y = F_y0 sqrt(1 - (F_x/(mu Fz))^2). mu = 0: no tire forces."),
    .units = RT_DOC(CAR3D_UNITS),
};
