/* cs_slave.h - a compiled scene as a co-simulation slave, whatever the FMI version
 * (docs/fmi.md, "Export"): the values by value reference (fmu_cs_vars.h), a step of whole
 * base ticks recorded as `modrt run` records them, and the FMU state. fmi2cs.c and
 * fmi3cs.c bind it to FMI 2.0 and 3.0; it allocates nothing and logs nothing: each call
 * returns a CS_* status and, when not CS_OK, a one-line reason in the slave's msg. */
#ifndef CS_SLAVE_H
#define CS_SLAVE_H

#include <stddef.h>

#include "rt.h"
#include "rt_sim.h" /* a slave holds its rt_sim */

#define CS_MSG 256 /* characters of a reason */

/* the statuses, numbered as fmi2Status and fmi3Status number them */
enum { CS_OK = 0, CS_WARNING = 1, CS_ERROR = 3 };

typedef enum { CS_INSTANTIATED, CS_INIT, CS_STEP, CS_TERMINATED } cs_mode;

typedef struct cs_slave {
    rt_sim sim;
    const rt_scene *sc;
    cs_mode mode;
    uint32_t nvars;
    char msg[CS_MSG];       /* the reason of the last status other than CS_OK */
    real_t u[];             /* the imports, as last set (applied at each step) */
} cs_slave;

/* bytes of a slave of scene sc (cs_slave and its imports) */
size_t cs_size(const rt_scene *sc);
/* s (cs_size bytes, zeroed) made a slave of sc in the instantiated state; also a reset */
int cs_setup(cs_slave *s, const rt_scene *sc);

/* an instance more, or one fewer: a scene with FMU blocks (FMU_CS_ONCE, their instances
   are static) has one instance at a time (canBeInstantiatedOnlyOncePerProcess); claim
   returns NULL or the reason it refuses */
const char *cs_claim(void);
void cs_release(void);

/* FMI's mode changes: enter initialization (startTime must be 0, stopTime not past the
   end), exit it (the row at t = 0 recorded) */
int cs_enter_init(cs_slave *s, double start, int stop_defined, double stop);
int cs_exit_init(cs_slave *s);

int cs_get(cs_slave *s, uint32_t vr, double *v);
int cs_set(cs_slave *s, uint32_t vr, double v);

/* n whole base ticks from the communication point t, h = n * dt; CS_ERROR without any
   change for a step off the grid, from another point or past the end time; *at_end: the
   scene is at its end time */
int cs_step(cs_slave *s, double t, double h, int *at_end);

/* the FMU state: bytes of one, saved into / restored from such a buffer; check: CS_OK if
   buf holds a state this slave saved (its scene, its size) */
size_t cs_state_size(const cs_slave *s);
int cs_state_save(cs_slave *s, void *buf); /* CS_ERROR: a block's state cannot be saved */
int cs_state_check(cs_slave *s, const void *buf, size_t size);
int cs_state_load(cs_slave *s, const void *buf, size_t size);

#endif /* CS_SLAVE_H */
