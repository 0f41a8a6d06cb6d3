/* test_kinds_doc.c - every kind of the registry (models/registry.c) carries its reference
 * text for `modrt info KIND` and docs/blocks.md: a non-empty doc, and units with one
 * token per input, output, continuous state, discrete state and parameter (in that
 * order), separated by single spaces. Host test: the texts exist only where RT_KIND_DOCS
 * is 1. */
#include "models.h"
#include "testutil.h"

/* tokens of s separated by single spaces; -1 if a token is empty (leading, trailing or
   doubled space) */
static int unit_tokens(const char *s)
{
    int n = 1;
    if (*s == ' ')
        return -1;
    for (; *s; s++)
        if (*s == ' ') {
            if (s[1] == ' ' || s[1] == 0)
                return -1;
            n++;
        }
    return n;
}

static void test_kinds_doc(void)
{
#if RT_KIND_DOCS
    int n = 0;
    for (const mdl_entry *e = mdl_kinds; e->name; e++, n++) {
        const rt_kind *k = e->kind;
        int want = k->nu + k->ny + k->nx + k->nd + k->np;
        int ok = TH_CHECK(k->doc && k->doc[0]);
        ok &= TH_CHECK(k->units && k->units[0]);
        if (ok) {
            int got = unit_tokens(k->units);
            ok &= TH_CHECK(got == want);
            if (got != want)
                th_note("unit tokens (want nu+ny+nx+nd+np, -1: empty token)", got);
        }
        if (!ok)
            th_put(e->name), th_put(": kind without complete reference text\n");
    }
    TH_CHECK(n >= 20);
#endif
}

const th_test th_kinds_doc_tests[] = {
    {"kinds_doc", test_kinds_doc},
    {0, 0},
};
