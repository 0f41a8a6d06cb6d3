/* rt_config.h - compile-time configuration of modrt: the scalar type and every capacity limit.
 *
 * Every limit is a named constant with a default that a build may override with -D
 * (a per-scene build passes the exact sizes of its scene; test builds shrink them to
 * reach edge cases). The runtime checks a scene against these limits at init and
 * returns RT_E_CAPACITY naming the limit; it never writes past a static array. */
#ifndef RT_CONFIG_H
#define RT_CONFIG_H

/* scalar type: double by default, float with -DRT_REAL_FLOAT (make REAL=float) */
#ifdef RT_REAL_FLOAT
typedef float real_t;
#define RT_EPS 1.1920929e-07f /* unit roundoff of real_t */
#define RT_REAL_IS_FLOAT 1
#else
typedef double real_t;
#define RT_EPS 2.220446049250313e-16 /* unit roundoff of real_t */
#define RT_REAL_IS_FLOAT 0
#endif

/* ---- scene size limits (totals over all blocks of one scene) ---- */
#ifndef RT_MAX_BLOCKS
#define RT_MAX_BLOCKS 64 /* block instances */
#endif
#ifndef RT_MAX_X
#define RT_MAX_X 256 /* continuous states */
#endif
#ifndef RT_MAX_D
#define RT_MAX_D 64 /* discrete states */
#endif
#ifndef RT_MAX_U
#define RT_MAX_U 256 /* block inputs */
#endif
#ifndef RT_MAX_Y
#define RT_MAX_Y 256 /* block outputs */
#endif
#ifndef RT_MAX_P
#define RT_MAX_P 512 /* parameters */
#endif
#ifndef RT_MAX_ROOTS
#define RT_MAX_ROOTS 16 /* state-event root functions */
#endif
#ifndef RT_MAX_SETS
#define RT_MAX_SETS 4 /* integration sets */
#endif
#ifndef RT_MAX_REC
#define RT_MAX_REC 64 /* recorded signals */
#endif
#ifndef RT_MAX_LOOPS
#define RT_MAX_LOOPS 8 /* potential + actual algebraic loops reported */
#endif

/* ------------------------------------------------------------------ tolerances */

/* a DSS sample period (and any time the scene compiler turns into ticks) is a whole
   number of base ticks when it is within this fraction of the period of one */
#ifndef RT_TICK_MATCH_REL
#define RT_TICK_MATCH_REL 1e-6
#endif
/* torn loops (rt/loop.c): residual tolerance of the torn inputs when the scene gives
   none (scaled norm), and the pivot threshold of the inverse-Jacobian initialisation */
#ifndef RT_LOOP_TOL
#define RT_LOOP_TOL (RT_REAL_IS_FLOAT ? 1e-5 : 1e-10)
#endif
#ifndef RT_LOOP_PIVOT_TOL
#define RT_LOOP_PIVOT_TOL (RT_REAL_IS_FLOAT ? 1e-6 : 1e-13)
#endif

/* 1: kinds carry their reference text (RT_DOC in rt.h) for `modrt info KIND`; embedded
   images build with 0 and keep no such strings in flash */
#ifndef RT_KIND_DOCS
#define RT_KIND_DOCS 1
#endif

#ifndef RT_ERR_LEN
#define RT_ERR_LEN 128 /* characters of an init error description */
#endif

/* nodes of the graphs searched at init (output ports, blocks) */
#define RT_MAX_NODES (RT_MAX_Y > RT_MAX_BLOCKS ? RT_MAX_Y : RT_MAX_BLOCKS)

/* evaluation sequence: at most one call per output port plus one per block (a per-scene
   build passes its scene's exact length) */
#ifndef RT_MAX_SEQ
#define RT_MAX_SEQ (RT_MAX_Y + RT_MAX_BLOCKS)
#endif

/* ---- integrators ---- */
#ifndef RT_MAX_STAGES
#define RT_MAX_STAGES 6 /* stage buffers: Runge-Kutta stages (Dormand-Prince: 6, its error
                           estimate reuses them); an implicit method's stages + 3 */
#endif

/* ---- multirate (rt/xset.c) ---- */
#define RT_HIST 3 /* communication points kept per cross-set signal (Hermite needs 3) */
#ifndef RT_MAX_HIST_Y
/* outputs the cross-set history is indexed by: the highest output index another set
   reads, plus one (a scene of one set needs 1) */
#define RT_MAX_HIST_Y RT_MAX_Y
#endif

#ifndef RT_MAX_XPRED
/* inputs a set extrapolates over its step from another set (rt/xset.c, rti_xset_predict):
   for each, what its scheme predicted for the end of the reader's step, checked against
   the source's value there, and the input's scale. A per-scene build may set 0 (a scene
   with no such input; rt_init refuses one that has some) */
#define RT_MAX_XPRED RT_MAX_U
#endif

#ifndef RT_MAX_HELD_SIG
/* recorded and link-exported multibody signals (energy, residual, reaction) of sets
   stepping over several ticks or in the background, held between their steps like
   outputs (rt/sim.c). A per-scene build may set 0: the scene then carries no such array */
#define RT_MAX_HELD_SIG RT_MAX_REC
#endif

#ifndef RT_MAX_HELD_Y
/* outputs kept aside while a set stepping over several ticks steps, and its step's end
   outputs kept for its renewal when its state reaches the tick (rt/sim.c): the highest
   output index of such a set, plus one. A per-scene build may set 0 (no such set): the
   scene then carries neither array */
#define RT_MAX_HELD_Y RT_MAX_Y
#endif

/* ---- state events (rt/step.c) ---- */
#ifndef RT_MAX_EVENT_X
/* states of the largest set with root functions: event location keeps the state at the
   right end of its bracket (a scene without roots needs 1) */
#define RT_MAX_EVENT_X RT_MAX_X
#endif

/* ---- background sets (rt/bg.c) ---- */
#ifndef RT_MAX_BG
/* states plus outputs of the background set (rt/bg.c): the result of its step waits
   there for its deadline */
#define RT_MAX_BG 512
#endif

/* ---- multibody (rt/mbs.c) ---- */
#ifndef RT_MAX_MBS_Z
#define RT_MAX_MBS_Z 64 /* generalized velocities of the MBS blocks of one set */
#endif
#ifndef RT_MAX_MBS_Q
#define RT_MAX_MBS_Q 80 /* generalized coordinates of the MBS blocks of one set */
#endif
#ifndef RT_MAX_MBS_C
#define RT_MAX_MBS_C 40 /* constraints (internal + joints) of one set */
#endif
#ifndef RT_MAX_JOINTS
#define RT_MAX_JOINTS 32 /* joints of a scene */
#endif
#ifndef RT_MAX_MBS_BZ
#define RT_MAX_MBS_BZ 16 /* generalized velocities of one MBS block (node Jacobians, M) */
#endif
/* exact per-scene sizes of the multibody tables (totals over every set; `modrt sizes`
   prints them): the defaults hold any scene within the per-set limits above */
#ifndef RT_MAX_MBS_ROWS
#define RT_MAX_MBS_ROWS (RT_MAX_MBS_C * RT_MAX_SETS) /* constraint rows of all sets */
#endif
#ifndef RT_MAX_MBS_TOUCH
/* (block, row) pairs that can be non-zero in W: each row touches one or two blocks */
#define RT_MAX_MBS_TOUCH (2 * RT_MAX_MBS_ROWS)
#endif
#ifndef RT_MAX_MBS_TW
/* entries of W and of Y = M^-1 W^T kept: the velocities of the block of every touch */
#define RT_MAX_MBS_TW (RT_MAX_MBS_C * RT_MAX_MBS_Z)
#endif
#ifndef RT_MAX_MBS_QT
/* coordinates of one set's MBS blocks whose K depends on q or that have a kinb (the
   projection's predicted coordinates) */
#define RT_MAX_MBS_QT RT_MAX_MBS_Q
#endif
#ifndef RT_MAX_MBS_TY
/* entries of Y = M^-1 W^T kept: as RT_MAX_MBS_TW over the blocks with a dense M (a
   diagonal M divides where Y is needed) */
#define RT_MAX_MBS_TY RT_MAX_MBS_TW
#endif
#ifndef RT_MAX_MBS_PAIRS
/* entries of A = W M^-1 W^T that blocks contribute: t (t + 1) / 2 for a block touching
   t rows, summed over the blocks */
#define RT_MAX_MBS_PAIRS (RT_MAX_MBS_C * (RT_MAX_MBS_C + 1) / 2)
#endif
#ifndef RT_MAX_MBS_LNZ
/* off-diagonal non-zeros of the sparse LDL^T factors of A (fill included), all sets */
#define RT_MAX_MBS_LNZ (RT_MAX_MBS_C > 1 ? RT_MAX_MBS_C * (RT_MAX_MBS_C - 1) / 2 : 1)
#endif
#ifndef RT_MAX_MBS_M
/* entries of the mass matrices of all MBS blocks: nz for a diagonal M, nz (nz + 1)
   otherwise (its LU factors and row pivots) */
#define RT_MAX_MBS_M (RT_MAX_MBS_Z * (RT_MAX_MBS_BZ + 1))
#endif
#ifndef RT_MAX_MBS_JZ
/* velocities of the largest MBS block whose nodes have Jacobians to map (any kind but
   those flagged RT_MBS_NODE_POINT) */
#define RT_MAX_MBS_JZ RT_MAX_MBS_BZ
#endif
#ifndef RT_MAX_MBS_JROWS
/* constraint rows of all joints (their multipliers are kept for recorded reactions) */
#define RT_MAX_MBS_JROWS (RT_MAX_JOINTS * 6)
#endif
#ifndef RT_MBS_PIVOT_TOL
/* pivot threshold of the factorizations of M and W M^-1 W^T, relative to the largest
   entry: a well-posed chain of ten links has relative pivots near 1e-2, a redundant or
   straightened chain near the unit roundoff */
#define RT_MBS_PIVOT_TOL (RT_REAL_IS_FLOAT ? (real_t)1e-5 : (real_t)1e-10)
#endif
#ifndef RT_MBS_RES_TOL
/* largest |g| accepted after the two projection iterations; above it the step is counted
   as degraded (RT_CNT_DEGRADED) [m or 1] */
#define RT_MBS_RES_TOL (RT_REAL_IS_FLOAT ? (real_t)1e-4 : (real_t)1e-9)
#endif
#ifndef RT_MBS_LEN_MIN
/* a spherical difference joint whose nodes are closer than this has no direction;
   its direction falls back to +x deterministically [m] */
#define RT_MBS_LEN_MIN (RT_REAL_IS_FLOAT ? (real_t)1e-15 : (real_t)1e-100)
#endif

/* ---- implicit integrators and algebraic loops ---- */
#ifndef RT_MAX_TICKS
/* the longest run in base ticks: t = tick * dt stays exact in the tick count */
#define RT_MAX_TICKS ((uint64_t)1 << 53)
#endif
#ifndef RT_TICK_SLACK
/* end time / base tick may differ from a whole number by this much relative rounding
   (at most a quarter tick); more is an error, not a silent rounding */
#define RT_TICK_SLACK (16 * RT_EPS)
#endif
#ifndef RT_ERR_TOL
/* the local error a step may show by its method's embedded estimate, scaled norm
   max_i |e_i| / (1 + |x_i|), unless the set says `accuracy (...)`; a step above it is
   counted (errest) and the status says so: it reports, the fixed schedule never changes */
#define RT_ERR_TOL (RT_REAL_IS_FLOAT ? (real_t)1e-2 : (real_t)1e-3)
#endif
#ifndef RT_XSET_LOST
/* an input a set extrapolates over its step from another set, off at the step's end by
   more than this times 1 + the largest |u| it has had (rti_xset_predict): the set
   integrated an input with no correct digit of the signal's range, a coupling past its
   stability limit. Counted as errest, status failed. A bound, not an accuracy: a sound
   coupling stays far below (pendulum10_actuated: 0.008 as shipped, 0.07 to 0.08 with its
   chain at 16 ms; 2.6 to 47 at 32 ms, where it is 0.13 to 0.19 m off or diverges,
   docs/multirate.md) */
#define RT_XSET_LOST ((real_t)1)
#endif
#ifndef RT_ERR_LOST
/* a step whose estimate exceeds this (an error as large as the state's scale 1 + |x|)
   has no correct digit: counted as errest too, but the status is failed, not doubtful */
#define RT_ERR_LOST ((real_t)1)
#endif
#ifndef RT_GROWTH_FACTOR
/* a set whose state norm max(1, |x|) grows by more than this factor in each of
   RT_GROWTH_STEPS consecutive steps is unstable (counted: unstable), long before it
   overflows; a stable method on a well-posed model never grows that fast at its step */
#define RT_GROWTH_FACTOR 4
#endif
#ifndef RT_GROWTH_STEPS
#define RT_GROWTH_STEPS 3
#endif
#ifndef RT_IMP_SUBSTEPS
/* a failing implicit step is retried with a Jacobian at its iterate, then split into
   2, 4, ... up to this many substeps (a power of two); worst-case work of one step is
   then 2 + (2 + 4 + ... + RT_IMP_SUBSTEPS) = 2 RT_IMP_SUBSTEPS step-equivalents */
#define RT_IMP_SUBSTEPS 8
#endif
#ifndef RT_MAX_IMPLICIT_N
#define RT_MAX_IMPLICIT_N 64 /* states of a set integrated by an implicit method */
#endif
#ifndef RT_MAX_TRANSITION_N
/* states of a set stepped by its transition matrix (method transition, a linear set):
   its two n x n scratch matrices in rt_work */
#define RT_MAX_TRANSITION_N 8
#endif
#ifndef RT_TRANSITION_THETA
/* the transition method's phi functions: h J is halved until its 1-norm is at most this,
   a Taylor polynomial of degree RT_TRANSITION_TAYLOR is summed there (truncation
   theta^13 / 15! = 9e-17) and doubled back (integ_transition.c) */
#define RT_TRANSITION_THETA ((real_t)0.5)
#endif
#ifndef RT_TRANSITION_TAYLOR
#define RT_TRANSITION_TAYLOR 12 /* degree of that Taylor polynomial of phi2 */
#endif
#ifndef RT_TRANSITION_INC
/* the transition method's Jacobian comes from differences over increments of this times
   max(1, |x_j|): large, since f is linear (no truncation error), so that the rounding of
   f (about eps |f|) is small against the change */
#define RT_TRANSITION_INC ((real_t)1024)
#endif
#ifndef RT_TRANSITION_HALVINGS
/* the most halvings: a set with |h J|_1 above theta 2^this is refused at its first step
   (singular), which bounds the refresh's work */
#define RT_TRANSITION_HALVINGS 40
#endif
#ifndef RT_MAX_TORN
#define RT_MAX_TORN 16 /* torn inputs over all actual loops */
#endif
#ifndef RT_LOOP_ITER_MAX
#define RT_LOOP_ITER_MAX 8 /* default Broyden iterations per loop evaluation */
#endif
#ifndef RT_LOOP_ITER_LIMIT
#define RT_LOOP_ITER_LIMIT 32 /* the most a scene may ask for */
#endif
#ifndef RT_MAX_LOOP_HIST
/* entries of the histogram of loop solves by iterations taken: the scene's iteration
   bound plus one (a scene without actual loops needs 1) */
#define RT_MAX_LOOP_HIST (RT_LOOP_ITER_LIMIT + 1)
#endif

/* ---- state events ---- */
#ifndef RT_EVENT_ITER_MAX
#define RT_EVENT_ITER_MAX 48 /* re-steps to locate one root (Illinois) */
#endif
#ifndef RT_EVENTS_PER_STEP_MAX
#define RT_EVENTS_PER_STEP_MAX 4 /* events handled within one set step */
#endif
#ifndef RT_EVENT_TTOL
/* width of the final event bracket, relative to the step: 1e-12 of a 1 ms step is 1 fs,
   far below any model's time scale, yet reached in a few Illinois iterations */
#define RT_EVENT_TTOL (RT_REAL_IS_FLOAT ? (real_t)1e-6 : (real_t)1e-12)
#endif
#ifndef RT_EVENT_PROBE
/* after a handler leaves its root on the far side of the crossing, the root's motion is
   measured over this fraction of the step (one Euler step of the set, rt/step.c): about
   the cube root of the unit roundoff, so the change is well above rounding while the
   curvature of the trajectory over it stays below the first-order change */
#define RT_EVENT_PROBE (RT_REAL_IS_FLOAT ? (real_t)3.90625e-3 : (real_t)7.62939453125e-6)
#endif
#ifndef RT_EVENT_MARGIN
/* a root a handler sent back toward its side fires again when it comes back this
   fraction of its probed motion beyond the point it was handled at (in time, this
   fraction of RT_EVENT_PROBE of the step: 7e-12 s at 1 ms in double): below any physical
   scale, above the rounding of a root such as z - zt(t) near that point unless the root
   moves slower than about 3e-5 of its terms per second */
#define RT_EVENT_MARGIN (RT_REAL_IS_FLOAT ? (real_t)0.0625 : (real_t)9.765625e-4)
#endif

#if RT_MAX_BLOCKS > 65535 || RT_MAX_Y > 65535 || RT_MAX_U > 65535 || RT_MAX_X > 65535
#error "modrt indexes blocks, states and ports with 16-bit integers: keep every RT_MAX_* below 65536."
#endif
#if RT_MAX_STAGES < 6
#error "RT_MAX_STAGES must be at least 6: the fifth-order Dormand-Prince method has six stages."
#endif
#if RT_MAX_SETS > 32
#error "rt_tick keeps a bit per set in a 32-bit word (its renewals): RT_MAX_SETS at most 32."
#endif

#endif /* RT_CONFIG_H */
