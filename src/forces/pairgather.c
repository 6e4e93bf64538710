/* Per-particle sums of per-pair forces (forces/pairgather.h). */
#include "forces/pairgather.h"

#include <stdlib.h>
#include <string.h>

#include "forces/pairkern.h"

cl_status cl_pairgather_init(cl_pairgather *g, const int *ia, const int *ib,
                             size_t n, cl_error *err)
{
    memset(g, 0, sizeof *g);
    g->n = n;
    for (size_t k = 0; k < n; k++) {
        size_t top = (size_t)(ia[k] > ib[k] ? ia[k] : ib[k]);
        g->np = top + 1 > g->np ? top + 1 : g->np;
    }
    g->start = calloc(2 * g->np + 2, sizeof *g->start);
    g->list = malloc((2 * n + 1) * sizeof *g->list);
    g->f4 = malloc((4 * n + 4) * sizeof *g->f4);
    if (!g->start || !g->list || !g->f4)
        return cl_error_set(err, CL_ENOMEM, "out of memory (per-particle "
                            "sums, %zu pairs)", n);
    /* Counting sort by list 2p (p is a) or 2p + 1 (p is b), stable:
     * each list in increasing k. */
    for (size_t k = 0; k < n; k++) {
        g->start[2 * (size_t)ia[k] + 1]++;
        g->start[2 * (size_t)ib[k] + 2]++;
    }
    for (size_t q = 0; q < 2 * g->np; q++)
        g->start[q + 1] += g->start[q];
    for (size_t k = 0; k < n; k++) {
        g->list[g->start[2 * (size_t)ia[k]]++] = 4 * (long)k;
        g->list[g->start[2 * (size_t)ib[k] + 1]++] = 4 * (long)k;
    }
    /* start[q] is now the end of list q: shift back by one list. */
    memmove(g->start + 1, g->start, 2 * g->np * sizeof *g->start);
    g->start[0] = 0;
    return CL_OK;
}

void cl_pairgather_free(cl_pairgather *g)
{
    free(g->start);
    free(g->list);
    free(g->f4);
    memset(g, 0, sizeof *g);
}

/* Four doubles, one vector register in the AVX2 clone (GCC's vector
 * extensions; two in the default one). */
typedef double v4d __attribute__((vector_size(32)));

/* The sum of the per-pair forces of list [e0, e1) into *s, in the
 * list's order. */
CL_PAIR_INLINE void list_sum(const double *restrict f4,
                             const long *restrict list, size_t e0, size_t e1,
                             v4d *s)
{
    v4d sum = {0.0, 0.0, 0.0, 0.0};
    for (size_t e = e0; e < e1; e++) {
        v4d q;
        memcpy(&q, f4 + list[e], sizeof q);
        sum += q;
    }
    *s = sum;
}

/* Particles [p0, p1). */
CL_PAIR_KERNEL
static void gather_range(const cl_pairgather *g, size_t p0, size_t p1,
                         double *restrict f)
{
    const size_t *start = g->start;
    for (size_t p = p0; p < p1; p++) {
        v4d sa, sb;
        list_sum(g->f4, g->list, start[2 * p], start[2 * p + 1], &sa);
        list_sum(g->f4, g->list, start[2 * p + 1], start[2 * p + 2], &sb);
        v4d net = sa - sb;
        f[3 * p] += net[0];
        f[3 * p + 1] += net[1];
        f[3 * p + 2] += net[2];
    }
}

void cl_pairgather_add(const cl_pairgather *g, int threads, double *f)
{
    if (threads <= 1) {
        gather_range(g, 0, g->np, f);
        return;
    }
    size_t nt = (size_t)threads;
#pragma omp parallel for num_threads(threads) schedule(static)
    for (size_t t = 0; t < nt; t++)
        gather_range(g, g->np * t / nt, g->np * (t + 1) / nt, f);
}
