/* setp.c - parameters written during a run with FMU blocks (make test-fmi, tests/fmi/run.sh):
 * a scene file run to t1, each BLOCK.PARAM=VALUE written there by rt_set_param (between
 * ticks, as an application or a tuning front end does), then run to its end. Every row
 * from t = 0 goes to the CSV, for the closed forms of tests/fmi/check.py; prints the
 * statuses, the trace hash and the FMU summary.
 *
 * Usage: setp SCENE.scn T1 CSV BLOCK.PARAM=VALUE... */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fmu.h"
#include "fmu_scn.h"
#include "rt_sim.h"
#include "scn_host.h"

static rt_sim sim;

static void row(const rt_scene *sc, FILE *f)
{
    rt_record(sc, &sim, NULL);
    fprintf(f, "%.17g", (double)rt_time(sc, &sim));
    for (uint16_t i = 0; i < sc->nrecs; i++)
        fprintf(f, ",%.17g", (double)rt_rec_value(sc, &sim, i));
    fputc('\n', f);
}

int main(int argc, char **argv)
{
    if (argc < 5) {
        fprintf(stderr, "usage: setp SCENE.scn T1 CSV BLOCK.PARAM=VALUE...\n");
        return 2;
    }
    const rt_scene *sc = scn_host_load(argv[1], &fmu_scn_ops);
    if (!sc)
        return 2;
    uint64_t n1 = (uint64_t)(atof(argv[2]) / (double)sc->dt + 0.5);
    rt_status st = rt_init(sc, &sim);
    FILE *f = fopen(argv[3], "w");
    if (st != RT_OK || !f) {
        printf("rt_init: %s: %s\n", rt_status_name(st), rt_error_text(&sim));
        return 1;
    }
    fputs("t", f);
    for (uint16_t i = 0; i < sc->nrecs; i++)
        fprintf(f, ",%s.%s", sc->blocks[sc->recs[i].block].name, rt_rec_signal(sc, i));
    fputc('\n', f);
    row(sc, f);
    while (rt_ticks_done(&sim) < n1 && rt_tick(sc, &sim) != RT_E_ARG)
        row(sc, f);
    for (int i = 4; i < argc; i++) {
        char block[128], *dot = strchr(argv[i], '.'), *eq = strchr(argv[i], '=');
        if (!dot || !eq || eq < dot || (size_t)(dot - argv[i]) >= sizeof block) {
            fprintf(stderr, "setp: %s: expected BLOCK.PARAM=VALUE\n", argv[i]);
            return 2;
        }
        memcpy(block, argv[i], (size_t)(dot - argv[i]));
        block[dot - argv[i]] = 0;
        *eq = 0;
        st = rt_set_param(sc, &sim, block, dot + 1, (real_t)atof(eq + 1));
        printf("set %s.%s: %s\n", block, dot + 1, rt_status_name(st));
    }
    for (rt_status t = RT_OK; t == RT_OK;)
        if ((t = rt_tick(sc, &sim)) != RT_E_ARG)
            row(sc, f);
    fclose(f);
    printf("hash: %016llx\n", (unsigned long long)rt_trace_hash(&sim));
    printf("status: %s\n", rt_status_name(rt_stats_of(&sim)->status));
    fmu_summary(stdout);
    return 0;
}
