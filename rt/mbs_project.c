/* mbs_project.c - the post-stabilizing projection of a set's multibody state after every
 * step (paper, section 3, eq. 10; Hairer & Wanner VII.2, Ascher et al. 1995):
 *
 *   positions:  exactly two simplified-Newton iterations of the mass-weighted projection,
 *               M and W = G K frozen at the predicted state (q~, z~):
 *                   q_{k+1} = q_k - K(q~) M^-1 W^T (W M^-1 W^T)^-1 g(q_k)        (10a)
 *               then unit quaternions are renormalized (the correction K ds is tangent);
 *   velocities: one direct solve at the projected q, since g' is linear in z:
 *                   z = z~ - M^-1 W^T (W M^-1 W^T)^-1 g'(q, z~)                  (10b)
 *
 * From consistent values g(q~) = O(h^(p+1)); Newton is quadratic, so two iterations leave
 * O(h^(4(p+1))), roundoff for any practical step, at a fixed cost per step. */
#include "rti_mbs.h"

static const rt_mbs_spec *spec_of(const rt_scene *sc, uint16_t b)
{
    return (const rt_mbs_spec *)sc->blocks[b].kind->spec;
}

/* qt <- q of every MBS block of the set whose K depends on q: the frozen point of the
   iteration */
static void save_q(const rt_scene *sc, rt_sim *sim, uint8_t set)
{
    const rt_mbs_work *w = &sim->work.mbs;
    if (w->points[set]) /* a point's K is I */
        return;
    for (uint16_t k = w->sb[set]; k < w->sb[set + 1]; k++) {
        uint16_t b = w->sblk[k];
        if (spec_of(sc, b)->flags & RT_MBS_K_CONST)
            continue;
        for (uint16_t i = 0; i < spec_of(sc, b)->nq; i++)
            sim->work.mbs.qt[sim->work.mbs.qo[b] + i] = sim->state.x[sim->plan.x_off[b] + i];
    }
}

/* x[from .. from + 3) += dz (in a) for every block of a set of points (rt_mbs_work.points):
   from 0 their q (K = I), from 3 their z */
static void points_add(rt_sim *sim, uint8_t set, unsigned from)
{
    const rt_mbs_work *w = &sim->work.mbs;
    for (unsigned k = w->sb[set], k1 = w->sb[set + 1]; k < k1; k++) {
        unsigned b = w->sblk[k];
        real_t *x = sim->state.x + sim->plan.x_off[b] + from;
        const real_t *dz = w->a + w->zo[b];
        x[0] += dz[0], x[1] += dz[1], x[2] += dz[2];
    }
}

/* z += dz (in a) for every MBS block of the set */
static void move_z(const rt_scene *sc, rt_sim *sim, uint8_t set)
{
    rt_mbs_work *w = &sim->work.mbs;
    if (w->points[set]) {
        points_add(sim, set, 3);
        return;
    }
    for (uint16_t k = w->sb[set]; k < w->sb[set + 1]; k++) {
        uint16_t b = w->sblk[k];
        const rt_mbs_spec *sp = spec_of(sc, b);
        real_t *z = sim->state.x + sim->plan.x_off[b] + sp->nq;
        for (uint16_t c = 0; c < sp->nz; c++)
            z[c] += w->a[w->zo[b] + c];
    }
}

/* q += K(q~) dz (in a), block by block: the velocity-space correction mapped to coordinates */
static void move_q(const rt_scene *sc, rt_sim *sim, uint8_t set, real_t t)
{
    rt_mbs_work *w = &sim->work.mbs;
    if (w->points[set]) { /* K = I: kin copies dz, so q += dz */
        points_add(sim, set, 0);
        return;
    }
    for (uint16_t k = w->sb[set]; k < w->sb[set + 1]; k++) {
        uint16_t b = w->sblk[k];
        const rt_mbs_spec *sp = spec_of(sc, b);
        real_t dq[RT_MAX_MBS_Q];
        rt_args a;
        rti_args(sc, sim, b, t, 0, &a);
        if (!(sp->flags & RT_MBS_K_CONST)) /* K at the predicted coordinates (kin reads q) */
            a.x = w->qt + w->qo[b];
        sp->kin(&a, w->a + w->zo[b], dq);
        for (uint16_t i = 0; i < sp->nq; i++)
            sim->state.x[sim->plan.x_off[b] + i] += dq[i];
    }
}

/* the kinds' own normalization (unit quaternions) */
static void normalize(const rt_scene *sc, rt_sim *sim, uint8_t set)
{
    const rt_mbs_work *w = &sim->work.mbs;
    if (w->points[set]) /* a point has nothing to normalize */
        return;
    for (uint16_t k = w->sb[set]; k < w->sb[set + 1]; k++)
        if (spec_of(sc, w->sblk[k])->normalize)
            spec_of(sc, w->sblk[k])->normalize(sim->state.x + sim->plan.x_off[w->sblk[k]]);
}

/* one correction: v <- A^-1 v in place (v = g or g', evaluated anew before they are read
   again), dz = -Y v into a (free during the projection) */
static void correct(const rt_scene *sc, rt_sim *sim, uint8_t set, real_t *v)
{
    rti_mbs_solve(sim, set, v);
    rti_mbs_correct(sc, sim, set, v, sim->work.mbs.a, 0);
}

/* the largest |g| of the set's rows in w->g (NaN counts as worst) and its row into *row,
   kept in the high-water mark res_max */
static real_t worst_row(rt_mbs_work *w, uint8_t set, uint16_t *row)
{
    real_t worst = 0;
    *row = 0;
    for (uint16_t r = 0; r < w->nc[set]; r++) {
        real_t v = rt_fabs(w->g[r]);
        if (!(v <= worst))
            worst = v, *row = r;
    }
    if (!(worst <= w->res_max))
        w->res_max = worst;
    return worst;
}

/* largest |g| after the projection: a high-water mark, and a degraded step above the
   tolerance (the two iterations did not reach the manifold: a far-off or singular state) */
static void check_residual(const rt_scene *sc, rt_sim *sim, uint8_t set)
{
    rt_mbs_work *w = &sim->work.mbs;
    uint16_t row;
    real_t worst = worst_row(w, set, &row);
    w->projections++;
    if (!(worst <= RT_MBS_RES_TOL))
        rti_count(sim, RT_CNT_DEGRADED, rti_mbs_row_block(sc, sim, set, row), RT_E_DEGRADED);
}

/* multipliers at the step end, for recorded joint reactions: outputs give the inputs */
static void refresh_lambda(const rt_scene *sc, rt_sim *sim, uint8_t set, real_t t)
{
    if (!sim->work.mbs.need_lambda)
        return;
    rti_outputs(sc, sim, (rti_at){t, set, RTI_IN_STEP});
    rti_mbs_lambda(sc, sim, set, t);
}

/* positions (10a): M, W and K frozen at the predicted state, two iterations */
static void positions(const rt_scene *sc, rt_sim *sim, uint8_t set, real_t t)
{
    rt_mbs_work *w = &sim->work.mbs;
    save_q(sc, sim, set);
    rti_mbs_assemble(sc, sim, set, t, RTI_MBS_JAC);
    rti_mbs_schur(sc, sim, set);
    correct(sc, sim, set, w->g);
    move_q(sc, sim, set, t);
    rti_mbs_assemble(sc, sim, set, t, RTI_MBS_G);
    correct(sc, sim, set, w->g);
    move_q(sc, sim, set, t);
    normalize(sc, sim, set);
}

/* velocities (10b): W and M at the projected positions, one solve; leaves g of the
   projected positions in w->g */
static void velocities(const rt_scene *sc, rt_sim *sim, uint8_t set, real_t t)
{
    rt_mbs_work *w = &sim->work.mbs;
    rti_mbs_assemble(sc, sim, set, t, RTI_MBS_JAC);
    rti_mbs_schur(sc, sim, set);
    correct(sc, sim, set, w->gd);
    move_z(sc, sim, set);
}

/* largest |g| in w->g (NaN: infinite) */
static real_t g_max(const rt_mbs_work *w, uint8_t set)
{
    real_t worst = 0;
    for (uint16_t r = 0; r < w->nc[set]; r++)
        worst = rt_fabs(w->g[r]) <= worst ? worst : rt_isfinite(w->g[r]) ? rt_fabs(w->g[r])
                                                                          : (real_t)1e30;
    return worst;
}

/* without projection (stabilization none or Baumgarte) the constraints drift: g at the
   step's end against the set's accuracy (a length [m] or a unit), the row's block counted
   as one whose invariant broke above it. Reads the state, changes nothing */
static void check_drift(const rt_scene *sc, rt_sim *sim, uint8_t set, real_t t)
{
    uint16_t row;
    rti_mbs_assemble(sc, sim, set, t, RTI_MBS_G);
    real_t worst = worst_row(&sim->work.mbs, set, &row);
    if (!(worst <= rti_accuracy(&sc->sets[set].cfg)))
        rti_count(sim, RT_CNT_INVARIANT, rti_mbs_row_block(sc, sim, set, row), RT_E_INVARIANT);
}

void rti_mbs_project(const rt_scene *sc, rt_sim *sim, uint8_t set, real_t t)
{
    rt_mbs_work *w = &sim->work.mbs;
    if (w->nz[set] == 0)
        return;
    if (sc->code && sc->code->project && sc->code->project(sc, sim, set, t))
        return; /* written out for this scene (rt_scene_code) */
    if (sc->stab != RT_STAB_PROJECT || w->nc[set] == 0) {
        if (sc->stab == RT_STAB_PROJECT)
            normalize(sc, sim, set);
        else if (w->nc[set] > 0)
            check_drift(sc, sim, set, t);
        refresh_lambda(sc, sim, set, t);
        return;
    }
    positions(sc, sim, set, t);
    velocities(sc, sim, set, t);
    check_residual(sc, sim, set);
    refresh_lambda(sc, sim, set, t);
}

real_t rti_mbs_settle(const rt_scene *sc, rt_sim *sim, uint8_t set, real_t t)
{
    rt_mbs_work *w = &sim->work.mbs;
    if (w->nz[set] == 0)
        return 0;
    w->projections++;
    if (w->nc[set] == 0)
        normalize(sc, sim, set);
    else {
        /* the first round is a step's projection; more only while it is not enough */
        for (unsigned k = 0; k < RT_INIT_PROJ_MAX; k++) {
            positions(sc, sim, set, t);
            rti_mbs_assemble(sc, sim, set, t, RTI_MBS_G);
            if (g_max(w, set) <= RT_MBS_RES_TOL)
                break;
        }
        velocities(sc, sim, set, t);
    }
    refresh_lambda(sc, sim, set, t);
    return w->nc[set] > 0 ? g_max(w, set) : 0;
}
