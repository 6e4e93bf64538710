/* PETSc's start (linalg/petscenv.h): through the plug-in's entry point. */
#include "linalg/petscenv.h"

#include "linalg/petscenv_abi.h"

cl_status cl_petsc_start(cl_error *err)
{
    static int started;
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
