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
 * Cost: O(n^2) closed-form steps for any input (no nested iteration).
 *
 * On a sample grid (Ts > 0; docs/sampled-limits.md): every stage except a mode-tuned last one
 * lasts a whole number of samples, N[k] Ts with N[k] >= T[k]/Ts (the continuous length) and
 * N[k] >= N[k+1] + ... + N[n-1] (samples of the stages after it; a tuned stage counts its
 * floor(T/Ts) + 1 taps); a harmonic last stage takes the next odd N when the largest sampled
 * tap would exceed (pi/2)/(T/Ts). A tuned last stage keeps its exact length (its zero stays
 * on the mode, exact timing) and the design bounds the top derivative with its largest
 * sampled tap / Ts instead of the continuous peak density: both are satisfied. Then every
 * backward difference of the sampled output (chain fed with a step of h at a sample) obeys
 * the bounds: |D^i q[m]| / Ts^i <= limits[i-1] for i = 1..n (to rounding). Price: the
 * duration grows by less than one sample per stage for n <= 3 (at most 2^(n-1) - 1 + 1
 * samples over ceil for longer chains), see docs/sampled-limits.md for measured figures.
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
 *         samples in all, or no multiple k <= ::SMS_KINEMATIC_MAX_MULTIPLE meets the bounds),
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
 * ::SMS_TIMING_EXACT, which for the lengths on the grid is the plain integer-N filter), so that
 * sms_chain_init() with the same Ts builds the chain directly and its sampled output keeps
 * every bound. Same arguments and statuses; Ts = 0 gives ::SMS_ERR_SAMPLE_PERIOD (a chain
 * always runs at a sample period).
 */
SMS_API sms_status sms_kinematic_configs(double h, const double *limits, size_t n,
                                         sms_profile profile, double wn, double zeta, double Ts,
                                         sms_stage_config *configs, size_t capacity,
                                         size_t *count);

/* ------------------------------------------------------------------------------------------ */
/* Online multi-point generator                                                                */
/* ------------------------------------------------------------------------------------------ */

/** @brief Most constant-jerk segments of a time-optimal plan: velocity change (3), cruise (1),
 * stop (3). */
#define SMS_PLAN_MAX_SEGMENTS 7

/** @brief Bounds of a time-optimal plan: |v| <= vmax, |a| <= amax, |j| <= jmax (finite, > 0). */
typedef struct sms_plan_limits {
    sms_real vmax, amax, jmax;
} sms_plan_limits;

/** @brief The generator's running time-optimal plan (read-only; built by the generator).
 * Segment i starts n[i] samples plus f[i] (in [0, Ts)) seconds after the plan's first
 * sample, in state (p, v, a), and applies jerk j for d seconds. From `end` samples + `end_f`
 * on the output rests exactly at `goal`. Times split into whole samples and a fraction keep
 * a float build exact over any number of samples (a float time in seconds would not). */
typedef struct sms_plan {
    size_t count;                      /* segments in use (0: at rest at goal) */
    size_t n[SMS_PLAN_MAX_SEGMENTS];
    sms_real f[SMS_PLAN_MAX_SEGMENTS];
    sms_real p[SMS_PLAN_MAX_SEGMENTS], v[SMS_PLAN_MAX_SEGMENTS], a[SMS_PLAN_MAX_SEGMENTS];
    sms_real j[SMS_PLAN_MAX_SEGMENTS], d[SMS_PLAN_MAX_SEGMENTS];
    size_t end;
    sms_real end_f;
    sms_real goal;
    sms_real duration;                 /* sum of d [s] (continuous, before the grid) */
} sms_plan;

/**
 * @brief Limits and optional mode of the online generator (docs/design.md).
 *
 * | field   | valid range |
 * |---------|-------------|
 * | vmax, amax, jmax | finite, > 0 |
 * | profile | an ::sms_profile (::SMS_PROFILE_DAMPED needs wn > 0) |
 * | wn      | 0 (no mode) or finite > 0 and below pi/Ts [rad/s] |
 * | zeta    | [0, 1) |
 */
typedef struct sms_generator_config {
    double vmax, amax, jmax;
    sms_profile profile;
    double wn;   /**< 0: no mode to cancel */
    double zeta;
} sms_generator_config;

/**
 * @brief Online generator: a staircase of targets in, a bounded smooth trajectory out.
 *
 * Two realisations, chosen by the config:
 *
 * **Time-optimal** (::SMS_PROFILE_POLYNOMIAL without a mode, wn = 0). Whenever the target
 * differs from the goal of the running plan, the generator re-plans on that sample from its
 * exact state (q, v, a) there: the time-optimal jerk-limited motion to the target at rest
 * (ruckig's duration for this single-axis problem): a velocity change (v, a) -> (vp, 0) with
 * jerk +-jmax and the acceleration held at +-amax if reached, a cruise at vp = +-vmax when the
 * distance allows, and the stop (vp, 0) -> (0, 0); vp solves "distance of the two changes =
 * target - q", which increases with vp (bisection, in ::sms_real, no libm). q, v, a stay
 * continuous across a re-plan, the jerk jumps. The output is the exact closed form at each
 * sample instant (jerk: the right limit at a jump), so every sampled difference dq/Ts,
 * d2q/Ts^2, d3q/Ts^3 is an average of v, a, j and keeps the bounds (docs/sampled-limits.md).
 * Once the target holds, q equals it exactly from the first sample at or after the plan's
 * continuous end on: a rest-to-rest move of any length takes its time-optimal duration
 * rounded up to the sample grid (h = 0.1, v = 1, a = 10, j = 1000 from rest: 0.297 s). Any
 * Ts works (no stage has to be longer than a sample). Times are kept as whole samples plus a
 * fraction and every segment is anchored on its own start (the stop on the target), so a
 * float build keeps its error at the rounding of the positions for any move and run length.
 * Per sample: O(1); a re-plan: about 60 (double) or 30 (float) evaluations of the distance.
 *
 * **Tail** (a trigonometric or damped profile, or a mode wn > 0: the last stage must have
 * that family or be tuned to the mode). Structure: a variable first stage followed by a fixed
 * tail X = M(T2) * L(T3), where T2, T3 and the family L of the last stage come from
 * sms_kinematic_design() for a move long enough to reach vmax with the limits
 * {vmax, amax, jmax} (so T2 >= T3, the tail lasts Tc = T2 + T3). The first stage is the
 * moving average of length T1 = |segment| / V applied to each segment, realised as its output
 * r(t): a ramp at velocity V towards the current target. V is re-planned per segment
 * (|V| <= vmax, T1 >= Tc so short moves use V < vmax), the tail is fixed.
 *
 * Why it never exceeds a bound, for any target sequence: r'(t) is piecewise constant and is
 * changed only (i) on sample instants, (ii) at least Nc = ceil(Tc/Ts) samples after its
 * previous change, (iii) by at most vmax (a reversal first stops: V -> 0, then after Nc
 * samples starts the other way), and |r'| <= vmax always. The output is q = r * X. Since X
 * has support [0, Tc] and changes are >= Tc apart, at any instant at most the last change
 * dV is still inside the tail's window, so exactly:
 *   q'(t)   = r'(t) - dV (1 - F(s)),   |q'|   <= max|r'|           <= vmax,
 *   q''(t)  = dV x2(s),                |q''|  <= vmax / T2         <= amax,
 *   q'''(t) = dV x2'(s),               |q'''| <= vmax peak(L) / T2 <= jmax,
 * with s the time since that change, x2 the tail's impulse response (peak 1/T2 because
 * T2 >= T3) and F its integral; the last inequality of each line is the kinematic design.
 * Reaching: once the target holds, r ends its last segment exactly on it and q equals the
 * target exactly Nc samples later. Outputs are the exact values at the sample instants
 * (tables of the tail's responses filled at init), so the sampled differences keep the bounds
 * here too. The jerk at a jump on a sample instant is the right limit, decided on sample
 * indices (|b/Ts - round(b/Ts)| <= 1e-9 max(1, b/Ts) puts a breakpoint b on the grid).
 * Time: a segment from rest of length D >= vmax Tc takes D/vmax + Tc rounded up to the grid;
 * shorter moves take 2 Tc (bounded, not time-optimal). A target that arrives while a change
 * is still inside the tail waits (at most Nc samples); a reversal stops first and waits Nc.
 * Needs T2, T3 >= Ts (::SMS_ERR_DURATION_BELOW_TS otherwise).
 *
 * Both: per-sample work O(1), no libm, ::sms_real only; a non-finite target is ignored.
 */
typedef struct sms_generator {
    double Ts;
    double vmax;
    double T2, T3;        /**< tail stage lengths [s] */
    sms_kind last_kind;   /**< family of the tail's last stage */
    double sigma;         /**< its sigma (exponential), else 0 */
    size_t n_tail;        /**< Nc: samples from a change until the tail has absorbed it */
    double mean_delay;    /**< mean of the tail's impulse response [s] */
    sms_real Ts_signal;   /**< Ts and mean_delay in signal precision, so that the float */
    sms_real mean_delay_signal; /**< build's per-sample path uses no double arithmetic */
    sms_real step_distance; /**< vmax Ts: the farthest the first stage moves in one sample */
    sms_real *table;      /**< caller buffer: 4 (Nc + 1) reals: E, F, x2, x2' at s = m Ts */
    /* dynamic state */
    sms_real target;      /**< latest valid target */
    sms_real start;       /**< r at the start of the running segment */
    sms_real goal;        /**< where the running segment ends */
    sms_real r;           /**< first-stage output at the current sample */
    sms_real velocity;    /**< r' (V) */
    sms_real change;      /**< the last change of r' (dV) */
    size_t seg_len;       /**< samples of the running segment (0: at rest) */
    size_t seg_pos;       /**< samples elapsed in it */
    size_t age;           /**< samples since the last change, saturated at Nc */
    /* time-optimal realisation */
    int time_optimal;     /**< 1: time-optimal plan (polynomial, no mode); 0: tail */
    sms_plan_limits limits; /**< vmax, amax, jmax in signal precision */
    sms_real plan_q, plan_v, plan_a; /**< state the running plan started from */
    sms_plan plan;        /**< the running plan (its goal is the target it heads for) */
    size_t k;             /**< samples since the plan's first sample */
} sms_generator;

/** @brief Reals the generator's buffer needs: 4 (Nc + 1) for the tail, 0 for the
 * time-optimal realisation (which needs no buffer: init then accepts buffer NULL).
 * @return ::SMS_OK, ::SMS_ERR_NULL, ::SMS_ERR_SAMPLE_PERIOD, ::SMS_ERR_LIMIT, ::SMS_ERR_KIND,
 *         ::SMS_ERR_WN, ::SMS_ERR_ZETA, ::SMS_ERR_ABOVE_NYQUIST, ::SMS_ERR_DURATION_BELOW_TS
 *         (a tail stage shorter than Ts), ::SMS_ERR_TOO_LONG. */
SMS_API sms_status sms_generator_buffer_size(const sms_generator_config *config, double Ts,
                                             size_t *n_reals);
/** @brief Validate, design the tail, fill the tables; the generator rests at 0.
 * @return as sms_generator_buffer_size(), plus ::SMS_ERR_BUFFER_TOO_SMALL. Untouched on error. */
SMS_API sms_status sms_generator_init(sms_generator *g, const sms_generator_config *config,
                                      double Ts, sms_real *buffer, size_t n_reals);
/** @brief Rest at `position` (target, output and first stage all there). */
SMS_API void sms_generator_reset(sms_generator *g, sms_real position);
/**
 * @brief Advance one sample with the current target (the staircase value) and write
 * out[0..3] = q, q', q'', q''' at this instant. A non-finite target is ignored (the previous
 * target is kept), so the output stays bounded.
 */
SMS_API void sms_generator_step(sms_generator *g, sms_real target, sms_real out[4]);
/** @brief n steps: targets[0..n-1] in, out[4 i .. 4 i + 3] = q, v, a, j of step i.
 * Equal, bit for bit, to n calls of sms_generator_step() and to any split into blocks. */
SMS_API void sms_generator_process(sms_generator *g, const sms_real *targets, size_t n,
                                   sms_real *out);
/** @brief Tail: its duration Tc = T2 + T3 [s] (the output lags r by this at most).
 * Time-optimal: 0 (there is no tail). */
SMS_API double sms_generator_tail_duration(const sms_generator *g);
/** @brief Number of doubles sms_generator_get_state() writes: 9 (tail) or 6 (time-optimal:
 * target, goal, the plan's start q, v, a and the samples since it; loading re-plans from
 * these, so a saved state can also move the generator to any sample of its plan). */
SMS_API size_t sms_generator_state_count(const sms_generator *g);
SMS_API void sms_generator_get_state(const sms_generator *g, double *dst);
/** @brief Restore a saved state; ::SMS_ERR_STATE (nothing written) if n or a field is invalid. */
SMS_API sms_status sms_generator_set_state(sms_generator *g, const double *src, size_t n);
SMS_API sms_status sms_generator_check_state(const sms_generator *g, const double *src, size_t n);
/** @brief Point a copied generator at a buffer holding the same tables. */
SMS_API void sms_generator_rebind(sms_generator *g, sms_real *buffer);

/* ------------------------------------------------------------------------------------------ */
/* B-spline interpolating filters                                                              */
/* ------------------------------------------------------------------------------------------ */

#define SMS_BSPLINE_MAX_DEGREE 7
#define SMS_BSPLINE_MAX_AXES 3

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
    double Ts;
    size_t k0;             /**< pass-through offset (see above) */
    long m_first;          /**< first m with c_m != 0 (<= 0) */
    size_t n_coeff;        /**< number of c_m stored */
    double coeff[SMS_BSPLINE_MAX_DEGREE + 2];
    sms_smoother stages[SMS_BSPLINE_MAX_AXES * SMS_BSPLINE_MAX_DEGREE]; /**< rectangular, axis a:
                                                                         [a p, a p + p) */
} sms_bspline;

/** @brief Reals needed: n_axes p times one rectangular stage of N samples.
 * @return ::SMS_OK, ::SMS_ERR_NULL, ::SMS_ERR_ORDER (degree or n_axes out of range),
 *         ::SMS_ERR_SAMPLE_PERIOD, ::SMS_ERR_DURATION, ::SMS_ERR_DURATION_BELOW_TS, ::SMS_ERR_TOO_LONG. */
SMS_API sms_status sms_bspline_buffer_size(unsigned degree, size_t n_axes, double T, double Ts,
                                           size_t *n_reals);
/** @brief Build the chains (knot spacing N = round(T/Ts) samples) at rest at 0 and compute
 * c_m. Same statuses as sms_bspline_buffer_size() plus ::SMS_ERR_BUFFER_TOO_SMALL. */
SMS_API sms_status sms_bspline_init(sms_bspline *b, unsigned degree, size_t n_axes, double T,
                                    double Ts, sms_real *buffer, size_t n_reals);
/** @brief Rest every axis at rest[axis] (n_axes values). */
SMS_API void sms_bspline_reset(sms_bspline *b, const sms_real *rest);
/** @brief One sample: in[axis] (the held control point) -> out[axis]; in == out allowed. */
SMS_API void sms_bspline_step(sms_bspline *b, const sms_real *in, sms_real *out);
/** @brief Doubles of work memory sms_bspline_control_points() needs for n_via via-points. */
SMS_API size_t sms_bspline_work_size(const sms_bspline *b, size_t n_via);
/**
 * @brief Control points C (n_via rows of n_axes, row-major) from via-points Q (same layout).
 * @param work    sms_bspline_work_size() doubles of scratch memory
 * @return ::SMS_OK, ::SMS_ERR_NULL, ::SMS_ERR_ORDER (n_via < 2), ::SMS_ERR_LIMIT (a
 *         non-finite via-point), ::SMS_ERR_BUFFER_TOO_SMALL (n_work). control untouched on error.
 */
SMS_API sms_status sms_bspline_control_points(const sms_bspline *b, const double *via,
                                              size_t n_via, double *control, double *work,
                                              size_t n_work);
/** @brief Sample (after reset) at which the output passes through via-point i, 1 <= i <= M-2:
 * (i-1) N + k0. */
SMS_API size_t sms_bspline_pass_sample(const sms_bspline *b, size_t i);
/**
 * @brief Shortest knot spacing that puts the first zero of sinc^p at or below every mode:
 * T = N Ts with N = ceil(2 pi / (min wn Ts)) (T >= 2 pi / min wn, docs/filters.md).
 * @return ::SMS_OK, ::SMS_ERR_NULL, ::SMS_ERR_ORDER (n = 0), ::SMS_ERR_WN, ::SMS_ERR_SAMPLE_PERIOD.
 */
SMS_API sms_status sms_bspline_period_for_modes(const double *wn, size_t n, double Ts, double *T);
SMS_API size_t sms_bspline_state_count(const sms_bspline *b);
SMS_API void sms_bspline_get_state(const sms_bspline *b, double *dst);
SMS_API sms_status sms_bspline_set_state(sms_bspline *b, const double *src, size_t n);

#ifdef __cplusplus
}
#endif
#endif
