/* Tests for PETSc's start through its plug-in (linalg/petscenv.h). */
#include <criterion/criterion.h>

#include <dirent.h>
#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "linalg/petscenv.h"
#include "runcli.h"

/* Started twice it is started once; PETSc leaves SIGINT to the program
 * (core/stop.h), so the handler installed before is still there. */
static void mark(int sig)
{
    (void)sig;
}

Test(petscenv, starts_once_and_keeps_the_signal_handlers)
{
    cl_error err;
    struct sigaction before = {.sa_handler = mark}, after;
    sigemptyset(&before.sa_mask);
    cr_assert_eq(sigaction(SIGINT, &before, NULL), 0);
    cr_assert_eq(cl_petsc_start(&err), CL_OK, "%s", err.msg);
    cr_assert_eq(cl_petsc_start(&err), CL_OK, "%s", err.msg);
    cr_assert_eq(sigaction(SIGINT, NULL, &after), 0);
    cr_assert_eq((void *)after.sa_handler, (void *)mark);
}

/* The entries of folder `dir` but "." and ".."; the first one's name in
 * `first` (size 256). */
static int entries(const char *dir, char *first)
{
    DIR *d = opendir(dir);
    cr_assert_not_null(d, "%s", dir);
    int n = 0;
    for (struct dirent *e; (e = readdir(d)) != NULL;) {
        if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0)
            continue;
        if (n++ == 0)
            snprintf(first, 256, "%s", e->d_name);
    }
    closedir(d);
    return n;
}

/* Open MPI's session directories go into a folder of this process's own
 * under TMPDIR (docs/architecture.md "Plug-ins"), not passed on to
 * programs it starts, and removed at exit: a child process starts PETSc
 * and exits; its TMPDIR is empty afterwards. */
Test(petscenv, session_directory_is_private_and_removed_at_exit)
{
    char tmp[] = "/tmp/clothode-petscenv-XXXXXX";
    cr_assert_not_null(mkdtemp(tmp));
    cr_assert_eq(setenv("TMPDIR", tmp, 1), 0);
    cr_assert_eq(unsetenv("OMPI_MCA_orte_tmpdir_base"), 0);
    pid_t pid = fork();
    cr_assert_geq(pid, 0);
    if (pid == 0) {
        cl_error err;
        char name[256] = "";
        if (cl_petsc_start(&err) != CL_OK)
            _exit(2);
        if (entries(tmp, name) != 1 ||
            strncmp(name, "clothode-mpi-", 13) != 0)
            _exit(3);
        exit(getenv("OMPI_MCA_orte_tmpdir_base") == NULL ? 0 : 4);
    }
    int status = 0;
    cr_assert_eq(waitpid(pid, &status, 0), pid);
    cr_assert(WIFEXITED(status) && WEXITSTATUS(status) == 0,
              "child status %d", status);
    char name[256] = "";
    cr_assert_eq(entries(tmp, name), 0, "left behind: %s", name);
    cr_assert_eq(rmdir(tmp), 0);
}

/* A TMPDIR where no folder can be made: one message naming it and why,
 * before MPI is touched (Open MPI would abort the process). */
Test(petscenv, unusable_tmpdir_is_reported)
{
    cl_error err;
    cr_assert_eq(setenv("TMPDIR", "/dev/null/tmp", 1), 0);
    cr_assert_eq(unsetenv("OMPI_MCA_orte_tmpdir_base"), 0);
    cr_assert_eq(cl_petsc_start(&err), CL_ESOLVER);
    cr_assert_not_null(strstr(err.msg, "TMPDIR = /dev/null/tmp"), "%s",
                       err.msg);
    cr_assert_not_null(strstr(err.msg, strerror(ENOTDIR)), "%s", err.msg);
}

/* What PETSc prints as it ends reaches stdout: the command finalises it
 * before closing stdout (before: at exit, after stdout was closed, so
 * -options_left and -log_view printed nothing); and once finalised it is
 * not started again. */
Test(petscenv, reports_at_the_end_reach_stdout)
{
    cli_result r;
    char dir[64];
    tmp_mkdtemp(dir, sizeof dir, "petscend");
    cr_assert_eq(setenv("PETSC_OPTIONS", "-clamg_no_such_option 7 "
                        "-options_left", 1), 0);
    cli_run(&r, "run", "hang", "--set", "cloth.n=6", "--integrator",
            "semi-bdf2", "--linsol", "amg", "--dt", "1e-2", "--t-end",
            "0.02", "--frames", "0", "--out", dir, "--quiet", NULL);
    cr_assert_eq(unsetenv("PETSC_OPTIONS"), 0);
    cli_assert_ok(&r);
    cr_assert(strstr(r.out, "Option left: name:-clamg_no_such_option "
                            "value: 7"), "%s", r.out);
    cli_result_free(&r);
    tmp_rm_rf(dir);
    cl_error err;
    cl_petsc_stop(); /* not started here: nothing */
    cr_assert_eq(cl_petsc_start(&err), CL_OK, "%s", err.msg);
    cl_petsc_stop();
    cr_assert_eq(cl_petsc_start(&err), CL_EUNSUPPORTED);
    cr_assert(strstr(err.msg, "cannot be started again"), "%s", err.msg);
}
