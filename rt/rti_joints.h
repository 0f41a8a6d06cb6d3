/* rti_joints.h - the point equations of the joint kinds whose rows a scene's written-out
 * code (rt_scene_code, tools/scenec/spec.c) calls inline: rt/joints.c's kinds call the same
 * functions, so both paths compute the same operations (the same bits). Internal to rt/
 * and to generated scenes. */
#ifndef RTI_JOINTS_H
#define RTI_JOINTS_H

#include "rt.h"

static inline real_t rti_joint_dot3(const real_t *a, const real_t *b)
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* spherical difference joint |r1 - r2| - l = 0 (eq. 8); p = {l}: with d = r1 - r2,
   e = d / |d|: g' = e . (v1 - v2), c = (|d'|^2 - (e . d')^2) / |d|; the translational
   entries only (rt_joint_kind.eval_points) */
static inline void rti_sphdiff_points(const real_t *p, const real_t *r1, const real_t *v1,
                                      const real_t *r2, const real_t *v2, rt_joint_eval *e)
{
    real_t d[3], dd[3], u[3] = {1, 0, 0};
    for (int i = 0; i < 3; i++)
        d[i] = r1[i] - r2[i], dd[i] = v1[i] - v2[i];
    real_t len = rt_sqrt(rti_joint_dot3(d, d));
    e->g[0] = len - p[0];
    e->c[0] = 0;
    /* coincident nodes have no direction: +x, no curvature term (finite, deterministic) */
    if (len > RT_MBS_LEN_MIN)
        for (int i = 0; i < 3; i++)
            u[i] = d[i] / len;
    for (int i = 0; i < 3; i++)
        e->C[0][i] = u[i], e->C[0][6 + i] = -u[i];
    if (len > RT_MBS_LEN_MIN) {
        real_t ud = rti_joint_dot3(u, dd);
        e->c[0] = (rti_joint_dot3(dd, dd) - ud * ud) / len;
    }
}

/* g alone: the first lines of rti_sphdiff_points (rt_joint_kind.g_points) */
static inline void rti_sphdiff_g(const real_t *p, const real_t *r1, const real_t *r2, real_t *g)
{
    real_t d[3];
    for (int i = 0; i < 3; i++)
        d[i] = r1[i] - r2[i];
    g[0] = rt_sqrt(rti_joint_dot3(d, d)) - p[0];
}

#endif /* RTI_JOINTS_H */
