/* Benchmark workload 7 (bench/bench.h): the contact layer's nearest-
 * triangle query by its bounding-volume tree (contact/bvh.h) against
 * trying every triangle, CPU time per point, on an icosphere of level 5
 * (20480 triangles, radius 1), for 10^4 points in two spreads:
 *   band  within 10 % of the radius of the surface, inside and outside
 *         (uniform directions and radii 0.9..1.1), where contact is looked
 *         for: goal >= 50x;
 *   cube  uniform in the cube [-1.5, 1.5]^3, a sixth of them deep inside
 *         where every triangle is nearly as near as the nearest and the
 *         tree prunes little: no goal, for the record.
 * Both answers are compared on the points brute force got through. */
#include <math.h>
#include <stdbool.h>
#include <stdlib.h>

#include "bench/bench_impl.h"
#include "contact/bvh.h"
#include "contact/icosphere.h"
#include "core/stop.h"

#define W7_LEVEL 5
#define W7_POINTS 10000
#define W7_MIN_BRUTE 64     /* points brute force is timed on at least */

typedef void (*w7_query)(const cl_bvh *, const double *, cl_bvh_hit *);

typedef struct {
    cl_shape_surface s;
    cl_bvh b;
    double *x;              /* the points, 3 each */
    double *tree, *brute;   /* squared distances found for them */
} w7_case;

/* The points of the band (radii 0.9..1.1) or of the cube. */
static void w7_points(bool band, double *x)
{
    unsigned long long seed = 7;
    for (size_t k = 0; k < W7_POINTS; k++) {
        double *p = x + 3 * k, r2;
        do {
            for (int i = 0; i < 3; i++)
                p[i] = cl_bench_uniform(&seed);
            r2 = p[0] * p[0] + p[1] * p[1] + p[2] * p[2];
        } while (band && (r2 > 1 || r2 < 1e-4));
        double scale = band ? (1 + 0.1 * cl_bench_uniform(&seed)) / sqrt(r2)
                            : 1.5;
        for (int i = 0; i < 3; i++)
            p[i] *= scale;
    }
}
/* Seconds per point of `query` (CPU and wall) over the points, cycling,
 * until `budget` CPU seconds have passed and at least `min` points are
 * done, or a signal stops the bench; their squared distances into d2 (the
 * first W7_POINTS).  Returns the number of points done. */
static long w7_time(const w7_case *w, w7_query query, double budget,
                    long min, double *d2, double *cpu, double *wall)
{
    double c0, w0, c1, w1;
    long k = 0;
    cl_bench_clock(&c0, &w0);
    c1 = c0;
    w1 = w0;
    while ((k < min || c1 - c0 < budget) && !cl_stop_interrupted()) {
        for (int r = 0; r < 16; r++, k++) {
            cl_bvh_hit h;
            query(&w->b, w->x + 3 * (k % W7_POINTS), &h);
            if (k < W7_POINTS)
                d2[k] = h.p.dist2;
        }
        cl_bench_clock(&c1, &w1);
    }
    *cpu = k ? (c1 - c0) / (double)k : NAN;
    *wall = k ? (w1 - w0) / (double)k : NAN;
    return k;
}

static void w7_measure(cl_bctx *c, w7_case *w, bool band)
{
    cl_bench_row *row = cl_bench_row_add(c, 7, band ? "band 0.9..1.1 R"
                                                    : "cube 1.5 R");
    snprintf(row->side_a, sizeof row->side_a, "bvh nearest triangle");
    snprintf(row->side_b, sizeof row->side_b, "every triangle");
    w7_points(band, w->x);
    long na = w7_time(w, cl_bvh_nearest, c->plan.eval_budget, W7_POINTS,
                      w->tree, &row->cpu_a, &row->wall_a);
    long nb = w7_time(w, cl_bvh_nearest_brute, c->plan.eval_budget,
                      W7_MIN_BRUTE, w->brute, &row->cpu_b, &row->wall_b);
    long compared = nb < W7_POINTS ? nb : W7_POINTS, differ = 0;
    for (long k = 0; k < compared; k++)
        differ += fabs(sqrt(w->tree[k]) - sqrt(w->brute[k])) > 1e-12;
    cl_bench_judge(row, row->cpu_b / row->cpu_a, "x", band ? ">=" : "",
                   50.0);
    cl_bench_note(row, "icosphere of %zu triangles; %ld points timed "
                  "(tree), %ld (brute force); %ld of %ld distances differ",
                  w->s.ntri, na, nb, differ, compared);
    cl_bench_log_row(c, row);
}

void cl_bench_w7(cl_bctx *c)
{
    cl_bench_log(c, "  nearest triangle: tree against brute force ...");
    w7_case w = {.x = malloc(3 * W7_POINTS * sizeof *w.x),
                 .tree = malloc(W7_POINTS * sizeof *w.tree),
                 .brute = malloc(W7_POINTS * sizeof *w.brute)};
    cl_error err = {0};
    if (!w.x || !w.tree || !w.brute) {
        c->nomem = true;
    } else if (cl_icosphere(W7_LEVEL, (const double[3]){0, 0, 0}, 1.0, &w.s,
                            &err) ||
               cl_bvh_build(&w.b, w.s.vert, w.s.ntri,
                            (const int(*)[3])w.s.tri, &err)) {
        cl_bench_note(cl_bench_row_add(c, 7, "icosphere"), "%s", err.msg);
    } else {
        w7_measure(c, &w, true);
        w7_measure(c, &w, false);
    }
    cl_bvh_free(&w.b);
    cl_shape_surface_free(&w.s);
    free(w.x);
    free(w.tree);
    free(w.brute);
}
