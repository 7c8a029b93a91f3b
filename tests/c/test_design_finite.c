/* SPDX-License-Identifier: Apache-2.0 */
/* No design returns SMS_OK with an infinite or NaN length or duration: every design function of
 * the public API over a grid of extreme arguments (from the smallest subnormal to DBL_MAX, and
 * the values around the thresholds where a length stops fitting), each result either a non-OK
 * status or finite. The trigonometric kinematic profile at Ts >= 1e308 returned SMS_OK with
 * T = inf, and the phase-synchronised duration returned inf or NaN for a long or slow move
 * (vmax = 4.9e-324 over 1e-6: the unit limits vmax/|d|, amax/|d| it formed underflowed). */
#include <float.h>
#include <math.h>
#include <string.h>
#include "check.h"

/* Positive magnitudes from the smallest subnormal to DBL_MAX. */
static const double mags[] = {4.9e-324, 1e-310, DBL_MIN, 1e-300, 1e-200, 1e-100, 1e-20, 1e-9,
                              1e-6, 1e-3, 0.5, 1.0, 3.0, 1e3, 1e9, 1e20, 1e100, 1e200, 1e300,
                              1e306, 1e307, 1e308, 1.7e308, DBL_MAX};
#define N_MAGS (sizeof mags / sizeof mags[0])

static int bad;   /* OK with a non-finite result, reported once per function and case */

static void expect_finite(const char *what, sms_status st, const double *v, size_t n,
                          double a, double b, double c)
{
    size_t i;
    if (st != SMS_OK)
        return;
    for (i = 0; i < n; ++i)
        if (!isfinite(v[i])) {
            if (bad++ < 200)
                fprintf(stderr, "%s(%g, %g, %g): SMS_OK with result[%zu] = %g\n", what, a, b, c,
                        i, v[i]);
            CHECK(0);
            return;
        }
    CHECK(1);
}

static void design_for_mode(void)
{
    int kind;
    size_t i, j;
    for (kind = 0; kind < SMS_KIND_COUNT; ++kind)
        for (i = 0; i < N_MAGS; ++i)
            for (j = 0; j < 4; ++j) {
                const double zeta[] = {0.0, 0.3, 0.999999, 1e-300};
                sms_stage_config c;
                sms_status st = sms_design_for_mode((sms_kind)kind, mags[i], zeta[j], 1u, &c);
                double v[3];
                v[0] = c.T;
                v[1] = c.wn;
                v[2] = c.sigma;
                expect_finite("sms_design_for_mode", st, v, 3, kind, mags[i], zeta[j]);
                if (st == SMS_OK) {
                    double amp[SMS_SHAPER_MAX_IMPULSES], times[SMS_SHAPER_MAX_IMPULSES];
                    size_t count = 0;
                    if (kind >= SMS_SHAPER_ZV && kind != SMS_NOTCH_TUSTIN && kind != SMS_NOTCH_MATCHED
                        && sms_shaper_impulses(&c, amp, times, SMS_SHAPER_MAX_IMPULSES, &count) == SMS_OK) {
                        expect_finite("sms_shaper_impulses (times)", SMS_OK, times, count, kind,
                                      mags[i], zeta[j]);
                        expect_finite("sms_shaper_impulses (amplitudes)", SMS_OK, amp, count, kind,
                                      mags[i], zeta[j]);
                    }
                }
            }
}

static void kinematic(void)
{
    const sms_profile profiles[] = {SMS_PROFILE_POLYNOMIAL, SMS_PROFILE_TRIGONOMETRIC,
                                    SMS_PROFILE_DAMPED};
    const double Ts_values[] = {0.0, 1e-3, 1.0, 1e300, 1e307, 1e308, DBL_MAX};
    size_t p, i, j, t, n;
    for (p = 0; p < 3; ++p)
        for (n = 1; n <= 3; ++n)
            for (i = 0; i < N_MAGS; i += 1)
                for (j = 0; j < N_MAGS; j += 3)
                    for (t = 0; t < sizeof Ts_values / sizeof Ts_values[0]; ++t) {
                        double limits[3], T[8];
                        sms_stage_config cfg[8];
                        size_t count = 0, k;
                        sms_status st;
                        limits[0] = mags[j];
                        limits[1] = mags[(j + 5) % N_MAGS];
                        limits[2] = mags[(j + 11) % N_MAGS];
                        st = sms_kinematic_design(mags[i], limits, n, profiles[p],
                                                  p == 2 ? 50.0 : 0.0, p == 2 ? 0.1 : 0.0,
                                                  Ts_values[t], T, 8, &count);
                        expect_finite("sms_kinematic_design", st, T, count, mags[i], limits[0],
                                      Ts_values[t]);
                        if (Ts_values[t] > 0.0) {
                            st = sms_kinematic_configs(mags[i], limits, n, profiles[p],
                                                       p == 2 ? 50.0 : 0.0, p == 2 ? 0.1 : 0.0,
                                                       Ts_values[t], cfg, 8, &count);
                            for (k = 0; k < (st == SMS_OK ? count : 0u); ++k)
                                T[k] = cfg[k].T;
                            expect_finite("sms_kinematic_configs", st, T, st == SMS_OK ? count : 0u,
                                          mags[i], limits[0], Ts_values[t]);
                        }
                    }
    /* the case that was reported: trigonometric profile, Ts at or beyond 1e308 */
    {
        const double limits[3] = {1.0, 1.0, 1.0};
        double T[4];
        size_t count = 0;
        sms_status st = sms_kinematic_design(1.0, limits, 1, SMS_PROFILE_TRIGONOMETRIC, 0.0, 0.0,
                                             1e308, T, 4, &count);
        CHECK(st != SMS_OK || isfinite(T[0]));
    }
}

static void generators(void)
{
    const sms_profile profiles[] = {SMS_PROFILE_POLYNOMIAL, SMS_PROFILE_TRIGONOMETRIC,
                                    SMS_PROFILE_DAMPED};
    size_t p, i, j, t;
    for (p = 0; p < 3; ++p)
        for (i = 0; i < N_MAGS; i += 2)
            for (j = 0; j < N_MAGS; j += 2)
                for (t = 0; t < N_MAGS; t += 4) {
                    sms_generator_config c;
                    sms_generator_reach_info r;
                    size_t need = 0;
                    double v[4];
                    sms_status st;
                    c.vmax = mags[i];
                    c.amax = mags[j];
                    c.jmax = mags[(i + j) % N_MAGS];
                    c.profile = profiles[p];
                    c.wn = p == 2 ? 50.0 : 0.0;
                    c.zeta = p == 2 ? 0.1 : 0.0;
                    c.vmin = c.amin = 0.0; /* symmetric */
                    c.qmin = c.qmax = 0.0; /* no position limits */
                    st = sms_generator_reach(&c, mags[t], &r);
                    v[0] = r.peak_acceleration;
                    v[1] = r.duration;
                    v[2] = r.distance;
                    v[3] = r.samples;
                    expect_finite("sms_generator_reach", st, v, 4, c.vmax, c.amax, mags[t]);
                    (void)sms_generator_buffer_size(&c, mags[t], &need);
                }
}

static void bspline_and_notch(void)
{
    size_t i, j;
    for (i = 0; i < N_MAGS; ++i)
        for (j = 0; j < N_MAGS; ++j) {
            double wn[2], T = 0.0, xi2 = 0.0;
            sms_status st;
            wn[0] = mags[i];
            wn[1] = mags[j];
            st = sms_bspline_period_for_modes(wn, 2, 1e-3, &T);
            expect_finite("sms_bspline_period_for_modes", st, &T, 1, mags[i], mags[j], 1e-3);
            st = sms_bspline_period_for_modes(wn, 1, mags[j], &T);
            expect_finite("sms_bspline_period_for_modes", st, &T, 1, mags[i], 0.0, mags[j]);
            st = sms_notch_pole_zeta_from_bandwidth(mags[i], 0.1, mags[j], &xi2);
            expect_finite("sms_notch_pole_zeta_from_bandwidth", st, &xi2, 1, mags[i], 0.1,
                          mags[j]);
        }
}

static void multi_phase(void)
{
    size_t i, j;
    for (i = 0; i < N_MAGS; i += 2)
        for (j = 0; j < N_MAGS; j += 2) {
            sms_multi_generator_config c;
            double delta[2], T = 0.0;
            sms_status st;
            memset(&c, 0, sizeof c);
            c.n_axes = 2;
            c.vmax[0] = c.vmax[1] = mags[i];
            c.amax[0] = c.amax[1] = mags[(i + 3) % N_MAGS];
            c.jmax[0] = c.jmax[1] = mags[(i + 7) % N_MAGS];
            c.sync = SMS_SYNC_PHASE;
            delta[0] = mags[j];
            delta[1] = -0.5 * mags[j];
            st = sms_multi_phase_duration(&c, delta, &T);
            expect_finite("sms_multi_phase_duration", st, &T, 1, mags[i], mags[j], 0.0);
        }
}

static void identify(void)
{
    size_t i, j;
    for (i = 0; i < N_MAGS; ++i)
        for (j = 0; j < N_MAGS; ++j) {
            sms_mode m;
            double v[4];
            sms_status st = sms_identify_from_peaks(0.0, 1.0, mags[i], 1.0 / (1.0 + mags[j]), &m);
            v[0] = m.wn;
            v[1] = m.zeta;
            v[2] = m.wd;
            v[3] = m.sigma;
            expect_finite("sms_identify_from_peaks", st, v, 4, mags[i], mags[j], 0.0);
        }
}

static void kinematic_batch(void)
{
    const double Ts_values[] = {0.0, 1e-3, 1e308, DBL_MAX};
    size_t i, j, t;
    for (i = 0; i < N_MAGS; i += 2)
        for (j = 0; j < N_MAGS; j += 3)
            for (t = 0; t < sizeof Ts_values / sizeof Ts_values[0]; ++t) {
                double h[2], limits[6], T[6];
                size_t index = 0;
                sms_status st;
                h[0] = mags[i];
                h[1] = -mags[(i + 7) % N_MAGS];
                limits[0] = limits[3] = mags[j];
                limits[1] = limits[4] = mags[(j + 5) % N_MAGS];
                limits[2] = limits[5] = mags[(j + 11) % N_MAGS];
                st = sms_kinematic_design_batch(2, h, 1, limits, 3, 3, SMS_PROFILE_TRIGONOMETRIC,
                                                0.0, 0.0, Ts_values[t], T, 6, &index);
                expect_finite("sms_kinematic_design_batch", st, T, 6, mags[i], limits[0],
                              Ts_values[t]);
            }
}

static void multi_reach(void)
{
    const double Ts_values[] = {1e-300, 1e-3, 1.0, 1e300, DBL_MAX};
    size_t i, j, t;
    for (i = 0; i < N_MAGS; i += 2)
        for (j = 0; j < N_MAGS; j += 3)
            for (t = 0; t < sizeof Ts_values / sizeof Ts_values[0]; ++t) {
                sms_multi_generator_config c;
                sms_generator_reach_info r;
                size_t axis = 0;
                double v[4];
                sms_status st;
                memset(&c, 0, sizeof c);
                c.n_axes = 2;
                c.sync = (i / 2) % 2 ? SMS_SYNC_PHASE : SMS_SYNC_INDEPENDENT;
                c.vmax[0] = mags[i];
                c.amax[0] = mags[j];
                c.jmax[0] = mags[(i + j) % N_MAGS];
                c.vmax[1] = c.amax[1] = c.jmax[1] = 1.0;
                st = sms_multi_generator_reach(&c, Ts_values[t], &r, &axis);
                v[0] = r.peak_acceleration;
                v[1] = r.duration;
                v[2] = r.distance;
                v[3] = r.samples;
                expect_finite("sms_multi_generator_reach", st, v, 4, c.vmax[0], c.amax[0],
                              Ts_values[t]);
            }
}

/* The duration of a phase-synchronised move scales exactly: with distance and limits times
 * 2^e it is unchanged, with the limits times 2^e, 2^2e, 2^3e it is divided by 2^e. Scaled this
 * way to the ends of the range (durations of 2^-320 s to 2^320 s, limits and distances to
 * 2^+-960; exponents that sqrt and cbrt take exactly), it must stay the unscaled duration times
 * its factor to the closed form's roundings (8 eps; the scaled limits stay normal). */
static void multi_phase_scaling(void)
{
    const double d0[3] = {0.3, -1.7, 0.05};
    const double v0[3] = {2.0, 0.5, 1.0}, a0[3] = {10.0, 3.0, 40.0}, j0[3] = {300.0, 90.0, 20.0};
    int set, e;
    /* the four regimes: cruise at vmax after reaching amax, cruise without reaching amax, peak
     * velocity below vmax with amax, jerk alone */
    const double scale[4] = {100.0, 100.0, 0.01, 1e-3}, a_factor[4] = {1.0, 1e6, 1.0, 1.0};
    for (set = 0; set < 4; ++set) {
        sms_multi_generator_config c;
        double T0 = 0.0, delta[3];
        size_t i;
        memset(&c, 0, sizeof c);
        c.n_axes = 3;
        c.sync = SMS_SYNC_PHASE;
        for (i = 0; i < 3; ++i) {
            c.vmax[i] = v0[i];
            c.amax[i] = a_factor[set] * a0[i];
            c.jmax[i] = j0[i];
            delta[i] = scale[set] * d0[i];
        }
        CHECK_STATUS(sms_multi_phase_duration(&c, delta, &T0), SMS_OK);
        for (e = -320; e <= 320; e += 20) {
            sms_multi_generator_config ct = c, cd = c;
            double dd[3], Tt = 0.0, Td = 0.0;
            sms_status st;
            for (i = 0; i < 3; ++i) {
                ct.vmax[i] = ldexp(c.vmax[i], e);
                ct.amax[i] = ldexp(c.amax[i], 2 * e);
                ct.jmax[i] = ldexp(c.jmax[i], 3 * e);
                cd.vmax[i] = ldexp(c.vmax[i], 3 * e);
                cd.amax[i] = ldexp(c.amax[i], 3 * e);
                cd.jmax[i] = ldexp(c.jmax[i], 3 * e);
                dd[i] = ldexp(delta[i], 3 * e);
            }
            st = sms_multi_phase_duration(&ct, delta, &Tt);
            if (st == SMS_OK)
                CHECK_CLOSE(ldexp(Tt, e), T0, 8.0 * DBL_EPSILON, T0);
            else
                CHECK_STATUS(st, SMS_ERR_TOO_LONG);
            st = sms_multi_phase_duration(&cd, dd, &Td);
            CHECK_STATUS(st, SMS_OK);
            if (st == SMS_OK)
                CHECK_CLOSE(Td, T0, 8.0 * DBL_EPSILON, T0);
        }
    }
    /* closed forms at the ends of the range, where a unit limit under- or overflows:
     * cruising at vmax for 1e300 s (amax/|d| = 1e-600), the jerk-limited 4 cbrt(|d|/(2 jmax))
     * of 1e-100 s and of 1e100 s */
    {
        const double d[3] = {1e300, 1e-300, 1.0}, v[3] = {1.0, 1.0, 1e300};
        const double a[3] = {1e-300, 1.0, 1e300}, j[3] = {1e-300, 1.0, 1e-300};
        const double expect[3] = {2e300, 0.79370052598409974 * 4e-100, 0.79370052598409974 * 4e100};
        for (set = 0; set < 3; ++set) {
            sms_multi_generator_config c;
            double T = 0.0;
            memset(&c, 0, sizeof c);
            c.n_axes = 1;
            c.vmax[0] = v[set];
            c.amax[0] = a[set];
            c.jmax[0] = j[set];
            CHECK_STATUS(sms_multi_phase_duration(&c, &d[set], &T), SMS_OK);
            CHECK_CLOSE(T, expect[set], 8.0 * DBL_EPSILON, expect[set]);
        }
    }
    /* the reported case: vmax = 4.9e-324 over 1e-6 lasts 2e317 s, more than a double holds */
    {
        sms_multi_generator_config c;
        const double delta[2] = {1e-6, -0.5e-6};
        double T = -1.0;
        memset(&c, 0, sizeof c);
        c.n_axes = 2;
        c.sync = SMS_SYNC_PHASE;
        c.vmax[0] = c.vmax[1] = 4.9e-324;
        c.amax[0] = c.amax[1] = 1.0;
        c.jmax[0] = c.jmax[1] = 1.0;
        CHECK_STATUS(sms_multi_phase_duration(&c, delta, &T), SMS_ERR_TOO_LONG);
        CHECK(T == -1.0);
    }
}

static void identify_record(void)
{
    const double Ts_values[] = {1e-300, 1e-3, 1.0, 1e300};
    double x[64];
    size_t i, t, k;
    for (i = 0; i < N_MAGS; i += 3)
        for (t = 0; t < sizeof Ts_values / sizeof Ts_values[0]; ++t) {
            sms_mode m;
            double v[4];
            sms_status st;
            for (k = 0; k < 64; ++k) /* 8 samples per period, decaying by 0.9 per period */
                x[k] = mags[i] * pow(0.9, (double)k / 8.0) * cos(0.785398163397448 * (double)k);
            st = sms_identify_from_record(x, 64, Ts_values[t], &m);
            v[0] = m.wn;
            v[1] = m.zeta;
            v[2] = m.wd;
            v[3] = m.sigma;
            expect_finite("sms_identify_from_record", st, v, 4, mags[i], Ts_values[t], 0.0);
        }
}

static void coeffs_make(void)
{
    const double Ts_values[] = {4.9e-324, 1e-300, 1e-3, 1.0, 1e300, DBL_MAX};
    int kind;
    size_t i, t, k;
    for (kind = 0; kind < SMS_KIND_COUNT; ++kind)
        for (i = 0; i < N_MAGS; ++i)
            for (t = 0; t < sizeof Ts_values / sizeof Ts_values[0]; ++t) {
                sms_stage_config c = sms_stage_config_default((sms_kind)kind);
                sms_stage_coeffs co;
                static sms_shaper_tap taps[SMS_SHAPER_MAX_TAPS];
                double v[8];
                size_t n = 0;
                sms_status st;
                c.T = mags[i];
                c.wn = 1.0 / mags[i];
                c.zeta = 0.1;
                c.sigma = kind == SMS_DAMPED_HARMONIC || kind == SMS_EXPONENTIAL ? -0.5 / mags[i] : 0.0;
                st = sms_stage_coeffs_make(&c, Ts_values[t], &co, taps, SMS_SHAPER_MAX_TAPS);
                if (st != SMS_OK)
                    continue;
                if (kind <= SMS_EXPONENTIAL) {
                    const sms_smoother_coeffs *s = &co.u.smoother;
                    v[n++] = (double)s->pole_m1_re;
                    v[n++] = (double)s->pole_im;
                    v[n++] = (double)s->pole_lo_re;
                    v[n++] = (double)s->pole_lo_im;
                    v[n++] = (double)s->gain;
                    v[n++] = (double)s->tail_re;
                    v[n++] = (double)s->tail_im;
                    for (k = 0; k < s->n_corrections; ++k)
                        CHECK(isfinite((double)s->correction_gain[k]));
                } else if (kind == SMS_NOTCH_TUSTIN || kind == SMS_NOTCH_MATCHED) {
                    v[n++] = (double)co.u.notch.d0;
                    v[n++] = (double)co.u.notch.d2;
                    v[n++] = (double)co.u.notch.a1;
                    v[n++] = (double)co.u.notch.a2;
                } else {
                    for (k = 0; k < co.u.shaper.n_taps; ++k)
                        CHECK(isfinite((double)co.u.shaper.taps[k].gain));
                }
                for (k = 0; k < SMS_STATE_IDENTITY_COUNT; ++k)
                    CHECK(isfinite(co.identity[k]));
                expect_finite("sms_stage_coeffs_make", st, v, n, kind, mags[i], Ts_values[t]);
            }
}

int main(void)
{
    design_for_mode();
    kinematic();
    generators();
    bspline_and_notch();
    multi_phase();
    multi_phase_scaling();
    kinematic_batch();
    multi_reach();
    coeffs_make();
    identify();
    identify_record();
    return check_summary("test_design_finite");
}
