/* Tests for io/config: INI loading with line numbers, --set overrides, strict
 * typed getters, unused-key detection and write/reload round trips; the
 * fuzzing harness of the loader on its seeds and on every input that once
 * made it fail (tests/fuzz/config/crash-*). */
#define _GNU_SOURCE /* memmem, memfd_create: the harness */
#include <criterion/criterion.h>

#include <dirent.h>
#include <limits.h>
#include <stdarg.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "io/config.h"

#define CL_FUZZ_ENTRY cl_fuzz_config_one
#include "fuzz/fuzz_config.c"

static const char *const integrators[] = {"cvode-bdf", "symplectic-euler",
                                          NULL};

/* A temporary file holding `text`; the name goes into path[]. */
static void write_tmp(char path[64], const char *text)
{
    strcpy(path, "/tmp/clothode-config-XXXXXX");
    int fd = mkstemp(path);
    cr_assert_geq(fd, 0, "mkstemp failed");
    FILE *f = fdopen(fd, "w");
    cr_assert_not_null(f);
    cr_assert_geq(fputs(text, f), 0);
    cr_assert_eq(fclose(f), 0);
}

/* Load `text` into cfg through a temporary file (removed afterwards). */
static cl_status load_text(cl_config *cfg, const char *text, char path[64],
                           cl_error *err)
{
    write_tmp(path, text);
    cl_status rc = cl_config_load(cfg, path, err);
    unlink(path);
    return rc;
}

/* A configuration loaded from `text` that must parse. */
static cl_config *cfg_from(const char *text)
{
    char path[64];
    cl_error err = {0};
    cl_config *cfg = cl_config_alloc();
    cr_assert_not_null(cfg);
    cl_status rc = load_text(cfg, text, path, &err);
    cr_assert_eq(rc, CL_OK, "load failed: %s", err.msg);
    return cfg;
}

#define assert_msg_has(err, text)                                            \
    cr_assert_not_null(strstr((err).msg, (text)),                            \
                       "message \"%s\" lacks \"%s\"", (err).msg, (text))

/* ------------------------------------------------------------- parsing */

Test(config, parses_numbers)
{
    cl_config *cfg = cfg_from("[type1]\nks = 200\nkd = -1.5e-3\n"
                              "m = 0x1p-2\nc = +7.25   ; comment\n");
    cl_error err = {0};
    double ks = 0, kd = 0, m = 0, c = 0;
    cr_assert_eq(cl_config_double(cfg, "type1", "ks", 1, 0, INFINITY, &ks,
                                  &err), CL_OK, "%s", err.msg);
    cr_assert_eq(cl_config_double(cfg, "type1", "kd", 1, -INFINITY,
                                  INFINITY, &kd, &err), CL_OK, "%s", err.msg);
    cr_assert_eq(cl_config_double(cfg, "type1", "m", 1, 0, 1, &m, &err),
                 CL_OK, "%s", err.msg);
    cr_assert_eq(cl_config_double(cfg, "type1", "c", 1, 7.25, 7.25, &c,
                                  &err), CL_OK, "bounds are inclusive: %s",
                 err.msg);
    cr_assert_eq(ks, 200.0);
    cr_assert_eq(kd, -1.5e-3);
    cr_assert_eq(m, 0.25);
    cr_assert_eq(c, 7.25);
    cl_config_free(cfg);
}

Test(config, parses_integers)
{
    cl_config *cfg = cfg_from("[cloth]\nnx = 32\nny = +3\nneg = -4096\n");
    cl_error err = {0};
    long nx = 0, ny = 0, neg = 0;
    cr_assert_eq(cl_config_long(cfg, "cloth", "nx", 1, 3, 4096, &nx, &err),
                 CL_OK, "%s", err.msg);
    cr_assert_eq(cl_config_long(cfg, "cloth", "ny", 1, 3, 4096, &ny, &err),
                 CL_OK, "%s", err.msg);
    cr_assert_eq(cl_config_long(cfg, "cloth", "neg", 1, LONG_MIN, LONG_MAX,
                                &neg, &err), CL_OK, "%s", err.msg);
    cr_assert_eq(nx, 32);
    cr_assert_eq(ny, 3);
    cr_assert_eq(neg, -4096);
    cl_config_free(cfg);
}

Test(config, parses_bools)
{
    static const struct {
        const char *text;
        bool value;
    } cases[] = {{"true", true}, {"FALSE", false}, {"Yes", true},
                 {"no", false},  {"ON", true},     {"off", false},
                 {"1", true},    {"0", false}};
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        cl_config *cfg = cl_config_alloc();
        cl_error err = {0};
        char set[64];
        snprintf(set, sizeof set, "run.flag=%s", cases[i].text);
        cr_assert_eq(cl_config_set(cfg, set, &err), CL_OK, "%s", err.msg);
        bool b = !cases[i].value;
        cr_assert_eq(cl_config_bool(cfg, "run", "flag", !cases[i].value, &b,
                                    &err), CL_OK, "%s: %s", set, err.msg);
        cr_assert_eq(b, cases[i].value, "%s", set);
        cl_config_free(cfg);
    }
}

Test(config, parses_choices)
{
    cl_config *cfg = cfg_from("[run]\nintegrator = symplectic-euler\n");
    cl_error err = {0};
    int k = -1;
    cr_assert_eq(cl_config_choice(cfg, "run", "integrator", integrators, 0,
                                  &k, &err), CL_OK, "%s", err.msg);
    cr_assert_eq(k, 1);
    cl_config_free(cfg);
}

Test(config, parses_vectors)
{
    cl_config *cfg = cfg_from("[gravity]\ng = 0, -9.81, 0\n"
                              "a = 1 2\t3\nb = 1 ,2,  3\nc = 5\n");
    cl_error err = {0};
    double g[3], a[3], b[3], c[1];
    cr_assert_eq(cl_config_vector(cfg, "gravity", "g", 3, g, &err), CL_OK,
                 "%s", err.msg);
    cr_assert_eq(cl_config_vector(cfg, "gravity", "a", 3, a, &err), CL_OK,
                 "%s", err.msg);
    cr_assert_eq(cl_config_vector(cfg, "gravity", "b", 3, b, &err), CL_OK,
                 "%s", err.msg);
    cr_assert_eq(cl_config_vector(cfg, "gravity", "c", 1, c, &err), CL_OK,
                 "%s", err.msg);
    cr_assert(g[0] == 0 && g[1] == -9.81 && g[2] == 0);
    cr_assert(a[0] == 1 && a[1] == 2 && a[2] == 3);
    cr_assert(b[0] == 1 && b[1] == 2 && b[2] == 3);
    cr_assert_eq(c[0], 5);
    cl_config_free(cfg);
}

Test(config, parses_strings_and_sectionless_keys)
{
    cl_config *cfg = cfg_from("name = hang\n[output]\ndir = out/run 1\n");
    cr_assert_str_eq(cl_config_string(cfg, "", "name", "x"), "hang");
    cr_assert_str_eq(cl_config_string(cfg, "output", "dir", "x"),
                     "out/run 1");
    cr_assert_str_eq(cl_config_string(cfg, "output", "none", "dflt"),
                     "dflt");
    cl_config_free(cfg);
}

Test(config, absent_keys_give_defaults)
{
    cl_config *cfg = cfg_from("[run]\nt_end = 1\n");
    cl_error err = {0};
    double d = 0;
    long l = 0;
    bool b = false;
    int k = -1;
    double v[3] = {7, 8, 9};
    cr_assert_eq(cl_config_double(cfg, "run", "dt", 0.5, 0, 1, &d, &err),
                 CL_OK);
    cr_assert_eq(cl_config_long(cfg, "run", "n", 12, 0, 100, &l, &err),
                 CL_OK);
    cr_assert_eq(cl_config_bool(cfg, "run", "b", true, &b, &err), CL_OK);
    cr_assert_eq(cl_config_choice(cfg, "x", "y", integrators, 1, &k, &err),
                 CL_OK);
    cr_assert_eq(cl_config_vector(cfg, "gravity", "g", 3, v, &err), CL_OK);
    cr_assert_eq(d, 0.5);
    cr_assert_eq(l, 12);
    cr_assert(b);
    cr_assert_eq(k, 1);
    cr_assert(v[0] == 7 && v[1] == 8 && v[2] == 9, "vector left untouched");
    cl_config_free(cfg);
}

Test(config, keys_and_sections_are_case_sensitive_and_trimmed)
{
    cl_config *cfg = cfg_from("[ Run ]\n  Dt   =   0.25  \n");
    cl_error err = {0};
    double d = -1;
    cr_assert_eq(cl_config_double(cfg, "run", "dt", 1, 0, 1, &d, &err),
                 CL_OK);
    cr_assert_eq(d, 1, "different case is a different key");
    cr_assert_eq(cl_config_double(cfg, "Run", "Dt", 1, 0, 1, &d, &err),
                 CL_OK, "%s", err.msg);
    cr_assert_eq(d, 0.25);
    cl_config_free(cfg);
}

Test(config, set_overrides_file_and_adds_keys)
{
    cl_config *cfg = cfg_from("[type1]\nks = 200\n");
    cl_error err = {0};
    cr_assert_eq(cl_config_set(cfg, "type1.ks=300", &err), CL_OK, "%s",
                 err.msg);
    cr_assert_eq(cl_config_set(cfg, " run . t_end = 4.5 ", &err), CL_OK,
                 "%s", err.msg);
    cr_assert_eq(cl_config_set(cfg, "a.b.c=x=y", &err), CL_OK, "%s",
                 err.msg);
    cr_assert_eq(cl_config_set(cfg, "out.note=", &err), CL_OK, "%s",
                 err.msg);
    double ks = 0, t = 0;
    cr_assert_eq(cl_config_double(cfg, "type1", "ks", 0, 0, INFINITY, &ks,
                                  &err), CL_OK);
    cr_assert_eq(cl_config_double(cfg, "run", "t_end", 0, 0, INFINITY, &t,
                                  &err), CL_OK, "%s", err.msg);
    cr_assert_eq(ks, 300);
    cr_assert_eq(t, 4.5);
    /* split at the last '.' before '=': sections may hold dots
     * ([obstacle.ball]), keys do not */
    cr_assert_str_eq(cl_config_string(cfg, "a.b", "c", NULL), "x=y");
    cr_assert_str_eq(cl_config_string(cfg, "out", "note", NULL), "");
    char buf[64];
    cr_assert_str_eq(cl_config_origin(cfg, "type1", "ks", buf, sizeof buf),
                     "--set");
    cr_assert_str_eq(cl_config_origin(cfg, "type1", "kd", buf, sizeof buf),
                     "(default)");
    cl_config_free(cfg);
}

/* ------------------------------------------------------- loading errors */

/* Loading `text` fails with CL_EPARSE, the message naming "<file>:<line>:"
 * and containing each string of the NULL-terminated argument list. */
static void expect_parse_error(const char *text, int line, ...)
{
    char path[64], want[96];
    cl_error err = {0};
    cl_config *cfg = cl_config_alloc();
    cr_assert_eq(load_text(cfg, text, path, &err), CL_EPARSE);
    cr_assert_eq(err.code, CL_EPARSE);
    snprintf(want, sizeof want, "%s:%d:", path, line);
    assert_msg_has(err, want);
    va_list ap;
    va_start(ap, line);
    for (const char *sub; (sub = va_arg(ap, const char *));)
        assert_msg_has(err, sub);
    va_end(ap);
    cl_config_free(cfg);
}

/* Loading the file at path fails with code, the message containing each
 * string of the NULL-terminated argument list. */
static void expect_load_refused(const char *path, cl_status code, ...)
{
    cl_config *cfg = cl_config_alloc();
    cl_error err = {0};
    cr_assert_eq(cl_config_load(cfg, path, &err), code, "%s: %s", path,
                 err.msg);
    cr_assert_eq(err.code, code);
    va_list ap;
    va_start(ap, code);
    for (const char *sub; (sub = va_arg(ap, const char *));)
        assert_msg_has(err, sub);
    va_end(ap);
    cl_config_free(cfg);
}

Test(config, missing_file_is_eio)
{
    expect_load_refused("/nonexistent/dir/hang.ini", CL_EIO,
                        "/nonexistent/dir/hang.ini", "No such file", NULL);
}

Test(config, directory_is_eio)
{
    expect_load_refused("/tmp", CL_EIO, "/tmp", NULL);
}

/* A device (one that never ends, too) is refused before it is read. */
Test(config, endless_device_is_refused_unread)
{
    expect_load_refused("/dev/zero", CL_EIO,
                        "/dev/zero: it is a device, not a regular file",
                        NULL);
}

/* Text beyond 16 MiB (here comments, endless in spirit) is refused. */
Test(config, text_beyond_16_mib_is_refused)
{
    char path[64];
    write_tmp(path, "");
    FILE *fp = fopen(path, "w");
    cr_assert_not_null(fp);
    static char line[4096];
    memset(line, '#', sizeof line - 1);
    line[sizeof line - 2] = '\n';
    for (int k = 0; k < (16 << 20) / (int)(sizeof line - 1) + 2; k++)
        fputs(line, fp);
    cr_assert_eq(fclose(fp), 0);
    expect_load_refused(path, CL_EPARSE, "longer than 16 MiB", NULL);
    unlink(path);
}

Test(config, malformed_line_reports_its_line)
{
    expect_parse_error("; comment\n[run]\ndt = 1\n"
                       "this line has no equals sign\nx = 2\n"
                       "another bad line\n", 4, "malformed", NULL);
}

Test(config, malformed_section_header)
{
    expect_parse_error("[run]\ndt = 1\n[broken\n", 3, NULL);
}

/* Text after a section's ']' would be dropped unread: refused, but for a
 * comment. */
Test(config, text_after_a_section_header_is_refused)
{
    expect_parse_error("[run]\ndt = 1\n[damping] kd = 5\n", 3,
                       "text after the section header: \"kd = 5\"", NULL);
    expect_parse_error("[damping]]\nkd = 5\n", 1, "\"]\"", NULL);
    cl_config *cfg = cfg_from("[damping] ; the dashpots\nkd = 5\n");
    cr_assert_not_null(cfg);
    cl_config_free(cfg);
}

Test(config, indented_continuation_is_rejected)
{
    expect_parse_error("[cloth]\nnx = 10\n  ny = 10\n", 3, "[cloth] nx",
                       "indent", NULL);
}

Test(config, indented_key_after_header_is_fine)
{
    cl_config *cfg = cfg_from("[cloth]\n   nx = 10\n");
    cr_assert_str_eq(cl_config_string(cfg, "cloth", "nx", ""), "10");
    cl_config_free(cfg);
}

Test(config, long_line_is_reported_not_split)
{
    size_t n = 5000;
    char *text = malloc(n + 64);
    cr_assert_not_null(text);
    strcpy(text, "[run]\ndt = 1\nnote = ");
    size_t len = strlen(text);
    memset(text + len, 'a', n);
    strcpy(text + len + n, "\nx = 1\n");
    expect_parse_error(text, 3, "line of 5007 characters; the INI parser reads"
                       " lines of at most 197", NULL);
    free(text);
}

Test(config, last_line_without_newline_and_crlf)
{
    cl_config *cfg = cfg_from("[run]\r\ndt = 0.5\r\nn = 3");
    cl_error err = {0};
    double dt = 0;
    long n = 0;
    cr_assert_eq(cl_config_double(cfg, "run", "dt", 0, 0, 1, &dt, &err),
                 CL_OK, "%s", err.msg);
    cr_assert_eq(cl_config_long(cfg, "run", "n", 0, 0, 9, &n, &err), CL_OK,
                 "%s", err.msg);
    cr_assert_eq(dt, 0.5);
    cr_assert_eq(n, 3);
    cl_config_free(cfg);
}

/* -------------------------------------------------------- getter errors */

/* Load "[sec]\n<line>" and return the path (line 2 holds the key). */
static cl_config *cfg_one(const char *text, char path[64])
{
    cl_error err = {0};
    cl_config *cfg = cl_config_alloc();
    cr_assert_eq(load_text(cfg, text, path, &err), CL_OK, "%s", err.msg);
    return cfg;
}

/* ------------------------------------------------------ strict inputs */

Test(config, duplicate_key_is_refused_with_both_lines)
{
    char path[64], want[160];
    cl_error err = {0};
    cl_config *cfg = cl_config_alloc();
    cr_assert_eq(load_text(cfg, "[run]\ndt = 1\nt_end = 2\ndt = 2\n", path,
                           &err), CL_EPARSE);
    snprintf(want, sizeof want,
             "%s:4: duplicate key [run] dt (first on line 2)", path);
    assert_msg_has(err, want);
    cl_config_free(cfg);
}

Test(config, duplicate_section_is_refused)
{
    expect_parse_error("[run]\ndt = 1\n\n[other]\nx = 1\n[ run ]\nt = 2\n",
                       6, "duplicate section [run] (opened on line 1)",
                       NULL);
}

Test(config, later_file_overrides_with_its_own_origin)
{
    char path[64], want[96];
    cl_error err = {0};
    cl_config *cfg = cfg_from("[run]\ndt = 1\n");
    cr_assert_eq(load_text(cfg, "; override\n[run]\ndt = 2\n", path, &err),
                 CL_OK, "%s", err.msg);
    double dt = 0;
    cr_assert_eq(cl_config_double(cfg, "run", "dt", 0, 0, 10, &dt, &err),
                 CL_OK);
    cr_assert_eq(dt, 2);
    char buf[128];
    snprintf(want, sizeof want, "%s:3", path);
    cr_assert_str_eq(cl_config_origin(cfg, "run", "dt", buf, sizeof buf),
                     want);
    cl_config_free(cfg);
}

Test(config, nul_byte_is_refused_with_line_and_column)
{
    static const char text[] = "[run]\ndt = 1\0 2\n";
    char path[64] = "/tmp/clothode-config-XXXXXX", want[96];
    int fd = mkstemp(path);
    cr_assert_geq(fd, 0);
    cr_assert_eq(write(fd, text, sizeof text - 1), (ssize_t)sizeof text - 1);
    cr_assert_eq(close(fd), 0);
    cl_error err = {0};
    cl_config *cfg = cl_config_alloc();
    cr_assert_eq(cl_config_load(cfg, path, &err), CL_EPARSE);
    unlink(path);
    snprintf(want, sizeof want, "%s:2: NUL byte at column 7", path);
    assert_msg_has(err, want);
    cl_config_free(cfg);
}

Test(config, empty_file_is_refused)
{
    expect_parse_error("", 1, "no key = value line", NULL);
    expect_parse_error("; comments only\n\n[run]\n", 1,
                       "no key = value line", NULL);
}

Test(config, huge_tiny_and_non_physical_numbers_are_refused)
{
    static const char *const bad[][2] = {
        {"1e400", "beyond the range of a double"},
        {"-1e-400", "rounds to a subnormal number or zero"},
        {"1e300", "larger in magnitude than any physical parameter"},
        {"1.000001e12", "at most 1e12"}};
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
        char text[64], path[64], want[160];
        snprintf(text, sizeof text, "[type1]\nks = %s\n", bad[i][0]);
        cl_config *cfg = cfg_one(text, path);
        cl_error err = {0};
        double ks = 0;
        cr_assert_eq(cl_config_double(cfg, "type1", "ks", 1, -INFINITY,
                                      INFINITY, &ks, &err), CL_EINVAL, "%s",
                     bad[i][0]);
        snprintf(want, sizeof want, "%s:2: [type1] ks = \"%s\": expected a"
                 " number in [-1e+12, 1e+12] (this is", path, bad[i][0]);
        assert_msg_has(err, want);
        assert_msg_has(err, bad[i][1]);
        cl_config_free(cfg);
    }
    cl_config *cfg = cfg_from("[type1]\nks = 1e12\n");
    cl_error err = {0};
    double ks = 0;
    cr_assert_eq(cl_config_double(cfg, "type1", "ks", 1, 0, INFINITY, &ks,
                                  &err), CL_OK, "%s", err.msg);
    cr_assert_eq(ks, 1e12);
    cl_config_free(cfg);
}

Test(config, set_of_a_key_twice_is_refused)
{
    cl_config *cfg = cl_config_alloc();
    cl_error err = {0};
    cr_assert_eq(cl_config_set_once(cfg, "run.dt=1", NULL, &err), CL_OK);
    cr_assert_eq(cl_config_set_once(cfg, "run.dt=2", NULL, &err), CL_EINVAL);
    assert_msg_has(err, "--set \"run.dt=2\": [run] dt is already set by an"
                        " earlier --set");
    cr_assert_eq(cl_config_set_once(cfg, "run.rtol=1e-6", "--rtol", &err),
                 CL_OK);
    cr_assert_eq(cl_config_set_once(cfg, "run.rtol=1e-7", NULL, &err),
                 CL_EINVAL);
    assert_msg_has(err, "[run] rtol is already set by --rtol");
    cr_assert_eq(cl_config_set(cfg, "run.rtol=1e-8", &err), CL_OK,
                 "a library caller may override");
    cl_config_free(cfg);
}

Test(config, set_too_long_for_a_line_is_refused)
{
    char set[256] = "run.note=";
    memset(set + strlen(set), 'a', 193);
    cl_config *cfg = cl_config_alloc();
    cl_error err = {0};
    cr_assert_eq(cl_config_set(cfg, set, &err), CL_EINVAL);
    assert_msg_has(err, "too long for a line of the INI file written back"
                        " (at most 197 characters for key=value)");
    set[strlen(set) - 1] = '\0'; /* note=<192 a>: 197 characters */
    cr_assert_eq(cl_config_set(cfg, set, &err), CL_OK, "%s", err.msg);
    cl_config_free(cfg);
}

Test(config, non_numeric_double_is_rejected)
{
    static const char *const bad[] = {"abc", "1.5x", "1.5 2", "--1", "1e",
                                      "1e999"};
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
        char text[64], path[64], want[160];
        snprintf(text, sizeof text, "; hang\n[type1]\nks = %s\n", bad[i]);
        cl_config *cfg = cfg_one(text, path);
        cl_error err = {0};
        double ks = 42;
        cr_assert_eq(cl_config_double(cfg, "type1", "ks", 1, 0, INFINITY,
                                      &ks, &err), CL_EINVAL, "%s", bad[i]);
        cr_assert_eq(ks, 42, "output untouched on error");
        snprintf(want, sizeof want,
                 "%s:3: [type1] ks = \"%s\": expected a number in [0, 1e+12]",
                 path,
                 bad[i]);
        assert_msg_has(err, want);
        cl_config_free(cfg);
    }
}

Test(config, empty_value_is_rejected)
{
    char path[64];
    cl_config *cfg = cfg_one("[type1]\nks =\n", path);
    cl_error err = {0};
    double ks = 0;
    cr_assert_eq(cl_config_double(cfg, "type1", "ks", 1, -INFINITY,
                                  INFINITY, &ks, &err), CL_EINVAL);
    assert_msg_has(err, "ks = \"\": expected a number in [-1e+12, 1e+12]");
    cl_config_free(cfg);
}

Test(config, nan_and_inf_are_rejected)
{
    static const char *const bad[] = {"nan", "NaN", "inf", "-inf",
                                      "infinity"};
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
        cl_config *cfg = cl_config_alloc();
        cl_error err = {0};
        char set[64];
        snprintf(set, sizeof set, "run.dt=%s", bad[i]);
        cr_assert_eq(cl_config_set(cfg, set, &err), CL_OK);
        double dt = 0;
        cr_assert_eq(cl_config_double(cfg, "run", "dt", 1, -INFINITY,
                                      INFINITY, &dt, &err), CL_EINVAL, "%s",
                     bad[i]);
        assert_msg_has(err, "--set: [run] dt");
        assert_msg_has(err, "expected a number in [-1e+12, 1e+12] (this is");
        cl_config_free(cfg);
    }
}

Test(config, double_out_of_range_shows_range)
{
    char path[64], want[96];
    cl_config *cfg = cfg_one("[run]\ndt = 2\nrho = -1\nc = 1\n", path);
    cl_error err = {0};
    double x = 0;
    cr_assert_eq(cl_config_double(cfg, "run", "dt", 0, 0.001, 1, &x, &err),
                 CL_EINVAL);
    snprintf(want, sizeof want, "%s:2:", path);
    assert_msg_has(err, want);
    assert_msg_has(err, "expected a number in [0.001, 1]");
    cr_assert_eq(cl_config_double(cfg, "run", "rho", 0, 0, INFINITY, &x,
                                  &err), CL_EINVAL);
    assert_msg_has(err, "[run] rho = \"-1\": expected a number in [0, 1e+12]");
    cr_assert_eq(cl_config_double(cfg, "run", "c", 0, -INFINITY, 0.1, &x,
                                  &err), CL_EINVAL);
    assert_msg_has(err, "expected a number in [-1e+12, 0.1]");
    cl_config_free(cfg);
}

Test(config, integer_errors_show_range)
{
    static const char *const bad[] = {"2", "5000", "1.0", "1e3", "0x10",
                                      "abc", "99999999999999999999999"};
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
        char text[96], path[64], want[160];
        snprintf(text, sizeof text, "[cloth]\nnx = %s\n", bad[i]);
        cl_config *cfg = cfg_one(text, path);
        cl_error err = {0};
        long nx = 7;
        cr_assert_eq(cl_config_long(cfg, "cloth", "nx", 1, 3, 4096, &nx,
                                    &err), CL_EINVAL, "%s", bad[i]);
        cr_assert_eq(nx, 7);
        snprintf(want, sizeof want,
                 "%s:2: [cloth] nx = \"%s\": expected an integer in"
                 " [3, 4096]", path, bad[i]);
        assert_msg_has(err, want);
        cl_config_free(cfg);
    }
}

Test(config, integer_one_sided_ranges)
{
    cl_config *cfg = cl_config_alloc();
    cl_error err = {0};
    long x = 0;
    cr_assert_eq(cl_config_set(cfg, "a.n=-1", &err), CL_OK);
    cr_assert_eq(cl_config_long(cfg, "a", "n", 0, 0, LONG_MAX, &x, &err),
                 CL_EINVAL);
    assert_msg_has(err, "expected an integer >= 0");
    cr_assert_eq(cl_config_set(cfg, "a.m=x", &err), CL_OK);
    cr_assert_eq(cl_config_long(cfg, "a", "m", 0, LONG_MIN, LONG_MAX, &x,
                                &err), CL_EINVAL);
    assert_msg_has(err, "\"x\": expected an integer");
    cl_config_free(cfg);
}

Test(config, bad_bool_is_rejected)
{
    char path[64];
    cl_config *cfg = cfg_one("[type2]\nenabled = maybe\n", path);
    cl_error err = {0};
    bool b = true;
    cr_assert_eq(cl_config_bool(cfg, "type2", "enabled", true, &b, &err),
                 CL_EINVAL);
    assert_msg_has(err, ":2: [type2] enabled = \"maybe\": expected");
    assert_msg_has(err, "true/false");
    cl_config_free(cfg);
}

Test(config, bad_choice_lists_allowed_names)
{
    char path[64], want[160];
    cl_config *cfg = cfg_one("[run]\nintegrator = foo\n", path);
    cl_error err = {0};
    int k = 5;
    cr_assert_eq(cl_config_choice(cfg, "run", "integrator", integrators, 0,
                                  &k, &err), CL_EINVAL);
    cr_assert_eq(k, 5);
    snprintf(want, sizeof want,
             "%s:2: [run] integrator = \"foo\": expected one of cvode-bdf,"
             " symplectic-euler", path);
    assert_msg_has(err, want);
    cl_config_free(cfg);
}

Test(config, choice_is_case_sensitive)
{
    cl_config *cfg = cl_config_alloc();
    cl_error err = {0};
    int k = 0;
    cr_assert_eq(cl_config_set(cfg, "run.integrator=CVODE-BDF", &err),
                 CL_OK);
    cr_assert_eq(cl_config_choice(cfg, "run", "integrator", integrators, 0,
                                  &k, &err), CL_EINVAL);
    cl_config_free(cfg);
}

Test(config, bad_vectors_are_rejected)
{
    static const char *const bad[] = {"0, -9.81",   "0, 1, 2, 3", "0, x, 1",
                                      "0,,1,2",     ",0,1,2",     "0,1,2,",
                                      "0, inf, 1",  "0, nan, 1",  "1-2 3 4",
                                      ""};
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
        cl_config *cfg = cl_config_alloc();
        cl_error err = {0};
        char set[64];
        snprintf(set, sizeof set, "gravity.g=%s", bad[i]);
        cr_assert_eq(cl_config_set(cfg, set, &err), CL_OK, "%s", err.msg);
        double g[3] = {1, 2, 3};
        cr_assert_eq(cl_config_vector(cfg, "gravity", "g", 3, g, &err),
                     CL_EINVAL, "\"%s\" accepted", bad[i]);
        cr_assert(g[0] == 1 && g[1] == 2 && g[2] == 3, "output untouched");
        assert_msg_has(err, "--set: [gravity] g = \"");
        assert_msg_has(err, "expected 3 finite numbers separated by commas");
        cl_config_free(cfg);
    }
}

/* ------------------------------------------------------------ --set form */

Test(config, bad_set_forms_are_rejected)
{
    static const char *const bad[] = {"run.dt",   "rundt=1",   ".dt=1",
                                      "run.=1",   " . =1",     "run=a.b",
                                      "run.a:b=1", "run.#x=1", "r]n.x=1",
                                      "run.x=a ;b", "run.x=;b"};
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
        cl_config *cfg = cl_config_alloc();
        cl_error err = {0};
        cr_assert_eq(cl_config_set(cfg, bad[i], &err), CL_EINVAL, "%s",
                     bad[i]);
        char want[64];
        snprintf(want, sizeof want, "\"%s\"", bad[i]);
        assert_msg_has(err, want);
        assert_msg_has(err, "section.key=value");
        cr_assert_eq(cl_config_check_unused(cfg, &err), CL_OK,
                     "nothing was stored for %s", bad[i]);
        cl_config_free(cfg);
    }
}

/* ----------------------------------------------------------- unused keys */

Test(config, all_keys_used_passes)
{
    cl_config *cfg = cfg_from("[run]\ndt = 1\n[output]\ndir = x\n");
    cl_error err = {0};
    double dt;
    cr_assert_eq(cl_config_double(cfg, "run", "dt", 0, 0, 9, &dt, &err),
                 CL_OK);
    cl_config_string(cfg, "output", "dir", NULL);
    cr_assert_eq(cl_config_check_unused(cfg, &err), CL_OK, "%s", err.msg);
    cl_config_free(cfg);
}

Test(config, unknown_key_reported_with_line_and_known_keys)
{
    char path[64], want[160];
    cl_config *cfg = cfg_one("[run]\ndt = 1\n\n[type1]\nks = 1\n\n"
                             "kss = 2\nfoo = 3\n", path);
    cl_error err = {0};
    double x;
    cr_assert_eq(cl_config_double(cfg, "type1", "ks", 0, 0, 9, &x, &err),
                 CL_OK);
    cr_assert_eq(cl_config_double(cfg, "type1", "kd", 0, 0, 9, &x, &err),
                 CL_OK, "absent key, still known");
    cr_assert_eq(cl_config_double(cfg, "run", "dt", 0, 0, 9, &x, &err),
                 CL_OK);
    cr_assert_eq(cl_config_check_unused(cfg, &err), CL_EINVAL);
    cr_assert_eq(err.code, CL_EINVAL);
    snprintf(want, sizeof want,
             "%s:7: unknown key [type1] kss (known keys in [type1]: ks, kd)",
             path);
    assert_msg_has(err, want);
    cl_config_free(cfg);
}

Test(config, unknown_section_reported)
{
    char path[64], want[160];
    cl_config *cfg = cfg_one("[run]\ndt = 1\n[typ1]\nks = 1\n", path);
    cl_error err = {0};
    double x;
    cl_config_double(cfg, "run", "dt", 0, 0, 9, &x, &err);
    cl_config_double(cfg, "type1", "ks", 0, 0, 9, &x, &err);
    cl_config_double(cfg, "type1", "kd", 0, 0, 9, &x, &err);
    cr_assert_eq(cl_config_check_unused(cfg, &err), CL_EINVAL);
    snprintf(want, sizeof want,
             "%s:4: unknown section [typ1] (known sections: [run], [type1])",
             path);
    assert_msg_has(err, want);
    cl_config_free(cfg);
}

/* A family of sections read through cl_config_section_at counts as known,
 * [obstacle.NAME]; its keys are those asked for in each member. */
Test(config, section_family_reported_as_known)
{
    char path[64], want[200];
    cl_config *cfg = cfg_one("[run]\ndt = 1\n[obstacle.ball]\nr = 1\n"
                             "rr = 2\n[obstacl.ball]\nr = 1\n", path);
    cl_error err = {0};
    double x;
    cl_config_double(cfg, "run", "dt", 0, 0, 9, &x, &err);
    cr_assert_str_eq(cl_config_section_at(cfg, "obstacle.", 0),
                     "obstacle.ball");
    cr_assert_null(cl_config_section_at(cfg, "obstacle.", 1));
    cl_config_double(cfg, "obstacle.ball", "r", 0, 0, 9, &x, &err);
    cr_assert_eq(cl_config_check_unused(cfg, &err), CL_EINVAL);
    snprintf(want, sizeof want, "%s:5: unknown key [obstacle.ball] rr "
             "(known keys in [obstacle.ball]: r)", path);
    assert_msg_has(err, want);
    cl_config_double(cfg, "obstacle.ball", "rr", 0, 0, 9, &x, &err);
    cr_assert_eq(cl_config_check_unused(cfg, &err), CL_EINVAL);
    snprintf(want, sizeof want, "%s:7: unknown section [obstacl.ball] "
             "(known sections: [run], [obstacle.NAME], [obstacle.ball])",
             path);
    assert_msg_has(err, want);
    cl_config_free(cfg);
}

Test(config, load_without_a_path_is_refused)
{
    cl_config *cfg = cl_config_alloc();
    cl_error err = {0};
    cr_assert_eq(cl_config_load(cfg, NULL, &err), CL_EINVAL);
    cr_assert_str_eq(err.msg, "no problem file named (path NULL)");
    cl_config_free(cfg);
}

Test(config, unknown_key_outside_sections)
{
    char path[64], want[160];
    cl_config *cfg = cfg_one("title = x\n[run]\ndt = 1\n", path);
    cl_error err = {0};
    double x;
    cl_config_double(cfg, "run", "dt", 0, 0, 9, &x, &err);
    cr_assert_eq(cl_config_check_unused(cfg, &err), CL_EINVAL);
    snprintf(want, sizeof want,
             "%s:1: unknown key title outside any section (known sections:"
             " [run])", path);
    assert_msg_has(err, want);
    cl_config_free(cfg);
}

Test(config, unknown_key_from_set)
{
    cl_config *cfg = cfg_from("[run]\ndt = 1\n");
    cl_error err = {0};
    double x;
    cr_assert_eq(cl_config_set(cfg, "run.dtt=2", &err), CL_OK);
    cl_config_double(cfg, "run", "dt", 0, 0, 9, &x, &err);
    cr_assert_eq(cl_config_check_unused(cfg, &err), CL_EINVAL);
    assert_msg_has(err, "--set: unknown key [run] dtt (known keys in [run]:"
                        " dt)");
    cl_config_free(cfg);
}

Test(config, key_set_after_it_was_asked_counts_as_used)
{
    cl_config *cfg = cl_config_alloc();
    cl_error err = {0};
    double x;
    cl_config_double(cfg, "run", "dt", 0, 0, 9, &x, &err);
    cr_assert_eq(cl_config_set(cfg, "run.dt=2", &err), CL_OK);
    cr_assert_eq(cl_config_check_unused(cfg, &err), CL_OK, "%s", err.msg);
    cl_config_free(cfg);
}

Test(config, ignored_section_is_not_reported)
{
    cl_config *cfg = cfg_from("[run]\ndt = 1\nt_end = 2\n[type1]\nks = 1\n");
    cl_error err = {0};
    double x;
    cl_config_double(cfg, "type1", "ks", 0, 0, 9, &x, &err);
    cl_config_ignore_section(cfg, "run");
    cr_assert_eq(cl_config_check_unused(cfg, &err), CL_OK, "%s", err.msg);
    cl_config_free(cfg);
}

/* --------------------------------------------------------------- writing */

Test(config, write_and_reload_round_trip)
{
    cl_config *cfg = cfg_from("title = hang\n[type1]\nks = 200\nkd = 0.5\n"
                              "[run]\ndt = 1e-3\n");
    cl_error err = {0};
    cr_assert_eq(cl_config_set(cfg, "type1.ks=250", &err), CL_OK);
    cr_assert_eq(cl_config_set(cfg, "run.integrator=cvode-bdf", &err), CL_OK);
    cr_assert_eq(cl_config_set(cfg, "gravity.g=0, -9.81, 0", &err), CL_OK);
    cr_assert_eq(cl_config_set(cfg, "output.note=", &err), CL_OK);
    char path[64];
    write_tmp(path, "old contents\n");
    cr_assert_eq(cl_config_write(cfg, path, &err), CL_OK, "%s", err.msg);

    /* grouped by section, first-appearance order, final values only */
    FILE *f = fopen(path, "r");
    cr_assert_not_null(f);
    char text[512] = {0};
    size_t n = fread(text, 1, sizeof text - 1, f);
    fclose(f);
    cr_assert_gt(n, 0);
    const char *top = strstr(text, "title = hang");
    const char *t1 = strstr(text, "[type1]\nks = 250\nkd = 0.5\n");
    const char *run = strstr(text, "[run]\ndt = 1e-3\nintegrator = cvode");
    const char *grav = strstr(text, "[gravity]\ng = 0, -9.81, 0\n");
    cr_assert(top == text && t1 && run && grav && t1 < run && run < grav,
              "unexpected layout:\n%s", text);
    cr_assert_null(strstr(text, "200"), "overridden value written:\n%s",
                   text);
    cr_assert_null(strstr(text, "old contents"));

    cl_config *back = cl_config_alloc();
    cr_assert_eq(cl_config_load(back, path, &err), CL_OK, "%s", err.msg);
    unlink(path);
    for (size_t s = 0; s < 6; s++) {
        static const char *const keys[][2] = {
            {"", "title"},           {"type1", "ks"}, {"type1", "kd"},
            {"run", "integrator"},   {"gravity", "g"}, {"output", "note"}};
        const char *a = cl_config_string(cfg, keys[s][0], keys[s][1], NULL);
        const char *b = cl_config_string(back, keys[s][0], keys[s][1], NULL);
        cr_assert(a && b && !strcmp(a, b), "[%s] %s differs", keys[s][0],
                  keys[s][1]);
    }
    cl_config_string(back, "run", "dt", NULL);
    cr_assert_eq(cl_config_check_unused(back, &err), CL_OK,
                 "reloaded file has extra keys: %s", err.msg);
    cl_config_free(back);
    cl_config_free(cfg);
}

Test(config, longest_lines_read_back)
{
    char text[512] = "[run]\nnote=";
    memset(text + strlen(text), 'b', 192); /* note=<192 b>: 197 chars */
    strcat(text, "\n");
    cl_config *cfg = cfg_from(text);
    cl_error err = {0};
    char path[64];
    write_tmp(path, "");
    cr_assert_eq(cl_config_write(cfg, path, &err), CL_OK, "%s", err.msg);
    cl_config *back = cl_config_alloc();
    cr_assert_eq(cl_config_load(back, path, &err), CL_OK, "%s", err.msg);
    unlink(path);
    cr_assert_str_eq(cl_config_string(back, "run", "note", ""),
                     cl_config_string(cfg, "run", "note", NULL));
    cl_config_free(back);
    cl_config_free(cfg);
}

Test(config, write_leaves_no_temporary_files)
{
    char dir[] = "/tmp/clothode-config-dir-XXXXXX";
    cr_assert_not_null(mkdtemp(dir));
    char path[96];
    snprintf(path, sizeof path, "%s/used.ini", dir);
    cl_config *cfg = cfg_from("[run]\ndt = 1\n");
    cl_error err = {0};
    cr_assert_eq(cl_config_write(cfg, path, &err), CL_OK, "%s", err.msg);
    cr_assert_eq(unlink(path), 0);
    cr_assert_eq(rmdir(dir), 0, "directory not empty after write");
    cl_config_free(cfg);
}

Test(config, write_to_missing_directory_is_eio)
{
    cl_config *cfg = cfg_from("[run]\ndt = 1\n");
    cl_error err = {0};
    cr_assert_eq(cl_config_write(cfg, "/nonexistent/dir/used.ini", &err),
                 CL_EIO);
    assert_msg_has(err, "/nonexistent/dir/used.ini");
    cl_config_free(cfg);
}

/* ---- the resolved configuration (run.json) ---------------------------- */

typedef struct {
    char text[1024];
} visits;

static void visit(void *ctx, const char *sec, const char *key,
                  const char *value, bool given)
{
    visits *v = ctx;
    size_t n = strlen(v->text);
    snprintf(v->text + n, sizeof v->text - n, "%s%s.%s=%s;", given ? "" : "*",
             sec, key, value);
}

/* Given entries first (file, then --set), then every default a getter
 * used, once, in the order asked; a key with no default is left out. */
Test(config, resolved_lists_given_values_then_defaults)
{
    cl_config *cfg = cfg_from("[run]\ndt = 1e-3\n[cloth]\nn = 8\n");
    cl_error err;
    double d;
    long l;
    bool b;
    int c;
    double vec[3] = {1, 2, 3};
    cr_assert_eq(cl_config_set(cfg, "cloth.n=12", &err), CL_OK);
    cr_assert_eq(cl_config_double(cfg, "run", "dt", 0, 0, 1, &d, &err),
                 CL_OK);
    cr_assert_eq(cl_config_double(cfg, "run", "rtol", 1e-6, 0, 1, &d, &err),
                 CL_OK);
    cr_assert_eq(cl_config_double(cfg, "run", "rtol", 5, 0, 9, &d, &err),
                 CL_OK);
    cr_assert_eq(cl_config_long(cfg, "run", "samples", 200, 1, 1000, &l,
                                &err), CL_OK);
    cr_assert_eq(cl_config_bool(cfg, "type1", "enabled", true, &b, &err),
                 CL_OK);
    cr_assert_eq(cl_config_choice(cfg, "run", "integrator", integrators, 1,
                                  &c, &err), CL_OK);
    cr_assert_eq(cl_config_vector(cfg, "gravity", "g", 3, vec, &err), CL_OK);
    cr_assert_str_eq(cl_config_string(cfg, "run", "linsol", "klu"), "klu");
    cr_assert_null(cl_config_string(cfg, "run", "state", NULL));
    visits v = {""};
    cl_config_resolved(cfg, visit, &v);
    cr_assert_str_eq(v.text, "run.dt=1e-3;cloth.n=12;*run.rtol=1e-06;"
                             "*run.samples=200;*type1.enabled=true;"
                             "*run.integrator=symplectic-euler;"
                             "*run.linsol=klu;");
    cl_config_free(cfg);
}

/* ------------------------------------------------------------- fuzzing */

/* Each seed and each input the fuzzer once failed on (crash-*: a section
 * name inih cut at 49 characters, a line "=..." with no key written back
 * as an indented continuation, a top-level key that moved the blank line
 * of the next section) goes through the harness, which aborts on a
 * crash, a written config.ini that does not read back or one that reads
 * back to other bytes. */
Test(config, fuzz_seeds_and_crashes_pass_the_harness)
{
    DIR *d = opendir("tests/fuzz/config");
    cr_assert_not_null(d, "run from the repository root");
    size_t crashes = 0;
    for (struct dirent *e; (e = readdir(d));) {
        char path[512];
        if (e->d_name[0] == '.')
            continue;
        snprintf(path, sizeof path, "tests/fuzz/config/%s", e->d_name);
        FILE *f = fopen(path, "rb");
        cr_assert_not_null(f, "%s", path);
        uint8_t data[1 << 14];
        size_t n = fread(data, 1, sizeof data, f);
        fclose(f);
        cl_fuzz_config_one(data, n);
        crashes += !strncmp(e->d_name, "crash-", 6);
    }
    closedir(d);
    cr_assert_eq(crashes, 3);
}

Test(config, long_section_name_and_empty_key_are_refused)
{
    char name[64], set[96];
    memset(name, 's', 50);
    name[50] = '\0';
    char text[128];
    snprintf(text, sizeof text, "[%s]\nk = 1\n", name);
    expect_parse_error(text, 1, "section name of 50 characters; the INI"
                       " parser reads names of at most 49", NULL);
    snprintf(set, sizeof set, "%s.k=1", name);
    cl_config *cfg = cl_config_alloc();
    cl_error err = {0};
    cr_assert_eq(cl_config_set(cfg, set, &err), CL_EINVAL);
    assert_msg_has(err, "section name longer than the INI parser reads");
    name[49] = '\0';
    snprintf(set, sizeof set, "%s.k=1", name);
    cr_assert_eq(cl_config_set(cfg, set, &err), CL_OK, "%s", err.msg);
    cl_config_free(cfg);
    expect_parse_error("[run]\ndt = 1\n= 2\n", 3, "'=' without a key name",
                       NULL);
}

/* A key a section lacks is named with the file and line of the section's
 * first entry, or the file alone when the section has none. */
Test(config, missing_key_names_its_section_s_place)
{
    char path[64], want[128];
    cl_config *cfg = cl_config_alloc();
    cl_error err = {0};
    cr_assert_eq(load_text(cfg, "[cloth]\nn = 4\n\n[obstacle.s]\n"
                                "shape = sphere\n", path, &err),
                 CL_OK, "%s", err.msg);
    cr_assert_eq(cl_config_missing(cfg, "obstacle.s", "radius", "a number "
                                   "> 0", &err), CL_EINVAL);
    snprintf(want, sizeof want, "%s:5: [obstacle.s] radius: required (a "
             "number > 0)", path);
    cr_assert_str_eq(err.msg, want);
    cl_config_missing(cfg, "gravity", "g", "three numbers", &err);
    snprintf(want, sizeof want, "%s: [gravity] g: required (three numbers)",
             path);
    cr_assert_str_eq(err.msg, want);
    cl_config_free(cfg);
}
