/* port.c - the board-neutral Cortex-M port (any ARMv7-M or ARMv8-M mainline core: M3, M4,
 * M4F, M7, M33...): implements ports/port.h with the core's own registers only, so it runs
 * on an STM32, an NXP, a Nordic or an Atmel part as it is. docs/porting.md tells how to
 * build it; ports/cmsis/memory.ld holds the numbers a board changes.
 *
 *   tick:    SysTick on the core clock, PORT_CORE_HZ (required: -DPORT_CORE_HZ=168000000);
 *            SysTick_Handler calls the tick function; port_timer_wait sleeps in WFI.
 *            Periods longer than the 24-bit reload use a whole software divider.
 *   cycles:  the DWT cycle counter, enabled here (DEMCR.TRCENA, DWT_CTRL.CYCCNTENA; the
 *            M7's lock access register unlocked first): without that it reads 0 unless a
 *            debugger enabled it. Extended to 64 bits by counting wraps. QEMU does not
 *            model the DWT: there it reads 0 (the MPS2 port times with a board timer).
 *   console: semihosting (PORT_CONSOLE_SEMIHOST, the default: needs a debugger or QEMU,
 *            without one the bkpt faults) or none (-DPORT_CONSOLE_SEMIHOST=0: port_write
 *            drops the text; put your UART driver into port_write).
 *   background level: PendSV at the lowest priority, SysTick at the highest.
 * The register names follow CMSIS (SysTick->LOAD is PORT_SYST_RVR here): with your vendor's
 * CMSIS headers at hand the same lines read SysTick_Config(PORT_CORE_HZ / ...). The reset
 * handler, vector table and fault reports are ports/cortex-m/startup.c (plain ARMv7-M, no
 * board in it), which calls cm_port_init before app_main. */
#include <stdint.h>

#include "../port.h"
#include "../cortex-m/cm_port.h"

#ifndef PORT_CORE_HZ
#error "ports/cmsis/port.c: define PORT_CORE_HZ, the core clock in Hz (e.g. -DPORT_CORE_HZ=168000000 on an STM32F407 at full speed)"
#endif
#ifndef PORT_CONSOLE_SEMIHOST
#define PORT_CONSOLE_SEMIHOST 1
#endif

#define PORT_REG(addr) (*(volatile uint32_t *)(uintptr_t)(addr))
/* architectural registers (ARMv7-M Architecture Reference Manual, B3 and C1) */
#define PORT_SYST_CSR    PORT_REG(0xE000E010u) /* SysTick->CTRL */
#define PORT_SYST_RVR    PORT_REG(0xE000E014u) /* SysTick->LOAD (24 bits) */
#define PORT_SYST_CVR    PORT_REG(0xE000E018u) /* SysTick->VAL */
#define PORT_ICSR        PORT_REG(0xE000ED04u) /* SCB->ICSR */
#define PORT_SHPR3       PORT_REG(0xE000ED20u) /* SCB->SHP: PendSV, SysTick priorities */
#define PORT_DEMCR       PORT_REG(0xE000EDFCu) /* CoreDebug->DEMCR, bit 24 TRCENA */
#define PORT_DWT_CTRL    PORT_REG(0xE0001000u) /* DWT->CTRL, bit 0 CYCCNTENA */
#define PORT_DWT_CYCCNT  PORT_REG(0xE0001004u) /* DWT->CYCCNT */
#define PORT_DWT_LAR     PORT_REG(0xE0001FB0u) /* DWT->LAR (M7: writes need the key) */

/* ------------------------------------------------------------------ console and exit */

void port_write(const char *s)
{
#if PORT_CONSOLE_SEMIHOST
    if (s && *s)
        cm_semihost(CM_SYS_WRITE0, s);
#else
    (void)s; /* your UART here */
#endif
}

void port_exit(int code)
{
#if PORT_CONSOLE_SEMIHOST
    uint32_t c = (uint32_t)code & 0xFFu;
    const uint32_t block[2] = {CM_ADP_STOPPED_APPLICATION_EXIT, code != 0 && c == 0 ? 1 : c};
    cm_semihost(CM_SYS_EXIT_EXTENDED, block);
#else
    (void)code;
#endif
    for (;;)
        __asm__ volatile("cpsid i\n\twfi");
}

/* ------------------------------------------------------------------ cycles */

static uint32_t cyc_last;
static uint64_t cyc_high;

void cm_port_init(void)
{
    PORT_DEMCR |= 1u << 24;   /* TRCENA: the DWT is powered */
    PORT_DWT_LAR = 0xC5ACCE55u; /* unlock (M7; ignored where there is no lock) */
    PORT_DWT_CYCCNT = 0;
    PORT_DWT_CTRL |= 1u;      /* CYCCNTENA */
    cyc_last = 0, cyc_high = 0;
}

uint64_t port_cycles(void)
{
    uint32_t primask;
    __asm__ volatile("mrs %0, primask\n\tcpsid i" : "=r"(primask)::"memory");
    uint32_t now = PORT_DWT_CYCCNT;
    if (now < cyc_last)
        cyc_high += (uint64_t)1 << 32;
    cyc_last = now;
    uint64_t c = cyc_high | now;
    __asm__ volatile("msr primask, %0" ::"r"(primask) : "memory");
    return c;
}

/* ------------------------------------------------------------------ tick (SysTick) */

static void (*volatile tick_fn)(void *);
static void *volatile tick_ctx;
static volatile uint32_t tick_flag, wraps, period_start;
static uint32_t tick_div, tick_count;

void SysTick_Handler(void)
{
    uint32_t w = ++wraps;
    if (++tick_count < tick_div)
        return;
    tick_count = 0, period_start = w, tick_flag = 1;
    void (*fn)(void *) = tick_fn;
    if (fn)
        fn(tick_ctx);
}

int port_timer_start(uint32_t period_us, void (*fn)(void *ctx), void *ctx)
{
    uint64_t ticks = (uint64_t)period_us * PORT_CORE_HZ / 1000000u;
    uint64_t div = (ticks + 0xFFFFFFu) / 0x1000000u; /* the smallest divider in 24 bits */
    while (div > 0 && div <= 0xFFFFu && ticks % div != 0)
        div++;
    if (period_us == 0 || div == 0 || div > 0xFFFFu || ticks / div < 2)
        return -1; /* not a whole number of core cycles per SysTick period */
    PORT_SYST_CSR = 0;
    tick_ctx = ctx, tick_fn = fn;
    tick_div = (uint32_t)div, tick_count = 0, tick_flag = 0, wraps = 0, period_start = 0;
    PORT_SYST_RVR = (uint32_t)(ticks / div) - 1u;
    PORT_SYST_CVR = 0;
    PORT_SYST_CSR = 7u; /* core clock, interrupt, enable */
    return 0;
}

void port_timer_wait(void)
{
    for (;;) { /* tested with interrupts masked: WFI still wakes on the pending tick */
        __asm__ volatile("cpsid i" ::: "memory");
        if (tick_flag || (PORT_SYST_CSR & 1u) == 0) {
            tick_flag = 0;
            __asm__ volatile("cpsie i" ::: "memory");
            return;
        }
        __asm__ volatile("dsb\n\twfi\n\tcpsie i\n\tisb" ::: "memory");
    }
}

int port_timer_late(void)
{
    if ((PORT_SYST_CSR & 1u) == 0)
        return 0;
    uint32_t primask;
    __asm__ volatile("mrs %0, primask\n\tcpsid i" : "=r"(primask)::"memory");
    uint32_t w = wraps + ((PORT_ICSR >> 26) & 1u); /* a SysTick pending: PENDSTSET */
    int late = w - period_start >= tick_div;
    __asm__ volatile("msr primask, %0" ::"r"(primask) : "memory");
    return late;
}

void port_timer_stop(void)
{
    PORT_SYST_CSR = 0;
    PORT_ICSR = 1u << 25; /* PENDSTCLR */
    tick_fn = 0, tick_flag = 0;
}

/* ------------------------------------------------------------------ background level */

static void (*volatile bg_fn)(void *);
static void *volatile bg_ctx;

void PendSV_Handler(void)
{
    void (*fn)(void *) = bg_fn;
    if (fn)
        fn(bg_ctx);
}

int port_bg_start(void (*fn)(void *ctx), void *ctx)
{
    bg_ctx = ctx, bg_fn = fn;
    PORT_SHPR3 = (PORT_SHPR3 & 0x0000FFFFu) | (0xFFu << 16); /* PendSV lowest, SysTick 0 */
    return 0;
}

void port_bg_request(void)
{
    PORT_ICSR = 1u << 28; /* PENDSVSET */
    __asm__ volatile("dsb\n\tisb" ::: "memory");
}
