/* Pins from the problem file: groups, selectors, boxes, prescribed
 * motion. */
#include "model/pins.h"

#include <ctype.h>
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
    double w[3];
    double stop;
} pin_motion;

enum { PIN_INT, PIN_NONE, PIN_OVERFLOW };

/* An int at s + *used after optional blanks, or after "NAME =" when name is
 * not NULL; *used grows by what was read.  PIN_NONE if there is none,
 * PIN_OVERFLOW if it does not fit an int (strtol saturates; sscanf's %d is
 * undefined there). */
static int pin_int(const char *s, const char *name, int *k, int *used)
{
    const char *p = s + *used;
    if (name) {
        p += strspn(p, " \t");
        if (strncmp(p, name, strlen(name)) != 0)
            return PIN_NONE;
        p += strspn(p + strlen(name), " \t") + strlen(name);
        if (*p++ != '=')
            return PIN_NONE;
    }
    p += strspn(p, " \t");
    if (!(isdigit((unsigned char)*p) ||
          ((*p == '-' || *p == '+') && isdigit((unsigned char)p[1]))))
        return PIN_NONE;
    char *end;
    errno = 0;
    long v = strtol(p, &end, 10);
    *used = (int)(end - s);
    if (errno == ERANGE || v < INT_MIN || v > INT_MAX)
        return PIN_OVERFLOW;
    *k = (int)v;
    return PIN_INT;
}

/* "i , j": two ints separated by a comma. */
static int pin_pair(const char *s, int *i, int *j, int *used)
{
    int rc = pin_int(s, NULL, i, used);
    if (rc != PIN_INT)
        return rc;
    *used += (int)strspn(s + *used, " \t");
    if (s[*used] != ',')
        return PIN_NONE;
    ++*used;
    return pin_int(s, NULL, j, used);
}

/* The message on an index that does not fit an int. */
static cl_status pin_overflow(const char *s, int used, cl_error *err)
{
    return cl_error_set(err, CL_EINVAL,
                        "\"%.*s\": index beyond the range of an int (%d .. %d);"
                        " allowed: 0 .. n-1, or negative from the end",
                        used, s, INT_MIN, INT_MAX);
}

/* Pin one token: "p=K", or on a grid "i,j", "i=K" or "j=K"; *used is its
 * length.  CL_EPARSE (without a message) for a token of no known form. */
static cl_status pin_token(cl_cloth *c, const char *s, const pin_motion *pm,
                           int *used, cl_error *err)
{
    int i, j, k, got;
    cl_status rc = CL_OK;
    *used = 0;
    if ((got = pin_int(s, "p", &k, used)) == PIN_INT) {
        rc = cl_cloth_pin_particle(c, k, pm->w, pm->stop, err);
    } else if (got == PIN_NONE && c->kind == CL_CLOTH_MESH) {
        return CL_EPARSE;
    } else if (got == PIN_NONE &&
               (got = pin_int(s, "i", &k, used)) == PIN_INT) {
        for (j = 0; rc == CL_OK && j < c->nv; j++)
            rc = cl_cloth_pin(c, k, j, pm->w, pm->stop, err);
    } else if (got == PIN_NONE &&
               (got = pin_int(s, "j", &k, used)) == PIN_INT) {
        for (i = 0; rc == CL_OK && i < c->nu; i++)
            rc = cl_cloth_pin(c, i, k, pm->w, pm->stop, err);
    } else if (got == PIN_NONE &&
               (got = pin_pair(s, &i, &j, used)) == PIN_INT) {
        rc = cl_cloth_pin(c, i, j, pm->w, pm->stop, err);
    }
    if (got == PIN_OVERFLOW)
        return pin_overflow(s, *used, err);
    if (got == PIN_NONE ||
        (rc == CL_OK && s[*used] && s[*used] != ' ' && s[*used] != '\t'))
        return CL_EPARSE;
    return rc;
}

/* What a token may be, for the message on one that cannot be read. */
static const char *token_forms(const cl_cloth *c)
{
    return c->kind == CL_CLOTH_MESH
               ? "p=K (a vertex, 0-based; a mesh cloth has no rows or "
                 "columns for i,j, i=K, j=K)"
               : "i,j (one particle), i=K (a row), j=K (a column) or p=K "
                 "(particle i*nv + j)";
}

/* err's message prefixed with "origin: [sec] key: "; returns rc. */
static cl_status in_key(cl_config *cfg, const char *sec, const char *key,
                        cl_status rc, cl_error *err)
{
    char where[256], msg[sizeof err->msg];
    snprintf(msg, sizeof msg, "%s", err->msg);
    return cl_error_set(err, rc, "%s: [%s] %s: %s",
                        cl_config_origin(cfg, sec, key, where, sizeof where),
                        sec, key, msg);
}

/* The pins of the `at` list s. */
static cl_status pin_list(cl_config *cfg, const char *sec, const char *s,
                          cl_cloth *c, const pin_motion *pm, cl_error *err)
{
    char where[256];
    for (;;) {
        int used;
        s += strspn(s, " \t");
        if (!*s)
            return CL_OK;
        cl_status rc = pin_token(c, s, pm, &used, err);
        if (rc == CL_EPARSE)
            return cl_error_set(err, CL_EINVAL,
                                "%s: [%s] at: cannot read \"%s\": expected "
                                "%s, separated by spaces",
                                cl_config_origin(cfg, sec, "at", where,
                                                 sizeof where), sec, s,
                                token_forms(c));
        if (rc)
            return in_key(cfg, sec, "at", rc, err);
        s += used;
    }
}

/* Pin every particle whose rest position lies in the box b (x0, y0, z0,
 * x1, y1, z1). */
static cl_status pin_box(cl_config *cfg, const char *sec, const double b[6],
                         cl_cloth *c, const pin_motion *pm, cl_error *err)
{
    size_t caught = 0;
    for (size_t p = 0; p < c->np; p++) {
        const double *X = c->X0 + 3 * p;
        bool inside = true;
        for (int d = 0; d < 3; d++)
            inside = inside && b[d] <= X[d] && X[d] <= b[3 + d];
        if (!inside)
            continue;
        cl_status rc = cl_cloth_pin_particle(c, (int)p, pm->w, pm->stop, err);
        if (rc)
            return in_key(cfg, sec, "box", rc, err);
        caught++;
    }
    if (caught == 0)
        return cl_config_refuse(cfg, sec, "box", CL_EINVAL,
                                "no particle's rest position lies in the box "
                                "(x0, y0, z0, x1, y1, z1 with x0 <= x <= x1, "
                                "y0 <= y <= y1, z0 <= z <= z1)", err);
    return CL_OK;
}

/* [pins] stop: a time (s) after which the group stays put, or "never"
 * (the default), so that a problem's stop can be lifted by --set or a
 * sweep's axis. */
static cl_status read_stop(cl_config *cfg, const char *sec, double *stop,
                           cl_error *err)
{
    /* the default is recorded (run.json, config.ini) as "never" */
    if (strcmp(cl_config_string(cfg, sec, "stop", "never"), "never") == 0) {
        *stop = INFINITY;
        return CL_OK;
    }
    cl_error why = {0};
    if (cl_config_double(cfg, sec, "stop", INFINITY, 0.0, INFINITY, stop,
                         &why) == CL_OK)
        return CL_OK;
    return cl_config_refuse(cfg, sec, "stop", CL_EINVAL,
                            "expected a time in [0, 1e+12] s, or never",
                            err);
}

static cl_status read_group(cl_config *cfg, const char *sec, bool first,
                            cl_cloth *c, cl_error *err)
{
    pin_motion pm = {{0.0, 0.0, 0.0}, INFINITY};
    double box[6];
    bool has_box = cl_config_string(cfg, sec, "box", NULL) != NULL;
    bool corners = first && !has_box && c->kind == CL_CLOTH_GRID;
    cl_status rc;
    if ((rc = cl_config_vector(cfg, sec, "velocity", 3, pm.w, err)) ||
        (rc = read_stop(cfg, sec, &pm.stop, err)) ||
        (rc = cl_config_vector(cfg, sec, "box", 6, box, err)) ||
        (rc = pin_list(cfg, sec,
                       cl_config_string(cfg, sec, "at",
                                        corners ? "0,0 0,-1" : ""),
                       c, &pm, err)))
        return rc;
    return has_box ? pin_box(cfg, sec, box, c, &pm, err) : CL_OK;
}

cl_status cl_pins_read(cl_config *cfg, cl_cloth *c, cl_error *err)
{
    static const char *const groups[] = {"pins", "pins2", "pins3", "pins4"};
    cl_status rc = CL_OK;
    for (size_t g = 0; rc == CL_OK && g < 4; g++)
        rc = read_group(cfg, groups[g], g == 0, c, err);
    return rc;
}
