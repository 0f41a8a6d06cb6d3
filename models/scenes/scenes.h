/* scenes.h - the library scenes: one const rt_scene per models/scenes/<name>.scn, compiled
 * by scenec into build/gen/scenes/<name>.c (tools/scenec/scenec.mk). */
#ifndef MDL_SCENES_H
#define MDL_SCENES_H

#include "../models.h"

extern const rt_scene mdl_scene_oscillator;
extern const rt_scene mdl_scene_vanderpol;
extern const rt_scene mdl_scene_pi_loop;
extern const rt_scene mdl_scene_bouncing_ball;
extern const rt_scene mdl_scene_beltgear;
extern const rt_scene mdl_scene_pendulum10;
extern const rt_scene mdl_scene_pendulum10_actuated;
extern const rt_scene mdl_scene_pendulum10_actuated_single;

#endif /* MDL_SCENES_H */
