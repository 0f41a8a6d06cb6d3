/* vm.c - the expression VM of the host interpreter (`modrt run FILE.scn`): runs the
 * service programs of defined systems on a small stack of real_t. Each operation is the
 * one emit.c prints as C, in the same order, so an interpreted scene and its compiled
 * form compute the same bits (conditions and limits by rt/rt_expr.h's functions on
 * both sides). */
#include "scn.h"

#include "rt_expr.h"

/* a binary operation on the two top operands */
static real_t binop(uint8_t op, real_t a, real_t b)
{
    switch (op) {
    case SCN_OP_ADD: return a + b;
    case SCN_OP_SUB: return a - b;
    case SCN_OP_MUL: return a * b;
    case SCN_OP_DIV: return a / b;
    case SCN_OP_LT: return rt_x_lt(a, b);
    case SCN_OP_LE: return rt_x_le(a, b);
    case SCN_OP_GT: return rt_x_gt(a, b);
    case SCN_OP_GE: return rt_x_ge(a, b);
    case SCN_OP_EQ: return rt_x_eq(a, b);
    case SCN_OP_NE: return rt_x_ne(a, b);
    case SCN_OP_AND: return rt_x_and(a, b);
    default: return rt_x_or(a, b); /* SCN_OP_OR */
    }
}

/* the value an operand instruction pushes */
static real_t operand(const scn_prog *p, const scn_ins *in, const rt_args *a,
                      const real_t *loc)
{
    switch (in->op) {
    case SCN_OP_CONST: return p->k[in->a];
    case SCN_OP_TIME: return a->t;
    case SCN_OP_TPIECE: return a->t_piece;
    case SCN_OP_STEP: return a->h;
    case SCN_OP_IN: return a->u[in->a];
    case SCN_OP_PAR: return a->p[in->a];
    case SCN_OP_STATE: return a->x[in->a];
    case SCN_OP_DSTATE: return a->d[in->a];
    default: return loc[in->a]; /* SCN_OP_LOC */
    }
}

/* a dispatch loop over the program: operands push, operations replace the top */
static void run(const scn_prog *p, const rt_args *a, real_t *out)
{
    real_t st[SCN_MAX_STACK + 1], loc[SCN_MAX_LOCALS];
    uint32_t sp = 0;
    for (uint32_t i = 0; i < p->n; i++) {
        const scn_ins *in = &p->ins[i];
        const scn_fn *f;
        switch (in->op) {
        case SCN_OP_NEG:
            st[sp - 1] = -st[sp - 1];
            break;
        case SCN_OP_NOT:
            st[sp - 1] = rt_x_not(st[sp - 1]);
            break;
        case SCN_OP_SEL:
            sp -= 2;
            st[sp - 1] = rt_x_if(st[sp - 1], st[sp], st[sp + 1]);
            break;
        case SCN_OP_CALL:
            f = &scn_fns[in->a];
            if (f->nargs == 1) {
                st[sp - 1] = f->f1(st[sp - 1]);
            } else {
                sp--;
                st[sp - 1] = f->f2(st[sp - 1], st[sp]);
            }
            break;
        case SCN_OP_OUT:
            out[in->a] = st[--sp];
            break;
        case SCN_OP_SETLOC:
            loc[in->a] = st[--sp];
            break;
        default:
            if (in->op <= SCN_OP_LOC) {
                st[sp++] = operand(p, in, a, loc);
            } else if (in->a >= SCN_SW_BASE) { /* a located switch: its mode at a tie */
                sp--;
                real_t l = st[sp - 1], r = st[sp];
                st[sp - 1] = rt_x_swc(l, r, a->x[in->a - SCN_SW_BASE], in->op - SCN_OP_LT);
            } else { /* (t compared with an instant: the time rt_x_at reads) */
                sp--;
                real_t l = st[sp - 1], r = st[sp];
                l = in->a == SCN_TSIDE_LEFT ? rt_x_at(a->t, l, r) : l;
                r = in->a == SCN_TSIDE_RIGHT ? rt_x_at(a->t, r, l) : r;
                st[sp - 1] = binop(in->op, l, r);
            }
        }
    }
}

void scn_vm_output(const rt_args *a, real_t *y)
{
    run(&((const scn_vm_spec *)a->spec)->out, a, y);
}

void scn_vm_deriv(const rt_args *a, real_t *xdot)
{
    run(&((const scn_vm_spec *)a->spec)->der, a, xdot);
}

void scn_vm_update(const rt_args *a, real_t *dnext)
{
    run(&((const scn_vm_spec *)a->spec)->upd, a, dnext);
}

real_t scn_vm_next(const rt_args *a)
{
    const scn_vm_spec *vs = a->spec;
    real_t v[SCN_MAX_TEV];
    run(&vs->tev, a, v);
    return rt_x_next(a->t, v, vs->ntev);
}

/* the largest |w| of the body's sin and cos arguments w t + phi: each argument at t = 1
   less its value at t = 0 */
real_t scn_vm_band(const rt_args *a)
{
    const scn_vm_spec *vs = a->spec;
    real_t v0[SCN_MAX_BAND], v1[SCN_MAX_BAND];
    rt_args b = *a;
    b.t = 0, run(&vs->band, &b, v0);
    b.t = 1, run(&vs->band, &b, v1);
    return rt_x_band(v0, v1, vs->nband);
}

void scn_vm_roots(const rt_args *a, real_t *r)
{
    run(&((const scn_vm_spec *)a->spec)->roots, a, r);
}

/* the modes of the define's located switches at the start of a step part (rt_kind.instant):
   each from its sides' difference there (its rising root, rt_x_sw_mode), held through
   the part. Returns 1 if a mode changed from one the switch had (the runtime counts an
   event and evaluates the set's outputs and roots again), 0 if none did or a first one
   was taken (the comparison's own value, which it read before: nothing changes) */
int scn_vm_instant(const rt_args *a, real_t *x, real_t *d)
{
    const scn_vm_spec *vs = a->spec;
    real_t r[SCN_MAX_PORTS];
    int changed = 0;
    (void)d;
    run(&vs->roots, a, r);
    for (uint16_t k = 0; k < vs->nsw; k++) {
        const uint16_t *w = vs->sw[k];
        real_t m = x[w[0]], v = rt_x_sw_mode(r[w[1]], m);
        changed |= (m == 0 || m == 1) && v != m;
        x[w[0]] = v;
    }
    return changed;
}

/* the handler of root which, or its rest clause's if the crossing came less than the
   clause's time after the root's previous one (d[which], t_last); its assignments write
   the states in place, in order. The root's t_last becomes this crossing's time. */
void scn_vm_event(const rt_args *a, uint16_t which, real_t *x, real_t *d)
{
    const scn_vm_spec *vs = a->spec;
    real_t tq[SCN_MAX_PORTS];
    int rest = 0;
    if (vs->rest_t[which].n > 0) {
        run(&vs->rest_t[which], a, tq);
        rest = a->t - d[which] < tq[which];
    }
    run(rest ? &vs->rest[which] : &vs->event[which], a, x);
    d[which] = a->t;
}
