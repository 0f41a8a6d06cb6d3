/* order.c - evaluation order and loop classification (paper, section 3).
 *
 * Two graphs are searched for strongly connected components:
 *  - the block graph (an edge for every connection): a component with a cycle is a
 *    potential loop;
 *  - the port graph (output port -> output port when the first feeds an input that the
 *    second depends on directly): a component with a cycle is an actual loop, one that
 *    every block on it passes through by throughput.
 * The evaluation sequence walks the port graph in topological order and calls a block
 * again only when an output needs inputs that were not final at its last call. So a
 * potential loop costs a repeated call at most, and is solved by ordering alone.
 * An actual loop is torn: a depth-first search inside it marks the inputs that carry
 * its back edges (the loop-closing edges); without them the loop is acyclic, its calls
 * form one contiguous segment of the sequence, and the torn inputs become the unknowns
 * the loop solver iterates on. */
#include "rti.h"

/* block owning global output v: the first b whose outputs end after v (the last block
   if none), by bisection over the non-decreasing y_off */
static uint16_t block_of_y(const rt_sim *sim, uint16_t nb, uint16_t v)
{
    uint16_t lo = 0, hi = nb ? (uint16_t)(nb - 1) : 0; /* the answer lies in [lo, hi] */
    while (lo < hi) {
        uint16_t mid = (uint16_t)(lo + (hi - lo) / 2);
        if (sim->plan.y_off[mid + 1] > v)
            hi = mid;
        else
            lo = (uint16_t)(mid + 1);
    }
    return lo;
}

typedef struct graph_ctx {
    const rt_scene *sc;
    const rt_sim *sim;
} graph_ctx;

/* 1 if output j of kind k depends directly on its input i (a throughput) */
int rti_feeds(const rt_kind *k, uint16_t j, uint16_t i)
{
    switch (k->feed) {
    case RT_FEED_ALL:
        return 1;
    case RT_FEED_TABLE:
        return k->feed_table[j * k->nu + i] != 0;
    default:
        return 0;
    }
}

/* the successor cursor of the port graph packs the connection being scanned (high bits)
   and the next output of its destination to try (low bits) */
#define CURSOR_CONN_SHIFT 16
#define CURSOR_OUT_MASK 0xFFFFu

/* port graph: successors of output v are the outputs of each block it feeds that depend
   on the fed input */
static int port_next(const void *ctx, uint16_t v, uint32_t *cursor)
{
    const graph_ctx *g = ctx;
    const rt_scene *sc = g->sc;
    uint16_t a = block_of_y(g->sim, sc->nblocks, v);
    uint16_t ya = (uint16_t)(v - g->sim->plan.y_off[a]);
    for (uint32_t c = *cursor >> CURSOR_CONN_SHIFT; c < sc->nconns; c++) {
        const rt_conn *cn = &sc->conns[c];
        uint32_t j = (c == (*cursor >> CURSOR_CONN_SHIFT)) ? (*cursor & CURSOR_OUT_MASK) : 0;
        if (cn->from != a || cn->y != ya)
            continue;
        const rt_kind *k = sc->blocks[cn->to].kind;
        uint8_t src = g->sim->plan.src_kind[g->sim->plan.u_off[cn->to] + cn->u];
        if (src == RT_SRC_TORN || src == RT_SRC_XSET || src == RT_SRC_HELD)
            j = k->ny; /* a torn or cross-set input carries no algebraic edge */
        for (; j < k->ny; j++) {
            if (rti_feeds(k, (uint16_t)j, cn->u)) {
                *cursor = (c << CURSOR_CONN_SHIFT) | (j + 1);
                return g->sim->plan.y_off[cn->to] + (int)j;
            }
        }
        *cursor = (c + 1) << CURSOR_CONN_SHIFT;
    }
    *cursor = (uint32_t)sc->nconns << CURSOR_CONN_SHIFT;
    return -1;
}

/* block graph: successors of block v are the blocks its outputs are connected to */
static int block_next(const void *ctx, uint16_t v, uint32_t *cursor)
{
    const graph_ctx *g = ctx;
    while (*cursor < g->sc->nconns) {
        const rt_conn *cn = &g->sc->conns[(*cursor)++];
        if (cn->from == v && g->sc->blocks[cn->from].set == g->sc->blocks[cn->to].set)
            return cn->to; /* across sets a signal is sampled, so it closes no loop */
    }
    return -1;
}

/* a component is a loop if it has several nodes or a node that reaches itself; count and
   first: its nodes and its lowest node (component_sizes) */
static int is_cycle(rti_next_fn next, const graph_ctx *g, uint16_t count, uint16_t first)
{
    if (count > 1)
        return 1;
    uint32_t cur = 0;
    for (int s; (s = next(g, first, &cur)) >= 0;)
        if (s == first)
            return 1;
    return 0;
}

/* in one pass over the n nodes, each component's node count (into the search's index
   array, free once rti_scc has returned) and lowest node (into its low array) */
static void component_sizes(rt_scc_work *w, uint16_t n, uint16_t ncomp)
{
    for (uint16_t id = 0; id < ncomp; id++)
        w->index[id] = 0, w->low[id] = 0;
    for (uint16_t v = 0; v < n; v++)
        if (w->index[w->comp[v]]++ == 0)
            w->low[w->comp[v]] = v;
}

/* appends block b to loop being built, skipping repeats */
static void loop_add_block(rt_sim *sim, rt_loop *l, uint16_t b)
{
    for (uint16_t i = 0; i < l->nblocks; i++)
        if (sim->plan.loop_blocks[l->first + i] == b)
            return;
    sim->plan.loop_blocks[l->first + l->nblocks++] = b;
}

/* is block b on one of the actual loops recorded so far? */
static int in_actual_loop(const rt_sim *sim, uint16_t b)
{
    for (uint8_t l = 0; l < sim->plan.nloops; l++)
        for (uint16_t i = 0; sim->plan.loops[l].actual && i < sim->plan.loops[l].nblocks; i++)
            if (sim->plan.loop_blocks[sim->plan.loops[l].first + i] == b)
                return 1;
    return 0;
}

/* a block component that holds an actual loop is reported as that loop only */
static int holds_actual(const rt_sim *sim, const uint16_t *comp, uint16_t n, uint16_t id)
{
    for (uint16_t v = 0; v < n; v++)
        if (comp[v] == id && in_actual_loop(sim, v))
            return 1;
    return 0;
}

/* records every cyclic component of a graph as a loop */
static rt_status record_loops(const rt_scene *sc, rt_sim *sim, rti_next_fn next,
                              const graph_ctx *g, uint16_t n, uint16_t ncomp, int ports,
                              uint16_t *used)
{
    uint16_t *comp = sim->work.w.scc.comp;
    component_sizes(&sim->work.w.scc, n, ncomp);
    for (uint16_t id = 0; id < ncomp; id++) {
        uint16_t first = sim->work.w.scc.low[id];
        if (!is_cycle(next, g, sim->work.w.scc.index[id], first) ||
            (!ports && holds_actual(sim, comp, n, id)))
            continue;
        if (sim->plan.nloops >= RT_MAX_LOOPS)
            return rti_capacity(sim, 0, 0, RT_LIM_LOOPS);
        rt_loop *l = &sim->plan.loops[sim->plan.nloops++];
        l->actual = (uint8_t)ports;
        l->first = *used;
        l->nblocks = 0;
        l->seq0 = first; /* a port of the loop, where tearing starts its search */
        l->seq1 = l->torn0 = l->ntorn = l->h0 = 0;
        for (uint16_t v = 0; v < n; v++) {
            if (comp[v] != id)
                continue;
            uint16_t b = ports ? block_of_y(sim, sc->nblocks, v) : v;
            if (*used + l->nblocks >= 2 * RT_MAX_BLOCKS)
                return rti_fail(sim, RT_E_CAPACITY, "loop listing exceeds 2 * ", RTI_LIMIT(RT_MAX_BLOCKS),
                                (const char *)0);
            loop_add_block(sim, l, b);
        }
        *used = (uint16_t)(*used + l->nblocks);
    }
    return RT_OK;
}

/* position after which every input that output j of block b depends on is final */
static uint16_t inputs_ready(const rt_scene *sc, const rt_sim *sim, uint16_t b, uint16_t j)
{
    const rt_kind *k = sc->blocks[b].kind;
    uint16_t req = 0;
    for (uint16_t i = 0; i < k->nu; i++) {
        uint16_t gi = (uint16_t)(sim->plan.u_off[b] + i);
        if (sim->plan.src_kind[gi] != RT_SRC_Y || !rti_feeds(k, j, i))
            continue;
        uint16_t d = sim->work.w.scc.done[sim->plan.src[gi]];
        if (d > req)
            req = d;
    }
    return req;
}

/* appends one entry to the sequence */
static rt_status emit(rt_sim *sim, uint8_t kind, uint16_t index)
{
    if (sim->plan.nseq >= RT_MAX_SEQ)
        return rti_capacity(sim, 0, 0, RT_LIM_SEQ);
    sim->plan.seq[sim->plan.nseq].kind = kind;
    sim->plan.seq[sim->plan.nseq++].index = index;
    return RT_OK;
}

/* makes output v final: reuses the block's last call if it came after every input v
   needs (and after floor, the start of a loop segment), else calls the block again */
static rt_status place_port(const rt_scene *sc, rt_sim *sim, uint16_t v, uint16_t floor)
{
    rt_scc_work *w = &sim->work.w.scc;
    uint16_t b = block_of_y(sim, sc->nblocks, v);
    uint16_t req = inputs_ready(sc, sim, b, (uint16_t)(v - sim->plan.y_off[b]));
    req = req > floor ? req : floor;
    if (w->last[b] > req) {
        w->done[v] = w->last[b];
        return RT_OK;
    }
    rt_status st = emit(sim, RT_SEQ_CALL, b);
    w->last[b] = w->done[v] = sim->plan.nseq;
    return st;
}

/* one actual loop: a marker, then its ports in the order of the torn (acyclic) graph */
static rt_status place_loop(const rt_scene *sc, rt_sim *sim, uint16_t ny, uint16_t oid,
                            uint16_t nc_torn, int l)
{
    rt_scc_work *w = &sim->work.w.scc;
    rt_loop *lp = &sim->plan.loops[l];
    rt_status st = emit(sim, RT_SEQ_LOOP, (uint16_t)l);
    uint16_t floor = sim->plan.nseq;
    lp->seq0 = sim->plan.nseq;
    for (uint16_t id = nc_torn; id-- > 0 && st == RT_OK;)
        for (uint16_t v = 0; v < ny && st == RT_OK; v++)
            if (w->orig[v] == oid && w->comp[v] == id)
                st = place_port(sc, sim, v, floor);
    lp->seq1 = sim->plan.nseq;
    return st;
}

/* walks the original components in topological order; loops become segments */
static rt_status build_sequence(const rt_scene *sc, rt_sim *sim, uint16_t ny, uint16_t nc_orig,
                                uint16_t nc_torn, const uint8_t *is_loop)
{
    rt_scc_work *w = &sim->work.w.scc;
    rt_status st = RT_OK;
    for (uint16_t b = 0; b < sc->nblocks; b++)
        w->last[b] = 0;
    sim->plan.nseq = 0;
    /* the ports of each original component, ascending, by counting sort: component c's
       are stack[index[c] .. low[c]) (the search's arrays, free once rti_scc has returned) */
    uint16_t start = 0;
    for (uint16_t c = 0; c < nc_orig; c++)
        w->low[c] = 0;
    for (uint16_t v = 0; v < ny; v++)
        w->low[w->orig[v]]++;
    for (uint16_t c = 0; c < nc_orig; c++) {
        uint16_t count = w->low[c];
        w->index[c] = w->low[c] = start;
        start = (uint16_t)(start + count);
    }
    for (uint16_t v = 0; v < ny; v++)
        w->stack[w->low[w->orig[v]]++] = v;
    /* components are numbered sinks first: walk them from the highest id down */
    for (uint16_t oid = nc_orig; oid-- > 0 && st == RT_OK;) {
        int l = is_loop[oid] - 1; /* the actual loop of this component, or -1 */
        if (l >= 0) {
            st = place_loop(sc, sim, ny, oid, nc_torn, l);
            continue;
        }
        for (uint16_t i = w->index[oid]; i < w->low[oid] && st == RT_OK; i++)
            st = place_port(sc, sim, w->stack[i], 0);
    }
    return st;
}

/* marks input gi torn for loop l: its value becomes an unknown of the loop solver */
static rt_status tear_input(rt_sim *sim, uint16_t gi, rt_loop *lp)
{
    if (sim->plan.ntorn >= RT_MAX_TORN)
        return rti_capacity(sim, 0, 0, RT_LIM_TORN);
    sim->plan.torn_in[sim->plan.ntorn] = gi;
    sim->plan.torn_src[sim->plan.ntorn] = sim->plan.src[gi];
    sim->state.torn_val[sim->plan.ntorn] = 0;
    sim->plan.src_kind[gi] = RT_SRC_TORN;
    sim->plan.src[gi] = sim->plan.ntorn++;
    lp->ntorn++;
    return RT_OK;
}

/* depth-first search inside component id from root: every edge back to a port on the
   current path closes a loop, and its input is torn */
static rt_status tear_from(const graph_ctx *g, rt_sim *sim, uint16_t id, uint16_t root,
                           rt_loop *lp)
{
    rt_scc_work *w = &sim->work.w.scc;
    const rt_scene *sc = g->sc;
    uint16_t depth = 0;
    w->call[depth++] = root;
    w->color[root] = 1;
    w->cursor[root] = 0;
    while (depth > 0) {
        uint16_t v = w->call[depth - 1];
        int s = port_next(g, v, &w->cursor[v]);
        if (s < 0) {
            w->color[v] = 2;
            depth--;
            continue;
        }
        if (w->orig[s] != id)
            continue;
        if (w->color[s] == 1) {
            const rt_conn *cn = &sc->conns[(w->cursor[v] >> CURSOR_CONN_SHIFT)];
            rt_status st = tear_input(sim, (uint16_t)(sim->plan.u_off[cn->to] + cn->u), lp);
            if (st != RT_OK)
                return st;
        } else if (w->color[s] == 0) {
            w->color[s] = 1;
            w->cursor[s] = 0;
            w->call[depth++] = (uint16_t)s;
        }
    }
    return RT_OK;
}

/* tears every actual loop; is_loop[component] = loop index + 1 */
static rt_status tear_loops(const rt_scene *sc, rt_sim *sim, const graph_ctx *g, uint16_t ny,
                            uint8_t nactual, uint8_t *is_loop)
{
    rt_scc_work *w = &sim->work.w.scc;
    uint16_t h = 0;
    sim->plan.ntorn = 0;
    for (uint16_t v = 0; v < ny; v++)
        w->color[v] = 0;
    for (uint8_t l = 0; l < nactual; l++) {
        rt_loop *lp = &sim->plan.loops[l];
        uint16_t root = lp->seq0; /* record_loops left a port of the loop here */
        uint16_t id = w->orig[root];
        lp->torn0 = sim->plan.ntorn, lp->ntorn = 0, lp->h0 = h;
        is_loop[id] = (uint8_t)(l + 1);
        rt_status st = tear_from(g, sim, id, root, lp);
        if (st != RT_OK)
            return st;
        h = (uint16_t)(h + lp->ntorn * lp->ntorn);
    }
    (void)sc;
    return RT_OK;
}

rt_status rti_order(const rt_scene *sc, rt_sim *sim)
{
    graph_ctx g = {sc, sim};
    rt_scc_work *w = &sim->work.w.scc;
    uint16_t ny = sim->plan.y_off[sc->nblocks], used = 0;
    uint8_t is_loop[RT_MAX_NODES];
    rt_status st;
    sim->plan.nloops = 0;
    sim->plan.ntorn = 0;

    /* actual loops: cycles of the port graph */
    uint16_t nc_orig = rti_scc(ny, port_next, &g, w, w->comp);
    st = record_loops(sc, sim, port_next, &g, ny, nc_orig, 1, &used);
    if (st != RT_OK)
        return st;
    uint8_t nactual = sim->plan.nloops;
    for (uint16_t v = 0; v < ny; v++)
        w->orig[v] = w->comp[v];
    for (uint16_t c = 0; c < nc_orig; c++)
        is_loop[c] = 0;

    /* potential loops: cycles of the block graph that hold no actual loop */
    uint16_t nc = rti_scc(sc->nblocks, block_next, &g, w, w->comp);
    st = record_loops(sc, sim, block_next, &g, sc->nblocks, nc, 0, &used);
    if (st != RT_OK)
        return st;
    if (nactual > 0 && !sc->loop_solver) {
        const rt_loop *l = &sim->plan.loops[0];
        return rti_fail(sim, RT_E_LOOP, "actual algebraic loop through block ",
                        sc->blocks[sim->plan.loop_blocks[l->first]].name,
                        " and the scene names no loop solver", (const char *)0);
    }

    /* tear them, then order the now acyclic graph */
    st = tear_loops(sc, sim, &g, ny, nactual, is_loop);
    if (st != RT_OK)
        return st;
    uint16_t nc_torn = rti_scc(ny, port_next, &g, w, w->comp);
    return build_sequence(sc, sim, ny, nc_orig, nc_torn, is_loop);
}
