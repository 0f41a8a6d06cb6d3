/* tev.c - known time events: the instants at which a kind switches in time (a step, a
 * pulse edge; an FMU's time events), declared by rt_kind.next_event, as part of the fixed
 * schedule.
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
 * then converges at first order whatever its own.) */
#include "rti.h"

#define NEVER UINT64_MAX

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

/* set s's first instant strictly after time t [s]: the earliest over its blocks */
static instant set_next(const rt_scene *sc, rt_sim *sim, uint8_t s, real_t t)
{
    instant in = {NEVER, 0, RT_TEV_NEVER, 0};
    for (uint16_t k = sim->plan.blk_of[s]; k < sim->plan.blk_of[s + 1]; k++) {
        uint16_t b = sim->plan.set_blk[k];
        if (!sc->blocks[b].kind->next_event)
            continue;
        real_t te = block_next(sc, sim, b, t);
        if (te < in.t) /* (a NaN is no instant) */
            in.t = te, in.block = b;
    }
    real_t q = in.t / sc->dt;
    if (!(q < (real_t)sim->plan.n_ticks))
        return in;
    in.tick = (uint64_t)(q + (real_t)0.5);
    in.off = rt_fabs(q - (real_t)in.tick);
    return in;
}

/* set s's first instant after base tick k, asked half a tick after it: rounding of an
   instant at k cannot return k again */
static instant next_after(const rt_scene *sc, rt_sim *sim, uint8_t s, uint64_t k)
{
    instant in = set_next(sc, sim, s, ((real_t)k + (real_t)0.5) * sc->dt);
    if (in.tick != NEVER && in.tick <= k)
        in.tick = k + 1;
    return in;
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

/* set s's step from tick k to ke (one part), its evaluations on their side of the
   instants around it (rt_args.t_piece) */
static void part(const rt_scene *sc, rt_sim *sim, uint8_t s, uint64_t k, uint64_t ke)
{
    real_t t = (real_t)k * sc->dt, h = sc->dt * (real_t)(ke - k);
    sim->work.t_piece = t + (real_t)0.5 * h;
    rti_step_set(sc, sim, s, t, h);
}
#endif

void rti_tev_step(const rt_scene *sc, rt_sim *sim, uint8_t s, uint64_t tick, uint32_t ratio)
{
#if RT_MAX_TEV > 0
    uint64_t end = tick + ratio, k = tick, ke;
    if (sim->plan.set_flags[s] & RTI_SET_TEV) {
        /* part by part to each instant inside the step; the last part ends at the step's
           end whatever lies inside it (rti_tev_init refused a scene needing more parts) */
        for (int n = 1; n < RT_TEV_PARTS_MAX && (ke = next_tick(sc, sim, s, k)) < end; n++) {
            part(sc, sim, s, k, ke);
            k = ke;
        }
        part(sc, sim, s, k, end);
        sim->work.t_piece = 0;
        return;
    }
#endif
    rti_step_set(sc, sim, s, (real_t)tick * sc->dt, sim->plan.set_h[s]);
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

/* does set s hold a kind with known time events */
static int has_events(const rt_scene *sc, const rt_sim *sim, uint8_t s)
{
    for (uint16_t k = sim->plan.blk_of[s]; k < sim->plan.blk_of[s + 1]; k++)
        if (sc->blocks[sim->plan.set_blk[k]].kind->next_event)
            return 1;
    return 0;
}

rt_status rti_tev_init(const rt_scene *sc, rt_sim *sim)
{
    unsigned n = 0;
    for (uint8_t s = 0; s < sc->nsets; s++) {
        if (!has_events(sc, sim, s))
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
    if (!sc->blocks[b].kind->next_event)
        return RT_OK;
    rti_tev_moved(sim, sc->blocks[b].set); /* its instants may have moved */
    return check_set(sc, sim, sc->blocks[b].set);
}
