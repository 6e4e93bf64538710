/* The explicit limit against the penalty stiffness (see contact_limit.h). */
#include "analysis/contact_limit.h"

#include <math.h>
#include <stdlib.h>

#include "analysis/spectrum.h"

/* The spectrum's prediction at the initial state into r. */
static cl_status predict(cl_model *m, const cl_integrator_type *type,
                         cl_climit_result *r, cl_error *err)
{
    size_t n = cl_model_system(m)->n;
    double *x = malloc(n * sizeof *x), *v = malloc(n * sizeof *v);
    cl_spectrum sp = {0};
    cl_status rc = x && v ? cl_model_initial_state(m, x, v)
                          : cl_error_set(err, CL_ENOMEM, "out of memory");
    if (!rc && !(rc = cl_spectrum_compute(m, 0.0, x, v, &sp, err))) {
        r->predicted = cl_spectrum_step_limit(&sp, type->region);
        r->w_max = sp.w_max;
    }
    cl_spectrum_free(&sp);
    free(x);
    free(v);
    return rc;
}

cl_status cl_climit_run(cl_model *m, const cl_integrator_type *type,
                        const cl_integrator_opts *io, const cl_stab_opts *o,
                        cl_climit_result *r, cl_error *err)
{
    r->predicted = r->w_max = NAN;
    cl_status rc = predict(m, type, r, err);
    return rc ? rc : cl_stability(m, type, io, o, &r->stab, err);
}

void cl_climit_write_row(FILE *fp, const cl_climit_result *r, bool header)
{
    if (header)
        fputs("integrator,k,dt_stable,dt_unstable,predicted,w_max,runs\n",
              fp);
    fprintf(fp, "%s,%.9g,%.9g,%.9g,%.9g,%.9g,%d\n", r->label, r->k,
            r->stab.dt_stable, r->stab.dt_unstable, r->predicted, r->w_max,
            r->stab.ntrial);
}
