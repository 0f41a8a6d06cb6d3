/* rt_sim.h - the storage layout of a running scene (rt_sim: plan, state, stats, work) and
 * of its snapshot (rt_state). The runtime's own: an application includes it only where it
 * allocates an rt_sim or an rt_state (static storage; the sizes are rt_config.h's), and
 * reads a run through the functions of rt.h (rt_ticks_done, rt_trace_hash, rt_output,
 * rt_stats_of, ...), so the layout may change without it. */
#ifndef RT_SIM_H
#define RT_SIM_H

#include "rt.h"

/* Scratch of the graph searches at init (shares storage with the integrator workspace). */
typedef struct rt_scc_work {
    uint16_t index[RT_MAX_NODES];
    uint16_t low[RT_MAX_NODES];
    uint16_t stack[RT_MAX_NODES];
    uint16_t call[RT_MAX_NODES];   /* explicit depth-first call stack */
    uint32_t cursor[RT_MAX_NODES]; /* successor cursor per node */
    uint8_t on[RT_MAX_NODES];      /* node is on the component stack */
    uint16_t comp[RT_MAX_NODES];   /* component of each node */
    uint16_t done[RT_MAX_NODES];   /* sequence position where an output became final */
    uint16_t orig[RT_MAX_NODES];   /* component before tearing */
    uint8_t color[RT_MAX_NODES];   /* tearing search: 0 new, 1 on the path, 2 done */
    uint16_t last[RT_MAX_BLOCKS];  /* sequence position of a block's last call */
} rt_scc_work;

#define RT_ALL_SETS 0xFF

/* The plan of a running scene: computed once by rt_init from the scene, never written
 * during ticks (layout, routing, evaluation sequence, loops, schedule). Only rt/ reads it. */
typedef struct rt_plan {
    /* sets: slice of x each set integrates, and slice of r holding each set's roots */
    uint16_t set_x[RT_MAX_SETS + 1];
    uint16_t set_r[RT_MAX_SETS + 1];
    real_t set_h[RT_MAX_SETS];       /* each set's step [s] (rt_set_step) */

    /* layout: offsets of each block's slice in the value arrays (size nblocks + 1) */
    uint16_t x_off[RT_MAX_BLOCKS + 1], d_off[RT_MAX_BLOCKS + 1];
    uint16_t u_off[RT_MAX_BLOCKS + 1], y_off[RT_MAX_BLOCKS + 1];
    uint16_t p_off[RT_MAX_BLOCKS + 1];
    uint32_t period[RT_MAX_BLOCKS]; /* DSS sample period in base ticks, 0 otherwise */
    uint16_t dss_first, dss_end;    /* the DSS blocks lie in [dss_first, dss_end) */

    /* signal routing: each input reads y[src[i]] or def[i] */
    uint8_t src_kind[RT_MAX_U];      /* rt_src_kind */
    uint16_t src[RT_MAX_U];          /* global output index */
    real_t def[RT_MAX_U];            /* default value */

    /* evaluation order (rt/order.c) */
    rt_seq_step seq[RT_MAX_SEQ];
    uint8_t seq_flags[RT_MAX_SEQ];   /* per entry of seq, what a right-hand side does with
                                        it (rti_rhs_call) and whether a tick's renewal
                                        calls it (rti_eval_plan) */
    uint16_t nseq;
    /* per set, what a pass over that set alone walks (rti_eval_plan), so that the fast
       set of a multirate scene does not scan the slow set's entries every stage: its
       entries of seq in sequence order (a loop's entry stands for its calls), and its
       blocks in block order */
    uint16_t set_seq[RT_MAX_SEQ];    /* set s: set_seq[seq_of[s] .. seq_of[s + 1]) */
    uint16_t seq_of[RT_MAX_SETS + 1];
    uint16_t rhs_calls[RT_MAX_SETS]; /* entries of set s a right-hand side runs (0: none,
                                        as in a multibody set without signal blocks) */
    uint16_t set_blk[RT_MAX_BLOCKS]; /* set s: set_blk[blk_of[s] .. blk_of[s + 1]) */
    uint16_t blk_of[RT_MAX_SETS + 1];
    rt_loop loops[RT_MAX_LOOPS];
    uint8_t nloops;
    uint16_t loop_blocks[2 * RT_MAX_BLOCKS]; /* blocks of each loop, see rt_loop */

    /* torn loop inputs (rt/loop.c): the unknowns of the actual loops */
    uint16_t ntorn;
    uint16_t torn_in[RT_MAX_TORN];   /* global input index of each torn input */
    uint16_t torn_src[RT_MAX_TORN];  /* the output that drives it (loop-closing edge) */

    /* multirate (rt/xset.c) */
    uint8_t sched[RT_MAX_SETS];      /* order sets step in within a tick (slowest first) */
    uint8_t rsched[RT_MAX_SETS];     /* order the sets' outputs are refreshed in at a tick:
                                        sched's, but a set whose sampled outputs another
                                        set reads (RT_SRC_HELD) before that set (rt/xset.c),
                                        so the trace does not depend on how the scene
                                        lists its sets */
    uint16_t set_flags[RT_MAX_SETS]; /* rti_set_flag bits of each set (rti_eval_plan) */
    uint32_t inv_sets;               /* bit s: set s holds a kind declaring invariants, which
                                        its steps check (rti_invariant_init) */
    uint8_t interp[RT_MAX_U];        /* rt_interp of each cross-set input */
    uint8_t src_set[RT_MAX_U];       /* the set a cross-set input comes from */
    uint8_t xsrc[RT_MAX_HIST_Y];     /* 1: output read by another set (keeps history);
                                        sized like the history: higher outputs never are */
    uint16_t set_xout[RT_MAX_SETS];  /* the set's highest output read by other sets, plus
                                        one (0: none): its history push stops there */
    int16_t bg_set;                  /* the scene's background set (rt/bg.c), -1: none */
    /* recorded value i < RT_MAX_REC: its place in state.y when it is a block's output (the
       common case), else RTI_REC_OTHER (read through its kind or the MBS services); set at
       init, so rt_record reads an output with one load (rt/held.c) */
    uint16_t rec_y[RT_MAX_REC];
    /* what its release and its publication copy between the tick and a context, listed
       at init so the tick walks no block (rt/bg.c): its outputs, runs [bg_y[k],
       bg_y[k + 1]) of y for even k < nbg_y; its inputs from other sets (RT_SRC_HELD or
       RT_SRC_XSET); and the slots of its held signals in state.held_sig (rt/held.c) */
    uint16_t bg_y[2 * RT_MAX_BLOCKS];
    uint16_t bg_in[RT_MAX_U];
    uint16_t nbg_y, nbg_in;
#if RT_MAX_HELD_SIG > 0
    uint16_t bg_sig[RT_MAX_HELD_SIG];
    uint16_t nbg_sig;
#endif
#if RT_MAX_XPRED > 0
    /* inputs a set reads from another set's history, whose error is checked
       (rti_xset_predict), the block each belongs to and how it reads it (RTI_XP_*);
       grouped by set, set s's from xpred_of[s] to xpred_of[s + 1] */
    uint16_t xpred_in[RT_MAX_XPRED], xpred_blk[RT_MAX_XPRED];
    uint8_t xpred_how[RT_MAX_XPRED];
    uint16_t nxpred, xpred_of[RT_MAX_SETS + 1];
#endif

    uint64_t n_ticks;                /* ticks to reach t_end */
} rt_plan;

/* The state of a running scene: everything a snapshot or a replay needs to continue
 * bit for bit, in one struct, so that saving and restoring it is one copy. */
struct rt_state {
    uint64_t tick;                   /* base ticks done; t = tick * dt */
    uint64_t set_tick[RT_MAX_SETS];  /* tick each set's state belongs to */
    real_t x[RT_MAX_X];              /* continuous state */
    real_t d[RT_MAX_D];              /* discrete state */
    real_t y[RT_MAX_Y];              /* outputs (DSS outputs held between hits) */
    real_t p[RT_MAX_P];              /* parameters (may be changed before the run) */
    real_t r[RT_MAX_ROOTS];          /* root values at the end of the last step */
    real_t r_prev[RT_MAX_ROOTS];     /* root values one integration before state.r, and
                                        per set that integration's length (r_prev_h; 0:
                                        none, or an event since): three values show a
                                        root that crosses and returns within one step
                                        (rt/step.c, excursion) */
    real_t r_prev_h[RT_MAX_SETS];
    real_t r_late[RT_MAX_SETS];      /* per set with r_kept: how long before the tick the
                                        crossing may have come (0: at the tick), judged
                                        at its event (rt/held.c, step.c) */
    real_t r_lvl[RT_MAX_ROOTS];      /* level each root crosses at: 0, or after a handler
                                        that sent it back (or stopped it) the value it
                                        was handled at, less a margin (rt/step.c) */
    real_t torn_val[RT_MAX_TORN];    /* torn inputs' values (warm start of the next solve) */
    real_t torn_range[RT_MAX_TORN];  /* the largest |value| each has had at a solve's end, up
                                        to 1: its scale below 1 (rt/loop.c) */
    real_t loop_h[RT_MAX_TORN * RT_MAX_TORN]; /* inverse Jacobians, Broyden-updated */
    real_t hist_t[RT_MAX_SETS][RT_HIST]; /* communication times, newest first [s] */
    real_t hist_y[RT_HIST][RT_MAX_HIST_Y];/* cross-set outputs at those times */
    rt_implicit_ws imp[RT_MAX_SETS]; /* implicit methods' persistent data per set */
    /* the background set's step in flight (rt/bg.c): released at tick bg_due - ratio,
       published at tick bg_due; bg_result holds its result (x slice, then the outputs of
       its blocks) until then when it ran inline (no background context attached) */
    uint64_t bg_due;                 /* tick its result is due */
    real_t bg_result[RT_MAX_BG];     /* inline result, published at bg_due */
    /* per cross-set output, one of two: the background set is read ahead of its history
       only, every other set between its points or ahead, so an output needs one, and a
       second array would cost every rt_sim RT_MAX_HIST_Y reals for nothing */
    union {
        /* of the background set: what the parabolic extrapolation showed at the newest
           point, minus that point; faded out over the next macro step, so the value read
           stays continuous (rt/xset.c) */
        real_t bg_jump[RT_MAX_HIST_Y];
        /* of any other set: the second difference of the three points before the newest
           (NaN: fewer), whose change to the newest three is the third difference a
           parabola's error is estimated by (rt/xpred.c) */
        real_t hist_d2[RT_MAX_HIST_Y];
    };
#if RT_MAX_HELD_Y > 0
    /* a set stepping over several ticks in the tick whose outputs another set reads: its
       outputs at its step's end, evaluated then for its history and taken from here when
       its state reaches the tick (RTI_SET_KEEPS_END, rt/held.c) */
    real_t y_end[RT_MAX_HELD_Y];
#endif
#if RT_MAX_XPRED > 0
    /* per input of plan.xpred_in: ahead, the value its scheme gave for the end of its
       set's step, made at the step's start (NaN: none yet), checked at the next; between
       two points, the newer point's time when that interval was judged; and the largest
       |u| the input has had at those checks, its scale (rti_xset_predict) */
    real_t xpred[RT_MAX_XPRED], xscale[RT_MAX_XPRED];
    /* per input of plan.xpred_in: the sensitivity of its set's derivatives to it, the
       largest |df_i/du| / (1 + |x_i|) [1/s per unit of u], measured by a difference every
       RT_XSET_GAIN_EVERY steps of the set and before a miss near its accuracy is judged
       (NaN: due), which turns a missed prediction into an error of the set's state
       (rti_xset_predict) */
    real_t xgain[RT_MAX_XPRED];
#endif
#if RT_MAX_HELD_SIG > 0
    /* recorded (in record order), then link-exported (in export order) multibody signals
       of the sets held between steps: they change with the set's state only, so they are
       computed when its outputs are; a background set's by its step, at the step's end,
       into bg_result_sig (in the context the step runs in), taken over at its
       publication (rt/held.c, rt/bg.c) */
    real_t held_sig[RT_MAX_HELD_SIG];
    real_t bg_result_sig[RT_MAX_HELD_SIG];
#endif
#if RT_MAX_TEV > 0
    /* per set holding a kind with known time events: the base tick of its next instant,
       UINT64_MAX: none before the end, 0: to be found (at the start, after a parameter
       change); so a step walks the set's blocks only at an instant (rt/tev.c) */
    uint64_t tev_next[RT_MAX_SETS];
#endif
    uint64_t hash;                   /* trace hash of the recorded values (rt_hash_real) */
    int16_t bg_nonfinite;            /* the first block of the background set whose outputs
                                        its step ended with are not finite, -1: none; found
                                        by the step, counted by the tick that publishes it
                                        (rt/bg.c, rt/sim.c) */
    /* the byte-wide members last, together: no padding after each (RAM of small targets) */
    uint8_t loop_h_valid[RT_MAX_LOOPS];/* loop_h of loop l holds an estimate */
    uint8_t hist_n[RT_MAX_SETS];     /* valid history points per set */
    uint8_t param_changed[RT_MAX_SETS]; /* a parameter of the set changed (rt_set_param):
                                        its next step forms its Jacobian anew (rt/step.c;
                                        a background set's in the context that runs it)
                                        and a multi-tick set's renewal evaluates its
                                        outputs in full (rt/held.c) */
    uint8_t bg_busy;                 /* 1: a step is released and not yet published */
    uint8_t hist_ev[RT_MAX_SETS];    /* per set, a bit per interval of its history that
                                        holds a state event (bit 0: the newest, between
                                        hist_t[s][1] and [0]), whose outputs may jump
                                        anywhere inside it; RTI_HIST_EV_STEP: one in the
                                        step not yet pushed (rt/step.c, rt/xset.c) */
    uint8_t r_kept[RT_MAX_SETS];     /* 1: a root of the set crossed by its inputs' jump at
                                        the tick its state reached; its value kept from
                                        the step's end, and its handler due at the tick */
#if RT_MAX_KSTATE > 0
    /* the internal state of the blocks whose kind keeps one (rt_kind.save), written by
       rt_snapshot only: per such block in block order its size (4 bytes, little-endian;
       RTI_KSTATE_BAD: the save failed) and its bytes (rt/snapshot.c) */
    uint8_t kstate[RT_MAX_KSTATE];
#endif
    int8_t r_side[RT_MAX_ROOTS];     /* per root, the side (+1 above r_lvl, -1 below) a
                                        handler sent it back to (or stopped it on) and
                                        it must not leave without a located crossing;
                                        0: none (until it is seen on that side of 0) */
    uint8_t mbs_restart;             /* a multibody block's parameter or state changed
                                        before the first tick (rt_set_param): rt_refresh
                                        projects the start again (rt/mbs_start.c); kept
                                        while the start it makes is refused */
};


/* Scratch of the tick: meaningless between ticks. Only rt/ touches it. */
typedef struct rt_work {
    real_t u[RT_MAX_U];              /* gathered inputs */
    /* integrator workspace; the graph searches of rt_init use the same storage */
    union {
        real_t k[RT_MAX_STAGES][RT_MAX_X];
        rt_scc_work scc;
    } w;
    real_t x0[RT_MAX_X];
#if RT_MAX_TRANSITION_N > 0
    real_t tm[2 * RT_MAX_TRANSITION_N * RT_MAX_TRANSITION_N]; /* method transition */
#endif
    real_t xb[RT_MAX_EVENT_X];           /* state at the right end of an event bracket */
    real_t xs[RT_MAX_X];             /* saved state for event location */
    real_t rs[RT_MAX_ROOTS];         /* root values scratch */
#if RT_MAX_HELD_Y > 0
    real_t y_shown[RT_MAX_HELD_Y];   /* a multi-tick set's outputs at the tick it steps
                                        from, kept while its step overwrites y (held.c) */
#endif
    real_t loop_work[RT_MAX_TORN * (RT_MAX_TORN + 4)]; /* loop solver scratch */
    uint16_t loop_piv[RT_MAX_TORN];
    /* the fault counters and status before the last rt_refresh before the first tick
       (held.c; has0: taken): the next such refresh takes its counts back first, so the
       start is judged with the parameters it has then alone (rt_init's own refresh
       solved the loops with the scene's values, which --set may have replaced) */
    uint32_t count0[RT_CNT_COUNT];
    rt_status status0;
    uint8_t has0;
    rt_mbs_work mbs;                 /* multibody tables and assembly workspace */
#if RT_MAX_TEV > 0
    real_t t_piece;                  /* midpoint of the step part a set with known time
                                        events is integrating [s] (rt_args.t_piece); 0:
                                        none, at a tick (rt/tev.c) */
#endif
} rt_work;

/* One running scene. The caller owns it (static storage); rt_init fills every part.
 * Sizes are the compile-time limits of rt_config.h. Who may read what:
 *   plan   rt/ only (init writes it, ticks read it)
 *   state  rt/; applications only to snapshot and restore it whole (rt_snapshot)
 *   stats  rt/ writes; applications read (summaries, tests)
 *   work   rt/ only */
struct rt_sim {
    /* what rt_init found wrong, and where. First, at offset 0 under every limit: rt_init
       can say that the caller's rt_sim has another layout than the runtime's (rt_sim.h's
       rt_init) without writing past the caller's object */
    char err[RT_ERR_LEN];
    rt_plan plan;
    rt_state state;
    rt_stats stats;
    rt_work work;
    const rt_scene *sc;              /* (the pointers last, beside each other: no padding
                                        before the 8-byte-aligned plan on 32-bit targets) */
    /* the background context (rt_bg_attach): a second rt_sim the background set steps
       in, so that it shares no memory with the tick; NULL: its steps run inline at
       release (the simulated clock). Two counters hand a step over, each written by one
       side only and never reset, so no side can see a stale pair: bg_released counts the
       steps the tick released, bg_finished (written by the background context) the
       released step it finished; a step is pending while they differ. */
    struct rt_sim *bg;
    uint32_t bg_released, bg_finished;
    /* written by the background context with bg_finished: its step counted something
       (a fault counter, the status, a loop solve), which the publication merges into the
       tick's statistics; 0: the publication skips those (rt/bg.c) */
    uint8_t bg_counted;
};

/* rt_sim's layout under this build's limits, as one number: its size, where its parts
   start (err is at 0 under every limit) and the limits themselves. Two builds with other
   limits (RT_MAX_*, REAL) differ in one of them: rt_init refuses an rt_sim laid out
   otherwise than the runtime's (below), and a scene's written-out code compiled so
   (rt_scene_code.sim_layout) */
#define RT_SIM_LAYOUT                                                                     \
    ((uint32_t)sizeof(rt_sim) ^ (uint32_t)offsetof(rt_sim, state) * 2654435761u ^        \
     (uint32_t)offsetof(rt_sim, stats) * 40503u ^ (uint32_t)offsetof(rt_sim, work) * 97u ^ \
     (uint32_t)offsetof(rt_sim, plan) * 7u ^ RT_SIM_LIMITS)
/* every capacity limit's value at its own odd weight (its row of RT_LIMIT_LIST), summed:
   two builds that trade sizes inside one part of rt_sim (one more discrete state, one
   parameter fewer: the same size and offsets) still differ */
#define RT_X_LIMIT_MIX(name, field, least, dflt, what)                                     \
    +(uint32_t)RT_MAX_##name * ((2u * (uint32_t)RT_LIM_##name + 1u) * 0x9e3779b1u)
#define RT_SIM_LIMITS (0u RT_LIMIT_LIST(RT_X_LIMIT_MIX))

/* Every file that can allocate an rt_sim or an rt_state includes this header: its
   rt_init, rt_bg_attach, rt_snapshot and rt_restore pass the layout it allocates with,
   which the runtime checks against its own before it writes anything (rt.h:
   rt_init_checked, ...) */
#define rt_init(scene, sim) rt_init_checked((scene), (sim), RT_SIM_LAYOUT)
#define rt_bg_attach(scene, sim, bg) rt_bg_attach_checked((scene), (sim), (bg), RT_SIM_LAYOUT)
#define rt_snapshot(sim, out) rt_snapshot_checked((sim), (out), RT_SIM_LAYOUT)
#define rt_restore(sim, in) rt_restore_checked((sim), (in), RT_SIM_LAYOUT)

#endif /* RT_SIM_H */
