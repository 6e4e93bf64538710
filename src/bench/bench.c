/* Benchmarks (bench/bench.h): the plan of a full or quick run, the
 * order of the workloads, the table as CSV and as text. */
#include "bench/bench.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bench/bench_impl.h"
#include "core/stop.h"
#include "io/atomic.h"
#include "io/csv.h"

static const cl_bplan full_plan = {
    .w1_cases = 2, .w1_n = {16, 32}, .w1_t = {2.0, 0.5}, .select = 0,
    .peer_budget = 800.0,
    .w2_n = 32, .w2_t = 2.0, .w2_large = true, .w2_cap = 600.0,
    .w3_nn = 4, .w3_n = {16, 32, 64, 128}, .w3_budget = 1.0,
    .eval_budget = 1.0, .w6_n = 128, .w13_n = 128,
    .w10_nn = 3, .w10_n = {64, 128, 256}, .w10_budget = 2.0,
    .w12_n = 256, .w12_t = 2.0,
    .w11_nn = 3, .w11_n = {32, 64, 128}, .w11_t = 2.0,
};

static const cl_bplan quick_plan = {
    .w1_cases = 1, .w1_n = {16}, .w1_t = {0.25}, .select = 0,
    .peer_budget = 60.0,
    .w2_n = 16, .w2_t = 0.5, .w2_large = false,
    .w3_nn = 2, .w3_n = {16, 32}, .w3_budget = 0.3,
    .eval_budget = 0.25, .w6_n = 32, .w13_n = 64,
    .w10_nn = 2, .w10_n = {16, 32}, .w10_budget = 0.3,
    .w12_n = 32, .w12_t = 0.1,
    .w11_nn = 1, .w11_n = {16}, .w11_t = 0.25,
};

/* Workload 12 (CPU minutes) runs only when named by --only. */
static bool selected(const cl_bctx *c, int w)
{
    return c->o->only ? (c->o->only >> w & 1u) != 0 : w != 12;
}

/* Rows by workload, keeping the order within each (insertion sort). */
static void sort_rows(cl_bench_table *t)
{
    for (size_t i = 1; i < t->n; i++) {
        cl_bench_row r = t->row[i];
        size_t j = i;
        for (; j > 0 && t->row[j - 1].workload > r.workload; j--)
            t->row[j] = t->row[j - 1];
        t->row[j] = r;
    }
}

/* Workloads by number (0: the choice of solver; 1 runs last, after the
 * peers). */
static void (*const work[CL_BENCH_WORKLOADS + 1])(cl_bctx *) = {
    cl_bench_choose, cl_bench_w1,  cl_bench_w2,  cl_bench_w3,  cl_bench_w4,
    cl_bench_w5,     cl_bench_w6,  cl_bench_w7,  cl_bench_w8,  cl_bench_w9,
    cl_bench_w10,    cl_bench_w11, cl_bench_w12, cl_bench_w13};

/* Workload w (0: the choice of solver) unless out of memory; false if a
 * signal interrupted it, and then its rows are dropped: the cases after
 * the signal failed or were cut short. */
static bool run_workload(cl_bctx *c, int w)
{
    size_t before = c->t->n;
    if (!c->nomem)
        work[w](c);
    if (!cl_stop_interrupted())
        return true;
    c->t->n = before;
    c->stopped_in = w;
    return false;
}

cl_status cl_bench_run(const cl_bench_opts *o, cl_bench_table *t,
                       cl_error *err)
{
    if (o->only >> (CL_BENCH_WORKLOADS + 1) || (o->only & 1u))
        return cl_error_set(err, CL_EINVAL, "workloads are 1..%d",
                            CL_BENCH_WORKLOADS);
    cl_bctx c = {.o = o, .t = t, .plan = o->quick ? quick_plan : full_plan,
                 .stopped_in = -1};
    if (selected(&c, 1))
        cl_bench_peers_start(&c);
    bool go = !(selected(&c, 1) || selected(&c, 2) || selected(&c, 6)) ||
              run_workload(&c, 0);
    for (int w = 2; w <= CL_BENCH_WORKLOADS && go; w++)
        go = !selected(&c, w) || run_workload(&c, w);
    if (go && selected(&c, 1))
        run_workload(&c, 1);
    cl_bench_peers_stop(&c);
    cl_bench_runs_free(&c);
    sort_rows(t);
    if (c.nomem)
        return cl_error_set(err, CL_ENOMEM, "out of memory (bench)");
    const char *sig = cl_stop_signal_name(cl_stop_requested());
    if (cl_stop_interrupted() && c.stopped_in < 0)
        return cl_error_set(err, CL_EINTR, "interrupted by %s after the last "
                            "workload", sig);
    if (cl_stop_interrupted())
        return cl_error_set(err, CL_EINTR, "interrupted by %s in workload "
                            "%d; the table holds the workloads finished "
                            "before it", sig, c.stopped_in);
    return CL_OK;
}

void cl_bench_table_free(cl_bench_table *t)
{
    free(t->row);
    *t = (cl_bench_table){0};
}

/* ---- CSV -------------------------------------------------------------- */

static void csv_number(FILE *fp, double v)
{
    if (isfinite(v))
        fprintf(fp, "%.6g", v);
}

static void csv_row(FILE *fp, const cl_bench_row *r)
{
    const double num[] = {r->cpu_a, r->cpu_b, r->wall_a, r->wall_b,
                          r->error_a, r->error_b, r->ratio};
    fprintf(fp, "%d,", r->workload);
    cl_csv_text(fp, r->kase);
    fputc(',', fp);
    cl_csv_text(fp, r->side_a);
    fputc(',', fp);
    cl_csv_text(fp, r->side_b);
    for (size_t k = 0; k < sizeof num / sizeof *num; k++) {
        fputc(',', fp);
        csv_number(fp, num[k]);
    }
    fprintf(fp, ",%s,%s,", r->unit, r->goal);
    csv_number(fp, r->target);
    fprintf(fp, ",%s,", r->met == 1 ? "yes" : r->met == 0 ? "no" : "");
    cl_csv_text(fp, r->note);
    fputc('\n', fp);
}

cl_status cl_bench_write_csv(const char *path, const cl_bench_table *t,
                             cl_error *err)
{
    cl_afile af;
    cl_status rc = cl_afile_open(&af, path, err);
    if (rc)
        return rc;
    fputs("workload,case,side_a,side_b,cpu_a,cpu_b,wall_a,wall_b,error_a,"
          "error_b,ratio,unit,goal,target,met,note\n", af.fp);
    for (size_t k = 0; k < t->n; k++)
        csv_row(af.fp, &t->row[k]);
    return cl_afile_commit(&af, err);
}

/* ---- text --------------------------------------------------------------- */

static const char *fmt_time(char *buf, size_t len, double s)
{
    static const char *const unit[] = {"s", "ms", "us", "ns"};
    int k = 0;
    if (!isfinite(s))
        return "-";
    for (; k < 3 && fabs(s) < 0.9995 && s != 0; k++)
        s *= 1e3;
    snprintf(buf, len, s >= 999.5 ? "%.0f %s" : "%.3g %s", s, unit[k]);
    return buf;
}

static const char *fmt_error(char *buf, size_t len, double e)
{
    if (!isfinite(e))
        return "-";
    snprintf(buf, len, "%.2e", e);
    return buf;
}

static const char *fmt_figure(char *buf, size_t len, const cl_bench_row *r)
{
    if (!isfinite(r->ratio))
        return "-";
    if (!strcmp(r->unit, "x"))
        snprintf(buf, len, "%.3gx", r->ratio);
    else if (!strcmp(r->unit, "exponent"))
        snprintf(buf, len, "p = %.2f", r->ratio);
    else
        snprintf(buf, len, "%.4g %s", r->ratio, r->unit);
    return buf;
}

static const char *fmt_goal(char *buf, size_t len, const cl_bench_row *r)
{
    if (!*r->goal)
        return "";
    const char *unit = !strcmp(r->unit, "x")   ? "x"
                       : !strcmp(r->unit, "%") ? " %"
                                               : "";
    snprintf(buf, len, "%s %g%s", r->goal, r->target, unit);
    return buf;
}

enum { NCOL = 11 };

/* The printed cells of a row. */
static void cells(const cl_bench_row *r, char buf[NCOL][64],
                  const char *cell[NCOL])
{
    snprintf(buf[0], 64, "%d", r->workload);
    cell[0] = buf[0];
    cell[1] = r->kase;
    cell[2] = r->side_a;
    cell[3] = *r->side_b ? r->side_b : "-";
    cell[4] = fmt_time(buf[4], 64, r->cpu_a);
    cell[5] = fmt_time(buf[5], 64, r->cpu_b);
    cell[6] = fmt_error(buf[6], 64, r->error_a);
    cell[7] = fmt_error(buf[7], 64, r->error_b);
    cell[8] = fmt_figure(buf[8], 64, r);
    cell[9] = fmt_goal(buf[9], 64, r);
    cell[10] = r->met == 1 ? "yes" : r->met == 0 ? "NO" : "";
}

static void print_line(FILE *fp, const char *const cell[NCOL],
                       const int width[NCOL])
{
    for (int k = 0; k < NCOL; k++)
        fprintf(fp, k < 4 ? "%-*s%s" : "%*s%s", width[k], cell[k],
                k + 1 < NCOL ? "  " : "\n");
}

void cl_bench_print(const cl_bench_table *t, FILE *fp)
{
    static const char *const head[NCOL] = {
        "W", "case", "side a", "side b", "cpu a", "cpu b", "error a",
        "error b", "figure", "goal", "met"};
    int width[NCOL];
    char buf[NCOL][64];
    const char *cell[NCOL];
    for (int k = 0; k < NCOL; k++)
        width[k] = (int)strlen(head[k]);
    for (size_t i = 0; i < t->n; i++) {
        cells(&t->row[i], buf, cell);
        for (int k = 0; k < NCOL; k++)
            if ((int)strlen(cell[k]) > width[k])
                width[k] = (int)strlen(cell[k]);
    }
    print_line(fp, head, width);
    for (size_t i = 0; i < t->n; i++) {
        cells(&t->row[i], buf, cell);
        print_line(fp, cell, width);
    }
    fprintf(fp, "notes:\n");
    for (size_t i = 0; i < t->n; i++)
        if (*t->row[i].note)
            fprintf(fp, "  [%d] %s, %s: %s\n", t->row[i].workload,
                    t->row[i].kase, t->row[i].side_a, t->row[i].note);
}
