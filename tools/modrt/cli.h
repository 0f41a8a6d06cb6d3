/* cli.h - the command-line conventions of the modrt applications: subcommands as rows of
 * a const table, GNU-style options (in any order with the positional arguments,
 * `--opt value` or `--opt=value`, `--` ends the options), `--help` per subcommand on
 * stdout with exit 0, and one line on stderr with exit 2 for every bad argument.
 * Exit codes: CLI_OK (0), CLI_FAULTS (1: a run failed: NaN, instability, a degraded
 * step, a lost link...), CLI_USAGE (2), CLI_DOUBTFUL (3: the run completed but a step's
 * error estimate or a deadline was exceeded): rt_status_severity of the run's status;
 * CLI_IO (4: an output file could not be opened or written: the CSV, the replay log, the
 * real-time log), CLI_INTERRUPTED (5: SIGINT or SIGTERM ended the run before its end). */
#ifndef CLI_H
#define CLI_H

#include "rt.h"

enum { CLI_OK = 0, CLI_FAULTS = 1, CLI_USAGE = 2, CLI_DOUBTFUL = 3, CLI_IO = 4, CLI_INTERRUPTED = 5 };

#define CLI_POS_MAX 8 /* positional arguments of one subcommand */

/* One option of a subcommand. The handler checks the value and stores it in the
   subcommand's context; it returns CLI_OK or CLI_USAGE after printing one line (cli_fail). */
typedef struct cli_opt {
    const char *name;   /* long name without the dashes, e.g. "t-end" */
    const char *arg;    /* placeholder of its value in the help ("S", "FILE"); NULL: a flag */
    const char *help;   /* one line */
    int (*set)(void *ctx, const char *val); /* val is NULL for a flag */
} cli_opt;

/* One subcommand: `modrt NAME ARGS [options]`. */
typedef struct cli_cmd {
    const char *name;    /* e.g. "run" */
    const char *args;    /* synopsis of the positional arguments, e.g. "SCENE" */
    const char *summary; /* what it does, one line (the usage list) */
    const char *help;    /* more text for `modrt NAME --help` (may be NULL) */
    const cli_opt *opts; /* options, ending in a row with name NULL; NULL: none */
    uint8_t npos_min, npos_max; /* positional arguments accepted */
    void *ctx;           /* the context the option handlers fill */
    int (*run)(void *ctx, int npos, char **pos);
} cli_cmd;

/* Parses argv[0..argc) (the words after the subcommand) against c's options, collects
   the positional words into pos, and runs c. Returns the exit code. */
int cli_dispatch(const cli_cmd *c, int argc, char **argv);
/* Prints `modrt: what: detail` (detail may be NULL) on stderr; returns CLI_USAGE. */
int cli_fail(const char *what, const char *detail);
/* A whole string as a finite number; 1 on success. */
int cli_real(const char *s, double *v);
/* A whole string as an unsigned integer in [lo, hi]; 1 on success. */
int cli_uint(const char *s, unsigned long lo, unsigned long hi, unsigned long *v);
/* The registered scene called name, or a scene file (FILE.scn, compiled in memory).
   NULL after one error line on stderr. */
const rt_scene *cli_scene(const char *name);
/* Prints a real in the shortest form that reads back to the same value. */
const char *cli_fmt(char *buf, size_t n, double v);
/* The exit code of a run whose worst status has severity sev (rt_status_severity):
   CLI_OK, CLI_DOUBTFUL or CLI_FAULTS. */
int cli_exit_code(int sev);
/* `--set BLOCK.PARAM=VALUE` onto the initialised sim. CLI_OK, or CLI_USAGE after one
   line that says what is wrong (the runtime's reason when it gives one). */
int cli_set_param(const rt_scene *sc, rt_sim *sim, const char *arg);
/* rt_refresh after the --set values: the initial state they make is judged as rt_init
   judges a scene's (a body off its joints, a mode against its state); CLI_OK or the
   refusal on stderr */
int cli_refresh(const rt_scene *sc, rt_sim *sim);
/* The end time t_end [s] onto sc: a whole number of its base ticks (within rt_init's
   slack, RT_TICK_SLACK) and at most RT_MAX_TICKS of them. CLI_OK, or CLI_USAGE after one
   line "WHAT must be ..." (what: the option or the file that asked for it). */
int cli_end_time(rt_scene *sc, double t_end, const char *what);
/* "Block.signal", the name of recorded signal i, into buf. */
void cli_rec_name(const rt_scene *sc, uint16_t i, char *buf, size_t n);
/* 1 when name starts with one of the comma-separated prefixes of list (NULL: all). */
int cli_selected(const char *name, const char *list);

#endif /* CLI_H */
