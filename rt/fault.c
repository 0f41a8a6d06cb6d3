/* fault.c - the fault plan of a fault-injection test build (rti.h, RT_FAULT_INJECT): which
 * fault, where and when. Empty in every other build. */
#include "rti.h"

#if RT_FAULT_INJECT
rti_fault rti_fault_plan;
const rt_sim *rti_fault_sim;

int rti_fault_due(rti_fault_kind k)
{
    const rti_fault *f = &rti_fault_plan;
    return f->kind == k && rti_fault_sim && rti_fault_sim->state.tick >= f->from_tick &&
           rti_fault_sim->state.tick < f->to_tick;
}
#else
typedef int rti_fault_unused; /* ISO C: a translation unit is not empty */
#endif
