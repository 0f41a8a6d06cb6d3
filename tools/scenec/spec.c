/* spec.c - specialized C for a scene (rt_scene_code, docs/overhead.md): the work the
 * table-driven path does for it, written out with the tables rt_init built for the scene
 * (scenec runs it as its last check): block and joint indices, state offsets, the
 * multibody touches, the pattern of the sparse L D L^T and its slots, as constants.
 *
 * Bit-identical by construction: every sum is the generic path's, term by term in its
 * order (the same expressions, the same +0 starts); only the loops over tables become
 * straight-line code. Counters and faults go through the same rti_ calls. The multibody
 * part of a set with constraint rows is written out, for point masses alone and for
 * bodies (any M, rows of their own or not, points among them); a multibody set without
 * rows gets its outputs and derivatives written out and calls the generic
 * rti_mbs_accel, as rti_rhs does. A set that takes no step of its
 * own is left to the generic path: its rhs and project entries return 0 for that set.
 * Every set's output sequence at a tick or in a step is written out (outputs).
 *
 * The tables' offsets do not depend on the build's limits (they are packed from 0); the
 * one that does, a slot of L in lv, is written relative to RT_MAX_MBS_ROWS. */
#include "scn.h"

#include "rti_mbs.h"

/* which of a constraint row's g, g' and gam an assembly writes: what the code after it
   reads (the generic path writes all three; the state's bits do not depend on the ones
   nobody reads, and each assembly forms its own before they are read) */
enum {
    ROW_G = 1,  /* the position residual: the projection's, Baumgarte's */
    ROW_GD = 2, /* g': the velocity projection's, Baumgarte's */
    ROW_GAM = 4 /* the curvature term: a right-hand side's */
};

/* the comment over an assembly's rows: what it writes of them */
static void rows_comment(FILE *f, const char *what, int jac, int rows)
{
    fprintf(f, "    /* the joints' rows:%s%s%s%s (%s) */\n", rows & ROW_G ? " g" : "",
            rows & ROW_GD ? " g'" : "", jac && (rows & ROW_GAM) ? " gam" : "", jac ? " W" : "",
            what);
}

/* the rows a right-hand side reads: gam, and g and g' under Baumgarte (lambda_accel) */
static int accel_rows(const rt_scene *sc)
{
    return ROW_GAM | (sc->stab == RT_STAB_BAUMGARTE ? ROW_G | ROW_GD : 0);
}

/* a set whose multibody part the generator writes out: point masses only, joints with
   eval_points, at least one constraint row */
static int mbs_points_set(const rt_scene *sc, const rt_sim *sim, uint8_t s)
{
    const rt_mbs_work *w = &sim->work.mbs;
    if (!sc->mbs || w->nz[s] == 0 || !w->points[s] || w->nc[s] == 0)
        return 0;
    for (uint16_t k = w->sj[s]; k < w->sj[s + 1]; k++) {
        const rt_joint *j = &sc->joints[w->sjnt[k]];
        if (!j->kind->eval_points || j->kind->nc > RT_MBS_JOINT_NC_MAX)
            return 0;
    }
    return 1;
}

/* block b's multibody spec, and its velocities */
static const rt_mbs_spec *spec_of(const rt_scene *sc, uint16_t b)
{
    return (const rt_mbs_spec *)sc->blocks[b].kind->spec;
}

static unsigned nz_of(const rt_sim *sim, uint16_t b)
{
    return spec_of(sim->sc, b)->nz;
}

/* a set whose multibody part the generator writes out through the general node path:
   bodies (and points among them), at least one constraint row. M constant (factored at
   the first assembly) or formed and factored in every assembly with Jacobians, diagonal
   or dense; rows of a block's own (its constr) or not. Its Schur complement, factors,
   solve and z' take the points' form with nz velocities a block (rt/mbs_asm.c: a
   diagonal M divides on the fly, a dense one keeps Y = M^-1 W^T); its joints' rows are
   assemble_joint's */
static int mbs_bodies_set(const rt_scene *sc, const rt_sim *sim, uint8_t s)
{
    const rt_mbs_work *w = &sim->work.mbs;
    return sc->mbs && w->nz[s] > 0 && !w->points[s] && w->nc[s] > 0;
}

/* is side `side` of joint j a point: an anchor or a block whose node is its point
   (RT_MBS_NODE_POINT: a point in a set with bodies) */
static int point_side(const rt_scene *sc, const rt_joint *j, int side)
{
    int16_t b = (int16_t)(side ? j->b2 : j->b1);
    return b < 0 || (spec_of(sc, (uint16_t)b)->flags & RT_MBS_NODE_POINT) != 0;
}

/* does set s of bodies (mbs_bodies_set) have a joint between two points, whose rows
   point_joint writes */
static int point_joints(const rt_scene *sc, const rt_sim *sim, uint8_t s)
{
    const rt_mbs_work *w = &sim->work.mbs;
    for (uint16_t k = w->sj[s]; k < w->sj[s + 1]; k++) {
        const rt_joint *j = &sc->joints[w->sjnt[k]];
        if (j->kind->eval_points && point_side(sc, j, 0) && point_side(sc, j, 1))
            return 1;
    }
    return 0;
}

/* does block b keep Y = M^-1 W^T (a dense M), and where the written-out code finds that
   block's entries of M^-1 W^T for its touch i: the local quotients q (a diagonal M) or
   w->Y */
static int dense_m(const rt_scene *sc, uint16_t b)
{
    return !(spec_of(sc, b)->flags & RT_MBS_M_DIAG);
}

static void y_of(const rt_scene *sc, const rt_sim *sim, uint16_t b, unsigned i,
                 const char **name, unsigned *at)
{
    const rt_mbs_work *w = &sim->work.mbs;
    unsigned nz = spec_of(sc, b)->nz;
    *name = dense_m(sc, b) ? "Y" : "q";
    *at = (dense_m(sc, b) ? w->yo[b] : w->wo[b]) + nz * i;
}

/* a set whose right-hand side the generator writes out: every set that steps (its
   outputs and derivatives; its multibody part written out if mbs_points_set, else the
   generic service's call) */
static int rhs_set(const rt_sim *sim, uint8_t s)
{
    return !(sim->plan.set_flags[s] & RTI_SET_NO_STEP);
}

/* the written-out rti_gather of block b: each input from its source */
static void gather(FILE *f, const rt_sim *sim, uint16_t b)
{
    for (unsigned i = sim->plan.u_off[b]; i < sim->plan.u_off[b + 1]; i++)
        switch (sim->plan.src_kind[i]) {
        case RT_SRC_Y:
        case RT_SRC_HELD:
            fprintf(f, "    u[%u] = y[%u];\n", i, sim->plan.src[i]);
            break;
        case RT_SRC_TORN:
            fprintf(f, "    u[%u] = sim->state.torn_val[%u];\n", i, sim->plan.src[i]);
            break;
        case RT_SRC_XSET:
            fprintf(f, "    u[%u] = rti_xset_value(sim, %u, %u, %u, t, %u);\n", i,
                    sim->plan.src[i], sim->plan.src_set[i], sim->plan.interp[i], b);
            break;
        default:
            fprintf(f, "    u[%u] = sim->plan.def[%u];\n", i, i);
            break;
        }
}

/* rt_args of block b (rti_args) with its offsets as constants, and its piece if it has
   known time events */
static void block_args(FILE *f, const rt_scene *sc, const rt_sim *sim, uint16_t b,
                       const char *h)
{
    fprintf(f, "    args(sim, %u, %u, %u, %u, %u, t, %s, &ar);\n", b, sim->plan.x_off[b],
            sim->plan.d_off[b], sim->plan.u_off[b], sim->plan.p_off[b], h);
    if (sc->blocks[b].kind->next_event)
        fprintf(f, "    ar.t_piece = rti_piece(sc, sim, sc->blocks[%u].kind, t);\n", b);
}

/* call_output's injected fault after block b's output call (RT_FAULT_INJECT builds) */
static void fault_nan(FILE *f, const rt_scene *sc, const rt_sim *sim, uint16_t b)
{
    if (sc->blocks[b].kind->ny > 0)
        fprintf(f, "#if RT_FAULT_INJECT\n    if (rti_fault_due(RTI_FAULT_NAN) && "
                   "rti_fault_plan.block == %u)\n        y[%u] = (real_t)0 / (real_t)0;\n"
                   "#endif\n", b, sim->plan.y_off[b]);
}

/* a block whose output equation copies its state (RT_MBS_Y_STATE): the copies, no call
   (1), else 0 */
static int state_copy(FILE *f, const rt_scene *sc, const rt_sim *sim, uint16_t b)
{
    const rt_kind *k = sc->blocks[b].kind;
    if (k->type != RT_KIND_MBS || !(((const rt_mbs_spec *)k->spec)->flags & RT_MBS_Y_STATE))
        return 0;
    for (unsigned i = 0; i < k->ny; i++)
        fprintf(f, "    y[%u] = sim->state.x[%u];\n", sim->plan.y_off[b] + i,
                sim->plan.x_off[b] + i);
    return 1;
}

/* rti_rhs's set_outputs: the set's entries of the sequence a right-hand side calls */
static void outputs(FILE *f, const rt_scene *sc, const rt_sim *sim, uint8_t s)
{
    if (sim->plan.rhs_calls[s] == 0)
        return;
    fputs("    /* the outputs the set reads live, in sequence order (set_outputs) */\n", f);
    for (uint16_t i = sim->plan.seq_of[s]; i < sim->plan.seq_of[s + 1]; i++) {
        uint16_t q = sim->plan.set_seq[i], b = sim->plan.seq[q].index;
        uint8_t fl = sim->plan.seq_flags[q] & RTI_SEQ_RHS;
        const rt_kind *k;
        if (sim->plan.seq[q].kind == RT_SEQ_LOOP) {
            fprintf(f, "    sc->loop_solver->solve(sc, sim, %u, t, RTI_IN_RHS);\n", b);
            continue;
        }
        k = sc->blocks[b].kind;
        if (fl == RTI_RHS_SKIP || k->type == RT_KIND_DSS) /* held in a step: call_output */
            continue;
        fprintf(f, "    /* %s */\n", sc->blocks[b].name);
        if (state_copy(f, sc, sim, b)) {
            fault_nan(f, sc, sim, b);
            continue;
        }
        if (k->feed != RT_FEED_NONE)
            gather(f, sim, b);
        block_args(f, sc, sim, b, "0");
        fprintf(f, "    blocks[%u].kind->%s(&ar, y + %u);\n", b,
                fl == RTI_RHS_LEAN ? "output_lean" : "output", sim->plan.y_off[b]);
        fault_nan(f, sc, sim, b);
    }
}

/* one block's output call of set_outputs at a tick or in a step (call_output): a
   sampled block only at its sample hits, with its period for h */
static void tick_call(FILE *f, const rt_scene *sc, const rt_sim *sim, uint16_t b)
{
    const rt_kind *k = sc->blocks[b].kind;
    int dss = k->type == RT_KIND_DSS;
    fprintf(f, "    /* %s */\n", sc->blocks[b].name);
    /* the period from the plan: a copy of the scene at another base tick (a reference
       run) keeps this code */
    if (dss)
        fprintf(f, "    if (hit && rti_tick_mod(sim->state.tick, sim->plan.period[%u]) == 0) {\n"
                   "    real_t hs = sc->dt * (real_t)sim->plan.period[%u];\n", b, b);
    else
        fputs("    {\n", f);
    if (state_copy(f, sc, sim, b)) {
        fault_nan(f, sc, sim, b);
        fputs("    }\n", f);
        return;
    }
    if (k->feed != RT_FEED_NONE)
        gather(f, sim, b);
    block_args(f, sc, sim, b, dss ? "hs" : "0");
    fprintf(f, "    blocks[%u].kind->output(&ar, y + %u);\n", b, sim->plan.y_off[b]);
    fault_nan(f, sc, sim, b);
    fputs("    }\n", f);
}

/* rti_outputs of set s at a tick or in a step (set_outputs), its sequence written out;
   a right-hand side's are its rhs entry's (outputs, above) */
static void tick_outputs(FILE *f, const rt_scene *sc, const rt_sim *sim, uint8_t s)
{
    fprintf(f, "\n/* set %s: rti_outputs at a tick or in a step (set_outputs) */\n"
               "static int outputs_%u(const rt_scene *sc, rt_sim *sim, real_t t, int mode)\n{\n"
               "    real_t *u = sim->work.u, *y = sim->state.y;\n"
               "    rt_args ar;\n"
               "    int hit = mode == RTI_AT_TICK || mode == RTI_AT_TICK_RECALL;\n"
               "    (void)sc, (void)u, (void)y, (void)ar, (void)t, (void)hit;\n"
               "    if (mode == RTI_IN_RHS)\n        return 0;\n",
            sc->sets[s].name, s);
    for (uint16_t i = sim->plan.seq_of[s]; i < sim->plan.seq_of[s + 1]; i++) {
        uint16_t q = sim->plan.set_seq[i], b = sim->plan.seq[q].index;
        int recall = (sim->plan.seq_flags[q] & RTI_SEQ_RECALL) != 0;
        if (!recall)
            fputs("    if (mode != RTI_AT_TICK_RECALL) {\n", f);
        if (sim->plan.seq[q].kind == RT_SEQ_LOOP)
            fprintf(f, "    sc->loop_solver->solve(sc, sim, %u, t, mode);\n", b);
        else
            tick_call(f, sc, sim, b);
        if (!recall)
            fputs("    }\n", f);
    }
    fputs("    return 1;\n}\n", f);
}

/* rti_rhs's derivatives of the set's blocks with states of their own */
static void derivs(FILE *f, const rt_scene *sc, const rt_sim *sim, uint8_t s)
{
    if (!(sim->plan.set_flags[s] & RTI_SET_DERIV))
        return;
    fputs("    /* the blocks' derivatives */\n", f);
    for (uint16_t i = sim->plan.blk_of[s]; i < sim->plan.blk_of[s + 1]; i++) {
        uint16_t b = sim->plan.set_blk[i];
        const rt_kind *k = sc->blocks[b].kind;
        if (k->nx == 0 || !k->deriv)
            continue;
        fprintf(f, "    /* %s */\n", sc->blocks[b].name);
        gather(f, sim, b);
        block_args(f, sc, sim, b, "h");
        fprintf(f, "    blocks[%u].kind->deriv(&ar, xdot + %u);\n", b,
                sim->plan.x_off[b] - sim->plan.set_x[s]);
    }
}

/* lv's slot as the build's limits place it */
static void slot(FILE *f, unsigned v)
{
    if (v >= RT_MAX_MBS_ROWS)
        fprintf(f, "lv[RT_MAX_MBS_ROWS + %u]", v - RT_MAX_MBS_ROWS);
    else
        fprintf(f, "lv[%u]", v);
}

/* rt_args of block b with its offsets as constants, as rti_args fills it (no piece: the
   multibody services never set one) */
static void mbs_args(FILE *f, const rt_sim *sim, uint16_t b)
{
    fprintf(f, "    args(sim, %u, %u, %u, %u, %u, t, 0, &ar);\n", b, sim->plan.x_off[b],
            sim->plan.d_off[b], sim->plan.u_off[b], sim->plan.p_off[b]);
}

/* mass_factor (rt/mbs_asm.c) of block b's diagonal M of nz entries at w->M + mo: every
   pivot at or below the threshold replaced by it and counted */
static void mass_diag(FILE *f, uint16_t b, unsigned mo, unsigned nz, int iso)
{
    fputs("    {\n        real_t big = 0, floor_;\n        int low = 0;\n", f);
    for (unsigned i = 0; i < nz; i++)
        fprintf(f, "        big = w->M[%u] > big ? w->M[%u] : big;\n", mo + i, mo + i);
    fputs("        floor_ = RT_MBS_PIVOT_TOL * (big > 0 ? big : 1);\n", f);
    for (unsigned i = 0; i < nz; i++)
        fprintf(f, "        if (!(w->M[%u] > floor_))\n            w->M[%u] = floor_, low = 1;\n",
                mo + i, mo + i);
    if (iso) /* M = m I (RT_MBS_M_ISO): 1/m */
        fprintf(f, "        w->M[%u] = (real_t)1 / w->M[%u];\n", mo + nz, mo);
    fprintf(f, "        if (low)\n            rti_count(sim, RT_CNT_SINGULAR, %u, RT_E_SINGULAR);\n"
               "        w->m_valid[%u] = 1;\n    }\n", b, b);
}

/* does block b's M^-1 k depend on its parameters alone (RT_MBS_F_PARAM, a constant
   diagonal M, no inputs): formed once, kept until a parameter changes */
static int param_force(const rt_scene *sc, uint16_t b)
{
    const rt_mbs_spec *sp = spec_of(sc, b);
    unsigned need = RT_MBS_F_PARAM | RT_MBS_M_CONST | RT_MBS_M_DIAG;
    return (sp->flags & need) == need && sc->blocks[b].kind->nu == 0;
}

/* block b's M^-1 k kept after its diagonal M's factors (rti_mbs_m_entries), formed
   there (force, divided by M) at the first evaluation after M's factoring (m_valid bit
   1, cleared with bit 0); copied into a unless the set is of points, whose sums read it
   where it is kept (force_at) */
static void kept_force(FILE *f, const rt_sim *sim, uint16_t b, unsigned nz, int copy)
{
    const rt_mbs_work *w = &sim->work.mbs;
    unsigned zo = w->zo[b], mo = w->mo[b], ko = mo + rti_mbs_m_kept(spec_of(sim->sc, b));
    if (copy) {
        fprintf(f, "    if (w->m_valid[%u] & 2u) {\n", b);
        for (unsigned c = 0; c < nz; c++)
            fprintf(f, "        a[%u] = M[%u];\n", zo + c, ko + c);
        fputs("    } else {\n", f);
    } else {
        fprintf(f, "    if (!(w->m_valid[%u] & 2u)) {\n", b);
    }
    mbs_args(f, sim, b);
    fprintf(f, "    ((const rt_mbs_spec *)ar.spec)->force(&ar, a + %u);\n", zo);
    for (unsigned c = 0; c < nz; c++)
        fprintf(f, "    a[%u] /= M[%u];\n    w->M[%u] = a[%u];\n", zo + c, mo + c,
                ko + c, zo + c);
    fprintf(f, "    w->m_valid[%u] |= 2u;\n    }\n", b);
}

/* does an assembly for `what` keep block b's M^-1 k (kept_force): forces, and one of its
   parameters alone (a constant M then) */
static int kept_of(const rt_scene *sc, uint16_t b, int what)
{
    return (what & RTI_MBS_FORCE) && param_force(sc, b);
}

/* where a right-hand side of set s finds block b's M^-1 k: a point's kept one where it is
   kept (kept_force), else in a */
static void force_at(const rt_scene *sc, const rt_sim *sim, uint8_t s, uint16_t b,
                     const char **name, unsigned *at)
{
    const rt_mbs_work *w = &sim->work.mbs;
    int kept = w->points[s] && kept_of(sc, b, RTI_MBS_FORCE);
    *name = kept ? "M" : "a";
    *at = kept ? w->mo[b] + rti_mbs_m_kept(spec_of(sc, b)) : w->zo[b];
}

/* block b's part of the assembly (assemble_point_set; assemble_block): a varying M
   formed and factored where `what` has RTI_MBS_JAC (a constant one was at the first
   assembly), M^-1 k for RTI_MBS_FORCE (a diagonal M divided out, a dense one solved with
   its factors), the block's own rows by its constr (W's rows for RTI_MBS_JAC) */
static void block_part(FILE *f, const rt_scene *sc, const rt_sim *sim, uint8_t s, uint16_t b,
                       int what)
{
    const rt_mbs_work *w = &sim->work.mbs;
    const rt_mbs_spec *sp = spec_of(sc, b);
    unsigned zo = w->zo[b], mo = w->mo[b];
    int mass = (what & RTI_MBS_JAC) && !(sp->flags & RT_MBS_M_CONST);
    int force = what & RTI_MBS_FORCE, dense = dense_m(sc, b), kept = kept_of(sc, b, what);
    if (!mass && !force && sp->nc == 0)
        return;
    fprintf(f, "    /* %s: %s%s */\n", sc->blocks[b].name,
            mass    ? "its M, M^-1 k"
            : kept  ? "M^-1 k of its parameters alone, kept"
            : force ? "M^-1 k (M factored at the first assembly)"
                    : "",
            sp->nc ? (mass || force ? ", its own rows" : "its own rows") : "");
    if (!kept || sp->nc)
        mbs_args(f, sim, b);
    if (mass) {
        fprintf(f, "    ((const rt_mbs_spec *)ar.spec)->mass(&ar, w->M + %u);\n", mo);
        if (dense)
            fprintf(f, "    rti_mbs_mass_factor(sim, ar.spec, %u, w->M + %u);\n"
                       "    w->m_valid[%u] = 1;\n", b, mo, b);
        else
            mass_diag(f, b, mo, sp->nz, (sp->flags & RT_MBS_M_ISO) != 0);
    }
    if (kept) {
        kept_force(f, sim, b, sp->nz, !w->points[s]);
    } else if (force) {
        if (sc->blocks[b].kind->nu > 0)
            gather(f, sim, b);
        fprintf(f, "    ((const rt_mbs_spec *)ar.spec)->force(&ar, a + %u);\n", zo);
        if (dense)
            fprintf(f, "    rti_mbs_mass_solve(ar.spec, w->M + %u, a + %u);\n", mo, zo);
        for (unsigned c = 0; c < sp->nz && !dense; c++)
            fprintf(f, "    a[%u] /= M[%u];\n", zo + c, mo + c);
    }
    if (sp->nc == 0)
        return;
    fprintf(f, "    ((const rt_mbs_spec *)ar.spec)->constr(&ar, g + %u, gd + %u, ", w->co[b],
            w->co[b]);
    if (what & RTI_MBS_JAC)
        fprintf(f, "W + %u, %u, gam + %u);\n", w->wo[b], sp->nz, w->co[b]);
    else
        fprintf(f, "0, %u, gam + %u);\n", sp->nz, w->co[b]);
}

/* every block's part, in block order; in a set of points those whose M^-1 k is kept
   last, behind one test of their m_valid bits 1 (each block's part is its own: the
   order changes no value) */
static void forces(FILE *f, const rt_scene *sc, const rt_sim *sim, uint8_t s, int what)
{
    const rt_mbs_work *w = &sim->work.mbs;
    int group = w->points[s] && (what & RTI_MBS_FORCE), nkept = 0;
    for (uint16_t k = w->sb[s]; k < w->sb[s + 1]; k++)
        if (!group || !kept_of(sc, w->sblk[k], what))
            block_part(f, sc, sim, s, w->sblk[k], what);
        else
            nkept++;
    if (nkept == 0)
        return;
    fputs("    if (!(2u", f); /* (every kept one's m_valid bit 1: one branch) */
    for (uint16_t k = w->sb[s]; k < w->sb[s + 1]; k++)
        if (kept_of(sc, w->sblk[k], what))
            fprintf(f, " & w->m_valid[%u]", w->sblk[k]);
    fputs(")) {\n", f);
    for (uint16_t k = w->sb[s]; k < w->sb[s + 1]; k++)
        if (kept_of(sc, w->sblk[k], what))
            block_part(f, sc, sim, s, w->sblk[k], what);
    fputs("    }\n", f);
}

/* point_rows (rt/mbs_asm.c) of joint ji between two points (point nodes or an anchor)
   for `what` (RTI_MBS_JAC, _FORCE, _G): g by g_points alone for RTI_MBS_G where the kind
   has it, else its eval_points (a spherical difference joint's equations inline) and
   of g, g' and gam the ones `rows` asks for (W with RTI_MBS_JAC) */
static void point_joint(FILE *f, const rt_scene *sc, const rt_sim *sim, uint16_t ji, int what,
                        int rows)
{
    const rt_mbs_work *w = &sim->work.mbs;
    const rt_joint *j = &sc->joints[ji];
    int one = j->b2 < 0, same = j->b2 == j->b1, sphdiff = j->kind == &rt_joint_sphdiff;
    fputs("    {\n", f);
    if (one) /* the velocity of an anchor, and the origin */
        fputs("        static const real_t zero[3] = {0, 0, 0};\n", f);
    fprintf(f, "        const real_t *r1 = x + %u, *v1 = r1 + 3;\n", sim->plan.x_off[j->b1]);
    if (one && j->at) /* the anchor, at rest */
        fprintf(f, "        const real_t *r2 = joints[%u].at, *v2 = zero;\n", ji);
    else if (one) /* the origin */
        fputs("        const real_t *r2 = zero, *v2 = zero;\n", f);
    else
        fprintf(f, "        const real_t *r2 = x + %u, *v2 = r2 + 3;\n", sim->plan.x_off[j->b2]);
    if (what == RTI_MBS_G && j->kind->g_points) {
        fputs("        (void)v1, (void)v2;\n", f);
        if (sphdiff)
            fprintf(f, "        rti_sphdiff_g(joints[%u].p, r1, r2, g + %u);\n    }\n", ji,
                    w->jrow[ji]);
        else
            fprintf(f, "        joints[%u].kind->g_points(joints[%u].p, r1, r2, g + %u);\n"
                       "    }\n", ji, ji, w->jrow[ji]);
        return;
    }
    if (sphdiff) /* the kind's own equations, inline (rt/rti_joints.h) */
        fprintf(f, "        rti_sphdiff_points(joints[%u].p, r1, v1, r2, v2, &e);\n", ji);
    else
        fprintf(f, "        joints[%u].kind->eval_points(joints[%u].p, r1, v1, r2, v2, &e);\n",
                ji, ji);
    for (unsigned i = 0; i < j->kind->nc; i++) {
        unsigned r = w->jrow[ji] + i, w1 = w->jw[ji][0] + 3 * i;
        unsigned w2 = (one ? w->jw[ji][0] : w->jw[ji][1]) + 3 * i;
        fprintf(f, "        C = e.C[%u];\n", i);
        if (rows & ROW_G)
            fprintf(f, "        g[%u] = e.g[%u];\n", r, i);
        if (rows & ROW_GD)
            fprintf(f, "        acc = 0;\n"
                       "        acc += C[0] * v1[0] + C[6] * v2[0];\n"
                       "        acc += C[1] * v1[1] + C[7] * v2[1];\n"
                       "        acc += C[2] * v1[2] + C[8] * v2[2];\n"
                       "        gd[%u] = acc;\n", r);
        if (!(what & RTI_MBS_JAC))
            continue;
        if (rows & ROW_GAM)
            fprintf(f, "        gam[%u] = (real_t)0 + e.c[%u];\n", r, i);
        fprintf(f, "        W[%u] = C[0], W[%u] = C[1], W[%u] = C[2];\n", w1, w1 + 1, w1 + 2);
        if (one)
            continue;
        if (same)
            fprintf(f, "        W[%u] += C[6], W[%u] += C[7], W[%u] += C[8];\n", w2, w2 + 1,
                    w2 + 2);
        else
            fprintf(f, "        W[%u] = C[6], W[%u] = C[7], W[%u] = C[8];\n", w2, w2 + 1, w2 + 2);
    }
    fputs("    }\n", f);
}

/* assemble_point_set (rt/mbs_asm.c) for `what` (RTI_MBS_JAC, _FORCE, _G), the rows' `rows` */
static void assemble(FILE *f, const rt_scene *sc, const rt_sim *sim, uint8_t s, int what,
                     int rows)
{
    const rt_mbs_work *w = &sim->work.mbs;
    if (what & RTI_MBS_FORCE)
        forces(f, sc, sim, s, what);
    rows_comment(f, "point_rows", what & RTI_MBS_JAC, rows);
    for (uint16_t k = w->sj[s]; k < w->sj[s + 1]; k++)
        point_joint(f, sc, sim, w->sjnt[k], what, rows);
}

/* map_row (rt/mbs_asm.c) of a body side with nz velocities: W's slice at wo (+)= the
   six coefficients from C[c0] times the node's 6 x nz Jacobian J, a zero coefficient
   skipped */
static void map_body_row(FILE *f, unsigned wo, unsigned c0, unsigned side, int add,
                         unsigned nz)
{
    for (unsigned c = 0; c < nz && !add; c++)
        fprintf(f, "        W[%u] = 0;\n", wo + c);
    for (unsigned k = 0; k < 6; k++) {
        fprintf(f, "        if (C[%u] != 0) {\n", c0 + k);
        for (unsigned c = 0; c < nz; c++)
            fprintf(f, "            W[%u] += C[%u] * J%u[%u];\n", wo + c, c0 + k, side,
                    k * nz + c);
        fputs("        }\n", f);
    }
}

/* map_row of a joint side: a point node's Jacobian [I; 0] takes the first three
   coefficients as they are, a body's goes through map_body_row */
static void map_side_row(FILE *f, unsigned wo, unsigned c0, unsigned side, int add,
                         unsigned nz, int point)
{
    if (!point) {
        map_body_row(f, wo, c0, side, add, nz);
        return;
    }
    for (unsigned c = 0; c < 3; c++)
        fprintf(f, add ? "        W[%u] += C[%u];\n" : "        W[%u] = C[%u];\n", wo + c, c0 + c);
}

/* rti_mbs_assemble of a set of bodies (mbs_bodies_set) for `what` (RTI_MBS_JAC, _FORCE,
   _G): each block's M^-1 k (its only part: no rows of its own, M factored once), then
   assemble_joint: the nodes by rti_mbs_joint (with their Jacobians for RTI_MBS_JAC), per
   row g and g' (and gam) by row_dot's sums and W's rows by map_row, term by term */
static void assemble_bodies(FILE *f, const rt_scene *sc, const rt_sim *sim, uint8_t s,
                            int what, int rows)
{
    const rt_mbs_work *w = &sim->work.mbs;
    int jac = what & RTI_MBS_JAC;
    forces(f, sc, sim, s, what);
    rows_comment(f, "assemble_joint", jac, rows);
    for (uint16_t k = w->sj[s]; k < w->sj[s + 1]; k++) {
        uint16_t ji = w->sjnt[k];
        const rt_joint *j = &sc->joints[ji];
        const char *dot = j->kind->trans ? "rowdot6" : "rowdot12";
        int p1 = point_side(sc, j, 0), p2 = point_side(sc, j, 1);
        if (j->kind->eval_points && p1 && p2) { /* assemble_points: between two points */
            point_joint(f, sc, sim, ji, what, rows);
            continue;
        }
        fputs("    {\n        rt_mbs_node n1, n2;\n"
              "        const real_t *J0 = w->J[0], *J1 = w->J[1];\n"
              "        (void)J0, (void)J1;\n", f);
        if (j->b2 >= 0 && !j->axis_S && !p1 && !p2) { /* rti_mbs_joint: both by their kinds */
            fputs("    ", f), mbs_args(f, sim, (uint16_t)j->b1);
            fprintf(f, "        ((const rt_mbs_spec *)ar.spec)->node(&ar, %u, &n1, %s);\n",
                    j->n1, jac ? "w->J[0]" : "0");
            fputs("    ", f), mbs_args(f, sim, (uint16_t)j->b2);
            fprintf(f, "        ((const rt_mbs_spec *)ar.spec)->node(&ar, %u, &n2, %s);\n",
                    j->n2, jac ? "w->J[1]" : "0");
            fprintf(f, "        joints[%u].kind->eval(joints[%u].p, &n1, &n2, &e);\n", ji, ji);
        } else
            fprintf(f, "        rti_mbs_joint(sc, sim, %u, t, &n1, &n2, %s, &e);\n", ji,
                    jac ? "w->J[0], w->J[1]" : "0, 0");
        for (unsigned i = 0; i < j->kind->nc; i++) {
            unsigned r = w->jrow[ji] + i;
            fprintf(f, "        C = e.C[%u];\n", i);
            if (rows & ROW_G)
                fprintf(f, "        g[%u] = e.g[%u];\n", r, i);
            if (rows & ROW_GD)
                fprintf(f, "        gd[%u] = %s(C, n1.v, n1.w, n2.v, n2.w);\n", r, dot);
            if (!jac)
                continue;
            if (rows & ROW_GAM)
                fprintf(f, "        gam[%u] = %s(C, n1.ar, n1.aw, n2.ar, n2.aw) + e.c[%u];\n",
                        r, dot, i);
            unsigned nz1 = nz_of(sim, (uint16_t)j->b1);
            map_side_row(f, w->jw[ji][0] + nz1 * i, 0, 0, 0, nz1, p1);
            if (j->b2 >= 0) {
                unsigned nz2 = nz_of(sim, (uint16_t)j->b2);
                map_side_row(f, w->jw[ji][1] + nz2 * i, 6, 1, j->b2 == j->b1, nz2, p2);
            }
        }
        fputs("    }\n", f);
    }
}

/* the entries of M^-1 W^T: of a diagonal M, q = W / M entry by entry (the quotients
   rti_mbs_schur and rti_mbs_correct divide for every term, each formed once: the same
   bits); of a dense M, schur_block's Y, each touch's row of W solved with M's factors */
static void quotients(FILE *f, const rt_scene *sc, const rt_sim *sim, uint8_t s)
{
    const rt_mbs_work *w = &sim->work.mbs;
    if (w->points[s]) /* M = m I: 1/m in the sums (point_shares, rti_mbs_correct) */
        return;
    fputs("    /* M^-1 W^T, entry by entry */\n", f);
    for (uint16_t k = w->sb[s]; k < w->sb[s + 1]; k++) {
        uint16_t b = w->sblk[k];
        unsigned mo = w->mo[b], nz = nz_of(sim, b), nt = (unsigned)(w->to[b + 1] - w->to[b]);
        for (unsigned i = 0, wi = w->wo[b], yi = w->yo[b]; i < nt && dense_m(sc, b);
             i++, wi += nz, yi += nz) {
            for (unsigned c = 0; c < nz; c++)
                fprintf(f, "    Y[%u] = W[%u];\n", yi + c, wi + c);
            fprintf(f, "    rti_mbs_mass_solve(blocks[%u].kind->spec, w->M + %u, Y + %u);\n", b,
                    mo, yi);
        }
        for (unsigned i = 0, wi = w->wo[b]; i < nt && !dense_m(sc, b); i++, wi += nz)
            for (unsigned c = 0; c < nz; c++)
                fprintf(f, "    q[%u] = W[%u] / M[%u];\n", wi + c, wi + c, mo + c);
    }
}

/* rti_mbs_schur for points: the slots cleared, each block's shares (point_shares: C.C
   and W_i . W_k times 1/m) */
static void schur(FILE *f, const rt_sim *sim, uint8_t s)
{
    const rt_mbs_work *w = &sim->work.mbs;
    fputs("    /* A = W M^-1 W^T into the pattern's slots (rti_mbs_schur) */\n", f);
    for (unsigned i = w->rb[s]; i < w->rb[s + 1]; i++)
        fputs("    ", f), slot(f, i), fputs(" = 0;\n", f);
    for (unsigned e = w->lp[w->rb[s]]; e < w->lp[w->rb[s + 1]]; e++)
        fputs("    ", f), slot(f, RT_MAX_MBS_ROWS + e), fputs(" = 0;\n", f);
    for (uint16_t k = w->sb[s]; k < w->sb[s + 1]; k++) {
        uint16_t b = w->sblk[k];
        unsigned nt = (unsigned)(w->to[b + 1] - w->to[b]), wo = w->wo[b], nz = nz_of(sim, b);
        unsigned inv = w->mo[b] + rti_mbs_m_inv(spec_of(sim->sc, b)); /* 1/m (points) */
        const uint16_t *ps = w->pslot + w->po[b];
        for (unsigned i = 0; i < nt && w->points[s]; i++)
            for (unsigned kk = i; kk < nt; kk++) {
                fputs("    ", f);
                slot(f, *ps++);
                if (kk == i) /* 1/m after M (rti_mbs_m_inv) */
                    fprintf(f, " += (W[%u] * W[%u] + W[%u] * W[%u] + W[%u] * W[%u]) * M[%u];\n",
                            wo + 3 * i, wo + 3 * i, wo + 3 * i + 1, wo + 3 * i + 1,
                            wo + 3 * i + 2, wo + 3 * i + 2, inv);
                else
                    fprintf(f, " += dot3(W + %u, W + %u) * M[%u];\n", wo + 3 * i,
                            wo + 3 * kk, inv);
            }
        for (unsigned i = 0; i < nt && !w->points[s]; i++)
            for (unsigned kk = i; kk < nt; kk++) {
                const char *y;
                unsigned at;
                y_of(sim->sc, sim, b, kk, &y, &at);
                fputs("    ", f);
                slot(f, *ps++);
                if (nz == 3)
                    fprintf(f, " += dot3(W + %u, %s + %u);\n", wo + 3 * i, y, at);
                else
                    fprintf(f, " += dotn(W + %u, %s + %u, %u);\n", wo + nz * i, y, at, nz);
            }
    }
}

/* row i's elimination of rti_mbs_ldl_factor (rows lp, columns lj): with `sure` every row
   before it kept its pivot (above its floor, so nonzero), and the tests for a dropped
   row's zero pivot are left out (the same operations where they pass) */
static void factor_row(FILE *f, const uint16_t *lp, const uint16_t *lj, unsigned i, int sure)
{
    unsigned e0 = lp[i], e1 = lp[i + 1];
    fprintf(f, "        d = D[%u];\n", i);
    fputs("        floor_ = RT_MBS_PIVOT_TOL * (d > low ? d : low);\n", f);
    for (unsigned e = e0; e < e1; e++) {
        unsigned j = lj[e];
        fprintf(f, "        tt = L[%u];\n", e);
        for (unsigned q = lp[j], q1 = e > e0 ? lp[j + 1] : q; q < q1; q++)
            fprintf(f, "        tt -= L[%u] * u[%u];\n", q, lj[q]);
        if (sure)
            fprintf(f, "        u[%u] = tt;\n        L[%u] = tt / D[%u];\n", j, e, j);
        else
            fprintf(f, "        u[%u] = D[%u] != 0 ? tt : 0;\n"
                       "        L[%u] = D[%u] != 0 ? tt / D[%u] : 0;\n", j, j, e, j, j);
        fprintf(f, "        d -= L[%u] * u[%u];\n", e, j);
    }
    for (unsigned e = e0; e < e1; e++)
        fprintf(f, "        u[%u] = 0;\n", lj[e]);
    if (i == 0 && sure) /* (called once: the generic row 0 is entered past it) */
        fputs("        if (rti_fault_due(RTI_FAULT_SINGULAR))\n"
              "            d = -big - 1;\n", f);
}

/* rti_mbs_ldl_factor over the set's fixed pattern, then rti_mbs_schur's counts. Rows
   first as long as each keeps its pivot (one comparison, no test of an earlier pivot for
   zero: factor_row's sure path); the first that does not is judged by the generic tests
   and the rows after it eliminated with them (the same outcomes and operations: d >
   floor_ is neither within +-floor_ nor below it, and a kept pivot is nonzero) */
static void factor(FILE *f, const rt_sim *sim, uint8_t s)
{
    static unsigned nfactor; /* labels unique in the generated file */
    const rt_mbs_work *w = &sim->work.mbs;
    unsigned base = w->rb[s], n = w->rb[s + 1] - base;
    const uint16_t *lp = w->lp + base, *lj = w->lj, *perm = w->perm + base;
    fputs("    /* its L D L^T over the pattern found at init (rti_mbs_ldl_factor) */\n", f);
    fprintf(f, "    {\n        real_t *D = lv + %u, u[%u], big = 0, d, tt;\n", base, n);
    fprintf(f, "        uint16_t deficit = w->ndrop[%u], drop = 0;\n", s);
    fputs("        int bad = -1;\n        (void)u, (void)tt; /* (a single row eliminates nothing) */\n", f);
    for (unsigned i = 0; i < n; i++)
        fprintf(f, "        big = D[%u] > big ? D[%u] : big;\n", i, i);
    for (unsigned i = 0; i < n; i++)
        fprintf(f, "        u[%u] = 0;\n", i);
    fputs("        real_t low = RT_MBS_PIVOT_TOL * (big > 0 ? big : 1), floor_;\n", f);
    fprintf(f, "        w->drop_row[%u] = 0;\n", s);
    unsigned id = nfactor++;
    for (unsigned i = 0; i < n; i++) {
        factor_row(f, lp, lj, i, 1);
        fprintf(f, "        if (!(d > floor_))\n            goto judge%u_%u;\n        D[%u] = d;\n",
                id, i, i);
    }
    fprintf(f, "        goto kept%u;\n", id);
    for (unsigned i = 0; i < n; i++) {
        if (i > 0) /* (row 0 is entered at its judgement only) */
            factor_row(f, lp, lj, i, 0);
        fprintf(f, "    judge%u_%u:\n", id, i);
        fprintf(f, "        if (!(d > floor_)) {\n"
                   "            if (d >= -floor_)\n"
                   "                w->drop_row[%u] = drop++ ? w->drop_row[%u] : %u, d = 0;\n"
                   "            else\n"
                   "                bad = bad < 0 ? %u : bad, d = floor_;\n"
                   "        }\n"
                   "        D[%u] = d;\n", s, s, perm[i], perm[i], i);
    }
    fprintf(f, "    kept%u:\n        w->ndrop[%u] = drop;\n", id, s);
    fprintf(f, "        if (bad >= 0)\n"
               "            rti_count(sim, RT_CNT_SINGULAR, rti_mbs_row_block(sc, sim, %u, "
               "(uint16_t)bad), RT_E_SINGULAR);\n", s);
    fprintf(f, "        if (w->ndrop[%u] != deficit && w->ndrop[%u] > 0)\n"
               "            rti_count(sim, RT_CNT_REDUNDANT, rti_mbs_row_block(sc, sim, %u, "
               "w->drop_row[%u]), RT_OK);\n    }\n", s, s, s, s);
}

/* rti_mbs_ldl_solve of the set's rows into v, a conflict counted as rti_mbs_solve does.
   With no row dropped every pivot is nonzero (a dropped row's alone is 0): the division
   without its test, and no conflict to look for */
static void solve(FILE *f, const rt_sim *sim, uint8_t s, const char *v)
{
    const rt_mbs_work *w = &sim->work.mbs;
    unsigned base = w->rb[s], n = w->rb[s + 1] - base;
    const uint16_t *lp = w->lp + base, *lj = w->lj, *perm = w->perm + base;
    fprintf(f, "    {\n        const real_t *D = lv + %u;\n        real_t y[%u], scale = 0, tt;\n",
            base, n);
    fputs("        int conflict = -1;\n", f);
    fprintf(f, "        if (w->ndrop[%u]) {\n", s);
    for (unsigned i = 0; i < n; i++)
        fprintf(f, "            scale = rt_fmax(scale, rt_fabs(%s[%u]));\n", v, i);
    fputs("        }\n", f);
    for (unsigned i = 0; i < n; i++) {
        fprintf(f, "        tt = %s[%u];\n", v, perm[i]);
        for (unsigned e = lp[i]; e < lp[i + 1]; e++)
            fprintf(f, "        tt -= L[%u] * y[%u];\n", e, lj[e]);
        fprintf(f, "        y[%u] = tt;\n", i);
    }
    fprintf(f, "        if (!w->ndrop[%u]) {\n", s);
    for (unsigned i = 0; i < n; i++)
        fprintf(f, "            y[%u] /= D[%u];\n", i, i);
    fputs("        } else {\n", f);
    for (unsigned i = 0; i < n; i++)
        fprintf(f, "        if (D[%u] != 0)\n            y[%u] /= D[%u];\n        else {\n"
                   "            if (!(rt_fabs(y[%u]) <= RT_MBS_RES_TOL + RT_MBS_RANK_TOL * scale)"
                   " && conflict < 0)\n                conflict = %u;\n"
                   "            y[%u] = 0;\n        }\n", i, i, i, i, perm[i], i);
    fputs("        }\n", f);
    for (unsigned i = n; i-- > 0;) {
        fprintf(f, "        tt = y[%u];\n", i);
        for (unsigned e = lp[i]; e < lp[i + 1]; e++)
            fprintf(f, "        y[%u] -= L[%u] * tt;\n", lj[e], e);
        fprintf(f, "        %s[%u] = tt;\n", v, perm[i]);
    }
    fprintf(f, "        if (conflict >= 0)\n"
               "            rti_count(sim, RT_CNT_SINGULAR, rti_mbs_row_block(sc, sim, %u, "
               "(uint16_t)conflict), RT_E_SINGULAR);\n    }\n", s);
}

/* rti_mbs_correct of a set of points: dz = -M^-1 W^T v into a, added to it if add (a
   set of points adds to its M^-1 k where force_at finds it and writes z' into xdot,
   which rti_mbs_accel copies from a); without add a point's dz is added to its
   x[from .. from + 3) at once (rt/mbs_project.c points_add: the same sums; from is read
   for a set of points alone) */
static void correct(FILE *f, const rt_sim *sim, uint8_t s, const char *v, int add, int from)
{
    const rt_mbs_work *w = &sim->work.mbs;
    for (uint16_t k = w->sb[s]; k < w->sb[s + 1]; k++) {
        uint16_t b = w->sblk[k];
        unsigned zo = w->zo[b], nz = nz_of(sim, b);
        if (nz != 3 || dense_m(sim->sc, b)) { /* rti_mbs_correct's loops over the block's
                                                  nz velocities */
            for (unsigned c = 0; c < nz && !add; c++)
                fprintf(f, "    a[%u] = 0;\n", zo + c);
            for (unsigned i = w->to[b]; i < w->to[b + 1]; i++) {
                const char *y;
                unsigned at;
                y_of(sim->sc, sim, b, i - w->to[b], &y, &at);
                fprintf(f, "    vi = %s[%u];\n", v, w->trow[i]);
                for (unsigned c = 0; c < nz; c++)
                    fprintf(f, "    a[%u] -= %s[%u] * vi;\n", zo + c, y, at + c);
            }
            continue;
        }
        const char *src;
        unsigned at;
        force_at(sim->sc, sim, s, b, &src, &at);
        if (add)
            fprintf(f, "    d0 = %s[%u], d1 = %s[%u], d2 = %s[%u];\n", src, at, src, at + 1,
                    src, at + 2);
        else
            fputs("    d0 = 0, d1 = 0, d2 = 0;\n", f);
        const char *y = w->points[s] ? "W" : "q"; /* points: v times 1/m (M = m I) */
        for (unsigned i = w->to[b], wi = w->wo[b]; i < w->to[b + 1]; i++, wi += 3) {
            if (w->points[s])
                fprintf(f, "    vi = %s[%u] * M[%u];\n", v, w->trow[i],
                        w->mo[b] + rti_mbs_m_inv(spec_of(sim->sc, b)));
            else
                fprintf(f, "    vi = %s[%u];\n", v, w->trow[i]);
            fprintf(f, "    d0 -= %s[%u] * vi;\n", y, wi);
            fprintf(f, "    d1 -= %s[%u] * vi;\n", y, wi + 1);
            fprintf(f, "    d2 -= %s[%u] * vi;\n", y, wi + 2);
        }
        if (!w->points[s]) {
            fprintf(f, "    a[%u] = d0, a[%u] = d1, a[%u] = d2;\n", zo, zo + 1, zo + 2);
        } else if (add) {
            unsigned q = sim->plan.x_off[b] - sim->plan.set_x[s] + 3;
            fprintf(f, "    xdot[%u] = d0, xdot[%u] = d1, xdot[%u] = d2;\n", q, q + 1, q + 2);
        } else { /* points_add of this point, at once */
            unsigned xo = sim->plan.x_off[b] + (unsigned)from;
            fprintf(f, "    xw[%u] += d0, xw[%u] += d1, xw[%u] += d2;\n", xo, xo + 1, xo + 2);
        }
    }
}

/* rti_mbs_accel's q' = K z + b (the kind's kin and kinb) and z' for a set of bodies */
static void kinematics(FILE *f, const rt_scene *sc, const rt_sim *sim, uint8_t s)
{
    const rt_mbs_work *w = &sim->work.mbs;
    fputs("    /* q' = K z + b, z' */\n", f);
    for (uint16_t k = w->sb[s]; k < w->sb[s + 1]; k++) {
        uint16_t b = w->sblk[k];
        const rt_mbs_spec *sp = spec_of(sc, b);
        unsigned xo = sim->plan.x_off[b], q = xo - sim->plan.set_x[s], zo = w->zo[b];
        if (sp->flags & RT_MBS_NODE_POINT) { /* a point: copies, no call */
            fprintf(f, "    xdot[%u] = x[%u], xdot[%u] = x[%u], xdot[%u] = x[%u];\n", q, xo + 3,
                    q + 1, xo + 4, q + 2, xo + 5);
            fprintf(f, "    xdot[%u] = a[%u], xdot[%u] = a[%u], xdot[%u] = a[%u];\n", q + 3, zo,
                    q + 4, zo + 1, q + 5, zo + 2);
            continue;
        }
        mbs_args(f, sim, b);
        fprintf(f, "    ((const rt_mbs_spec *)ar.spec)->kin(&ar, ar.x + %u, xdot + %u);\n",
                sp->nq, q);
        if (sp->kinb) {
            fprintf(f, "    ((const rt_mbs_spec *)ar.spec)->kinb(&ar, w->qt + %u);\n", w->qo[b]);
            for (unsigned i = 0; i < sp->nq; i++)
                fprintf(f, "    xdot[%u] += w->qt[%u];\n", q + i, w->qo[b] + i);
        }
        for (unsigned c = 0; c < sp->nz; c++)
            fprintf(f, "    xdot[%u] = a[%u];\n", q + sp->nq + c, zo + c);
    }
}

/* rti_mbs_lambda's right side, solve and z' (rti_mbs_correct, add), then rti_mbs_accel's
   q' = v, v' = a for points, kinematics for bodies */
static void lambda_accel(FILE *f, const rt_scene *sc, const rt_sim *sim, uint8_t s)
{
    const rt_mbs_work *w = &sim->work.mbs;
    fputs("    /* A lambda = W M^-1 k + gam (eq. 7b), in gam */\n", f);
    if (sc->stab == RT_STAB_BAUMGARTE)
        for (unsigned r = 0; r < w->nc[s]; r++)
            fprintf(f, "    gam[%u] += sc->baumgarte[0] * gd[%u] + sc->baumgarte[1] * g[%u];\n",
                    r, r, r);
    for (uint16_t k = w->sj[s]; k < w->sj[s + 1] && w->points[s]; k++) {
        /* point_accels: C . (a1 - a2) per row */
        uint16_t ji = w->sjnt[k];
        const rt_joint *j = &sc->joints[ji];
        const char *s1, *s2;
        unsigned at1, at2;
        force_at(sc, sim, s, (uint16_t)j->b1, &s1, &at1);
        for (unsigned i = 0; i < j->kind->nc; i++) {
            unsigned r = w->jrow[ji] + i, w1 = w->jw[ji][0] + 3 * i;
            if (j->b2 < 0) {
                fprintf(f, "    gam[%u] += dot3(W + %u, %s + %u);\n", r, w1, s1, at1);
                continue;
            }
            force_at(sc, sim, s, (uint16_t)j->b2, &s2, &at2);
            fprintf(f, "    d0 = %s[%u] - %s[%u], d1 = %s[%u] - %s[%u], d2 = %s[%u] - %s[%u];\n",
                    s1, at1, s2, at2, s1, at1 + 1, s2, at2 + 1, s1, at1 + 2, s2, at2 + 2);
            fprintf(f, "    acc = 0;\n    acc += W[%u] * d0;\n    acc += W[%u] * d1;\n"
                       "    acc += W[%u] * d2;\n    gam[%u] += acc;\n", w1, w1 + 1, w1 + 2, r);
        }
    }
    for (uint16_t k = w->sb[s]; k < w->sb[s + 1] && !w->points[s]; k++) {
        uint16_t b = w->sblk[k];
        unsigned nz = nz_of(sim, b);
        for (unsigned i = w->to[b], wi = w->wo[b]; i < w->to[b + 1]; i++, wi += nz)
            if (nz == 3)
                fprintf(f, "    gam[%u] += dot3(W + %u, a + %u);\n", w->trow[i], wi,
                        w->zo[b]);
            else
                fprintf(f, "    gam[%u] += dotn(W + %u, a + %u, %u);\n", w->trow[i], wi,
                        w->zo[b], nz);
    }
    solve(f, sim, s, "gam");
    fputs("    /* z' = M^-1 k - M^-1 W^T lambda, into a */\n", f);
    correct(f, sim, s, "gam", 1, -1); /* (points: into xdot) */
    if (w->need_lambda) {
        fputs("    /* the joints' multipliers, read by a reaction */\n", f);
        for (uint16_t k = w->sj[s]; k < w->sj[s + 1]; k++) {
            uint16_t j = w->sjnt[k];
            for (unsigned i = 0; i < sc->joints[j].kind->nc; i++)
                fprintf(f, "    w->jlam[%u] = gam[%u];\n", w->jlo[j] + i, w->jrow[j] + i);
        }
    }
    if (!w->points[s]) {
        kinematics(f, sc, sim, s);
        return;
    }
    fputs("    /* q' = v (v' = z' is in xdot) */\n", f);
    for (uint16_t k = w->sb[s]; k < w->sb[s + 1]; k++) {
        uint16_t b = w->sblk[k];
        unsigned xo = sim->plan.x_off[b], q = xo - sim->plan.set_x[s];
        fprintf(f, "    xdot[%u] = x[%u], xdot[%u] = x[%u], xdot[%u] = x[%u];\n", q, xo + 3,
                q + 1, xo + 4, q + 2, xo + 5);
    }
}

/* the locals of a written-out multibody part and its guard: every point's M factored */
static void locals(FILE *f, const rt_sim *sim, uint8_t s)
{
    const rt_mbs_work *w = &sim->work.mbs;
    fputs("    rt_mbs_work *w = &sim->work.mbs;\n"
          "    real_t *lv = w->lv, *L = lv + RT_MAX_MBS_ROWS, *a = w->a, *Y = w->Y;\n"
          "    real_t *g = w->g, *gd = w->gd, *gam = w->gam, *xw = sim->state.x;\n"
          "    const real_t *M = w->M, *x = xw, *C;\n"
          "    real_t acc, d0, d1, d2, vi;\n"
          "    rt_joint_eval e;\n"
          "    (void)L, (void)g, (void)gd, (void)gam, (void)xw, (void)x, (void)sc, (void)t, (void)acc;\n"
          "    (void)Y, (void)a;\n"
          "    (void)M;\n"
          "    (void)d0, (void)d1, (void)d2;\n", f);
    unsigned nq = 0;
    for (uint16_t k = w->sb[s]; k < w->sb[s + 1]; k++) {
        uint16_t b = w->sblk[k];
        unsigned end = w->wo[b] + nz_of(sim, b) * (unsigned)(w->to[b + 1] - w->to[b]);
        nq = end > nq ? end : nq;
    }
    if (w->points[s]) /* W formed and read within the call; 1/m, no quotients */
        fprintf(f, "    real_t W[%u];\n", nq ? nq : 1);
    else
        fprintf(f, "    real_t *W = w->W, q[%u]; /* M^-1 W^T (quotients) */\n    (void)q;\n",
                nq ? nq : 1);
    fputs("    if (!((", f); /* (bit 0 of every block's m_valid: one branch) */
    for (uint16_t k = w->sb[s]; k < w->sb[s + 1]; k++)
        fprintf(f, "%sw->m_valid[%u]", k > w->sb[s] ? " & " : "", w->sblk[k]);
    fputs(") & 1u))\n        return 0; /* the first assembly factors M: the generic path */\n", f);
}

/* the set's assembly (`what`: RTI_MBS_JAC, with RTI_MBS_FORCE for a right-hand side; the
   rows' `rows`) and the factors of its Schur complement over the fixed pattern */
static void factored(FILE *f, const rt_scene *sc, const rt_sim *sim, uint8_t s, int what,
                     int rows)
{
    if (sim->work.mbs.points[s])
        assemble(f, sc, sim, s, what, rows);
    else
        assemble_bodies(f, sc, sim, s, what, rows);
    quotients(f, sc, sim, s);
    schur(f, sim, s);
    factor(f, sim, s);
}

/* save_q (rt/mbs_project.c): the coordinates of every body whose K depends on them,
   frozen in qt for the projection's position iterations */
static void saved_q(FILE *f, const rt_scene *sc, const rt_sim *sim, uint8_t s)
{
    const rt_mbs_work *w = &sim->work.mbs;
    for (uint16_t k = w->sb[s]; k < w->sb[s + 1] && !w->points[s]; k++) {
        uint16_t b = w->sblk[k];
        const rt_mbs_spec *sp = spec_of(sc, b);
        for (unsigned i = 0; i < sp->nq && !(sp->flags & RT_MBS_K_CONST); i++)
            fprintf(f, "    w->qt[%u] = xw[%u];\n", w->qo[b] + i, sim->plan.x_off[b] + i);
    }
}

/* move_q and move_z (rt/mbs_project.c) of a set of bodies: q += K dz by the kind's kin
   (K at the frozen coordinates if it depends on them), or z += dz */
static void bodies_add(FILE *f, const rt_scene *sc, const rt_sim *sim, uint8_t s, int vel)
{
    const rt_mbs_work *w = &sim->work.mbs;
    for (uint16_t k = w->sb[s]; k < w->sb[s + 1]; k++) {
        uint16_t b = w->sblk[k];
        const rt_mbs_spec *sp = spec_of(sc, b);
        unsigned xo = sim->plan.x_off[b], zo = w->zo[b];
        if (vel) {
            for (unsigned c = 0; c < sp->nz; c++)
                fprintf(f, "    xw[%u] += a[%u];\n", xo + sp->nq + c, zo + c);
            continue;
        }
        fprintf(f, "    {\n        real_t dq[%u];\n    ", sp->nq);
        mbs_args(f, sim, b);
        if (!(sp->flags & RT_MBS_K_CONST))
            fprintf(f, "        ar.x = w->qt + %u;\n", w->qo[b]);
        fprintf(f, "        ((const rt_mbs_spec *)ar.spec)->kin(&ar, a + %u, dq);\n", zo);
        for (unsigned i = 0; i < sp->nq; i++)
            fprintf(f, "        xw[%u] += dq[%u];\n", xo + i, i);
        fputs("    }\n", f);
    }
}

/* one correction of the projection: the solve for residual v ("g" or "gd"), the change
   of the coordinates it gives, added to the positions (vel 0) or the velocities (1) */
static void corrected(FILE *f, const rt_scene *sc, const rt_sim *sim, uint8_t s,
                      const char *v, int vel)
{
    solve(f, sim, s, v);
    if (sim->work.mbs.points[s]) { /* each point's correction added where it is formed */
        correct(f, sim, s, v, 0, vel ? 3 : 0);
        return;
    }
    correct(f, sim, s, v, 0, -1);
    bodies_add(f, sc, sim, s, vel);
}

/* the kinds' own normalization after the positions (rt/mbs_project.c normalize) */
static void normalized(FILE *f, const rt_scene *sc, const rt_sim *sim, uint8_t s)
{
    const rt_mbs_work *w = &sim->work.mbs;
    for (uint16_t k = w->sb[s]; k < w->sb[s + 1] && !w->points[s]; k++) {
        uint16_t b = w->sblk[k];
        if (spec_of(sc, b)->normalize)
            fprintf(f, "    ((const rt_mbs_spec *)blocks[%u].kind->spec)->normalize(xw + %u);\n",
                    b, sim->plan.x_off[b]);
    }
}

/* a set whose projection the generator writes out (RT_STAB_PROJECT): points or bodies */
static int project_set(const rt_scene *sc, const rt_sim *sim, uint8_t s)
{
    return sc->stab == RT_STAB_PROJECT &&
           (mbs_points_set(sc, sim, s) || mbs_bodies_set(sc, sim, s));
}

/* the right-hand side of a set (rti_rhs): outputs, derivatives, rti_mbs_accel (written
   out for points, else the generic service) */
static void rhs_points(FILE *f, const rt_scene *sc, const rt_sim *sim, uint8_t s)
{
    const rt_mbs_work *w = &sim->work.mbs;
    int mbs = sc->mbs && w->nz[s] > 0, pts = mbs && mbs_points_set(sc, sim, s);
    int bodies = mbs && mbs_bodies_set(sc, sim, s);
    fprintf(f, "\n/* set %s: rti_rhs", sc->sets[s].name);
    if (pts)
        fprintf(f, ", rti_mbs_accel of its %u points and %u constraint rows",
                (unsigned)(w->sb[s + 1] - w->sb[s]), (unsigned)w->nc[s]);
    else if (bodies)
        fprintf(f, ", rti_mbs_accel of its %u bodies and %u constraint rows",
                (unsigned)(w->sb[s + 1] - w->sb[s]), (unsigned)w->nc[s]);
    else if (mbs)
        fputs(", its multibody part by the generic rti_mbs_accel", f);
    fprintf(f, " */\nstatic int rhs_%u(const rt_scene *sc, rt_sim *sim, real_t t, real_t h, "
               "real_t *restrict xdot)\n{\n", s);
    fputs("    real_t *u = sim->work.u, *y = sim->state.y;\n    rt_args ar;\n"
          "    (void)sc, (void)u, (void)y, (void)ar, (void)t, (void)h, (void)xdot;\n", f);
    if (pts || bodies)
        locals(f, sim, s);
    outputs(f, sc, sim, s);
    derivs(f, sc, sim, s);
    if (pts) {
        factored(f, sc, sim, s, RTI_MBS_JAC | RTI_MBS_FORCE, accel_rows(sc));
        lambda_accel(f, sc, sim, s);
    } else if (bodies) {
        factored(f, sc, sim, s, RTI_MBS_JAC | RTI_MBS_FORCE, accel_rows(sc));
        lambda_accel(f, sc, sim, s);
    } else if (mbs)
        fprintf(f, "    sc->mbs->accel(sc, sim, %u, t, xdot);\n", s);
    fputs("    return 1;\n}\n", f);
}

/* rti_mbs_project of a set of points or bodies (project_set): positions (two
   iterations), velocities, check_residual, refresh_lambda */
static void project_points(FILE *f, const rt_scene *sc, const rt_sim *sim, uint8_t s)
{
    const rt_mbs_work *w = &sim->work.mbs;
    fprintf(f, "\n/* set %s: rti_mbs_project (eq. 10) */\n", sc->sets[s].name);
    fprintf(f, "static int project_%u(const rt_scene *sc, rt_sim *sim, real_t t)\n{\n", s);
    fputs("    real_t *u = sim->work.u, *y = sim->state.y;\n    rt_args ar;\n"
          "    (void)u, (void)y, (void)ar;\n", f);
    locals(f, sim, s);
    fputs("    /* positions (10a) */\n", f);
    saved_q(f, sc, sim, s);
    factored(f, sc, sim, s, RTI_MBS_JAC, ROW_G);
    corrected(f, sc, sim, s, "g", 0);
    if (sim->work.mbs.points[s])
        assemble(f, sc, sim, s, RTI_MBS_G, ROW_G);
    else
        assemble_bodies(f, sc, sim, s, RTI_MBS_G, ROW_G);
    corrected(f, sc, sim, s, "g", 0);
    normalized(f, sc, sim, s);
    fputs("    /* velocities (10b) */\n", f);
    factored(f, sc, sim, s, RTI_MBS_JAC, ROW_G | ROW_GD); /* g: check_residual's */
    corrected(f, sc, sim, s, "gd", 1);
    fputs("    /* check_residual */\n    {\n        real_t worst = 0, v;\n"
          "        uint16_t row = 0;\n", f);
    for (unsigned r = 0; r < w->nc[s]; r++)
        fprintf(f, "        v = rt_fabs(g[%u]);\n        if (!(v <= worst))\n"
                   "            worst = v, row = %u;\n", r, r);
    fprintf(f, "        w->projections++;\n        if (!(worst <= w->res_max))\n"
               "            w->res_max = worst;\n        if (!(worst <= RT_MBS_RES_TOL))\n"
               "            rti_count(sim, RT_CNT_DEGRADED, rti_mbs_row_block(sc, sim, %u, row), "
               "RT_E_DEGRADED);\n    }\n", s);
    if (w->need_lambda)
        fprintf(f, "    rti_outputs(sc, sim, (rti_at){t, %u, RTI_IN_STEP});\n"
                   "    rti_mbs_lambda(sc, sim, %u, t);\n", s, s);
    fputs("    return 1;\n}\n", f);
}

/* rti_args with the block's offsets as constants */
static const char helpers[] =
    "\n/* ---- specialized code (tools/scenec/spec.c): rt/'s work for this scene, written out */\n"
    "#include \"rti_mbs.h\"\n\n"
    "/* GCC's straight-line (SLP) vectorizer pairs neighbouring entries of the written-out\n"
    "   sums into vector lanes and pays more in shuffles than it saves (3 % more\n"
    "   instructions on pendulum10, x86-64): off for this code. It computes lane by lane\n"
    "   what the scalar code does, so no value depends on it (and -ffp-contract=off stays) */\n"
    "#if defined(__GNUC__) && !defined(__clang__)\n"
    "#pragma GCC optimize(\"no-tree-slp-vectorize\")\n"
    "#endif\n\n"
    "static inline void args(rt_sim *sim, uint16_t b, unsigned xo, unsigned dof, unsigned uo,\n"
    "                        unsigned po, real_t t, real_t h, rt_args *ar)\n{\n"
    "    ar->t = t, ar->h = h;\n"
    "    ar->x = sim->state.x + xo, ar->d = sim->state.d + dof;\n"
    "    ar->u = sim->work.u + uo, ar->p = sim->state.p + po;\n"
    "    ar->spec = blocks[b].kind->spec, ar->t_piece = t;\n}\n\n"
    "/* rt/mbs_asm.c's dot of three terms, plain and with M^-1 W^T's entries (b = q): the\n"
    "   same sums */\n"
    "static inline real_t dot3(const real_t *a, const real_t *b)\n{\n"
    "    real_t acc = 0;\n    acc += a[0] * b[0];\n    acc += a[1] * b[1];\n"
    "    acc += a[2] * b[2];\n    return acc;\n}\n";

/* row_dot (rt/mbs_asm.c) of a joint row's twelve coefficients, and of a translational
   kind's six (its angular terms left out); dot of n terms: the same sums */
static const char body_helpers[] =
    "\n/* rt/mbs_asm.c's row_dot: C . [x1; y1; x2; y2], and without the angular terms */\n"
    "static inline real_t rowdot12(const real_t *C, const real_t *x1, const real_t *y1,\n"
    "                              const real_t *x2, const real_t *y2)\n{\n"
    "    real_t s = 0;\n"
    "    s += C[0] * x1[0] + C[3] * y1[0] + C[6] * x2[0] + C[9] * y2[0];\n"
    "    s += C[1] * x1[1] + C[4] * y1[1] + C[7] * x2[1] + C[10] * y2[1];\n"
    "    s += C[2] * x1[2] + C[5] * y1[2] + C[8] * x2[2] + C[11] * y2[2];\n"
    "    return s;\n}\n\n"
    "static inline real_t rowdot6(const real_t *C, const real_t *x1, const real_t *y1,\n"
    "                             const real_t *x2, const real_t *y2)\n{\n"
    "    real_t s = 0;\n    (void)y1, (void)y2;\n"
    "    s += C[0] * x1[0] + C[6] * x2[0];\n"
    "    s += C[1] * x1[1] + C[7] * x2[1];\n"
    "    s += C[2] * x1[2] + C[8] * x2[2];\n"
    "    return s;\n}\n\n"
    "/* rt/mbs_asm.c's dot of n terms from the first (a body's velocities other than 3) */\n"
    "static inline real_t dotn(const real_t *a, const real_t *b, unsigned n)\n{\n"
    "    real_t acc = 0;\n"
    "    for (unsigned c = 0; c < n; c++)\n        acc += a[c] * b[c];\n"
    "    return acc;\n}\n";

int scn_emit_code(FILE *f, const scn_ctx *c)
{
    const rt_scene *sc = &c->image;
    const rt_sim *sim = c->sim;
    int any = 0, proj = 0, pts = 0, bodies = 0;
    for (uint8_t s = 0; sim && s < sc->nsets; s++) {
        any |= rhs_set(sim, s);
        pts |= mbs_points_set(sc, sim, s);
        bodies |= mbs_bodies_set(sc, sim, s);
        pts |= mbs_bodies_set(sc, sim, s) && point_joints(sc, sim, s);
        proj |= project_set(sc, sim, s);
    }
    if (!any)
        return 0;
    fputs("\n#if RT_SCENE_CODE /* 0: the table-driven path (rt/rt_config.h) */", f);
    fputs(helpers, f);
    if (pts)
        fputs("#include \"rti_joints.h\"\n", f);
    if (bodies)
        fputs(body_helpers, f);
    for (uint8_t s = 0; s < sc->nsets; s++) {
        if (rhs_set(sim, s))
            rhs_points(f, sc, sim, s);
        if (project_set(sc, sim, s))
            project_points(f, sc, sim, s);
        tick_outputs(f, sc, sim, s);
    }
    fputs("\nstatic int rhs(const rt_scene *sc, rt_sim *sim, uint8_t set, real_t t, real_t h,\n"
          "               real_t *xdot)\n{\n    switch (set) {\n", f);
    for (uint8_t s = 0; s < sc->nsets; s++)
        if (rhs_set(sim, s))
            fprintf(f, "    case %u: return rhs_%u(sc, sim, t, h, xdot);\n", s, s);
    fputs("    default: return 0;\n    }\n}\n", f);
    if (proj) {
        fputs("\nstatic int project(const rt_scene *sc, rt_sim *sim, uint8_t set, real_t t)\n"
              "{\n    switch (set) {\n", f);
        for (uint8_t s = 0; s < sc->nsets; s++)
            if (project_set(sc, sim, s))
                fprintf(f, "    case %u: return project_%u(sc, sim, t);\n", s, s);
        fputs("    default: return 0;\n    }\n}\n", f);
    }
    fputs("\nstatic int outputs(const rt_scene *sc, rt_sim *sim, uint8_t set, real_t t, int mode)\n"
          "{\n    switch (set) {\n", f);
    for (uint8_t s = 0; s < sc->nsets; s++)
        fprintf(f, "    case %u: return outputs_%u(sc, sim, t, mode);\n", s, s);
    fputs("    default: return 0;\n    }\n}\n", f);
    fprintf(f, "\nstatic const rt_scene_code scene_code = {.rhs = rhs%s, .outputs = outputs,\n"
               "                                          .sim_layout = RT_SIM_LAYOUT};\n#endif\n",
            proj ? ", .project = project" : "");
    return 1;
}
