/* master.c - a foreign master for an exported FMI 3.0 Co-Simulation FMU (tests/fmi/run.sh):
 * it knows the FMU only through its unpacked directory, its modelDescription.xml and the
 * FMI functions, as another tool would. It
 *   1. runs the FMU from 0 to its stop time in steps of one base tick, folding the time and
 *      the recorded outputs of every communication point into the trace hash as rt.h
 *      defines it, and prints that hash (run.sh compares it with `modrt run`'s);
 *   2. runs a second instance in steps of 10 ticks: the outputs must be the same bits as
 *      the first run's at those points;
 *   3. saves the FMU state at a tenth of the run (fmi3GetFMUState, also serialized and
 *      read back), steps on, goes back to the saved state and steps again: the same bits;
 *   4. asks for a step of 1.5 ticks and for one from a wrong communication point: both
 *      fmi3Error with a logged reason, nothing changed.
 * Usage: master FMU_DIR; prints "ok: ..." / "FAIL: ..." lines and "hash: H". */
#define _POSIX_C_SOURCE 200809L
#include <dlfcn.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fmi_api.h"
#include "fmu_md.h"

#define HASH_INIT 0xcbf29ce484222325ull /* RT_HASH_INIT, RT_HASH_MUL of rt/rt.h */
#define HASH_MUL 0x9e3779b97f4a7c15ull
#define MAX_OUT 256

typedef struct fns {
    fmi3InstantiateCoSimulationTYPE *inst;
    fmi3EnterInitializationModeTYPE *enter;
    fmi3ExitInitializationModeTYPE *exit;
    fmi3DoStepTYPE *step;
    fmi3GetFloat64TYPE *get;
    fmi3SetFloat64TYPE *set;
    fmi3GetFMUStateTYPE *gets;
    fmi3SetFMUStateTYPE *sets;
    fmi3FreeFMUStateTYPE *frees;
    fmi3SerializedFMUStateSizeTYPE *size;
    fmi3SerializeFMUStateTYPE *ser;
    fmi3DeserializeFMUStateTYPE *des;
    fmi3FreeInstanceTYPE *free;
} fns;

static fns f;
static fmu_md md;
static fmi3ValueReference out[MAX_OUT];
static size_t nout, nrec; /* outputs; the first nrec are the recorded signals */
static double dt, t_end;
static char last_log[512];
static int failures;

static void logger(fmi3InstanceEnvironment env, fmi3Status s, fmi3String cat, fmi3String msg)
{
    (void)env, (void)s, (void)cat;
    snprintf(last_log, sizeof last_log, "%s", msg);
}

static void check(int ok, const char *what)
{
    printf("%s: %s\n", ok ? "ok" : "FAIL", what);
    failures += !ok;
}

static uint64_t hash(uint64_t h, double v)
{
    uint64_t u;
    memcpy(&u, &v, sizeof u);
    h = (h ^ u) * HASH_MUL;
    return h ^ (h >> 32);
}

static fmi3Instance start(const char *dir)
{
    char res[4200];
    snprintf(res, sizeof res, "%s/resources/", dir);
    fmi3Instance c = f.inst("master", md.token, res, 0, 0, 0, 0, NULL, 0, NULL, logger, NULL);
    if (!c || f.enter(c, 0, 0, 0, 1, t_end) != fmi3OK || f.exit(c) != fmi3OK) {
        printf("FAIL: instantiate and initialize: %s\n", last_log);
        exit(1);
    }
    return c;
}

static int step(fmi3Instance c, double t, double h)
{
    fmi3Boolean ev, term, early;
    fmi3Float64 last;
    return f.step(c, t, h, 1, &ev, &term, &early, &last);
}

/* the outputs at the current point */
static void outputs(fmi3Instance c, double *v)
{
    if (f.get(c, out, nout, v, nout) != fmi3OK) {
        printf("FAIL: fmi3GetFloat64: %s\n", last_log);
        exit(1);
    }
}

static int load(const char *dir)
{
    char p[4200], err[FMU_ERR_LEN];
    snprintf(p, sizeof p, "%s/modelDescription.xml", dir);
    FILE *x = fopen(p, "rb");
    static char buf[1 << 22];
    size_t n = x ? fread(buf, 1, sizeof buf, x) : 0;
    if (x)
        fclose(x);
    if (!n || fmu_md_parse(buf, n, &md, err, sizeof err) != 0 || !md.cs_id) {
        printf("FAIL: modelDescription.xml: %s\n", n ? err : "unreadable");
        return -1;
    }
    for (uint32_t i = 0; i < md.nv && nout < MAX_OUT; i++)
        if (md.v[i].causality == FMU_C_OUTPUT) {
            out[nout++] = md.v[i].vr;
            nrec += strncmp(md.v[i].name, "export.", 7) != 0;
        }
    /* the step and the stop time: DefaultExperiment is not read by fmu_md; the scene's
       tick is the fixed internal step, which run.sh passes through the environment */
    dt = atof(getenv("MASTER_DT") ? getenv("MASTER_DT") : "0");
    t_end = atof(getenv("MASTER_END") ? getenv("MASTER_END") : "0");
    snprintf(p, sizeof p, "%s/binaries/x86_64-linux/%s.so", dir, md.cs_id);
    void *so = dlopen(p, RTLD_NOW | RTLD_LOCAL);
    if (!so || !(dt > 0) || !(t_end > 0)) {
        printf("FAIL: %s: %s\n", p, so ? "MASTER_DT / MASTER_END not set" : dlerror());
        return -1;
    }
    *(void **)&f.inst = dlsym(so, "fmi3InstantiateCoSimulation");
    *(void **)&f.enter = dlsym(so, "fmi3EnterInitializationMode");
    *(void **)&f.exit = dlsym(so, "fmi3ExitInitializationMode");
    *(void **)&f.step = dlsym(so, "fmi3DoStep");
    *(void **)&f.get = dlsym(so, "fmi3GetFloat64");
    *(void **)&f.set = dlsym(so, "fmi3SetFloat64");
    *(void **)&f.gets = dlsym(so, "fmi3GetFMUState");
    *(void **)&f.sets = dlsym(so, "fmi3SetFMUState");
    *(void **)&f.frees = dlsym(so, "fmi3FreeFMUState");
    *(void **)&f.size = dlsym(so, "fmi3SerializedFMUStateSize");
    *(void **)&f.ser = dlsym(so, "fmi3SerializeFMUState");
    *(void **)&f.des = dlsym(so, "fmi3DeserializeFMUState");
    *(void **)&f.free = dlsym(so, "fmi3FreeInstance");
    return f.inst && f.enter && f.exit && f.step && f.get && f.set && f.gets && f.sets && f.frees &&
           f.size && f.ser && f.des && f.free ? 0 : (printf("FAIL: a function is missing\n"), -1);
}

static int vr_of(const char *name)
{
    for (uint32_t i = 0; i < md.nv; i++)
        if (!strcmp(md.v[i].name, name))
            return (int)md.v[i].vr;
    printf("FAIL: no variable %s\n", name);
    exit(1);
}

/* 5 (MASTER_PI_CSV): pi_link's controller closed by this master, with the PI law of
   models/pi.c (c = Kp e + I, I += Ki Ts e, every 10 ms on the exported Ref.y and
   Plant.y): Plant.y must be the same bits as pi_loop's, whose PI is inside the scene */
static int closed_loop(const char *dir, const char *csv, long n)
{
    FILE *in = fopen(csv, "r");
    char line[512];
    int col = -1, bad = 0;
    if (!in || !fgets(line, sizeof line, in)) {
        printf("FAIL: %s unreadable\n", csv);
        return 1;
    }
    int i = 0;
    for (char *t = strtok(line, ",\n"); t; t = strtok(NULL, ",\n"), i++)
        col = !strcmp(t, "Plant.y") ? i : col;
    if (col < 0) {
        printf("FAIL: %s has no column Plant.y\n", csv);
        return 1;
    }
    fmi3Instance c = start(dir);
    fmi3ValueReference ex[2] = {(fmi3ValueReference)vr_of("export.Ref.y"),
                                (fmi3ValueReference)vr_of("export.Plant.y")};
    fmi3ValueReference cu = (fmi3ValueReference)vr_of("c"), py = (fmi3ValueReference)vr_of("Plant.y");
    double integral = 0, y[2], u, p;
    for (long k = 0; k <= n && !bad; k++) {
        if (k % 10 == 0) {
            f.get(c, ex, 2, y, 2);
            double e = y[0] - y[1];
            u = 0.8 * e + integral;
            integral = integral + 3.0 * 0.01 * e;
            f.set(c, &cu, 1, &u, 1);
        }
        f.get(c, &py, 1, &p, 1);
        if (!fgets(line, sizeof line, in))
            bad = 1;
        char *t = strtok(line, ",\n");
        for (int j = 0; t && j < col; j++)
            t = strtok(NULL, ",\n");
        bad |= !t || strtod(t, NULL) != p;
        if (bad)
            printf("  row %ld: Plant.y %.17g, pi_loop %s\n", k, p, t ? t : "-");
        if (k < n && step(c, k * dt, dt) != fmi3OK)
            bad = 1;
    }
    fclose(in);
    f.free(c);
    check(!bad, "pi_link's FMU with its PI closed by the master: Plant.y = pi_loop's, bit for bit");
    return 0;
}

int main(int argc, char **argv)
{
    if (argc != 2 || load(argv[1]) != 0)
        return 1;
    long n = lround(t_end / dt);
    double *first = calloc((size_t)(n + 1) * nout, sizeof *first), v[MAX_OUT], w[MAX_OUT];

    /* 1: one tick per step, the trace hash over time and the recorded outputs */
    fmi3Instance a = start(argv[1]);
    uint64_t h = HASH_INIT;
    for (long k = 0;; k++) {
        outputs(a, first + (size_t)k * nout);
        h = hash(h, k * dt);
        for (size_t i = 0; i < nrec; i++)
            h = hash(h, first[(size_t)k * nout + i]);
        if (k == n || step(a, k * dt, dt) != fmi3OK)
            break;
    }
    printf("hash: %016llx\n", (unsigned long long)h);

    /* 2: steps of 10 ticks land on the same bits */
    fmi3Instance b = start(argv[1]);
    int same = 1;
    for (long k = 0; k + 10 <= n; k += 10) {
        same &= step(b, k * dt, 10 * dt) == fmi3OK;
        outputs(b, v);
        same &= memcmp(v, first + (size_t)(k + 10) * nout, nout * sizeof *v) == 0;
    }
    check(same, "steps of 10 ticks give the same bits as steps of 1 tick");

    /* 3: the FMU state saved, serialized, restored: the same bits again */
    f.free(b);
    b = start(argv[1]);
    long k0 = n / 10, m = n / 5;
    fmi3FMUState s = NULL, s2 = NULL;
    for (long k = 0; k < k0; k++)
        step(b, k * dt, dt);
    size_t sz = 0;
    int ok = f.gets(b, &s) == fmi3OK && f.size(b, s, &sz) == fmi3OK;
    fmi3Byte *ser = malloc(sz ? sz : 1);
    ok = ok && f.ser(b, s, ser, sz) == fmi3OK && f.des(b, ser, sz, &s2) == fmi3OK;
    for (long k = k0; k < k0 + m; k++)
        step(b, k * dt, dt);
    outputs(b, v);
    ok = ok && f.sets(b, s2) == fmi3OK;
    for (long k = k0; k < k0 + m; k++)
        ok = ok && step(b, k * dt, dt) == fmi3OK;
    outputs(b, w);
    check(ok && !memcmp(v, w, nout * sizeof *v) &&
          !memcmp(v, first + (size_t)(k0 + m) * nout, nout * sizeof *v),
          "a saved and serialized FMU state, restored, steps to the same bits");
    f.frees(b, &s), f.frees(b, &s2);

    /* 4: steps the FMU must refuse */
    outputs(b, v);
    last_log[0] = 0;
    int r1 = step(b, (k0 + m) * dt, 1.5 * dt);
    check(r1 == fmi3Error && strstr(last_log, "not a whole number of base ticks"),
          "a step of 1.5 ticks: fmi3Error, logged");
    printf("  logged: %s\n", last_log);
    last_log[0] = 0;
    int r2 = step(b, (k0 + m + 3) * dt, dt);
    check(r2 == fmi3Error && strstr(last_log, "is not the FMU's time"),
          "a step from a wrong communication point: fmi3Error, logged");
    outputs(b, w);
    check(!memcmp(v, w, nout * sizeof *v), "a refused step changes nothing");
    f.free(a), f.free(b);
    free(first), free(ser);
    if (getenv("MASTER_PI_CSV"))
        failures += closed_loop(argv[1], getenv("MASTER_PI_CSV"), n);
    fmu_md_free(&md);
    printf("master: %d failed\n", failures);
    return failures != 0;
}
