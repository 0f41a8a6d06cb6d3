/* start.S - RISC-V bare-metal start-up and trap entry of the port for QEMU virt
 * (-bios none: every hart jumps to the ELF entry at 0x80000000 in machine mode), for
 * rv64gc/lp64d and rv32imac/ilp32.
 *
 * _start: parks harts other than 0 (WFI loop), sets gp (with relaxation off, so the
 * linker cannot rewrite the gp load relative to gp itself), sp (__stack_top from
 * ports/riscv/link.ld), mtvec (rv_trap_entry, direct mode), mstatus.FS = Initial and
 * fcsr = 0 when the F/D extensions are present, copies .data when its load address
 * differs, clears .bss, then calls rv_port_init, app_main and port_exit(status).
 *
 * rv_trap_entry: saves the caller-saved integer registers (and the caller-saved FP
 * registers and fcsr on F/D targets), calls rv_trap(mcause, mepc, mtval) in port.c,
 * restores and returns with mret. Callee-saved registers are preserved by rv_trap per
 * the ABI. */

#if __riscv_xlen == 64
#define REG_S sd
#define REG_L ld
#define REGBYTES 8
#else
#define REG_S sw
#define REG_L lw
#define REGBYTES 4
#endif

#if defined(__riscv_flen) && __riscv_flen == 64
#define FREG_S fsd
#define FREG_L fld
#define FREGBYTES 8
#elif defined(__riscv_flen) && __riscv_flen == 32
#define FREG_S fsw
#define FREG_L flw
#define FREGBYTES 4
#endif

    .section .boot, "ax", @progbits  /* not .text.<name>: -ffunction-sections cannot collide */
    .globl _start
    .type _start, @function
_start:
    csrr    t0, mhartid
    bnez    t0, rv_park

    .option push
    .option norelax
    la      gp, __global_pointer$
    .option pop
    la      sp, __stack_top

    la      t0, rv_trap_entry
    csrw    mtvec, t0
    csrw    mie, zero

#ifdef __riscv_flen
    li      t0, (1 << 13)          /* mstatus.FS = Initial: FP instructions allowed */
    csrs    mstatus, t0
    csrw    fcsr, zero
#endif

    /* Copy .data from its load address (a no-op with the single-RAM link.ld). */
    la      a0, __data_load
    la      a1, __data_start
    la      a2, __data_end
    beq     a0, a1, 2f
1:  bgeu    a1, a2, 2f
    lw      t0, 0(a0)
    sw      t0, 0(a1)
    addi    a0, a0, 4
    addi    a1, a1, 4
    j       1b
2:
    /* Clear .bss (4-byte aligned at both ends, see link.ld). */
    la      a0, __bss_start
    la      a1, __bss_end
3:  bgeu    a0, a1, 4f
    sw      zero, 0(a0)
    addi    a0, a0, 4
    j       3b
4:
    call    rv_port_init
    call    app_main
    call    port_exit
rv_park:
    wfi
    j       rv_park
    .size _start, . - _start

/* Trap frame: ra, t0-t6, a0-a7 (16 integer registers), then ft0-ft11, fa0-fa7 and fcsr
   on F/D targets; rounded up to 16 bytes (the stack alignment of both ABIs). */
#define INT_FRAME (16 * REGBYTES)
#ifdef __riscv_flen
#define FP_FRAME (20 * FREGBYTES + REGBYTES)
#else
#define FP_FRAME 0
#endif
#define FRAME (((INT_FRAME + FP_FRAME) + 15) & ~15)

    .section .text.rv_trap_entry, "ax", @progbits
    .globl rv_trap_entry
    .type rv_trap_entry, @function
    .balign 4
rv_trap_entry:
    addi    sp, sp, -FRAME
    REG_S   ra,  0 * REGBYTES(sp)
    REG_S   t0,  1 * REGBYTES(sp)
    REG_S   t1,  2 * REGBYTES(sp)
    REG_S   t2,  3 * REGBYTES(sp)
    REG_S   t3,  4 * REGBYTES(sp)
    REG_S   t4,  5 * REGBYTES(sp)
    REG_S   t5,  6 * REGBYTES(sp)
    REG_S   t6,  7 * REGBYTES(sp)
    REG_S   a0,  8 * REGBYTES(sp)
    REG_S   a1,  9 * REGBYTES(sp)
    REG_S   a2, 10 * REGBYTES(sp)
    REG_S   a3, 11 * REGBYTES(sp)
    REG_S   a4, 12 * REGBYTES(sp)
    REG_S   a5, 13 * REGBYTES(sp)
    REG_S   a6, 14 * REGBYTES(sp)
    REG_S   a7, 15 * REGBYTES(sp)
#ifdef __riscv_flen
#define FOFF(i) (INT_FRAME + (i) * FREGBYTES)
    FREG_S  ft0,  FOFF(0)(sp)
    FREG_S  ft1,  FOFF(1)(sp)
    FREG_S  ft2,  FOFF(2)(sp)
    FREG_S  ft3,  FOFF(3)(sp)
    FREG_S  ft4,  FOFF(4)(sp)
    FREG_S  ft5,  FOFF(5)(sp)
    FREG_S  ft6,  FOFF(6)(sp)
    FREG_S  ft7,  FOFF(7)(sp)
    FREG_S  ft8,  FOFF(8)(sp)
    FREG_S  ft9,  FOFF(9)(sp)
    FREG_S  ft10, FOFF(10)(sp)
    FREG_S  ft11, FOFF(11)(sp)
    FREG_S  fa0,  FOFF(12)(sp)
    FREG_S  fa1,  FOFF(13)(sp)
    FREG_S  fa2,  FOFF(14)(sp)
    FREG_S  fa3,  FOFF(15)(sp)
    FREG_S  fa4,  FOFF(16)(sp)
    FREG_S  fa5,  FOFF(17)(sp)
    FREG_S  fa6,  FOFF(18)(sp)
    FREG_S  fa7,  FOFF(19)(sp)
    frcsr   t0
    REG_S   t0, FOFF(20)(sp)
#endif
    csrr    a0, mcause
    csrr    a1, mepc
    csrr    a2, mtval
    call    rv_trap
#ifdef __riscv_flen
    REG_L   t0, FOFF(20)(sp)
    fscsr   t0
    FREG_L  ft0,  FOFF(0)(sp)
    FREG_L  ft1,  FOFF(1)(sp)
    FREG_L  ft2,  FOFF(2)(sp)
    FREG_L  ft3,  FOFF(3)(sp)
    FREG_L  ft4,  FOFF(4)(sp)
    FREG_L  ft5,  FOFF(5)(sp)
    FREG_L  ft6,  FOFF(6)(sp)
    FREG_L  ft7,  FOFF(7)(sp)
    FREG_L  ft8,  FOFF(8)(sp)
    FREG_L  ft9,  FOFF(9)(sp)
    FREG_L  ft10, FOFF(10)(sp)
    FREG_L  ft11, FOFF(11)(sp)
    FREG_L  fa0,  FOFF(12)(sp)
    FREG_L  fa1,  FOFF(13)(sp)
    FREG_L  fa2,  FOFF(14)(sp)
    FREG_L  fa3,  FOFF(15)(sp)
    FREG_L  fa4,  FOFF(16)(sp)
    FREG_L  fa5,  FOFF(17)(sp)
    FREG_L  fa6,  FOFF(18)(sp)
    FREG_L  fa7,  FOFF(19)(sp)
#endif
    REG_L   ra,  0 * REGBYTES(sp)
    REG_L   t0,  1 * REGBYTES(sp)
    REG_L   t1,  2 * REGBYTES(sp)
    REG_L   t2,  3 * REGBYTES(sp)
    REG_L   t3,  4 * REGBYTES(sp)
    REG_L   t4,  5 * REGBYTES(sp)
    REG_L   t5,  6 * REGBYTES(sp)
    REG_L   t6,  7 * REGBYTES(sp)
    REG_L   a0,  8 * REGBYTES(sp)
    REG_L   a1,  9 * REGBYTES(sp)
    REG_L   a2, 10 * REGBYTES(sp)
    REG_L   a3, 11 * REGBYTES(sp)
    REG_L   a4, 12 * REGBYTES(sp)
    REG_L   a5, 13 * REGBYTES(sp)
    REG_L   a6, 14 * REGBYTES(sp)
    REG_L   a7, 15 * REGBYTES(sp)
    addi    sp, sp, FRAME
    mret
    .size rv_trap_entry, . - rv_trap_entry
