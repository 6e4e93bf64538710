/* Pins from the problem file: groups, selectors, boxes, prescribed
 * motion. */
#include "model/pins.h"

#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <string.h>

typedef struct {
    double w[3];
    double stop;
} pin_motion;

/* Pin one token: "p=K", or on a grid "i,j", "i=K" or "j=K"; *used is its
 * length. */
static cl_status pin_token(cl_cloth *c, const char *s, const pin_motion *pm,
                           int *used, cl_error *err)
{
    int i, j, k;
    cl_status rc = CL_OK;
    *used = 0;
    if (sscanf(s, "p = %d%n", &k, used) == 1) {
        rc = cl_cloth_pin_particle(c, k, pm->w, pm->stop, err);
    } else if (c->kind == CL_CLOTH_MESH) {
        return CL_EPARSE;
    } else if (sscanf(s, "i = %d%n", &k, used) == 1) {
        for (j = 0; rc == CL_OK && j < c->nv; j++)
            rc = cl_cloth_pin(c, k, j, pm->w, pm->stop, err);
    } else if (sscanf(s, "j = %d%n", &k, used) == 1) {
        for (i = 0; rc == CL_OK && i < c->nu; i++)
            rc = cl_cloth_pin(c, i, k, pm->w, pm->stop, err);
    } else if (sscanf(s, "%d , %d%n", &i, &j, used) == 2) {
        rc = cl_cloth_pin(c, i, j, pm->w, pm->stop, err);
    } else {
        return CL_EPARSE;
    }
    if (rc == CL_OK && s[*used] && s[*used] != ' ' && s[*used] != '\t')
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

static cl_status read_group(cl_config *cfg, const char *sec, bool first,
                            cl_cloth *c, cl_error *err)
{
    pin_motion pm = {{0.0, 0.0, 0.0}, INFINITY};
    double box[6];
    bool has_box = cl_config_string(cfg, sec, "box", NULL) != NULL;
    bool corners = first && !has_box && c->kind == CL_CLOTH_GRID;
    cl_status rc;
    if ((rc = cl_config_vector(cfg, sec, "velocity", 3, pm.w, err)) ||
        (rc = cl_config_double(cfg, sec, "stop", INFINITY, 0.0, INFINITY,
                               &pm.stop, err)) ||
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
