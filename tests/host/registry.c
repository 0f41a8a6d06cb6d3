/* registry.c - the host-only test tables (they use libm or stdio as references). */
#include "harness.h"

void test_rmath_libm(void);

static const th_test rmath_libm_tests[] = {{"rmath_libm", test_rmath_libm}, {0, 0}};

extern const th_test th_tune_tests[];
extern const th_test th_kinds_doc_tests[];
extern const th_test th_link_tests[];
extern const th_test th_bg_host_tests[];
extern const th_test th_renew_tests[];
extern const th_test th_linkframe_tests[];
extern const th_test th_scene_code_tests[];
extern const th_test th_layout_tests[];

const th_test *const th_host[] = {rmath_libm_tests, th_tune_tests, th_kinds_doc_tests,
                                  th_link_tests, th_bg_host_tests, th_renew_tests,
                                  th_linkframe_tests, th_scene_code_tests, th_layout_tests, 0};
