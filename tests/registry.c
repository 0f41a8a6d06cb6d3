/* registry.c - the portable test tables: everything here runs on the host and, unchanged,
 * on bare-metal targets under QEMU. One table per test file. */
#include "harness.h"

extern const th_test th_integ_tests[], th_order_tests[], th_event_tests[], th_sim_tests[];
extern const th_test th_scene_tests[], th_linalg_tests[], th_loop_tests[], th_implicit_tests[];
extern const th_test th_mbs_tests[], th_beltgear_tests[], th_xset_tests[];
extern const th_test th_mbs_body_tests[], th_joint_tests[], th_mbs_scene_tests[];
extern const th_test th_actuated_tests[], th_limits_tests[], th_mbs_ldl_tests[];
extern const th_test th_vehicle_3d_tests[], th_bg_tests[], th_transition_tests[];
extern const th_test th_tev_tests[];
void test_rmath_values(void);
void test_rmath_identities(void);

static const th_test rmath_tests[] = {
    {"rmath_values", test_rmath_values},
    {"rmath_identities", test_rmath_identities},
    {0, 0},
};

const th_test *const th_portable[] = {
    rmath_tests, th_integ_tests, th_order_tests, th_event_tests, th_sim_tests,
    th_scene_tests, th_linalg_tests, th_loop_tests, th_beltgear_tests, th_xset_tests, th_implicit_tests,
    th_transition_tests, th_tev_tests,
    th_mbs_tests, th_mbs_ldl_tests, th_mbs_body_tests, th_joint_tests, th_mbs_scene_tests,
    th_actuated_tests, th_bg_tests, th_limits_tests, th_vehicle_3d_tests, 0,
};
