/* Stability limit of a fixed-step integrator by doubling and bisection on
 * the number of steps (see stability.h). */
#include "analysis/stability.h"

#include <math.h>
#include <string.h>

#include "analysis/trial.h"
#include "io/csv.h"

cl_status cl_stab_check(cl_model *m, const cl_integrator_type *type,
                        const cl_stab_opts *o, cl_error *err)
{
    if (!type->fixed_step)
        return cl_error_set(err, CL_EINVAL, "%s chooses its own steps by "
                            "error control: a stability limit is defined "
                            "for fixed-step integrators only", type->name);
    if (!(o->t_end > 0 && isfinite(o->t_end)))
        return cl_error_set(err, CL_EINVAL, "t_end = %g: expected > 0",
                            o->t_end);
    if (!(o->dt_min > 0 && o->dt_min < o->dt_max &&
          o->dt_max <= o->t_end / 10))
        return cl_error_set(err, CL_EINVAL, "dt range [%g, %g]: expected "
                            "0 < dt_min < dt_max <= t_end/10 = %g (a run "
                            "of fewer than 10 steps has no room to blow up)",
                            o->dt_min, o->dt_max, o->t_end / 10);
    if (!(o->rel > 0 && o->rel < 1) || o->checks < 1)
        return cl_error_set(err, CL_EINVAL, "rel = %g, checks = %ld: "
                            "expected 0 < rel < 1 and checks >= 1", o->rel,
                            o->checks);
    return cl_trial_repeatable(m, err);
}

int cl_stab_try(cl_trial *t, const cl_integrator_type *type,
                const cl_integrator_opts *io, const cl_stab_opts *o,
                long nsteps, cl_stab_trial *tr, cl_error *err)
{
    cl_integrator_opts to = *io;
    to.dt = o->t_end / (double)nsteps;
    tr->dt = to.dt;
    tr->nsteps = nsteps;
    tr->rc = cl_trial_run(t, type, &to, o->t_end, o->checks, o->max_stretch,
                          &tr->stats, &tr->why);
    tr->stretch = t->stretch_seen;
    if (tr->rc == CL_OK || tr->rc == CL_EBLOWUP || tr->rc == CL_ESOLVER ||
        tr->rc == CL_EINFEASIBLE) /* a run stopped by its state: unstable */
        return tr->rc == CL_OK;
    *err = tr->why;
    return -1;
}

/* Run with N steps into the next trial of r: as cl_stab_try, and -1 when
 * r has no room for another trial. */
static int try_steps(cl_trial *t, const cl_integrator_type *type,
                     const cl_integrator_opts *io, const cl_stab_opts *o,
                     long nsteps, cl_stab_result *r, cl_error *err)
{
    if (r->ntrial == CL_STAB_MAX_TRIALS) {
        cl_error_set(err, CL_ESOLVER, "%s: no bracket after %d runs",
                     type->name, CL_STAB_MAX_TRIALS);
        return -1;
    }
    return cl_stab_try(t, type, io, o, nsteps, &r->trial[r->ntrial++], err);
}

/* Doubling from N0 to the first N that is stable and whose double (the
 * step halved) is stable too: a stable step above an unstable one (a
 * step that happens to damp the initial state's modes exactly) is not
 * taken for the limit.  *nu, *ns: the bracket (ns = 0 if none down to
 * dt_min).  Returns -1 on a failure, else 0. */
static int bracket(cl_trial *t, const cl_integrator_type *type,
                   const cl_integrator_opts *io, const cl_stab_opts *o,
                   long *nu, long *ns, cl_stab_result *r, cl_error *err)
{
    long nmax = (long)floor(o->t_end / o->dt_min);
    *ns = 0;
    for (long n = *nu * 2; n <= nmax; n *= 2) {
        int s = try_steps(t, type, io, o, n, r, err);
        if (s < 0)
            return -1;
        if (s && *ns)
            return 0;
        if (!s)
            *nu = n;
        *ns = s ? n : 0;
    }
    return 0;
}

/* Bisection on N between nu (unstable) and ns (stable). */
static int bisect(cl_trial *t, const cl_integrator_type *type,
                  const cl_integrator_opts *io, const cl_stab_opts *o,
                  long *nu, long *ns, cl_stab_result *r, cl_error *err)
{
    while (*ns - *nu > fmax(1.0, o->rel * (double)*nu)) {
        long mid = *nu + (*ns - *nu) / 2;
        int s = try_steps(t, type, io, o, mid, r, err);
        if (s < 0)
            return -1;
        *(s ? ns : nu) = mid;
    }
    return 0;
}

/* The trial with nsteps steps. */
static int trial_of(const cl_stab_result *r, long nsteps)
{
    for (int k = 0; k < r->ntrial; k++)
        if (r->trial[k].nsteps == nsteps)
            return k;
    return -1;
}

cl_status cl_stability(cl_model *m, const cl_integrator_type *type,
                       const cl_integrator_opts *io, const cl_stab_opts *o,
                       cl_stab_result *r, cl_error *err)
{
    cl_trial t = {0};
    memset(r, 0, sizeof *r);
    r->type = type;
    r->label = type->name;
    r->dt_stable = r->dt_unstable = NAN;
    r->failed = r->held = -1;
    cl_status rc = cl_stab_check(m, type, o, err);
    if (rc || (rc = cl_trial_init(&t, m, err))) {
        cl_trial_free(&t);
        return rc;
    }
    long nu = (long)ceil(o->t_end / o->dt_max - 1e-9), ns = nu;
    int s = try_steps(&t, type, io, o, nu, r, err);
    /* stable at dt_max only if at dt_max/2 too (within the range), as in
     * bracket() */
    if (s == 1 && 2 * nu <= (long)floor(o->t_end / o->dt_min) &&
        (s = try_steps(&t, type, io, o, 2 * nu, r, err)) == 0)
        nu *= 2;
    bool stable_at_max = s == 1;
    if (s == 0 && (s = bracket(&t, type, io, o, &nu, &ns, r, err)) == 0 &&
        ns)
        s = bisect(&t, type, io, o, &nu, &ns, r, err);
    cl_trial_free(&t);
    if (s < 0)
        return err->code;
    if (ns) {
        r->held = trial_of(r, ns);
        r->dt_stable = o->t_end / (double)ns;
    }
    if (!stable_at_max) {
        r->failed = trial_of(r, nu);
        r->dt_unstable = o->t_end / (double)nu;
    }
    return CL_OK;
}

void cl_stab_write_rows(FILE *fp, const cl_stab_result *r, bool header)
{
    if (header)
        fprintf(fp, "integrator,dt,steps,stable,status,cpu,stretch,"
                    "reason\n");
    for (int k = 0; k < r->ntrial; k++) {
        const cl_stab_trial *t = &r->trial[k];
        fputs(r->label, fp);
        fprintf(fp, ",%.9g,%ld,%d,%s,%.6g,%.6g,", t->dt, t->nsteps,
                t->rc == CL_OK, t->rc ? cl_status_name(t->rc) : "ok",
                t->stats.cpu, t->stretch);
        cl_csv_quoted(fp, t->rc ? t->why.msg : "");
        fputc('\n', fp);
    }
}
