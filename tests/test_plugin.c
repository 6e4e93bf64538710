/* Tests for plug-in loading (linalg/plugin.h). */
#include <criterion/criterion.h>

#include <stdlib.h>
#include <string.h>

#include "linalg/plugin.h"
#include "pluginabi.h"
#include "runcli.h"

Test(plugin, unknown_plugin_names_every_place_tried)
{
    cl_error err;
    void *sym = NULL;
    setenv("CLOTHODE_PLUGIN_DIR", "/nonexistent-plugins", 1);
    cr_assert_eq(cl_plugin_symbol("nosuch", "f", &sym, &err),
                 CL_EUNSUPPORTED);
    cr_assert_null(sym);
    cr_assert_not_null(strstr(err.msg, "clothode-nosuch.so"), "%s", err.msg);
    cr_assert_not_null(strstr(err.msg, "/nonexistent-plugins/"), "%s",
                       err.msg);
    cr_assert_not_null(strstr(err.msg, "../lib/clothode/"), "%s", err.msg);
}

Test(plugin, missing_entry_point_is_refused_by_name)
{
    cl_error err;
    void *sym = NULL;
    cr_assert_eq(cl_plugin_symbol("petsc", "clp_no_such_entry", &sym, &err),
                 CL_EINVAL);
    cr_assert_not_null(strstr(err.msg, "clp_no_such_entry"), "%s", err.msg);
}

Test(plugin, petsc_entry_point_is_found_beside_the_program)
{
    cl_error err;
    void *sym = NULL;
    cr_assert_eq(cl_plugin_symbol("petsc", "clp_petsc_start", &sym, &err),
                 CL_OK, "%s", err.msg);
    cr_assert_not_null(sym);
}

/* ---- the interface version (CL_PLUGIN_ABI) ---------------------------- */

/* The test plug-ins of tests/plugins/probe.c (Makefile, "Test plug-ins"):
 * right/ with this build's version, wrong/ with 0123456789abcdef, none/
 * without one. */
static void plugins_in(const char *sub)
{
    char dir[4096];
    snprintf(dir, sizeof dir, "%s/%s", CL_TEST_PLUGINS, sub);
    setenv("CLOTHODE_PLUGIN_DIR", dir, 1);
}

Test(plugin, plugin_of_this_interface_version_is_loaded)
{
    cl_error err;
    void *sym = NULL;
    plugins_in("right");
    cr_assert_eq(cl_plugin_symbol("probe", "clp_probe", &sym, &err), CL_OK,
                 "%s", err.msg);
    cr_assert_eq(((int (*)(void))sym)(), 42);
}

Test(plugin, plugin_of_another_interface_version_is_refused_naming_both)
{
    cl_error err;
    void *sym = NULL;
    plugins_in("wrong");
    for (int k = 0; k < 2; k++) {  /* and again: nothing was kept */
        cr_assert_eq(cl_plugin_symbol("petsc", "clp_petsc_start", &sym,
                                      &err), CL_EUNSUPPORTED);
        cr_assert_null(sym);
        cr_assert_not_null(strstr(err.msg, CL_TEST_PLUGINS
                                  "/wrong/clothode-petsc.so"), "%s",
                           err.msg);
        cr_assert_not_null(strstr(err.msg, "interface 0123456789abcdef, "
                                  "this program for " CL_PLUGIN_ABI ":"),
                           "%s", err.msg);
    }
}

Test(plugin, plugin_without_interface_version_is_refused)
{
    cl_error err;
    void *sym = NULL;
    plugins_in("none");
    cr_assert_eq(cl_plugin_symbol("petsc", "clp_petsc_start", &sym, &err),
                 CL_EUNSUPPORTED);
    cr_assert_null(sym);
    cr_assert_not_null(strstr(err.msg, CL_TEST_PLUGINS
                              "/none/clothode-petsc.so has no plug-in "
                              "interface version (clp_plugin_abi), this "
                              "program's is " CL_PLUGIN_ABI ":"), "%s",
                       err.msg);
}

/* The command line with a PETSc plug-in of another version: one message
 * naming the file and both versions, a non-zero exit, no crash. */
Test(plugin, cli_refuses_a_plugin_of_another_version_in_one_message)
{
    char out[1024];
    cli_result r;
    tmp_mkdtemp(out, sizeof out, "plugin");
    plugins_in("wrong");
    cli_run(&r, "run", "hang", "--set", "cloth.n=4", "--t-end", "0.01",
            "--integrator", "petsc-alpha2", "--out", out, NULL);
    cli_assert_error(&r, 0, "wrong/clothode-petsc.so", "0123456789abcdef",
                     CL_PLUGIN_ABI, NULL);
    cli_result_free(&r);
    cli_run(&r, "run", "hang", "--set", "cloth.n=4", "--t-end", "0.01",
            "--linsol", "amg", "--out", out, NULL);
    cli_assert_error(&r, 0, "wrong/clothode-petsc.so", CL_PLUGIN_ABI, NULL);
    cli_result_free(&r);
    tmp_rm_rf(out);
}
