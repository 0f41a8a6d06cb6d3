/* master.c - a foreign master for an exported FMI 3.0 or 2.0 Co-Simulation FMU
 * (tests/fmi/run.sh): it knows the FMU only through its unpacked directory, its
 * modelDescription.xml and the FMI functions of the version it declares, as another tool
 * would (FMI 2.0: memory from its allocateMemory / freeMemory, which it counts). It
 *   1. runs the FMU from 0 to its stop time in steps of one base tick, folding the time and
 *      the recorded outputs of every communication point into the trace hash as rt.h
 *      defines it, and prints that hash (run.sh compares it with `modrt run`'s);
 *   2. runs a second instance in steps of 10 ticks: the outputs must be the same bits as
 *      the first run's at those points;
 *   3. saves the FMU state at a tenth of the run (fmi3GetFMUState, also serialized and
 *      read back), steps on, goes back to the saved state and steps again: the same bits
 *      on every row
 *      (an FMU whose description says it cannot save its state must refuse, logged);
 *   4. asks for a step of 1.5 ticks and for one from a wrong communication point: both
 *      fmi3Error / fmi2Error with a logged reason, nothing changed;
 *   5. resets the instance mid-run, initializes it again and steps: the first run's bits;
 *   one instance lives at a time (each freed before the next is made); an FMU that says
 *   canBeInstantiatedOnlyOncePerProcess must refuse a second one while the first lives;
 *   (2.0) 6. the status functions after the last step (fmi2LastSuccessfulTime the stop
 *      time, fmi2Terminated true), an Integer request refused, every block it allocated
 *      for the FMU freed once the instances are.
 * MASTER_CSV names a file for the first run's rows (t and the recorded outputs).
 * Usage: master FMU_DIR; prints "ok: ..." / "FAIL: ..." lines and "hash: H". */
#define _POSIX_C_SOURCE 200809L
#include <dlfcn.h>
#include <math.h>
#include <stdarg.h>
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
    fmi3ResetTYPE *reset;
    fmi3FreeInstanceTYPE *free;
} fns;

/* FMI 2.0 */
typedef struct fns2 {
    fmi2InstantiateTYPE *inst;
    fmi2SetupExperimentTYPE *setup;
    fmi2EnterInitializationModeTYPE *enter;
    fmi2ExitInitializationModeTYPE *exit;
    fmi2DoStepTYPE *step;
    fmi2GetRealTYPE *get;
    fmi2SetRealTYPE *set;
    fmi2GetIntegerTYPE *geti;
    fmi2GetRealStatusTYPE *rstat;
    fmi2GetBooleanStatusTYPE *bstat;
    fmi2GetFMUstateTYPE *gets;
    fmi2SetFMUstateTYPE *sets;
    fmi2FreeFMUstateTYPE *frees;
    fmi2SerializedFMUstateSizeTYPE *size;
    fmi2SerializeFMUstateTYPE *ser;
    fmi2DeSerializeFMUstateTYPE *des;
    fmi2ResetTYPE *reset;
    fmi2FreeInstanceTYPE *free;
} fns2;

static fns f;
static fns2 f2;
static long live_blocks; /* allocateMemory calls not yet freed (FMI 2.0) */
static fmu_md md;
static fmi3ValueReference out[MAX_OUT];
static size_t nout, nrec; /* outputs; the first nrec are the recorded signals */
static double dt, t_end;
static char last_log[512];
static int failures;
static int once; /* canBeInstantiatedOnlyOncePerProcess (fmu_md reads Model Exchange's only) */
static int can_state; /* canGetAndSetFMUState (3.0) / canGetAndSetFMUstate (2.0) */

static void logger(fmi3InstanceEnvironment env, fmi3Status s, fmi3String cat, fmi3String msg)
{
    (void)env, (void)s, (void)cat;
    snprintf(last_log, sizeof last_log, "%s", msg);
}

static void logger2(fmi2ComponentEnvironment env, fmi2String name, fmi2Status s,
                    fmi2String cat, fmi2String msg, ...)
{
    va_list ap;
    (void)env, (void)name, (void)s, (void)cat;
    va_start(ap, msg);
    vsnprintf(last_log, sizeof last_log, msg, ap);
    va_end(ap);
}

static void *alloc2(size_t n, size_t size)
{
    void *p = calloc(n, size);
    live_blocks += p != NULL;
    return p;
}

static void free2(void *p)
{
    live_blocks -= p != NULL;
    free(p);
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

/* ---- the calls the checks make, in the FMU's FMI version (statuses: 0 OK, 3 Error) */

static const fmi2CallbackFunctions callbacks2 = {logger2, alloc2, free2, NULL, NULL};

static void *start(const char *dir)
{
    char res[4200];
    int ok;
    void *c;
    snprintf(res, sizeof res, "%s%s/resources/", md.version == 2 ? "file://" : "", dir);
    if (md.version == 2) {
        c = f2.inst("master", fmi2CoSimulation, md.token, res, &callbacks2, 0, 0);
        ok = c && f2.setup(c, 0, 0, 0, 1, t_end) == fmi2OK && f2.enter(c) == fmi2OK &&
             f2.exit(c) == fmi2OK;
    } else {
        c = f.inst("master", md.token, res, 0, 0, 0, 0, NULL, 0, NULL, logger, NULL);
        ok = c && f.enter(c, 0, 0, 0, 1, t_end) == fmi3OK && f.exit(c) == fmi3OK;
    }
    if (!ok) {
        printf("FAIL: instantiate and initialize: %s\n", last_log);
        exit(1);
    }
    return c;
}

static int step(void *c, double t, double h)
{
    fmi3Boolean ev, term, early;
    fmi3Float64 last;
    return md.version == 2 ? (int)f2.step(c, t, h, 1)
                           : (int)f.step(c, t, h, 1, &ev, &term, &early, &last);
}

static int get(void *c, const uint32_t *vr, size_t n, double *v)
{
    return md.version == 2 ? (int)f2.get(c, vr, n, v) : (int)f.get(c, vr, n, v, n);
}

static int set(void *c, const uint32_t *vr, size_t n, const double *v)
{
    return md.version == 2 ? (int)f2.set(c, vr, n, v) : (int)f.set(c, vr, n, v, n);
}

static int save(void *c, void **s)
{
    return md.version == 2 ? (int)f2.gets(c, s) : (int)f.gets(c, s);
}

static int restore(void *c, void *s)
{
    return md.version == 2 ? (int)f2.sets(c, s) : (int)f.sets(c, s);
}

static void drop(void *c, void **s)
{
    if (md.version == 2)
        f2.frees(c, s);
    else
        f.frees(c, s);
}

/* the state serialized and read back as a new one */
static int reserialize(void *c, void *s, void **back, void **buf)
{
    size_t sz = 0;
    if (md.version == 2) {
        int ok = f2.size(c, s, &sz) == fmi2OK && (*buf = malloc(sz ? sz : 1)) &&
                 f2.ser(c, s, *buf, sz) == fmi2OK && f2.des(c, *buf, sz, back) == fmi2OK;
        return ok ? 0 : 3;
    }
    int ok = f.size(c, s, &sz) == fmi3OK && (*buf = malloc(sz ? sz : 1)) &&
             f.ser(c, s, *buf, sz) == fmi3OK && f.des(c, *buf, sz, back) == fmi3OK;
    return ok ? 0 : 3;
}

/* Reset, then initialized again as a fresh instance is */
static int again(void *c)
{
    if (md.version == 2)
        return f2.reset(c) == fmi2OK && f2.setup(c, 0, 0, 0, 1, t_end) == fmi2OK &&
               f2.enter(c) == fmi2OK && f2.exit(c) == fmi2OK ? 0 : 3;
    return f.reset(c) == fmi3OK && f.enter(c, 0, 0, 0, 1, t_end) == fmi3OK &&
           f.exit(c) == fmi3OK ? 0 : 3;
}

static void finish(void *c)
{
    if (md.version == 2)
        f2.free(c);
    else
        f.free(c);
}

/* the outputs at the current point */
static void outputs(void *c, double *v)
{
    if (get(c, out, nout, v) != 0) {
        printf("FAIL: get the outputs: %s\n", last_log);
        exit(1);
    }
}

#define SYM(p, name) (*(void **)&(p) = dlsym(so, name))

static int bind2(void *so)
{
    return SYM(f2.inst, "fmi2Instantiate") && SYM(f2.setup, "fmi2SetupExperiment") &&
           SYM(f2.enter, "fmi2EnterInitializationMode") &&
           SYM(f2.exit, "fmi2ExitInitializationMode") && SYM(f2.step, "fmi2DoStep") &&
           SYM(f2.get, "fmi2GetReal") && SYM(f2.set, "fmi2SetReal") &&
           SYM(f2.geti, "fmi2GetInteger") && SYM(f2.rstat, "fmi2GetRealStatus") &&
           SYM(f2.bstat, "fmi2GetBooleanStatus") && SYM(f2.gets, "fmi2GetFMUstate") &&
           SYM(f2.sets, "fmi2SetFMUstate") && SYM(f2.frees, "fmi2FreeFMUstate") &&
           SYM(f2.size, "fmi2SerializedFMUstateSize") && SYM(f2.ser, "fmi2SerializeFMUstate") &&
           SYM(f2.des, "fmi2DeSerializeFMUstate") && SYM(f2.free, "fmi2FreeInstance") &&
           SYM(f2.reset, "fmi2Reset");
}

static int bind3(void *so)
{
    return SYM(f.inst, "fmi3InstantiateCoSimulation") &&
           SYM(f.enter, "fmi3EnterInitializationMode") &&
           SYM(f.exit, "fmi3ExitInitializationMode") && SYM(f.step, "fmi3DoStep") &&
           SYM(f.get, "fmi3GetFloat64") && SYM(f.set, "fmi3SetFloat64") &&
           SYM(f.gets, "fmi3GetFMUState") && SYM(f.sets, "fmi3SetFMUState") &&
           SYM(f.frees, "fmi3FreeFMUState") && SYM(f.size, "fmi3SerializedFMUStateSize") &&
           SYM(f.ser, "fmi3SerializeFMUState") && SYM(f.des, "fmi3DeserializeFMUState") &&
           SYM(f.free, "fmi3FreeInstance") && SYM(f.reset, "fmi3Reset");
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
    once = n && strstr(buf, "canBeInstantiatedOnlyOncePerProcess=\"true\"") != NULL;
    can_state = n && (strstr(buf, "canGetAndSetFMUState=\"true\"") ||
                      strstr(buf, "canGetAndSetFMUstate=\"true\""));
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
    snprintf(p, sizeof p, "%s/binaries/%s/%s.so", dir,
             md.version == 2 ? "linux64" : "x86_64-linux", md.cs_id);
    void *so = dlopen(p, RTLD_NOW | RTLD_LOCAL);
    if (!so || !(dt > 0) || !(t_end > 0)) {
        printf("FAIL: %s: %s\n", p, so ? "MASTER_DT / MASTER_END not set" : dlerror());
        return -1;
    }
    return (md.version == 2 ? bind2(so) : bind3(so)) ? 0
         : (printf("FAIL: a function is missing\n"), -1);
}

static int vr_of(const char *name)
{
    for (uint32_t i = 0; i < md.nv; i++)
        if (!strcmp(md.v[i].name, name))
            return (int)md.v[i].vr;
    printf("FAIL: no variable %s\n", name);
    exit(1);
}

/* 7 (MASTER_PI_CSV): pi_link's controller closed by this master, with the PI law of
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
    void *c = start(dir);
    fmi3ValueReference ex[2] = {(fmi3ValueReference)vr_of("export.Ref.y"),
                                (fmi3ValueReference)vr_of("export.Plant.y")};
    fmi3ValueReference cu = (fmi3ValueReference)vr_of("c"), py = (fmi3ValueReference)vr_of("Plant.y");
    double integral = 0, y[2], u, p;
    for (long k = 0; k <= n && !bad; k++) {
        if (k % 10 == 0) {
            get(c, ex, 2, y);
            double e = y[0] - y[1];
            u = 0.8 * e + integral;
            integral = integral + 3.0 * 0.01 * e;
            set(c, &cu, 1, &u);
        }
        get(c, &py, 1, &p);
        if (!fgets(line, sizeof line, in))
            bad = 1;
        char *t = strtok(line, ",\n");
        for (int j = 0; t && j < col; j++)
            t = strtok(NULL, ",\n");
        bad |= !t || strtod(t, NULL) != p;
        if (bad)
            printf("  row %ld: Plant.y %.17g, pi_loop %s\n", k, p, t ? t : "-");
        if (k < n && step(c, k * dt, dt) != 0)
            bad = 1;
    }
    fclose(in);
    finish(c);
    check(!bad, "pi_link's FMU with its PI closed by the master: Plant.y = pi_loop's, bit for bit");
    return 0;
}

/* 6 (FMI 2.0): what only 2.0 has, on an instance at its stop time */
static void status2(void *c)
{
    fmi2Real last = -1;
    fmi2Boolean term = 0;
    fmi2Integer iv;
    fmi2ValueReference vr = out[0];
    check(f2.rstat(c, fmi2LastSuccessfulTime, &last) == fmi2OK && fabs(last - t_end) < 1e-9 &&
          f2.bstat(c, fmi2Terminated, &term) == fmi2OK && term,
          "fmi2GetRealStatus / fmi2GetBooleanStatus at the stop time: its time, terminated");
    last_log[0] = 0;
    check(f2.geti(c, &vr, 1, &iv) == fmi2Error && strstr(last_log, "Real variables only") &&
          f2.geti(c, &vr, 0, &iv) == fmi2OK,
          "fmi2GetInteger of a Real refused with a logged reason, of nothing served");
}

/* the first run's recorded outputs at every communication point, as modrt run --csv
   writes a trace (t, then the recorded signals by name): for run.sh's closed forms */
static void write_csv(const char *path, const double *rows, long n)
{
    FILE *o = fopen(path, "w");
    if (!o) {
        check(0, "MASTER_CSV writable");
        return;
    }
    fputs("t", o);
    for (size_t i = 0, j = 0; i < md.nv && j < nrec; i++)
        if (md.v[i].causality == FMU_C_OUTPUT && strncmp(md.v[i].name, "export.", 7) != 0)
            fprintf(o, ",%s", md.v[i].name), j++;
    for (long k = 0; k <= n; k++) {
        fprintf(o, "\n%.17g", k * dt);
        for (size_t i = 0; i < nrec; i++)
            fprintf(o, ",%.17g", rows[(size_t)k * nout + i]);
    }
    fputs("\n", o);
    fclose(o);
}

int main(int argc, char **argv)
{
    if (argc != 2 || load(argv[1]) != 0)
        return 1;
    long n = lround(t_end / dt);
    double *first = calloc((size_t)(n + 1) * nout, sizeof *first), v[MAX_OUT], w[MAX_OUT];

    /* 1: one tick per step, the trace hash over time and the recorded outputs */
    void *a = start(argv[1]);
    uint64_t h = HASH_INIT;
    for (long k = 0;; k++) {
        outputs(a, first + (size_t)k * nout);
        h = hash(h, k * dt);
        for (size_t i = 0; i < nrec; i++)
            h = hash(h, first[(size_t)k * nout + i]);
        if (k == n || step(a, k * dt, dt) != 0)
            break;
    }
    printf("hash: %016llx\n", (unsigned long long)h);
    if (getenv("MASTER_CSV"))
        write_csv(getenv("MASTER_CSV"), first, n);
    if (md.version == 2)
        status2(a);
    if (once) { /* a second instance while the first lives: refused, saying why */
        last_log[0] = 0;
        void *two = md.version == 2
                  ? (void *)f2.inst("second", fmi2CoSimulation, md.token, "", &callbacks2, 0, 0)
                  : (void *)f.inst("second", md.token, "", 0, 0, 0, 0, NULL, 0, NULL, logger, NULL);
        check(!two && strstr(last_log, "canBeInstantiatedOnlyOncePerProcess"),
              "canBeInstantiatedOnlyOncePerProcess: a second instance refused, logged");
    }
    finish(a); /* one instance at a time: an FMU may be instantiable only once per process */

    /* 2: steps of 10 ticks land on the same bits */
    void *b = start(argv[1]);
    int same = 1;
    for (long k = 0; k + 10 <= n; k += 10) {
        same &= step(b, k * dt, 10 * dt) == 0;
        outputs(b, v);
        same &= memcmp(v, first + (size_t)(k + 10) * nout, nout * sizeof *v) == 0;
    }
    check(same, "steps of 10 ticks give the same bits as steps of 1 tick");

    /* 3: the FMU state saved, serialized, restored: the same bits again */
    finish(b);
    b = start(argv[1]);
    long k0 = n / 10, m = n / 5;
    void *s = NULL, *s2 = NULL, *ser = NULL;
    for (long k = 0; k < k0; k++)
        step(b, k * dt, dt);
    last_log[0] = 0;
    int ok = save(b, &s) == 0 && reserialize(b, s, &s2, &ser) == 0;
    if (!can_state) /* the flag false: the FMU must say it cannot, not save half a state */
        check(!ok && last_log[0], "canGetAndSetFMUState false: the FMU state refused, logged");
    for (long k = k0; k < k0 + m; k++)
        step(b, k * dt, dt);
    outputs(b, v);
    ok = ok && restore(b, s2) == 0;
    for (long k = k0; can_state && ok && k < k0 + m; k++) { /* every row, not the last only */
        ok = step(b, k * dt, dt) == 0;
        outputs(b, w);
        ok = ok && !memcmp(w, first + (size_t)(k + 1) * nout, nout * sizeof *w);
    }
    if (can_state)
        check(ok && !memcmp(v, w, nout * sizeof *v) &&
              !memcmp(v, first + (size_t)(k0 + m) * nout, nout * sizeof *v),
              "a saved and serialized FMU state, restored, steps to the same bits on every row");
    if (s)
        drop(b, &s);
    if (s2)
        drop(b, &s2);

    /* 4: steps the FMU must refuse */
    outputs(b, v);
    last_log[0] = 0;
    int r1 = step(b, (k0 + m) * dt, 1.5 * dt);
    check(r1 == 3 && strstr(last_log, "not a whole number of base ticks"),
          "a step of 1.5 ticks: Error, logged");
    printf("  logged: %s\n", last_log);
    last_log[0] = 0;
    int r2 = step(b, (k0 + m + 3) * dt, dt);
    check(r2 == 3 && strstr(last_log, "is not the FMU's time"),
          "a step from a wrong communication point: Error, logged");
    outputs(b, w);
    check(!memcmp(v, w, nout * sizeof *v), "a refused step changes nothing");

    /* 5: Reset mid-run, initialized again: the first run's bits from the start */
    int ok5 = again(b) == 0;
    for (long k = 0; ok5 && k < k0; k++)
        ok5 = step(b, k * dt, dt) == 0;
    outputs(b, v);
    check(ok5 && !memcmp(v, first + (size_t)k0 * nout, nout * sizeof *v),
          "Reset and initialized again, it steps to the first run's bits");
    finish(b);
    free(first), free(ser);
    if (getenv("MASTER_PI_CSV"))
        failures += closed_loop(argv[1], getenv("MASTER_PI_CSV"), n);
    if (md.version == 2)
        check(live_blocks == 0, "every block of allocateMemory freed by freeMemory");
    fmu_md_free(&md);
    printf("master: %d failed\n", failures);
    return failures != 0;
}
