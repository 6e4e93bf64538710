/* A collected sweep table read back as a study's runs (sweep_table.h). */
#include "analysis/sweep_table.h"

#include "analysis/sweep.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/exit.h"
#include "io/input.h"
#include "io/sha256.h"

#define TABLE_LINE_MAX (1 << 20) /* bytes of a row: paths, a message */

/* ---- reading ------------------------------------------------------------ */

/* The fields of one CSV line (RFC 4180 quoting), appended to *cells. */
static int split(const char *line, char ***cells, int *n)
{
    int count = 0;
    for (const char *p = line;; count++) {
        char *f = malloc(strlen(p) + 1), *o = f;
        char **grown = f ? realloc(*cells, (size_t)(*n + 1) * sizeof *grown)
                         : NULL;
        if (!grown) {
            free(f);
            return -1;
        }
        *cells = grown;
        bool quoted = *p == '"';
        for (p += quoted; *p && (quoted || (*p != ',' && *p != '\n'));) {
            if (quoted && *p == '"' && p[1] == '"')
                *o++ = '"', p += 2;
            else if (quoted && *p == '"')
                quoted = false, p++;
            else
                *o++ = *p++;
        }
        *o = '\0';
        (*cells)[(*n)++] = f;
        if (*p != ',')
            return count + 1;
        p++;
    }
}

/* One file's rows appended to t (its header the first file's). */
static cl_status read_one(const char *path, int src, cl_sweep_table *t,
                          cl_error *err)
{
    const char *why;
    FILE *fp = cl_input_open(path, "r", &why);
    if (!fp)
        return cl_error_set(err, CL_EIO, "cannot read the sweep table %s: %s",
                            path, why);
    char *line = NULL, **head = NULL;
    size_t cap = 0;
    int nf, nhead = 0, lineno = 1;
    cl_status rc = CL_OK;
    ssize_t len = cl_input_line(fp, &line, &cap, TABLE_LINE_MAX);
    bool header_unread = len < CL_INPUT_END; /* too long, or no memory */
    if (len > 0 &&
        split(line, src ? &head : &t->head, src ? &nhead : &t->ncol) < 0)
        rc = cl_error_set(err, CL_ENOMEM, "out of memory");
    for (int k = 0; !rc && !header_unread && src && k < t->ncol; k++)
        if (nhead != t->ncol || strcmp(head[k], t->head[k]))
            rc = cl_error_set(err, CL_EPARSE, "--from-sweep %s: its columns "
                              "are not those of %s (tables of the stages "
                              "of one sweep are; one collected by an "
                              "earlier clothode lacks the newer columns: "
                              "collect it again)", path, t->paths[0]);
    cl_sweep_strings_free(head, nhead);
    while (!rc && !header_unread &&
           (len = cl_input_line(fp, &line, &cap, TABLE_LINE_MAX)) > 0) {
        lineno++;
        int *grown = realloc(t->src, (size_t)(t->nrow + 1) * sizeof *grown);
        nf = grown ? split(line, &t->cell, &t->ncell) : -1;
        if (grown)
            t->src = grown;
        if (nf < 0)
            rc = cl_error_set(err, CL_ENOMEM, "out of memory");
        else if (nf != t->ncol)
            rc = cl_error_set(err, CL_EPARSE, "%s:%d: %d fields, the header "
                              "has %d", path, lineno, nf, t->ncol);
        else
            t->src[t->nrow++] = src;
    }
    if (!rc && len == CL_INPUT_NOMEM)
        rc = cl_error_set(err, CL_ENOMEM, "%s:%d: out of memory", path,
                          header_unread ? 1 : lineno + 1);
    if (!rc && len == CL_INPUT_LONG)
        rc = cl_error_set(err, CL_EPARSE, "%s:%d: a line longer than %d "
                          "bytes (not a table of 'clothode sweep collect')",
                          path, header_unread ? 1 : lineno + 1,
                          TABLE_LINE_MAX);
    if (!rc && ferror(fp))
        rc = cl_error_set(err, CL_EIO, "cannot read the sweep table %s",
                          path);
    free(line);
    fclose(fp);
    return rc;
}

cl_status cl_sweep_table_read(const char *list, cl_sweep_table *t,
                              cl_error *err)
{
    memset(t, 0, sizeof *t);
    t->path = strdup(list);
    cl_status rc = t->path ? CL_OK
                           : cl_error_set(err, CL_ENOMEM, "out of memory");
    size_t n = strlen(list);
    if (!rc && (!n || list[0] == ',' || list[n - 1] == ',' ||
                strstr(list, ",,")))
        rc = cl_error_set(err, CL_EINVAL, "\"%s\": an empty name in the "
                          "list of tables (comma-separated CSV files)", list);
    for (const char *p = list; !rc && *p; p += *p == ',') {
        size_t len = strcspn(p, ",");
        char **grown = realloc(t->paths, (size_t)(t->npath + 1) *
                                             sizeof *grown);
        if (grown)
            t->paths = grown;
        if (!grown || !(t->paths[t->npath] = strndup(p, len)))
            rc = cl_error_set(err, CL_ENOMEM, "out of memory");
        else
            rc = read_one(t->paths[t->npath], t->npath, t, err), t->npath++;
        p += len;
    }
    t->keep = rc ? NULL : malloc((size_t)t->nrow + 1);
    for (int k = 0; t->keep && k < t->nrow; k++)
        t->keep[k] = true;
    if (!rc && !t->keep)
        rc = cl_error_set(err, CL_ENOMEM, "out of memory");
    return rc;
}

void cl_sweep_table_free(cl_sweep_table *t)
{
    cl_sweep_strings_free(t->head, t->ncol);
    cl_sweep_strings_free(t->cell, t->ncell);
    free(t->keep);
    free(t->path);
    cl_sweep_strings_free(t->paths, t->npath);
    free(t->src);
    memset(t, 0, sizeof *t);
}

static int column(const cl_sweep_table *t, const char *name)
{
    for (int k = 0; k < t->ncol; k++)
        if (!strcmp(t->head[k], name))
            return k;
    return -1;
}

bool cl_sweep_table_has(const cl_sweep_table *t, const char *name)
{
    return column(t, name) >= 0;
}

static const char *at(const cl_sweep_table *t, int row, int col)
{
    return col < 0 ? "NA" : t->cell[(size_t)row * t->ncol + col];
}

static double number_at(const cl_sweep_table *t, int row, int col)
{
    char *end;
    const char *s = at(t, row, col);
    double v = strtod(s, &end);
    return end > s && !*end ? v : NAN;
}

const char *cl_sweep_table_text(const cl_sweep_table *t, int row,
                                const char *name)
{
    return at(t, row, column(t, name));
}

double cl_sweep_table_value(const cl_sweep_table *t, int row,
                            const char *name)
{
    return number_at(t, row, column(t, name));
}

/* ---- selecting the rows of the study's problem -------------------------- */

bool cl_sweep_same_value(const char *a, const char *b)
{
    char *ea, *eb;
    double x = strtod(a, &ea), y = strtod(b, &eb);
    if (ea > a && !*ea && eb > b && !*eb)
        return fabs(x - y) <= 1e-12 * fmax(fabs(x), fabs(y));
    return !strcmp(a, b);
}

/* A problem axis: not a method's [run] key (the levels and steps). */
static bool problem_axis(const char *key)
{
    return strncmp(key, "run.", 4) || !strcmp(key, "run.t_end");
}

/* Keep the rows whose value of axis c is the configuration's; an axis
 * the configuration does not give must have one value, which a problem
 * key then takes, so that the command's model is the one the sweep's
 * runs had (before: at the key's default, a constant [init] time or
 * type1.ks of the sweep was not the study's); t_end, which the command
 * read before the table, must be given. */
static cl_status select_axis(cl_sweep_table *t, cl_config *cfg, int c,
                             cl_error *err)
{
    char sec[128];
    const char *key = t->head[c], *dot = strrchr(key, '.');
    snprintf(sec, sizeof sec, "%.*s", (int)(dot - key), key);
    const char *want = cl_config_string(cfg, sec, dot + 1, NULL);
    const char *first = NULL;
    for (int r = 0; r < t->nrow; r++) {
        if (!t->keep[r] || !strcmp(at(t, r, column(t, "role")), "reference"))
            continue;
        if (want)
            t->keep[r] = cl_sweep_same_value(at(t, r, c), want);
        else if (!first)
            first = at(t, r, c);
        else if (!cl_sweep_same_value(first, at(t, r, c)))
            return cl_error_set(err, CL_EINVAL, "--from-sweep %s: the sweep "
                                "has several values of %s (%s, %s, ...): "
                                "give one with --set %s=VALUE", t->path, key,
                                first, at(t, r, c), key);
    }
    /* NA: the runs had the problem file's value (an axis of another
     * part of the sweep) */
    if (want || !first || !*first || !strcmp(first, "NA"))
        return CL_OK;
    if (!strcmp(sec, "run")) /* t_end, read before the table */
        return cl_error_set(err, CL_EINVAL, "--from-sweep %s: the sweep's "
                            "runs have %s = %s, which neither the problem "
                            "nor the command gives: give it (--t-end %s)",
                            t->path, key, first, first);
    char a[4200];
    snprintf(a, sizeof a, "%s=%s", key, first);
    return cl_config_set_as(cfg, a, "--from-sweep", err);
}

/* Whether a table's digest field holds one (not "", not "NA"). */
static bool recorded(const char *sha)
{
    return *sha && strcmp(sha, "NA");
}

/* Row r's run was of the problem file `mine` (SHA-256 `hex`): by the
 * SHA-256 of the file it read (its run.json, column problem_sha256) when
 * it recorded one, which decides (a file edited since, at the same path,
 * held other values); else by the sweep's problem path (cl_same_input). */
static cl_status same_problem_row(const cl_sweep_table *t, int r,
                                  const char *mine, const char *hex,
                                  cl_error *err)
{
    int cs = column(t, "problem_sha256");
    const char *sha = cs >= 0 ? at(t, r, cs) : "";
    if (recorded(sha))
        return strcmp(sha, hex)
                   ? cl_error_set(err, CL_EINVAL, "--from-sweep %s: the run "
                                  "%s read a problem file of other bytes "
                                  "(SHA-256 %.12s...) than %s now "
                                  "(%.12s...): the file changed after it "
                                  "ran, or it is another problem; give the "
                                  "sweep's problem, or run the sweep again",
                                  t->path, at(t, r, column(t, "id")), sha,
                                  mine, hex)
                   : CL_OK;
    const char *path = at(t, r, column(t, "problem"));
    return cl_same_input(path, mine)
               ? CL_OK
               : cl_error_set(err, CL_EINVAL, "--from-sweep %s: its runs are "
                              "of %s, not of %s; give the sweep's problem",
                              t->path, path, mine);
}

/* The table's runs read the same files the problem names (meshes):
 * their inputs_sha256, where recorded, agree (a mesh edited between two
 * runs of the sweep would mix two cloths or obstacles in one table). */
static cl_status same_inputs(const cl_sweep_table *t, cl_error *err)
{
    int c = column(t, "inputs_sha256");
    const char *first = NULL;
    int r0 = 0;
    for (int r = 0; c >= 0 && r < t->nrow; r++) {
        const char *sha = at(t, r, c);
        if (!recorded(sha))
            continue;
        if (!first) {
            first = sha;
            r0 = r;
        } else if (strcmp(sha, first))
            return cl_error_set(err, CL_EINVAL, "--from-sweep %s: the runs "
                                "%s and %s read different files the "
                                "problem names (inputs_sha256 %.12s... and "
                                "%.12s...: a mesh or [init] state changed "
                                "between the sweep's runs); run the sweep "
                                "again",
                                t->path, at(t, r0, column(t, "id")),
                                at(t, r, column(t, "id")), first, sha);
    }
    return CL_OK;
}

/* The files the model named (cl_config_input_files), as their digest. */
typedef struct {
    cl_sweep_inputs in;
    cl_error *err;
    cl_status rc;
} inputs_now;

static void add_input(void *ctx, const char *sec, const char *key,
                      const char *path, bool given)
{
    inputs_now *d = ctx;
    char hex[CL_SHA256_HEX], name[256];
    (void)given;
    if (d->rc || (d->rc = cl_sha256_file(path, hex, d->err)))
        return;
    snprintf(name, sizeof name, "%s.%s", sec, key);
    cl_sweep_inputs_add(&d->in, name, hex);
}

cl_status cl_sweep_table_same_inputs(const cl_sweep_table *t,
                                     const cl_config *cfg, cl_error *err)
{
    int c = column(t, "inputs_sha256");
    const char *rec = NULL;
    for (int r = 0; c >= 0 && !rec && r < t->nrow; r++)
        rec = recorded(at(t, r, c)) ? at(t, r, c) : NULL;
    if (!rec)
        return CL_OK;
    inputs_now d = {{"", 0}, err, CL_OK};
    char hex[CL_SHA256_HEX];
    cl_config_input_files(cfg, add_input, &d);
    if (d.rc)
        return d.rc;
    cl_sweep_inputs_digest(&d.in, hex);
    return strcmp(rec, hex)
               ? cl_error_set(err, CL_EINVAL, "--from-sweep %s: its runs "
                              "read other files than the problem names now "
                              "(inputs_sha256 %.12s..., now %.12s...: a "
                              "mesh or [init] state changed after the "
                              "sweep ran, or is not the sweep's); run the "
                              "sweep again", t->path, rec, hex)
               : CL_OK;
}

/* The table's runs are of this problem (same_problem_row, every row)
 * and read the same meshes (same_inputs), and no model key changed by
 * --set that is not an axis of the table
 * (the runs had the file's value); the keys of [run] and of the
 * command's own section `own` are no model's. */
static cl_status same_problem(const cl_sweep_table *t, cl_config *cfg,
                              const char *own, cl_error *err)
{
    if (column(t, "problem") < 0)
        return cl_error_set(err, CL_EPARSE, "--from-sweep %s: no problem "
                            "column (collected by an earlier clothode: "
                            "collect the sweep again)", t->path);
    const char *file = cl_config_path(cfg);
    char *mine = file ? realpath(file, NULL) : NULL, hex[CL_SHA256_HEX];
    cl_status rc = mine ? cl_sha256_file(mine, hex, err)
                        : cl_error_set(err, CL_EIO, "%s: cannot resolve the "
                                       "problem file", file ? file : "(none)");
    for (int r = 0; !rc && r < t->nrow; r++)
        rc = same_problem_row(t, r, mine, hex, err);
    free(mine);
    if (!rc)
        rc = same_inputs(t, err);
    const char *sec, *key;
    char name[256];
    for (size_t k = 0; !rc && (key = cl_config_set_key_at(cfg, k, &sec));
         k++) {
        snprintf(name, sizeof name, "%s.%s", sec, key);
        if (strcmp(sec, "run") && (!own || strcmp(sec, own)) &&
            column(t, name) < 0)
            rc = cl_error_set(err, CL_EINVAL, "--from-sweep %s: --set %s, "
                              "yet it is no axis of the sweep, whose runs "
                              "had the problem file's value; --set only the "
                              "sweep's axes", t->path, name);
    }
    return rc;
}

cl_status cl_sweep_table_select(cl_sweep_table *t, cl_config *cfg,
                                const char *own, cl_error *err)
{
    int lo = column(t, "integrator"), hi = column(t, "status");
    if (lo < 0 || hi < lo || column(t, "role") < 0)
        return cl_error_set(err, CL_EPARSE, "--from-sweep %s: not a table "
                            "of 'clothode sweep collect' (no role, "
                            "integrator or status column)", t->path);
    cl_status rc = same_problem(t, cfg, own, err);
    if (rc)
        return rc;
    for (int r = 0; r < t->nrow; r++)
        t->keep[r] = true;
    for (int c = lo + 1; !rc && c < hi; c++)
        if (problem_axis(t->head[c]) && strchr(t->head[c], '.'))
            rc = select_axis(t, cfg, c, err);
    return rc;
}

/* ---- the rows of one method --------------------------------------------- */

static int by_param_down(const void *a, const void *b)
{
    double x = ((const cl_sweep_row *)a)->param, y = ((const cl_sweep_row *)b)->param;
    return (x < y) - (x > y);
}

int cl_sweep_table_rows(const cl_sweep_table *t, const char *label,
                       const char *param, cl_sweep_row *out, int max,
                       cl_error *err)
{
    int cp = column(t, param), ci = column(t, "integrator"), n = 0;
    if (cp < 0)
        return cl_error_set(err, CL_EINVAL, "--from-sweep %s: no %s column "
                            "for %s", t->path, param, label), -1;
    for (int r = 0; r < t->nrow; r++) {
        if (!t->keep[r] || strcmp(at(t, r, ci), label) ||
            strcmp(at(t, r, column(t, "role")), "job") ||
            isnan(number_at(t, r, cp)))
            continue;
        if (n == max)
            return cl_error_set(err, CL_EINVAL, "--from-sweep %s: more than "
                                "%d runs of %s", t->path, max, label), -1;
        out[n++] = (cl_sweep_row){r, number_at(t, r, cp)};
    }
    if (n == 0)
        return cl_error_set(err, CL_EINVAL, "--from-sweep %s: no runs of %s "
                            "(with this problem's axis values)", t->path,
                            label), -1;
    qsort(out, (size_t)n, sizeof *out, by_param_down);
    for (int k = 1; k < n; k++)
        if (out[k].param == out[k - 1].param)
            return cl_error_set(err, CL_EINVAL, "--from-sweep %s: two runs of "
                                "%s at %s = %g (another of the method's axes, "
                                "such as run.atol, varies on its own): a "
                                "level is one run; sweep it as a function of "
                                "%s (atol = rtol / 100) or in parts",
                                t->path, label, param, out[k].param, param),
                   -1;
    return n;
}

static void row_stats(const cl_sweep_table *t, int r, cl_stats *s)
{
    double steps = number_at(t, r, column(t, "steps")),
           rhs = number_at(t, r, column(t, "rhs_evals"));
    s->steps = isnan(steps) ? 0 : (long)steps;
    s->rhs_evals = isnan(rhs) ? 0 : (long)rhs;
    double newton = number_at(t, r, column(t, "nonlin_iters"));
    s->nonlin_iters = isnan(newton) ? 0 : (long)newton;
    s->cpu = number_at(t, r, column(t, "cpu"));
    s->wall = number_at(t, r, column(t, "wall"));
}

static bool complete(const cl_sweep_table *t, int r)
{
    return !strcmp(at(t, r, column(t, "status")), "complete");
}

/* A failed run that got going (a time reached) and was stopped by its
 * state, as the stability search counts a run unstable (stability.h): a
 * blow-up, or a solver that gave up (a state where it cannot go on
 * included).  A run stopped by a signal, a budget, or an I/O error says
 * nothing about the step. */
static bool went_unstable(const cl_sweep_table *t, int r)
{
    const char *why = at(t, r, column(t, "exit"));
    return !strcmp(at(t, r, column(t, "status")), "failed") &&
           !isnan(number_at(t, r, column(t, "t_reached"))) &&
           (!strcmp(why, cl_exit_name(CL_EXIT_BLOWUP)) ||
            !strcmp(why, cl_exit_name(CL_EXIT_SOLVER)));
}

bool cl_sweep_table_trial(const cl_sweep_table *t, cl_sweep_row row,
                          cl_stab_trial *tr)
{
    int r = row.row;
    memset(tr, 0, sizeof *tr);
    if (!complete(t, r) && !went_unstable(t, r))
        return false;
    tr->dt = row.param;
    tr->stretch = NAN;
    tr->rc = complete(t, r) ? CL_OK : CL_EBLOWUP;
    row_stats(t, r, &tr->stats);
    tr->nsteps = tr->stats.steps;
    if (tr->rc)
        snprintf(tr->why.msg, sizeof tr->why.msg, "failed at t = %g s (%s)",
                 number_at(t, r, column(t, "t_reached")),
                 at(t, r, column(t, "exit")));
    return true;
}

cl_status cl_stab_from_sweep(const cl_sweep_table *t, const char *label,
                             const cl_integrator_type *type,
                             cl_stab_result *r, cl_error *err)
{
    cl_sweep_row rows[CL_STAB_MAX_TRIALS];
    int n = cl_sweep_table_rows(t, label, "run.dt", rows, CL_STAB_MAX_TRIALS, err);
    memset(r, 0, sizeof *r);
    r->type = type;
    r->label = label;
    r->dt_stable = r->dt_unstable = NAN;
    r->failed = r->held = -1;
    for (int k = 0; k < n; k++) {
        cl_stab_trial *tr = &r->trial[r->ntrial];
        if (!cl_sweep_table_trial(t, rows[k], tr))
            continue; /* never ran, or refused its input */
        if (tr->rc) /* the smallest unstable step: rows go down in dt */
            r->failed = r->ntrial;
        r->ntrial++;
    }
    if (r->failed >= 0)
        r->dt_unstable = r->trial[r->failed].dt;
    for (int k = r->ntrial - 1; k >= 0; k--)
        if (!r->trial[k].rc && !(r->trial[k].dt >= r->dt_unstable)) {
            r->dt_stable = r->trial[k].dt;
            r->held = k;
        }
    return n < 0 ? err->code : CL_OK;
}

cl_status cl_stab_limit(const cl_sweep_table *t, cl_model *m,
                        const char *label, const cl_integrator_type *type,
                        const cl_integrator_opts *io, const cl_stab_opts *o,
                        cl_stab_result *r, cl_error *err)
{
    return t ? cl_stab_from_sweep(t, label, type, r, err)
             : cl_stability(m, type, io, o, r, err);
}

bool cl_sweep_table_has_runs(const cl_sweep_table *t, const char *label,
                             const char *param)
{
    int cp = column(t, param), ci = column(t, "integrator");
    for (int r = 0; cp >= 0 && r < t->nrow; r++)
        if (t->keep[r] && !strcmp(at(t, r, ci), label) &&
            !strcmp(at(t, r, column(t, "role")), "job") &&
            !isnan(number_at(t, r, cp)))
            return true;
    return false;
}

cl_status cl_conv_from_sweep(const cl_sweep_table *t, const char *label,
                             const cl_integrator_type *type,
                             cl_conv_result *r, cl_error *err)
{
    cl_sweep_row rows[CL_CONV_MAX_LEVELS];
    memset(r, 0, sizeof *r);
    r->type = type;
    r->label = label;
    /* petsc-*: fixed steps where the sweep gave them a dt */
    r->fixed = type->fixed_step ||
               (type->dt_fixes_step &&
                cl_sweep_table_has_runs(t, label, "run.dt"));
    int n = cl_sweep_table_rows(t, label, r->fixed ? "run.dt" : "run.rtol", rows,
                        CL_CONV_MAX_LEVELS, err);
    for (int k = 0; k < n; k++) {
        int row = rows[k].row;
        cl_conv_level *l = &r->lev[r->nlev++];
        l->param = rows[k].param;
        l->rc = complete(t, row) ? CL_OK : CL_EBLOWUP;
        if (l->rc)
            snprintf(l->why.msg, sizeof l->why.msg, "%s (%s)",
                     at(t, row, column(t, "status")),
                     at(t, row, column(t, "exit")));
        l->err_x = number_at(t, row, column(t, "err_x"));
        l->err_v = number_at(t, row, column(t, "err_v"));
        l->fitted = !l->rc && l->err_x > 0;
        l->fitted_v = l->fitted && l->err_v > 0;
        row_stats(t, row, &l->stats);
    }
    cl_conv_fit(r);
    return n < 0 ? err->code : CL_OK;
}
