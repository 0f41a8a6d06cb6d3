/* main.c - host test runner: the portable tests (tests/registry.c), then the tests that
 * need the host (libm as a reference). An optional argument filters tests by name. */
#include "harness.h"

extern const th_test *const th_portable[];
extern const th_test *const th_host[];

int main(int argc, char **argv)
{
    const char *filter = argc > 1 ? argv[1] : 0;
    th_run(th_portable, filter);
    th_run(th_host, filter);
    return th_summary() ? 1 : 0;
}
