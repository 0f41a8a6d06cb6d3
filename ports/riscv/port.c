/* port.c - the RISC-V bare-metal port for QEMU virt (-bios none, machine mode, hart 0;
 * rv64gc/lp64d and rv32imac/ilp32): implements ports/port.h.
 *
 * Console: the ns16550 UART at 0x10000000 (polls LSR.THRE, offset 5 bit 5, before each
 * byte; "\n" is sent as is). Exit: the SiFive test device at 0x100000, 0x5555 for status
 * 0, (status << 16) | 0x3333 otherwise, so QEMU exits with the status.
 *
 * Time source for port_cycles: the minstret CSR (minstreth:minstret on rv32, read
 * hi-lo-hi). Under QEMU -icount shift=0 it is QEMU's virtual clock in ns, i.e. exactly
 * the number of instructions executed, the same on every run; with sleep=off, idle time
 * in WFI jumps straight to the next timer deadline, so it stays repeatable across
 * port_timer_wait too. (Without -icount it follows the host clock.)
 *
 * Tick source for port_timer_*: the CLINT machine timer, mtime at 0x0200BFF8 and hart 0's
 * mtimecmp at 0x02004000, 10 MHz on virt (RV_MTIME_HZ). The machine timer interrupt
 * (through rv_trap_entry in start.S) advances mtimecmp by one period from the previous
 * deadline (no drift), sets a tick flag and calls the registered function;
 * port_timer_wait sleeps (WFI) until the flag is set and clears it (ticks missed
 * meanwhile coalesce); port_timer_late reports an overrun when that next deadline has
 * already passed. A tick function overrunning by several periods gets the missed calls
 * back to back (each interrupt advances the deadline by one period), as POSIX does with
 * absolute deadlines. Any other trap (exception or unexpected interrupt) is reported on
 * the UART and ends the run with status 3. */
#include <stdint.h>

#include "../port.h"

#ifndef RV_MTIME_HZ
#define RV_MTIME_HZ 10000000u
#endif

#define RV_UART_BASE   0x10000000u
#define RV_TEST_BASE   0x00100000u
#define RV_CLINT_MTIMECMP0 0x02004000u
#define RV_CLINT_MTIME     0x0200BFF8u

#define RV_REG8(a)  (*(volatile uint8_t *)(uintptr_t)(a))
#define RV_REG32(a) (*(volatile uint32_t *)(uintptr_t)(a))

#define RV_MIP_MTIP    (1u << 7)
#define RV_MSTATUS_MIE (1u << 3)

void rv_port_init(void);
void rv_trap(uintptr_t mcause, uintptr_t mepc, uintptr_t mtval);

#define rv_csr_read(csr)                                       \
    __extension__({                                            \
        uintptr_t v_;                                          \
        __asm__ volatile("csrr %0, " #csr : "=r"(v_)::"memory"); \
        v_;                                                    \
    })
#define rv_csr_set(csr, bits) __asm__ volatile("csrs " #csr ", %0" ::"r"((uintptr_t)(bits)) : "memory")
#define rv_csr_clear(csr, bits) __asm__ volatile("csrc " #csr ", %0" ::"r"((uintptr_t)(bits)) : "memory")

/* ------------------------------------------------------------------ console and exit */

static void rv_putc(char c)
{
    while ((RV_REG8(RV_UART_BASE + 5) & 0x20u) == 0) {
    }
    RV_REG8(RV_UART_BASE) = (uint8_t)c;
}

void port_write(const char *s)
{
    if (!s) return;
    while (*s) rv_putc(*s++);
}

void port_exit(int code)
{
    /* Shell exit statuses are 8 bits: never let a failure wrap to 0. */
    uint32_t c = (uint32_t)code & 0xFFu;
    if (code != 0 && c == 0) c = 1;
    RV_REG32(RV_TEST_BASE) = c == 0 ? 0x5555u : (c << 16) | 0x3333u;
    for (;;) __asm__ volatile("wfi");
}

static void rv_write_hex(const char *label, uint64_t v)
{
    char buf[19];
    buf[0] = '0';
    buf[1] = 'x';
    for (int i = 0; i < 16; i++) buf[2 + i] = "0123456789abcdef"[(v >> (60 - 4 * i)) & 0xFu];
    buf[18] = '\0';
    port_write(label);
    port_write(buf);
}

/* ------------------------------------------------------------------ cost counter */

uint64_t port_cycles(void)
{
#if __riscv_xlen == 32
    uint32_t hi, lo, hi2;
    do {
        hi = (uint32_t)rv_csr_read(minstreth);
        lo = (uint32_t)rv_csr_read(minstret);
        hi2 = (uint32_t)rv_csr_read(minstreth);
    } while (hi != hi2);
    return ((uint64_t)hi << 32) | lo;
#else
    return rv_csr_read(minstret);
#endif
}

/* ------------------------------------------------------------------ machine timer */

static uint64_t rv_mtime(void)
{
#if __riscv_xlen == 32
    uint32_t hi, lo, hi2;
    do {
        hi = RV_REG32(RV_CLINT_MTIME + 4);
        lo = RV_REG32(RV_CLINT_MTIME);
        hi2 = RV_REG32(RV_CLINT_MTIME + 4);
    } while (hi != hi2);
    return ((uint64_t)hi << 32) | lo;
#else
    return *(volatile uint64_t *)(uintptr_t)RV_CLINT_MTIME;
#endif
}

static void rv_set_mtimecmp(uint64_t t)
{
#if __riscv_xlen == 32
    /* Never let the 64-bit compare value pass through a smaller value than both halves. */
    RV_REG32(RV_CLINT_MTIMECMP0 + 4) = 0xFFFFFFFFu;
    RV_REG32(RV_CLINT_MTIMECMP0) = (uint32_t)t;
    RV_REG32(RV_CLINT_MTIMECMP0 + 4) = (uint32_t)(t >> 32);
#else
    *(volatile uint64_t *)(uintptr_t)RV_CLINT_MTIMECMP0 = t;
#endif
}

static void (*volatile rv_tick_fn)(void *);
static void *volatile rv_tick_ctx;
static volatile uint32_t rv_tick_flag;
static volatile uint32_t rv_tick_running;
static uint64_t rv_tick_period; /* mtime ticks */
static uint64_t rv_tick_next;   /* current deadline */

void rv_port_init(void)
{
    rv_set_mtimecmp(UINT64_MAX);
}

void rv_trap(uintptr_t mcause, uintptr_t mepc, uintptr_t mtval)
{
    const uintptr_t irq_bit = (uintptr_t)1 << (sizeof(uintptr_t) * 8 - 1);
    if (mcause == (irq_bit | 7u)) { /* machine timer interrupt */
        rv_tick_next += rv_tick_period;
        rv_set_mtimecmp(rv_tick_next);
        rv_tick_flag = 1;
        void (*fn)(void *) = rv_tick_fn;
        if (fn) fn(rv_tick_ctx);
        return;
    }
    port_write("\n*** TRAP: ");
    port_write((mcause & irq_bit) ? "unexpected interrupt" : "exception");
    rv_write_hex(" mcause=", mcause);
    rv_write_hex(" mepc=", mepc);
    rv_write_hex(" mtval=", mtval);
    port_write("\n");
    port_exit(3);
}

int port_timer_start(uint32_t period_us, void (*fn)(void *ctx), void *ctx)
{
    if (period_us == 0) return -1;
    uint64_t ticks = (uint64_t)period_us * (RV_MTIME_HZ / 1000000u);
    if (ticks == 0) return -1;

    rv_csr_clear(mie, RV_MIP_MTIP);
    rv_tick_ctx = ctx;
    rv_tick_fn = fn;
    rv_tick_period = ticks;
    rv_tick_flag = 0;
    rv_tick_next = rv_mtime() + ticks;
    rv_set_mtimecmp(rv_tick_next);
    rv_tick_running = 1;
    rv_csr_set(mie, RV_MIP_MTIP);
    rv_csr_set(mstatus, RV_MSTATUS_MIE);
    return 0;
}

void port_timer_wait(void)
{
    for (;;) {
        /* Test the flag with interrupts masked so the tick cannot slip in between the
           test and the WFI; WFI still wakes on the pending (mie-enabled) interrupt. */
        rv_csr_clear(mstatus, RV_MSTATUS_MIE);
        if (rv_tick_flag || !rv_tick_running) {
            rv_tick_flag = 0;
            rv_csr_set(mstatus, RV_MSTATUS_MIE);
            return;
        }
        __asm__ volatile("wfi" ::: "memory");
        rv_csr_set(mstatus, RV_MSTATUS_MIE);
    }
}

/* The tick now running is late when the deadline that ends its period (the value just
   written to mtimecmp) has passed, i.e. the next machine timer interrupt is already due. */
int port_timer_late(void)
{
    if (!rv_tick_running) return 0;
    uintptr_t prev;
    /* Mask the timer interrupt while reading the 64-bit deadline (two loads on rv32). */
    __asm__ volatile("csrrc %0, mstatus, %1" : "=r"(prev) : "r"((uintptr_t)RV_MSTATUS_MIE) : "memory");
    uint64_t deadline = rv_tick_next;
    if (prev & RV_MSTATUS_MIE) rv_csr_set(mstatus, RV_MSTATUS_MIE);
    return rv_mtime() >= deadline;
}

void port_timer_stop(void)
{
    rv_csr_clear(mie, RV_MIP_MTIP);
    rv_set_mtimecmp(UINT64_MAX);
    rv_tick_running = 0;
    rv_tick_fn = 0;
    rv_tick_flag = 0;
}

/* no interrupt level below the timer's here: the application runs background work
   itself (between ticks in its main loop, or in a thread of lower priority) */
int port_bg_start(void (*fn)(void *ctx), void *ctx)
{
    (void)fn, (void)ctx;
    return -1;
}

void port_bg_request(void) {}
