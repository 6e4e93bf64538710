/* Helpers for the end-to-end tests of the clothode command line
 * (tests/test_cli.c): run the program with posix_spawn and capture its exit
 * status, stdout and stderr; scratch directories; small CSV readers.
 *
 * The program is $CLOTHODE (default build/clothode), run from the current
 * directory (the repository root, so that bare problem names resolve to
 * problems/NAME.ini). */
#ifndef CL_TEST_RUNCLI_H
#define CL_TEST_RUNCLI_H

#include <criterion/criterion.h>

#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <signal.h>
#include <spawn.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "tmpdir.h"

extern char **environ;

/* A child that runs longer than this is killed and the test fails. */
#define CLI_TIMEOUT_S 600.0
#define CLI_MAX_ARGS 64

typedef struct {
    int exited;     /* 1 if the program exited normally */
    int status;     /* its exit status (when exited) */
    int signal;     /* the signal that ended it (when not exited), else 0 */
    char *out;      /* everything it wrote to stdout, NUL-terminated */
    char *err;      /* everything it wrote to stderr, NUL-terminated */
    char cmd[2048]; /* the command line, for messages */
} cli_result;

static inline const char *cli_binary(void)
{
    const char *b = getenv("CLOTHODE");
    return b && *b ? b : "build/clothode";
}

/* The whole content of an open stream from its start. */
static inline char *cli_slurp_fp(FILE *fp)
{
    cr_assert_eq(fseek(fp, 0, SEEK_END), 0);
    long n = ftell(fp);
    cr_assert(n >= 0);
    rewind(fp);
    char *s = malloc((size_t)n + 1);
    cr_assert_not_null(s);
    size_t got = fread(s, 1, (size_t)n, fp);
    s[got] = '\0';
    return s;
}

static inline double cli_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Run argv[0] (a path, or a name looked up in PATH) with argv
 * (NULL-terminated), stdin from /dev/null, capturing its output. */
static inline void cli_spawn(cli_result *r, char *const argv[])
{
    size_t len = 0;
    memset(r, 0, sizeof *r);
    for (size_t k = 0; argv[k] && len < sizeof r->cmd; k++)
        len += (size_t)snprintf(r->cmd + len, sizeof r->cmd - len, "%s%s",
                                k ? " " : "", argv[k]);
    FILE *out = tmpfile(), *err = tmpfile();
    cr_assert(out && err, "tmpfile: %s", strerror(errno));
    posix_spawn_file_actions_t fa;
    cr_assert_eq(posix_spawn_file_actions_init(&fa), 0);
    cr_assert_eq(posix_spawn_file_actions_addopen(&fa, STDIN_FILENO,
                                                  "/dev/null", O_RDONLY, 0),
                 0);
    cr_assert_eq(posix_spawn_file_actions_adddup2(&fa, fileno(out),
                                                  STDOUT_FILENO), 0);
    cr_assert_eq(posix_spawn_file_actions_adddup2(&fa, fileno(err),
                                                  STDERR_FILENO), 0);
    pid_t pid;
    int rc = posix_spawnp(&pid, argv[0], &fa, NULL, argv, environ);
    posix_spawn_file_actions_destroy(&fa);
    cr_assert_eq(rc, 0, "posix_spawn %s: %s", argv[0], strerror(rc));

    int ws = 0;
    double deadline = cli_now() + CLI_TIMEOUT_S;
    for (;;) {
        pid_t w = waitpid(pid, &ws, WNOHANG);
        if (w == pid)
            break;
        cr_assert(w == 0 || errno == EINTR, "waitpid: %s", strerror(errno));
        if (cli_now() > deadline) {
            kill(pid, SIGKILL);
            waitpid(pid, &ws, 0);
            cr_assert_fail("%s: still running after %.0f s, killed", r->cmd,
                           CLI_TIMEOUT_S);
        }
        nanosleep(&(struct timespec){0, 2000000}, NULL);
    }
    r->exited = WIFEXITED(ws);
    r->status = r->exited ? WEXITSTATUS(ws) : -1;
    r->signal = WIFSIGNALED(ws) ? WTERMSIG(ws) : 0;
    r->out = cli_slurp_fp(out);
    r->err = cli_slurp_fp(err);
    fclose(out);
    fclose(err);
}

/* Run $CLOTHODE with the given arguments (a NULL-terminated array). */
static inline void cli_runv(cli_result *r, const char *const *args)
{
    char *argv[CLI_MAX_ARGS + 2];
    size_t argc = 0;
    argv[argc++] = (char *)cli_binary();
    for (; args[argc - 1]; argc++) {
        cr_assert(argc <= CLI_MAX_ARGS, "too many arguments");
        argv[argc] = (char *)args[argc - 1];
    }
    argv[argc] = NULL;
    struct stat st;
    cr_assert_eq(stat(argv[0], &st), 0,
                 "program %s not found (build it, or set $CLOTHODE)",
                 argv[0]);
    cli_spawn(r, argv);
}

/* cli_run(&r, "run", "hang", ..., NULL) */
static inline void cli_run(cli_result *r, ...)
{
    const char *args[CLI_MAX_ARGS + 1];
    size_t n = 0;
    va_list ap;
    va_start(ap, r);
    for (const char *a; (a = va_arg(ap, const char *));) {
        cr_assert(n < CLI_MAX_ARGS, "too many arguments");
        args[n++] = a;
    }
    va_end(ap);
    args[n] = NULL;
    cli_runv(r, args);
}

static inline void cli_result_free(cli_result *r)
{
    free(r->out);
    free(r->err);
    r->out = r->err = NULL;
}

/* The program ended by exit (not by a signal: a crash or a sanitizer abort
 * fails the test) and its stderr shows no sanitizer report. */
static inline void cli_assert_no_crash(const cli_result *r)
{
    cr_assert(r->exited, "%s: killed by signal %d (%s)\nstderr:\n%s", r->cmd,
              r->signal, strsignal(r->signal), r->err);
    cr_assert(!strstr(r->err, "Sanitizer") &&
                  !strstr(r->err, "runtime error:"),
              "%s: sanitizer report\n%s", r->cmd, r->err);
}

/* Exit status 0 and no error message. */
static inline void cli_assert_ok(const cli_result *r)
{
    cli_assert_no_crash(r);
    cr_assert_eq(r->status, 0, "%s: exit status %d\nstderr:\n%s", r->cmd,
                 r->status, r->err);
    cr_assert(!strstr(r->err, "clothode"), "%s: message on stderr:\n%s",
              r->cmd, r->err);
}

/* Run a command given as a NULL-ended list; it must succeed with nothing
 * on standard error. */
static inline void cli_run_ok(const char *const *args)
{
    cli_result r;
    cli_runv(&r, args);
    cli_assert_ok(&r);
    cli_result_free(&r);
}

/* The sweep file `text` written to ROOT/s.ini, planned into ROOT/s (dir),
 * run on two jobs and collected into ROOT/s.csv (table); dir and table
 * hold len bytes. */
static inline void cli_sweep_through(const char *root, const char *text,
                                     char *dir, char *table, size_t len)
{
    char ini[4200];
    snprintf(ini, sizeof ini, "%s/s.ini", root);
    snprintf(dir, len, "%s/s", root);
    snprintf(table, len, "%s/s.csv", root);
    tmp_put(ini, text);
    cli_run_ok((const char *const[]){"sweep", "plan", ini, "--out", dir,
                                     "--quiet", NULL});
    cli_run_ok((const char *const[]){"sweep", "run", dir, "--jobs", "2",
                                     "--quiet", NULL});
    cli_run_ok((const char *const[]){"sweep", "collect", dir, "--out",
                                     table, "--quiet", NULL});
}

static inline size_t cli_count_lines(const char *s)
{
    size_t n = 0;
    for (; *s; s++)
        n += *s == '\n';
    return n;
}

/* A refused input: non-zero exit, nothing on stdout, and on stderr one
 * message line starting "clothode" that contains every string of the
 * NULL-terminated list `want`.  With `usage_lines` the message may be
 * followed by lines of usage help (none of them another "clothode..."
 * message); otherwise it must be the only line. */
static inline void cli_assert_error_list(const cli_result *r,
                                         int usage_lines,
                                         const char *const *want)
{
    cli_assert_no_crash(r);
    cr_assert_neq(r->status, 0, "%s: exit status 0 for a bad input", r->cmd);
    cr_assert_str_empty(r->out, "%s: wrote to stdout:\n%s", r->cmd, r->out);
    cr_assert(!strncmp(r->err, "clothode", 8),
              "%s: stderr does not start with \"clothode\":\n%s", r->cmd,
              r->err);
    const char *nl = strchr(r->err, '\n');
    cr_assert_not_null(nl, "%s: unterminated message:\n%s", r->cmd, r->err);
    size_t len = (size_t)(nl - r->err);
    if (!usage_lines)
        cr_assert_eq(cli_count_lines(r->err), 1,
                     "%s: expected one line on stderr, got\n%s", r->cmd,
                     r->err);
    else
        for (const char *p = nl + 1; *p; p = strchr(p, '\n') + 1) {
            cr_assert(strncmp(p, "clothode", 8),
                      "%s: a second message on stderr:\n%s", r->cmd, r->err);
            cr_assert_not_null(strchr(p, '\n'));
        }
    for (size_t k = 0; want[k]; k++) {
        const char *at = strstr(r->err, want[k]);
        cr_assert(at && at < r->err + len,
                  "%s: message lacks \"%s\":\n%s", r->cmd, want[k], r->err);
    }
}

/* The same with the strings as arguments: cli_assert_error(&r, 0, "dt",
 * NULL). */
static inline void cli_assert_error(const cli_result *r, int usage_lines,
                                    ...)
{
    const char *want[CLI_MAX_ARGS + 1];
    size_t n = 0;
    va_list ap;
    va_start(ap, usage_lines);
    for (const char *a; (a = va_arg(ap, const char *));) {
        cr_assert(n < CLI_MAX_ARGS, "too many strings");
        want[n++] = a;
    }
    va_end(ap);
    want[n] = NULL;
    cli_assert_error_list(r, usage_lines, want);
}

/* ---- scratch directories ---------------------------------------------- */

/* Made by tmp_mkdtemp(buf, len, "cli"), written with tmp_put, removed by
 * tmp_rm_rf (tmpdir.h). */

static inline int cli_exists(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 && S_ISREG(st.st_mode) && st.st_size > 0;
}

/* ---- CSV -------------------------------------------------------------- */

/* A CSV file as lines (line[0] the header), each without its '\n'. */
typedef struct {
    char *buf;
    char **line;
    size_t n;
} cli_lines;

static inline void cli_read_lines(const char *path, cli_lines *L)
{
    FILE *fp = fopen(path, "r");
    cr_assert_not_null(fp, "cannot open %s: %s", path, strerror(errno));
    L->buf = cli_slurp_fp(fp);
    fclose(fp);
    size_t cap = cli_count_lines(L->buf) + 1;
    L->line = malloc(cap * sizeof *L->line);
    cr_assert_not_null(L->line);
    L->n = 0;
    for (char *p = L->buf; *p;) {
        char *nl = strchr(p, '\n');
        L->line[L->n++] = p;
        if (!nl)
            break;
        *nl = '\0';
        p = nl + 1;
    }
}

static inline void cli_lines_free(cli_lines *L)
{
    free(L->buf);
    free(L->line);
    L->buf = NULL;
    L->line = NULL;
    L->n = 0;
}

/* Parse a line of exactly `n` comma-separated numbers into v. */
static inline void cli_parse_row(const char *line, double *v, size_t n,
                                 const char *what)
{
    const char *p = line;
    for (size_t k = 0; k < n; k++) {
        char *end;
        v[k] = strtod(p, &end);
        cr_assert(end != p, "%s: field %zu of \"%s\" is not a number", what,
                  k + 1, line);
        cr_assert(k + 1 == n ? *end == '\0' : *end == ',',
                  "%s: \"%s\" does not have %zu fields", what, line, n);
        p = end + 1;
    }
}

/* forces.csv (header p,fx,fy,fz, rows in particle order) of np
 * particles into f[3*np]. */
static inline void cli_read_forces(const char *path, size_t np, double *f)
{
    cli_lines L;
    cli_read_lines(path, &L);
    cr_assert(L.n >= 1, "%s is empty", path);
    cr_assert_str_eq(L.line[0], "p,fx,fy,fz", "%s: header", path);
    cr_assert_eq(L.n, np + 1, "%s: %zu rows, expected %zu", path, L.n - 1, np);
    for (size_t k = 1; k < L.n; k++) {
        double row[4];
        cli_parse_row(L.line[k], row, 4, path);
        cr_assert_eq(row[0], (double)(k - 1), "%s: row %zu is particle %g",
                     path, k, row[0]);
        memcpy(f + 3 * (k - 1), row + 1, 3 * sizeof *f);
    }
    cli_lines_free(&L);
}

/* A state file (header p,x,y,z,vx,vy,vz) of np particles into x, v
 * (3*np each, indexed by particle). */
static inline void cli_read_state(const char *path, size_t np, double *x,
                                  double *v)
{
    cli_lines L;
    cli_read_lines(path, &L);
    cr_assert(L.n >= 1);
    cr_assert_str_eq(L.line[0], "p,x,y,z,vx,vy,vz", "%s: header", path);
    cr_assert_eq(L.n, np + 1, "%s: %zu rows, expected %zu", path, L.n - 1,
                 np);
    unsigned char *seen = calloc(np, 1);
    for (size_t k = 1; k < L.n; k++) {
        double row[7];
        cli_parse_row(L.line[k], row, 7, path);
        size_t p = (size_t)row[0];
        cr_assert(row[0] >= 0 && p < np && (double)p == row[0] && !seen[p],
                  "%s: bad or repeated particle index in \"%s\"", path,
                  L.line[k]);
        seen[p] = 1;
        memcpy(x + 3 * p, row + 1, 3 * sizeof *x);
        memcpy(v + 3 * p, row + 4, 3 * sizeof *v);
    }
    free(seen);
    cli_lines_free(&L);
}

#endif
