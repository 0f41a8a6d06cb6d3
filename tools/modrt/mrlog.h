/* mrlog.h - the replay log of `modrt run --record FILE` and `modrt replay FILE`
 * (docs/link.md, "Replay log"): every vector of imported values applied during a live
 * run with the tick it was applied at, the scene's identity and the options that change
 * the numbers, in a versioned binary file with a CRC-32 on the header, on every record
 * and on the end marker, which says how the run ended and at which tick (a run stopped
 * early replays to there, not to the header's end time). A log that is corrupt, truncated
 * or written for another scene or another build's number type is refused with one line
 * saying what and where. */
#ifndef MODRT_MRLOG_H
#define MODRT_MRLOG_H

#include <stddef.h>
#include <stdint.h>

#include "rt.h"

#define MRL_SCENE_LEN 255  /* the scene: a library name or a scene file's absolute path */
#define MRL_MAX_SETS 32    /* --set and per-set overrides */
#define MRL_SET_LEN 127

/* how the recorded run ended (the end marker, version 3) */
typedef enum mrl_end {
    MRL_END_DONE = 0,    /* at its end time */
    MRL_END_SIGINT = 1,  /* SIGINT, between two ticks */
    MRL_END_SIGTERM = 2, /* SIGTERM, between two ticks */
    MRL_END_STOPPED = 3, /* real time, --overrun stop: after a missed deadline */
    MRL_END_LINK = 4,    /* an import's stop policy: at the exchange of its last tick */
    MRL_END_COUNT_,
    MRL_END_UNKNOWN = 255 /* reading a version 1 or 2 log: its end marker does not say */
} mrl_end;

typedef struct mrl_header {
    uint16_t version;       /* of the file read (writing: always the newest) */
    uint32_t id;            /* the link id of the scene's layout */
    uint16_t nimp;          /* values per record */
    uint8_t real_size;      /* sizeof(real_t) of the build that wrote it */
    uint8_t realtime;       /* 1: recorded in soft real time, 0: lock-step */
    double t_end;           /* the run's end time [s] */
    uint32_t every;         /* --every */
    uint64_t scene_fp;      /* fp_scene of the scene as run (fingerprint.h); version 1: 0 */
    uint64_t run;           /* the link's run nonce (0: no link); version 1: 0 */
    char scene[MRL_SCENE_LEN + 1];
    uint16_t nsets;
    /* the options that change the numbers, in order: "BLOCK.PARAM=VALUE" (--set), or
       "--OPTION SET=VALUE" (--method, --step, --tol, --accuracy, --substeps, --newton) */
    char sets[MRL_MAX_SETS][MRL_SET_LEN + 1];
    /* reading, from the end marker (version 3; older: MRL_END_UNKNOWN and 0) */
    uint8_t ended;          /* mrl_end: how the run ended */
    uint64_t last_tick;     /* the last tick the run reached */
} mrl_header;

typedef struct mrl_writer mrl_writer;

/* Creates the log and writes its header; NULL with a reason in err. */
mrl_writer *mrl_create(const char *path, const mrl_header *h, char *err, size_t n);
/* Appends one applied vector; -1 on a write error (reported by mrl_finish). */
int mrl_append(mrl_writer *w, uint64_t tick, const real_t *v);
/* Writes the end marker (how the run ended, the last tick it reached) and closes; 0, or
   -1 with a reason in err. */
int mrl_finish(mrl_writer *w, mrl_end ended, uint64_t last_tick, char *err, size_t n);
/* The name of an end ("end time", "SIGINT", ...). */
const char *mrl_end_name(mrl_end e);

/* Opens a log and checks all of it (header, every record, the end marker): 0, or -1
   with "what at byte N" in err. Then mrl_next yields its records in order. */
int mrl_open(const char *path, mrl_header *h, char *err, size_t n);
/* Checks that every record of the open log is applied by a replay of a scene that ends at
   tick `last` (or earlier, where the end marker says the run ended) and exchanges every
   `period` ticks: no record past the end, and in a
   lock-step log (h.realtime 0) every record on an exchange tick. 0, or -1 with the number
   of such records and the first one's byte offset and tick in err. */
int mrl_check_schedule(uint64_t last, uint32_t period, int realtime, char *err, size_t n);
/* Checks the end marker of the open log against a replay that ends at tick `last`: the
   run cannot have gone past it, and a run that reached its end time ended there. 0, or -1
   with both ticks and the marker's byte offset in err. */
int mrl_check_end(uint64_t last, char *err, size_t n);
/* The scene argument as a log records it: a path ending in ".scn" made absolute (so the
   log replays from any directory), a library name as it is. 0, or -1 with the reason. */
int mrl_scene_name(const char *scene, char *out, size_t n, char *err, size_t en);
/* The next record's tick and values (h.nimp of them); 0 at the end. */
int mrl_next(uint64_t *tick, real_t *v);
void mrl_close(void);

/* Runner hook of a replay: applies each recorded vector at its tick; 1 (the run ends) at
   the last tick of a run its link's stop policy ended (MRL_END_LINK). */
int mrl_replay_exchange(void *ctx, const rt_scene *sc, rt_sim *sim);

#endif /* MODRT_MRLOG_H */
