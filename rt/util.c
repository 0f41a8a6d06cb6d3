/* util.c - status and counter names, capacity faults, the trace hash, and the few string
 * helpers that freestanding code needs (no libc). */
#include <stdarg.h>

#include "rti.h"

static const char *const status_text[] = {
#define RT_X_TEXT(id, sev, text) text,
    RT_STATUS_LIST(RT_X_TEXT)
#undef RT_X_TEXT
};

static const unsigned char status_severity[] = {
#define RT_X_SEV(id, sev, text) sev,
    RT_STATUS_LIST(RT_X_SEV)
#undef RT_X_SEV
};

static const char *const counter_key[] = {
#define RT_X_KEY(id, key, text) key,
    RT_COUNTER_LIST(RT_X_KEY)
#undef RT_X_KEY
};

const char *rt_status_name(rt_status s)
{
    return (unsigned)s < RT_STATUS_COUNT ? status_text[s] : "?";
}

int rt_status_severity(rt_status s)
{
    return (unsigned)s < RT_STATUS_COUNT ? status_severity[s] : 3;
}

const char *rt_counter_key(rt_counter c)
{
    return (unsigned)c < RT_CNT_COUNT ? counter_key[c] : "?";
}

int rt_streq(const char *a, const char *b)
{
    while (*a && *a == *b)
        a++, b++;
    return *a == *b;
}

/* ------------------------------------------------------------------ name lists */

#define RT_X_NAME(id, name) name,
static const char *const kind_type_names[] = {RT_KIND_TYPE_LIST(RT_X_NAME)};
static const char *const interp_names[] = {RT_INTERP_LIST(RT_X_NAME)};
static const char *const stab_names[] = {RT_STAB_LIST(RT_X_NAME)};
static const char *const policy_names[] = {RT_LINK_POLICY_LIST(RT_X_NAME)};
#undef RT_X_NAME

static int find_name(const char *const *names, int n, const char *name)
{
    for (int i = 0; i < n; i++)
        if (rt_streq(names[i], name))
            return i;
    return -1;
}

const char *rt_kind_type_name(rt_kind_type t)
{
    return (unsigned)t < RT_KIND_TYPE_COUNT ? kind_type_names[t] : "?";
}

const char *rt_interp_name(rt_interp i)
{
    return (unsigned)i < RT_INTERP_COUNT ? interp_names[i] : "?";
}

int rt_stab_find(const char *name)
{
    return find_name(stab_names, RT_STAB_COUNT, name);
}

const char *rt_link_policy_name(int p)
{
    return (unsigned)p < RT_LINK_POLICY_COUNT ? policy_names[p] : "?";
}

int rt_link_policy_find(const char *name)
{
    return find_name(policy_names, RT_LINK_POLICY_COUNT, name);
}

void rti_zero(void *p, size_t n)
{
    unsigned char *b = p;
    while (n--)
        *b++ = 0;
}

/* the strings of ap up to a null pointer into sim->err from its n-th byte, truncated */
static void put_parts(rt_sim *sim, size_t n, va_list ap)
{
    for (const char *s; (s = va_arg(ap, const char *)) != 0;)
        while (*s && n + 1 < RT_ERR_LEN)
            sim->err[n++] = *s++;
    sim->err[n] = 0;
}

rt_status rti_fail(rt_sim *sim, rt_status status, ...)
{
    va_list ap;
    va_start(ap, status);
    put_parts(sim, 0, ap);
    va_end(ap);
    return status;
}

rt_status rti_layout_check(rt_sim *sim, uint32_t caller_layout)
{
    if (caller_layout == RT_SIM_LAYOUT)
        return RT_OK;
    /* rt_init would write at this build's offsets past a smaller object (or leave a
       larger one's parts where the caller's file does not look for them) */
    return rti_fail(sim, RT_E_SCENE, "rt_sim compiled with other limits than the runtime "
                    "(RT_MAX_*, REAL): build every file with the same (scenec --sizes)",
                    (const char *)0);
}

void rti_note(rt_sim *sim, ...)
{
    va_list ap;
    size_t n = 0;
    while (sim->err[n])
        n++;
    if (n > 0 && n + 3 < RT_ERR_LEN)
        sim->err[n++] = ';', sim->err[n++] = ' ';
    va_start(ap, sim);
    put_parts(sim, n, ap);
    va_end(ap);
}

const char *rti_real_text(char *buf, real_t v)
{
    /* d.dde+xx: three digits are what a message needs; no libc printf in rt/ */
    char *p = buf;
    real_t a = v;
    int e = 0;
    if (a != a)
        return "nan";
    if (a < 0)
        *p++ = '-', a = -a;
    if (a - a != 0) { /* infinite */
        p[0] = 'i', p[1] = 'n', p[2] = 'f', p[3] = 0;
        return buf;
    }
    while (a != 0 && a < 1 && e > -330)
        a *= 10, e--;
    while (a >= 10)
        a /= 10, e++;
    unsigned d = (unsigned)(a * 100 + (real_t)0.5);
    if (d >= 1000)
        d /= 10, e++;
    *p++ = (char)('0' + d / 100), *p++ = '.';
    *p++ = (char)('0' + d / 10 % 10), *p++ = (char)('0' + d % 10);
    *p++ = 'e', *p++ = e < 0 ? '-' : '+';
    e = e < 0 ? -e : e;
    if (e >= 100)
        *p++ = (char)('0' + e / 100);
    *p++ = (char)('0' + e / 10 % 10), *p++ = (char)('0' + e % 10), *p = 0;
    return buf;
}

const char *rt_error_text(const rt_sim *sim)
{
    return sim->err;
}

void rti_count(rt_sim *sim, rt_counter c, int b, rt_status status)
{
    if (sim->stats.count[c]++ == 0)
        sim->stats.first_tick[c] = (uint32_t)sim->state.tick;
    sim->stats.last_block[c] = (int16_t)b;
    if (rt_status_severity(status) > rt_status_severity(sim->stats.status))
        sim->stats.status = status; /* the worst; the first of equally bad ones */
}

void rt_note_status(rt_sim *sim, rt_status status)
{
    if (rt_status_severity(status) > rt_status_severity(sim->stats.status))
        sim->stats.status = status;
}

void rt_note_count(rt_sim *sim, rt_counter c, uint32_t n, uint64_t first_tick,
                   rt_status status)
{
    if (n == 0)
        return;
    if (sim->stats.count[c] == 0)
        sim->stats.first_tick[c] = (uint32_t)first_tick;
    sim->stats.count[c] += n;
    rt_note_status(sim, status);
}

uint64_t rt_hash_real(uint64_t h, real_t v)
{
    return rti_hash(h, v);
}

/* ------------------------------------------------------------------ capacity limits */

/* each row of RT_LIMIT_LIST: what it counts, its macro, its value in this build */
static const struct {
    const char *what, *macro;
    uint32_t value;
} limits[RT_LIM_COUNT] = {
#define RT_X_ROW(name, field, least, dflt, what)                                             \
    {what, "RT_MAX_" #name, (uint32_t)(RT_MAX_##name)},
    RT_LIMIT_LIST(RT_X_ROW)
#undef RT_X_ROW
};

/* s appended at buf[*n], within cap bytes and terminated */
static void put(char *buf, size_t cap, size_t *n, const char *s)
{
    while (*s && *n + 1 < cap)
        buf[(*n)++] = *s++;
    buf[*n] = 0;
}

const char *rt_limit_text(char *buf, size_t cap, rt_limit lim)
{
    char num[11], *p = num + sizeof num - 1; /* the value in decimal, from its end */
    size_t n = 0;
    if (cap == 0)
        return buf;
    buf[0] = 0;
    if ((unsigned)lim >= RT_LIM_COUNT)
        return buf;
    uint32_t v = limits[lim].value;
    *p = 0;
    do
        *--p = (char)('0' + v % 10);
    while ((v /= 10) != 0);
    put(buf, cap, &n, limits[lim].what);
    put(buf, cap, &n, " exceed ");
    put(buf, cap, &n, limits[lim].macro);
    put(buf, cap, &n, " (");
    put(buf, cap, &n, p);
    put(buf, cap, &n, " in rt_config.h)");
    return buf;
}

rt_status rti_capacity(rt_sim *sim, const char *place, const char *name, rt_limit lim)
{
    char text[RT_ERR_LEN];
    rt_limit_text(text, sizeof text, lim);
    return place && name ? rti_fail(sim, RT_E_CAPACITY, place, name, ": ", text, (const char *)0)
                         : rti_fail(sim, RT_E_CAPACITY, text, (const char *)0);
}
