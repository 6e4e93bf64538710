/* A unit cube centred at the origin as OBJ text (8 vertices, 6 quads,
 * counter-clockwise seen from outside), for the tests of the OBJ reader
 * and of the mesh shape.  Header only. */
#ifndef CL_TESTS_CUBE_OBJ_H
#define CL_TESTS_CUBE_OBJ_H

static const char cube_obj[] =
    "# unit cube\n"
    "v -0.5 -0.5 -0.5\nv 0.5 -0.5 -0.5\nv 0.5 0.5 -0.5\nv -0.5 0.5 -0.5\n"
    "v -0.5 -0.5 0.5\nv 0.5 -0.5 0.5\nv 0.5 0.5 0.5\nv -0.5 0.5 0.5\n"
    "f 1 4 3 2\n"  /* z = -0.5 */
    "f 5 6 7 8\n"  /* z = +0.5 */
    "f 1 2 6 5\n"  /* y = -0.5 */
    "f 4 8 7 3\n"  /* y = +0.5 */
    "f 1 5 8 4\n"  /* x = -0.5 */
    "f 2 3 7 6\n"; /* x = +0.5 */

#endif
