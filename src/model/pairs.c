/* Pair connection sets on a grid cloth (SPEC 2). */
#include "model/pairs.h"

#include <stdlib.h>

cl_status cl_pairs_from_offsets(const cl_cloth *c, size_t noff,
                                const int (*off)[2], cl_pairset *s,
                                cl_error *err)
{
    s->n = 0;
    s->pair = malloc((c->np * noff + 1) * sizeof *s->pair);
    if (!s->pair)
        return cl_error_set(err, CL_ENOMEM, "out of memory (pairs)");
    for (int i = 0; i < c->nu; i++)
        for (int j = 0; j < c->nv; j++)
            for (size_t k = 0; k < noff; k++) {
                int i2 = i + off[k][0], j2 = j + off[k][1];
                if (i2 < 0 || i2 >= c->nu || j2 < 0 || j2 >= c->nv)
                    continue;
                cl_pair *pr = &s->pair[s->n++];
                pr->a = cl_cloth_index(c, i, j);
                pr->b = cl_cloth_index(c, i2, j2);
                pr->rest = cl_dist(c->X0 + 3 * pr->a, c->X0 + 3 * pr->b);
            }
    return CL_OK;
}

/* Offsets with di > 0, or di == 0 and dj > 0: each unordered pair once. */
cl_status cl_pairs_type1(const cl_cloth *c, cl_pairset *s, cl_error *err)
{
    static const int off[][2] = {{0, 1}, {1, -1}, {1, 0}, {1, 1}};
    return cl_pairs_from_offsets(c, 4, off, s, err);
}

cl_status cl_pairs_type2(const cl_cloth *c, cl_pairset *s, cl_error *err)
{
    static const int off[][2] = {{0, 2}, {2, -2}, {2, 0}, {2, 2}};
    return cl_pairs_from_offsets(c, 4, off, s, err);
}

size_t cl_level_offsets(long levels, int (*off)[2])
{
    size_t n = 0;
    for (int l = 1; l <= levels; l++) {
        static const int unit[4][2] = {{0, 1}, {1, 0}, {1, 1}, {1, -1}};
        for (int k = 0; k < 4; k++, n++) {
            off[n][0] = l * unit[k][0];
            off[n][1] = l * unit[k][1];
        }
    }
    return n;
}

cl_status cl_pairs_levels(const cl_cloth *c, long levels, cl_pairset *s,
                          cl_error *err)
{
    long span = c->nu > c->nv ? c->nu : c->nv;
    if (levels > span - 1)
        levels = span - 1;
    int(*off)[2] = malloc((4 * (size_t)(levels > 0 ? levels : 0) + 1) *
                          sizeof *off);
    if (!off)
        return cl_error_set(err, CL_ENOMEM, "out of memory (levels)");
    cl_status rc = cl_pairs_from_offsets(c, cl_level_offsets(levels, off),
                                         (const int(*)[2])off, s, err);
    free(off);
    return rc;
}

void cl_pairs_free(cl_pairset *s)
{
    free(s->pair);
    s->pair = NULL;
    s->n = 0;
}
