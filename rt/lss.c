/* lss.c - services of linear state-space kinds, x' = A x + B u, y = C x + D u (eq. 4).
 * The matrices are const tables of the kind (rt_lss_spec); sizes come from rt_args'
 * kind through the spec, so one pair of functions serves every LSS kind. */
#include "rti.h"

/* the sizes travel with the matrices: an LSS spec is embedded in this wrapper */
void rt_lss_output(const rt_args *a, real_t *y)
{
    const rt_lss_spec *m = a->spec;
    for (uint16_t i = 0; i < m->ny; i++) {
        real_t acc = 0;
        for (uint16_t j = 0; j < m->nx; j++)
            acc += m->C[i * m->nx + j] * a->x[j];
        for (uint16_t j = 0; j < m->nu; j++)
            acc += m->D ? m->D[i * m->nu + j] * a->u[j] : 0;
        y[i] = acc;
    }
}

void rt_lss_deriv(const rt_args *a, real_t *xdot)
{
    const rt_lss_spec *m = a->spec;
    for (uint16_t i = 0; i < m->nx; i++) {
        real_t acc = 0;
        for (uint16_t j = 0; j < m->nx; j++)
            acc += m->A[i * m->nx + j] * a->x[j];
        for (uint16_t j = 0; j < m->nu; j++)
            acc += m->B ? m->B[i * m->nu + j] * a->u[j] : 0;
        xdot[i] = acc;
    }
}
