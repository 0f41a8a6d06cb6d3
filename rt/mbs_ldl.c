/* mbs_ldl.c - the sparse L D L^T factorization of a set's Schur complement
 * A = W M^-1 W^T (eq. 9), which is symmetric positive definite when W has full rank.
 *
 * Eq. (9)'s Jacobian is block-sparse: a constraint row couples only the one or two blocks
 * it touches, so A_rs can be non-zero only when rows r and s touch a common block. A chain
 * gives a tridiagonal A, a tree or a few closed loops a sparse one. At init (symbolic
 * phase) a minimum-degree elimination order and the pattern of L with its fill are
 * computed once from the touches; every evaluation then only adds the blocks' shares into
 * the pattern's slots and factors those non-zeros (numeric phase). Loops run in a fixed
 * order: the same A gives the same bits on every target.
 *
 * Rank-revealing: A is positive semidefinite, and the pivot of row i is the squared
 * M^-1-distance of its row of W from the span of the rows eliminated before it. A pivot
 * at or below RT_MBS_PIVOT_TOL times A's largest diagonal entry marks a row that depends
 * on earlier ones (a redundant joint, a chain pulled straight): it is dropped (D = 0, its
 * column of L zero, its multiplier zero), so the rows kept have full rank, whatever the
 * order. In a solve the forward substitution leaves at a dropped row exactly the part of
 * its right-hand side that the rows it depends on do not give: zero when the redundancy
 * is consistent (two identical rods: solved), not zero when the rows conflict (two rods of
 * different lengths from one anchor: reported). A negative pivot beyond the threshold or
 * a NaN is not a rank question (A is then not semidefinite): it is replaced by the
 * threshold and reported as singular. */
#include "rti_mbs.h"

/* A per-scene image sizes every table to its scene: a scene without multibody rows gets
 * RT_MAX_MBS_C = 1, and GCC 12 then reports writes past the one-row graph on loop paths
 * bounded by w->nc (never above RT_MAX_MBS_C, which rti_capacity checks at init) that it
 * cannot prove unreachable. The host and cross builds at full size keep both warnings. */
#if defined(__GNUC__) && !defined(__clang__) && RT_MAX_MBS_C <= 1
#pragma GCC diagnostic ignored "-Warray-bounds"
#pragma GCC diagnostic ignored "-Wstringop-overflow"
#endif

#define WORD_BITS 32
#define ADJ_WORDS ((RT_MAX_MBS_C + WORD_BITS - 1) / WORD_BITS)

/* the graph of A's pattern while it is eliminated: adjacency bitsets by set row */
typedef struct graph {
    uint32_t adj[RT_MAX_MBS_C][ADJ_WORDS];
    uint16_t deg[RT_MAX_MBS_C]; /* neighbours not eliminated, kept as rows go and fill
                                   comes, so that choosing a row costs n, not n^2 */
    uint8_t gone[RT_MAX_MBS_C]; /* eliminated */
} graph;

static int has(const graph *g, uint16_t r, uint16_t s)
{
    return (int)((g->adj[r][s / WORD_BITS] >> (s % WORD_BITS)) & 1u);
}

static void link2(graph *g, uint16_t r, uint16_t s)
{
    g->adj[r][s / WORD_BITS] |= 1u << (s % WORD_BITS);
    g->adj[s][r / WORD_BITS] |= 1u << (r % WORD_BITS);
}

/* rows r, s share a block: A_rs may be non-zero */
static void touches_graph(const rt_scene *sc, const rt_mbs_work *w, uint8_t set, graph *g)
{
    for (uint16_t r = 0; r < w->nc[set]; r++) {
        g->gone[r] = 0;
        for (int k = 0; k < ADJ_WORDS; k++)
            g->adj[r][k] = 0;
    }
    for (uint16_t b = 0; b < sc->nblocks; b++)
        if (rti_mbs_in_set(sc, b, set))
            for (uint16_t i = w->to[b]; i < w->to[b + 1]; i++)
                for (uint16_t k = w->to[b]; k < w->to[b + 1]; k++)
                    if (w->trow[i] != w->trow[k])
                        link2(g, w->trow[i], w->trow[k]);
    for (uint16_t r = 0; r < w->nc[set]; r++) {
        g->deg[r] = 0;
        for (uint16_t s = 0; s < w->nc[set]; s++)
            g->deg[r] = (uint16_t)(g->deg[r] + has(g, r, s));
    }
}

/* the remaining row with the fewest remaining neighbours (the lowest on ties) */
static uint16_t min_degree(const graph *g, uint16_t n)
{
    uint16_t best = 0, best_deg = UINT16_MAX;
    for (uint16_t r = 0; r < n; r++)
        if (!g->gone[r] && g->deg[r] < best_deg)
            best = r, best_deg = g->deg[r];
    return best;
}

/* minimum-degree order; eliminating a row joins its remaining neighbours (the fill), so
   afterwards the graph holds the pattern of L + L^T. Work: n per row to find it and its
   neighbours, and the square of its neighbours for the fill (a chain: n^2 in all) */
static void order(graph *g, uint16_t n, uint16_t *perm)
{
    uint16_t nb[RT_MAX_MBS_C];
    for (uint16_t k = 0; k < n; k++) {
        uint16_t v = min_degree(g, n), m = 0;
        perm[k] = v;
        g->gone[v] = 1;
        for (uint16_t r = 0; r < n; r++) /* its remaining neighbours, ascending */
            if (!g->gone[r] && has(g, v, r))
                nb[m++] = r, g->deg[r]--;
        for (uint16_t i = 0; i < m; i++)
            for (uint16_t j = (uint16_t)(i + 1); j < m; j++)
                if (!has(g, nb[i], nb[j])) {
                    link2(g, nb[i], nb[j]);
                    g->deg[nb[i]]++, g->deg[nb[j]]++;
                }
    }
}

/* position of set row r in the elimination order */
static uint16_t pos_of(const rt_mbs_work *w, uint8_t set, uint16_t r)
{
    uint16_t i = 0;
    while (w->perm[w->rb[set] + i] != r)
        i++;
    return i;
}

/* the slot in lv where A_rs (set rows) is kept: its diagonal, or L's entry */
static uint16_t slot(const rt_mbs_work *w, uint8_t set, uint16_t r, uint16_t s)
{
    uint16_t i = pos_of(w, set, r), j = pos_of(w, set, s);
    if (i == j)
        return (uint16_t)(w->rb[set] + i);
    uint16_t hi = i > j ? i : j, lo = i > j ? j : i, row = (uint16_t)(w->rb[set] + hi);
    uint16_t e = w->lp[row];
    while (w->lj[e] != lo)
        e++;
    return (uint16_t)(RT_MAX_MBS_ROWS + e);
}

/* the slots of every pair (i <= k) of each block's touches */
static rt_status pair_slots(const rt_scene *sc, rt_sim *sim, uint8_t set, uint32_t *np)
{
    rt_mbs_work *w = &sim->work.mbs;
    for (uint16_t b = 0; b < sc->nblocks; b++) {
        if (!rti_mbs_in_set(sc, b, set))
            continue;
        uint16_t t0 = w->to[b], t1 = w->to[b + 1];
        if (*np + (uint32_t)(t1 - t0) * (t1 - t0 + 1) / 2 > RT_MAX_MBS_PAIRS)
            return rti_capacity(sim, "block ", sc->blocks[b].name, RT_LIM_MBS_PAIRS);
        w->po[b] = (uint16_t)*np;
        for (uint16_t i = t0; i < t1; i++)
            for (uint16_t k = i; k < t1; k++)
                w->pslot[(*np)++] = slot(w, set, w->trow[i], w->trow[k]);
        w->po[b + 1] = (uint16_t)*np;
    }
    return RT_OK;
}

rt_status rti_mbs_ldl_init(const rt_scene *sc, rt_sim *sim, uint8_t set, uint32_t *np)
{
    graph g; /* 4 bytes per 32 rows squared: 360 bytes at the default 40 rows */
    rt_mbs_work *w = &sim->work.mbs;
    uint16_t n = w->nc[set], base = w->rb[set];
    if ((uint32_t)base + n > RT_MAX_MBS_ROWS)
        return rti_capacity(sim, "set ", sc->sets[set].name, RT_LIM_MBS_ROWS);
    w->rb[set + 1] = (uint16_t)(base + n);
    touches_graph(sc, w, set, &g);
    order(&g, n, w->perm + base);
    /* L's row i: the positions j < i adjacent in the filled graph, ascending */
    uint32_t e = w->lp[base];
    for (uint16_t i = 0; i < n; i++) {
        for (uint16_t j = 0; j < i; j++)
            if (has(&g, w->perm[base + i], w->perm[base + j])) {
                if (e >= RT_MAX_MBS_LNZ)
                    return rti_capacity(sim, "set ", sc->sets[set].name, RT_LIM_MBS_LNZ);
                w->lj[e++] = j;
            }
        w->lp[base + i + 1] = (uint16_t)e;
    }
    return pair_slots(sc, sim, set, np);
}

/* ------------------------------------------------------------------ numeric phase */

void rti_mbs_ldl_clear(rt_mbs_work *w, uint8_t set)
{
    for (uint16_t i = w->rb[set]; i < w->rb[set + 1]; i++)
        w->lv[i] = 0;
    for (uint16_t e = w->lp[w->rb[set]]; e < w->lp[w->rb[set + 1]]; e++)
        w->lv[RT_MAX_MBS_ROWS + e] = 0;
}

int rti_mbs_ldl_factor(rt_mbs_work *w, uint8_t set)
{
    unsigned base = w->rb[set], n = w->rb[set + 1] - base;
    real_t *D = w->lv + base, *L = w->lv + (size_t)RT_MAX_MBS_ROWS;
    const uint16_t *lp = w->lp + base, *lj = w->lj;
    real_t u[RT_MAX_MBS_C]; /* row i so far: u[j] = L_ij D_j, zero outside its pattern */
    real_t big = 0;
    for (unsigned i = 0; i < n; i++) {
        big = D[i] > big ? D[i] : big; /* semidefinite: the largest entry is on it */
        u[i] = 0;
    }
    /* each row's pivot is judged against its own diagonal (a rod on a heavy body has a
       far smaller one than a rod on a light body, and is as independent: pendulums of
       1e6 and 1e-5 kg in one set lost the heavy one's rod to a threshold relative to the
       set's largest), but never below the tolerance times the set's scale (a row that
       restrains nothing, zero to roundoff, is still dropped) */
    real_t low = RT_MBS_PIVOT_TOL * (big > 0 ? big : 1);
    int bad = -1;
    uint16_t drop = 0;
    w->drop_row[set] = 0;
    for (unsigned i = 0; i < n; i++) {
        real_t d = D[i];
        real_t floor_ = RT_MBS_PIVOT_TOL * (d > low ? d : low);
        unsigned e0 = lp[i], e1 = lp[i + 1];
        for (unsigned e = e0; e < e1; e++) {
            unsigned j = lj[e];
            real_t t = L[e];
            /* L_jk D_k L_ik over row j's columns k < j; u is zero where row i has none,
               so all of it for row i's first entry (a chain's only one): skipped there,
               the same sum (t is never -0: A's slots sum from +0) */
            for (unsigned f = lp[j], f1 = e > e0 ? lp[j + 1] : f; f < f1; f++)
                t -= L[f] * u[lj[f]];
            /* a dropped row j has no column: L_ij = 0 */
            u[j] = D[j] != 0 ? t : 0;
            L[e] = D[j] != 0 ? t / D[j] : 0;
            d -= L[e] * u[j];
        }
        for (unsigned e = e0; e < e1; e++)
            u[lj[e]] = 0;
        if (i == 0 && rti_fault_due(RTI_FAULT_SINGULAR))
            d = -big - 1;
        if (!(d > floor_)) { /* (the rule passes this one comparison) */
            if (d >= -floor_) { /* depends on the rows before it: dropped */
                w->drop_row[set] = drop++ ? w->drop_row[set] : w->perm[base + i];
                d = 0;
            } else { /* indefinite or NaN: go on with the threshold */
                bad = bad < 0 ? (int)w->perm[base + i] : bad;
                d = floor_;
            }
        }
        D[i] = d;
    }
    w->ndrop[set] = drop;
    return bad;
}

int rti_mbs_ldl_solve(const rt_mbs_work *w, uint8_t set, real_t *v)
{
    unsigned base = w->rb[set], n = w->rb[set + 1] - base;
    const real_t *D = w->lv + base, *L = w->lv + (size_t)RT_MAX_MBS_ROWS;
    const uint16_t *lp = w->lp + base, *perm = w->perm + base, *lj = w->lj;
    /* row i reads y[j < i] only, each written before; gcc cannot see it where the limit
       is one row (the array becomes a scalar): y[0] is set for it, not the whole array
       (40 stores per solve at the default limit) */
    real_t y[RT_MAX_MBS_C];
    real_t scale = 0;
    int conflict = -1;
    y[0] = 0;
    if (w->ndrop[set])
        for (unsigned i = 0; i < n; i++)
            scale = rt_fmax(scale, rt_fabs(v[i]));
    for (unsigned i = 0; i < n; i++) { /* L y = P v */
        real_t t = v[perm[i]];
        for (unsigned e = lp[i], e1 = lp[i + 1]; e < e1; e++)
            t -= L[e] * y[lj[e]];
        y[i] = t;
    }
    for (unsigned i = 0; i < n; i++) {
        if (D[i] != 0) {
            y[i] /= D[i];
            continue;
        }
        /* a dropped row: what is left of its right-hand side is the conflict */
        if (!(rt_fabs(y[i]) <= RT_MBS_RES_TOL + RT_MBS_RANK_TOL * scale) && conflict < 0)
            conflict = perm[i];
        y[i] = 0;
    }
    for (unsigned i = n; i-- > 0;) { /* L^T x = y */
        real_t t = y[i];
        for (unsigned e = lp[i], e1 = lp[i + 1]; e < e1; e++)
            y[lj[e]] -= L[e] * t;
        v[perm[i]] = t;
    }
    return conflict;
}
