/* harness.c - the in-house test harness: counts checks, prints failures and the summary
 * line "N passed, N failed". Uses port_write only, so it runs on bare metal as well. */
#include "harness.h"

#include "port.h"

#define NUM_BUF 40 /* digits of the longest number printed */

static unsigned passed, failed;
static const char *current;

void th_put(const char *s) { port_write(s); }

void th_put_int(long long v)
{
    char buf[NUM_BUF];
    int n = NUM_BUF - 1;
    unsigned long long u = v < 0 ? 0ull - (unsigned long long)v : (unsigned long long)v;
    buf[n] = 0;
    do {
        buf[--n] = (char)('0' + u % 10);
        u /= 10;
    } while (u && n > 1);
    if (v < 0)
        buf[--n] = '-';
    th_put(buf + n);
}

void th_put_hex64(uint64_t v)
{
    char buf[17];
    for (int i = 15; i >= 0; i--, v >>= 4)
        buf[i] = "0123456789abcdef"[v & 15];
    buf[16] = 0;
    th_put(buf);
}

/* scientific notation with 17 significant digits: enough to tell any two doubles apart,
   and it needs no libc */
void th_put_real(double v)
{
    if (v != v) {
        th_put("nan");
        return;
    }
    if (v < 0) {
        th_put("-");
        v = -v;
    }
    if (v > 1.7976931348623157e308) {
        th_put("inf");
        return;
    }
    int e = 0;
    while (v >= 10) v /= 10, e++;
    while (v > 0 && v < 1) v *= 10, e--;
    char buf[24];
    int n = 0;
    for (int i = 0; i < 17; i++) {
        int d = (int)v;
        buf[n++] = (char)('0' + d);
        if (i == 0)
            buf[n++] = '.';
        v = (v - d) * 10;
    }
    buf[n] = 0;
    th_put(buf);
    th_put("e");
    th_put_int(e);
}

static void where(const char *expr, const char *file, int line)
{
    th_put("FAIL ");
    th_put(current ? current : "?");
    th_put(" ");
    th_put(file);
    th_put(":");
    th_put_int(line);
    th_put(": ");
    th_put(expr);
}

int th_check(int ok, const char *expr, const char *file, int line)
{
    if (ok) {
        passed++;
        return 1;
    }
    failed++;
    where(expr, file, line);
    th_put("\n");
    return 0;
}

int th_near(double a, double b, double tol, const char *expr, const char *file, int line)
{
    double d = a - b;
    if (d < 0)
        d = -d;
    if (d <= tol) { /* false for NaN */
        passed++;
        return 1;
    }
    failed++;
    where(expr, file, line);
    th_put(" = ");
    th_put_real(a);
    th_put(", expected ");
    th_put_real(b);
    th_put(" within ");
    th_put_real(tol);
    th_put("\n");
    return 0;
}

int th_eq_u64(uint64_t a, uint64_t b, const char *expr, const char *file, int line)
{
    if (a == b) {
        passed++;
        return 1;
    }
    failed++;
    where(expr, file, line);
    th_put(" = ");
    th_put_hex64(a);
    th_put(", expected ");
    th_put_hex64(b);
    th_put("\n");
    return 0;
}

void th_note(const char *text, double value)
{
    th_put("  note: ");
    th_put(current ? current : "");
    th_put(": ");
    th_put(text);
    th_put(" ");
    th_put_real(value);
    th_put("\n");
}

int th_has(const char *s, const char *f)
{
    for (; *s; s++) {
        const char *a = s, *b = f;
        while (*a && *b && *a == *b)
            a++, b++;
        if (!*b)
            return 1;
    }
    return !*f;
}

/* runs one test, printing "ok" when none of its checks failed */
static void run_one(const th_test *t)
{
    current = t->name;
    unsigned before = failed;
    t->fn();
    if (failed == before) {
        th_put("ok   ");
        th_put(t->name);
        th_put("\n");
    }
}

void th_run(const th_test *const *tables, const char *filter)
{
    for (; *tables; tables++)
        for (const th_test *t = *tables; t->name; t++)
            if (!filter || th_has(t->name, filter))
                run_one(t);
    current = 0;
}

int th_summary(void)
{
    th_put_int(passed);
    th_put(" passed, ");
    th_put_int(failed);
    th_put(" failed\n");
    return (int)failed;
}

