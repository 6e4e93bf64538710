/* The entry points of PETSc's start and end in the plug-in
 * clothode-petsc.so (linalg/plugin.h, linalg/petscenv.h): looked up as
 * "clp_petsc_start" and "clp_petsc_stop" by linalg/petscenv.c, defined by
 * linalg/petscenv_petsc.c.  The start returns 0, or nonzero with msg
 * filled. */
#ifndef CL_PETSCENV_ABI_H
#define CL_PETSCENV_ABI_H

#include "core/decls.h"
#include "linalg/plugin.h"

CL_BEGIN_DECLS

typedef int (*clp_petsc_start_fn)(cl_plugin_msg *msg);
typedef void (*clp_petsc_stop_fn)(void);

CL_END_DECLS

#endif
