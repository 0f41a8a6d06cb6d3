/* uart.c - the link UART of the Cortex-M port (port_link_* of ports/port.h): a CMSDK APB
 * UART (MPS2 UART0 by default; CM_LINK_UART_BASE, CM_LINK_UART_IRQ in cm_port.h) whose
 * receive interrupt moves each byte into a ring buffer the application drains with
 * port_link_getc between ticks; transmission is polled. At 921,600 baud a byte arrives
 * every 11 us, far more often than a 1 ms tick could poll a one-byte receive register:
 * the interrupt is what keeps bytes from being lost. Linked only into images that use the
 * link (tools/image.sh): the vector table points the interrupt at a fault otherwise. */
#include <stdint.h>

#include "../port.h"
#include "cm_port.h"

#if CM_CONSOLE == CM_CONSOLE_UART && CM_LINK_UART_BASE == CM_UART_BASE
#error "The link and the console share one UART: build with CONSOLE=semihost, itm or none, or set CM_LINK_UART_BASE and CM_LINK_UART_IRQ to another UART."
#endif

#ifndef CM_LINK_RX_BUF
#define CM_LINK_RX_BUF 1024u /* bytes; a power of 2, at least two of the largest frames */
#endif
#if CM_LINK_RX_BUF & (CM_LINK_RX_BUF - 1)
#error "CM_LINK_RX_BUF must be a power of 2."
#endif

#define LU_DATA      CM_REG(CM_LINK_UART_BASE + 0x00u)
#define LU_STATE     CM_REG(CM_LINK_UART_BASE + 0x04u) /* 0 TX full, 1 RX full, 3 RX overrun */
#define LU_CTRL      CM_REG(CM_LINK_UART_BASE + 0x08u) /* 0 TX en, 1 RX en, 3 RX int en */
#define LU_INTCLEAR  CM_REG(CM_LINK_UART_BASE + 0x0Cu) /* write 1: clear (1 RX, 3 RX overrun) */
#define LU_BAUDDIV   CM_REG(CM_LINK_UART_BASE + 0x10u)
#define LU_TX_FULL   (1u << 0)
#define LU_RX_FULL   (1u << 1)
#define LU_RX_OVR    (1u << 3)
#define LU_MIN_DIV   16u /* the CMSDK UART's smallest baud divider */

/* the ring: written by the interrupt (head), read by the application (tail) */
static volatile uint8_t lu_ring[CM_LINK_RX_BUF];
static volatile uint32_t lu_head, lu_tail, lu_lost;

void cm_link_uart_irq(void)
{
    LU_INTCLEAR = (1u << 1);
    while (LU_STATE & LU_RX_FULL) {
        uint8_t b = (uint8_t)LU_DATA;
        if (lu_head - lu_tail < CM_LINK_RX_BUF)
            lu_ring[lu_head++ & (CM_LINK_RX_BUF - 1)] = b;
        else
            lu_lost++;
    }
    if (LU_STATE & LU_RX_OVR) { /* the hardware lost a byte before we could take it */
        LU_STATE = LU_RX_OVR;
        LU_INTCLEAR = (1u << 3);
        lu_lost++;
    }
}

int port_link_open(uint32_t baud)
{
    uint32_t div = baud ? CM_SYSCLK_HZ / baud : 0;
    if (div < LU_MIN_DIV)
        return -1;
    LU_CTRL = 0;
    LU_BAUDDIV = div;
    lu_head = lu_tail = lu_lost = 0;
    LU_CTRL = (1u << 0) | (1u << 1) | (1u << 3);
    CM_NVIC_ISER0 = 1u << CM_LINK_UART_IRQ;
    return 0;
}

int port_link_getc(void)
{
    if (lu_tail == lu_head)
        return -1;
    return lu_ring[lu_tail++ & (CM_LINK_RX_BUF - 1)];
}

void port_link_write(const uint8_t *b, uint32_t n)
{
    while (n--) {
        while (LU_STATE & LU_TX_FULL) {
        }
        LU_DATA = *b++;
    }
}

void port_link_wait(void)
{
    /* looked at with interrupts masked: a byte arriving before the WFI still wakes it */
    __asm__ volatile("cpsid i" ::: "memory");
    if (lu_tail == lu_head)
        __asm__ volatile("dsb\n\twfi" ::: "memory");
    __asm__ volatile("cpsie i\n\tisb" ::: "memory");
}

uint32_t port_link_lost(void)
{
    return lu_lost;
}
