/* A collected sweep table as a study's runs (analysis/sweep_table.h):
 * rows selected by the problem's axis values, stability brackets and
 * convergence levels from them, and the command line's --from-sweep. */
#include <criterion/criterion.h>

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "analysis/sweep_table.h"
#include "integrators/integrator.h"
#include "io/config.h"
#include "runcli.h"
#include "timelimit.h"

static char tmp[512];

static void setup(void)
{
    time_limit(120);
    tmp_mkdtemp(tmp, sizeof tmp, "sweeptab");
}

static void teardown(void)
{
    tmp_rm_rf(tmp);
}

TestSuite(sweep_table, .init = setup, .fini = teardown);

#define HEAD "id,role,integrator,cloth.n,run.dt,run.t_end,status,exit," \
             "t_reached,steps,rhs_evals,cpu,err_x,err_v,problem\n"

/* rk4 on two sizes: at n = 6 stable up to 4e-3, blown up at 8e-3 and
 * 1.6e-2, one run missing and one refused; symplectic-euler never
 * unstable. */
static const char *const table =
    HEAD
    "a1,job,rk4,6,0.001,2,complete,ok,2,2000,8000,0.5,4e-9,1e-8,@P@\n"
    "a2,job,rk4,6,0.002,2,complete,ok,2,1000,4000,0.25,6.4e-8,1.6e-7,@P@\n"
    "a3,job,rk4,6,0.004,2,complete,ok,2,500,2000,0.125,1.024e-6,2.56e-6,@P@\n"
    "a4,job,rk4,6,0.008,2,failed,blow-up,0.72,NA,NA,NA,NA,NA,@P@\n"
    "a5,job,rk4,6,0.016,2,failed,interrupted,0.1,NA,NA,NA,NA,NA,@P@\n"
    "a6,job,rk4,6,0.0005,2,missing,missing,NA,NA,NA,NA,NA,NA,@P@\n"
    "a7,job,rk4,6,0.03,2,failed,usage,NA,NA,NA,NA,NA,NA,@P@\n"
    "b1,job,rk4,8,0.001,2,failed,blow-up,1.5,NA,NA,NA,NA,NA,@P@\n"
    "c1,job,symplectic-euler,6,0.001,2,complete,ok,2,2000,2000,0.1,1e-3,"
    "1e-2,@P@\n"
    "c2,job,symplectic-euler,6,0.002,2,complete,ok,2,1000,1000,0.05,2e-3,"
    "2e-2,@P@\n"
    "r1,reference,cvode-bdf,6,NA,2,complete,ok,2,900,1800,2,NA,NA,@P@\n";

/* A table whose @P@ are the absolute path of `problem`, the problem its
 * runs are of (the studies check it). */
static void put_table(const char *path, const char *text,
                      const char *problem)
{
    static char out[1 << 14];
    char *hang = realpath(problem, NULL);
    cr_assert_not_null(hang, "%s", problem);
    size_t u = 0;
    for (const char *p = text; *p && u + strlen(hang) + 1 < sizeof out;)
        if (!strncmp(p, "@P@", 3)) {
            u += (size_t)sprintf(out + u, "%s", hang);
            p += 3;
        } else {
            out[u++] = *p++;
        }
    out[u] = '\0';
    free(hang);
    tmp_put(path, out);
}

/* The table `text` selected for a problem of no keys with the sets
 * (the rows are selected by them alone); the configuration after the
 * selection into *kept (NULL: freed). */
static void load_text(cl_sweep_table *t, const char *text,
                      const char *const *sets, cl_status want,
                      cl_config **kept, cl_error *err)
{
    char path[1024], problem[1024];
    snprintf(problem, sizeof problem, "%s/p.ini", tmp);
    tmp_put(problem, "[x]\ny = 1\n");
    snprintf(path, sizeof path, "%s/t.csv", tmp);
    put_table(path, text, problem);
    cl_config *cfg = cl_config_alloc();
    cr_assert_eq(cl_config_load(cfg, problem, err), CL_OK);
    for (int k = 0; sets[k]; k++)
        cr_assert_eq(cl_config_set(cfg, sets[k], err), CL_OK);
    cr_assert_eq(cl_sweep_table_read(path, t, err), CL_OK, "%s", err->msg);
    cr_assert_eq(cl_sweep_table_select(t, cfg, NULL, err), want, "%s",
                 err->msg);
    if (kept)
        *kept = cfg;
    else
        cl_config_free(cfg);
}

static void load(cl_sweep_table *t, const char *const *sets, cl_status want,
                 cl_error *err)
{
    load_text(t, table, sets, want, NULL, err);
}

/* An axis of one value that the command's configuration does not give
 * becomes the command's (a problem key), so that its model is the one
 * the sweep's runs had: before, a constant init.time = 0.15 left a study
 * at t = 0 with rows of runs from 0.15.  NA (the runs had the file's
 * value) is not taken; t_end, read before the table, must be given. */
Test(sweep_table, a_constant_axis_is_the_commands_value)
{
    static const char *const one =
        "id,role,integrator,type1.ks,init.time,init.seed,run.t_end,status,"
        "exit,t_reached,steps,rhs_evals,cpu,err_x,err_v,problem\n"
        "a1,job,rk4,250,0.15,NA,2,complete,ok,2,2000,8000,0.5,NA,NA,@P@\n";
    cl_sweep_table t;
    cl_error err = {0};
    cl_config *cfg;
    load_text(&t, one, (const char *const[]){"run.t_end=2", NULL}, CL_OK,
              &cfg, &err);
    cr_assert_str_eq(cl_config_string(cfg, "type1", "ks", "none"), "250");
    cr_assert_str_eq(cl_config_string(cfg, "init", "time", "none"), "0.15");
    cr_assert_str_eq(cl_config_string(cfg, "init", "seed", "none"), "none");
    cl_config_free(cfg);
    cl_sweep_table_free(&t);
    load_text(&t, one, (const char *const[]){NULL}, CL_EINVAL, NULL, &err);
    cr_assert(strstr(err.msg, "run.t_end = 2, which neither the problem nor "
                              "the command gives"), "%s", err.msg);
    cl_sweep_table_free(&t);
}

Test(sweep_table, stability_bracket_from_rows)
{
    cl_sweep_table t;
    cl_error err = {0};
    cl_stab_result r;
    load(&t, (const char *const[]){"cloth.n=6", "run.t_end=2", NULL}, CL_OK,
         &err);
    const cl_integrator_type *rk4 = cl_integrator_find("rk4");
    cr_assert_eq(cl_stab_from_sweep(&t, "rk4", rk4, &r, &err), CL_OK, "%s",
                 err.msg);
    /* the missing, the refused and the interrupted runs are no trials
     * (a run stopped by a signal or a budget says nothing of the step) */
    cr_assert_eq(r.ntrial, 4);
    cr_assert_eq(r.trial[0].dt, 0.008);
    cr_assert_eq(r.trial[3].dt, 0.001);
    cr_assert_eq(r.dt_unstable, 0.008);
    cr_assert_eq(r.dt_stable, 0.004);
    cr_assert_eq(r.trial[r.failed].rc, CL_EBLOWUP);
    cr_assert_str_eq(r.trial[r.failed].why.msg,
                     "failed at t = 0.72 s (blow-up)");
    cr_assert_eq(r.trial[1].stats.steps, 500);
    cr_assert_eq(r.trial[1].stats.cpu, 0.125);
    cl_stab_result se;
    cr_assert_eq(cl_stab_from_sweep(&t, "symplectic-euler",
                                    cl_integrator_find("symplectic-euler"),
                                    &se, &err), CL_OK);
    cr_assert(isnan(se.dt_unstable));
    cr_assert_eq(se.dt_stable, 0.002);
    cr_assert_eq(se.failed, -1);
    cl_sweep_table_free(&t);
}

/* Errors 4^-k... against dt halving: order 4 between every pair. */
Test(sweep_table, convergence_levels_from_rows)
{
    cl_sweep_table t;
    cl_error err = {0};
    cl_conv_result r;
    load(&t, (const char *const[]){"cloth.n=6", "run.t_end=2", NULL}, CL_OK,
         &err);
    cr_assert_eq(cl_conv_from_sweep(&t, "rk4", cl_integrator_find("rk4"), &r,
                                    &err), CL_OK, "%s", err.msg);
    cr_assert_eq(r.nlev, 7);
    cr_assert_eq(r.lev[0].param, 0.03);
    cr_assert_eq(r.lev[0].rc, CL_EBLOWUP);
    cr_assert_str_eq(r.lev[0].why.msg, "failed (usage)");
    cr_assert_eq(r.nfit, 3);
    cr_assert_float_eq(r.lev[4].order, 4.0, 1e-12);
    cr_assert_float_eq(r.lev[5].order, 4.0, 1e-12);
    cr_assert_float_eq(r.slope_x, 4.0, 1e-12);
    cr_assert_float_eq(r.slope_v, 4.0, 1e-12);
    cr_assert(!r.lev[6].fitted); /* missing */
    cl_sweep_table_free(&t);
}

Test(sweep_table, rows_must_name_one_value_of_an_axis)
{
    cl_sweep_table t;
    cl_error err = {0};
    load(&t, (const char *const[]){NULL}, CL_EINVAL, &err);
    cr_assert(strstr(err.msg, "the sweep has several values of cloth.n (6, "
                              "8, ...): give one with --set cloth.n=VALUE"),
              "%s", err.msg);
    cl_sweep_table_free(&t);
    load(&t, (const char *const[]){"cloth.n=12", NULL}, CL_OK, &err);
    cl_stab_result r;
    cr_assert_eq(cl_stab_from_sweep(&t, "rk4", cl_integrator_find("rk4"), &r,
                                    &err), CL_EINVAL);
    cr_assert(strstr(err.msg, "no runs of rk4"), "%s", err.msg);
    cl_sweep_table_free(&t);
}

/* An empty name in the list of tables (--table '', --from-sweep A.csv,,B)
 * is refused: read as no table, it gave no rows and nothing to refine. */
/* A line longer than 1 MB is refused as it is read, with its line: a row
 * of the first table, the header of the second (before: its columns were
 * said not to be the first's); the rows of a table count from its own
 * line 2 (before: from the rows of the tables before it). */
Test(sweep_table, overlong_line_refused)
{
    static char text[(1 << 20) + 4096];
    char first[1100], second[1100], list[2300];
    cl_sweep_table t;
    cl_error err = {0};
    snprintf(first, sizeof first, "%s/t.csv", tmp);
    snprintf(second, sizeof second, "%s/u.csv", tmp);
    snprintf(list, sizeof list, "%s,%s", first, second);
    put_table(first, table, "problems/hang.ini");
    size_t n = (size_t)sprintf(text, HEAD "a1,job,rk4,6,0.001,2,complete,");
    memset(text + n, 'x', 1 << 20);
    strcpy(text + n + (1 << 20), "\n");
    tmp_put(second, text);
    cr_assert_eq(cl_sweep_table_read(second, &t, &err), CL_EPARSE);
    cr_assert(strstr(err.msg, "u.csv:2: a line longer than 1048576 bytes"),
              "%s", err.msg);
    cl_sweep_table_free(&t);
    memset(text, 'x', (1 << 20) + 10);
    strcpy(text + (1 << 20) + 10, "\n");
    tmp_put(second, text);
    cr_assert_eq(cl_sweep_table_read(list, &t, &err), CL_EPARSE);
    cr_assert(strstr(err.msg, "u.csv:1: a line longer"), "%s", err.msg);
    cl_sweep_table_free(&t);
    tmp_put(second, HEAD "a1,job,rk4,6\n");
    cr_assert_eq(cl_sweep_table_read(list, &t, &err), CL_EPARSE);
    cr_assert(strstr(err.msg, "u.csv:2: 4 fields"), "%s", err.msg);
    cl_sweep_table_free(&t);
}

Test(sweep_table, empty_table_names_are_refused)
{
    char list[1200];
    cl_sweep_table t;
    cl_error err = {0};
    snprintf(list, sizeof list, "%s/t.csv", tmp);
    put_table(list, table, "problems/hang.ini");
    cr_assert_eq(cl_sweep_table_read("", &t, &err), CL_EINVAL);
    cr_assert(strstr(err.msg, "an empty name in the list of tables"), "%s",
              err.msg);
    cl_sweep_table_free(&t);
    snprintf(list, sizeof list, "%s/t.csv,,%s/t.csv", tmp, tmp);
    cr_assert_eq(cl_sweep_table_read(list, &t, &err), CL_EINVAL);
    cr_assert(strstr(err.msg, "an empty name"), "%s", err.msg);
    cl_sweep_table_free(&t);
    snprintf(list, sizeof list, "%s/t.csv,", tmp);
    cr_assert_eq(cl_sweep_table_read(list, &t, &err), CL_EINVAL);
    cl_sweep_table_free(&t);
    snprintf(list, sizeof list, "%s/t.csv,%s/t.csv", tmp, tmp);
    cr_assert_eq(cl_sweep_table_read(list, &t, &err), CL_OK, "%s", err.msg);
    cr_assert_eq(t.nrow, 22);
    cl_sweep_table_free(&t);
}

/* A level is one run: an atol axis crossed with rtol (not following it)
 * gives two runs at one rtol, refused (before: both taken as levels, an
 * order of inf between them). */
Test(sweep_table, two_runs_at_one_level_are_refused)
{
    char path[1024], problem[1024];
    snprintf(problem, sizeof problem, "%s/p.ini", tmp);
    tmp_put(problem, "[x]\ny = 1\n");
    snprintf(path, sizeof path, "%s/atol.csv", tmp);
    put_table(path, "id,role,integrator,run.rtol,run.atol,status,exit,"
                    "t_reached,steps,err_x,err_v,problem\n"
                    "a,job,cvode-bdf,1e-4,1e-6,complete,ok,1,10,1e-5,1e-4,@P@\n"
                    "b,job,cvode-bdf,1e-4,1e-8,complete,ok,1,12,2e-6,3e-5,@P@\n"
                    "c,job,cvode-bdf,1e-5,1e-6,complete,ok,1,20,9e-7,8e-6,@P@\n",
              problem);
    cl_config *cfg = cl_config_alloc();
    cl_error err = {0};
    cl_sweep_table t;
    cr_assert_eq(cl_config_load(cfg, problem, &err), CL_OK);
    cr_assert_eq(cl_sweep_table_read(path, &t, &err), CL_OK, "%s", err.msg);
    cr_assert_eq(cl_sweep_table_select(&t, cfg, NULL, &err), CL_OK, "%s",
                 err.msg);
    cl_conv_result r;
    cr_assert_eq(cl_conv_from_sweep(&t, "cvode-bdf",
                                    cl_integrator_find("cvode-bdf"), &r,
                                    &err), CL_EINVAL);
    cr_assert(strstr(err.msg, "two runs of cvode-bdf at run.rtol = 0.0001"),
              "%s", err.msg);
    cl_sweep_table_free(&t);
    cl_config_free(cfg);
}

/* The command line: the study's table from the sweep's rows of n = 6. */
Test(sweep_table, stability_cli_from_sweep)
{
    char path[1024], out[1024], csv[1300], text[4096];
    snprintf(path, sizeof path, "%s/t.csv", tmp);
    put_table(path, table, "problems/hang.ini");
    snprintf(out, sizeof out, "%s/stab", tmp);
    cli_result r;
    cli_run(&r, "stability", "hang", "--set", "cloth.n=6", "--t-end", "2",
            "--integrator", "rk4,symplectic-euler", "--from-sweep", path,
            "--out", out, NULL);
    cli_assert_ok(&r);
    cr_assert(strstr(r.out, "rk4                      0.004      -       0.008"
                            "     4  failed at t = 0.72 s (blow-up)\n"), "%s",
              r.out);
    cr_assert(strstr(r.out, "symplectic-euler   stable at dt_max = 0.002 (2 "
                            "runs, d/L -)\n"), "%s", r.out);
    cli_result_free(&r);
    /* another problem's table, and a model key the sweep's runs did not
     * have, are refused: before, hang's numbers were printed under
     * spring2's name, and under ks = 300 */
    cli_run(&r, "stability", "spring2", "--t-end", "2", "--integrator",
            "rk4", "--from-sweep", path, "--out", out, NULL);
    cli_assert_error(&r, 0, "its runs are of", "hang.ini, not of",
                     "spring2.ini", NULL);
    cli_result_free(&r);
    cli_run(&r, "stability", "hang", "--set", "cloth.n=6", "--set",
            "type1.ks=300", "--t-end", "2", "--integrator", "rk4",
            "--from-sweep", path, "--out", out, NULL);
    cli_assert_error(&r, 0, "--set type1.ks, yet it is no axis", NULL);
    cli_result_free(&r);
    /* the search's own options, which the table does not use, are
     * refused (before: ignored, the output unchanged); so are
     * convergence's levels */
    static const char *const own[][4] = {
        {"stability", "--dt-max", "1e-3", "--dt-max ([stability] dt_max) "
         "goes with a search of its own (not --from-sweep)"},
        {"convergence", "--levels", "3", "--levels ([convergence] levels) "
         "goes with levels run here (not --from-sweep)"}};
    for (int k = 0; k < 2; k++) {
        cli_run(&r, own[k][0], "hang", "--set", "cloth.n=6", "--t-end", "2",
                "--integrator", "rk4", "--from-sweep", path, own[k][1],
                own[k][2], "--out", out, NULL);
        cli_assert_error(&r, 0, own[k][3], NULL);
        cli_result_free(&r);
    }
    /* the study's own keys are no model's; a sweep planned on another
     * machine names its problem by a path not here: its name decides */
    char moved[1200], out2[1200];
    snprintf(moved, sizeof moved, "%s/moved.csv", tmp);
    snprintf(out2, sizeof out2, "%s/stab-moved", tmp);
    static char text2[1 << 14];
    tmp_slurp(path, text2, sizeof text2);
    char *hang = realpath("problems/hang.ini", NULL);
    cr_assert_not_null(hang);
    FILE *fp = fopen(moved, "w");
    cr_assert_not_null(fp);
    for (const char *p = text2; *p;)
        if (!strncmp(p, hang, strlen(hang))) {
            fputs("/elsewhere/problems/hang.ini", fp);
            p += strlen(hang);
        } else {
            fputc(*p++, fp);
        }
    fclose(fp);
    free(hang);
    cli_run(&r, "stability", "hang", "--set", "cloth.n=6", "--set",
            "stability.checks=20", "--t-end", "2", "--integrator", "rk4",
            "--from-sweep", moved, "--out", out2, NULL);
    cli_assert_ok(&r);
    cr_assert(strstr(r.out, "rk4                      0.004      -       0.008"
                            "     4  failed at t = 0.72 s (blow-up)\n"), "%s",
              r.out);
    cli_result_free(&r);
    snprintf(csv, sizeof csv, "%s/stability.csv", out);
    tmp_slurp(csv, text, sizeof text);
    cr_assert_eq(cli_count_lines(text), 1 + 4 + 2);
    /* the moved table's rows: rk4's four */
    snprintf(csv, sizeof csv, "%s/stability.csv", out2);
    tmp_slurp(csv, text, sizeof text);
    cr_assert_eq(cli_count_lines(text), 1 + 4);
}

/* stability --axis on a small hang: symplectic Euler's limit falls as
 * ks^(-1/2) (the stiffest Type1 spring, h < 2 / w_max with w_max ~
 * sqrt(ks)): the fitted slope of the measured brackets within 0.1 of
 * -1/2, the spectrum's exactly -1/2, and the measured limit above the
 * prediction at rest by less than 1.6x. */
Test(sweep_table, stability_axis_slope_is_minus_one_half)
{
    char out[1024], csv[1100], text[4096];
    snprintf(out, sizeof out, "%s/axis", tmp);
    cli_result r;
    cli_run(&r, "stability", "hang", "--set", "cloth.n=6", "--t-end", "0.2",
            "--integrator", "symplectic-euler", "--axis",
            "type1.ks=logspace(3, 5, 3)", "--out", out, NULL);
    cli_assert_ok(&r);
    double measured, predicted;
    const char *s = strstr(r.out, "\nsymplectic-euler    ");
    s = s ? strstr(s + 1, "\nsymplectic-euler    ") : NULL;
    s = s ? strstr(s + 1, "\nsymplectic-euler    ") : NULL;
    s = s ? strstr(s + 1, "\nsymplectic-euler    ") : NULL; /* the slope */
    cr_assert(s && sscanf(s, " symplectic-euler %lf %lf", &measured,
                          &predicted) == 2, "%s", r.out);
    cr_assert_float_eq(measured, -0.5, 0.1, "%s", r.out);
    cr_assert_float_eq(predicted, -0.5, 1e-3, "%s", r.out);
    cli_result_free(&r);
    snprintf(csv, sizeof csv, "%s/limits.csv", out);
    tmp_slurp(csv, text, sizeof text);
    cr_assert_eq(cli_count_lines(text), 1 + 3);
    double ks, lo, hi, pred;
    const char *row = strstr(text, "symplectic-euler,10000,");
    cr_assert(row && sscanf(row, "symplectic-euler,%lf,%lf,%lf,%lf", &ks,
                            &lo, &hi, &pred) == 4, "%s", text);
    cr_assert(lo >= pred && hi < 1.6 * pred, "%s", text);
}

/* The same from a sweep over type1.ks x dt: each value's rows. */
Test(sweep_table, stability_axis_from_sweep)
{
    char path[1024], out[1024];
    snprintf(path, sizeof path, "%s/ks.csv", tmp);
    put_table(path, "id,role,integrator,cloth.n,type1.ks,run.dt,status,"
                    "exit,t_reached,steps,cpu,problem\n"
                    "a,job,rk4,6,1000,0.002,complete,ok,0.2,100,0.1,@P@\n"
                    "b,job,rk4,6,1000,0.004,failed,blow-up,0.1,NA,NA,@P@\n"
                    "c,job,rk4,6,4000,0.001,complete,ok,0.2,200,0.1,@P@\n"
                    "d,job,rk4,6,4000,0.002,failed,blow-up,0.1,NA,NA,@P@\n",
              "problems/hang.ini");
    snprintf(out, sizeof out, "%s/axis", tmp);
    cli_result r;
    cli_run(&r, "stability", "hang", "--set", "cloth.n=6", "--t-end", "0.2",
            "--integrator", "rk4", "--axis", "type1.ks=1000,4000",
            "--from-sweep", path, "--out", out, NULL);
    cli_assert_ok(&r);
    cr_assert(strstr(r.out, "rk4                      1000       0.002 "
                            "      0.004"), "%s", r.out);
    cr_assert(strstr(r.out, "rk4                      4000       0.001 "
                            "      0.002"), "%s", r.out);
    cr_assert(strstr(r.out, "rk4                                  -0.500 "
                            "     -0.500"), "%s", r.out);
    cli_result_free(&r);
    /* a key the problem does not have is refused, not searched under its
     * name with the problem unchanged */
    cli_run(&r, "stability", "hang", "--set", "cloth.n=6", "--t-end", "0.2",
            "--integrator", "rk4", "--axis", "type1.kz=1000,4000",
            "--from-sweep", path, "--out", out, NULL);
    cli_assert_error(&r, 0, "--axis: unknown key [type1] kz", NULL);
    cli_result_free(&r);
    /* a [run] key (read by the search, not the model: every value gave
     * the same row) and a value that is not a number are refused */
    cli_run(&r, "stability", "hang", "--set", "cloth.n=6", "--t-end", "0.2",
            "--integrator", "rk4", "--axis", "run.dt=1e-4,2e-4", "--out",
            out, NULL);
    cli_assert_error(&r, 0, "--axis", "the search's own", NULL);
    cli_result_free(&r);
    cli_run(&r, "stability", "hang", "--set", "cloth.n=6", "--t-end", "0.2",
            "--integrator", "rk4", "--axis", "type1.enabled=true,false",
            "--out", out, NULL);
    cli_assert_error(&r, 0, "--axis", "must be a number", NULL);
    cli_result_free(&r);
}
