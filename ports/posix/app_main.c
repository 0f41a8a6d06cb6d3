/* app_main.c - the POSIX entry point for applications written against ports/port.h
 * (the cross-test images): bare-metal startup code calls app_main; here main does. */
#include <stdio.h>

#include "port.h"

int main(void)
{
    /* every line out as soon as it is complete, as on bare metal: a run cut off by its
       instruction budget (the QEMU plugin ends the process at once) keeps what it printed */
    (void)setvbuf(stdout, NULL, _IOLBF, 0);
    return app_main();
}
