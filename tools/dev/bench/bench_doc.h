/* bench_doc.h - what the benchmarks share for recording their figures: the host's
 * processor name, and writing a table into a document between two marker lines. */
#ifndef BENCH_DOC_H
#define BENCH_DOC_H

#include <stddef.h>

#define MAX_DOC 131072 /* bytes of a document a table is spliced into */
#define DOC_BEGIN "<!-- bench:begin -->"
#define DOC_END "<!-- bench:end -->"

/* The host's processor, for the record (Linux); "unknown" elsewhere. */
void bench_cpu_name(char *buf, size_t n);
/* Writes text to path; 0 on success, else prints the error and returns 1. */
int bench_write_file(const char *path, const char *text);
/* Replaces the lines between DOC_BEGIN and DOC_END of path with text; the messages name
   the calling tool. 0 on success, 1 (with a message) otherwise. */
int bench_splice_doc(const char *tool, const char *path, const char *text);

#endif /* BENCH_DOC_H */
