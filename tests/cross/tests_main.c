/* tests_main.c - the unit-test image for cross targets: every portable test table, the
 * summary line, and the exit status through the port (QEMU's exit status). */
#include "harness.h"
#include "port.h"

extern const th_test *const th_portable[];

int app_main(void)
{
    th_run(th_portable, 0);
    return th_summary() ? 1 : 0;
}
