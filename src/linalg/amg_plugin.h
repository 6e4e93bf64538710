/* What a setup of the multigrid preconditioner recomputes: the argument
 * `mode` of the plug-in's clp_amg_setup (linalg/linsol_amg.c, its caller;
 * linsol_amg_petsc.c, the plug-in's side). */
#ifndef CL_AMG_PLUGIN_H
#define CL_AMG_PLUGIN_H

enum {
    /* a new hierarchy: coarsening, interpolation, coarse operators,
     * smoothers */
    CLP_AMG_BUILD,
    /* the kept interpolation P: the coarse operators P^T A P and every
     * smoother recomputed (amg-hypre: the whole preconditioner kept) */
    CLP_AMG_GALERKIN,
    /* the coarse operators and their smoothers kept; only the finest
     * level's smoother (its diagonal blocks and eigenvalue bound) on the
     * new A (amg-hypre: the whole preconditioner kept) */
    CLP_AMG_SMOOTHER,
};

#endif
