/* make install, as a library user sees it (scripts/install-check.sh):
 * the example examples/embed_cvode.c, built against the installed
 * libclothode with pkg-config, integrates a 6 x 6 hang with its own CVODE
 * (dense Jacobian from the system's blocks) and ends at the same energy as
 * the installed clothode run by problem name (cvode-bdf with its default
 * linear solver), both at rtol 1e-8; the installed library holds no
 * benchmark object; a program of one's own linked with it, outside the
 * prefix, finds the installed PETSc plug-in; a C++ program that includes
 * every installed header integrates the same cloth through the library's
 * cvode-bdf and ends at the command's energy, and every installed header
 * gives its declarations C linkage in C++ (core/decls.h); the example
 * refuses a problem that needs more than forces (PBD's projections). */
#include <criterion/criterion.h>

#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "timelimit.h"

Test(install, example_builds_with_pkg_config_and_agrees)
{
    time_limit(300);
    /* the build whose clothode the suite runs: build or build-san */
    const char *bin = getenv("CLOTHODE");
    const char *build = bin && strstr(bin, "build-san") ? "build-san"
                                                         : "build";
    char cmd[256];
    snprintf(cmd, sizeof cmd, "scripts/install-check.sh %s 2>&1", build);
    FILE *p = popen(cmd, "r");
    cr_assert_not_null(p);
    char line[1024], out[8192] = "";
    double example = NAN, clothode = NAN, cxx = NAN;
    long bench_objects = -1, unwrapped = -1, hooks = -1;
    bool plugin = false;
    while (fgets(line, sizeof line, p)) {
        plugin = plugin || !strcmp(line, "plugin found\n");
        strncat(out, line, sizeof out - strlen(out) - 1);
        sscanf(line, "example %lf", &example);
        sscanf(line, "clothode %lf", &clothode);
        sscanf(line, "cxx %lf", &cxx);
        sscanf(line, "bench_objects %ld", &bench_objects);
        sscanf(line, "unwrapped %ld", &unwrapped);
        sscanf(line, "hooks refused %ld", &hooks);
    }
    int status = pclose(p);
    cr_assert_eq(status, 0, "install-check failed:\n%s", out);
    cr_assert(isfinite(example) && isfinite(clothode) && isfinite(cxx), "%s",
              out);
    cr_expect_eq(bench_objects, 0, "%s", out);
    cr_expect_eq(unwrapped, 0, "%s", out);
    cr_expect(plugin, "%s", out);
    cr_expect_eq(hooks, 1, "the example ran a PBD problem:\n%s", out);
    cr_expect_lt(fabs(example - clothode), 1e-6 * fabs(clothode),
                 "example %.12g, clothode %.12g", example, clothode);
    /* the same integrator and tolerances; clothode stops at its samples */
    cr_expect_lt(fabs(cxx - clothode), 1e-7 * fabs(clothode),
                 "C++ %.12g, clothode %.12g", cxx, clothode);
}
