/* SPDX-License-Identifier: Apache-2.0 */
/**
 * @file multi_generator.h
 * @brief Online multi-axis generator: a staircase of target vectors in, q, v, a, j per axis out,
 * every axis within its own vmax, amax, jmax at every sample; phase-synchronised (straight
 * lines, common arrival) or independent axes from rest, or per-axis plans from any state to
 * target states (position, velocity, acceleration) synchronised in time, time if necessary,
 * or not at all (::sms_sync, sms_multi_generator_step_target()).
 *
 * The profile lives in the caller's ::sms_multi_generator; optional vibration stages per axis
 * live in caller memory sized by sms_multi_generator_memory(); nothing is allocated. The
 * per-sample path uses ::sms_real only and no libm (square and cube roots are Newton
 * iterations), so a float build needs no double arithmetic.
 */
#ifndef SMOOTHSHAPER_MULTI_GENERATOR_H
#define SMOOTHSHAPER_MULTI_GENERATOR_H

#include "smoothshaper/chain.h"
#include "smoothshaper/align.h"
#include "smoothshaper/trajectory.h"

#ifdef __cplusplus
extern "C" {
#endif

/** @brief Most axes one generator drives. */
#define SMS_MULTI_MAX_AXES 8
/** @brief Signals filtered per axis when the axis has vibration stages: q, v, a, j. */
#define SMS_MULTI_SIGNALS 4
/**
 * @brief Doubles of configuration identity at the start of a saved state
 * (sms_multi_generator_get_state()), in this order: the head of config.h (::SMS_STATE_TAG,
 * ::SMS_STATE_VERSION, sizeof(::sms_real), ::SMS_STATE_KIND_MULTI_GENERATOR, Ts), n_axes,
 * sync, then for each of the ::SMS_MULTI_MAX_AXES axis slots vmax, amax, jmax (as given to
 * init), n_stages, qmin and qmax (0 for the slots beyond n_axes; 0, 0: no position limits). Loading compares them with the
 * generator's own (exact equality) and refuses a state of another configuration, writing
 * nothing, with the status naming the first field that differs (::SMS_ERR_STATE_FORMAT,
 * ::SMS_ERR_STATE_PRECISION, ::SMS_ERR_STATE_KIND, ::SMS_ERR_STATE_TS, ::SMS_ERR_STATE_AXES,
 * ::SMS_ERR_STATE_SYNC, ::SMS_ERR_STATE_VMAX, ::SMS_ERR_STATE_AMAX, ::SMS_ERR_STATE_JMAX,
 * ::SMS_ERR_STATE_STAGES, ::SMS_ERR_POSITION_LIMIT for qmin and qmax); a stage of another stage configuration is named by its own
 * stage identity (config.h: ::SMS_ERR_STATE_KIND, ::SMS_ERR_STATE_WN, ...).
 */
#define SMS_MULTI_IDENTITY_COUNT (7 + 6 * SMS_MULTI_MAX_AXES)

/** @brief How the axes are coordinated (values stable: FMU parameter). */
typedef enum sms_sync {
    SMS_SYNC_PHASE = 0,      /**< one common profile: straight lines, common start and arrival */
    SMS_SYNC_INDEPENDENT = 1, /**< each axis time-optimal on its own */
    SMS_SYNC_TIME = 2,       /**< per-axis plans from any state (q, v, a) to any target state,
                                  all arriving on one common sample (curved paths) */
    SMS_SYNC_TIME_IF_NECESSARY = 3, /**< as ::SMS_SYNC_TIME for an axis whose target moves
                                  (velocity or acceleration not 0); one whose target is at rest
                                  takes its own time-optimal plan */
    SMS_SYNC_NONE = 4        /**< per-axis plans, each axis time-optimal on its own */
} sms_sync;

/** @brief Does the mode plan each axis from any state (::SMS_SYNC_TIME,
 * ::SMS_SYNC_TIME_IF_NECESSARY, ::SMS_SYNC_NONE, sms_multi_generator_step_target())? */
#define SMS_SYNC_PER_AXIS_PLANS(sync) ((sync) >= SMS_SYNC_TIME && (sync) <= SMS_SYNC_NONE)

/**
 * @brief A target vector of the per-axis plan modes (sms_multi_generator_step_target()).
 *
 * | field | valid range (sms_multi_generator_check_target()) |
 * |-------|---------------------------------------------------|
 * | position[i] | finite; within [qmin[i], qmax[i]] when axis i has position limits (else ::SMS_ERR_POSITION_LIMIT) |
 * | velocity[i] | finite, \|v\| <= vmax[i]; 0 when axis i has position limits |
 * | acceleration[i] | finite, \|a\| <= amax[i], v -+ a\|a\|/(2 jmax[i]) within +-vmax[i]; 0 when axis i has position limits |
 * | sync[i] | 0 (the generator's mode) or ::SMS_SYNC_TIME, ::SMS_SYNC_TIME_IF_NECESSARY, ::SMS_SYNC_NONE |
 * | minimum_duration | finite, >= 0 [s], below 2^50 samples |
 *
 * Axis i is synchronised when its mode (sync[i], or the generator's when 0) is
 * ::SMS_SYNC_TIME, or ::SMS_SYNC_TIME_IF_NECESSARY with velocity[i] or acceleration[i] not 0.
 * The common arrival N (samples from the re-plan) is the smallest at or after every axis's
 * own earliest arrival (all axes but those of ::SMS_SYNC_NONE) and minimum_duration, at which
 * every synchronised axis has a motion of exactly N samples; the other axes move time-optimally.
 */
typedef struct sms_multi_target {
    /** target position of axis i (units of axis i), finite; slots >= n_axes are not read */
    sms_real position[SMS_MULTI_MAX_AXES];
    /** velocity of axis i at its arrival (units per s), \|v\| <= vmax[i]; 0 ends at rest */
    sms_real velocity[SMS_MULTI_MAX_AXES];
    /** acceleration of axis i at its arrival (units per s^2), \|a\| <= amax[i], and the
     * velocity it brings within +-vmax[i] (the table above) */
    sms_real acceleration[SMS_MULTI_MAX_AXES];
    /** synchronisation of axis i for this target: 0 (the generator's mode), ::SMS_SYNC_TIME,
     * ::SMS_SYNC_TIME_IF_NECESSARY or ::SMS_SYNC_NONE */
    int sync[SMS_MULTI_MAX_AXES];
    /** [s] of the synchronised axes, finite, >= 0, below 2^50 Ts; 0: as fast as possible
     * (the other axes ignore it) */
    sms_real minimum_duration;
} sms_multi_target;

/** @brief One axis's running plan in the per-axis plan modes (read-only). */
typedef struct sms_multi_axis_plan {
    sms_plan plan;           /**< the single-axis plan to the target state (trajectory.h) */
    sms_real q0;             /**< position it started from (its sample 0) */
    sms_real v0;             /**< velocity it started from */
    sms_real a0;             /**< acceleration it started from */
    sms_real tmin;           /**< the minimum duration it was planned with [s] (0: none) */
    size_t k;                /**< samples since its first sample */
} sms_multi_axis_plan;

/**
 * @brief Limits of the multi-axis generator.
 *
 * | field | valid range |
 * |-------|-------------|
 * | n_axes | 1 .. ::SMS_MULTI_MAX_AXES |
 * | vmax[i], amax[i], jmax[i], i < n_axes | finite, > 0 (units of axis i per s, s^2, s^3), and a move of axis i can reach vmax[i] (sms_multi_generator_reach()) |
 * | sync | an ::sms_sync |
 * | n_stages[i], i < n_axes | 0 (no filter) .. ::SMS_CHAIN_MAX_STAGES |
 * | stages[i] | n_stages[i] valid stage configs (config.h), or NULL when n_stages[i] = 0 |
 * | align | 0 (off) or 1: pad every axis to the common lag (below) |
 * | qmin[i], qmax[i], i < n_axes | both 0 (axis i has no position limits) or finite with qmin[i] < qmax[i] (as ::sms_real too), each at most 2^-4 of the largest ::sms_real in magnitude (sms_generator_reach() of the axis) |
 *
 * Position limits (ruckig's min_position and max_position per DoF): an axis with qmin[i],
 * qmax[i] set reports q within [qmin[i], qmax[i]] at every sample, in every mode. Its targets
 * rest inside: a position outside is refused with ::SMS_ERR_POSITION_LIMIT (naming the axis),
 * a velocity or acceleration other than 0 with ::SMS_ERR_TARGET_VELOCITY or
 * ::SMS_ERR_TARGET_ACCELERATION; sms_multi_generator_step() keeps such an axis's previous
 * target position, as for a non-finite one, and sms_multi_generator_reset() to a position
 * outside changes nothing. Init rests each such axis at 0, or at its limit nearer 0.
 * - ::SMS_SYNC_PHASE, ::SMS_SYNC_INDEPENDENT: a move from rest to a target inside stays on
 *   the segment between two points inside. A group (all axes in phase, one in independent)
 *   with an axis under position limits does not blend a target that changes mid-motion: the
 *   new target waits for the running move's arrival (as one seen during the stop transition
 *   does) and starts from rest there, so every move is one from rest to rest inside.
 * - Per-axis plan modes: each bounded axis plans by the single-axis generator's rule
 *   (trajectory.h, ::sms_generator_config): its time-optimal motion when it stays inside,
 *   else the brake to rest, a rest until the next sample and the move from there; the first
 *   whose continuous extremes stay inside to 16 u (|qmin[i]| + |qmax[i]|), q then held to the
 *   limits. A synchronised bounded axis whose motion of the common duration would cross (the
 *   stretched move after its brake) takes its move without the stretch and arrives earlier.
 *   When no plan of some bounded axis stays inside (a state whose brake would cross), the
 *   running plans of every axis go on and the re-plan is tried on the next sample;
 *   sms_multi_generator_start() refuses such a state, or a q outside, with
 *   ::SMS_ERR_POSITION_LIMIT naming the axis.
 * Last in the struct: a zeroed or shorter initialiser has none.
 *
 * Vibration stages: axis i filters each of its four outputs q, v, a, j through its own copy
 * of the chain stages[i][0 .. n_stages[i]) (the stages of sms_chain_init(), the same configs
 * the single-axis chain takes). A linear filter applied to every coordinate of a straight
 * move q(t) = p + s(t) d gives p + H(s) d: the same stages on every axis keep a straight move
 * straight (every axis is delayed and smoothed alike); different stages per axis bend it.
 * A zero-initialised config has no stages.
 *
 * Alignment (align = 1): each axis's chain delays a constant-speed motion by its lag D_i
 * (align.h); different lags put the axes of a straight move at different points of it, so the
 * path leaves the line at constant speed by about v |D_i - D_j| Ts. With align = 1 every
 * axis's q, v, a, j also pass through a fractional delay (sms_delay) of D - D_i samples,
 * D = max_i D_i (axes without stages: D), so every axis lags by exactly D: a straight
 * constant-speed segment stays on the line to rounding (the different smoothing of the
 * stages still bends the accelerations; docs/align.md has both). sms_multi_generator_lag()
 * reports D.
 */
typedef struct sms_multi_generator_config {
    size_t n_axes;                      /**< 1 .. ::SMS_MULTI_MAX_AXES */
    double vmax[SMS_MULTI_MAX_AXES];    /**< velocity bound of each axis, finite, > 0 */
    double amax[SMS_MULTI_MAX_AXES];    /**< acceleration bound of each axis, finite, > 0 */
    double jmax[SMS_MULTI_MAX_AXES];    /**< jerk bound of each axis, finite, > 0 */
    sms_sync sync;                      /**< how the axes are coordinated (::sms_sync) */
    const sms_stage_config *stages[SMS_MULTI_MAX_AXES]; /**< each axis's vibration stages */
    size_t n_stages[SMS_MULTI_MAX_AXES]; /**< how many, 0 .. ::SMS_CHAIN_MAX_STAGES */
    int align;                          /**< 1: delay every axis to the common lag */
    double qmin[SMS_MULTI_MAX_AXES];    /**< lower position limit of each axis (0 and qmax 0: none) */
    double qmax[SMS_MULTI_MAX_AXES];    /**< upper position limit of each axis (0 and qmin 0: none) */
} sms_multi_generator_config;

/** @brief One running move of a group of axes (all axes in phase mode, one in independent). */
typedef struct sms_multi_move {
    sms_real T1;       /**< first velocity transition: length [s] */
    sms_real rho1;     /**< its jerk-phase fraction, in (0, 1/2] */
    sms_real tau;      /**< cruise [s] */
    sms_real T2;       /**< stop transition: length [s] */
    sms_real rho2;     /**< its jerk-phase fraction */
    sms_real off;      /**< move time [s] of its first sample (k = 0), in [0, Ts) */
    sms_real seen;     /**< move time at which the pending target appeared */
    size_t k;          /**< samples since the first sample */
    size_t k_end;      /**< sample of arrival */
    int active;        /**< 1 while moving */
    int pending;       /**< 1 while the target differs from the move's goal */
    int refused;       /**< 1 while the held target is one whose move could not be represented
                            (it is not tried again until the target changes) */
} sms_multi_move;

/**
 * @brief Online multi-axis generator.
 *
 * A move of a group of axes (all axes in ::SMS_SYNC_PHASE, each axis alone in
 * ::SMS_SYNC_INDEPENDENT) starts at position p with velocity V and zero acceleration and has
 * three phases: a velocity transition V -> W of length T1, a cruise at W for tau, and a stop
 * transition W -> 0 of length T2. A transition from V_a to V_b is a straight line in velocity
 * space with one normalised S-curve for every axis:
 *   v(t) = V_a + (V_b - V_a) F(t / T),   F(0) = 0, F(1) = 1,
 * F' piecewise linear (jerk +c, 0, -c over fractions rho, 1 - 2 rho, rho of T; rho <= 1/2).
 * For a change dV the shortest such transition follows from the scaled unit limits
 *   A = min_i amax_i / |dV_i|,  J = min_i jmax_i / |dV_i|:
 *   T = 1/A + A/J, rho = (A/J)/T  if A^2 <= J;   T = 2/sqrt(J), rho = 1/2 otherwise,
 * and then |a_i| <= |dV_i| A <= amax_i, |j_i| <= |dV_i| J <= jmax_i; a longer T with the same rho
 * only lowers them. The transition is point-symmetric, so it covers (V_a + V_b) T / 2.
 * Landing on the target B: with kappa = T1/2 + tau + T2/2,
 *   W kappa = B - p - V T1/2,
 * so W is parallel to u = B - p - V T1/2. Given T1, kappa is the smallest value with
 * |W_i| <= vmax_i and tau >= 0 (T2 = the shortest stop transition of W); the move is feasible
 * when the shortest transition V -> W fits in T1, i.e. when the excess T(W - V) - T1 (a
 * continuous function of T1) is <= 0. T1 is the feasible root of the excess in
 * [T(V), T(2 vmax)] (the upper end is always feasible), found by the Illinois variant of
 * regula falsi (Dowell and Jarratt 1971) with a bisection every fourth step, down to
 * neighbouring reals: about 5 evaluations per re-plan on random moves. The arrival is then
 * moved onto the next sample by lengthening the cruise (W shrinks towards 0, which keeps
 * every bound: the new change W - V is a convex combination of two that fit T1, and what fits
 * T1 is a convex set, docs/multi-axis.md), and the output is set exactly to B at the arrival
 * sample. A planned end within 2 eps of the duration after a sample arrives on that sample
 * instead (a whole number of samples computed a rounding above): it raises W, v and the
 * stop's a, j by up to 4 eps, and the first transition's a, j by up to 8 eps, its jerk
 * fraction then chosen to fit T1 (rho = min(1/2, A/(J T1)) when the shortest transition of
 * W - V is longer than T1), so reported v, a, j stay within L (1 + 16 eps).
 *
 * From rest (V = 0) this is the time-optimal jerk-limited straight move, u = B - p and the
 * path parameter s in [0, 1] has the limits min_i vmax_i/|d_i|, min_i amax_i/|d_i|,
 * min_i jmax_i/|d_i| (d = B - p): every axis starts and arrives on the same sample, q stays on
 * the segment from p to B, and the duration is the time-optimal one rounded up to the sample
 * grid. (ruckig's Synchronization::Phase gives the same duration when it finds a
 * phase-synchronised profile; when it does not, it falls back to a shorter, curved
 * time-synchronised move.)
 *
 * A target that changes mid-motion is blended: the running move continues to the end of its
 * first transition (or, if the change arrives later, to the current sample during the cruise),
 * where the acceleration is zero; a new move starts there from (p, V) towards the new target:
 * one velocity transition straight from V to the new cruise velocity, cruise, stop. The corner
 * between the two straight segments is cut by that transition (so the path leaves the straight
 * lines there); no axis exceeds any limit, because each transition keeps them by
 * construction and transitions never overlap. A change seen during the stop transition waits
 * for the arrival and then starts from rest. Every output q, v, a, j is the exact value of
 * this continuous profile at the sample instant (the jerk at a jump is the right limit), so
 * the backward differences dq/Ts, d2q/Ts^2, d3q/Ts^3 are averages of v, a, j and keep the
 * limits too, to the rounding of the positions for any move length (each phase is evaluated
 * by its own time, the stop by the whole samples left; the rule and its numbers are in
 * docs/multi-axis.md). Per-sample work is O(n_axes); a re-plan costs a bounded number (at most 200,
 * typically 5) of O(n_axes) evaluations.
 *
 * Vibration stages (::sms_multi_generator_config): after the profile, axis i's q, v, a, j each
 * pass through a copy of its chain, y = H(x) per signal; the filtered v, a, j are the
 * derivatives of the filtered q at the same instants (a filter of samples commutes with the
 * derivative of the continuous profile). The stage structs and delay lines live in caller
 * memory sized by sms_multi_generator_memory().
 */
typedef struct sms_multi_generator {
    size_t n_axes;                       /**< axes in use */
    sms_sync sync;                       /**< as configured */
    double Ts;                           /**< sample period [s] */
    sms_real Ts_signal;                  /**< Ts in signal precision */
    sms_real vmax[SMS_MULTI_MAX_AXES];   /**< velocity bounds in signal precision */
    sms_real amax[SMS_MULTI_MAX_AXES];   /**< acceleration bounds */
    sms_real jmax[SMS_MULTI_MAX_AXES];   /**< jerk bounds */
    sms_real target[SMS_MULTI_MAX_AXES]; /**< latest valid target */
    sms_real goal[SMS_MULTI_MAX_AXES];   /**< target of the running move */
    sms_real p[SMS_MULTI_MAX_AXES];      /**< position at the running move's start */
    sms_real V[SMS_MULTI_MAX_AXES];      /**< velocity at its start */
    sms_real W[SMS_MULTI_MAX_AXES];      /**< its cruise velocity */
    sms_multi_move move[SMS_MULTI_MAX_AXES]; /**< phase: move[0]; independent: move[i] */
    size_t dropped; /**< target vectors (of a group) dropped since init or the last reset
                         (read-only; a diagnostic count, not part of the saved state) */
    /** vibration stages of axis i, signal m (n_stages 0: none), in caller memory */
    sms_chain chain[SMS_MULTI_MAX_AXES][SMS_MULTI_SIGNALS];
    double identity[SMS_MULTI_IDENTITY_COUNT]; /**< configuration and Ts it was built for */
    int aligned;                        /**< config.align */
    double axis_lag[SMS_MULTI_MAX_AXES]; /**< lag of axis i's chain [samples] (0: none) */
    double lag;                         /**< the common lag D when aligned, else max axis_lag */
    /** alignment delays of axis i, signal m (aligned only), rings in caller memory */
    sms_delay delay[SMS_MULTI_MAX_AXES][SMS_MULTI_SIGNALS];
    /* per-axis plan modes (SMS_SYNC_PER_AXIS_PLANS) */
    sms_multi_target request;   /**< the last target vector given, as given */
    sms_multi_target aim;       /**< the target of the running plans */
    sms_multi_axis_plan axis[SMS_MULTI_MAX_AXES]; /**< each axis's running plan */
    int plan_pending;           /**< 1: a valid new target waits for this sample's re-plan */
    int plan_refused;           /**< 1 while the held target's motion could not be formed */
    /* position limits (::sms_multi_generator_config qmin, qmax) */
    int bounded[SMS_MULTI_MAX_AXES];     /**< 1: axis i has position limits */
    sms_real qmin[SMS_MULTI_MAX_AXES];   /**< its lower limit in signal precision */
    sms_real qmax[SMS_MULTI_MAX_AXES];   /**< its upper limit */
    sms_real qtol[SMS_MULTI_MAX_AXES];   /**< how far a plan's computed extremes may pass them:
                                              16 u (|qmin| + |qmax|) */
} sms_multi_generator;

/**
 * @brief Check, in O(n_axes), that every axis's limits let a move reach its vmax at Ts (what
 * init checks after each limit is finite and > 0).
 *
 * Per axis the planner forms the quantities of the single-axis planner with linear jerk
 * ramps: velocity changes J dv (|dv| <= 2 vmax_i), squares of accelerations up to
 * ap = min(amax_i, sqrt(vmax_i jmax_i)), durations up to about that of the move of axis i
 * from rest to vmax_i and back to rest, distances up to a few times its distance.
 * With h and T the distance and duration of that move, axis i is feasible when, in this
 * order:
 * 1. sms_generator_reach() accepts vmax[i], amax[i], jmax[i] with ::SMS_PROFILE_POLYNOMIAL
 *    (each limit in [MIN, MAX/16], 16 vmax jmax <= MAX, T/Ts <= 2^50, ap^2 >= MIN/eps,
 *    T >= MIN and h in [MIN/eps, MAX/16]);
 * 2. amax/vmax, jmax/vmax, amax/h, jmax/h <= 2^56 ("amax/vmax", ..., "jmax/h"): the planner
 *    caps its unit limits amax/|dV|, jmax/|d| at 2^60, which would lengthen the move to
 *    vmax, its stop or its reversal beyond the plan;
 * 3. (16 T)^2 <= MAX ("the duration to reach vmax, squared"), (amax/(16 h))^2 >= MIN/eps
 *    ("(amax/h)^2") and jmax/(16 h) >= MIN/eps ("jmax/h"): the landing squares durations and
 *    unit accelerations of displacements up to 16 h.
 * A phase-synchronised move scales every axis's limits by the same path direction
 * (limit_i/|d_i|, the minimum over axes), so it adds no condition: a random search over the
 * whole range of the type, both sync modes, found no accepted set that drops the move of any
 * axis to h, h/2, 3 h, 1e-9 h, eps^1.5 h (together, alone, mixed) or the reversal from full
 * speed (docs/multi-axis.md). Outside the region no move of that axis that reaches vmax[i]
 * can be planned, e.g. vmax = 1, amax = 1e-30, jmax = 1e-300 at Ts = 1 ms: reaching vmax takes
 * 4 sqrt(vmax/jmax) = 4e150 s.
 * @param reach  out (may be NULL): for the first refused axis, the quantity out of range,
 *               its arguments (e.g. "vmax, jmax", of that axis), value and bound; for an
 *               accepted set, the move of the last axis
 * @param axis   out (may be NULL): the refused axis (else 0)
 * @return ::SMS_OK, ::SMS_ERR_NULL, ::SMS_ERR_ORDER (n_axes), ::SMS_ERR_SAMPLE_PERIOD,
 *         ::SMS_ERR_LIMIT.
 * @param config the axes' limits (sync and stages are not read)
 * @param Ts     sample period [s], finite, > 0,
 *               at most ::SMS_TS_MAX (a larger one: ::SMS_ERR_SAMPLE_PERIOD_RANGE)
 */
SMS_API sms_status sms_multi_generator_reach(const sms_multi_generator_config *config, double Ts,
                                             sms_generator_reach_info *reach, size_t *axis);
/**
 * @brief Caller memory a configuration needs (size query, O(stages) closed form).
 * @param config   limits and stages (see ::sms_multi_generator_config)
 * @param Ts       sample period [s], finite and > 0,
 *                 at most ::SMS_TS_MAX (a larger one: ::SMS_ERR_SAMPLE_PERIOD_RANGE)
 * @param n_stage_structs receives the ::sms_stage count: 4 sum_i n_stages[i] (0: no stages)
 * @param n_cells  receives the ::sms_memory_cell count of the stages' instances, tap tables
 *                 and delay lines: 4 sum_i sms_chain_memory_size(stages[i]), and with align
 *                 the alignment delays' rings (4 (floor(D - D_i) + 2) reals per axis)
 * @param bad_axis if not NULL, receives the offending axis (else 0)
 * @return as sms_multi_generator_init(): the limits and every stage config are validated.
 */
SMS_API sms_status sms_multi_generator_memory(const sms_multi_generator_config *config, double Ts,
                                              size_t *n_stage_structs, size_t *n_cells,
                                              size_t *bad_axis);
/**
 * @brief Validate the limits, Ts and the stages and build the stages into caller memory; the
 * generator rests at 0 on every axis.
 * @param g       caller-owned generator
 * @param config  limits and stages (see ::sms_multi_generator_config for ranges)
 * @param Ts      sample period [s], finite and > 0,
 *                at most ::SMS_TS_MAX (a larger one: ::SMS_ERR_SAMPLE_PERIOD_RANGE)
 * @param stages  caller memory of n_stage_structs ::sms_stage (sms_multi_generator_memory());
 *                may be NULL when no axis has stages
 * @param n_stage_structs its length
 * @param memory  caller memory of n_cells cells for the stages (may be NULL if 0)
 * @param n_cells its length
 * @param bad_axis if not NULL, receives the offending axis for ::SMS_ERR_LIMIT and stage
 *                errors (else 0)
 * @return ::SMS_OK, ::SMS_ERR_NULL, ::SMS_ERR_ORDER (n_axes out of range, or n_stages[i]
 *         above ::SMS_CHAIN_MAX_STAGES), ::SMS_ERR_SAMPLE_PERIOD, ::SMS_ERR_LIMIT (a limit not
 *         finite and > 0, or limits with which no move of an axis can reach its vmax:
 *         sms_multi_generator_reach() names the axis and the quantity), ::SMS_ERR_KIND
 *         (sync), the first failing stage config's status (its axis in bad_axis),
 *         ::SMS_ERR_TOO_LONG, ::SMS_ERR_BUFFER_TOO_SMALL (stages or memory shorter than
 *         sms_multi_generator_memory() says). g, stages and memory untouched on error.
 */
SMS_API sms_status sms_multi_generator_init(sms_multi_generator *g,
                                            const sms_multi_generator_config *config, double Ts,
                                            sms_stage *stages, size_t n_stage_structs,
                                            sms_memory_cell *memory, size_t n_cells,
                                            size_t *bad_axis);
/** @brief Rest at position[0 .. n_axes-1] (targets and output there; the stages settled:
 * q's chain as if its input had been the position forever, v, a, j's at 0); NULL: at 0 (an
 * axis with position limits that exclude 0: at the nearer limit). A position outside an
 * axis's position limits changes nothing.
 * @param g      the generator, built by sms_multi_generator_init()
 * @param position n_axes finite positions, or NULL
 */
SMS_API void sms_multi_generator_reset(sms_multi_generator *g, const sms_real *position);
/**
 * @brief Advance one sample with the current target vector (n_axes values; a non-finite
 * component keeps that axis's previous target) and write out[4 i + m] = q, q', q'', q''' of
 * axis i at this instant (after the axis's stages, if any). A target vector whose move cannot
 * be represented in ::sms_real is dropped: a displacement B - p that is not finite, a move
 * that lasts more than 2^52 samples (e.g. |d| = 1e300 with vmax = 1) or whose duration in
 * seconds overflows ::sms_real (float: |d_i|/vmax_i above FLT_MAX). Within feasible limits
 * (sms_multi_generator_reach()) nothing else drops a move, however far beyond the distance
 * to reach vmax it goes: a move whose cruise reaches vmax is landed on kappa = max_i
 * |u_i|/vmax_i without forming the unit limits amax_i/|u_i|, jmax_i/|u_i|, which underflow
 * for long moves. A dropped target leaves the axes (of the group) at their previous goal, so
 * every output stays finite, and it is not tried again until the target vector changes (one
 * attempt, not one per sample). The group's `move[].refused` is 1 while its held target is dropped, and `dropped` counts
 * the drops.
 * @param g      the generator, built by sms_multi_generator_init()
 * @param target n_axes target positions
 * @param out    receives 4 n_axes values
 */
SMS_API void sms_multi_generator_step(sms_multi_generator *g, const sms_real *target,
                                      sms_real *out);
/** @brief The lag of the output [s]: with align, the common lag D Ts of every axis; without,
 * the largest axis's (each axis i lags by axis_lag[i] Ts). 0 without stages. O(1).
 * @param g      the generator (read only)
 * @return the lag [s], >= 0
 */
SMS_API double sms_multi_generator_lag(const sms_multi_generator *g);
/** @brief n samples: targets[k n_axes + i] in, out[(k n_axes + i) 4 + m] out.
 * @param g      the generator, built by sms_multi_generator_init()
 * @param targets n rows of n_axes target positions
 * @param n      number of samples, any
 * @param out    receives 4 n_axes n values
 */
SMS_API void sms_multi_generator_process(sms_multi_generator *g, const sms_real *targets,
                                         size_t n, sms_real *out);
/** @brief 1 while any axis's profile is moving or waiting for a new target, else 0 (stages'
 * outputs settle sms_chain_length() samples later; a notch's only asymptotically).
 * @param g      the generator (read only)
 * @return 1 or 0
 */
SMS_API int sms_multi_generator_busy(const sms_multi_generator *g);
/**
 * @brief Is `target` one the generator can plan to? O(n_axes), writes nothing but *axis.
 * In ::SMS_SYNC_PHASE and ::SMS_SYNC_INDEPENDENT only positions at rest are planned: a
 * velocity or acceleration not 0 is refused with its status, a sync[i] not 0 with
 * ::SMS_ERR_TARGET_SYNC.
 * @param g      the generator, built by sms_multi_generator_init() (read only)
 * @param target the target vector: n_axes entries of each array are read
 * @param axis  out (may be NULL): the first refused axis (else 0)
 * @return ::SMS_OK; ::SMS_ERR_NULL (g or target); ::SMS_ERR_TARGET_POSITION, ::SMS_ERR_TARGET_VELOCITY,
 *         ::SMS_ERR_TARGET_ACCELERATION (the ranges of ::sms_multi_target, the limits as
 *         ::sms_real holds them); ::SMS_ERR_POSITION_LIMIT (a position outside its axis's
 *         [qmin, qmax]); ::SMS_ERR_TARGET_SYNC; ::SMS_ERR_DURATION
 *         (minimum_duration).
 */
SMS_API sms_status sms_multi_generator_check_target(const sms_multi_generator *g,
                                                    const sms_multi_target *target,
                                                    size_t *axis);
/**
 * @brief Advance one sample towards a target state vector and write out[4 i + m] as
 * sms_multi_generator_step() does.
 *
 * Per-axis plan modes: on the sample the target differs from the running plans' (field for
 * field), every axis re-plans from its exact state (q, v, a) there with the single-axis
 * planner of sms_generator_step_target() (Berscheid and Kroeger 2021 profile families; a
 * motion of a given duration: the convex combination of the two that end farthest either
 * way). The time-optimal arrivals N_i (whole samples) give N = max over the axes not of
 * ::SMS_SYNC_NONE; every synchronised axis (::sms_multi_target) is planned to arrive exactly
 * on sample N; where a duration is blocked for an axis (some moving targets cannot be
 * reached in some durations above the optimum) its planner returns the next N' that it can
 * reach, N becomes N' and the synchronised axes are planned again (a few rounds at most).
 * Each axis's samples are the exact values of its continuous plan, so every axis keeps its
 * vmax, amax, jmax at every sample and in the sampled differences
 * (docs/sampled-limits.md), and lands exactly on its target. A target whose motion cannot be
 * formed (a value not finite, more than 2^52 samples, no common duration) is dropped, the
 * running plans go on; an invalid one (sms_multi_generator_check_target()) is ignored.
 * sms_multi_generator_step() in these modes is this with the positions at rest.
 *
 * ::SMS_SYNC_PHASE and ::SMS_SYNC_INDEPENDENT: the positions of a valid target, as
 * sms_multi_generator_step().
 * @param g      the generator, built by sms_multi_generator_init()
 * @param target the target state vector (n_axes entries of each array read); an invalid one
 *               keeps the previous target
 * @param out    receives 4 n_axes values
 */
SMS_API void sms_multi_generator_step_target(sms_multi_generator *g,
                                             const sms_multi_target *target, sms_real *out);
/** @brief n samples: targets[k] in, out[(k n_axes + i) 4 + m] out; equal, bit for bit, to n
 * calls of sms_multi_generator_step_target().
 * @param g       the generator, built by sms_multi_generator_init()
 * @param targets n target vectors, one per sample
 * @param n       number of samples, any
 * @param out     receives 4 n_axes n values
 */
SMS_API void sms_multi_generator_process_targets(sms_multi_generator *g,
                                                 const sms_multi_target *targets, size_t n,
                                                 sms_real *out);
/**
 * @brief Per-axis plan modes: continue from the motion state (q[i], v[i], a[i]) of every axis:
 * the generator is there now, on the first sample of the plans to `target` (as
 * sms_multi_generator_step_target() plans them; NULL: every axis brakes to rest at once,
 * time-optimally on its own, its target then the stop's position), and its next step is the
 * plans' next sample. The stages (if any) keep their history.
 * @param g      the generator, built by sms_multi_generator_init(); unchanged on error
 * @param q      n_axes positions, finite
 * @param v      n_axes velocities, \|v[i]\| <= vmax[i]
 * @param a      n_axes accelerations, \|a[i]\| <= amax[i] and \|v[i] + a[i]\|a[i]\|/(2 jmax[i])\|
 *               <= vmax[i]
 * @param target the target vector to plan to (the ranges of ::sms_multi_target), or NULL
 * @param axis  out (may be NULL): the refused axis (else 0)
 * @return ::SMS_OK; ::SMS_ERR_NULL; ::SMS_ERR_KIND (not a per-axis plan mode);
 *         ::SMS_ERR_TARGET_POSITION (q not finite); ::SMS_ERR_TARGET_VELOCITY (v not finite or
 *         |v| > vmax); ::SMS_ERR_TARGET_ACCELERATION (a not finite, |a| > amax or
 *         |v + a|a|/(2 jmax)| > vmax: no plan can start there), each to ::SMS_LIMIT_RTOL; a
 *         status of sms_multi_generator_check_target() for `target`;
 *         ::SMS_ERR_POSITION_LIMIT (position limits: q[i] outside [qmin[i], qmax[i]], or no
 *         plan of axis i from its state stays inside, its brake to rest included);
 *         ::SMS_ERR_TOO_LONG (the motion cannot be formed). Nothing changed on error.
 */
SMS_API sms_status sms_multi_generator_start(sms_multi_generator *g, const sms_real *q,
                                             const sms_real *v, const sms_real *a,
                                             const sms_multi_target *target, size_t *axis);
/** @brief Samples from the last one output until every axis has reached its target state
 * (0 once reached). O(n_axes). Per-axis plan modes; 0 in the others.
 * @param g      the generator (read only)
 * @return the samples left, the largest of sms_multi_generator_axis_arrival() over the axes
 */
SMS_API uint64_t sms_multi_generator_arrival(const sms_multi_generator *g);
/** @brief The same for one axis: samples until it reaches its target state (0 once reached,
 * for an axis out of range, and in the modes without per-axis plans). O(1).
 * @param g      the generator (read only)
 * @param axis   the axis, 0 .. n_axes - 1
 * @return the samples left
 */
SMS_API uint64_t sms_multi_generator_axis_arrival(const sms_multi_generator *g, size_t axis);
/**
 * @brief Up to n steps with the same targets (target[0 .. n_axes-1]), at a cost bounded
 * whatever n: the state and last output (out, 4 n_axes values) of that many calls of
 * sms_multi_generator_step(), bit for bit.
 *
 * The profile alone is advanced in closed form between the samples on which a move changes
 * (a new target, its plan or drop: at most two per group; a move's sample is a function of
 * its index), O(groups log n). With vibration stages, S = the largest
 * sms_chain_settle_bound() of the axes' chains: when the profile rests for the last S + 2
 * samples, the stages are put into their absorbed state (sms_chain_settle(), O(memory));
 * otherwise the profile and the stages' phase jump to the last S + 2 samples, which are
 * stepped: FIR stages then hold exactly their last inputs; a notch enters those samples from
 * its stale state, a transient its settle bound decays from the largest state past the
 * smallest subnormal, so the result is n steps to rounding (bit for bit in the tests, which
 * allow 8 eps of each value's scale).
 * @return the steps done: n, or 0 (a notch that does not decay, S >= 1e15).
 * @param g      the generator, built by sms_multi_generator_init()
 * @param target n_axes held target positions
 * @param n      steps, any (0: nothing changes, out untouched)
 * @param out    receives the last step's 4 n_axes values
 */
SMS_API uint64_t sms_multi_generator_hold(sms_multi_generator *g, const sms_real *target,
                                          uint64_t n, sms_real *out);
/**
 * @brief Time-optimal phase-synchronised rest-to-rest duration for a displacement vector:
 * the jerk-limited straight move under every axis's limits (continuous time, no grid).
 * Computed from the move's time constants (the longest |d_i|/vmax_i, sqrt(|d_i|/amax_i),
 * cbrt(|d_i|/jmax_i) of the axes), never from the unit limits vmax_i/|d_i|, ..., which over-
 * or underflow for long or short moves: over 200,000 random sets of 3 axes with limits and
 * displacements in [1e-300, 1e300] it is within 8.8e-16 (relative) of the closed form
 * evaluated in extended precision.
 * @param config  n_axes in 1 .. ::SMS_MULTI_MAX_AXES; vmax[i], amax[i], jmax[i] finite, > 0
 *                (sync and the stages are not read)
 * @param delta   n_axes displacements (finite; all zero gives 0)
 * @param T       receives the duration [s]; untouched on error
 * @return ::SMS_OK, ::SMS_ERR_NULL, ::SMS_ERR_ORDER, ::SMS_ERR_LIMIT (limits or delta),
 *         ::SMS_ERR_TOO_LONG (the duration exceeds the largest double, e.g. vmax = 4.9e-324
 *         over 1e-6).
 */
SMS_API sms_status sms_multi_phase_duration(const sms_multi_generator_config *config,
                                            const double *delta, double *T);

/** @brief Number of doubles sms_multi_generator_get_state() writes:
 * ::SMS_MULTI_IDENTITY_COUNT (the configuration identity) + 5 n_axes (target, goal, p, V, W)
 * + 12 per move (n_axes moves, or 1 in phase mode) + the stages' states (sms_chain_state_count()
 * of each chain: axis by axis, q, v, a, j; every stage state with its own stage identity)
 * + with align, the alignment delays' states (sms_delay_state_count(), axis by axis, q, v, a,
 * j).
 * @param g      the generator (read only)
 * @return the count
 */
SMS_API size_t sms_multi_generator_state_count(const sms_multi_generator *g);
/** @brief Write the state (sms_multi_generator_state_count() doubles, layout above) to dst.
 * @param g      the generator (read only)
 * @param dst    sms_multi_generator_state_count() doubles
 */
SMS_API void sms_multi_generator_get_state(const sms_multi_generator *g, double *dst);
/**
 * @brief Restore a saved state into a generator with the same configuration.
 * @return ::SMS_OK, ::SMS_ERR_NULL; ::SMS_ERR_STATE_FORMAT .. ::SMS_ERR_STATE_STAGES (see
 * ::SMS_MULTI_IDENTITY_COUNT) if it was saved by another configuration (checked first, whatever
 * n), or a stage's identity status for a stage of another configuration; ::SMS_ERR_STATE (n
 * differs, a value is non-finite, a count is not a whole number, a flag is not 0/1,
 * k > k_end, rho outside (0, 1/2], a duration negative, a start or cruise velocity beyond its
 * axis's vmax (1 + ::SMS_LIMIT_RTOL), the tolerance of the reported values, or
 * a stage state that does not fit its stage); nothing written on error.
 * @param g      the generator, built by sms_multi_generator_init(); untouched on error
 * @param src    the saved state
 * @param n      its length in doubles, sms_multi_generator_state_count()
 */
SMS_API sms_status sms_multi_generator_set_state(sms_multi_generator *g, const double *src,
                                                 size_t n);
/** @brief What sms_multi_generator_set_state() would return, writing nothing.
 * @param g      the generator (read only)
 * @param src    the saved state
 * @param n      its length in doubles
 * @return what sms_multi_generator_set_state() would return
 */
SMS_API sms_status sms_multi_generator_check_state(const sms_multi_generator *g,
                                                   const double *src, size_t n);
/**
 * @brief The largest |value| that axis `axis`'s chain for signal `signal` can output in a run:
 * the bound a restored state's values behind that chain (the alignment delays' rings, an
 * importer's last reported outputs) are held to, so that every state the generator reached
 * itself is accepted.
 *
 * The chain's input is the axis's position (signal 0, within the chain's finite input range
 * sms_chain_input_max()) or the profile's velocity, acceleration or jerk (signals 1, 2, 3,
 * within vmax, amax, jmax times 1 + ::SMS_LIMIT_RTOL, the tolerance of the reported values,
 * the limits as ::sms_real). Its stages map x - rest to y - rest with gain at most
 * G_0 ... G_{n-1} (sms_stage_gain_bound()) and can overshoot their input's range (shapers with
 * negative impulses, notches, corrected smoothers), so the result is
 * (1 + 2 G_0 ... G_{n-1}) times that input range, times 1 + 2^-20 for the chain's rounding
 * (relative, far above the rounding of any chain in double or float, whatever long double
 * is); without stages, the input range itself (the signal passes through unchanged).
 * @param g       the generator, built by sms_multi_generator_init() (read only)
 * @param axis    the axis, 0 .. n_axes - 1
 * @param signal  0 position [m], 1 velocity [m/s], 2 acceleration [m/s^2], 3 jerk [m/s^3]
 *                (in the units of the configuration's limits)
 * @return the bound, > 0, in the signal's unit (+inf only if a stage's gain bound is); 0 if
 *         g is NULL or axis or signal is out of range
 */
SMS_API double sms_multi_generator_output_range(const sms_multi_generator *g, size_t axis,
                                                size_t signal);
/** @brief After copying g, its stages and its memory elsewhere (same layout), point the
 * copy's chains at the copy's stages and memory.
 * @param g      the copied generator
 * @param stages the copy of its stage structs
 * @param memory the copy of its memory
 */
SMS_API void sms_multi_generator_rebind(sms_multi_generator *g, sms_stage *stages,
                                        sms_memory_cell *memory);

#ifdef __cplusplus
}
#endif
#endif
