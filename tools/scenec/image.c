/* image.c - the checked scene as an rt_scene in host memory: the same tables, in the
 * same order and with the same values, that emit.c writes as C; defined systems get
 * kinds whose services run on the VM (vm.c), or the LSS services of rt/lss.c. rt_init
 * then checks the whole, so a scene scenec accepts initialises on every target.
 * Also scn_compile, the one entry point of a compilation. */
#include "scn.h"
#include "rt_sim.h" /* allocates the rt_sim it checks the scene with */

#include <string.h>

/* n values as real_t (NULL when n is 0) */
static const real_t *reals(scn_ctx *c, const double *v, size_t n)
{
    if (n == 0)
        return NULL;
    real_t *out = scn_alloc(c, n * sizeof *out);
    for (size_t i = 0; i < n; i++)
        out[i] = (real_t)v[i];
    return out;
}

/* the program of the statements marked in `in`, flattened in order */
static scn_prog program_of(scn_ctx *c, const scn_define *d, const uint8_t *in, const real_t *k)
{
    uint32_t n = 0;
    for (uint32_t s = d->st0; s < d->st1; s++)
        n += in[s - d->st0] ? c->sc.st[s].code1 - c->sc.st[s].code0 : 0;
    scn_ins *ins = scn_alloc(c, (n ? n : 1) * sizeof *ins);
    n = 0;
    for (uint32_t s = d->st0; s < d->st1; s++) {
        const scn_stmt *st = &c->sc.st[s];
        if (!in[s - d->st0])
            continue;
        memcpy(ins + n, c->sc.code + st->code0, (st->code1 - st->code0) * sizeof *ins);
        n += st->code1 - st->code0;
    }
    return (scn_prog){ins, n, k, d->nloc};
}

/* the program of one service */
static scn_prog program(scn_ctx *c, const scn_define *d, uint8_t kind, const real_t *k)
{
    uint8_t in[SCN_MAX_STMTS];
    scn_service(c, d, kind, in);
    return program_of(c, d, in, k);
}

/* roots and one handler program per root (`when`), with its rest clause's */
static void events(scn_ctx *c, const scn_define *d, const real_t *k, scn_vm_spec *vs,
                   rt_kind *kd)
{
    if (d->nr == 0)
        return;
    scn_prog *ev = scn_alloc(c, 3 * d->nr * sizeof *ev);
    uint8_t in[SCN_MAX_STMTS];
    for (uint16_t r = 0; r < d->nr; r++) {
        scn_service_event(c, d, r, in);
        ev[r] = program_of(c, d, in, k);
        scn_service_root(c, d, SCN_ST_REST_T, r, in);
        ev[d->nr + r] = program_of(c, d, in, k);
        scn_service_root(c, d, SCN_ST_REST, r, in);
        ev[2 * d->nr + r] = program_of(c, d, in, k);
    }
    vs->roots = program(c, d, SCN_ST_ROOT, k);
    vs->event = ev, vs->rest_t = ev + d->nr, vs->rest = ev + 2 * d->nr;
    kd->roots = scn_vm_roots, kd->event = scn_vm_event;
    vs->sw = d->swm, vs->nsw = d->nswm;
    if (d->nswm)
        kd->instant = scn_vm_instant, kd->instant_own = 1;
}

/* the kind of a define with its services */
static const rt_kind *define_services(scn_ctx *c, const scn_define *d, const real_t *k)
{
    rt_kind *kd = scn_alloc(c, sizeof *kd);
    *kd = *d->kind;
    if (d->type == SCN_DEF_LSS) {
        rt_lss_spec *m = scn_alloc(c, sizeof *m);
        m->nx = d->nx, m->nu = d->nu, m->ny = d->ny;
        m->A = reals(c, d->A.v, (size_t)d->A.rows * d->A.cols);
        m->B = d->B.given ? reals(c, d->B.v, (size_t)d->B.rows * d->B.cols) : NULL;
        m->C = reals(c, d->C.v, (size_t)d->C.rows * d->C.cols);
        m->D = d->D.given ? reals(c, d->D.v, (size_t)d->D.rows * d->D.cols) : NULL;
        kd->spec = m;
        kd->output = d->ny ? rt_lss_output : NULL;
        kd->deriv = rt_lss_deriv;
        return kd;
    }
    scn_vm_spec *vs = scn_alloc(c, sizeof *vs);
    vs->out = program(c, d, SCN_ST_OUT, k);
    vs->der = program(c, d, SCN_ST_DER, k);
    vs->upd = program(c, d, SCN_ST_NEXT, k);
    kd->spec = vs;
    kd->output = d->ny ? scn_vm_output : NULL;
    kd->deriv = d->type == SCN_DEF_SS && d->nx ? scn_vm_deriv : NULL;
    kd->update = d->type == SCN_DEF_DSS ? scn_vm_update : NULL;
    if (d->ntev) { /* the instants its body compares t with: time events */
        vs->tev = program(c, d, SCN_ST_TEV, k), vs->ntev = d->ntev;
        kd->next_event = scn_vm_next, kd->time_event = rt_tev_none;
    }
    if (d->nband) { /* its sin and cos of t: its band */
        vs->band = program(c, d, SCN_ST_BAND, k), vs->nband = d->nband;
        kd->band = scn_vm_band;
    }
    events(c, d, k, vs, kd);
    return kd;
}

static void blocks(scn_ctx *c, rt_scene *sc, const rt_kind *const *dk)
{
    const scn_scene *s = &c->sc;
    rt_block *bl = scn_alloc(c, (s->nblk + 1u) * sizeof *bl);
    for (uint16_t i = 0; i < s->nblk; i++) {
        const scn_block *b = &s->blk[i];
        const rt_kind *k = b->kind;
        bl[i].name = b->name.s;
        bl[i].kind = b->def >= 0 ? dk[b->def] : k;
        bl[i].p = b->p_given ? reals(c, b->p, k->np) : NULL;
        bl[i].x0 = b->x_given ? reals(c, b->x0, k->nx) : NULL;
        bl[i].d0 = b->d_given ? reals(c, b->d0, k->nd) : NULL;
        bl[i].set = (uint8_t)b->set;
        bl[i].ts = (real_t)b->ts;
    }
    sc->blocks = bl, sc->nblocks = s->nblk;
}

static void wiring(scn_ctx *c, rt_scene *sc)
{
    const scn_scene *s = &c->sc;
    rt_conn *cn = scn_alloc(c, (s->nconn + 1u) * sizeof *cn);
    uint8_t *in = scn_alloc(c, s->nconn + 1u), any = 0;
    for (uint16_t i = 0; i < s->nconn; i++) {
        cn[i] = (rt_conn){s->conn[i].fb, s->conn[i].fy, s->conn[i].tb, s->conn[i].tu};
        in[i] = s->conn[i].interp, any |= in[i];
    }
    sc->conn_interp = any ? in : NULL; /* only scenes that choose per connection */
    rt_default *df = scn_alloc(c, (s->ndflt + 1u) * sizeof *df);
    for (uint16_t i = 0; i < s->ndflt; i++)
        df[i] = (rt_default){s->dflt[i].b, s->dflt[i].u, (real_t)s->dflt[i].v};
    sc->conns = s->nconn ? cn : NULL, sc->nconns = s->nconn;
    sc->defaults = s->ndflt ? df : NULL, sc->ndefaults = s->ndflt;
}

static void sets_recs(scn_ctx *c, rt_scene *sc)
{
    const scn_scene *s = &c->sc;
    rt_set *st = scn_alloc(c, s->nset * sizeof *st);
    for (uint16_t i = 0; i < s->nset; i++) {
        const scn_set *x = &s->set[i];
        st[i].name = x->name.s, st[i].method = x->m, st[i].ratio = x->ratio;
        st[i].interp = x->interp;
        st[i].cfg = x->cfg;
        st[i].background = x->background;
    }
    rt_rec *r = scn_alloc(c, (s->nrec + 1u) * sizeof *r);
    for (uint16_t i = 0; i < s->nrec; i++)
        r[i] = s->rec[i].r;
    sc->sets = st, sc->nsets = (uint8_t)s->nset;
    sc->recs = s->nrec ? r : NULL, sc->nrecs = s->nrec;
}

static void joints(scn_ctx *c, rt_scene *sc)
{
    const scn_scene *s = &c->sc;
    rt_joint *j = scn_alloc(c, (s->njnt + 1u) * sizeof *j);
    int mbs = 0;
    for (uint16_t i = 0; i < s->njnt; i++) {
        const scn_joint *x = &s->jnt[i];
        const scn_link *l = &s->lnk[x->link];
        j[i].name = x->name.s, j[i].kind = x->kind;
        j[i].b1 = l->b1, j[i].n1 = l->n1, j[i].b2 = l->b2, j[i].n2 = l->n2;
        j[i].p = reals(c, x->p, x->kind->np);
        j[i].at = l->has_at ? reals(c, l->at, 3) : NULL;
        j[i].at_S = l->has_turn ? reals(c, l->at_S, 9) : NULL;
        j[i].axis_S = x->axis_at ? reals(c, x->axis_S, 9) : NULL;
    }
    for (uint16_t b = 0; b < s->nblk; b++)
        mbs |= s->blk[b].kind->type == RT_KIND_MBS;
    sc->joints = s->njnt ? j : NULL, sc->njoints = s->njnt;
    sc->mbs = mbs ? &rt_mbs : NULL;
    sc->stab = mbs ? s->stab_kind : 0;
    sc->baumgarte[0] = (real_t)s->alpha, sc->baumgarte[1] = (real_t)s->beta;
}

/* rt_init as the last check; its message goes to the scene statement */
static int init_check(scn_ctx *c)
{
    scn_scene *s = &c->sc;
    if (!c->sim)
        c->sim = scn_alloc(c, sizeof *c->sim);
    rt_status st = rt_init(&c->image, c->sim);
    if (st == RT_OK)
        return 0;
    scn_fail(c, s->name.pos, s->name.s,
             scn_fmt(c, "the runtime rejects the scene: %s: %s", rt_status_name(st),
                     rt_error_text(c->sim)),
             st == RT_E_LOOP ? "solve loops by (broyden); for an actual algebraic loop"
                             : "a scene rt_init accepts");
    return -1;
}

int scn_build_image(scn_ctx *c)
{
    const scn_scene *s = &c->sc;
    rt_scene *sc = &c->image;
    const rt_kind *dk[SCN_MAX_DEFINES];
    const real_t *k = reals(c, s->k, s->nk);
    memset(sc, 0, sizeof *sc);
    for (uint16_t i = 0; i < s->ndef; i++)
        dk[i] = define_services(c, s->def[i], k);
    sc->name = s->name.s, sc->doc = s->doc ? s->doc : "";
    sc->dt = (real_t)s->dt, sc->t_end = (real_t)s->t_end;
    scn_fmu_start(c); /* FMU systems' initial states */
    if (c->err)
        return -1;
    blocks(c, sc, dk);
    wiring(c, sc);
    sets_recs(c, sc);
    joints(c, sc);
    sc->loop_solver = s->solver.s ? &rt_broyden : NULL;
    sc->loop_iter_max = (uint8_t)s->loop_iter;
    sc->loop_tol = (real_t)s->loop_tol;
    sc->link = s->link.name ? &s->link : NULL;
    sc->bg = NULL;
    for (uint16_t i = 0; i < s->nset; i++)
        sc->bg = s->set[i].background ? &rt_bg : sc->bg;
    return init_check(c);
}

int scn_compile(scn_ctx *c, const char *path, const char *text, size_t len)
{
    if (scn_open_main(c, path, text, len) == 0 && scn_parse(c) == 0 && scn_check(c) == 0)
        scn_build_image(c);
    return c->err ? -1 : 0;
}
