/* linalg.h - dense linear algebra on caller-owned storage for the runtime's inner solves:
 * LU with partial pivoting and a pivot threshold (singularity is reported, never a
 * division by zero), and the matching solves. Internal to rt/ (prefix rti_). */
#ifndef RTI_LINALG_H
#define RTI_LINALG_H

#include "rt.h"

/* Factors the n x n row-major matrix a in place into P A = L U (unit L below the
   diagonal, U on and above), writing the row permutation into piv. A pivot whose
   magnitude is at most tol times the largest entry of the matrix marks it singular:
   returns RT_E_SINGULAR (the factors are completed with that pivot set to the threshold,
   so a solve stays finite and deterministic), else RT_OK. */
rt_status rti_lu(real_t *a, uint16_t n, uint16_t *piv, real_t tol);

/* Solves A x = b in place (b becomes x) with the factors of rti_lu. */
void rti_lu_solve(const real_t *lu, uint16_t n, const uint16_t *piv, real_t *b);

/* Solves A X = B for m right-hand sides stored as the columns of the n x m row-major B. */
void rti_lu_solve_cols(const real_t *lu, uint16_t n, const uint16_t *piv, real_t *b,
                       uint16_t m);

/* Largest magnitude of n values (the infinity norm of a vector). */
real_t rti_norm_inf(const real_t *v, uint16_t n);

#endif /* RTI_LINALG_H */
