/* Sweeps (analysis/sweep.h): the plan's axes, ids and commands, the
 * manifest read back, and collect's outcomes of complete, failed and
 * missing jobs. */
#include <criterion/criterion.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/sweep.h"
#include "io/atomic.h"
#include "io/config.h"
#include "runcli.h"
#include "timelimit.h"

static char tmp[512];

static void setup(void)
{
    time_limit(120);
    tmp_mkdtemp(tmp, sizeof tmp, "sweep");
}

static void teardown(void)
{
    tmp_rm_rf(tmp);
}

TestSuite(sweep, .init = setup, .fini = teardown);

/* The sweep file `text` read and expanded into sw (into tmp/d). */
/* The plan of a sweep file holding `text`, its directory `dir`. */
static cl_status plan_text_in(const char *text, const char *dir,
                              cl_sweep *sw, cl_error *err)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/s.ini", tmp);
    tmp_put(path, text);
    cl_config *cfg = cl_config_alloc();
    memset(sw, 0, sizeof *sw);
    cl_status rc = cl_config_load(cfg, path, err);
    if (!rc)
        rc = cl_sweep_read(cfg, sw, err);
    if (!rc) {
        sw->dir = strdup(dir);
        sw->clothode = strdup("/bin/clothode");
        rc = cl_sweep_expand(sw, err);
    }
    cl_config_free(cfg);
    return rc;
}

/* ... in tmp/d. */
static cl_status plan_text(const char *text, cl_sweep *sw, cl_error *err)
{
    char dir[1024];
    snprintf(dir, sizeof dir, "%s/d", tmp);
    return plan_text_in(text, dir, sw, err);
}

static const char *id_of(const cl_sweep *sw, const char *integrator,
                         const char *dt)
{
    for (int k = 0; k < sw->njob; k++)
        if (!strcmp(sw->job[k].integrator, integrator) &&
            !strcmp(sw->job[k].value[0], dt))
            return sw->job[k].id;
    cr_assert_fail("no job %s dt=%s", integrator, dt);
    return NULL;
}

Test(sweep, axes_expand_lists_linspace_logspace)
{
    cl_sweep sw;
    cl_error err = {0};
    cr_assert_eq(plan_text("[sweep]\nproblem = p.ini\n"
                           "integrator = rk4, semi-bdf2:pcg\n"
                           "dt = logspace(-4, -2, 3)\n"
                           "type1.ks = linspace(100, 200, 5)\n"
                           "n = 6, 8\n", &sw, &err), CL_OK, "%s", err.msg);
    cr_assert_eq(sw.naxis, 3);
    cr_assert_str_eq(sw.axis[0].key, "run.dt");
    cr_assert_str_eq(sw.axis[0].v[0], "0.0001");
    cr_assert_str_eq(sw.axis[0].v[1], "0.001");
    cr_assert_str_eq(sw.axis[0].v[2], "0.01");
    cr_assert_str_eq(sw.axis[1].key, "type1.ks");
    cr_assert_eq(sw.axis[1].n, 5);
    cr_assert_str_eq(sw.axis[1].v[1], "125");
    cr_assert_str_eq(sw.axis[1].v[4], "200");
    cr_assert_str_eq(sw.axis[2].key, "cloth.n");
    cr_assert_str_eq(sw.axis[2].v[1], "8");
    cr_assert_eq(sw.njob, 2 * 3 * 5 * 2);
    /* integrator slowest, the last axis fastest */
    cr_assert_str_eq(sw.job[0].integrator, "rk4");
    cr_assert_str_eq(sw.job[1].value[2], "8");
    cr_assert_str_eq(sw.job[2].value[1], "125");
    cr_assert_str_eq(sw.job[30].integrator, "semi-bdf2:pcg");
    char tail[2200];
    snprintf(tail, sizeof tail,
             " --out %s/d/jobs/%s/run --quiet 2> %s/d/jobs/%s/stderr", tmp,
             sw.job[1].id, tmp, sw.job[1].id);
    cr_assert(strstr(sw.job[1].command,
                     " run p.ini --integrator rk4 --set run.frames=0 --set "
                     "run.dt=0.0001 --set type1.ks=100 --set cloth.n=8 "
                     "--out "),
              "%s", sw.job[1].command);
    cr_assert(strstr(sw.job[1].command, tail), "%s", sw.job[1].command);
    /* the job records its own exit status, and returns it */
    char head[1200], end[3600];
    snprintf(head, sizeof head, "rm -rf %s/d/jobs/%s/exit %s/d/jobs/%s/run "
             "|| exit 125; /bin/clothode run ", tmp, sw.job[1].id, tmp,
             sw.job[1].id);
    snprintf(end, sizeof end, "/stderr; s=$?; echo $s > %s/d/jobs/%s/exit.tmp"
             " && mv %s/d/jobs/%s/exit.tmp %s/d/jobs/%s/exit; exit $s", tmp,
             sw.job[1].id, tmp, sw.job[1].id, tmp, sw.job[1].id);
    const char *cmd = sw.job[1].command;
    cr_assert(!strncmp(cmd, head, strlen(head)), "%s", cmd);
    cr_assert(strlen(cmd) > strlen(end) &&
                  !strcmp(cmd + strlen(cmd) - strlen(end), end), "%s", cmd);
    for (int a = 0; a < sw.njob; a++)
        for (int b = a + 1; b < sw.njob; b++)
            cr_assert_str_neq(sw.job[a].id, sw.job[b].id);
    cl_sweep_free(&sw);
}

/* A run.frames axis takes the place of the command's run.frames=0 (run
 * would refuse the key twice); a command that would not fit is refused,
 * not cut short. */
Test(sweep, frames_axis_and_command_length)
{
    cl_sweep sw;
    cl_error err = {0};
    cr_assert_eq(plan_text("[sweep]\nproblem = p.ini\nintegrator = rk4\n"
                           "dt = 1e-3\nrun.frames = 2\n", &sw, &err), CL_OK,
                 "%s", err.msg);
    cr_assert_null(strstr(sw.job[0].command, "run.frames=0"), "%s",
                   sw.job[0].command);
    cr_assert(strstr(sw.job[0].command, " --set run.frames=2 "), "%s",
              sw.job[0].command);
    cl_sweep_free(&sw);
    static char dir[4001];
    memset(dir, 'd', sizeof dir - 1);
    dir[0] = '/';
    cr_assert_eq(plan_text_in("[sweep]\nproblem = p.ini\nintegrator = rk4\n"
                              "dt = 1e-3\n", dir, &sw, &err), CL_EINVAL);
    cr_assert(strstr(err.msg, "its command line is longer than 16383 "
                              "characters"), "%s", err.msg);
    cl_sweep_free(&sw);
}

/* Ids hash the parameters: the same job keeps its id when the axes are
 * reordered and values added around it. */
Test(sweep, ids_are_stable)
{
    cl_sweep a, b;
    cl_error err = {0};
    cr_assert_eq(plan_text("[sweep]\nproblem = p.ini\nintegrator = rk4\n"
                           "dt = 1e-3, 2e-3\nn = 6\n", &a, &err), CL_OK);
    cr_assert_eq(plan_text("[sweep]\nproblem = p.ini\n"
                           "integrator = fe, rk4\nn = 6\n"
                           "dt = 5e-4, 1e-3, 2e-3\n", &b, &err), CL_OK);
    cr_assert_str_eq(a.job[0].id, "ca0465cfe9cf");
    char text[512];
    cl_sweep_canonical(&a, &a.job[0], text, sizeof text);
    cr_assert_str_eq(text, "integrator=rk4\ncloth.n=6\nrun.dt=1e-3");
    for (int k = 0; k < b.njob; k++)
        if (!strcmp(b.job[k].integrator, "rk4") &&
            !strcmp(b.job[k].value[1], "1e-3"))
            cr_assert_str_eq(b.job[k].id, a.job[0].id);
    cl_sweep_free(&a);
    cl_sweep_free(&b);
}

/* With one t_end, dt becomes T / round(T / dt): whole steps. */
Test(sweep, dt_snapped_to_whole_steps)
{
    cl_sweep sw;
    cl_error err = {0};
    cr_assert_eq(plan_text("[sweep]\nproblem = p.ini\n"
                           "integrator = symplectic-euler\n"
                           "dt = 1e-5, 3.1622776601683795e-05, -1, inf\n"
                           "t_end = 0.05\n",
                           &sw, &err), CL_OK, "%s", err.msg);
    /* 0.05 / 3.16e-5 = 1581.1 steps -> 1581, to the last digit: the
     * double 0.05 / 1581 the stability search steps with */
    cr_assert_str_eq(id_of(&sw, "symplectic-euler", "3.162555344718533e-05"),
                     sw.job[1].id);
    cr_assert_eq(strtod(sw.job[1].value[0], NULL), 0.05 / 1581);
    cr_assert_str_eq(sw.job[0].value[0], "1e-05");
    /* left as written, for the plan's check to refuse */
    cr_assert_str_eq(sw.job[2].value[0], "-1");
    cr_assert_str_eq(sw.job[3].value[0], "inf");
    cl_sweep_free(&sw);
}

Test(sweep, refused_keys_and_values)
{
    static const struct {
        const char *text, *want;
    } bad[] = {
        {"[sweep]\nproblem = p.ini\nintegrator = rk4\ndt = linspace(1, 2)\n",
         "s.ini:4: [sweep] dt = \"linspace(1, 2)\": expected a list"},
        {"[sweep]\nproblem = p.ini\nintegrator = rk5\n",
         "[sweep] integrator = \"rk5\": expected NAME[:LINSOL]"},
        {"[sweep]\nproblem = p.ini\nintegrator = rk4\nks = 1, 2\n",
         "[sweep] ks = \"1, 2\": expected problem, integrator, reference, an "
         "axis dt"},
        {"[sweep]\nintegrator = rk4\n", "a problem file is required"},
        {"[sweep]\nproblem = p.ini\nintegrator = rk4\ndt = 1e-3, 1e-3\n",
         "two jobs are the same run"},
        /* one number written two ways is one value */
        {"[sweep]\nproblem = p.ini\nintegrator = cvode-bdf\n"
         "rtol = 1e-4, 0.0001\n", "two jobs are the same run"},
        {"[sweep]\nproblem = p.ini\nintegrator = rk4\ndt = 1e-3\n"
         "type1.ks = 200, 2e2\n", "two jobs are the same run"},
        {"[sweep]\nproblem = p.ini\nintegrator = rk4\ndt = 1e-3, ,2\n",
         "expected a list"},
        /* parts */
        {"[sweep]\nproblem = p.ini\n[sweep.a]\ndt = 1\n",
         "[sweep.a] integrator: NAME[:LINSOL], ... is required"},
        {"[sweep]\nproblem = p.ini\nintegrator = rk4\n[sweep.a]\n"
         "reference = 1e-9\n", "[sweep.a] reference = \"1e-9\": belongs in "
                               "[sweep]"},
        {"[sweep]\nproblem = p.ini\nintegrator = rk4\natol = rtol / 100\n",
         "or KEY * C or KEY / C of a numeric axis above"},
        /* one axis written two ways in a section */
        {"[sweep]\nproblem = p.ini\nintegrator = rk4\ncloth.n = 8, 9\n"
         "n = 8\n", "s.ini:5: [sweep] n = \"8\": an axis given twice in one "
                    "section"},
        {"[sweep]\nproblem = p.ini\nintegrator = rk4\nn = 8\n[sweep.a]\n"
         "dt = 1e-3\nrun.dt = 2e-3\n", "[sweep.a] run.dt = \"2e-3\": an axis "
                                      "given twice"},
    };
    for (size_t k = 0; k < sizeof bad / sizeof *bad; k++) {
        cl_sweep sw;
        cl_error err = {0};
        cr_assert_eq(plan_text(bad[k].text, &sw, &err), CL_EINVAL, "%s",
                     bad[k].text);
        cr_assert(strstr(err.msg, bad[k].want), "%s\ngot: %s\nwant: %s",
                  bad[k].text, err.msg, bad[k].want);
        cl_sweep_free(&sw);
    }
}

/* Reference runs: one per combination of the problem's axes, shared by
 * the methods' values. */
Test(sweep, references_per_problem_axis)
{
    cl_sweep sw;
    cl_error err = {0};
    cr_assert_eq(plan_text("[sweep]\nproblem = p.ini\nreference = 1e-10\n"
                           "integrator = rk4, semi-bdf2\n"
                           "dt = 1e-3, 2e-3\nn = 6, 8\n", &sw, &err), CL_OK,
                 "%s", err.msg);
    cr_assert_eq(sw.njob, 8 + 2);
    cr_assert(sw.job[8].reference && sw.job[9].reference);
    cr_assert_null(sw.job[8].value[0]);
    cr_assert_str_eq(sw.job[8].value[1], "6");
    for (int k = 0; k < 8; k++)
        cr_assert_eq(sw.job[k].ref, 8 + (k % 2), "job %d", k);
    cr_assert(strstr(sw.job[9].command, "--integrator cvode-bdf --set "
                                        "run.frames=0 --set cloth.n=8 --rtol 1e-10 "
                                        "--atol 1e-12 --out"),
              "%s", sw.job[9].command);
    cl_sweep_free(&sw);
}

/* The manifest written and read back gives the same plan. */
Test(sweep, manifest_round_trip)
{
    cl_sweep a, b = {0};
    cl_error err = {0};
    cr_assert_eq(plan_text("[sweep]\nproblem = p q.ini\nreference = 1e-9\n"
                           "integrator = rk4\ndt = 1e-3, 2e-3\n"
                           "gravity.g = 0 -9.81 0, 0 -1 0\n", &a, &err),
                 CL_OK, "%s", err.msg);
    cr_assert(strstr(a.job[0].command, "'p q.ini'"), "%s", a.job[0].command);
    cr_assert_eq(cl_sweep_write(&a, &err), CL_OK, "%s", err.msg);
    cr_assert_eq(cl_sweep_load(a.dir, &b, &err), CL_OK, "%s", err.msg);
    cr_assert_eq(b.njob, a.njob);
    cr_assert_eq(b.naxis, 2);
    cr_assert_str_eq(b.ref_rtol, "1e-09");
    for (int k = 0; k < a.njob; k++) {
        cr_assert_str_eq(b.job[k].id, a.job[k].id);
        cr_assert_str_eq(b.job[k].command, a.job[k].command);
        cr_assert_eq(b.job[k].ref, a.job[k].ref);
        cr_assert_eq(b.job[k].reference, a.job[k].reference);
    }
    cr_assert_str_eq(b.job[1].value[1], "0 -1 0");
    cl_sweep_free(&b);
    /* moved elsewhere, it is still read (collected where it is), but not
     * run there: its jobs would write where it was */
    char moved[1100];
    snprintf(moved, sizeof moved, "%s/moved", tmp);
    cr_assert_eq(rename(a.dir, moved), 0);
    memset(&b, 0, sizeof b);
    cr_assert_eq(cl_sweep_load(moved, &b, &err), CL_OK, "%s", err.msg);
    cl_sweep_free(&b);
    cli_result r;
    cli_run(&r, "sweep", "run", moved, NULL);
    cli_assert_error(&r, 0, "planned for", "sweep plan SWEEP.ini --out",
                     NULL);
    cli_result_free(&r);
    cr_assert_eq(rename(moved, a.dir), 0);
    /* a manifest whose job lines do not record their exit status (an
     * earlier clothode's) is refused with the way out */
    char path[1100];
    static char json[1 << 16];
    snprintf(path, sizeof path, "%s/sweep.json", a.dir);
    tmp_slurp(path, json, sizeof json);
    char *tail = strstr(json, "; exit $s\"");
    cr_assert_not_null(tail);
    memmove(tail, tail + 9, strlen(tail + 9) + 1);
    tmp_put(path, json);
    memset(&b, 0, sizeof b);
    cr_assert_eq(cl_sweep_load(a.dir, &b, &err), CL_EINVAL);
    cr_assert(strstr(err.msg, "planned by an earlier clothode") &&
                  strstr(err.msg, "plan it again"), "%s", err.msg);
    cl_sweep_free(&a);
    cl_sweep_free(&b);
}

static void put_job_file(const cl_sweep *sw, int k, const char *name,
                         const char *text)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/jobs/%s/%s", sw->dir, sw->job[k].id,
             name);
    *strrchr(path, '/') = '\0';
    cl_error err;
    cr_assert_eq(cl_mkdir_p(path, &err), CL_OK);
    strcat(path, "/");
    strcat(path, strrchr(name, '/') ? strrchr(name, '/') + 1 : name);
    tmp_put(path, text);
}

/* Four jobs: complete, failed (exit 1), killed (signal 2: 130) and
 * missing, as their status files say. */
Test(sweep, collect_complete_failed_missing)
{
    cl_sweep sw;
    cl_error err = {0};
    cr_assert_eq(plan_text("[sweep]\nproblem = p.ini\nintegrator = rk4\n"
                           "dt = 1e-3, 2e-3, 4e-3, 8e-3\n", &sw, &err),
                 CL_OK);
    cr_assert_eq(cl_sweep_write(&sw, &err), CL_OK, "%s", err.msg);
    put_job_file(&sw, 0, "exit", "0\n");
    put_job_file(&sw, 0, "run/stats.csv", "steps,50\nrhs_evals,200\n"
                                      "nonlin_iters,NA\ncpu,0.25\n");
    put_job_file(&sw, 0, "run/series.csv",
                 "t,kinetic\n0,0\n0.025,1\n0.05,2\n");
    put_job_file(&sw, 1, "exit", "1\n");
    put_job_file(&sw, 2, "exit", "130\n");
    cl_sweep_outcome out[4];
    cl_sweep_counts c;
    cl_sweep_outcomes(&sw, out, &c);
    cr_assert_eq(c.complete, 1);
    cr_assert_eq(c.failed, 2);
    cr_assert_eq(c.missing, 1);
    cr_assert_str_eq(out[0].exit_class, "ok");
    cr_assert_eq(out[0].stat[0], 50);
    cr_assert_eq(out[0].stat[1], 200);
    cr_assert(isnan(out[0].stat[6]));
    cr_assert_eq(out[0].stat[12], 0.25);
    cr_assert_eq(out[0].t_reached, 0.05);
    /* a run.json's integrator times stand for stats.csv's */
    put_job_file(&sw, 0, "run/run.json", "{\"times\": {\"wall\": 9, "
                 "\"integrator_wall\": 2.5, \"integrator_cpu\": 1.5}}\n");
    cl_sweep_outcomes(&sw, out, &c);
    cr_assert_eq(out[0].stat[11], 2.5);
    cr_assert_eq(out[0].stat[12], 1.5);
    cr_assert_str_eq(out[1].exit_class, "other");
    cr_assert_str_eq(out[2].exit_class, "signal-2");
    cr_assert_eq(out[3].state, CL_SWEEP_MISSING);
    cr_assert_str_eq(out[3].exit_class, "missing");
    /* a status file that holds anything but 0 to 255 alone on its line
     * records no status (before: "0 extra" was ok, 300 signal-172, a
     * number past int exit--1) */
    static const char *const odd[] = {"0 extra\n", "300\n", "1.5\n",
                                      "99999999999999999999\n", "-1\n", ""};
    for (size_t k = 0; k < sizeof odd / sizeof *odd; k++) {
        put_job_file(&sw, 3, "exit", odd[k]);
        cl_sweep_outcomes(&sw, out, &c);
        cr_expect_eq(out[3].state, CL_SWEEP_MISSING, "exit file \"%s\"",
                     odd[k]);
    }
    put_job_file(&sw, 3, "exit", "255");
    cl_sweep_outcomes(&sw, out, &c);
    cr_assert_str_eq(out[3].exit_class, "signal-127");
    cl_sweep_free(&sw);
}

/* The command line: the table has a row per job, the summary names the
 * failed and the missing ones. */
Test(sweep, collect_cli_summary)
{
    cl_sweep sw;
    cl_error err = {0};
    cr_assert_eq(plan_text("[sweep]\nproblem = p.ini\nintegrator = rk4\n"
                           "dt = 1e-3, 2e-3, 4e-3\n", &sw, &err), CL_OK);
    cr_assert_eq(cl_sweep_write(&sw, &err), CL_OK, "%s", err.msg);
    put_job_file(&sw, 0, "exit", "0\n");
    put_job_file(&sw, 0, "run/stats.csv", "steps,50\n");
    put_job_file(&sw, 1, "exit", "3\n");
    put_job_file(&sw, 1, "stderr", "clothode: it broke, here\nmore\n");
    char table[1024], line[512];
    snprintf(table, sizeof table, "%s/t.csv", tmp);
    cli_result r;
    cli_run(&r, "sweep", "collect", sw.dir, "--out", table, NULL);
    cli_assert_ok(&r);
    snprintf(line, sizeof line, "failed     %s rk4 run.dt=2e-3 (solver): "
             "clothode: it broke, here\n"
             "missing    %s rk4 run.dt=4e-3\n"
             "1 complete, 1 failed, 1 missing\n", sw.job[1].id,
             sw.job[2].id);
    cr_assert(strstr(r.out, line), "%s", r.out);
    cli_result_free(&r);
    char text[4096];
    tmp_slurp(table, text, sizeof text);
    cr_assert_eq(cli_count_lines(text), 4);
    cr_assert(!strncmp(text, "id,role,integrator,run.dt,status,exit,"
                             "t_reached,steps,", 38), "%s", text);
    snprintf(line, sizeof line, "\n%s,job,rk4,4e-3,missing,missing,NA,",
             sw.job[2].id);
    cr_assert(strstr(text, line), "%s", text);
    /* the message, then the problem the runs are of and the SHA-256 of
     * the file each read and of the meshes it named (none here: no
     * run.json) */
    cr_assert(strstr(text, ",NA,NA,\"clothode: it broke, here\",p.ini,NA,"
                           "NA\n"), "%s", text);
    cl_sweep_free(&sw);
}

/* Parts: fixed-step methods over dt, adaptive ones over rtol with atol
 * following it, one reference for both. */
Test(sweep, parts_and_derived_axes)
{
    cl_sweep sw;
    cl_error err = {0};
    cr_assert_eq(plan_text("[sweep]\nproblem = p.ini\nreference = 1e-11\n"
                           "t_end = 0.2\n"
                           "[sweep.fixed]\nintegrator = rk4, semi-bdf2:pcg\n"
                           "dt = 1e-3, 5e-4\n"
                           "[sweep.adaptive]\nintegrator = cvode-bdf:pcg\n"
                           "rtol = logspace(-4, -6, 3)\natol = rtol / 100\n",
                           &sw, &err), CL_OK, "%s", err.msg);
    cr_assert_eq(sw.nplan, 2);
    cr_assert_eq(sw.njob, 4 + 3 + 1);
    cr_assert_eq(sw.naxis, 4);
    cr_assert_str_eq(sw.axis[0].key, "run.t_end");
    cr_assert_str_eq(sw.axis[1].key, "run.dt");
    cr_assert_str_eq(sw.axis[2].key, "run.rtol");
    cr_assert_str_eq(sw.axis[3].key, "run.atol");
    cr_assert_str_eq(sw.job[1].integrator, "rk4");
    cr_assert_str_eq(sw.job[1].value[1], "0.0005");
    cr_assert_null(sw.job[1].value[2]);
    cr_assert_str_eq(sw.job[5].integrator, "cvode-bdf:pcg");
    cr_assert_null(sw.job[5].value[1]);
    cr_assert_str_eq(sw.job[5].value[2], "1e-05");
    cr_assert_str_eq(sw.job[5].value[3], "1e-07");
    cr_assert_str_eq(sw.job[6].value[3], "1e-08");
    for (int k = 0; k < 7; k++)
        cr_assert_eq(sw.job[k].ref, 7);
    cr_assert_str_eq(sw.job[7].value[0], "0.2");
    cl_sweep_free(&sw);
}

/* The options of sweep run are the command line's own: --help names no
 * key of a sweep file; a sweep directory that is not one is refused. */
Test(sweep, run_help_and_refusals)
{
    cli_result r;
    cli_run(&r, "sweep", "run", "--help", NULL);
    cli_assert_ok(&r);
    cr_assert(strstr(r.out, "--chunk C          slurm: jobs per array task; "
                            "1 .. 100000, default 1\n"), "%s", r.out);
    cr_assert_null(strstr(r.out, "[sweep]"), "%s", r.out);
    cli_result_free(&r);
    cli_run(&r, "sweep", "run", tmp, NULL);
    cli_assert_error(&r, 0, "sweep.json: cannot read it (No such file or "
                     "directory); a sweep directory is made by 'clothode "
                     "sweep plan'", NULL);
    cli_result_free(&r);
    cli_run(&r, "sweep", "run", tmp, "--engine", "ssh", NULL);
    cli_assert_error(&r, 1, "--sshloginfile FILE goes with --engine ssh",
                     NULL);
    cli_result_free(&r);
    /* the slurm engine's options with another engine */
    cli_run(&r, "sweep", "run", tmp, "--chunk", "5", NULL);
    cli_assert_error(&r, 1, "--chunk, --throttle, --time, --mem and --wait "
                     "go with --engine slurm", NULL);
    cli_result_free(&r);
    /* a host file that cannot be read is refused before GNU parallel */
    cli_run(&r, "sweep", "run", tmp, "--engine", "ssh", "--sshloginfile",
            "/nonexistent/hosts", NULL);
    cli_assert_error(&r, 0, "--sshloginfile /nonexistent/hosts: cannot read "
                     "it", NULL);
    cr_assert_eq(r.status, 7);
    cli_result_free(&r);
    cli_run(&r, "sweep", "frobnicate", NULL);
    cr_assert_eq(r.status, 2);
    cli_assert_error(&r, 5, "sweep: unknown subcommand 'frobnicate'",
                     "plan, run, collect or refine", NULL);
    cli_result_free(&r);
    cli_run(&r, "sweep", NULL);
    cr_assert_eq(r.status, 2);
    cli_assert_error(&r, 5, "sweep: a subcommand is needed", NULL);
    cli_result_free(&r);
}
