/* SPDX-License-Identifier: Apache-2.0 */
/* Internal: the time-optimal jerk-limited single-axis plan from a state (q, v, a) to a target
 * at rest, evaluated exactly at sample instants. In ::sms_real, no libm: the online generator
 * re-plans on its per-sample path, and a float build must not pull in double arithmetic.
 * Other generators (multi-axis, FMUs) may reuse it; the interface below is kept stable. */
#ifndef SMS_PLAN_H
#define SMS_PLAN_H

#include "smoothshaper/trajectory.h"

/* Time-optimal plan from (q, v, a) to goal at rest, starting on a sample instant.
 * Precondition (what any plan's own state satisfies): |v| <= vmax, |a| <= amax and
 * |v + a|a|/(2 jmax)| <= vmax (the velocity after bringing a to 0 as fast as possible).
 * Structure: a velocity change (v, a) -> (vp, 0) (jerk +-jmax, hold +-amax if reached,
 * jerk -+jmax), a cruise at vp, and the stop (vp, 0) -> (0, 0) anchored on the goal. vp is
 * +-vmax when the distance allows (the cruise covers the rest), else it solves "distance of
 * the two changes = goal - q" by bisection in sms_real, taking the neighbour that leaves a
 * distance to cover at vp (a cruise of a rounding's length), so the parts meet to the
 * rounding of the positions; a target at the direct stop to rounding takes vp = `after`
 * and no cruise (the parts then meet to 8 eps of |q| + |goal| + the distance).
 * Returns 1 when planned; 0 when the plan cannot be represented in sms_real (a value it
 * would evaluate not finite, e.g. amax/jmax or the distance overflowing, or more than 2^52
 * samples long, e.g. 1e300 at vmax 1, or its parts not meeting where the distances
 * underflow); plan is then untouched. */
int sms_plan_to_rest(sms_plan *plan, const sms_plan_limits *lim, sms_real Ts, sms_real q,
                     sms_real v, sms_real a, sms_real goal);

/* Shapes of the acceleration transitions: linear ramps (constant jerk +-jmax) or half-cosine
 * ones (jerk jmax sin(pi t/d), continuous, zero at both ends: the trigonometric profile). */
#define SMS_PLAN_RAMP 0
#define SMS_PLAN_COSINE 1

/* As sms_plan_to_rest() with transitions of the given shape. A half-cosine transition of
 * duration d and peak jerk jmax changes a by (2/pi) jmax d and v by d times the mean of its
 * end accelerations, exactly as a linear ramp at the mean jerk (2/pi) jmax: the plan's
 * durations are those of the ramp plan at that jerk (rest to rest: ruckig's duration with
 * jmax 2/pi, which is the trigonometric kinematic design's), only the positions differ
 * (a whole transition moves q by (1/4 - 1/pi^2) instead of 1/6 times j d^3). The brake
 * precondition uses the mean jerk. Plan segments store the mean jerk in j[]. Returns as
 * sms_plan_to_rest(). */
int sms_plan_to_rest_shaped(sms_plan *plan, const sms_plan_limits *lim, int shape, sms_real Ts,
                            sms_real q, sms_real v, sms_real a, sms_real goal);

/* The change of (v, a) to (velocity, 0) from position q in the least time of the shape's
 * transitions (the velocity interface): a transition of a towards +-amax, a hold there if
 * reached, a transition back to 0 (half cosines never take a across zero, as above); then the
 * plan moves on at `velocity` (its drift). Same precondition on (v, a); returns as
 * sms_plan_to_rest(). */
int sms_plan_velocity_shaped(sms_plan *plan, const sms_plan_limits *lim, int shape, sms_real Ts,
                             sms_real q, sms_real v, sms_real a, sms_real velocity);

/* The jerk the planner uses for a shape: jmax (ramps) or (2/pi) jmax (half-cosine). */
sms_real sms_plan_mean_jerk(const sms_plan_limits *lim, int shape);

/* q, v, a, j at sample k after the plan's first sample (jerk: right limit at a jump; a
 * half-cosine transition is evaluated by its own series, no libm). From the end on: q = goal +
 * drift t (t since the end), v = drift, a = j = 0. */
void sms_plan_eval(const sms_plan *plan, sms_real Ts, size_t k, sms_real out[4]);

/* The first sample k at which sms_plan_eval() gives the rest on the goal (q = goal, v = a =
 * j = 0 exactly), as every later one does. */
size_t sms_plan_rest_sample(const sms_plan *plan, sms_real Ts);

/* The first sample at or after the plan's arrival at its target state, by the rule
 * sms_plan_eval() applies to every breakpoint (within the grid tolerance of a sample: on it). */
size_t sms_plan_arrival_sample(const sms_plan *plan, sms_real Ts);

/* The least and the largest position of a plan of linear ramps (shape SMS_PLAN_RAMP) over
 * its whole time, the rest on the goal after it included: each segment's ends and the
 * instants inside it where its velocity (a quadratic) is zero. Returns 0 (lo, hi untouched)
 * for a plan that drifts on (drift != 0: no bound) or of the half-cosine shape. */
int sms_plan_extent(const sms_plan *plan, sms_real *lo, sms_real *hi);

/* sqrt(x) for x >= 0 in sms_real without libm (Newton after scaling by powers of 4). */
sms_real sms_plan_sqrt(sms_real x);

/* Add a segment (start state p, v, a, jerk j, d seconds) at time (n, f) and move (n, f) to its
 * end (whole samples plus a fraction in [0, Ts)); a segment of d <= 0 is skipped. */
void sms_plan_push(sms_plan *plan, sms_real Ts, size_t *n, sms_real *f, sms_real p, sms_real v,
                   sms_real a, sms_real j, sms_real d);

/* Can every value the plan evaluates be formed? Each segment's start values and the bound
 * |p| + d (|v| + d (|a|/2 + d |j|/4)) of every term sms_plan_eval() forms within it (the
 * half-cosine position term is at most |j| d^3/4, the ramp's |j| d^3/6) are finite. */
int sms_plan_finite(const sms_plan *plan);

/* A plan longer than this many samples is not formed: its sample counts must stay exact in
 * size_t and in the double of a saved state (2^52: about 1.4e5 years at 1 ms). */
sms_real sms_plan_max_samples(void);

#endif
