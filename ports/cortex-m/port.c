/* port.c - the Cortex-M bare-metal port (MPS2 AN385 M3 / AN386 M4F / AN500 M7, real boards
 * or QEMU mps2-an385/-an386/-an500): implements ports/port.h.
 *
 * Console and exit (cm_port.h, -DCM_CONSOLE=...): by default ARM semihosting (bkpt 0xab):
 * port_write uses SYS_WRITE0, port_exit uses SYS_EXIT_EXTENDED {ADP_Stopped_ApplicationExit,
 * code}, so QEMU exits with the code. Run QEMU with -semihosting-config
 * enable=on,target=native,chardev=... (see ports/targets.mk); without a debugger the bkpt
 * faults and the fault handler locks up, so always run under timeout. A board without a
 * debugger builds with CM_CONSOLE_UART (polled CMSDK UART), CM_CONSOLE_ITM (stimulus port
 * 0, SWO) or CM_CONSOLE_NONE; then no bkpt is linked unless CM_EXIT_SEMIHOST=1 asks for
 * it (the cross tests use UART output with a semihosting exit).
 *
 * Time source for port_cycles: timer 1 of the CMSDK APB dual timer at 0x40002000, free
 * running, 32-bit, prescale 1, clocked by the 25 MHz SYSCLK; wrap-arounds are counted in
 * software to make 64 bits. The ARMv7-M DWT cycle counter is not used: QEMU does not
 * model it (CYCCNT reads 0). port_cycles returns timer ticks x 40 (CM_CYCLES_PER_TICK =
 * 1e9 / SYSCLK), i.e. nanoseconds of the 25 MHz board; under QEMU -icount shift=0 (one
 * instruction = 1 ns of virtual time) that is the retired-instruction count rounded down
 * to a multiple of 40, exact and repeatable run to run. Exact per-instruction counts
 * between two port_cycles calls: tools/dev/qemu/insn_count.c with addr=<port_cycles>.
 * Run with -icount shift=0,sleep=off so idle time (WFI) advances virtual time to the next
 * timer deadline deterministically instead of at host speed.
 *
 * Tick source for port_timer_*: SysTick on the processor clock (CM_SYSCLK_HZ). The
 * SysTick exception calls the registered function and sets a tick flag; port_timer_wait
 * sleeps (WFI) until the flag is set and clears it (ticks missed meanwhile coalesce).
 * Periods longer than the 24-bit reload (671 ms at 25 MHz) use a whole software divider
 * when one exists, else port_timer_start returns -1. port_timer_late reports an overrun
 * when the current period has already ended (another SysTick is pending or was taken).
 * SysTick keeps one pending tick: a tick function overrunning by several periods gets
 * one late call, the further missed periods are dropped (RISC-V and POSIX catch up).
 *
 * QEMU 7.2 quirk (mps2, -icount sleep=off): when the CPU sleeps in WFI, virtual time
 * jumps by twice the time left to the next timer deadline, so under QEMU every wait that
 * actually sleeps ends at 2x the remaining time (a 1 ms tick with little work in it is
 * ~2 ms of virtual time). Repeatable, and instruction counts per tick are unaffected,
 * but virtual time between ticks is stretched. The RISC-V virt machine does not do this.
 * Build with -DCM_TIMER_WAIT_SPIN=1 to poll the flag instead of WFI: exact tick times
 * under QEMU, at the cost of executing (and emulating) the idle loop. */
#include <stdint.h>

#include "../port.h"
#include "cm_port.h"

/* 1: port_timer_wait polls the tick flag instead of sleeping in WFI (see above). */
#ifndef CM_TIMER_WAIT_SPIN
#define CM_TIMER_WAIT_SPIN 0
#endif

#ifndef CM_CYCLES_PER_TICK
#define CM_CYCLES_PER_TICK (1000000000u / CM_SYSCLK_HZ)
#endif

/* ------------------------------------------------------------------ console */

#if CM_CONSOLE == CM_CONSOLE_UART
static void cm_console_init(void)
{
    CM_UART_BAUDDIV = CM_SYSCLK_HZ / CM_UART_BAUD;
    CM_UART_CTRL = 1u; /* transmit only, polled */
}
static void cm_console_putc(char ch)
{
    while (CM_UART_STATE & 1u) {
    }
    CM_UART_DATA = (uint32_t)(unsigned char)ch;
}
#elif CM_CONSOLE == CM_CONSOLE_ITM
static void cm_console_init(void) {}
static void cm_console_putc(char ch)
{
    if ((CM_ITM_TCR & 1u) == 0 || (CM_ITM_TER & 1u) == 0) return; /* no trace probe */
    while ((CM_ITM_PORT0 & 1u) == 0) {
    }
    *(volatile uint8_t *)(uintptr_t)0xE0000000u = (uint8_t)ch;
}
#else
static void cm_console_init(void) {}
#endif

void port_write(const char *s)
{
    if (!s || !*s) return;
#if CM_CONSOLE == CM_CONSOLE_SEMIHOST
    cm_semihost(CM_SYS_WRITE0, s);
#elif CM_CONSOLE == CM_CONSOLE_UART || CM_CONSOLE == CM_CONSOLE_ITM
    while (*s) cm_console_putc(*s++);
#endif
}

void port_exit(int code)
{
#if CM_EXIT_SEMIHOST
    /* Shell exit statuses are 8 bits: never let a failure wrap to 0. */
    uint32_t c = (uint32_t)code & 0xFFu;
    if (code != 0 && c == 0) c = 1;
    const uint32_t block[2] = {CM_ADP_STOPPED_APPLICATION_EXIT, c};
    cm_semihost(CM_SYS_EXIT_EXTENDED, block);
    /* Host without SYS_EXIT_EXTENDED: plain SYS_EXIT (status 0 or 1 only). */
    cm_semihost(CM_SYS_EXIT, (const void *)(uintptr_t)(c == 0 ? CM_ADP_STOPPED_APPLICATION_EXIT : 0x20023u /* RunTimeErrorUnknown */));
#else
    (void)code; /* nowhere to report it: the application printed its status */
#endif
    for (;;) __asm__ volatile("cpsid i\n\twfi");
}

/* ------------------------------------------------------------------ cost counter */

static uint32_t cm_cyc_last;  /* ticks elapsed at the previous read (low 32 bits) */
static uint64_t cm_cyc_high;  /* wrap-arounds << 32 */

void cm_port_init(void)
{
    cm_console_init();
    CM_DUALTIMER1_CTRL = 0; /* stop; free-running mode, interrupt disabled */
    CM_DUALTIMER1_LOAD = 0xFFFFFFFFu;
    CM_DUALTIMER1_CTRL = CM_DUALTIMER_CTRL_EN | CM_DUALTIMER_CTRL_32BIT;
    cm_cyc_last = 0;
    cm_cyc_high = 0;
}

uint64_t port_cycles(void)
{
    uint32_t primask;
    __asm__ volatile("mrs %0, primask\n\tcpsid i" : "=r"(primask)::"memory");
    uint32_t elapsed = 0xFFFFFFFFu - CM_DUALTIMER1_VALUE; /* down counter from 2^32-1 */
    if (elapsed < cm_cyc_last) cm_cyc_high += (uint64_t)1 << 32;
    cm_cyc_last = elapsed;
    uint64_t ticks = cm_cyc_high | elapsed;
    __asm__ volatile("msr primask, %0" ::"r"(primask) : "memory");
    return ticks * CM_CYCLES_PER_TICK;
}

/* ------------------------------------------------------------------ periodic tick */

static void (*volatile cm_tick_fn)(void *);
static void *volatile cm_tick_ctx;
static volatile uint32_t cm_tick_flag;
static uint32_t cm_tick_div;            /* SysTick interrupts per period */
static uint32_t cm_tick_count;          /* interrupts since the last period boundary */
static volatile uint32_t cm_wraps;      /* SysTick interrupts since port_timer_start */
static volatile uint32_t cm_period_start; /* cm_wraps when the current period began */

void SysTick_Handler(void)
{
    uint32_t w = ++cm_wraps;
    if (++cm_tick_count < cm_tick_div) return;
    cm_tick_count = 0;
    cm_period_start = w;
    cm_tick_flag = 1;
    void (*fn)(void *) = cm_tick_fn;
    if (fn) fn(cm_tick_ctx);
}

int port_timer_start(uint32_t period_us, void (*fn)(void *ctx), void *ctx)
{
    if (period_us == 0) return -1;
    uint64_t ticks = (uint64_t)period_us * (CM_SYSCLK_HZ / 1000000u);
    uint64_t div = (ticks + 0xFFFFFFu) / 0x1000000u; /* smallest divider fitting 24 bits */
    while (div <= 0xFFFFu && ticks % div != 0) div++;
    if (div > 0xFFFFu || ticks / div < 2) return -1;

    CM_SYST_CSR = 0;
    cm_tick_ctx = ctx;
    cm_tick_fn = fn;
    cm_tick_div = (uint32_t)div;
    cm_tick_count = 0;
    cm_tick_flag = 0;
    cm_wraps = 0;
    cm_period_start = 0;
    CM_SYST_RVR = (uint32_t)(ticks / div) - 1u;
    CM_SYST_CVR = 0;                          /* any write clears the counter */
    CM_SYST_CSR = (1u << 2) | (1u << 1) | 1u; /* processor clock, interrupt, enable */
    return 0;
}

void port_timer_wait(void)
{
    for (;;) {
        /* Check the flag with interrupts masked so a tick cannot slip in between the
           test and the WFI; WFI still wakes on the pending SysTick. */
        __asm__ volatile("cpsid i" ::: "memory");
        if (cm_tick_flag) {
            cm_tick_flag = 0;
            __asm__ volatile("cpsie i" ::: "memory");
            return;
        }
        if ((CM_SYST_CSR & 1u) == 0) { /* timer stopped: do not sleep forever */
            __asm__ volatile("cpsie i" ::: "memory");
            return;
        }
#if CM_TIMER_WAIT_SPIN
        __asm__ volatile("cpsie i" ::: "memory");
#else
        __asm__ volatile("dsb\n\twfi\n\tcpsie i\n\tisb" ::: "memory");
#endif
    }
}

/* The tick now running is late when its period is over: SysTick has wrapped cm_tick_div
   times since the period began, counting a wrap that is pending but not yet handled
   (the usual case when called from the tick function, inside the SysTick handler). */
int port_timer_late(void)
{
    if ((CM_SYST_CSR & 1u) == 0) return 0;
    uint32_t primask;
    __asm__ volatile("mrs %0, primask\n\tcpsid i" : "=r"(primask)::"memory");
    uint32_t w = cm_wraps + ((CM_ICSR >> 26) & 1u); /* ICSR.PENDSTSET */
    int late = w - cm_period_start >= cm_tick_div;
    __asm__ volatile("msr primask, %0" ::"r"(primask) : "memory");
    return late;
}

void port_timer_stop(void)
{
    CM_SYST_CSR = 0;
    CM_ICSR = 1u << 25; /* PENDSTCLR: drop a tick that is already pending */
    cm_tick_fn = 0;
    cm_tick_flag = 0;
}

/* ------------------------------------------------------------------ background level */

/* PendSV at the lowest priority (0xFF) and SysTick at the highest (0): the tick preempts
   the background work anywhere, the background never delays a tick. A request while
   PendSV runs pends it once more (the handler then finds nothing left to do). */
static void (*volatile cm_bg_fn)(void *);
static void *volatile cm_bg_ctx;

void PendSV_Handler(void)
{
    void (*fn)(void *) = cm_bg_fn;
    if (fn) fn(cm_bg_ctx);
}

int port_bg_start(void (*fn)(void *ctx), void *ctx)
{
    cm_bg_ctx = ctx;
    cm_bg_fn = fn;
    CM_SHPR3 = (CM_SHPR3 & 0x0000FFFFu) | (0xFFu << 16); /* PRI_14 PendSV lowest, PRI_15
                                                            SysTick highest */
    return 0;
}

void port_bg_request(void)
{
    CM_ICSR = 1u << 28; /* PENDSVSET */
    __asm__ volatile("dsb\n\tisb" ::: "memory");
}
