/* mbs.c - the multibody services a scene names with .mbs = &rt_mbs: init (checks of the
 * MBS blocks, joints and recorded MBS signals against the compile-time limits, the index
 * tables of rt_mbs_work, the initial projection) and the recordable MBS signals (energy,
 * constraint residuals, joint reactions). The solve is in rt/mbs_asm.c, the projection in
 * rt/mbs_project.c, the joint kinds in rt/joints.c. */
#include "rti_mbs.h"

static const rt_mbs_spec *spec_of(const rt_scene *sc, uint16_t b)
{
    return (const rt_mbs_spec *)sc->blocks[b].kind->spec;
}

static int is_mbs(const rt_scene *sc, int b)
{
    return b >= 0 && b < sc->nblocks && sc->blocks[b].kind->type == RT_KIND_MBS;
}

/* ------------------------------------------------------------------ init checks */

/* a kind's MBS part: sizes agree, the hooks its sizes need are there */
static rt_status check_spec(const rt_scene *sc, rt_sim *sim, uint16_t b)
{
    const rt_kind *k = sc->blocks[b].kind;
    const rt_mbs_spec *sp = spec_of(sc, b);
    int ok = sp->nq + sp->nz == k->nx && sp->nz > 0 && sp->kin && sp->mass && sp->force &&
             sp->energy && (sp->nc == 0 || sp->constr) && (sp->nn == 0 || sp->node) &&
             (!(sp->flags & RT_MBS_NODE_POINT) || (sp->nq == 3 && sp->nz == 3)) &&
             (!(sp->flags & RT_MBS_M_ISO) || (sp->flags & RT_MBS_M_DIAG)) &&
             (!(sp->flags & RT_MBS_Y_STATE) || (k->ny == k->nx && k->feed == RT_FEED_NONE));
    if (!ok) /* (a flag the written-out code trusts, Y_STATE's copy, is held here too) */
        return rti_fail(sim, RT_E_SCENE, "block ", sc->blocks[b].name,
                        ": its MBS description is inconsistent (nx != nq + nz, a hook "
                        "is missing, or a flag its sizes contradict)", (const char *)0);
    if (sp->nz > RT_MAX_MBS_BZ)
        return rti_capacity(sim, "block ", sc->blocks[b].name, RT_LIM_MBS_BZ);
    if (!(sp->flags & RT_MBS_NODE_POINT) && sp->nz > RT_MAX_MBS_JZ)
        return rti_capacity(sim, "block ", sc->blocks[b].name, RT_LIM_MBS_JZ);
    return RT_OK;
}

/* one joint: kind, blocks, nodes, one set, parameters */
static rt_status check_joint(const rt_scene *sc, rt_sim *sim, const rt_joint *j)
{
    const char *name = j->name ? j->name : "?";
    const rt_joint_kind *k = j->kind;
    if (!k || !k->eval || k->nc == 0 || k->nc > RT_MBS_JOINT_NC_MAX)
        return rti_fail(sim, RT_E_SCENE, "joint ", name, ": no valid joint kind",
                        (const char *)0);
    if (!is_mbs(sc, j->b1) || (j->b2 != -1 && !is_mbs(sc, j->b2)))
        return rti_fail(sim, RT_E_SCENE, "joint ", name,
                        ": links a block that does not exist or is not an MBS block",
                        (const char *)0);
    if (j->n1 < 0 || j->n1 >= spec_of(sc, (uint16_t)j->b1)->nn ||
        (j->b2 >= 0 && (j->n2 < 0 || j->n2 >= spec_of(sc, (uint16_t)j->b2)->nn)))
        return rti_fail(sim, RT_E_SCENE, "joint ", name, ": node index out of range",
                        (const char *)0);
    if (j->b2 >= 0 && sc->blocks[j->b1].set != sc->blocks[j->b2].set)
        return rti_fail(sim, RT_E_SCENE, "joint ", name,
                        ": links blocks of different sets (a joint couples one index-1 "
                        "system)", (const char *)0);
    if ((k->np > 0 && !j->p) || (k->check && j->p && k->check(j->p) != 0))
        return rti_fail(sim, RT_E_PARAM, "joint ", name, ": parameters out of range for ",
                        k->name, (const char *)0);
    return RT_OK;
}

/* offsets of each MBS block within its set (M's over all sets), and the set totals
   against the limits */
static rt_status block_tables(const rt_scene *sc, rt_sim *sim)
{
    rt_mbs_work *w = &sim->work.mbs;
    uint32_t mo = 0, nqt[RT_MAX_SETS] = {0};
    for (uint8_t s = 0; s < RT_MAX_SETS; s++)
        w->nz[s] = w->nq[s] = w->nc[s] = 0;
    for (uint16_t b = 0; b < sc->nblocks; b++) {
        w->zo[b] = w->qo[b] = w->mo[b] = w->co[b] = 0;
        w->m_valid[b] = 0;
        if (!is_mbs(sc, b))
            continue;
        rt_status st = check_spec(sc, sim, b);
        if (st != RT_OK)
            return st;
        const rt_mbs_spec *sp = spec_of(sc, b);
        uint8_t s = sc->blocks[b].set;
        w->zo[b] = w->nz[s], w->qo[b] = (uint16_t)nqt[s], w->co[b] = w->nc[s];
        w->mo[b] = (uint16_t)mo;
        if (!(sp->flags & RT_MBS_K_CONST) || sp->kinb)
            nqt[s] += sp->nq;
        uint32_t nz = (uint32_t)w->nz[s] + sp->nz, nq = (uint32_t)w->nq[s] + sp->nq;
        uint32_t nc = (uint32_t)w->nc[s] + sp->nc;
        mo += rti_mbs_m_entries(sp);
        rt_limit over = nz > RT_MAX_MBS_Z       ? RT_LIM_MBS_Z
                        : nq > RT_MAX_MBS_Q     ? RT_LIM_MBS_Q
                        : nc > RT_MAX_MBS_C     ? RT_LIM_MBS_C
                        : mo > RT_MAX_MBS_M     ? RT_LIM_MBS_M
                        : nqt[s] > RT_MAX_MBS_QT ? RT_LIM_MBS_QT
                                                 : RT_LIM_COUNT;
        if (over != RT_LIM_COUNT)
            return rti_capacity(sim, "set ", sc->sets[s].name, over);
        w->nz[s] = (uint16_t)nz, w->nq[s] = (uint16_t)nq, w->nc[s] = (uint16_t)nc;
    }
    return RT_OK;
}

/* joint rows follow the internal rows of their set, in joint order */
static rt_status joint_tables(const rt_scene *sc, rt_sim *sim)
{
    rt_mbs_work *w = &sim->work.mbs;
    uint32_t lo = 0;
    if (sc->njoints > RT_MAX_JOINTS)
        return rti_capacity(sim, 0, 0, RT_LIM_JOINTS);
    if (sc->njoints > 0 && !sc->joints)
        return rti_fail(sim, RT_E_SCENE, "njoints > 0 but no joint table", (const char *)0);
    for (uint16_t j = 0; j < sc->njoints; j++) {
        const rt_joint *jt = &sc->joints[j];
        rt_status st = check_joint(sc, sim, jt);
        if (st != RT_OK)
            return st;
        uint8_t s = sc->blocks[jt->b1].set;
        if (w->nc[s] + jt->kind->nc > RT_MAX_MBS_C)
            return rti_capacity(sim, "joint ", jt->name, RT_LIM_MBS_C);
        if (lo + jt->kind->nc > RT_MAX_MBS_JROWS)
            return rti_capacity(sim, "joint ", jt->name, RT_LIM_MBS_JROWS);
        w->jrow[j] = w->nc[s];
        w->nc[s] = (uint16_t)(w->nc[s] + jt->kind->nc);
        w->jlo[j] = (uint16_t)lo;
        for (uint16_t i = 0; i < jt->kind->nc; i++)
            w->jlam[lo++] = 0;
    }
    return RT_OK;
}

/* one touch (block b, row r): counted always, stored while it fits */
static void add_touch(rt_mbs_work *w, uint32_t *n, uint16_t r)
{
    if (*n < RT_MAX_MBS_TOUCH)
        w->trow[*n] = r;
    (*n)++;
}

/* the rows each block touches (its internal rows, then its joints' rows), ascending, and
   where each touch's slice of W and Y begins */
static rt_status touch_tables(const rt_scene *sc, rt_sim *sim)
{
    rt_mbs_work *w = &sim->work.mbs;
    uint32_t n = 0, tw = 0, ty = 0;
    for (uint16_t b = 0; b < sc->nblocks; b++) {
        w->to[b] = (uint16_t)n;
        w->wo[b] = (uint16_t)tw;
        w->yo[b] = (uint16_t)ty;
        if (!is_mbs(sc, b))
            continue;
        for (uint16_t i = 0; i < spec_of(sc, b)->nc; i++)
            add_touch(w, &n, (uint16_t)(w->co[b] + i));
        for (uint16_t j = 0; j < sc->njoints; j++) {
            const rt_joint *jt = &sc->joints[j];
            if (jt->b1 != b && jt->b2 != b)
                continue;
            uint16_t at = (uint16_t)(tw + (n - w->to[b]) * spec_of(sc, b)->nz);
            w->jw[j][jt->b1 == b ? 0 : 1] = at;
            if (jt->b2 == b)
                w->jw[j][1] = at;
            for (uint16_t i = 0; i < jt->kind->nc; i++)
                add_touch(w, &n, (uint16_t)(w->jrow[j] + i));
        }
        tw += (n - w->to[b]) * spec_of(sc, b)->nz;
        if (!(spec_of(sc, b)->flags & RT_MBS_M_DIAG))
            ty += (n - w->to[b]) * spec_of(sc, b)->nz;
        rt_limit over = n > RT_MAX_MBS_TOUCH ? RT_LIM_MBS_TOUCH
                        : tw > RT_MAX_MBS_TW ? RT_LIM_MBS_TW
                        : ty > RT_MAX_MBS_TY ? RT_LIM_MBS_TY
                                             : RT_LIM_COUNT;
        if (over != RT_LIM_COUNT)
            return rti_capacity(sim, "block ", sc->blocks[b].name, over);
    }
    w->to[sc->nblocks] = (uint16_t)n;
    return RT_OK;
}

/* does set s hold points only: each MBS block a point node (RT_MBS_NODE_POINT) with a
   constant M = m I (RT_MBS_M_ISO), no constraints of its own and nothing to normalize,
   each joint's kind one that evaluates points with C2 = -C1 (eval_points, anti; its ends
   are blocks of the set, so points, or the inertial frame: check_joint) between two
   different ends? Its multibody path then looks up no spec and forms A from C.C and 1/m
   (rt/mbs_asm.c assemble_point_set, point_shares; rt/mbs_project.c points_add) */
static uint8_t points_only(const rt_scene *sc, const rt_mbs_work *w, uint8_t s)
{
    const uint8_t need = RT_MBS_NODE_POINT | RT_MBS_M_DIAG | RT_MBS_M_ISO | RT_MBS_M_CONST;
    for (uint16_t k = w->sb[s]; k < w->sb[s + 1]; k++) {
        const rt_mbs_spec *sp = spec_of(sc, w->sblk[k]);
        if ((sp->flags & need) != need || sp->nc > 0 || sp->normalize)
            return 0;
    }
    for (uint16_t k = w->sj[s]; k < w->sj[s + 1]; k++) {
        const rt_joint *j = &sc->joints[w->sjnt[k]];
        if (!j->kind->eval_points || !j->kind->anti || j->b2 == j->b1)
            return 0;
    }
    return 1;
}

/* each set's MBS blocks and joints, in scene order: what the evaluations loop over */
static rt_status set_lists(const rt_scene *sc, rt_sim *sim)
{
    rt_mbs_work *w = &sim->work.mbs;
    uint16_t nb = 0, nj = 0;
    for (uint8_t s = 0; s < sc->nsets; s++) {
        w->sb[s] = nb, w->sj[s] = nj;
        for (uint16_t b = 0; b < sc->nblocks; b++)
            if (rti_mbs_in_set(sc, b, s))
                w->sblk[nb++] = b;
        for (uint16_t j = 0; j < sc->njoints; j++)
            if (sc->blocks[sc->joints[j].b1].set == s)
                w->sjnt[nj++] = j;
    }
    w->sb[sc->nsets] = nb, w->sj[sc->nsets] = nj;
    for (uint8_t s = 0; s < RT_MAX_SETS; s++)
        w->points[s] = s < sc->nsets && points_only(sc, w, s);
    return RT_OK;
}

/* the symbolic phase of each set's sparse factorization (rt/mbs_ldl.c) */
static rt_status factor_tables(const rt_scene *sc, rt_sim *sim)
{
    rt_mbs_work *w = &sim->work.mbs;
    uint32_t np = 0;
    w->rb[0] = 0, w->lp[0] = 0;
    for (uint8_t s = 0; s < sc->nsets; s++) {
        rt_status st = rti_mbs_ldl_init(sc, sim, s, &np);
        if (st != RT_OK)
            return st;
    }
    return RT_OK;
}

/* a multibody signal (recorded or exported): an MBS block, a known quantity, a joint
   acting on that block; a joint's reaction sets need_lambda (the multipliers are kept
   per joint, and again at each step end: rt/mbs_project.c) */
static rt_status check_signal(const rt_scene *sc, rt_sim *sim, const rt_rec *r,
                              const char *what)
{
    int ok = is_mbs(sc, r->block);
    if (ok && r->index >= RT_MBS_SIG_NSET) {
        uint16_t j = (uint16_t)((r->index - RT_MBS_SIG_JOINT) / RT_MBS_JSIG_COUNT);
        uint16_t c = (uint16_t)((r->index - RT_MBS_SIG_JOINT) % RT_MBS_JSIG_COUNT);
        ok = r->index >= RT_MBS_SIG_JOINT && j < sc->njoints &&
             sc->joints[j].b1 == (int16_t)r->block &&
             (c < RT_MBS_JSIG_LAMBDA || c - RT_MBS_JSIG_LAMBDA < sc->joints[j].kind->nc);
        sim->work.mbs.need_lambda = 1;
    }
    if (!ok)
        return rti_fail(sim, RT_E_SCENE, "a ", what, " MBS signal of ",
                        sc->blocks[r->block < sc->nblocks ? r->block : 0].name,
                        " names no MBS quantity of that block", (const char *)0);
    return RT_OK;
}

/* the recorded and the link's exported multibody signals */
static rt_status check_recs(const rt_scene *sc, rt_sim *sim)
{
    sim->work.mbs.need_lambda = 0;
    for (uint16_t i = 0; i < sc->nrecs; i++)
        if (sc->recs[i].what == RT_SIG_MBS && check_signal(sc, sim, &sc->recs[i], "recorded") != RT_OK)
            return RT_E_SCENE;
    for (uint16_t i = 0; sc->link && i < sc->link->nexp; i++)
        if (sc->link->exp[i].what == RT_SIG_MBS &&
            check_signal(sc, sim, &sc->link->exp[i], "exported") != RT_OK)
            return RT_E_SCENE;
    return RT_OK;
}

/* the start again, with the tables init built (rt_refresh before the first tick) */
static int restart(const rt_scene *sc, rt_sim *sim)
{
    return rti_mbs_start(sc, sim);
}

static int init(const rt_scene *sc, rt_sim *sim)
{
    rt_status st;
    /* Baumgarte with alpha = beta = 0 is no stabilization under another name: a scene
       asking for it and getting none would be told nothing */
    if (sc->stab > RT_STAB_BAUMGARTE ||
        (sc->stab == RT_STAB_BAUMGARTE &&
         !(sc->baumgarte[0] >= 0 && sc->baumgarte[1] >= 0 &&
           sc->baumgarte[0] + sc->baumgarte[1] > 0 &&
           rt_isfinite(sc->baumgarte[0]) && rt_isfinite(sc->baumgarte[1]))))
        return rti_fail(sim, RT_E_SCENE, "unknown stabilization, or Baumgarte parameters "
                        "not finite, >= 0 and not both 0", (const char *)0);
    if ((st = block_tables(sc, sim)) != RT_OK || (st = joint_tables(sc, sim)) != RT_OK ||
        (st = touch_tables(sc, sim)) != RT_OK || (st = set_lists(sc, sim)) != RT_OK ||
        (st = factor_tables(sc, sim)) != RT_OK ||
        (st = check_recs(sc, sim)) != RT_OK)
        return st;
    sim->work.mbs.res_max = 0;
    sim->work.mbs.projections = 0;
    /* the index-1 formulation needs consistent initial values (rt/mbs_start.c) */
    return rti_mbs_start(sc, sim);
}

/* ------------------------------------------------------------------ signals */

/* largest |g| (pos) or |g'| (!pos) of the set's constraints at the current state */
static real_t residual(const rt_scene *sc, const rt_sim *sim, uint8_t set, real_t t, int pos)
{
    const rt_mbs_work *w = &sim->work.mbs;
    real_t worst = 0;
    for (uint16_t i = w->sb[set]; i < w->sb[set + 1]; i++) {
        uint16_t b = w->sblk[i];
        const rt_mbs_spec *sp = spec_of(sc, b);
        if (sp->nc == 0)
            continue;
        real_t g[RT_MAX_MBS_C], gd[RT_MAX_MBS_C];
        rt_args a;
        rti_args(sc, sim, b, t, 0, &a);
        sp->constr(&a, g, gd, 0, 0, 0);
        for (uint16_t i = 0; i < sp->nc; i++)
            worst = rt_fmax(worst, rt_fabs(pos ? g[i] : gd[i]));
    }
    for (uint16_t i = w->sj[set]; i < w->sj[set + 1]; i++) {
        uint16_t j = w->sjnt[i];
        real_t g[RT_MBS_JOINT_NC_MAX], gd[RT_MBS_JOINT_NC_MAX];
        rti_mbs_joint_g(sc, sim, j, t, g, pos ? 0 : gd);
        for (uint16_t i = 0; i < sc->joints[j].kind->nc; i++)
            worst = rt_fmax(worst, rt_fabs(pos ? g[i] : gd[i]));
    }
    return worst;
}

/* kinetic (which = 0), potential (1) or total (2) energy of the set */
static real_t energy(const rt_scene *sc, const rt_sim *sim, uint8_t set, real_t t, int which)
{
    real_t sum = 0;
    for (uint16_t b = 0; b < sc->nblocks; b++) {
        if (!rti_mbs_in_set(sc, b, set))
            continue;
        real_t e[2];
        rt_args a;
        rti_args(sc, sim, b, t, 0, &a);
        spec_of(sc, b)->energy(&a, e);
        sum += which == 2 ? e[0] + e[1] : e[which];
    }
    return sum;
}

/* component c of joint j's reaction on node 1: -C1^T lambda, or lambda itself */
static real_t reaction(const rt_scene *sc, const rt_sim *sim, uint16_t j, uint16_t c,
                       real_t t)
{
    const real_t *lam = sim->work.mbs.jlam + sim->work.mbs.jlo[j];
    if (c >= RT_MBS_JSIG_LAMBDA)
        return lam[c - RT_MBS_JSIG_LAMBDA];
    rt_mbs_node n1, n2;
    rt_joint_eval e;
    rti_mbs_joint(sc, sim, j, t, &n1, &n2, 0, 0, &e);
    real_t f = 0;
    for (uint16_t i = 0; i < sc->joints[j].kind->nc; i++)
        f -= e.C[i][c] * lam[i];
    return f;
}

static real_t signal(const rt_scene *sc, const rt_sim *sim, uint16_t block, uint16_t index)
{
    uint8_t set = sc->blocks[block].set;
    real_t t = rti_time(sc, sim);
    switch (index) {
    case RT_MBS_SIG_ENERGY:
        return energy(sc, sim, set, t, 2);
    case RT_MBS_SIG_KINETIC:
        return energy(sc, sim, set, t, 0);
    case RT_MBS_SIG_POTENTIAL:
        return energy(sc, sim, set, t, 1);
    case RT_MBS_SIG_RESIDUAL:
        return residual(sc, sim, set, t, 1);
    case RT_MBS_SIG_RESIDUAL_V:
        return residual(sc, sim, set, t, 0);
    default:
        index = (uint16_t)(index - RT_MBS_SIG_JOINT);
        return reaction(sc, sim, index / RT_MBS_JSIG_COUNT, index % RT_MBS_JSIG_COUNT, t);
    }
}

#define SIG_NAME(e, name, meaning) name,
static const char *const set_names[RT_MBS_SIG_NSET] = {RT_MBS_SIG_LIST(SIG_NAME)};
static const char *const joint_names[RT_MBS_JSIG_COUNT] = {
    RT_MBS_JSIG_LIST(SIG_NAME)
    "lambda1", "lambda2", "lambda3", "lambda4", "lambda5", "lambda6",
};
#undef SIG_NAME

static const char *signal_name(const rt_scene *sc, uint16_t block, uint16_t index)
{
    (void)sc, (void)block;
    if (index < RT_MBS_SIG_NSET)
        return set_names[index];
    if (index < RT_MBS_SIG_JOINT)
        return "?";
    return joint_names[(index - RT_MBS_SIG_JOINT) % RT_MBS_JSIG_COUNT];
}

const rt_mbs_ops rt_mbs = {
    .init = init,
    .accel = rti_mbs_accel,
    .project = rti_mbs_project,
    .restart = restart,
    .signal = signal,
    .signal_name = signal_name,
};
