/* rti_mbs.h - internal to rt/mbs*.c: the steps of the multibody services (assembly,
 * Schur complement, index-1 solve, projection) that rt/mbs.c, rt/mbs_asm.c and
 * rt/mbs_project.c share. Applications and models see rt_mbs.h (through rt.h) only. */
#ifndef RTI_MBS_H
#define RTI_MBS_H

#include "rti.h"

/* What rti_mbs_assemble evaluates (rt/mbs_asm.c defines the functions below but
   rti_mbs_in_set): */
enum {
    RTI_MBS_G = 0,     /* g (g' need not be: joint rows between points whose kind has
                          g_points get g alone and keep their old g') */
    RTI_MBS_JAC = 1,   /* also M (factored), W and gam */
    RTI_MBS_FORCE = 2  /* also the free accelerations M^-1 k (needs RTI_MBS_JAC) */
};
/* Is block b an MBS block of set `set`? (inline: the factorization, rt/mbs_ldl.c, asks
   it too, below the assembly) */
static inline int rti_mbs_in_set(const struct rt_scene *sc, uint16_t b, uint8_t set)
{
    return sc->blocks[b].kind->type == RT_KIND_MBS && sc->blocks[b].set == set;
}
/* Entries of a block's M factors in rt_mbs_work.M (mo): a diagonal M's nz, then 1/m where
   M = m I (RT_MBS_M_ISO, at rti_mbs_m_inv), then nz more where M^-1 k depends on the
   parameters alone (RT_MBS_F_PARAM with RT_MBS_M_CONST: a scene's written-out code keeps
   it there, at rti_mbs_m_kept, tools/scenec/spec.c); a dense M's nz^2 factors and nz row
   pivots. Init places them (rt/mbs.c), modrt sizes counts them (describe.c). */
static inline uint32_t rti_mbs_m_inv(const rt_mbs_spec *sp)
{
    return sp->nz;
}
static inline uint32_t rti_mbs_m_kept(const rt_mbs_spec *sp)
{
    return sp->nz + ((sp->flags & RT_MBS_M_ISO) ? 1u : 0u);
}
static inline uint32_t rti_mbs_m_entries(const rt_mbs_spec *sp)
{
    uint32_t kept = (sp->flags & RT_MBS_F_PARAM) && (sp->flags & RT_MBS_M_CONST);
    return (sp->flags & RT_MBS_M_DIAG) ? rti_mbs_m_kept(sp) + sp->nz * kept
                                       : (uint32_t)sp->nz * (sp->nz + 1u);
}
/* Evaluates joint ji: its nodes (Jacobians into J1, J2 unless NULL) and its kind. */
void rti_mbs_joint(const struct rt_scene *sc, const struct rt_sim *sim, uint16_t ji, real_t t,
                   rt_mbs_node *n1, rt_mbs_node *n2, real_t *J1, real_t *J2,
                   rt_joint_eval *e);
/* g and g' of joint ji's rows at the current state (its kind's nc values each): between
   two points straight from their coordinates (eval_points; g alone by g_points when gd is
   NULL), else through the nodes; the same bits either way (the residual signals of
   rt/mbs.c) */
void rti_mbs_joint_g(const struct rt_scene *sc, const struct rt_sim *sim, uint16_t ji, real_t t,
                     real_t *g, real_t *gd);
/* Factors block b's M in place (a diagonal M is only checked; a dense one by LU, its row
   pivots after its factors), counting a pivot at or below RT_MBS_PIVOT_TOL; and v <- M^-1 v
   with those factors. The assembly's and a scene's written-out code's (tools/scenec/spec.c)
   for bodies with a varying or dense M. */
void rti_mbs_mass_factor(struct rt_sim *sim, const rt_mbs_spec *sp, uint16_t b, real_t *M);
void rti_mbs_mass_solve(const rt_mbs_spec *sp, const real_t *M, real_t *v);
/* Evaluates the set's MBS blocks and joints at the current state into sim->work.mbs. */
void rti_mbs_assemble(const struct rt_scene *sc, struct rt_sim *sim, uint8_t set, real_t t,
                      int what);
/* Forms Y = M^-1 W^T and A = W Y over the touched rows and factors A (rt/mbs_ldl.c); an
   indefinite A is counted (RT_CNT_SINGULAR) with the block of the offending row, a change
   of its rank deficit to a non-zero one as RT_CNT_REDUNDANT. */
void rti_mbs_schur(const struct rt_scene *sc, struct rt_sim *sim, uint8_t set);
/* v (nc values) <- A^-1 v with the factors of rti_mbs_schur; a dropped row whose
   right-hand side conflicts with the others is counted (RT_CNT_SINGULAR, its block). */
void rti_mbs_solve(struct rt_sim *sim, uint8_t set, real_t *v);
/* dz = -Y v (add: dz -= Y v): the velocity-space correction of multipliers v. */
void rti_mbs_correct(const struct rt_scene *sc, struct rt_sim *sim, uint8_t set,
                     const real_t *v, real_t *dz, int add);
/* rt/mbs_ldl.c. Symbolic phase at init: the elimination order and L's pattern of set
   `set` (w->rb[set] and w->lp[w->rb[set]] set by the previous set), and the slots of each
   block's pairs of touches from *np on (advanced). */
rt_status rti_mbs_ldl_init(const struct rt_scene *sc, struct rt_sim *sim, uint8_t set,
                           uint32_t *np);
/* Zeroes the set's A before the blocks add their shares. */
void rti_mbs_ldl_clear(rt_mbs_work *w, uint8_t set);
/* Factors the set's A = L D L^T in place, dropping the rows that depend on earlier ones
   (w->ndrop[set], w->drop_row[set]); returns the set row of the first negative or NaN
   pivot (replaced by the threshold), or -1. */
int rti_mbs_ldl_factor(rt_mbs_work *w, uint8_t set);
/* v <- A^-1 v with the factors, a dropped row's multiplier zero; returns the first
   dropped row whose right-hand side conflicts with the rows it depends on, or -1. */
int rti_mbs_ldl_solve(const rt_mbs_work *w, uint8_t set, real_t *v);
/* The block owning constraint row `row` of the set (a joint's b1), or -1. */
int rti_mbs_row_block(const struct rt_scene *sc, const struct rt_sim *sim, uint8_t set,
                      uint16_t row);
/* The index-1 solve at the current state: lambda into gam (and jlam if need_lambda), and
   z' = M^-1 k - Y lambda into a. */
void rti_mbs_lambda(const struct rt_scene *sc, struct rt_sim *sim, uint8_t set, real_t t);
/* The accel service (see rt_mbs_ops) and the project service (rt/mbs_project.c). */
void rti_mbs_accel(const struct rt_scene *sc, struct rt_sim *sim, uint8_t set, real_t t,
                   real_t *xdot);
void rti_mbs_project(const struct rt_scene *sc, struct rt_sim *sim, uint8_t set, real_t t);
/* rt_init's projection (rt/mbs_project.c): rounds of a step's projection of positions,
   at most RT_INIT_PROJ_MAX, until the largest |g| is within RT_MBS_RES_TOL, then the
   velocities, whatever the scene's stabilization; counts nothing and returns the largest
   |g| left. */
real_t rti_mbs_settle(const struct rt_scene *sc, struct rt_sim *sim, uint8_t set, real_t t);
/* rt/mbs_start.c: the initial state of each set: quaternions, constraints, redundancy
   (RT_CNT_INIT_MOVED, RT_E_INCONSISTENT; the warnings into rt_error_text). */
rt_status rti_mbs_start(const struct rt_scene *sc, struct rt_sim *sim);

#endif /* RTI_MBS_H */
