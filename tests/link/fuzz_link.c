/* fuzz_link.c - libFuzzer target for the controller link's decoders: the first byte of an
 * input picks the datagram decoder (link_decode, as the POSIX link calls it for pi_link)
 * or the replay-log reader (mrl_open on the input written to a file, then every record).
 * Neither may crash, hang, leak or trip a sanitizer on any input; the counts of each
 * decoder verdict are printed at exit (docs/link.md quotes them). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "common/link_wire.h"
#include "mrlog.h"

static unsigned long verdicts[LINK_E_COUNT_], logs_ok, logs_refused;
static char path[64];

static void report(void)
{
    fprintf(stderr, "link fuzz verdicts:");
    for (int e = 0; e < LINK_E_COUNT_; e++)
        fprintf(stderr, " %s %lu", link_wire_error_key(e), verdicts[e]);
    fprintf(stderr, "; logs accepted %lu refused %lu\n", logs_ok, logs_refused);
    unlink(path);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (!path[0]) {
        snprintf(path, sizeof path, "build/fuzz/link-input-%d.mrl", (int)getpid());
        atexit(report);
    }
    if (size == 0)
        return 0;
    if (data[0] & 1) { /* bit 1: seal the CRC first, so the checks behind it are reached */
        static uint8_t buf[LINK_MAX_PACKET + 64];
        link_packet p;
        size_t n = size - 1 < sizeof buf ? size - 1 : sizeof buf;
        memcpy(buf, data + 1, n);
        if ((data[0] & 2) && n >= 4) {
            uint32_t c = link_crc32(0, buf, n - 4);
            for (int i = 0; i < 4; i++)
                buf[n - 4 + i] = (uint8_t)(c >> (8 * i));
        }
        link_expect x = {.type = LINK_TYPE_IMPORTS, .name = "pi_link", .id = 0x5a17c0deu,
                         .n = (uint16_t)(data[0] >> 2), .check_run = 1,
                         .run = 0x0123456789abcdefull};
        link_wire_error e = link_decode(buf, size - 1, &x, &p);
        verdicts[e]++;
        return 0;
    }
    FILE *f = fopen(path, "wb");
    if (!f)
        return 0;
    fwrite(data + 1, 1, size - 1, f);
    fclose(f);
    static mrl_header h;
    char err[512];
    if (mrl_open(path, &h, err, sizeof err) == 0) {
        /* the checks a replay makes against its scene (the seeds' run: 1000 ticks,
           exchanges every 10); either may refuse and close the log */
        if (mrl_check_schedule(1000, 10, h.realtime, err, sizeof err) == 0)
            mrl_check_end(1000, err, sizeof err);
        uint64_t tick;
        real_t v[LINK_MAX_VALUES];
        while (mrl_next(&tick, v))
            ;
        logs_ok++;
    } else {
        logs_refused++;
    }
    mrl_close();
    return 0;
}
