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

/* ------------------------------------------------------------------ tolerances */

/* a DSS sample period (and any time the scene compiler turns into ticks) is a whole
   number of base ticks when it is within this fraction of the period of one */
#ifndef RT_TICK_MATCH_REL
#define RT_TICK_MATCH_REL 1e-6
#endif
/* torn loops (rt/loop.c): residual tolerance of the torn inputs when the scene gives
   none (scaled norm), and the pivot threshold of the inverse-Jacobian initialisation */
#ifndef RT_LOOP_STEP_FACTOR
#define RT_LOOP_STEP_FACTOR 1000 /* a solved loop's Newton correction, in its tolerances */
#endif
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

/* 1: a scene compiled by scenec carries the code written out for it (rt_scene_code,
   tools/scenec/spec.c); 0: its rt_scene.code is NULL and it runs the table-driven path
   (the same bits; make image IMAGE_CFLAGS=-DRT_SCENE_CODE=0 measures that one) */
#ifndef RT_SCENE_CODE
#define RT_SCENE_CODE 1
#endif

#ifndef RT_ERR_LEN
#define RT_ERR_LEN 128 /* characters of an init error description */
#endif

/* nodes of the graphs searched at init (output ports, blocks) */
#define RT_MAX_NODES (RT_MAX_Y > RT_MAX_BLOCKS ? RT_MAX_Y : RT_MAX_BLOCKS)

/* ---- integrators ---- */
#ifndef RT_MAX_STAGES
#define RT_MAX_STAGES 6 /* stage buffers: Runge-Kutta stages (Dormand-Prince: 6, its error
                           estimate reuses them); an implicit method's stages + 3 */
#endif

/* ---- multirate (rt/xset.c) ---- */
#define RT_HIST 3 /* communication points kept per cross-set signal (Hermite needs 3) */

/* ---- multibody (rt/mbs.c) ---- */
#ifndef RT_MBS_PIVOT_TOL
/* pivot threshold of the factorizations of M and W M^-1 W^T, relative to the largest
   entry (for W M^-1 W^T: to the row's own diagonal, never below this tolerance times the
   largest, rt/mbs_ldl.c): a well-posed chain of ten links has relative pivots near 1e-2,
   a redundant or straightened chain near the unit roundoff */
#define RT_MBS_PIVOT_TOL (RT_REAL_IS_FLOAT ? (real_t)1e-5 : (real_t)1e-10)
#endif
#ifndef RT_MBS_RES_TOL
/* largest |g| accepted after the two projection iterations; above it the step is counted
   as degraded (RT_CNT_DEGRADED) [m or 1] */
#define RT_MBS_RES_TOL (RT_REAL_IS_FLOAT ? (real_t)1e-4 : (real_t)1e-9)
#endif
#ifndef RT_INV_TOL
/* absolute tolerance of a kind's declared invariants that give none (rt_invariant.tol):
   a step may leave a concentration this far below 0, a conserved sum this far off */
#define RT_INV_TOL (RT_REAL_IS_FLOAT ? (real_t)1e-4 : (real_t)1e-8)
#endif
#ifndef RT_MBS_RANK_TOL
/* a constraint row dropped as dependent on others (rt/mbs_ldl.c) conflicts with them when
   what its right-hand side asks beyond theirs exceeds RT_MBS_RES_TOL plus this fraction
   of the largest right-hand side: two identical rods agree to the bit, two rods of
   different lengths from one anchor disagree by the difference */
#define RT_MBS_RANK_TOL (RT_REAL_IS_FLOAT ? (real_t)1e-4 : (real_t)1e-8)
#endif
#ifndef RT_INIT_TOL
/* the farthest rt_init moves a multibody node (or the unit vector of a quaternion) to put
   the initial state on its constraints; beyond it the set-up is refused as a mistake
   (RT_E_INCONSISTENT), below it the move is reported with the block (RT_CNT_INIT_MOVED)
   [m or 1] */
#define RT_INIT_TOL (RT_REAL_IS_FLOAT ? (real_t)1e-2 : (real_t)1e-3)
#endif
#ifndef RT_INIT_ROT_TOL
/* the largest rotation [rad] rt_init gives a multibody node's frame to put the initial
   state on its constraints; beyond it the set-up is refused (RT_E_INCONSISTENT), below it
   the turn is reported with the block (RT_CNT_INIT_MOVED). Not RT_INIT_TOL's number: a
   position error within that on a short lever turns a small body by more (0.5 mm at a
   node 1 cm from the centre of mass: 0.05 rad) */
#define RT_INIT_ROT_TOL (real_t)0.1
#endif
#ifndef RT_INIT_PROJ_MAX
/* projections rt_init may do to bring the initial state within RT_MBS_RES_TOL of its
   constraints (a step's projection does one: two position iterations) */
#define RT_INIT_PROJ_MAX 8
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
#ifndef RT_XSET_GAIN_EVERY
/* a set that extrapolates another measures its sensitivity to those inputs (two
   right-hand sides each) at every this many of its steps: what turns a missed prediction
   into an error of its state, compared with its accuracy (rti_xset_predict) */
#define RT_XSET_GAIN_EVERY 256
#endif
#ifndef RT_XSET_FRESH
/* and afresh before it judges a miss whose estimate from the last measurement exceeds
   this fraction of its accuracy */
#define RT_XSET_FRESH ((real_t)0.25)
#endif
#ifndef RT_XSET_NOGAIN
/* and afresh at every step while the last measurement found next to none: below this
   fraction of a strong coupling's (the input's whole range moving the scaled state by 1
   per step), where the miss would exceed RT_XSET_FRESH of the accuracy at a strong one.
   A sensitivity of 0 is no promise: an enable, a gain or a state of the reader can raise
   it at any step (a lag enabled 0.1 s in, after the measurement at its start, was 82 %
   off with status ok) */
#define RT_XSET_NOGAIN ((real_t)1e-6)
#endif
#ifndef RT_XSET_BIGMISS
/* and afresh at every RT_XSET_BIGMISS_EVERY-th step while the input's miss is above
   this fraction of its range: a sensitivity measured where the reader's response was
   weak (a rate that switches with the input's sign, measured on the weak side) is no
   promise once the input swings (a reader of a 2 Hz source at 100 ms, measured 0.001 at
   its start, was 23 % off with status ok). Not at every step: a coarse coupling's misses
   are that large at every step (lane_change's vehicles every 40 ms in the tick: two
   right-hand sides more a step, 7 % of the run) */
#define RT_XSET_BIGMISS ((real_t)0.01)
#endif
#ifndef RT_XSET_BIGMISS_EVERY
#define RT_XSET_BIGMISS_EVERY 4
#endif
#ifndef RT_XSET_FD
/* the input's difference for that sensitivity, relative to 1 + its range */
#define RT_XSET_FD (RT_REAL_IS_FLOAT ? (real_t)1e-3 : (real_t)1e-7)
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
/* the defaults of an implicit set's Newton iteration (RT_SET_CFG_LIST): iterations per
   stage, steps between Jacobian refreshes, and the residual tolerance: 1e-8 in double;
   single precision resolves about 1e-7 relative, so its default sits two digits above */
#ifndef RT_IMP_NEWTON_MAX
#define RT_IMP_NEWTON_MAX 4
#endif
#ifndef RT_IMP_JAC_EVERY
#define RT_IMP_JAC_EVERY 1
#endif
#ifndef RT_IMP_TOL
#define RT_IMP_TOL (RT_REAL_IS_FLOAT ? (real_t)1e-5 : (real_t)1e-8)
#endif
#ifndef RT_IMP_STALL
/* an implicit step whose first Newton correction moved the state by more than this times
   its residual tolerance but which ended within the tolerance of its start has stalled
   (its stage equations met a spurious solution, a cycle of the method: SDIRK2's two half
   steps on a relaxation jump); counted as degraded (integ_implicit.c) */
#define RT_IMP_STALL 100
#endif
#ifndef RT_W_SECANT
/* a ROS2 step on a kept Jacobian W checks W along its own first stage: the secant
   f(t + h, x0 + h k1) - f(t + h, x0) against W h k1. A mismatch above this fraction of
   W h k1 says W is not the Jacobian there (an input switched a stiffness off); once h
   times such misses, summed since the refresh and scaled as the estimate, moved the state
   by more than RT_W_DRIFT times the set's accuracy, the step is redone on a fresh one
   (integ_implicit.c) */
#define RT_W_SECANT ((real_t)0.5)
#endif
#ifndef RT_W_DRIFT
#define RT_W_DRIFT ((real_t)0.25)
#endif
#ifndef RT_HIDDEN_OSC_HL
/* an L-stable implicit step whose estimate its iteration matrix filtered within the
   accuracy, though the raw difference was not, takes the raw one when the difference
   holds a mode of |h lambda| above this that does not decay over the step (an undamped
   stiff oscillation the method wipes out; integ_implicit.c hidden_oscillation) */
#define RT_HIDDEN_OSC_HL 2
#endif
#ifndef RT_HIDDEN_OSC_RES
/* ... when the Krylov space that mode comes from is invariant to this fraction of |mu|
   (what M^-1 maps out of it): the mode is one of M's, not a point of its field of
   values */
#define RT_HIDDEN_OSC_RES 1e-3
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
#ifndef RT_LOOP_ITER_MAX
#define RT_LOOP_ITER_MAX 8 /* default Broyden iterations per loop evaluation */
#endif
#ifndef RT_LOOP_ITER_LIMIT
#define RT_LOOP_ITER_LIMIT 32 /* the most a scene may ask for */
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
#ifndef RT_TEV_PARTS_MAX
/* parts one set step may be split into at known time events strictly inside it (rt/tev.c):
   each part is a step of the set's method, so a step's work is at most this many times
   its bound (rt_step_bound); a scene needing more is refused at rt_init */
#define RT_TEV_PARTS_MAX 4
#endif

/* ------------------------------------------------------------------ the list of limits */

/* Every capacity limit, one row each, in the order `scenec --sizes` and `modrt sizes` print
 * them: L(NAME, field, least, default, what). The limit is RT_MAX_NAME; field: the member
 * of rt_sizes that measures it in a scene (rt_sizes_of); least: the smallest value a
 * per-scene build passes (0: the arrays it sizes may be left out); default: its value
 * unless the build passes -DRT_MAX_NAME=...; what: the things it counts, as its capacity
 * message names them (rt_limit_text). The preprocessor cannot write a #define, so the
 * defaults' #ifndef blocks are written from this list into rt_limits.h by
 * tests/static/limits.py --write (make test-static fails when they differ). Not in the
 * list: RT_MAX_STAGES (a property of the methods), RT_MAX_TICKS (of the tick counter) and
 * RT_MAX_NODES (derived). */
#define RT_LIMIT_LIST(L)                                                                    \
    /* totals over all blocks of one scene */                                               \
    L(BLOCKS, blocks, 1, 64, "blocks")                                                      \
    L(X, x, 1, 256, "continuous states")                                                    \
    L(D, d, 1, 64, "discrete states")                                                       \
    L(U, u, 1, 256, "block inputs")                                                         \
    L(Y, y, 1, 256, "block outputs")                                                        \
    L(P, p, 1, 512, "parameters")                                                           \
    L(ROOTS, roots, 1, 48, "state-event root functions (a when: one, a located switch: two)") \
    L(SETS, sets, 1, 4, "integration sets")                                                 \
    L(REC, recs, 1, 64, "recorded signals")                                                 \
    /* potential + actual algebraic loops reported */                                       \
    L(LOOPS, loops, 1, 8, "algebraic loops")                                                \
    /* torn inputs over all actual loops */                                                 \
    L(TORN, torn, 1, 16, "torn loop inputs")                                                \
    L(IMPLICIT_N, implicit_n, 1, 64, "states of a set with an implicit method")             \
    /* states of a set stepped by its transition matrix (method transition, a linear set): \
       its two n x n scratch matrices in rt_work */                                         \
    L(TRANSITION_N, transition_n, 0, 8, "states of a set with the transition method")       \
    /* outputs the cross-set history is indexed by: the highest output index another set   \
       reads, plus one (a scene of one set needs 1) */                                      \
    L(HIST_Y, hist_y, 1, RT_MAX_Y, "outputs read by another set")                           \
    /* outputs kept aside while a set stepping over several ticks steps, and its step's    \
       end outputs kept for its renewal when its state reaches the tick (rt/held.c): the   \
       highest output index of such a set, plus one. 0: no such set, neither array */       \
    L(HELD_Y, held_y, 0, RT_MAX_Y, "outputs of sets stepping over several ticks")           \
    /* recorded and link-exported multibody signals (energy, residual, reaction) of sets   \
       stepping over several ticks or in the background, held between their steps like    \
       outputs (rt/held.c). 0: the scene carries no such array */                           \
    L(HELD_SIG, held_sig, 0, RT_MAX_REC, "recorded and exported multibody signals of sets " \
                                         "stepping over several ticks")                     \
    /* states of the largest set with root functions: event location keeps the state at   \
       the right end of its bracket (rt/step.c; a scene without roots needs 1) */           \
    L(EVENT_X, event_x, 1, RT_MAX_X, "states of a set with roots")                          \
    /* evaluation sequence: at most one call per output port plus one per block */          \
    L(SEQ, seq, 1, (RT_MAX_Y + RT_MAX_BLOCKS), "entries of the evaluation sequence")        \
    /* entries of the histogram of loop solves by iterations taken: the scene's iteration  \
       bound plus one (a scene without actual loops needs 1) */                             \
    L(LOOP_HIST, loop_hist, 1, (RT_LOOP_ITER_LIMIT + 1), "entries of the loops' iteration " \
                                                         "histogram")                       \
    /* states plus outputs of the background set (rt/bg.c): the result of its step waits  \
       there for its deadline */                                                            \
    L(BG, bg, 1, 512, "states and outputs of a background set")                             \
    /* inputs a set extrapolates over its step from another set (rt/xpred.c): for each,    \
       what its scheme predicted for the end of the reader's step, checked against the     \
       source's value there, and the input's scale. 0: a scene with no such input */       \
    L(XPRED, xpred, 0, RT_MAX_U, "inputs extrapolated from another set")                    \
    /* sets holding a kind with known time events (rt/tev.c): where any, each set keeps    \
       the tick of its next instant (rt_state.tev_next) and a step part its midpoint       \
       (rt_work.t_piece). 0: a scene with none */                                           \
    L(TEV, tev, 0, RT_MAX_SETS, "sets with known time events")                              \
    /* bytes of a snapshot (rt_state.kstate) for the internal state of blocks whose kind   \
       keeps one outside x, d and p (rt_kind.save: an FMU's serialized FMU state), 4 bytes \
       of size per such block included (rt/snapshot.c); rt_snapshot returns RT_E_CAPACITY \
       beyond it. A per-scene build passes what its kinds report after rt_init */          \
    L(KSTATE, kstate, 0, 16384, "bytes of the blocks' internal state in a snapshot")       \
    /* multibody (rt/mbs.c): per set, per block, and the exact per-scene sizes of the      \
       multibody tables (totals over every set), whose defaults hold any scene within the  \
       per-set limits */                                                                    \
    L(JOINTS, joints, 1, 32, "joints")                                                      \
    L(MBS_Z, mbs_z, 1, 64, "generalized velocities of a multibody set")                     \
    L(MBS_Q, mbs_q, 1, 80, "generalized coordinates of a multibody set")                    \
    /* constraints (internal + joints) of one set */                                        \
    L(MBS_C, mbs_c, 1, 40, "constraints of a multibody set")                                \
    /* generalized velocities of one MBS block (node Jacobians, M) */                       \
    L(MBS_BZ, mbs_bz, 1, 16, "generalized velocities of a multibody block")                 \
    L(MBS_ROWS, mbs_rows, 1, (RT_MAX_MBS_C * RT_MAX_SETS), "constraint rows of all sets")   \
    /* each row touches one or two blocks */                                                \
    L(MBS_TOUCH, mbs_touch, 1, (2 * RT_MAX_MBS_ROWS),                                       \
      "(block, constraint row) pairs that can be non-zero in W")                            \
    /* entries of W and of Y = M^-1 W^T kept: the velocities of the block of every touch */ \
    L(MBS_TW, mbs_tw, 1, (RT_MAX_MBS_C * RT_MAX_MBS_Z), "entries of W kept")                \
    /* coordinates of one set's MBS blocks whose K depends on q or that have a kinb (the   \
       projection's predicted coordinates) */                                               \
    L(MBS_QT, mbs_qt, 1, RT_MAX_MBS_Q, "coordinates with a q-dependent K or a kinb")        \
    /* as RT_MAX_MBS_TW over the blocks with a dense M (a diagonal M divides where Y is    \
       needed) */                                                                           \
    L(MBS_TY, mbs_ty, 1, RT_MAX_MBS_TW, "entries of M^-1 W^T kept")                         \
    /* t (t + 1) / 2 for a block touching t rows, summed over the blocks */                 \
    L(MBS_PAIRS, mbs_pairs, 1, (RT_MAX_MBS_C * (RT_MAX_MBS_C + 1) / 2),                     \
      "entries of W M^-1 W^T that blocks contribute")                                       \
    /* the sparse factors of A = W M^-1 W^T, fill included, all sets */                     \
    L(MBS_LNZ, mbs_lnz, 1, (RT_MAX_MBS_C > 1 ? RT_MAX_MBS_C * (RT_MAX_MBS_C - 1) / 2 : 1), \
      "off-diagonal non-zeros of the LDL^T factors")                                        \
    /* nz for a diagonal M, nz (nz + 1) otherwise (its LU factors and row pivots) */        \
    L(MBS_M, mbs_m, 1, (RT_MAX_MBS_Z * (RT_MAX_MBS_BZ + 1)),                                \
      "entries of the mass matrices' factors")                                              \
    /* their multipliers are kept for recorded reactions */                                 \
    L(MBS_JROWS, mbs_jrows, 1, (RT_MAX_JOINTS * 6), "rows of the joints' constraints")      \
    /* any kind but those flagged RT_MBS_NODE_POINT */                                      \
    L(MBS_JZ, mbs_jz, 1, RT_MAX_MBS_BZ, "velocities of a block whose nodes have Jacobians")

#include "rt_limits.h"

/* rt_limits.h is the list's: RT_MAX_NAME of a row it lacks is undeclared here */
#define RT_X_HAS_VALUE(name, field, least, dflt, what)                                      \
    typedef char rt_limit_##name[RT_MAX_##name >= 0 ? 1 : -1];
RT_LIMIT_LIST(RT_X_HAS_VALUE)
#undef RT_X_HAS_VALUE

#if RT_MAX_BLOCKS > 65535 || RT_MAX_Y > 65535 || RT_MAX_U > 65535 || RT_MAX_X > 65535
#error "modrt indexes blocks, states and ports with 16-bit integers: keep every RT_MAX_* below 65536."
#endif
#if RT_MAX_STAGES < 6
#error "RT_MAX_STAGES must be at least 6: the fifth-order Dormand-Prince method has six stages."
#endif
#if RT_HIST > 7
#error "state.hist_ev keeps a bit per history interval below its step bit (0x80): RT_HIST at most 7."
#endif
#if RT_MAX_SETS > 32
#error "rt_tick keeps a bit per set in a 32-bit word (its renewals): RT_MAX_SETS at most 32."
#endif

#endif /* RT_CONFIG_H */
