/* app_main.c - the POSIX entry point for applications written against ports/port.h
 * (the cross-test images): bare-metal startup code calls app_main; here main does. */
#include "port.h"

int main(void)
{
    return app_main();
}
