/* slow_close.c - a test shim loaded by LD_PRELOAD (tests/cli_io.sh): every fclose waits
 * 0.2 s before it closes, so that the end of a run, where modrt closes its CSV and its
 * replay log, lasts long enough for signals sent meanwhile to reach it there. */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <stdio.h>
#include <time.h>

int fclose(FILE *f)
{
    static int (*real)(FILE *);
    struct timespec wait = {0, 200000000};
    if (!real)
        real = (int (*)(FILE *))dlsym(RTLD_NEXT, "fclose");
    nanosleep(&wait, NULL);
    return real(f);
}
