/* snap.c - snapshots of a run with FMU blocks (make test-fmi, tests/fmi/run.sh): a scene
 * file run straight to t2; run again to t1, snapshotted (rt_snapshot), run on to t2 across
 * the FMUs' events, restored (rt_restore) and run to t2 again. Prints the statuses, the
 * trace hashes of the three runs to t2 (each recording every tick from 0, the restored one
 * from the snapshot's hash on) and the rows of the restored run after t1 as CSV, for the
 * closed forms of tests/fmi/check.py.
 *
 * Usage: snap SCENE.scn T1 T2 CSV */
#include <stdio.h>
#include <stdlib.h>

#include "fmu.h"
#include "fmu_scn.h"
#include "rt_sim.h"
#include "scn_host.h"

static rt_sim sim;
static rt_state snap;

/* ticks until tick n (or the end), each recorded; CSV rows when f */
static void run_to(const rt_scene *sc, uint64_t n, FILE *f)
{
    while (rt_ticks_done(&sim) < n && rt_tick(sc, &sim) != RT_E_ARG) {
        rt_record(sc, &sim, NULL);
        if (!f)
            continue;
        fprintf(f, "%.17g", (double)rt_time(sc, &sim));
        for (uint16_t i = 0; i < sc->nrecs; i++)
            fprintf(f, ",%.17g", (double)rt_rec_value(sc, &sim, i));
        fputc('\n', f);
    }
}

static int start(const rt_scene *sc)
{
    rt_status st = rt_init(sc, &sim);
    if (st != RT_OK) {
        printf("rt_init: %s: %s\n", rt_status_name(st), rt_error_text(&sim));
        return -1;
    }
    rt_record(sc, &sim, NULL);
    return 0;
}

int main(int argc, char **argv)
{
    if (argc != 5) {
        fprintf(stderr, "usage: snap SCENE.scn T1 T2 CSV\n");
        return 2;
    }
    const rt_scene *sc = scn_host_load(argv[1], &fmu_scn_ops);
    if (!sc)
        return 2;
    uint64_t n1 = (uint64_t)(atof(argv[2]) / (double)sc->dt + 0.5);
    uint64_t n2 = (uint64_t)(atof(argv[3]) / (double)sc->dt + 0.5);
    if (start(sc))
        return 1;
    run_to(sc, n2, NULL);
    printf("straight: %016llx\n", (unsigned long long)rt_trace_hash(&sim));
    if (start(sc))
        return 1;
    run_to(sc, n1, NULL);
    printf("snapshot: %s\n", rt_status_name(rt_snapshot(&sim, &snap)));
    run_to(sc, n2, NULL);
    printf("on: %016llx\n", (unsigned long long)rt_trace_hash(&sim));
    printf("restore: %s\n", rt_status_name(rt_restore(&sim, &snap)));
    FILE *f = fopen(argv[4], "w");
    if (!f)
        return 2;
    fputs("time", f);
    for (uint16_t i = 0; i < sc->nrecs; i++)
        fprintf(f, ",%s", rt_rec_signal(sc, i));
    fputc('\n', f);
    run_to(sc, n2, f);
    fclose(f);
    printf("restored: %016llx\n", (unsigned long long)rt_trace_hash(&sim));
    printf("status: %s\n", rt_status_name(rt_stats_of(&sim)->status));
    fmu_summary(stdout);
    return 0;
}
