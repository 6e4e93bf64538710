/* Pins from the problem file: groups, row/column selectors, prescribed
 * motion with a stop time; and the seeded initial imperfection. */
#include <criterion/criterion.h>

#include <math.h>
#include <string.h>

#include "io/config.h"
#include "system/model.h"

static cl_model *model_with(const char *const *sets, cl_error *err,
                            cl_status *rc)
{
    cl_config *cfg = cl_config_alloc();
    cl_model *m = NULL;
    cr_assert_not_null(cfg);
    for (size_t k = 0; sets[k]; k++)
        cr_assert_eq(cl_config_set(cfg, sets[k], err), CL_OK, "%s", err->msg);
    *rc = cl_model_create(cfg, &m, err);
    cl_config_free(cfg);
    return m;
}

static cl_model *model_ok(const char *const *sets)
{
    cl_error err = {0};
    cl_status rc;
    cl_model *m = model_with(sets, &err, &rc);
    cr_assert_eq(rc, CL_OK, "%s", err.msg);
    return m;
}

Test(pins, rows_columns_and_particles)
{
    static const char *const sets[] = {"cloth.nu=5", "cloth.nv=4",
                                       "pins.at=i=0 j=-1", "pins2.at=4,0",
                                       NULL};
    cl_model *m = model_ok(sets);
    const cl_cloth *c = cl_model_cloth(m);
    /* Row i = 0 (4), column j = 3 without (0,3) (4 more), and (4,0). */
    cr_assert_eq(c->npin, 9);
    cr_assert_eq(c->nfree, 20 - 9);
    for (int j = 0; j < 4; j++)
        cr_assert_lt(c->dof[cl_cloth_index(c, 0, j)], 0);
    for (int i = 0; i < 5; i++)
        cr_assert_lt(c->dof[cl_cloth_index(c, i, 3)], 0);
    cr_assert_lt(c->dof[cl_cloth_index(c, 4, 0)], 0);
    cr_assert_geq(c->dof[cl_cloth_index(c, 2, 1)], 0);
    cl_model_free(m);
}

Test(pins, motion_stops)
{
    static const char *const sets[] = {"cloth.n=3", "pins.at=0,0",
                                       "pins.velocity=0.5, 0, -1",
                                       "pins.stop=2", NULL};
    cl_model *m = model_ok(sets);
    const cl_cloth *c = cl_model_cloth(m);
    double x[27], v[27], xf[27], vf[27] = {0};
    memset(x, 0, sizeof x);
    memset(v, 0, sizeof v);
    cl_cloth_scatter(c, 1.0, x, v, xf, vf);
    cr_assert_float_eq(xf[0], 0.5, 1e-15);
    cr_assert_float_eq(xf[2], -1.0, 1e-15);
    cr_assert_float_eq(vf[0], 0.5, 0.0);
    cl_cloth_scatter(c, 5.0, x, v, xf, vf);
    cr_assert_float_eq(xf[0], 1.0, 1e-15, "held after the stop time");
    cr_assert_float_eq(xf[2], -2.0, 1e-15);
    cr_assert_float_eq(vf[0], 0.0, 0.0);
    cr_assert_float_eq(vf[2], 0.0, 0.0);
    cl_model_free(m);
    /* stop = never lifts it: the pin moves on */
    static const char *const never[] = {"cloth.n=3", "pins.at=0,0",
                                        "pins.velocity=0.5, 0, -1",
                                        "pins.stop=never", NULL};
    m = model_ok(never);
    cl_cloth_scatter(cl_model_cloth(m), 5.0, x, v, xf, vf);
    cr_assert_float_eq(xf[0], 2.5, 1e-15, "still moving at t = 5 s");
    cr_assert_float_eq(vf[2], -1.0, 0.0);
    cl_model_free(m);
}

/* The default stop is recorded (run.json, config.ini) as the value that
 * reads back as it: "never". */
static void find_stop(void *ctx, const char *sec, const char *key,
                      const char *value, bool given)
{
    if (!strcmp(sec, "pins") && !strcmp(key, "stop") && !given)
        *(const char **)ctx = value;
}

Test(pins, default_stop_is_recorded_as_never)
{
    cl_config *cfg = cl_config_alloc();
    cl_error err = {0};
    cl_model *m = NULL;
    cr_assert_eq(cl_config_set(cfg, "cloth.n=3", &err), CL_OK);
    cr_assert_eq(cl_model_create(cfg, &m, &err), CL_OK, "%s", err.msg);
    const char *stop = NULL;
    cl_config_resolved(cfg, find_stop, &stop);
    cr_assert_str_eq(stop, "never");
    cl_model_free(m);
    cl_config_free(cfg);
}

Test(pins, errors_name_the_key)
{
    static const char *const bad[][4] = {
        {"pins.at=0,0 x", NULL, NULL, "cannot read"},
        {"pins.at=i=70", NULL, NULL, "outside"},
        {"pins.at=0,0", "pins2.at=j=0", "pins2.velocity=1,0,0", "twice"},
        {"pins.stop=-1", NULL, NULL, "stop = \"-1\": expected a time in "
                                     "[0, 1e+12] s, or never"},
        {"pins.stop=nevermore", NULL, NULL, "or never"},
    };
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        const char *sets[4] = {bad[k][0], bad[k][1], bad[k][2], NULL};
        cl_error err = {0};
        cl_status rc;
        cl_model *m = model_with(sets, &err, &rc);
        cr_assert_eq(rc, CL_EINVAL, "%s: %d", bad[k][0], rc);
        cr_assert_null(m);
        cr_assert_not_null(strstr(err.msg, bad[k][3]), "\"%s\" lacks \"%s\"",
                           err.msg, bad[k][3]);
        cr_assert_not_null(strstr(err.msg, "[pins"), "%s", err.msg);
    }
}

Test(pins, perturbation_is_seeded_and_out_of_plane)
{
    static const char *const a[] = {"cloth.n=6", "init.perturb=1e-3",
                                    "init.seed=7", NULL};
    static const char *const b[] = {"cloth.n=6", "init.perturb=1e-3",
                                    "init.seed=8", NULL};
    cl_model *ma = model_ok(a), *ma2 = model_ok(a), *mb = model_ok(b);
    const cl_cloth *c = cl_model_cloth(ma);
    size_t n = 3 * c->nfree;
    double xa[108], va[108], xa2[108], va2[108], xb[108], vb[108], x0[108];
    cr_assert_eq(cl_model_initial_state(ma, xa, va), CL_OK);
    cr_assert_eq(cl_model_initial_state(ma2, xa2, va2), CL_OK);
    cr_assert_eq(cl_model_initial_state(mb, xb, vb), CL_OK);
    cl_cloth_gather(c, c->X0, x0);
    cr_assert_eq(memcmp(xa, xa2, n * sizeof *xa), 0, "same seed, same state");
    cr_assert_neq(memcmp(xa, xb, n * sizeof *xa), 0, "other seed differs");
    double amax = 0;
    for (size_t k = 0; k < n; k++) {
        if (k % 3 != 1)
            cr_assert_eq(xa[k], x0[k], "only y is perturbed");
        amax = fmax(amax, fabs(xa[k] - x0[k]));
        cr_assert_eq(va[k], 0.0);
    }
    cr_assert_leq(amax, 1e-3);
    cr_assert_gt(amax, 5e-4, "uniform noise reaches near its amplitude");
    cl_model_free(ma);
    cl_model_free(ma2);
    cl_model_free(mb);
}
