/* insn_count.c - QEMU TCG plugin counting executed guest instructions, in total and
 * between successive executions of a marker address (for cost per tick).
 *
 * Build (host):  gcc -O2 -shared -fPIC -o build/host/libinsn_count.so tools/dev/qemu/insn_count.c
 * Use:           qemu-system-arm ... -plugin ./build/host/libinsn_count.so -d plugin -kernel app.elf
 *                qemu-aarch64 -plugin ./build/host/libinsn_count.so,addr=0x4005d0 -d plugin ./app
 * Arguments (comma separated after the .so):
 *   addr=<hex|dec>  marker: the address of a function the application calls once per
 *                   tick (port_cycles is the natural one); Thumb bit 0 is ignored, so the
 *                   value printed by `nm` works. Prints the number of hits and
 *                   min/median/max of the instruction counts between successive hits.
 *   stop=<hex|dec>  a second marker: an interval then runs from a hit of addr to the next
 *                   hit of stop (instructions from stop to the next addr are not counted),
 *                   e.g. the tick context only, without the background work that runs
 *                   between ticks (tests/cross/footprint_main.c).
 *   first=<i>,count=<n>  statistics over intervals i .. i+n-1 only (0-based; default all),
 *                   e.g. to skip start-up and keep the steady-state ticks.
 *   dump=on         also print every interval ("insn_count: interval <i> <n>").
 *   limit=<n>       a budget: once the guest has executed more than n instructions the
 *                   plugin prints "insn_count: stopped after <n> instructions (the
 *                   image's budget)" on stderr and ends QEMU with exit status 3. Counted per
 *                   translation block as it runs (a block left early by an exception
 *                   counts whole), so it bounds a run by the guest's work, not by the
 *                   machine's load (tests/cross/run.sh). Alone, it counts per block only.
 * Output goes to QEMU's log (-d plugin: stderr, or -D file):
 *   insn_count: total <N>
 *   insn_count: marker 0x<addr> hits <H> intervals <n> min <a> median <b> max <c>
 *
 * Counting is inline, per instruction (a host add before each guest instruction), so a
 * count is exact at the marker and repeatable run to run. An interval is the number of
 * instructions from one marker hit up to, not including, the next one; checked on
 * RISC-V, where intervals equal the guest's own minstret deltas exactly, also across code
 * doing MMIO. Counts of qemu-aarch64 (user mode) depend on the environment and argv
 * size: run under `env -i`. One vCPU is assumed (the counters are not per vCPU).
 *
 * Findings (QEMU 7.2, Debian 12), on what gives deterministic per-tick instruction counts:
 *   - RISC-V virt: minstret read in the guest under -icount shift=0 counts executed
 *     instructions exactly (it is QEMU's virtual clock in ns, 1 ns per instruction);
 *     port_cycles reads it, no plugin needed. With sleep=off, time spent in WFI jumps to
 *     the next timer deadline, so the counter also advances deterministically across idle.
 *   - Cortex-M (mps2): the DWT cycle counter reads 0. The CMSDK dual timer at 0x40002000
 *     and SysTick are repeatable under -icount shift=0 but tick at 25 MHz, i.e. once per
 *     40 virtual ns = 40 instructions: port_cycles returns ticks x 40, exact only to a
 *     multiple of 40. For exact per-tick counts use this plugin with addr=port_cycles.
 *     (Also: with sleep=off, a WFI on mps2 advances virtual time by twice the time left
 *     to the next timer deadline; repeatable, and it does not change instruction counts.)
 *   - AArch64 user mode (qemu-aarch64): no deterministic guest counter (qemu-user has
 *     no -icount); use this plugin with addr=port_cycles, under env -i.
 *   - Host: valgrind --tool=callgrind (not this plugin).
 *
 * Debian ships no qemu-plugin.h: the few declarations needed from the plugin API are
 * written out below, as in QEMU 7.2's header; the plugin declares API version 1. */
#include <inttypes.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* ------------------------------------------------------------------ plugin API (v1) */

#define QEMU_PLUGIN_EXPORT __attribute__((visibility("default")))

typedef uint64_t qemu_plugin_id_t;

typedef struct qemu_info_t {
    const char *target_name;
    struct {
        int min;
        int cur;
    } version;
    bool system_emulation;
    union {
        struct {
            int smp_vcpus;
            int max_vcpus;
        } system;
    };
} qemu_info_t;

struct qemu_plugin_tb;
struct qemu_plugin_insn;

enum qemu_plugin_cb_flags { QEMU_PLUGIN_CB_NO_REGS, QEMU_PLUGIN_CB_R_REGS, QEMU_PLUGIN_CB_RW_REGS };
enum qemu_plugin_op { QEMU_PLUGIN_INLINE_ADD_U64 };

typedef void (*qemu_plugin_udata_cb_t)(qemu_plugin_id_t id, void *userdata);
typedef void (*qemu_plugin_vcpu_udata_cb_t)(unsigned int vcpu_index, void *userdata);
typedef void (*qemu_plugin_vcpu_tb_trans_cb_t)(qemu_plugin_id_t id, struct qemu_plugin_tb *tb);

void qemu_plugin_register_vcpu_tb_trans_cb(qemu_plugin_id_t id, qemu_plugin_vcpu_tb_trans_cb_t cb);
void qemu_plugin_register_vcpu_insn_exec_cb(struct qemu_plugin_insn *insn, qemu_plugin_vcpu_udata_cb_t cb,
                                            enum qemu_plugin_cb_flags flags, void *userdata);
void qemu_plugin_register_vcpu_insn_exec_inline(struct qemu_plugin_insn *insn, enum qemu_plugin_op op,
                                                void *ptr, uint64_t imm);
void qemu_plugin_register_vcpu_tb_exec_cb(struct qemu_plugin_tb *tb, qemu_plugin_vcpu_udata_cb_t cb,
                                          enum qemu_plugin_cb_flags flags, void *userdata);
void qemu_plugin_register_atexit_cb(qemu_plugin_id_t id, qemu_plugin_udata_cb_t cb, void *userdata);
size_t qemu_plugin_tb_n_insns(const struct qemu_plugin_tb *tb);
struct qemu_plugin_insn *qemu_plugin_tb_get_insn(const struct qemu_plugin_tb *tb, size_t idx);
uint64_t qemu_plugin_insn_vaddr(const struct qemu_plugin_insn *insn);
void qemu_plugin_outs(const char *string);

QEMU_PLUGIN_EXPORT int qemu_plugin_version = 1;
QEMU_PLUGIN_EXPORT int qemu_plugin_install(qemu_plugin_id_t id, const qemu_info_t *info, int argc,
                                           char **argv);

/* ------------------------------------------------------------------ state */

static uint64_t insn_total;     /* instructions executed (inline add) */
static bool marker_on;
static uint64_t marker_addr;
static bool stop_on;
static uint64_t stop_addr;
static bool armed;              /* stop marker: an interval is open */
static bool dump_on;
static size_t stat_first;
static size_t stat_count = SIZE_MAX;
static uint64_t marker_hits;
static uint64_t marker_last;    /* insn_total before the previous hit */
static uint64_t *intervals;
static size_t n_intervals, cap_intervals;
static uint64_t limit;          /* budget of instructions, 0: none */
static uint64_t block_total;    /* instructions of the blocks run (the budget's count) */

#define LIMIT_EXIT 3 /* QEMU's exit status when the budget ran out */

static void on_block(unsigned int vcpu_index, void *userdata)
{
    (void)vcpu_index;
    block_total += (uintptr_t)userdata;
    if (block_total > limit) {
        fprintf(stderr, "insn_count: stopped after %" PRIu64 " instructions (the image's budget)\n",
                limit);
        _exit(LIMIT_EXIT); /* from the vCPU thread: no QEMU clean-up to wait for */
    }
}

static void add_interval(uint64_t n)
{
    if (n_intervals == cap_intervals) {
        size_t cap = cap_intervals ? 2 * cap_intervals : 1024;
        uint64_t *p = realloc(intervals, cap * sizeof *p);
        if (!p) return;
        intervals = p;
        cap_intervals = cap;
    }
    intervals[n_intervals++] = n;
}

static void on_marker(unsigned int vcpu_index, void *userdata)
{
    (void)vcpu_index;
    (void)userdata;
    /* The marker instruction has no inline add (whether an inline op runs before or
       after a callback of the same instruction is not part of the API): count it here. */
    uint64_t now = insn_total++;
    if (marker_hits++ > 0 && !stop_on)
        add_interval(now - marker_last);
    marker_last = now;
    armed = true;
}

static void on_stop(unsigned int vcpu_index, void *userdata)
{
    (void)vcpu_index;
    (void)userdata;
    uint64_t now = insn_total++;
    if (armed)
        add_interval(now - marker_last);
    armed = false;
}

static void on_tb_trans(qemu_plugin_id_t id, struct qemu_plugin_tb *tb)
{
    (void)id;
    size_t n = qemu_plugin_tb_n_insns(tb);
    if (limit)
        qemu_plugin_register_vcpu_tb_exec_cb(tb, on_block, QEMU_PLUGIN_CB_NO_REGS, (void *)(uintptr_t)n);
    if (limit && !marker_on && !stop_on)
        return; /* a budget only: no count per instruction */
    for (size_t i = 0; i < n; i++) {
        struct qemu_plugin_insn *insn = qemu_plugin_tb_get_insn(tb, i);
        uint64_t va = qemu_plugin_insn_vaddr(insn);
        if (marker_on && va == marker_addr)
            qemu_plugin_register_vcpu_insn_exec_cb(insn, on_marker, QEMU_PLUGIN_CB_NO_REGS, NULL);
        else if (stop_on && va == stop_addr)
            qemu_plugin_register_vcpu_insn_exec_cb(insn, on_stop, QEMU_PLUGIN_CB_NO_REGS, NULL);
        else
            qemu_plugin_register_vcpu_insn_exec_inline(insn, QEMU_PLUGIN_INLINE_ADD_U64, &insn_total, 1);
    }
}

static int cmp_u64(const void *a, const void *b)
{
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return (x > y) - (x < y);
}

static void plugin_at_exit(qemu_plugin_id_t id, void *userdata)
{
    (void)id;
    (void)userdata;
    char line[160];
    snprintf(line, sizeof line, "insn_count: total %" PRIu64 "\n",
             limit && !marker_on && !stop_on ? block_total : insn_total);
    qemu_plugin_outs(line);
    if (!marker_on) return;
    if (dump_on) {
        for (size_t i = 0; i < n_intervals; i++) {
            snprintf(line, sizeof line, "insn_count: interval %zu %" PRIu64 "\n", i, intervals[i]);
            qemu_plugin_outs(line);
        }
    }
    size_t lo = stat_first < n_intervals ? stat_first : n_intervals;
    size_t n = n_intervals - lo < stat_count ? n_intervals - lo : stat_count;
    if (n > 0) {
        uint64_t *v = intervals + lo;
        qsort(v, n, sizeof *v, cmp_u64);
        snprintf(line, sizeof line,
                 "insn_count: marker 0x%" PRIx64 " hits %" PRIu64 " intervals %zu min %" PRIu64
                 " median %" PRIu64 " max %" PRIu64 "\n",
                 marker_addr, marker_hits, n, v[0], v[n / 2], v[n - 1]);
    } else {
        snprintf(line, sizeof line, "insn_count: marker 0x%" PRIx64 " hits %" PRIu64 " intervals 0\n",
                 marker_addr, marker_hits);
    }
    qemu_plugin_outs(line);
}

QEMU_PLUGIN_EXPORT int qemu_plugin_install(qemu_plugin_id_t id, const qemu_info_t *info, int argc,
                                           char **argv)
{
    (void)info;
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i];
        if (strncmp(a, "addr=", 5) == 0) {
            char *end;
            marker_addr = strtoull(a + 5, &end, 0) & ~(uint64_t)1;
            if (end == a + 5 || *end != '\0') {
                fprintf(stderr, "insn_count: bad marker address '%s'\n", a + 5);
                return -1;
            }
            marker_on = true;
        } else if (strncmp(a, "limit=", 6) == 0) {
            char *end;
            limit = strtoull(a + 6, &end, 0);
            if (end == a + 6 || *end != '\0' || limit == 0) {
                fprintf(stderr, "insn_count: bad instruction budget '%s'\n", a + 6);
                return -1;
            }
        } else if (strncmp(a, "stop=", 5) == 0) {
            char *end;
            stop_addr = strtoull(a + 5, &end, 0) & ~(uint64_t)1;
            if (end == a + 5 || *end != '\0') {
                fprintf(stderr, "insn_count: bad stop address '%s'\n", a + 5);
                return -1;
            }
            stop_on = true;
        } else if (strncmp(a, "first=", 6) == 0 || strncmp(a, "count=", 6) == 0) {
            char *end;
            unsigned long long v = strtoull(a + 6, &end, 0);
            if (end == a + 6 || *end != '\0') {
                fprintf(stderr, "insn_count: bad number in '%s'\n", a);
                return -1;
            }
            if (a[0] == 'f') stat_first = (size_t)v;
            else stat_count = (size_t)v;
        } else if (strcmp(a, "dump=on") == 0) {
            dump_on = true;
        } else if (strcmp(a, "dump=off") == 0) {
            dump_on = false;
        } else {
            fprintf(stderr, "insn_count: unknown argument '%s' (expected addr=<address>, stop=<address>, first=<i>, count=<n>, dump=on)\n", a);
            return -1;
        }
    }
    qemu_plugin_register_vcpu_tb_trans_cb(id, on_tb_trans);
    qemu_plugin_register_atexit_cb(id, plugin_at_exit, NULL);
    return 0;
}
