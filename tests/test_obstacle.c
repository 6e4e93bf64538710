/* Obstacles (contact/obstacle.h): the scripted path (keyframes held before
 * the first and after the last, linear in between), the rotation about
 * the pivot, the exact velocity field against the motion of a shape point,
 * queries on a moved and turned shape, names and refusals, the
 * constraint response's keys, the times of impact of straight moves
 * (continuous collision detection) against every shape, static and
 * moving, project's continuous detection against a moving box, and the
 * slim contact points (no derivatives) against the full ones. */
#include <criterion/criterion.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "contact/obstacle.h"
#include "fdcheck.h"
#include "obstaclecase.h"

#define NSET 12

static cl_status try_make(cl_obstacle *o, const char *sec,
                          const char *const *sets, cl_error *err)
{
    cl_config *cfg = cl_config_alloc();
    cr_assert_not_null(cfg);
    for (size_t k = 0; sets[k]; k++)
        cr_assert_eq(cl_config_set(cfg, sets[k], err), CL_OK, "%s", err->msg);
    cl_status rc = cl_obstacle_create(cfg, sec, o, err);
    cl_config_free(cfg);
    return rc;
}

static void make(cl_obstacle *o, const char *const *sets)
{
    cl_error err = {0};
    cr_assert_eq(try_make(o, "obstacle.o", sets, &err), CL_OK, "%s",
                 err.msg);
}

Test(obstacle, path_is_held_and_interpolated)
{
    cl_obstacle o;
    const char *sets[NSET] = {"obstacle.o.shape = sphere",
                              "obstacle.o.radius = 1",
                              "obstacle.o.path = 1: 0, 0, 0; 3: 2, -4, 6",
                              "obstacle.o.response = project", NULL};
    make(&o, sets);
    cl_pose P;
    cl_obstacle_pose(&o, 0.5, &P); /* before the first keyframe */
    for (int i = 0; i < 3; i++)
        cr_expect_eq(P.s[i], 0.0);
    cr_expect_eq(P.sdot[0], 0.0);
    cl_obstacle_pose(&o, 2.5, &P); /* three quarters of the way */
    cr_expect_float_eq(P.s[0], 1.5, 1e-15);
    cr_expect_float_eq(P.s[1], -3.0, 1e-15);
    cr_expect_float_eq(P.s[2], 4.5, 1e-15);
    cr_expect_float_eq(P.sdot[0], 1.0, 1e-15);
    cr_expect_float_eq(P.sdot[1], -2.0, 1e-15);
    cr_expect_float_eq(P.sdot[2], 3.0, 1e-15);
    cl_obstacle_pose(&o, 7.0, &P); /* held after the last */
    cr_expect_eq(P.s[2], 6.0);
    cr_expect_eq(P.sdot[2], 0.0);
    cr_expect_not(P.rotates);
    cl_obstacle_free(&o);
}

/* The world position of the shape point X at time t (docs/model.md,
 * eq. C2). */
static void world(const cl_obstacle *o, double t, const double X[3],
                  double x[3])
{
    cl_pose P;
    cl_obstacle_pose(o, t, &P);
    for (int i = 0; i < 3; i++) {
        x[i] = o->pivot[i] + P.s[i];
        for (int j = 0; j < 3; j++)
            x[i] += P.R[3 * i + j] * (X[j] - o->pivot[j]);
    }
}

Test(obstacle, velocity_field_is_the_motion_of_the_shape)
{
    cl_obstacle o;
    const char *sets[NSET] = {"obstacle.o.shape = box",
                              "obstacle.o.center = 1, 2, 3",
                              "obstacle.o.size = 1, 2, 3",
                              "obstacle.o.path = 0: 0, 0, 0; 4: 1, 2, -2",
                              "obstacle.o.omega = 0.4, -0.3, 1.1",
                              "obstacle.o.response = penalty",
                              "obstacle.o.k = 1", NULL};
    make(&o, sets);
    cr_expect_float_eq(o.pivot[0], 1.0, 0.0);
    const double X[3] = {1.7, 2.9, 2.2}; /* a point of the box's frame */
    double t = 1.3, h = 1e-6, xp[3], xm[3], x[3];
    world(&o, t + h, X, xp);
    world(&o, t - h, X, xm);
    world(&o, t, X, x);
    cl_pose P;
    cl_obstacle_pose(&o, t, &P);
    cl_contact_point q;
    cl_obstacle_near(&o, &P, x, INFINITY, NULL, &q);
    for (int i = 0; i < 3; i++)
        cr_expect_float_eq(q.u[i], (xp[i] - xm[i]) / (2 * h), 1e-8,
                           "u[%d] = %.12g", i, q.u[i]);
    /* the rotation is a rotation: R R^T = I, det 1 */
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            double rr = 0.0;
            for (int k = 0; k < 3; k++)
                rr += P.R[3 * i + k] * P.R[3 * j + k];
            cr_expect_float_eq(rr, i == j, 1e-14);
        }
    cl_obstacle_free(&o);
}

/* A turned, moved box: the corner that moved with it is on its surface, a
 * point along its moved face normal is at the expected distance. */
Test(obstacle, queries_follow_the_moved_and_turned_shape)
{
    cl_obstacle o;
    const char *sets[NSET] = {"obstacle.o.shape = box",
                              "obstacle.o.size = 2, 2, 2",
                              "obstacle.o.path = 0: 0, 0, 0; 1: 3, 0, 0",
                              "obstacle.o.omega = 0, 0, 1.5707963267948966",
                              "obstacle.o.response = project", NULL};
    make(&o, sets);
    const double corner[3] = {1, 1, 1}, face[3] = {1.5, 0.2, -0.3};
    double x[3], y[3];
    world(&o, 1.0, corner, x);
    world(&o, 1.0, face, y);
    cl_pose P;
    cl_obstacle_pose(&o, 1.0, &P);
    cl_contact_point q;
    cl_obstacle_near(&o, &P, x, INFINITY, NULL, &q);
    cr_expect_lt(fabs(q.d), 1e-14, "corner at d = %g", q.d);
    cl_obstacle_near(&o, &P, y, INFINITY, NULL, &q);
    cr_expect_float_eq(q.d, 0.5, 1e-14);
    /* turned a quarter about z and moved 3 along x: the +x face normal
     * now points along +y */
    cr_expect_float_eq(q.n[1], 1.0, 1e-14);
    cr_expect_float_eq(q.c[0], y[0] - 0.5 * q.n[0], 1e-14);
    cr_expect_float_eq(q.c[1], y[1] - 0.5, 1e-14);
    cl_obstacle_free(&o);
}

Test(obstacle, names_shapes_and_responses_are_checked)
{
    static const struct {
        const char *sec, *sets[NSET], *what;
    } bad[] = {
        {"obstacle.b@d", {"obstacle.b@d.shape = sphere"}, "name"},
        {"obstacle.o", {"obstacle.o.response = project"},
         "--set: [obstacle.o] shape: required (sphere, plane, box or mesh)"},
        {"obstacle.o", {"obstacle.o.shape = sphere", "obstacle.o.radius = 1"},
         "[obstacle.o] response: required"},
        {"obstacle.o", {"obstacle.o.shape = sphere", "obstacle.o.radius = 1",
                        "obstacle.o.response = penalty"},
         "[obstacle.o] k: required (response = penalty's stiffness"},
        {"obstacle.o", {"obstacle.o.shape = sphere", "obstacle.o.radius = 1",
                        "obstacle.o.omega = 1, 2",
                        "obstacle.o.response = project"}, "omega"},
        /* before: accepted, and the obstacle's pose NaN (|omega| t
         * overflowed), so that it touched nothing */
        {"obstacle.o", {"obstacle.o.shape = sphere", "obstacle.o.radius = 1",
                        "obstacle.o.omega = 0, -1e200, 0",
                        "obstacle.o.response = project"},
         "[obstacle.o] omega = \"0, -1e200, 0\": each component at most "
         "1e9 rad/s in size"},
        {"obstacle.o", {"obstacle.o.shape = sphere", "obstacle.o.radius = 1",
                        "obstacle.o.response = barrier",
                        "obstacle.o.dhat = 0.01"}, "kappa"},
        {"obstacle.o", {"obstacle.o.shape = sphere", "obstacle.o.radius = 1",
                        "obstacle.o.response = barrier",
                        "obstacle.o.kappa = 1", "obstacle.o.dhat = -1"},
         "dhat"},
    };
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        cl_obstacle o;
        cl_error err = {0};
        cr_expect_eq(try_make(&o, bad[k].sec, bad[k].sets, &err), CL_EINVAL,
                     "%s", bad[k].what);
        cr_expect(strstr(err.msg, bad[k].what), "%s", err.msg);
        cl_obstacle_free(&o);
    }
}

/* Two answers at the same point: equal up to the rounding of computing
 * the distance to the same feature in other ways (a mesh's kept feature,
 * contact/meshfeat.h, against the tree's closest point): d and c to
 * 1e-14 m, n and G to 1e-14 (1 + 1 / |d|) relative (the rounding of
 * x - c over |d|), u and W exactly. */
static void same_answer(const cl_contact_point *a, const cl_contact_point *b,
                        unsigned long k)
{
    double tol = 1e-14 * (1 + 1 / fabs(b->d));
    cr_assert_leq(fabs(a->d - b->d), 1e-14, "d, step %lu", k);
    cr_assert_leq(fd_relerr(a->c, b->c, 3), 1e-14, "c, step %lu", k);
    cr_assert_leq(fd_relerr(a->n, b->n, 3), tol, "n, step %lu", k);
    cr_assert_leq(fd_relerr(a->G, b->G, 9), tol, "G, step %lu", k);
    cr_assert_eq(memcmp(a->u, b->u, sizeof a->u), 0, "u, step %lu", k);
    cr_assert_eq(memcmp(a->W, b->W, sizeof a->W), 0, "W, step %lu", k);
}

/* A random walk of x about obstacle o (20000 steps of up to 1 cm,
 * 1e-3 s each): cl_obstacle_near with a memo (and the shape's cache, if
 * it has one) answers as it does without; exactly, unless `kept` (a
 * mesh's cache answers from its kept feature: same_answer). */
static void memo_walk(const cl_obstacle *o, const double start[3], bool kept)
{
    unsigned char cache[1024] = {0};
    cr_assert_leq(o->type->cache_size, sizeof cache);
    cl_contact_memo memo = {.d = -INFINITY,
                            .cache = o->type->cache_size ? cache : NULL};
    double x[3] = {start[0], start[1], start[2]};
    unsigned long seed = 12345, steps = 20000, near = 0;
    for (unsigned long k = 0; k < steps; k++) {
        for (int i = 0; i < 3; i++) { /* a small random step */
            seed = seed * 6364136223846793005UL + 1442695040888963407UL;
            x[i] += 0.01 * ((double)(seed >> 11) / 9007199254740992.0 - 0.5);
        }
        cl_pose P;
        cl_obstacle_pose(o, 1e-3 * (double)k, &P);
        cl_contact_point a, b;
        bool with = cl_obstacle_near(o, &P, x, 0.05, &memo, &a);
        bool without = cl_obstacle_near(o, &P, x, 0.05, NULL, &b);
        cr_assert_eq(with, without, "step %lu", k);
        if (with && kept)
            same_answer(&a, &b, k);
        else if (with)
            cr_assert_eq(memcmp(&a, &b, sizeof a), 0, "step %lu", k);
        near += with;
    }
    cr_assert_gt(near, steps / 10, "the walk came near %lu times", near);
}

/* The memo only skips queries that cannot matter, about a moving, turning
 * box and a moving, turning mesh (whose memo keeps nearby triangles). */
Test(obstacle, memo_skips_only_what_cannot_matter)
{
    cl_obstacle o;
    const char *box[NSET] = {"obstacle.o.shape = box",
                             "obstacle.o.size = 1, 1, 1",
                             "obstacle.o.path = 0: 0, 0, 0; 10: 1, 0, 0",
                             "obstacle.o.omega = 0, 0.3, 0",
                             "obstacle.o.response = penalty",
                             "obstacle.o.k = 1", NULL};
    make(&o, box);
    memo_walk(&o, (double[]){0.52, 0.2, 0.1}, false);
    cl_obstacle_free(&o);
    const char *mesh[NSET] = {"obstacle.o.shape = mesh",
                              "obstacle.o.file = problems/meshes/sphere.obj",
                              "obstacle.o.scale = 0.5",
                              "obstacle.o.path = 0: 0, 0, 0; 10: 1, 0, 0",
                              "obstacle.o.omega = 0, 0.3, 0",
                              "obstacle.o.response = penalty",
                              "obstacle.o.k = 1", NULL};
    make(&o, mesh);
    memo_walk(&o, (double[]){0.51, 0.1, 0.1}, true);
    cl_obstacle_free(&o);
}

/* The screen of a moving half-space computes its distances directly (not
 * through the memos): about a tilted floor on a path, 2000 points within
 * 5 cm of it, every point the query puts closer than dmax is listed, and
 * no point the query puts farther than dmax by more than 1e-9 m; a point
 * that is not a number is listed. */
Test(obstacle, halfspace_screen_lists_exactly_the_near_points)
{
    cl_obstacle o;
    const char *plane[NSET] = {"obstacle.o.shape = plane",
                               "obstacle.o.point = 0.3, -1.2, 0.1",
                               "obstacle.o.normal = 0.1, 1, -0.2",
                               "obstacle.o.path = 0: 0, 0, 0; 1: 0.4, 0.2, 0",
                               "obstacle.o.response = penalty",
                               "obstacle.o.k = 1", NULL};
    make(&o, plane);
    enum { NP = 2000 };
    static double x[3 * NP];
    static size_t near[NP];
    static cl_contact_memo memo[NP];
    unsigned long seed = 777;
    for (size_t i = 0; i < 3 * NP; i++) {
        seed = seed * 6364136223846793005UL + 1442695040888963407UL;
        x[i] = (double)(seed >> 11) / 9007199254740992.0 - 0.5;
    }
    cl_pose P;
    cl_obstacle_pose(&o, 0.5, &P);
    const double dmax = 0.01;
    for (size_t p = 0; p < NP; p++) { /* to d = x_p,0 / 10, within 5 cm */
        cl_contact_point q;
        memo[p] = (cl_contact_memo){.d = -INFINITY};
        cl_obstacle_near(&o, &P, x + 3 * p, INFINITY, NULL, &q);
        double move = q.d - 0.1 * x[3 * p];
        for (int i = 0; i < 3; i++)
            x[3 * p + i] -= move * q.n[i];
    }
    x[3 * (NP - 1)] = NAN;
    size_t nnear = cl_obstacle_screen(&o, &P, x, NP, dmax, memo, near);
    size_t listed = 0, closer = 0;
    for (size_t p = 0; p + 1 < NP; p++) {
        cl_contact_point q;
        cl_obstacle_near(&o, &P, x + 3 * p, INFINITY, NULL, &q);
        bool in = listed < nnear && near[listed] == p;
        listed += in;
        closer += q.d < dmax;
        cr_assert(q.d >= dmax || in, "point %zu at d = %g not listed", p,
                  q.d);
        cr_assert(q.d < dmax + 1e-9 || !in, "point %zu at d = %g listed", p,
                  q.d);
    }
    cr_assert_eq(listed + 1, nnear);
    cr_assert_eq(near[nnear - 1], NP - 1);
    cr_assert(closer > NP / 4 && closer < NP - NP / 4, "%zu", closer);
    cl_obstacle_free(&o);
}

/* Empty memos for np points, with their shape caches. */
static cl_contact_memo *memos(const cl_obstacle *o, size_t np,
                              unsigned char **cache)
{
    size_t size = o->type->cache_size;
    cl_contact_memo *m = malloc(np * sizeof *m);
    *cache = calloc(np, size ? size : 1);
    cr_assert(m && *cache);
    for (size_t p = 0; p < np; p++)
        m[p] = (cl_contact_memo){.d = -INFINITY,
                                 .cache = size ? *cache + p * size : NULL};
    return m;
}

/* cl_obstacle_near_slim against cl_obstacle_near: NP points in a 12 cm
 * shell about the surface take 200 small random steps, the obstacle
 * moving; at each the points screened are queried both ways, each with
 * its own memos, and the slim ones must be the points cl_obstacle_near
 * finds within dmax, in order, with its d, n and u bit for bit. */
static void slim_walk(const cl_obstacle *o, const double centre[3])
{
    enum { NP = 300 };
    static double x[3 * NP];
    static size_t listed[NP], kept[NP];
    static cl_contact_slim slim[NP];
    unsigned char *ca, *cb;
    cl_contact_memo *ma = memos(o, NP, &ca), *mb = memos(o, NP, &cb);
    unsigned long seed = 4242, found = 0;
    for (size_t i = 0; i < 3 * NP; i++) {
        seed = seed * 6364136223846793005UL + 1442695040888963407UL;
        x[i] = centre[i % 3] +
               (double)(seed >> 11) / 9007199254740992.0 - 0.5;
    }
    for (size_t p = 0; p < NP; p++) { /* to d in [-2, 10) cm */
        cl_contact_point q;
        cl_pose P;
        cl_obstacle_pose(o, 0.0, &P);
        cl_obstacle_near(o, &P, x + 3 * p, INFINITY, NULL, &q);
        double move = q.d - (0.12 * (double)p / NP - 0.02);
        for (int i = 0; i < 3; i++)
            x[3 * p + i] -= move * q.n[i];
    }
    for (int step = 0; step < 200; step++) {
        cl_pose P;
        const double dmax = 0.01;
        cl_obstacle_pose(o, 1e-3 * step, &P);
        for (size_t i = 0; i < 3 * NP; i++) {
            seed = seed * 6364136223846793005UL + 1442695040888963407UL;
            x[i] += 2e-3 * ((double)(seed >> 11) / 9007199254740992.0 - 0.5);
        }
        size_t n = cl_obstacle_screen(o, &P, x, NP, dmax, mb, listed);
        memcpy(kept, listed, n * sizeof *kept);
        size_t nslim = cl_obstacle_near_slim(o, &P, x, dmax, mb, kept, n,
                                             slim), k = 0;
        for (size_t i = 0; i < n; i++) {
            size_t p = listed[i];
            cl_contact_point q;
            if (!cl_obstacle_near(o, &P, x + 3 * p, dmax, &ma[p], &q))
                continue;
            cr_assert_lt(k, nslim, "step %d: point %zu missing", step, p);
            cr_assert_eq(kept[k], p, "step %d", step);
            cr_assert(slim[k].d == q.d &&
                      !memcmp(slim[k].n, q.n, sizeof q.n) &&
                      !memcmp(slim[k].u, q.u, sizeof q.u),
                      "step %d, point %zu: d %.17g against %.17g", step, p,
                      slim[k].d, q.d);
            k++;
        }
        cr_assert_eq(k, nslim, "step %d", step);
        found += k;
    }
    cr_assert_gt(found, 200 * NP / 20, "%lu points found", found);
    free(ma);
    free(mb);
    free(ca);
    free(cb);
}

Test(obstacle, slim_points_are_the_full_ones)
{
    static const char *const shapes[][NSET] = {
        {"obstacle.o.shape = plane", "obstacle.o.point = 0.3, -1.2, 0.1",
         "obstacle.o.normal = 0.1, 1, -0.2",
         "obstacle.o.path = 0: 0, 0, 0; 1: 0.4, 0.2, 0", NULL},
        {"obstacle.o.shape = plane", "obstacle.o.point = 0, -1, 0",
         "obstacle.o.normal = 0, 1, 0", "obstacle.o.omega = 0.2, 0, 0.1",
         NULL},
        {"obstacle.o.shape = sphere", "obstacle.o.radius = 0.5",
         "obstacle.o.path = 0: 0, 0, 0; 1: 0.3, 0, 0", NULL},
        {"obstacle.o.shape = box", "obstacle.o.size = 1, 0.6, 0.8",
         "obstacle.o.omega = 0, 0.3, 0", NULL},
        {"obstacle.o.shape = mesh",
         "obstacle.o.file = problems/meshes/sphere.obj",
         "obstacle.o.scale = 0.5", NULL},
        {"obstacle.o.shape = mesh",
         "obstacle.o.file = problems/meshes/sphere.obj",
         "obstacle.o.scale = 0.5", "obstacle.o.omega = 0, 0.3, 0.1",
         "obstacle.o.path = 0: 0, 0, 0; 1: 0.2, 0, 0", NULL}};
    static const double centre[][3] = {{0.3, -1.2, 0.1}, {0, -1, 0},
                                       {0, 0, 0}, {0, 0, 0}, {0, 0, 0},
                                       {0, 0, 0}};
    for (size_t s = 0; s < sizeof shapes / sizeof *shapes; s++) {
        const char *sets[NSET] = {"obstacle.o.response = penalty",
                                  "obstacle.o.k = 1", NULL};
        for (size_t k = 0; shapes[s][k]; k++)
            sets[k + 2] = shapes[s][k];
        cl_obstacle o;
        make(&o, sets);
        slim_walk(&o, centre[s]);
        cl_obstacle_free(&o);
    }
}

/* The time of impact of the move x0 -> x1 (obstacle o static at t = 0). */
static double toi(const cl_obstacle *o, const double x0[3],
                  const double x1[3])
{
    cl_pose P;
    cl_obstacle_pose(o, 0.0, &P);
    return cl_obstacle_toi(o, &P, x0, &P, x1, 0.0);
}

#define BARRIER "obstacle.o.response = barrier", "obstacle.o.kappa = 1", \
                "obstacle.o.dhat = 0.01"

Test(obstacle, time_of_impact_plane_sphere_box)
{
    cl_obstacle o;
    const char *plane[NSET] = {"obstacle.o.shape = plane",
                               "obstacle.o.normal = 0, 1, 0", BARRIER, NULL};
    make(&o, plane);
    double a0[3] = {0.0, 0.3, 0.0}, a1[3] = {0.2, -0.1, 0.1};
    cr_expect_float_eq(toi(&o, a0, a1), 0.75, 1e-15); /* 0.3 / 0.4 */
    double a2[3] = {1.0, 0.05, 0.0};
    cr_expect_eq(toi(&o, a0, a2), INFINITY, "stays above");
    cl_obstacle_free(&o);
    const char *sphere[NSET] = {"obstacle.o.shape = sphere",
                                "obstacle.o.radius = 0.5", BARRIER, NULL};
    make(&o, sphere);
    double b0[3] = {-1.0, 0.3, 0.0}, b1[3] = {1.0, 0.3, 0.0};
    cr_expect_float_eq(toi(&o, b0, b1), 0.3, 1e-15); /* x = -0.4 */
    double c0[3] = {-1.0, 0.6, 0.0}, c1[3] = {1.0, 0.6, 0.0};
    cr_expect_eq(toi(&o, c0, c1), INFINITY, "passes above");
    double d1[3] = {-0.7, 0.3, 0.0};
    cr_expect_eq(toi(&o, b0, d1), INFINITY, "stops short");
    cl_obstacle_free(&o);
    const char *box[NSET] = {"obstacle.o.shape = box",
                             "obstacle.o.size = 2, 1, 1", BARRIER, NULL};
    make(&o, box);
    double e0[3] = {0.0, 1.5, 0.2}, e1[3] = {0.0, -0.5, 0.2};
    cr_expect_float_eq(toi(&o, e0, e1), 0.5, 1e-15); /* the top face */
    double f0[3] = {1.5, 1.5, 0.0}, f1[3] = {0.5, -0.5, 0.0};
    cr_expect_float_eq(toi(&o, f0, f1), 0.5, 1e-15); /* the edge x=1,y=.5 */
    double g0[3] = {1.5, 1.5, 0.0}, g1[3] = {1.5, -1.5, 0.0};
    cr_expect_eq(toi(&o, g0, g1), INFINITY, "passes beside");
    cl_obstacle_free(&o);
}

/* A cube mesh: a face hit, a crossing through an edge shared by two
 * triangles (found, not slipped through), a miss; and a plane moving up
 * 1 m in 1 s reaching a particle at rest 0.5 m above it at t = 0.5 s. */
Test(obstacle, time_of_impact_mesh_and_moving)
{
    char dir[512], file[800];
    oc_cube(dir, sizeof dir, file, sizeof file);
    cl_obstacle o;
    const char *mesh[NSET] = {"obstacle.o.shape = mesh", file, OC_CUBE_SCALE,
                              BARRIER, NULL};
    make(&o, mesh);
    double a0[3] = {0.2, 3.0, 0.1}, a1[3] = {0.2, -1.0, 0.1};
    cr_expect_float_eq(toi(&o, a0, a1), 0.5, 1e-15);
    /* through the diagonal x = z of the top quad's two triangles */
    double b0[3] = {0.2, 2.0, 0.2}, b1[3] = {0.2, 0.0, 0.2};
    cr_expect_float_eq(toi(&o, b0, b1), 0.5, 1e-12);
    double c0[3] = {1.5, 1.5, 0.0}, c1[3] = {1.5, -1.5, 0.0};
    cr_expect_eq(toi(&o, c0, c1), INFINITY, "passes beside");
    cl_obstacle_free(&o);
    tmp_rm_rf(dir);
    const char *moving[NSET] = {"obstacle.o.shape = plane",
                                "obstacle.o.normal = 0, 1, 0",
                                "obstacle.o.path = 0: 0, 0, 0; 1: 0, 1, 0",
                                BARRIER, NULL};
    make(&o, moving);
    cl_pose P0, P1;
    cl_obstacle_pose(&o, 0.0, &P0);
    cl_obstacle_pose(&o, 1.0, &P1);
    double x[3] = {0.3, 0.5, -0.2};
    cr_expect_float_eq(cl_obstacle_toi(&o, &P0, x, &P1, x, 0.0), 0.5, 1e-15);
    cl_obstacle_free(&o);
}

/* make() from the lines "key = value\n..." of [obstacle.o]. */
static void make_lines(cl_obstacle *o, const char *lines)
{
    char copy[1024], set[NSET][128];
    const char *sets[NSET + 1] = {NULL};
    int n = 0;
    snprintf(copy, sizeof copy, "%s", lines);
    for (char *l = strtok(copy, "\n"); l && n < NSET; l = strtok(NULL, "\n")) {
        snprintf(set[n], sizeof set[n], "obstacle.o.%s", l);
        sets[n] = set[n];
        n++;
    }
    make(o, sets);
}

Test(obstacle, constraint_response_and_ccd_are_read)
{
    cl_obstacle o;
    make_lines(&o, "shape = plane\nnormal = 0, 1, 0\nresponse = constraint\n"
                   "offset = 0.002\nmu = 0.3");
    cr_assert_eq(o.resp.kind, CL_RESPONSE_CONSTRAINT);
    cr_assert_eq(o.resp.offset, 0.002);
    cr_assert_eq(o.resp.mu, 0.3);
    cl_obstacle_free(&o);
    make_lines(&o, "shape = plane\nnormal = 0, 1, 0\nresponse = project\n"
                   "ccd = true");
    cr_assert(o.resp.ccd);
    cl_obstacle_free(&o);
}

/* A box 2 cm wide along x moving at 100 m/s along +x after a particle
 * that moves at 10 m/s along +x: over the step [0.01, 0.02] s their gap
 * of 0.5 m closes at s = 0.5 / 0.9; the hit point is the box's +x face
 * where the box is at 0.02 s.  A particle touching the face at the start
 * is left to the discrete check. */
Test(obstacle, sweep_meets_a_moving_box)
{
    cl_obstacle o;
    make_lines(&o, "shape = box\nsize = 0.02, 1, 1\n"
                   "path = 0: 0, 0, 0; 1: 100, 0, 0\nresponse = project\n"
                   "ccd = true");
    cl_pose P0, P1;
    cl_obstacle_pose(&o, 0.01, &P0);
    cl_obstacle_pose(&o, 0.02, &P1);
    /* the face at 1 + 0.01 = 1.01 at 0.01 s; the particle at 1.51 */
    double x0[3] = {1.51, 0.1, 0}, x1[3] = {1.61, 0.1, 0}, s, hit[3];
    cr_assert(cl_obstacle_sweep(&o, &P0, x0, &P1, x1, 0.0, &s, hit));
    cr_assert_float_eq(s, 0.5 / 0.9, 1e-12);
    cr_assert_float_eq(hit[0], 2.0 + 0.01, 1e-12);
    cr_assert_float_eq(hit[1], 0.1, 1e-15);
    double slow[3] = {1.515, 0.1, 0};   /* 0.465 m ahead at 0.0105 s */
    cl_obstacle_pose(&o, 0.0105, &P1);
    cr_assert_not(cl_obstacle_sweep(&o, &P0, x0, &P1, slow, 0.0, &s, hit));
    double on[3] = {1.01, 0.1, 0};      /* touching at the start */
    cl_obstacle_pose(&o, 0.02, &P1);
    cr_assert_not(cl_obstacle_sweep(&o, &P0, on, &P1, x1, 0.0, &s, hit));
    cl_obstacle_free(&o);
}
