/* The entry point of PETSc's start in the plug-in clothode-petsc.so
 * (linalg/plugin.h, linalg/petscenv.h): looked up as "clp_petsc_start" by
 * linalg/petscenv.c, defined by linalg/petscenv_petsc.c.  0, or nonzero
 * with msg filled. */
#ifndef CL_PETSCENV_ABI_H
#define CL_PETSCENV_ABI_H

#include "linalg/plugin.h"

typedef int (*clp_petsc_start_fn)(cl_plugin_msg *msg);

#endif
