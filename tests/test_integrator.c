/* Integrator registry, creation without a type, fixed-step bookkeeping
 * (cl_fixed_steps_to) and the statistics output (CSV rows parsed back,
 * human block). */
#include <criterion/criterion.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "integrators/integrator.h"

Test(integrator, find_by_name)
{
    const cl_integrator_type *a = cl_integrator_find("cvode-bdf");
    const cl_integrator_type *b = cl_integrator_find("symplectic-euler");
    cr_assert_not_null(a);
    cr_assert_not_null(b);
    cr_assert_str_eq(a->name, "cvode-bdf");
    cr_assert_not(a->fixed_step);
    cr_assert(b->fixed_step);
    cr_assert_null(cl_integrator_find("no-such-method"));
    cr_assert_null(cl_integrator_find(""));
    cr_assert_null(cl_integrator_find(NULL));
}

/* cl_integrator_create with what cl_integrator_find gives for an
 * unknown name, or without a system or options: CL_EINVAL, no state. */
Test(integrator, create_without_type_system_or_options)
{
    const cl_integrator_type *rk4 = cl_integrator_find("rk4");
    cl_integrator_opts o = {.dt = 1e-3};
    double x[3] = {0}, v[3] = {0};
    void *st = (void *)&o;
    cl_error err = {0};
    cr_assert_eq(cl_integrator_create(cl_integrator_find("nope"), NULL, &o,
                                      0.0, x, v, &st, &err), CL_EINVAL);
    cr_assert_null(st);
    cr_assert(strstr(err.msg, "unknown name"), "%s", err.msg);
    cr_assert_eq(cl_integrator_create(rk4, NULL, &o, 0.0, x, v, &st, &err),
                 CL_EINVAL);
    cr_assert(strstr(err.msg, "system"), "%s", err.msg);
    cl_system sys = {0};
    cr_assert_eq(cl_integrator_create(rk4, &sys, NULL, 0.0, x, v, &st, &err),
                 CL_EINVAL);
    cr_assert(strstr(err.msg, "options"), "%s", err.msg);
    cr_assert_null(st);
}

Test(integrator, registry_rows_complete_and_unique)
{
    size_t n = 0;
    for (; cl_integrator_registry[n]; n++) {
        const cl_integrator_type *t = cl_integrator_registry[n];
        cr_assert(t->name && t->name[0] && t->doc && t->doc[0]);
        cr_assert(t->create && t->advance && t->stats && t->free, "%s",
                  t->name);
        cr_assert_not_null(t->region, "%s", t->name);
        cr_assert_eq(cl_integrator_find(t->name), t, "%s", t->name);
        for (size_t j = 0; j < n; j++)
            cr_assert_str_neq(cl_integrator_registry[j]->name, t->name);
    }
    cr_assert_geq(n, 2);
}

/* A region with a step limit (Taylor, symplectic) belongs to a fixed-step
 * method, and a Taylor polynomial has the degree region.h allows. */
Test(integrator, regions_fit_the_methods)
{
    for (size_t i = 0; cl_integrator_registry[i]; i++) {
        const cl_integrator_type *t = cl_integrator_registry[i];
        cl_region_kind k = t->region->kind;
        if (k == CL_REGION_TAYLOR || k == CL_REGION_SYMPLECTIC)
            cr_assert(t->fixed_step, "%s", t->name);
        if (k == CL_REGION_TAYLOR)
            cr_assert(t->region->degree >= 1 && t->region->degree <= 4,
                      "%s", t->name);
        if (k == CL_REGION_SECTOR)
            cr_assert(t->region->alpha > 0 && t->region->alpha <= 90,
                      "%s", t->name);
    }
}

Test(integrator, fixed_steps_accepts_multiples)
{
    long k = -1;
    cl_error err;
    cr_assert_eq(cl_fixed_steps_to(0.3, 0.1, 0, &k, &err), CL_OK);
    cr_assert_eq(k, 3);
    cr_assert_eq(cl_fixed_steps_to(0.3, 0.1, 1, &k, &err), CL_OK);
    cr_assert_eq(k, 2);
    cr_assert_eq(cl_fixed_steps_to(0.3, 0.1, 3, &k, &err), CL_OK);
    cr_assert_eq(k, 0);
    cr_assert_eq(cl_fixed_steps_to(0.0, 5e-4, 0, &k, &err), CL_OK);
    cr_assert_eq(k, 0);
    cr_assert_eq(cl_fixed_steps_to(1000.0, 1e-3, 0, &k, &err), CL_OK);
    cr_assert_eq(k, 1000000);
    /* 7 * 0.7 accumulated by repeated addition is not 4.9 exactly. */
    double t = 0;
    for (int i = 0; i < 7; i++)
        t += 0.7;
    cr_assert_eq(cl_fixed_steps_to(t, 0.7, 2, &k, &err), CL_OK);
    cr_assert_eq(k, 5);
}

Test(integrator, fixed_steps_rejects_non_multiples_backwards_bad_dt)
{
    long k = 99;
    cl_error err;
    cr_assert_eq(cl_fixed_steps_to(0.25, 0.1, 0, &k, &err), CL_EINVAL);
    cr_assert_not_null(strstr(err.msg, "multiple"), "%s", err.msg);
    cr_assert_eq(cl_fixed_steps_to(1.0 + 1e-6, 0.1, 0, &k, &err), CL_EINVAL);
    cr_assert_eq(cl_fixed_steps_to(0.1, 0.1, 2, &k, &err), CL_EINVAL);
    cr_assert_not_null(strstr(err.msg, "behind"), "%s", err.msg);
    cr_assert_eq(cl_fixed_steps_to(-0.2, 0.1, 0, &k, &err), CL_EINVAL);
    cr_assert_eq(cl_fixed_steps_to(1.0, 0.0, 0, &k, &err), CL_EINVAL);
    cr_assert_eq(cl_fixed_steps_to(1.0, -0.1, 0, &k, &err), CL_EINVAL);
    cr_assert_eq(cl_fixed_steps_to(1.0, NAN, 0, &k, &err), CL_EINVAL);
    cr_assert_eq(cl_fixed_steps_to(INFINITY, 0.1, 0, &k, &err), CL_EINVAL);
    cr_assert_eq(cl_fixed_steps_to(1e300, 1e-300, 0, &k, &err), CL_EINVAL);
    cr_assert_eq(k, 99, "nsteps must be untouched on failure");
}

static cl_stats sample_stats(void)
{
    return (cl_stats){.steps = 11, .rhs_evals = 22, .jac_evals = 3,
                      .lin_setups = 4, .lin_solves = 15, .lin_iters = 0,
                      .nonlin_iters = 15, .nonlin_fails = 1, .err_fails = 2,
                      .symbolic_facts = 1, .lin_fallbacks = 2,
                      .wall = 0.5, .cpu = 0.25};
}

/* cl_stats_print's output in a malloc'd string. */
static char *stats_text(const cl_stats *s, bool human)
{
    char *buf = NULL;
    size_t len = 0;
    FILE *fp = open_memstream(&buf, &len);
    cr_assert_not_null(fp);
    cl_stats_print(s, fp, human);
    cr_assert_eq(fclose(fp), 0);
    return buf;
}

/* An adaptive method's output time: refused when not finite or behind
 * the current time, naming the method (before, CVODE's, IDA's and
 * ARKODE's said that NaN "lies behind the last one"). */
Test(integrator, output_time_checked)
{
    cl_error err;
    cr_assert_eq(cl_output_time_check("m", 0.5, 0.5, &err), CL_OK);
    cr_assert_eq(cl_output_time_check("m", 0.6, 0.5, &err), CL_OK);
    cr_assert_eq(cl_output_time_check("m", NAN, 0.5, &err), CL_EINVAL);
    cr_assert_str_eq(err.msg, "m: output time nan is not finite");
    cr_assert_eq(cl_output_time_check("m", INFINITY, 0.5, &err), CL_EINVAL);
    cr_assert_str_eq(err.msg, "m: output time inf is not finite");
    cr_assert_eq(cl_output_time_check("m", 0.25, 0.5, &err), CL_EINVAL);
    cr_assert_str_eq(err.msg, "m: output time 0.25 lies behind the current "
                     "time 0.5");
}

Test(integrator, stats_csv_rows_parse_back)
{
    cl_stats s = sample_stats();
    char *buf = stats_text(&s, false);
    const struct { const char *name; double value; } want[] = {
        {"steps", 11}, {"rhs_evals", 22}, {"jac_evals", 3},
        {"lin_setups", 4}, {"lin_solves", 15}, {"lin_iters", 0},
        {"nonlin_iters", 15}, {"nonlin_fails", 1}, {"err_fails", 2},
        {"symbolic_facts", 1}, {"lin_fallbacks", 2}};
    size_t nw = sizeof want / sizeof want[0], rows = 0;
    for (char *line = strtok(buf, "\n"); line; line = strtok(NULL, "\n")) {
        char *comma = strchr(line, ',');
        cr_assert_not_null(comma, "row without comma: %s", line);
        *comma = '\0';
        size_t i = 0;
        while (i < nw && strcmp(want[i].name, line) != 0)
            i++;
        cr_assert_lt(i, nw, "unexpected row %s", line);
        cr_assert_float_eq(strtod(comma + 1, NULL), want[i].value, 1e-12,
                           "%s", line);
        rows++;
    }
    cr_assert_eq(rows, nw);
    free(buf);
}

/* lin_recoveries (amg's recovered solves) is a row only when not 0, so
 * that the stats.csv of every other run keeps its bytes. */
Test(integrator, stats_recoveries_row_only_when_counted)
{
    cl_stats s = sample_stats();
    char *buf = stats_text(&s, false);
    cr_assert_null(strstr(buf, "recover"), "%s", buf);
    free(buf);
    s.lin_recoveries = 3;
    buf = stats_text(&s, false);
    cr_assert_not_null(strstr(buf, "\nlin_recoveries,3\n"), "%s", buf);
    free(buf);
    buf = stats_text(&s, true);
    const char *row = strstr(buf, "linear solve recoveries");
    cr_assert_not_null(row, "%s", buf);
    cr_assert_eq(strtol(row + strlen("linear solve recoveries"), NULL, 10),
                 3);
    free(buf);
}

Test(integrator, stats_human_block_one_line_per_counter)
{
    cl_stats s = sample_stats();
    char *buf = stats_text(&s, true);
    size_t lines = 0, width = 0;
    for (char *line = strtok(buf, "\n"); line; line = strtok(NULL, "\n")) {
        cr_assert_null(strchr(line, ','), "%s", line);
        if (lines++ == 0)
            width = strlen(line);
        cr_assert_eq(strlen(line), width, "not aligned: '%s'", line);
    }
    cr_assert_eq(lines, 13);
    free(buf);
}

/* A counter the method's library does not expose prints as "n/a" in the
 * human block (still aligned) and "NA" in CSV, never as a number. */
Test(integrator, stats_not_available_prints_na)
{
    cl_stats s = sample_stats();
    s.nonlin_iters = CL_STAT_NA;
    for (int human = 0; human < 2; human++) {
        char *buf = stats_text(&s, human);
        const char *want =
            human ? "nonlinear iterations" : "\nnonlin_iters,NA\n";
        char *row = strstr(buf, want);
        cr_assert_not_null(row, "%s", buf);
        cr_assert_null(strstr(buf, "-1"), "%s", buf);
        if (human) {
            char *eol = strchr(row, '\n');
            cr_assert_not_null(eol);
            cr_assert_eq(strncmp(eol - 3, "n/a", 3), 0, "%s", buf);
            cr_assert_eq(eol - row, strchr(buf, '\n') - buf - 2, "%s", buf);
        }
        free(buf);
    }
}

/* The name of the linear solver gets a row of its own when reported. */
Test(integrator, stats_linsol_row_when_reported)
{
    cl_stats s = sample_stats();
    snprintf(s.linsol, sizeof s.linsol, "auto:pcg");
    for (int human = 0; human < 2; human++) {
        char *buf = stats_text(&s, human);
        const char *want = human ? "linear solver" : "\nlinsol,auto:pcg\n";
        cr_assert_not_null(strstr(buf, want), "%s", buf);
        cr_assert_not_null(strstr(buf, "auto:pcg"), "%s", buf);
        free(buf);
    }
}
