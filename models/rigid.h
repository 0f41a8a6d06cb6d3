/* rigid.h - kinematics of a spatial rigid body with a unit quaternion, shared by the
 * multibody kinds that have one (mbs_body.c, vehicle_3d.c): rotation, quaternion
 * kinematics, interaction nodes at body offsets. The state layout is that of mbs_body:
 * x = [r (3), p (4, scalar first), v (3, inertial), w (3, body frame)]. Static inline
 * functions, not a unit of their own: a scene's image links only the model units that
 * define its kinds (tests/scenec/effects.sh). */
#ifndef MDL_RIGID_H
#define MDL_RIGID_H

#include "rt.h"

/* offsets into the state of a rigid body */
enum { MDL_RB_R = 0, MDL_RB_P = 3, MDL_RB_V = 7, MDL_RB_W = 10, MDL_RB_NQ = 7, MDL_RB_NZ = 6 };

/* c = a x b */
static inline void mdl_cross3(const real_t *a, const real_t *b, real_t *c)
{
    /* cppcheck's whole-program pass sizes real_t[3] as float and calls offset 16 (b[2] as
       double) out of bounds: a false positive (every caller passes three real_t) */
    // cppcheck-suppress ctuArrayIndex
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
}

/* y = A x for a row-major 3 x 3 A; written out, not as a loop: gcc -O2 keeps a loop of
   three here, and these products are the bulk of a car's kinematics (#13) */
static inline void mdl_mul3(const real_t *A, const real_t *x, real_t *y)
{
    real_t x0 = x[0], x1 = x[1], x2 = x[2];
    y[0] = A[0] * x0 + A[1] * x1 + A[2] * x2;
    y[1] = A[3] * x0 + A[4] * x1 + A[5] * x2;
    y[2] = A[6] * x0 + A[7] * x1 + A[8] * x2;
}

/* y = A^T x for a row-major 3 x 3 A */
static inline void mdl_mul3t(const real_t *A, const real_t *x, real_t *y)
{
    real_t x0 = x[0], x1 = x[1], x2 = x[2];
    y[0] = A[0] * x0 + A[3] * x1 + A[6] * x2;
    y[1] = A[1] * x0 + A[4] * x1 + A[7] * x2;
    y[2] = A[2] * x0 + A[5] * x1 + A[8] * x2;
}

/* R(q / |q|), row-major; a zero quaternion reads as the identity (finite,
   deterministic) */
static inline void mdl_rotation(const real_t *q, real_t *R)
{
    real_t n = rt_sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    real_t a = 1, b = 0, c = 0, d = 0;
    if (n > 0)
        a = q[0] / n, b = q[1] / n, c = q[2] / n, d = q[3] / n;
    R[0] = 1 - 2 * (c * c + d * d), R[1] = 2 * (b * c - a * d), R[2] = 2 * (b * d + a * c);
    R[3] = 2 * (b * c + a * d), R[4] = 1 - 2 * (b * b + d * d), R[5] = 2 * (c * d - a * b);
    R[6] = 2 * (b * d - a * c), R[7] = 2 * (c * d + a * b), R[8] = 1 - 2 * (b * b + c * c);
}

/* r' = v, p' = 1/2 p (x) (0, w): K(q) of eq. 6a applied to v = [v; w] (q = x); K keeps
   |p| constant up to the integrator's error, the projection renormalizes it */
static inline void mdl_rigid_kin(const real_t *x, const real_t *v, real_t *qd)
{
    const real_t *p = x + MDL_RB_P, *w = v + 3;
    qd[0] = v[0], qd[1] = v[1], qd[2] = v[2];
    qd[3] = (real_t)-0.5 * (p[1] * w[0] + p[2] * w[1] + p[3] * w[2]);
    qd[4] = (real_t)0.5 * (p[0] * w[0] + p[2] * w[2] - p[3] * w[1]);
    qd[5] = (real_t)0.5 * (p[0] * w[1] + p[3] * w[0] - p[1] * w[2]);
    qd[6] = (real_t)0.5 * (p[0] * w[2] + p[1] * w[1] - p[2] * w[0]);
}

/* the 6 x 6 Jacobians of a node at body offset s, Jr = [I, -R [s]x], Jw = [0, R], row-major
   into J. Column c of [s]x is s x e_c, so column c of -R [s]x is -R (s x e_c): computed
   as that product, zero terms included, so that the results keep their bits (and the
   signs of their zeros) of the loop this replaces */
static inline void mdl_rigid_jacobian(const real_t *R, const real_t *s, real_t *J)
{
    static const real_t e[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    for (int r = 0; r < 3; r++) {
        real_t *jr = J + 6 * r, *jw = J + 6 * (3 + r);
        jr[0] = jr[1] = jr[2] = 0, jw[0] = jw[1] = jw[2] = 0;
        jr[r] = 1;
        jw[3] = R[3 * r], jw[4] = R[3 * r + 1], jw[5] = R[3 * r + 2];
    }
    for (int c = 0; c < 3; c++) {
        real_t se[3], col[3];
        mdl_cross3(s, e[c], se);
        mdl_mul3(R, se, col);
        J[3 + c] = -col[0], J[9 + c] = -col[1], J[15 + c] = -col[2];
    }
}

/* what both node functions below give alike: w_I = R w, ar = R (w x (w x s)) from
   wws = w x (w x s), and the frame S = R */
static inline void rigid_node_frame(const real_t *R, const real_t *w, const real_t *wws,
                                    rt_mbs_node *n)
{
    mdl_mul3(R, w, n->w);
    mdl_mul3(R, wws, n->ar);
    for (int k = 0; k < 9; k++)
        n->S[k] = R[k];
}

/* the node at body offset s of the body in state x with rotation R: r = r0 + R s,
   v = v0 + R (w x s), w_I = R w, ar = R (w x (w x s)), aw = 0, frame S = R; if J is not
   NULL the 6 x 6 Jacobians Jr = [I, -R [s]x], Jw = [0, R] */
static inline void mdl_rigid_node(const real_t *x, const real_t *R, const real_t *s, rt_mbs_node *n,
                    real_t *J)
{
    const real_t *w = x + MDL_RB_W;
    real_t t[3], ws[3], wws[3];
    mdl_cross3(w, s, ws);
    mdl_cross3(w, ws, wws);
    mdl_mul3(R, s, t);
    for (int k = 0; k < 3; k++)
        n->r[k] = x[k] + t[k];
    mdl_mul3(R, ws, t);
    for (int k = 0; k < 3; k++)
        n->v[k] = x[MDL_RB_V + k] + t[k], n->aw[k] = 0;
    rigid_node_frame(R, w, wws, n);
    if (!J)
        return;
    mdl_rigid_jacobian(R, s, J);
}

/* mdl_rigid_node for a node on the body x axis, s = (d, 0, 0) (a car's hitches): the
   products with the zero components left out, the others in the same order, so the
   values are mdl_rigid_node's (up to the sign of a zero). With w x s = (0, w_z d,
   -w_y d), w x (w x s) = (-(w_y^2 + w_z^2) d, w_x w_y d, w_x w_z d) and -R [s]x =
   [0, -d R e_z, d R e_y] */
static inline void mdl_rigid_node_x(const real_t *x, const real_t *R, real_t d, rt_mbs_node *n,
                                    real_t *J)
{
    const real_t *w = x + MDL_RB_W;
    real_t ws1 = w[2] * d, ws2 = -(w[1] * d);
    real_t wws[3] = {w[1] * ws2 - w[2] * ws1, -(w[0] * ws2), w[0] * ws1};
    for (int k = 0; k < 3; k++) {
        const real_t *Rk = R + 3 * k;
        n->r[k] = x[k] + Rk[0] * d;
        n->v[k] = x[MDL_RB_V + k] + (Rk[1] * ws1 + Rk[2] * ws2);
        n->aw[k] = 0;
    }
    rigid_node_frame(R, w, wws, n);
    if (!J)
        return;
    for (int r = 0; r < 3; r++) {
        real_t *jr = J + 6 * r, *jw = J + 6 * (3 + r);
        const real_t *Rr = R + 3 * r;
        jr[0] = jr[1] = jr[2] = 0, jw[0] = jw[1] = jw[2] = 0;
        jr[r] = 1;
        jr[3] = 0, jr[4] = -(Rr[2] * d), jr[5] = Rr[1] * d;
        jw[3] = Rr[0], jw[4] = Rr[1], jw[5] = Rr[2];
    }
}

/* p <- p / |p| in q = [r, p] (after the position projection); returns |p| before */
static inline real_t mdl_rigid_normalize(real_t *q)
{
    real_t n = rt_sqrt(q[3] * q[3] + q[4] * q[4] + q[5] * q[5] + q[6] * q[6]);
    if (n > 0)
        for (int i = 3; i < 7; i++)
            q[i] /= n;
    return n;
}

#endif /* MDL_RIGID_H */
