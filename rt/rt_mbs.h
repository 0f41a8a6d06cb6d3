/* rt_mbs.h - multibody modules (paper, eqs. 6-10): the MBS kind's type-specific part,
 * interaction nodes [r|S], joint kinds and joints between nodes, the recordable MBS
 * signals, and the workspace of the assembly, the index-1 solve and the projection.
 * Included by rt.h; the services live in rt/mbs.c, rt/mbs_asm.c, rt/mbs_project.c and
 * the joint kinds in rt/joints.c. docs/mbs.md gives the equations as implemented.
 *
 * An MBS block kind (rt_kind.type == RT_KIND_MBS, deriv == NULL, spec -> rt_mbs_spec)
 * has nx = nq + nz states x = [q, z] and describes, in the descriptor form of eq. 6,
 *     q' = K(q) z + b(q,t)                      (6a)
 *     M(q) z' = k(q,z,u,t) - (G K)^T lambda     (6b)
 *     g(q,t) = 0                                (6c, internal constraints)
 * Its interaction nodes give position, rotation, velocities, Jacobians with respect to z
 * and the acceleration terms, so that joints (rt_joint_kind) never see a block's
 * coordinates. The runtime stacks the blocks of one set into the block-diagonal system
 * of eq. 9 and solves it with the Schur complement W M^-1 W^T, W = G K. */
#ifndef RT_MBS_H
#define RT_MBS_H

#include <stdint.h>

#include "rt_config.h"

struct rt_scene;
struct rt_sim;
struct rt_args;

/* ------------------------------------------------------------------ limits
   (the tunable ones, RT_MAX_MBS_* and RT_MBS_*_TOL, are in rt_config.h) */

#define RT_MBS_JOINT_NC_MAX 6 /* constraint equations of one joint (the fixed joint has 6) */
#if RT_MAX_MBS_TW > 65535 || RT_MAX_MBS_TY > 65535 || RT_MAX_MBS_M > 65535 || \
    RT_MAX_MBS_ROWS + RT_MAX_MBS_LNZ > 65535 || RT_MAX_MBS_PAIRS > 65535
#error "rt_mbs_work indexes its tables with 16-bit integers: keep RT_MAX_MBS_TW, \
RT_MAX_MBS_M, RT_MAX_MBS_PAIRS and RT_MAX_MBS_ROWS + RT_MAX_MBS_LNZ below 65536."
#endif

/* ------------------------------------------------------------------ nodes */

/* The state of one interaction node [r|S] (paper, Fig. 2), all in the inertial frame.
 * With the block's generalized velocities z, the node's velocities are
 *     v = Jr z + (terms of b and t),  w = Jw z + (...),
 * and its accelerations r'' = Jr z' + ar, w' = Jw z' + aw, where Jr, Jw are the 3 x nz
 * Jacobians the node function writes on request. */
typedef struct rt_mbs_node {
    real_t r[3];  /* position [m] */
    real_t S[9];  /* rotation of the node frame to the inertial frame, row-major */
    real_t v[3];  /* velocity [m/s] */
    real_t w[3];  /* angular velocity [rad/s] */
    real_t ar[3]; /* acceleration at z' = 0 [m/s^2] */
    real_t aw[3]; /* angular acceleration at z' = 0 [rad/s^2] */
} rt_mbs_node;

/* ------------------------------------------------------------------ the MBS kind */

/* flags of rt_mbs_spec */
#define RT_MBS_M_DIAG 0x01  /* M is diagonal: mass() writes nz values, solves divide */
#define RT_MBS_M_CONST 0x02 /* M depends on parameters only: factored once, again only
                               after a parameter change or a restored state */
#define RT_MBS_K_CONST 0x08    /* K does not depend on q (kin reads no coordinate): the
                                  projection keeps no predicted q for the block */
#define RT_MBS_F_PARAM 0x10    /* k depends on the parameters alone (force reads no q, z,
                                  u or t): with RT_MBS_M_CONST and a diagonal M, M^-1 k
                                  stays the same until a parameter changes, and a scene's
                                  written-out code forms it once (kept after M's factors
                                  in rt_mbs_work.M) */
#define RT_MBS_NODE_POINT 0x04 /* every node is the point itself: x = [r, v], nq = nz = 3,
                                  r' = v (K = I, no kinb: the runtime copies instead of
                                  calling kin), Jr = I, Jw = 0, S = I, no acceleration
                                  terms; the
                                  assembly fills such nodes itself, asks for no Jacobian
                                  and takes a joint's translational coefficients as the
                                  row of W */
#define RT_MBS_M_ISO 0x20      /* M = m I: mass() writes nz equal values (with
                                  RT_MBS_M_DIAG); a set of such points forms A with 1/m
                                  (kept after M's factors) and divides no row of W by M */
#define RT_MBS_Y_STATE 0x40    /* the kind's output equation copies the state (ny = nx,
                                  y = x, no input read: rt_init checks): written-out code copies without the call */

/* Type-specific part of an MBS kind (rt_kind.spec). The hooks read the block's state
 * x = [q (nq), z (nz)], inputs, parameters and time through rt_args; none may allocate
 * or fail, and each must give finite values for any finite state. */
typedef struct rt_mbs_spec {
    uint16_t nq, nz;  /* coordinates, velocities: the kind's nx is nq + nz */
    uint16_t nc;      /* internal constraints (eq. 6c within the module) */
    uint16_t nn;      /* interaction nodes */
    uint8_t flags;    /* special properties (paper, Fig. 3): RT_MBS_M_DIAG, ... */
    const char *const *node_names; /* nn names, e.g. "c" */
    /* Kinematics without the rheonomic term: qd = K(q) v for any v of nz values (eq. 6a).
       Reads q only (the projection calls it with the predicted q). Never NULL. */
    void (*kin)(const struct rt_args *a, const real_t *v, real_t *qd);
    /* Rheonomic term b(q,t) of eq. 6a, nq values. NULL: b = 0. */
    void (*kinb)(const struct rt_args *a, real_t *b);
    /* Mass matrix M(q), nz x nz row-major, symmetric positive definite; with
       RT_MBS_M_DIAG only its nz diagonal entries. Never NULL. */
    void (*mass)(const struct rt_args *a, real_t *M);
    /* Applied, gyroscopic and input forces k(q,z,u,t) of eq. 6b, nz values. Never NULL. */
    void (*force)(const struct rt_args *a, real_t *k);
    /* Internal constraints: g (nc values, eq. 6c) and g' (nc, eq. 7a); if W is not NULL
       also W = G K (nc rows of nz, row stride ld) and the acceleration term gam with
       g'' = W z' + gam (eq. 7b). NULL iff nc == 0. */
    void (*constr)(const struct rt_args *a, real_t *g, real_t *gd, real_t *W, uint16_t ld,
                   real_t *gam);
    /* Node i: fills n; if J is not NULL also writes the Jacobians as 6 rows of nz values
       (rows 0-2: Jr, rows 3-5: Jw). Never NULL when nn > 0. */
    void (*node)(const struct rt_args *a, uint16_t i, rt_mbs_node *n, real_t *J);
    /* Kinetic energy e[0] = z^T M z / 2 and potential energy e[1] [J]. Never NULL. */
    void (*energy)(const struct rt_args *a, real_t *e);
    /* Called on q after the position projection, e.g. to renormalize unit quaternions
       (which K keeps tangent); returns the norm the quantity had (1 when it was unit), so
       that rt_init can report a non-unit initial quaternion (rt/mbs_start.c). NULL:
       nothing to normalize. */
    real_t (*normalize)(real_t *q);
} rt_mbs_spec;

/* ------------------------------------------------------------------ joints */

/* What a joint kind computes from its two nodes: the constraints g (eq. 8 and kin), their
 * time derivative g' = C [v1; w1; v2; w2] (eq. 7a; C has 12 columns: node 1 velocity,
 * node 1 angular velocity, node 2 velocity, node 2 angular velocity), and the term c of
 * the acceleration constraint g'' = C [r1''; w1'; r2''; w2'] + c (eq. 7b). */
typedef struct rt_joint_eval {
    real_t g[RT_MBS_JOINT_NC_MAX];       /* residuals [m or 1] */
    real_t C[RT_MBS_JOINT_NC_MAX][12];   /* velocity coefficients */
    real_t c[RT_MBS_JOINT_NC_MAX];       /* C' [v1; w1; v2; w2] */
} rt_joint_eval;

/* A joint kind (const table element, rt/joints.c). */
typedef struct rt_joint_kind {
    const char *name;             /* e.g. "sphdiff" */
    uint8_t nc;                   /* constraint equations, <= RT_MBS_JOINT_NC_MAX */
    uint8_t np;                   /* parameters */
    uint8_t trans;                /* 1: translational conditions only, C's angular columns
                                     (3-5, 9-11) are always zero and need not be read */
    uint8_t anti;                 /* 1: eval_points gives C[i][6..8] = -C[i][0..2] (the rows
                                     read r1 - r2 and v1 - v2 only): a row's two blocks see
                                     the same C.C (rt/mbs_asm.c point_shares) */
    const char *const *p_names;   /* np names (NULL iff np == 0) */
    /* Returns 0 when the parameters are valid. NULL: any parameters are. */
    int (*check)(const real_t *p);
    /* Evaluates g, C and c for nodes n1, n2. Never NULL; finite for finite nodes. */
    void (*eval)(const real_t *p, const rt_mbs_node *n1, const rt_mbs_node *n2,
                 rt_joint_eval *e);
    /* What eval computes when both nodes are points (RT_MBS_NODE_POINT or an anchor:
       position r, velocity v, S = I, no rotation, no acceleration terms), from r and v
       directly: g, c and the translational coefficients C[i][0..2], C[i][6..8], the same
       bits as eval; the other entries of e are left unwritten. NULL: the runtime fills
       the nodes and calls eval. Only for translational kinds (trans = 1). */
    void (*eval_points)(const real_t *p, const real_t *r1, const real_t *v1,
                        const real_t *r2, const real_t *v2, rt_joint_eval *e);
    /* g alone between two points, the same bits as eval_points' g (the recorded position
       residual, every tick: no C, c or g'). NULL: eval_points serves. */
    void (*g_points)(const real_t *p, const real_t *r1, const real_t *r2, real_t *g);
    /* Reference text (`modrt info KIND`, docs/blocks.md), through RT_DOC(...) (hosts
       only): what it holds, its constraint equations in the nodes' terms; and the
       directions it leaves free. NULL: none. */
    const char *doc;
    const char *free;
} rt_joint_kind;

/* the library of joint kinds */
extern const rt_joint_kind rt_joint_sphdiff;   /* |r1 - r2| - l = 0 (eq. 8); p = {l [m]} */
extern const rt_joint_kind rt_joint_spherical; /* r1 - r2 = 0 */
extern const rt_joint_kind rt_joint_revolute;  /* r1 = r2, node z axes parallel */
extern const rt_joint_kind rt_joint_fixed;     /* r1 = r2, S1 = S2 (a fixed anchor) */
extern const rt_joint_kind rt_joint_prismatic; /* S1 = S2, r2 on node 1's z axis */

/* Registry row of a joint kind; the registry rt_joint_kinds ends with {NULL, NULL}. */
typedef struct rt_joint_entry {
    const char *name;
    const rt_joint_kind *kind;
} rt_joint_entry;
extern const rt_joint_entry rt_joint_kinds[];

/* A joint instance of a scene: links node n1 of block b1 with node n2 of block b2;
   b2 = -1 links to an inertial node (an anchor) at position at, rotation at_S. Both
   blocks must be MBS blocks of the same set. */
typedef struct rt_joint {
    const char *name;                 /* e.g. "J1" (named in error messages) */
    const rt_joint_kind *kind;
    int16_t b1, n1;                   /* block index, node index */
    int16_t b2, n2;                   /* block index or -1, node index */
    const real_t *p;                  /* kind->np parameters (e.g. the length l of eq. 8) */
    const real_t *at;                 /* anchor position [m], 3 values; NULL: origin */
    const real_t *at_S;               /* anchor rotation, 9 values row-major; NULL: unit */
    const real_t *axis_S;             /* the joint frame within both node frames, 9 values
                                         row-major: its third column is the joint's axis
                                         (revolute axis, prismatic direction), the kinds
                                         see node frames S A; NULL: unit (the z axis) */
} rt_joint;

/* ------------------------------------------------------------------ signals */

/* Recordable MBS quantities: rt_rec {block, RT_SIG_MBS, index}. For index below
 * RT_MBS_SIG_JOINT the quantity belongs to the set of `block` (any MBS block of it) and
 * is computed from the current state. Joint signals have index RT_MBS_SIG_JOINT_AT(j, c)
 * and block = the joint's b1 (the block the reaction acts on). */
/* The set signals, declared once: X(ENUM, name, meaning). */
#define RT_MBS_SIG_LIST(X)                                                                 \
    X(RT_MBS_SIG_ENERGY, "energy", "kinetic + potential energy of the set [J]")            \
    X(RT_MBS_SIG_KINETIC, "kinetic", "kinetic energy of the set [J]")                     \
    X(RT_MBS_SIG_POTENTIAL, "potential", "potential energy of the set [J]")               \
    X(RT_MBS_SIG_RESIDUAL, "residual", "largest |g| of the set's constraints [m or 1]")   \
    X(RT_MBS_SIG_RESIDUAL_V, "residual_v", "largest |g'| [m/s or 1/s]")
#define RT_MBS_SIG_ENUM(e, name, meaning) e,
enum {
    RT_MBS_SIG_LIST(RT_MBS_SIG_ENUM)
    RT_MBS_SIG_NSET,       /* (count) */
    RT_MBS_SIG_JOINT = 16  /* first joint signal */
};
/* components of a joint signal: reaction force (inertial frame) and torque on node 1
   from the last index-1 solve (refreshed at the step end when a scene records them), and
   the multipliers lambda of the joint's rows (the tension for a spherical difference),
   "lambda1".. per row. Declared once: X(ENUM, name, meaning). */
#define RT_MBS_JSIG_LIST(X)                                                                \
    X(RT_MBS_JSIG_FX, "fx", "reaction force on node 1, x [N]")                           \
    X(RT_MBS_JSIG_FY, "fy", "reaction force on node 1, y [N]")                           \
    X(RT_MBS_JSIG_FZ, "fz", "reaction force on node 1, z [N]")                           \
    X(RT_MBS_JSIG_MX, "mx", "reaction torque on node 1, x [N m]")                        \
    X(RT_MBS_JSIG_MY, "my", "reaction torque on node 1, y [N m]")                        \
    X(RT_MBS_JSIG_MZ, "mz", "reaction torque on node 1, z [N m]")
enum {
    RT_MBS_JSIG_LIST(RT_MBS_SIG_ENUM)
    RT_MBS_JSIG_LAMBDA, /* first multiplier */
    RT_MBS_JSIG_COUNT = RT_MBS_JSIG_LAMBDA + RT_MBS_JOINT_NC_MAX
};
#define RT_MBS_SIG_JOINT_AT(j, c) ((uint16_t)(RT_MBS_SIG_JOINT + (j) * RT_MBS_JSIG_COUNT + (c)))

/* ------------------------------------------------------------------ workspace */

/* Workspace of the multibody services, in rt_sim. The tables are filled by init. Index
 * conventions: a set's velocities z are numbered block by block (zo), its constraint
 * rows internal rows first (co), then joint rows (jrow); a block's touches (the rows
 * that can be non-zero in its columns of W) are trow[to[b] .. to[b+1]), and W and
 * Y = M^-1 W^T keep one slice of the block's nz velocities per touch. A is factored as
 * L D L^T over the pattern init computed (rt/mbs_ldl.c). Every array is sized by its own
 * limit of rt_config.h, so a per-scene build holds exactly its scene. */
typedef struct rt_mbs_work {
    /* tables (init) */
    uint16_t zo[RT_MAX_BLOCKS];     /* first velocity of each MBS block within its set */
    uint16_t qo[RT_MAX_BLOCKS];     /* its first entry in qt (blocks with a kinb or a K
                                       that depends on q; 0 for the others) */
    uint16_t mo[RT_MAX_BLOCKS];     /* first entry of its M factors in M (all sets) */
    uint16_t co[RT_MAX_BLOCKS];     /* first internal constraint row within its set */
    uint16_t to[RT_MAX_BLOCKS + 1]; /* its touches: trow[to[b] .. to[b+1]) */
    uint16_t wo[RT_MAX_BLOCKS];     /* first entry of its touches' slices in W */
    uint16_t yo[RT_MAX_BLOCKS];     /* ... in Y (blocks with a dense M only) */
    uint16_t po[RT_MAX_BLOCKS + 1]; /* its pairs of touches: pslot[po[b] .. po[b+1]) */
    uint16_t trow[RT_MAX_MBS_TOUCH];/* constraint rows touching each block, ascending */
    uint16_t pslot[RT_MAX_MBS_PAIRS];/* where each pair (i <= k) of a block's touches adds
                                       to A: an index into lv */
    uint16_t sb[RT_MAX_SETS + 1];   /* each set's MBS blocks: sblk[sb[s] .. sb[s+1]) */
    uint16_t sblk[RT_MAX_BLOCKS];   /* ... in block order */
    uint16_t sj[RT_MAX_SETS + 1];   /* each set's joints: sjnt[sj[s] .. sj[s+1]) */
    uint16_t sjnt[RT_MAX_JOINTS];   /* ... in joint order */
    uint16_t jrow[RT_MAX_JOINTS];   /* first row of each joint within its set */
    uint16_t jw[RT_MAX_JOINTS][2];  /* W slices of its first row in b1's and b2's columns
                                       (its rows follow, nz of the block apart) */
    uint16_t jlo[RT_MAX_JOINTS];    /* first of its multipliers in jlam */
    uint16_t nz[RT_MAX_SETS];       /* velocities of each set's MBS blocks */
    uint16_t nq[RT_MAX_SETS];       /* coordinates of each set's MBS blocks */
    uint16_t nc[RT_MAX_SETS];       /* constraint rows of each set */
    uint8_t need_lambda;            /* the scene records or exports joint reactions */
    uint8_t m_valid[RT_MAX_BLOCKS]; /* bit 0: M of a block with RT_MBS_M_CONST is
                                       factored; bit 1: M^-1 k of its parameters alone is
                                       kept after them (written-out code); 0 after a
                                       parameter change or a restore */
    uint8_t points[RT_MAX_SETS];    /* 1: the set holds points only (rt/mbs.c points_only) */
    uint16_t ndrop[RT_MAX_SETS];    /* rows of each set's A dropped as dependent on others
                                       at its last factorization (its rank deficit) */
    uint16_t drop_row[RT_MAX_SETS]; /* ... the first of them (a set row) */
    /* the sparse LDL^T of each set's A (rt/mbs_ldl.c): rows in elimination order */
    uint16_t rb[RT_MAX_SETS + 1];   /* first row of each set in perm, lp and lv */
    uint16_t perm[RT_MAX_MBS_ROWS]; /* set row eliminated at each position */
    uint16_t lp[RT_MAX_MBS_ROWS + 1];/* row i of L: columns lj[lp[i] .. lp[i+1]) */
    uint16_t lj[RT_MAX_MBS_LNZ];    /* column positions within the set, ascending */

    /* values */
    real_t lv[RT_MAX_MBS_ROWS + RT_MAX_MBS_LNZ]; /* A, then its factors: the diagonal D
                                       (lv[rb[s] + i]), then L (lv[RT_MAX_MBS_ROWS + e]) */
    real_t M[RT_MAX_MBS_M];         /* factors of each block's M (a diagonal M: nz values;
                                       a dense M: nz^2 factors, then nz row pivots) */
    real_t W[RT_MAX_MBS_TW];        /* W = G K: per touch the block's nz columns (the
                                       interpreted path's; written-out code keeps a set
                                       of points' W in a local array) */
    real_t Y[RT_MAX_MBS_TY];        /* M^-1 W^T, transposed like W (dense M only) */
    real_t a[RT_MAX_MBS_Z];         /* forces k, free accelerations M^-1 k, then z' (the
                                       index-1 solve); the correction dz (projection).
                                       The interpreted path's: written-out code of a set
                                       of points writes z' into the derivative and adds
                                       dz where it forms it */
    real_t g[RT_MAX_MBS_C];         /* g [m or 1] */
    real_t gd[RT_MAX_MBS_C];        /* g' */
    real_t gam[RT_MAX_MBS_C];       /* acceleration term of eq. 7b, then the multipliers */
    real_t qt[RT_MAX_MBS_QT];       /* predicted coordinates (projection), kinb scratch */
    real_t J[2][6 * RT_MAX_MBS_JZ]; /* Jacobians of a joint's two nodes */
    real_t jlam[RT_MAX_MBS_JROWS];  /* multipliers of each joint (at jlo), kept only where
                                       a reaction is read (need_lambda) */

    /* statistics (high-water marks for sizing and reports) */
    real_t res_max;       /* largest |g| right after a projection */
    uint32_t projections; /* projections done */
} rt_mbs_work;

/* ------------------------------------------------------------------ services */

/* The multibody services a scene with MBS blocks names (rt_scene.mbs = &rt_mbs). */
typedef struct rt_mbs_ops {
    /* Called at the end of rt_init: checks joints, sizes and recorded MBS signals, builds
       the tables, and projects the initial state (RT_STAB_PROJECT). Returns an rt_status. */
    int (*init)(const struct rt_scene *sc, struct rt_sim *sim);
    /* Fills q' and z' of the set's MBS blocks (index-1 system, eqs. 6a, 6b, 7b, 9) into
       xdot (the set's slice). Called in every right-hand side, after all outputs. */
    void (*accel)(const struct rt_scene *sc, struct rt_sim *sim, uint8_t set, real_t t,
                  real_t *xdot);
    /* Post-stabilizing projection of the set's MBS state at time t (eq. 10), after every
       step of the set when the scene's stab is RT_STAB_PROJECT. */
    void (*project)(const struct rt_scene *sc, struct rt_sim *sim, uint8_t set, real_t t);
    /* Projects the initial state of every set onto its constraints again and judges the
       moves as init does (before the first tick, after rt_set_param changed a block). */
    int (*restart)(const struct rt_scene *sc, struct rt_sim *sim);
    /* Value of the recorded signal {block, RT_SIG_MBS, index} at the current state. */
    real_t (*signal)(const struct rt_scene *sc, const struct rt_sim *sim, uint16_t block,
                     uint16_t index);
    /* Its name (without the block's), e.g. "energy" or "fx". */
    const char *(*signal_name)(const struct rt_scene *sc, uint16_t block, uint16_t index);
} rt_mbs_ops;

/* The services of rt/mbs.c. */
extern const rt_mbs_ops rt_mbs;

#endif /* RT_MBS_H */
