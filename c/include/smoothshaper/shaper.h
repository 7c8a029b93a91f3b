/* SPDX-License-Identifier: Apache-2.0 */
/**
 * @file shaper.h
 * @brief Input shapers: ZV^n (ZV, ZVD, ZVDD, ...), EI, two- and three-hump EI, MZV, generalised
 * MZV, specified-insensitivity (SI), user-defined impulses; and the input smoothers of 3-D
 * printer firmware (smooth ZV ... smooth SI), FIR filters on the same engine (docs/filters.md).
 *
 * A shaper is a sparse FIR filter y[n] = sum_k g_k x[n - d_k] (k = 0..n_taps-1) with unit DC
 * gain (sum g_k = 1). Work per sample is O(n_taps) <= ::SMS_SHAPER_MAX_TAPS. The caller owns
 * all memory, like a CMSIS-DSP sparse FIR: the ::sms_shaper instance (a few words), the tap
 * table (sms_shaper_tap_count() ::sms_shaper_tap, n_taps of them: 3 for ZV, at most
 * ::SMS_SHAPER_MAX_TAPS) and the delay line (sms_shaper_buffer_size() reals = the
 * impulse-response length L = max d_k + 1).
 *
 * Mode: wn [rad/s], zeta; wd = wn sqrt(1 - zeta^2), Td = 2 pi / wd, p = -zeta wn + j wd.
 * Continuous designs (amplitudes A_m, sum 1, at times t_m), sources cited in shaper_designs.c:
 * - ZV^n, n = 1 (ZV), 2 (ZVD), 3 (ZVDD) or sms_stage_config::order (ZVN):
 *   A_m = C(n,m) K^m / (1+K)^n at t_m = m Td/2, m = 0..n, K = exp(-zeta pi / sqrt(1-zeta^2));
 *   H_c(s) = ((1 + K e^{-s Td/2})/(1+K))^n has a zero of multiplicity n at p.
 * - EI (one hump, tolerance V = sms_stage_config::tolerance): undamped closed form
 *   [(1+V)/4, (1-V)/2, (1+V)/4] at [0, Td/2, Td]: |H(j wn)| = V at the top of the hump, zeros on
 *   either side. zeta > 0: the closed-form amplitudes B_m weighted by K^m and normalised (as
 *   Klipper and the NumPy reference), so H_c(sigma + j w) = H_B(j w)/S, S = sum_m B_m K^m, H_B the
 *   closed form at the same times: hump and zeros kept along Re s = sigma; |H_c(p)| = V/S.
 * - EI2 (two-hump EI): 4 impulses at m Td/2, exact zero at the mode, two humps of height V
 *   (undamped closed form; for zeta > 0 the amplitudes are weighted by K^m, which keeps the
 *   exact zero at p).
 * - MZV: K' = exp(-0.75 zeta pi / sqrt(1-zeta^2)), [1 - 1/sqrt2, (sqrt2 - 1) K', (1 - 1/sqrt2) K'^2]
 *   normalised, at [0, 0.375 Td, 0.75 Td]; exact zero at p.
 * - EI3 (three-hump EI, tolerance V): [A1, A2, A3, A2, A1] at m Td/2, m = 0..4, with
 *   A1 = (1 + 3V + 2 sqrt(2V(V+1)))/16, A2 = (1-V)/4, A3 = (1+V)/2 - 2 A1 (undamped closed
 *   form; humps of height V at the mode and on either side); zeta > 0: weighted by K^m as EI.
 * - GMZV (generalised MZV as 3-D printer firmware defines it): n = sms_stage_config::order
 *   impulses (3..::SMS_SHAPER_MAX_IMPULSES) at t_j = j D Td/(n-1), D = sms_stage_config::duration
 *   (damped periods, 0 < D < (n-1)/2); amplitudes are the least-squares solution of sum A = 1
 *   and H(j wd (1 + i/tau)) = 0, i = 0..n-2, tau = D (n-2)/(n-2D-1), weighted by
 *   e^{-zeta wn t_j} and normalised. n = 3, D = 0.75 is MZV. Configurations whose least-squares
 *   amplitudes go negative (in practice D < 0.5) are rejected with ::SMS_ERR_SHAPER_DURATION.
 *   The zeros crowd together as D approaches (n-1)/2: the system's condition number grows from
 *   ~10 (D = 0.3 (n-1)) to ~1e12 (n = 9, D = 0.49 (n-1)), and the amplitudes are only as
 *   accurate as cond * machine epsilon there.
 * - SI (specified insensitivity; Singhose, Seering and Singer, "Input shaping for vibration
 *   reduction with specified insensitivity to modeling errors", 1996): n = sms_stage_config::order
 *   (3, 5, 7, 9) impulses at t_m = m D Td/(n-1), D = sms_stage_config::duration in
 *   [(n-1)/4, (n-1)/2] damped periods, symmetric undamped amplitudes B_m whose response
 *   R(theta) = H(jw) e^{j w D Td/2}, theta = w D Td/(n-1), is the scaled Chebyshev polynomial
 *   V T_d(x(cos theta)), d = (n-1)/2, V = sms_stage_config::tolerance: |H| <= V over the widest
 *   band w in [wd (1 - I/2), wd (1 + I/2)] any such shaper reaches, the equal-ripple optimum of
 *   Dolph (1946), closed form in filter/shaper_si.c. I from sms_shaper_si_insensitivity(); the
 *   shortest (n, D) for a wanted I from sms_shaper_si_design(). D = (n-1)/2 is EI (n = 3) and
 *   the three-hump EI (n = 5); D = 1/2 with n = 3 is ZV. No amplitude is negative, so |H| <= 1
 *   at every frequency. zeta > 0: weighted by e^{-zeta wn t_m} as EI (band along Re s = sigma).
 * - IMPULSES (user-defined, e.g. a firmware's shaper pasted as amplitudes and times):
 *   n = sms_stage_config::order impulses sms_stage_config::amplitudes[m] (normalised to sum 1,
 *   as firmware applies them; negative ones allowed) at sms_stage_config::times[m] [s]
 *   (>= 0, strictly increasing; a first time > 0 is a pure delay). No mode: wn and zeta are not
 *   read; exact timing splits each off-grid impulse linearly between its two neighbouring
 *   samples with no correction, which keeps sum g = 1 and the centroid sum g_k d_k Ts =
 *   sum A_m t_m exactly (a sampled ramp comes out as the continuous shaper's output).
 * - Input smoothers (D. Butyugin's for Klipper-derived firmware: dmbutyugin/klipper
 *   klippy/extras/shaper_defs.py, 2024; Kalico): ::SMS_SMOOTH_ZV, ::SMS_SMOOTH_MZV,
 *   ::SMS_SMOOTH_EI (kernels fitted as cubics in zeta, valid for zeta in [0, 0.25]: there the
 *   kernel stays >= -0.14 % of its peak and the residual at the mode <= 0.18 %),
 *   ::SMS_SMOOTH_EI2, ::SMS_SMOOTH_ZVD_EI, ::SMS_SMOOTH_SI (zeta not read). A polynomial
 *   kernel g(tau) = P(tau/T - 1/2)/T of degree 6 to 10 on [0, T], zero at both ends, unit area,
 *   T = t(zeta) 2 pi/wn with t = 0.665 (smooth ZV at zeta = 0), 0.852, 0.968, 1.149, 1.475,
 *   1.245 (T in design periods). Its residual for a step: e^{-zeta wn T} |H_c(p)|, H_c(s) =
 *   int_0^T g(tau) e^{-s tau} dtau. Realised with every sample a tap (L = ceil(T/Ts) + 1, so
 *   O(L) work per sample and L taps in the table): h_k = int g(tau) Lambda(tau/Ts - k) dtau
 *   (Lambda the unit triangle: the smoother applied to the linear interpolation of the
 *   samples), plus the correction of least sum d_k^2/|h_k| that makes sum h = 1,
 *   sum k h_k Ts = int tau g and H(e^{p Ts}) = H_c(p) exact: the design's residual at the mode
 *   for any Ts, and each tap moved in proportion to itself (filter/input_smoother.c). Exact
 *   timing only (::SMS_TIMING_PAPER is refused with ::SMS_ERR_KIND); the kernel must span at
 *   least 4 samples (T >= 4 Ts, else ::SMS_ERR_ABOVE_NYQUIST: wn below about pi/(3 Ts) for
 *   smooth ZV).
 *
 * Discretisation (docs/exact-mode.md): ::SMS_TIMING_PAPER puts each impulse at sample
 * round(t_m/Ts). ::SMS_TIMING_EXACT splits an off-grid impulse linearly between its two
 * neighbouring samples and adds the least-norm correction on {0} and the split samples so that
 * H(1) = 1 and H(e^{p Ts}) = H_c(p) (0 for ZV^n, EI2, MZV; V-sized for EI); ZV^n is the n-fold
 * convolution of the exact discrete ZV (zero of multiplicity n at e^{p Ts}).
 *
 * Non-finite input: it enters the delay line like any sample, so the outputs at delays d_k after
 * it are non-finite, and from L samples after it on the output is clean again (a FIR cannot be
 * poisoned for ever).
 */
#ifndef SMOOTHSHAPER_SHAPER_H
#define SMOOTHSHAPER_SHAPER_H

#include "smoothshaper/config.h"

#ifdef __cplusplus
extern "C" {
#endif

/** @brief Most non-zero taps of a discrete impulse shaper: the exact ZV^n is the n-fold
 * convolution of a 3-tap ZV (delays 0, m, m+1), i.e. at most (n+1)(n+2)/2 = 45 distinct delays
 * for n = 8. An input smoother has one tap per sample of its window (sms_shaper_tap_count()). */
#define SMS_SHAPER_MAX_TAPS 45

/** @brief Longest input smoother window L [samples]: every sample is a tap, so the work per
 * sample and of init grow with L (2^20: about 1 ms of init, 1e6 multiply-adds per sample);
 * longer ones are refused with ::SMS_ERR_TOO_LONG (at Ts = 10 us that is a 10 s kernel). */
#define SMS_INPUT_SMOOTHER_MAX_LENGTH 1048576

/** @brief One non-zero tap of a shaper: y[n] += gain x[n - delay]. */
typedef struct sms_shaper_tap {
    size_t delay;   /**< d_k [samples], strictly increasing along the table */
    sms_real gain;  /**< g_k; the gains of a table sum to 1 */
} sms_shaper_tap;

/** @brief Instance of one shaper. Fields are public for inspection; change them only through
 * the functions below. */
typedef struct sms_shaper {
    sms_kind kind;                        /**< a shaper or input-smoother kind */
    size_t length;                        /**< impulse response length L = max delay + 1 [samples] */
    size_t n_taps;                        /**< taps used, 1..::SMS_SHAPER_MAX_TAPS */
    sms_shaper_tap *taps;                 /**< caller table of n_taps taps (written by init) */
    sms_real rest;                        /**< operating point set by the last reset */
    sms_real *history;                    /**< caller buffer: the last L inputs (ring) */
    size_t history_len;                   /**< = length */
    size_t head;                          /**< ring index the next input is written to */
    double identity[SMS_STATE_IDENTITY_COUNT]; /**< config and Ts it was built for (config.h) */
} sms_shaper;

/**
 * @brief Reals of delay line a shaper of this config needs at period Ts (= its length L).
 * @param config  a shaper or input-smoother kind (::SMS_SHAPER_ZV .. ::SMS_SHAPER_MZV,
 *                ::SMS_SHAPER_EI3 .. ::SMS_SHAPER_IMPULSES); fields see config.h
 * @param Ts      sample period [s], finite, > 0
 * @param n_reals receives L
 * @return ::SMS_OK, ::SMS_ERR_NULL, then the first failing check in this order:
 *         ::SMS_ERR_SAMPLE_PERIOD (Ts NaN/Inf or <= 0; checked first, as the smoothers do),
 *         ::SMS_ERR_KIND (not a shaper kind, or a timing it does not have: the input
 *         smoothers have exact timing only),
 *         ::SMS_ERR_WN (NaN/Inf or <= 0), ::SMS_ERR_ABOVE_NYQUIST (wn >= pi/Ts; input
 *         smoothers: a kernel shorter than 4 Ts),
 *         ::SMS_ERR_ZETA (NaN/Inf or outside [0,1); [0, 0.25] for ::SMS_SMOOTH_ZV,
 *         ::SMS_SMOOTH_MZV, ::SMS_SMOOTH_EI), ::SMS_ERR_ORDER (ZVN: order outside
 *         1..::SMS_SHAPER_MAX_ORDER; GMZV: outside 3..::SMS_SHAPER_MAX_IMPULSES; SI: not 3, 5,
 *         7 or 9; IMPULSES: outside 1..::SMS_SHAPER_MAX_IMPULSES),
 *         ::SMS_ERR_TOLERANCE (EI, EI2, EI3, SI: outside (0,1)), ::SMS_ERR_SHAPER_DURATION
 *         (GMZV: duration NaN/Inf, outside (0, (order-1)/2), or a negative least-squares
 *         amplitude; SI: outside [(order-1)/4, (order-1)/2]),
 *         ::SMS_ERR_IMPULSE_AMPLITUDE, ::SMS_ERR_IMPULSE_TIME (IMPULSES, in that order, after
 *         the order; wn, zeta and the Nyquist check do not apply),
 *         ::SMS_ERR_TOO_LONG (L above 2^40 samples: state indices must stay exact doubles;
 *         an input smoother's above ::SMS_INPUT_SMOOTHER_MAX_LENGTH),
 *         ::SMS_ERR_ZETA also when exact timing cannot weigh the impulses in double (zeta so
 *         close to 1 that e^{zeta wn t} overflows over the span; paper timing still works).
 *         The fields T, sigma, k and notch_pole_zeta are not read (duration only by GMZV and
 *         SI, amplitudes and times only by IMPULSES).
 */
SMS_API sms_status sms_shaper_buffer_size(const sms_stage_config *config, double Ts, size_t *n_reals);
/**
 * @brief Entries of tap table a shaper of this config needs at period Ts: its number of
 * non-zero taps, 1..::SMS_SHAPER_MAX_TAPS (e.g. 3 for an exact-timing ZV off the sample grid,
 * 2 on it; 45 for exact ZV^8); for an input smoother its length L (every sample a tap).
 * @return as sms_shaper_buffer_size() (same checks, same order).
 * @param config  a shaper or input-smoother config (as sms_shaper_buffer_size())
 * @param Ts      sample period [s], finite, > 0
 * @param n_taps  receives the number of taps
 */
SMS_API sms_status sms_shaper_tap_count(const sms_stage_config *config, double Ts, size_t *n_taps);
/**
 * @brief Validate and build a shaper at rest at 0.
 * @param f       instance; untouched on error
 * @param taps    caller table of n_taps >= sms_shaper_tap_count() entries; init writes the
 *                taps into it and f keeps the pointer
 * @param buffer  caller memory of n_reals >= L reals (the delay line); kept by f
 * @return as sms_shaper_buffer_size(), or ::SMS_ERR_NULL (f, config, taps or buffer NULL),
 *         ::SMS_ERR_BUFFER_TOO_SMALL (n_taps or n_reals below the size queries). Nothing is
 *         written on error (neither f, nor the table, nor the buffer).
 * @param config  the stage description (checked as sms_shaper_buffer_size() says)
 * @param Ts      sample period [s], finite, > 0
 * @param n_taps  entries in taps
 * @param n_reals reals in buffer
 */
SMS_API sms_status sms_shaper_init(sms_shaper *f, const sms_stage_config *config, double Ts,
                                   sms_shaper_tap *taps, size_t n_taps, sms_real *buffer,
                                   size_t n_reals);
/** @brief Rest at `rest`: as if the input had been `rest` forever (the output is then `rest`).
 * @param f       the shaper, built by sms_shaper_init() or sms_shaper_init_coeffs()
 * @param rest    finite, |rest| <= ::SMS_INPUT_MAX
 */
SMS_API void sms_shaper_reset(sms_shaper *f, sms_real rest);
/** @brief One sample in place: x <- sum_k g_k x[n - d_k], computed as
 * x[n] + sum_k g_k (x[n - d_k] - x[n]) (the taps sum to 1): once the last L inputs are equal
 * the output is that input exactly, and after sms_shaper_reset(f, rest) an input of rest
 * comes out as rest from the first sample.
 * @param f       the shaper, built by sms_shaper_init() or sms_shaper_init_coeffs()
 * @param x       in: the input x[n]; out: the output y[n]
 */
SMS_API void sms_shaper_step(sms_shaper *f, sms_real *x);
/** @brief n samples; in == out allowed, other overlaps not. Same result as n calls of step.
 * @param f       the shaper, built by sms_shaper_init() or sms_shaper_init_coeffs()
 * @param in      n inputs
 * @param out     n outputs; may be in itself
 * @param n       number of samples, any
 */
SMS_API void sms_shaper_process(sms_shaper *f, const sms_real *in, sms_real *out, size_t n);
/** @brief Doubles in a saved state: ::SMS_STATE_IDENTITY_COUNT + L + 4 (the configuration
 * identity of config.h, then kind, L, head, rest, the delay line in ring order).
 * @param f       the shaper (read only)
 * @return ::SMS_STATE_IDENTITY_COUNT + L + 4
 */
SMS_API size_t sms_shaper_state_count(const sms_shaper *f);
/** @brief Write sms_shaper_state_count() doubles to dst.
 * @param f       the shaper (read only)
 * @param dst     sms_shaper_state_count() doubles
 */
SMS_API void sms_shaper_get_state(const sms_shaper *f, double *dst);
/** @brief Restore a saved state; validates first and writes nothing on error (::SMS_ERR_STATE:
 * wrong n, kind, length or head; ::SMS_ERR_NULL).
 * @param f       the shaper, built by sms_shaper_init() or sms_shaper_init_coeffs(); untouched on error
 * @param src     the saved state
 * @param n       its length in doubles, sms_shaper_state_count()
 * @return ::SMS_OK, ::SMS_ERR_NULL, ::SMS_ERR_STATE_FORMAT .. ::SMS_ERR_STATE_DURATION (saved by
 *         another configuration, config.h), or ::SMS_ERR_STATE
 */
SMS_API sms_status sms_shaper_set_state(sms_shaper *f, const double *src, size_t n);
/** @brief The validation of sms_shaper_set_state() alone: writes nothing.
 * @param f       the shaper (read only)
 * @param src     the saved state
 * @param n       its length in doubles
 * @return what sms_shaper_set_state() would return
 */
SMS_API sms_status sms_shaper_check_state(const sms_shaper *f, const double *src, size_t n);
/** @brief Is src a state a run with every input and rest value |x| <= x_max could reach? What
 * sms_shaper_check_state() accepts, with the rest and the delay line (the inputs as they came)
 * finite and within x_max. Writes nothing.
 * @return ::SMS_OK, what sms_shaper_check_state() returns, or ::SMS_ERR_STATE.
 * @param f       the shaper (read only)
 * @param src     the saved state
 * @param n       its length in doubles
 * @param x_max   the largest |input| of the run, finite, >= 0
 */
SMS_API sms_status sms_shaper_check_state_range(const sms_shaper *f, const double *src,
                                                size_t n, double x_max);
/**
 * @brief The continuous design: amplitudes (sum 1) and times [s] in increasing order.
 * @param capacity room in amplitudes and times; ::SMS_SHAPER_MAX_IMPULSES always suffices
 * @param count    receives the number of impulses (n+1 for ZV^n, 3 for EI and MZV, 4 for EI2,
 *                 5 for EI3, order for GMZV, SI and IMPULSES)
 * @return ::SMS_OK, ::SMS_ERR_NULL, the config's status (checked as for Ts -> 0, i.e. without
 *         the Nyquist and length checks; ::SMS_ERR_KIND for an input smoother, a kernel rather
 *         than impulses), ::SMS_ERR_BUFFER_TOO_SMALL (capacity < count), ::SMS_ERR_TOO_LONG
 *         (the damped period 2 pi/(wn sqrt(1 - zeta^2)) overflows double).
 * @param config   a shaper config (not an input smoother)
 * @param amplitudes receives the count amplitudes A_m
 * @param times    receives the count times t_m [s]
 */
SMS_API sms_status sms_shaper_impulses(const sms_stage_config *config, double *amplitudes,
                                       double *times, size_t capacity, size_t *count);
/**
 * @brief The realised discrete impulse response h[0..L-1] (double, whatever the build
 * precision), L from sms_shaper_buffer_size(). Zeros between the sparse taps are written.
 * @return as sms_shaper_buffer_size(), or ::SMS_ERR_BUFFER_TOO_SMALL (n_taps < L).
 * @param config  a shaper or input-smoother config
 * @param Ts      sample period [s], finite, > 0
 * @param taps    receives h[0..L-1]
 * @param n_taps  room in taps, >= L
 */
SMS_API sms_status sms_shaper_taps(const sms_stage_config *config, double Ts, double *taps, size_t n_taps);
/**
 * @brief The continuous design's transfer function H_c(s) at s = s_re + j s_im [1/s]: for a
 * shaper sum_m A_m e^{-s t_m} (the impulses of sms_shaper_impulses()), for an input smoother
 * int_0^T g(tau) e^{-s tau} dtau (composite Gauss-Legendre, to about 1e-16 of the integral's
 * scale). |H_c(p)| e^{-zeta wn t_end} at the pole p = -zeta wn + j wd is the fraction of a step's
 * vibration the continuous filter leaves (t_end its last impulse time or T).
 * @return ::SMS_OK, ::SMS_ERR_NULL, the config's status (checked as for
 *         sms_shaper_impulses()), ::SMS_ERR_WN (s not finite), ::SMS_ERR_TOO_LONG (the value
 *         overflows); nothing written on error.
 * @param config  a shaper or input-smoother config
 * @param s_re    Re s [1/s], finite
 * @param s_im    Im s [rad/s], finite
 * @param h_re    receives Re H_c(s)
 * @param h_im    receives Im H_c(s)
 */
SMS_API sms_status sms_shaper_transfer(const sms_stage_config *config, double s_re, double s_im,
                                       double *h_re, double *h_im);

/**
 * @brief Insensitivity of an SI shaper: the relative width I = (w_hi - w_lo)/wd of the band
 * around the mode over which its residual stays <= tolerance (undamped form; for zeta > 0 the
 * same band along Re s = -zeta wn), from the closed form of filter/shaper_si.c.
 * @param order      3, 5, 7 or 9 impulses
 * @param duration   span in damped periods, in [(order-1)/4, (order-1)/2]
 * @param tolerance  V in (0, 1)
 * @param insensitivity receives I in (0, 2)
 * @return ::SMS_OK, ::SMS_ERR_NULL, ::SMS_ERR_ORDER, ::SMS_ERR_TOLERANCE,
 *         ::SMS_ERR_SHAPER_DURATION (checked in that order); nothing written on error.
 */
SMS_API sms_status sms_shaper_si_insensitivity(unsigned order, double duration, double tolerance,
                                               double *insensitivity);
/**
 * @brief The shortest SI shaper whose residual stays <= tolerance over the relative band I
 * around the mode: the smallest duration over order = 3, 5, 7, 9 with
 * sms_shaper_si_insensitivity() >= I (bisection on the duration, to 1e-15 relative). Below the
 * band of the shortest (order 3, duration 1/2: ZV) that one is returned.
 * @param tolerance      V in (0, 1)
 * @param insensitivity  I in (0, 2)
 * @param order,duration receive the design (write them into sms_stage_config with kind
 *                       ::SMS_SHAPER_SI and the same tolerance)
 * @return ::SMS_OK, ::SMS_ERR_NULL, ::SMS_ERR_TOLERANCE, ::SMS_ERR_SHAPER_DURATION (I NaN or
 *         outside (0, 2)), ::SMS_ERR_ORDER (I wider than 9 impulses reach: about 1.43 at
 *         V = 0.05); nothing written on error.
 */
SMS_API sms_status sms_shaper_si_design(double tolerance, double insensitivity, unsigned *order,
                                        double *duration);

#ifdef __cplusplus
}
#endif
#endif
