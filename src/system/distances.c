/* Gathering the distance constraints of a model: see system/distances.h. */
#include "system/distances.h"

#include <math.h>
#include <stdlib.h>

/* The integrators' number of particle p's end: its free index, or -1 - j
 * for pin j (whose position the system's anchors hook gives). */
static int end_index(const cl_cloth *c, int p)
{
    if (c->dof[p] >= 0)
        return c->dof[p];
    size_t j = 0;
    while (j < c->npin && c->pins[j].p != p)
        j++;
    return -1 - (int)j;
}

/* Append the n constraints of one term at position at. */
static void add_term(const cl_cloth *c, const cl_pair *pair, const double *k,
                     size_t n, size_t at, cl_distance_set *ds)
{
    for (size_t i = 0; i < n; i++) {
        ds->end[at + i][0] = end_index(c, pair[i].a);
        ds->end[at + i][1] = end_index(c, pair[i].b);
        ds->rest[at + i] = pair[i].rest;
        ds->stiffness[at + i] = k ? k[i] : INFINITY;
    }
}

cl_status cl_distance_set_build(const cl_cloth *c, size_t nterm,
                                const cl_term_type *const *type,
                                void *const *state, cl_distance_set *ds,
                                cl_error *err)
{
    const cl_pair *pair;
    const double *k;
    size_t n = 0;
    *ds = (cl_distance_set){.d.nanchor = c->npin};
    for (size_t t = 0; t < nterm; t++)
        if (type[t]->distances)
            n += type[t]->distances(state[t], &pair, &k);
    if (n == 0)
        return CL_OK;
    ds->end = malloc(n * sizeof *ds->end);
    ds->rest = malloc(n * sizeof *ds->rest);
    ds->stiffness = malloc(n * sizeof *ds->stiffness);
    if (!ds->end || !ds->rest || !ds->stiffness) {
        cl_distance_set_free(ds);
        return cl_error_set(err, CL_ENOMEM, "out of memory (distances)");
    }
    for (size_t t = 0, at = 0; t < nterm; t++) {
        if (!type[t]->distances)
            continue;
        size_t nt = type[t]->distances(state[t], &pair, &k);
        add_term(c, pair, k, nt, at, ds);
        at += nt;
    }
    ds->d = (cl_distances){.n = n, .end = (const int(*)[2])ds->end,
                           .rest = ds->rest, .stiffness = ds->stiffness,
                           .nanchor = c->npin};
    return CL_OK;
}

void cl_distance_set_free(cl_distance_set *ds)
{
    free(ds->end);
    free(ds->rest);
    free(ds->stiffness);
    *ds = (cl_distance_set){.end = NULL};
}
