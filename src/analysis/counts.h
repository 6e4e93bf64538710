/* Connection counts of an n x n grid, measured from the built topology,
 * beside the seed's closed forms (seed 000 section 4.1; SPEC 2):
 *   Type1 2(n-1)(2n-1), Type2 4(n-1)(n-2), CK = 8n^2 - 18n + 10. */
#ifndef CL_COUNTS_H
#define CL_COUNTS_H

#include "core/error.h"

typedef struct {
    int n;
    long type1, type1_formula;
    long type2, type2_formula;
    long ck, ck_formula;   /* Type1 + Type2 */
} cl_counts;

cl_status cl_counts_measure(int n, cl_counts *c, cl_error *err);

#endif
