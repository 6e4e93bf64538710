/* Helpers of the contact-response tests (tests/test_penalty.c,
 * tests/test_barrier.c): an obstacle named "o" from "section.key = value"
 * assignments, the world point of a shape-frame point, and the cube mesh
 * of tests/cube_obj.h written to a directory.  Header only (static
 * inline), included after <criterion/criterion.h>; the checks at
 * several points of one obstacle. */
#ifndef CL_TESTS_OBSTACLECASE_H
#define CL_TESTS_OBSTACLECASE_H

#include <criterion/criterion.h>

#include <stdio.h>

#include "contact/obstacle.h"
#include "cube_obj.h"
#include "tmpdir.h"

/* An obstacle named "o" from assignments (NULL-terminated). */
static inline void oc_make(cl_obstacle *o, const char *const *sets)
{
    cl_error err = {0};
    cl_config *cfg = cl_config_alloc();
    cr_assert_not_null(cfg);
    for (size_t k = 0; sets[k]; k++)
        cr_assert_eq(cl_config_set(cfg, sets[k], &err), CL_OK, "%s", err.msg);
    cr_assert_eq(cl_obstacle_create(cfg, "obstacle.o", o, &err), CL_OK, "%s",
                 err.msg);
    cl_config_free(cfg);
}

/* The world point of the shape-frame point X (relative to the pivot q):
 * x = q + R X + s. */
static inline void oc_to_world(const cl_pose *P, const double q[3],
                               const double X[3], double x[3])
{
    for (int i = 0; i < 3; i++)
        x[i] = q[i] + P->s[i] + P->R[3 * i] * X[0] + P->R[3 * i + 1] * X[1] +
               P->R[3 * i + 2] * X[2];
}

/* check(o, t, x, what[k]) at the world points x of the shape-frame points
 * X[k] (relative to the pivot) of the obstacle made from `sets`, at time
 * t. */
typedef void (*oc_check_fn)(const cl_obstacle *o, double t,
                            const double x[3], const char *what);

static inline void oc_check_points(const char *const *sets, double t,
                                   const double (*X)[3],
                                   const char *const *what, int n,
                                   oc_check_fn check)
{
    cl_obstacle o;
    cl_pose P;
    oc_make(&o, sets);
    cl_obstacle_pose(&o, t, &P);
    for (int k = 0; k < n; k++) {
        double x[3];
        oc_to_world(&P, o.pivot, X[k], x);
        check(&o, t, x, what[k]);
    }
    cl_obstacle_free(&o);
}

/* The cube of side 2 centred at the origin (cube_obj scaled by 2) in a new
 * temporary directory dir: its "obstacle.o.file = ..." assignment into
 * file (and "obstacle.o.scale = 2" to add beside it). */
#define OC_CUBE_SCALE "obstacle.o.scale = 2"
static inline void oc_cube(char *dir, size_t dsize, char *file,
                           size_t fsize)
{
    char obj[700];
    tmp_mkdtemp(dir, dsize, "obstacle");
    snprintf(obj, sizeof obj, "%s/cube.obj", dir);
    tmp_put(obj, cube_obj);
    snprintf(file, fsize, "obstacle.o.file = %s", obj);
}

#endif
