/* tests_main.c - the unit-test image for cross targets: every portable test table, or one
 * part of them, the summary line, and the exit status through the port (QEMU's exit
 * status). A part (-DTH_PART=k -DTH_PARTS=n) runs every n-th test from the k-th on, so
 * that no one emulated run is long (the soft-float targets run the tests for minutes);
 * it first prints "tests: N", the tests it is to run, so that a run cut off can count the
 * tests it never finished (tests/cross/run.sh). */
#include "harness.h"
#include "port.h"

#ifndef TH_PART
#define TH_PART 0
#define TH_PARTS 1
#endif
#define TH_MAX_PART 1024 /* tests of one part */

extern const th_test *const th_portable[];

static th_test part[TH_MAX_PART + 1];

int app_main(void)
{
    unsigned n = 0, i = 0;
    for (const th_test *const *tb = th_portable; *tb; tb++)
        for (const th_test *t = *tb; t->name; t++, i++)
            if (i % TH_PARTS == TH_PART) {
                if (n == TH_MAX_PART) {
                    th_put("FAIL tests_main: more tests than TH_MAX_PART\n");
                    return 1;
                }
                part[n++] = *t;
            }
    th_put("tests: ");
    th_put_int(n);
    th_put("\n");
    const th_test *const tables[] = {part, 0};
    th_run(tables, 0);
    return th_summary() ? 1 : 0;
}
