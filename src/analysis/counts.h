/* Connection counts of an n x n grid, measured from the built topology,
 * beside the closed forms of Jiao, section 4.1 (docs/model.md 2):
 *   Choi-Ko: Type1 2(n-1)(2n-1), Type2 4(n-1)(n-2), CK = 8n^2 - 18n + 10.
 *   Baraff-Witkin, from the triangle mesh (model/mesh.h): triangles
 *   2(n-1)^2 (Jiao's T for stretch/shear), bending hinges = interior
 *   edges (n-1)(3n-5); Jiao's bending T = 2n(n-1) + (n-1)^2 counts all
 *   3n^2 - 4n + 1 edges, boundary included, and gives its
 *   BW = 2(n-1)^2 + 2n(n-1) + (n-1)^2 = 5n^2 - 8n + 3; with interior
 *   edges BW = 2(n-1)^2 + (n-1)(3n-5) = 5n^2 - 12n + 7. */
#ifndef CL_COUNTS_H
#define CL_COUNTS_H

#include "core/decls.h"
#include "core/error.h"

CL_BEGIN_DECLS

typedef struct {
    int n;
    long type1, type1_formula;
    long type2, type2_formula;
    long ck, ck_formula;   /* Type1 + Type2 */
    long bw_tri, bw_tri_formula;    /* triangles, 2(n-1)^2 */
    long bw_bend, bw_bend_formula;  /* interior edges, (n-1)(3n-5) */
    long bw_edges, bw_bend_seed;    /* all edges; Jiao 2n(n-1)+(n-1)^2 */
    long bw, bw_formula;            /* triangles + interior edges */
    long bw_seed;                   /* Jiao's BW = 5n^2 - 8n + 3 */
} cl_counts;

cl_status cl_counts_measure(int n, cl_counts *c, cl_error *err);

CL_END_DECLS

#endif
