/* SPDX-License-Identifier: Apache-2.0 */
/**
 * @file smoother.h
 * @brief FIR smoothers in O(1), drift-free recursive form: rectangular, harmonic, damped
 * harmonic and exponential (docs/filters.md).
 *
 * Every smoother is the FIR filter y[n] = sum_{i=0}^{L-1} h[i] x[n-i] with unit DC gain
 * (sum h = 1) and the taps of docs/exact-mode.md (sms_smoother_taps() writes them). With
 * r = e^{sigma Ts} and, for an integer N = T/Ts:
 *
 * | family (kind)              | taps h[i], i = 0..N-1            | transfer function |
 * |----------------------------|----------------------------------|-------------------|
 * | ::SMS_RECTANGULAR          | 1/N                              | (1/N)(1 - z^-N)/(1 - z^-1) |
 * | ::SMS_HARMONIC             | sin(pi i/N)/sum                  | (1 - cos(pi/N))(z^-1 + z^-(N+1))/(1 - 2cos(pi/N) z^-1 + z^-2) |
 * | ::SMS_DAMPED_HARMONIC      | r^i sin(pi i/N)/sum              | K (z^-1 + r^N z^-(N+1))/(1 - 2 r cos(pi/N) z^-1 + r^2 z^-2), K = (1 - 2r cos(pi/N) + r^2)/(1 + r^N) |
 * | ::SMS_EXPONENTIAL          | r^i/sum                          | ((1 - r)/(1 - r^N))(1 - r^N z^-N)/(1 - r z^-1) |
 *
 * Timing (sms_stage_config::timing) when nu = T/Ts is not an integer (to 1e-9 relative):
 * ::SMS_TIMING_PAPER uses N = round(nu) (>= 1) and the table above (T' = N Ts);
 * ::SMS_TIMING_EXACT keeps T. With N0 = floor(nu), f = nu - N0 (docs/exact-mode.md): base
 * taps h_c(i Ts) for i < N0 and f h_c(N0 Ts) (the part of the last interval inside [0, T));
 * a correction on taps N0-1 and N0 puts the zero s* = sigma + j w* exactly on z* = e^{s* Ts}, w* = k 2 pi/T (rectangular,
 * exponential) or k 3 pi/T (harmonic families); then all taps are scaled to sum 1.
 * L = N0 + 1. The correction is small, so the taps stay non-negative and a step never
 * overshoots. Exact timing's largest tap can reach about 1.14/nu for a rectangular stage.
 * ::SMS_TIMING_BOUNDED (rectangular, exponential) keeps w* and T with L = N0 + 2 taps
 *   u, r, r^2, ..., r^N0, u r^(N0+1)  (scaled to sum 1),
 *   u = sin(pi x0 f)/(2 sin(pi x0) cos(pi x0 (1 - f))),  x0 = k/nu,
 * in (0, 1/2): the largest tap is at most the continuous peak density times Ts (1/nu for the
 * rectangular stage), the density a kinematic design budgets for (docs/exact-mode.md).
 *
 * Realisation (O(1) per sample, no libm): the first M taps (M = N, N0, or N0 + 1 bounded) are
 * Re or Im of c q^i with the pole q = r (rectangular, exponential) or q = r e^{j pi/nu}
 * (harmonic families), computed by the complex first-order recursion
 *   w[n] = q w[n-1] + c x[n] - c q^M x[n-M],   y[n] = Re/Im w[n] + sum_j d_j x[n-j],
 * where d_j are the (at most 2) direct taps: on N0-1 and N0 (exact timing), or on 0 and
 * N0 + 1 (bounded timing). A rotation is used rather than the
 * real second-order resonator 1 - 2 r cos(pi/N) z^-1 + r^2 z^-2, whose rounding is amplified
 * about N^2 times. The recursion cancels its own pole, so on its own it would accumulate
 * rounding for ever (docs/numerics.md). Hence:
 * - two copies run side by side, each restarted from zero every 2M samples, M apart (on the
 *   samples where the ring's head is 0); a copy restarted at t0 ignores inputs before t0 and
 *   is exact once it has consumed M samples, and the output always comes from the copy that
 *   has consumed between M and 2M samples;
 * - each copy filters x - ref, ref being the (finite) input just before its restart, and adds
 *   ref back (unit DC gain; the corrections, which sum to 0, act on x - ref too), so its
 *   rounding scales with how much the input varies within 2M samples, not with its offset;
 * - each copy's state is w + lo: w takes the increment (q - 1) w + c x - c q^M x[n-M], and lo
 *   (a small state on the same pole) collects what that addition rounds away (Dekker's
 *   Fast2Sum, exact when the increment is below the state, which is when the loss would be
 *   systematic) and what the rounded pole misses (q_lo w, q_lo from a long double design).
 *   For a pole near 1 both errors are otherwise systematic and tap i would be off by ~i eps
 *   (1e-5 at i = 1500 in float). Fast2Sum needs IEEE evaluation: do not build with -ffast-math.
 * The error against the exact convolution is therefore bounded independently of the run
 * length. Measured (tests/bench/drift_bench.c, L = 71..10005, all families): max |error| over
 * 1e9 samples of 1e3 + U(-1, 1) is 2.4e-16 (double) and 2.2e-7 (float) relative to 1e3; over
 * 1e8 samples of 1e3 U(-1, 1), 2.7e-16 and 1.4e-7.
 * Exact rest: once the last L inputs are equal the output is that input, bit for bit (the
 * taps sum to 1; the recursion alone would be within an ulp of it), so a held input comes out
 * exactly L samples after it was first applied, and after sms_smoother_reset(f, rest) an
 * input of rest comes out as rest from the first sample.
 * Cost (tests/bench/speed_bench.c, x86-64, -O2): about twice the plain drifting recursion of
 * the same filter (docs/benchmarks.md); sms_smoother_process() runs blocks with the state in
 * locals and the two copies in the two lanes of one SIMD register (SSE2/NEON with GCC or
 * Clang; elsewhere the copies run one after the other, same arithmetic, smaller code); for
 * the harmonic families, where a register holds four sms_real (float, or double with AVX) and
 * no product can be fused into a sum unseen (no FMA, or GCC in ISO C mode), both copies'
 * Re and Im share one register. sms_smoother_step() runs the two-lane per-sample code on one
 * sample with the state in the instance. Every path gives the same bits.

 * Non-finite input: a NaN or Inf sample makes the output NaN while it is inside the ring or
 * inside the recursion copy in use; at most 2M + 1 samples after it the output is again the
 * exact convolution of the inputs since (the state is never poisoned for ever).
 */
#ifndef SMOOTHSHAPER_SMOOTHER_H
#define SMOOTHSHAPER_SMOOTHER_H

#include <stdint.h>
#include "smoothshaper/config.h"

#ifdef __cplusplus
extern "C" {
#endif

/** @brief Most direct taps: floor(nu)-1 and floor(nu) (exact timing), or 0 and floor(nu)+1
 * (bounded timing). */
#define SMS_SMOOTHER_MAX_CORRECTIONS 2

/** @brief Instance of one smoother. Fields are public for inspection; change them only
 * through the functions below. */
typedef struct sms_smoother {
    sms_kind kind;              /**< ::SMS_RECTANGULAR .. ::SMS_EXPONENTIAL */
    size_t length;              /**< impulse response length L [samples] */
    size_t window;              /**< M: taps from the recursion, ring length; restarts every 2M */
    sms_real pole_m1_re;        /**< Re q - 1, rounded: the recursion's pole q */
    sms_real pole_im;           /**< Im q, rounded */
    sms_real pole_lo_re;        /**< what the rounding lost of Re q (to ~2^-64) */
    sms_real pole_lo_im;        /**< what the rounding lost of Im q */
    sms_real gain_re;           /**< Re c, c the weight of the newest input */
    sms_real gain_im;           /**< Im c */
    sms_real tail_re;           /**< Re of -c q^M, the weight of x[n-M] */
    sms_real tail_im;           /**< Im of -c q^M */
    int imag_out;               /**< 1: output Im w (harmonic families); 0: Re w */
    int real_only;              /**< 1: q, c, -c q^M are real (rectangular, exponential) */
    size_t n_corrections;       /**< direct taps in use (0 or 2) */
    size_t correction_delay[SMS_SMOOTHER_MAX_CORRECTIONS];  /**< {M-1, M}, or {0, M} (bounded) */
    sms_real correction_gain[SMS_SMOOTHER_MAX_CORRECTIONS]; /**< d_j, the direct taps' gains */
    sms_real w_re[2];           /**< Re of the state of the two restarted copies (main part):
                                     [0] the old copy, which gives the output, [1] the young one */
    sms_real w_im[2];           /**< Im of the copies' states */
    sms_real lo_re[2];          /**< Re of their small parts: rounding of the increments, q_lo w */
    sms_real lo_im[2];          /**< Im of their small parts */
    sms_real ref[2];            /**< each copy's reference: its (finite) input at restart */
    size_t run;                 /**< of the latest inputs, how many equal the one before them
                                     (at most L): from L - 1 on, the output is the input */
    unsigned variant;           /**< the per-sample loop that runs it (pole, direct taps) */
    sms_real rest;              /**< operating point set by reset */
    sms_real *history;          /**< caller buffer: the last M inputs (ring) */
    size_t history_len;         /**< M */
    size_t head;                /**< ring slot of x[n-M] (the oldest), 0..M-1 */
    double input_limit;         /**< |x| keeping every internal sum finite, before the cap
                                     at ::SMS_INPUT_MAX of sms_smoother_input_max() */
    double identity[SMS_STATE_IDENTITY_COUNT]; /**< config and Ts it was built for (config.h) */
} sms_smoother;

/**
 * @brief Validate a smoother config and report the buffer it needs.
 * @param config  a smoother config (kind ::SMS_RECTANGULAR .. ::SMS_EXPONENTIAL)
 * @param Ts      sample period [s], finite and > 0
 * @param n_reals receives M, the ring length in ::sms_real (M = N, or floor(T/Ts) for
 *                exact timing off the grid, floor(T/Ts) + 1 for bounded timing off it)
 * @return ::SMS_OK or the status sms_smoother_init() would return for a large enough buffer.
 */
SMS_API sms_status sms_smoother_buffer_size(const sms_stage_config *config, double Ts, size_t *n_reals);

/**
 * @brief Validate, design and build a smoother at rest at 0. Design runs in double with libm
 * (O(L) once); nothing is allocated.
 *
 * Checks, first failure wins (the order of the table in config.h):
 * - ::SMS_ERR_NULL: f or config is NULL;
 * - ::SMS_ERR_SAMPLE_PERIOD: Ts is NaN/Inf or <= 0;
 * - ::SMS_ERR_KIND: config->kind is not a smoother, or config->timing is unknown, or
 *   ::SMS_TIMING_BOUNDED for a harmonic family;
 * - ::SMS_ERR_DURATION: T is NaN/Inf or <= 0;
 * - ::SMS_ERR_DURATION_BELOW_TS: T < Ts (beyond the 1e-9 integer test), or a harmonic family
 *   with N < 2 samples (integer or paper timing: its only sample, sin(0), is zero);
 * - ::SMS_ERR_SIGMA: damped families: sigma is NaN/Inf or > 0; also a sigma so negative that
 *   a design constant overflows ::sms_real or that the finite input range
 *   (sms_smoother_input_max()) falls below 1;
 * - ::SMS_ERR_MULTIPLE: k < 1;
 * - ::SMS_ERR_EVEN_MULTIPLE: k even for ::SMS_HARMONIC or ::SMS_DAMPED_HARMONIC;
 * - ::SMS_ERR_ABOVE_NYQUIST: exact or bounded timing with T/Ts off the grid and the pinned zero w* at or
 *   above pi/Ts (k 2 >= T/Ts rectangular/exponential, k 3 >= T/Ts harmonic families);
 * - ::SMS_ERR_TOO_LONG: T/Ts + 2 exceeds min(2^52, SIZE_MAX/32);
 * - ::SMS_ERR_NULL: buffer is NULL; ::SMS_ERR_BUFFER_TOO_SMALL: n_reals < M.
 * @param f       instance to fill; untouched on error
 * @param config  the stage description
 * @param Ts      sample period [s]
 * @param buffer  caller memory for the ring, at least sms_smoother_buffer_size() reals; the
 *                smoother keeps this pointer (see sms_stage_rebind())
 * @param n_reals length of buffer
 * @return ::SMS_OK, or the first failing check above (f untouched).
 */
SMS_API sms_status sms_smoother_init(sms_smoother *f, const sms_stage_config *config, double Ts,
                                     sms_real *buffer, size_t n_reals);

/**
 * @brief Put the filter at rest at `rest`, as if every past input had been `rest`: the next
 * outputs equal `rest` until the input changes. O(M) (clears the ring).
 * @param rest finite; a NaN/Inf rest makes every output NaN until the next finite reset.
 * @param f       the smoother, built by sms_smoother_init() or sms_smoother_init_coeffs()
 */
SMS_API void sms_smoother_reset(sms_smoother *f, sms_real rest);

/**
 * @brief The finite input range of this smoother: inputs and reset values with
 * |x| <= sms_smoother_input_max() keep every output and state finite (beyond it, or for
 * NaN/Inf, see "Non-finite input" above). Computed at init in closed form from the designed
 * constants: with c the weight of the newest input, r = e^{sigma Ts} and
 * S = (1 - r^M)/(1 - r) (S = M when sigma = 0), the recursion state is at most 4 |c| S times
 * the input range, and the bound is
 *   min(::SMS_INPUT_MAX, REAL_MAX / (32 |c| max(S, 1) + 8 + 8 (|d_0| + |d_1|))),
 * REAL_MAX the overflow threshold of ::sms_real and d_j the exact-timing direct taps. It is
 * ::SMS_INPUT_MAX for every rectangular, harmonic and exponential smoother (|c| S is 1, or
 * about pi/2) and for lightly damped harmonic ones. A heavily damped harmonic smoother
 * (c ~ e^{-sigma Ts}/sin(pi/N), beyond about 50 in double or 30 in float) has a smaller range,
 * e.g. in double 3.1e298 at sigma Ts = -19, N = 2 and 7.8e219 at sigma Ts = -200, N = 2
 * (docs/numerics.md has a table). sms_smoother_init() refuses with ::SMS_ERR_SIGMA a sigma for
 * which the range would fall below 1 (sigma Ts below about -706 in double, -85 in float).
 * @param f       the smoother (read only)
 * @return the largest |input| [same unit as the signal], in [1, ::SMS_INPUT_MAX]
 */
SMS_API double sms_smoother_input_max(const sms_smoother *f);

/** @brief Filter one sample in place: *x = y[n] for input x[n]. O(1), no libm; the same bits
 * as sms_smoother_process() on that sample.
 * @param f       the smoother, built by sms_smoother_init() or sms_smoother_init_coeffs()
 * @param x       in: the input x[n], |x| <= sms_smoother_input_max(); out: the output y[n]
 */
SMS_API void sms_smoother_step(sms_smoother *f, sms_real *x);

/** @brief Filter n samples; in == out (in place) is allowed, other overlaps are not.
 * Equal, bit for bit, to n calls of sms_smoother_step() and to any split into blocks.
 * @param f       the smoother, built by sms_smoother_init() or sms_smoother_init_coeffs()
 * @param in      n inputs, |x| <= sms_smoother_input_max()
 * @param out     n outputs; may be in itself
 * @param n       number of samples, any (0 does nothing)
 */
SMS_API void sms_smoother_process(sms_smoother *f, const sms_real *in, sms_real *out, size_t n);

/**
 * @brief Samples of a constant input after which this smoother has absorbed it: from the
 * current phase, one more than the sample on which the second of the two copies in use
 * restarts under the input (each restarts every 2M samples, the two M apart, referred to the
 * input before it; a copy restarted on a constant input x keeps w = lo = 0 and ref = x for
 * ever), and at least L + 2, so it lies in [M + 2, 2M + 2] (M the ring length). After that
 * many samples of x the state is the absorbed one: the ring holds x, both copies w = lo = 0
 * and ref = x, run = L, and only head still moves (period M). O(1).
 * @param f       the smoother (read only)
 * @return the sample count, in [M + 2, 2M + 2]
 */
SMS_API uint64_t sms_smoother_settle_length(const sms_smoother *f);

/**
 * @brief Filter n samples of the constant input x in O(M) time, with the state and output of
 * n calls of sms_smoother_step() with x, bit for bit: valid when n >= sms_smoother_settle_length()
 * (as then the absorbed state above is reached one sample before the end); the last sample is
 * computed by sms_smoother_step() from the absorbed state, with head advanced by n - 1 in
 * closed form (head + n mod M).
 * @param x  finite, |x| <= sms_smoother_input_max()
 * @param n  samples, >= sms_smoother_settle_length() (fewer: the state is undefined)
 * @return the output of the last sample.
 * @param f       the smoother, built by sms_smoother_init() or sms_smoother_init_coeffs()
 */
SMS_API sms_real sms_smoother_settle(sms_smoother *f, sms_real x, uint64_t n);

/**
 * @brief Advance head by n samples as n samples would (the copies swap roles on the way, which
 * an absorbed state's equal copies do not show), leaving every value (ring, copies,
 * references, run) as it is. On an absorbed state (above) this is exactly n samples of
 * the absorbed input; on any other it is the phase of n samples later with stale values, which
 * the next sms_smoother_settle_length() samples replace entirely (the generator jumps along a
 * plan this way, then filters the last samples). O(1).
 * @param f       the smoother, built by sms_smoother_init() or sms_smoother_init_coeffs()
 * @param n       samples to advance, any
 */
SMS_API void sms_smoother_advance(sms_smoother *f, uint64_t n);

/** @brief Number of doubles of the saved state: ::SMS_STATE_IDENTITY_COUNT + M + 13 (the
 * configuration identity of config.h, then head, run, rest, the two copies' w and lo as four
 * complex numbers (old copy first), their two references, the ring).
 * @param f       the smoother (read only)
 * @return ::SMS_STATE_IDENTITY_COUNT + M + 13
 */
SMS_API size_t sms_smoother_state_count(const sms_smoother *f);

/** @brief Write the dynamic state, sms_smoother_state_count() doubles, into dst. Loading it
 * into an identically configured smoother continues bit-exactly.
 * @param f       the smoother (read only)
 * @param dst     sms_smoother_state_count() doubles
 */
SMS_API void sms_smoother_get_state(const sms_smoother *f, double *dst);

/**
 * @brief Restore a saved state; validates first and writes nothing on error.
 * @return ::SMS_OK; ::SMS_ERR_NULL; ::SMS_ERR_STATE_FORMAT .. ::SMS_ERR_STATE_DURATION if it was
 * saved by another configuration (the status names the first field of the identity that
 * differs, config.h); ::SMS_ERR_STATE if n != sms_smoother_state_count(), the
 * head is not an integer in [0, M), run is not an integer in [0, L],
 * rest or a reference is not finite, or a finite value lies outside the range of ::sms_real (NaN/Inf in the
 * ring and the copies are accepted: they are what a non-finite input leaves behind).
 * @param f       the smoother, built by sms_smoother_init() or sms_smoother_init_coeffs(); untouched on error
 * @param src     the saved state
 * @param n       its length in doubles, sms_smoother_state_count()
 */
SMS_API sms_status sms_smoother_set_state(sms_smoother *f, const double *src, size_t n);

/** @brief The validation of sms_smoother_set_state() alone: writes nothing.
 * @param f       the smoother (read only)
 * @param src     the saved state
 * @param n       its length in doubles
 * @return what sms_smoother_set_state() would return.
 */
SMS_API sms_status sms_smoother_check_state(const sms_smoother *f, const double *src, size_t n);
/**
 * @brief Is src a state a run could reach with every input and rest value |x| <= x_max? What
 * sms_smoother_check_state() accepts, and every value finite: the rest within x_max, the ring
 * and the references (which hold x - rest) within 2 x_max, the two copies within 2 x_max times
 * the internal gain the input range leaves room for (REAL_MAX, the overflow threshold of ::sms_real, over the uncapped range
 * behind sms_smoother_input_max()) and at most half of REAL_MAX, each with a margin of
 * 2^-20 for rounding. A loader of
 * states from outside (a file, an FMU state) uses this to refuse a state no run produces.
 * @param x_max  the largest |input| of the run, at most sms_smoother_input_max()
 * @return ::SMS_OK, what sms_smoother_check_state() returns, or ::SMS_ERR_STATE. Writes nothing.
 * @param f       the smoother (read only)
 * @param src     the saved state
 * @param n       its length in doubles
 */
SMS_API sms_status sms_smoother_check_state_range(const sms_smoother *f, const double *src,
                                                  size_t n, double x_max);

/**
 * @brief Write the L impulse-response taps (normalised, DC gain 1) of a config, computed in
 * double, into taps[0..L-1]; the instance realises exactly these (to rounding).
 * @param n_taps length of taps; must be >= L (L = N, or floor(T/Ts) + 1 for exact timing off
 *               the grid, floor(T/Ts) + 2 for bounded timing); entries past L are left alone
 * @return ::SMS_OK, ::SMS_ERR_NULL (config or taps), ::SMS_ERR_BUFFER_TOO_SMALL (n_taps < L),
 *         or a validation status of sms_smoother_init().
 * @param config  a smoother config
 * @param Ts      sample period [s], finite and > 0
 * @param taps    receives the L taps
 */
SMS_API sms_status sms_smoother_taps(const sms_stage_config *config, double Ts, double *taps, size_t n_taps);

/** @brief Impulse-response length L of a config (the n_taps that sms_smoother_taps() needs).
 * @return ::SMS_OK, ::SMS_ERR_NULL, or a validation status of sms_smoother_init().
 * @param config  a smoother config
 * @param Ts      sample period [s], finite and > 0
 * @param length  receives L (untouched on error)
 */
SMS_API sms_status sms_smoother_length(const sms_stage_config *config, double Ts, size_t *length);

#ifdef __cplusplus
}
#endif
#endif
