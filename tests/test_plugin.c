/* Tests for plug-in loading (linalg/plugin.h). */
#include <criterion/criterion.h>

#include <stdlib.h>
#include <string.h>

#include "linalg/plugin.h"

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
