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

/* every limit of RT_LIMIT_LIST as measured (rt_sizes_of), at least its row's least */
void scn_host_sizes(FILE *f, const rt_scene *sc, const rt_sim *sim)
{
    static const struct {
        const char *name;
        size_t at;       /* offset of its member of rt_sizes */
        unsigned least;
    } row[] = {
#define RT_X_ROW(name, field, least, dflt, what) {#name, offsetof(rt_sizes, field), least},
        RT_LIMIT_LIST(RT_X_ROW)
#undef RT_X_ROW
    };
    rt_sizes z;
    rt_sizes_of(sc, sim, &z);
    for (size_t i = 0; i < sizeof row / sizeof row[0]; i++) {
        uint16_t v;
        memcpy(&v, (const char *)&z + row[i].at, sizeof v);
        fprintf(f, "%s-DRT_MAX_%s=%u", i ? " " : "", row[i].name,
                v > row[i].least ? (unsigned)v : row[i].least);
    }
    fputc('\n', f);
}
