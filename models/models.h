/* models.h - the model library: one const rt_kind per model (mdl_<name>_kind), with the
 * port indices a hand-written scene uses. The scene compiler reads the same kinds through
 * the registry mdl_kinds (models/registry.c). */
#ifndef MDL_MODELS_H
#define MDL_MODELS_H

#include "rt.h"

/* harmonic oscillator x'' = -omega^2 x (NSS); outputs x, v */
extern const rt_kind mdl_oscillator_kind;
enum { MDL_OSC_Y_X = 0, MDL_OSC_Y_V };

/* van der Pol oscillator x'' = mu (1 - x^2) x' - x (NSS); outputs x, v */
extern const rt_kind mdl_vanderpol_kind;

/* first-order lag T y' = K u - y (NSS); input u, output y */
extern const rt_kind mdl_pt1_kind;
enum { MDL_PT1_U = 0 };
enum { MDL_PT1_Y = 0 };

/* sampled PI controller (DSS): inputs r (reference), m (measurement); output c */
extern const rt_kind mdl_pi_kind;
enum { MDL_PI_U_R = 0, MDL_PI_U_M };
enum { MDL_PI_Y_C = 0 };

/* step source y = y0 for t < t0, y1 after (OUTPUT) */
extern const rt_kind mdl_step_kind;

/* pulse train: y1 on [t0 + k T, t0 + k T + w), y0 elsewhere (OUTPUT) */
extern const rt_kind mdl_pulse_kind;

/* sine source y = a sin(omega t + phase) + offset (OUTPUT) */
extern const rt_kind mdl_sine_kind;

/* gain y = k u (OUTPUT, throughput) */
extern const rt_kind mdl_gain_kind;

/* sum y = c1 u1 + c2 u2 (OUTPUT, throughput) */
extern const rt_kind mdl_sum_kind;

/* bouncing ball with restitution (NSS + state event): outputs h, v; discrete states
   count the impacts and hold the last impact time */
extern const rt_kind mdl_ball_kind;
extern const rt_kind mdl_coulomb_kind, mdl_relay_kind;
enum { MDL_BALL_D_N = 0, MDL_BALL_D_T };

/* belt gear parts (paper Fig. 6): pulley a = (M + s r F)/J (throughput), rotor
   (integrates a into phi, omega), belt force with a belt-inertia term (throughput from
   the accelerations) */
extern const rt_kind mdl_pulley_kind, mdl_rotor_kind, mdl_belt_kind;

/* multibody modules (MBS, eq. 6; services rt/mbs.c, nodes and joints rt_mbs.h):
   mass point, states x y z vx vy vz, node "c" (mbs_pointf: force inputs fx fy fz) */
extern const rt_kind mdl_mbs_point_kind, mdl_mbs_pointf_kind;
/* spatial rigid body with a unit quaternion, nodes "cm", "n1", "n2"
   (mbs_bodyf: inputs force fx fy fz, body torque tx ty tz) */
extern const rt_kind mdl_mbs_body_kind, mdl_mbs_bodyf_kind;
enum { MDL_MBS_BODY_Y_N1 = 9, MDL_MBS_BODY_Y_N2 = 15 };      /* node x y z vx vy vz (outputs) */
/* two mass points joined by an internal rod (an internal constraint), nodes "p1", "p2" */
extern const rt_kind mdl_mbs_dumbbell_kind;
/* planar single-track car with linear tires (vehicle_st.c), inputs delta, Fx; nodes
   "front", "rear" (hitch points) */
extern const rt_kind mdl_st_car_kind, mdl_st_car_mf_kind; /* linear / Magic-Formula tires */
/* spatial car (vehicle_3d.c): a rigid chassis with a unit quaternion on four sprung
   corners, the ports and nodes of st_car plus the input Fa and the outputs z, roll,
   pitch and the corner loads */
extern const rt_kind mdl_car3d_kind, mdl_car3d_mf_kind; /* linear / Magic-Formula tires */
/* aerodynamic drag from the forward speed (drag.c) */
extern const rt_kind mdl_drag_kind;
/* the ISO 3888-1 double lane change (lane_change.c): a pure-pursuit driver on its centre
   line (iso_driver: the course as the standard draws it; iso_driver_cc: the variant with
   the offset between lane centres), its cone check (iso_cones: the footprint's margin),
   and the towed vehicle's steering from the tow-bar angles */
extern const rt_kind mdl_iso_driver_kind, mdl_iso_driver_cc_kind, mdl_iso_cones_kind,
    mdl_tow_steer_kind;
enum { MDL_ST_X, MDL_ST_Y, MDL_ST_PSI, MDL_ST_U, MDL_ST_V, MDL_ST_R, MDL_ST_AY };

/* registry of model kinds by name, ending in {NULL, NULL} */
typedef struct mdl_entry {
    const char *name;
    const rt_kind *kind;
} mdl_entry;
extern const mdl_entry mdl_kinds[];

/* registry of library scenes, ending in {NULL, NULL} */
extern const rt_scene_entry mdl_scenes[];

/* driven arm (models/actuator.c): stiff second-order servo y'' + 2 zeta omega y' +
   omega^2 y = omega^2 k u (NSS; input u, outputs y, yd); digital PD controller with
   feed-forward raising an arm along a quintic (DSS; inputs x z of the arm's end, outputs
   u, theta, thr); motor turning the arm (OUTPUT; inputs tau x z, outputs fx fy fz) */
extern const rt_kind mdl_servo2_kind, mdl_arm_pd_kind, mdl_arm_motor_kind;
enum { MDL_SERVO2_Y = 0, MDL_SERVO2_YD };
enum { MDL_ARM_PD_Y_U = 0, MDL_ARM_PD_Y_THETA, MDL_ARM_PD_Y_THR };

/* a steering chain's actuators (models/steer_chain.c): a DC torque motor with a PI
   current loop (NSS; input iref, outputs s, phi, w, i) and a valve-controlled hydraulic
   cylinder on the steering rack (NSS; input xv, outputs delta, y, p) */
extern const rt_kind mdl_dc_motor_kind, mdl_hyd_servo_kind;

#endif /* MDL_MODELS_H */
