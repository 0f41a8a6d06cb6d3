/* fmu_libc.c - the few C library functions FMU code calls in a per-scene image, whose
 * ports link no C library (-nostdlib; ports/common/libc_min.c has the mem* functions):
 * strlen, strcmp, strncmp, and snprintf / vsnprintf for messages (logged text and fault
 * reasons), which format %s, %c, %d, %i, %u, %x, %zu and %% and print any other
 * conversion (a float) as '?': a message is for a person, never a value the run uses.
 * Linked only into images with FMU blocks (tools/image.sh). */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

size_t strlen(const char *s);
int strcmp(const char *a, const char *b);
int strncmp(const char *a, const char *b, size_t n);
int vsnprintf(char *restrict out, size_t n, const char *restrict fmt, va_list ap);
int snprintf(char *restrict out, size_t n, const char *restrict fmt, ...);

size_t strlen(const char *s)
{
    size_t n = 0;
    while (s[n])
        n++;
    return n;
}

int strncmp(const char *a, const char *b, size_t n)
{
    for (; n && *a && *a == *b; n--, a++, b++)
        ;
    return n ? (unsigned char)*a - (unsigned char)*b : 0;
}

int strcmp(const char *a, const char *b) { return strncmp(a, b, SIZE_MAX); }

typedef struct sink {
    char *out;
    size_t n, len;
} sink;

static void put(sink *s, char c)
{
    if (s->len + 1 < s->n)
        s->out[s->len] = c;
    s->len++;
}

static void number(sink *s, uintmax_t v, unsigned base, int neg)
{
    char d[24];
    int k = 0;
    do
        d[k++] = "0123456789abcdef"[v % base];
    while ((v /= base) && k < 24);
    if (neg)
        put(s, '-');
    while (k)
        put(s, d[--k]);
}

int vsnprintf(char *restrict out, size_t n, const char *restrict fmt, va_list ap)
{
    sink s = {out, n, 0};
    for (const char *p = fmt; *p; p++) {
        if (*p != '%') {
            put(&s, *p);
            continue;
        }
        while (p[1] == '-' || p[1] == '.' || p[1] == '*' || (p[1] >= '0' && p[1] <= '9'))
            if (*++p == '*')
                (void)va_arg(ap, int);
        int z = p[1] == 'z' || p[1] == 'l';
        p += z;
        switch (*++p) {
        case 's': {
            const char *t = va_arg(ap, const char *);
            for (t = t ? t : "(null)"; *t; t++)
                put(&s, *t);
            break;
        }
        case 'c': put(&s, (char)va_arg(ap, int)); break;
        case 'd':
        case 'i': {
            intmax_t v = z ? (intmax_t)va_arg(ap, long) : va_arg(ap, int);
            number(&s, v < 0 ? (uintmax_t)-v : (uintmax_t)v, 10, v < 0);
            break;
        }
        case 'u':
        case 'x': number(&s, z ? va_arg(ap, size_t) : va_arg(ap, unsigned), *p == 'u' ? 10 : 16, 0); break;
        case '%': put(&s, '%'); break;
        case 0: p--; break;
        default: /* a floating-point conversion: its argument is a double */
            (void)va_arg(ap, double);
            put(&s, '?');
        }
    }
    if (n)
        out[s.len < n ? s.len : n - 1] = 0;
    return (int)s.len;
}

int snprintf(char *restrict out, size_t n, const char *restrict fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int r = vsnprintf(out, n, fmt, ap);
    va_end(ap);
    return r;
}
