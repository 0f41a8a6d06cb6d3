/* registry.c - the registry of integration methods, by name (for scenes and the CLI). */
#include "rti.h"

const rt_integrator_entry rt_integrators[] = {
    {"euler", &rt_euler},
    {"heun", &rt_heun},
    {"bs3", &rt_bs3},
    {"rk4", &rt_rk4},
    {"dopri5", &rt_dopri5},
    {"beuler", &rt_beuler},
    {"trap", &rt_trap},
    {"sdirk2", &rt_sdirk2},
    {"sdirk3", &rt_sdirk3},
    {"ros2", &rt_ros2},
    {"transition", &rt_transition},
    {0, 0},
};

const rt_integrator *rt_integrator_find(const char *name)
{
    for (const rt_integrator_entry *e = rt_integrators; e->name; e++)
        if (rt_streq(e->name, name))
            return e->method;
    return 0;
}
