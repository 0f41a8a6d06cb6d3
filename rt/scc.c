/* scc.c - Tarjan's strongly connected components, iterative, on static scratch.
 *
 * Used at init on two graphs: the port-level throughput graph (actual loops and the
 * evaluation order) and the block-level connection graph (potential loops). Iterative,
 * because the recursion depth of the textbook version is the graph size and an embedded
 * stack should not depend on the scene. */
#include "rti.h"

#define UNVISITED 0xFFFFu

/* pops one component ending at root v; returns the next component id */
static uint16_t pop_component(rti_scc_work *w, uint16_t *sp, uint16_t v, uint16_t id,
                              uint16_t *comp)
{
    uint16_t u;
    do {
        u = w->stack[--*sp];
        w->on[u] = 0;
        comp[u] = id;
    } while (u != v);
    return (uint16_t)(id + 1);
}

static uint16_t min16(uint16_t a, uint16_t b) { return a < b ? a : b; }

uint16_t rti_scc(uint16_t n, rti_next_fn next, const void *ctx, rti_scc_work *w,
                 uint16_t *comp)
{
    uint16_t counter = 0, ncomp = 0, sp = 0;
    for (uint16_t v = 0; v < n; v++) {
        w->index[v] = UNVISITED;
        w->on[v] = 0;
        w->cursor[v] = 0;
    }
    for (uint16_t root = 0; root < n; root++) {
        if (w->index[root] != UNVISITED)
            continue;
        /* depth-first search with an explicit call stack */
        uint16_t depth = 0;
        w->call[depth++] = root;
        w->index[root] = w->low[root] = counter++;
        w->stack[sp++] = root;
        w->on[root] = 1;
        while (depth > 0) {
            uint16_t v = w->call[depth - 1];
            int s = next(ctx, v, &w->cursor[v]);
            if (s >= 0) {
                uint16_t u = (uint16_t)s;
                if (w->index[u] == UNVISITED) {
                    /* descend */
                    w->index[u] = w->low[u] = counter++;
                    w->stack[sp++] = u;
                    w->on[u] = 1;
                    w->call[depth++] = u;
                } else if (w->on[u]) {
                    w->low[v] = min16(w->low[v], w->index[u]);
                }
                continue;
            }
            /* v is finished: close its component, then return to the caller */
            if (w->low[v] == w->index[v])
                ncomp = pop_component(w, &sp, v, ncomp, comp);
            depth--;
            if (depth > 0) {
                uint16_t p = w->call[depth - 1];
                w->low[p] = min16(w->low[p], w->low[v]);
            }
        }
    }
    return ncomp;
}
