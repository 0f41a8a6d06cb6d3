/* step.c - one step of one set: the integrator, then state events (the paper's roots).
 *
 * A root crossing found at the end of a step is located by the Illinois variant of
 * regula falsi, re-stepping from the saved state to trial fractions of the step, at most
 * RT_EVENT_ITER_MAX times. The block's event handler runs at the right end of the final
 * bracket (just past the crossing, so the condition has definitely fired), and the step
 * is finished from there. At most RT_EVENTS_PER_STEP_MAX events per step: the work of a
 * tick stays bounded whatever the model does. */
#include "rti.h"

/* max(1, max_i |x_i|), NaN if x holds one. Taken on the bits: |x|'s bits (the sign
   cleared) order as the values do for every non-negative value, inf's are RT_EXP_BITS and
   a NaN's more, so an integer maximum per value gives the same bits with no compare of
   reals (a call each on a soft-float target) and no branch. An integer maximum is exact
   in any order: four states per iteration, two into each of two maxima, quarter the
   loop's own count and test. With xs, x is also kept there (the state a failed step goes
   back to, rti_step_set, an event's re-steps start from, trial, and the method reads as
   the step's start, rt_iwork.xs), in the same pass */
#define RT_ABS_BITS(v) ((v).u & ~RT_SIGN_BIT)
#define RT_MAX_BITS(m, a) ((a) > (m) ? (a) : (m))
static RTI_INLINE real_t norm_bits(const real_t *x, real_t *xs, uint16_t n)
{
    rt_real_bits m0 = ((rt_real_rep){.r = 1}).u, m1 = m0;
    uint32_t i = 0;
    for (; i + 4u <= n; i += 4u) {
        rt_real_rep v0 = {.r = x[i]}, v1 = {.r = x[i + 1u]}, v2 = {.r = x[i + 2u]},
                    v3 = {.r = x[i + 3u]};
        if (xs) /* as read: a store to xs makes no reload of x */
            xs[i] = v0.r, xs[i + 1u] = v1.r, xs[i + 2u] = v2.r, xs[i + 3u] = v3.r;
        m0 = RT_MAX_BITS(m0, RT_ABS_BITS(v0)), m1 = RT_MAX_BITS(m1, RT_ABS_BITS(v1));
        m0 = RT_MAX_BITS(m0, RT_ABS_BITS(v2)), m1 = RT_MAX_BITS(m1, RT_ABS_BITS(v3));
    }
    for (; i < n; i++) { /* the last states of a count not a multiple of four, alone */
        rt_real_rep v = {.r = x[i]};
        if (xs)
            xs[i] = v.r;
        m0 = RT_MAX_BITS(m0, RT_ABS_BITS(v));
    }
    rt_real_rep m = {.u = RT_MAX_BITS(m0, m1)};
    return m.r; /* (a NaN with its sign cleared where x holds one) */
}
#undef RT_ABS_BITS
#undef RT_MAX_BITS

static real_t norm(const real_t *x, uint16_t n) { return norm_bits(x, 0, n); }

static real_t keep_norm(const real_t *x, real_t *xs, uint16_t n)
{
    return norm_bits(x, xs, n);
}

/* an explicit method past its stability limit multiplies the state by |R(h lambda)| > 1
   every step: RT_GROWTH_STEPS steps in a row of growth by RT_GROWTH_FACTOR are counted
   (unstable) long before the values overflow */
static void watch_growth(rt_sim *sim, uint8_t s, real_t before, real_t after)
{
    uint8_t *g = &sim->stats.growth[s];
    *g = after > (real_t)RT_GROWTH_FACTOR * before ? (uint8_t)(*g + 1) : 0;
    if (*g >= RT_GROWTH_STEPS) {
        rti_count(sim, RT_CNT_UNSTABLE, -1, RT_E_UNSTABLE);
        sim->stats.unstable[s]++;
        *g = 0;
    }
}

/* the integrator's workspace of set s */
static void iwork_of(const rt_scene *sc, rt_sim *sim, uint8_t s, rt_iwork *w)
{
    for (int i = 0; i < RT_MAX_STAGES; i++)
        w->k[i] = sim->work.w.k[i];
    w->x0 = sim->work.x0, w->xs = 0;
#if RT_MAX_TRANSITION_N > 0
    w->tm = sim->work.tm;
#else
    w->tm = 0; /* no set of this build's scene takes the transition method (rt/eval.c) */
#endif
    w->imp = &sim->state.imp[s];
    w->stats = &sim->stats.istats[s];
    w->cfg = &sc->sets[s].cfg;
    w->autonomous = (sim->plan.set_flags[s] & RTI_SET_AUTONOMOUS) != 0;
}

void rti_prime_set(const rt_scene *sc, rt_sim *sim, uint8_t s, real_t t, real_t h)
{
    const rt_integrator *m = sc->sets[s].method;
    if (!m->prime || (sim->plan.set_flags[s] & RTI_SET_NO_STEP))
        return;
    rti_rhs_ctx ctx = {sc, sim, s, h};
    rt_rhs f = {rti_rhs, &ctx};
    rt_iwork w;
    uint16_t x0 = sim->plan.set_x[s], n = (uint16_t)(sim->plan.set_x[s + 1] - x0);
    iwork_of(sc, sim, s, &w);
    m->prime(m, &f, t, h, sim->state.x + x0, n, &w);
}

/* integrates the set from t by h in place (its state before the step kept in work.xs,
   where the method reads it too), then post-stabilizes its multibody part (eq. 10); a
   step that ended above its residual tolerance is counted as degraded.
   Returns the final state's norm, after the projection (NaN or inf if a value is not
   finite): one pass serves the growth watch and the finite check */
static real_t integrate(const rt_scene *sc, rt_sim *sim, uint8_t s, real_t t, real_t h)
{
    rti_rhs_ctx ctx = {sc, sim, s, h};
    rt_rhs f = {rti_rhs, &ctx};
    rt_iwork w;
    uint16_t x0 = sim->plan.set_x[s], n = (uint16_t)(sim->plan.set_x[s + 1] - x0);
    iwork_of(sc, sim, s, &w);
    if (sim->state.param_changed[s]) /* a parameter changed since the last step */
        sim->state.imp[s].valid = 0, sim->state.param_changed[s] = 0;
    uint32_t split = w.stats->substepped;
    real_t before = keep_norm(sim->state.x + x0, sim->work.xs, n);
    w.xs = sim->work.xs; /* one copy of the start: the method need not make its own */
    w.stats->last_err = 0;
    uint64_t r0 = sim->stats.rhs_evals[s];
    rt_status st = sc->sets[s].method->step(sc->sets[s].method, &f, t, h, sim->state.x + x0, n, &w);
    if (sim->stats.rhs_evals[s] - r0 > w.stats->rhs_step_max) /* the work bound's witness */
        w.stats->rhs_step_max = (uint32_t)(sim->stats.rhs_evals[s] - r0);
    if (st == RT_E_NOCONV)
        rti_count(sim, RT_CNT_DEGRADED, -1, RT_E_DEGRADED);
    else if (st == RT_E_SINGULAR)
        rti_count(sim, RT_CNT_SINGULAR, -1, RT_E_SINGULAR);
    else if (st == RT_E_DAMPED)
        rti_count(sim, RT_CNT_DAMPED, -1, RT_E_DAMPED);
    if (w.stats->substepped != split)
        rti_count(sim, RT_CNT_SUBSTEP, -1, RT_OK); /* recovered: reported, not a fault */
    real_t acc = rti_accuracy(w.cfg);
    real_t e = w.stats->last_err; /* a NaN estimate is the nan counter's (below) */
    if (e == e && !(e <= acc)) {
        rti_count(sim, RT_CNT_ERREST, -1,
                  w.stats->last_err <= RT_ERR_LOST ? RT_E_ACCURACY : RT_E_LOST);
        sim->stats.errest[s]++;
    }
    /* projects when stab is RT_STAB_PROJECT; otherwise refreshes recorded reactions */
    if (sc->mbs && sim->work.mbs.nz[s] > 0)
        sc->mbs->project(sc, sim, s, t + h);
    real_t after = norm(sim->state.x + x0, n);
    watch_growth(sim, s, before, after);
    return after;
}

/* the event bookkeeping of one set's roots: levels and sides (rt_state.r_lvl, r_side),
   whether a root going NaN is taken for a crossing to locate (class "lost", below) */
typedef struct rootset {
    real_t *lvl;
    int8_t *side;
    int lost;   /* 1: a root that ends NaN from a finite start is located (finite state) */
} rootset;

static rootset roots_of(rt_sim *sim, uint8_t s)
{
    uint16_t r0 = sim->plan.set_r[s];
    return (rootset){sim->state.r_lvl + r0, sim->state.r_side + r0, 0};
}

/* does a held root of a kind that asks for every sign change (rt_kind.roots_every_sign)
   return from ra to rb to the side of zero it was held from (an FMU's ball lifting off
   after its impact): a crossing too, besides leaving its level */
static int returned(const rt_kind *k, real_t ra, real_t rb, int side)
{
    return k->roots_every_sign && side != 0 && (real_t)side * ra <= 0 && (real_t)side * rb > 0;
}

int rti_root_crossed(const rt_kind *k, uint16_t i, real_t ra, real_t rb, real_t lvl, int side)
{
    if (side != 0)
        return ((real_t)side * (ra - lvl) >= 0 && (real_t)side * (rb - lvl) < 0) ||
               returned(k, ra, rb, side);
    int dir = k->root_dir ? k->root_dir[i] : 0;
    int down = ra > 0 && rb <= 0, up = ra < 0 && rb >= 0;
    return dir < 0 ? down : dir > 0 ? up : (down || up);
}

/* the side root i was on before a crossing from ra to rb: +1 above its level, -1 below */
static int8_t side_before(const rt_kind *k, uint16_t i, real_t ra, real_t rb, real_t lvl,
                          int side)
{
    int dir = k->root_dir ? k->root_dir[i] : 0;
    if (returned(k, ra, rb, side))
        return (int8_t)-side;
    return (int8_t)(side != 0 ? side : dir != 0 ? -dir : ra - lvl > 0 ? 1 : -1);
}

/* the next block of set s with roots from its k-th (plan.set_blk, the order of
   rti_roots), advancing k; sc->nblocks past the last. Every walk of a set's roots
   below goes block by block so, from k = plan.blk_of[s], root n counting on */
static uint16_t next_root_block(const rt_scene *sc, const rt_sim *sim, uint8_t s, uint16_t *k)
{
    while (*k < sim->plan.blk_of[s + 1]) {
        uint16_t b = sim->plan.set_blk[(*k)++];
        if (sc->blocks[b].kind->nr > 0)
            return b;
    }
    return sc->nblocks;
}

/* where between ra (0) and rb (1) a root's straight line meets its level: the order in
   which crossings of one interval came (1 where the line says nothing: flat, or NaN) */
static real_t crossing_at(real_t ra, real_t rb, real_t lvl)
{
    real_t fa = ra - lvl, fb = rb - lvl, th = fa / (fa - fb);
    return th >= 0 && th <= 1 ? th : 1;
}

/* the root of the set crossing between ra and rb (or, rs->lost, going NaN from a finite
   value) that crossed first by its straight line between them, the first in block order
   among equals; -1 if none. With two crossings in one interval the earlier must be
   located and handled first: taking the first in block order would run both handlers at
   the later one's time. Writes the owning block into *blk and the root's index within it
   into *which. */
static int find_crossing(const rt_scene *sc, const rt_sim *sim, uint8_t s, const rootset *rs,
                         const real_t *ra, const real_t *rb, uint16_t *blk, uint16_t *which)
{
    uint16_t n = 0, j = sim->plan.blk_of[s];
    int best = -1;
    real_t at = 2;
    for (uint16_t b; (b = next_root_block(sc, sim, s, &j)) < sc->nblocks;) {
        const rt_kind *k = sc->blocks[b].kind;
        for (uint16_t i = 0; i < k->nr; i++, n++) {
            real_t th;
            if (rti_root_crossed(k, i, ra[n], rb[n], rs->lvl[n], rs->side[n]))
                th = crossing_at(ra[n], rb[n], rs->lvl[n]);
            else if (rs->lost && ra[n] == ra[n] && rb[n] != rb[n])
                th = 1;
            else
                continue;
            if (th < at)
                best = n, at = th, *blk = b, *which = i;
        }
    }
    return best;
}

/* state at fraction th of the step from the saved start state, with its roots in r */
static void trial(const rt_scene *sc, rt_sim *sim, uint8_t s, real_t t, real_t h, real_t th,
                  real_t *r)
{
    uint16_t x0 = sim->plan.set_x[s], n = (uint16_t)(sim->plan.set_x[s + 1] - x0);
    for (uint16_t i = 0; i < n; i++)
        sim->state.x[x0 + i] = sim->work.xs[i];
    integrate(sc, sim, s, t, th * h);
    rti_outputs(sc, sim, (rti_at){t + th * h, s, RTI_IN_STEP});
    rti_roots(sc, sim, s, t + th * h, r);
}

typedef struct bracket {
    real_t a, b;   /* fractions of the step around the crossing */
    real_t ra, rb; /* the located root's values there (rb NaN: where it went NaN) */
    int root;      /* root index within the set */
} bracket;

/* narrows the bracket by Illinois regula falsi (bisection while rb is NaN); leaves the
   state at its right end in xb */
static void locate(const rt_scene *sc, rt_sim *sim, uint8_t s, real_t t, real_t h, bracket *k,
                   const rootset *rs, const real_t *r_start)
{
    uint16_t x0 = sim->plan.set_x[s], n = (uint16_t)(sim->plan.set_x[s + 1] - x0);
    int side = 0;
    uint32_t it = 0;
    /* rb == 0: the right end sits exactly on the root, nothing left to narrow */
    for (; it < RT_EVENT_ITER_MAX && k->b - k->a > RT_EVENT_TTOL && k->rb != 0; it++) {
        /* the secant through the values relative to the root's level */
        real_t lv = rs->lvl[k->root], fa = k->ra - lv, fb = k->rb - lv;
        real_t th = (k->a * fb - k->b * fa) / (fb - fa);
        if (!(th > k->a && th < k->b))
            th = (real_t)0.5 * (k->a + k->b);
        /* keep the trial half a tolerance inside the bracket: once the secant sits on the
           root, the next trial lands on the other side and the bracket collapses */
        real_t guard = (real_t)0.5 * RT_EVENT_TTOL;
        th = th < k->a + guard ? k->a + guard : th > k->b - guard ? k->b - guard : th;
        trial(sc, sim, s, t, h, th, sim->work.rs);
        uint16_t blk, which;
        /* an earlier crossing of any root in [a, th] takes over the bracket */
        int c = find_crossing(sc, sim, s, rs, r_start, sim->work.rs, &blk, &which);
        if (c >= 0) {
            k->root = c, k->b = th, k->rb = sim->work.rs[c];
            for (uint16_t i = 0; i < n; i++)
                sim->work.xb[i] = sim->state.x[x0 + i];
            k->ra = side == -1 ? lv + (k->ra - lv) * (real_t)0.5 : k->ra; /* Illinois */
            side = -1;
        } else {
            k->a = th, k->ra = sim->work.rs[k->root];
            k->rb = side == 1 ? lv + (k->rb - lv) * (real_t)0.5 : k->rb;
            side = 1;
        }
    }
    if (it > sim->stats.event_iter_max)
        sim->stats.event_iter_max = it;
    if (k->b - k->a > RT_EVENT_TTOL && k->rb != 0)
        rti_count(sim, RT_CNT_EVENT_NOLOC, -1, RT_E_NOLOC);
}

/* runs, at the located time te with the state in xb, the handler of every root that
   crossed since the start of the (sub)step (roots r_start): the located one and any
   crossing at the same time, e.g. two bodies hitting their floors together, which would
   otherwise start the rest of the step on the wrong side and never be seen again.
   Handlers run in root order, each with the outputs after the previous one. The side
   each fired root came from is written into fired (0: did not fire). */
static void fire(const rt_scene *sc, rt_sim *sim, uint8_t s, real_t te, const rootset *rs,
                 const real_t *r_start, int8_t *fired)
{
    uint16_t x0 = sim->plan.set_x[s], n = (uint16_t)(sim->plan.set_x[s + 1] - x0), m = 0;
    uint16_t j = sim->plan.blk_of[s];
    for (uint16_t i = 0; i < n; i++)
        sim->state.x[x0 + i] = sim->work.xb[i];
    rti_outputs(sc, sim, (rti_at){te, s, RTI_IN_STEP});
    rti_roots(sc, sim, s, te, sim->work.rs);
    for (uint16_t b; (b = next_root_block(sc, sim, s, &j)) < sc->nblocks;) {
        const rt_kind *k = sc->blocks[b].kind;
        for (uint16_t i = 0; i < k->nr; i++, m++) {
            fired[m] = 0;
            if (!rti_root_crossed(k, i, r_start[m], sim->work.rs[m], rs->lvl[m], rs->side[m]))
                continue;
            fired[m] = side_before(k, i, r_start[m], sim->work.rs[m], rs->lvl[m], rs->side[m]);
            rt_args a;
            rti_gather(sim, b, te);
            rti_args(sc, sim, b, te, 0, &a);
            k->event(&a, i, sim->state.x + sim->plan.x_off[b], sim->state.d + sim->plan.d_off[b]);
            rti_count(sim, RT_CNT_EVENTS, b, RT_OK);
            rti_outputs(sc, sim, (rti_at){te, s, RTI_IN_STEP});
        }
    }
}

/* after fire at te: a handler that moved another root of the set past its level there
   (a handler's output another block's `when` watches) runs that root's handler too, at
   te, in rounds until none crosses: each root's crossing is judged from its value before
   the round's handlers, or after its own where it fired. RT_EVENTS_PER_STEP_MAX rounds
   at most (past them counted event_limit, block -1). fired gathers the roots that fired */
static void cascade(const rt_scene *sc, rt_sim *sim, uint8_t s, real_t te, const rootset *rs,
                    int8_t *fired)
{
    uint16_t x0 = sim->plan.set_x[s], n = (uint16_t)(sim->plan.set_x[s + 1] - x0);
    real_t start[RT_MAX_ROOTS], now[RT_MAX_ROOTS];
    int8_t last[RT_MAX_ROOTS] = {0}, more[RT_MAX_ROOTS] = {0};
    uint16_t nr = (uint16_t)(sim->plan.set_r[s + 1] - sim->plan.set_r[s]);
    for (uint16_t m = 0; m < nr; m++)
        start[m] = sim->work.rs[m], last[m] = fired[m];
    for (int round = 0;; round++) {
        uint16_t m = 0, j = sim->plan.blk_of[s];
        int any = 0;
        rti_roots(sc, sim, s, te, now);
        for (uint16_t b; (b = next_root_block(sc, sim, s, &j)) < sc->nblocks;) {
            const rt_kind *k = sc->blocks[b].kind;
            for (uint16_t i = 0; i < k->nr; i++, m++) {
                /* (a handler that puts a root exactly on its level, a stop's v = 0,
                   does not cross it) */
                start[m] = last[m] || now[m] == rs->lvl[m] ? now[m] : start[m];
                any |= rti_root_crossed(k, i, start[m], now[m], rs->lvl[m], rs->side[m]);
            }
        }
        if (!any)
            return;
        if (round + 1 >= RT_EVENTS_PER_STEP_MAX) {
            rti_count(sim, RT_CNT_EVENT_LIMIT, -1, RT_E_EVENT);
            return;
        }
        for (uint16_t i = 0; i < n; i++)
            sim->work.xb[i] = sim->state.x[x0 + i];
        fire(sc, sim, s, te, rs, start, more);
        for (m = 0; m < nr; m++) {
            last[m] = more[m];
            if (more[m] != 0)
                fired[m] = more[m];
        }
    }
}

/* the roots of the set one Euler step of length tau ahead of the state at t, into r: the
   sign of each root's motion (its first-order rate), whatever the curvature of the path
   beyond. The state and the outputs at t are left as they were. */
static void probe(const rt_scene *sc, rt_sim *sim, uint8_t s, real_t t, real_t tau, real_t *r)
{
    uint16_t x0 = sim->plan.set_x[s], n = (uint16_t)(sim->plan.set_x[s + 1] - x0);
    real_t *x = sim->state.x + x0, *f = sim->work.w.k[0], *keep = sim->work.xb;
    rti_rhs_ctx ctx = {sc, sim, s, tau};
    rti_rhs(&ctx, t, f);
    for (uint16_t i = 0; i < n; i++)
        keep[i] = x[i], x[i] = x[i] + tau * f[i];
    rti_outputs(sc, sim, (rti_at){t + tau, s, RTI_IN_STEP});
    rti_roots(sc, sim, s, t + tau, r);
    for (uint16_t i = 0; i < n; i++)
        x[i] = keep[i];
    rti_outputs(sc, sim, (rti_at){t, s, RTI_IN_STEP});
}

/* after the handlers at te (roots r there): each fired root the handlers did not put back
   on its side of zero. The handler ran just past the crossing, so a bounce leaves its
   root a hair on the far side, moving back: crossing zero again on the way out and once
   more on the way down within one step (a flight shorter than the step) shows no sign
   change at the step's end, and the body tunnels. So the root's motion is probed: sent
   back, it is held on its side of the level it was handled at (less a margin): leaving
   that level again is its next crossing. Stopped there (a directional root, or a guard),
   the same. A root fired by an input's jump (jumped: at the step's start, rt/held.c) is
   freed whatever its motion: it stands where the jump left it, past its level, not a hair
   from it, and a level held there would count every later jump a crossing (a counter of a
   sampled staircase crossing its level once). Moving on (a handler that only counts a
   pass), it waits to be seen on its side again, unless it was held when it fired: a
   contact whose handler let it through fires again at once (its handler turns it back, or
   the per-step bound counts it), never silently. A root of a kind that asks for every
   sign change (rt_kind.roots_every_sign, FMI's event indicators) is held the same way,
   and its return to the side of zero it was held from is a crossing too (returned): fired
   by that, it is free. A free root the handlers left exactly on zero (the located end
   sat on it) shows no sign change however it moves on: it is moved a hair to the side the
   probe sends it, so that leaving zero again in the rest of the step is seen (a crest
   above a level inside one step: up at te, down before the step ends); not at the
   step's end (rest 0), where the tick takes the root's value afresh and a hair left
   there would read as a jump across the level (rt/held.c keep_jumped: fired again).
   Returns the probe's length if such a root was sent back and the probe finds it back on
   its side, so that the next integration ends there and its return is located, else 0 */
static real_t settle(const rt_scene *sc, rt_sim *sim, uint8_t s, real_t te, real_t h,
                     real_t t_max, const rootset *rs, const int8_t *fired, real_t *r,
                     int jumped, int rest)
{
    uint16_t m = 0, j = sim->plan.blk_of[s];
    uint8_t done[RT_MAX_ROOTS];
    int far = 0;
    for (uint16_t b; (b = next_root_block(sc, sim, s, &j)) < sc->nblocks;) {
        const rt_kind *k = sc->blocks[b].kind;
        for (uint16_t i = 0; i < k->nr; i++, m++) {
            int back = k->roots_every_sign && rs->side[m] != 0 && fired[m] == -rs->side[m];
            done[m] = fired[m] == 0 || (real_t)fired[m] * r[m] > 0 || back || jumped;
            if (fired[m] != 0 && done[m])
                rs->lvl[m] = 0, rs->side[m] = 0; /* put back on its side, or returned */
            far |= !done[m];
        }
    }
    m = 0, j = sim->plan.blk_of[s];
    if (!far)
        return 0;
    real_t *rp = sim->work.rs, tau = h * RT_EVENT_PROBE, cap = 0;
    /* never past a time event known at run time (an FMU is never evaluated beyond its
       nextEventTime, rt/tev.c); t_max is RT_TEV_NEVER otherwise */
    tau = te + tau > t_max ? t_max - te : tau;
    probe(sc, sim, s, te, tau, rp);
    for (uint16_t b; (b = next_root_block(sc, sim, s, &j)) < sc->nblocks;) {
        const rt_kind *k = sc->blocks[b].kind;
        for (uint16_t i = 0; i < k->nr; i++, m++) {
            int8_t sd = fired[m];
            if (done[m])
                continue;
            real_t d = rp[m] - r[m], v = (real_t)sd * d;
            if (k->roots_every_sign && v > 0 && (real_t)sd * rp[m] > 0)
                cap = tau;
            int held = (k->root_dir && k->root_dir[i] != 0) || (k->root_guard && k->root_guard[i]);
            if (v > 0)
                rs->side[m] = sd, rs->lvl[m] = r[m] - d * RT_EVENT_MARGIN;
            else if ((v == 0 && held) || rs->side[m] != 0)
                rs->side[m] = sd, rs->lvl[m] = r[m];
            else
                rs->side[m] = 0, rs->lvl[m] = 0;
        }
    }
    for (uint16_t i = 0; rest && i < m; i++) /* (m: the set's roots, counted above) */
        if (r[i] == 0 && rs->side[i] == 0 && rp[i] != 0 && rp[i] == rp[i])
            r[i] = rp[i] > 0 ? RTI_ROOT_HAIR : -RTI_ROOT_HAIR;
    return cap;
}

/* a guard root (rt_kind.root_guard, a floor, or a root a handler sent back to its side)
   that ends the step beyond its level and further than it started, with no crossing
   located: the model tunnels through its floor */
static void check_guards(const rt_scene *sc, rt_sim *sim, uint8_t s, const rootset *rs,
                         const real_t *ra, const real_t *rb)
{
    uint16_t n = 0, j = sim->plan.blk_of[s];
    for (uint16_t b; (b = next_root_block(sc, sim, s, &j)) < sc->nblocks;) {
        const rt_kind *k = sc->blocks[b].kind;
        for (uint16_t i = 0; i < k->nr; i++, n++) {
            int sd = rs->side[n] != 0 ? rs->side[n] : k->root_guard && k->root_guard[i];
            real_t side = (real_t)sd;
            if (sd != 0 && side * (rb[n] - rs->lvl[n]) < 0 && side * rb[n] < side * ra[n])
                rti_count(sim, RT_CNT_INVARIANT, b, RT_E_INVARIANT);
        }
    }
}

/* a root seen on its side of zero is free of its level again */
static void release(uint16_t nr, const rootset *rs, const real_t *r)
{
    for (uint16_t i = 0; i < nr; i++)
        if (rs->side[i] != 0 && (real_t)rs->side[i] * r[i] > 0)
            rs->side[i] = 0, rs->lvl[i] = 0;
}

/* the first block of set s with a NaN root in r, or -1 */
static int nan_root_block(const rt_scene *sc, const rt_sim *sim, uint8_t s, const real_t *r)
{
    uint16_t n = 0, j = sim->plan.blk_of[s];
    for (uint16_t b; (b = next_root_block(sc, sim, s, &j)) < sc->nblocks;) {
        const rt_kind *k = sc->blocks[b].kind;
        for (uint16_t i = 0; i < k->nr; i++, n++)
            if (r[n] != r[n])
                return b;
    }
    return -1;
}

/* the latest time the probe after an event may reach: the set's next time event known at
   run time (rt/tev.c), if it has them; else no limit */
static real_t probe_limit(const rt_scene *sc, rt_sim *sim, uint8_t s, real_t t)
{
    if (!(sim->plan.set_flags[s] & RTI_SET_TEV_DYN))
        return (real_t)RT_TEV_NEVER;
    return rti_tev_dyn_next(sc, sim, s, t);
}

/* what the inputs a set reads from other sets may do to its event at te (the state
   before the handlers in xb and in the set's state): the located root c's share, in its
   units, and the handled state's, relative (|dx_i| / (1 + |x_i|)), summed over the inputs
   by rti_xset_shifted (event_effect_of) */
typedef struct event_effect {
    const rt_scene *sc;
    rt_sim *sim;
    uint8_t s;
    real_t te;
    int c;              /* the located root, within the set */
    uint16_t blk, which; /* its block and its index there */
    int run;            /* 1: the handler may be run on trial (a kind without a state of its
                           own, rt_kind.save, whose discrete state fits a stage buffer) */
    real_t r0, dr, dx;  /* the root unshifted; the sums */
    real_t window;      /* the longest window an input moving the root misses over */
} event_effect;

/* block blk's handler `which` run at t on the state before it (at te), its result (the
   block's states) into out; the state and discrete state as they were after */
static void handled(const event_effect *e, real_t t, real_t *out)
{
    rt_sim *sim = e->sim;
    const rt_kind *kd = e->sc->blocks[e->blk].kind;
    real_t *x = sim->state.x + sim->plan.x_off[e->blk], *d = sim->state.d + sim->plan.d_off[e->blk];
    real_t *keep_d = sim->work.w.k[4];
    uint16_t xs = (uint16_t)(sim->plan.x_off[e->blk] - sim->plan.set_x[e->s]);
    for (uint16_t i = 0; i < kd->nd; i++)
        keep_d[i] = d[i];
    rt_args a;
    rti_gather(sim, e->blk, t);
    rti_args(e->sc, sim, e->blk, t, 0, &a);
    kd->event(&a, e->which, x, d);
    for (uint16_t i = 0; i < kd->nx; i++)
        out[i] = x[i], x[i] = sim->work.xb[xs + i];
    for (uint16_t i = 0; i < kd->nd; i++)
        d[i] = keep_d[i];
}

/* the largest difference of the handled states in k[3] from those in k[2], scaled as the
   set's steps scale their errors (rti_err_floor: |e| / (A / R + |x|)) */
static real_t handled_diff(const event_effect *e)
{
    const real_t *x0 = e->sim->work.w.k[2], *x1 = e->sim->work.w.k[3];
    real_t g = 0, sa = rti_err_floor(&e->sc->sets[e->s].cfg);
    for (uint16_t i = 0; i < e->sc->blocks[e->blk].kind->nx; i++) {
        real_t q = rt_fabs(x1[i] - x0[i]) / (sa + rt_fabs(x0[i]));
        g = q > g || q != q ? q : g;
    }
    return g;
}

static void event_effect_of(void *ctx, real_t w, real_t window)
{
    event_effect *e = ctx;
    real_t r[RT_MAX_ROOTS];
    rti_outputs(e->sc, e->sim, (rti_at){e->te, e->s, RTI_IN_STEP});
    rti_roots(e->sc, e->sim, e->s, e->te, r);
    real_t dr = w * rt_fabs(r[e->c] - e->r0);
    e->dr += dr;
    e->window = dr > 0 && window > e->window ? window : e->window;
    if (!e->run)
        return;
    handled(e, e->te, e->sim->work.w.k[3]);
    e->dx += w * handled_diff(e);
}

/* how far the event of root c (block blk, its root `which`) at te may be off (the state
   there in xb, before its handlers): its time, and (*dx) the state its handler leaves.
   A crossing kept from a jump of the set's inputs at the step's start (rt/held.c; r_left
   its value before the jump) came up to `late` before te: its distance from its level
   over its rate there (an Euler probe) plus the jump's spread over `late` (exact for a
   hold of a line); a root reading other sets is off by what their schemes miss, which over its
   rate is a time (at most the step h); a handler reading them leaves a state off by what
   they miss. 0 and *dx 0: nothing to judge; else the derivatives at te before the
   handlers are left in k[1] */
static real_t unsure_by(const rt_scene *sc, rt_sim *sim, uint8_t s, real_t te, real_t h,
                        const rootset *rs, int c, uint16_t blk, uint16_t which, real_t late,
                        real_t r_left, real_t *dx)
{
    uint16_t x0 = sim->plan.set_x[s], n = (uint16_t)(sim->plan.set_x[s + 1] - x0);
    const rt_kind *kd = sc->blocks[blk].kind;
    *dx = 0;
    if (!(late > 0) && !(sim->plan.set_flags[s] & RTI_SET_XPRED))
        return 0;
    real_t ra[RT_MAX_ROOTS], rp[RT_MAX_ROOTS], tau = h * RT_EVENT_PROBE;
    real_t t_max = probe_limit(sc, sim, s, te);
    tau = te + tau > t_max ? t_max - te : tau;
    for (uint16_t i = 0; i < n; i++)
        sim->state.x[x0 + i] = sim->work.xb[i];
    rti_outputs(sc, sim, (rti_at){te, s, RTI_IN_STEP});
    rti_roots(sc, sim, s, te, ra);
    probe(sc, sim, s, te, tau, rp);
    for (uint16_t i = 0; i < n; i++)
        sim->work.w.k[1][i] = sim->work.w.k[0][i];
    real_t own = (rp[c] - ra[c]) / tau, rate = rt_fabs(own), d = 0;
    if (late > 0) {
        /* over the interval the root moved by its own rate and by the jump, spread over
           it: it met its level its distance over both before te */
        d = rt_fabs(ra[c] - rs->lvl[c]) / rt_fabs(own + (ra[c] - r_left) / late);
        d = d < late ? d : late; /* (NaN: the interval) */
    }
    event_effect e = {sc, sim, s, te, c, blk, which, !kd->save && kd->nd <= RT_MAX_X, ra[c],
                      0, 0, h};
    if (e.run)
        handled(&e, te, sim->work.w.k[2]);
    rti_xset_shifted(sc, sim, s, te, h, event_effect_of, &e);
    rti_outputs(sc, sim, (rti_at){te, s, RTI_IN_STEP});
    real_t m = e.dr / rate, off = d + (m < e.window ? m : e.window);
    *dx = e.dx;
    if (e.run && off > 0) {
        /* a handler that reads the time (a time stamp, a rest clause's t + T) or inputs
           moving with it leaves a state off by its rate times the time's miss */
        handled(&e, te + tau, sim->work.w.k[3]);
        *dx += handled_diff(&e) / tau * off;
    }
    return off;
}

/* the handlers at te ran up to `off` off the crossing's time and left a state up to dx
   off (unsure_by): the error that put into the set's state, the change of its
   derivatives across them times `off` (a bounce a step late moves its body by the
   velocity's jump times the delay) and dx, held to the set's accuracy as a coupling
   error (block b's) */
static void judge_event(const rt_scene *sc, rt_sim *sim, uint8_t s, real_t te, real_t h,
                        uint16_t b, real_t off, real_t dx)
{
    uint16_t x0 = sim->plan.set_x[s], n = (uint16_t)(sim->plan.set_x[s + 1] - x0);
    const real_t *f0 = sim->work.w.k[1], *f1 = sim->work.w.k[0], *x = sim->state.x + x0;
    rti_rhs_ctx ctx = {sc, sim, s, h};
    rti_rhs(&ctx, te, sim->work.w.k[0]);
    real_t g = 0, sa = rti_err_floor(&sc->sets[s].cfg); /* (scaled as the steps' errors) */
    for (uint16_t i = 0; i < n; i++) {
        real_t e = rt_fabs(f1[i] - f0[i]) / (sa + rt_fabs(x[i]));
        g = e > g || e != e ? e : g;
    }
    rti_xset_judge(sc, sim, s, b, g * off + dx);
    rti_outputs(sc, sim, (rti_at){te, s, RTI_IN_STEP});
}

/* at the run's start a directional root may sit exactly on its level (a ball released on
   its floor, falling): 0 is on neither side, so no sign change ever shows, and the body
   goes through. Such a root moving the way it crosses over the first integration (rb) is
   taken to start a hair before its level in ra (the span's start values), so its
   crossing is located at once and its handler runs; one moving away, or an undirected
   root (which would fire whichever way it left), stays as it is */
static void start_on_level(const rt_scene *sc, const rt_sim *sim, uint8_t s, const rootset *rs,
                           real_t *ra, const real_t *rb)
{
    uint16_t n = 0, j = sim->plan.blk_of[s];
    for (uint16_t b; (b = next_root_block(sc, sim, s, &j)) < sc->nblocks;) {
        const rt_kind *k = sc->blocks[b].kind;
        for (uint16_t i = 0; i < k->nr; i++, n++) {
            int dir = k->root_dir ? k->root_dir[i] : 0;
            if (ra[n] == 0 && rs->side[n] == 0 && rs->lvl[n] == 0 && dir * rb[n] > 0)
                ra[n] = (real_t)-dir * RTI_ROOT_HAIR;
        }
    }
}

/* an integration from t0 over sub with no earlier point for its excursions (its end
   state in x, its start in work.xs): its roots a probe's length after its start
   (RT_EVENT_PROBE of sub, an Euler step: probe) into rq, the state and outputs at the
   end put back. Returns the
   probe's length as a fraction of sub, 0 if none fits (the rest shorter than two probes,
   or a time event right after t0) or the set's method keeps state a trial would move (an
   implicit or transition method) or it has joints */
static real_t after_probe(const rt_scene *sc, rt_sim *sim, uint8_t s, real_t t0, real_t sub,
                          real_t *rq)
{
    uint16_t x0 = sim->plan.set_x[s], n = (uint16_t)(sim->plan.set_x[s + 1] - x0);
    const rt_integrator *m = sc->sets[s].method;
    if (m->implicit || m->linear || (sc->mbs && sim->work.mbs.nz[s] > 0))
        return 0; /* (a trial's integration moves an implicit method's kept Jacobian and
                     its schedule, a probe a multibody set's multipliers: a run with no
                     excursion must keep its bits) */
    real_t tau = sub * RT_EVENT_PROBE, t_max = probe_limit(sc, sim, s, t0);
    tau = t0 + tau > t_max ? t_max - t0 : tau;
    if (!(tau > 0 && tau < (real_t)0.5 * sub))
        return 0;
    real_t *x = sim->state.x + x0, *end = sim->work.w.k[RT_MAX_STAGES - 1];
    for (uint16_t i = 0; i < n; i++)
        end[i] = x[i], x[i] = sim->work.xs[i];
    probe(sc, sim, s, t0, tau, rq); /* (x back at t0) */
    for (uint16_t i = 0; i < n; i++)
        x[i] = end[i];
    rti_outputs(sc, sim, (rti_at){t0 + sub, s, RTI_IN_STEP});
    return tau / sub;
}

/* a root that crossed its level and came back within the integration from t0 over sub (ra
   at its start, rb at its end, on one side): the parabola through it at the start of
   the integration before (state.r_prev, r_prev_h before t0: of the same length, or of
   another between RTI_EXCURSION_SPAN and its inverse times sub, the rest of a step
   after an event or a part before a time event; where there is none, the run's first
   step, the rest of a step after an event (after: tried there too), a step after a rest
   shorter than that, a probe's point from its start: after_probe), ra and rb reaches
   beyond the level between them. The first such root's parabola's extremum is tried
   (trial: the real state there) and, if a root crossed by then, the crossing is located in [0, th] as any other: a ball
   thrown up to a ceiling it touches for less than a step. Its roots are written into rt,
   th into *th, its block into *blk and its index there into *which; -1 if none (the state
   and outputs at the end restored). Once a step at most: one integration more in its work
   bound, two for a multibody set (rt_set_step_bound). A root whose path is no parabola
   may be missed (a spike within the step); `modrt check` sees such a step at half the
   step (docs/solvers.md) */
static int excursion(const rt_scene *sc, rt_sim *sim, uint8_t s, const rootset *rs,
                     const real_t *ra, real_t t0, real_t sub, real_t *rt, real_t *th,
                     uint16_t *blk, uint16_t *which)
{
    uint16_t r0 = sim->plan.set_r[s], nr = (uint16_t)(sim->plan.set_r[s + 1] - r0);
    const real_t *rp = sim->state.r_prev + r0, *rb = sim->work.rs;
    /* the third point's place, in sub from t0: -d before it, or a probe's at d < 0 */
    real_t d = sim->state.r_prev_h[s] / sub, rq[RT_MAX_ROOTS];
    if (!(d >= (real_t)RTI_EXCURSION_SPAN && d <= 1 / (real_t)RTI_EXCURSION_SPAN)) {
        if (!(d = -after_probe(sc, sim, s, t0, sub, rq)))
            return -1;
        rp = rq;
    }
    real_t at = 2;
    for (uint16_t i = 0; i < nr; i++) {
        if (rs->side[i] != 0 || rs->lvl[i] != 0 || !(ra[i] * rb[i] > 0))
            continue; /* held at a level, or not on one side at both ends */
        real_t a, b; /* ra + b u + a u^2 through rp at u = -d, ra at 0, rb at 1 */
        if (d == 1) { /* (equal lengths: the arithmetic of three equally spaced values) */
            a = (real_t)0.5 * (rb[i] - 2 * ra[i] + rp[i]), b = (real_t)0.5 * (rb[i] - rp[i]);
        } else {
            a = (rp[i] - ra[i] + d * (rb[i] - ra[i])) / (d * (d + 1));
            b = (rb[i] - ra[i]) - a;
        }
        real_t sx = -b / (2 * a); /* the extremum, in steps from t0 */
        if (sx > 0 && sx < 1 && sx < at && (ra[i] + (b + a * sx) * sx) * ra[i] < 0)
            at = sx;
    }
    if (!(at < 1))
        return -1;
    uint16_t x0 = sim->plan.set_x[s], n = (uint16_t)(sim->plan.set_x[s + 1] - x0);
    for (uint16_t i = 0; i < n; i++)
        sim->work.xb[i] = sim->state.x[x0 + i]; /* the end, kept */
    trial(sc, sim, s, t0, sub, at, rt);
    int c = find_crossing(sc, sim, s, rs, ra, rt, blk, which);
    if (c >= 0) {
        *th = at;
        return c;
    }
    if (sc->mbs && sim->work.mbs.nz[s] > 0) {
        /* a projection's multipliers (recorded reactions) are the trial's now: the
           integration again from its start (one more in the bound) */
        for (uint16_t i = 0; i < n; i++)
            sim->state.x[x0 + i] = sim->work.xs[i];
        integrate(sc, sim, s, t0, sub);
    } else {
        for (uint16_t i = 0; i < n; i++)
            sim->state.x[x0 + i] = sim->work.xb[i];
    }
    rti_outputs(sc, sim, (rti_at){t0 + sub, s, RTI_IN_STEP});
    return -1;
}

/* sub-steps from t0 to t + h, locating and firing events on the way. A root that ends a
   span NaN (its state finite) is counted (nan, with its block): where it went NaN from a
   finite value is located like a crossing, so a crossing of any root before that point
   is found and handled; the NaN root itself has no handler to run. may_stop: in a set
   with time events known at run time, an event that moves the next of them inside the
   rest of the step ends the step at the event (rt/tev.c goes on from there with a part
   to that instant). Returns the time reached: t + h, or the event's */
static real_t step_with_events(const rt_scene *sc, rt_sim *sim, uint8_t s, real_t t, real_t h,
                               int may_stop)
{
    uint16_t x0 = sim->plan.set_x[s], n = (uint16_t)(sim->plan.set_x[s + 1] - x0);
    uint16_t nr = (uint16_t)(sim->plan.set_r[s + 1] - sim->plan.set_r[s]);
    real_t *r = sim->state.r + sim->plan.set_r[s];
    int8_t fired[RT_MAX_ROOTS];
    rootset rs = roots_of(sim, s);
    /* span: the rest of the step from t0; sub: this integration's part of it (less only
       after an event whose root returns within the probe, settle) */
    real_t t0 = t, span = h, cap = 0, rt[RT_MAX_ROOTS], late = sim->state.r_late[s];
    int nan_seen = 0, tried = 0, after = 0, kept = sim->state.r_kept[s];
    sim->state.r_late[s] = 0, sim->state.r_kept[s] = 0;
    for (int ev = 0;; ev++) {
        /* a root crossed by the inputs' jump at the tick (rt/held.c): its crossing is at
           the step's start, an integration of length 0 from there */
        real_t sub = kept ? 0 : cap > 0 && cap < span ? cap : span;
        cap = 0, kept = 0; /* (once: if nothing crosses there, the step goes on) */
        if (sub > 0)
            integrate(sc, sim, s, t0, sub); /* keeps the span's start in work.xs */
        rti_outputs(sc, sim, (rti_at){t0 + sub, s, RTI_IN_STEP});
        rti_roots(sc, sim, s, t0 + sub, sim->work.rs);
        int nb = nan_root_block(sc, sim, s, sim->work.rs);
        rs.lost = nb >= 0 && rt_all_finite(sim->state.x + x0, n);
        if (rs.lost && !nan_seen)
            rti_count(sim, RT_CNT_NAN, nb, RT_E_NAN), nan_seen = 1;
        uint16_t blk, which;
        if (ev == 0 && t0 == 0 && sim->state.tick == 0)
            start_on_level(sc, sim, s, &rs, r, sim->work.rs);
        int c = find_crossing(sc, sim, s, &rs, r, sim->work.rs, &blk, &which);
        real_t b = 1, rb = c >= 0 ? sim->work.rs[c] : 0;
        /* an excursion: where nothing crossed, once a step; after an event also before a
           crossing the rest found (the handled mode pushes another root through its level
           and back before the first crosses: a body reversing in a layer it entered) */
        if (sub > 0 && (after || (c < 0 && !tried++))) {
            uint16_t eb, ew;
            int ce = excursion(sc, sim, s, &rs, r, t0, sub, rt, &b, &eb, &ew);
            if (ce >= 0)
                c = ce, rb = rt[ce], blk = eb, which = ew;
        }
        after = 0;
        if (c < 0) {
            check_guards(sc, sim, s, &rs, r, sim->work.rs);
            release(nr, &rs, sim->work.rs);
            for (uint16_t i = 0; i < nr; i++) /* three points for the next excursion */
                sim->state.r_prev[sim->plan.set_r[s] + i] = r[i];
            sim->state.r_prev_h[s] = sub;
            if (!(sub < span))
                break;
            for (uint16_t i = 0; i < nr; i++) /* the rest of the step from there */
                r[i] = sim->work.rs[i];
            span = (t0 + span) - (t0 + sub);
            t0 = t0 + sub;
            ev--; /* no event */
            continue;
        }
        sim->state.r_prev_h[s] = 0; /* the roots jump at the handlers */
        bracket k = {0, b, r[c], rb, c};
        for (uint16_t i = 0; i < n; i++)
            sim->work.xb[i] = sim->state.x[x0 + i];
        /* past the bound the crossing is handled where the step ends, unlocated: the work
           stays bounded, and a body chattering on its floor (Zeno) stays on it */
        if (ev >= RT_EVENTS_PER_STEP_MAX)
            rti_count(sim, RT_CNT_EVENT_LIMIT, blk, RT_E_EVENT);
        else if (sub > 0)
            locate(sc, sim, s, t0, sub, &k, &rs, r);
        real_t te = t0 + k.b * sub;
        real_t dx, off = unsure_by(sc, sim, s, te, h, &rs, c, blk, which, ev == 0 ? late : 0,
                                        r[c], &dx);
        fire(sc, sim, s, te, &rs, r, fired);
        cascade(sc, sim, s, te, &rs, fired);
        sim->state.hist_ev[s] |= RTI_HIST_EV_STEP; /* its readers: a jump inside */
        /* the handlers may have changed the dynamics (a mode, a stiffness that ends): an
           implicit method's kept Jacobian belongs to the state before them, and a
           W-method's estimate filtered by it reads a frozen state as exact */
        sim->state.imp[s].valid = 0;
        rti_xset_gain_stale(sim, s); /* (a mode: the inputs' sensitivity moves too) */
        if (off > 0 || dx > 0)
            judge_event(sc, sim, s, te, h, blk, off, dx);
        /* the rest of the step starts from the handled state */
        span = (t0 + span) - te;
        t0 = te;
        rti_outputs(sc, sim, (rti_at){t0, s, RTI_IN_STEP});
        rti_roots(sc, sim, s, t0, r);
        cap = settle(sc, sim, s, t0, h, probe_limit(sc, sim, s, t0), &rs, fired, r, sub == 0,
                     span > 0);
        cap = ev + 1 < RT_EVENTS_PER_STEP_MAX ? cap : 0; /* past the bound: to the end */
        if (!(span > 0))
            return t + h; /* an event at the step's end: r holds the roots after them */
        /* the rest is checked for an excursion (excursion) while its events are located:
           past the bound a crossing an excursion finds inside the rest would go on */
        after = ev + 1 < RT_EVENTS_PER_STEP_MAX;
        if (may_stop && (sim->plan.set_flags[s] & RTI_SET_TEV_DYN) &&
            rti_tev_dyn_next(sc, sim, s, t0) < t0 + span)
            return t0; /* r holds the roots after its handlers */
    }
    for (uint16_t i = 0; i < nr; i++)
        r[i] = sim->work.rs[i];
    return t + h;
}

/* the first block of the set holding a non-finite state, or -1 (the set's states are
   one slice: checked at once, and walked by block only when one is not finite) */
static int nonfinite_block(const rt_scene *sc, const rt_sim *sim, uint8_t s)
{
    const real_t *x = sim->state.x;
    if (rt_all_finite(x + sim->plan.set_x[s], sim->plan.set_x[s + 1] - sim->plan.set_x[s]))
        return -1;
    for (unsigned k = sim->plan.blk_of[s], k1 = sim->plan.blk_of[s + 1]; k < k1; k++) {
        uint16_t b = sim->plan.set_blk[k];
        for (unsigned i = sim->plan.x_off[b], i1 = i + sc->blocks[b].kind->nx; i < i1; i++)
            if (!rt_isfinite(x[i]))
                return b;
    }
    return -1;
}

void rti_step_witness(rt_sim *sim, uint8_t s, uint64_t r0)
{
    uint64_t d = sim->stats.rhs_evals[s] - r0;
    if (d > sim->stats.istats[s].rhs_set_step_max)
        sim->stats.istats[s].rhs_set_step_max = (uint32_t)d;
}

real_t rti_step_set(const rt_scene *sc, rt_sim *sim, uint8_t s, real_t t, real_t h, int may_stop)
{
    uint16_t x0 = sim->plan.set_x[s], n = (uint16_t)(sim->plan.set_x[s + 1] - x0);
    real_t after = -1, reached = t + h; /* unknown */
    if (sim->plan.set_r[s + 1] > sim->plan.set_r[s]) {
        reached = step_with_events(sc, sim, s, t, h, may_stop);
    } else {
        after = integrate(sc, sim, s, t, h); /* keeps the state before it in work.xs */
    }
    /* a non-finite state is not propagated: the set keeps its state from before the step
       (deterministic degradation) and the fault is counted with the block (a finite norm
       of the final state says there is none) */
    int bad = after >= 0 && rt_isfinite(after) ? -1 : nonfinite_block(sc, sim, s);
    if (bad >= 0) {
        for (uint16_t i = 0; i < n; i++)
            sim->state.x[x0 + i] = sim->work.xs[i];
        rti_count(sim, RT_CNT_NAN, bad, RT_E_NAN);
    }
    rti_invariants(sc, sim, s); /* what the kinds declare of their states */
    return reached;
}
