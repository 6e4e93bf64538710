/* The plug-in's side of PETSc's start (linalg/petscenv.h).  Built into
 * clothode-petsc.so only; it calls nothing of the library. */
#include <errno.h>
#include <petscsys.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

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
void clp_petsc_stop(void);

/* This process's own base of Open MPI's session directories, "" when the
 * caller chose one (OMPI_MCA_orte_tmpdir_base). */
static char session_base[4096];

static void stop_petsc(void)
{
    PetscBool done = PETSC_TRUE;
    if (PetscFinalized(&done) == 0 && !done) {
        MPI_OWN_BEGIN();
        PetscFinalize();
        MPI_OWN_END();
    }
    if (session_base[0] != '\0')
        rmdir(session_base);
    session_base[0] = '\0';
}

/* Before exit, while stdout is open: what PETSc prints as it ends
 * (-log_view, -options_left, -memory_view) reaches it. */
void clp_petsc_stop(void)
{
    stop_petsc();
}

/* An isolated singleton has the same name in every process, [[0,1],0],
 * so all of them make and use the one session directory
 * $TMPDIR/ompi.HOST.UID/jf.0/1/0, and each removes that tree when it
 * finalises: a process starting while another stops finds a level of it
 * gone ("A call to mkdir was unable to create the desired directory ...
 * orte_session_dir failed") and Open MPI aborts it in MPI_Init (Open MPI
 * issues 3818, "singleton hang at beginning", and 8510, "A call to mkdir
 * was unable to create the desired directory", for concurrent jobs on one
 * node).  Each process therefore gets its own base of that tree, the MCA
 * parameter orte_tmpdir_base ("Base of the session directory tree to be
 * used by all processes", ompi_info --all), made here and removed after
 * MPI_Finalize, which removes what Open MPI put in it.  A base the caller
 * set is used as it is. */
static int private_session_base(cl_plugin_msg *msg)
{
    if (getenv("OMPI_MCA_orte_tmpdir_base") != NULL)
        return 0;
    const char *tmp = getenv("TMPDIR");
    if (tmp == NULL || tmp[0] == '\0')
        tmp = "/tmp";
    int len = snprintf(session_base, sizeof session_base,
                       "%s/clothode-mpi-XXXXXX", tmp);
    const char *why = "name too long";
    if (len > 0 && (size_t)len < sizeof session_base) {
        if (mkdtemp(session_base) != NULL)
            return setenv("OMPI_MCA_orte_tmpdir_base", session_base, 1);
        why = strerror(errno);
    }
    session_base[0] = '\0';
    snprintf(msg->text, sizeof msg->text,
             "MPI not started: cannot make its session directory in "
             "TMPDIR = %s (%s); set TMPDIR to a writable directory",
             tmp, why);
    return 1;
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
    if (private_session_base(msg) != 0)
        return 1;
    MPI_OWN_BEGIN();
    int bad = PetscOptionsSetValue(NULL, "-no_signal_handler", NULL) != 0 ||
              PetscInitializeNoArguments() != 0;
    MPI_OWN_END();
    if (bad) {
        stop_petsc();
        snprintf(msg->text, sizeof msg->text,
                 "PETSc (through MPI) could not be initialised");
        return 1;
    }
    /* Read by MPI_Init; programs this process starts make their own. */
    if (session_base[0] != '\0')
        unsetenv("OMPI_MCA_orte_tmpdir_base");
    PetscPushErrorHandler(PetscReturnErrorHandler, NULL);
    atexit(stop_petsc);
    return 0;
}
