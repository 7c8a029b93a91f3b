/* SPDX-License-Identifier: Apache-2.0 */
/* Internal: the parts of the kinematic design (docs/design.md, docs/sampled-limits.md), all
 * design-time code (libm allowed, never on a per-sample path):
 *   kinematic.c             validation, the mode-tuned last stage, the public designs
 *   kinematic_continuous.c  the recursion's closed forms: the continuous lengths for n bounds
 *   kinematic_grid.c        whole-sample lengths that keep every bound at every sample
 *   kinematic_overlap.c     the exact search for chains whose copies overlap where they cancel
 */
#ifndef SMS_KINEMATIC_PARTS_H
#define SMS_KINEMATIC_PARTS_H

#include <math.h>
#include "trajectory/trajectory_internal.h"

#define KIN_PI 3.14159265358979323846

/* D(h) and lengths for the whole chain: in plain arithmetic when the problem is moderate,
 * else in logarithms (any accepted input, ratios up to 1e60, up to 8 stages). */
double sms_kin_solve_plan(const sms_kin_plan *p, double h, double *T);

/* Smallest whole number of samples N with N Ts >= T: round(nu) when nu passes the integer
 * test of docs/exact-mode.md, else ceil(nu); at least 1. */
static inline double sms_kin_grid_ceil(double nu)
{
    double r = floor(nu + 0.5);
    if (fabs(nu - r) <= 1e-9 * (nu > 1.0 ? nu : 1.0))
        return r < 1.0 ? 1.0 : r;
    return ceil(nu);
}

/* The taps of a bounded tuned stage as the exact top-level test reads them: tap0 on 0, gain q^i
 * on 1 .. L-2, tapL on L-1 (q = e^decay); `bounded` 0 when the stage is not of this form. */
typedef struct sms_kin_tuned {
    int bounded;
    double tap0, tapL, gain, decay, L;
} sms_kin_tuned;

/* The timing of a stage tuned to the mode on a grid (kinematic_grid.c). */
sms_timing sms_kin_tuned_timing(sms_kind kind);

/* Largest tap, length in samples and the sum of the first and last taps of the stage tuned to
 * the mode, and its form for the exact test (kinematic_grid.c). */
sms_status sms_kin_tuned_taps(sms_kind kind, double T, double sigma, unsigned k, double Ts,
                              double *peak, double *support, double *ends, sms_kin_tuned *form);

/* Whole-sample lengths N[0..n-1] for the continuous design T (kinematic_grid.c). */
sms_status sms_kin_on_grid(const sms_kin_plan *p, double h, const double *T, sms_kind last_kind,
                           int tuned, double supp_last, const sms_kin_tuned *form, double Ts,
                           double *N);

/* The overlap search: replaces N (and *best) when it finds a shorter feasible chain
 * (kinematic_overlap.c). */
void sms_kin_overlap_search(const sms_kin_plan *p, double logh, double logTs, const double *T,
                            double Ts, int harmonic, const sms_kin_tuned *tuned, double *best,
                            double *N);

#endif
