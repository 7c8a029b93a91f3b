/* SPDX-License-Identifier: Apache-2.0 */
/**
 * @file trajectory.h
 * @brief Kinematic design (limits, optionally mixed with a mode), the online multi-point
 * generator and B-spline interpolating filters (docs/design.md, docs/filters.md).
 *
 * Design quantities are `double`; the signal path uses ::sms_real. Nothing allocates.
 */
#ifndef SMOOTHSHAPER_TRAJECTORY_H
#define SMOOTHSHAPER_TRAJECTORY_H

#include "smoothshaper/chain.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ------------------------------------------------------------------------------------------ */
/* Kinematic design                                                                            */
/* ------------------------------------------------------------------------------------------ */

/** @brief Family of the last stage of a kinematic chain (values stable: FMU enumeration). */
typedef enum sms_profile {
    SMS_PROFILE_POLYNOMIAL = 0,    /**< all stages rectangular: trapezoid, double-S, ... */
    SMS_PROFILE_TRIGONOMETRIC = 1, /**< last stage harmonic: modified trapezoid / double-S (seed 000 eq. 6) */
    SMS_PROFILE_DAMPED = 2         /**< last stage exponential tuned to a damped mode (Béarée 2014) */
} sms_profile;

/** @brief Most bounds (derivative orders) accepted by the kinematic design. */
#define SMS_KINEMATIC_MAX_ORDER 8

/** @brief Largest mode multiple k the design tries for a mode-tuned last stage. */
#define SMS_KINEMATIC_MAX_MULTIPLE 10000u

/**
 * @brief Time-optimal rest-to-rest chain for a displacement h and bounds on n derivatives,
 * continuous (Ts = 0) or realised on the sample grid of Ts (Ts > 0).
 *
 * limits[i] bounds |q^(i+1)|: limits[0] = vmax, limits[1] = amax, limits[2] = jmax, ...
 * The result has exactly n stages, stage i of length T[i] [s]; the trajectory (a step of h
 * through the chain) lasts T[0] + ... + T[n-1] and satisfies every bound.
 *
 * Stage families: stages 0..n-2 are rectangular. The last stage is
 * - ::SMS_PROFILE_POLYNOMIAL: rectangular, T = q^(n-1)/q^(n) of the effective bounds;
 * - ::SMS_PROFILE_TRIGONOMETRIC: harmonic, T = (pi/2) q^(n-1)/q^(n) (n = 1: T = pi |h| / (2 vmax));
 * - with a mode (wn > 0): tuned to it, T = k Tm, Tm = 2 pi/wd (rectangular; exponential with
 *   sigma = -zeta wn for ::SMS_PROFILE_DAMPED) or Tm = 3 pi/wd with k odd (harmonic), and the
 *   multiple k >= 1 that gives the shortest trajectory within every bound is chosen.
 *   ::SMS_PROFILE_DAMPED requires wn > 0 and n >= 2.
 *   Seed 001 sec. 5.2 (T1 = h/v, T2 = v/a, T3 = 2 pi/wn) is limits {v, a, j} with any
 *   j >= a wn / (2 pi).
 *
 * Unreachable bounds (short moves, T2 < T3, ...): the design works from the last stage up.
 * A chain with T[k] >= T[k+1] + ... + T[n-1] for every k has peak |q^(i)| equal to
 * |h| g / (T[0] ... T[i-1]) (g = 1, or the peak density times T of a non-rectangular last
 * stage), so each bound is met with equality where reachable. Where the inequality would fail,
 * the bound of that derivative is lowered to the value at which it holds with equality (the
 * time-scaling argument D(lambda h) <= lambda D(h) shows the duration then decreases
 * monotonically towards that point, so this is the shortest chain of this structure). For
 * n <= 3 (polynomial) this is the time-optimal bounded-jerk trajectory (ruckig's duration,
 * e.g. h = 40, v = 250, a = 5000, j = 200000 gives 0.16 + 0.05 + 0.025 = 0.235 s); for n >= 4
 * it is the shortest chain of this structure, which need not be the unconstrained optimum.
 * Cost: O(n^2) closed-form steps for any input (no nested iteration); with a mode, one such
 * solve per multiple k tried, at most ::SMS_KINEMATIC_MAX_MULTIPLE (a rectangular tuned
 * stage skips the multiples whose chain must last k Tm + |h|/vmax or more, longer than the
 * best found; measured up to about 27 ms for eight bounds, 0.5 ms for three); with Ts > 0
 * the grid search below adds a bounded number of chain tests (median CPU time from about
 * 0.1 us for one bound to 48 us for eight, largest about 0.6 ms; docs/sampled-limits.md).
 *
 * On a sample grid (Ts > 0; docs/sampled-limits.md): every stage except a mode-tuned last one
 * lasts a whole number of samples N[k] Ts, the lengths chosen together. First rule: N[k] >=
 * N[k+1] + ... + N[n-1] (samples of the stages after it; a tuned stage counts its L taps,
 * less one when its first and last tap together stay within the top bound: copies then meet
 * only in those), each level within its bound; a harmonic last stage takes the next odd
 * N when the largest sampled tap would exceed (pi/2)/(T/Ts). A tuned last stage keeps its
 * exact length (its zero stays on the mode): rectangular and exponential with
 * ::SMS_TIMING_BOUNDED (L = floor(T/Ts) + 2 taps, none above the continuous peak density
 * times Ts, so the continuous design's density holds), the half sine with exact timing
 * (L = floor(T/Ts) + 1), the design bounding the top derivative with its largest sampled
 * tap / Ts when that exceeds the continuous peak density: both are satisfied. The search:
 * each stage's ceiling +-1 (3^m chains); when that leaves more than one sample per stage over
 * the continuous optimum, a chain without a tuned stage gets
 * a depth-first search (at most 4 * 2^n level tests of O(2^i) each per pair of first two
 * lengths) with an exact bound on the sampled differences, h max|c_A| / (Ts^i prod_A N) with
 * A the i largest boxes and c_A the running count of their signed subset sums, which lets
 * copies of stages overlap where they cancel; a harmonic last stage enters only the top
 * difference, which the search evaluates exactly (one phasor sweep over the copies' ends);
 * still over, +1 .. -2 from the ceilings with each stage lifted to the samples after it (4^m
 * chains), and the depth-first search again when those found a shorter chain. A bounded
 * tuned stage's boxes get the same depth-first search whenever they are over the continuous
 * lengths at all, its top difference evaluated exactly (one sweep over where the copies
 * start, enter and leave their geometric run, and end). O(1) for any input: at most three
 * searches of at most 49 * 4 * 2^n level tests, and 4^m chains.
 * Then every backward difference of the sampled output (chain fed with a step of h at a
 * sample) obeys the bounds: |D^i q[m]| / Ts^i <= limits[i-1] for i = 1..n (to rounding).
 * Price: at most one sample per stage over the continuous optimum for every n (measured over
 * 1e5 random designs per n and an adversarial search; the search is bounded, so this is not
 * a proof); a harmonic last stage one sample more when a continuous stage is shorter than a
 * sample (a sampled half sine starts with a zero tap: docs/sampled-limits.md proves that
 * floor). A grid chain may also be shorter than the continuous optimum: the bounds are on
 * sampled differences.
 *
 * @param h         displacement, finite and != 0 (the sign is irrelevant to the lengths)
 * @param limits    n bounds, each finite and > 0
 * @param n         1 .. ::SMS_KINEMATIC_MAX_ORDER
 * @param profile   an ::sms_profile
 * @param wn        0: no mode; else the mode's natural frequency, finite and > 0 [rad/s]
 * @param zeta      damping ratio of the mode, [0, 1) (ignored when wn == 0)
 * @param Ts        0: continuous lengths; else the sample period [s], finite and > 0
 * @param T         receives n lengths [s]
 * @param capacity  length of T (>= n)
 * @param count     receives n
 * @return ::SMS_OK, ::SMS_ERR_NULL, ::SMS_ERR_ORDER (n out of range, or DAMPED with n < 2),
 *         ::SMS_ERR_LIMIT (h or a limit not finite/positive, or a ratio |h|/vmax,
 *         vmax/amax, amax/jmax, ..., 1/wn below 1e-60: a stage would be shorter than any
 *         usable duration), ::SMS_ERR_TOO_LONG (such a ratio above 1e60, more than 2^52
 *         samples in all, a length beyond double (e.g. whole samples of a Ts near DBL_MAX),
 *         or no multiple k <= ::SMS_KINEMATIC_MAX_MULTIPLE meets the bounds),
 *         ::SMS_ERR_KIND (profile), ::SMS_ERR_WN (wn < 0, NaN/Inf, or 0 with DAMPED),
 *         ::SMS_ERR_ZETA, ::SMS_ERR_SAMPLE_PERIOD (Ts < 0 or not finite),
 *         ::SMS_ERR_ABOVE_NYQUIST (tuned stage on a grid too coarse to place its zero),
 *         ::SMS_ERR_BUFFER_TOO_SMALL (capacity < n). Every check is O(1) before any
 *         iteration; outputs untouched on error.
 */
SMS_API sms_status sms_kinematic_design(double h, const double *limits, size_t n,
                                        sms_profile profile, double wn, double zeta, double Ts,
                                        double *T, size_t capacity, size_t *count);

/**
 * @brief As sms_kinematic_design() on the grid of Ts (> 0), but fills ready-to-use stage
 * configs (kind, T, sigma, and k = the mode multiple for a tuned stage, else 1; timing
 * ::SMS_TIMING_EXACT, which for the lengths on the grid is the plain integer-N filter, and
 * ::SMS_TIMING_BOUNDED for a tuned rectangular or exponential stage), so that
 * sms_chain_init() with the same Ts builds the chain directly and its sampled output keeps
 * every bound. Same arguments and statuses; Ts = 0 gives ::SMS_ERR_SAMPLE_PERIOD (a chain
 * always runs at a sample period).
 * @param h         displacement, finite and != 0
 * @param limits    n bounds, each finite and > 0
 * @param n         1 .. ::SMS_KINEMATIC_MAX_ORDER
 * @param profile   an ::sms_profile
 * @param wn        0: no mode; else the mode's natural frequency, finite and > 0 [rad/s]
 * @param zeta      damping ratio of the mode, [0, 1) (ignored when wn == 0)
 * @param Ts        the sample period [s], finite and > 0
 * @param configs   receives n stage configs
 * @param capacity  length of configs (>= n)
 * @param count     receives n
 * @return as sms_kinematic_design(); ::SMS_ERR_SAMPLE_PERIOD also for Ts = 0
 */
SMS_API sms_status sms_kinematic_configs(double h, const double *limits, size_t n,
                                         sms_profile profile, double wn, double zeta, double Ts,
                                         sms_stage_config *configs, size_t capacity,
                                         size_t *count);

/**
 * @brief sms_kinematic_design() for m problems in one call (design loops, sweeps over h or
 * the bounds), each design exactly as sms_kinematic_design() gives it alone (the same
 * arithmetic: bit for bit).
 *
 * Problem i has displacement h[i * h_stride] and the n bounds
 * limits[i * limits_stride] .. limits[i * limits_stride + n - 1]; a stride of 0 shares one
 * value (h) or one row of bounds among all problems, h_stride = 1 and limits_stride = n read
 * one per problem. profile, wn, zeta and Ts are shared. Problem i's n lengths go to
 * T[i * n] .. T[i * n + n - 1].
 *
 * @param m              number of problems (0: nothing to do)
 * @param h              displacements, each finite and != 0 (NULL allowed when m == 0)
 * @param h_stride       0 or any step between successive problems' h
 * @param limits         rows of n bounds, each finite and > 0 (NULL allowed when m == 0)
 * @param limits_stride  0 or any step between successive problems' rows
 * @param n              bounds per problem, 1 .. ::SMS_KINEMATIC_MAX_ORDER
 * @param profile, wn, zeta, Ts  as for sms_kinematic_design(), shared by every problem
 * @param T              receives m * n lengths [s]
 * @param capacity       length of T (>= m * n)
 * @param index          receives the index of the problem whose status is returned when a
 *                       problem is refused, else m
 * @return ::SMS_OK; ::SMS_ERR_NULL (T or index NULL, or h or limits NULL with m > 0),
 *         ::SMS_ERR_ORDER (n out of range), ::SMS_ERR_BUFFER_TOO_SMALL (capacity < m * n):
 *         checked first, T untouched (*index = m unless index is NULL); else the status of the first
 *         problem sms_kinematic_design() refuses (its index in *index; the rows before it
 *         hold their designs, the rest of T is untouched). Cost: m designs, each O(n^2)
 *         closed-form steps (with Ts, the grid search of sms_kinematic_design()).
 */
SMS_API sms_status sms_kinematic_design_batch(size_t m, const double *h, size_t h_stride,
                                              const double *limits, size_t limits_stride,
                                              size_t n, sms_profile profile, double wn,
                                              double zeta, double Ts, double *T,
                                              size_t capacity, size_t *index);

/* ------------------------------------------------------------------------------------------ */
/* Online multi-point generator                                                                */
/* ------------------------------------------------------------------------------------------ */

/** @brief Most segments of a plan: a motion to a moving target on the sample grid is the
 * convex combination of two motions of up to 7 pieces each (13 segments on the union of
 * their breakpoints), then the acceleration's return to zero after the target (1); a plan to
 * rest has at most 8 (a velocity change of 3, or 4 when a half-cosine plan first brings an
 * opposite acceleration to zero, a cruise, the stop). With position limits (qmin, qmax of
 * ::sms_generator_config) a plan may first brake to rest (3 segments) and wait there for the
 * next sample (1) before its move: 4 more. */
#define SMS_PLAN_MAX_SEGMENTS 20

/** @brief Bounds of a time-optimal plan: |v| <= vmax, |a| <= amax, |j| <= jmax (finite, > 0). */
typedef struct sms_plan_limits {
    sms_real vmax;   /**< velocity bound */
    sms_real amax;   /**< acceleration bound */
    sms_real jmax;   /**< jerk bound */
} sms_plan_limits;

/** @brief The generator's running time-optimal plan (read-only; built by the generator).
 * Segment i starts n[i] samples plus f[i] (in [0, Ts)) seconds after the plan's first
 * sample, in state (p, v, a), and applies jerk j for d seconds (shape 1: j is the mean jerk
 * of a half-cosine transition of a, whose peak jerk is (pi/2) j). From `end` samples + `end_f`
 * on the output is exactly at `goal` and moves on at `drift` (0: at rest on it): q = goal +
 * drift t, t the time since the end. The target state is reached at `arrive` samples +
 * `arrive_f` (the end, or the start of the acceleration's return to zero after a target
 * with an acceleration). Times split into whole samples and a fraction keep a float build
 * exact over any number of samples (a float time in seconds would not). */
typedef struct sms_plan {
    size_t count;                      /**< segments in use (0: at rest at goal) */
    int shape;                         /**< 0: linear ramps of a; 1: half-cosine transitions */
    size_t end;                        /**< whole samples to the end (what every sample after
                                            the plan reads first) */
    sms_real end_f;                    /**< and the fraction of a sample [s], in [0, Ts) */
    sms_real goal;                     /**< position the plan ends on */
    sms_real drift;                    /**< velocity after the end (0: at rest on goal) */
    size_t arrive;                     /**< whole samples to the target state */
    sms_real arrive_f;                 /**< and the fraction [s], in [0, Ts) */
    sms_real duration;                 /**< sum of d [s] (continuous, before the grid) */
    size_t n[SMS_PLAN_MAX_SEGMENTS];   /**< segment starts: whole samples */
    sms_real f[SMS_PLAN_MAX_SEGMENTS]; /**< segment starts: fraction [s], in [0, Ts) */
    sms_real p[SMS_PLAN_MAX_SEGMENTS]; /**< position at each segment's start */
    sms_real v[SMS_PLAN_MAX_SEGMENTS]; /**< velocity at each segment's start */
    sms_real a[SMS_PLAN_MAX_SEGMENTS]; /**< acceleration at each segment's start */
    sms_real j[SMS_PLAN_MAX_SEGMENTS]; /**< jerk of each segment (mean jerk for shape 1) */
    sms_real d[SMS_PLAN_MAX_SEGMENTS]; /**< duration of each segment [s] */
} sms_plan;

/** @brief What a target asks for (values stable: FMU enumeration and saved states). */
typedef enum sms_interface {
    SMS_INTERFACE_POSITION = 0, /**< arrive at `position` with `velocity` and `acceleration` */
    SMS_INTERFACE_VELOCITY = 1, /**< reach `velocity` with `acceleration` (position free) */
    SMS_INTERFACE_STOP = 2      /**< brake to rest at once (velocity 0, acceleration 0) */
} sms_interface;

/**
 * @brief A target of the online generator (sms_generator_step_target()).
 *
 * | field        | valid range (sms_generator_check_target()) |
 * |--------------|--------------------------------------------|
 * | interface    | an ::sms_interface |
 * | position     | finite (position interface; ignored otherwise); within [qmin, qmax] with position limits (else ::SMS_ERR_POSITION_LIMIT) |
 * | velocity     | finite, \|v\| <= vmax (ignored for stop); vmin <= v <= vmax with asymmetric limits; 0 with position limits |
 * | acceleration | finite, \|a\| <= amax, and v - a\|a\|/(2 jmax), v + a\|a\|/(2 jmax) within \|.\| <= vmax (ignored for stop); with asymmetric limits amin <= a <= amax and both within [vmin, vmax]; 0 with position limits |
 * | minimum_duration | finite, >= 0 [s], below 2^50 samples of Ts; 0 with the trigonometric profile (ignored for stop) |
 *
 * The acceleration row keeps the velocity within its bound on the way in (where the
 * acceleration was last zero on the fastest approach) and after the target (where it returns
 * to zero). The trigonometric profile plans position targets at rest and velocity targets
 * with acceleration 0 only.
 *
 * `minimum_duration` (ruckig's minimum_duration; 0: none) stretches the move: the target
 * state is reached exactly on the first sample N after the re-plan with N Ts >= both the
 * time-optimal duration and minimum_duration (within 8 ulps of a sample: on it) at which a
 * motion of N Ts within the limits exists (a blocked duration is skipped to the next that
 * has one). Such a motion is the convex combination of the two that end farthest either way
 * (docs/design.md, "A minimum duration"); for the velocity interface, their midpoint. A start
 * whose acceleration returns to zero on the velocity bound to 16 u of the velocity scale (the
 * ramp into a cruise, the cruise) counts as on it, so a minimum given there stretches the move. Like
 * every field it is part of the target: the move is stretched from the sample the target
 * (with it) was given on. Last in the struct so that initialisers of the other four stay
 * valid ({q, v, a, interface} leaves it 0).
 */
typedef struct sms_target {
    sms_real position;         /**< position interface: where to arrive */
    sms_real velocity;         /**< velocity at the target */
    sms_real acceleration;     /**< acceleration at the target */
    int interface;             /**< an ::sms_interface */
    sms_real minimum_duration; /**< [s], 0: as fast as the limits allow */
} sms_target;

/**
 * @brief Limits and optional mode of the online generator (docs/design.md).
 *
 * | field   | valid range |
 * |---------|-------------|
 * | vmax, amax, jmax | finite, > 0, and a plan can reach vmax (sms_generator_reach()) |
 * | profile | an ::sms_profile (::SMS_PROFILE_DAMPED needs wn > 0) |
 * | wn      | 0 (no mode) or finite > 0 and below pi/Ts [rad/s] |
 * | zeta    | [0, 1) |
 * | vmin    | 0 (symmetric: -vmax) or finite < 0, and a plan can reach it (sms_generator_reach()) |
 * | amin    | 0 (symmetric: -amax) or finite < 0 |
 * | qmin, qmax | both 0 (no position limits) or finite with qmin < qmax (as ::sms_real too), each at most 2^-4 of the largest ::sms_real in magnitude; linear-ramp profiles only |
 *
 * **Asymmetric limits** (ruckig's min_velocity and min_acceleration): with vmin or amin set,
 * the velocity stays within [vmin, vmax] and the acceleration within [amin, amax] at every
 * sample (different bounds forward and backward: gravity on a vertical axis, a conveyor that
 * must never run backwards fast). The jerk bound stays symmetric. Every motion is planned by
 * the same families (docs/design.md, "Asymmetric limits"); only the linear-ramp profiles
 * (::SMS_PROFILE_POLYNOMIAL, ::SMS_PROFILE_DAMPED) take them: the trigonometric profile is
 * refused with ::SMS_ERR_LIMIT when either is set to another value than 0, -vmax or -amax.
 * Last in the struct so that initialisers of the other six stay valid and mean the symmetric
 * limits (set both fields, or zero the struct, when filling it field by field).
 *
 * **Position limits** (ruckig's min_position and max_position): with qmin, qmax set the
 * position stays within [qmin, qmax] at every sample (the reported q exactly: the plan is
 * checked with the continuous extremes of its segments to 16 u (|qmin| + |qmax|), u the unit
 * roundoff, and q is held to the limits, which changes it by no more than that and the
 * rounding of the sample). Targets then rest inside: a position target outside [qmin, qmax]
 * is refused with ::SMS_ERR_POSITION_LIMIT, and a target velocity or acceleration other than
 * 0 (a motion that would drift on after it) with ::SMS_ERR_TARGET_VELOCITY or
 * ::SMS_ERR_TARGET_ACCELERATION, so the velocity interface plans only the stop.
 * sms_generator_start() refuses a state outside, or from which neither the time-optimal
 * motion to the target nor the brake to rest (the time-optimal change to velocity 0, the stop
 * interface) stays inside, with ::SMS_ERR_POSITION_LIMIT (a harder brake, one that reverses
 * before it rests, may still stay inside from some of these: they are refused all the same);
 * sms_generator_reset() to a position outside is ignored, and init rests at 0, or at the limit
 * nearer to 0 when 0 lies outside. A re-plan takes the time-optimal motion when it stays
 * inside; else it brakes to rest at once (the stop), waits there for the next sample, and
 * moves to the target (time-optimal from that rest, with what is left of minimum_duration;
 * without it when the stretched motion would cross a limit): the first whose segments stay
 * inside. When not even the brake stays inside (a state on the way of a plan that overshoots
 * towards a limit and turns back before it: its own brake turns later), the running plan goes
 * on, which stays inside, and the re-plan is tried again on the next sample, as for a state
 * no half-cosine plan can start from. The brake-then-move motion is not time-optimal under
 * the constraint in general (a motion that starts braking and turns towards the target
 * before it rests is shorter); it is what docs/design.md ("Position limits") describes.
 * Last in the struct (0, 0: none, as a zeroed or shorter initialiser leaves them).
 */
typedef struct sms_generator_config {
    double vmax;          /**< velocity bound, finite, > 0 */
    double amax;          /**< acceleration bound, finite, > 0 */
    double jmax;          /**< jerk bound, finite, > 0 */
    sms_profile profile;  /**< shape of the transitions, and of the tuned stage */
    double wn;            /**< 0: no mode to cancel; else [rad/s], finite, below pi/Ts */
    double zeta;          /**< the mode's damping ratio, [0, 1) */
    double vmin;          /**< lower velocity bound, finite, < 0; 0: -vmax */
    double amin;          /**< lower acceleration bound, finite, < 0; 0: -amax */
    double qmin;          /**< lower position limit, finite, < qmax; 0 and qmax 0: none */
    double qmax;          /**< upper position limit, finite, > qmin; 0 and qmin 0: none */
} sms_generator_config;

/**
 * @brief Doubles of configuration identity at the start of a saved generator state
 * (sms_generator_get_state()), in this order: the head of config.h (::SMS_STATE_TAG,
 * ::SMS_STATE_VERSION, sizeof(::sms_real), ::SMS_STATE_KIND_GENERATOR, Ts), then vmax, amax,
 * jmax, profile, wn, zeta exactly as given to sms_generator_init(), then the lower bounds vmin
 * and amin in effect (-vmax and -amax for symmetric limits, so a config with 0 and one with
 * -vmax are the same configuration), then qmin and qmax (0, 0: no position limits). Loading
 * compares them with
 * the generator's own (exact equality) and refuses a state of another configuration, writing
 * nothing, with the status naming the first field that differs (::SMS_ERR_STATE_FORMAT,
 * ::SMS_ERR_STATE_PRECISION, ::SMS_ERR_STATE_KIND, ::SMS_ERR_STATE_TS, ::SMS_ERR_STATE_VMAX,
 * ::SMS_ERR_STATE_AMAX, ::SMS_ERR_STATE_JMAX, ::SMS_ERR_STATE_PROFILE, ::SMS_ERR_STATE_WN,
 * ::SMS_ERR_STATE_ZETA, then ::SMS_ERR_STATE_VMAX for vmin and ::SMS_ERR_STATE_AMAX for amin:
 * the velocity and the acceleration bounds, and ::SMS_ERR_POSITION_LIMIT for qmin and qmax).
 */
#define SMS_GENERATOR_IDENTITY_COUNT 15

/** @brief Doubles of a saved generator state after its identity (sms_generator_get_state()),
 * and where each field lies counted from the end of the identity: the latest target and the
 * goal of the running plan (each position, velocity, acceleration, interface,
 * minimum_duration), the running plan's start q, v, a and the samples since it. */
#define SMS_GENERATOR_PLAN_STATE_COUNT 14
#define SMS_GENERATOR_STATE_TARGET 0 /**< target: position, velocity, acceleration, interface,
                                        minimum_duration */
#define SMS_GENERATOR_STATE_GOAL 5   /**< goal of the running plan, the same five */
#define SMS_GENERATOR_STATE_Q 10     /**< the running plan's start position */
#define SMS_GENERATOR_STATE_V 11     /**< ... velocity */
#define SMS_GENERATOR_STATE_A 12     /**< ... acceleration */
#define SMS_GENERATOR_STATE_K 13     /**< samples since the plan's first */

/**
 * @brief How far, relative, the generators' reported |v|, |a|, |j| may exceed vmax, amax,
 * jmax: 32 u, u the unit roundoff of ::sms_real (2^-53 double, 2^-24 float; the rounding of
 * the plan's own values and of the tuned stage's average, docs/sampled-limits.md and
 * docs/multi-axis.md). A saved state is checked to the same: its velocities, accelerations
 * and brake velocity within limit (1 + SMS_LIMIT_RTOL), the limits as ::sms_real.
 */
#ifdef SMS_USE_FLOAT
#define SMS_LIMIT_RTOL 1.9073486328125e-6 /* 2^-19 */
#else
#define SMS_LIMIT_RTOL 3.5527136788005009e-15 /* 2^-48 */
#endif

/**
 * @brief Online generator: a staircase of targets in, a bounded smooth trajectory out.
 *
 * **The plan.** Whenever the target differs from the goal of the running plan, the
 * generator re-plans on that sample from its exact state (q, v, a) there: the time-optimal
 * motion to the target at rest within vmax, amax, jmax, made of a velocity change
 * (v, a) -> (vp, 0) (a transition of the acceleration towards +-amax, a hold there if
 * reached, a transition back to 0), a cruise at vp, and the stop (vp, 0) -> (0, 0)
 * anchored on the target. vp = +-vmax when the distance allows; else vp solves "distance of
 * the two changes = target - q", which increases with vp (bisection, in ::sms_real, no
 * libm), and the cruise covers what the last bit of vp leaves, so the parts meet to the
 * rounding of the positions. The transitions' shape is the profile's:
 * - ::SMS_PROFILE_POLYNOMIAL (and ::SMS_PROFILE_DAMPED): linear ramps at jerk +-jmax. Rest
 *   to rest this is ruckig's time-optimal duration (h = 0.0819, v = 1, a = 10, j = 100:
 *   0.297 s).
 * - ::SMS_PROFILE_TRIGONOMETRIC: half-cosine transitions, a(t) = a0 + da (1 - cos(pi t/d))/2
 *   with peak jerk jmax, so the jerk is continuous and zero at both ends of a transition (the
 *   modified double-S). A transition of da lasts (pi/2) da/jmax: the durations are those of
 *   the ramp plan at jerk (2/pi) jmax. Rest to rest this is the shortest motion of this
 *   family: the trigonometric kinematic design's duration (sms_kinematic_design()).
 * q, v, a stay continuous across a re-plan; the jerk may jump there (within +-jmax). Once
 * the target holds, the plan rests exactly on it from the first sample at or after its
 * continuous end: a rest-to-rest move takes its time-optimal duration rounded up to the grid.
 *
 * **The mode** (wn > 0). The plan then runs through the stage tuned to the mode, the
 * shortest one whose zero cancels it: rectangular (polynomial) or exponential with sigma =
 * -zeta wn (damped) of length Tm = 2 pi/wd, harmonic of length 3 pi/wd (trigonometric),
 * wd = wn sqrt(1 - zeta^2), with exact timing (its zero lies exactly on the mode for any Ts,
 * docs/exact-mode.md): q = h * p, and v, a, j are the same taps applied to the plan's v, a,
 * j. The taps are non-negative and sum to 1, so every output and every backward difference
 * of the output is an average of the plan's and keeps its bound; the vibration zero is the
 * stage's. Both hold; what is given up is time: the stage adds Tm (rounded up to whole
 * samples) after the plan, where the offline design (sms_kinematic_design()) lets the tuned
 * stage shape the jerk itself (docs/sampled-limits.md). Once the plan has rested on the
 * target for the stage's length, the output is the target exactly.
 *
 * **Samples.** Outputs are the exact values at the sample instants (jerk: the right limit at
 * a jump), so every sampled difference dq/Ts, d2q/Ts^2, d3q/Ts^3 is a weighted average of v,
 * a, j and keeps the bounds (docs/sampled-limits.md). Any Ts works (no stage has to be longer
 * than a sample; the tuned stage needs its mode below pi/Ts). Times are whole samples plus a
 * fraction and every segment is anchored on its own start (the stop on the target); the
 * tuned stage is the drift-free smoother of smoother.h. A float build keeps its error at the
 * rounding of the positions for any move and run length. With u the unit roundoff of
 * ::sms_real: reported |v|, |a|, |j| <= limit (1 + 32 u); each sample's q carries at most
 * 16 u of the largest |position| or |target| (docs/sampled-limits.md, "What rounding adds").
 * Per sample: O(1), no libm (a half-cosine transition sums its own series, about 30 terms);
 * a re-plan: about 60 (double) or 30 (float) evaluations of the distance (at most about
 * 2200 or 330 when vp lies many binades below vmax); a non-finite target is ignored.
 *
 * **Feasible limits.** init accepts a limit set only if the plan can reach vmax: the move
 * from rest that reaches vmax and stops (sms_generator_reach()) must be representable in
 * ::sms_real with room for a reversal, and last at most 2^50 samples. Otherwise no move that
 * reaches vmax could ever be planned (e.g. vmax = 1, amax = 1e-30, jmax = 1e-300 at Ts = 1 ms:
 * reaching vmax takes 4 sqrt(vmax/jmax) = 4e150 s), so the limits are refused in O(1) with
 * ::SMS_ERR_LIMIT and sms_generator_reach() names the quantity out of range.
 *
 * **Dropped targets.** Within feasible limits some targets still cannot be planned: the move
 * would last more than 2^52 samples (a cruise of distance/vmax; e.g. a target of 1e300 with
 * vmax = 1), or a value on the way (a distance, a position) would overflow ::sms_real. Such
 * a target is dropped: the running plan goes on to its goal (or the output rests where it
 * is), `refused` is 1 and `dropped` counts it, and the target is not tried again until the
 * input changes. So every output is finite, vmax, amax and jmax hold at every sample, and
 * every saved state loads again. Exactly the targets whose move is non-finite or longer than
 * 2^52 samples are dropped (docs/sampled-limits.md).
 */
typedef struct sms_generator {
    double Ts;            /**< sample period [s] */
    double vmax;          /**< velocity bound as given */
    int shape;            /**< the plan's transitions: 0 linear ramps, 1 half-cosine */
    double stage_T;       /**< length of the tuned stage [s] (0: no mode) */
    size_t stage_length;  /**< its taps L: the output rests L samples after the plan (0: none) */
    size_t stage_window;  /**< its ring length M (reals per channel in the buffer) */
    sms_smoother stage[4]; /**< the tuned stage on q, v, a, j (rings in the caller buffer) */
    size_t quiet;         /**< samples the plan has rested on its goal, saturated at L */
    sms_real Ts_signal;   /**< Ts in signal precision (no double on a float build's path) */
    sms_real *buffer;     /**< caller buffer: 4 M reals (NULL without a mode) */
    int time_optimal;     /**< 1: the plan is time-optimal for the profile (every config) */
    sms_plan_limits limits; /**< vmax, amax, jmax in signal precision */
    sms_real vmin;        /**< lower velocity bound in signal precision (-vmax: symmetric) */
    sms_real amin;        /**< lower acceleration bound in signal precision (-amax: symmetric) */
    int asymmetric;       /**< 1 when vmin != -vmax or amin != -amax */
    int bounded;          /**< 1 with position limits (qmin, qmax) */
    sms_real qmin;        /**< lower position limit in signal precision (bounded only) */
    sms_real qmax;        /**< upper position limit in signal precision (bounded only) */
    sms_real qtol;        /**< how far a plan's computed extremes may pass them: 16 u
                               (|qmin| + |qmax|), the rounding of the positions */
    double identity[SMS_GENERATOR_IDENTITY_COUNT]; /**< config and Ts it was built for */
    /* dynamic state */
    sms_target target;    /**< latest valid target (a stop as velocity 0, acceleration 0; the
                               position of a velocity target as 0) */
    sms_target goal;      /**< the target the running plan heads for */
    sms_target request;   /**< the last target given, as given: a sample whose target equals it
                               field for field takes no other look at it */
    int pending;          /**< 1 while the target differs from the goal and is not dropped: a
                               re-plan is due (at the first sample a plan can start from) */
    int refused;          /**< 1 while the held target is dropped (its move cannot be represented);
                               cleared when the target changes, by reset and set_state */
    size_t dropped;       /**< targets dropped since init or the last reset (read-only; not part
                               of the saved state: a diagnostic count) */
    sms_real plan_q;      /**< position the running plan started from */
    sms_real plan_v;      /**< velocity it started from */
    sms_real plan_a;      /**< acceleration it started from */
    sms_plan plan;        /**< the running plan */
    size_t k;             /**< samples since the plan's first sample */
} sms_generator;

/**
 * @brief The move that reaches vmax from rest, and which derived quantity of a refused limit
 * set is out of range (sms_generator_reach()).
 *
 * J is jmax, or the mean jerk (2/pi) jmax of the trigonometric profile's half-cosine
 * transitions; ap = min(amax, sqrt(vmax J)) is the peak acceleration of that move; it lasts
 * duration = 2 (vmax/ap + ap/J) and covers distance = vmax (vmax/ap + ap/J).
 */
typedef struct sms_generator_reach_info {
    double peak_acceleration; /**< ap [units/s^2] */
    double duration;          /**< [s] */
    double distance;          /**< [units] */
    double samples;           /**< duration/Ts */
    const char *quantity;     /**< NULL when feasible; else the quantity out of range:
                                   "vmax/amax", "sqrt(vmax/jmax)", "vmax*jmax",
                                   "amax^2", "the distance to reach vmax", or a single
                                   argument ("vmax", "Ts") that is itself out of range */
    const char *arguments;    /**< the arguments it is formed from, e.g. "amax, jmax" */
    double value;             /**< its value (in its unit: s for a duration) */
    double bound;             /**< the bound it exceeds (or falls below) */
} sms_generator_reach_info;

/**
 * @brief Check that a plan can reach vmax with these limits at Ts, in O(1) (what init checks).
 *
 * The planner forms, for a move from any state within the bounds, the products J dv
 * (|dv| <= 2 vmax), squares of accelerations up to ap, durations up to about `duration` and
 * distances up to a few times `distance`. With M = 16 (room for a reversal and the stop),
 * MAX and MIN the largest and the smallest normal number of ::sms_real and eps its machine
 * epsilon (float: 3.4e38, 1.2e-38, 1.2e-7; double: 1.8e308, 2.2e-308, 2.2e-16), the limits
 * are feasible (::SMS_OK) when, checked in this order:
 * 1. Ts is finite and > 0 in ::sms_real; vmax, amax, jmax are finite and in [MIN, MAX/M];
 * 2. M vmax J <= MAX (the velocity changes J dv stay finite);
 * 3. duration/Ts <= 2^50: reaching vmax fits the plan's 2^52 samples with room for a
 *    reversal. The quantity named is the longer term: vmax/amax when amax is reached
 *    (amax^2 < vmax J, which makes amax/J the shorter one: a long amax/jmax means amax is
 *    never reached), sqrt(vmax/J) when it is not (J = (2/pi) jmax for the trigonometric
 *    profile, named "sqrt(pi vmax/(2 jmax))");
 * 4. ap^2 >= MIN/eps (squares of accelerations, and the products of moves down to about
 *    eps^1.5 `distance`, stay normal): "amax^2" or "vmax*jmax";
 * 5. duration >= MIN and MIN/eps <= distance <= MAX/M.
 * With asymmetric limits (vmin or amin set) vmin and amin must be 0 or negative with their
 * magnitudes in [MIN, MAX/M] (else the quantity is "vmin" or "amin"; with the trigonometric
 * profile, which takes symmetric limits only, "vmin" or "amin" with the arguments
 * "vmin, profile" or "amin, profile"), and steps 2 to 5 hold for each pair of a velocity
 * bound and an acceleration bound, checked in the order (vmax, amax), (|vmin|, |amin|),
 * (vmax, |amin|), (|vmin|, amax): a refusal names its pair ("vmin/amin", "vmin*jmax",
 * "amin^2", "the distance to reach vmin", ...); on success `reach` describes the (vmax, amax)
 * move.
 * Inside this region every rest-to-rest move from about eps^1.5 `distance` up to `distance`,
 * a reversal from full speed, and any longer move whose plan stays within 2^52 samples and
 * finite is planned; outside it no move that reaches vmax can be (3: beyond 2^52 samples
 * once the margin is used; 1, 2, 4, 5: a product overflows or loses its bits).
 * @param reach  out (may be NULL): the move, and on ::SMS_ERR_LIMIT the first quantity out
 *               of range with its value and bound.
 * @return ::SMS_OK, ::SMS_ERR_NULL (config), ::SMS_ERR_SAMPLE_PERIOD, ::SMS_ERR_LIMIT.
 * @param config the limits and the profile
 * @param Ts     sample period [s], finite, > 0,
 *               at most ::SMS_TS_MAX (a larger one: ::SMS_ERR_SAMPLE_PERIOD_RANGE)
 */
SMS_API sms_status sms_generator_reach(const sms_generator_config *config, double Ts,
                                       sms_generator_reach_info *reach);

/** @brief Reals the generator's buffer needs: 4 M for the tuned stage's rings (M its ring
 * length, about Tm/Ts), 0 without a mode (init then accepts buffer NULL).
 * @return ::SMS_OK, ::SMS_ERR_NULL, ::SMS_ERR_SAMPLE_PERIOD, ::SMS_ERR_LIMIT (a bound not
 *         finite/positive, or limits with which no plan can reach vmax: sms_generator_reach()
 *         says which quantity), ::SMS_ERR_KIND
 *         (profile), ::SMS_ERR_WN (wn < 0, NaN/Inf, or 0 with DAMPED), ::SMS_ERR_ZETA,
 *         ::SMS_ERR_ABOVE_NYQUIST (wn >= pi/Ts), ::SMS_ERR_DURATION_BELOW_TS (the tuned
 *         stage shorter than a sample), ::SMS_ERR_TOO_LONG (the tuned stage too long).
 * @param config the limits and the optional mode (ranges in ::sms_generator_config)
 * @param Ts     sample period [s], finite, > 0,
 *               at most ::SMS_TS_MAX (a larger one: ::SMS_ERR_SAMPLE_PERIOD_RANGE)
 * @param n_reals receives 4 M (0 without a mode)
 */
SMS_API sms_status sms_generator_buffer_size(const sms_generator_config *config, double Ts,
                                             size_t *n_reals);
/** @brief Validate, design the tuned stage if any; the generator rests at 0 (with position
 * limits that exclude 0: at the nearer limit).
 * @return as sms_generator_buffer_size(), plus ::SMS_ERR_BUFFER_TOO_SMALL. Untouched on error.
 * @param g      instance to fill; untouched on error
 * @param config the limits and the optional mode
 * @param Ts     sample period [s], finite, > 0,
 *               at most ::SMS_TS_MAX (a larger one: ::SMS_ERR_SAMPLE_PERIOD_RANGE)
 * @param buffer the tuned stage's rings, kept by g (NULL allowed without a mode)
 * @param n_reals reals in buffer, >= sms_generator_buffer_size()
 */
SMS_API sms_status sms_generator_init(sms_generator *g, const sms_generator_config *config,
                                      double Ts, sms_real *buffer, size_t n_reals);
/** @brief Rest at `position` (target, plan and stage all there). O(M).
 * @param g      the generator, built by sms_generator_init()
 * @param position finite, and within [qmin, qmax] with position limits (else ignored: the
 *                 generator stays as it is, as for a non-finite one)
 */
SMS_API void sms_generator_reset(sms_generator *g, sms_real position);
/**
 * @brief Advance one sample with the current target (the staircase value) and write
 * out[0..3] = q, q', q'', q''' at this instant. A non-finite target is ignored (the previous
 * target is kept), so the output stays bounded.
 * @param g      the generator, built by sms_generator_init()
 * @param target the target position of this sample
 * @param out    receives q, v, a, j
 */
SMS_API void sms_generator_step(sms_generator *g, sms_real target, sms_real out[4]);
/** @brief n steps: targets[0..n-1] in, out[4 i .. 4 i + 3] = q, v, a, j of step i.
 * Equal, bit for bit, to n calls of sms_generator_step() and to any split into blocks.
 * @param g      the generator, built by sms_generator_init()
 * @param targets n target positions
 * @param n      number of samples, any
 * @param out    receives 4 n values
 */
SMS_API void sms_generator_process(sms_generator *g, const sms_real *targets, size_t n,
                                   sms_real *out);
/**
 * @brief n steps with the same target: the state and the last output (out[0..3]) of n calls
 * of sms_generator_step() with `target`, bit for bit, at a cost bounded whatever n.
 *
 * The generator is stepped until the target has been planned (or dropped): one sample, or for
 * the trigonometric profile until a state the plan can start from, at most one acceleration
 * transition, (pi/2) 2 amax/jmax. From then on the plan is fixed and sample k of it is
 * closed form: without a mode the index jumps, O(1). With a mode the tuned stage's state
 * depends only on its last 2M + 2 inputs (M its ring length: both restarted copies begin and
 * the ring refills within them): when those all lie at the plan's rest, the stages are put
 * in their absorbed state (sms_smoother_settle(), O(M) writes); otherwise the plan index and
 * the stages' phase jump to the last 2M + 2 samples, which are stepped.
 * @param n  steps (0: nothing changes, out untouched)
 * @param g      the generator, built by sms_generator_init()
 * @param target the held target position
 * @param out    receives q, v, a, j of the last step
 */
SMS_API void sms_generator_hold(sms_generator *g, sms_real target, uint64_t n, sms_real out[4]);

/**
 * @brief Is `target` one the generator can plan to? O(1), writes nothing.
 * @return ::SMS_OK; ::SMS_ERR_NULL; ::SMS_ERR_INTERFACE (not an ::sms_interface);
 *         ::SMS_ERR_TARGET_POSITION (position interface, position not finite);
 *         ::SMS_ERR_TARGET_VELOCITY (not finite, |v| > vmax, or not 0 for a position target
 *         of the trigonometric profile); ::SMS_ERR_TARGET_ACCELERATION (not finite,
 *         |a| > amax, v - a|a|/(2 jmax) or v + a|a|/(2 jmax) beyond +-vmax, or not 0 for
 *         the trigonometric profile). With asymmetric limits each side has its own bound:
 *         [vmin, vmax] and [amin, amax]. The limits are compared as ::sms_real holds them.
 * @param g      the generator (read only)
 * @param target the target to check
 */
SMS_API sms_status sms_generator_check_target(const sms_generator *g, const sms_target *target);
/** @brief sms_generator_check_target() of n targets: ::SMS_OK, or the status of the first
 * refused one and its index in *index (n when all pass; index may be NULL). O(n), writes
 * nothing else. ::SMS_ERR_NULL when g is NULL, or targets is NULL with n > 0.
 * @param g      the generator (read only)
 * @param targets n targets
 * @param n      how many
 * @param index  receives the index of the first refused target, or n (may be NULL)
 * @return ::SMS_OK, ::SMS_ERR_NULL or the first refused target's status
 */
SMS_API sms_status sms_generator_check_targets(const sms_generator *g, const sms_target *targets,
                                               size_t n, size_t *index);
/**
 * @brief Advance one sample towards `target` and write out[0..3] = q, q', q'', q''' at this
 * instant (sms_generator_step() is this with a position target at rest).
 *
 * The generator re-plans on the sample where the target differs from the one its plan heads
 * for, from its exact state there:
 * - ::SMS_INTERFACE_POSITION: the time-optimal motion to (position, velocity, acceleration)
 *   within vmax, amax, jmax (the profile families of Berscheid and Kroeger, "Jerk-limited
 *   real-time trajectory generation with arbitrary target states", 2021). A target at rest
 *   is reached in the optimum's duration rounded up to the grid and rested on exactly; a
 *   moving target is reached exactly on a sample: the first whole number of samples at or
 *   after the optimum at which a motion within the limits exists (the next sample, unless
 *   that duration is blocked: some moving targets cannot be reached in some durations above
 *   the optimum, and the next duration that can is taken);
 * - ::SMS_INTERFACE_VELOCITY: the time-optimal change to (velocity, acceleration), the
 *   position free;
 * - ::SMS_INTERFACE_STOP: the velocity interface to rest: braking at once.
 * After the target the output moves on: its acceleration returns to zero at jmax and the
 * velocity it leaves is held (a target at rest: the output rests on it). Every sample is the
 * exact value of that continuous motion, so the limits hold at every sample as for rest
 * targets (docs/sampled-limits.md). An invalid target (sms_generator_check_target()) is
 * ignored, the previous one kept; a valid one whose motion cannot be represented is dropped
 * (`refused`, `dropped`), as for sms_generator_step().
 * @param g      the generator, built by sms_generator_init()
 * @param target the target of this sample, not NULL (an invalid one is ignored, see above)
 * @param out    receives q, v, a, j
 */
SMS_API void sms_generator_step_target(sms_generator *g, const sms_target *target,
                                       sms_real out[4]);
/** @brief n steps: targets[0..n-1] in, out[4 i .. 4 i + 3] = q, v, a, j of step i. Equal,
 * bit for bit, to n calls of sms_generator_step_target() and to any split into blocks.
 * @param g      the generator, built by sms_generator_init()
 * @param targets n targets
 * @param n      number of samples, any
 * @param out    receives 4 n values
 */
SMS_API void sms_generator_process_targets(sms_generator *g, const sms_target *targets,
                                           size_t n, sms_real *out);
/** @brief sms_generator_hold() with any target: n calls of sms_generator_step_target(), bit
 * for bit, at a cost bounded whatever n.
 * @param g      the generator, built by sms_generator_init()
 * @param target the held target
 * @param n      steps (0: nothing changes, out untouched)
 * @param out    receives q, v, a, j of the last step
 */
SMS_API void sms_generator_hold_target(sms_generator *g, const sms_target *target, uint64_t n,
                                       sms_real out[4]);
/**
 * @brief Continue from the motion state (q, v, a): the generator is there now, on the first
 * sample of a plan to `target` (NULL: a stop), and its next step is the plan's next sample.
 * The tuned stage (a mode) keeps its history and filters the new plan from the next step on.
 * @return ::SMS_OK; ::SMS_ERR_NULL (g); ::SMS_ERR_TARGET_POSITION (q not finite);
 *         ::SMS_ERR_TARGET_VELOCITY (v not finite or |v| > vmax; asymmetric limits: v outside
 *         [vmin, vmax]); ::SMS_ERR_TARGET_ACCELERATION (a not finite, |a| > amax or
 *         |v + a|a|/(2 J)| > vmax, J the shape's mean jerk, each on its own side with
 *         asymmetric limits: no plan can start there); ::SMS_ERR_POSITION_LIMIT (position
 *         limits: q outside [qmin, qmax], or neither the time-optimal motion to the target
 *         nor the brake to rest from (q, v, a) stays inside);
 *         a status of sms_generator_check_target() for `target`;
 *         ::SMS_ERR_TOO_LONG (the motion to the target cannot be represented). Each bound
 *         holds to ::SMS_LIMIT_RTOL (a state the generator reported is always accepted).
 *         Nothing is changed on error.
 * @param g      the generator, built by sms_generator_init(); untouched on error
 * @param q      position now
 * @param v      velocity now
 * @param a      acceleration now
 * @param target where to go from there (NULL: a stop)
 */
SMS_API sms_status sms_generator_start(sms_generator *g, sms_real q, sms_real v, sms_real a,
                                       const sms_target *target);
/** @brief Samples from the last one output until the one on which the plan reaches its
 * target state (0 once reached; a velocity target: its velocity and acceleration).
 * @param g      the generator (read only)
 * @return samples, 0 once the target state is reached
 */
SMS_API uint64_t sms_generator_arrival(const sms_generator *g);
/** @brief Length of the tuned stage [s]: the output lags the plan by it (0 without a mode).
 * @param g      the generator (read only)
 * @return the length [s], >= 0
 */
SMS_API double sms_generator_tail_duration(const sms_generator *g);
/** @brief Number of doubles sms_generator_get_state() writes:
 * ::SMS_GENERATOR_IDENTITY_COUNT + 12 without a mode (the configuration identity, then the
 * target and the goal of the running plan, each as position, velocity, acceleration and
 * interface in canonical form (a stop as the velocity interface to 0), the start q, v, a of
 * the running plan and the samples since it; loading re-plans from these, so a saved state
 * can also move the generator to any sample of its plan), and with a mode 1 more (the quiet
 * samples) plus the four stage states (sms_smoother_state_count() each, every one with its
 * own stage identity).
 * @param g      the generator (read only)
 * @return the count
 */
SMS_API size_t sms_generator_state_count(const sms_generator *g);
/** @brief Write the state (sms_generator_state_count() doubles, layout above) to dst.
 * @param g      the generator (read only)
 * @param dst    sms_generator_state_count() doubles
 */
SMS_API void sms_generator_get_state(const sms_generator *g, double *dst);
/** @brief Restore a saved state.
 * @return ::SMS_OK; ::SMS_ERR_NULL; ::SMS_ERR_STATE_FORMAT .. ::SMS_ERR_STATE_ZETA (see
 *         ::SMS_GENERATOR_IDENTITY_COUNT) if it was saved by another configuration (checked
 *         first, whatever n); ::SMS_ERR_STATE if n differs or a field is invalid (non-finite,
 *         beyond the limits, a target sms_generator_check_target() refuses or not in
 *         canonical form, a count out of range, a plan the generator cannot form). Nothing
 *         is written on error.
 * @param g      the generator, built by sms_generator_init(); untouched on error
 * @param src    the saved state
 * @param n      its length in doubles, sms_generator_state_count()
 */
SMS_API sms_status sms_generator_set_state(sms_generator *g, const double *src, size_t n);
/** @brief What sms_generator_set_state() would return, writing nothing.
 *
 * "Beyond the limits": the running plan's start v and a (as ::sms_real holds them) must keep
 * |v| <= vmax (1 + ::SMS_LIMIT_RTOL), |a| <= amax (1 + ::SMS_LIMIT_RTOL) and the brake velocity
 * |v + a|a|/(2 J)| <= vmax (1 + ::SMS_LIMIT_RTOL), J the shape's mean jerk (jmax, or (2/pi)
 * jmax for half-cosine transitions), the limits as ::sms_real: the tolerance of the reported
 * values, so a restored state is one the generator could have reached itself (its own saved
 * states stay within 15 u, tests/c/test_generator.c) and reports nothing beyond it.
 * @param g      the generator (read only)
 * @param src    the saved state
 * @param n      its length in doubles
 * @return what sms_generator_set_state() would return
 */
SMS_API sms_status sms_generator_check_state(const sms_generator *g, const double *src, size_t n);
/** @brief Point a copied generator at a buffer holding the same stage rings.
 * @param g      the copied generator
 * @param buffer the copy of its buffer
 */
SMS_API void sms_generator_rebind(sms_generator *g, sms_real *buffer);

/* ------------------------------------------------------------------------------------------ */
/* B-spline interpolating filters                                                              */
/* ------------------------------------------------------------------------------------------ */

/** @brief Highest B-spline degree p. */
#define SMS_BSPLINE_MAX_DEGREE 7
/** @brief Most axes of one B-spline filter. */
#define SMS_BSPLINE_MAX_AXES 3

/**
 * @brief Doubles of configuration identity at the start of a saved B-spline state
 * (sms_bspline_get_state()): the head of config.h (::SMS_STATE_TAG, ::SMS_STATE_VERSION,
 * sizeof(::sms_real), ::SMS_STATE_KIND_BSPLINE, Ts), then degree, n_axes and the knot
 * spacing N Ts (T as realised: two T that round to the same N give the same filter). Loading
 * refuses a state of another configuration, writing nothing, with the status naming the first
 * field that differs (::SMS_ERR_STATE_FORMAT, ::SMS_ERR_STATE_PRECISION, ::SMS_ERR_STATE_KIND,
 * ::SMS_ERR_STATE_TS, ::SMS_ERR_STATE_DEGREE, ::SMS_ERR_STATE_AXES, ::SMS_ERR_STATE_T).
 */
#define SMS_BSPLINE_IDENTITY_COUNT 8

/**
 * @brief Uniform B-spline of degree p, knot spacing T = N Ts, on up to 3 axes (docs/filters.md).
 *
 * Each axis is a chain of p rectangular stages of N samples fed with control points held
 * for N samples each. Let d[k] be the response of one control point held N samples and
 * filtered (support k = 0 .. (p+1)(N-1)), k0 = floor((p+1)(N-1)/2) its centre and
 * c_m = d[k0 + m N]. For via-points Q_0 .. Q_{M-1} (M >= 2), sms_bspline_control_points()
 * returns C_0 .. C_{M-1} with C_0 = Q_0, C_{M-1} = Q_{M-1} and interior points solving
 * sum_m c_m C_{i-m} = Q_i, i = 1 .. M-2 (C_j = Q_0 for j < 0, Q_{M-1} for j > M-1).
 * Feeding protocol (sample 0 = first sample after reset(Q_0)): input C_j on samples
 * [(j-1) N, j N) for j = 1 .. M-2, then C_{M-1} forever. Then the output rests at Q_0
 * before sample 0 (at sample 0 it has moved by (C_1 - Q_0) / N^p), passes through Q_i at
 * sample (i-1) N + k0 (sms_bspline_pass_sample()),
 * and equals Q_{M-1} from sample (M-2) N + p (N-1) on.
 * Its transfer function is P(z) * M_N(z)^p: zeros at w = k 2 pi / T for every k >= 1.
 * The c_m are measured from the filter itself at init, so the pass-through holds to the
 * filter's own rounding (1e-12 relative in double). Memory: the caller owns the struct and
 * one buffer (the stages' delay lines); a copied struct keeps pointing at the same buffer.
 */
typedef struct sms_bspline {
    unsigned degree;       /**< p, 1 .. ::SMS_BSPLINE_MAX_DEGREE */
    size_t n_axes;         /**< 1 .. ::SMS_BSPLINE_MAX_AXES */
    size_t N;              /**< knot spacing in samples, N = round(T/Ts) >= 1 */
    double Ts;             /**< sample period [s] */
    size_t k0;             /**< pass-through offset (see above) */
    long m_first;          /**< first m with c_m != 0 (<= 0) */
    size_t n_coeff;        /**< number of c_m stored */
    double coeff[SMS_BSPLINE_MAX_DEGREE + 2]; /**< c_m, m = m_first .. m_first + n_coeff - 1 */
    sms_smoother stages[SMS_BSPLINE_MAX_AXES * SMS_BSPLINE_MAX_DEGREE]; /**< rectangular, axis a:
                                                                         [a p, a p + p) */
    double identity[SMS_BSPLINE_IDENTITY_COUNT]; /**< configuration it was built for */
} sms_bspline;

/** @brief Reals needed: n_axes p times one rectangular stage of N samples.
 * @return ::SMS_OK, ::SMS_ERR_NULL, ::SMS_ERR_ORDER (degree or n_axes out of range),
 *         ::SMS_ERR_SAMPLE_PERIOD, ::SMS_ERR_DURATION, ::SMS_ERR_DURATION_BELOW_TS, ::SMS_ERR_TOO_LONG.
 * @param degree  p, 1 .. ::SMS_BSPLINE_MAX_DEGREE
 * @param n_axes  1 .. ::SMS_BSPLINE_MAX_AXES
 * @param T       knot spacing [s], finite, >= Ts (the rule of config.h)
 * @param Ts      sample period [s], finite, > 0,
 *                at most ::SMS_TS_MAX (a larger one: ::SMS_ERR_SAMPLE_PERIOD_RANGE)
 * @param n_reals receives n_axes p N
 */
SMS_API sms_status sms_bspline_buffer_size(unsigned degree, size_t n_axes, double T, double Ts,
                                           size_t *n_reals);
/** @brief Build the chains (knot spacing N = round(T/Ts) samples) at rest at 0 and compute
 * c_m. Same statuses as sms_bspline_buffer_size() plus ::SMS_ERR_BUFFER_TOO_SMALL.
 * @param b       instance to fill; untouched on error
 * @param degree  p, 1 .. ::SMS_BSPLINE_MAX_DEGREE
 * @param n_axes  1 .. ::SMS_BSPLINE_MAX_AXES
 * @param T       knot spacing [s], finite, >= Ts
 * @param Ts      sample period [s], finite, > 0,
 *                at most ::SMS_TS_MAX (a larger one: ::SMS_ERR_SAMPLE_PERIOD_RANGE)
 * @param buffer  the stages' delay lines, kept by b
 * @param n_reals reals in buffer, >= sms_bspline_buffer_size()
 * @return as sms_bspline_buffer_size(), or ::SMS_ERR_BUFFER_TOO_SMALL
 */
SMS_API sms_status sms_bspline_init(sms_bspline *b, unsigned degree, size_t n_axes, double T,
                                    double Ts, sms_real *buffer, size_t n_reals);
/** @brief Rest every axis at rest[axis] (n_axes values).
 * @param b      the B-spline filter, built by sms_bspline_init()
 * @param rest   n_axes finite values
 */
SMS_API void sms_bspline_reset(sms_bspline *b, const sms_real *rest);
/** @brief One sample: in[axis] (the held control point) -> out[axis]; in == out allowed.
 * @param b      the B-spline filter, built by sms_bspline_init()
 * @param in     n_axes inputs
 * @param out    receives n_axes outputs; may be in itself
 */
SMS_API void sms_bspline_step(sms_bspline *b, const sms_real *in, sms_real *out);
/** @brief Doubles of work memory sms_bspline_control_points() needs for n_via via-points.
 * @param b      the B-spline filter (read only)
 * @param n_via  via-points
 * @return the number of doubles
 */
SMS_API size_t sms_bspline_work_size(const sms_bspline *b, size_t n_via);
/**
 * @brief Control points C (n_via rows of n_axes, row-major) from via-points Q (same layout).
 * @param work    sms_bspline_work_size() doubles of scratch memory
 * @return ::SMS_OK, ::SMS_ERR_NULL, ::SMS_ERR_ORDER (n_via < 2), ::SMS_ERR_LIMIT (a
 *         non-finite via-point), ::SMS_ERR_BUFFER_TOO_SMALL (n_work). control untouched on error.
 * @param b      the B-spline filter (read only)
 * @param via    n_via rows of n_axes via-points, finite
 * @param n_via  rows, >= 2
 * @param control receives n_via rows of n_axes control points
 * @param n_work doubles in work
 */
SMS_API sms_status sms_bspline_control_points(const sms_bspline *b, const double *via,
                                              size_t n_via, double *control, double *work,
                                              size_t n_work);
/** @brief Sample (after reset) at which the output passes through via-point i, 1 <= i <= M-2:
 * (i-1) N + k0.
 * @param b      the B-spline filter (read only)
 * @param i      the via-point, 1 .. M-2
 * @return the sample index
 */
SMS_API size_t sms_bspline_pass_sample(const sms_bspline *b, size_t i);
/**
 * @brief Shortest knot spacing that puts the first zero of sinc^p at or below every mode:
 * T = N Ts with N = ceil(2 pi / (min wn Ts)) (T >= 2 pi / min wn, docs/filters.md).
 * @return ::SMS_OK, ::SMS_ERR_NULL, ::SMS_ERR_ORDER (n = 0), ::SMS_ERR_WN, ::SMS_ERR_SAMPLE_PERIOD,
 *         ::SMS_ERR_TOO_LONG (T beyond double: a mode far below 1/Ts, or Ts near DBL_MAX).
 * @param wn     n natural frequencies [rad/s], each finite and > 0
 * @param n      modes, >= 1
 * @param Ts     sample period [s], finite, > 0
 * @param T      receives the knot spacing [s]
 */
SMS_API sms_status sms_bspline_period_for_modes(const double *wn, size_t n, double Ts, double *T);
/** @brief Doubles sms_bspline_get_state() writes: ::SMS_BSPLINE_IDENTITY_COUNT (the
 * configuration identity) + n_axes p stage states (sms_smoother_state_count() each, axis by
 * axis, stage by stage, every one with its own stage identity).
 * @param b      the B-spline filter (read only)
 * @return the count
 */
SMS_API size_t sms_bspline_state_count(const sms_bspline *b);
/** @brief Write the state (sms_bspline_state_count() doubles, layout above) to dst.
 * @param b      the B-spline filter (read only)
 * @param dst    sms_bspline_state_count() doubles
 */
SMS_API void sms_bspline_get_state(const sms_bspline *b, double *dst);
/** @brief Restore a saved state.
 * @return ::SMS_OK; ::SMS_ERR_NULL; ::SMS_ERR_STATE_FORMAT .. ::SMS_ERR_STATE_T (see
 *         ::SMS_BSPLINE_IDENTITY_COUNT) if it was saved by another configuration (checked
 *         first, whatever n); ::SMS_ERR_STATE if n differs or a stage state does not fit its
 *         stage. Nothing is written on error.
 * @param b      the B-spline filter, built by sms_bspline_init(); untouched on error
 * @param src    the saved state
 * @param n      its length in doubles, sms_bspline_state_count()
 */
SMS_API sms_status sms_bspline_set_state(sms_bspline *b, const double *src, size_t n);
/** @brief What sms_bspline_set_state() would return, writing nothing.
 * @param b      the B-spline filter (read only)
 * @param src    the saved state
 * @param n      its length in doubles
 * @return what sms_bspline_set_state() would return
 */
SMS_API sms_status sms_bspline_check_state(const sms_bspline *b, const double *src, size_t n);

#ifdef __cplusplus
}
#endif
#endif
