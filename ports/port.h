/* port.h - what every port provides to an application (CLI, scene runner, test runner).
 *
 * A port is chosen by the include path and the sources the build links: ports/posix for
 * hosts and Linux targets, ports/cortex-m and ports/riscv for bare metal. The runtime in
 * rt/ never includes this header: only applications and the test harness do. */
#ifndef PORT_H
#define PORT_H

#include <stdint.h>

/* Writes a NUL-terminated string to the console (stdout, UART or semihosting). */
void port_write(const char *s);
/* Ends the program with an exit status (0 = success); does not return. */
void port_exit(int code);
/* A deterministic cost counter (retired instructions or cycles under QEMU -icount),
   or 0 where the port has none. */
uint64_t port_cycles(void);

/* Periodic tick source: calls fn(ctx) every period_us microseconds of the port's time
   base (a hardware timer on bare metal, CLOCK_MONOTONIC with an absolute deadline on
   POSIX), so the caller keeps its state in ctx, not in file-scope globals. Returns 0 on
   success, -1 if the port cannot provide the period. */
int port_timer_start(uint32_t period_us, void (*fn)(void *ctx), void *ctx);
/* Waits for the next timer tick (WFI on bare metal, clock_nanosleep on POSIX). */
void port_timer_wait(void);
void port_timer_stop(void);
/* Returns 1 if the tick now running has passed its deadline (an overrun), else 0. */
int port_timer_late(void);

/* Work below the tick (a background set's step, rt_background): port_bg_start registers
   fn(ctx), which then runs at a priority below the timer's tick function each time
   port_bg_request() is called (PendSV on Cortex-M: lowest priority, preempted by SysTick
   at any instruction). Returns 0, or -1 where the port has no such level (RISC-V, POSIX:
   the application runs the work itself, in its main loop or a thread of lower priority). */
int port_bg_start(void (*fn)(void *ctx), void *ctx);
void port_bg_request(void);

/* The link UART: the board's serial line to the other side of the controller link
   (docs/link.md, "Over a serial line"). Only ports with a link UART provide these, and an
   application links them only when it uses them (the Cortex-M port: ports/cortex-m/uart.c).
   port_link_open sets it up at `baud` bits per second, 8N1, receiving from its interrupt
   into a buffer: 0, or -1 where the rate cannot be made. port_link_getc returns the next
   received byte, or -1 when none waits (it never waits). port_link_write sends n bytes,
   waiting while the transmitter is full. port_link_lost counts the bytes received while
   the buffer was full (dropped). port_link_wait sleeps until a byte waits or another
   interrupt (the timer's) fires: a wait for an answer that neither spins nor misses one. */
int port_link_open(uint32_t baud);
int port_link_getc(void);
void port_link_wait(void);
void port_link_write(const uint8_t *b, uint32_t n);
uint32_t port_link_lost(void);

/* The application's entry point, called by bare-metal startup code after .data/.bss
   are set up; its return value becomes the exit status. */
int app_main(void);

#endif /* PORT_H */
