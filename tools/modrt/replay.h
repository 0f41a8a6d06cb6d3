/* replay.h - the scene of a replay log set up as its live run was (`modrt replay`, and a
 * campaign's replay runs, `modrt sweep`): the log's scene, end time and options, refused
 * when the build, the scene's fingerprint or the log's schedule do not match. */
#ifndef MODRT_REPLAY_H
#define MODRT_REPLAY_H

#include "mrlog.h"
#include "rt.h"
#include "study.h"

/* What a campaign changes on top of the live run's options (NULL: nothing). The log's
   identity is checked against the scene as recorded, before these apply. */
typedef struct replay_more {
    double t_end;              /* < 0: the log's end time */
    const study_args *study;   /* per-set overrides after the log's, or NULL */
    const char *const *sets;   /* BLOCK.PARAM=VALUE after the log's */
    int nsets;
} replay_more;

/* The scene of the open log h (read from path), initialised into sim as the live run was,
   then with more's overrides: CLI_OK, or CLI_USAGE after one line that says what does not
   match (another build, another scene or version of it, a record the run never applies,
   a bad option). sc's sets may point at study.c's copy until the next study_apply. */
int replay_scene(const mrl_header *h, const char *path, const replay_more *more, rt_scene *sc,
                 rt_sim *sim);

/* where a replay stops: the tick the recorded run reached when a signal or `--overrun stop`
   ended it between two ticks (a version-3 log's end marker), or NULL: at its end (a link's
   stop policy ends the replay at its exchange instead) */
const uint64_t *replay_stop_tick(const mrl_header *h);

/* how a replay that reached that tick ends, as the recorded run ended: the signal that
   interrupted it (SIGINT, SIGTERM: the run's summary says "interrupted", its exit status
   is 5), or 0 and, after `--overrun stop`, RT_E_STOPPED noted as the run's status; 0 for a
   replay that stopped elsewhere. `modrt replay` and a campaign's replay runs both end so. */
int replay_end(const mrl_header *h, rt_sim *sim);

#endif /* MODRT_REPLAY_H */
