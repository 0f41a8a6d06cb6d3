/* port.c - the POSIX port: console through stdio, exit through exit(), and a periodic
 * real-time tick from CLOCK_MONOTONIC with absolute deadlines (clock_nanosleep with
 * TIMER_ABSTIME), so a late tick does not shift every later one. The simulated clock
 * needs no timer at all: the runner ticks as fast as it can (see main.c). */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "port.h"

#define NS_PER_S 1000000000L

static struct timespec next_deadline;
static long period_ns;
static void (*tick_fn)(void *);
static void *tick_ctx;

/* a console has nowhere to report its own failure: the result is dropped on purpose */
void port_write(const char *s)
{
    (void)fputs(s, stdout);
}

void port_exit(int code)
{
    (void)fflush(stdout);
    exit(code);
}

/* no deterministic counter on a host: benchmarks use callgrind or wall time instead */
uint64_t port_cycles(void)
{
    return 0;
}

static void advance(struct timespec *t, long ns)
{
    t->tv_nsec += ns;
    while (t->tv_nsec >= NS_PER_S) {
        t->tv_nsec -= NS_PER_S;
        t->tv_sec++;
    }
}

int port_timer_start(uint32_t period_us, void (*fn)(void *ctx), void *ctx)
{
    if (period_us == 0 || !fn)
        return -1;
    period_ns = (long)period_us * 1000L;
    tick_fn = fn, tick_ctx = ctx;
    clock_gettime(CLOCK_MONOTONIC, &next_deadline);
    advance(&next_deadline, period_ns);
    return 0;
}

/* sleeps until the next absolute deadline, then runs the tick function */
void port_timer_wait(void)
{
    while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &next_deadline, 0) != 0)
        ;
    advance(&next_deadline, period_ns);
    if (tick_fn)
        tick_fn(tick_ctx);
}

void port_timer_stop(void)
{
    tick_fn = 0;
}

/* the deadline of the tick now running has passed if the clock is beyond it */
int port_timer_late(void)
{
    struct timespec now;
    clock_gettime(CLOCK_MONOTONIC, &now);
    return now.tv_sec > next_deadline.tv_sec ||
           (now.tv_sec == next_deadline.tv_sec && now.tv_nsec > next_deadline.tv_nsec);
}

/* no interrupt level below the timer's here: the application runs background work
   itself (between ticks in its main loop, or in a thread of lower priority) */
int port_bg_start(void (*fn)(void *ctx), void *ctx)
{
    (void)fn, (void)ctx;
    return -1;
}

void port_bg_request(void) {}
