/* fmu_zip.c - an FMU archive unpacked into the cache (fmu_unpack): libzip reads it; every
 * entry name is checked before anything is written (no absolute path, no `..` component,
 * no backslash or drive letter: an entry never lands outside the FMU's directory), and the
 * sizes are bounded. The directory is named after a hash of the file's bytes, written
 * under a temporary name and renamed when complete, so concurrent runs and an interrupted
 * unpack never see half an FMU. */
#define _XOPEN_SOURCE 700
#include "fmu.h"

#include <errno.h>
#include <ftw.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include <zip.h>

/* FNV-1a, 64 bits, over the file's bytes: the cache key */
static int file_hash(const char *path, unsigned long long *h, char *err, size_t errlen)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        snprintf(err, errlen, "%s: %s", path, strerror(errno));
        return -1;
    }
    unsigned char buf[65536];
    size_t n;
    *h = 0xcbf29ce484222325ull;
    while ((n = fread(buf, 1, sizeof buf, f)) > 0)
        for (size_t i = 0; i < n; i++)
            *h = (*h ^ buf[i]) * 0x100000001b3ull;
    int bad = ferror(f);
    fclose(f);
    if (bad) {
        snprintf(err, errlen, "%s: read error", path);
        return -1;
    }
    return 0;
}

static int mkdirs(char *p)
{
    for (char *s = p + 1; *s; s++) {
        if (*s != '/')
            continue;
        *s = 0;
        int r = mkdir(p, 0755);
        *s = '/';
        if (r != 0 && errno != EEXIST)
            return -1;
    }
    return mkdir(p, 0755) == 0 || errno == EEXIST ? 0 : -1;
}

static const char *cache_root(char *buf, size_t n)
{
    const char *e = getenv("MODRT_FMU_CACHE");
    if (e && *e)
        return e;
    e = getenv("XDG_CACHE_HOME");
    if (e && *e)
        snprintf(buf, n, "%s/modrt/fmu", e);
    else if ((e = getenv("HOME")) && *e)
        snprintf(buf, n, "%s/.cache/modrt/fmu", e);
    else
        snprintf(buf, n, "/tmp/modrt-fmu-%lu", (unsigned long)getuid());
    return buf;
}

/* an entry name that stays inside the directory it is unpacked into */
static int safe_name(const char *s)
{
    if (!*s || s[0] == '/' || strchr(s, '\\') || (s[0] && s[1] == ':'))
        return 0;
    for (const char *c = s; *c;) {
        const char *e = strchr(c, '/');
        size_t n = e ? (size_t)(e - c) : strlen(c);
        if ((n == 2 && c[0] == '.' && c[1] == '.'))
            return 0;
        c += n + (e ? 1 : 0);
    }
    return 1;
}

/* checks every entry before anything is written */
static int check_entries(zip_t *z, const char *path, char *err, size_t errlen)
{
    zip_int64_t n = zip_get_num_entries(z, 0);
    unsigned long long total = 0;
    int md = 0;
    if (n < 0 || (unsigned long long)n > FMU_MAX_ENTRIES) {
        snprintf(err, errlen, "%s: more than %u entries", path, FMU_MAX_ENTRIES);
        return -1;
    }
    for (zip_int64_t i = 0; i < n; i++) {
        zip_stat_t st;
        const char *name = zip_get_name(z, (zip_uint64_t)i, ZIP_FL_ENC_RAW);
        if (!name || zip_stat_index(z, (zip_uint64_t)i, 0, &st) != 0) {
            snprintf(err, errlen, "%s: entry %lld unreadable: %s", path, (long long)i,
                     zip_strerror(z));
            return -1;
        }
        if (!safe_name(name)) {
            snprintf(err, errlen, "%s: entry '%s' would be written outside the FMU's "
                     "directory (absolute path or '..'): refused", path, name);
            return -1;
        }
        total += st.size;
        if (total > FMU_MAX_UNPACKED) {
            snprintf(err, errlen, "%s: unpacks to more than %llu bytes", path,
                     (unsigned long long)FMU_MAX_UNPACKED);
            return -1;
        }
        md |= !strcmp(name, "modelDescription.xml");
    }
    if (!md) {
        snprintf(err, errlen, "%s: no modelDescription.xml at the archive's root", path);
        return -1;
    }
    return 0;
}

static int write_entry(zip_t *z, zip_uint64_t i, const char *name, const char *dir,
                       char *err, size_t errlen)
{
    size_t len = strlen(dir) + strlen(name) + 2;
    char *out = malloc(len);
    if (!out)
        return snprintf(err, errlen, "out of memory"), -1;
    snprintf(out, len, "%s/%s", dir, name);
    int rc = 0;
    if (name[strlen(name) - 1] == '/') { /* a directory */
        out[len - 2] = 0;
        rc = mkdirs(out);
    } else {
        char *slash = strrchr(out, '/');
        *slash = 0;
        rc = mkdirs(out);
        *slash = '/';
        zip_file_t *zf = rc ? NULL : zip_fopen_index(z, i, 0);
        FILE *f = zf ? fopen(out, "wb") : NULL;
        char buf[65536];
        zip_int64_t got;
        while (f && (got = zip_fread(zf, buf, sizeof buf)) > 0)
            if (fwrite(buf, 1, (size_t)got, f) != (size_t)got)
                got = -1;
        rc = !f || got < 0 || ferror(f) ? -1 : 0;
        if (zf && rc)
            snprintf(err, errlen, "entry '%s': %s", name, zip_file_strerror(zf));
        if (f)
            rc |= fclose(f) != 0 ? -1 : 0;
        if (zf)
            zip_fclose(zf);
    }
    if (rc && !*err)
        snprintf(err, errlen, "cannot write %s: %s", out, strerror(errno));
    free(out);
    return rc;
}

static int rm_one(const char *p, const struct stat *sb, int flag, struct FTW *ftw)
{
    (void)sb, (void)flag, (void)ftw;
    return remove(p);
}

static int extract(const char *path, const char *dir, char *err, size_t errlen)
{
    int ze = 0;
    zip_t *z = zip_open(path, ZIP_RDONLY | ZIP_CHECKCONS, &ze);
    if (!z) {
        zip_error_t e;
        zip_error_init_with_code(&e, ze);
        snprintf(err, errlen, "%s: not a readable zip archive (%s)", path, zip_error_strerror(&e));
        zip_error_fini(&e);
        return -1;
    }
    int rc = check_entries(z, path, err, errlen);
    zip_int64_t n = zip_get_num_entries(z, 0);
    char *d = strdup(dir);
    rc = rc || !d || mkdirs(d) ? (rc ? rc : (snprintf(err, errlen, "cannot create %s", dir), -1)) : 0;
    free(d);
    for (zip_int64_t i = 0; rc == 0 && i < n; i++) {
        char msg[FMU_ERR_LEN] = "";
        rc = write_entry(z, (zip_uint64_t)i, zip_get_name(z, (zip_uint64_t)i, ZIP_FL_ENC_RAW), dir,
                         msg, sizeof msg);
        if (rc)
            snprintf(err, errlen, "%s: %s", path, msg);
    }
    zip_discard(z);
    return rc;
}

char *fmu_unpack(const char *path, char *err, size_t errlen)
{
    unsigned long long h;
    char rootbuf[4096], dir[4200], tmp[4300];
    if (file_hash(path, &h, err, errlen))
        return NULL;
    const char *root = cache_root(rootbuf, sizeof rootbuf);
    snprintf(dir, sizeof dir, "%s/%016llx", root, h);
    struct stat st;
    if (stat(dir, &st) == 0 && S_ISDIR(st.st_mode))
        return realpath(dir, NULL); /* absolute: the FMU and its build may chdir */
    snprintf(tmp, sizeof tmp, "%s.tmp%ld", dir, (long)getpid());
    nftw(tmp, rm_one, 16, FTW_DEPTH | FTW_PHYS); /* a leftover of an interrupted run */
    if (extract(path, tmp, err, errlen)) {
        nftw(tmp, rm_one, 16, FTW_DEPTH | FTW_PHYS);
        return NULL;
    }
    if (rename(tmp, dir) != 0) { /* another process got there first: its copy is whole */
        nftw(tmp, rm_one, 16, FTW_DEPTH | FTW_PHYS);
        if (stat(dir, &st) != 0) {
            snprintf(err, errlen, "cannot create %s: %s", dir, strerror(errno));
            return NULL;
        }
    }
    return realpath(dir, NULL);
}
