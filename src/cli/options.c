/* The option tables of the subcommands (see options.h): parsing with
 * getopt_long, reading through the configuration, --help. */
#include "cli/options.h"

#include <assert.h>
#include <getopt.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"

/* Rows of a table with groups expanded: at most this many. */
#define OPT_MAX_ROWS 64
/* getopt_long's value of the k-th row: above every character. */
#define OPT_VAL0 256

typedef struct {
    const cl_cli_opt *row;
    size_t at;    /* offset of its value in the settings */
    bool offered; /* an option of the command line */
    bool unread;  /* a key the command does not read (cl_cli_opt unread) */
} opt_flat;

/* Whether `name` is a word of the space-separated list. */
static bool listed(const char *list, const char *name)
{
    size_t n = strlen(name);
    for (const char *p = list; p && (p = strstr(p, name)); p += n)
        if ((p == list || p[-1] == ' ') && (p[n] == ' ' || !p[n]))
            return true;
    return false;
}

static int flatten(const cl_cli_opt *rows, size_t base, const char *hide,
                   const char *unread, opt_flat *f, int n)
{
    for (const cl_cli_opt *r = rows; r->type != CL_CLI_END; r++) {
        if (r->type == CL_CLI_GROUP) {
            n = flatten(r->group, base + r->field, r->hide, r->unread, f, n);
            continue;
        }
        assert(n < OPT_MAX_ROWS);
        bool skip = listed(unread, r->name ? r->name : r->key);
        f[n++] = (opt_flat){r, base + r->field,
                            r->name && !skip && !listed(hide, r->name),
                            skip};
    }
    return n;
}

int cl_cli_sets_add(cl_cli_sets *s, const char *key, const char *val,
                    const char *label)
{
    size_t len = (key ? strlen(key) : 0) + strlen(val) + 2;
    char *a = malloc(len);
    char **grown = realloc(s->v, (size_t)(s->n + 1) * sizeof *grown);
    if (grown)
        s->v = grown;
    const char **lgrown = realloc(s->label, (size_t)(s->n + 1) *
                                                sizeof *lgrown);
    if (lgrown)
        s->label = lgrown;
    if (!a || !grown || !lgrown) {
        free(a);
        return -1;
    }
    snprintf(a, len, "%s%s%s", key ? key : "", key ? "=" : "", val);
    s->label[s->n] = key ? label : NULL;
    s->v[s->n++] = a;
    return 0;
}

void cl_cli_sets_free(cl_cli_sets *s)
{
    for (int k = 0; k < s->n; k++)
        free(s->v[k]);
    free(s->v);
    free(s->label);
    s->v = NULL;
    s->label = NULL;
    s->n = 0;
}

/* The option of row r found by getopt_long, with its argument. */
static int take(const cl_cli_table *t, const opt_flat *f, const char *arg,
                char *settings)
{
    const cl_cli_opt *r = f->row;
    cl_cli_args *a = (cl_cli_args *)settings;
    char key[128];
    if (r->type == CL_CLI_HELP) {
        cl_cli_help(t, stdout);
        return -2;
    }
    if (r->type == CL_CLI_FLAG) {
        *(bool *)(settings + f->at) = true;
        return 0;
    }
    if (r->type == CL_CLI_SET)
        return cl_cli_sets_add(&a->sets, NULL, arg, NULL);
    if (!r->key) {
        *(const char **)(settings + f->at) = arg;
        return 0;
    }
    snprintf(key, sizeof key, "%s.%s", r->sec, r->key);
    return cl_cli_sets_add(&a->sets, key, arg, r->name);
}

/* A usage error (exit status 2) printed, and -1. */
static int refused(const cl_cli_table *t, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));
static int refused(const cl_cli_table *t, const char *fmt, ...)
{
    char msg[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    cl_cli_usage_error(t->cmd, "%s", msg);
    return -1;
}

/* The argument count and the required options, once all are parsed. */
static int check_given(const cl_cli_table *t, int argc, char **argv,
                       const opt_flat *f, int n, const bool *given)
{
    if (t->npos == 1 && optind != argc - 1)
        return refused(t, "expected exactly one %s, got %d",
                       t->pos ? t->pos : "PROBLEM", argc - optind);
    if (t->npos == 0 && optind != argc)
        return refused(t, "unexpected argument '%s'", argv[optind]);
    for (int k = 0; k < n; k++) /* a keyed one may come from the file */
        if (f[k].row->required && !f[k].row->key && !given[k])
            return refused(t, "--%s %s is required", f[k].row->name,
                           f[k].row->arg);
    return optind;
}

int cl_cli_parse(int argc, char **argv, const cl_cli_table *t,
                 void *settings)
{
    opt_flat f[OPT_MAX_ROWS];
    struct option lo[OPT_MAX_ROWS + 1];
    bool given[OPT_MAX_ROWS] = {false};
    int n = flatten(t->rows, 0, NULL, NULL, f, 0), m = 0, c;
    for (int k = 0; k < n; k++) {
        if (f[k].offered)
            lo[m++] = (struct option){f[k].row->name,
                                      f[k].row->arg ? required_argument
                                                    : no_argument,
                                      NULL, OPT_VAL0 + k};
        if (!f[k].row->key && f[k].row->type == CL_CLI_STRING)
            *(const char **)((char *)settings + f[k].at) = f[k].row->sdef;
    }
    lo[m] = (struct option){0};
    optind = 1;
    opterr = 0;
    while ((c = getopt_long(argc, argv, ":", lo, NULL)) != -1) {
        const char *opt = argv[optind - 1];
        if (c == ':')
            return refused(t, "option '%s' needs a value (%s %s)", opt, opt,
                           f[optopt - OPT_VAL0].row->arg);
        if (c == '?' && optopt >= OPT_VAL0)
            return refused(t, "option '%s' takes no value", opt);
        if (c == '?')
            return refused(t, "unknown or ambiguous option '%s'", opt);
        /* an option of no key (--out, ...) given twice would keep the last
         * silently; a keyed one is refused as a key set twice, --set and
         * a flag may repeat */
        const cl_cli_opt *row = f[c - OPT_VAL0].row;
        if (given[c - OPT_VAL0] && !row->key && row->arg &&
            row->type != CL_CLI_SET)
            return refused(t, "option --%s given twice; give it once",
                           row->name);
        given[c - OPT_VAL0] = true;
        int rc = take(t, &f[c - OPT_VAL0], optarg, settings);
        if (rc == -1)
            return refused(t, "out of memory");
        if (rc)
            return rc;
    }
    return check_given(t, argc, argv, f, n, given);
}

cl_status cl_cli_refuse_unless(const cl_config *cfg, const cl_cli_table *t,
                               const char *const *names, bool mode,
                               const char *with, cl_error *err)
{
    for (int k = 0; !mode && names[k]; k++)
        for (const cl_cli_opt *r = t->rows; r->type != CL_CLI_END; r++)
            if (r->name && r->key && !strcmp(r->name, names[k]) &&
                cl_config_peek(cfg, r->sec, r->key))
                return cl_error_set(err, CL_EINVAL, "--%s ([%s] %s) goes "
                                    "with %s; without it, it would be "
                                    "ignored", r->name, r->sec, r->key,
                                    with);
    return CL_OK;
}

/* ---- reading the keys -------------------------------------------------- */

const char *cl_cli_join(const char *const *names, char *buf, size_t len)
{
    size_t used = 0;
    buf[0] = '\0';
    for (size_t k = 0; names[k] && used < len; k++)
        used += (size_t)snprintf(buf + used, len - used, "%s%s",
                                 k ? ", " : "", names[k]);
    return buf;
}

/* A list of row->names separated by commas or spaces, each at most once:
 * bit k of *mask for names[k]. */
static cl_status read_names(cl_config *cfg, const cl_cli_opt *r,
                            unsigned *mask, cl_error *err)
{
    const char *v = cl_config_string(cfg, r->sec, r->key,
                                     r->sdef ? r->sdef : "");
    char why[256] = "expected a list of ";
    *mask = 0;
    for (const char *p = v + strspn(v, ", "); *p; p += strspn(p, ", ")) {
        size_t n = strcspn(p, ", "), k = 0;
        while (r->names[k] && !(strlen(r->names[k]) == n &&
                                !strncmp(p, r->names[k], n)))
            k++;
        if (!r->names[k]) {
            size_t at = strlen(why);
            cl_cli_join(r->names, why + at, sizeof why - at);
            return cl_config_refuse(cfg, r->sec, r->key, CL_EINVAL, why,
                                    err);
        }
        if (*mask & 1u << k) {
            snprintf(why, sizeof why, "%s is listed twice", r->names[k]);
            return cl_config_refuse(cfg, r->sec, r->key, CL_EINVAL, why,
                                    err);
        }
        *mask |= 1u << k;
        p += n;
    }
    if (*mask)
        return CL_OK;
    snprintf(why, sizeof why, "an empty list; expected at least one of ");
    cl_cli_join(r->names, why + strlen(why), sizeof why - strlen(why));
    return cl_config_refuse(cfg, r->sec, r->key, CL_EINVAL, why, err);
}

static cl_status read_row(cl_config *cfg, const cl_cli_opt *r, char *s,
                          size_t at, cl_error *err)
{
    double def = r->def, hi = r->hi;
    long v;
    cl_status rc;
    if (r->bounds)
        r->bounds(s, &def, &hi);
    switch (r->type) {
    case CL_CLI_DOUBLE:
        return cl_config_double(cfg, r->sec, r->key, def, r->lo, hi,
                                (double *)(s + at), err);
    case CL_CLI_LONG:
        return cl_config_long(cfg, r->sec, r->key, (long)def, (long)r->lo,
                              (long)hi, (long *)(s + at), err);
    case CL_CLI_INT:
        rc = cl_config_long(cfg, r->sec, r->key, (long)def, (long)r->lo,
                            (long)hi, &v, err);
        if (!rc)
            *(int *)(s + at) = (int)v;
        return rc;
    case CL_CLI_STRING:
        *(const char **)(s + at) = cl_config_string(cfg, r->sec, r->key,
                                                     r->sdef ? r->sdef : "");
        return CL_OK;
    case CL_CLI_NAMES:
        return read_names(cfg, r, (unsigned *)(s + at), err);
    case CL_CLI_METHODS:
        return cl_cli_methods_read(cfg, r, (cl_cli_methods *)(s + at), err);
    default:
        return CL_OK;
    }
}

cl_status cl_cli_not_read(cl_config *cfg, const char *cmd, const char *sec,
                          const char *key, cl_error *err)
{
    char why[160];
    if (!cl_config_set_by_command(cfg, sec, key)) {
        cl_config_ignore(cfg, sec, key);
        return CL_OK;
    }
    snprintf(why, sizeof why, "clothode %s does not read it (in a problem "
             "file it is ignored, so that one file serves run and the "
             "studies)", cmd);
    return cl_config_refuse(cfg, sec, key, CL_EINVAL, why, err);
}

cl_status cl_cli_read(cl_config *cfg, const cl_cli_table *t, void *settings,
                      cl_error *err)
{
    opt_flat f[OPT_MAX_ROWS];
    int n = flatten(t->rows, 0, NULL, NULL, f, 0);
    cl_status rc = CL_OK;
    for (int k = 0; !rc && k < n; k++)
        if (f[k].unread)
            rc = cl_cli_not_read(cfg, t->cmd, f[k].row->sec, f[k].row->key,
                                 err);
        else if (f[k].row->key)
            rc = read_row(cfg, f[k].row, settings, f[k].at, err);
    /* a required keyed string: given as the option, by --set or in the
     * problem file */
    for (int k = 0; !rc && k < n; k++)
        if (f[k].row->required && f[k].row->key &&
            f[k].row->type == CL_CLI_STRING &&
            !**(const char **)((char *)settings + f[k].at))
            rc = cl_error_set(err, CL_EINVAL, "%s: --%s %s ([%s] %s) is "
                              "required", t->cmd, f[k].row->name,
                              f[k].row->arg, f[k].row->sec, f[k].row->key);
    return rc;
}

/* ---- --help ------------------------------------------------------------ */

/* "lead  text" with the text from column 21 (or two spaces after a longer
 * lead), wrapped at column 78 with continuation lines indented to 21. */
static void wrapped(FILE *fp, const char *lead, const char *text)
{
    int col = fprintf(fp, "%-19s  ", lead);
    bool first = true;
    for (const char *p = text; *p; first = false) {
        int n = (int)strcspn(p, " ");
        if (!first && col + 1 + n > 78)
            col = fprintf(fp, "\n%21s", "") - 1;
        else if (!first)
            col += fprintf(fp, " ");
        col += fprintf(fp, "%.*s", n, p);
        p += n + (p[n] == ' ');
    }
    fputc('\n', fp);
}

/* The row's help with its key (with_key), whether it is required, its
 * range and default: "final time (s); [run] t_end, default 2". */
static void describe(const cl_cli_opt *r, bool with_key, char *buf,
                     size_t len)
{
    char more[256] = "";
    size_t u = 0;
    if (with_key && r->key)
        u += (size_t)snprintf(more + u, sizeof more - u, ", [%s] %s", r->sec,
                              r->key);
    if (r->required)
        u += (size_t)snprintf(more + u, sizeof more - u, ", required");
    bool integer = r->type == CL_CLI_LONG || r->type == CL_CLI_INT;
    if (integer)
        u += (size_t)snprintf(more + u, sizeof more - u, ", %.0f .. %.0f",
                              r->lo, r->hi);
    /* a default set by bounds (0 in the row) is told by the help text */
    if (integer || (r->type == CL_CLI_DOUBLE && r->def != 0))
        snprintf(more + u, sizeof more - u, ", default %.*g",
                 integer ? 17 : 6, r->def);
    else if (r->sdef && *r->sdef)
        snprintf(more + u, sizeof more - u, ", default %s", r->sdef);
    snprintf(buf, len, *more ? "%s; %s" : "%s", r->help, more + 2);
}

void cl_cli_help(const cl_cli_table *t, FILE *fp)
{
    opt_flat f[OPT_MAX_ROWS];
    int n = flatten(t->rows, 0, NULL, NULL, f, 0);
    char lead[64], text[768];
    bool keys = false;
    fprintf(fp, "usage: clothode %s%s%s\n%s\n", t->cmd,
            *t->synopsis ? " " : "", t->synopsis, t->about);
    for (int k = 0; k < n; k++) {
        const cl_cli_opt *r = f[k].row;
        keys |= r->key && !f[k].offered && !f[k].unread;
        if (!f[k].offered)
            continue;
        snprintf(lead, sizeof lead, "  --%s%s%s", r->name, r->arg ? " " : "",
                 r->arg ? r->arg : "");
        describe(r, t->npos == 1 && !t->pos, text, sizeof text); /* keys of
                                                      * a problem */
        wrapped(fp, lead, text);
    }
    if (keys)
        fprintf(fp, "Keys without an option (problem file or --set "
                    "SEC.KEY=VAL):\n");
    for (int k = 0; keys && k < n; k++)
        if (f[k].row->key && !f[k].offered && !f[k].unread) {
            snprintf(lead, sizeof lead, "  [%s] %s", f[k].row->sec,
                     f[k].row->key);
            describe(f[k].row, false, text, sizeof text);
            wrapped(fp, lead, text);
        }
    if (t->notes)
        fputs(t->notes, fp);
}
