/* SPDX-License-Identifier: Apache-2.0 */
/* Internal: the time-optimal jerk-limited motion of one axis between arbitrary states
 * (p0, v0, a0) -> (pf, vf, af) within vmin <= v <= vmax, amin <= a <= amax, |j| <= jmax, and
 * the motion of a given duration; in sms_real without libm (the generator re-plans on its
 * per-sample path). The problem and its profile families are those of Berscheid and Kroeger,
 * "Jerk-limited real-time trajectory generation with arbitrary target states" (RSS 2021); the
 * derivation here is this file's own, docs/design.md ("Any state to any state") writes it out.
 *
 * Family s (s = +1, or -1 with every quantity mirrored): jerk +J until the acceleration
 * reaches x, a hold at x (only when x = the upper acceleration bound), jerk -J down to y (with
 * a cruise at a = 0 inserted where the velocity reaches the upper bound), a hold at y (only at
 * the lower bound), jerk +J up to af. The velocity where the middle ramp's acceleration is
 * zero, m, ties the two halves: m = c0 + x^2/J (+ x t2) = cf + y^2/J (+ |y| t6), with
 * c0 = v0 - a0^2/(2J) and cf = vf - af^2/(2J). Every time-optimal motion is a member of one
 * family (case NONE: no hold, no cruise; ACC0: hold at x; ACC1: hold at y; ACC0_ACC1: both;
 * VEL: the cruise), and so is the motion of a given duration that ends farthest in the
 * direction s (Pontryagin: the costate of the acceleration is a convex quadratic, so the jerk
 * switches + - + at most, with holds on the bounds). Hence:
 * - time-optimal (step 1): the shortest member that reaches pf, over every case's roots;
 * - duration T (step 2): the farthest members of both families P+(T) >= P-(T); every pf in
 *   between is reached in exactly T by the convex combination of their jerks (the limits are
 *   convex and the dynamics linear), and no pf outside is. */
#ifndef SMS_THIRD_ORDER_H
#define SMS_THIRD_ORDER_H

#include "smoothshaper/trajectory.h"

/* Bounds of one axis: vmin < 0 < vmax, amin < 0 < amax, jmax > 0 (finite). */
typedef struct sms_to_limits {
    sms_real vmax, vmin, amax, amin, jmax;
} sms_to_limits;

/* A motion from a start state: pieces of constant jerk j[i] for t[i] seconds, each starting
 * at the acceleration a[i] exactly (the rounding of a ramp is not carried into a long hold or
 * cruise); piece `cruise` (-1: none) runs at the velocity bound v_cruise exactly. */
#define SMS_TO_PIECES 7
typedef struct sms_to_profile {
    int count;
    sms_real j[SMS_TO_PIECES], t[SMS_TO_PIECES], a[SMS_TO_PIECES];
    int cruise;
    sms_real v_cruise;
    sms_real duration; /* sum of t */
} sms_to_profile;

/* Durations of every valid member that reaches the target, at most this many. */
#define SMS_TO_MAX_ROOTS 24

/* Time-optimal motion (p0, v0, a0) -> (pf, vf, af). Preconditions: both states within the
 * bounds, the start able to bring a to zero within the velocity bounds
 * (vmin <= v0 + a0|a0|/(2 jmax) <= vmax) and the target reachable (vmin <= vf - af|af|/(2 jmax)
 * <= vmax). Returns 1 and the shortest member in best, the durations of all valid members
 * found (ascending, at most SMS_TO_MAX_ROOTS) in roots and their count in n_roots (both may
 * be NULL); 0 when none is found (not expected within the preconditions; the caller falls
 * back). The pieces reproduce the target to the rounding of the positions. */
int sms_to_time_optimal(sms_real p0, sms_real v0, sms_real a0, sms_real pf, sms_real vf,
                        sms_real af, const sms_to_limits *lim, sms_to_profile *best,
                        sms_real *roots, int *n_roots);

/* The motion of duration T >= 0 that ends at (vf, af) farthest in the direction s (+1: the
 * largest end position, -1: the smallest). Returns 1 with the profile and its end position
 * p0 + displacement in *end; 0 when no member lasts T (T below the shortest change of
 * (v0, a0) to (vf, af), or the family has no member of that length). */
int sms_to_extremal(sms_real v0, sms_real a0, sms_real vf, sms_real af, const sms_to_limits *lim,
                    sms_real T, int s, sms_to_profile *out, sms_real *displacement);

/* Time-optimal change (v0, a0) -> (vf, af), position free (the velocity interface): jerk +-J,
 * a hold at the acceleration bound if reached, jerk -+J. Same preconditions on v and a.
 * Returns 1 and the profile; 0 when none is found. */
int sms_to_velocity(sms_real v0, sms_real a0, sms_real vf, sms_real af, const sms_to_limits *lim,
                    sms_to_profile *out);

/* (p, v, a) advanced by the profile's pieces (a set to each piece's start, v to the cruise). */
void sms_to_integrate(const sms_to_profile *prof, sms_real *p, sms_real *v, sms_real *a);

#endif
