/* SPDX-License-Identifier: Apache-2.0 */
/**
 * @file scheduled.h
 * @brief A ZV^n input shaper whose mode follows a scheduling signal (position, payload, any
 * measured variable) through a table (value -> wn, zeta): scheduled shaping
 * (docs/scheduled.md has the proofs of what follows).
 *
 * **Schedule.** The caller gives points (s_j, wn_j, zeta_j), s_j strictly increasing. Between
 * two points the mode's pole p = sigma + j wd (sigma = -zeta wn, wd = wn sqrt(1 - zeta^2)) is
 * interpolated linearly in s; outside the table it is that of the nearest end point. A
 * non-finite schedule value keeps the taps in use.
 *
 * **Filter (time-varying impulse times over one delay line).** At every update (every sample,
 * or every N: config.update_every) the taps are those of the exact-timing ZV^n of
 * docs/exact-mode.md for the current pole: the exact ZV is the unique filter with taps a0, a1,
 * a2 on delays 0, m and m + 1 (m = floor(mu), mu = pi/(wd Ts) the half period in samples) with
 * unit DC gain and a zero at z_p = e^{p Ts}; in closed form, with u = -e^{p Ts f}/K
 * (z_p^-m; f = mu - m, K = e^{sigma Ts mu} = e^{-zeta pi/sqrt(1 - zeta^2)}) and
 * v = u e^{-p Ts} (z_p^-(m+1)),
 *   a1 = Im v / D, a2 = -Im u / D, a0 = 1 - a1 - a2,  D = (1 - Re u) Im v - (1 - Re v) Im u,
 * and ZV^n is its n-fold convolution (a zero of multiplicity n on z_p). The output is
 *   y[n] = x[n] + sum_k g_k(n) (x[n - d_k(n)] - x[n])   (the taps g_k on delays d_k > 0),
 * so a constant input passes exactly. Hence (docs/scheduled.md): at every sample the frozen
 * filter is exactly the fixed exact ZV^n of the current mode (its zero on z_p, unit DC gain);
 * a schedule constant over the shaper's length gives exactly the fixed shaper's output; the
 * taps are continuous in the pole (a tap moves to the next delay as f passes 1), so the output
 * changes continuously with the schedule.
 *
 * Per update: one division, the exponentials by a series (no libm on the per-sample path), the
 * 3-tap solve and the n-fold convolution (at most 45 taps); per sample: the taps over the ring.
 * The design arithmetic is double in both builds, the signal path ::sms_real. Memory: the ring
 * of L = n (m_max + 1) + 1 reals, m_max from the lowest wd of the table (caller buffer,
 * sms_scheduled_buffer_size()).
 */
#ifndef SMOOTHSHAPER_SCHEDULED_H
#define SMOOTHSHAPER_SCHEDULED_H

#include <stdint.h>
#include "smoothshaper/shaper.h"

#ifdef __cplusplus
extern "C" {
#endif

/** @brief Most points of a schedule table. */
#define SMS_SCHEDULE_MAX_POINTS 64

/** @brief One point of a schedule: at scheduling value `value`, the mode (wn, zeta). */
typedef struct sms_schedule_point {
    double value;   /**< scheduling value (any unit), strictly increasing along the table */
    double wn;      /**< natural frequency [rad/s], finite, > 0, below pi/Ts */
    double zeta;    /**< damping ratio, [0, 1) */
} sms_schedule_point;

/**
 * @brief A scheduled shaper.
 *
 * | field | valid range |
 * |-------|-------------|
 * | kind | ::SMS_SHAPER_ZV, ::SMS_SHAPER_ZVD, ::SMS_SHAPER_ZVDD, ::SMS_SHAPER_ZVN |
 * | order | ::SMS_SHAPER_ZVN: n, 1 .. ::SMS_SHAPER_MAX_ORDER (else not read) |
 * | points, n_points | 1 .. ::SMS_SCHEDULE_MAX_POINTS points, values finite and strictly increasing |
 * | update_every | N >= 1: the taps are recomputed every N samples (1: every sample) |
 */
typedef struct sms_scheduled_config {
    sms_kind kind;                     /**< the ZV^n kind */
    unsigned order;                    /**< n of ::SMS_SHAPER_ZVN */
    const sms_schedule_point *points;  /**< the table, n_points entries */
    size_t n_points;                   /**< 1 .. ::SMS_SCHEDULE_MAX_POINTS */
    unsigned update_every;             /**< N >= 1 */
} sms_scheduled_config;

/** @brief Instance. Fields are public for inspection; change them only through the functions
 * below. */
typedef struct sms_scheduled {
    unsigned order;                          /**< n of ZV^n */
    unsigned update_every;                   /**< N */
    unsigned countdown;                      /**< the next update is in countdown - 1 samples */
    double Ts;                               /**< sample period [s] */
    size_t n_points;                         /**< points in the table */
    double value[SMS_SCHEDULE_MAX_POINTS];   /**< s_j */
    double sigma_ts[SMS_SCHEDULE_MAX_POINTS]; /**< sigma_j Ts */
    double wd_ts[SMS_SCHEDULE_MAX_POINTS];   /**< wd_j Ts */
    double schedule;                         /**< the value the taps were last computed for */
    size_t n_taps;                           /**< taps with d_k > 0 in use */
    size_t delay[SMS_SHAPER_MAX_TAPS];       /**< d_k, increasing */
    sms_real gain[SMS_SHAPER_MAX_TAPS];      /**< g_k */
    sms_real *ring;                          /**< caller buffer: the last L inputs */
    size_t len;                              /**< L */
    size_t head;                             /**< slot the next input is written to */
} sms_scheduled;

/** @brief Reals of ring buffer this config needs at Ts: L = n (m_max + 1) + 1.
 * @return ::SMS_OK, ::SMS_ERR_NULL, ::SMS_ERR_SAMPLE_PERIOD, ::SMS_ERR_KIND (not a ZV^n kind),
 *         ::SMS_ERR_ORDER (ZVN order, or n_points outside 1 .. ::SMS_SCHEDULE_MAX_POINTS),
 *         ::SMS_ERR_MULTIPLE (update_every 0), ::SMS_ERR_STATE (values not finite or not
 *         strictly increasing), ::SMS_ERR_WN, ::SMS_ERR_ABOVE_NYQUIST, ::SMS_ERR_ZETA (a point's
 *         mode, as sms_shaper_buffer_size() checks it), ::SMS_ERR_TOO_LONG.
 * @param config the schedule and the shaper (ranges in the table above)
 * @param Ts     sample period [s], finite, > 0
 * @param n_reals receives L
 */
SMS_API sms_status sms_scheduled_buffer_size(const sms_scheduled_config *config, double Ts,
                                             size_t *n_reals);
/** @brief Validate and build, at rest at 0 with the taps of the first point's mode.
 * @return as sms_scheduled_buffer_size(), ::SMS_ERR_NULL, ::SMS_ERR_BUFFER_TOO_SMALL. Nothing
 *         is written on error.
 * @param f      instance to fill; untouched on error
 * @param config the schedule and the shaper; the table is copied, config may go away
 * @param Ts     sample period [s], finite, > 0
 * @param buffer the ring, kept by f
 * @param n_reals reals in buffer, >= sms_scheduled_buffer_size()
 */
SMS_API sms_status sms_scheduled_init(sms_scheduled *f, const sms_scheduled_config *config,
                                      double Ts, sms_real *buffer, size_t n_reals);
/** @brief Rest at rest (the ring filled with it) with the taps of the schedule value s,
 * computed now; the updates follow on the next sample and every N samples after it.
 * @param f      the scheduled shaper, built by sms_scheduled_init()
 * @param rest   finite
 * @param s      the scheduling value, finite (outside the table: its nearest end point)
 */
SMS_API void sms_scheduled_reset(sms_scheduled *f, sms_real rest, double s);
/** @brief One sample in place, scheduled by s (the taps are updated first when due).
 * @param f      the scheduled shaper, built by sms_scheduled_init()
 * @param x      in: the input x[n]; out: the output y[n]
 * @param s      the scheduling value of this sample, finite
 */
SMS_API void sms_scheduled_step(sms_scheduled *f, sms_real *x, double s);
/** @brief n samples: in[i] scheduled by schedule[i]; in == out allowed. The same as n steps.
 * @param f      the scheduled shaper, built by sms_scheduled_init()
 * @param in     n inputs
 * @param schedule n scheduling values, finite
 * @param out    n outputs; may be in itself
 * @param n      number of samples, any
 */
SMS_API void sms_scheduled_process(sms_scheduled *f, const sms_real *in, const double *schedule,
                                   sms_real *out, size_t n);
/** @brief The mode the schedule maps s to (the interpolated pole as wn, zeta).
 * @param f      the scheduled shaper (read only)
 * @param s      the scheduling value, finite
 * @param wn     receives wn [rad/s]
 * @param zeta   receives zeta
 */
SMS_API void sms_scheduled_mode(const sms_scheduled *f, double s, double *wn, double *zeta);
/** @brief The impulse response h[0 .. L) of the taps in use (double): h[0] = 1 - sum g_k.
 * @return ::SMS_OK, ::SMS_ERR_NULL, ::SMS_ERR_BUFFER_TOO_SMALL (n < L).
 * @param f      the scheduled shaper (read only)
 * @param taps   receives h[0 .. L)
 * @param n      room in taps, >= L
 */
SMS_API sms_status sms_scheduled_taps(const sms_scheduled *f, double *taps, size_t n);
/** @brief The taps' lag (centroid) [samples], for align.h.
 * @param f      the scheduled shaper (read only)
 * @return the centroid sum_k k h[k] [samples], >= 0
 */
SMS_API double sms_scheduled_lag(const sms_scheduled *f);
/** @brief Doubles of a saved state: 5 + L (order, N, countdown, schedule, head, the ring).
 * @param f      the scheduled shaper (read only)
 * @return 5 + L
 */
SMS_API size_t sms_scheduled_state_count(const sms_scheduled *f);
/** @brief Write the state, sms_scheduled_state_count() doubles.
 * @param f    the scheduled shaper (read only)
 * @param dst  sms_scheduled_state_count() doubles */
SMS_API void sms_scheduled_get_state(const sms_scheduled *f, double *dst);
/** @brief Restore a state of an identically configured scheduled shaper (the taps recomputed
 * for the saved schedule value); ::SMS_ERR_STATE if it does not fit, and nothing written.
 * @param f      the scheduled shaper, built by sms_scheduled_init(); untouched on error
 * @param src    the saved state
 * @param n      its length in doubles, sms_scheduled_state_count()
 * @return ::SMS_OK, ::SMS_ERR_NULL or ::SMS_ERR_STATE
 */
SMS_API sms_status sms_scheduled_set_state(sms_scheduled *f, const double *src, size_t n);

#ifdef __cplusplus
}
#endif
#endif
