/* The advice table of cl_solver_hint: one row per failure flag, matched on
 * the name without its solver prefix (CV_, IDA_, KIN_, GSL_), since CVODE
 * and IDA share their flags' meanings (SUNDIALS user guides, "Return
 * flags"). */
#include "integrators/hint.h"

#include <string.h>

static const struct {
    const char *flag, *hint;
} hints[] = {
    {"TOO_MUCH_WORK", "raise the steps allowed per output interval "
                      "(--set run.max_steps=N, default 500 for SUNDIALS) or "
                      "loosen --rtol/--atol"},
    {"EMAXITER", "raise the steps allowed per output interval (--set "
                 "run.max_steps=N) or loosen --rtol/--atol"},
    {"TOO_MUCH_ACC", "loosen --rtol/--atol: the solver cannot reach them in "
                     "double precision"},
    {"ERR_FAILURE", "loosen --rtol/--atol, or check the parameters: the "
                    "error test fails at the smallest step"},
    {"CONV_FAILURE", "choose a direct --linsol (klu) or loosen --rtol: "
                     "Newton fails at the smallest step"},
    {"NLS_FAIL", "choose a direct --linsol (klu) or loosen --rtol"},
    {"LINIT_FAIL", "choose another --linsol (klu)"},
    {"LSETUP_FAIL", "choose --linsol klu (cholmod and pcg need a symmetric "
                    "positive definite Newton matrix), or reduce --dt or "
                    "--rtol"},
    {"LSOLVE_FAIL", "choose --linsol klu, or raise --set run.lin_maxit=N"},
    {"LINSOLV_NO_RECOVERY", "choose --linsol klu or reduce --dt"},
    {"LINESEARCH_NONCONV", "reduce --dt, or choose --linsol klu: the line "
                           "search found no better iterate"},
    {"LINESEARCH_BCFAIL", "reduce --dt"},
    {"MAXITER_REACHED", "raise --set run.newton_maxit=N or reduce --dt"},
    {"MXNEWT_5X_EXCEEDED", "reduce --dt: the Newton step is too large"},
    {"TOO_CLOSE", "choose a larger --t-end"},
    {"ILL_INPUT", "check --rtol, --atol, --dt and --max-order"},
    {"MEM_FAIL", "choose a smaller cloth: out of memory"},
};

/* Where a fixed step's advice differs: no smaller step is tried. */
static const struct {
    const char *flag, *hint;
} fixed_hints[] = {
    {"CONV_FAILURE", "reduce --dt or raise --max-newton: Newton fails at "
                     "the fixed step, which is not retried smaller"},
    {"NLS_FAIL", "reduce --dt or raise --max-newton, or choose a direct "
                 "--linsol (klu)"},
};

const char *cl_solver_hint(const char *flag_name, bool fixed_step)
{
    const char *us = flag_name ? strchr(flag_name, '_') : NULL;
    for (size_t k = 0; fixed_step && us &&
                       k < sizeof fixed_hints / sizeof *fixed_hints; k++)
        if (!strcmp(us + 1, fixed_hints[k].flag))
            return fixed_hints[k].hint;
    for (size_t k = 0; us && k < sizeof hints / sizeof *hints; k++)
        if (!strcmp(us + 1, hints[k].flag))
            return hints[k].hint;
    return "change --rtol/--atol, --dt, --linsol or --set run.max_steps=N";
}
