/* fingerprint.c - the scene fingerprint of the replay log (fingerprint.h): FNV-1a 64 over
 * the scene's contents field by field (never over struct bytes, whose padding is not
 * defined), pointers followed to what they point at, names with their terminating NUL.
 * What a kind computes is identified by its name, its dimensions and default values, and
 * for the kinds a scene file defines (interpreted by tools/scenec/vm.c) or an `lss` block
 * by their programs or matrices too, for an FMU block by the hash of its FMU file: the
 * code of compiled kinds is the build's. */
#include "fingerprint.h"

#include "fmu.h"
#include "scn.h"

#define FP_START 0xcbf29ce484222325ull
#define FP_PRIME 0x100000001b3ull

static void bytes(uint64_t *h, const void *p, size_t n)
{
    const uint8_t *b = p;
    while (n--)
        *h = (*h ^ *b++) * FP_PRIME;
}

static void u64(uint64_t *h, uint64_t v)
{
    for (int i = 0; i < 8; i++)
        *h = (*h ^ (uint8_t)(v >> (8 * i))) * FP_PRIME;
}

/* a real by its bit pattern, as binary64 whatever the build's real_t */
static void real(uint64_t *h, real_t v)
{
    union { double d; uint64_t u; } c = {.d = (double)v};
    u64(h, c.u);
}

static void reals(uint64_t *h, const real_t *v, const real_t *fallback, size_t n)
{
    u64(h, n);
    for (size_t i = 0; i < n; i++)
        real(h, v ? v[i] : fallback ? fallback[i] : 0);
}

static void str(uint64_t *h, const char *s)
{
    s = s ? s : "";
    while (*s)
        bytes(h, s++, 1);
    bytes(h, "", 1);
}

static void prog(uint64_t *h, const scn_prog *p)
{
    u64(h, p->n), u64(h, p->nloc);
    for (uint32_t i = 0; i < p->n; i++)
        u64(h, (uint64_t)p->ins[i].op << 16 | p->ins[i].a);
    /* the constants an instruction may name: as many as the program has instructions
       at most; the interpreter reads them through `a`, so hash those it names */
    for (uint32_t i = 0; i < p->n; i++)
        if (p->k && p->ins[i].op == SCN_OP_CONST)
            real(h, p->k[p->ins[i].a]);
}

/* what a define's kind declares besides its programs: its roots' directions and guards,
   its invariants */
static void declared(uint64_t *h, const rt_kind *k)
{
    for (uint16_t r = 0; r < k->nr; r++)
        u64(h, (uint64_t)(k->root_dir ? (uint8_t)k->root_dir[r] : 0) << 8 |
                   (k->root_guard ? k->root_guard[r] : 0));
    u64(h, k->ninv);
    for (uint8_t i = 0; i < k->ninv; i++) {
        const rt_invariant *v = &k->inv[i];
        u64(h, v->type), u64(h, v->n), real(h, v->c), real(h, v->tol);
        for (uint8_t j = 0; j < v->n; j++)
            u64(h, v->x[j]);
    }
}

/* what a kind computes, beyond its name: a scene file's define (its programs, among them
   each root's rest clause, and what it declares), the matrices of an LSS block, or the FMU
   file an FMU block runs (its name stays when the file is replaced by another build of
   the model) */
static void kind_spec(uint64_t *h, const rt_kind *k)
{
    const char *fmu = fmu_kind_file_id(k);
    if (fmu)
        str(h, fmu);
    if (k->output == scn_vm_output || k->deriv == scn_vm_deriv || k->update == scn_vm_update) {
        const scn_vm_spec *v = k->spec;
        prog(h, &v->out), prog(h, &v->der), prog(h, &v->upd), prog(h, &v->roots);
        prog(h, &v->tev), prog(h, &v->band);
        for (uint16_t r = 0; r < k->nr && v->event; r++)
            prog(h, &v->event[r]);
        for (uint16_t r = 0; r < k->nr && v->rest_t; r++)
            prog(h, &v->rest_t[r]), prog(h, &v->rest[r]);
        declared(h, k);
    } else if (k->deriv == rt_lss_deriv && k->spec) {
        const rt_lss_spec *m = k->spec;
        size_t nx = m->nx, nu = m->nu, ny = m->ny;
        reals(h, m->A, 0, nx * nx), reals(h, m->B, 0, nx * nu);
        reals(h, m->C, 0, ny * nx), reals(h, m->D, 0, ny * nu);
    }
}

static void kind(uint64_t *h, const rt_kind *k)
{
    str(h, k->name);
    u64(h, k->type), u64(h, k->nu), u64(h, k->ny), u64(h, k->nx), u64(h, k->nd);
    u64(h, k->np), u64(h, k->nr), u64(h, k->feed);
    kind_spec(h, k);
}

static void block(uint64_t *h, const rt_block *b)
{
    const rt_kind *k = b->kind;
    str(h, b->name);
    kind(h, k);
    reals(h, b->p, k->p_default, k->np);
    reals(h, b->x0, k->x_default, k->nx);
    reals(h, b->d0, k->d_default, k->nd);
    u64(h, b->set), real(h, b->ts);
}

static void set(uint64_t *h, const rt_set *s)
{
    str(h, s->name), str(h, s->method ? s->method->name : "");
    u64(h, s->ratio), u64(h, s->interp), u64(h, s->background);
    for (int id = 0; id < RT_CFG_N; id++) /* every setting of RT_SET_CFG_LIST */
        real(h, rt_set_cfg_get(&s->cfg, (rt_cfg_id)id));
}

static void rec(uint64_t *h, const rt_rec *r)
{
    u64(h, r->block), u64(h, r->what), u64(h, r->index);
}

static void joint(uint64_t *h, const rt_joint *j)
{
    static const real_t unit[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    str(h, j->name), str(h, j->kind->name);
    u64(h, (uint16_t)j->b1), u64(h, (uint16_t)j->n1), u64(h, (uint16_t)j->b2),
        u64(h, (uint16_t)j->n2);
    reals(h, j->p, 0, j->kind->np), reals(h, j->at, 0, 3), reals(h, j->at_S, unit, 9);
}

static void link(uint64_t *h, const rt_link *l)
{
    if (!l)
        return u64(h, 0);
    str(h, l->name), u64(h, l->period), u64(h, l->id), u64(h, l->block);
    u64(h, l->nexp);
    for (uint16_t i = 0; i < l->nexp; i++)
        rec(h, &l->exp[i]);
    reals(h, l->def, 0, l->nimp);
    for (uint16_t i = 0; i < l->nimp; i++)
        u64(h, l->policy[i]);
}

uint64_t fp_scene(const rt_scene *sc)
{
    uint64_t h = FP_START;
    str(&h, sc->name), real(&h, sc->dt), real(&h, sc->t_end);
    u64(&h, sc->nblocks);
    for (uint16_t i = 0; i < sc->nblocks; i++)
        block(&h, &sc->blocks[i]);
    u64(&h, sc->nconns);
    for (uint16_t i = 0; i < sc->nconns; i++) {
        const rt_conn *c = &sc->conns[i];
        u64(&h, c->from), u64(&h, c->y), u64(&h, c->to), u64(&h, c->u);
        u64(&h, sc->conn_interp ? sc->conn_interp[i] : 0);
    }
    u64(&h, sc->ndefaults);
    for (uint16_t i = 0; i < sc->ndefaults; i++) {
        u64(&h, sc->defaults[i].block), u64(&h, sc->defaults[i].u);
        real(&h, sc->defaults[i].value);
    }
    u64(&h, sc->nsets);
    for (uint8_t i = 0; i < sc->nsets; i++)
        set(&h, &sc->sets[i]);
    u64(&h, sc->nrecs);
    for (uint16_t i = 0; i < sc->nrecs; i++)
        rec(&h, &sc->recs[i]);
    u64(&h, sc->njoints);
    for (uint16_t i = 0; i < sc->njoints; i++)
        joint(&h, &sc->joints[i]);
    u64(&h, sc->stab), real(&h, sc->baumgarte[0]), real(&h, sc->baumgarte[1]);
    u64(&h, sc->loop_iter_max), real(&h, sc->loop_tol);
    u64(&h, sc->mbs != 0), u64(&h, sc->loop_solver != 0), u64(&h, sc->bg != 0);
    link(&h, sc->link);
    return h;
}
