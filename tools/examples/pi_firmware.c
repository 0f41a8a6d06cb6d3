/* pi_firmware.c - the PI controller of scene pi_link as firmware for a Cortex-M board: the
 * controller side of the modrt link over the board's UART, with the client library of
 * ports/common/linkclient.c and the port's link UART (ports/port.h, port_link_*: bytes
 * received by interrupt into a buffer). The law and the order of its arithmetic are those
 * of tools/examples/pi_controller.c and of pi_loop's PI block, so `modrt run pi_link
 * --link serial:...` against this board gives pi_loop's trace bit for bit. Sleeps (WFI)
 * while no byte waits. Built and run under QEMU by tests/link/serial_qemu.sh; on a board:
 * docs/link.md, "A controller on a microcontroller". */
#include "common/linkclient.h"
#include "port.h"

#ifndef PI_FW_BAUD
#define PI_FW_BAUD 115200u
#endif

#define KP 0.8
#define KI 3.0
#define TS 0.01

/* one byte read ahead by idle(), handed out first */
static int held = -1;

static int uart_read(void *ctx)
{
    (void)ctx;
    int b = held;
    held = -1;
    return b >= 0 ? b : port_link_getc();
}

static void uart_write(void *ctx, const uint8_t *b, size_t n)
{
    (void)ctx;
    port_link_write(b, (uint32_t)n);
}

/* sleeps until an interrupt unless a byte already waits (looked at with interrupts
   masked, so that one arriving between the look and the WFI still wakes it) */
static void idle(void)
{
    __asm__ volatile("cpsid i" ::: "memory");
    if (held < 0)
        held = port_link_getc();
    if (held < 0)
        __asm__ volatile("dsb\n\twfi" ::: "memory");
    __asm__ volatile("cpsie i\n\tisb" ::: "memory");
}

int app_main(void)
{
    static const char *const layout[] = {"pi_link", "Ctrl", "Ref", "y", "Plant", "y", ">", "c"};
    static linkclient c;
    const linkclient_io io = {uart_read, uart_write, 0};
    if (port_link_open(PI_FW_BAUD) != 0 ||
        linkclient_init(&c, "pi_link", linkclient_layout_id(layout, 8), 2, 1, &io) != 0) {
        port_write("pi_firmware: cannot open the link UART\n");
        return 1;
    }
    port_write("pi_firmware: ready\n");
    double integral = 0;
    for (;;) {
        if (linkclient_poll(&c)) {
            if (c.new_run) /* the plant started a run: the controller starts afresh */
                integral = 0;
            double e = c.req.v[0] - c.req.v[1];
            double u = KP * e + integral;
            integral = integral + KI * TS * e;
            linkclient_answer(&c, &u);
        }
        idle();
    }
}
