/* host.c - scene files in the modrt CLI (scn_host.h): one compilation per process, kept
 * for the process's lifetime because the scene it returns points into it; and the exact
 * per-scene limits, shared by `scenec --sizes` and `modrt sizes`. */
#include "scn_host.h"

#include <stdio.h>
#include <string.h>

#include "scn.h"

int scn_host_is_file(const char *arg)
{
    size_t n = strlen(arg);
    return n > 4 && strcmp(arg + n - 4, ".scn") == 0;
}

const rt_scene *scn_host_load(const char *path, const scn_fmu_ops *fmu)
{
    static scn_ctx *last; /* owns the scene's memory until exit (modrt loads one) */
    scn_ctx *c = scn_new();
    if (!c) {
        fputs("modrt: out of memory\n", stderr);
        return NULL;
    }
    c->fmu = fmu;
    if (scn_compile(c, path, NULL, 0) != 0) {
        for (const char *l = c->msg, *e; *l; l = *e ? e + 1 : e) { /* one error a line */
            e = strchr(l, '\n') ? strchr(l, '\n') : l + strlen(l);
            fprintf(stderr, "modrt: %.*s\n", (int)(e - l), l);
        }
        scn_free(c);
        return NULL;
    }
    last = c;
    return &last->image;
}

static unsigned at_least_1(unsigned n) { return n ? n : 1; }

/* multibody limits beyond joints come from the set workspaces (rt_sizes_of) */
void scn_host_sizes(FILE *f, const rt_scene *sc, const rt_sim *sim)
{
    rt_sizes z;
    rt_sizes_of(sc, sim, &z);
    fprintf(f, "-DRT_MAX_BLOCKS=%u -DRT_MAX_X=%u -DRT_MAX_D=%u -DRT_MAX_U=%u -DRT_MAX_Y=%u "
               "-DRT_MAX_P=%u -DRT_MAX_ROOTS=%u -DRT_MAX_SETS=%u -DRT_MAX_REC=%u "
               "-DRT_MAX_LOOPS=%u -DRT_MAX_TORN=%u -DRT_MAX_IMPLICIT_N=%u "
               "-DRT_MAX_TRANSITION_N=%u",
            at_least_1(z.blocks), at_least_1(z.x), at_least_1(z.d), at_least_1(z.u),
            at_least_1(z.y), at_least_1(z.p), at_least_1(z.roots), at_least_1(z.sets),
            at_least_1(z.recs), at_least_1(z.loops), at_least_1(z.torn),
            at_least_1(z.implicit_n), z.transition_n);
    /* (RT_MAX_TRANSITION_N, RT_MAX_HELD_Y, RT_MAX_HELD_SIG, RT_MAX_XPRED and RT_MAX_TEV may be 0: their arrays are left out of the
       scene's rt_work and rt_state) */
    fprintf(f, " -DRT_MAX_HIST_Y=%u -DRT_MAX_HELD_Y=%u -DRT_MAX_HELD_SIG=%u -DRT_MAX_EVENT_X=%u "
               "-DRT_MAX_SEQ=%u -DRT_MAX_LOOP_HIST=%u -DRT_MAX_BG=%u -DRT_MAX_XPRED=%u "
               "-DRT_MAX_TEV=%u",
            at_least_1(z.hist_y), z.held_y, z.held_sig, at_least_1(z.event_x),
            at_least_1(z.seq),
            at_least_1(z.loop_hist), at_least_1(z.bg), z.xpred, z.tev);
    fprintf(f, " -DRT_MAX_JOINTS=%u -DRT_MAX_MBS_Z=%u -DRT_MAX_MBS_Q=%u -DRT_MAX_MBS_C=%u "
               "-DRT_MAX_MBS_BZ=%u", at_least_1(sc->njoints), at_least_1(z.mbs_z),
            at_least_1(z.mbs_q), at_least_1(z.mbs_c), at_least_1(z.mbs_bz));
    /* the multibody tables over all sets (their defaults derive from the limits above) */
    fprintf(f, " -DRT_MAX_MBS_ROWS=%u -DRT_MAX_MBS_TOUCH=%u -DRT_MAX_MBS_TW=%u "
               "-DRT_MAX_MBS_QT=%u -DRT_MAX_MBS_TY=%u -DRT_MAX_MBS_PAIRS=%u "
               "-DRT_MAX_MBS_LNZ=%u -DRT_MAX_MBS_M=%u -DRT_MAX_MBS_JROWS=%u -DRT_MAX_MBS_JZ=%u\n",
            at_least_1(z.mbs_rows), at_least_1(z.mbs_touch), at_least_1(z.mbs_tw),
            at_least_1(z.mbs_qt), at_least_1(z.mbs_ty), at_least_1(z.mbs_pairs),
            at_least_1(z.mbs_lnz), at_least_1(z.mbs_m), at_least_1(z.mbs_jrows),
            at_least_1(z.mbs_jz));
}
