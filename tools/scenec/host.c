/* host.c - scene files in the modrt CLI (scn_host.h): one compilation per process, kept
 * for the process's lifetime because the scene it returns points into it. */
#include "scn_host.h"

#include <stdio.h>
#include <string.h>

#include "scn.h"

int scn_host_is_file(const char *arg)
{
    size_t n = strlen(arg);
    return n > 4 && strcmp(arg + n - 4, ".scn") == 0;
}

const rt_scene *scn_host_load(const char *path)
{
    static scn_ctx *last; /* owns the scene's memory until exit (modrt loads one) */
    scn_ctx *c = scn_new();
    if (!c) {
        fputs("modrt: out of memory\n", stderr);
        return NULL;
    }
    if (scn_compile(c, path, NULL, 0) != 0) {
        fprintf(stderr, "modrt: %s\n", c->msg);
        scn_free(c);
        return NULL;
    }
    last = c;
    return &last->image;
}
