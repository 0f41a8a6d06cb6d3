/* linalg.c - dense LU with partial pivoting and its solves, and the phi functions of a
 * matrix (the transition method's), on caller-owned storage.
 *
 * Used by the multibody index-1 solve and projection and by the implicit integrators.
 * Loops run in a fixed order, so the same matrix gives the same bits on every target. */
#include "linalg.h"
#include "rti.h"

real_t rti_norm_inf(const real_t *v, uint16_t n)
{
    real_t m = 0;
    for (uint16_t i = 0; i < n; i++) {
        real_t a = rt_fabs(v[i]);
        m = a > m ? a : m;
    }
    return m;
}

/* row with the largest magnitude in column k at or below the diagonal */
static uint16_t pivot_row(const real_t *a, uint16_t n, uint16_t k)
{
    uint16_t p = k;
    real_t best = rt_fabs(a[k * n + k]);
    for (uint16_t i = (uint16_t)(k + 1); i < n; i++) {
        real_t v = rt_fabs(a[i * n + k]);
        if (v > best)
            best = v, p = i;
    }
    return p;
}

static void swap_rows(real_t *a, uint16_t n, uint16_t i, uint16_t j)
{
    for (uint16_t c = 0; c < n; c++) {
        real_t t = a[i * n + c];
        a[i * n + c] = a[j * n + c];
        a[j * n + c] = t;
    }
}

rt_status rti_lu_stages(real_t *a, uint16_t n, uint16_t *piv, real_t floor_, uint16_t k0,
                        uint16_t k1)
{
    rt_status st = RT_OK;
    for (uint16_t k = k0; k < k1 && k < n; k++) {
        uint16_t p = pivot_row(a, n, k);
        piv[k] = p;
        if (p != k)
            swap_rows(a, n, p, k);
        real_t d = a[k * n + k];
        if (k == 0 && rti_fault_due(RTI_FAULT_SINGULAR))
            d = 0;
        if (!(rt_fabs(d) > floor_)) {
            /* singular or NaN: continue with the threshold so the result stays finite */
            st = RT_E_SINGULAR;
            d = a[k * n + k] = d < 0 ? -floor_ : floor_;
        }
        for (uint16_t i = (uint16_t)(k + 1); i < n; i++) {
            real_t l = a[i * n + k] / d;
            a[i * n + k] = l;
            for (uint16_t j = (uint16_t)(k + 1); j < n; j++)
                a[i * n + j] -= l * a[k * n + j];
        }
    }
    return st;
}

real_t rti_lu_floor(const real_t *a, uint16_t n, real_t tol)
{
    real_t scale = rti_norm_inf(a, (uint16_t)(n * n));
    return tol * (scale > 0 ? scale : 1);
}

rt_status rti_lu(real_t *a, uint16_t n, uint16_t *piv, real_t tol)
{
    return rti_lu_stages(a, n, piv, rti_lu_floor(a, n, tol), 0, n);
}

void rti_lu_unfactor(real_t *a, uint16_t n, const uint16_t *piv)
{
    /* (L U)_ij = sum_{k <= min(i, j)} L_ik U_kj, L_ii = 1: from the last row and column
       back, an entry overwrites only what no later one reads */
    for (uint16_t i = n; i-- > 0;)
        for (uint16_t j = n; j-- > 0;) {
            uint16_t m = i <= j ? i : (uint16_t)(j + 1);
            real_t s = i <= j ? a[i * n + j] : 0;
            for (uint16_t k = 0; k < m; k++)
                s += a[i * n + k] * a[k * n + j];
            a[i * n + j] = s;
        }
    for (uint16_t k = n; k-- > 0;) /* P^T: the factorization's row swaps, last first */
        if (piv[k] != k)
            swap_rows(a, n, piv[k], k);
}

/* the sign of det A = det P^T det U: a negative pivot or a row exchange flips it */
int rti_lu_det_negative(const real_t *lu, uint16_t n, const uint16_t *piv)
{
    int neg = 0;
    for (uint16_t k = 0; k < n; k++)
        neg ^= (lu[(size_t)k * n + k] < 0) ^ (piv[k] != k);
    return neg;
}

/* Each row's sum runs in a local, in the same order as b[i] -= ... would: the same bits,
   without a store and reload of b[i] per term (b may alias lu for all the compiler
   knows). The implicit sets solve with it twice per ROS2 step. */
void rti_lu_solve(const real_t *lu, uint16_t n, const uint16_t *piv, real_t *b)
{
    for (size_t k = 0; k < n; k++) {
        real_t t = b[piv[k]];
        b[piv[k]] = b[k];
        b[k] = t;
    }
    for (size_t i = 1; i < n; i++) { /* L y = P b */
        const real_t *row = lu + i * n;
        real_t s = b[i];
        for (size_t j = 0; j < i; j++)
            s -= row[j] * b[j];
        b[i] = s;
    }
    for (size_t i = n; i-- > 0;) { /* U x = y */
        const real_t *row = lu + i * n;
        real_t s = b[i];
        for (size_t j = i + 1; j < n; j++)
            s -= row[j] * b[j];
        b[i] = s / row[i];
    }
}

void rti_lu_solve_cols(const real_t *lu, uint16_t n, const uint16_t *piv, real_t *b,
                       uint16_t m)
{
    for (uint16_t k = 0; k < n; k++) /* apply the row swaps in factorization order */
        if (piv[k] != k)
            for (uint16_t c = 0; c < m; c++) {
                real_t t = b[piv[k] * m + c];
                b[piv[k] * m + c] = b[k * m + c];
                b[k * m + c] = t;
            }
    for (uint16_t c = 0; c < m; c++) {
        for (uint16_t i = 1; i < n; i++)
            for (uint16_t j = 0; j < i; j++)
                b[i * m + c] -= lu[i * n + j] * b[j * m + c];
        for (uint16_t i = n; i-- > 0;) {
            for (uint16_t j = (uint16_t)(i + 1); j < n; j++)
                b[i * m + c] -= lu[i * n + j] * b[j * m + c];
            b[i * m + c] /= lu[i * n + i];
        }
    }
}

/* ------------------------------------------------------------------ phi functions */

/* the largest column sum of |a| (NaN if an entry is) */
static real_t norm_1(const real_t *a, uint16_t n)
{
    real_t m = 0;
    for (uint16_t j = 0; j < n; j++) {
        real_t c = 0;
        for (uint16_t i = 0; i < n; i++)
            c += rt_fabs(a[i * n + j]);
        if (c != c)
            return c;
        m = c > m ? c : m;
    }
    return m;
}

/* c = a b (n x n; c distinct from both) */
static void mat_mul(real_t *c, const real_t *a, const real_t *b, uint16_t n)
{
    for (uint16_t i = 0; i < n; i++)
        for (uint16_t j = 0; j < n; j++) {
            real_t s = 0;
            for (uint16_t k = 0; k < n; k++)
                s += a[i * n + k] * b[k * n + j];
            c[i * n + j] = s;
        }
}

/* d = (t + p d) r, entrywise over n x n (d's old entries are read) */
static void combine(real_t *d, const real_t *t, real_t p, real_t r, uint16_t n)
{
    for (uint32_t i = 0; i < (uint32_t)n * n; i++)
        d[i] = (t[i] + p * d[i]) * r;
}

/* d = t + q I, n x n (d's old entries are not read: an overflow of the last refresh
   leaves no infinity to multiply by zero) */
static void shift(real_t *d, const real_t *t, real_t q, uint16_t n)
{
    for (uint16_t i = 0; i < n; i++)
        for (uint16_t j = 0; j < n; j++)
            d[i * n + j] = t[i * n + j] + (i == j ? q : 0);
}

rt_status rti_phi12(real_t *a, uint16_t n, real_t *p1, real_t *p2, real_t *t, real_t theta,
                    unsigned degree, unsigned max_halvings)
{
    real_t norm = norm_1(a, n), scale = 1;
    unsigned s = 0;
    if (!rt_isfinite(norm))
        return RT_E_SINGULAR;
    while (norm * scale > theta) { /* halvings are exact (barring underflow) */
        if (++s > max_halvings)
            return RT_E_SINGULAR;
        scale *= (real_t)0.5;
    }
    for (uint32_t i = 0; i < (uint32_t)n * n; i++)
        a[i] *= scale;
    /* phi2 = sum_k A^k / (k + 2)!, k = 0..degree, by Horner from the highest term */
    real_t c = 1;
    for (unsigned k = 2; k <= degree + 2; k++)
        c /= (real_t)k;
    for (uint32_t i = 0; i < (uint32_t)n * n; i++)
        t[i] = 0;
    shift(p2, t, c, n);
    for (unsigned k = degree; k-- > 0;) {
        c *= (real_t)(k + 3); /* 1 / (k + 3)! -> 1 / (k + 2)! */
        mat_mul(t, p2, a, n);
        shift(p2, t, c, n);
    }
    mat_mul(t, a, p2, n); /* phi1 = I + A phi2 */
    shift(p1, t, 1, n);
    mat_mul(t, a, p1, n); /* e^A = I + A phi1, in a */
    shift(a, t, 1, n);
    for (unsigned i = 0; i < s; i++) {
        mat_mul(t, p1, p1, n); /* phi2(2A) = (phi1^2 + 2 phi2) / 4 */
        combine(p2, t, 2, (real_t)0.25, n);
        mat_mul(t, a, p1, n); /* phi1(2A) = (e^A phi1 + phi1) / 2 */
        combine(p1, t, 1, (real_t)0.5, n);
        if (i + 1 < s) { /* e^2A = (e^A)^2 */
            mat_mul(t, a, a, n);
            shift(a, t, 0, n);
        }
    }
    /* a growing mode overflows (e^1000): no usable matrices */
    return rt_all_finite(p1, n * n) && rt_all_finite(p2, n * n) ? RT_OK : RT_E_SINGULAR;
}
