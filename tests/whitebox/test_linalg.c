/* test_linalg.c - tests of rt/linalg.c: solves against systems built from known
 * solutions, pivoting, and singular matrices reported without non-finite results. */
#include "linalg.h"
#include "testutil.h"

/* A x = b with b computed from a chosen x; a zero leading pivot forces a row swap */
static void test_lu_solve(void)
{
    real_t a[9] = {0, 2, 1, 1, 1, 1, 4, -3, 2}, lu[9];
    const real_t x[3] = {1, -2, (real_t)0.5};
    real_t b[3], bb[6];
    uint16_t piv[3];
    for (int i = 0; i < 3; i++) {
        b[i] = a[3 * i] * x[0] + a[3 * i + 1] * x[1] + a[3 * i + 2] * x[2];
        bb[2 * i] = b[i], bb[2 * i + 1] = 2 * b[i];
    }
    for (int i = 0; i < 9; i++)
        lu[i] = a[i];
    TH_CHECK(rti_lu(lu, 3, piv, (real_t)1e-12) == RT_OK);
    rti_lu_solve(lu, 3, piv, b);
    rti_lu_solve_cols(lu, 3, piv, bb, 2);
    double tol = RT_REAL_IS_FLOAT ? 1e-5 : 1e-14;
    for (int i = 0; i < 3; i++) {
        TH_NEAR(b[i], x[i], tol);
        TH_NEAR(bb[2 * i], x[i], tol);
        TH_NEAR(bb[2 * i + 1], 2 * x[i], 2 * tol);
    }
}

/* rank 1: reported singular, and the solve still gives finite numbers */
static void test_lu_singular(void)
{
    real_t a[4] = {1, 2, 2, 4}, b[2] = {1, 1};
    uint16_t piv[2];
    TH_CHECK(rti_lu(a, 2, piv, (real_t)1e-12) == RT_E_SINGULAR);
    rti_lu_solve(a, 2, piv, b);
    TH_CHECK(rt_isfinite(b[0]) && rt_isfinite(b[1]));
    real_t z[4] = {0, 0, 0, 0};
    TH_CHECK(rti_lu(z, 2, piv, (real_t)1e-12) == RT_E_SINGULAR);
}

/* the factors in parts (rti_lu_floor, rti_lu_stages) are rti_lu's bit for bit, and
   rti_lu_unfactor gives the matrix back (4 x 4, pivoting on three of the stages) */
static void test_lu_parts(void)
{
    const real_t a[16] = {0, 2, 1, 3, 1, 1, 1, -1, 4, -3, 2, 0, 2, 5, -1, 1};
    real_t lu[16], lp[16];
    uint16_t piv[4], pp[4];
    for (int i = 0; i < 16; i++)
        lu[i] = lp[i] = a[i];
    TH_CHECK(rti_lu(lu, 4, piv, (real_t)1e-12) == RT_OK);
    real_t fl = rti_lu_floor(lp, 4, (real_t)1e-12);
    TH_CHECK(rti_lu_stages(lp, 4, pp, fl, 0, 1) == RT_OK);
    TH_CHECK(rti_lu_stages(lp, 4, pp, fl, 1, 3) == RT_OK);
    TH_CHECK(rti_lu_stages(lp, 4, pp, fl, 3, 4) == RT_OK);
    int same = 1, swaps = 0;
    for (int i = 0; i < 16; i++)
        same &= lu[i] == lp[i];
    for (int i = 0; i < 4; i++)
        same &= piv[i] == pp[i], swaps += piv[i] != i;
    TH_CHECK(same && swaps >= 2);
    rti_lu_unfactor(lu, 4, piv);
    double tol = RT_REAL_IS_FLOAT ? 1e-5 : 1e-14;
    for (int i = 0; i < 16; i++)
        TH_NEAR(lu[i], a[i], tol);
}

/* the determinant's sign from the factors against the cofactor expansion, for every
   sign pattern of a 3 x 3 matrix whose factors exchange rows or not: a permutation of
   the rows flips it once per transposition */
static void test_lu_det_sign(void)
{
    static const real_t base[9] = {1, 2, 0, 3, 1, 4, (real_t)0.5, 5, 2};
    int checked = 0;
    for (int perm = 0; perm < 6; perm++)
        for (int neg = 0; neg < 8; neg++) {
            static const int rows[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2},
                                           {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
            real_t a[9], lu[9];
            uint16_t piv[3];
            for (int i = 0; i < 3; i++)
                for (int j = 0; j < 3; j++)
                    a[3 * i + j] = base[3 * rows[perm][i] + j] * ((neg >> i) & 1 ? -1 : 1);
            double det = (double)a[0] * ((double)a[4] * a[8] - (double)a[5] * a[7]) -
                         (double)a[1] * ((double)a[3] * a[8] - (double)a[5] * a[6]) +
                         (double)a[2] * ((double)a[3] * a[7] - (double)a[4] * a[6]);
            for (int i = 0; i < 9; i++)
                lu[i] = a[i];
            TH_CHECK(rti_lu(lu, 3, piv, (real_t)1e-12) == RT_OK);
            TH_CHECK(rti_lu_det_negative(lu, 3, piv) == (det < 0));
            checked++;
        }
    TH_CHECK(checked == 48);
}

const th_test th_linalg_tests[] = {
    {"linalg_lu_solve", test_lu_solve},
    {"linalg_lu_singular", test_lu_singular},
    {"linalg_lu_parts", test_lu_parts},
    {"linalg_lu_det_sign", test_lu_det_sign},
    {0, 0},
};
