/* Mesh cloths read from Wavefront OBJ files (model/cloth_read.h): the
 * particles and their vertex-area masses, scale and translate, pins by
 * particle index and by box, the mass-spring network of triangle edges and
 * bend pairs (forces/springs.h), spring damping on the same pairs,
 * position-based constraints, Baraff-Witkin on the mesh's own triangles
 * (forces/bw.h), frames and series of a run, and the refusal of grid-only
 * keys and terms.  Every OBJ file is written by the test into a scratch
 * directory. */
#include <criterion/criterion.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bwcheck.h"
#include "forces/springs.h"
#include "model/cloth_read.h"
#include "model/pairs.h"
#include "runcli.h"
#include "timelimit.h"

/* ---- fixture: a scratch directory per test, OBJ files in it ------------ */

static char dir[512];

static void setup(void)
{
    time_limit(600);
    tmp_mkdtemp(dir, sizeof dir, "mesh");
}

static void teardown(void)
{
    tmp_rm_rf(dir);
}

TestSuite(cloth_mesh, .init = setup, .fini = teardown);

typedef struct {
    char path[700]; /* the file */
    char key[720];  /* "cloth.mesh=<path>" */
} obj_file;

/* DIR/name: np vertices X (3 np) and ntri triangles (0-based), then the
 * lines of `extra` (may be NULL). */
static obj_file obj_write(const char *name, size_t np, const double *X,
                          size_t ntri, const int (*tri)[3], const char *extra)
{
    obj_file o;
    snprintf(o.path, sizeof o.path, "%s/%s", dir, name);
    snprintf(o.key, sizeof o.key, "cloth.mesh=%s", o.path);
    FILE *fp = fopen(o.path, "w");
    cr_assert_not_null(fp, "cannot write %s", o.path);
    fprintf(fp, "# test mesh\n");
    for (size_t p = 0; p < np; p++)
        fprintf(fp, "v %.17g %.17g %.17g\n", X[3 * p], X[3 * p + 1],
                X[3 * p + 2]);
    for (size_t t = 0; t < ntri; t++)
        fprintf(fp, "f %d %d %d\n", tri[t][0] + 1, tri[t][1] + 1,
                tri[t][2] + 1);
    if (extra)
        fputs(extra, fp);
    cr_assert_eq(fclose(fp), 0);
    return o;
}

/* The triangulation of an nu x nv grid (su x sv) as an OBJ file: the same
 * particles, rest positions and triangles as the grid cloth. */
static obj_file grid_obj(const char *name, int nu, int nv, double su,
                         double sv)
{
    cl_cloth c;
    cl_error err;
    cr_assert_eq(cl_cloth_grid(nu, nv, su, sv, 1.0, &c, &err), CL_OK);
    obj_file o = obj_write(name, c.np, c.X0, c.ntri,
                           (const int(*)[3])c.tri, NULL);
    cl_cloth_free(&c);
    return o;
}

/* A 4 x 4 grid triangulation, 0.3 m per side, jittered in the plane and
 * bent out of it: no two rest lengths alike, not flat. */
static obj_file bumpy_obj(const char *name)
{
    cl_cloth c;
    cl_error err;
    fd_rng r = {.s = 77};
    cr_assert_eq(cl_cloth_grid(4, 4, 0.9, 0.9, 1.0, &c, &err), CL_OK);
    for (size_t p = 0; p < c.np; p++) {
        double *X = c.X0 + 3 * p;
        X[0] += 0.05 * fd_rand(&r);
        X[2] += 0.05 * fd_rand(&r);
        X[1] = 0.1 * sin(3.0 * X[0]) * cos(2.0 * X[2]) + 0.02 * fd_rand(&r);
    }
    obj_file o = obj_write(name, c.np, c.X0, c.ntri, (const int(*)[3])c.tri,
                           NULL);
    cl_cloth_free(&c);
    return o;
}

/* The Choi-Ko terms and gravity off: what a mesh cloth is tested with. */
#define MESH_MODEL(o, ...)                                                  \
    FD_MODEL((o).key, "type1.enabled=false", "type2.enabled=false",         \
             "gravity.g=0,0,0", __VA_ARGS__)

static cl_status mesh_try(const char *const *sets, cl_error *err)
{
    cl_model *m = NULL;
    memset(err, 0, sizeof *err);
    cl_status rc = fd_model_try(sets, &m, err);
    cl_model_free(m);
    return rc;
}

/* A refused model: status `want` (CL_OK: any failure) and a message with
 * both strings. */
static void expect_refused(const char *const *sets, cl_status want,
                           const char *s1, const char *s2)
{
    cl_error err;
    cl_status rc = mesh_try(sets, &err);
    if (want == CL_OK)
        cr_assert_neq(rc, CL_OK, "%s: accepted", s1);
    else
        cr_assert_eq(rc, want, "%s: status %d (%s)", s1, rc, err.msg);
    cr_assert_not_null(strstr(err.msg, s1), "\"%s\" lacks \"%s\"", err.msg,
                       s1);
    cr_assert_not_null(strstr(err.msg, s2), "\"%s\" lacks \"%s\"", err.msg,
                       s2);
}

/* The pinned particles, as a 0/1 mask over np. */
static void pinned_mask(const cl_cloth *c, unsigned char *mask)
{
    for (size_t p = 0; p < c->np; p++)
        mask[p] = c->dof[p] < 0;
}

/* ---- particles, masses, triangles -------------------------------------- */

/* The 3 x 3 square (grid triangulation): vertex (i, j) lies in 2, 3, 1 /
 * 3, 6, 3 / 1, 3, 2 triangles of equal area, so m = mass count / 24. */
Test(cloth_mesh, particles_and_area_masses)
{
    static const int count[9] = {2, 3, 1, 3, 6, 3, 1, 3, 2};
    obj_file o = grid_obj("square.obj", 3, 3, 1.0, 1.0);
    cl_model *m = MESH_MODEL(o, "cloth.mass=0.4");
    const cl_cloth *c = cl_model_cloth(m);
    cr_assert_eq(c->kind, CL_CLOTH_MESH);
    cr_assert_eq(c->np, 9);
    cr_assert_eq(c->ntri, 8);
    cr_assert_eq(c->nu, 0, "a mesh has no grid rows");
    cr_assert_eq(c->npin, 0, "no default pins on a mesh");
    int grid[8][3];
    cl_grid_triangles(3, 3, grid);
    cr_assert_eq(memcmp(c->tri, grid, sizeof grid), 0, "the file's triangles");
    double sum = 0.0;
    for (int p = 0; p < 9; p++) {
        cr_assert_float_eq(c->mass[p], 0.4 * count[p] / 24.0, 1e-16,
                           "particle %d: %g", p, c->mass[p]);
        sum += c->mass[p];
    }
    cr_assert_float_eq(sum, 0.4, 1e-15);
    char shape[96];
    cr_assert_str_eq(cl_cloth_shape(c, shape, sizeof shape),
                     "9 particles, 8 triangles");
    cl_model_free(m);
}

Test(cloth_mesh, two_triangles_scale_translate_particle_mass)
{
    static const double X[] = {0, 0, 0, 1, 0, 0, 1, 0, 1, 0, 0, 1};
    static const int tri[2][3] = {{0, 1, 2}, {0, 2, 3}};
    obj_file o = obj_write("two.obj", 4, X, 2, tri, NULL);
    cl_model *m = MESH_MODEL(o, "cloth.scale=2", "cloth.translate=1,2,3",
                             "cloth.mass=0.3");
    const cl_cloth *c = cl_model_cloth(m);
    for (size_t k = 0; k < 12; k++)
        cr_assert_eq(c->X0[k], 2.0 * X[k] + (double)(k % 3 + 1),
                     "coordinate %zu", k);
    /* 0 and 2 lie in both triangles: a third of 2 m^2 each, the others a
     * third of 1 m^2 (scaled areas, the same shares). */
    cr_assert_float_eq(c->mass[0], 0.1, 1e-16);
    cr_assert_float_eq(c->mass[2], 0.1, 1e-16);
    cr_assert_float_eq(c->mass[1], 0.05, 1e-16);
    cr_assert_float_eq(c->mass[3], 0.05, 1e-16);
    cl_model_free(m);
    m = MESH_MODEL(o, "cloth.particle_mass=0.02", "cloth.mass=5");
    for (size_t p = 0; p < 4; p++)
        cr_assert_eq(cl_model_cloth(m)->mass[p], 0.02);
    cl_model_free(m);
}

Test(cloth_mesh, grid_cloth_keeps_its_triangles)
{
    cl_model *m = FD_MODEL("cloth.nu=4", "cloth.nv=3", "pins.at=");
    const cl_cloth *c = cl_model_cloth(m);
    int grid[12][3];
    cr_assert_eq(c->kind, CL_CLOTH_GRID);
    cr_assert_eq(c->ntri, cl_grid_triangles(4, 3, grid));
    cr_assert_eq(memcmp(c->tri, grid, sizeof grid), 0);
    char shape[96];
    cr_assert_str_eq(cl_cloth_shape(c, shape, sizeof shape),
                     "4 x 3 particles");
    size_t n;
    int(*tri)[3] = malloc(c->ntri * sizeof *tri);
    cr_assert_not_null(tri);
    cr_assert_eq(cl_model_triangles(m, tri, &n, NULL), CL_OK);
    cr_assert_eq(n, 12);
    cr_assert_eq(memcmp(tri, grid, sizeof grid), 0);
    free(tri);
    cl_model_free(m);
}

/* ---- pair sets ---------------------------------------------------------- */

/* Sorted, each pair once, a < b, rest length the rest distance. */
static void check_set(const cl_cloth *c, const cl_pairset *s)
{
    for (size_t k = 0; k < s->n; k++) {
        const cl_pair *p = &s->pair[k];
        cr_assert(p->a >= 0 && p->a < p->b && (size_t)p->b < c->np);
        cr_assert_eq(p->rest, cl_dist(c->X0 + 3 * p->a, c->X0 + 3 * p->b));
        if (k)
            cr_assert(p[-1].a < p->a || (p[-1].a == p->a && p[-1].b < p->b),
                      "pairs %zu, %zu out of order or repeated", k - 1, k);
    }
}

static void expect_counts(const cl_cloth *c, size_t edges, size_t bend)
{
    cl_pairset e, b;
    cl_error err;
    cr_assert_eq(cl_pairs_mesh_edges(c, &e, &err), CL_OK);
    cr_assert_eq(cl_pairs_mesh_bend(c, &b, &err), CL_OK, "%s", err.msg);
    check_set(c, &e);
    check_set(c, &b);
    cr_assert_eq(e.n, edges, "%zu edges, expected %zu", e.n, edges);
    cr_assert_eq(b.n, bend, "%zu bend pairs, expected %zu", b.n, bend);
    cl_pairs_free(&e);
    cl_pairs_free(&b);
}

/* A grid triangulation of nu x nv has (nu-1) nv + nu (nv-1) + (nu-1)(nv-1)
 * edges, of which 2 (nu-1) + 2 (nv-1) on the boundary; each interior edge
 * gives one bend pair, all distinct.  The same counts on the grid cloth
 * and on its triangulation read as a mesh. */
Test(cloth_mesh, pair_counts)
{
    for (int nu = 2; nu <= 6; nu++)
        for (int nv = 2; nv <= 5; nv++) {
            size_t edges = (size_t)((nu - 1) * nv + nu * (nv - 1) +
                                    (nu - 1) * (nv - 1));
            size_t bend = edges - (size_t)(2 * (nu - 1) + 2 * (nv - 1));
            cl_cloth g;
            cl_error err;
            cr_assert_eq(cl_cloth_grid(nu, nv, 1.0, 0.7, 1.0, &g, &err),
                         CL_OK);
            expect_counts(&g, edges, bend);
            obj_file o = obj_write("g.obj", g.np, g.X0, g.ntri,
                                   (const int(*)[3])g.tri, NULL);
            cl_cloth_free(&g);
            cl_model *m = MESH_MODEL(o, "pins.at=");
            expect_counts(cl_model_cloth(m), edges, bend);
            cl_model_free(m);
        }
}

/* Two triangles: 5 edges, one bend pair (the other diagonal); a closed
 * tetrahedron: 6 edges, and every far-vertex pair is an edge, so no bend
 * pair. */
Test(cloth_mesh, pair_counts_small_meshes)
{
    static const double X[] = {0, 0, 0, 1, 0, 0, 1, 0, 1, 0, 0, 1};
    static const int two[2][3] = {{0, 1, 2}, {0, 2, 3}};
    static const double T[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    static const int tet[4][3] = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
    cl_cloth c;
    cl_error err;
    cr_assert_eq(cl_cloth_mesh(4, X, 2, two, 1.0, &c, &err), CL_OK);
    expect_counts(&c, 5, 1);
    cl_pairset b;
    cr_assert_eq(cl_pairs_mesh_bend(&c, &b, &err), CL_OK);
    cr_assert(b.pair[0].a == 1 && b.pair[0].b == 3);
    cl_pairs_free(&b);
    cl_cloth_free(&c);
    cr_assert_eq(cl_cloth_mesh(4, T, 4, tet, 1.0, &c, &err), CL_OK);
    expect_counts(&c, 6, 0);
    cl_cloth_free(&c);
}

/* The spring network of a mesh: the edges at k_structural, then the bend
 * pairs at k_bend; k_bend = 0 leaves them out. */
Test(cloth_mesh, spring_network)
{
    obj_file o = grid_obj("square.obj", 3, 3, 1.0, 1.0);
    static const char *const kbs[] = {"springs.k_bend=9", "springs.k_bend=0"};
    for (int k = 0; k < 2; k++) {
        cl_config *cfg = cl_config_alloc();
        cl_error err;
        cl_model *m = MESH_MODEL(o, "pins.at=");
        cr_assert_eq(cl_config_set(cfg, "springs.k_structural=70", &err),
                     CL_OK);
        cr_assert_eq(cl_config_set(cfg, kbs[k], &err), CL_OK);
        cl_springnet net;
        cr_assert_eq(cl_springs_network(cfg, cl_model_cloth(m), &net, &err),
                     CL_OK, "%s", err.msg);
        cr_assert_eq(net.set.n, k == 0 ? 24u : 16u);
        for (size_t i = 0; i < net.set.n; i++)
            cr_assert_eq(net.k[i], i < 16 ? 70.0 : 9.0, "pair %zu", i);
        cl_springnet_free(&net);
        cl_model_free(m);
        cl_config_free(cfg);
    }
}

/* ---- pins --------------------------------------------------------------- */

Test(cloth_mesh, pins_by_index_and_box)
{
    obj_file o = grid_obj("square.obj", 3, 3, 1.0, 1.0);
    /* x = 0.5 is the middle column of vertices 3, 4, 5. */
    cl_model *m = MESH_MODEL(o, "pins.at=p=0 p=-1", "pins2.box=0.4,-1,-1, "
                             "0.6,1,2", "pins2.velocity=0,1,0",
                             "pins2.stop=1");
    const cl_cloth *c = cl_model_cloth(m);
    unsigned char mask[9], want[9] = {1, 0, 0, 1, 1, 1, 0, 0, 1};
    pinned_mask(c, mask);
    cr_assert_eq(memcmp(mask, want, 9), 0);
    cr_assert_eq(c->npin, 5);
    double x[12] = {0}, xf[27], vf[27];
    cl_cloth_scatter(c, 2.0, x, x, xf, vf);
    cr_assert_eq(xf[3 * 4 + 1], 1.0, "moved at 1 m/s until t = 1");
    cr_assert_eq(xf[3 * 8 + 1], 0.0);
    cl_model_free(m);
}

/* On a grid: p=K is particle i*nv + j; a box replaces the default corner
 * pins of [pins]. */
Test(cloth_mesh, grid_pins_by_index_and_box)
{
    cl_model *m = FD_MODEL("cloth.n=3", "pins.at=p=5");
    const cl_cloth *c = cl_model_cloth(m);
    cr_assert_eq(c->npin, 1);
    cr_assert_lt(c->dof[cl_cloth_index(c, 1, 2)], 0);
    cl_model_free(m);
    m = FD_MODEL("cloth.n=4", "pins.box=0.9,-1,-1, 1.1,1,2");
    c = cl_model_cloth(m);
    cr_assert_eq(c->npin, 4, "the row i = 3 only");
    for (int j = 0; j < 4; j++)
        cr_assert_lt(c->dof[cl_cloth_index(c, 3, j)], 0);
    cl_model_free(m);
}

/* Settings refused on the mesh o (Choi-Ko off) with a message holding s1
 * and s2; up to three settings, the unused ones NULL. */
typedef struct {
    const char *set[3], *s1, *s2;
} mesh_case;

static void expect_mesh_cases(const obj_file *o, const mesh_case *cases,
                              size_t n)
{
    for (size_t k = 0; k < n; k++)
        expect_refused(FD_SETS(o->key, "type1.enabled=false",
                               "type2.enabled=false", cases[k].set[0],
                               cases[k].set[1], cases[k].set[2]),
                       CL_EINVAL, cases[k].s1, cases[k].s2);
}

Test(cloth_mesh, pin_errors)
{
    obj_file o = grid_obj("square.obj", 3, 3, 1.0, 1.0);
    static const mesh_case cases[] = {
        {{"pins.at=p=9"}, "[pins] at", "p=9 lies outside the 9"},
        {{"pins.at=p=-10"}, "[pins] at", "outside"},
        {{"pins.at=0,0"}, "[pins] at", "no rows or columns"},
        {{"pins3.at=j=1"}, "[pins3] at", "p=K"},
        {{"pins2.box=2,2,2, 3,3,3"}, "[pins2] box", "no particle"},
        {{"pins.box=0,0,0, 1,1"}, "[pins] box", "6 finite numbers"},
        {{"pins.at=p=4", "pins2.box=0.4,-1,-1, 0.6,1,2",
          "pins2.velocity=1,0,0"},
         "[pins2] box",
         "twice"},
    };
    expect_mesh_cases(&o, cases, sizeof cases / sizeof cases[0]);
    expect_refused(FD_SETS("cloth.n=3", "pins.box=5,5,5, 6,6,6"), CL_EINVAL,
                   "[pins] box", "no particle");
}

/* ---- refused keys and terms --------------------------------------------- */

Test(cloth_mesh, grid_keys_and_terms_refused)
{
    obj_file o = grid_obj("square.obj", 3, 3, 1.0, 1.0);
    static const mesh_case cases[] = {
        {{"cloth.n=5"}, "[cloth] n = \"5\"", "mesh cloth"},
        {{"cloth.nv=5"}, "[cloth] nv", "grid key"},
        {{"cloth.size=2"}, "[cloth] size", "grid key"},
        {{"cloth.su=2"}, "[cloth] su", "grid key"},
        {{"cloth.diagonal=alternate"}, "[cloth] diagonal", "grid key"},
        {{"type2.enabled=true"}, "[type2] enabled", "Type2"},
        {{"damping.kd=0.1"}, "[damping] kd", "Type1 and Type2 pairs"},
        {{"springs.enabled=true", "springs.levels=1"}, "[springs] levels",
         "grid offsets"},
        {{"springs.enabled=true", "springs.k_shear=5"}, "[springs] k_shear",
         "no shear springs"},
        {{"spring-damping.kd=1", "springs.levels=2"}, "[springs] levels",
         "grid offsets"},
        {{"pbd.enabled=true", "pbd.levels=3"}, "[pbd] levels", "beyond 2"},
        {{"cloth.scale=0"}, "[cloth] scale", "expected"},
        {{"cloth.translate=1,2"}, "[cloth] translate", "3 finite"},
    };
    expect_mesh_cases(&o, cases, sizeof cases / sizeof cases[0]);
    /* Type1 is on by default: the message names the mesh key. */
    expect_refused(FD_SETS(o.key, "type2.enabled=false"), CL_EINVAL,
                   "[cloth] mesh", "[type1] enabled = false");
    /* Mesh keys on a grid. */
    expect_refused(FD_SETS("cloth.n=3", "cloth.scale=2"), CL_EINVAL,
                   "[cloth] scale", "mesh cloth only");
    expect_refused(FD_SETS("cloth.n=3", "cloth.translate=0,1,0"), CL_EINVAL,
                   "[cloth] translate", "mesh cloth only");
    /* What is allowed: k_shear = 0, spring damping, PBD levels 1 and 2. */
    cl_error err;
    cr_assert_eq(mesh_try(FD_SETS(o.key, "type1.enabled=false",
                                  "type2.enabled=false",
                                  "springs.enabled=true",
                                  "springs.k_shear=0",
                                  "spring-damping.kd=0.5", "pbd.enabled=true",
                                  "pbd.levels=2"),
                          &err),
                 CL_OK, "%s", err.msg);
}

Test(cloth_mesh, bad_mesh_files_refused)
{
    static const double X[] = {0, 0, 0, 1, 0, 0, 1, 0, 1, 0, 0, 1, 5, 5, 5};
    static const int two[2][3] = {{0, 1, 2}, {0, 2, 3}};
    static const int fin[3][3] = {{0, 1, 2}, {0, 1, 3}, {0, 1, 4}};
    static const int twice[3][3] = {{0, 1, 2}, {0, 2, 3}, {2, 1, 0}};
    char missing[720];
    snprintf(missing, sizeof missing, "cloth.mesh=%s/none.obj", dir);
    expect_refused(FD_SETS(missing), CL_OK, "[cloth] mesh", "none.obj");
    expect_refused(FD_SETS("cloth.mesh="), CL_EINVAL, "[cloth] mesh",
                   "file name");
    obj_file o = obj_write("lone.obj", 5, X, 2, two, NULL);
    expect_refused(FD_SETS(o.key), CL_EINVAL, "[cloth] mesh",
                   "vertex 4 belongs to no triangle");
    o = obj_write("fin.obj", 5, X, 3, fin, NULL);
    expect_refused(FD_SETS(o.key), CL_EINVAL, "[cloth] mesh",
                   "shared by 3 triangles");
    o = obj_write("twice.obj", 4, X, 3, twice, NULL);
    expect_refused(FD_SETS(o.key), CL_EINVAL, "[cloth] mesh",
                   "mesh triangles 0 and 2 have the same vertices (0, 1, 2):"
                   " a triangle given twice");
    o = obj_write("junk.obj", 4, X, 2, two, "bogus statement\n");
    expect_refused(FD_SETS(o.key), CL_OK, "[cloth] mesh", "junk.obj");
}

/* ---- springs ------------------------------------------------------------ */

/* At rest every spring of a bumpy mesh has d == L bit for bit: force and
 * energy exactly zero (spring damping too, at rest velocity). */
Test(cloth_mesh, springs_at_rest_exactly_zero)
{
    obj_file o = bumpy_obj("bumpy.obj");
    cl_model *m = MESH_MODEL(o, "springs.enabled=true", "springs.k_bend=7",
                             "spring-damping.kd=0.3");
    size_t n = fd_n(m);
    double *v = fd_vec(n), *f = fd_vec(n);
    cl_energy e = fd_eval(m, cl_model_cloth(m)->X0, v, f);
    cr_assert_eq(fd_maxabs(f, n), 0.0);
    cr_assert_eq(fd_term_energy(&e, "springs"), 0.0);
    cr_assert_eq(e.power_diss, 0.0);
    free(v);
    free(f);
    cl_model_free(m);
}

/* x = 1.03 X0 + jitter (5% of the smallest edge), v random. */
static void mesh_state(const cl_model *m, fd_rng *r, double *x, double *v)
{
    const cl_cloth *c = cl_model_cloth(m);
    cl_pairset e;
    cl_error err;
    cr_assert_eq(cl_pairs_mesh_edges(c, &e, &err), CL_OK);
    double h = INFINITY;
    for (size_t k = 0; k < e.n; k++)
        h = fmin(h, e.pair[k].rest);
    cl_pairs_free(&e);
    for (size_t i = 0; i < 3 * c->np; i++) {
        x[i] = 1.03 * c->X0[i] + 0.05 * h * fd_rand(r);
        v[i] = 0.3 * fd_rand(r);
    }
}

Test(cloth_mesh, springs_jacobian_fd)
{
    obj_file o = bumpy_obj("bumpy.obj");
    cl_model *m = MESH_MODEL(o, "springs.enabled=true", "springs.k_bend=7");
    size_t n = fd_n(m);
    double *x = fd_vec(n), *v = fd_vec(n), ex, ev;
    fd_rng r = {.s = 5};
    mesh_state(m, &r, x, v);
    fd_check_jacobian(m, x, v, 1e-7, 1e-6, false, "mesh springs", &ex, &ev);
    cr_assert_lt(ex, 1e-8, "df/dx vs FD: rel err %g", ex);
    cr_assert_eq(ev, 0.0);
    cr_assert_lt(fd_check_structure(m, x, v), 1e-13);
    cr_assert_lt(fd_check_energy(m, x, v, 1e-7, "mesh springs"), 1e-8);
    cl_model_free(m);
    m = MESH_MODEL(o, "spring-damping.kd=0.4", "springs.k_bend=2");
    fd_check_jacobian(m, x, v, 1e-7, 1e-6, false, "mesh spring damping",
                      &ex, &ev);
    cr_assert_lt(ex, 1e-8, "dd/dx vs FD: rel err %g", ex);
    cr_assert_lt(ev, 1e-8, "dd/dv vs FD: rel err %g", ev);
    cl_model_free(m);
    free(x);
    free(v);
}

/* Spring damping acts on exactly the pairs of the spring network: the
 * off-diagonal blocks of df/dv. */
Test(cloth_mesh, spring_damping_follows_the_network)
{
    obj_file o = grid_obj("square.obj", 3, 3, 1.0, 1.0);
    static const char *const kbs[] = {"springs.k_bend=3", "springs.k_bend=0"};
    for (int k = 0; k < 2; k++) {
        cl_model *m = MESH_MODEL(o, "pins.at=", "spring-damping.kd=0.5",
                                 kbs[k]);
        const cl_cloth *c = cl_model_cloth(m);
        size_t n = fd_n(m);
        double *x = fd_vec(n), *v = fd_vec(n), *Jx = fd_vec(n * n),
               *Jv = fd_vec(n * n);
        memcpy(x, c->X0, n * sizeof *x);
        fd_jacobian(m, x, v, Jx, Jv);
        cl_pairset s, b = {0};
        cl_error err;
        cr_assert_eq(cl_pairs_mesh_edges(c, &s, &err), CL_OK);
        if (k == 0) {
            cr_assert_eq(cl_pairs_mesh_bend(c, &b, &err), CL_OK);
            cr_assert_eq(cl_pairs_append(&s, &b, &err), CL_OK);
        }
        unsigned char want[81] = {0};
        for (size_t i = 0; i < s.n; i++)
            want[9 * s.pair[i].a + s.pair[i].b] =
                want[9 * s.pair[i].b + s.pair[i].a] = 1;
        for (size_t a = 0; a < 9; a++)
            for (size_t bb = 0; bb < 9; bb++) {
                double block = 0.0;
                for (int i = 0; i < 3; i++)
                    for (int j = 0; j < 3; j++)
                        block = fmax(block, fabs(Jv[(3 * a + i) * n +
                                                    3 * bb + j]));
                if (a != bb)
                    cr_assert_eq(block > 0, want[9 * a + bb],
                                 "k_bend case %d: block (%zu, %zu)", k, a,
                                 bb);
            }
        cl_pairs_free(&s);
        free(x);
        free(v);
        free(Jx);
        free(Jv);
        cl_model_free(m);
    }
}

/* ---- position-based constraints ----------------------------------------- */

/* Levels 1 (edges) and 2 (edges and bend pairs) on a mesh: a projection
 * from a state shrunk by 3% restores every edge (to 1e-4: the Gauss-Seidel
 * sweeps converge slowly along the mesh's soft bending modes). */
Test(cloth_mesh, pbd_restores_the_edges)
{
    obj_file o = bumpy_obj("bumpy.obj");
    static const char *const levels[] = {"pbd.levels=1", "pbd.levels=2"};
    for (int k = 0; k < 2; k++) {
        cl_model *m = MESH_MODEL(o, "pbd.enabled=true", "pbd.iterations=400",
                                 levels[k]);
        const cl_cloth *c = cl_model_cloth(m);
        const cl_system *sys = cl_model_system(m);
        cr_assert_not_null(sys->project);
        double *x = fd_vec(sys->n), *xf = fd_vec(3 * c->np);
        for (size_t i = 0; i < sys->n; i++)
            x[i] = 0.97 * c->X0[i];
        cr_assert_eq(sys->project(sys->data, 0.0, x), CL_OK);
        cl_cloth_scatter(c, 0.0, x, NULL, xf, NULL);
        cl_pairset e;
        cl_error err;
        cr_assert_eq(cl_pairs_mesh_edges(c, &e, &err), CL_OK);
        for (size_t i = 0; i < e.n; i++) {
            const cl_pair *p = &e.pair[i];
            double d = cl_dist(xf + 3 * p->a, xf + 3 * p->b);
            cr_assert_lt(fabs(d - p->rest), 1e-4 * p->rest,
                         "levels %d: edge %d-%d at %g of %g", k + 1, p->a,
                         p->b, d, p->rest);
        }
        cl_pairs_free(&e);
        free(x);
        free(xf);
        cl_model_free(m);
    }
}

/* ---- Baraff-Witkin ------------------------------------------------------ */

/* y = s R X0 + t: a similarity, under which every triangle is stretched by
 * s in every direction of its plane, whatever its (u, v). */
static void similarity(const cl_cloth *c, double s, fd_rng *r, double *x)
{
    double R[9], t[3];
    fd_rotation(r, R);
    fd_random_vec(r, 1.0, t, 3);
    fd_apply(R, t, c->X0, x, c->np);
    for (size_t i = 0; i < 3 * c->np; i++)
        x[i] = s * (x[i] - t[i % 3]) + t[i % 3];
}

static void expect_same(cl_model *a, cl_model *b, const double *x,
                        const double *v, const char *term)
{
    size_t n = fd_n(a);
    double *fa = fd_vec(n), *fb = fd_vec(n);
    cl_energy ea = fd_eval(a, x, v, fa), eb = fd_eval(b, x, v, fb);
    double Ea = fd_term_energy(&ea, term), Eb = fd_term_energy(&eb, term);
    cr_assert_gt(Ea, 0.0, "%s: no energy to compare", term);
    cr_assert_lt(fabs(Ea - Eb), 1e-12 * Ea, "%s: grid %.17g, mesh %.17g",
                 term, Ea, Eb);
    double ef = fd_relerr(fb, fa, n);
    cr_assert_lt(ef, 1e-10, "%s: forces differ by %g", term, ef);
    free(fa);
    free(fb);
}

/* The grid's own triangulation read as a mesh: the same triangles give the
 * same stretch energy and forces under a similarity (which stretches every
 * direction of a triangle's plane alike, so the per-triangle (u, v) of a
 * mesh and the grid's (x, z) agree), and the same bend under any
 * deformation (hinges do not use (u, v)).  Under other deformations the
 * stretch and shear of a mesh differ from the grid's where a triangle's
 * first edge is not along x: forces/bw.h. */
Test(cloth_mesh, bw_matches_the_grid)
{
    obj_file o = grid_obj("grid.obj", 5, 4, 1.3, 0.9);
    static const char *const grid[] = {"cloth.nu=5", "cloth.nv=4",
                                       "cloth.su=1.3", "cloth.sv=0.9"};
    fd_rng r = {.s = 9};
    cl_model *ga = BW_ONLY(grid[0], grid[1], grid[2], grid[3],
                           "bw-stretch.enabled=true", "bw-stretch.k=3e5");
    cl_model *ma = MESH_MODEL(o, "damping.kd=0", "bw-stretch.enabled=true",
                              "bw-stretch.k=3e5");
    size_t n = fd_n(ga);
    cr_assert_eq(n, fd_n(ma));
    double *x = fd_vec(n), *v = fd_vec(n);
    similarity(cl_model_cloth(ga), 1.07, &r, x);
    fd_random_vec(&r, 0.2, v, n);
    expect_same(ga, ma, x, v, "bw-stretch");
    cl_model_free(ga);
    cl_model_free(ma);

    ga = BW_ONLY(grid[0], grid[1], grid[2], grid[3], "bw-bend.enabled=true",
                 "bw-bend.k=3e-3");
    ma = MESH_MODEL(o, "damping.kd=0", "bw-bend.enabled=true",
                    "bw-bend.k=3e-3");
    fd_deform(ga, NULL, 0.1, 0.3, &r, x);
    expect_same(ga, ma, x, v, "bw-bend");
    cl_model_free(ga);
    cl_model_free(ma);
    free(x);
    free(v);
}

/* Stretch (anisotropic), shear and bend on a bumpy mesh: exact Jacobians
 * against finite differences, f = -dE/dx, symmetry, Newton's third law. */
Test(cloth_mesh, bw_jacobian_fd_on_a_bumpy_mesh)
{
    obj_file o = bumpy_obj("bumpy.obj");
    static const char *const terms[][4] = {
        {"bw-stretch.enabled=true", "bw-stretch.ku=3e5", "bw-stretch.kv=1e5",
         "bw-stretch.bu=0.98"},
        {"bw-shear.enabled=true", "bw-shear.k=2e5", "damping.kd=0",
         "pins.at="},
        {"bw-bend.enabled=true", "bw-bend.k=1e-2", "damping.kd=0",
         "pins.at="},
    };
    for (int k = 0; k < 3; k++) {
        cl_model *m = MESH_MODEL(o, terms[k][0], terms[k][1], terms[k][2],
                                 terms[k][3]);
        size_t n = fd_n(m);
        double *x = fd_vec(n), *v = fd_vec(n);
        fd_rng r = {.s = 31 + (uint64_t)k};
        mesh_state(m, &r, x, v);
        bw_check_potential(m, x, v, 1e-6, terms[k][0]);
        free(x);
        free(v);
        cl_model_free(m);
    }
}

/* At rest the per-triangle frames give w_u, w_v of unit length to
 * round-off: no stretch force beyond round-off. */
Test(cloth_mesh, bw_stretch_rest_state)
{
    obj_file o = bumpy_obj("bumpy.obj");
    cl_model *m = MESH_MODEL(o, "bw-stretch.enabled=true",
                             "bw-shear.enabled=true");
    size_t n = fd_n(m);
    double *v = fd_vec(n), *f = fd_vec(n);
    cl_energy e = fd_eval(m, cl_model_cloth(m)->X0, v, f);
    cr_assert_lt(fd_maxabs(f, n), 1e-7, "rest force %g", fd_maxabs(f, n));
    cr_assert_lt(e.potential, 1e-20, "rest energy %g", e.potential);
    free(v);
    free(f);
    cl_model_free(m);
}

/* ---- a run: frames and series ------------------------------------------- */

/* A problem file next to its mesh, `mesh = NAME` relative to it. */
static void write_problem(const char *ini, const char *mesh)
{
    char text[1024];
    snprintf(text, sizeof text,
             "[cloth]\nmesh = %s\nmass = 0.1\n"
             "[pins]\nat = p=0 p=2\n"
             "[type1]\nenabled = false\n[type2]\nenabled = false\n"
             "[springs]\nenabled = true\n"
             "[gravity]\ng = 0, -9.81, 0\n"
             "[run]\nintegrator = symplectic-euler\ndt = 1e-3\n"
             "t_end = 0.05\nsamples = 5\nframes = 1\n",
             mesh);
    tmp_put(ini, text);
}

/* Field `col` (0-based) of the last line of a CSV text. */
static void last_field(const char *text, int col, char *out, size_t len)
{
    const char *line = text, *p;
    for (p = text; *p; p++)
        if (*p == '\n' && p[1])
            line = p + 1;
    for (int k = 0; k < col; k++)
        line = strchr(line, ',') + 1;
    size_t n = strcspn(line, ",\n");
    snprintf(out, len, "%.*s", (int)(n < len ? n : len - 1), line);
}

Test(cloth_mesh, run_writes_mesh_frames_and_na_columns)
{
    grid_obj("flat.obj", 3, 3, 1.0, 1.0);
    bumpy_obj("bumpy.obj");
    static const char *const meshes[] = {"flat.obj", "bumpy.obj"};
    for (int k = 0; k < 2; k++) {
        char ini[800], out[800], path[900], text[1 << 16], cell[64];
        snprintf(ini, sizeof ini, "%s/p%d.ini", dir, k);
        snprintf(out, sizeof out, "%s/out%d", dir, k);
        write_problem(ini, meshes[k]);
        cli_result r;
        cli_run(&r, "run", ini, "--out", out, NULL);
        cli_assert_ok(&r);
        cr_assert(strstr(r.out, k ? "16 particles, 18 triangles"
                                  : "9 particles, 8 triangles"),
                  "%s", r.out);
        cli_result_free(&r);
        snprintf(path, sizeof path, "%s/series.csv", out);
        tmp_slurp(path, text, sizeof text);
        cr_assert(strstr(text, "max_offplane,wrinkles,broken\n"), "%s", text);
        last_field(text, 9, cell, sizeof cell);
        cr_assert_str_eq(cell, "NA", "wrinkles: a grid's centre line");
        last_field(text, 8, cell, sizeof cell);
        if (k == 0)
            cr_assert_gt(strtod(cell, NULL), 0.0, "flat: offplane %s", cell);
        else
            cr_assert_str_eq(cell, "NA", "bumpy: no rest plane");
        snprintf(path, sizeof path, "%s/frame_00001.obj", out);
        tmp_slurp(path, text, sizeof text);
        cr_assert(strstr(text, k ? " np=16\n" : " np=9\n"), "%s", text);
        size_t faces = 0;
        for (const char *p = text; (p = strstr(p, "\nf ")); p++)
            faces++;
        cr_assert_eq(faces, k ? 18u : 8u);
        snprintf(path, sizeof path, "%s/frame_00001.vtk", out);
        tmp_slurp(path, text, sizeof text);
        cr_assert(strstr(text, k ? "POLYGONS 18 72\n" : "POLYGONS 8 32\n"),
                  "%s", text);
    }
}

/* With obstacles the contact columns follow `broken`, and the NA columns
 * stay the ones they name (a mesh cloth's wrinkles and, off a flat rest
 * mesh, max_offplane), not counted from the end. */
Test(cloth_mesh, na_columns_with_obstacles)
{
    bumpy_obj("bumpy.obj");
    char ini[800], out[800], path[900], text[1 << 16], cell[64];
    snprintf(ini, sizeof ini, "%s/contact.ini", dir);
    snprintf(out, sizeof out, "%s/contact-out", dir);
    write_problem(ini, "bumpy.obj");
    FILE *f = fopen(ini, "a");
    cr_assert_not_null(f);
    fputs("[obstacle.floor]\nshape = plane\npoint = 0, -0.001, 0\n"
          "normal = 0, 1, 0\nresponse = penalty\nk = 10\neps = 0.1\n", f);
    cr_assert_eq(fclose(f), 0);
    cli_result r;
    cli_run(&r, "run", ini, "--out", out, NULL);
    cli_assert_ok(&r);
    cli_result_free(&r);
    snprintf(path, sizeof path, "%s/series.csv", out);
    tmp_slurp(path, text, sizeof text);
    cr_assert(strstr(text, "gravity,contact,potential,"), "%s", text);
    cr_assert(strstr(text, "max_offplane,wrinkles,broken,contacts,"
                           "max_penetration,contact_force,friction_power\n"),
              "%s", text);
    last_field(text, 9, cell, sizeof cell);
    cr_assert_str_eq(cell, "NA", "max_offplane: no rest plane");
    last_field(text, 10, cell, sizeof cell);
    cr_assert_str_eq(cell, "NA", "wrinkles: a grid's centre line");
    last_field(text, 12, cell, sizeof cell);
    cr_assert_gt(strtod(cell, NULL), 0.0, "contacts %s", cell);
    last_field(text, 14, cell, sizeof cell);
    cr_assert_gt(strtod(cell, NULL), 0.0, "contact_force %s", cell);
}
