/* libc_min.c - memcpy, memmove, memset and memcmp for the bare-metal ports (Cortex-M and
 * RISC-V both link this file; they are built with -nostdlib, and gcc may emit calls to
 * these four even in freestanding code, for struct copies and zeroing).
 *
 * Small and correct rather than fast: byte loops, plus a word loop in memcpy/memset when
 * both pointers are word aligned. The optimize attribute stops gcc from recognising the
 * loops below as memcpy/memset and turning them into calls to themselves
 * (-ftree-loop-distribute-patterns is on at -O2 even with -ffreestanding). */
#include <stddef.h>
#include <stdint.h>

#if defined(__GNUC__) && !defined(__clang__)
#define LIBC_MIN_NOPATTERN __attribute__((optimize("no-tree-loop-distribute-patterns")))
#else
#define LIBC_MIN_NOPATTERN
#endif

void *memcpy(void *restrict dst, const void *restrict src, size_t n);
void *memmove(void *dst, const void *src, size_t n);
void *memset(void *dst, int c, size_t n);
int memcmp(const void *a, const void *b, size_t n);

/* Word accesses through a may_alias type, so the copies are valid for any object type. */
typedef uintptr_t __attribute__((may_alias)) libc_word;

LIBC_MIN_NOPATTERN void *memcpy(void *restrict dst, const void *restrict src, size_t n)
{
    unsigned char *d = dst;
    const unsigned char *s = src;
    if ((((uintptr_t)d | (uintptr_t)s) & (sizeof(libc_word) - 1)) == 0) {
        while (n >= sizeof(libc_word)) {
            *(libc_word *)(void *)d = *(const libc_word *)(const void *)s;
            d += sizeof(libc_word);
            s += sizeof(libc_word);
            n -= sizeof(libc_word);
        }
    }
    while (n--) *d++ = *s++;
    return dst;
}

LIBC_MIN_NOPATTERN void *memmove(void *dst, const void *src, size_t n)
{
    unsigned char *d = dst;
    const unsigned char *s = src;
    if (d == s || n == 0) return dst;
    if ((uintptr_t)d - (uintptr_t)s >= n) {
        /* d is below s, or at least n bytes above it: a forward copy never reads a byte
           it has already overwritten. */
        while (n--) *d++ = *s++;
    } else {
        d += n;
        s += n;
        while (n--) *--d = *--s;
    }
    return dst;
}

LIBC_MIN_NOPATTERN void *memset(void *dst, int c, size_t n)
{
    unsigned char *d = dst;
    unsigned char b = (unsigned char)c;
    if (((uintptr_t)d & (sizeof(libc_word) - 1)) == 0 && n >= sizeof(libc_word)) {
        libc_word w = (libc_word)0x0101010101010101ull * b;
        while (n >= sizeof(libc_word)) {
            *(libc_word *)(void *)d = w;
            d += sizeof(libc_word);
            n -= sizeof(libc_word);
        }
    }
    while (n--) *d++ = b;
    return dst;
}

LIBC_MIN_NOPATTERN int memcmp(const void *a, const void *b, size_t n)
{
    const unsigned char *p = a;
    const unsigned char *q = b;
    for (; n; n--, p++, q++) {
        if (*p != *q) return (int)*p - (int)*q;
    }
    return 0;
}
