/* mbs_asm.c - the multibody assembly and the index-1 solve of one set: the block-diagonal
 * M and the stacked W = G K of eq. 9, the Schur complement A = W M^-1 W^T over the rows
 * each block touches, the multipliers lambda, and z' (eqs. 6b, 7b); the mbs accel service.
 *
 * Only (block, row) pairs that can be non-zero are formed and stored: a joint row touches
 * the two blocks it links, an internal row its own block, so W and Y keep one slice of a
 * block's velocities per touch, A only the entries the blocks share, and its sparse
 * L D L^T (rt/mbs_ldl.c) only the pattern found at init: a chain of n bodies costs O(n).
 * Loops run in a fixed order, so the same state gives the same bits on every target. */
#include "linalg.h"
#include "rti_mbs.h"

/* A per-scene image sizes every table to its scene: one without multibody blocks gets
 * RT_MAX_MBS_M = 1, and GCC 12 then reports the reads of a point's 1/m (its M entry 3,
 * point_shares, rti_mbs_correct) on paths it cannot prove unreachable (no set of points
 * exists: rt_mbs_work.points is 0). As rt/mbs_ldl.c for its one-row graph. */
#if defined(__GNUC__) && !defined(__clang__) && RT_MAX_MBS_M <= 3
#pragma GCC diagnostic ignored "-Warray-bounds"
#endif

static const rt_mbs_spec *spec_of(const rt_scene *sc, uint16_t b)
{
    return (const rt_mbs_spec *)sc->blocks[b].kind->spec;
}

/* ------------------------------------------------------------------ nodes and joints */

/* an inertial node: the joint's anchor point and frame, at rest */
static void anchor(const rt_joint *j, rt_mbs_node *n)
{
    for (int i = 0; i < 3; i++) {
        n->r[i] = j->at ? j->at[i] : 0;
        n->v[i] = n->w[i] = n->ar[i] = n->aw[i] = 0;
    }
    for (int i = 0; i < 9; i++)
        n->S[i] = j->at_S ? j->at_S[i] : (i % 4 == 0 ? 1 : 0);
}

/* a node of a kind flagged RT_MBS_NODE_POINT is the point itself: r = q, v = z, S = I, at
   rest in rotation, no acceleration terms; filled here without a call (and no Jacobian:
   Jr = I, Jw = 0 is what the flag declares) */
static void point_node(const real_t *x, rt_mbs_node *n, int trans)
{
    for (int i = 0; i < 3; i++) {
        n->r[i] = x[i];
        n->v[i] = x[3 + i];
        n->ar[i] = 0;
    }
    if (trans) /* a translational joint kind reads no rotation (rt_joint_kind.trans) */
        return;
    for (int i = 0; i < 3; i++)
        n->w[i] = n->aw[i] = 0;
    for (int i = 0; i < 9; i++)
        n->S[i] = i % 4 == 0 ? 1 : 0;
}

/* node `side` (0: n1 of b1, 1: n2 of b2) of joint j; Jacobians into J if not NULL */
static void joint_node(const rt_scene *sc, const rt_sim *sim, const rt_joint *j, int side,
                       real_t t, rt_mbs_node *n, real_t *J)
{
    int16_t b = (int16_t)(side ? j->b2 : j->b1);
    if (b < 0) {
        anchor(j, n);
        return;
    }
    const rt_mbs_spec *sp = spec_of(sc, (uint16_t)b);
    if (sp->flags & RT_MBS_NODE_POINT) {
        point_node(sim->state.x + sim->plan.x_off[b], n, j->kind->trans);
        return;
    }
    rt_args a;
    rti_args(sc, sim, (uint16_t)b, t, 0, &a);
    sp->node(&a, (uint16_t)(side ? j->n2 : j->n1), n, J);
}

/* position r and velocity v of block b's point (its coordinates x = [r, v]), or for
   b < 0 of joint j's anchor, at rest (the origin without one) */
static RTI_INLINE void side_rv(const rt_sim *sim, const rt_joint *j, int16_t b,
                               const real_t **r, const real_t **v)
{
    static const real_t zero[3] = {0, 0, 0};
    if (b < 0) {
        *r = j->at ? j->at : zero, *v = zero;
        return;
    }
    *r = sim->state.x + sim->plan.x_off[b], *v = *r + 3;
}

/* the position and velocity of side `side` of joint j if that node is a point (a point
   node or an anchor: 1), else 0 */
static int point_of(const rt_scene *sc, const rt_sim *sim, const rt_joint *j, int side,
                    const real_t **r, const real_t **v)
{
    int16_t b = (int16_t)(side ? j->b2 : j->b1);
    side_rv(sim, j, b, r, v);
    return b < 0 || (spec_of(sc, (uint16_t)b)->flags & RT_MBS_NODE_POINT) != 0;
}

/* S <- S A (3 x 3, row-major) */
static void turn(real_t *S, const real_t *A)
{
    for (real_t *row = S; row < S + 9; row += 3) {
        real_t a = row[0], b = row[1], c = row[2];
        for (unsigned k = 0; k < 3; k++)
            row[k] = a * A[k] + b * A[3 + k] + c * A[6 + k];
    }
}

void rti_mbs_joint(const rt_scene *sc, const rt_sim *sim, uint16_t ji, real_t t,
                   rt_mbs_node *n1, rt_mbs_node *n2, real_t *J1, real_t *J2, rt_joint_eval *e)
{
    const rt_joint *j = &sc->joints[ji];
    joint_node(sc, sim, j, 0, t, n1, J1);
    joint_node(sc, sim, j, 1, t, n2, J2);
    if (j->axis_S) { /* the joint frame: S A on both sides (velocities are inertial) */
        turn(n1->S, j->axis_S);
        turn(n2->S, j->axis_S);
    }
    j->kind->eval(j->p, n1, n2, e);
}

void rti_mbs_joint_g(const rt_scene *sc, const rt_sim *sim, uint16_t ji, real_t t, real_t *g,
                     real_t *gd)
{
    const rt_joint *j = &sc->joints[ji];
    const real_t *r1, *v1, *r2, *v2;
    rt_joint_eval e;
    int points = point_of(sc, sim, j, 0, &r1, &v1) && point_of(sc, sim, j, 1, &r2, &v2);
    if (!gd && points && j->kind->g_points) {
        j->kind->g_points(j->p, r1, r2, g);
        return;
    }
    if (j->kind->eval_points && points) {
        j->kind->eval_points(j->p, r1, v1, r2, v2, &e);
        for (uint16_t i = 0; i < j->kind->nc; i++) {
            const real_t *C = e.C[i];
            real_t s = 0; /* the general sum below, term by term: the angular terms are +0 */
            for (int k = 0; k < 3; k++)
                s += C[k] * v1[k] + C[6 + k] * v2[k];
            g[i] = e.g[i];
            if (gd)
                gd[i] = s;
        }
        return;
    }
    rt_mbs_node n1, n2;
    rti_mbs_joint(sc, sim, ji, t, &n1, &n2, 0, 0, &e);
    for (uint16_t i = 0; i < j->kind->nc; i++) {
        const real_t *C = e.C[i];
        real_t s = 0;
        for (int k = 0; k < 3; k++)
            s += C[k] * n1.v[k] + C[3 + k] * n1.w[k] + C[6 + k] * n2.v[k] + C[9 + k] * n2.w[k];
        g[i] = e.g[i];
        if (gd)
            gd[i] = s;
    }
}

/* C_i . [x1; y1; x2; y2] for four 3-vectors; a translational joint kind (trans) has no
   angular coefficients, whose zero terms are left out (the same sum) */
static real_t row_dot(const real_t *C, int trans, const real_t *x1, const real_t *y1,
                      const real_t *x2, const real_t *y2)
{
    real_t s = 0;
    if (trans) {
        for (int k = 0; k < 3; k++)
            s += C[k] * x1[k] + C[6 + k] * x2[k];
        return s;
    }
    for (int k = 0; k < 3; k++)
        s += C[k] * x1[k] + C[3 + k] * y1[k] + C[6 + k] * x2[k] + C[9 + k] * y2[k];
    return s;
}

/* W[row, block cols] (+)= C6 J: six coefficients times a node's 6 x nz Jacobian; zero
   coefficients (a translational joint's rotation part) are skipped; a point node's
   Jacobian [I; 0] maps the first three coefficients unchanged */
static void map_row(const rt_mbs_spec *sp, const real_t *C6, const real_t *J, real_t *Wrow,
                    int add)
{
    uint16_t nz = sp->nz;
    if (sp->flags & RT_MBS_NODE_POINT) {
        for (uint16_t c = 0; c < 3; c++)
            Wrow[c] = add ? Wrow[c] + C6[c] : C6[c];
        return;
    }
    if (!add)
        for (uint16_t c = 0; c < nz; c++)
            Wrow[c] = 0;
    for (int k = 0; k < 6; k++) {
        if (C6[k] == 0)
            continue;
        for (uint16_t c = 0; c < nz; c++)
            Wrow[c] += C6[k] * J[k * nz + c];
    }
}

/* sum_c a_c b_c / m_c (m NULL: no division), in the order of a loop from c = 0; three
   velocities (a point, a planar body) spelled out, the common case of the inner loops */
static inline real_t dot(const real_t *a, const real_t *b, const real_t *m, uint16_t n)
{
    real_t acc = 0;
    if (n == 3 && m) {
        acc += a[0] * (b[0] / m[0]);
        acc += a[1] * (b[1] / m[1]);
        acc += a[2] * (b[2] / m[2]);
    } else if (n == 3) {
        acc += a[0] * b[0];
        acc += a[1] * b[1];
        acc += a[2] * b[2];
    } else {
        for (uint16_t c = 0; c < n; c++)
            acc += a[c] * (m ? b[c] / m[c] : b[c]);
    }
    return acc;
}

/* the rows of joint ji between two points (r1, v1) and (r2, v2) by its kind's
   eval_points: g, g' = C1 v1 + C2 v2, and with jac gam = c (points have no acceleration
   terms: the general path adds a zero sum, +0) and W's rows C1, C2 (a point node's
   Jacobian is [I; 0]); the same bits as the general path below, without node structs.
   RTI_MBS_G alone: g by the kind's g_points if it has one (the same bits again) */
static RTI_INLINE void point_rows(const rt_joint *j, uint16_t ji, rt_mbs_work *w, int what,
                                  const real_t *r1, const real_t *v1, const real_t *r2,
                                  const real_t *v2)
{
    const rt_joint_kind *jk = j->kind;
    if (what == RTI_MBS_G && jk->g_points) { /* g alone, the same bits */
        jk->g_points(j->p, r1, r2, w->g + w->jrow[ji]);
        return;
    }
    int jac = what & RTI_MBS_JAC;
    rt_joint_eval e;
    jk->eval_points(j->p, r1, v1, r2, v2, &e);
    unsigned nc = jk->nc, r = w->jrow[ji];
    int one = j->b2 < 0, same = j->b2 == j->b1; /* one: b2 is the inertial frame */
    real_t *W1 = w->W + w->jw[ji][0], *W2 = one ? W1 : w->W + w->jw[ji][1];
    for (unsigned i = 0; i < nc; i++, r++, W1 += 3, W2 += 3) {
        const real_t *C = e.C[i];
        real_t s = 0; /* the sum of the general path's row_dot, term by term */
        s += C[0] * v1[0] + C[6] * v2[0];
        s += C[1] * v1[1] + C[7] * v2[1];
        s += C[2] * v1[2] + C[8] * v2[2];
        w->g[r] = e.g[i];
        w->gd[r] = s;
        if (!jac)
            continue;
        w->gam[r] = (real_t)0 + e.c[i];
        W1[0] = C[0], W1[1] = C[1], W1[2] = C[2];
        if (one)
            continue;
        if (same)
            W2[0] += C[6], W2[1] += C[7], W2[2] += C[8];
        else
            W2[0] = C[6], W2[1] = C[7], W2[2] = C[8];
    }
}

/* the rows of joint ji by point_rows if its kind has eval_points and both sides are
   points (else 0: the general path) */
static int assemble_points(const rt_scene *sc, rt_sim *sim, uint16_t ji, int what)
{
    const rt_joint *j = &sc->joints[ji];
    const real_t *r1, *v1, *r2, *v2;
    if (!j->kind->eval_points || !point_of(sc, sim, j, 0, &r1, &v1) ||
        !point_of(sc, sim, j, 1, &r2, &v2))
        return 0;
    point_rows(j, ji, &sim->work.mbs, what, r1, v1, r2, v2);
    return 1;
}

/* rows of joint ji: g, g', and with RTI_MBS_JAC the rows of W and gam (eq. 7b) */
static void assemble_joint(const rt_scene *sc, rt_sim *sim, uint16_t ji, real_t t, int what)
{
    rt_mbs_work *w = &sim->work.mbs;
    const rt_joint *j = &sc->joints[ji];
    int jac = what & RTI_MBS_JAC;
    rt_mbs_node n1, n2;
    rt_joint_eval e;
    if (assemble_points(sc, sim, ji, what))
        return;
    rti_mbs_joint(sc, sim, ji, t, &n1, &n2, jac ? w->J[0] : 0, jac ? w->J[1] : 0, &e);
    uint16_t b1 = (uint16_t)j->b1, nz1 = spec_of(sc, b1)->nz;
    for (uint16_t i = 0; i < j->kind->nc; i++) {
        uint16_t r = (uint16_t)(w->jrow[ji] + i);
        w->g[r] = e.g[i];
        w->gd[r] = row_dot(e.C[i], j->kind->trans, n1.v, n1.w, n2.v, n2.w);
        if (!jac)
            continue;
        w->gam[r] = row_dot(e.C[i], j->kind->trans, n1.ar, n1.aw, n2.ar, n2.aw) + e.c[i];
        map_row(spec_of(sc, b1), e.C[i], w->J[0],
                w->W + w->jw[ji][0] + (size_t)i * nz1, 0);
        if (j->b2 >= 0) {
            uint16_t b2 = (uint16_t)j->b2, nz2 = spec_of(sc, b2)->nz;
            map_row(spec_of(sc, b2), e.C[i] + 6, w->J[1],
                    w->W + w->jw[ji][1] + (size_t)i * nz2, b2 == b1);
        }
    }
}

/* ------------------------------------------------------------------ blocks */

/* factors block b's M in place (a diagonal M is only checked); a pivot at or below the
   threshold is counted and replaced by it, so the solves stay finite. A dense M keeps its
   nz row pivots after the nz^2 factors, as reals (small integers, exact) */
void rti_mbs_mass_factor(rt_sim *sim, const rt_mbs_spec *sp, uint16_t b, real_t *M)
{
    rt_status st = RT_OK;
    if (sp->flags & RT_MBS_M_DIAG) {
        real_t big = 0;
        for (uint16_t i = 0; i < sp->nz; i++)
            big = M[i] > big ? M[i] : big;
        real_t floor_ = RT_MBS_PIVOT_TOL * (big > 0 ? big : 1);
        for (uint16_t i = 0; i < sp->nz; i++)
            if (!(M[i] > floor_))
                M[i] = floor_, st = RT_E_SINGULAR;
        if (sp->flags & RT_MBS_M_ISO) /* M = m I: A and the corrections multiply by 1/m */
            M[rti_mbs_m_inv(sp)] = (real_t)1 / M[0];
    } else {
        uint16_t piv[RT_MAX_MBS_BZ];
        st = rti_lu(M, sp->nz, piv, RT_MBS_PIVOT_TOL);
        for (uint16_t i = 0; i < sp->nz; i++)
            M[sp->nz * sp->nz + i] = (real_t)piv[i];
    }
    if (st != RT_OK)
        rti_count(sim, RT_CNT_SINGULAR, b, RT_E_SINGULAR);
}

/* v <- M^-1 v with the factors of rti_mbs_mass_factor */
void rti_mbs_mass_solve(const rt_mbs_spec *sp, const real_t *M, real_t *v)
{
    if (sp->flags & RT_MBS_M_DIAG) {
        for (unsigned i = 0, n = sp->nz; i < n; i++)
            v[i] /= M[i];
        return;
    }
    uint16_t piv[RT_MAX_MBS_BZ];
    for (uint16_t i = 0; i < sp->nz; i++)
        piv[i] = (uint16_t)M[sp->nz * sp->nz + i];
    rti_lu_solve(M, sp->nz, piv, v);
}

/* block b's own part: M factors (once for a constant M), free accelerations M^-1 k,
   internal constraint rows (its first touches, so their W slices form an nc x nz matrix) */
static void assemble_block(const rt_scene *sc, rt_sim *sim, uint16_t b, real_t t, int what)
{
    rt_mbs_work *w = &sim->work.mbs;
    const rt_mbs_spec *sp = spec_of(sc, b);
    if (what == RTI_MBS_G && sp->nc == 0) /* nothing of the block's own */
        return;
    uint16_t zo = w->zo[b];
    real_t *M = w->M + w->mo[b];
    rt_args a;
    rti_args(sc, sim, b, t, 0, &a);
    if ((what & RTI_MBS_JAC) && !((sp->flags & RT_MBS_M_CONST) && w->m_valid[b])) {
        sp->mass(&a, M);
        rti_mbs_mass_factor(sim, sp, b, M);
        w->m_valid[b] = 1;
    }
    if (what & RTI_MBS_FORCE) {
        if (sc->blocks[b].kind->nu > 0)
            rti_gather(sim, b, t); /* the inputs are applied forces (eq. 6b) */
        sp->force(&a, w->a + zo);
        rti_mbs_mass_solve(sp, M, w->a + zo);
    }
    if (sp->nc > 0) {
        uint16_t r = w->co[b];
        real_t *W = (what & RTI_MBS_JAC) ? w->W + w->wo[b] : 0;
        sp->constr(&a, w->g + r, w->gd + r, W, sp->nz, w->gam + r);
    }
}

/* a set of points only (rt_mbs_work.points, rt/mbs.c): assemble_block and
   assemble_points without looking up a spec per block and joint side. Such a block has a
   constant diagonal M, factored by assemble_block at its first assembly, and no rows of
   its own: all the block part does is k and M^-1 k; the same calls, the same bits */
static void assemble_point_set(const rt_scene *sc, rt_sim *sim, uint8_t set, real_t t, int what)
{
    rt_mbs_work *w = &sim->work.mbs;
    for (unsigned k = w->sb[set], k1 = w->sb[set + 1]; k < k1 && what != RTI_MBS_G; k++) {
        uint16_t b = w->sblk[k];
        if (!w->m_valid[b]) { /* the first assembly factors M */
            assemble_block(sc, sim, b, t, what);
            continue;
        }
        if (!(what & RTI_MBS_FORCE))
            continue;
        const rt_kind *kd = sc->blocks[b].kind;
        real_t *ab = w->a + w->zo[b];
        const real_t *M = w->M + w->mo[b];
        rt_args a;
        if (kd->nu > 0)
            rti_gather(sim, b, t); /* the inputs are applied forces (eq. 6b) */
        rti_args(sc, sim, b, t, 0, &a);
        ((const rt_mbs_spec *)kd->spec)->force(&a, ab);
        ab[0] /= M[0], ab[1] /= M[1], ab[2] /= M[2];
    }
    for (unsigned k = w->sj[set], k1 = w->sj[set + 1]; k < k1; k++) {
        uint16_t ji = w->sjnt[k];
        const rt_joint *j = &sc->joints[ji];
        const real_t *r1, *v1, *r2, *v2;
        side_rv(sim, j, j->b1, &r1, &v1);
        side_rv(sim, j, j->b2, &r2, &v2);
        point_rows(j, ji, w, what, r1, v1, r2, v2);
    }
}

void rti_mbs_assemble(const rt_scene *sc, rt_sim *sim, uint8_t set, real_t t, int what)
{
    const rt_mbs_work *w = &sim->work.mbs;
    if (w->points[set]) {
        assemble_point_set(sc, sim, set, t, what);
        return;
    }
    for (uint16_t k = w->sb[set]; k < w->sb[set + 1]; k++)
        assemble_block(sc, sim, w->sblk[k], t, what);
    for (uint16_t k = w->sj[set]; k < w->sj[set + 1]; k++)
        assemble_joint(sc, sim, w->sjnt[k], t, what);
}

/* ------------------------------------------------------------------ the Schur complement */

int rti_mbs_row_block(const rt_scene *sc, const rt_sim *sim, uint8_t set, uint16_t row)
{
    const rt_mbs_work *w = &sim->work.mbs;
    for (uint16_t j = 0; j < sc->njoints; j++) {
        const rt_joint *jt = &sc->joints[j];
        if (sc->blocks[jt->b1].set == set && row >= w->jrow[j] &&
            row < w->jrow[j] + jt->kind->nc)
            return jt->b1;
    }
    for (uint16_t b = 0; b < sc->nblocks; b++)
        if (rti_mbs_in_set(sc, b, set) && row >= w->co[b] &&
            row < w->co[b] + spec_of(sc, b)->nc)
            return b;
    return -1;
}

/* a diagonal M's shares W_i M^-1 W_k^T of nt touches (nz columns each) into the slots ps */
static RTI_INLINE void diag_shares(real_t *lv, const real_t *W, const real_t *M,
                                   const uint16_t *ps, unsigned nt, uint16_t nz)
{
    const real_t *Wi = W;
    for (unsigned i = 0; i < nt; i++, Wi += nz) {
        const real_t *Wk = Wi;
        for (unsigned k = i; k < nt; k++, Wk += nz)
            lv[*ps++] += dot(Wi, Wk, M, nz);
    }
}

/* point b's shares of A = W M^-1 W^T (a set of points, M = m I) over the pairs of rows
   it touches: a row with itself (C.C) / m (the same C.C at both its points, which see C
   and -C: rt_joint_kind.anti), two rows
   (W_i . W_k) / m; 1/m kept after M's factors */
static RTI_INLINE void point_shares(rt_mbs_work *w, unsigned b)
{
    const real_t *Wi = w->W + w->wo[b], im = w->M[w->mo[b] + 3];
    const uint16_t *ps = w->pslot + w->po[b];
    for (unsigned i = 0, nt = (unsigned)(w->to[b + 1] - w->to[b]); i < nt; i++, Wi += 3) {
        w->lv[*ps++] += (Wi[0] * Wi[0] + Wi[1] * Wi[1] + Wi[2] * Wi[2]) * im;
        const real_t *Wk = Wi + 3;
        for (unsigned k = i + 1; k < nt; k++, Wk += 3)
            w->lv[*ps++] += dot(Wi, Wk, 0, 3) * im;
    }
}

/* block b's share of A = W Y over the pairs of rows it touches, Y = M^-1 W^T: a diagonal
   M divides on the fly (Y is kept only for a dense M, RT_MAX_MBS_TY) */
static void schur_block(rt_mbs_work *w, const rt_mbs_spec *sp, uint16_t b)
{
    uint16_t nz = sp->nz, t0 = w->to[b], t1 = w->to[b + 1];
    const real_t *M = w->M + w->mo[b];
    const real_t *W = w->W + w->wo[b], *Wi = W;
    const uint16_t *ps = w->pslot + w->po[b];
    if (sp->flags & RT_MBS_M_DIAG) { /* a point's nz = 3 specialized at compile time */
        if (nz == 3)
            diag_shares(w->lv, W, M, ps, t1 - t0, 3);
        else
            diag_shares(w->lv, W, M, ps, t1 - t0, nz);
        return;
    }
    real_t *Y = w->Y + w->yo[b], *Yi = Y;
    for (uint16_t i = t0; i < t1; i++, Wi += nz, Yi += nz) {
        for (uint16_t c = 0; c < nz; c++)
            Yi[c] = Wi[c];
        rti_mbs_mass_solve(sp, M, Yi);
    }
    for (Wi = W; t0 < t1; t0++, Wi += nz, Y += nz) {
        const real_t *Yk = Y;
        for (uint16_t k = t0; k < t1; k++, Yk += nz)
            w->lv[*ps++] += dot(Wi, Yk, 0, nz);
    }
}

void rti_mbs_schur(const rt_scene *sc, rt_sim *sim, uint8_t set)
{
    rt_mbs_work *w = &sim->work.mbs;
    if (w->nc[set] == 0)
        return;
    rti_mbs_ldl_clear(w, set);
    if (w->points[set]) /* points only: no spec to look up, 1/m for M^-1 */
        for (unsigned k = w->sb[set], k1 = w->sb[set + 1]; k < k1; k++)
            point_shares(w, w->sblk[k]);
    else
        for (uint16_t k = w->sb[set]; k < w->sb[set + 1]; k++)
            schur_block(w, spec_of(sc, w->sblk[k]), w->sblk[k]);
    uint16_t deficit = w->ndrop[set];
    int bad = rti_mbs_ldl_factor(w, set);
    if (bad >= 0) /* counted with the block owning the first offending row */
        rti_count(sim, RT_CNT_SINGULAR, rti_mbs_row_block(sc, sim, set, (uint16_t)bad),
                  RT_E_SINGULAR);
    /* dependent rows solve as they are (their conflicts are found in the solves): counted
       when the rank deficit changes, not in every factorization */
    if (w->ndrop[set] != deficit && w->ndrop[set] > 0)
        rti_count(sim, RT_CNT_REDUNDANT, rti_mbs_row_block(sc, sim, set, w->drop_row[set]),
                  RT_OK);
}

void rti_mbs_solve(rt_sim *sim, uint8_t set, real_t *v)
{
    int row = rti_mbs_ldl_solve(&sim->work.mbs, set, v);
    if (row >= 0) /* dependent rows that ask for different things: no answer meets both */
        rti_count(sim, RT_CNT_SINGULAR, rti_mbs_row_block(sim->sc, sim, set, (uint16_t)row),
                  RT_E_SINGULAR);
}

void rti_mbs_correct(const rt_scene *sc, rt_sim *sim, uint8_t set, const real_t *v,
                     real_t *dz, int add)
{
    rt_mbs_work *w = &sim->work.mbs;
    const uint16_t *trow = w->trow;
    for (unsigned k = w->sb[set], k1 = w->sb[set + 1]; k < k1; k++) {
        unsigned b = w->sblk[k], i = w->to[b], i1 = w->to[b + 1];
        real_t *d = dz + w->zo[b];
        const real_t *M = w->M + w->mo[b], *Wi = w->W + w->wo[b], *Yi = w->Y + w->yo[b];
        if (w->points[set]) { /* M = m I, no spec to look up: each touch's multiplier
                                 times 1/m, kept in registers */
            real_t d0 = add ? d[0] : 0, d1 = add ? d[1] : 0, d2 = add ? d[2] : 0;
            for (real_t im = M[3]; i < i1; i++, Wi += 3) { /* 1/m after M (rti_mbs_m_inv) */
                real_t s = v[trow[i]] * im;
                d0 -= Wi[0] * s;
                d1 -= Wi[1] * s;
                d2 -= Wi[2] * s;
            }
            d[0] = d0, d[1] = d1, d[2] = d2;
            continue;
        }
        const rt_mbs_spec *sp = spec_of(sc, (uint16_t)b);
        unsigned nz = sp->nz;
        int diag = (sp->flags & RT_MBS_M_DIAG) != 0;
        if (diag && nz == 3) { /* a diagonal M of three velocities (a point among bodies, a
                                  planar body): the same sums, kept in registers */
            real_t d0 = add ? d[0] : 0, d1 = add ? d[1] : 0, d2 = add ? d[2] : 0;
            for (; i < i1; i++, Wi += 3) {
                real_t vi = v[trow[i]];
                d0 -= (Wi[0] / M[0]) * vi;
                d1 -= (Wi[1] / M[1]) * vi;
                d2 -= (Wi[2] / M[2]) * vi;
            }
            d[0] = d0, d[1] = d1, d[2] = d2;
            continue;
        }
        for (unsigned c = 0; c < nz && !add; c++)
            d[c] = 0;
        for (; i < i1; i++, Wi += nz, Yi += nz) {
            real_t vi = v[trow[i]];
            for (unsigned c = 0; c < nz; c++)
                d[c] -= (diag ? Wi[c] / M[c] : Yi[c]) * vi;
        }
    }
}

/* ------------------------------------------------------------------ the index-1 solve */

/* a set of points: W M^-1 k of each row, C . (a1 - a2) from the free accelerations a of
   its two points (C2 = -C1, rt_joint_kind.anti; an anchor's is zero), added to lam */
static void point_accels(const rt_scene *sc, const rt_mbs_work *w, uint8_t set, real_t *lam)
{
    for (unsigned k = w->sj[set], k1 = w->sj[set + 1]; k < k1; k++) {
        uint16_t ji = w->sjnt[k];
        const rt_joint *j = &sc->joints[ji];
        const real_t *W1 = w->W + w->jw[ji][0], *a1 = w->a + w->zo[j->b1];
        const real_t *a2 = j->b2 >= 0 ? w->a + w->zo[j->b2] : 0;
        for (unsigned i = 0, r = w->jrow[ji]; i < j->kind->nc; i++, r++, W1 += 3) {
            real_t d[3] = {a1[0], a1[1], a1[2]};
            if (a2)
                d[0] -= a2[0], d[1] -= a2[1], d[2] -= a2[2];
            lam[r] += dot(W1, d, 0, 3);
        }
    }
}

void rti_mbs_lambda(const rt_scene *sc, rt_sim *sim, uint8_t set, real_t t)
{
    rt_mbs_work *w = &sim->work.mbs;
    uint16_t m = w->nc[set];
    rti_mbs_assemble(sc, sim, set, t, RTI_MBS_JAC | RTI_MBS_FORCE);
    if (m == 0) /* no constraint: z' is the free acceleration */
        return;
    rti_mbs_schur(sc, sim, set);
    /* A lambda = W M^-1 k + gam (+ alpha g' + beta g): eq. 7b with z' from eq. 6b; the
       right side and then lambda are formed in gam, which is not needed after */
    real_t *lam = w->gam;
    if (sc->stab == RT_STAB_BAUMGARTE)
        for (uint16_t r = 0; r < m; r++)
            lam[r] += sc->baumgarte[0] * w->gd[r] + sc->baumgarte[1] * w->g[r];
    if (w->points[set])
        point_accels(sc, w, set, lam);
    else
        for (unsigned k = w->sb[set], k1 = w->sb[set + 1]; k < k1; k++) {
            unsigned b = w->sblk[k], nz = spec_of(sc, (uint16_t)b)->nz;
            const real_t *ab = w->a + w->zo[b];
            const real_t *Wi = w->W + w->wo[b];
            for (unsigned i = w->to[b], i1 = w->to[b + 1]; i < i1; i++, Wi += nz)
                lam[w->trow[i]] += dot(Wi, ab, 0, (uint16_t)nz);
        }
    rti_mbs_solve(sim, set, lam);
    rti_mbs_correct(sc, sim, set, lam, w->a, 1); /* z' = M^-1 k - Y lambda, into a */
    if (!w->need_lambda) /* nobody reads a joint's multipliers */
        return;
    for (uint16_t k = w->sj[set]; k < w->sj[set + 1]; k++) {
        uint16_t j = w->sjnt[k];
        for (uint16_t i = 0; i < sc->joints[j].kind->nc; i++)
            w->jlam[w->jlo[j] + i] = lam[w->jrow[j] + i];
    }
}

/* q' = K z + b (eq. 6a) and z' = M^-1 (k - W^T lambda) for every MBS block of the set */
void rti_mbs_accel(const rt_scene *sc, rt_sim *sim, uint8_t set, real_t t, real_t *xdot)
{
    rt_mbs_work *w = &sim->work.mbs;
    if (w->nz[set] == 0)
        return;
    rti_mbs_lambda(sc, sim, set, t);
    for (uint16_t k = w->sb[set]; k < w->sb[set + 1]; k++) {
        uint16_t b = w->sblk[k];
        real_t *qd = xdot + (sim->plan.x_off[b] - sim->plan.set_x[set]);
        if (w->points[set] || (spec_of(sc, b)->flags & RT_MBS_NODE_POINT)) {
            /* q' = v, v' = a: copies, no call */
            const real_t *x = sim->state.x + sim->plan.x_off[b], *ab = w->a + w->zo[b];
            qd[0] = x[3], qd[1] = x[4], qd[2] = x[5];
            qd[3] = ab[0], qd[4] = ab[1], qd[5] = ab[2];
            continue;
        }
        const rt_mbs_spec *sp = spec_of(sc, b);
        rt_args a;
        rti_args(sc, sim, b, t, 0, &a);
        sp->kin(&a, a.x + sp->nq, qd);
        if (sp->kinb) {
            real_t *bq = w->qt + w->qo[b]; /* qt is free outside the projection */
            sp->kinb(&a, bq);
            for (uint16_t i = 0; i < sp->nq; i++)
                qd[i] += bq[i];
        }
        for (uint16_t c = 0; c < sp->nz; c++)
            qd[sp->nq + c] = w->a[w->zo[b] + c];
    }
}
