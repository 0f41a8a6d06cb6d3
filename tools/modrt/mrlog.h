/* mrlog.h - the replay log of `modrt run --record FILE` and `modrt replay FILE`
 * (docs/link.md, "Replay log"): every vector of imported values applied during a live
 * run with the tick it was applied at, the scene's identity and the options that change
 * the numbers, in a versioned binary file with a CRC-32 on the header, on every record
 * and on the end marker. A log that is corrupt, truncated or written for another scene
 * or another build's number type is refused with one line saying what and where. */
#ifndef MODRT_MRLOG_H
#define MODRT_MRLOG_H

#include <stddef.h>
#include <stdint.h>

#include "rt.h"

#define MRL_SCENE_LEN 255  /* the scene as given to run: a library name or a file path */
#define MRL_MAX_SETS 32    /* --set overrides */
#define MRL_SET_LEN 127

typedef struct mrl_header {
    uint32_t id;            /* the link id of the scene's layout */
    uint16_t nimp;          /* values per record */
    uint8_t real_size;      /* sizeof(real_t) of the build that wrote it */
    uint8_t realtime;       /* 1: recorded in soft real time, 0: lock-step */
    double t_end;           /* the run's end time [s] */
    uint32_t every;         /* --every */
    char scene[MRL_SCENE_LEN + 1];
    uint16_t nsets;
    char sets[MRL_MAX_SETS][MRL_SET_LEN + 1]; /* --set BLOCK.PARAM=VALUE, in order */
} mrl_header;

typedef struct mrl_writer mrl_writer;

/* Creates the log and writes its header; NULL with a reason in err. */
mrl_writer *mrl_create(const char *path, const mrl_header *h, char *err, size_t n);
/* Appends one applied vector; -1 on a write error (reported by mrl_finish). */
int mrl_append(mrl_writer *w, uint64_t tick, const real_t *v);
/* Writes the end marker and closes; 0, or -1 with a reason in err. */
int mrl_finish(mrl_writer *w, char *err, size_t n);

/* Opens a log and checks all of it (header, every record, the end marker): 0, or -1
   with "what at byte N" in err. Then mrl_next yields its records in order. */
int mrl_open(const char *path, mrl_header *h, char *err, size_t n);
/* The next record's tick and values (h.nimp of them); 0 at the end. */
int mrl_next(uint64_t *tick, real_t *v);
void mrl_close(void);

/* Runner hook of a replay: applies each recorded vector at its tick. */
int mrl_replay_exchange(void *ctx, const rt_scene *sc, rt_sim *sim);

#endif /* MODRT_MRLOG_H */
