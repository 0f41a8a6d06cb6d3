/* rti.h - internal interfaces shared between the files of rt/ (prefix rti_).
 * Applications include rt.h only. */
#ifndef RTI_H
#define RTI_H

#include "rt_sim.h"

/* evaluation modes of the output sequence */
typedef enum {
    RTI_AT_TICK = 0, /* at a tick boundary: DSS blocks whose sample hits are called */
    RTI_IN_STEP,     /* inside a set step: DSS outputs are held, not called */
    RTI_IN_RHS,      /* inside a right-hand side: as RTI_IN_STEP, and blocks whose outputs
                        no continuous block of their set reads are not called, nor a
                        block's repeated call if none reads an output that depends on
                        its inputs, nor a sampled block; a kind's lean output equation
                        where it gives all that is read (plan.seq_flags) */
    RTI_AT_TICK_RECALL /* at a tick boundary, right after the step's end evaluation at the
                          same time (RTI_IN_STEP, for the history): as RTI_AT_TICK, but
                          only the entries whose outputs may differ from that
                          evaluation's are called again (RTI_SEQ_RECALL, rti_eval_plan) */
} rti_mode;

/* An evaluation instant, passed down explicitly (no ambient "current set/time" in
   rt_sim): the time, the set whose blocks are evaluated (RT_ALL_SETS: every set) and the
   mode of the output sequence. */
typedef struct rti_at {
    real_t t;
    uint8_t set;
    rti_mode mode;
} rti_at;

/* src_kind of an input not routed yet (rt_init's routing fills every input) */
#define RTI_SRC_UNSET 0xFF
/* rt_plan.rec_y of a recorded value that is no block's output (y's places are uint16_t
   and fewer than this) */
#define RTI_REC_OTHER 0xFFFFu

/* keeps GCC's interprocedural passes (inlining, pure/const discovery) away from a
   function; see rti_gather for the miscompilation it prevents */
#if defined(__GNUC__) && !defined(__clang__)
#define RTI_NOIPA __attribute__((noipa))
#else
#define RTI_NOIPA
#endif

/* asks for a small hot function to be inlined where a constant argument lets the
   compiler specialize it (unrolled loops); plain inline elsewhere */
#if defined(__GNUC__)
#define RTI_INLINE inline __attribute__((always_inline))
#else
#define RTI_INLINE inline
#endif

/* ---- invariants (invariant.c) ---- */
/* Checks the kinds' declared invariants (types, indices, tolerances) at init. */
rt_status rti_invariant_init(const rt_scene *sc, rt_sim *sim);
/* Each block's initial state against its kind's rules (rt_kind.check_start): RT_E_PARAM
   with the block and the kind's reason for the first that breaks them. */
rt_status rti_check_starts(const rt_scene *sc, rt_sim *sim);
/* After a step of set s: each block's invariants at its new state, a violation counted
   (RT_CNT_INVARIANT with the block, RT_E_INVARIANT). */
void rti_invariants(const rt_scene *sc, rt_sim *sim, uint8_t s);

/* ---- text (util.c) ---- */
/* Writes the NULL-terminated list of strings into sim->err and returns status. */
rt_status rti_fail(rt_sim *sim, rt_status status, ...);
/* Appends the NULL-terminated list of strings to sim->err ("; " after earlier text): the
   warnings of an rt_init that returns RT_OK (rt_error_text). */
void rti_note(rt_sim *sim, ...);
/* v as "d.dde+xx" into buf (RTI_REAL_TEXT bytes); returns buf (or a constant "nan"). */
#define RTI_REAL_TEXT 16
const char *rti_real_text(char *buf, real_t v);
/* "RT_LOOP_ITER_LIMIT (32 in rt_config.h)": a constant with its value, for rti_fail's
   messages about the limits that are not capacities (those say rti_capacity) */
#define RTI_STR2(x) #x
#define RTI_STR(x) RTI_STR2(x)
#define RTI_LIMIT(name) #name " (" RTI_STR(name) " in rt_config.h)"
/* RT_E_CAPACITY with the limit's own text (rt_limit_text) and where it was exceeded:
   "[<place><name>: ]<what it counts> exceed RT_MAX_<NAME> (<value> in rt_config.h)",
   place "set ", "block " or "joint " and the item's name, or both 0 for the scene */
rt_status rti_capacity(rt_sim *sim, const char *place, const char *name, rt_limit lim);
/* RT_OK when caller_layout is this build's RT_SIM_LAYOUT; else RT_E_SCENE with its text
   in sim->err, which every layout has at offset 0 (nothing else of sim is written): the
   caller's rt_sim was compiled with other limits (rt_init_checked, rt_bg_attach_checked) */
rt_status rti_layout_check(rt_sim *sim, uint32_t caller_layout);
/* Sets n bytes at p to zero (freestanding memset). */
void rti_zero(void *p, size_t n);
/* The trace hash of one more value (rt_hash_real): one multiply and one xor-shift, on the
   value's bit pattern as an integer (a float's zero-extended), so it does not depend on
   the target's byte order. Every bit of a value reaches the high half through the odd
   multiplier and the high half the low half through the shift, ahead of the next value's
   multiply. It runs at every tick over every recorded value, so it takes one multiply per
   value where a byte-wise hash (FNV-1a) takes eight. */
static inline uint64_t rti_hash(uint64_t h, real_t v)
{
    union {
        real_t r;
#if RT_REAL_IS_FLOAT
        uint32_t u;
#else
        uint64_t u;
#endif
    } bits;
    bits.r = v;
    h = (h ^ (uint64_t)bits.u) * RT_HASH_MUL;
    return h ^ (h >> 32);
}
/* the value of a signal reference (recorded or exported) at the current state (held.c) */
real_t rti_sig_value(const rt_scene *sc, const rt_sim *sim, const rt_rec *r);
/* the link's exported signal i (i < nexp): its held value if it is a multibody signal of
   a set held between steps, as recording shows it, else its value now (held.c) */
real_t rti_export_value(const rt_scene *sc, const rt_sim *sim, uint16_t i);
/* checks the scene's controller link (link.c), at init */
rt_status rti_link_check(const rt_scene *sc, rt_sim *sim);
/* Bumps counter c and remembers block b (-1: none); keeps the first fault in sim->stats.status. */
void rti_count(rt_sim *sim, rt_counter c, int b, rt_status status);

/* ---- evaluation order (order.c) ---- */
/* Builds sim->plan.seq and sim->plan.loops from the port-level throughput graph; RT_E_LOOP when an
   actual loop is found (its blocks are in sim->plan.loops). */
rt_status rti_order(const rt_scene *sc, rt_sim *sim);
/* 1 if output j of kind k depends directly on its input i (a throughput) */
int rti_feeds(const rt_kind *k, uint16_t j, uint16_t i);

/* ---- evaluation (eval.c) ---- */
/* Fills an argument record for block b at time t. Always inline: the record holds
   pointers into *sim, and GCC 12 (AArch64, -O1 and up) lost that escape in its summary
   of an out-of-line version, deleting the input gathering before block calls as dead
   stores (seen as wrong results under qemu-aarch64; x86-64 happened to inline it). */
static inline void rti_args(const rt_scene *sc, const rt_sim *sim, uint16_t b, real_t t,
                            real_t h, rt_args *a)
{
    a->t = t;
    a->h = h;
    a->x = sim->state.x + sim->plan.x_off[b];
    a->d = sim->state.d + sim->plan.d_off[b];
    a->u = sim->work.u + sim->plan.u_off[b];
    a->p = sim->state.p + sim->plan.p_off[b];
    a->spec = sc->blocks[b].kind->spec;
    a->t_piece = t; /* a kind with known time events gets its piece: rti_piece */
}
/* the time of the piece between known time events an evaluation of kind k at t lies in
   (rt_args.t_piece): the midpoint of the step part being integrated (rt/tev.c); else, at
   a tick, half a base tick after t, or t itself for a kind whose instants may lie off the
   grid (rt_kind.time_event: one may lie within half a tick after t). Set where a kind
   with rt_kind.next_event is called (its output, derivative and roots, rt/eval.c): the
   others never read it */
static inline real_t rti_piece(const rt_scene *sc, const rt_sim *sim, const rt_kind *k,
                               real_t t)
{
#if RT_MAX_TEV > 0
    if (sim->work.t_piece > 0)
        return sim->work.t_piece;
#else
    (void)sim; /* no set has known time events: never inside a part */
#endif
    return k->time_event ? t : t + (real_t)0.5 * sc->dt;
}
/* Gathers the inputs of block b at time t from the outputs that feed them (y = P u; an
   input from another set is reconstructed at t). */
void rti_gather(rt_sim *sim, uint16_t b, real_t t);
/* the block whose outputs hold global output index v (inline: the plan builders in
   eval.c, xset.c and tev.c ask it without calling one another for it) */
static inline uint16_t rti_writer(const rt_scene *sc, const rt_sim *sim, uint16_t v)
{
    uint16_t b = 0;
    while (b + 1 < sc->nblocks && sim->plan.y_off[b + 1] <= v)
        b++;
    return b;
}
/* Calls the output equations of sequence entries [begin, end) (a loop segment). */
void rti_run_calls(const rt_scene *sc, rt_sim *sim, uint16_t begin, uint16_t end, rti_at at);
/* Evaluates the output sequence at the instant at, solving actual loops on the way. */
void rti_outputs(const rt_scene *sc, rt_sim *sim, rti_at at);
/* Root values of the blocks of set s at time t (outputs must be current) into r. */
void rti_roots(const rt_scene *sc, rt_sim *sim, uint8_t s, real_t t, real_t *r);
/* The evaluation tables of the passes over one set (after routing, rti_xset_init and
   rti_order): each set's entries of the sequence and its blocks (plan.set_seq,
   plan.set_blk), the entries a right-hand side need not call (plan.seq_flags): a
   block's first call if no input of its own set reads its outputs live, a repeated call
   (after its inputs changed) if none reads one that depends on them, and those a tick's
   renewal calls again (RTI_SEQ_RECALL); the set flags it owns (plan.set_flags). Returns
   RT_OK. */
rt_status rti_eval_plan(const rt_scene *sc, rt_sim *sim);
/* what init found of a set (plan.set_flags), one bit each, and the file that finds it */
enum {
    RTI_SET_DERIV = 1,      /* a block has a deriv (NSS, LSS): rti_rhs walks them  eval.c */
    RTI_SET_AUTONOMOUS = 2, /* its right-hand side does not read t over a step     eval.c */
    RTI_SET_LINEAR = 4,     /* linear in its state (the transition method's test)  eval.c */
    RTI_SET_NO_STEP = 8,    /* no state, root or rhs call: the tick skips its step eval.c */
    RTI_SET_HOLDS_SIG = 16, /* holds recorded/exported multibody signals (held_sig) held.c */
    RTI_SET_XPRED = 32,     /* reads another set's history: its error checked      eval.c */
    RTI_SET_KEEPS_END = 64, /* multi-tick, read by others: step end kept in y_end  held.c */
    RTI_SET_TEV = 128,      /* holds a kind with known time events                 tev.c */
    RTI_SET_TEV_DYN = 256,  /* holds one whose instants are known at run time only tev.c */
    RTI_SET_STEP_END = 512, /* holds a kind with a step-end service (step_end)     tev.c */
    RTI_SET_EVERY_SIGN = 1024, /* holds a kind with roots_every_sign               tev.c */
    RTI_SET_INSTANT = 2048, /* holds a kind taking values at instants (instant)    tev.c */
    RTI_SET_TEV_SERVE = 4096, /* holds a time_event that serves (not rt_tev_none)  tev.c */
    RTI_SET_INSTANT_IN = 8192 /* one whose instant takes values from outside (not
                                 instant_own): its parts end where they change     tev.c */
};
/* The first block of set s that keeps it from being linear in its state, or -1. */
int rti_nonlinear_block(const rt_scene *sc, const rt_sim *sim, uint8_t s);
/* what a right-hand side does with an entry of the sequence (plan.seq_flags & RTI_SEQ_RHS) */
typedef enum { RTI_RHS_CALL = 0, RTI_RHS_SKIP, RTI_RHS_LEAN } rti_rhs_call;
/* the bits of plan.seq_flags (rti_eval_plan) */
enum {
    RTI_SEQ_RHS = 3,   /* the entry's rti_rhs_call */
    RTI_SEQ_RECALL = 4 /* a renewal calls it again: a loop, a sampled block, or one with
                          throughput reading a history, a sampled or a recalled output */
};
/* The next run of consecutive blocks of set s from its k-th (plan.set_blk, ascending):
   their outputs are one range of y, [y_off[b], y_off[*end]); returns b, advances k. */
static inline uint16_t rti_block_run(const rt_sim *sim, uint8_t s, uint16_t *k, uint16_t *end)
{
    uint16_t b = sim->plan.set_blk[(*k)++], e = (uint16_t)(b + 1);
    while (*k < sim->plan.blk_of[s + 1] && sim->plan.set_blk[*k] == e)
        (*k)++, e++;
    *end = e;
    return b;
}
/* a tick count as a real, from 32 bits while it fits (the same value, so the same
   bits): a 64-bit integer's conversion is a library call on a 32-bit core, a 32-bit
   one an instruction with an FPU; and the time of tick `tick`: the count times the base
   step, never a running sum */
static inline real_t rti_tick_real(uint64_t tick)
{
    return tick <= UINT32_MAX ? (real_t)(uint32_t)tick : (real_t)tick;
}
/* ... and back: a real in [0, 2^64) truncated to a count, through 32 bits below 2^32 */
static inline uint64_t rti_real_tick(real_t q)
{
    return q < (real_t)4294967296.0 ? (uint64_t)(uint32_t)q : (uint64_t)q;
}
static inline real_t rti_tick_time(uint64_t tick, real_t dt)
{
    return rti_tick_real(tick) * dt;
}
/* the time of the current state (rt_time) */
static inline real_t rti_time(const rt_scene *sc, const rt_sim *sim)
{
    return rti_tick_time(sim->state.tick, sc->dt);
}
/* the tick count modulo r (a set's ratio, a sampled block's period): in 32 bits while
   the count fits, as it does for 49 days at 1 ms: a 64-bit remainder is a library call
   of some hundred instructions on a 32-bit core, a 32-bit one an instruction (Cortex-M3,
   M4, M7) */
static inline uint32_t rti_tick_mod(uint64_t tick, uint32_t r)
{
    return tick <= UINT32_MAX ? (uint32_t)tick % r : (uint32_t)(tick % r);
}
/* does set s's state belong to the current tick: it has just stepped to it (each tick for
   a set of ratio 1), its background step was published at it (rt/bg.c), or the run is
   at its start. Between those ticks its outputs are held (rt/held.c) */
static inline int rti_at_tick(const rt_sim *sim, uint8_t s)
{
    return sim->state.set_tick[s] == sim->state.tick;
}
/* continuous states set s integrates (rt_set_nx) */
static inline uint16_t rti_set_nx(const rt_sim *sim, uint8_t s)
{
    return (uint16_t)(sim->plan.set_x[s + 1] - sim->plan.set_x[s]);
}
/* Right-hand side of set s: outputs, then derivatives of the set's blocks. */
rt_status rti_rhs(void *ctx, real_t t, real_t *xdot);
/* a set's settings with every zero replaced by its default (RT_SET_CFG_LIST): the one
   place a default is chosen (rt_set_cfg_of for the tools) */
static inline rt_set_cfg rti_set_cfg_of(const rt_set_cfg *c)
{
    rt_set_cfg r = *c;
#define RT_X_DFLT(id, word, opt, field, kind, max, scope, dflt, help)                       \
    if (!(r.field > 0))                                                                     \
        r.field = dflt;
    RT_SET_CFG_LIST(RT_X_DFLT)
#undef RT_X_DFLT
    return r;
}
/* the accuracy a set's error estimates are held to */
static inline real_t rti_accuracy(const rt_set_cfg *c)
{
    return rti_set_cfg_of(c).accuracy;
}
/* the floor of the error norm of a set's estimates, max_i |e_i| / (floor + |x_i|): 1
   unless the set declares an absolute tolerance (atol / accuracy; docs/solvers.md) */
static inline real_t rti_err_floor(const rt_set_cfg *c)
{
    rt_set_cfg d = rti_set_cfg_of(c);
    return d.atol > 0 ? d.atol / d.accuracy : (real_t)1;
}
/* Forward-difference Jacobian of f at (t, x) around fb = f(t, x) into the n x n row-major
   jac, column by column: x_j moves in place by inc max(1, |x_j|), re-measured as the
   representable difference, and is restored bit for bit; fd is n scratch. Returns the
   first error of f, or RT_OK (rt/integ_implicit.c; the transition method's too). */
rt_status rti_fd_jacobian(const rt_rhs *f, real_t t, real_t *x, uint16_t n, const real_t *fb,
                          real_t inc, real_t *fd, real_t *jac);

typedef struct rti_rhs_ctx {
    const rt_scene *sc;
    rt_sim *sim;
    uint8_t set;
    real_t h;
} rti_rhs_ctx;

/* the earliest time event after t known at run time (rt_kind.time_event) of set s [s],
   RT_TEV_NEVER if none (eval.c) */
real_t rti_tev_dyn_next(const rt_scene *sc, rt_sim *sim, uint8_t s, real_t t);

/* ---- multirate (xset.c) ---- */
/* Marks inputs fed by another set, chooses their schemes, orders the schedule. */
rt_status rti_xset_init(const rt_scene *sc, rt_sim *sim);
/* Pushes set s's outputs read by other sets, at time t, into their history. */
void rti_xset_push(const rt_scene *sc, rt_sim *sim, uint8_t s, real_t t);
/* Output v of set q reconstructed at time t by the scheme, for an evaluation of block
   reader's set (RT_MAX_BLOCKS: at a tick, outside any set's step). */
real_t rti_xset_value(const rt_sim *sim, uint16_t v, uint8_t q, uint8_t scheme, real_t t,
                      uint16_t reader);
/* does set s read another set's history (the error of each such input is checked,
   rt/xpred.c); _npred: the inputs that do, of every set (RT_MAX_XPRED) */
int rti_xset_monitors(const rt_scene *sc, const rt_sim *sim, uint8_t s);
uint16_t rti_xset_npred(const rt_scene *sc, const rt_sim *sim);
/* how an input reads its source's history over its set's step (plan.xpred_how) */
enum {
    RTI_XP_NONE,   /* not from another set's history */
    RTI_XP_AHEAD,  /* beyond the newest point: its prediction checked at the next */
    RTI_XP_BRACKET, /* between two points: the scheme's error over them estimated */
    RTI_XP_HELD    /* a sampled output that moves inside the reader's step, held over it:
                      checked at the next step's start, as ahead */
};

/* how far before its level a root is taken to start, so that a crossing at the very
   start (a root on its level, rt/step.c; a mode condition past it, rt/held.c) is seen */
#define RTI_ROOT_HAIR (RT_REAL_IS_FLOAT ? (real_t)1e-30 : (real_t)1e-300)

/* the shortest previous integration, as a fraction of the current one (and the longest,
   as its inverse), whose start a root's excursion parabola takes as its third point
   (rt/step.c excursion): closer, its curvature is a difference of rounding */
#define RTI_EXCURSION_SPAN ((real_t)0.015625)

/* state.hist_ev: the set's step in progress fired an event (its next push's interval) */
#define RTI_HIST_EV_STEP 0x80u

/* ---- the communication-error monitor (xpred.c) ---- */
/* at the start of set s's step over [t, t + h]: the inputs it extrapolates from other sets
   against what their schemes predicted at its last step (RT_E_COUPLING past
   RT_XSET_LOST), and their predictions for t + h kept; the inputs it reads between two
   points of a source's history, at the first step in a new interval, by the error of
   their scheme over it. _reset: none (the run's start) */
void rti_xset_predict(const rt_scene *sc, rt_sim *sim, uint8_t s, real_t t, real_t h);
void rti_xset_predict_reset(rt_sim *sim);
/* set s's sensitivity to the inputs it reads from other sets, at its step's start t (step h), when
   due (every RT_XSET_GAIN_EVERY steps of it, or NaN: none yet, or marked by a miss near
   the accuracy): two right-hand sides per input, in the context that runs the step
   (rti_xset_predict calls it for a set of the tick, rt/bg.c for the background set) */
void rti_xset_gain(const rt_scene *sc, rt_sim *sim, uint8_t s, real_t t, real_t h);
/* set s switched (a time event, an event's handlers: a gain or an enable may have moved):
   its sensitivities are measured afresh at its next step (rti_xset_gain). Not the
   background set's: its release is judged with what its last step measured, and a NaN
   there would leave that step unjudged. Inline: rt/step.c and rt/tev.c mark, xpred.c
   measures, and none of them calls another for it */
static inline void rti_xset_gain_stale(rt_sim *sim, uint8_t s)
{
#if RT_MAX_XPRED > 0
    for (uint16_t k = sim->plan.xpred_of[s];
         s != sim->plan.bg_set && k < sim->plan.xpred_of[s + 1]; k++)
        sim->state.xgain[k] = (real_t)0 / (real_t)0;
#else
    (void)sim, (void)s;
#endif
}
/* set s, its state at a tick where an input from another set's history jumped: how long
   before the tick the jump built up, the longest such interval (a source extrapolated
   over s's step: the step; one read between points: its interval ending there); 0 where
   no such source has a point now, or its jump is at a known instant (rt/tev.c) */
real_t rti_xset_late(const rt_scene *sc, rt_sim *sim, uint8_t s);

/* ---- what a signal read from another set misses by (xmiss.c) ---- */
/* an error est that set s took from its coupling (block b), against its accuracy: above
   it, counted like a step whose estimate exceeds it (errest, RT_E_ACCURACY); the largest
   kept in stats.xset_est */
void rti_xset_judge(const rt_scene *sc, rt_sim *sim, uint8_t s, uint16_t b, real_t est);
/* what the inputs set s reads from other sets may put into something computed from them
   (a root, a handler's result) at time t of its step h: per input whose scheme misses
   there (by the points' next difference, at t's place among them), its history
   shifted by a small d that every scheme reproduces, fn is called with w = miss / d (so
   w times the change is that input's share) and the window the miss spans (the source's
   interval read between points, h read ahead), then the history restored bit for bit.
   An interval of the source that holds a state event (state.hist_ev) misses as a hold */
typedef void (*rti_xset_effect)(void *ctx, real_t w, real_t window);
void rti_xset_shifted(const rt_scene *sc, rt_sim *sim, uint8_t s, real_t t, real_t h,
                      rti_xset_effect fn, void *ctx);

/* ---- what a set shows between its steps (held.c) ---- */
/* the highest output index of a set stepping over several ticks, plus one (RT_MAX_HELD_Y) */
uint16_t rti_held_top(const rt_scene *sc, const rt_sim *sim);
/* recorded and exported multibody signals held between their set's steps: how many
   (RT_MAX_HELD_SIG) */
uint16_t rti_held_sigs(const rt_scene *sc);
/* at init (after rti_eval_plan): the set flags RTI_SET_HOLDS_SIG and RTI_SET_KEEPS_END */
rt_status rti_held_plan(const rt_scene *sc, rt_sim *sim);
/* around set s's step in the tick (ratio: its ticks per step): its outputs at this tick
   kept aside (work.y_shown) before, and put back after, its step's end ones kept in
   state.y_end when it keeps them */
void rti_held_before_step(rt_sim *sim, uint8_t s, uint32_t ratio);
void rti_held_after_step(rt_sim *sim, uint8_t s, uint32_t ratio);
/* after the tick's steps and publication: the outputs, roots and held signals of every
   set whose state reached the new tick; recall: a bit per set whose step's end evaluated
   its outputs at that time already (only the entries RTI_SEQ_RECALL are called again) */
void rti_held_renew(const rt_scene *sc, rt_sim *sim, uint32_t recall);
/* set s's held signals at the end of its background step, into bg_result_sig of the
   context it ran in (tick: the tick there), and at its publication from there into
   held_sig (the slots of plan.bg_sig) */
void rti_hold_bg_signals(const rt_scene *sc, rt_sim *ctx, uint8_t s, uint64_t tick);
void rti_publish_signals(rt_sim *sim, const rt_sim *ctx);
/* the slots in held_sig of set s's held signals, ascending, into slots (as many as the
   scene holds, RT_MAX_HELD_SIG at most after rt_init's check); returns their number */
uint16_t rti_held_slots(const rt_scene *sc, uint8_t s, uint16_t *slots);

/* ---- the background set (bg.c; the rest through rt_scene.bg) ---- */
/* Reals of the background set's result (states and outputs), 0 without one. */
uint32_t rti_bg_size(const rt_scene *sc, const rt_sim *sim);

/* ---- known time events (tev.c) ---- */
/* at init (after rti_eval_plan and the tick count): flags the sets holding a kind with
   known time events (RTI_SET_TEV) and checks every instant up to the end time: on the
   base tick grid, and at most RT_TEV_PARTS_MAX parts per step; else RT_E_SCENE; and
   every block's band (rt_kind.band) below pi / h of each set that integrates it, else
   RT_E_PARAM */
rt_status rti_tev_init(const rt_scene *sc, rt_sim *sim);
/* the same checks for block b's set after a parameter of b changed (rt_set_param), and
   its band (rt_kind.band) against the steps that integrate it: at or above pi / h the
   steps sample an alias of it, RT_E_PARAM */
rt_status rti_tev_check_block(const rt_scene *sc, rt_sim *sim, uint16_t b);
/* set s's step from base tick `tick` over `ratio` ticks: one rti_step_set, or one per
   part between the known time events inside it, each evaluated on its own side of them */
void rti_tev_step(const rt_scene *sc, rt_sim *sim, uint8_t s, uint64_t tick, uint32_t ratio);
/* the known instants strictly inside set s's step from base tick `tick` over `ratio`
   ticks, of a set with nothing to integrate (RTI_SET_NO_STEP; rti_tev_step does the
   same for the others): a block switching there whose outputs another set reads through
   the history (whose points are the step's ends) is counted, errest */
void rti_tev_inside(const rt_scene *sc, rt_sim *sim, uint8_t s, uint64_t tick, uint32_t ratio);
/* an instant of set s at time t, where its state is (the start of a step part, the tick
   its state reaches): its outputs there (on the side work.t_piece says), then each kind's
   rt_kind.instant with its inputs there; the set's roots again after one that ran an
   event. Returns 1 if one did */
int rti_tev_instant(const rt_scene *sc, rt_sim *sim, uint8_t s, real_t t);
/* a parameter of set s changed: its next instant is found anew */
void rti_tev_moved(rt_sim *sim, uint8_t s);
/* is base tick `tick` a known time event of set s (of its kinds without time_event) */
int rti_tev_at(const rt_scene *sc, rt_sim *sim, uint8_t s, uint64_t tick);
/* the same for any tick, past ones too (without rti_tev_at's memory of the next one) */
int rti_tev_was(const rt_scene *sc, rt_sim *sim, uint8_t s, uint64_t tick);
/* 1 if block b (a kind that knows its instants ahead) has one at base tick `tick` */
int rti_tev_block_was(const rt_scene *sc, rt_sim *sim, uint16_t b, uint64_t tick);

/* ---- set steps and events (step.c) ---- */
/* Advances set s from t by its step h, handling state events; never stops half-way, but
   (may_stop) at an event that moved a time event known at run time inside the step
   (rt/tev.c). Returns the time reached: t + h, or that event's. */
real_t rti_step_set(const rt_scene *sc, rt_sim *sim, uint8_t s, real_t t, real_t h, int may_stop);
/* does root i of kind k cross from ra to rb in its declared direction? A root a handler
   sent back to (or stopped on) side `side` of its level lvl (rt_state.r_side, r_lvl)
   crosses when it leaves the level to the other */
int rti_root_crossed(const rt_kind *k, uint16_t i, real_t ra, real_t rb, real_t lvl, int side);
/* before the first tick: set s's method makes ready what it keeps between steps of h
   from time t (rt_integrator.prime; ROS2's first Jacobian of a spread refresh) */
void rti_prime_set(const rt_scene *sc, rt_sim *sim, uint8_t s, real_t t, real_t h);
/* records the right-hand sides set s's whole step took since its count was r0
   (rt_istats.rhs_set_step_max, the witness of rt_set_step_bound) */
void rti_step_witness(rt_sim *sim, uint8_t s, uint64_t r0);

/* ---- graph search (scc.c) ---- */
/* Successor enumeration: returns the next successor of v after cursor (updating it),
   or -1 when v has no more. Cursors start at 0. */
typedef int (*rti_next_fn)(const void *ctx, uint16_t v, uint32_t *cursor);

typedef rt_scc_work rti_scc_work;

/* Tarjan's strongly connected components over n nodes without recursion. Writes the
   component id of each node into comp (components numbered in reverse topological order:
   sinks first) and returns the number of components. */
uint16_t rti_scc(uint16_t n, rti_next_fn next, const void *ctx, rti_scc_work *w,
                 uint16_t *comp);

/* ------------------------------------------------------------------ fault injection */

/* A test build (-DRT_FAULT_INJECT=1, `make test-faults`) can force one fault from a chosen
   tick on (tests/faults/test_faults.c, docs/reliability.md); other builds have no hook. */
#ifndef RT_FAULT_INJECT
#define RT_FAULT_INJECT 0
#endif
typedef enum {
    RTI_FAULT_NONE = 0,
    RTI_FAULT_NAN,      /* output 0 of block `block` is NaN */
    RTI_FAULT_SINGULAR, /* every LU factorization meets a zero pivot */
    RTI_FAULT_LOOP,     /* an algebraic loop cannot meet its tolerance */
    RTI_FAULT_NEWTON    /* every Newton iteration of an implicit step diverges */
} rti_fault_kind;
typedef struct rti_fault {
    rti_fault_kind kind;
    int16_t block;      /* RTI_FAULT_NAN: the block */
    uint64_t from_tick; /* the first tick it happens in */
    uint64_t to_tick;   /* the tick it stops at (exclusive) */
} rti_fault;
#if RT_FAULT_INJECT
extern rti_fault rti_fault_plan;
extern const rt_sim *rti_fault_sim; /* the simulator ticking (set by rt_tick) */
int rti_fault_due(rti_fault_kind k);
#else
#define rti_fault_due(k) 0
#endif

#endif /* RTI_H */
