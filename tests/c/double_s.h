/* SPDX-License-Identifier: Apache-2.0 */
/* Time-optimal rest-to-rest jerk-limited duration (Biagiotti & Melchiorri, Trajectory
 * Planning for Automatic Machines and Robots, 2008, sec. 3.4), written independently of the
 * library's design and generator; the kinematic and generator tests compare against it. */
#ifndef SMS_TEST_DOUBLE_S_H
#define SMS_TEST_DOUBLE_S_H
#include <math.h>

static double double_s_duration(double h, double v, double a, double j)
{
    double Tj, Ta, Tv;
    if (v * j >= a * a) {
        Tj = a / j;
        Ta = Tj + v / a;
    } else {
        Tj = sqrt(v / j);
        Ta = 2.0 * Tj;
    }
    Tv = h / v - Ta;
    if (Tv >= 0.0)
        return 2.0 * Ta + Tv;
    if (h >= 2.0 * a * a * a / (j * j)) {
        Tj = a / j;
        Ta = 0.5 * Tj + sqrt(0.25 * Tj * Tj + h / a);
        return 2.0 * Ta;
    }
    Tj = cbrt(h / (2.0 * j));
    return 4.0 * Tj;
}

#endif
