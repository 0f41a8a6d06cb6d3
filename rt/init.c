/* init.c - rt_init: checks a scene against its kinds and the compile-time limits, lays out
 * the value arrays, routes every input (y = P u, eq. 2), and computes the evaluation order.
 *
 * All of this runs once, before the first tick; nothing here is on the tick path. */
#include "rti.h"

/* the services a kind must provide for its sizes and type */
static rt_status check_kind(rt_sim *sim, const rt_block *b)
{
    const rt_kind *k = b->kind;
    int ok = k != 0;
    ok = ok && (k->ny == 0 || k->output != 0);
    ok = ok && (k->nr == 0 || (k->roots != 0 && k->event != 0));
    ok = ok && (k->feed != RT_FEED_TABLE || k->feed_table != 0);
    ok = ok && (k->output_lean == 0 || k->lean_skip != 0);
    if (ok && (k->type == RT_KIND_NSS || k->type == RT_KIND_LSS))
        ok = k->deriv != 0;
    if (ok && k->type == RT_KIND_DSS)
        ok = k->update != 0 && k->nx == 0;
    if (ok && (k->type == RT_KIND_OUTPUT))
        ok = k->nx == 0 && k->nd == 0;
    if (ok && k->type == RT_KIND_MBS)
        ok = k->spec != 0 && k->deriv == 0;
    if (!ok)
        return rti_fail(sim, RT_E_SCENE, "block ", b->name,
                        ": its kind lacks a service its sizes or type require",
                        (const char *)0);
    return RT_OK;
}

/* sample period of a DSS block in base ticks; 0 on a mismatch */
static uint32_t period_ticks(const rt_scene *sc, const rt_block *b)
{
    if (!(b->ts > 0) || !(sc->dt > 0))
        return 0;
    real_t r = b->ts / sc->dt;
    uint32_t n = (uint32_t)(r + (real_t)0.5);
    real_t err = rt_fabs((real_t)n * sc->dt - b->ts);
    return (n > 0 && err <= (real_t)RT_TICK_MATCH_REL * b->ts) ? n : 0;
}

/* offsets of every block's slices; continuous states grouped by set */
static rt_status layout(const rt_scene *sc, rt_sim *sim)
{
    uint32_t nx = 0, nd = 0, nu = 0, ny = 0, np = 0, nr = 0;
    for (uint8_t s = 0; s < sc->nsets; s++) {
        sim->plan.set_x[s] = (uint16_t)nx;
        sim->plan.set_r[s] = (uint16_t)nr;
        for (uint16_t b = 0; b < sc->nblocks; b++) {
            if (sc->blocks[b].set != s)
                continue;
            sim->plan.x_off[b] = (uint16_t)nx;
            nx += sc->blocks[b].kind->nx;
            nr += sc->blocks[b].kind->nr;
            if (nx > RT_MAX_X || nr > RT_MAX_ROOTS)
                return rti_capacity(sim, "block ", sc->blocks[b].name,
                                    nx > RT_MAX_X ? RT_LIM_X : RT_LIM_ROOTS);
        }
    }
    sim->plan.set_x[sc->nsets] = (uint16_t)nx;
    sim->plan.set_r[sc->nsets] = (uint16_t)nr;
    for (uint8_t s = 0; s < sc->nsets; s++)
        sim->plan.set_h[s] = rt_set_step(sc, s);
    for (uint8_t s = 0; s < sc->nsets; s++)
        if (sc->sets[s].method->implicit &&
            sim->plan.set_x[s + 1] - sim->plan.set_x[s] > RT_MAX_IMPLICIT_N)
            return rti_capacity(sim, "set ", sc->sets[s].name, RT_LIM_IMPLICIT_N);

    sim->plan.x_off[sc->nblocks] = (uint16_t)nx;
    for (uint16_t b = 0; b <= sc->nblocks; b++) {
        sim->plan.d_off[b] = (uint16_t)nd;
        sim->plan.u_off[b] = (uint16_t)nu;
        sim->plan.y_off[b] = (uint16_t)ny;
        sim->plan.p_off[b] = (uint16_t)np;
        if (b == sc->nblocks)
            break;
        const rt_kind *k = sc->blocks[b].kind;
        nd += k->nd, nu += k->nu, ny += k->ny, np += k->np;
        rt_limit over = nd > RT_MAX_D   ? RT_LIM_D
                        : nu > RT_MAX_U ? RT_LIM_U
                        : ny > RT_MAX_Y ? RT_LIM_Y
                        : np > RT_MAX_P ? RT_LIM_P
                                        : RT_LIM_COUNT;
        if (over != RT_LIM_COUNT)
            return rti_capacity(sim, "block ", sc->blocks[b].name, over);
    }
    return RT_OK;
}

/* copies n values from src, or from fallback, or zeros */
static void fill(real_t *dst, const real_t *src, const real_t *fallback, uint16_t n)
{
    for (uint16_t i = 0; i < n; i++)
        dst[i] = src ? src[i] : fallback ? fallback[i] : 0;
}

/* parameters, initial states, sample periods; each block's parameter check */
static rt_status initial_values(const rt_scene *sc, rt_sim *sim)
{
    sim->plan.dss_first = sim->plan.dss_end = 0;
    for (uint16_t b = 0; b < sc->nblocks; b++) {
        const rt_block *bl = &sc->blocks[b];
        const rt_kind *k = bl->kind;
        fill(sim->state.p + sim->plan.p_off[b], bl->p, k->p_default, k->np);
        fill(sim->state.x + sim->plan.x_off[b], bl->x0, k->x_default, k->nx);
        fill(sim->state.d + sim->plan.d_off[b], bl->d0, k->d_default, k->nd);
        for (uint16_t j = 0; j < k->ny; j++)
            sim->state.y[sim->plan.y_off[b] + j] = 0;
        sim->plan.period[b] = 0;
        if (k->type == RT_KIND_DSS)
            sim->plan.dss_first = sim->plan.dss_end ? sim->plan.dss_first : b,
            sim->plan.dss_end = (uint16_t)(b + 1);
        if (k->type == RT_KIND_DSS && (sim->plan.period[b] = period_ticks(sc, bl)) == 0)
            return rti_fail(sim, RT_E_SCENE, "block ", bl->name,
                            ": sample period is not a positive multiple of the base tick",
                            (const char *)0);
        if (k->type == RT_KIND_DSS && sim->plan.period[b] % sc->sets[bl->set].ratio != 0)
            return rti_fail(sim, RT_E_SCENE, "block ", bl->name,
                            ": sample period is not a whole multiple of its set's step",
                            (const char *)0);
        if (k->check && k->check(sim->state.p + sim->plan.p_off[b], k->spec) != RT_OK)
            return rti_fail(sim, RT_E_PARAM, "block ", bl->name,
                            ": parameters out of range for kind ", k->name, (const char *)0);
    }
    return RT_OK;
}

/* one connection: indices in range, input not yet driven */
static rt_status route_conn(const rt_scene *sc, rt_sim *sim, const rt_conn *c)
{
    if (c->from >= sc->nblocks || c->to >= sc->nblocks)
        return rti_fail(sim, RT_E_SCENE, "a connection names a block index out of range",
                        (const char *)0);
    const rt_block *f = &sc->blocks[c->from], *t = &sc->blocks[c->to];
    if (c->y >= f->kind->ny)
        return rti_fail(sim, RT_E_SCENE, "connection from ", f->name,
                        ": output index out of range", (const char *)0);
    if (c->u >= t->kind->nu)
        return rti_fail(sim, RT_E_SCENE, "connection to ", t->name,
                        ": input index out of range", (const char *)0);
    uint16_t gi = (uint16_t)(sim->plan.u_off[c->to] + c->u);
    if (sim->plan.src_kind[gi] != RTI_SRC_UNSET)
        return rti_fail(sim, RT_E_SCENE, "input ", t->name, ".", t->kind->u_names[c->u],
                        " is driven twice", (const char *)0);
    sim->plan.src_kind[gi] = RT_SRC_Y;
    sim->plan.src[gi] = (uint16_t)(sim->plan.y_off[c->from] + c->y);
    return RT_OK;
}

/* every input reads a connected output or a default value */
static rt_status route(const rt_scene *sc, rt_sim *sim)
{
    uint16_t nu = sim->plan.u_off[sc->nblocks];
    rt_status st;
    for (uint16_t i = 0; i < nu; i++) {
        sim->plan.src_kind[i] = RTI_SRC_UNSET, sim->plan.src[i] = 0, sim->plan.def[i] = 0, sim->work.u[i] = 0;
        sim->plan.interp[i] = 0, sim->plan.src_set[i] = 0;
    }
    for (uint16_t v = 0; v < sim->plan.y_off[sc->nblocks] && v < RT_MAX_HIST_Y; v++)
        sim->plan.xsrc[v] = 0; /* (the history hist_y was zeroed with the state) */
    for (uint16_t c = 0; c < sc->nconns; c++)
        if ((st = route_conn(sc, sim, &sc->conns[c])) != RT_OK)
            return st;
    for (uint16_t i = 0; i < sc->ndefaults; i++) {
        const rt_default *d = &sc->defaults[i];
        if (d->block >= sc->nblocks || d->u >= sc->blocks[d->block].kind->nu)
            return rti_fail(sim, RT_E_SCENE, "a default value names an input out of range",
                            (const char *)0);
        uint16_t gi = (uint16_t)(sim->plan.u_off[d->block] + d->u);
        if (sim->plan.src_kind[gi] != RTI_SRC_UNSET)
            return rti_fail(sim, RT_E_SCENE, "input ", sc->blocks[d->block].name, ".",
                            sc->blocks[d->block].kind->u_names[d->u],
                            " is both connected and given a default", (const char *)0);
        sim->plan.src_kind[gi] = RT_SRC_DEFAULT;
        sim->plan.def[gi] = d->value;
    }
    for (uint16_t b = 0; b < sc->nblocks; b++)
        for (uint16_t i = 0; i < sc->blocks[b].kind->nu; i++)
            if (sim->plan.src_kind[sim->plan.u_off[b] + i] == RTI_SRC_UNSET)
                return rti_fail(sim, RT_E_UNCONNECTED, "input ", sc->blocks[b].name, ".",
                                sc->blocks[b].kind->u_names[i],
                                " is not connected and has no default value",
                                (const char *)0);
    return RT_OK;
}

/* the per-scene sizes of the cross-set history, the loop histogram (after rti_order,
   which finds the torn inputs) and event location */
static rt_status check_history(const rt_scene *sc, rt_sim *sim)
{
    /* (the outputs read by another set were checked against RT_MAX_HIST_Y as they were
       found, rti_xset_init) */
    if (rti_held_top(sc, sim) > RT_MAX_HELD_Y)
        return rti_capacity(sim, 0, 0, RT_LIM_HELD_Y);
    if (rti_held_sigs(sc) > RT_MAX_HELD_SIG)
        return rti_capacity(sim, 0, 0, RT_LIM_HELD_SIG);
    uint32_t iters = sc->loop_iter_max ? sc->loop_iter_max : RT_LOOP_ITER_MAX;
    if (sim->plan.ntorn > 0 && iters > RT_MAX_LOOP_HIST - 1)
        return rti_capacity(sim, 0, 0, RT_LIM_LOOP_HIST); /* a bin per count, 0 too */
    for (uint8_t s = 0; s < sc->nsets; s++)
        if (sim->plan.set_r[s + 1] > sim->plan.set_r[s] &&
            sim->plan.set_x[s + 1] - sim->plan.set_x[s] > RT_MAX_EVENT_X)
            return rti_capacity(sim, "set ", sc->sets[s].name, RT_LIM_EVENT_X);
    return RT_OK;
}

/* a tolerance setting: 0 selects the default; else positive and finite */
static int tol_ok(real_t v)
{
    return v == 0 || (v > 0 && rt_isfinite(v));
}

/* one set's method, step and settings (rt_set_check: what the scene compiler and modrt's
   per-set options check, checked again for a hand-written scene) */
static rt_status check_set(const rt_scene *sc, uint8_t s, rt_sim *sim)
{
    rt_cfg_id bad;
    const char *msg = rt_set_check(&sc->sets[s], &bad);
    if (!msg)
        return RT_OK;
    return rti_fail(sim, bad == RT_CFG_N ? RT_E_SCENE : RT_E_PARAM, "set ", sc->sets[s].name,
                    ": ", msg, (const char *)0);
}

/* scene-level checks before anything is laid out */
static rt_status check_scene(const rt_scene *sc, rt_sim *sim)
{
    if (sc->nblocks > RT_MAX_BLOCKS)
        return rti_capacity(sim, 0, 0, RT_LIM_BLOCKS);
    if (sc->nsets > RT_MAX_SETS)
        return rti_capacity(sim, 0, 0, RT_LIM_SETS);
    if (sc->nsets == 0)
        return rti_fail(sim, RT_E_CAPACITY, "a scene needs at least one set", (const char *)0);
    if (sc->code && sc->code->sim_layout != RT_SIM_LAYOUT)
        /* the code reads rt_sim at its own build's offsets: run, it would compute garbage */
        return rti_fail(sim, RT_E_SCENE, "scene code compiled with other limits than the "
                        "runtime (RT_MAX_*, REAL): build both with the same",
                        (const char *)0);
    if (!(sc->dt > 0) || !(sc->t_end >= 0) || !rt_isfinite(sc->t_end))
        return rti_fail(sim, RT_E_SCENE, "base tick must be > 0 and end time >= 0",
                        (const char *)0);
    for (uint8_t s = 0; s < sc->nsets; s++) {
        rt_status st = check_set(sc, s, sim);
        if (st != RT_OK)
            return st;
    }
    if (!tol_ok(sc->loop_tol) || sc->loop_iter_max > RT_LOOP_ITER_LIMIT)
        return rti_fail(sim, RT_E_PARAM, "loop tolerance must be 0 (default) or positive "
                        "and finite, loop iterations at most ", RTI_LIMIT(RT_LOOP_ITER_LIMIT),
                        (const char *)0);
    for (uint16_t b = 0; b < sc->nblocks; b++) {
        rt_status st = check_kind(sim, &sc->blocks[b]);
        if (st != RT_OK)
            return st;
        if (sc->blocks[b].kind->type == RT_KIND_MBS && !sc->mbs)
            return rti_fail(sim, RT_E_SCENE, "block ", sc->blocks[b].name,
                            " is a multibody module but the scene names no MBS services",
                            (const char *)0);
        if (sc->blocks[b].set >= sc->nsets)
            return rti_fail(sim, RT_E_SCENE, "block ", sc->blocks[b].name,
                            " names a set that does not exist", (const char *)0);
    }
    for (uint16_t i = 0; i < sc->nrecs; i++) {
        const rt_rec *r = &sc->recs[i];
        if (r->what == RT_SIG_MBS) {
            if (!sc->mbs || r->block >= sc->nblocks)
                return rti_fail(sim, RT_E_SCENE, "a recorded multibody signal names no ",
                                "multibody block of a scene with MBS services",
                                (const char *)0);
            continue; /* its index is checked by the MBS services' init */
        }
        const rt_kind *k = r->block < sc->nblocks ? sc->blocks[r->block].kind : 0;
        uint16_t n = !k ? 0 : r->what == RT_SIG_Y ? k->ny : r->what == RT_SIG_X ? k->nx : k->nd;
        if (r->index >= n)
            return rti_fail(sim, RT_E_SCENE, "a recorded signal is out of range",
                            (const char *)0);
    }
    return RT_OK;
}

/* the number of ticks that reaches t_end, rounded to the nearest tick */
/* the end time in base ticks: a whole number of them (a quarter tick of rounding at most,
   RT_TICK_SLACK), and at most RT_MAX_TICKS; else RT_E_SCENE and n_ticks stays 0 */
static rt_status tick_count(const rt_scene *sc, rt_sim *sim)
{
    real_t n = sc->t_end / sc->dt;
    if (!(n >= 0 && n <= (real_t)RT_MAX_TICKS))
        return rti_fail(sim, RT_E_SCENE, "end time out of range: not negative, and at most "
                        "RT_MAX_TICKS (2^53) base ticks", (const char *)0);
    real_t k = (real_t)(uint64_t)(n + (real_t)0.5), slack = RT_TICK_SLACK * (n > 1 ? n : 1);
    if (!(rt_fabs(n - k) <= (slack < (real_t)0.25 ? slack : (real_t)0.25)))
        return rti_fail(sim, RT_E_SCENE, "end time is not a whole number of base ticks",
                        (const char *)0);
    sim->plan.n_ticks = (uint64_t)k;
    return RT_OK;
}

/* a set whose method needs a set linear in its state (rt_integrator.linear) is one, and
   small enough (after rti_eval_plan: the sets' blocks and routes) */
static rt_status check_methods(const rt_scene *sc, rt_sim *sim)
{
    for (uint8_t s = 0; s < sc->nsets; s++) {
        const rt_set *st = &sc->sets[s];
        int b = st->method->linear ? rti_nonlinear_block(sc, sim, s) : -1;
        if (b >= 0)
            return rti_fail(sim, RT_E_SCENE, "set ", st->name, ": method ", st->method->name,
                            " needs a set linear in its state, but block ",
                            sc->blocks[b].name, " (", sc->blocks[b].kind->name,
                            ") is not a linear kind (rt_kind.linear), is a multibody "
                            "module or has a torn input", (const char *)0);
        if (st->method->linear && rt_set_nx(sim, s) > RT_MAX_TRANSITION_N)
            return rti_capacity(sim, "set ", st->name, RT_LIM_TRANSITION_N);
    }
    return RT_OK;
}

/* the background set, if the scene declares one: its services check it (rt/bg.c) */
static rt_status bg_init(const rt_scene *sc, rt_sim *sim)
{
    sim->plan.bg_set = -1;
    sim->bg = 0;
    sim->bg_released = sim->bg_finished = 0;
    for (uint8_t s = 0; s < sc->nsets; s++)
        if (sc->sets[s].background && !sc->bg)
            return rti_fail(sim, RT_E_SCENE, "set ", sc->sets[s].name, " is background but "
                            "the scene names no background services (rt_scene.bg)",
                            (const char *)0);
    return sc->bg ? sc->bg->init(sc, sim) : RT_OK;
}

/* the name in parentheses: rt_sim.h's rt_init macro does not expand here */
rt_status (rt_init)(const rt_scene *sc, rt_sim *sim)
{
    return rt_init_checked(sc, sim, RT_SIM_LAYOUT);
}

rt_status rt_init_checked(const rt_scene *sc, rt_sim *sim, uint32_t caller_layout)
{
    rt_status st;
    if (!sc || !sim)
        return RT_E_ARG;
    /* before anything else is written: sim may be smaller than this build's rt_sim */
    if ((st = rti_layout_check(sim, caller_layout)) != RT_OK)
        return st;
    sim->sc = sc;
    sim->err[0] = 0;
    /* a re-used rt_sim starts as a fresh one: no value of the last run can leak into
       this one (a replay must not depend on what ran before) */
    rti_zero(&sim->state, sizeof sim->state);
    rti_zero(&sim->stats, sizeof sim->stats);
    rti_zero(&sim->work, sizeof sim->work);
    sim->plan.nseq = 0;
    sim->plan.nloops = 0;
    sim->state.hash = RT_HASH_INIT;
    for (int c = 0; c < RT_CNT_COUNT; c++)
        sim->stats.last_block[c] = -1;
    for (uint8_t s = 0; s < RT_MAX_SETS; s++)
        sim->plan.set_xout[s] = 0, sim->plan.sched[s] = s;
    if ((st = check_scene(sc, sim)) != RT_OK || (st = rti_invariant_init(sc, sim)) != RT_OK ||
        (st = layout(sc, sim)) != RT_OK ||
        (st = initial_values(sc, sim)) != RT_OK || (st = rti_check_starts(sc, sim)) != RT_OK ||
        (st = route(sc, sim)) != RT_OK ||
        (st = rti_xset_init(sc, sim)) != RT_OK || (st = rti_order(sc, sim)) != RT_OK ||
        /* the link's exports count among the held signals (check_history) */
        (st = rti_link_check(sc, sim)) != RT_OK || (st = check_history(sc, sim)) != RT_OK ||
        (st = rti_eval_plan(sc, sim)) != RT_OK || (st = check_methods(sc, sim)) != RT_OK ||
        (st = rti_held_plan(sc, sim)) != RT_OK ||
        (st = bg_init(sc, sim)) != RT_OK)
        return st;
    /* the graph searches used the integrator scratch: zero it again */
    rti_zero(&sim->work.w, sizeof sim->work.w);
    if (sc->mbs && (st = (rt_status)sc->mbs->init(sc, sim)) != RT_OK)
        return st;
    /* the known time events up to the end time (rt/tev.c) */
    if ((st = tick_count(sc, sim)) != RT_OK || (st = rti_tev_init(sc, sim)) != RT_OK)
        return st;
    if ((st = rt_refresh(sc, sim)) != RT_OK)
        return st;
    for (uint8_t s = 0; s < sc->nsets; s++)
        rti_prime_set(sc, sim, s, 0, sim->plan.set_h[s]);
    return RT_OK;
}
