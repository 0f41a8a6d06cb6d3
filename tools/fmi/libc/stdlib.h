/* stdlib.h - what FMU code in an image may use of <stdlib.h> on a target whose toolchain has
 * no C library (tools/image.sh; docs/fmi.md, "FMUs in images"): the allocation functions,
 * which an image names after its static arena (fmu_arena.c). */
#ifndef FMU_LIBC_STDLIB_H
#define FMU_LIBC_STDLIB_H

#include <stddef.h>

void *calloc(size_t n, size_t size);
void *malloc(size_t size);
void free(void *p);

#endif
