/* replay.c - the scene of a replay log set up as its live run was (replay.h): one path
 * for `modrt replay` and a campaign's replay runs, so both refuse the same logs. */
#include <signal.h>
#include <stdio.h>
#include <string.h>

#include "cli.h"
#include "fingerprint.h"
#include "replay.h"

/* the log's per-set options ("--method main=rk4"), then more's, onto the scene */
static int replay_study(const mrl_header *h, const study_args *more, rt_scene *sc)
{
    static study_args st;
    static char names[MRL_MAX_SETS][MRL_SET_LEN + 1];
    memset(&st, 0, sizeof st);
    for (uint16_t i = 0; i < h->nsets; i++) {
        char *sp = strchr(strcpy(names[i], h->sets[i]), ' ');
        if (strncmp(names[i], "--", 2) != 0)
            continue;
        if (!sp)
            return cli_fail("replay: a malformed option in the log", h->sets[i]);
        *sp = 0;
        if (study_add(&st, names[i] + 2, sp + 1) != CLI_OK)
            return CLI_USAGE;
    }
    for (int i = 0; more && i < more->n; i++)
        if (study_add(&st, more->opt[i], more->val[i]) != CLI_OK)
            return CLI_USAGE;
    return study_apply(&st, sc);
}

/* the log's scene is the one recorded: its link layout and, from version 2, its
   fingerprint (every table and parameter value, fingerprint.h) */
static int replay_same_scene(const mrl_header *h, const rt_scene *sc, const char *path)
{
    char what[700];
    uint32_t id = sc->link ? sc->link->id : 0;
    uint16_t nimp = sc->link ? sc->link->nimp : 0;
    if (id != h->id || nimp != h->nimp) {
        snprintf(what, sizeof what, "link layout 0x%08x with %u imports, but scene %s has "
                 "0x%08x with %u: another scene or another version of it",
                 (unsigned)h->id, (unsigned)h->nimp, h->scene, (unsigned)id, (unsigned)nimp);
        return cli_fail(path, what);
    }
    uint64_t fp = fp_scene(sc);
    if (h->version >= 2 && fp != h->scene_fp) {
        snprintf(what, sizeof what, "recorded with scene fingerprint %016llx, but scene %s "
                 "is now %016llx: the scene changed since (a table, a parameter value or "
                 "an FMU file)",
                 (unsigned long long)h->scene_fp, h->scene, (unsigned long long)fp);
        return cli_fail(path, what);
    }
    if (h->version < 2)
        fprintf(stderr, "modrt: warning: %s: a version %u log names its scene by name and "
                "link layout only; a changed parameter would go unnoticed\n", path,
                (unsigned)h->version);
    return CLI_OK;
}

int replay_scene(const mrl_header *h, const char *path, const replay_more *more, rt_scene *sc,
                 rt_sim *sim)
{
    char err[600];
    const rt_scene *base = cli_scene(h->scene);
    if (!base)
        return CLI_USAGE;
    *sc = *base;
    sc->t_end = (real_t)h->t_end;
    if (h->real_size != sizeof(real_t))
        return cli_fail(path, h->real_size == 4 ? "was recorded by a float build; this is a "
                                                  "double build"
                                                : "was recorded by a double build; this is a "
                                                  "float build");
    if (replay_study(h, NULL, sc) != CLI_OK)
        return CLI_USAGE;
    int rc = replay_same_scene(h, sc, path);
    if (rc != CLI_OK)
        return rc;
    if (more && more->study && more->study->n > 0) { /* from the scene's own sets again */
        sc->sets = base->sets;
        if (replay_study(h, more->study, sc) != CLI_OK)
            return CLI_USAGE;
    }
    if (more && more->t_end >= 0 && cli_end_time(sc, more->t_end, path) != CLI_OK)
        return CLI_USAGE;
    rt_status st = rt_init(sc, sim);
    if (st != RT_OK)
        return cli_fail(rt_status_name(st), rt_error_text(sim));
    if (mrl_check_schedule(rt_tick_count(sim), sc->link ? sc->link->period : 1, h->realtime,
                           err, sizeof err) != 0)
        return cli_fail("replay", err);
    int nsets = 0;
    for (uint16_t i = 0; i < h->nsets; i++)
        if (strncmp(h->sets[i], "--", 2) != 0 && (++nsets, cli_set_param(sc, sim, h->sets[i])))
            return CLI_USAGE;
    for (int i = 0; more && i < more->nsets; i++, nsets++)
        if (cli_set_param(sc, sim, more->sets[i]) != CLI_OK)
            return CLI_USAGE;
    if (nsets > 0)
        return cli_refresh(sc, sim);
    return CLI_OK;
}

const uint64_t *replay_stop_tick(const mrl_header *h)
{
    int early = h->version >= 3 && h->ended != MRL_END_DONE && h->ended != MRL_END_LINK;
    return early ? &h->last_tick : NULL;
}

int replay_end(const mrl_header *h, rt_sim *sim)
{
    if (h->version < 3 || rt_ticks_done(sim) != h->last_tick)
        return 0;
    if (h->ended == MRL_END_STOPPED)
        rt_note_status(sim, RT_E_STOPPED);
    return h->ended == MRL_END_SIGINT ? SIGINT : h->ended == MRL_END_SIGTERM ? SIGTERM : 0;
}
