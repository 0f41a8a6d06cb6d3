/* mujoco_bench.c - MuJoCo 2.2.2 (Debian's libmujoco-dev) on the models mujoco_chain.py
 * writes (scale.sh's chain and tree), for MuJoCo beside modrt at equal accuracy
 * (tools/dev/bench/mujoco_scale.sh, docs/overhead.md "Beside MuJoCo"). A bench program
 * only: make test never builds it.
 *
 * Usage: mujoco_bench MODEL.xml run euler|rk4 H T     steps of H up to T seconds; prints
 *                                                     the last body's position "x y z"
 *        mujoco_bench MODEL.xml count euler|rk4 H N   N steps of H in mj_steps (the
 *                                                     function callgrind counts; callgrind's
 *                                                     instrumentation starts just before)
 *        mujoco_bench MODEL.xml save OUT.mjb          the compiled model (MuJoCo's binary
 *                                                     format: loads in no time under
 *                                                     valgrind, where compiling 1000 bodies
 *                                                     takes an hour); MODEL may be .mjb */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <mujoco/mujoco.h>
#include <valgrind/callgrind.h>

__attribute__((noinline)) void mj_steps(const mjModel *m, mjData *d, long n)
{
    for (long i = 0; i < n; i++)
        mj_step(m, d);
}

int main(int argc, char **argv)
{
    int save = argc == 4 && strcmp(argv[2], "save") == 0;
    if (!save && (argc != 6 || (strcmp(argv[2], "run") != 0 && strcmp(argv[2], "count") != 0) ||
                  (strcmp(argv[3], "euler") != 0 && strcmp(argv[3], "rk4") != 0))) {
        fprintf(stderr, "usage: mujoco_bench MODEL.xml|MODEL.mjb run|count euler|rk4 H T|N\n"
                        "       mujoco_bench MODEL.xml save OUT.mjb\n");
        return 2;
    }
    char err[1000] = "";
    size_t len = strlen(argv[1]);
    mjModel *m = len > 4 && strcmp(argv[1] + len - 4, ".mjb") == 0
                     ? mj_loadModel(argv[1], NULL)
                     : mj_loadXML(argv[1], NULL, err, sizeof err);
    if (!m) {
        fprintf(stderr, "mujoco_bench: %s: %s\n", argv[1], err[0] ? err : "cannot load");
        return 1;
    }
    if (save) {
        mj_saveModel(m, argv[3], NULL, 0);
        mj_deleteModel(m);
        return 0;
    }
    double h = atof(argv[4]);
    if (!(h > 0)) {
        fprintf(stderr, "mujoco_bench: step %s is not positive\n", argv[4]);
        return 2;
    }
    m->opt.timestep = h;
    m->opt.integrator = strcmp(argv[3], "rk4") == 0 ? mjINT_RK4 : mjINT_EULER;
    mjData *d = mj_makeData(m);
    if (!d) {
        fprintf(stderr, "mujoco_bench: mj_makeData failed\n");
        return 1;
    }
    long n = strcmp(argv[2], "count") == 0 ? atol(argv[5]) : lround(atof(argv[5]) / h);
    CALLGRIND_START_INSTRUMENTATION;
    mj_steps(m, d, n);
    mj_kinematics(m, d); /* positions at the end of the last step */
    int last = mj_name2id(m, mjOBJ_BODY, "last");
    if (last < 0) {
        fprintf(stderr, "mujoco_bench: %s has no body named last\n", argv[1]);
        return 1;
    }
    const double *p = d->xipos + 3 * last;
    if (last != m->nbody - 1) {
        fprintf(stderr, "mujoco_bench: body last is not the last body\n");
        return 1;
    }
    int bad = 0;
    for (int i = 0; i < mjNWARNING; i++)
        bad += d->warning[i].number;
    if (bad || !isfinite(p[0] + p[1] + p[2])) {
        fprintf(stderr, "mujoco_bench: %d warnings, position %g %g %g\n", bad, p[0], p[1],
                p[2]);
        return 1;
    }
    for (int b = 1; b < m->nbody; b++) /* every body's position, as scale_bench run */
        printf("%.17g %.17g %.17g\n", d->xipos[3 * b], d->xipos[3 * b + 1],
               d->xipos[3 * b + 2]);
    mj_deleteData(d);
    mj_deleteModel(m);
    return 0;
}
