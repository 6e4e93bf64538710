/* PETSc, started once per process and only when a solver on it is used
 * (linalg/plugin.h: it lives in the plug-in clothode-petsc.so).
 *
 * MPI comes up as a singleton of this process alone (no mpirun, no
 * daemon), PETSc with its signal handlers off (core/stop.h keeps SIGINT
 * and SIGTERM) and errors returned, not printed; both are finalised at
 * exit. */
#ifndef CL_PETSCENV_H
#define CL_PETSCENV_H

#include "core/decls.h"
#include "core/error.h"

CL_BEGIN_DECLS

/* Load the plug-in and start PETSc, the first time; later calls return
 * CL_OK at once. */
cl_status cl_petsc_start(cl_error *err);

/* Finalise PETSc and MPI now, if cl_petsc_start started them (else
 * nothing; they are finalised at exit otherwise): a program calls it
 * before it closes stdout, so that the reports PETSc prints as it ends
 * (-log_view, -options_left, given in PETSC_OPTIONS or --petsc) are
 * written.  PETSc cannot be started again in the process. */
void cl_petsc_stop(void);

CL_END_DECLS

#endif
