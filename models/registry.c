/* registry.c - the model library's registry of kinds by name, one row per model. Only
 * hosts (CLI, scene compiler, interpreter) link it; a compiled scene names its kinds
 * directly, so an image links only the models its scene uses. */
#include "models.h"

const mdl_entry mdl_kinds[] = {
    {"oscillator", &mdl_oscillator_kind},
    {"vanderpol", &mdl_vanderpol_kind},
    {"pt1", &mdl_pt1_kind},
    {"pi", &mdl_pi_kind},
    {"step", &mdl_step_kind},
    {"sine", &mdl_sine_kind},
    {"gain", &mdl_gain_kind},
    {"sum", &mdl_sum_kind},
    {"ball", &mdl_ball_kind},
    {"coulomb", &mdl_coulomb_kind},
    {"relay", &mdl_relay_kind},
    {"mbs_point", &mdl_mbs_point_kind},
    {"mbs_pointf", &mdl_mbs_pointf_kind},
    {"mbs_body", &mdl_mbs_body_kind},
    {"mbs_bodyf", &mdl_mbs_bodyf_kind},
    {"mbs_dumbbell", &mdl_mbs_dumbbell_kind},
    {"st_car", &mdl_st_car_kind},
    {"st_car_mf", &mdl_st_car_mf_kind},
    {"car3d", &mdl_car3d_kind},
    {"car3d_mf", &mdl_car3d_mf_kind},
    {"drag", &mdl_drag_kind},
    {"iso_driver", &mdl_iso_driver_kind},
    {"tow_steer", &mdl_tow_steer_kind},
    {"pulley", &mdl_pulley_kind},
    {"rotor", &mdl_rotor_kind},
    {"belt", &mdl_belt_kind},
    {"servo2", &mdl_servo2_kind},
    {"dc_motor", &mdl_dc_motor_kind},
    {"hyd_servo", &mdl_hyd_servo_kind},
    {"arm_pd", &mdl_arm_pd_kind},
    {"arm_motor", &mdl_arm_motor_kind},
    {0, 0},
};
