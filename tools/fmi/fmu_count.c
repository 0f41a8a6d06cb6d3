/* fmu_count.c - compiled into an FMI 3.0 source FMU's binary for the host (fmu_build.c),
 * with the FMU's calloc, malloc and free named fmu_count_calloc, fmu_count_malloc and
 * fmu_count_free, as an image names them after its static arena (fmu_arena.c): the memory
 * comes from the C library, and what the arena would have handed out for it is tallied
 * (FMU_COUNT_ALIGN: the arena's alignment), so `scenec --sizes` can size an image's arena
 * (fmu_arena_need). Nothing of modrt is included: the FMU's build sees only this file. */
#include <stddef.h>

#undef calloc
#undef malloc
#undef free
void *calloc(size_t n, size_t size); /* the C library's (stdlib.h names the counting ones) */
void free(void *p);

static size_t used;

void *fmu_count_calloc(size_t n, size_t size)
{
    void *p = calloc(n, size);
    if (p)
        used = ((used + FMU_COUNT_ALIGN - 1) & ~(size_t)(FMU_COUNT_ALIGN - 1)) + n * size;
    return p;
}

void *fmu_count_malloc(size_t size) { return fmu_count_calloc(1, size); }

void fmu_count_free(void *p) { free(p); } /* (the arena reuses nothing: used stays) */

/* bytes the arena would have handed out so far (dlsym'd by the importer) */
size_t fmu_count_used(void) { return used; }
