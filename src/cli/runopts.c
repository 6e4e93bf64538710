/* The integrator options of the [run] section, shared by the subcommands
 * that run integrators (run, convergence). */
#include <math.h>
#include <string.h>

#include "cli/cli.h"

/* The numeric keys. */
static cl_status read_numbers(cl_config *cfg, cl_integrator_opts *io,
                              long *max_order, cl_error *err)
{
    cl_status rc;
    if ((rc = cl_config_double(cfg, "run", "dt", 0.0, 0.0, INFINITY, &io->dt,
                               err)) ||
        (rc = cl_config_double(cfg, "run", "rtol", 1e-6, 1e-15, 1.0,
                               &io->rtol, err)) ||
        (rc = cl_config_double(cfg, "run", "atol", 1e-8, 1e-300, INFINITY,
                               &io->atol, err)) ||
        (rc = cl_config_long(cfg, "run", "max_steps", 0, 0, 1L << 40,
                             &io->max_steps, err)) ||
        (rc = cl_config_double(cfg, "run", "newton_tol", 0.0, 0.0, 1.0,
                               &io->newton_tol, err)) ||
        (rc = cl_config_long(cfg, "run", "newton_maxit", 0, 0, 1000000,
                             &io->newton_maxit, err)) ||
        (rc = cl_config_double(cfg, "run", "lin_tol", 0.0, 0.0, 1.0,
                               &io->lin_tol, err)) ||
        (rc = cl_config_long(cfg, "run", "lin_maxit", 0, 0, 100000000,
                             &io->lin_maxit, err)) ||
        (rc = cl_config_double(cfg, "run", "verlet_damping", 0.0, 0.0,
                               0.999999, &io->vdamp, err)))
        return rc;
    return cl_config_long(cfg, "run", "max_order", 0, 0, 12, max_order, err);
}

cl_status cl_cli_integrator_opts(cl_config *cfg,
                                 const cl_integrator_type *type,
                                 bool need_dt, cl_integrator_opts *io,
                                 cl_error *err)
{
    long max_order;
    char where[256];
    cl_status rc = read_numbers(cfg, io, &max_order, err);
    if (rc)
        return rc;
    io->max_order = (int)max_order;
    io->linsol = cl_config_string(cfg, "run", "linsol", "");
    if (*io->linsol && !type->takes_linsol)
        return cl_error_set(err, CL_EINVAL,
                            "%s: [run] linsol = \"%s\": integrator %s has no "
                            "choice of linear solver",
                            cl_config_origin(cfg, "run", "linsol", where,
                                             sizeof where),
                            io->linsol, type->name);
    if (max_order && !type->takes_max_order)
        return cl_error_set(err, CL_EINVAL,
                            "%s: [run] max_order = %ld: integrator %s has "
                            "no choice of order (CVODE and IDA have)",
                            cl_config_origin(cfg, "run", "max_order", where,
                                             sizeof where),
                            max_order, type->name);
    if (need_dt && type->fixed_step && !(io->dt > 0))
        return cl_error_set(err, CL_EINVAL,
                            "%s: [run] dt = %g: integrator %s takes fixed "
                            "steps and needs dt > 0 (--dt H)",
                            cl_config_origin(cfg, "run", "dt", where,
                                             sizeof where),
                            io->dt, type->name);
    return CL_OK;
}

cl_status cl_cli_integrator_list(cl_config *cfg, bool need_dt, int max,
                                 const cl_integrator_type **type,
                                 cl_integrator_opts *io, int *n,
                                 cl_error *err)
{
    const char *list = cl_config_string(cfg, "run", "integrator",
                                        "cvode-bdf");
    char where[256], name[64];
    cl_config_origin(cfg, "run", "integrator", where, sizeof where);
    *n = 0;
    for (const char *p = list; *p;) {
        size_t len = strcspn(p, ",");
        if (len == 0 || len >= sizeof name || *n == max)
            return cl_error_set(err, CL_EINVAL, "%s: [run] integrator = "
                                "\"%s\": expected 1 to %d names separated "
                                "by commas", where, list, max);
        memcpy(name, p, len);
        name[len] = '\0';
        if (!(type[*n] = cl_integrator_find(name)))
            return cl_error_set(err, CL_EINVAL, "%s: [run] integrator = "
                                "\"%s\": unknown integrator \"%s\" ("
                                "clothode list shows them)", where, list,
                                name);
        cl_status rc = cl_cli_integrator_opts(cfg, type[*n], need_dt,
                                              &io[*n], err);
        if (rc)
            return rc;
        ++*n;
        p += len + (p[len] == ',');
    }
    return *n ? CL_OK
              : cl_error_set(err, CL_EINVAL, "%s: [run] integrator is empty",
                             where);
}
