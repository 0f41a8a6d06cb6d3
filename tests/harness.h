/* harness.h - the in-house test harness: checks, near-equality, a summary line.
 *
 * It depends only on port_write (ports/port.h), so the same test files run on the host
 * and on bare-metal targets under QEMU. A test is a void function registered in the
 * table of tests/registry.c; th_run runs them and prints "N passed, N failed". */
#ifndef TH_HARNESS_H
#define TH_HARNESS_H

#include <stdint.h>

typedef struct th_test {
    const char *name;
    void (*fn)(void);
} th_test;

/* Runs every test of the NULL-terminated tables (a NULL-terminated list of them) whose
   name contains filter (NULL: all); prints "ok <name>" per clean test and one line per
   failed check. */
void th_run(const th_test *const *tables, const char *filter);
/* Prints the summary line "N passed, N failed"; returns the number of failures. */
int th_summary(void);

/* Each check counts as one pass or one fail; they return the condition. */
#define TH_CHECK(cond) th_check((cond) ? 1 : 0, #cond, __FILE__, __LINE__)
#define TH_NEAR(a, b, tol) th_near((double)(a), (double)(b), (double)(tol), #a, __FILE__, __LINE__)
#define TH_EQ_U64(a, b) th_eq_u64((uint64_t)(a), (uint64_t)(b), #a, __FILE__, __LINE__)
int th_check(int ok, const char *expr, const char *file, int line);
int th_near(double a, double b, double tol, const char *expr, const char *file, int line);
int th_eq_u64(uint64_t a, uint64_t b, const char *expr, const char *file, int line);

/* Prints a note (shown always) with optional number: "  note: <text> <value>". */
void th_note(const char *text, double value);

/* Does text s contain f? (for checking error messages) */
int th_has(const char *s, const char *f);

/* Formatting helpers usable without libc: decimal, %.17g-like real, 16-digit hex. */
void th_put(const char *s);
void th_put_int(long long v);
void th_put_real(double v);
void th_put_hex64(uint64_t v);

#endif /* TH_HARNESS_H */
