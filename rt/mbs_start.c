/* mbs_start.c - the initial state of the multibody sets, at the end of rt_init: unit
 * quaternions, the state put onto its constraints, and what that did, reported with the
 * block and the distance instead of fixed silently. A user learns that B3 starts 2 cm off
 * its rod, that a quaternion was not unit, or which joints repeat or contradict others.
 *
 *   quaternion of norm n (spec.normalize): normalized and counted (RT_CNT_INIT_MOVED)
 *       when |n - 1| > RT_MBS_RES_TOL; refused (RT_E_PARAM) when n is 0 or not finite;
 *   constraints: projected (rti_mbs_settle) with the scene's projection, and also under
 *       the other stabilizations when |g| > RT_MBS_RES_TOL (the index-1 formulation needs
 *       consistent values); a node moved (or turned, or its velocities changed) by more
 *       than RT_MBS_RES_TOL is counted with its block, moved by more than RT_INIT_TOL or
 *       turned by more than RT_INIT_ROT_TOL refused (RT_E_INCONSISTENT) naming the most
 *       violated joint;
 *   rows dependent on others (rt/mbs_ldl.c): consistent ones are reported (redundant,
 *       status ok); an initial state they leave off the constraints is refused, naming
 *       the joints involved.
 * The warnings go to rt_error_text (rt_init returns RT_OK). */
#include "rti_mbs.h"

static const rt_mbs_spec *spec_of(const rt_scene *sc, uint16_t b)
{
    return (const rt_mbs_spec *)sc->blocks[b].kind->spec;
}

static real_t dist3(const real_t *a, const real_t *b)
{
    real_t d0 = a[0] - b[0], d1 = a[1] - b[1], d2 = a[2] - b[2];
    return rt_sqrt(d0 * d0 + d1 * d1 + d2 * d2);
}

/* the angle [rad] between two node frames, from the chord |S1 - S0| (Frobenius) =
   2 sqrt(2) sin(angle / 2) */
static real_t angle_between(const real_t *S0, const real_t *S1)
{
    static const real_t two_sqrt2 = (real_t)2.8284271247461903;
    real_t c = 0;
    for (int i = 0; i < 9; i++)
        c += (S1[i] - S0[i]) * (S1[i] - S0[i]);
    real_t h = rt_sqrt(c) / two_sqrt2;
    return 2 * rt_asin(h < 1 ? h : 1);
}

/* what the start moved block b's nodes by between the saved state x0 and now, the
   largest over its nodes: displacement [m] (mv[0]), velocity change [m/s] (mv[1]),
   rotation [rad] (mv[2]) and angular velocity change [rad/s] (mv[3]): a node at a body's
   centre of mass keeps its place when the body's orientation is put right. A block
   without nodes: of its coordinates and velocities (mv[0], mv[1]) */
static void node_moves(const rt_scene *sc, const rt_sim *sim, uint16_t b, const real_t *x0,
                       real_t *mv)
{
    const rt_mbs_spec *sp = spec_of(sc, b);
    uint32_t off = sim->plan.x_off[b];
    mv[0] = mv[1] = mv[2] = mv[3] = 0;
    if (sp->nn == 0) {
        for (uint16_t i = 0; i < sp->nq + sp->nz; i++)
            mv[i >= sp->nq] = rt_fmax(mv[i >= sp->nq], rt_fabs(sim->state.x[off + i] - x0[off + i]));
        return;
    }
    rt_args now, then;
    rti_args(sc, sim, b, 0, 0, &now);
    then = now, then.x = x0 + off;
    for (uint16_t i = 0; i < sp->nn; i++) {
        rt_mbs_node n0, n1;
        sp->node(&then, i, &n0, 0);
        sp->node(&now, i, &n1, 0);
        mv[0] = rt_fmax(mv[0], dist3(n0.r, n1.r));
        mv[1] = rt_fmax(mv[1], dist3(n0.v, n1.v));
        mv[2] = rt_fmax(mv[2], angle_between(n0.S, n1.S));
        mv[3] = rt_fmax(mv[3], dist3(n0.w, n1.w));
    }
}

/* quaternions of the set's blocks: normalized (reported) or refused */
static rt_status quaternions(const rt_scene *sc, rt_sim *sim, uint8_t set)
{
    const rt_mbs_work *w = &sim->work.mbs;
    char txt[RTI_REAL_TEXT];
    for (uint16_t k = w->sb[set]; k < w->sb[set + 1]; k++) {
        uint16_t b = w->sblk[k];
        const rt_mbs_spec *sp = spec_of(sc, b);
        if (!sp->normalize)
            continue;
        real_t *q = sim->state.x + sim->plan.x_off[b];
        real_t n = sp->normalize(q);
        if (!(n > 0) || n - n != 0)
            return rti_fail(sim, RT_E_PARAM, "block ", sc->blocks[b].name,
                            ": initial quaternion of norm ", rti_real_text(txt, n),
                            " gives no orientation", (const char *)0);
        if (rt_fabs(n - 1) <= RT_MBS_RES_TOL) { /* unit as given: keep its bits */
            for (uint16_t i = 0; i < sp->nq; i++)
                q[i] = sim->work.x0[sim->plan.x_off[b] + i];
            continue;
        }
        rti_count(sim, RT_CNT_INIT_MOVED, b, RT_OK);
        rti_note(sim, sc->blocks[b].name, ": quaternion of norm ", rti_real_text(txt, n),
                 " normalized", (const char *)0);
        for (uint16_t i = 0; i < sp->nq; i++) /* the moves below: from the unit one */
            sim->work.x0[sim->plan.x_off[b] + i] = q[i];
    }
    return RT_OK;
}

/* the joint of set row `row`, or -1 (a block's internal row) */
static int joint_of_row(const rt_scene *sc, const rt_mbs_work *w, uint8_t set, uint16_t row)
{
    for (uint16_t k = w->sj[set]; k < w->sj[set + 1]; k++) {
        uint16_t j = w->sjnt[k];
        if (row >= w->jrow[j] && row < w->jrow[j] + sc->joints[j].kind->nc)
            return j;
    }
    return -1;
}

static const char *row_owner(const rt_scene *sc, const rt_sim *sim, uint8_t set, uint16_t row)
{
    int j = joint_of_row(sc, &sim->work.mbs, set, row);
    int b = rti_mbs_row_block(sc, sim, set, row);
    return j >= 0 ? sc->joints[j].name : b >= 0 ? sc->blocks[b].name : "?";
}

/* the first joint (or block) whose rows the set's first dropped row depends on: a
   non-zero entry of its row of L (the factors of the last solve); NULL when it has none
   (a row that restrains no motion, e.g. the orientation rows of a joint on a point) */
static const char *depends_on(const rt_scene *sc, const rt_sim *sim, uint8_t set)
{
    const rt_mbs_work *w = &sim->work.mbs;
    uint16_t base = w->rb[set], n = w->nc[set], i = 0;
    while (i < n && w->perm[base + i] != w->drop_row[set])
        i++;
    for (uint16_t e = w->lp[base + i]; i < n && e < w->lp[base + i + 1]; e++)
        if (w->lv[RT_MAX_MBS_ROWS + e] != 0)
            return row_owner(sc, sim, set, w->perm[base + w->lj[e]]);
    return 0;
}

/* the joint (or block) with the largest |g| at the current state, and that |g| */
static const char *worst_row(const rt_scene *sc, rt_sim *sim, uint8_t set, real_t *g)
{
    rt_mbs_work *w = &sim->work.mbs;
    uint16_t row = 0;
    rti_mbs_assemble(sc, sim, set, 0, RTI_MBS_G);
    *g = 0;
    for (uint16_t r = 0; r < w->nc[set]; r++)
        if (!(rt_fabs(w->g[r]) <= *g))
            *g = rt_fabs(w->g[r]), row = r;
    return w->nc[set] ? row_owner(sc, sim, set, row) : "";
}

/* moves of each block reported; the largest beyond RT_INIT_TOL refused */
static rt_status report_moves(const rt_scene *sc, rt_sim *sim, uint8_t set,
                              const char *joint, real_t g0)
{
    const rt_mbs_work *w = &sim->work.mbs;
    char t1[RTI_REAL_TEXT], t2[RTI_REAL_TEXT], t3[RTI_REAL_TEXT], t4[RTI_REAL_TEXT];
    for (uint16_t k = w->sb[set]; k < w->sb[set + 1]; k++) {
        uint16_t b = w->sblk[k];
        real_t mv[4];
        node_moves(sc, sim, b, sim->work.x0, mv);
        if (!(mv[0] <= RT_INIT_TOL))
            return rti_fail(sim, RT_E_INCONSISTENT, sc->blocks[b].name, " starts ",
                            rti_real_text(t1, mv[0]), " m off its constraints (",
                            joint, " violated by ", rti_real_text(t2, g0), "), above RT_INIT_TOL = ",
                            rti_real_text(t3, RT_INIT_TOL), (const char *)0);
        if (!(mv[2] <= RT_INIT_ROT_TOL))
            return rti_fail(sim, RT_E_INCONSISTENT, sc->blocks[b].name, " starts rotated ",
                            rti_real_text(t1, mv[2]), " rad off its constraints (", joint,
                            " violated by ", rti_real_text(t2, g0), "), above RT_INIT_ROT_TOL = ",
                            rti_real_text(t3, RT_INIT_ROT_TOL), (const char *)0);
        if (mv[0] <= RT_MBS_RES_TOL && mv[1] <= RT_MBS_RES_TOL && mv[2] <= RT_MBS_RES_TOL &&
            mv[3] <= RT_MBS_RES_TOL)
            continue;
        rti_count(sim, RT_CNT_INIT_MOVED, b, RT_OK);
        if (mv[2] <= RT_MBS_RES_TOL && mv[3] <= RT_MBS_RES_TOL)
            rti_note(sim, sc->blocks[b].name, " moved ", rti_real_text(t1, mv[0]), " m, ",
                     rti_real_text(t2, mv[1]), " m/s onto its constraints", (const char *)0);
        else
            rti_note(sim, sc->blocks[b].name, " moved ", rti_real_text(t1, mv[0]), " m, ",
                     rti_real_text(t2, mv[1]), " m/s, ", rti_real_text(t3, mv[2]), " rad, ",
                     rti_real_text(t4, mv[3]), " rad/s onto its constraints", (const char *)0);
    }
    return RT_OK;
}

/* one set: quaternions, the projection, its report */
static rt_status start_set(const rt_scene *sc, rt_sim *sim, uint8_t set)
{
    rt_mbs_work *w = &sim->work.mbs;
    char t1[RTI_REAL_TEXT], t2[RTI_REAL_TEXT];
    rt_status st = quaternions(sc, sim, set);
    if (st != RT_OK)
        return st;
    real_t g0;
    const char *joint = worst_row(sc, sim, set, &g0);
    if (sc->stab != RT_STAB_PROJECT && !(g0 > RT_MBS_RES_TOL)) {
        rti_mbs_project(sc, sim, set, 0); /* the initial multipliers, if recorded */
        return RT_OK;
    }
    real_t left = rti_mbs_settle(sc, sim, set, 0);
    if (!(left <= RT_MBS_RES_TOL)) { /* no state meets every constraint near this one */
        const char *what = worst_row(sc, sim, set, &left);
        const char *dep = w->ndrop[set] ? depends_on(sc, sim, set) : 0;
        if (dep)
            return rti_fail(sim, RT_E_INCONSISTENT, "joints ",
                            row_owner(sc, sim, set, w->drop_row[set]), " and ", dep,
                            " constrain the same motion and disagree (", what, " left off by ",
                            rti_real_text(t1, left), ")", (const char *)0);
        return rti_fail(sim, RT_E_INCONSISTENT, "no state near the initial one meets ", what,
                        ": off by ", rti_real_text(t1, left), " after ",
                        RTI_STR(RT_INIT_PROJ_MAX), " projections (", joint, " off by ",
                        rti_real_text(t2, g0), " at the start)", (const char *)0);
    }
    if ((st = report_moves(sc, sim, set, joint, g0)) != RT_OK)
        return st;
    const char *dep = w->ndrop[set] ? depends_on(sc, sim, set) : 0;
    if (dep)
        rti_note(sim, row_owner(sc, sim, set, w->drop_row[set]), " repeats constraints of ",
                 dep, ": solved with its multipliers zero", (const char *)0);
    else if (w->ndrop[set])
        rti_note(sim, row_owner(sc, sim, set, w->drop_row[set]), " has a row that "
                 "restrains no motion: solved with its multiplier zero", (const char *)0);
    return RT_OK;
}

rt_status rti_mbs_start(const rt_scene *sc, rt_sim *sim)
{
    /* the state as given, to measure the moves (rt_work.x0: free at init) */
    for (uint32_t i = 0; i < sim->plan.x_off[sc->nblocks]; i++)
        sim->work.x0[i] = sim->state.x[i];
    for (uint8_t s = 0; s < sc->nsets; s++) {
        if (sim->work.mbs.nz[s] == 0)
            continue;
        rt_status st = start_set(sc, sim, s);
        if (st != RT_OK) { /* refused: the state as given, not half projected */
            for (uint32_t i = 0; i < sim->plan.x_off[sc->nblocks]; i++)
                sim->state.x[i] = sim->work.x0[i];
            return st;
        }
    }
    return RT_OK;
}
