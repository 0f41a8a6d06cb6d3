/* smoke.c - smoke test of a port (uses ports/port.h only): integrates a damped pendulum
 * with classical RK4 in double for 20000 steps using only + - * / (sin is a fixed
 * polynomial), prints the 64-bit FNV-1a hash of the final state's bits (identical on
 * every target when built with -ffp-contract=off), then times 101 further single steps
 * with port_cycles() (whole-run delta and min/median/max per step; that state is hashed
 * too), runs the periodic timer for 5 ticks (one overrunning on purpose, which
 * port_timer_late must report) and exits 0 when every check passed. */
#include <stdint.h>

#include "port.h"

#define SMOKE_STEPS 20000
#define SMOKE_SAMPLES 101
#define SMOKE_TICKS 5
#define SMOKE_TICK_US 1000u

typedef struct {
    double th; /* angle [rad] */
    double om; /* angular velocity [rad/s] */
} pend_state;

/* sin(x) for |x| <= 1.6 by its Taylor polynomial to x^15 (error < 1e-13 there);
   Horner form, + and * only. */
static double poly_sin(double x)
{
    double x2 = x * x;
    double p = -1.0 / 1307674368000.0;
    p = p * x2 + 1.0 / 6227020800.0;
    p = p * x2 - 1.0 / 39916800.0;
    p = p * x2 + 1.0 / 362880.0;
    p = p * x2 - 1.0 / 5040.0;
    p = p * x2 + 1.0 / 120.0;
    p = p * x2 - 1.0 / 6.0;
    p = p * x2 + 1.0;
    return p * x;
}

static pend_state deriv(pend_state s)
{
    const double g_over_l = 9.81 / 0.75;
    const double damping = 0.05;
    pend_state d;
    d.th = s.om;
    d.om = -g_over_l * poly_sin(s.th) - damping * s.om;
    return d;
}

static pend_state rk4_step(pend_state s, double h)
{
    pend_state k1 = deriv(s);
    pend_state t = {s.th + 0.5 * h * k1.th, s.om + 0.5 * h * k1.om};
    pend_state k2 = deriv(t);
    t.th = s.th + 0.5 * h * k2.th;
    t.om = s.om + 0.5 * h * k2.om;
    pend_state k3 = deriv(t);
    t.th = s.th + h * k3.th;
    t.om = s.om + h * k3.om;
    pend_state k4 = deriv(t);
    s.th = s.th + h / 6.0 * (k1.th + 2.0 * k2.th + 2.0 * k3.th + k4.th);
    s.om = s.om + h / 6.0 * (k1.om + 2.0 * k2.om + 2.0 * k3.om + k4.om);
    return s;
}

/* ------------------------------------------------------------------ output helpers */

static uint64_t double_bits(double d)
{
    union {
        double d;
        uint64_t u;
    } u;
    u.d = d;
    return u.u;
}

/* FNV-1a over the 8 bytes of v, least significant first (independent of endianness). */
static uint64_t fnv1a_u64(uint64_t h, uint64_t v)
{
    for (int i = 0; i < 8; i++) {
        h ^= (v >> (8 * i)) & 0xFFu;
        h *= 0x100000001b3ull;
    }
    return h;
}

static void put_hex64(uint64_t v)
{
    char buf[17];
    for (int i = 0; i < 16; i++) buf[i] = "0123456789abcdef"[(v >> (60 - 4 * i)) & 0xFu];
    buf[16] = '\0';
    port_write(buf);
}

static void put_u64(uint64_t v)
{
    char buf[21];
    int i = 20;
    buf[i] = '\0';
    do {
        buf[--i] = (char)('0' + (int)(v % 10u));
        v /= 10u;
    } while (v);
    port_write(&buf[i]);
}

static void put_kv(const char *key, uint64_t v)
{
    port_write(key);
    put_u64(v);
}

/* ------------------------------------------------------------------ timer */

static volatile uint32_t smoke_ticks;
static volatile uint32_t smoke_late;

/* The third tick overruns on purpose: it busy-waits until port_timer_late() says its
   period is over. Every other tick must not be late. */
static void on_tick(void)
{
    uint32_t n = ++smoke_ticks;
    if (n == 3)
        while (!port_timer_late()) {
        }
    if (port_timer_late()) smoke_late++;
}

int app_main(void)
{
    int failures = 0;
    const double h = 1e-3;
    pend_state s = {1.2, 0.0};

    /* The run whose final state is hashed. */
    uint64_t c0 = port_cycles();
    for (int i = 0; i < SMOKE_STEPS; i++) s = rk4_step(s, h);
    uint64_t c1 = port_cycles();

    uint64_t hash = 0xcbf29ce484222325ull;
    hash = fnv1a_u64(hash, double_bits(s.th));
    hash = fnv1a_u64(hash, double_bits(s.om));
    port_write("smoke: rk4 steps=20000 th=0x");
    put_hex64(double_bits(s.th));
    port_write(" om=0x");
    put_hex64(double_bits(s.om));
    port_write("\nsmoke: hash=");
    put_hex64(hash);
    port_write("\n");

    /* Cost of single steps: one port_cycles() call per step (the pattern a tick loop
       uses), min/median/max over SMOKE_SAMPLES steps. */
    uint64_t d[SMOKE_SAMPLES];
    pend_state q = s;
    uint64_t prev = port_cycles();
    for (int i = 0; i < SMOKE_SAMPLES; i++) {
        q = rk4_step(q, h);
        uint64_t now = port_cycles();
        d[i] = now - prev;
        prev = now;
    }
    /* Use q, or the compiler may drop the sampled steps as dead code. */
    uint64_t hash2 = fnv1a_u64(fnv1a_u64(hash, double_bits(q.th)), double_bits(q.om));
    port_write("smoke: hash_sampled=");
    put_hex64(hash2);
    port_write("\n");
    for (int i = 1; i < SMOKE_SAMPLES; i++) { /* insertion sort */
        uint64_t v = d[i];
        int j = i;
        for (; j > 0 && d[j - 1] > v; j--) d[j] = d[j - 1];
        d[j] = v;
    }
    put_kv("smoke: cycles rk4_total=", c1 - c0);
    put_kv(" step_min=", d[0]);
    put_kv(" step_med=", d[SMOKE_SAMPLES / 2]);
    put_kv(" step_max=", d[SMOKE_SAMPLES - 1]);
    port_write("\n");

    /* Periodic timer: SMOKE_TICKS waits for periods of SMOKE_TICK_US, one tick overrunning.
       Bare-metal ports call the tick function from the timer interrupt (the overrun
       tick is followed at once by the next one); POSIX calls it from port_timer_wait. */
    smoke_ticks = 0;
    smoke_late = 0;
    uint64_t t0 = port_cycles();
    if (port_timer_start(SMOKE_TICK_US, on_tick) != 0) {
        port_write("smoke: FAIL port_timer_start\n");
        failures++;
    } else {
        for (int i = 0; i < SMOKE_TICKS; i++) port_timer_wait();
        port_timer_stop();
        uint64_t t1 = port_cycles();
        uint32_t n = smoke_ticks, late = smoke_late;
        put_kv("smoke: timer waits=", SMOKE_TICKS);
        put_kv(" late=", late);
        put_kv(" cycles=", t1 - t0);
        port_write("\n");
        if (n < SMOKE_TICKS || late != 1) {
            put_kv("smoke: FAIL timer ticks=", n);
            port_write("\n");
            failures++;
        }
    }

    port_write(failures ? "smoke: FAIL\n" : "smoke: ok\n");
    return failures ? 1 : 0;
}
