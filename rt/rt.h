/* rt.h - the public API of the modrt runtime: block kinds, scenes, the simulator state,
 * status codes and the functions that initialise and tick a scene.
 *
 * Model (const, fits in flash): rt_kind (what a block computes), rt_scene (which blocks,
 * how they are wired, which sets integrate them). State (mutable, RAM): rt_sim, one per
 * running scene, owned by the caller. Every step-path function takes (model, state, ...)
 * in that order. Nothing here allocates; nothing here aborts. */
#ifndef RT_H
#define RT_H

#include <stddef.h>
#include <stdint.h>

#include "rt_config.h"
#include "rt_math.h"
#include "rt_mbs.h"

/* ------------------------------------------------------------------ status codes */

/* Declared once; expanded into the enum and the tables of rt_status_name and
 * rt_status_severity. Severity: 0 ok; 1 the answer was computed but may be inaccurate
 * (doubtful); 2 the answer is wrong or incomplete (failed); 3 the run could not start.
 * A run reports the most severe status it met (the first of equal ones). */
#define RT_STATUS_LIST(X)                                                        \
    X(RT_OK, 0, "ok")                                                            \
    X(RT_E_ARG, 3, "bad argument")                                               \
    X(RT_E_SCENE, 3, "malformed scene")                                          \
    X(RT_E_CAPACITY, 3, "scene exceeds a compile-time limit")                    \
    X(RT_E_UNCONNECTED, 3, "input is not connected and has no default value")    \
    X(RT_E_LOOP, 3, "algebraic loop that cannot be solved")                      \
    X(RT_E_PARAM, 3, "parameter out of range")                                   \
    X(RT_E_INCONSISTENT, 3, "initial state inconsistent: conflicting constraints, or too far off them (RT_INIT_TOL, RT_INIT_ROT_TOL)") \
    X(RT_E_SNAPSHOT, 3, "a block's internal state cannot be saved or restored (rt_snapshot, rt_restore)") \
    X(RT_E_NAN, 2, "non-finite value")                                           \
    X(RT_E_NOCONV, 2, "algebraic loop iteration did not converge")               \
    X(RT_E_DEGRADED, 2, "step accepted with its residual above tolerance (degraded)") \
    X(RT_E_SINGULAR, 2, "singular or near-singular matrix")                      \
    X(RT_E_EVENT, 2, "too many state events in one step")                        \
    X(RT_E_TEV, 2, "more time events in one step than RT_TEV_PARTS_MAX parts")  \
    X(RT_E_NOLOC, 2, "state event not located within its bound")                 \
    X(RT_E_INVARIANT, 2, "an invariant broken: a kind's declared invariant, a guard root crossed without a located event, or joints drifted past the set's accuracy unprojected") \
    X(RT_E_UNSTABLE, 2, "numerically unstable: the state grows without bound")   \
    X(RT_E_LINK, 2, "controller link lost (an import with policy stop)")         \
    X(RT_E_LINK_FAULT, 2, "controller link faults: bad datagrams or missing answers (link_bad, link_missing)") \
    X(RT_E_STOPPED, 2, "run stopped at a missed deadline (--overrun stop)")       \
    X(RT_E_ACCURACY, 1, "local error estimate above the set's accuracy")         \
    X(RT_E_LOST, 2, "local error estimate above RT_ERR_LOST: no correct digit left") \
    X(RT_E_COUPLING, 2, "input extrapolated from another set with no correct digit (above RT_XSET_LOST)") \
    X(RT_E_OVERRUN, 1, "tick deadline overrun")                                  \
    X(RT_E_DAMPED, 1, "an implicit step damped a mode that grows faster than its step resolves (damped)") \
    X(RT_E_DONE, 0, "end time reached")

typedef enum {
#define RT_X_ENUM(id, sev, text) id,
    RT_STATUS_LIST(RT_X_ENUM)
#undef RT_X_ENUM
    RT_STATUS_COUNT
} rt_status;

/* Fault counters bumped inside a tick (a tick never stops half-way; it counts, degrades
 * deterministically and remembers the last offending block). */
#define RT_COUNTER_LIST(X)                                                       \
    X(RT_CNT_NAN, "nan", "non-finite output, derivative or state")               \
    X(RT_CNT_EVENT_LIMIT, "event_limit", "events beyond RT_EVENTS_PER_STEP_MAX") \
    X(RT_CNT_TEV_LIMIT, "tev_limit", "time events known at run time beyond RT_TEV_PARTS_MAX parts of one step, handled at the step's end") \
    X(RT_CNT_EVENT_NOLOC, "event_noloc", "root not located within the bound")    \
    X(RT_CNT_NOCONV, "noconv", "iteration not converged within its bound")       \
    X(RT_CNT_SINGULAR, "singular", "singular matrix met")                        \
    X(RT_CNT_DEGRADED, "degraded", "step accepted with residual above tolerance")\
    X(RT_CNT_SUBSTEP, "substep", "implicit step that converged only in substeps") \
    X(RT_CNT_ERREST, "errest", "step whose local error estimate exceeds the set's accuracy (or an input it extrapolated from another set lost every digit)") \
    X(RT_CNT_INVARIANT, "invariant", "step ending with a kind's declared invariant broken (a negative concentration, a conserved sum lost), or further below a guard root (a floor) without a located crossing: the model tunnels; or a multibody set without projection whose constraints drifted past its accuracy") \
    X(RT_CNT_UNSTABLE, "unstable", "state growing without bound step after step (explicit method past its stability limit)") \
    X(RT_CNT_REDUNDANT, "redundant", "constraint rows found dependent on others and consistent with them: solved with their multipliers zero (counted when a set's rank deficit changes)") \
    X(RT_CNT_INIT_MOVED, "init_moved", "rt_init moved an initial multibody state onto its constraints or normalized its quaternion (rt_error_text says by how much), or a parameter set during the run put a multibody set off its constraints past RT_INIT_TOL (its next projection moves it back at once)") \
    X(RT_CNT_OVERRUN, "overrun", "tick finished after its deadline")             \
    X(RT_CNT_EVENTS, "events", "state events handled")                          \
    X(RT_CNT_DAMPED, "damped", "implicit step whose iteration matrix I - h gamma J has a negative determinant: a mode growing by more than e^(1/gamma) per step, which the method turns into one that does not (a step below the pole leaves the mode to the error estimate)")

typedef enum {
#define RT_X_ENUM(id, key, text) id,
    RT_COUNTER_LIST(RT_X_ENUM)
#undef RT_X_ENUM
    RT_CNT_COUNT
} rt_counter;

/* Returns the constant text of a status code ("?" for a value out of range). */
const char *rt_status_name(rt_status s);
/* 0 ok, 1 doubtful, 2 failed, 3 could not start (RT_STATUS_LIST) */
int rt_status_severity(rt_status s);
/* Returns the short key of a counter, as printed in run summaries ("?" if out of range). */
const char *rt_counter_key(rt_counter c);

/* ------------------------------------------------------------------ block kinds */

/* The paper's classification (section 2); declared once, expanded into the enum and
 * the names `modrt info` and docs/blocks.md print (rt_kind_type_name). */
#define RT_KIND_TYPE_LIST(X)                                                     \
    X(RT_KIND_OUTPUT, "output") /* y = g(u,p,t)                           eq. (1) */ \
    X(RT_KIND_NSS, "nss")       /* x' = f(x,u,p,t), y = g(x,u,p,t)        eq. (3) */ \
    X(RT_KIND_LSS, "lss")       /* x' = A x + B u, y = C x + D u          eq. (4) */ \
    X(RT_KIND_DSS, "dss")       /* x[k+1] = f(x[k],u[k],p), y held over k  eq. (5) */ \
    X(RT_KIND_MBS, "mbs")       /* q' = K z + b, M z' = k - (GK)^T lambda  eq. (6) */

typedef enum {
#define RT_X_ENUM(id, name) id,
    RT_KIND_TYPE_LIST(RT_X_ENUM)
#undef RT_X_ENUM
    RT_KIND_TYPE_COUNT
} rt_kind_type;
/* Returns the short name of a kind type ("?" if out of range). */
const char *rt_kind_type_name(rt_kind_type t);

/* How a kind's outputs depend directly on its inputs (its throughputs). */
typedef enum {
    RT_FEED_NONE = 0, /* no output depends directly on an input */
    RT_FEED_ALL,      /* every output depends on every input */
    RT_FEED_TABLE     /* rt_kind.feed[i*nu + j] != 0: output i depends on input j */
} rt_feed;

/* Everything a block function reads, for one evaluation. */
typedef struct rt_args {
    real_t t;          /* time [s] */
    real_t h;          /* step of the call: set step for derivatives, sample period for DSS [s] */
    const real_t *x;   /* continuous state, nx values */
    const real_t *d;   /* discrete state, nd values */
    const real_t *u;   /* inputs, nu values */
    const real_t *p;   /* parameters, np values */
    const void *spec;  /* the kind's type-specific const data (rt_kind.spec) */
    /* a time strictly between the known time events (rt_kind.next_event) on either side
       of this evaluation [s]: the midpoint of the step part being integrated, or half a
       base tick after t at a tick (t itself for a kind with time_event, whose next
       instant may lie closer: t_piece == t says "at t itself", rt_x_at). A kind whose
       outputs switch at its instants picks its piece by t_piece, never by t: the step
       ending at an instant then sees the left limit at its end (t == the instant), the
       step starting there the right limit, and rounding of t near an instant cannot pick
       the wrong side (rt/tev.c). Given to the output, derivative and roots of a kind
       with rt_kind.next_event; t elsewhere */
    real_t t_piece;
} rt_args;

/* what rt_kind.next_event returns when no known time event follows */
#define RT_TEV_NEVER ((real_t)1e30)

/* the rt_kind.time_event of a kind whose run-time instants serve nothing but end step
   parts (a defined system's comparisons of t, tools/scenec): the runtime never calls it
   (rt/tev.c), and the kind's set reads other sets' histories as a set without services
   does (rt/xset.c) */
void rt_tev_none(const rt_args *a, real_t *x, real_t *d);

/* do times a and b [s] name one instant: equal to the rounding a time on the base tick
   grid carries (RT_TICK_SLACK relative; 3 * 0.1 is the instant 0.3). A defined system's
   next instant is never such a neighbour of t (rt_x_next), and a step part never ends
   that close before its step's end (rt/tev.c) */
static inline int rt_same_instant(real_t a, real_t b)
{
    real_t m = rt_fabs(a) > rt_fabs(b) ? rt_fabs(a) : rt_fabs(b);
    return rt_fabs(a - b) <= (real_t)RT_TICK_SLACK * m;
}

/* What a kind knows of its continuous state and declares (rt_kind.inv), checked after
 * every step of its set (rt/invariant.c); a violation beyond the tolerance is counted
 * (RT_CNT_INVARIANT, the block) and fails the run (RT_E_INVARIANT): an answer with
 * negative concentrations is wrong whatever the error estimate says. Declared once:
 * X(ENUM, name, meaning). */
#define RT_INV_LIST(X)                                                                     \
    X(RT_INV_NONNEG, "nonnegative", "each state >= -tol (concentrations, masses)")         \
    X(RT_INV_SUM, "sum", "|sum of the states - c| <= tol (a conserved total)")             \
    X(RT_INV_NORM, "norm", "Euclidean norm of the states <= c + tol (a bounded norm)")
typedef enum {
#define RT_X_ENUM(id, name, text) id,
    RT_INV_LIST(RT_X_ENUM)
#undef RT_X_ENUM
    RT_INV_COUNT
} rt_inv_type;

typedef struct rt_invariant {
    uint8_t type;               /* rt_inv_type */
    uint8_t n;                  /* states it reads */
    const uint16_t *x;          /* their indices within the block's x (n values) */
    real_t c;                   /* the conserved sum, or the bound of the norm */
    real_t tol;                 /* absolute tolerance [the states' unit]; 0: RT_INV_TOL */
} rt_invariant;

/* A block kind: sizes, names and services, like the paper's system_descr (Fig. 3).
 * Every slot may be NULL where the comment says so; the runtime checks the rest at init. */
typedef struct rt_kind {
    const char *name;       /* type identifier, e.g. "oscillator" */
    rt_kind_type type;      /* classification */
    uint16_t nu, ny;        /* inputs, outputs */
    uint16_t nx, nd;        /* continuous states, discrete states */
    uint16_t np, nr;        /* parameters, root functions */
    const char *const *u_names; /* nu names (NULL only if nu == 0) */
    const char *const *y_names; /* ny names */
    const char *const *x_names; /* nx names */
    const char *const *d_names; /* nd names */
    const char *const *p_names; /* np names */
    const real_t *p_default;    /* np default parameters; NULL: all zero */
    const real_t *x_default;    /* nx default initial states; NULL: all zero */
    const real_t *d_default;    /* nd default initial discrete states; NULL: all zero */
    rt_feed feed;               /* throughput class */
    uint8_t autonomous;         /* 1: none of the services a right-hand side calls reads
                                   a->t (output, output_lean, deriv, an MBS kind's spec;
                                   an event handler may): its equations do not depend on
                                   time explicitly, which spares ROS2 its f_t evaluation
                                   in a set whose inputs hold over the step (rt/eval.c).
                                   0, the default: they may */
    uint8_t linear;             /* 1: output and deriv are affine in x and u,
                                   x' = A x + B u + c(t), y = C x + D u + e(t), with A,
                                   B, C, D functions of the parameters alone (a source
                                   of t, c and e only): a set of such blocks is linear
                                   in its state and may be stepped by its transition
                                   matrix (method transition, rt/integ_transition.c).
                                   0, the default: they may not */
    const uint8_t *feed_table;  /* ny*nu row-major, only for RT_FEED_TABLE */
    const int8_t *root_dir;     /* nr crossing directions: -1 falling, +1 rising, 0 both;
                                   NULL: both */
    const uint8_t *root_guard;  /* nr flags, 1: the root is a one-sided constraint (a
                                   floor) that must stay >= 0 except across a located
                                   crossing; a step ending further below is counted
                                   (invariant). NULL: none */
    const rt_invariant *inv;    /* ninv invariants of the continuous state, checked after
                                   each step (rt/invariant.c); NULL iff ninv == 0 */
    uint8_t ninv;

    /* Called once at rt_init with the instance parameters: returns RT_OK or RT_E_PARAM.
       May be NULL (no check). */
    rt_status (*check)(const real_t *p, const void *spec);
    /* The initial state against the kind's own rules (a mode that must match the
       continuous state): NULL when it holds, else why not. rt_init refuses a scene whose
       initial state breaks them, and rt_refresh before the first tick one changed since
       (RT_E_PARAM, the block and the reason). May be NULL (any initial state). */
    const char *(*check_start)(const rt_args *a);
    /* Output equation: writes ny outputs. Called in evaluation order at every stage;
       for DSS only at sample hits (outputs are held in between). NULL iff ny == 0. */
    void (*output)(const rt_args *a, real_t *y);
    /* Lean output equation, for outputs that cost what the state equation costs again (a
       car's lateral acceleration and wheel loads need its tire forces): writes the
       outputs not flagged in lean_skip (ny flags) and leaves the flagged ones as they
       were. A right-hand side calls it instead of output where no input of the set reads
       a flagged output live (rt/eval.c); at ticks and step ends output runs. NULL: none */
    void (*output_lean)(const rt_args *a, real_t *y);
    const uint8_t *lean_skip;
    /* State equation: writes nx derivatives. NSS and LSS; NULL otherwise. */
    void (*deriv)(const rt_args *a, real_t *xdot);
    /* Discrete update: writes nd next states from a->d and a->u at a sample hit. DSS only. */
    void (*update)(const rt_args *a, real_t *dnext);
    /* Root functions of state events: writes nr values. NULL iff nr == 0. */
    void (*roots)(const rt_args *a, real_t *r);
    /* Event handler, called at the located time of root `which` with the state after the
       crossing; may change x and d in place, and nothing else: in a set reading other
       sets it is also run on trial, on copies, to judge what their inputs' misses do to
       it (rt/step.c; not for a kind with `save`, whose state lives elsewhere). NULL iff
       nr == 0. */
    void (*event)(const rt_args *a, uint16_t which, real_t *x, real_t *d);
    const void *spec;           /* type-specific part (LSS matrices, MBS description) */
    /* Reference text (`modrt info KIND`, docs/blocks.md), compiled in only where
       RT_KIND_DOCS is 1 (hosts): write both through RT_DOC(...) so images drop them. */
    const char *doc;            /* what it computes: equations and meaning; NULL: none */
    const char *units;          /* units of inputs, outputs, states, discrete states and
                                   parameters in that order, separated by spaces ("-":
                                   dimensionless); NULL: not given */
    /* Known time events: returns the block's first instant strictly after a->t [s] at
       which its outputs or derivatives switch (a step, a pulse edge, a scheduled change;
       an FMU's next time event), or RT_TEV_NEVER (any time at or past the end time reads
       as none). Reads a->t and a->p only. The runtime ends every step of the block's set
       at each instant (splitting a step of several ticks), evaluates the step before it
       with the left limit and the one after with the right limit (rt_args.t_piece); the
       instants must lie on the base tick grid (rt_init refuses the scene otherwise,
       rt/tev.c). NULL: none (the kind has no switch in time) */
    real_t (*next_event)(const rt_args *a);
    /* The highest angular frequency [rad/s] of the kind's explicit time dependence (its
       outputs or derivatives as functions of t at fixed inputs and state: a sine's
       omega). Reads a->p only. A step h samples t at its stages: at omega h >= pi the
       samples are an alias (at omega h = 2 pi every stage sees the same phase and no
       estimate can tell), so rt_init refuses a scene (and rt_set_param a parameter)
       where a set integrating the signal steps that long (rt/tev.c). NULL: none, or
       not known (an FMU; a defined system declares the |w| of its sin and cos of
       w t + phi, tools/scenec) */
    real_t (*band)(const rt_args *a);

    /* Services of a kind that is a state machine of its own (an FMU, tools/fmi/); NULL or
       0 in the library's kinds. */
    /* Time events known only at run time: with this slot, next_event returns the block's
       first instant after a->t as its own state holds it now (an FMU's nextEventTime,
       set by its last event: it may read nothing of a) or as its parameters give it (a
       defined system's comparison of t with one, whose handler is rt_tev_none),
       RT_TEV_NEVER if none. Such instants may lie off the base tick grid and
       are not walked at rt_init: every step of the block's set ends a part exactly at the
       next one (rt/tev.c), and this handler runs there with the state at the instant; it
       may change x and d in place. More instants in one step than RT_TEV_PARTS_MAX parts
       are counted (tev_limit, RT_E_TEV) and handled at the step's end, never merged
       silently. rt_tev_none: instants that only end step parts */
    void (*time_event)(const rt_args *a, real_t *x, real_t *d);
    /* Called once at the end of each completed integration of the block's set (each step,
       or each part of a step split at time events, rt/tev.c), with the state there, before
       the time events due there; may run an event of its own there and change x and d in
       place: returns 1 if it did (the runtime then evaluates the set's outputs and roots
       again and counts an event), else 0. NULL: none */
    int (*step_end)(const rt_args *a, real_t *x, real_t *d);
    /* Values that may change only at an instant (FMI's discrete inputs and tunable
       parameters, which an FMU takes in event mode alone): called at each instant of the
       block's set, the start of every part of a step (its inputs there on the part's side
       of the set's known time events) and its end (after step_end and the time events due
       there), with the inputs, parameters and state there. The kind takes the new values
       (an event of its own, which may change x and d in place: returns 1, and the runtime
       evaluates the set's outputs and roots again and counts an event; else 0) and holds
       them through the part that follows: its evaluations inside a part never take a new
       one. NULL: none */
    int (*instant)(const rt_args *a, real_t *x, real_t *d);
    /* With instant: 1 per input of discrete variability, 0 per continuous one (NULL: all
       continuous). A step of the block's set also ends a part at each point strictly
       inside it of the history of a set that feeds such an input (the instant the other
       set's held value changes), so the kind takes it there (rt/tev.c) */
    const uint8_t *u_discrete;
    /* With instant: 1 if it takes nothing at an instant but values of its own, its modes
       from its state and continuous inputs (a defined system's located switches,
       docs/scene-language.md): the set's readers keep their step-end hold rule
       (rt/xset.c). 0: an FMU's discrete inputs and tunable parameters */
    uint8_t instant_own;
    /* 1: every sign change of a root is a crossing, as FMI's event indicators need (a
       change of domain z > 0 / z <= 0): a root an event leaves on its z <= 0 side that
       then returns to z > 0 crosses there too (rt/step.c); 0: a root a handler sent back
       is held on its side until it leaves that side again (the library's) */
    uint8_t roots_every_sign;
    /* 1: a directional root that starts past its level says the start state breaks the
       kind's mode (a relay on with its input below its switch-off level, a mass stuck
       under a force beyond static friction): its handler runs at the run's start
       (rt/held.c). 0: a root only fires on crossing (a defined system's `when`) */
    uint8_t roots_at_start;

    /* Internal state the kind keeps outside x, d and p (an FMU's memory: its counters, its
       discrete states, its pending time event), carried by snapshots (rt/snapshot.c).
       save writes it into buf (at most cap bytes) and its size into *n; with buf NULL it
       only reports the size it needs now (rt_sizes_of). Returns RT_OK, RT_E_CAPACITY
       (more than cap) or RT_E_SNAPSHOT (the kind cannot save it). restore reads back the n
       bytes a save wrote; RT_OK or RT_E_SNAPSHOT. Called between ticks only. NULL, both:
       the kind keeps no such state (every library kind) */
    rt_status (*save)(const void *spec, uint8_t *buf, uint32_t cap, uint32_t *n);
    rt_status (*restore)(const void *spec, const uint8_t *buf, uint32_t n);
} rt_kind;

/* A reference text of a kind: kept on hosts, dropped from embedded images. */
#if RT_KIND_DOCS
#define RT_DOC(text) text
#else
#define RT_DOC(text) ((const char *)0)
#endif

/* Type-specific part of a linear state-space kind: its sizes (equal to the kind's) and
 * row-major A (nx*nx), B (nx*nu; NULL: zero), C (ny*nx), D (ny*nu; NULL: zero).
 * The LSS services in rt/lss.c read it. */
typedef struct rt_lss_spec {
    uint16_t nx, nu, ny;
    const real_t *A, *B, *C, *D;
} rt_lss_spec;

/* LSS services, for kinds that describe a linear state-space system. */
void rt_lss_output(const rt_args *a, real_t *y);
void rt_lss_deriv(const rt_args *a, real_t *xdot);

/* ------------------------------------------------------------------ integrators */

struct rt_sim;
struct rt_integrator;

/* Right-hand side of one set: evaluates f at time t with the set's state as it currently
 * stands in x (the integrator writes stage states there) and writes n derivatives. */
typedef struct rt_rhs {
    rt_status (*eval)(void *ctx, real_t t, real_t *xdot);
    void *ctx;
} rt_rhs;

/* What an implicit method keeps from step to step for one set: the factored iteration
 * matrix is reused until its age reaches the set's refresh interval or h changes (ROS2
 * builds the next one in jac over the steps before: rt/integ_implicit.c). The
 * transition method keeps h phi1(hJ) in lu, h phi2(hJ) in jac and the last step's change
 * of f in best (rt/integ_transition.c). */
typedef struct rt_implicit_ws {
    real_t lu[RT_MAX_IMPLICIT_N * RT_MAX_IMPLICIT_N]; /* LU factors, row-major */
    real_t jac[RT_MAX_IMPLICIT_N * RT_MAX_IMPLICIT_N];/* last Jacobian df/dx */
    real_t xs[RT_MAX_IMPLICIT_N];   /* the step's start, kept across its retries */
    real_t best[RT_MAX_IMPLICIT_N]; /* the retries' result with the smallest residual */
    real_t h_factored;        /* step (times method constant) lu belongs to */
    real_t h_next, floor_next;/* a spread refresh (ROS2): h gamma and pivot floor of the
                                 matrix being factored in jac */
    real_t drift;             /* ROS2: what the steps since the refresh moved the state by
                                 their secant checks' misses (scaled as the estimate) */
    uint32_t age;             /* steps since the Jacobian was refreshed */
    /* the narrow members last, so that no padding sits between wide ones */
    uint16_t piv[RT_MAX_IMPLICIT_N];                  /* row pivots of lu */
    uint16_t piv_next[RT_MAX_IMPLICIT_N];             /* a spread refresh: those of jac */
    uint8_t valid;            /* lu holds a usable factorization */
    uint8_t neg_det;          /* the matrix lu factors has a negative determinant */
    uint8_t singular_next;    /* a spread refresh met a singular pivot */
} rt_implicit_ws;

/* Statistics an implicit method reports per set (high-water marks for sizing). */
typedef struct rt_istats {
    uint32_t newton_iter_max; /* most Newton iterations in one step (all stages) */
    uint32_t jac_evals;       /* Jacobian refreshes */
    uint32_t degraded;        /* steps ended with residual above tolerance */
    uint32_t retried;         /* steps that converged after a Jacobian at the iterate (DIRK),
                                 or redone on a fresh one after a secant check (ROS2) */
    real_t last_err;          /* the last step's local error estimate (scaled norm) */
    real_t err_max;           /* the largest of them */
    uint32_t substepped;      /* steps that converged only in substeps */
    real_t last_residual;     /* residual norm after the last iteration */
    uint32_t rhs_step_max;    /* most right-hand sides one step took (an event's re-steps
                                 each count as one); never above rt_step_bound's */
    uint32_t rhs_set_step_max; /* most one whole step of the set took in its tick: every
                                 part, re-step, probe and coupling check; never above
                                 rt_set_step_bound's */
} rt_istats;

/* The settings of a set's method, one row each: the one list every reader takes them
 * from (the scene compiler's clauses, its C and image, modrt's per-set options and info,
 * the checks of rt_set_check, the defaults of rt_set_cfg_of). Columns: id; the
 * scene-language clause; modrt's option (--OPT SET=VALUE; 0: none); the rt_set_cfg field;
 * its kind (RT_CFG_COUNT: a whole number 1..max, RT_CFG_POW2: a power of two 1..max,
 * RT_CFG_REAL: positive and finite, RT_CFG_PAIR: the optional second value of the row
 * before, as in accuracy (rtol, atol)); max; the methods it applies to (RT_CFG_ALL, or
 * RT_CFG_ITER: the implicit methods that iterate, not the transition method); the value
 * a zero selects (rt_config.h); what it means. */
#define RT_SET_CFG_LIST(X)                                                                  \
    X(RT_CFG_NEWTON, "newton", "newton", newton_max, RT_CFG_COUNT, 255, RT_CFG_ITER,        \
      RT_IMP_NEWTON_MAX, "Newton iterations per stage of an implicit set")                  \
    X(RT_CFG_JACOBIAN, "jacobian", "jacobian", jac_every, RT_CFG_COUNT, 65535, RT_CFG_ITER, \
      RT_IMP_JAC_EVERY, "steps between Jacobian refreshes of an implicit set")              \
    X(RT_CFG_TOL, "tolerance", "tol", tol, RT_CFG_REAL, 0, RT_CFG_ITER, RT_IMP_TOL,         \
      "Newton residual tolerance of an implicit set, scaled norm")                          \
    X(RT_CFG_SUBSTEPS, "substeps", "substeps", substeps, RT_CFG_POW2, 128, RT_CFG_ITER,     \
      RT_IMP_SUBSTEPS, "most substeps a failing implicit step is split into (1: none)")     \
    X(RT_CFG_ACCURACY, "accuracy", "accuracy", accuracy, RT_CFG_REAL, 0, RT_CFG_ALL,        \
      RT_ERR_TOL, "local error a step may show before it is counted (errest): max_i "      \
      "|e_i| / (1 + |x_i|)")                                                                \
    X(RT_CFG_ATOL, "accuracy", 0, atol, RT_CFG_PAIR, 0, RT_CFG_ALL, 0,                      \
      "absolute part of the accuracy (0: none): |e_i| <= atol + accuracy |x_i|")

typedef enum {
#define RT_X_ENUM_C(id, word, opt, field, kind, max, scope, dflt, help) id,
    RT_SET_CFG_LIST(RT_X_ENUM_C)
#undef RT_X_ENUM_C
    RT_CFG_N
} rt_cfg_id;
enum { RT_CFG_COUNT, RT_CFG_POW2, RT_CFG_REAL, RT_CFG_PAIR }; /* kinds of a setting */
enum { RT_CFG_ALL, RT_CFG_ITER };                             /* methods it applies to */

/* A set's settings (rt_set.cfg; zeros select the defaults, rt_set_cfg_of). */
typedef struct rt_set_cfg {
    uint8_t newton_max;
    uint8_t substeps;
    uint16_t jac_every;
    real_t tol;
    real_t accuracy;
    real_t atol;
} rt_set_cfg;

/* A row of RT_SET_CFG_LIST for the tools that read settings by name (rt_set_opts). */
typedef struct rt_set_opt {
    const char *word;      /* scene-language clause */
    const char *opt;       /* modrt's option, or 0 */
    uint8_t kind, scope;   /* RT_CFG_COUNT..., RT_CFG_ALL or RT_CFG_ITER */
    uint32_t max;          /* counts: the largest */
    const char *help;
} rt_set_opt;
extern const rt_set_opt rt_set_opts[RT_CFG_N];
/* setting id of c (0: its default), and setting it */
real_t rt_set_cfg_get(const rt_set_cfg *c, rt_cfg_id id);
void rt_set_cfg_put(rt_set_cfg *c, rt_cfg_id id, real_t v);
/* c with every zero replaced by its default */
rt_set_cfg rt_set_cfg_of(const rt_set_cfg *c);
/* 1: method m iterates (the settings of scope RT_CFG_ITER apply to it) */
int rt_method_iterates(const struct rt_integrator *m);

/* Workspace an integrator may use for one step of one set (carved from rt_sim). */
typedef struct rt_iwork {
    real_t *k[RT_MAX_STAGES]; /* stage derivatives, n values each */
    uint8_t autonomous;       /* 1: f(t, x) does not depend on t over the step */
    real_t *x0;               /* n values the method may write: the state at the start of
                                 the step, copied from x, or scratch if it reads xs */
    const real_t *xs;         /* NULL, or the state at the start of the step, which the
                                 caller keeps (n values, not to be written): a method may
                                 read it there instead of copying x into x0 */
    real_t *tm;               /* 2 RT_MAX_TRANSITION_N^2 scratch (method transition) */
    rt_implicit_ws *imp;      /* persistent implicit data of this set */
    rt_istats *stats;         /* statistics of this set */
    const rt_set_cfg *cfg; /* settings of this set */
} rt_iwork;

/* The most work of one step: right-hand-side evaluations and LU factorizations. */
typedef struct rt_step_work {
    uint32_t rhs;
    uint32_t lu;
} rt_step_work;

/* A fixed-step integration method (const method table). */
typedef struct rt_integrator {
    const char *name;  /* e.g. "rk4" */
    uint8_t order;     /* classical order of convergence */
    uint8_t stages;    /* stages per step (explicit: right-hand-side evaluations) */
    uint8_t implicit;  /* 1: needs rt_iwork.imp (n <= RT_MAX_IMPLICIT_N) */
    uint8_t w_method;  /* 1: its stages solve with a Jacobian it keeps and no iteration
                          tells a stale one (ROS2): renewed at its set's switches */
    uint8_t linear;    /* 1: only for a set linear in its state (n <= RT_MAX_TRANSITION_N;
                          checked at rt_init) */
    /* Advances x (n values) from t to t+h in place. Returns RT_OK, RT_E_NOCONV when the
       step ended with a residual above tolerance (counted as degraded), or the first
       error of the right-hand side; the step is always completed. */
    rt_status (*step)(const struct rt_integrator *m, const rt_rhs *f, real_t t, real_t h,
                      real_t *x, uint16_t n, const rt_iwork *w);
    const void *tab;   /* method data, e.g. a Butcher tableau */
    /* the most work one step of n states can take with the settings cfg, whatever the
       model does (the fixed bound of docs/solvers.md, "Bounded work") */
    void (*bound)(const struct rt_integrator *m, const rt_set_cfg *cfg, uint16_t n,
                  struct rt_step_work *w);
    /* before the first tick, at (t, x) for steps of h: what the method keeps from step to
       step made ready (ROS2's first Jacobian of a spread refresh), or NULL */
    void (*prime)(const struct rt_integrator *m, const rt_rhs *f, real_t t, real_t h,
                  real_t *x, uint16_t n, const rt_iwork *w);
} rt_integrator;

/* The library of integrators: a registry of {name, method} rows ending in {NULL, NULL}. */
typedef struct rt_integrator_entry {
    const char *name;
    const rt_integrator *method;
} rt_integrator_entry;
extern const rt_integrator_entry rt_integrators[];
extern const rt_integrator rt_euler, rt_heun, rt_bs3, rt_rk4, rt_dopri5;
extern const rt_integrator rt_beuler, rt_trap, rt_sdirk2, rt_sdirk3, rt_ros2, rt_transition;
/* Returns the integrator registered under name, or NULL. */
const rt_integrator *rt_integrator_find(const char *name);
/* the worst-case work of one step of set s of sc (n states) */
rt_step_work rt_step_bound(const struct rt_scene *sc, uint8_t s, uint16_t n);

/* ------------------------------------------------------------------ scenes */

/* A block instance of a scene. */
typedef struct rt_block {
    const char *name;      /* instance name, e.g. "Osc" */
    const rt_kind *kind;   /* what it computes */
    const real_t *p;       /* kind->np parameters; NULL: the kind's defaults */
    const real_t *x0;      /* kind->nx initial states; NULL: the kind's defaults */
    const real_t *d0;      /* kind->nd initial discrete states; NULL: the kind's defaults */
    uint8_t set;           /* index of the set that integrates it */
    real_t ts;             /* sample period of a DSS block [s]: a multiple of the base tick */
} rt_block;

/* How a signal that crosses from one set to another is reconstructed between the
 * source set's communication points (multirate, rt/xset.c). Errors in the macro step H:
 * hold O(H), linear extrapolation O(H^2), linear interpolation O(H^2), Hermite O(H^3).
 * Interpolation needs the source set to have stepped first: the schedule runs the
 * slowest set first, so a fast set interpolates a slow one and a slow set extrapolates
 * a fast one (an interpolating scheme falls back to extrapolation there). */
#define RT_INTERP_LIST(X)                                                        \
    X(RT_INTERP_SET, "set")           /* on a connection: the destination set's scheme */ \
    X(RT_INTERP_HOLD, "hold")         /* the value at the last communication point */     \
    X(RT_INTERP_EXTRAP, "extrapolate")/* linear extrapolation from the last two points */ \
    X(RT_INTERP_LINEAR, "linear")     /* linear interpolation between the points around t */ \
    X(RT_INTERP_HERMITE, "hermite")   /* cubic Hermite on the points around t, slopes from \
                                         the parabola through the last three points */  \
    X(RT_INTERP_QUAD, "quadratic")    /* the parabola through the last three points, also \
                                         ahead of them (a background set: third order) */

typedef enum {
#define RT_X_ENUM(id, name) id,
    RT_INTERP_LIST(RT_X_ENUM)
#undef RT_X_ENUM
    RT_INTERP_COUNT
} rt_interp;
/* The scene language's name of an interpolation scheme ("?" if out of range). */
const char *rt_interp_name(rt_interp i);

/* One connection of the incidence y = P u (eq. 2): output port -> input port. */
typedef struct rt_conn {
    uint16_t from, y;      /* source block index, its output index */
    uint16_t to, u;        /* destination block index, its input index */
} rt_conn;

/* A constant value for an input that is not connected. */
typedef struct rt_default {
    uint16_t block, u;     /* block index, input index */
    real_t value;
} rt_default;

/* A set: blocks integrated together by one method at one fixed step. */
typedef struct rt_set {
    const char *name;
    const rt_integrator *method;
    uint32_t ratio;        /* step = ratio * base tick */
    uint8_t interp;        /* rt_interp of its inputs from other sets (0: hold) */
    rt_set_cfg cfg;        /* settings of its method (RT_SET_CFG_LIST); zeros: defaults */
    uint8_t background;    /* 1: steps preemptible below the tick, Jacobi-coupled
                              (rt/bg.c, docs/multirate.md "Background sets") */
} rt_set;
/* Checks set st's method, step and settings (RT_SET_CFG_LIST), for the scene compiler,
   modrt's per-set options and rt_init alike: 0 when sound, else what is wrong (e.g.
   "tolerance must be positive and finite") with *bad the setting at fault (RT_CFG_N: the
   method or the step). */
const char *rt_set_check(const rt_set *st, rt_cfg_id *bad);
/* Set s's step [s]: the base tick times its ratio, the one place the product is formed
   (rt_init keeps it in the plan for the tick; tools that print a scene call it). */
real_t rt_set_step(const struct rt_scene *sc, uint8_t s);

/* What a recorded signal reads. RT_SIG_MBS: a multibody quantity computed by the scene's
   MBS services (energy, constraint residuals, joint reactions; index from rt_mbs.h). */
typedef enum { RT_SIG_Y = 0, RT_SIG_X, RT_SIG_D, RT_SIG_MBS } rt_sig_kind;

typedef struct rt_rec {
    uint16_t block;        /* block index */
    uint8_t what;          /* rt_sig_kind */
    uint16_t index;        /* output, state or discrete-state index */
} rt_rec;

/* What happens to an imported value that did not arrive in time (docs/link.md); declared
   once (rt_link_policy_name, rt_link_policy_find). */
#define RT_LINK_POLICY_LIST(X)                                                   \
    X(RT_LINK_HOLD, "hold")       /* keep the last value received */             \
    X(RT_LINK_DEFAULT, "default") /* fall back to the declared default */        \
    X(RT_LINK_STOP, "stop")       /* end the run (status RT_E_LINK) */

typedef enum {
#define RT_X_ENUM_P(id, name) id,
    RT_LINK_POLICY_LIST(RT_X_ENUM_P)
#undef RT_X_ENUM_P
    RT_LINK_POLICY_COUNT
} rt_link_policy;
const char *rt_link_policy_name(int policy);
int rt_link_policy_find(const char *name); /* -1 when unknown */

/* The scene's link to an external controller (scene language: export ... to (C);
 * import ... from (C);). The runtime does no I/O: an application (tools/modrt/link.c on
 * POSIX, a UART or CAN driver on a board) reads the exports and writes the imports
 * between ticks through rt_link_export / rt_link_apply, every `period` base ticks. The
 * imports are the discrete states (and held outputs) of a DSS block, `block`, so they
 * are part of the simulation state like any sampled signal. */
typedef struct rt_link {
    const char *name;             /* the controller's name in the scene */
    uint32_t period;              /* exchange every period base ticks (>= 1) */
    const rt_rec *exp;            /* exported signals, read like recorded ones */
    uint16_t nexp;
    uint16_t block;               /* the import block (DSS, nd = ny = nimp) */
    uint16_t nimp;
    const real_t *def;            /* nimp defaults (also the initial values) */
    const uint8_t *policy;        /* nimp rt_link_policy values */
    uint32_t id;                  /* hash of the scene name and the link layout (names) */
} rt_link;

/* A scene: one experiment, const data (what the scene compiler generates). */
typedef struct rt_scene {
    const char *name;
    const char *doc;              /* one line shown by `modrt list` */
    real_t dt;                    /* base tick [s] */
    real_t t_end;                 /* end time [s] */
    const rt_block *blocks;
    uint16_t nblocks;
    const rt_conn *conns;
    uint16_t nconns;
    const uint8_t *conn_interp;   /* nconns rt_interp values for connections across sets;
                                     NULL (or RT_INTERP_SET): the destination set's */
    const rt_default *defaults;
    uint16_t ndefaults;
    const rt_set *sets;
    uint8_t nsets;
    const rt_rec *recs;
    uint16_t nrecs;
    /* multibody: joints between nodes, and the services (NULL: the scene has no MBS
       blocks, and links none of that code) */
    const rt_joint *joints;
    uint16_t njoints;
    const rt_mbs_ops *mbs;
    uint8_t stab;          /* rt_stab: post-stabilization of MBS sets */
    real_t baumgarte[2];   /* alpha, beta of Baumgarte stabilization [1/s, 1/s^2] */
    /* algebraic loops: the solver of actual loops (NULL: an actual loop is an error) */
    const struct rt_loop_ops *loop_solver;
    uint8_t loop_iter_max; /* Broyden iterations per loop evaluation (0: default) */
    real_t loop_tol;       /* residual tolerance of torn inputs (0: default) */
    const rt_link *link;   /* the external controller's signals; NULL: none */
    /* the background set's services (rt_bg, rt/bg.c): non-NULL exactly when a set is
       declared background, so a scene without one links none of that code */
    const struct rt_bg_ops *bg;
    /* code scenec wrote for this scene (rt_scene_code); NULL: the table-driven path */
    const struct rt_scene_code *code;
} rt_scene;

/* Code written for one scene by scenec (tools/scenec/spec.c, docs/overhead.md): what the
 * table-driven path does for it, with the scene's evaluation sequence and multibody
 * pattern written out, the same operations in the same order (the same bits). A NULL
 * entry, or an entry that returns 0, leaves the work to the generic path. */
typedef struct rt_scene_code {
    /* the right-hand side of set `set` at t (after rt/eval.c's rti_rhs counted it) into
       xdot; 0: not written for this set or not for the state it finds (a mass matrix
       not yet factored), the generic path runs */
    int (*rhs)(const struct rt_scene *sc, struct rt_sim *sim, uint8_t set, real_t t,
               real_t h, real_t *xdot);
    /* the projection of set `set`'s multibody state at t (rt/mbs_project.c,
       RT_STAB_PROJECT); 0: not written for it, the generic path runs */
    int (*project)(const struct rt_scene *sc, struct rt_sim *sim, uint8_t set, real_t t);
    /* the outputs of set `set`'s sequence at t, at a tick or in a step (rt/eval.c's
       set_outputs; mode: rti_mode, rt/rti.h); 0: not written for that mode (a
       right-hand side's outputs are its rhs entry's), the generic path runs */
    int (*outputs)(const struct rt_scene *sc, struct rt_sim *sim, uint8_t set, real_t t,
                   int mode);
    /* RT_SIM_LAYOUT (rt/rt_sim.h) as the code was compiled: the code reads rt_sim's
       members at their offsets under its build's limits, so rt_init refuses it
       (RT_E_SCENE) when the runtime's differ (other RT_MAX_*, another REAL) */
    uint32_t sim_layout;
} rt_scene_code;

/* The background set's services (rt/bg.c), named by a scene that has one (rt_scene.bg). */
typedef struct rt_bg_ops {
    /* at rt_init: checks the background set (one per scene, no sampled blocks, no state
       events, no recorded joint reactions) and its result's size */
    rt_status (*init)(const rt_scene *sc, struct rt_sim *sim);
    /* at the start of a tick: releases the set's next step when it is due */
    void (*release)(const rt_scene *sc, struct rt_sim *sim);
    /* when the tick count has advanced: publishes the step due now, or counts an
       overrun when it has not finished (then publishes it at the first tick after) */
    void (*publish)(const rt_scene *sc, struct rt_sim *sim);
} rt_bg_ops;
extern const rt_bg_ops rt_bg;

/* Post-stabilization of multibody sets; declared once (rt_stab_find). */
#define RT_STAB_LIST(X)                                                          \
    X(RT_STAB_PROJECT, "project")   /* two-iteration position and direct velocity   \
                                       projection (eq. 10) */                       \
    X(RT_STAB_NONE, "none")         /* none: shows the drift */                     \
    X(RT_STAB_BAUMGARTE, "baumgarte") /* Baumgarte terms in the acceleration        \
                                         constraint, no projection */

typedef enum {
#define RT_X_ENUM(id, name) id,
    RT_STAB_LIST(RT_X_ENUM)
#undef RT_X_ENUM
    RT_STAB_COUNT
} rt_stab;
/* the method of a scene language name (-1 if none) */
int rt_stab_find(const char *name);

/* Registry row of a scene; registries end with {NULL, NULL}. */
typedef struct rt_scene_entry {
    const char *name;
    const rt_scene *scene;
} rt_scene_entry;

/* ------------------------------------------------------------------ simulator state */

/* Where a block input takes its value from (derived at init). */
typedef enum {
    RT_SRC_Y = 0,      /* an output: y[src] */
    RT_SRC_DEFAULT,    /* the scene's constant: def[i] */
    RT_SRC_TORN,       /* a torn loop input: the solver's unknown torn_val[src] */
    RT_SRC_XSET,       /* an output of another set, reconstructed from its history */
    RT_SRC_HELD        /* a sampled (DSS) output of another set: y[src], held from its
                          sample instant (zero-order hold), never interpolated */
} rt_src_kind;

/* One entry of the evaluation sequence. */
typedef enum {
    RT_SEQ_CALL = 0,   /* call block `index`'s output equation */
    RT_SEQ_LOOP        /* solve actual loop `index`: its calls follow this entry */
} rt_seq_kind;

typedef struct rt_seq_step {
    uint8_t kind;      /* rt_seq_kind */
    uint16_t index;    /* block or loop */
} rt_seq_step;

/* A loop found in the signal graph (reported by `modrt info`). A potential loop is a
 * strongly connected component of the block graph, solved by ordering alone; an actual
 * loop is one of the port-level throughput graph, torn at loop-closing edges whose
 * inputs become the unknowns of a Broyden iteration. */
typedef struct rt_loop {
    uint8_t actual;            /* 1: every block on it has throughput (actual loop) */
    uint16_t nblocks;          /* blocks in the strongly connected component */
    uint16_t first;            /* index of its first block in rt_sim.loop_blocks */
    /* actual loops only */
    uint16_t torn0, ntorn;     /* its torn inputs: rt_sim.torn_in[torn0 .. +ntorn] */
    uint16_t seq0, seq1;       /* its calls: rt_sim.seq[seq0 .. seq1) */
    uint16_t h0;               /* its inverse Jacobian: rt_state.loop_h[h0 .. +ntorn^2] */
} rt_loop;

/* The solver of actual loops a scene names (rt_scene.loop_solver; rt/loop.c). */
struct rt_sim;
typedef struct rt_loop_ops {
    /* Solves loop l at time t: evaluates its calls with the torn inputs as unknowns
       until the residual is below the scene's tolerance or the iteration bound. */
    void (*solve)(const struct rt_scene *sc, struct rt_sim *sim, uint8_t l, real_t t,
                  int mode);
} rt_loop_ops;
extern const rt_loop_ops rt_broyden;

/* One running scene (rt_sim) and its state, everything a run needs to continue
 * (rt_state): their layout is rt_sim.h's, which an application includes only where it
 * allocates them (static storage); the API below reads them for it. */
typedef struct rt_sim rt_sim;
typedef struct rt_state rt_state;

/* What a run has met: fault counters, the first fault, high-water marks and monitors.
 * Read by applications through rt_stats_of; written only by rt/. */
typedef struct rt_stats {
    rt_status status;                /* first fault met (RT_OK while clean) */
    uint32_t count[RT_CNT_COUNT];    /* fault counters */
    uint8_t growth[RT_MAX_SETS];     /* steps in a row the set's state grew fast */
    uint32_t unstable[RT_MAX_SETS];  /* RT_CNT_UNSTABLE by set */
    uint32_t errest[RT_MAX_SETS];    /* RT_CNT_ERREST by set */
    int16_t last_block[RT_CNT_COUNT];/* last offending block per counter, -1 none */
    uint32_t first_tick[RT_CNT_COUNT];/* tick of each counter's first count */
    uint32_t event_iter_max;         /* high-water mark of event-location iterations */
    uint32_t loop_hist[RT_MAX_LOOP_HIST]; /* loop solves by iterations taken */
    uint32_t loop_iter_max;          /* high-water mark of iterations per loop solve */
    real_t loop_residual;            /* largest residual left by a loop solve that failed */
    real_t xset_err[RT_MAX_SETS];    /* monitor: largest change of a set's cross-set
                                        outputs against their linear extrapolation over
                                        its step, and against what a slower reader's
                                        scheme predicted over the reader's step */
    rt_istats istats[RT_MAX_SETS];   /* implicit methods' statistics per set */
    uint64_t rhs_evals[RT_MAX_SETS]; /* right-hand-side evaluations of each set (the cost
                                        measure of `modrt tune` and the benchmarks) */
    uint32_t bg_late;                /* background steps not finished at their deadline
                                        (also counted as RT_CNT_OVERRUN) */
#if RT_MAX_XPRED > 0
    real_t xset_est[RT_MAX_SETS];    /* the largest local error a set took from the inputs
                                        it reads from other sets, estimated from a missed
                                        prediction (extrapolated) or the scheme's error
                                        over the source's step (interpolated) and the
                                        set's sensitivity to it (state.xgain), in the
                                        scaled norm of its accuracy (rti_xset_predict) */
#endif
} rt_stats;


/* ------------------------------------------------------------------ API */

/* Initialises sim for scene: layout, parameters and initial states, signal routing and
 * evaluation order, initial outputs. Returns RT_OK or the first problem found; on error
 * sim holds a description for rt_error_text. */
rt_status rt_init(const rt_scene *scene, rt_sim *sim);
/* rt_init for an rt_sim laid out as caller_layout says (RT_SIM_LAYOUT, rt_sim.h, in the
 * file that allocates it): when that is not the runtime's layout (a file compiled with
 * other RT_MAX_* or another REAL than rt/), returns RT_E_SCENE and writes nothing but
 * the description (at the start of sim, where every layout has it). Every rt_init of a
 * file that includes rt_sim.h (every file that can allocate an rt_sim) is this call. */
rt_status rt_init_checked(const rt_scene *scene, rt_sim *sim, uint32_t caller_layout);
/* Returns the text describing the last init error, or after an rt_init that returned
 * RT_OK what it reported (an initial state moved onto its constraints, a quaternion
 * normalized, redundant joints; "" if nothing). */
const char *rt_error_text(const rt_sim *sim);
/* Advances the scene by one base tick. Always completes the tick; faults go to the
 * counters and to sim->stats.status. Returns RT_E_DONE once t_end is reached. */
rt_status rt_tick(const rt_scene *scene, rt_sim *sim);
/* A fault the application met outside the tick (a lost link): the run's status becomes
 * status if that is more severe (rt_status_severity), as a counted fault makes it. */
void rt_note_status(rt_sim *sim, rt_status status);
/* n faults of counter c the application met outside the tick (deadlines its clock
 * missed): counted, the first of them at tick first_tick when the counter was 0, and the
 * run's status as rt_note_status makes it; nothing when n is 0. */
void rt_note_count(rt_sim *sim, rt_counter c, uint32_t n, uint64_t first_tick,
                   rt_status status);
/* Time of the current state [s]. */
real_t rt_time(const rt_scene *scene, const rt_sim *sim);
/* Re-evaluates the outputs and root values of every set whose state belongs to the current
 * tick (all sets at t = 0; between its steps a set's outputs are held): call it after
 * changing parameters or initial states before the run. Before the first tick it checks
 * the initial state again as rt_init does: the kinds' start rules (rt_kind.check_start),
 * and a multibody block's parameters or states changed since rt_init are projected onto
 * the constraints, refused past RT_INIT_TOL and counted (init_moved) below it. Returns
 * RT_OK, or the refusal's status with rt_error_text; then run rt_init again. */
rt_status rt_refresh(const rt_scene *scene, rt_sim *sim);

/* Recording: fills the nrecs recorded values at the current state and folds them into
 * sim->state.hash. */
void rt_record(const rt_scene *scene, rt_sim *sim, real_t *out);
/* Returns the value of recorded signal i at the current state. */
real_t rt_rec_value(const rt_scene *scene, const rt_sim *sim, uint16_t i);
/* Name parts of recorded signal i: block name and signal name. */
const char *rt_rec_signal(const rt_scene *scene, uint16_t i);

/* The controller link (rt/link.c; the I/O is the application's). rt_link_due: the
 * current tick is an exchange tick. rt_link_export: exported signal i at the current
 * state. rt_link_apply: the nimp imported values take effect from the current tick on
 * (written into the import block's discrete states and held outputs). */
int rt_link_due(const rt_scene *scene, const rt_sim *sim);
real_t rt_link_export(const rt_scene *scene, const rt_sim *sim, uint16_t i);
void rt_link_apply(const rt_scene *scene, rt_sim *sim, const real_t *v);

/* Background sets (rt/bg.c, docs/multirate.md "Background sets"). A set declared
 * `background` steps from kH to (k+1)H on the inputs of tick kH (a copy), and its result
 * becomes visible to the other sets and to the trace at tick (k+1)H, so the trace does not
 * depend on when within that window the step runs. Without a context attached, rt_tick
 * runs the step at its release (the simulated clock). rt_bg_attach makes bg (the
 * caller's storage, never touched by the tick while a step runs) the context the step
 * runs in: then rt_tick only releases it, the application runs rt_background from a
 * context below the tick (PendSV, a low-priority thread), and the tick at (k+1)H
 * publishes it, or counts an overrun (RT_CNT_OVERRUN, status RT_E_OVERRUN) and
 * publishes it at the first tick after it finished. Attach between ticks, with no step
 * in flight (after rt_init). */
rt_status rt_bg_attach(const rt_scene *scene, rt_sim *sim, rt_sim *bg);
/* rt_bg_attach for a context bg laid out as caller_layout says (as rt_init_checked):
 * another layout than the runtime's returns RT_E_SCENE, nothing attached and nothing
 * written into bg, with the description in rt_error_text(sim). Every rt_bg_attach of a
 * file that includes rt_sim.h is this call. */
rt_status rt_bg_attach_checked(const rt_scene *scene, rt_sim *sim, rt_sim *bg,
                               uint32_t caller_layout);
/* 1 if a released background step waits for rt_background (call after rt_tick). */
int rt_bg_pending(const rt_sim *sim);
/* Runs the released background step to its end, in the attached context; returns RT_OK,
 * or RT_E_ARG when none is pending. Call from the context below the tick only. */
rt_status rt_background(const rt_scene *scene, rt_sim *sim);
/* The scene's background set, -1 if it has none. */
int rt_bg_set(const rt_sim *sim);

/* Snapshots (rt/snapshot.c): the state part of rt_sim is everything a run needs to continue; one copy
 * out and one copy in (the plan must be the same scene's: restore after rt_init of it).
 * Blocks whose kind keeps internal state (rt_kind.save: an FMU's) add it, in block order,
 * to rt_state.kstate (RT_MAX_KSTATE bytes). rt_snapshot returns RT_OK, RT_E_CAPACITY when
 * those states exceed RT_MAX_KSTATE, or RT_E_SNAPSHOT when a kind cannot save its state
 * (an FMU without canGetAndSetFMUState / canSerializeFMUState); such a snapshot is marked
 * incomplete and rt_restore refuses it. rt_restore returns RT_E_SNAPSHOT, nothing changed,
 * for a snapshot whose kinds' states do not fit this scene's blocks (incomplete, another
 * scene's), and RT_E_SNAPSHOT after a kind failed to take its state back (the FMU counts
 * it as a fault: the run is not to be trusted).
 * With a background context attached the step in flight lives in the context: rt_restore
 * then takes only a snapshot without one (bg_busy 0, e.g. right after a publication)
 * while none runs, and re-attaches the context from the restored state; else RT_E_ARG,
 * nothing changed. */
rt_status rt_snapshot(const rt_sim *sim, rt_state *out);
rt_status rt_restore(rt_sim *sim, const rt_state *in);
/* rt_snapshot and rt_restore for a snapshot laid out as caller_layout says (RT_SIM_LAYOUT,
 * rt_sim.h, in the file that allocates it): another layout than the runtime's (other
 * RT_MAX_*, another REAL) returns RT_E_ARG, nothing written into out, nothing changed.
 * Every rt_snapshot and rt_restore of a file that includes rt_sim.h is this call. */
rt_status rt_snapshot_checked(const rt_sim *sim, rt_state *out, uint32_t caller_layout);
rt_status rt_restore_checked(rt_sim *sim, const rt_state *in, uint32_t caller_layout);
/* The blocks' internal states alone, in the layout rt_snapshot appends them to
 * rt_state.kstate: saved into buf (cap bytes: RT_OK, RT_E_CAPACITY or the kind's status),
 * and back (RT_E_SNAPSHOT when buf holds no whole state for a block, nothing changed, or
 * when a kind failed to take its own back, the others restored). For a tool that runs the
 * same scene's blocks in turns (modrt check's runs at h, h/2, h/4). */
rt_status rt_kinds_save(const rt_scene *sc, uint8_t *buf, uint32_t cap);
rt_status rt_kinds_restore(const rt_scene *sc, const uint8_t *buf, uint32_t cap);

/* Look-ups by name (for hosts, tests and the scene language); -1 when not found. */
int rt_block_index(const rt_scene *scene, const char *name);
int rt_param_index(const rt_kind *kind, const char *name);
/* Sets parameter `name` of block `block` before or between ticks; RT_E_ARG if unknown. A
   set stepping over several ticks, whose state is ahead of the tick, takes it from its
   next step on, where its state is (a kind that takes values at instants, rt_kind.instant:
   at that instant). Before the first tick an initial state can be set by name too, and
   rt_refresh then judges the start again. During the run, a multibody parameter that puts
   its set off its constraints past RT_INIT_TOL (a joint point moved) is counted
   (init_moved, the block, rt_error_text): the next projection moves the bodies back. */
rt_status rt_set_param(const rt_scene *scene, rt_sim *sim, const char *block,
                       const char *name, real_t value);

/* ------------------------------------------------------------------ describing a scene */

/* What rt_init decided, for tools that print or size a scene (rt/describe.c). Read
   through these, never through rt_sim.plan. Valid after a successful rt_init. */
/* The i-th set in step order within a tick (slowest first). */
uint8_t rt_set_at(const rt_sim *sim, uint8_t i);
/* Continuous states a set integrates. */
uint16_t rt_set_nx(const rt_sim *sim, uint8_t set);
/* 1 if other sets read outputs of this set (it keeps a history and a monitor). */
int rt_set_is_source(const rt_sim *sim, uint8_t set);
/* the most work one whole step of set s can take in its tick (or context): the method's
   bound (rt_step_bound) for every method step that event location and the parts at known
   time events may need, plus the probes and the coupling monitor's evaluations; the
   witness is rt_istats.rhs_set_step_max */
rt_step_work rt_set_step_bound(const rt_scene *sc, const rt_sim *sim, uint8_t s);
/* Base ticks to the end time. */
uint64_t rt_tick_count(const rt_sim *sim);
/* What a run shows now (as the last tick or refresh left it): output j of block b, its
   continuous state i, discrete state i and parameter i (as rt_set_param left it). */
real_t rt_output(const rt_sim *sim, uint16_t block, uint16_t j);
real_t rt_block_x(const rt_sim *sim, uint16_t block, uint16_t i);
real_t rt_block_d(const rt_sim *sim, uint16_t block, uint16_t i);
real_t rt_block_p(const rt_sim *sim, uint16_t block, uint16_t i);
/* Base ticks done (t = rt_ticks_done * dt), and the trace hash of every value rt_record
   folded in so far (RT_HASH_INIT before the first). */
uint64_t rt_ticks_done(const rt_sim *sim);
uint64_t rt_trace_hash(const rt_sim *sim);
/* What the run has met: fault counters, first fault, high-water marks, monitors. */
const rt_stats *rt_stats_of(const rt_sim *sim);
/* Where input u of block reads its value from, and (RT_SRC_XSET) how it is rebuilt. */
rt_src_kind rt_input_source(const rt_sim *sim, uint16_t block, uint16_t u, rt_interp *interp);
/* The evaluation sequence (rt/order.c): its length and entries. */
uint16_t rt_seq_count(const rt_sim *sim);
rt_seq_step rt_seq_at(const rt_sim *sim, uint16_t i);
/* The loops found: their number, each loop, and its i-th block. */
uint8_t rt_loop_count(const rt_sim *sim);
const rt_loop *rt_loop_at(const rt_sim *sim, uint8_t l);
uint16_t rt_loop_block(const rt_sim *sim, uint8_t l, uint16_t i);
/* Torn inputs of actual loops: their number, and torn input k as the edge it cuts. */
typedef struct rt_torn {
    uint16_t from, y;      /* the output that drives it: block, output index */
    uint16_t to, u;        /* the torn input: block, input index */
} rt_torn;
uint16_t rt_torn_count(const rt_sim *sim);
rt_torn rt_torn_at(const rt_scene *scene, const rt_sim *sim, uint16_t k);
/* The exact sizes of this scene: what its per-scene build's limits must hold, one member
   per row of RT_LIMIT_LIST (rt_config.h: what each counts). */
typedef struct rt_sizes {
#define RT_X_SIZE(name, field, least, dflt, what) uint16_t field;
    RT_LIMIT_LIST(RT_X_SIZE)
#undef RT_X_SIZE
} rt_sizes;
void rt_sizes_of(const rt_scene *scene, const rt_sim *sim, rt_sizes *out);
/* The capacity limits by name, one per row of RT_LIMIT_LIST (RT_LIM_BLOCKS, ...). */
typedef enum {
#define RT_X_LIM(name, field, least, dflt, what) RT_LIM_##name,
    RT_LIMIT_LIST(RT_X_LIM)
#undef RT_X_LIM
    RT_LIM_COUNT
} rt_limit;
/* Limit lim of this build in words from its row, "<what it counts> exceed RT_MAX_<NAME>
   (<value> in rt_config.h)", into buf (cap bytes, truncated; RT_ERR_LEN holds any):
   the text of every capacity fault of rt_init and of the scene compiler's. Returns buf. */
const char *rt_limit_text(char *buf, size_t cap, rt_limit lim);

/* Trace hash: per value h = (h ^ bits) * RT_HASH_MUL, then h ^= h >> 32, over the IEEE bit
 * pattern of each value as an integer (rti_hash, rt/rti.h). */
#define RT_HASH_INIT 0xcbf29ce484222325ull
#define RT_HASH_MUL 0x9e3779b97f4a7c15ull /* odd: 2^64 / golden ratio */
uint64_t rt_hash_real(uint64_t h, real_t v);

/* Length-limited string helpers for freestanding code. */
int rt_streq(const char *a, const char *b);

#endif /* RT_H */
