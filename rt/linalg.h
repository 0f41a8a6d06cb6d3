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
/* rti_lu in parts: the pivot floor of a (tol times its largest entry), then elimination
   stages k0 .. k1 - 1 (rti_lu is rti_lu_stages(a, n, piv, rti_lu_floor(a, n, tol), 0, n));
   a factorization spread over several calls (rt/integ_implicit.c) */
real_t rti_lu_floor(const real_t *a, uint16_t n, real_t tol);
rt_status rti_lu_stages(real_t *a, uint16_t n, uint16_t *piv, real_t floor_, uint16_t k0,
                        uint16_t k1);
/* The matrix P^T L U back from its factors in place (the inverse of rti_lu, to rounding) */
void rti_lu_unfactor(real_t *a, uint16_t n, const uint16_t *piv);

/* 1 when the matrix factored by rti_lu has a negative determinant: the product of U's
   diagonal, its sign flipped by each row exchange */
int rti_lu_det_negative(const real_t *lu, uint16_t n, const uint16_t *piv);

/* Solves A x = b in place (b becomes x) with the factors of rti_lu. */
void rti_lu_solve(const real_t *lu, uint16_t n, const uint16_t *piv, real_t *b);

/* Solves A X = B for m right-hand sides stored as the columns of the n x m row-major B. */
void rti_lu_solve_cols(const real_t *lu, uint16_t n, const uint16_t *piv, real_t *b,
                       uint16_t m);

/* phi1(A) = (e^A - I) A^-1 and phi2(A) = (e^A - I - A) A^-2 of the n x n row-major A,
   written to p1 and p2 (the transition method's matrices, rt/integ_transition.c): A is
   halved s times until its 1-norm is at most theta, the Taylor polynomial of phi2 of the
   given degree is summed there (phi1 = I + A phi2, e^A = I + A phi1), and the doubling
   formulas e^2A = (e^A)^2, phi1(2A) = (e^A + I) phi1(A) / 2,
   phi2(2A) = (phi1(A)^2 + 2 phi2(A)) / 4 (Skaflestad & Wright 2009) lead back. a is
   overwritten; t is n x n scratch; about (degree + 2 + 3 s) n^3 multiply-adds. Every
   entry is halved as often as the largest needs, so the squarings of e^A amplify the
   rounding of the slow modes by about the spread of A's eigenvalues (A = diag(-1e4, -50):
   70 ulp in phi1(-50)). Returns RT_E_SINGULAR, p1 and p2 unset, when A is not finite or
   needs more than max_halvings, RT_E_SINGULAR with p1 and p2 not finite when they
   overflow (a growing mode, e^1000), else RT_OK. */
rt_status rti_phi12(real_t *a, uint16_t n, real_t *p1, real_t *p2, real_t *t, real_t theta,
                    unsigned degree, unsigned max_halvings);

/* Largest magnitude of n values (the infinity norm of a vector). */
real_t rti_norm_inf(const real_t *v, uint16_t n);

#endif /* RTI_LINALG_H */
