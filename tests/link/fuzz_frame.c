/* fuzz_frame.c - libFuzzer target for the serial link's byte-stream side: any byte stream
 * fed to the frame receiver (ports/common/linkframe.c) and to the controller's client
 * library (ports/common/linkclient.c, answering every request it hands over). Neither may
 * crash, hang or trip a sanitizer; a datagram the receiver yields is never longer than
 * the largest one; the verdict counts are printed at exit. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "common/linkclient.h"
#include "common/linkframe.h"

static unsigned long verdicts[LINKFRAME_E_COUNT_], requests;

static void report(void)
{
    fprintf(stderr, "frame fuzz verdicts:");
    for (int v = 0; v < LINKFRAME_E_COUNT_; v++)
        fprintf(stderr, " %s %lu", linkframe_fault_key(v), verdicts[v]);
    fprintf(stderr, "; requests handed over %lu\n", requests);
}

typedef struct stream {
    const uint8_t *p;
    size_t n, at, sent;
} stream;

static int s_read(void *ctx)
{
    stream *s = ctx;
    return s->at < s->n ? s->p[s->at++] : -1;
}

static void s_write(void *ctx, const uint8_t *b, size_t n)
{
    stream *s = ctx;
    for (size_t i = 0; i < n; i++)
        s->sent += b[i]; /* touch every byte */
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static linkframe_rx rx;
    static linkclient c;
    static int once;
    if (!once)
        once = 1, atexit(report);
    linkframe_rx_init(&rx);
    for (size_t i = 0; i < size; i++) {
        const uint8_t *d;
        size_t len;
        linkframe_verdict v = linkframe_rx_byte(&rx, data[i], &d, &len);
        verdicts[v]++;
        if (v == LINKFRAME_DATAGRAM && (len > LINK_MAX_PACKET || d < rx.buf ||
                                        d + len > rx.buf + sizeof rx.buf))
            abort();
    }
    stream s = {data, size, 0, 0};
    const linkclient_io io = {s_read, s_write, &s};
    linkclient_init(&c, "pi_link", 0x5a17c0deu, 2, 1, &io);
    while (s.at < s.n)
        if (linkclient_poll(&c)) {
            double u = c.req.v[0] - c.req.v[1];
            requests++;
            linkclient_answer(&c, &u);
        }
    return 0;
}
