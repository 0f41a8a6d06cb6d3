/* cm_port.h - private to the Cortex-M port: the MPS2 clock, the registers the port uses
 * and the functions startup.c and port.c share. Applications include ports/port.h only. */
#ifndef CM_PORT_H
#define CM_PORT_H

#include <stdint.h>

/* MPS2 FPGA images (AN385/AN386/AN500) clock the CPU, SysTick (processor clock) and the
   CMSDK timers from the same 25 MHz SYSCLK; QEMU models the same. Override with
   -DCM_SYSCLK_HZ=... for another board. */
#ifndef CM_SYSCLK_HZ
#define CM_SYSCLK_HZ 25000000u
#endif

#define CM_REG(addr) (*(volatile uint32_t *)(uintptr_t)(addr))

/* System control space (ARMv7-M). */
#define CM_SYST_CSR   CM_REG(0xE000E010u) /* SysTick control and status */
#define CM_SYST_RVR   CM_REG(0xE000E014u) /* reload value (24 bits) */
#define CM_SYST_CVR   CM_REG(0xE000E018u) /* current value */
#define CM_ICSR       CM_REG(0xE000ED04u)
#define CM_VTOR       CM_REG(0xE000ED08u)
#define CM_SHPR3      CM_REG(0xE000ED20u) /* priorities of PendSV (bits 23:16), SysTick */
#define CM_SHCSR      CM_REG(0xE000ED24u)
#define CM_CFSR       CM_REG(0xE000ED28u)
#define CM_HFSR       CM_REG(0xE000ED2Cu)
#define CM_MMFAR      CM_REG(0xE000ED34u)
#define CM_BFAR       CM_REG(0xE000ED38u)
#define CM_CPACR      CM_REG(0xE000ED88u)

/* CMSDK APB dual timer (SP804-like) at 0x40002000: timer 1 is the cost counter. */
#define CM_DUALTIMER1_LOAD  CM_REG(0x40002000u)
#define CM_DUALTIMER1_VALUE CM_REG(0x40002004u)
#define CM_DUALTIMER1_CTRL  CM_REG(0x40002008u)
#define CM_DUALTIMER_CTRL_EN     (1u << 7)
#define CM_DUALTIMER_CTRL_32BIT  (1u << 1)

/* Consoles (port_write), chosen at build time with -DCM_CONSOLE=...: semihosting needs a
   debugger or QEMU (without one the bkpt faults); a board without one uses the UART, the
   ITM (SWO trace pin), or nothing. CM_EXIT_SEMIHOST 1: port_exit reports the exit code
   to the debugger / QEMU; 0: port_exit parks the core (interrupts off, WFI). */
#define CM_CONSOLE_NONE     0
#define CM_CONSOLE_SEMIHOST 1
#define CM_CONSOLE_UART     2
#define CM_CONSOLE_ITM      3
#ifndef CM_CONSOLE
#define CM_CONSOLE CM_CONSOLE_SEMIHOST
#endif
#ifndef CM_EXIT_SEMIHOST
#define CM_EXIT_SEMIHOST (CM_CONSOLE == CM_CONSOLE_SEMIHOST)
#endif

/* CMSDK APB UART (MPS2 UART0 at 0x40004000; another board: -DCM_UART_BASE=...). */
#ifndef CM_UART_BASE
#define CM_UART_BASE 0x40004000u
#endif
#ifndef CM_UART_BAUD
#define CM_UART_BAUD 115200u
#endif
#define CM_UART_DATA    CM_REG(CM_UART_BASE + 0x00u)
#define CM_UART_STATE   CM_REG(CM_UART_BASE + 0x04u) /* bit 0: transmit buffer full */
#define CM_UART_CTRL    CM_REG(CM_UART_BASE + 0x08u) /* bit 0: transmit enable */
#define CM_UART_BAUDDIV CM_REG(CM_UART_BASE + 0x10u)

/* The link UART (ports/cortex-m/uart.c): a CMSDK APB UART and its receive interrupt
   (MPS2: UART0 at 0x40004000, RX interrupt 0; UART1 0x40005000, 2; UART2 0x40006000, 4). */
#ifndef CM_LINK_UART_BASE
#define CM_LINK_UART_BASE 0x40004000u
#endif
#ifndef CM_LINK_UART_IRQ
#define CM_LINK_UART_IRQ 0
#endif
#define CM_NVIC_ISER0 CM_REG(0xE000E100u)
void cm_link_uart_irq(void);

/* ITM stimulus port 0 (ARMv7-M), as written by CMSIS ITM_SendChar: only when the
   debugger enabled the ITM (TCR.ITMENA) and the port (TER bit 0), else dropped. */
#define CM_ITM_PORT0 CM_REG(0xE0000000u)
#define CM_ITM_TER   CM_REG(0xE0000E00u)
#define CM_ITM_TCR   CM_REG(0xE0000E80u)

/* Semihosting (ARM "bkpt 0xab" on M-profile). */
#define CM_SYS_WRITE0        0x04u
#define CM_SYS_EXIT          0x18u
#define CM_SYS_EXIT_EXTENDED 0x20u
#define CM_ADP_STOPPED_APPLICATION_EXIT 0x20026u
/* one call: the operation in r0, its argument (block) in r1, the host's answer in r0 */
static inline uintptr_t cm_semihost(uintptr_t op, const void *arg)
{
    register uintptr_t r0 __asm__("r0") = op;
    register const void *r1 __asm__("r1") = arg;
    __asm__ volatile("bkpt 0xab" : "+r"(r0) : "r"(r1) : "memory");
    return r0;
}

/* port.c: starts the cost counter; called by the reset handler before app_main. */
void cm_port_init(void);
/* port.c: the SysTick and PendSV exception handlers (referenced by the vector table). */
void SysTick_Handler(void);
void PendSV_Handler(void);

#endif /* CM_PORT_H */
