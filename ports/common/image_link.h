/* image_link.h - the controller link of a per-scene image (ports/common/image_main.c):
 * the scene's exports and imports over the port's link UART, in the frames of
 * linkframe.h, lock-step (the default: the controller paces the run, deterministic) or in
 * real time (-DRT_IMAGE_LINK_REALTIME=1: ticks paced by the timer, an answer applied at
 * the first tick after it arrived). docs/link.md, "The plant on a board". */
#ifndef IMAGE_LINK_H
#define IMAGE_LINK_H

#include "rt.h"

#ifndef RT_IMAGE_LINK_REALTIME
#define RT_IMAGE_LINK_REALTIME 0
#endif
#ifndef RT_IMAGE_LINK_BAUD
#define RT_IMAGE_LINK_BAUD 115200u
#endif
#ifndef RT_IMAGE_LINK_TIMEOUT_US
#define RT_IMAGE_LINK_TIMEOUT_US 1000000u /* lock-step: the longest wait for an answer */
#endif

/* Opens the link UART for scene sc. Returns 0, or -1 (the port has no link UART at this
   rate, or the link carries more values than a datagram). */
int image_link_start(const rt_scene *sc, rt_sim *sim);
/* The exchange after a tick: 1 when an import with policy stop went missing (the run
   ends with status RT_E_LINK). */
int image_link_exchange(const rt_scene *sc, rt_sim *sim);
/* This run's nonce (docs/link.md): by default mixed from the time since reset; a board
   with a random number generator defines its own (the default is weak). */
uint64_t image_link_nonce(void);
/* Hands each count to put (sent, applied, bad, late, missing, dup, resent, lost: bytes the
   UART dropped); returns 1 if a count shows a fault (bad, missing, lost). */
int image_link_report(void (*put)(const char *key, uint64_t v));

#endif /* IMAGE_LINK_H */
