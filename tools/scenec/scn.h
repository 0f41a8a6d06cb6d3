/* scn.h - the scene language of modrt (docs/scene-language.md): the internal interfaces
 * shared by the files of tools/scenec/ (prefix scn_).
 *
 * One compilation is one scn_ctx: the sources (main file and includes), the scene it
 * describes (scn_scene, positions kept for error messages), and, once checked, the
 * rt_scene built from it in host memory. Pipeline:
 *
 *   lex.c    sources, includes, tokens, positions, the error report
 *   parse.c  statements                     -> scn_scene
 *   expr.c   constant expressions, define bodies -> bytecode (scn_ins)
 *   check.c  names, sizes, wiring, sets     -> resolved scn_scene, kinds of defines
 *   image.c  rt_scene in host memory (defines run by vm.c), checked by rt_init
 *   emit.c   the same scene as C const tables (defines as C functions)
 *
 * Scene-level numbers are doubles here and become real_t only in the image or in the
 * generated C (as (real_t)<double literal>), so both paths give the same bits in double
 * and in float builds. Define bodies compute in real_t: the VM and the generated C run
 * the same operations in the same order. */
#ifndef SCN_H
#define SCN_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "rt.h"

/* ------------------------------------------------------------------ limits */

#define SCN_MAX_FILES 64        /* source files of one compilation (main + includes) */
#define SCN_MAX_DEPTH 16        /* include nesting */
#define SCN_MAX_SRC (1u << 20)  /* bytes of one source file */
#define SCN_MAX_NAME 63         /* characters of a name */
#define SCN_MAX_EXPR_DEPTH 64   /* nested parentheses, calls and operators */
#define SCN_MAX_STACK 64        /* VM operand stack of one expression */
#define SCN_MAX_DEFINES 32      /* define statements */
#define SCN_MAX_PORTS 64        /* inputs, outputs, parameters or states of one define */
#define SCN_MAX_LOCALS 128      /* let names of one define */
#define SCN_MAX_STMTS 512       /* statements of all define bodies */
#define SCN_MAX_CODE 16384      /* instructions of all define bodies */
#define SCN_MAX_CONST 4096      /* constants of all define bodies */
#define SCN_MAX_MATRIX 1024     /* entries of one LSS matrix */
#define SCN_MAX_ASSIGN 1024     /* Block.name = value statements */
#define SCN_MAX_RECS RT_MAX_REC /* recorded signals */
#define SCN_MAX_MEMBERS 256     /* set members over all sets */
#define SCN_MSG_LEN 600         /* characters of an error message */
#define SCN_MAX_ERRORS 10       /* errors of independent checks one compilation reports */

/* ------------------------------------------------------------------ positions, names */

typedef struct scn_pos {
    uint16_t file;              /* index into scn_ctx.files */
    uint32_t line, col;         /* 1-based; col counts bytes */
} scn_pos;

typedef struct scn_name {
    const char *s;              /* NUL-terminated (arena) */
    scn_pos pos;                /* where it was written */
} scn_name;

/* Block.port (or Joint.parameter) */
typedef struct scn_ref {
    scn_name block, port;
} scn_ref;

/* ------------------------------------------------------------------ tokens */

typedef enum { SCN_T_EOF = 0, SCN_T_ID, SCN_T_NUM, SCN_T_STR, SCN_T_OP } scn_tok_kind;

typedef struct scn_tok {
    uint8_t kind;               /* scn_tok_kind */
    char op[3];                 /* SCN_T_OP: "(" "<=" ... */
    scn_pos pos;
    const char *raw;            /* the source text of the token */
    uint32_t rawlen;
    const char *s;              /* SCN_T_ID: the name; SCN_T_STR: the unescaped text */
    double num;                 /* SCN_T_NUM: its value */
} scn_tok;

/* ------------------------------------------------------------------ bytecode */

/* Operations of the expression VM (vm.c) and their C forms (emit.c). Operands on a stack
 * of real_t; `a` is the instruction's argument. */
/* a comparison's `a`: which operand is `t` compared with an instant (SCN_OP_TPIECE),
   read through rt_x_at; 0: a plain comparison */
enum { SCN_TSIDE_LEFT = 1, SCN_TSIDE_RIGHT = 2 };
/* a comparison's `a` from this on: a located switch (expr.c state_switch), its mode the
   define's state a - SCN_SW_BASE */
#define SCN_SW_BASE 0x100
#define SCN_OP_LIST(X)                                                              \
    X(SCN_OP_CONST)  /* push k[a] */                                                \
    X(SCN_OP_TIME)   /* push t [s] */                                               \
    X(SCN_OP_TPIECE) /* push t_piece [s]: t compared with an instant (a time event; \
                        the comparison's a: SCN_TSIDE_*) */                         \
    X(SCN_OP_STEP)   /* push h: the step of the call [s] */                         \
    X(SCN_OP_IN)     /* push u[a] */                                                \
    X(SCN_OP_PAR)    /* push p[a] */                                                \
    X(SCN_OP_STATE)  /* push x[a] (continuous) */                                   \
    X(SCN_OP_DSTATE) /* push d[a] (discrete) */                                     \
    X(SCN_OP_LOC)    /* push local a */                                             \
    X(SCN_OP_NEG) X(SCN_OP_NOT)                                                     \
    X(SCN_OP_ADD) X(SCN_OP_SUB) X(SCN_OP_MUL) X(SCN_OP_DIV)                         \
    X(SCN_OP_LT) X(SCN_OP_LE) X(SCN_OP_GT) X(SCN_OP_GE) X(SCN_OP_EQ) X(SCN_OP_NE)   \
    X(SCN_OP_AND) X(SCN_OP_OR)                                                      \
    X(SCN_OP_SEL)    /* c a b -> c != 0 ? a : b */                                  \
    X(SCN_OP_CALL)   /* function scn_fns[a] on its arguments */                     \
    X(SCN_OP_OUT)    /* pop into the service's output a (y, xdot or next state) */  \
    X(SCN_OP_SETLOC) /* pop into local a */

typedef enum {
#define SCN_X_ENUM(id) id,
    SCN_OP_LIST(SCN_X_ENUM)
#undef SCN_X_ENUM
    SCN_OP_COUNT
} scn_op;

typedef struct scn_ins {
    uint8_t op;                 /* scn_op */
    uint16_t a;                 /* argument */
} scn_ins;

/* Elementary functions of define bodies: rt_math.h, one row each. */
typedef struct scn_fn {
    const char *name;           /* as written in a scene */
    uint8_t nargs;              /* 1 or 2 */
    real_t (*f1)(real_t);
    real_t (*f2)(real_t, real_t);
    const char *c;              /* the C function the generated code calls */
} scn_fn;
extern const scn_fn scn_fns[];  /* ends with a row whose name is NULL */

/* A service program for the VM: the statements of one service of a define, flattened. */
typedef struct scn_prog {
    const scn_ins *ins;
    uint32_t n;
    const real_t *k;            /* constants, as real_t */
    uint16_t nloc;              /* locals of the define */
} scn_prog;

/* rt_kind.spec of an interpreted define: one program per service. */
typedef struct scn_vm_spec {
    scn_prog out, der, upd, roots;
    scn_prog tev;               /* the instants `t` is compared with (ntev values) */
    uint16_t ntev;
    scn_prog band;              /* the sin and cos arguments affine in `t` (nband values) */
    uint16_t nband;
    const scn_prog *event;      /* one handler program per root */
    const scn_prog *rest_t;     /* per root: its shortest flight (n = 0: no rest clause) */
    const scn_prog *rest;       /* per root: its rest handler */
    const uint16_t (*sw)[2];    /* the located switches (scn_define.swm) */
    uint16_t nsw;
} scn_vm_spec;

/* VM services (vm.c): the rt_kind slots of interpreted defines; they read a->spec. */
void scn_vm_output(const rt_args *a, real_t *y);
void scn_vm_deriv(const rt_args *a, real_t *xdot);
void scn_vm_update(const rt_args *a, real_t *dnext);
void scn_vm_roots(const rt_args *a, real_t *r);
void scn_vm_event(const rt_args *a, uint16_t which, real_t *x, real_t *d);
int scn_vm_instant(const rt_args *a, real_t *x, real_t *d);
real_t scn_vm_next(const rt_args *a);
real_t scn_vm_band(const rt_args *a);

/* ------------------------------------------------------------------ the scene */

/* names of the interpolation schemes (rt_interp) of signals that cross sets */
extern const char *const scn_interp_key[RT_INTERP_COUNT];

typedef enum { SCN_DEF_SS = 0, SCN_DEF_LSS, SCN_DEF_DSS } scn_def_type;
typedef enum {
    SCN_ST_LET = 0, SCN_ST_OUT, SCN_ST_DER, SCN_ST_NEXT,
    SCN_ST_ROOT,                /* the root function `when (...)`, index: the root */
    SCN_ST_EVENT,               /* a state assignment of root `root`'s handler */
    SCN_ST_REST_T,              /* the shortest flight of `rest (...)`, index: the root */
    SCN_ST_REST,                /* a state assignment of root `root`'s rest handler */
    SCN_ST_TEV,                 /* an instant `t` is compared with (a known time event),
                                   index: the instant */
    SCN_ST_BAND                 /* the argument of a sin or cos that is affine in `t` (its
                                   angular frequency: rt_kind.band), index: the argument */
} scn_stmt_kind;

/* a port, parameter or state of a define, with its default value */
typedef struct scn_var {
    scn_name name;
    double init;                /* default parameter or initial state (0 if none) */
} scn_var;

/* one statement of a define body: code [code0, code1) then SETLOC or OUT */
typedef struct scn_stmt {
    uint8_t kind;               /* scn_stmt_kind */
    uint16_t index;             /* local, output or state index */
    uint32_t code0, code1;      /* its instructions in scn_scene.code (terminator incl.) */
    scn_pos pos;
    uint16_t root;              /* SCN_ST_EVENT, _REST: the root whose handler it belongs to */
} scn_stmt;

typedef struct scn_matrix {
    double *v;                  /* rows*cols, row-major */
    uint16_t rows, cols;
    scn_pos pos;                /* the '[' */
    uint8_t given;
} scn_matrix;

#define SCN_MAX_INV 8           /* invariants of one define */
#define SCN_MAX_TEV 64          /* instants `t` is compared with in one define's body */
#define SCN_MAX_BAND 64         /* sin and cos of t in one define's body (its band) */
#define SCN_MAX_INV_N 16        /* states of one invariant */

/* invariants (nonnegative (a, b) [within (tol)], sum (a, b) = c, norm (a, b) <= c) */
typedef struct scn_inv {
    uint8_t type;               /* rt_inv_type */
    uint8_t n;
    scn_name x[SCN_MAX_INV_N];  /* state names */
    double c, tol;              /* the sum or bound; tolerance (0: RT_INV_TOL) */
} scn_inv;

typedef struct scn_define {
    scn_name name;
    uint8_t type;               /* scn_def_type */
    scn_var u[SCN_MAX_PORTS], y[SCN_MAX_PORTS], p[SCN_MAX_PORTS], x[SCN_MAX_PORTS];
    uint16_t nu, ny, np, nx;
    scn_name loc[SCN_MAX_LOCALS];
    uint16_t nloc;
    double period;              /* DSS default sample period [s]; 0: none */
    scn_pos period_pos;
    uint32_t st0, st1;          /* its statements in scn_scene.st */
    int8_t rdir[SCN_MAX_PORTS]; /* root directions of `when`: -1 falling, +1 rising, 0 both */
    uint8_t rest[SCN_MAX_PORTS];/* 1: the `when` has a rest clause */
    uint16_t nr;                /* roots (`when` statements, then two per switch) */
    uint16_t nsw;               /* comparisons of states made located switches (state_switch) */
    uint32_t sw[SCN_MAX_PORTS][3]; /* each one's sides, code [0, 1) and [1, 2), and [2] its
                                   comparison instruction */
    int16_t sw_let[SCN_MAX_PORTS]; /* the let it is in, -1: a derivative */
    scn_pos sw_pos[SCN_MAX_PORTS]; /* where its operator is */
    const char *sw_op[SCN_MAX_PORTS]; /* and its text */
    uint8_t loc_logic[SCN_MAX_LOCALS]; /* 1: let i holds a truth value (state_switch) */
    uint8_t loc_step[SCN_MAX_LOCALS]; /* 1: let i reads h (state_switch) */
    uint8_t loc_fixed[SCN_MAX_LOCALS]; /* 1: let i is fixed during the run (state_switch) */
    uint8_t sw_over[SCN_MAX_LOCALS]; /* 1: let i holds a comparison of states past the
                                       SCN_MAX_PORTS noted (finish_switches) */
    uint8_t sw_over_der;        /* 1: an output or a derivative does */
    scn_pos sw_over_pos[SCN_MAX_LOCALS + 1]; /* the first such in let i, [SCN_MAX_LOCALS]: */
    const char *sw_over_op[SCN_MAX_LOCALS + 1]; /* in a derivative; its operator */
    uint16_t nswm;              /* the switches made (finish_switches; one in a let no
                                   derivative reads stays a plain comparison) */
    uint16_t swm[SCN_MAX_PORTS][2]; /* each made one's mode state and rising root */
    uint16_t ntev;              /* instants `t` is compared with (SCN_ST_TEV statements) */
    uint16_t nband;             /* sin and cos arguments affine in `t` (SCN_ST_BAND) */
    scn_matrix A, B, C, D;      /* LSS */
    scn_inv inv[SCN_MAX_INV];   /* invariants (...) */
    uint8_t ninv;
    /* derived by check.c */
    rt_kind *kind;              /* sizes, names, defaults, feed (no services) */
    uint8_t *feed;              /* ny*nu: output i depends directly on input j */
} scn_define;

typedef struct scn_block {
    scn_name name, type;
    const char *unit;           /* from file ("unit"), or NULL */
    double ts;                  /* sample period [s] (DSS); 0: not given */
    scn_pos ts_pos;
    /* resolved */
    const rt_kind *kind;        /* library kind, or the define's kind */
    int16_t def;                /* index of its define, -1 for a library kind */
    int16_t set;                /* index of its set, -1 before sets are resolved */
    double *p, *x0, *d0;        /* values: kind defaults, then assignments */
    uint16_t *p_at, *x_at, *d_at, *u_at; /* assignment index + 1 of each value, 0: none */
    uint8_t p_given, x_given, d_given;   /* any assignment: emit the array */
    int16_t *u_conn;            /* connection driving each input, -1: none */
    uint8_t fmu;                /* 1: an FMU system (kind from scn_fmu_ops) */
} scn_block;

typedef struct scn_joint {
    scn_name name, type;
    const char *unit;
    const rt_joint_kind *kind;
    double *p;
    uint16_t *p_at;             /* assignment index + 1 of each parameter, 0: none */
    int16_t link;               /* index of its link statement, -1: not linked yet */
    double axis[3];             /* J.axis = (x, y, z): the joint's axis in both node frames */
    uint16_t axis_at;           /* its assignment index + 1, 0: none (the z axis) */
    double axis_S[9];           /* resolved: the joint frame, third column the unit axis */
} scn_joint;

typedef struct scn_conn {
    scn_ref from, to;
    uint8_t interp;             /* rt_interp; RT_INTERP_SET: the destination set's */
    uint16_t fb, fy, tb, tu;    /* resolved: block and port indices */
} scn_conn;

typedef struct scn_assign {
    scn_ref lhs;
    double v;
    double vec[3];              /* a direction (x, y, z): J.axis */
    uint8_t is_vec;
} scn_assign;

typedef struct scn_default {
    uint16_t b, u;
    double v;
} scn_default;

typedef struct scn_link {
    scn_ref a, b;               /* node a of block a, node b of block b */
    uint8_t ground;             /* b is the inertial frame */
    double at[3];               /* ground position [m] */
    uint8_t has_at;
    double turn[4];             /* rotated (angle deg|rad about (x, y, z)): [rad], axis */
    scn_pos turn_pos;
    uint8_t has_turn;
    double at_S[9];             /* resolved: the anchor's rotation, row-major */
    scn_name joint;
    /* resolved */
    int16_t b1, n1, b2, n2;
} scn_link;

typedef struct scn_set {
    scn_name name, method;
    double step;                /* [s], or ticks if step_ticks */
    uint8_t step_ticks, has_step;
    scn_pos step_pos;
    uint8_t interp;             /* rt_interp of inputs from other sets (0: hold) */
    uint8_t has_members;
    uint16_t m0, m1;            /* its members in scn_scene.members */
    rt_set_cfg cfg;             /* its settings (RT_SET_CFG_LIST), as rt_set.cfg */
    uint8_t has_cfg[RT_CFG_N];  /* a clause (or accuracy's second value) gave it */
    scn_pos cfg_pos[RT_CFG_N];  /* where */
    uint8_t background;         /* 1: steps below the tick (rt_set.background) */
    /* resolved */
    const rt_integrator *m;
    uint32_t ratio;
} scn_set;

typedef struct scn_rec {
    scn_ref sig;
    int8_t want;                /* -1 any, else rt_sig_kind asked for (state, output...) */
    rt_rec r;                   /* resolved */
} scn_rec;

typedef struct scn_scene {
    scn_name name;              /* scene (name); from the file name if absent */
    const char *doc;
    double dt, t_end;
    uint8_t has_dt, has_end, has_name;
    scn_pos dt_pos, end_pos;
    /* loops and multibody options */
    scn_name solver;            /* solve loops by (broyden) */
    uint32_t loop_iter;
    double loop_tol;
    scn_name stab;              /* stabilization (project|none|baumgarte) */
    double alpha, beta;
    uint8_t stab_kind;          /* rt_stab */

    scn_define *def[SCN_MAX_DEFINES]; /* arena: only the defines written */
    uint16_t ndef;
    scn_block blk[RT_MAX_BLOCKS];
    uint16_t nblk;
    scn_joint jnt[RT_MAX_JOINTS];
    uint16_t njnt;
    scn_conn conn[RT_MAX_U];
    uint16_t nconn;
    scn_assign asg[SCN_MAX_ASSIGN];
    uint16_t nasg;
    scn_default dflt[RT_MAX_U];
    uint16_t ndflt;
    scn_link lnk[RT_MAX_JOINTS];
    uint16_t nlnk;
    scn_set set[RT_MAX_SETS];
    uint16_t nset;
    scn_name members[SCN_MAX_MEMBERS];
    uint16_t nmembers;
    scn_rec rec[SCN_MAX_RECS];
    uint16_t nrec;

    /* the controller link: export (refs) to (C); import (names) from (C) [every (t)];
       resolved by check.c into link (docs/link.md) */
    scn_name ctl_exp, ctl_imp;  /* the controller each statement names (.s NULL: none) */
    scn_rec lexp[SCN_MAX_RECS];
    uint16_t nlexp;
    scn_var limp[SCN_MAX_PORTS]; /* import names and defaults */
    uint8_t lpol[SCN_MAX_PORTS]; /* their rt_link_policy */
    uint16_t nlimp;
    double lperiod;             /* exchange period [s] */
    rt_rec lexp_r[SCN_MAX_RECS];
    real_t ldef[SCN_MAX_PORTS];
    rt_link link;               /* resolved; link.name NULL: the scene has no link */

    /* define bodies */
    scn_stmt st[SCN_MAX_STMTS];
    uint32_t nst;
    scn_ins code[SCN_MAX_CODE];
    uint32_t ncode;
    double k[SCN_MAX_CONST];
    uint32_t nk;
} scn_scene;

/* ------------------------------------------------------------------ one compilation */

typedef struct scn_file {
    const char *path;           /* as opened (the main file as given) */
    const char *real;           /* resolved path for recursion checks */
    const char *text;
    size_t len;
    uint8_t generated;          /* 1: text the compiler made (scn_push_text), no file */
} scn_file;

typedef struct scn_lexer {
    uint16_t file;
    size_t off;
    uint32_t line, col;
} scn_lexer;

typedef struct scn_chunk scn_chunk;

/* FMU systems (`load system (P) of type (fmu) from file ("p.fmu");`, docs/fmi.md): the
   host's loader (tools/fmi/fmu_scn.c), named by the tools that read FMUs (modrt, scenec) */
typedef struct scn_fmu_ops {
    /* the kind of FMU block `block` read from the file at path: its own kind, its services
       driving an instance of its own. NULL with a one-line message in err */
    const rt_kind *(*kind)(const char *path, const char *block, char *err, size_t n);
    /* instantiates and initializes the FMU of kind k with parameters p and, where given[i],
       initial state x0[i]; writes the states it starts from into x0. 0, or -1 with err */
    int (*start)(const rt_kind *k, const real_t *p, real_t *x0, const uint8_t *given,
                 char *err, size_t n);
    /* writes the C of the started FMU block of kind k for an image (fmu_<block>_kind);
       0, or -1 with err (an FMU without sources) */
    int (*emit)(FILE *f, const rt_kind *k, char *err, size_t n);
} scn_fmu_ops;

typedef struct scn_ctx {
    /* options */
    const char *incdirs[8];     /* -I directories searched after the includer's */
    uint8_t nincdirs;
    uint8_t sandbox;            /* 1: includes never touch the file system (fuzzing) */
    const scn_fmu_ops *fmu;     /* FMU systems; NULL: this tool reads none */
    /* sources and tokens */
    scn_file files[SCN_MAX_FILES];
    uint16_t nfiles;
    scn_lexer lx[SCN_MAX_DEPTH + 1];
    uint8_t depth;              /* lx[depth] is the file being read */
    scn_tok tok;                /* the current token */
    uint32_t edepth;            /* expression nesting */
    uint32_t sdepth, smax;      /* VM stack depth of the expression being compiled */
    struct scn_define *def;     /* the define whose body is being parsed */
    uint16_t when;              /* 1 + the root whose handler or rest is being parsed (its
                                   t_last is readable there); 0: none */
    uint16_t after_when;        /* 1 + the root of a `when` the last body statement was
                                   (a rest clause may follow it); 0: none */
    uint32_t tev[SCN_MAX_TEV + SCN_MAX_BAND][5]; /* code [0, 1) of the instants the
                                   statement being compiled compares `t` with, and of its sin
                                   and cos arguments affine in `t`, made statements of kind
                                   [2] (SCN_ST_TEV, SCN_ST_BAND) after it; where `t` enters
                                   the comparison as a t + b, code [3, 4) is that side (the
                                   instant is ([0, 1) - b) / a) and [0, 1) the other */
    uint16_t ntev;
    uint8_t st_kind;            /* the kind (SCN_ST_*) of the statement being compiled */
    /* the error of the check under way (err, its position), the errors of independent
       checks before it (scn_keep_error), and at the end all of them, one per line, in the
       order of the file (msg) */
    int err;
    char msg[SCN_MSG_LEN * (SCN_MAX_ERRORS + 1)];
    scn_pos err_pos;
    char kept[SCN_MAX_ERRORS][SCN_MSG_LEN];
    scn_pos kept_pos[SCN_MAX_ERRORS];
    uint16_t nkept, nlost;
    /* memory */
    scn_chunk *chunks;
    /* the scene, and what image.c builds from it */
    scn_scene sc;
    rt_scene image;
    rt_sim *sim;
} scn_ctx;

/* ------------------------------------------------------------------ entry points */

/* Creates a context (NULL when out of memory); scn_free releases it and all it built. */
scn_ctx *scn_new(void);
void scn_free(scn_ctx *c);
/* Compiles the scene file `path` (or, if text is not NULL, the text given for it):
   parse, check, build the host image, run rt_init on it. Returns 0, or -1 with the
   message in c->msg ("file:line:col: error: ... near '...'; expected ..."). */
int scn_compile(scn_ctx *c, const char *path, const char *text, size_t len);
/* Writes the scene as C (const tables, define services) to f; returns 0 or -1. */
int scn_emit(scn_ctx *c, FILE *f);
/* spec.c: the scene's specialized code (rt_scene_code); 1 if it wrote any */
int scn_emit_code(FILE *f, const scn_ctx *c);
/* The C symbol of the compiled scene: "mdl_scene_<name>". */
#define SCN_SYMBOL_PREFIX "mdl_scene_"

/* ------------------------------------------------------------------ internal (lex.c) */

void *scn_alloc(scn_ctx *c, size_t n);                  /* zeroed arena memory */
char *scn_strndup(scn_ctx *c, const char *s, size_t n);
char *scn_fmt(scn_ctx *c, const char *fmt, ...);        /* arena-formatted text */
/* "fewer: <rt_limit_text>, the host CLI's limit (...)": what a scene past limit lim
   of the host build is told, after "too many <items>" */
char *scn_limit(scn_ctx *c, rt_limit lim);
/* Records the first error: "<file>:<line>:<col>: error: <what> near '<near>'; expected
   <expected>". Later calls are ignored, so a caller may simply return afterwards. */
void scn_fail(scn_ctx *c, scn_pos pos, const char *near, const char *what,
              const char *expected);
/* The same at the current token. */
void scn_fail_tok(scn_ctx *c, const char *what, const char *expected);
/* Keeps the pending error (if any) and clears it, so that a check that does not depend on
   the one that failed runs and reports its own error too (at most SCN_MAX_ERRORS). */
void scn_keep_error(scn_ctx *c);
/* Errors so far: kept, lost past the limit and pending. */
unsigned scn_error_count(const scn_ctx *c);
/* Ends a run of independent checks: every error kept, in the order of the file, becomes
   msg (one per line) and err is set; returns -1 if there was one, else 0. */
int scn_report_errors(scn_ctx *c);
const char *scn_near(scn_ctx *c, const scn_tok *t);     /* a token's text for messages */
const char *scn_path(const scn_ctx *c, scn_pos pos);    /* file of a position */
int scn_open_main(scn_ctx *c, const char *path, const char *text, size_t len);
/* Opens `name` (as written in an include at pos) and reads on from its first token. */
int scn_push_include(scn_ctx *c, const char *name, scn_pos pos);
/* reads generated text next, as if included (the statements an import expands to) */
int scn_push_text(scn_ctx *c, const char *label, const char *text, scn_pos pos);
void scn_pop_include(scn_ctx *c);
void scn_next(scn_ctx *c);                              /* reads the next token */
/* Comma-separated names for "expected" texts (at most max, then "..."). */
char *scn_list(scn_ctx *c, const char *const *names, size_t n, size_t max);

/* ------------------------------------------------------------------ internal (others) */

int scn_parse(scn_ctx *c);                              /* parse.c: all statements */
/* expr.c: token tests and expectations shared by the parsers */
int scn_is_op(const scn_ctx *c, const char *op);
int scn_is_word(const scn_ctx *c, const char *w);
int scn_accept_op(scn_ctx *c, const char *op);
void scn_expect_op(scn_ctx *c, const char *op);
void scn_expect_word(scn_ctx *c, const char *w);
/* A name; on anything else a syntax error expecting `what`. */
scn_name scn_expect_name(scn_ctx *c, const char *what);
/* A constant expression (numbers, pi, + - * /, parentheses) evaluated in double. */
double scn_const_expr(scn_ctx *c);
/* The body of define d, after its `by`: statements up to the closing '}'. */
void scn_parse_body(scn_ctx *c, scn_define *d);
/* An LSS matrix [a, b; c, d]. */
void scn_parse_matrix(scn_ctx *c, scn_matrix *m);
int scn_check(scn_ctx *c);                              /* check.c */
/* check.c: look-ups (-1 when not found) and texts for messages */
int scn_find_block(const scn_scene *s, const char *name);
int scn_find_joint(const scn_scene *s, const char *name);
int scn_find_name(const char *const *names, uint16_t n, const char *name);
int scn_block_of(scn_ctx *c, scn_name n);               /* -1 with an error */
const rt_kind *scn_library_kind(const char *name);
const char *scn_where(scn_ctx *c, scn_pos p);           /* "file:line:col" */
const char *scn_block_list(scn_ctx *c, int joints);
const char *scn_kind_desc(scn_ctx *c, const scn_block *b);
/* sets.c: sets, the links of multibody joints (link(A.n, B.m) by (J)), sample periods,
   recorded signals, parameter ranges, loop and stabilization options */
void scn_check_sets(scn_ctx *c);
void scn_check_joint_links(scn_ctx *c);
void scn_check_rest(scn_ctx *c);
/* resolves a recorded (or exported) signal reference into r->r (sets.c) */
void scn_resolve_rec(scn_ctx *c, scn_rec *r);
/* resolves the controller link (export/import) into c->sc.link, after scn_check_rest
   (link.c) */
void scn_check_ctl_link(scn_ctx *c);
/* sets.c: marks in[i] for the statements d->st0 + i of one service (SCN_ST_OUT, _DER or
   _NEXT): its own, and the lets they need, directly or through other lets */
void scn_service(const scn_ctx *c, const scn_define *d, uint8_t kind, uint8_t *in);
/* the same for the handler of root r (its SCN_ST_EVENT statements and the lets they use);
   kind SCN_ST_REST_T or SCN_ST_REST: its rest clause's flight time or handler */
void scn_service_event(const scn_ctx *c, const scn_define *d, uint16_t r, uint8_t *in);
void scn_service_root(const scn_ctx *c, const scn_define *d, uint8_t kind, uint16_t r,
                      uint8_t *in);
/* the initial t_last of a root: far in the past, so a first crossing never rests */
#define SCN_T_LAST0 (-1e30)
int scn_build_image(scn_ctx *c);                        /* image.c */
/* fmu.c: the kind of an FMU system (NULL with an error), and the start of every FMU
   system once the scene's values are known (their initial states into x0) */
const rt_kind *scn_fmu_kind(scn_ctx *c, scn_block *b);
void scn_fmu_start(scn_ctx *c);
/* The C literal of a double that reads back as the same double ("0.1", "-2", "1e-300"). */
void scn_real_literal(double v, char *buf, size_t n);

#endif /* SCN_H */
