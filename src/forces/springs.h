/* Mass-spring cloth (docs/model.md 2, 3.4; Zischg, Chea and Aigner, and
 * the Verlet-and-PBD report): the spring network, the `springs` term and
 * the `spring-damping` term.
 *
 * The network is read from INI section [springs] by cl_springs_network, the
 * one place that decides which particle pairs are springs and how stiff
 * each is; the springs term, the spring-damping term (and later position
 * constraints or tearing) all take their pairs from it, so they always agree.
 *
 * Pair sets on a grid, grid offsets (di, dj), each unordered pair once:
 *   structural  (+-1, 0), (0, +-1)            count 2 n (n-1)
 *   shear       (+-1, +-1) (both diagonals)    count 2 (n-1)^2
 *   bend        (+-2, 0), (0, +-2)            count 2 n (n-2)
 *   level l     (+-l, 0), (0, +-l), (+-l, +-l) count 2 (n-l)(2n-l), l < n
 * (counts for n x n; on nu x nv, axis u gives (nu-o) nv pairs, axis v
 * nu (nv-o), each diagonal (nu-o)(nv-o), o the offset).
 *
 * On a mesh cloth (model/cloth.h) the network is that of Zischg, Chea and
 * Aigner's mesh cloth ("Cloth Simulation", the skirt): structural springs
 * (k_structural) on every triangle edge, bend springs (k_bend) between the
 * two far vertices of every pair of neighbouring triangles
 * (model/pairs.h cl_pairs_mesh_edges, cl_pairs_mesh_bend), no shear
 * springs.  `levels` and a non-zero k_shear are grid notions and are
 * refused there.
 *
 * The rule: `levels = 0` (default) uses the named sets structural + shear
 * + bend, each with its own stiffness; a set whose stiffness is 0 is left
 * out (k_shear = 0 gives Zischg, Chea and Aigner's structural + bend).
 * `levels = k >= 1` replaces the named sets by levels 1..k (the
 * Verlet-and-PBD report): level 1 = structural + shear, level 2 adds the
 * +-2 axis and +-2 diagonal pairs, and so on; it is an error to set k_shear
 * or k_bend together with levels >= 1.  Levels 1..k on n x n (k < n) count
 *     sum_l 2 (n-l)(2n-l) = 4 n^2 k - 3 n k (k+1) + k (k+1)(2k+1)/3;
 * levels >= max(nu, nv) add nothing.
 *
 * INI section [springs]:
 *   enabled          (false) switches the springs term on;
 *   k_structural     (N/m, default 200 = hang's ks);
 *   k_shear          (N/m, default k_structural; Zischg, Chea and Aigner
 *                    give no value: they use no shear springs on their
 *                    triangle grid, where the diagonal is a structural
 *                    edge.  Without shear a square grid has no in-plane
 *                    shear stiffness);
 *   k_bend           (N/m, default k_structural / 8: Zischg, Chea and
 *                    Aigner, sec. 3.1.1, "a ratio of 1 : 8 ... between the
 *                    bending- and structural springs");
 *   levels           (0 .. 1000, default 0, see above);
 *   level_stiffness  (same | inverse, only with levels >= 1): `same` gives
 *                    every level the stiffness k_structural, as the
 *                    Verlet-and-PBD report does (one K for every
 *                    constraint of every level, rest length l h);
 *                    `inverse` gives level l k_structural / l, the same
 *                    axial rigidity k L per unit rest length. */
#ifndef CL_SPRINGS_H
#define CL_SPRINGS_H

#include "core/decls.h"
#include "forces/term.h"
#include "model/pairs.h"

CL_BEGIN_DECLS

typedef struct {
    cl_pairset set; /* each unordered pair once, a < b */
    double *k;      /* stiffness of pair k (N/m), > 0 */
} cl_springnet;

/* The spring pairs and their stiffnesses from [springs] (marks the keys as
 * used); free with cl_springnet_free. */
cl_status cl_springs_network(cl_config *cfg, const cl_cloth *cloth,
                             cl_springnet *net, cl_error *err);
void cl_springnet_free(cl_springnet *net);

extern const cl_term_type cl_term_springs;
extern const cl_term_type cl_term_spring_damping;

CL_END_DECLS

#endif
