/* test_bg.c - the background set (rt/bg.c) against preemption: the same trace bit for bit
 * as the simulated clock when the step runs in a thread that the ticks preempt at forced
 * points (before right-hand-side evaluations chosen by a seeded generator), when it runs
 * in a lower-priority thread paced by the POSIX timer, and the background transition of
 * pendulum10_actuated against a fine reference. Host only (threads, the wall clock). */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <pthread.h>
#include <string.h>

#include "harness.h"
#include "port.h"
#include "rt.h"
#include "rt_sim.h"
#include "scenes/scenes.h"

static rt_sim ref, sim, ctx;

/* ------------------------------------------------------------------ one core, forced
   preemption: a baton passed between the tick (main thread) and the background thread,
   so exactly one runs at a time, as on a single core where the tick interrupt preempts
   the background at the points the hook picks */

static pthread_mutex_t mu = PTHREAD_MUTEX_INITIALIZER;
static pthread_cond_t cv = PTHREAD_COND_INITIALIZER;
static int turn;            /* 0: the tick runs, 1: the background runs */
static int quit;
static uint64_t rng = 1;    /* seeded: the preemption pattern of one run */
static unsigned preempt_every; /* 1 in preempt_every evaluations yields (0: never) */
static long preemptions;
static pthread_t bg_thread;

static unsigned next_rand(void)
{
    rng = rng * 6364136223846793005ull + 1442695040888963407ull;
    return (unsigned)(rng >> 33);
}

/* hands the baton to `to` and waits until it comes back to `me` */
static void pass(int me, int to)
{
    pthread_mutex_lock(&mu);
    turn = to;
    pthread_cond_broadcast(&cv);
    while (turn != me && !quit)
        pthread_cond_wait(&cv, &mu);
    pthread_mutex_unlock(&mu);
}

/* the wrapped method: every right-hand side of the background step may be preempted */
static const rt_integrator *inner;
static rt_status hooked_eval(void *f, real_t t, real_t *xdot)
{
    if (pthread_equal(pthread_self(), bg_thread) && preempt_every &&
        next_rand() % preempt_every == 0) {
        preemptions++;
        pass(1, 0);
    }
    const rt_rhs *g = f;
    return g->eval(g->ctx, t, xdot);
}
static rt_status hooked_step(const rt_integrator *m, const rt_rhs *f, real_t t, real_t h,
                             real_t *x, uint16_t n, const rt_iwork *w)
{
    (void)m;
    rt_rhs g = {hooked_eval, (void *)f};
    return inner->step(inner, &g, t, h, x, n, w);
}

static void *bg_main(void *arg)
{
    const rt_scene *sc = arg;
    pthread_mutex_lock(&mu);
    for (;;) {
        while (turn != 1 && !quit)
            pthread_cond_wait(&cv, &mu);
        if (quit)
            break;
        pthread_mutex_unlock(&mu);
        if (rt_bg_pending(&sim))
            rt_background(sc, &sim);
        pthread_mutex_lock(&mu);
        turn = 0;
        pthread_cond_broadcast(&cv);
    }
    pthread_mutex_unlock(&mu);
    return 0;
}

/* the recorded values of both runs now, bit for bit */
static int same_now(const rt_scene *sc)
{
    int same = rt_time(sc, &ref) == rt_time(sc, &sim);
    for (uint16_t i = 0; i < sc->nrecs; i++) {
        real_t a = rt_rec_value(sc, &ref, i), b = rt_rec_value(sc, &sim, i);
        same = same && memcmp(&a, &b, sizeof a) == 0;
    }
    return same;
}

/* one run with seed and preemption rate against the simulated clock, tick by tick */
static int run_preempted(uint64_t seed, unsigned every, uint64_t ticks)
{
    static rt_set sets[RT_MAX_SETS];
    static rt_integrator hooked;
    rt_scene sc = mdl_scene_pendulum10_actuated;
    int s = -1, same = 1;
    for (uint8_t i = 0; i < sc.nsets; i++) {
        sets[i] = sc.sets[i];
        s = sets[i].background ? i : s;
    }
    inner = sets[s].method;
    hooked = *inner;
    hooked.step = hooked_step;
    sets[s].method = &hooked;
    sc.sets = sets;
    rng = seed, preempt_every = every, turn = 0, quit = 0;
    if (rt_init(&mdl_scene_pendulum10_actuated, &ref) != RT_OK || rt_init(&sc, &sim) != RT_OK ||
        rt_bg_attach(&sc, &sim, &ctx) != RT_OK)
        return 0;
    pthread_create(&bg_thread, 0, bg_main, &sc);
    rt_record(&sc, &sim, 0);
    rt_record(&mdl_scene_pendulum10_actuated, &ref, 0);
    for (uint64_t n = 0; n < ticks && same; n++) {
        /* the tick that reaches the deadline needs the step finished: let it run on */
        while (rt_bg_pending(&sim) && rt_ticks_done(&sim) + 1 >= sim.state.bg_due)
            pass(0, 1);
        rt_tick(&sc, &sim);
        rt_record(&sc, &sim, 0);
        rt_tick(&mdl_scene_pendulum10_actuated, &ref);
        rt_record(&mdl_scene_pendulum10_actuated, &ref, 0);
        same = same_now(&sc);
        /* the background gets the core at a random tick, until its hook yields */
        if (rt_bg_pending(&sim) && next_rand() % 2)
            pass(0, 1);
    }
    pthread_mutex_lock(&mu);
    quit = 1;
    pthread_cond_broadcast(&cv);
    pthread_mutex_unlock(&mu);
    pthread_join(bg_thread, 0);
    return same && rt_trace_hash(&sim) == rt_trace_hash(&ref) && rt_stats_of(&sim)->status == RT_OK &&
           rt_stats_of(&sim)->bg_late == 0;
}

static void test_bg_preempted(void)
{
    static const struct {
        uint64_t seed;
        unsigned every;
    } runs[] = {{1, 1}, {2, 2}, {3, 3}, {4, 7}, {5, 1}, {6, 2}};
    preemptions = 0;
    for (size_t i = 0; i < sizeof runs / sizeof runs[0]; i++)
        TH_CHECK(run_preempted(runs[i].seed, runs[i].every, 600));
    th_note("preemptions of the background step, over all runs", (double)preemptions);
    TH_CHECK(preemptions > 1000);
}

/* ------------------------------------------------------------------ the POSIX timer: the
   ticks paced by port_timer_wait in this thread, the background in another thread of
   lower priority where the system allows it, running concurrently on another core */

static pthread_mutex_t tmu = PTHREAD_MUTEX_INITIALIZER;
static pthread_cond_t tcv = PTHREAD_COND_INITIALIZER;
static int tquit;

static void *bg_loop(void *arg)
{
    const rt_scene *sc = arg;
    for (;;) {
        pthread_mutex_lock(&tmu);
        while (!rt_bg_pending(&sim) && !tquit)
            pthread_cond_wait(&tcv, &tmu);
        int q = tquit;
        pthread_mutex_unlock(&tmu);
        if (q)
            return 0;
        rt_background(sc, &sim);
    }
}

static void on_tick(void *arg)
{
    const rt_scene *sc = arg;
    rt_tick(sc, &sim);
    rt_record(sc, &sim, 0);
    pthread_mutex_lock(&tmu);
    pthread_cond_signal(&tcv); /* a step released now wakes the background */
    pthread_mutex_unlock(&tmu);
}

static void test_bg_timer(void)
{
    const rt_scene *sc = &mdl_scene_pendulum10_actuated;
    const uint64_t ticks = 300; /* 0.3 s at the scene's 1 ms */
    TH_CHECK(rt_init(sc, &ref) == RT_OK && rt_init(sc, &sim) == RT_OK);
    TH_CHECK(rt_bg_attach(sc, &sim, &ctx) == RT_OK);
    rt_record(sc, &ref, 0);
    rt_record(sc, &sim, 0);
    for (uint64_t n = 0; n < ticks; n++) {
        rt_tick(sc, &ref);
        rt_record(sc, &ref, 0);
    }
    pthread_t th;
    pthread_attr_t at;
    pthread_attr_init(&at);
    tquit = 0;
    pthread_create(&th, &at, bg_loop, (void *)sc);
    TH_CHECK(port_timer_start((uint32_t)(sc->dt * 1e6 + 0.5), on_tick, (void *)sc) == 0);
    while (rt_ticks_done(&sim) < ticks)
        port_timer_wait();
    port_timer_stop();
    pthread_mutex_lock(&tmu);
    tquit = 1;
    pthread_cond_signal(&tcv);
    pthread_mutex_unlock(&tmu);
    pthread_join(th, 0);
    th_note("background steps late (a loaded host; the trace is compared when 0)",
            (double)rt_stats_of(&sim)->bg_late);
    if (rt_stats_of(&sim)->bg_late == 0)
        TH_EQ_U64(rt_trace_hash(&sim), rt_trace_hash(&ref));
    else /* late steps are reported: never a silent difference (the status is the worst
            fault: the late step's longer extrapolation may add a worse one) */
        TH_CHECK(rt_status_severity(rt_stats_of(&sim)->status) >=
                     rt_status_severity(RT_E_OVERRUN) &&
                 rt_stats_of(&sim)->count[RT_CNT_OVERRUN] > 0);
}

/* ------------------------------------------------------------------ accuracy */

/* positions of B1..B10 (blocks 0..9) in s */
static void positions(const rt_sim *s, double *p)
{
    for (uint16_t b = 0; b < 10; b++)
        for (uint16_t k = 0; k < 3; k++)
            p[3 * b + k] = (double)rt_output(s, b, k);
}

/* the background transition of pendulum10_actuated against a fine reference (one set,
   Dormand-Prince at 0.1 ms, as tools/dev/bench/multirate_bench.c) every 0.128 s for 10 s:
   within the benchmark's bound of 1e-4 m (8.8e-5 m measured; binary32: 9.5e-5 m, checked
   against twice the bound) */
static void test_bg_reference(void)
{
    static rt_set one;
    rt_scene fine = mdl_scene_pendulum10_actuated_single;
    one = fine.sets[0];
    one.method = &rt_dopri5;
    one.cfg.jac_every = 0; /* ros2's Jacobian interval: dopri5 has none */
    fine.sets = &one;
    fine.dt = (real_t)1e-4;
    const rt_scene *sc = &mdl_scene_pendulum10_actuated;
    if (!TH_CHECK(rt_init(&fine, &ref) == RT_OK && rt_init(sc, &sim) == RT_OK))
        return; /* the loops below would wait for ticks that never come */
    double worst = 0, a[30], b[30];
    for (int k = 1; k <= 78; k++) {
        while (rt_ticks_done(&sim) < (uint64_t)(128 * k))
            rt_tick(sc, &sim);
        while (rt_ticks_done(&ref) < (uint64_t)(1280 * k))
            rt_tick(&fine, &ref);
        positions(&sim, a);
        positions(&ref, b);
        for (int i = 0; i < 30; i++)
            worst = fabs(a[i] - b[i]) > worst ? fabs(a[i] - b[i]) : worst;
    }
    th_note("pendulum10_actuated (chain in the background) - reference, every 0.128 s [m]",
            worst);
    TH_CHECK(worst < (RT_REAL_IS_FLOAT ? 2e-4 : 1e-4) && rt_stats_of(&sim)->status == RT_OK);
}

const th_test th_bg_host_tests[] = {
    {"bg_preempted", test_bg_preempted},
    {"bg_timer", test_bg_timer},
    {"bg_reference", test_bg_reference},
    {0, 0},
};
