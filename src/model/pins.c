/* Pins from the problem file: groups, selectors, prescribed motion. */
#include "model/pins.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

typedef struct {
    double w[3];
    double stop;
} pin_motion;

/* Pin one token: "i,j", "i=K" or "j=K"; *used is its length. */
static cl_status pin_token(cl_cloth *c, const char *s, const pin_motion *pm,
                           int *used, cl_error *err)
{
    int i, j, k;
    cl_status rc = CL_OK;
    *used = 0;
    if (sscanf(s, "i = %d%n", &k, used) == 1) {
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

static cl_status read_group(cl_config *cfg, const char *sec, const char *def,
                            cl_cloth *c, cl_error *err)
{
    pin_motion pm = {{0.0, 0.0, 0.0}, INFINITY};
    cl_status rc;
    if ((rc = cl_config_vector(cfg, sec, "velocity", 3, pm.w, err)) ||
        (rc = cl_config_double(cfg, sec, "stop", INFINITY, 0.0, INFINITY,
                               &pm.stop, err)))
        return rc;
    const char *s = cl_config_string(cfg, sec, "at", def);
    char where[256];
    for (;;) {
        int used;
        s += strspn(s, " \t");
        if (!*s)
            return CL_OK;
        rc = pin_token(c, s, &pm, &used, err);
        if (rc == CL_EPARSE)
            return cl_error_set(err, CL_EINVAL,
                                "%s: [%s] at: cannot read \"%s\": expected "
                                "i,j (one particle), i=K (a row) or j=K (a "
                                "column), separated by spaces",
                                cl_config_origin(cfg, sec, "at", where,
                                                 sizeof where), sec, s);
        if (rc) {
            char msg[sizeof err->msg];
            snprintf(msg, sizeof msg, "%s", err->msg);
            return cl_error_set(err, rc, "%s: [%s] at: %s",
                                cl_config_origin(cfg, sec, "at", where,
                                                 sizeof where), sec, msg);
        }
        s += used;
    }
}

cl_status cl_pins_read(cl_config *cfg, cl_cloth *c, cl_error *err)
{
    static const char *const groups[] = {"pins", "pins2", "pins3", "pins4"};
    cl_status rc = CL_OK;
    for (size_t g = 0; rc == CL_OK && g < 4; g++)
        rc = read_group(cfg, groups[g], g == 0 ? "0,0 0,-1" : "", c, err);
    return rc;
}
