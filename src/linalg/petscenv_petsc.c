/* The plug-in's side of PETSc's start (linalg/petscenv.h).  Built into
 * clothode-petsc.so only; it calls nothing of the library. */
#include <petscsys.h>
#include <stdio.h>
#include <stdlib.h>

#include "linalg/petscenv_abi.h"

/* Under AddressSanitizer: what MPI allocates while it starts and stops
 * (Open MPI's components, hwloc's topology, PMIx) it keeps for the
 * process's lifetime and never frees; LeakSanitizer is told to ignore
 * those allocations, and only those. */
#if defined(__SANITIZE_ADDRESS__)
#include <sanitizer/lsan_interface.h>
#define MPI_OWN_BEGIN() __lsan_disable()
#define MPI_OWN_END() __lsan_enable()
#else
#define MPI_OWN_BEGIN() ((void)0)
#define MPI_OWN_END() ((void)0)
#endif

int clp_petsc_start(cl_plugin_msg *msg);

static void stop_petsc(void)
{
    PetscBool done = PETSC_TRUE;
    if (PetscFinalized(&done) == 0 && !done) {
        MPI_OWN_BEGIN();
        PetscFinalize();
        MPI_OWN_END();
    }
}

int clp_petsc_start(cl_plugin_msg *msg)
{
    PetscBool up = PETSC_FALSE;
    if (PetscInitialized(&up) == 0 && up)
        return 0;
    /* Open MPI as a singleton isolated from any daemon, shared memory and
     * self transports only: 0.3 s to start instead of 2.7 s.  A user's
     * own OMPI_MCA_* settings win (setenv does not overwrite). */
    setenv("OMPI_MCA_ess_singleton_isolated", "1", 0);
    setenv("OMPI_MCA_btl", "self,vader", 0);
    setenv("OMPI_MCA_pml", "ob1", 0);
    MPI_OWN_BEGIN();
    int bad = PetscOptionsSetValue(NULL, "-no_signal_handler", NULL) != 0 ||
              PetscInitializeNoArguments() != 0;
    MPI_OWN_END();
    if (bad) {
        snprintf(msg->text, sizeof msg->text,
                 "PETSc (through MPI) could not be initialised");
        return 1;
    }
    PetscPushErrorHandler(PetscReturnErrorHandler, NULL);
    atexit(stop_petsc);
    return 0;
}
