/* tev.c - time events and the ends of a set's step parts: the instants at which a kind
 * switches in time (a step, a pulse edge), declared by rt_kind.next_event, as part of the
 * fixed schedule; the instants known only at run time of a kind with rt_kind.time_event
 * (an FMU's nextEventTime); and the services a kind asks for at the end of each completed
 * integration (rt_kind.step_end, FMI's CompletedIntegratorStep).
 *
 * A set holding such a kind ends a step at each of its instants. Every evaluation of a
 * step part (its stages, its end, the event location inside it) carries the part's
 * midpoint as rt_args.t_piece, and the kind picks its value by that: the part ending at
 * an instant sees the left limit at its end, the part starting there the right limit, and
 * an evaluation at a tick (the refresh, a sampled block's update, the history) the right
 * limit, as before. A step of several ticks with an instant strictly inside it is split
 * there into parts, each a step of the set's method; the set still steps and publishes at
 * the ticks of its fixed schedule, and a step holds at most RT_TEV_PARTS_MAX parts, so
 * its work stays bounded. rt_init walks every instant up to the end time: each must lie on
 * the base tick grid (the rule of the end time, RT_TICK_SLACK), else the scene is refused
 * with the block and the instant. (A switch inside a step instead would be read one
 * step early by every method whose stages reach t + h, rk4, dopri5, sdirk3, ..., which
 * then converges at first order whatever its own.)
 *
 * An instant known only at run time (the kind's next_event reads its own state, set by
 * its last event, or parameters rt_set_param may change: a defined system's comparison
 * of t with one, tools/scenec) cannot be walked at init and may lie anywhere: each step
 * of its set is integrated part by part, each part ending exactly at the earliest of the
 * step's end, the next instant of the set's other kinds (a tick) and the next run-time
 * instant (one within rounding before the step's end is the end: no sliver of a part),
 * so no stage of a part evaluates a kind past its instant; at a part's end the kinds'
 * step_end run, then the time_event of every instant due there. An event inside a part
 * that moves an instant into the rest of the part ends the part there (rt/step.c). The
 * parts stay at most RT_TEV_PARTS_MAX: an instant the last part passes is handled at the
 * step's end and counted (tev_limit, RT_E_TEV), never merged silently.
 *
 * Values a kind takes only at instants (rt_kind.instant: an FMU's discrete inputs and
 * tunable parameters, which FMI lets change in event mode alone; a defined system's
 * located switches, their modes from its own state and inputs, instant_own): the start and the end
 * of every part are such instants, where the kind is handed its inputs and parameters and
 * takes what changed (an event of its own); inside a part it holds them. So a part also
 * ends where such an input (RTI_SET_INSTANT_IN) is known to change: at each point strictly inside the step of
 * the history of a set that feeds it (the tick at which the other set's held value moves
 * on). A parameter written between ticks (rt_set_param) is taken at the start of the
 * set's next part, its next instant. */
#include "rti.h"

#define NEVER UINT64_MAX
/* the services a set steps in parts for (dyn_step), known ahead or not */
#define SET_PARTS (RTI_SET_TEV_DYN | RTI_SET_STEP_END | RTI_SET_INSTANT)

/* block b's first instant strictly after time t [s] */
static real_t block_next(const rt_scene *sc, rt_sim *sim, uint16_t b, real_t t)
{
    rt_args a;
    rti_args(sc, sim, b, t, 0, &a);
    return sc->blocks[b].kind->next_event(&a);
}

/* an instant found: its base tick (NEVER: none before the end time), the block it is
   of, its time [s] and its distance from the grid [ticks] */
typedef struct instant {
    uint64_t tick;
    uint16_t block;
    real_t t, off;
} instant;

/* does kind k switch at instants it knows before the run (walked at init, on the grid) */
static int known_ahead(const rt_kind *k)
{
    return k->next_event && !k->time_event;
}

/* set s's first instant strictly after time t [s]: the earliest over its blocks */
static instant set_next(const rt_scene *sc, rt_sim *sim, uint8_t s, real_t t)
{
    instant in = {NEVER, 0, RT_TEV_NEVER, 0};
    for (uint16_t k = sim->plan.blk_of[s]; k < sim->plan.blk_of[s + 1]; k++) {
        uint16_t b = sim->plan.set_blk[k];
        if (!known_ahead(sc->blocks[b].kind))
            continue;
        real_t te = block_next(sc, sim, b, t);
        if (te < in.t) /* (a NaN is no instant) */
            in.t = te, in.block = b;
    }
    real_t q = in.t / sc->dt;
    if (!(q < rti_tick_real(sim->plan.n_ticks)))
        return in;
    in.tick = rti_real_tick(q + (real_t)0.5);
    in.off = rt_fabs(q - rti_tick_real(in.tick));
    return in;
}

/* set s's first instant after base tick k, asked half a tick after it: rounding of an
   instant at k cannot return k again */
static instant next_after(const rt_scene *sc, rt_sim *sim, uint8_t s, uint64_t k)
{
    instant in = set_next(sc, sim, s, (rti_tick_real(k) + (real_t)0.5) * sc->dt);
    if (in.tick != NEVER && in.tick <= k)
        in.tick = k + 1;
    return in;
}

void rt_tev_none(const rt_args *a, real_t *x, real_t *d)
{
    (void)a, (void)x, (void)d; /* never called: part_end skips it */
}

/* set s switches at a time event here (a source's step, an edge, a define's comparison, an
   FMU's time event): a W-method's kept Jacobian belongs to the dynamics before it, and
   its estimate, filtered by it, reads a frozen state as exact (a stiffness that ends at
   the instant, ROS2 with its Jacobian every 64 steps: 0.75 off, status ok); a DIRK's
   Newton iteration tells a stale one itself, and a linear set's matrices cannot change.
   And the set's sensitivity to the inputs it reads from other sets may have moved (an
   enable): measured afresh (rti_xset_gain_stale) */
static void switched(const rt_scene *sc, rt_sim *sim, uint8_t s)
{
    if (sc->sets[s].method->w_method)
        sim->state.imp[s].valid = 0;
    rti_xset_gain_stale(sim, s);
}

/* is output v of set s read by another set (it keeps a history) */
static int read_elsewhere(const rt_sim *sim, uint8_t s, uint16_t v)
{
    return v < sim->plan.set_xout[s] && sim->plan.xsrc[v];
}

/* block b of set s switched strictly inside the set's step: another set reads its
   outputs only through its history, whose points are the step's ends, so a switch there
   (a pulse shorter than the step) is seen late, or not at all. Counted (errest:
   doubtful) if another set reads an output of b: its set's step is too long for the
   edges its readers take */
static void switched_inside(rt_sim *sim, uint8_t s, uint16_t b)
{
    for (uint16_t v = sim->plan.y_off[b]; v < sim->plan.y_off[b + 1]; v++)
        if (read_elsewhere(sim, s, v)) {
            rti_count(sim, RT_CNT_ERREST, b, RT_E_ACCURACY);
            sim->stats.errest[s]++;
            return;
        }
}

#if RT_MAX_TEV > 0
/* set s's first instant after base tick k, from state.tev_next while it lies after k
   (none can lie between the tick it was found from and it), else found anew */
static uint64_t next_tick(const rt_scene *sc, rt_sim *sim, uint8_t s, uint64_t k)
{
    uint64_t *next = &sim->state.tev_next[s];
    if (*next == 0 || *next <= k)
        *next = next_after(sc, sim, s, k).tick;
    return *next;
}

/* an instant of set s at base tick k strictly inside its step (switched_inside) */
static void inside_step(const rt_scene *sc, rt_sim *sim, uint8_t s, uint64_t k)
{
    instant in = set_next(sc, sim, s, (rti_tick_real(k) - (real_t)0.5) * sc->dt);
    if (in.tick == k)
        switched_inside(sim, s, in.block);
}

/* set s's step from tick k to ke (one part), its evaluations on their side of the
   instants around it (rt_args.t_piece) */
static void part(const rt_scene *sc, rt_sim *sim, uint8_t s, uint64_t k, uint64_t ke)
{
    real_t t = rti_tick_time(k, sc->dt), h = sc->dt * rti_tick_real(ke - k);
    sim->work.t_piece = t + (real_t)0.5 * h;
    rti_step_set(sc, sim, s, t, h, 0);
}
#endif

/* ------------------------------------------------------------------ instants known at run time */

/* the state of set s, kept in work.xb before a service that may change it */
static void keep_x(rt_sim *sim, uint8_t s)
{
    uint16_t x0 = sim->plan.set_x[s], n = (uint16_t)(sim->plan.set_x[s + 1] - x0);
    for (uint16_t i = 0; i < n; i++)
        sim->work.xb[i] = sim->state.x[x0 + i];
}

/* the services a kind runs at an instant of its set (serve) */
typedef enum { SERVE_TIME_EVENT, SERVE_STEP_END, SERVE_INSTANT } serve_what;

/* block b's service `what` at t, with its inputs there; a state it leaves not finite is
   counted (nan, the block) and the state before it kept, as a step's is (rt/step.c) */
static void serve(const rt_scene *sc, rt_sim *sim, uint8_t s, uint16_t b, real_t t,
                  serve_what what, int *changed)
{
    const rt_kind *k = sc->blocks[b].kind;
    real_t *x = sim->state.x + sim->plan.x_off[b], *d = sim->state.d + sim->plan.d_off[b];
    rt_args a;
    keep_x(sim, s);
    rti_gather(sim, b, t);
    rti_args(sc, sim, b, t, 0, &a);
    a.t_piece = rti_piece(sc, sim, k, t);
    int ran = 1;
    if (what == SERVE_STEP_END)
        ran = k->step_end(&a, x, d);
    else if (what == SERVE_INSTANT)
        ran = k->instant(&a, x, d);
    else
        k->time_event(&a, x, d);
    if (!ran)
        return;
    rti_count(sim, RT_CNT_EVENTS, b, RT_OK);
    if (!rt_all_finite(x, k->nx)) {
        uint16_t x0 = sim->plan.set_x[s], n = (uint16_t)(sim->plan.set_x[s + 1] - x0);
        for (uint16_t i = 0; i < n; i++)
            sim->state.x[x0 + i] = sim->work.xb[i];
        rti_count(sim, RT_CNT_NAN, b, RT_E_NAN);
    }
    rti_outputs(sc, sim, (rti_at){t, s, RTI_IN_STEP}); /* what the next service reads */
    *changed = 1;
}

/* each kind's instant service at t (rt_kind.instant), with its inputs there */
static void serve_instants(const rt_scene *sc, rt_sim *sim, uint8_t s, real_t t, int *changed)
{
    for (uint16_t k = sim->plan.blk_of[s]; k < sim->plan.blk_of[s + 1]; k++) {
        uint16_t b = sim->plan.set_blk[k];
        if (sc->blocks[b].kind->instant)
            serve(sc, sim, s, b, t, SERVE_INSTANT, changed);
    }
}

/* a signature of block b's outputs that another set reads: their bits (FNV-1a) */
static uint64_t read_sig(const rt_sim *sim, uint8_t s, uint16_t b)
{
    uint64_t h = 14695981039346656037u;
    for (uint16_t v = sim->plan.y_off[b]; v < sim->plan.y_off[b + 1]; v++)
        if (read_elsewhere(sim, s, v)) {
            rt_real_rep r = {.r = sim->state.y[v]};
            h = (h ^ (uint64_t)r.u) * 1099511628211u;
        }
    return h;
}

/* does an output of block b that another set reads jump at b's run-time instant t, where
   a part of set s ends (state.y holds the left limit there): the right limit against it,
   y left as it was. A kind's switch may lie in its derivatives alone (a kink in its
   outputs, which the readers' interpolation follows) */
static int jumps_at(const rt_scene *sc, rt_sim *sim, uint8_t s, uint16_t b, real_t t)
{
    const rt_kind *k = sc->blocks[b].kind;
    real_t *y = sim->state.y + sim->plan.y_off[b];
    if (!k->output)
        return 0;
    uint64_t left = read_sig(sim, s, b);
    rt_args a;
    rti_args(sc, sim, b, t, 0, &a);
    real_t tn = k->next_event(&a), half = (real_t)0.5 * sc->dt;
    a.t_piece = t + (tn - t < 2 * half ? (real_t)0.5 * (tn - t) : half); /* before the next */
    k->output(&a, y);
    int jump = read_sig(sim, s, b) != left;
    a.t_piece = rti_piece(sc, sim, k, t);
    k->output(&a, y);
    return jump;
}

/* at the end t of a part of set s begun at t0 (inside: strictly inside the set's step):
   each kind's step_end, then the time event of each block whose first run-time instant
   after t0 is due (at or before t: before it, by more than rounding, only past the bound
   of parts, counted), then the values each kind takes at instants; then the set's roots
   from the state after them */
static void part_end(const rt_scene *sc, rt_sim *sim, uint8_t s, real_t t0, real_t t,
                     int inside)
{
    uint16_t flags = sim->plan.set_flags[s];
    int changed = 0;
    rti_outputs(sc, sim, (rti_at){t, s, RTI_IN_STEP}); /* the inputs the services read */
    for (uint16_t k = sim->plan.blk_of[s]; (flags & RTI_SET_STEP_END) && k < sim->plan.blk_of[s + 1]; k++) {
        uint16_t b = sim->plan.set_blk[k];
        if (sc->blocks[b].kind->step_end)
            serve(sc, sim, s, b, t, SERVE_STEP_END, &changed);
    }
    for (uint16_t k = sim->plan.blk_of[s]; (flags & RTI_SET_TEV_DYN) && k < sim->plan.blk_of[s + 1]; k++) {
        uint16_t b = sim->plan.set_blk[k];
        if (!sc->blocks[b].kind->time_event)
            continue;
        real_t te = block_next(sc, sim, b, t0);
        if (!(te <= t))
            continue;
        if (te < t && !rt_same_instant(te, t)) /* passed by the last part the bound allows */
            rti_count(sim, RT_CNT_TEV_LIMIT, b, RT_E_TEV);
        switched(sc, sim, s);
        if (sc->blocks[b].kind->time_event != rt_tev_none)
            serve(sc, sim, s, b, t, SERVE_TIME_EVENT, &changed);
        else if (inside && jumps_at(sc, sim, s, b, t))
            switched_inside(sim, s, b);
    }
    if (flags & RTI_SET_INSTANT)
        serve_instants(sc, sim, s, t, &changed);
    if (changed && sim->plan.set_r[s + 1] > sim->plan.set_r[s])
        rti_roots(sc, sim, s, t, sim->state.r + sim->plan.set_r[s]);
}

int rti_tev_instant(const rt_scene *sc, rt_sim *sim, uint8_t s, real_t t)
{
    int changed = 0;
    rti_outputs(sc, sim, (rti_at){t, s, RTI_IN_STEP});
    serve_instants(sc, sim, s, t, &changed);
    if (changed && sim->plan.set_r[s + 1] > sim->plan.set_r[s])
        rti_roots(sc, sim, s, t, sim->state.r + sim->plan.set_r[s]);
    return changed;
}

/* the earliest point strictly between t and te of the history of a set that feeds an
   input of discrete variability (rt_kind.u_discrete) of a block of set s: where the
   value it reads next changes (RT_TEV_NEVER: none); *blk: that block */
static real_t input_next(const rt_scene *sc, const rt_sim *sim, uint8_t s, real_t t, real_t te,
                         uint16_t *blk)
{
    real_t tn = RT_TEV_NEVER;
    for (uint16_t k = sim->plan.blk_of[s]; k < sim->plan.blk_of[s + 1]; k++) {
        uint16_t b = sim->plan.set_blk[k];
        const rt_kind *kd = sc->blocks[b].kind;
        for (uint16_t i = 0; kd->u_discrete && i < kd->nu; i++) {
            uint16_t j = (uint16_t)(sim->plan.u_off[b] + i);
            if (!kd->u_discrete[i] || sim->plan.src_kind[j] != RT_SRC_XSET)
                continue;
            uint8_t q = sim->plan.src_set[j];
            for (uint8_t h = 0; h < sim->state.hist_n[q]; h++) {
                real_t th = sim->state.hist_t[q][h];
                if (th > t && th < te && th < tn)
                    tn = th, *blk = b;
            }
        }
    }
    return tn;
}

/* h, or the largest length with t + h <= te in this arithmetic if it reaches past te */
static real_t span_to(real_t t, real_t te, real_t h)
{
    if (!(t + h <= te))
        h = te - t;
    while (h > 0 && t + h > te)
        h -= h * RT_EPS;
    return h;
}

/* set s's step from tick over ratio ticks, part by part to each instant (known ahead: a
   tick; at run time: anywhere), with the services at each part's end */
static void dyn_step(const rt_scene *sc, rt_sim *sim, uint8_t s, uint64_t tick, uint32_t ratio)
{
    uint64_t end = tick + ratio;
#if RT_MAX_TEV > 0
    uint64_t k = tick; /* the tick the next known instant is sought from */
#endif
    real_t t = rti_tick_time(tick, sc->dt), t_end = rti_tick_time(end, sc->dt);
    for (int n = 1;; n++) {
        uint64_t kb = end;
#if RT_MAX_TEV > 0
        if (sim->plan.set_flags[s] & RTI_SET_TEV) {
            uint64_t ks = next_tick(sc, sim, s, k);
            kb = ks < end ? ks : end;
        }
#endif
        real_t tb = kb == end ? t_end : rti_tick_time(kb, sc->dt);
        if ((sim->plan.set_flags[s] & RTI_SET_INSTANT) && tb > t) {
            /* (its side of the known instants: any time before the next one) */
#if RT_MAX_TEV > 0
            sim->work.t_piece = (real_t)0.5 * (t + tb);
#endif
            rti_tev_instant(sc, sim, s, t); /* before the instants: an event may move them */
        }
        real_t td = (sim->plan.set_flags[s] & RTI_SET_TEV_DYN) ? rti_tev_dyn_next(sc, sim, s, t)
                                                                : (real_t)RT_TEV_NEVER;
        uint16_t bi = 0;
        real_t ti = (sim->plan.set_flags[s] & RTI_SET_INSTANT_IN)
                        ? input_next(sc, sim, s, t, t_end, &bi) : (real_t)RT_TEV_NEVER;
        td = ti < td ? ti : td;
        if (td < tb && rt_same_instant(td, tb))
            td = tb; /* the instant is the part's end to rounding: no sliver of a part */
        int last = n >= RT_TEV_PARTS_MAX;
        if (td < tb)
            tb = td, kb = NEVER;
        if (last && ti < t_end) /* an input's change the last part passes: taken late */
            rti_count(sim, RT_CNT_TEV_LIMIT, bi, RT_E_TEV);
        if (last)
            tb = t_end, kb = end; /* an instant before it is handled (late) at its end */
        real_t reached = t;
        if (tb > t) {
            /* a whole step without parts: its length as a step without parts has it; a
               part ending at a run-time instant: never past it */
            real_t h = n == 1 && tb == t_end ? sim->plan.set_h[s] : tb - t;
            if (td <= tb)
                h = span_to(t, tb, h);
#if RT_MAX_TEV > 0
            sim->work.t_piece = (real_t)0.5 * (t + tb);
#endif
            reached = rti_step_set(sc, sim, s, t, h, !last);
            if (reached >= t + h)
                reached = tb; /* the part's end, exactly */
        }
        part_end(sc, sim, s, t, reached, reached < t_end);
#if RT_MAX_TEV > 0
        if (reached == tb && kb != NEVER)
            k = kb;
        if (reached == tb && kb != NEVER && kb < end)
            inside_step(sc, sim, s, kb), switched(sc, sim, s);
#endif
        t = reached;
        if (t >= t_end)
            break;
    }
#if RT_MAX_TEV > 0
    sim->work.t_piece = 0;
#endif
}

void rti_tev_inside(const rt_scene *sc, rt_sim *sim, uint8_t s, uint64_t tick, uint32_t ratio)
{
#if RT_MAX_TEV > 0
    if (!(sim->plan.set_flags[s] & RTI_SET_TEV))
        return;
    for (uint64_t k = tick, end = tick + ratio; (k = next_tick(sc, sim, s, k)) < end;)
        inside_step(sc, sim, s, k);
#else
    (void)sc, (void)sim, (void)s, (void)tick, (void)ratio;
#endif
}

void rti_tev_step(const rt_scene *sc, rt_sim *sim, uint8_t s, uint64_t tick, uint32_t ratio)
{
    if (rti_tev_at(sc, sim, s, tick)) /* the step starts at an instant known ahead */
        switched(sc, sim, s);
    if (sim->plan.set_flags[s] & SET_PARTS) {
        dyn_step(sc, sim, s, tick, ratio);
        return;
    }
#if RT_MAX_TEV > 0
    uint64_t end = tick + ratio, k = tick, ke;
    if (sim->plan.set_flags[s] & RTI_SET_TEV) {
        /* part by part to each instant inside the step; the last part ends at the step's
           end whatever lies inside it (rti_tev_init refused a scene needing more parts) */
        for (int n = 1; n < RT_TEV_PARTS_MAX && (ke = next_tick(sc, sim, s, k)) < end; n++) {
            part(sc, sim, s, k, ke);
            inside_step(sc, sim, s, ke);
            switched(sc, sim, s);
            k = ke;
        }
        part(sc, sim, s, k, end);
        sim->work.t_piece = 0;
        return;
    }
#endif
    rti_step_set(sc, sim, s, rti_tick_time(tick, sc->dt), sim->plan.set_h[s], 0);
}

int rti_tev_at(const rt_scene *sc, rt_sim *sim, uint8_t s, uint64_t tick)
{
#if RT_MAX_TEV > 0
    return tick > 0 && (sim->plan.set_flags[s] & RTI_SET_TEV) &&
           next_tick(sc, sim, s, tick - 1) == tick;
#else
    (void)sc, (void)sim, (void)s, (void)tick;
    return 0;
#endif
}

int rti_tev_was(const rt_scene *sc, rt_sim *sim, uint8_t s, uint64_t tick)
{
    return tick > 0 && (sim->plan.set_flags[s] & RTI_SET_TEV) &&
           next_after(sc, sim, s, tick - 1).tick == tick;
}

int rti_tev_block_was(const rt_scene *sc, rt_sim *sim, uint16_t b, uint64_t tick)
{
#if RT_MAX_TEV > 0
    if (tick == 0 || !known_ahead(sc->blocks[b].kind))
        return 0;
    /* (asked half a tick before it, as next_after asks) */
    real_t q = block_next(sc, sim, b, (rti_tick_real(tick - 1) + (real_t)0.5) * sc->dt) / sc->dt;
    return q == q && rt_fabs(q - rti_tick_real(tick)) < (real_t)0.5;
#else
    (void)sc, (void)sim, (void)b, (void)tick;
    return 0;
#endif
}

void rti_tev_moved(rt_sim *sim, uint8_t s)
{
#if RT_MAX_TEV > 0
    sim->state.tev_next[s] = 0;
#else
    (void)sim, (void)s;
#endif
}

/* ------------------------------------------------------------------ checks at init */

/* the decimal digits of v into buf (at least 21 bytes); returns the end */
static char *put_uint(char *buf, uint64_t v)
{
    char tmp[21];
    int n = 0;
    do
        tmp[n++] = (char)('0' + v % 10), v /= 10;
    while (v);
    while (n)
        *buf++ = tmp[--n];
    *buf = 0;
    return buf;
}

/* t >= 0 [s] as decimal digits with up to 9 decimals, trailing zeros dropped */
static void put_time(char *buf, real_t t)
{
    uint64_t ns = (uint64_t)(t * (real_t)1e9 + (real_t)0.5);
    char *p = put_uint(buf, ns / 1000000000u);
    uint64_t frac = ns % 1000000000u;
    if (!frac)
        return;
    *p++ = '.';
    for (uint64_t d = 100000000u; frac; d /= 10)
        *p++ = (char)('0' + frac / d), frac %= d;
    *p = 0;
}

static rt_status off_grid(const rt_scene *sc, rt_sim *sim, const instant *in)
{
    char when[40], lo[24];
    uint64_t below = (uint64_t)(in->t / sc->dt);
    put_time(when, in->t);
    put_uint(lo, below);
    return rti_fail(sim, RT_E_SCENE, "block ", sc->blocks[in->block].name, ": time event at t = ",
                    when, " s is off the base tick grid (after tick ", lo, ")", (const char *)0);
}

static rt_status too_many_parts(const rt_scene *sc, rt_sim *sim, uint8_t s, const instant *in)
{
    char when[40];
    put_time(when, in->t);
    return rti_fail(sim, RT_E_SCENE, "set ", sc->sets[s].name, ": time events (block ",
                    sc->blocks[in->block].name, ", t = ", when, " s) split a step into more "
                    "than RT_TEV_PARTS_MAX parts: shorten its step", (const char *)0);
}

/* every instant of set s up to the end time: on the grid, at most RT_TEV_PARTS_MAX parts
   per step of the set (the walk is bounded by the instants before the end) */
static rt_status check_set(const rt_scene *sc, rt_sim *sim, uint8_t s)
{
    uint32_t ratio = sc->sets[s].ratio;
    real_t slack_max = (real_t)0.25;
    uint64_t step = NEVER;
    unsigned parts = 0;
    /* from t = 0 (an instant between 0 and half a tick is off the grid too) */
    instant in = set_next(sc, sim, s, 0);
    while (in.tick != NEVER) {
        real_t slack = RT_TICK_SLACK * (in.t / sc->dt > 1 ? in.t / sc->dt : 1);
        if (!(in.off <= (slack < slack_max ? slack : slack_max)))
            return off_grid(sc, sim, &in);
        if (in.tick % ratio != 0) { /* strictly inside a step of the set */
            if (in.tick / ratio != step)
                step = in.tick / ratio, parts = 1;
            if (++parts > RT_TEV_PARTS_MAX)
                return too_many_parts(sc, sim, s, &in);
        }
        in = next_after(sc, sim, s, in.tick);
    }
    return RT_OK;
}

/* the flags of set s's kinds: RTI_SET_TEV (time events, known ahead or at run time),
   RTI_SET_TEV_DYN (at run time), RTI_SET_TEV_SERVE (with a handler that serves: not
   rt_tev_none), RTI_SET_STEP_END (a step-end service), RTI_SET_INSTANT
   (values taken at instants), RTI_SET_INSTANT_IN (from outside the kind: an FMU's
   discrete inputs; not a defined system's switch modes, rt_kind.instant_own),
   RTI_SET_EVERY_SIGN (roots whose every sign change is a crossing, rt/step.c) */
static uint16_t tev_flags(const rt_scene *sc, const rt_sim *sim, uint8_t s)
{
    uint16_t f = 0;
    for (uint16_t k = sim->plan.blk_of[s]; k < sim->plan.blk_of[s + 1]; k++) {
        const rt_kind *kd = sc->blocks[sim->plan.set_blk[k]].kind;
        f = (uint16_t)(f | (kd->next_event ? RTI_SET_TEV : 0) |
                       (kd->next_event && kd->time_event ? RTI_SET_TEV_DYN : 0) |
                       (kd->time_event && kd->time_event != rt_tev_none ? RTI_SET_TEV_SERVE
                                                                        : 0) |
                       (kd->step_end ? RTI_SET_STEP_END : 0) |
                       (kd->instant ? RTI_SET_INSTANT : 0) |
                       (kd->instant && !kd->instant_own ? RTI_SET_INSTANT_IN : 0) |
                       (kd->nr && kd->roots_every_sign ? RTI_SET_EVERY_SIGN : 0));
    }
    return f;
}

/* ------------------------------------------------------------------ bands */

/* How block b's time dependence travels: carriers[k] is, for each block whose outputs
   carry it (b, and each block with throughput reading a carrier; not a sampled block,
   whose samples are the model's own), the longest step at which the signal has been
   sampled on its way there (another set's history of it is sampled at that set's step),
   and the set of that step; at < 0: not a carrier */
typedef struct carried {
    real_t h;
    int16_t at;   /* the set whose step h is; -1: none yet (0 s); -2: not a carrier */
} carried;

/* what input i reads of the carriers: the sampling its value has had (its writer's, and
   another set's history), or at = -2 when it reads none. A torn loop input reads the
   output that closes the loop */
static carried input_carried(const rt_scene *sc, const rt_sim *sim, uint16_t i,
                             const carried *via)
{
    carried c = {0, -2};
    uint8_t k = sim->plan.src_kind[i];
    uint16_t v = sim->plan.src[i];
    if (k == RT_SRC_TORN)
        v = sim->plan.torn_src[v];
    else if (k != RT_SRC_Y && k != RT_SRC_HELD && k != RT_SRC_XSET)
        return c;
    c = via[rti_writer(sc, sim, v)];
    if (c.at != -2 && k == RT_SRC_XSET && !(sim->plan.set_h[sim->plan.src_set[i]] <= c.h))
        c.h = sim->plan.set_h[sim->plan.src_set[i]], c.at = sim->plan.src_set[i];
    return c;
}

/* the longer sampling of a and b (b if a carries nothing) */
static carried longer(carried a, carried b)
{
    return b.at != -2 && (a.at == -2 || b.h > a.h) ? b : a;
}

/* block r's own sampling of the signal and the longest its inputs read */
static carried reads(const rt_scene *sc, const rt_sim *sim, uint16_t r, const carried *via)
{
    carried c = via[r];
    for (uint16_t i = sim->plan.u_off[r]; i < sim->plan.u_off[r + 1]; i++)
        c = longer(c, input_carried(sc, sim, i, via));
    return c;
}

/* the fixed point of the carriers from b (each pass can only lengthen a sampling, so it
   ends after at most one pass per block) */
static void carriers(const rt_scene *sc, const rt_sim *sim, uint16_t b, carried *via)
{
    for (uint16_t k = 0; k < sc->nblocks; k++)
        via[k] = (carried){0, k == b ? -1 : -2};
    for (int grew = 1; grew;) {
        grew = 0;
        for (uint16_t r = 0; r < sc->nblocks; r++) {
            const rt_kind *k = sc->blocks[r].kind;
            if (r == b || k->feed == RT_FEED_NONE || k->type == RT_KIND_DSS)
                continue;
            carried c = reads(sc, sim, r, via);
            if (c.at != via[r].at || c.h != via[r].h)
                via[r] = c, grew = 1;
        }
    }
}

/* block b's band against the steps that integrate it: each block with states or roots
   of its own that carries it or reads a carrier, at its set's step or the longer sampling the
   signal had on its way; a band of 0 (no time dependence, a sine of amplitude 0) none */
static rt_status check_band(const rt_scene *sc, rt_sim *sim, uint16_t b)
{
    const rt_kind *kb = sc->blocks[b].kind;
    if (!kb->band)
        return RT_OK;
    rt_args a;
    rti_args(sc, sim, b, 0, 0, &a);
    real_t w = kb->band(&a);
    if (w == 0)
        return RT_OK;
    carried via[RT_MAX_BLOCKS], worst = {0, -2};
    carriers(sc, sim, b, via);
    for (uint16_t r = 0; r < sc->nblocks; r++) {
        const rt_kind *k = sc->blocks[r].kind;
        if ((k->nx == 0 && k->nr == 0) || k->type == RT_KIND_DSS)
            continue; /* (roots sample it too: a crossing and back inside a step is unseen) */
        carried c = reads(sc, sim, r, via);
        if (c.at == -2)
            continue;
        c = longer(c, (carried){sim->plan.set_h[sc->blocks[r].set], sc->blocks[r].set});
        worst = longer(worst, c);
    }
    if (worst.at < 0 || w * worst.h < (real_t)RT_PI)
        return RT_OK;
    char t1[RTI_REAL_TEXT], t2[RTI_REAL_TEXT];
    return rti_fail(sim, RT_E_PARAM, sc->blocks[b].name, ": ", rti_real_text(t1, w),
                    " rad/s aliased by set ", sc->sets[worst.at].name, "'s step (needs h < ",
                    rti_real_text(t2, (real_t)RT_PI / w), " s)", (const char *)0);
}

rt_status rti_tev_init(const rt_scene *sc, rt_sim *sim)
{
    for (uint16_t b = 0; b < sc->nblocks; b++) {
        rt_status st = check_band(sc, sim, b);
        if (st != RT_OK)
            return st;
    }
    unsigned n = 0;
    for (uint8_t s = 0; s < sc->nsets; s++) {
        uint16_t f = tev_flags(sc, sim, s);
        sim->plan.set_flags[s] |= (uint16_t)(f & RTI_SET_EVERY_SIGN);
        /* steps for its services' sake */
        if (f & SET_PARTS)
            sim->plan.set_flags[s] = (uint16_t)((sim->plan.set_flags[s] | f) & ~RTI_SET_NO_STEP);
        if (!(f & RTI_SET_TEV))
            continue;
        if (++n > RT_MAX_TEV)
            return rti_capacity(sim, 0, 0, RT_LIM_TEV);
        sim->plan.set_flags[s] |= RTI_SET_TEV;
        rt_status st = check_set(sc, sim, s);
        if (st != RT_OK)
            return st;
    }
    return RT_OK;
}

rt_status rti_tev_check_block(const rt_scene *sc, rt_sim *sim, uint16_t b)
{
    rt_status st = check_band(sc, sim, b);
    if (st != RT_OK || !sc->blocks[b].kind->next_event)
        return st;
    rti_tev_moved(sim, sc->blocks[b].set); /* its instants may have moved */
    return check_set(sc, sim, sc->blocks[b].set);
}
