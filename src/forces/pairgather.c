/* Per-particle sums of per-pair forces (forces/pairgather.h). */
#include "forces/pairgather.h"

#include <stdlib.h>
#include <string.h>

#include "forces/pairkern.h"

cl_status cl_pairgather_init(cl_pairgather *g, const int *ia, const int *ib,
                             size_t n, size_t np, cl_error *err)
{
    memset(g, 0, sizeof *g);
    g->n = n;
    g->np = np;
    long *key = calloc(2 * n + 1, sizeof *key);
    g->start = malloc((2 * g->np + 1) * sizeof *g->start);
    g->list = malloc((2 * n + 1) * sizeof *g->list);
    g->f4 = malloc((4 * n + 4) * sizeof *g->f4);
    if (!key || !g->start || !g->list || !g->f4) {
        free(key);
        return cl_error_set(err, CL_ENOMEM, "out of memory (per-particle "
                            "sums, %zu pairs)", n);
    }
    /* Code 2k (p = a) in list 2p, code 2k + 1 (p = b) in list 2p + 1,
     * in increasing k; then each code as pair k's place 4k in f4. */
    for (size_t k = 0; k < n; k++) {
        key[2 * k] = 2 * (long)ia[k];
        key[2 * k + 1] = 2 * (long)ib[k] + 1;
    }
    cl_pairkern_incidence(key, 2 * n, 2 * g->np, g->start, g->list);
    for (size_t e = 0; e < 2 * n; e++)
        g->list[e] = 4 * (g->list[e] >> 1);
    free(key);
    return CL_OK;
}

void cl_pairgather_free(cl_pairgather *g)
{
    void *arr[] = {g->start, g->list, g->f4};
    for (size_t i = 0; i < sizeof arr / sizeof *arr; i++)
        free(arr[i]);
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
