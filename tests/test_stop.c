/* Tests for core/stop: the flag SIGINT and SIGTERM set (and SIGPROF and
 * SIGALRM, a CPU and a wall-time budget), and end to end the runs they
 * stop (analysis/simulate.c): everything computed is written. */
#include "runcli.h"

#include <sys/time.h>

#include "analysis/simulate.h"
#include "core/clock.h"
#include "core/stop.h"
#include "problem.h"
#include "timelimit.h"

Test(stop, signal_sets_the_flag_and_names_it)
{
    cl_stop_install();
    cr_assert_eq(cl_stop_requested(), 0);
    cr_assert_eq(cl_stop_status(CL_ESOLVER), CL_ESOLVER);
    cr_assert_eq(raise(SIGTERM), 0);
    cr_assert_eq(cl_stop_requested(), SIGTERM);
    /* a failure after the stop is the stop's; success stays success */
    cr_assert_eq(cl_stop_status(CL_ESOLVER), CL_EINTR);
    cr_assert_eq(cl_stop_status(CL_OK), CL_OK);
    cr_assert_str_eq(cl_stop_signal_name(SIGTERM), "SIGTERM");
    cr_assert_str_eq(cl_stop_signal_name(SIGINT), "SIGINT");
    cr_assert_str_eq(cl_stop_signal_name(SIGHUP), "signal 1");
    cl_error err;
    cr_assert_eq(cl_stop_error(&err, 1.5, NAN), CL_EINTR);
    cr_assert_str_eq(err.msg, "interrupted by SIGTERM at t = 1.5");
    cr_assert_eq(cl_stop_error(&err, 0, 100), CL_EINTR);
    cr_assert_str_eq(err.msg, "interrupted by SIGTERM at t = 0 (during the "
                     "advance to t = 100)");
}

/* A second signal ends the program, once CL_STOP_REPEAT_S have passed
 * since the first. */
Test(stop, second_signal_ends_the_program, .signal = SIGINT)
{
    cl_stop_install();
    raise(SIGINT);
    cr_assert_eq(cl_stop_requested(), SIGINT);
    nanosleep(&(struct timespec){.tv_nsec = 150000000}, NULL);
    raise(SIGINT);
}

/* A repeat within CL_STOP_REPEAT_S (timeout(1) signals the process and
 * then its group) is the same request: the program carries on to write
 * what it computed. */
Test(stop, repeat_at_once_is_the_same_request)
{
    cl_stop_install();
    raise(SIGTERM);
    raise(SIGTERM);
    raise(SIGINT);
    cr_assert_eq(cl_stop_requested(), SIGTERM);
}

/* A signal after a budget's timer replaces it (an interruption, which a
 * budget's stop is not), and forgetting the budget's stop (cl_stop_clear)
 * keeps it; a budget's timer after a signal does not replace the
 * signal. */
Test(stop, signal_after_a_budget_replaces_it)
{
    cl_error err;
    cl_stop_install();
    cr_assert_eq(cl_stop_after(CL_STOP_WALL, 100.0, &err), CL_OK);
    raise(SIGALRM);
    cr_assert_eq(cl_stop_requested(), SIGALRM);
    cr_assert(!cl_stop_interrupted());
    raise(SIGTERM);
    cr_assert_eq(cl_stop_requested(), SIGTERM);
    cr_assert(cl_stop_interrupted());
    cr_assert_eq(cl_stop_after(CL_STOP_WALL, 100.0, &err), CL_OK);
    raise(SIGALRM);
    cr_assert_eq(cl_stop_requested(), SIGTERM);
    cl_stop_clear();
    cr_assert_eq(cl_stop_requested(), SIGTERM);
}

/* ---- a CPU budget ------------------------------------------------------ */

/* Spin until a stop is asked for or `cap` seconds of CPU have gone by. */
static void spin_cpu(double cap)
{
    double c0 = cl_clock_cpu();
    volatile double sum = 0.0;
    while (!cl_stop_requested() && cl_clock_cpu() - c0 < cap)
        for (int i = 0; i < 10000; i++)
            sum += sqrt((double)i);
}

Test(stop, cpu_budget_sets_the_flag_and_clear_resets_it)
{
    cl_error err;
    cr_assert_eq(cl_stop_after(CL_STOP_CPU, 0.0, &err), CL_EINVAL);
    cr_assert_str_eq(err.msg, "CPU budget 0 s: must be a finite number > 0");
    cr_assert_eq(cl_stop_after(CL_STOP_WALL, -1.0, &err), CL_EINVAL);
    cr_assert_str_eq(err.msg, "wall-time budget -1 s: must be a finite "
                     "number > 0");
    cr_assert_eq(cl_stop_after(CL_STOP_CPU, NAN, &err), CL_EINVAL);
    cr_assert_eq(cl_stop_after(CL_STOP_CPU, INFINITY, &err), CL_EINVAL);
    cr_assert_eq(cl_stop_after(CL_STOP_CPU, 0.02, &err), CL_OK);
    spin_cpu(10.0);
    cr_assert_eq(cl_stop_requested(), SIGPROF);
    cr_assert_str_eq(cl_stop_signal_name(SIGPROF), "its CPU budget");
    cr_assert_str_eq(cl_stop_signal_name(SIGALRM), "its wall-time budget");
    cl_stop_clear();
    cr_assert_eq(cl_stop_requested(), 0);
    /* cleared before it fires: the timer is disarmed, no stop comes */
    cr_assert_eq(cl_stop_after(CL_STOP_CPU, 0.02, &err), CL_OK);
    cl_stop_clear();
    spin_cpu(0.1);
    cr_assert_eq(cl_stop_requested(), 0);
}

static volatile sig_atomic_t host_alarms;

static void host_alarm(int sig)
{
    (void)sig;
    host_alarms++;
}

/* A host program's own SIGALRM handler comes back once a budget is
 * disarmed, and its CPU-time timer is left alone. */
Test(stop, disarm_gives_back_the_host_s_alarm)
{
    struct sigaction sa, now;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = host_alarm;
    sigemptyset(&sa.sa_mask);
    cr_assert_eq(sigaction(SIGALRM, &sa, NULL), 0);
    struct itimerval prof = {.it_value = {.tv_sec = 100}}, left;
    cr_assert_eq(setitimer(ITIMER_PROF, &prof, NULL), 0);
    cl_error err;
    cr_assert_eq(cl_stop_after(CL_STOP_WALL, 10.0, &err), CL_OK);
    cr_assert_eq(cl_stop_after(CL_STOP_WALL, 20.0, &err), CL_OK);
    cl_stop_disarm();
    cr_assert_eq(sigaction(SIGALRM, NULL, &now), 0);
    cr_assert(now.sa_handler == host_alarm);
    cr_assert_eq(getitimer(ITIMER_PROF, &left), 0);
    cr_assert_gt(left.it_value.tv_sec, 90);
    cr_assert_eq(raise(SIGALRM), 0);
    cr_assert_eq(host_alarms, 1);
    cr_assert_eq(cl_stop_requested(), 0);
}

/* A timer's signal that arrives after the budget was disarmed (generated
 * just before) neither ends the process, whose SIGALRM had its default
 * action, nor stops the next run. */
Test(stop, late_timer_signal_is_ignored)
{
    struct sigaction dfl = {.sa_handler = SIG_DFL};
    sigemptyset(&dfl.sa_mask);
    cr_assert_eq(sigaction(SIGALRM, &dfl, NULL), 0);
    cl_error err;
    cr_assert_eq(cl_stop_after(CL_STOP_WALL, 10.0, &err), CL_OK);
    cl_stop_clear();
    cr_assert_eq(raise(SIGALRM), 0);
    cr_assert_eq(cl_stop_requested(), 0);
}

/* A run's wall-time budget is its own: the next run of the same process
 * (a program using the library) starts without it.  Before, the budget's
 * stop stayed, and every later run and force evaluation failed. */
Test(stop, max_wall_is_the_run_s_own)
{
    char dir[64], out[128];
    tmp_mkdtemp(dir, sizeof dir, "wallown");
    pr_problem p;
    pr_load(&p, "problems/hang.ini", "cloth.n=6", NULL);
    const cl_integrator_type *rk4 = cl_integrator_find("rk4");
    cl_integrator_opts io = {.dt = 1e-5};
    snprintf(out, sizeof out, "%s/a", dir);
    cl_sim_opts so = {.t_end = 100, .samples = 1, .outdir = out,
                      .max_stretch = 10, .max_wall = 1e-3};
    cl_sim_result res;
    cl_error err = {0};
    cr_assert_eq(cl_simulate(p.m, rk4, &io, &so, &res, &err), CL_EBUDGET,
                 "%s", err.msg);
    free(res.xfinal);
    cr_assert_eq(cl_stop_requested(), 0);
    so.t_end = 0.01;
    so.max_wall = 0;
    cr_assert_eq(cl_simulate(p.m, rk4, &io, &so, &res, &err), CL_OK, "%s",
                 err.msg);
    cr_assert_float_eq(res.t_reached, 0.01, 1e-12);
    free(res.xfinal);
    /* options out of range: refused before anything is done */
    so.max_stretch = 0;
    cr_assert_eq(cl_simulate(p.m, rk4, &io, &so, &res, &err), CL_EINVAL);
    cr_assert(strstr(err.msg, "max_stretch = 0: expected >= 1"), "%s",
              err.msg);
    so.max_stretch = 10;
    so.t_end = -1;
    cr_assert_eq(cl_simulate(p.m, rk4, &io, &so, &res, &err), CL_EINVAL);
    cr_assert(strstr(err.msg, "t_end = -1"), "%s", err.msg);
    pr_free(&p);
    tmp_rm_rf(dir);
}

/* ---- runs stopped by a signal ----------------------------------------- */

/* Start clothode with args (NULL-terminated, stdout and stderr to files in
 * dir), send sig after `after` seconds, wait; the exit status, or -1 when
 * it ended by a signal, and the seconds from the signal to the end into
 * *ended. */
static int run_and_signal(const char *dir, const char *const *args, int sig,
                          double after, double *ended)
{
    char *argv[CLI_MAX_ARGS + 2], out[300], err[300];
    size_t n = 0;
    argv[n++] = (char *)cli_binary();
    for (; args[n - 1]; n++)
        argv[n] = (char *)args[n - 1];
    argv[n] = NULL;
    snprintf(out, sizeof out, "%s.stdout", dir);
    snprintf(err, sizeof err, "%s.stderr", dir);
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_addopen(&fa, STDOUT_FILENO, out,
                                     O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_addopen(&fa, STDERR_FILENO, err,
                                     O_WRONLY | O_CREAT | O_TRUNC, 0644);
    pid_t pid;
    int rc = posix_spawnp(&pid, argv[0], &fa, NULL, argv, environ);
    posix_spawn_file_actions_destroy(&fa);
    cr_assert_eq(rc, 0, "posix_spawn: %s", strerror(rc));
    nanosleep(&(struct timespec){(time_t)after,
                                 (long)((after - (long)after) * 1e9)}, NULL);
    double t0 = cli_now();
    cr_assert_eq(kill(pid, sig), 0);
    int ws;
    cr_assert_eq(waitpid(pid, &ws, 0), pid);
    *ended = cli_now() - t0;
    unlink(out);
    return WIFEXITED(ws) ? WEXITSTATUS(ws) : -1;
}

/* The kinetic energy of a state file of np particles of equal mass m. */
static double kinetic_of(const char *path, size_t np, double m)
{
    double *x = malloc(3 * np * sizeof *x), *v = malloc(3 * np * sizeof *v);
    double e = 0;
    cli_read_state(path, np, x, v);
    for (size_t k = 0; k < 3 * np; k++)
        e += 0.5 * m * v[k] * v[k];
    free(x);
    free(v);
    return e;
}

/* A long run of a 32 x 32 hang to t = 100 s (capped at 60 s of wall
 * time) by `integrator` with `samples` samples, stopped by sig after 2 s:
 * exit status 6 within 10 s of the signal; run.json "interrupted"; every
 * series row complete and the last one at the time the message gives;
 * final.csv the state at that time (its kinetic energy is the last row's);
 * no temporaries.  With one sample the signal falls inside the run's only
 * advance (minutes long): the model's evaluations stop it
 * (system/system.h), and what is written is the state at t = 0. */
static void interrupted_run(int sig, const char *integrator,
                            const char *samples)
{
    char dir[64], path[300], json[1 << 16];
    double ended = 0;
    tmp_mkdtemp(dir, sizeof dir, "stop");
    bool fixed = !strncmp(integrator, "semi-", 5);
    const char *args[] = {"run", "hang", "--set", "cloth.n=32", "--t-end",
                          "100", "--samples", samples, "--frames", "0",
                          "--integrator", integrator, "--max-wall", "60",
                          "--out", dir, "--quiet", fixed ? "--dt" : NULL,
                          "1e-3", NULL};
    int status = run_and_signal(dir, args, sig, 2.0, &ended);
    snprintf(path, sizeof path, "%s.stderr", dir);
    tmp_slurp(path, json, sizeof json);
    unlink(path);
    cr_assert_eq(status, 6, "exit status %d: %s", status, json);
    cr_assert_lt(ended, 10.0, "%s: stopped %.1f s after the signal",
                 integrator, ended);
    double t_stop = -1;
    const char *at = strstr(json, " at t = ");
    cr_assert(strstr(json, cl_stop_signal_name(sig)) && at, "%s", json);
    t_stop = strtod(at + 8, NULL);
    if (strcmp(samples, "1"))
        cr_assert_gt(t_stop, 0.0);
    else
        cr_assert(t_stop == 0.0 && strstr(json, "during the advance to "
                                          "t = 100"), "%s", json);

    snprintf(path, sizeof path, "%s/run.json", dir);
    tmp_slurp(path, json, sizeof json);
    cr_assert(strstr(json, "\"status\": \"interrupted\""), "%s", json);
    cr_assert(strstr(json, "\"exit_status\": 6"));

    cli_lines L;
    snprintf(path, sizeof path, "%s/series.csv", dir);
    cli_read_lines(path, &L);
    size_t ncol = 1;
    for (const char *p = L.line[0]; *p; p++)
        ncol += *p == ',';
    cr_assert_geq(L.n, 2);
    double *row = malloc(ncol * sizeof *row), kinetic = 0, t = 0;
    for (size_t k = 1; k < L.n; k++) {
        cli_parse_row(L.line[k], row, ncol, path);
        t = row[0];
        kinetic = row[1];
    }
    free(row);
    cli_lines_free(&L);
    cr_assert(fabs(t - t_stop) <= 1e-9 * t_stop, "series ends at %g", t);

    snprintf(path, sizeof path, "%s/final.csv", dir);
    double ke = kinetic_of(path, 32 * 32, 0.1 / (32 * 32));
    cr_assert(fabs(ke - kinetic) <= 1e-8 * kinetic + 1e-15,
              "final.csv kinetic %.10g, series %.10g", ke, kinetic);
    snprintf(path, sizeof path, "%s/stats.csv", dir);
    cr_assert(cli_exists(path));

    char names[16][256];
    size_t n = tmp_list_dir(dir, names, 16);
    for (size_t k = 0; k < n && k < 16; k++)
        cr_assert(!strstr(names[k], ".tmp."), "leftover %s", names[k]);
    tmp_rm_rf(dir);
}

Test(stop, sigint_stops_a_run_with_everything_written)
{
    time_limit(120);
    interrupted_run(SIGINT, "cvode-bdf", "100000");
}

Test(stop, sigterm_stops_a_run_with_everything_written)
{
    time_limit(120);
    interrupted_run(SIGTERM, "cvode-bdf", "100000");
}

/* Inside one long advance: CVODE, a fixed-step method, PETSc's TSSolve. */
Test(stop, signals_stop_integrators_inside_an_advance)
{
    time_limit(120);
    interrupted_run(SIGINT, "cvode-bdf", "1");
    interrupted_run(SIGINT, "semi-bdf2", "1");
    interrupted_run(SIGTERM, "petsc-alpha2", "1");
}

/* --max-wall inside one long advance (one sample at t = 100 s): its
 * wall-time timer stops the evaluations, the run ends with status budget
 * and everything computed written (before, the budget was looked at only
 * at output times, so this run would have gone on to t = 100). */
Test(stop, max_wall_stops_a_run_inside_an_advance)
{
    time_limit(120);
    char dir[64], path[300];
    tmp_mkdtemp(dir, sizeof dir, "maxwall");
    cli_result r;
    cli_run(&r, "run", "hang", "--set", "cloth.n=32", "--t-end", "100",
            "--samples", "1", "--frames", "0", "--integrator", "semi-bdf2",
            "--dt", "1e-3", "--max-wall", "0.5", "--out", dir, "--quiet",
            NULL);
    cr_assert(r.exited && r.status == 5, "%s: %s", r.cmd, r.err);
    cr_assert(strstr(r.err, "budget --max-wall 0.5 s reached at t = 0 "
                     "(during the advance to t = 100)"), "%s", r.err);
    cli_result_free(&r);
    char json[1 << 16];
    snprintf(path, sizeof path, "%s/run.json", dir);
    tmp_slurp(path, json, sizeof json);
    cr_assert(strstr(json, "\"status\": \"budget\""), "%s", json);
    snprintf(path, sizeof path, "%s/final.csv", dir);
    cr_assert(cli_exists(path));
    tmp_rm_rf(dir);
}

/* args run in dir (made by the caller) and sent SIGTERM after `after`
 * seconds: exit status 6, `want` on stderr; dir removed. */
static void ends_as_stopped(const char *dir, const char *const *args,
                            double after, const char *want)
{
    char path[300], err[1024];
    double ended;
    int status = run_and_signal(dir, args, SIGTERM, after, &ended);
    cr_assert_eq(status, 6, "exit status %d", status);
    snprintf(path, sizeof path, "%s.stderr", dir);
    tmp_slurp(path, err, sizeof err);
    cr_assert(strstr(err, want), "%s", err);
    unlink(path);
    tmp_rm_rf(dir);
}

/* spectrum: a signal during its eigensolvers (GSL's QR iterations, not to
 * be cut short) is seen between and after them: exit status 6, where it
 * had run on and exited 0 (hang at n = 16: 768 unknowns, about 10 s). */
Test(stop, spectrum_stops_between_its_eigensolvers)
{
    time_limit(120);
    char dir[64], path[300];
    tmp_mkdtemp(dir, sizeof dir, "spectrum");
    snprintf(path, sizeof path, "%s/o", dir);
    const char *const args[] = {"spectrum", "hang", "--set", "cloth.n=16",
                                "--out", path, NULL};
    ends_as_stopped(dir, args, 0.5, "interrupted by SIGTERM");
}

/* A command with no stop points of its own (counts, asinc, sweep plan)
 * that runs to its end after a signal still exits 6, saying so: before,
 * counts at n = 2048 (several seconds) took SIGTERM and exited 0. */
Test(stop, a_command_that_ran_on_still_reports_the_signal)
{
    time_limit(120);
    char dir[64];
    tmp_mkdtemp(dir, sizeof dir, "counts");
    const char *const args[] = {"counts", "--n-min", "2048", "--n-max",
                                "2048", NULL};
    ends_as_stopped(dir, args, 0.3, "clothode: interrupted by SIGTERM "
                    "(after the command had done its work)");
}
