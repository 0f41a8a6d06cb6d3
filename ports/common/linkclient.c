/* linkclient.c - the controller side of the link over a byte stream (linkclient.h): the
 * framing receiver fed byte by byte, the datagram check, once-only delivery of each
 * request and the answer kept for a repeat. No libc. */
#include "linkclient.h"

uint32_t linkclient_layout_id(const char *const *words, int n)
{
    uint32_t h = 2166136261u;
    for (int i = 0; i < n; i++) {
        for (const char *s = words[i]; *s; s++)
            h = (h ^ (uint8_t)*s) * 16777619u;
        h = (h ^ (uint8_t)'|') * 16777619u;
    }
    return h;
}

int linkclient_init(linkclient *c, const char *scene, uint32_t id, uint16_t nexp,
                    uint16_t nimp, const linkclient_io *io)
{
    if (!c || !scene || !io || !io->read || !io->write || nexp > LINK_MAX_VALUES ||
        nimp > LINK_MAX_VALUES)
        return -1;
    c->scene = scene, c->id = id, c->nexp = nexp, c->nimp = nimp, c->io = *io;
    c->key = 0, c->pending = 0, c->new_run = 0, c->run = 0, c->answered = 0;
    c->answer_len = 0;
    c->last_seq = 0, c->last_crc = c->req_crc = 0, c->last_tick = 0;
    c->requests = c->repeats = c->overtaken = 0;
    for (int e = 0; e < LINK_E_COUNT_; e++)
        c->bad[e] = 0;
    linkframe_rx_init(&c->rx);
    return 0;
}

uint32_t linkclient_faults(const linkclient *c)
{
    uint32_t n = 0;
    for (int e = 0; e < LINK_E_COUNT_; e++)
        n += c->bad[e];
    for (int v = 0; v < LINKFRAME_E_COUNT_; v++)
        n += c->rx.fault[v];
    return n;
}

/* a checked request: the repeat of the last answered one is answered again; 1 if new */
static int take(linkclient *c, const uint8_t *d, size_t len)
{
    link_packet p;
    const link_expect x = {.type = LINK_TYPE_EXPORTS, .name = c->scene, .id = c->id,
                           .n = c->nexp, .key = c->key};
    link_wire_error e = link_decode(d, len, &x, &p);
    if (e != LINK_OK) {
        c->bad[e]++;
        return 0;
    }
    /* the same bytes as the request answered last: its CRC field, seq and tick agree */
    uint32_t crc = (uint32_t)link_get_le(d + LINK_SIZE(p.n) - 4, 4);
    if (c->answered && crc == c->last_crc && p.seq == c->last_seq && p.tick == c->last_tick) {
        c->repeats++;
        c->io.write(c->io.ctx, c->answer, c->answer_len);
        return 0;
    }
    if (c->pending && p.seq == c->req.seq && p.tick == c->req.tick)
        return 0; /* sent again before we answered: the answer is on its way */
    c->overtaken += (uint32_t)c->pending;
    c->new_run = c->requests == 0 || p.run != c->run;
    c->req = p, c->pending = 1, c->req_crc = crc, c->run = p.run;
    c->requests++;
    return 1;
}

int linkclient_poll(linkclient *c)
{
    int b;
    while ((b = c->io.read(c->io.ctx)) >= 0) {
        const uint8_t *d;
        size_t len;
        if (linkframe_rx_byte(&c->rx, (uint8_t)b, &d, &len) == LINKFRAME_DATAGRAM &&
            take(c, d, len))
            return 1; /* the rest of the bytes waits for the next call */
    }
    return c->pending;
}

int linkclient_answer(linkclient *c, const double *v)
{
    uint8_t d[LINK_MAX_PACKET];
    if (!c->pending)
        return -1;
    link_packet a = c->req; /* every field the answer echoes */
    a.type = LINK_TYPE_IMPORTS, a.n = c->nimp;
    for (uint16_t i = 0; i < c->nimp; i++) {
        if (!(v[i] - v[i] == 0))
            return -1;
        a.v[i] = v[i];
    }
    size_t n = link_encode(&a, c->key, d, sizeof d);
    c->answer_len = linkframe_encode(d, n, c->answer, sizeof c->answer);
    if (n == 0 || c->answer_len == 0)
        return -1;
    c->pending = 0, c->answered = 1;
    c->last_seq = a.seq, c->last_tick = a.tick, c->last_crc = c->req_crc;
    c->io.write(c->io.ctx, c->answer, c->answer_len);
    return 0;
}
