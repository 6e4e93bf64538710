/* The cloth of a problem from [cloth]: grid or OBJ mesh (keys in
 * model/cloth_read.h). */
#include "model/cloth_read.h"

#include <math.h>
#include <stdbool.h>
#include <stdio.h>

#include "io/obj.h"

#define SEC "cloth"

/* `code` with the message "origin: [sec] key = "value": why". */
/* The first of keys (NULL-terminated) the problem sets, or NULL. */
static const char *first_set(cl_config *cfg, const char *const *keys)
{
    for (size_t k = 0; keys[k]; k++)
        if (cl_config_string(cfg, SEC, keys[k], NULL))
            return keys[k];
    return NULL;
}

static cl_status read_grid(cl_config *cfg, cl_cloth *c, cl_error *err)
{
    static const char *const mesh_keys[] = {"scale", "translate", NULL};
    const char *k = first_set(cfg, mesh_keys);
    if (k)
        return cl_config_refuse(cfg, SEC, k, CL_EINVAL,
                                "applies to a mesh cloth only (set [cloth] "
                                "mesh = FILE.obj)", err);
    long n, nu, nv;
    double size, su, sv, mass, pmass;
    cl_status rc;
    if ((rc = cl_config_long(cfg, SEC, "n", 16, 2, 4096, &n, err)) ||
        (rc = cl_config_long(cfg, SEC, "nu", n, 1, 4096, &nu, err)) ||
        (rc = cl_config_long(cfg, SEC, "nv", n, 1, 4096, &nv, err)) ||
        (rc = cl_config_double(cfg, SEC, "size", 1.0, 1e-300, INFINITY,
                               &size, err)) ||
        (rc = cl_config_double(cfg, SEC, "su", size, 1e-300, INFINITY,
                               &su, err)) ||
        (rc = cl_config_double(cfg, SEC, "sv", size, 1e-300, INFINITY,
                               &sv, err)) ||
        (rc = cl_config_double(cfg, SEC, "mass", 0.1, 1e-300, INFINITY,
                               &mass, err)) ||
        (rc = cl_config_double(cfg, SEC, "particle_mass",
                               mass / (double)(nu * nv), 1e-300, INFINITY,
                               &pmass, err)))
        return rc;
    return cl_cloth_grid((int)nu, (int)nv, su, sv, pmass, c, err);
}

/* A mesh cloth from the file, masses as read_mesh says. */
static cl_status mesh_from_file(const char *path, double scale,
                                const double t[3], double mass, double pmass,
                                cl_cloth *c, cl_error *err)
{
    cl_obj obj;
    cl_status rc = cl_obj_read(path, &obj, err);
    if (rc)
        return rc;
    cl_obj_place(&obj, scale, t);
    rc = cl_cloth_mesh(obj.nvert, obj.vert, obj.ntri,
                       (const int(*)[3])obj.tri, mass, c, err);
    cl_obj_free(&obj);
    for (size_t p = 0; rc == CL_OK && pmass > 0 && p < c->np; p++)
        c->mass[p] = pmass;
    return rc;
}

static cl_status read_mesh(cl_config *cfg, cl_cloth *c, cl_error *err)
{
    static const char *const grid_keys[] = {"n",  "nu", "nv",       "size",
                                            "su", "sv", "diagonal", NULL};
    const char *k = first_set(cfg, grid_keys);
    if (k)
        return cl_config_refuse(cfg, SEC, k, CL_EINVAL,
                                "a grid key (n, nu, nv, size, su, sv, "
                                "diagonal) does not apply to a mesh cloth "
                                "([cloth] mesh): remove it", err);
    char path[4096];
    double scale, t[3] = {0.0, 0.0, 0.0}, mass, pmass;
    cl_status rc;
    if ((rc = cl_config_path_of(cfg, SEC, "mesh", path, sizeof path, err)) ||
        (rc = cl_config_double(cfg, SEC, "scale", 1.0, 1e-300, INFINITY,
                               &scale, err)) ||
        (rc = cl_config_vector(cfg, SEC, "translate", 3, t, err)) ||
        (rc = cl_config_double(cfg, SEC, "mass", 0.1, 1e-300, INFINITY,
                               &mass, err)) ||
        (rc = cl_config_double(cfg, SEC, "particle_mass", 0.0, 1e-300,
                               INFINITY, &pmass, err)))
        return rc;
    if ((rc = mesh_from_file(path, scale, t, mass, pmass, c, err))) {
        char msg[sizeof err->msg];
        snprintf(msg, sizeof msg, "%s", err->msg);
        return cl_config_refuse(cfg, SEC, "mesh", rc, msg, err);
    }
    return CL_OK;
}

cl_status cl_cloth_read(cl_config *cfg, cl_cloth *c, cl_error *err)
{
    return cl_config_string(cfg, SEC, "mesh", NULL) ? read_mesh(cfg, c, err)
                                                     : read_grid(cfg, c, err);
}

cl_status cl_cloth_grid_only(cl_config *cfg, const cl_cloth *c,
                             const char *sec, const char *key,
                             const char *why, cl_error *err)
{
    if (c->kind == CL_CLOTH_GRID)
        return CL_OK;
    bool named = cl_config_string(cfg, sec, key, NULL) != NULL;
    return cl_config_refuse(cfg, named ? sec : SEC, named ? key : "mesh",
                            CL_EINVAL, why, err);
}
