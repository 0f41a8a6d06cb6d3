/* fmu_arena.c - the memory of the FMUs in a per-scene image (docs/fmi.md, "FMUs in
 * images"): one static block of FMU_ARENA_BYTES, handed out in order and never reused.
 * FMI 2.0 FMUs get it through allocateMemory / freeMemory; FMI 3.0 has no memory
 * callbacks, so an image compiles an FMU's sources with calloc, malloc and free named
 * fmu_arena_calloc, fmu_arena_malloc and fmu_arena_free. Instances are made once, at the
 * first rt_init: the tick never allocates, and an arena too small fails that rt_init
 * (the FMU's instantiation returns NULL), never a tick. */
#include <stddef.h>
#include <string.h>

#include "fmu_int.h"

static _Alignas(FMU_ARENA_ALIGN) unsigned char arena[FMU_ARENA_BYTES];
static size_t used;

void *fmu_arena_calloc(size_t n, size_t size)
{
    size_t bytes = n * size, at = (used + FMU_ARENA_ALIGN - 1) & ~(size_t)(FMU_ARENA_ALIGN - 1);
    if ((size && bytes / size != n) || bytes > FMU_ARENA_BYTES - at || at > FMU_ARENA_BYTES)
        return NULL;
    used = at + bytes;
    memset(arena + at, 0, bytes);
    return arena + at;
}

void *fmu_arena_malloc(size_t size) { return fmu_arena_calloc(1, size); }

/* freed blocks are not reused: an FMU is instantiated once per image */
void fmu_arena_free(void *p) { (void)p; }

size_t fmu_arena_used(void) { return used; }
