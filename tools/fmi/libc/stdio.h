/* stdio.h - what FMU code in an image may use of <stdio.h> on a target whose toolchain has no
 * C library (tools/image.sh; docs/fmi.md, "FMUs in images"): the formatting of messages
 * that tools/fmi/fmu_libc.c implements, and FILE only as a name (no stream exists). */
#ifndef FMU_LIBC_STDIO_H
#define FMU_LIBC_STDIO_H

#include <stdarg.h>
#include <stddef.h>

typedef struct fmu_libc_file FILE;
int snprintf(char *restrict out, size_t n, const char *restrict fmt, ...);
int vsnprintf(char *restrict out, size_t n, const char *restrict fmt, va_list ap);

#endif
