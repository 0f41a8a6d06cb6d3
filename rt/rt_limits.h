/* rt_limits.h - the default of every capacity limit, written from RT_LIMIT_LIST
 * (rt_config.h) by tests/static/limit_defaults.py --write: edit the list, not this file
 * (make test-static fails when they differ). A build overrides any with -DRT_MAX_<NAME>. */
#ifndef RT_LIMITS_H
#define RT_LIMITS_H

/* blocks */
#ifndef RT_MAX_BLOCKS
#define RT_MAX_BLOCKS 64
#endif

/* continuous states */
#ifndef RT_MAX_X
#define RT_MAX_X 256
#endif

/* discrete states */
#ifndef RT_MAX_D
#define RT_MAX_D 64
#endif

/* block inputs */
#ifndef RT_MAX_U
#define RT_MAX_U 256
#endif

/* block outputs */
#ifndef RT_MAX_Y
#define RT_MAX_Y 256
#endif

/* parameters */
#ifndef RT_MAX_P
#define RT_MAX_P 512
#endif

/* state-event root functions (a when: one, a located switch: two) */
#ifndef RT_MAX_ROOTS
#define RT_MAX_ROOTS 48
#endif

/* integration sets */
#ifndef RT_MAX_SETS
#define RT_MAX_SETS 4
#endif

/* recorded signals */
#ifndef RT_MAX_REC
#define RT_MAX_REC 64
#endif

/* algebraic loops */
#ifndef RT_MAX_LOOPS
#define RT_MAX_LOOPS 8
#endif

/* torn loop inputs */
#ifndef RT_MAX_TORN
#define RT_MAX_TORN 16
#endif

/* states of a set with an implicit method */
#ifndef RT_MAX_IMPLICIT_N
#define RT_MAX_IMPLICIT_N 64
#endif

/* states of a set with the transition method */
#ifndef RT_MAX_TRANSITION_N
#define RT_MAX_TRANSITION_N 8
#endif

/* outputs read by another set */
#ifndef RT_MAX_HIST_Y
#define RT_MAX_HIST_Y RT_MAX_Y
#endif

/* outputs of sets stepping over several ticks */
#ifndef RT_MAX_HELD_Y
#define RT_MAX_HELD_Y RT_MAX_Y
#endif

/* recorded and exported multibody signals of sets stepping over several ticks */
#ifndef RT_MAX_HELD_SIG
#define RT_MAX_HELD_SIG RT_MAX_REC
#endif

/* states of a set with roots */
#ifndef RT_MAX_EVENT_X
#define RT_MAX_EVENT_X RT_MAX_X
#endif

/* entries of the evaluation sequence */
#ifndef RT_MAX_SEQ
#define RT_MAX_SEQ (RT_MAX_Y + RT_MAX_BLOCKS)
#endif

/* entries of the loops' iteration histogram */
#ifndef RT_MAX_LOOP_HIST
#define RT_MAX_LOOP_HIST (RT_LOOP_ITER_LIMIT + 1)
#endif

/* states and outputs of a background set */
#ifndef RT_MAX_BG
#define RT_MAX_BG 512
#endif

/* inputs extrapolated from another set */
#ifndef RT_MAX_XPRED
#define RT_MAX_XPRED RT_MAX_U
#endif

/* sets with known time events */
#ifndef RT_MAX_TEV
#define RT_MAX_TEV RT_MAX_SETS
#endif

/* bytes of the blocks' internal state in a snapshot */
#ifndef RT_MAX_KSTATE
#define RT_MAX_KSTATE 16384
#endif

/* joints */
#ifndef RT_MAX_JOINTS
#define RT_MAX_JOINTS 32
#endif

/* generalized velocities of a multibody set */
#ifndef RT_MAX_MBS_Z
#define RT_MAX_MBS_Z 64
#endif

/* generalized coordinates of a multibody set */
#ifndef RT_MAX_MBS_Q
#define RT_MAX_MBS_Q 80
#endif

/* constraints of a multibody set */
#ifndef RT_MAX_MBS_C
#define RT_MAX_MBS_C 40
#endif

/* generalized velocities of a multibody block */
#ifndef RT_MAX_MBS_BZ
#define RT_MAX_MBS_BZ 16
#endif

/* constraint rows of all sets */
#ifndef RT_MAX_MBS_ROWS
#define RT_MAX_MBS_ROWS (RT_MAX_MBS_C * RT_MAX_SETS)
#endif

/* (block, constraint row) pairs that can be non-zero in W */
#ifndef RT_MAX_MBS_TOUCH
#define RT_MAX_MBS_TOUCH (2 * RT_MAX_MBS_ROWS)
#endif

/* entries of W kept */
#ifndef RT_MAX_MBS_TW
#define RT_MAX_MBS_TW (RT_MAX_MBS_C * RT_MAX_MBS_Z)
#endif

/* coordinates with a q-dependent K or a kinb */
#ifndef RT_MAX_MBS_QT
#define RT_MAX_MBS_QT RT_MAX_MBS_Q
#endif

/* entries of M^-1 W^T kept */
#ifndef RT_MAX_MBS_TY
#define RT_MAX_MBS_TY RT_MAX_MBS_TW
#endif

/* entries of W M^-1 W^T that blocks contribute */
#ifndef RT_MAX_MBS_PAIRS
#define RT_MAX_MBS_PAIRS (RT_MAX_MBS_C * (RT_MAX_MBS_C + 1) / 2)
#endif

/* off-diagonal non-zeros of the LDL^T factors */
#ifndef RT_MAX_MBS_LNZ
#define RT_MAX_MBS_LNZ (RT_MAX_MBS_C > 1 ? RT_MAX_MBS_C * (RT_MAX_MBS_C - 1) / 2 : 1)
#endif

/* entries of the mass matrices' factors */
#ifndef RT_MAX_MBS_M
#define RT_MAX_MBS_M (RT_MAX_MBS_Z * (RT_MAX_MBS_BZ + 1))
#endif

/* rows of the joints' constraints */
#ifndef RT_MAX_MBS_JROWS
#define RT_MAX_MBS_JROWS (RT_MAX_JOINTS * 6)
#endif

/* velocities of a block whose nodes have Jacobians */
#ifndef RT_MAX_MBS_JZ
#define RT_MAX_MBS_JZ RT_MAX_MBS_BZ
#endif

#endif /* RT_LIMITS_H */
