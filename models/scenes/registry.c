/* registry.c - the registry of library scenes, one row per scene, for hosts. */
#include "scenes.h"

const rt_scene_entry mdl_scenes[] = {
    {"oscillator", &mdl_scene_oscillator},
    {"vanderpol", &mdl_scene_vanderpol},
    {"pi_loop", &mdl_scene_pi_loop},
    {"bouncing_ball", &mdl_scene_bouncing_ball},
    {"beltgear", &mdl_scene_beltgear},
    {"pendulum10", &mdl_scene_pendulum10},
    {"pendulum10_actuated", &mdl_scene_pendulum10_actuated},
    {"pendulum10_actuated_single", &mdl_scene_pendulum10_actuated_single},
    {0, 0},
};
