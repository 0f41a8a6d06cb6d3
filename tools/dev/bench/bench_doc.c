/* bench_doc.c - recording benchmark figures: the processor name, writing a file, and
 * splicing a table between the bench markers of a document (docs/mbs.md,
 * docs/multirate.md). Host code: libc is fine here. */
#include "bench_doc.h"

#include <stdio.h>
#include <string.h>

void bench_cpu_name(char *buf, size_t n)
{
    snprintf(buf, n, "unknown");
    FILE *f = fopen("/proc/cpuinfo", "r");
    char line[256];
    while (f && fgets(line, sizeof line, f))
        if (!strncmp(line, "model name", 10) && strchr(line, ':')) {
            snprintf(buf, n, "%s", strchr(line, ':') + 2);
            buf[strcspn(buf, "\n")] = 0;
            break;
        }
    if (f)
        fclose(f);
}

int bench_write_file(const char *path, const char *text)
{
    FILE *f = fopen(path, "w");
    if (!f || fputs(text, f) < 0 || fclose(f) != 0) {
        perror(path);
        return 1;
    }
    return 0;
}

int bench_splice_doc(const char *tool, const char *path, const char *text)
{
    static char old[MAX_DOC], out[2 * MAX_DOC];
    FILE *f = fopen(path, "r");
    size_t n = f ? fread(old, 1, sizeof old - 1, f) : 0;
    if (!f || n == sizeof old - 1) {
        fprintf(stderr, "%s: cannot read %s (or larger than %d bytes)\n", tool, path, MAX_DOC);
        if (f)
            fclose(f);
        return 1;
    }
    fclose(f);
    old[n] = 0;
    char *a = strstr(old, DOC_BEGIN), *b = a ? strstr(a, DOC_END) : 0;
    if (!a || !b) {
        fprintf(stderr, "%s: %s lacks the lines %s and %s\n", tool, path, DOC_BEGIN, DOC_END);
        return 1;
    }
    a += strlen(DOC_BEGIN);
    snprintf(out, sizeof out, "%.*s\n%s%s", (int)(a - old), old, text, b);
    return bench_write_file(path, out);
}
