/* Tests for contact/segment: a segment against a box (entry, start
 * inside, parallel to a face, miss, beyond its end) at known answers. */
#include <criterion/criterion.h>

#include "contact/segment.h"

TestSuite(segment);

static const double lo[3] = {-1, -2, -3}, hi[3] = {1, 2, 3};

Test(segment, box_entry_and_misses)
{
    double s;
    /* from x = -5 along +x at speed 2: enters x = -1 at s = 2 */
    cr_assert(cl_segment_box(lo, hi, (double[]){-5, 0, 0},
                             (double[]){2, 0, 0}, 10, &s));
    cr_assert_float_eq(s, 2.0, 1e-15);
    /* beyond the end of the segment */
    cr_assert_not(cl_segment_box(lo, hi, (double[]){-5, 0, 0},
                                 (double[]){2, 0, 0}, 1.5, &s));
    /* starting inside: s = 0 */
    cr_assert(cl_segment_box(lo, hi, (double[]){0.5, 1, 2},
                             (double[]){1, 1, 1}, 1, &s));
    cr_assert_eq(s, 0.0);
    /* parallel to the faces x = +-1 outside them: never */
    cr_assert_not(cl_segment_box(lo, hi, (double[]){1.5, -5, 0},
                                 (double[]){0, 1, 0}, 100, &s));
    /* diagonal: the last slab entered decides (z = -3 at s = 3) */
    cr_assert(cl_segment_box(lo, hi, (double[]){-2, -3, -6},
                             (double[]){1, 1, 1}, 10, &s));
    cr_assert_float_eq(s, 3.0, 1e-15);
    /* passing beside a corner: x enters at 2 after y left at 1 */
    cr_assert_not(cl_segment_box(lo, hi, (double[]){-3, 1, 0},
                                 (double[]){1, 1, 0}, 10, &s));
}
