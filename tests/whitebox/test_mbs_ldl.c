/* test_mbs_ldl.c - tests of rt/mbs_ldl.c, the sparse L D L^T of the Schur complement, on
 * a mechanism with a closed loop and a branch: five mass points, P0 on an anchor, the
 * quadrilateral P0-P1-P2-P3-P0 (a loop) and P4 hanging from P1 (a tree branch), all by
 * spherical difference joints. Checked against what is derived here by hand or
 * independently: the fill of the minimum-degree order (counted below), the solution of
 * A x = b against A assembled densely from the geometry, and a run that keeps the
 * constraints with the projection. */
#include "models.h"
#include "rti_mbs.h"
#include "testutil.h"

#define NP 5 /* points */
#define NJ 6 /* joints = constraint rows */

static const real_t pos[NP][3] = {
    {1, 0, 0}, {(real_t)1.5, (real_t)0.5, (real_t)-0.8}, {(real_t)2.2, (real_t)-0.3, (real_t)-1.1},
    {(real_t)1.9, (real_t)-0.6, (real_t)0.2}, {(real_t)0.8, 1, (real_t)-1.6},
};
static const real_t masses[NP] = {1, 2, (real_t)0.5, (real_t)1.5, 1};
/* joint k links point a[k] to point b[k] (-1: the anchor at the origin) */
static const int16_t ja[NJ] = {0, 1, 2, 3, 3, 4}, jb[NJ] = {-1, 0, 1, 2, 0, 1};

static real_t x0[NP][6], params[NP][4], lens[NJ][1];
static rt_block blocks[NP];
static rt_joint joints[NJ];
static rt_set set1;
static const rt_rec recs[] = {{0, RT_SIG_MBS, RT_MBS_SIG_RESIDUAL}};

static double absd(double v) { return v < 0 ? -v : v; }

/* |r_a - r_b| (b = -1: the origin) */
static double dist(const real_t *ra, int16_t b, double *e)
{
    double s = 0;
    for (int i = 0; i < 3; i++) {
        e[i] = (double)ra[i] - (b >= 0 ? (double)pos[b][i] : 0);
        s += e[i] * e[i];
    }
    s = (double)rt_sqrt((real_t)s);
    for (int i = 0; i < 3; i++)
        e[i] /= s;
    return s;
}

static rt_scene loop_scene(void)
{
    static const char *const names[NP] = {"P0", "P1", "P2", "P3", "P4"};
    static const char *const jnames[NJ] = {"J0", "J1", "J2", "J3", "J4", "J5"};
    for (int p = 0; p < NP; p++) {
        for (int i = 0; i < 3; i++)
            x0[p][i] = pos[p][i], x0[p][3 + i] = 0;
        params[p][0] = masses[p], params[p][1] = params[p][2] = 0;
        params[p][3] = (real_t)-9.81;
        blocks[p] = (rt_block){.name = names[p], .kind = &mdl_mbs_point_kind, .x0 = x0[p],
                               .p = params[p]};
    }
    for (int k = 0; k < NJ; k++) {
        double e[3];
        lens[k][0] = (real_t)dist(pos[ja[k]], jb[k], e);
        joints[k] = (rt_joint){.name = jnames[k], .kind = &rt_joint_sphdiff, .b1 = ja[k],
                               .b2 = jb[k], .p = lens[k]};
    }
    set1 = (rt_set){.name = "mbs", .method = &rt_rk4, .ratio = 1};
    return (rt_scene){.name = "loop", .dt = (real_t)1e-3, .t_end = 1, .blocks = blocks,
                      .nblocks = NP, .sets = &set1, .nsets = 1, .recs = recs, .nrecs = 1,
                      .joints = joints, .njoints = NJ, .mbs = &rt_mbs,
                      .stab = RT_STAB_PROJECT};
}

/* A = W M^-1 W^T from the geometry: row k is +e_k on point a, -e_k on point b */
static void dense_schur(double A[NJ][NJ])
{
    double W[NJ][3 * NP] = {{0}};
    for (int k = 0; k < NJ; k++) {
        double e[3];
        dist(pos[ja[k]], jb[k], e);
        for (int i = 0; i < 3; i++) {
            W[k][3 * ja[k] + i] += e[i];
            if (jb[k] >= 0)
                W[k][3 * jb[k] + i] -= e[i];
        }
    }
    for (int r = 0; r < NJ; r++)
        for (int s = 0; s < NJ; s++) {
            A[r][s] = 0;
            for (int c = 0; c < 3 * NP; c++)
                A[r][s] += W[r][c] * W[s][c] / (double)masses[c / 3];
        }
}

/* the pattern: rows sharing a point couple (8 pairs); minimum degree eliminates J0 (no
   fill), then J3 (its neighbours J2 and J4 are not coupled: one fill), then J4, J1, J2,
   J5 without fill: 9 entries below L's diagonal (the natural order would need 3 fills) */
static void test_fill(void)
{
    rt_scene sc = loop_scene();
    TH_CHECK(rt_init(&sc, &tu_sim) == RT_OK);
    const rt_mbs_work *w = &tu_sim.work.mbs;
    th_note("entries below the diagonal of L", w->lp[w->rb[1]]);
    TH_CHECK(w->rb[1] == NJ && w->lp[w->rb[1]] == 9);
    TH_CHECK(w->perm[0] == 0 && w->perm[1] == 3);
}

/* A x = b by the sparse factors against A formed densely here */
static void test_solve(void)
{
    rt_scene sc = loop_scene();
    double A[NJ][NJ], worst = 0;
    real_t x[NJ];
    TH_CHECK(rt_init(&sc, &tu_sim) == RT_OK);
    rti_mbs_assemble(&sc, &tu_sim, 0, 0, RTI_MBS_JAC);
    rti_mbs_schur(&sc, &tu_sim, 0);
    for (int r = 0; r < NJ; r++)
        x[r] = (real_t)(r + 1);
    rti_mbs_solve(&tu_sim, 0, x);
    dense_schur(A);
    for (int r = 0; r < NJ; r++) {
        double s = -(double)(r + 1);
        for (int c = 0; c < NJ; c++)
            s += A[r][c] * (double)x[c];
        worst = absd(s) > worst ? absd(s) : worst;
    }
    th_note("largest residual of A x = b", worst);
    TH_CHECK(worst < (RT_REAL_IS_FLOAT ? 1e-4 : 1e-12));
    TH_CHECK(rt_stats_of(&tu_sim)->count[RT_CNT_SINGULAR] == 0);
}

/* one second of motion: the loop closes and the branch hangs on after every projection */
static void test_run(void)
{
    rt_scene sc = loop_scene();
    TH_CHECK(rt_init(&sc, &tu_sim) == RT_OK);
    while (rt_tick(&sc, &tu_sim) == RT_OK)
        ;
    double res = (double)rt_rec_value(&sc, &tu_sim, 0);
    th_note("largest |g| at 1 s", res);
    TH_CHECK(rt_stats_of(&tu_sim)->status == RT_OK && res < (RT_REAL_IS_FLOAT ? 1e-4 : 1e-12));
    /* the points moved: gravity pulls the mechanism out of its start */
    TH_CHECK(absd((double)rt_output(&tu_sim, 4, 2) - (double)pos[4][2]) > 1e-2);
}

const th_test th_mbs_ldl_tests[] = {
    {"mbs_ldl_fill", test_fill},
    {"mbs_ldl_solve", test_solve},
    {"mbs_ldl_run", test_run},
    {0, 0},
};
