/* SPDX-License-Identifier: Apache-2.0 */
/* Many kinematic designs in one call: a loop over sms_kinematic_design(), so each problem's
 * lengths are the ones the single design gives, and a caller from an interpreted language
 * pays the call overhead once instead of per problem. */
#include "smoothshaper/trajectory.h"

sms_status sms_kinematic_design_batch(size_t m, const double *h, size_t h_stride,
                                      const double *limits, size_t limits_stride, size_t n,
                                      sms_profile profile, double wn, double zeta, double Ts,
                                      double *T, size_t capacity, size_t *index)
{
    size_t i, count;
    if (T == NULL || index == NULL || (m > 0 && (h == NULL || limits == NULL)))
        return SMS_ERR_NULL;
    *index = m;
    if (n < 1 || n > SMS_KINEMATIC_MAX_ORDER)
        return SMS_ERR_ORDER;
    if (m > capacity / n)
        return SMS_ERR_BUFFER_TOO_SMALL;
    for (i = 0; i < m; ++i) {
        const sms_status st = sms_kinematic_design(h[i * h_stride], limits + i * limits_stride,
                                                   n, profile, wn, zeta, Ts, T + i * n, n,
                                                   &count);
        if (st != SMS_OK) {
            *index = i;
            return st;
        }
    }
    return SMS_OK;
}
