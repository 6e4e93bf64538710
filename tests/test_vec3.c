/* Tests for core/vec3.h: the component operations against values worked
 * by hand, in place as well (out aliasing an input). */
#include <criterion/criterion.h>

#include "core/vec3.h"

Test(vec3, sum_difference_and_scaled_sum)
{
    const double a[3] = {1.5, -2.0, 0.25}, b[3] = {0.5, 4.0, -1.0};
    double out[3];
    cl_v3_add(a, b, out);
    cr_assert(out[0] == 2.0 && out[1] == 2.0 && out[2] == -0.75);
    cl_v3_sub(a, b, out);
    cr_assert(out[0] == 1.0 && out[1] == -6.0 && out[2] == 1.25);
    cl_v3_axpy(a, 2.0, b, out);
    cr_assert(out[0] == 2.5 && out[1] == 6.0 && out[2] == -1.75);
    cl_v3_scale(-4.0, a, out);
    cr_assert(out[0] == -6.0 && out[1] == 8.0 && out[2] == -1.0);
}

Test(vec3, in_place)
{
    double a[3] = {1.0, 2.0, 3.0};
    const double b[3] = {0.5, 0.25, 0.125};
    cl_v3_add(a, b, a);
    cr_assert(a[0] == 1.5 && a[1] == 2.25 && a[2] == 3.125);
    cl_v3_sub(a, b, a);
    cr_assert(a[0] == 1.0 && a[1] == 2.0 && a[2] == 3.0);
    cl_v3_scale(0.5, a, a);
    cr_assert(a[0] == 0.5 && a[1] == 1.0 && a[2] == 1.5);
    cl_v3_sub(a, a, a);
    cr_assert(a[0] == 0.0 && a[1] == 0.0 && a[2] == 0.0);
}
