/* test_vehicle_3d.c - the spatial car (models/vehicle_3d.c) and the steering chain's
 * actuators (models/steer_chain.c) through their hooks, against independent answers:
 * the hitch nodes' velocities against Jacobian times velocity and against a finite
 * difference of their positions; the applied forces against the energy hook (with tires
 * off and no dampers the generalized forces' power is minus the rate of the potential
 * energy, taken by a central difference along the motion; once with the anti-roll bars
 * alone); the bars' energy of a rolled car against K_b sin^2(phi) / 2; the static loads of the
 * preloaded car against m g l_r / (2 L) and m g l_f / (2 L); the motor and the hydraulic
 * servo at rest at the steady states computed by hand. Whole-scene checks of the cars are
 * in tests/vehicles/vehicles.py. */
#include "models.h"
#include "rigid.h"
#include "testutil.h"

static double absd(double v) { return v < 0 ? -v : v; }
static double fmax_d(double a, double b) { return a > b ? a : b; }

/* parameter indices of car3d (its p_names) and state offsets */
enum {
    P_M = 0, P_LF = 4, P_LR = 5, P_TF = 6, P_TR = 7, P_H = 8, P_MU = 12, P_KF = 15, P_KR = 16,
    P_CF_D = 17, P_CR_D = 18, P_PRE = 19, P_G = 24, P_KBF = 25, P_KBR = 26, NP = 27
};
enum { NX = 13, NZ = 6 };

/* a car turning, rolled, pitched and bouncing: x y z p0..p3 vx vy vz wx wy wz */
static const real_t moving[NX] = {3, -1, (real_t)0.54, (real_t)0.99, (real_t)0.06, (real_t)-0.04,
                                  (real_t)0.1, 19, 2, (real_t)0.3, (real_t)0.4, (real_t)-0.2,
                                  (real_t)0.5};

/* the same motion rolled and pitched half as much, so that with the anti-roll bars every
   wheel keeps touching the ground (the energy hook's premise) */
static const real_t moving_low[NX] = {3, -1, (real_t)0.54, (real_t)0.99, (real_t)0.03,
                                      (real_t)-0.02, (real_t)0.05, 19, 2, (real_t)0.3,
                                      (real_t)0.4, (real_t)-0.2, (real_t)0.5};

static void car_args(const rt_kind *k, const real_t *x, const real_t *u, const real_t *p,
                     rt_args *a)
{
    a->t = 0, a->h = 0, a->x = x, a->d = 0, a->u = u, a->p = p, a->spec = k->spec;
}

/* the state advanced along its own motion by dt: q + dt K(q) z, velocities unchanged
   (normalized quaternion: both positions are on the manifold) */
static void advance(const rt_mbs_spec *sp, const rt_args *a, real_t dt, real_t *x)
{
    real_t qd[7];
    sp->kin(a, a->x + 7, qd);
    for (int i = 0; i < NX; i++)
        x[i] = a->x[i] + (i < 7 ? dt * qd[i] : 0);
    sp->normalize(x);
}

/* hitch nodes: v = J z exactly; (r(t + dt) - r(t - dt)) / (2 dt) = v to O(dt^2) */
static void test_nodes(void)
{
    const rt_kind *k = &mdl_car3d_mf_kind;
    const rt_mbs_spec *sp = k->spec;
    static const real_t u[3] = {(real_t)0.05, 300, -150};
    real_t x[NX], xp[NX], xm[NX], J[6 * NZ];
    rt_args a, ap, am;
    for (int i = 0; i < NX; i++)
        x[i] = moving[i];
    sp->normalize(x);
    car_args(k, x, u, k->p_default, &a);
    const real_t dt = (real_t)(RT_REAL_IS_FLOAT ? 1e-3 : 1e-5);
    advance(sp, &a, dt, xp);
    advance(sp, &a, -dt, xm);
    car_args(k, xp, u, k->p_default, &ap);
    car_args(k, xm, u, k->p_default, &am);
    double worst_j = 0, worst_fd = 0;
    for (uint16_t n = 0; n < 2; n++) {
        rt_mbs_node nd, np_, nm;
        sp->node(&a, n, &nd, J);
        sp->node(&ap, n, &np_, 0);
        sp->node(&am, n, &nm, 0);
        for (int r = 0; r < 3; r++) {
            double jv = 0, jw = 0;
            for (int c = 0; c < NZ; c++)
                jv += (double)J[r * NZ + c] * (double)x[7 + c],
                    jw += (double)J[(3 + r) * NZ + c] * (double)x[7 + c];
            worst_j = fmax_d(worst_j, absd(jv - (double)nd.v[r]));
            worst_j = fmax_d(worst_j, absd(jw - (double)nd.w[r]));
            double fd = ((double)np_.r[r] - (double)nm.r[r]) / (2 * (double)dt);
            worst_fd = fmax_d(worst_fd, absd(fd - (double)nd.v[r]));
        }
    }
    th_note("hitch |J z - v|", worst_j);
    th_note("hitch |dr/dt - v| (central difference)", worst_fd);
    TH_CHECK(worst_j < (RT_REAL_IS_FLOAT ? 1e-4 : 1e-12));
    TH_CHECK(worst_fd < (RT_REAL_IS_FLOAT ? 1e-2 : 1e-8));
}

/* mdl_rigid_node_x (the hitches) gives the values of the general mdl_rigid_node at
   s = (d, 0, 0), to the bit (only a zero's sign may differ), in both states and both
   directions; the general node is the one test_mbs_body checks against mbs_body */
static void test_node_x(void)
{
    static const real_t d[2] = {2, (real_t)-1.75};
    const real_t *states[2] = {moving, moving_low};
    int differ = 0;
    for (int k = 0; k < 2; k++)
        for (int j = 0; j < 2; j++) {
            real_t x[NX], R[9], J1[36], J2[36], s[3] = {d[j], 0, 0};
            rt_mbs_node n1, n2;
            for (int i = 0; i < NX; i++)
                x[i] = states[k][i];
            mdl_rotation(x + MDL_RB_P, R);
            mdl_rigid_node(x, R, s, &n1, J1);
            mdl_rigid_node_x(x, R, d[j], &n2, J2);
            for (int i = 0; i < 3; i++)
                differ += n1.r[i] != n2.r[i] || n1.v[i] != n2.v[i] || n1.w[i] != n2.w[i] ||
                          n1.ar[i] != n2.ar[i] || n1.aw[i] != n2.aw[i];
            for (int i = 0; i < 9; i++)
                differ += n1.S[i] != n2.S[i];
            for (int i = 0; i < 36; i++)
                differ += J1[i] != J2[i];
        }
    TH_CHECK(differ == 0);
}

/* tires off (mu = 0), no dampers, no inputs: the generalized forces' power
   k . z = m g-free force . v + torque . w (the gyroscopic term does no work) equals
   -dV/dt along the motion, V the kind's potential energy, while every wheel touches the
   ground (checked). bars_only: corner springs off (the preload stays, so that the bars
   lift no wheel), so that only gravity, the preload and the anti-roll bars act (the bars'
   force and energy must agree on their own) */
static void energy_power(int bars_only)
{
    const rt_kind *k = &mdl_car3d_mf_kind;
    const rt_mbs_spec *sp = k->spec;
    static const real_t u[3] = {0, 0, 0};
    real_t p[NP], x[NX], xp[NX], xm[NX], f[NZ], M[NZ], e[2], ep[2], em[2];
    rt_args a, ap, am;
    for (int i = 0; i < NP; i++)
        p[i] = k->p_default[i];
    p[P_MU] = 0, p[P_CF_D] = 0, p[P_CR_D] = 0;
    if (bars_only)
        p[P_KF] = 0, p[P_KR] = 0;
    for (int i = 0; i < NX; i++)
        x[i] = moving_low[i];
    sp->normalize(x);
    car_args(k, x, u, p, &a);
    real_t y[14];
    k->output(&a, y);
    for (int i = 10; i < 14; i++)
        TH_CHECK(y[i] > 0);
    sp->force(&a, f);
    sp->mass(&a, M);
    sp->energy(&a, e);
    double power = 0, kin = 0;
    for (int i = 0; i < NZ; i++)
        power += (double)f[i] * (double)x[7 + i],
            kin += 0.5 * (double)M[i] * (double)x[7 + i] * (double)x[7 + i];
    /* float: a longer difference, so that the rounding of V (some 1e-3 J) stays small */
    const real_t dt = (real_t)(RT_REAL_IS_FLOAT ? 1e-2 : 1e-6);
    advance(sp, &a, dt, xp);
    advance(sp, &a, -dt, xm);
    car_args(k, xp, u, p, &ap);
    car_args(k, xm, u, p, &am);
    sp->energy(&ap, ep);
    sp->energy(&am, em);
    double dvdt = ((double)ep[1] - (double)em[1]) / (2 * (double)dt);
    th_note(bars_only ? "generalized force power, bars only [W]" : "generalized force power [W]",
            power);
    th_note("-dV/dt by central difference [W]", -dvdt);
    TH_NEAR(power, -dvdt, (RT_REAL_IS_FLOAT ? 1e-2 : 1e-8) * absd(power));
    TH_NEAR(e[0], kin, (RT_REAL_IS_FLOAT ? 1e-6 : 1e-12) * kin);
}

static void test_energy_power(void) { energy_power(0); }
static void test_energy_power_bars(void) { energy_power(1); }

/* the anti-roll bars' potential by hand: springs and preload off, the car rolled by phi
   about its x axis through the centre of mass at height h: the wheels of an axle of
   track t stand at -+ (t/2) sin(phi) relative to each other's mean, so a bar of roll
   stiffness K_b (K_b / t^2 on the height difference t sin(phi)) stores K_b sin^2(phi) / 2;
   V - m g z = (K_bf + K_br) sin^2(phi) / 2 */
static void test_bar_energy(void)
{
    const rt_kind *k = &mdl_car3d_mf_kind;
    const rt_mbs_spec *sp = k->spec;
    static const real_t u[3] = {0, 0, 0};
    real_t p[NP], x[NX], e[2];
    const double phi = 0.05;
    rt_args a;
    for (int i = 0; i < NP; i++)
        p[i] = k->p_default[i];
    p[P_KF] = 0, p[P_KR] = 0, p[P_PRE] = 0;
    for (int i = 0; i < NX; i++)
        x[i] = 0;
    x[2] = p[P_H];
    /* quaternion of a rotation phi about x: (cos(phi/2), sin(phi/2), 0, 0) */
    x[3] = rt_cos((real_t)(phi / 2)), x[4] = rt_sin((real_t)(phi / 2));
    car_args(k, x, u, p, &a);
    sp->energy(&a, e);
    double sp2 = (double)rt_sin((real_t)phi);
    double want = 0.5 * ((double)p[P_KBF] + (double)p[P_KBR]) * sp2 * sp2;
    double got = (double)e[1] - (double)p[P_M] * (double)p[P_G] * (double)x[2];
    th_note("bars' energy at 0.05 rad [J]", got);
    TH_NEAR(got, want, (RT_REAL_IS_FLOAT ? 1e-3 : 1e-10) * want);
}

/* preloaded car at its design height at rest: loads m g l_r / (2 L), m g l_f / (2 L),
   zero force and torque, so it stays */
static void test_static_loads(void)
{
    const rt_kind *k = &mdl_car3d_mf_kind;
    const rt_mbs_spec *sp = k->spec;
    static const real_t u[3] = {0, 0, 0};
    real_t x[NX], y[14], f[NZ];
    const real_t *p = k->p_default;
    rt_args a;
    for (int i = 0; i < NX; i++)
        x[i] = k->x_default[i];
    x[7] = 0;
    car_args(k, x, u, p, &a);
    k->output(&a, y);
    sp->force(&a, f);
    double L = (double)p[P_LF] + (double)p[P_LR], mg = (double)p[P_M] * (double)p[P_G];
    double ff = mg * (double)p[P_LR] / (2 * L), fr = mg * (double)p[P_LF] / (2 * L);
    double tol = RT_REAL_IS_FLOAT ? 1e-3 : 1e-9;
    TH_NEAR(y[10], ff, tol * ff);
    TH_NEAR(y[11], ff, tol * ff);
    TH_NEAR(y[12], fr, tol * fr);
    TH_NEAR(y[13], fr, tol * fr);
    for (int i = 0; i < NZ; i++)
        TH_NEAR(f[i], 0, tol * mg);
}

/* dc_motor at rest with iref = 0.5 A: i = iref, w = 0, phi = k i / ks, e = R i / Ki;
   hyd_servo at rest with xv = 0.2 mm: xs = xv, p = Kq xs / Kc, y = A p / kL, v = 0 */
static void test_chain_steady(void)
{
    const rt_kind *mk = &mdl_dc_motor_kind, *hk = &mdl_hyd_servo_kind;
    const real_t *mp = mk->p_default, *hp = hk->p_default;
    real_t iref = (real_t)0.5, mx[4], md[4], my[4], xv = (real_t)0.2, hx[4], hd[4], hy[3];
    mx[0] = iref, mx[1] = 0, mx[2] = mp[2] * iref / mp[5], mx[3] = mp[1] * iref / mp[7];
    rt_args a = {.x = mx, .u = &iref, .p = mp, .spec = mk->spec};
    mk->deriv(&a, md);
    mk->output(&a, my);
    for (int i = 0; i < 4; i++)
        TH_NEAR(md[i], 0, RT_REAL_IS_FLOAT ? 1e-2 : 1e-9);
    TH_NEAR(my[0], mp[8] * mx[2], 1e-12);
    double p_pa = (double)hp[1] * 1e-3 * (double)xv / (double)hp[2];
    hx[0] = xv, hx[1] = (real_t)(p_pa * 1e-6), hx[3] = 0;
    hx[2] = (real_t)((double)hp[5] * p_pa / (double)hp[8] * 1e3);
    rt_args b = {.x = hx, .u = &xv, .p = hp, .spec = hk->spec};
    hk->deriv(&b, hd);
    hk->output(&b, hy);
    th_note("hyd_servo steady pressure [MPa]", (double)hx[1]);
    for (int i = 0; i < 4; i++)
        TH_NEAR(hd[i], 0, RT_REAL_IS_FLOAT ? 1e-1 : 1e-6);
    TH_NEAR(hy[0], (double)hx[2] / (double)hp[9], 1e-6);
}

/* the lean output equation (a right-hand side's): the motion outputs as the full one
   gives them, bit for bit, and the tire-dependent ones (a_y, roll, pitch, loads)
   untouched; both kinds, a moving car */
static void test_lean_output(void)
{
    const rt_kind *kinds[2] = {&mdl_car3d_kind, &mdl_car3d_mf_kind};
    static const real_t u[3] = {(real_t)0.05, 300, -150};
    for (int n = 0; n < 2; n++) {
        const rt_kind *k = kinds[n];
        real_t full[14], lean[14];
        rt_args a;
        car_args(k, moving, u, k->p_default, &a);
        k->output(&a, full);
        for (int i = 0; i < 14; i++)
            lean[i] = -12345;
        if (!TH_CHECK(k->output_lean && k->lean_skip && k->ny == 14))
            return;
        k->output_lean(&a, lean);
        int ok = 1, skipped = 0;
        for (int i = 0; i < 14; i++) {
            ok &= k->lean_skip[i] ? lean[i] == -12345 : lean[i] == full[i];
            skipped += k->lean_skip[i];
        }
        TH_CHECK(ok && skipped == 7); /* ay, roll, pitch, four loads */
        TH_CHECK(!k->lean_skip[0] && !k->lean_skip[1] && !k->lean_skip[2] && !k->lean_skip[3]);
    }
}

const th_test th_vehicle_3d_tests[] = {
    {"vehicle_3d_nodes", test_nodes},
    {"vehicle_3d_node_x", test_node_x},
    {"vehicle_3d_energy_power", test_energy_power},
    {"vehicle_3d_energy_power_bars", test_energy_power_bars},
    {"vehicle_3d_bar_energy", test_bar_energy},
    {"vehicle_3d_static_loads", test_static_loads},
    {"steer_chain_steady", test_chain_steady},
    {"vehicle_3d_lean_output", test_lean_output},
    {0, 0},
};
