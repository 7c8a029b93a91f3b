/* SPDX-License-Identifier: Apache-2.0 */
/* A multi-axis generator configuration for the tests: n_axes axes, the sync mode, no
 * vibration stages, and axis i's vmax, amax, jmax from limits(i, lim) (lim[0..2]). */
#ifndef SMS_TEST_MULTI_CONFIG_H
#define SMS_TEST_MULTI_CONFIG_H

#include <string.h>
#include "smoothshaper/multi_generator.h"

static sms_multi_generator_config multi_config(size_t n_axes, sms_sync sync,
                                               void (*limits)(size_t axis, double lim[3]))
{
    sms_multi_generator_config c;
    size_t i;
    memset(&c, 0, sizeof c);
    c.n_axes = n_axes;
    c.sync = sync;
    for (i = 0; i < n_axes; ++i) {
        double lim[3];
        limits(i, lim);
        c.vmax[i] = lim[0];
        c.amax[i] = lim[1];
        c.jmax[i] = lim[2];
    }
    return c;
}

#endif
