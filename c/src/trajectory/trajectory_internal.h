/* SPDX-License-Identifier: Apache-2.0 */
/* Internal: the kinematic design shared by kinematic.c and generator.c; the report of a
 * refused limit set shared by the single- and the multi-axis generator's reach checks. */
#ifndef SMS_TRAJECTORY_INTERNAL_H
#define SMS_TRAJECTORY_INTERNAL_H

#include "smoothshaper/trajectory.h"

/* The problem being solved: n bounds, and how the last stage's length follows from its level. */
typedef struct sms_kin_plan {
    size_t n;
    double L[SMS_KINEMATIC_MAX_ORDER];
    int fixed;        /* 1: last stage has the fixed length T_fixed (tuned to a mode) */
    double c_last;    /* free last stage: T = c_last * X / L[n-1] (1 rectangular, pi/2 harmonic) */
    double T_fixed;   /* fixed last stage: its length ... */
    double rho_fixed; /* ... and its peak density (bounds q^(n) <= level * rho) */
} sms_kin_plan;

/* Family of the designed last stage. */
typedef struct sms_kin_last {
    sms_kind kind;
    double sigma;
    unsigned k;
    sms_timing timing; /* bounded for a mode-tuned rectangular/exponential stage on a grid */
} sms_kin_last;

/* Validate and design: T[0..n-1] (continuous lengths) and the last stage's family. */
sms_status sms_kin_solve(double h, const double *limits, size_t n, sms_profile profile,
                         double wn, double zeta, double *T, sms_kin_last *last);
/* As sms_kin_solve(), on the grid of Ts when Ts > 0 (sms_kinematic_design()). */
sms_status sms_kin_solve_sampled(double h, const double *limits, size_t n, sms_profile profile,
                                 double wn, double zeta, double Ts, double *T, sms_kin_last *last);
/* Peak of the normalised impulse response of a rectangular, harmonic or exponential stage. */
double sms_kin_peak_density(sms_kind kind, double T, double sigma);

/* Record in r the first quantity out of range (sms_generator_reach_info: quantity, the
 * arguments it is formed from, its value and the bound it broke); returns SMS_ERR_LIMIT. */
sms_status sms_reach_refused(sms_generator_reach_info *r, const char *quantity,
                             const char *arguments, double value, double bound);

#endif
