/* PETSc's start and end (linalg/petscenv.h): through the plug-in's entry
 * points. */
#include "linalg/petscenv.h"

#include "linalg/petscenv_abi.h"

static int started; /* 1 started, 2 stopped */

cl_status cl_petsc_start(cl_error *err)
{
    if (started == 2)
        return cl_error_set(err, CL_EUNSUPPORTED, "PETSc was finalised in "
                            "this process (cl_petsc_stop) and cannot be "
                            "started again");
    if (started)
        return CL_OK;
    void *sym;
    cl_status rc = cl_plugin_symbol("petsc", "clp_petsc_start", &sym, err);
    if (rc != CL_OK)
        return rc;
    cl_plugin_msg msg = {.text = ""};
    if (((clp_petsc_start_fn)sym)(&msg) != 0)
        return cl_error_set(err, CL_ESOLVER, "%s", msg.text);
    started = 1;
    return CL_OK;
}

void cl_petsc_stop(void)
{
    void *sym;
    cl_error ignored;
    if (started == 1 &&
        cl_plugin_symbol("petsc", "clp_petsc_stop", &sym, &ignored) == CL_OK)
        ((clp_petsc_stop_fn)sym)();
    started += started == 1;
}
