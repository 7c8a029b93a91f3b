/* SPDX-License-Identifier: Apache-2.0 */
/* The firmware filter of axis_filter.c run on a host (ctest, both precisions): a unit step,
 * printed as the README's C example prints it; the two must agree, and the step must rest on
 * 1 exactly. */
#include <stdio.h>
#include "axis_filter.h"

int main(void)
{
    sms_real y = 0;
    int n;
    if (axis_filter_init() != 0) {
        fprintf(stderr, "axis_filter_init failed\n");
        return 1;
    }
    for (n = 0; n < 140; n++) {
        y = axis_filter_sample((sms_real)1);
        if (n % 20 == 0 || n == 139)
            printf("y[%3d] = %.6f\n", n, (double)y);
    }
    printf("at rest on 1 exactly: %s\n", y == (sms_real)1 ? "yes" : "no");
    return 0;
}
