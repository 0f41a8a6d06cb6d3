/* rti_joints.h - the point equations of the joint kinds whose rows a scene's written-out
 * code (rt_scene_code, tools/scenec/spec.c) calls inline: rt/joints.c's kinds call the same
 * functions, so both paths compute the same operations (the same bits). Internal to rt/
 * and to generated scenes. */
#ifndef RTI_JOINTS_H
#define RTI_JOINTS_H

#include "rt.h"

/* spherical difference joint |r1 - r2| - l = 0 (eq. 8); p = {l}: with d = r1 - r2,
   e = d / |d|: g' = e . (v1 - v2), c = (|d'|^2 - (e . d')^2) / |d|; the translational
   entries only (rt_joint_kind.eval_points) */
static inline void rti_sphdiff_points(const real_t *p, const real_t *r1, const real_t *v1,
                                      const real_t *r2, const real_t *v2, rt_joint_eval *e)
{
    /* written out by hand: gcc -O2 keeps three-step loops as loops */
    real_t d0 = r1[0] - r2[0], d1 = r1[1] - r2[1], d2 = r1[2] - r2[2];
    real_t len = rt_sqrt(d0 * d0 + d1 * d1 + d2 * d2);
    real_t u0 = 1, u1 = 0, u2 = 0;
    e->g[0] = len - p[0];
    e->c[0] = 0;
    /* coincident nodes have no direction: +x, no curvature term (finite, deterministic) */
    if (len > RT_MBS_LEN_MIN) {
        real_t dd0 = v1[0] - v2[0], dd1 = v1[1] - v2[1], dd2 = v1[2] - v2[2];
        u0 = d0 / len, u1 = d1 / len, u2 = d2 / len;
        real_t ud = u0 * dd0 + u1 * dd1 + u2 * dd2;
        e->c[0] = ((dd0 * dd0 + dd1 * dd1 + dd2 * dd2) - ud * ud) / len;
    }
    e->C[0][0] = u0, e->C[0][1] = u1, e->C[0][2] = u2;
    e->C[0][6] = -u0, e->C[0][7] = -u1, e->C[0][8] = -u2;
}

/* g alone: the first lines of rti_sphdiff_points (rt_joint_kind.g_points) */
static inline void rti_sphdiff_g(const real_t *p, const real_t *r1, const real_t *r2, real_t *g)
{
    real_t d0 = r1[0] - r2[0], d1 = r1[1] - r2[1], d2 = r1[2] - r2[2];
    g[0] = rt_sqrt(d0 * d0 + d1 * d1 + d2 * d2) - p[0];
}

#endif /* RTI_JOINTS_H */
