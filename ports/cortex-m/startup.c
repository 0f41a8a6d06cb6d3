/* startup.c - Cortex-M (ARMv7-M: M3, M4F, M7) start-up code of the bare-metal port: the
 * vector table, the reset handler (copies .data from flash, zeroes .bss, enables the FPU
 * on FPU parts, starts the cost counter, calls app_main and exits with its status) and
 * the fault handlers, which report the exception, the stacked pc/lr and the fault status
 * registers through semihosting and exit with status 128 + exception number.
 *
 * Memory layout and the symbols used here come from ports/cortex-m/link.ld. */
#include <stdint.h>

#include "../port.h"
#include "cm_port.h"

/* Linker-script symbols (ports/cortex-m/link.ld). */
extern uint32_t __data_load[], __data_start[], __data_end[];
extern uint32_t __bss_start[], __bss_end[];
extern uint32_t __stack_top[];

void Reset_Handler(void);
void Fault_Handler(void);
/* the link UART's receive interrupt: a fault unless ports/cortex-m/uart.c is linked */
void cm_link_uart_irq(void) __attribute__((weak, alias("Fault_Handler")));
void cm_fault_report(const uint32_t *frame, uint32_t exc_return);

void Reset_Handler(void)
{
    /* Copy initialised data from its load address in flash, then zero .bss. The linker
       script aligns both to 4 bytes at each end. */
    const uint32_t *src = __data_load;
    /* the linker script's symbols bound one region each: comparing them is well defined
       here, whatever the C object model says of distinct objects */
    // cppcheck-suppress comparePointers
    for (uint32_t *dst = __data_start; dst < __data_end;) *dst++ = *src++;
    // cppcheck-suppress comparePointers
    for (uint32_t *dst = __bss_start; dst < __bss_end;) *dst++ = 0;

#if defined(__ARM_FP)
    /* Full access to CP10/CP11 (the FPU); without it the first FP instruction raises a
       UsageFault (NOCP). The barriers make the new access rights visible before any FP
       instruction is fetched. Nothing above this point uses the FPU. */
    CM_CPACR |= 0xFu << 20;
    __asm__ volatile("dsb\n\tisb" ::: "memory");
#endif

    /* Report MemManage, BusFault and UsageFault through their own vectors instead of
       escalating everything to HardFault. */
    CM_SHCSR |= (1u << 16) | (1u << 17) | (1u << 18);

    cm_port_init();
    port_exit(app_main());
}

/* Every fault and unexpected exception lands here. Finds the stacked exception frame
   (MSP or PSP, from EXC_RETURN bit 2) and passes it to the reporter; never returns. */
__attribute__((naked)) void Fault_Handler(void)
{
    __asm__ volatile(
        "tst   lr, #4\n\t"
        "ite   eq\n\t"
        "mrseq r0, msp\n\t"
        "mrsne r0, psp\n\t"
        "mov   r1, lr\n\t"
        "b     cm_fault_report\n\t");
}

static const char *const cm_exc_names[16] = {
    "?", "Reset", "NMI", "HardFault", "MemManage", "BusFault", "UsageFault", "?",
    "?", "?", "?", "SVCall", "DebugMonitor", "?", "PendSV", "SysTick",
};

/* writes "label0xXXXXXXXX" to the console */
static void cm_write_hex(const char *label, uint32_t v)
{
    char buf[11] = {'0', 'x'};
    for (int i = 0; i < 8; i++)
        buf[2 + i] = "0123456789abcdef"[(v >> (28 - 4 * i)) & 0xFu];
    buf[10] = 0;
    port_write(label);
    port_write(buf);
}

void cm_fault_report(const uint32_t *frame, uint32_t exc_return)
{
    uint32_t ipsr;
    __asm__ volatile("mrs %0, ipsr" : "=r"(ipsr));
    uint32_t exc = ipsr & 0x1FFu;

    port_write("\n*** FAULT: ");
    port_write(exc < 16 ? cm_exc_names[exc] : "unexpected interrupt");
    cm_write_hex(" exception=", exc);
    cm_write_hex(" pc=", frame[6]);
    cm_write_hex(" lr=", frame[5]);
    cm_write_hex(" xpsr=", frame[7]);
    cm_write_hex(" exc_return=", exc_return);
    cm_write_hex("\n*** CFSR=", CM_CFSR);
    cm_write_hex(" HFSR=", CM_HFSR);
    cm_write_hex(" MMFAR=", CM_MMFAR);
    cm_write_hex(" BFAR=", CM_BFAR);
    port_write("\n");
    port_exit(128 + (int)(exc & 0x7F));
}

/* The vector table, placed at 0x0 by the linker script: initial stack pointer, then the
   16 system exceptions and 32 external interrupts (the MPS2 images use fewer). */
#define CM_N_IRQ 32
typedef void (*cm_vector)(void);

__attribute__((section(".vectors"), used))
const cm_vector cm_vector_table[16 + CM_N_IRQ] = {
    [0] = (cm_vector)(uintptr_t)__stack_top,
    [1] = Reset_Handler,
    [2] = Fault_Handler,   /* NMI */
    [3] = Fault_Handler,   /* HardFault */
    [4] = Fault_Handler,   /* MemManage */
    [5] = Fault_Handler,   /* BusFault */
    [6] = Fault_Handler,   /* UsageFault */
    [11] = Fault_Handler,  /* SVCall: unused by the port */
    [12] = Fault_Handler,  /* DebugMonitor */
    [14] = PendSV_Handler, /* the background level (port_bg_start) */
    [15] = SysTick_Handler,
#define CM_IRQ_FAULT(n) [16 + (n)] = Fault_Handler
    [16 + CM_LINK_UART_IRQ] = cm_link_uart_irq, /* ports/cortex-m/uart.c, when linked */
    CM_IRQ_FAULT(1), CM_IRQ_FAULT(2), CM_IRQ_FAULT(3),
    CM_IRQ_FAULT(4), CM_IRQ_FAULT(5), CM_IRQ_FAULT(6), CM_IRQ_FAULT(7),
    CM_IRQ_FAULT(8), CM_IRQ_FAULT(9), CM_IRQ_FAULT(10), CM_IRQ_FAULT(11),
    CM_IRQ_FAULT(12), CM_IRQ_FAULT(13), CM_IRQ_FAULT(14), CM_IRQ_FAULT(15),
    CM_IRQ_FAULT(16), CM_IRQ_FAULT(17), CM_IRQ_FAULT(18), CM_IRQ_FAULT(19),
    CM_IRQ_FAULT(20), CM_IRQ_FAULT(21), CM_IRQ_FAULT(22), CM_IRQ_FAULT(23),
    CM_IRQ_FAULT(24), CM_IRQ_FAULT(25), CM_IRQ_FAULT(26), CM_IRQ_FAULT(27),
    CM_IRQ_FAULT(28), CM_IRQ_FAULT(29), CM_IRQ_FAULT(30), CM_IRQ_FAULT(31),
#undef CM_IRQ_FAULT
};
