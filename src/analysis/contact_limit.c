/* The explicit limit against the penalty stiffness (see contact_limit.h). */
#include "analysis/contact_limit.h"

#include <math.h>

#include "analysis/spectrum.h"

cl_status cl_climit_predict(cl_model *m, const cl_integrator_type *type,
                            double t, const double *x, const double *v,
                            cl_climit_result *r, cl_error *err)
{
    cl_spectrum sp = {0};
    r->predicted = r->w_max = NAN;
    cl_status rc = cl_spectrum_compute(m, t, x, v, &sp, err);
    if (!rc) {
        r->predicted = cl_spectrum_step_limit(&sp, type->region);
        r->w_max = sp.w_max;
    }
    cl_spectrum_free(&sp);
    return rc;
}

void cl_climit_print(FILE *fp, const cl_climit_result *r)
{
    fprintf(fp, "%-18s %10.4g %11.4g %11.4g %11.4g %10.4g %5d\n", r->label,
            r->k, r->stab.dt_stable, r->stab.dt_unstable, r->predicted,
            r->w_max, r->stab.ntrial);
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
