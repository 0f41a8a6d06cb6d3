/* string.h - what FMU code in an image may use of <string.h> on a target whose toolchain has
 * no C library (tools/image.sh; docs/fmi.md, "FMUs in images"): the memory functions of the
 * ports (ports/common/libc_min.c) and the string functions of tools/fmi/fmu_libc.c. */
#ifndef FMU_LIBC_STRING_H
#define FMU_LIBC_STRING_H

#include <stddef.h>

void *memcpy(void *restrict dst, const void *restrict src, size_t n);
void *memmove(void *dst, const void *src, size_t n);
void *memset(void *dst, int c, size_t n);
int memcmp(const void *a, const void *b, size_t n);
size_t strlen(const char *s);
int strcmp(const char *a, const char *b);
int strncmp(const char *a, const char *b, size_t n);

#endif
