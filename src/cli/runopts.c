/* The integrator options of the [run] section, shared by the subcommands
 * that run integrators (run, convergence). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
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

/* Entry "name" or "name:linsol" of the list into m. */
static cl_status parse_method(cl_config *cfg, bool need_dt, const char *list,
                              const char *where, const char *p, size_t len,
                              cl_cli_method *m, cl_error *err)
{
    char name[64];
    size_t nlen = strcspn(p, ":");
    nlen = nlen < len ? nlen : len;
    if (len >= sizeof m->label || nlen == 0 ||
        (nlen < len && len - nlen - 1 >= sizeof m->linsol))
        return cl_error_set(err, CL_EINVAL, "%s: [run] integrator = \"%s\": "
                            "bad entry \"%.*s\" (expected NAME or "
                            "NAME:LINSOL)", where, list, (int)len, p);
    memcpy(m->label, p, len);
    m->label[len] = '\0';
    memcpy(name, p, nlen);
    name[nlen] = '\0';
    snprintf(m->linsol, sizeof m->linsol, "%s",
             nlen < len ? m->label + nlen + 1 : "");
    if (!(m->type = cl_integrator_find(name)))
        return cl_error_set(err, CL_EINVAL, "%s: [run] integrator = \"%s\": "
                            "unknown integrator \"%s\" (clothode list shows "
                            "them)", where, list, name);
    if (*m->linsol && !m->type->takes_linsol)
        return cl_error_set(err, CL_EINVAL, "%s: [run] integrator = \"%s\": "
                            "integrator %s has no choice of linear solver",
                            where, list, name);
    cl_status rc = cl_cli_integrator_opts(cfg, m->type, need_dt, &m->io, err);
    if (!rc && *m->linsol)
        m->io.linsol = m->linsol;
    return rc;
}

cl_status cl_cli_methods(cl_config *cfg, bool need_dt, int max,
                         cl_cli_method *m, int *n, cl_error *err)
{
    const char *list = cl_config_string(cfg, "run", "integrator",
                                        "cvode-bdf");
    char where[256];
    cl_config_origin(cfg, "run", "integrator", where, sizeof where);
    *n = 0;
    for (const char *p = list; *p;) {
        size_t len = strcspn(p, ",");
        if (*n == max)
            return cl_error_set(err, CL_EINVAL, "%s: [run] integrator = "
                                "\"%s\": more than %d entries", where, list,
                                max);
        cl_status rc = parse_method(cfg, need_dt, list, where, p, len,
                                    &m[*n], err);
        if (rc)
            return rc;
        ++*n;
        p += len + (p[len] == ',');
    }
    return *n ? CL_OK
              : cl_error_set(err, CL_EINVAL, "%s: [run] integrator is empty",
                             where);
}

cl_status cl_cli_methods_try(cl_model *model, const cl_cli_method *m, int n,
                             cl_error *err)
{
    const cl_system *sys = cl_model_system(model);
    double *x = malloc(sys->n * sizeof *x), *v = malloc(sys->n * sizeof *v);
    cl_status rc = x && v ? cl_model_initial_state(model, x, v)
                          : cl_error_set(err, CL_ENOMEM, "out of memory");
    for (int k = 0; !rc && k < n; k++) {
        void *state = NULL;
        cl_integrator_opts io = m[k].io;
        if (m[k].type->fixed_step && !(io.dt > 0))
            io.dt = 1.0; /* a search (stability) sets the step later */
        cl_error why = {0};
        if ((rc = m[k].type->create(sys, &io, 0.0, x, v, &state, &why)))
            cl_error_set(err, rc, "%s: %s", m[k].label, why.msg);
        if (state)
            m[k].type->free(state);
    }
    free(x);
    free(v);
    return rc;
}
