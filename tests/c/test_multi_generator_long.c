/* SPDX-License-Identifier: Apache-2.0 */
/* Multi-axis generator on long moves (10^3 to 10^5 s at Ts = 1 ms, 10^6 to 10^8 samples), both
 * sync modes, float and double: windows around every breakpoint of the move (start, end of
 * the first transition, mid-cruise, start of the stop, arrival), reached by setting the
 * move's sample count (the public struct; a saved state carries the same count).
 *
 * Checked, per axis, with u the unit roundoff of sms_real (float 2^-24, double 2^-53) and Q
 * the largest |q| of the move (the axis moves monotonically from its start to its target):
 *   backward differences |d^i q| / Ts^i <= L_i (1 + 1e-9) + 2^i 8 u Q / Ts^i (i = 1, 2, 3),
 * the rule of the single-axis generator's tests: each sample carries at most 8 u Q of
 * rounding, and a difference of order i sums 2^i of them;
 *   reported |v|, |a|, |j| <= L (1 + 32 u): every plan keeps the limits in its own arithmetic
 * but for the arrival's rounding onto a sample at most 2 eps of the move earlier (the cruise
 * velocity grows by up to 4 eps) and the roundings of the plan and of the evaluation
 * (docs/multi-axis.md);
 *   phase-synchronised arrival on sample n = T/Ts of the time-optimal duration T (the limits
 * are numbers of sms_real, so T is the duration the float build plans), to its rounding: the
 * arrival is the nearest sample when the planned end is within 2 eps after it, else the next
 * one, so n - 16 u n <= k_end <= n + 1 + 16 u n; the output is exactly the target from there.
 * Before positions were evaluated per phase, a breakpoint snapped within 64 eps of the whole
 * move: 7.6 samples of a 1000 s move in float, and the differences reached 8 vmax (77 at
 * 10^4 s, 770 at 10^5 s). */
#include <stdlib.h>
#include <string.h>
#include "check.h"
#include "xorshift.h"
#include "smoothshaper/multi_generator.h"

#ifdef SMS_USE_FLOAT
#define UNIT_ROUNDOFF 5.9604644775390625e-8
#else
#define UNIT_ROUNDOFF 1.1102230246251565e-16
#endif
#define REPORT_TOL (32.0 * UNIT_ROUNDOFF) /* 16 eps */
#define WIN 1500

static uint64_t rng = 2463534242u;
static double urand(void)
{
    return xorshift_uniform(&rng);
}
static double log_uniform(double lo, double hi)
{
    return lo * pow(hi / lo, urand());
}
static double real(double x) /* x as a number of sms_real */
{
    return (double)(sms_real)x;
}

static sms_real out[WIN][4 * SMS_MULTI_MAX_AXES];
static double worst[4], worst_reported[4];

/* Check one window of samples of every axis (differences from its fourth sample on). */
static void check_window(const sms_multi_generator_config *c, double Ts, const double *Q)
{
    size_t i, k;
    int d;
    for (i = 0; i < c->n_axes; ++i) {
        const double L[4] = {0.0, c->vmax[i], c->amax[i], c->jmax[i]};
        for (k = 0; k < WIN; ++k) {
            for (d = 1; d < 4; ++d) {
                double r = fabs((double)out[k][4 * i + d]) / L[d];
                if (r > worst_reported[d])
                    worst_reported[d] = r;
                CHECK(r <= 1.0 + REPORT_TOL);
            }
            if (k >= 3) {
                double q0 = out[k][4 * i], q1 = out[k - 1][4 * i], q2 = out[k - 2][4 * i],
                       q3 = out[k - 3][4 * i];
                const double diff[4] = {0.0, q0 - q1, q0 - 2 * q1 + q2,
                                        q0 - 3 * q1 + 3 * q2 - q3};
                for (d = 1; d < 4; ++d) {
                    double floor_ = ldexp(8.0 * UNIT_ROUNDOFF * Q[i], d) / pow(Ts, d);
                    double r = (fabs(diff[d]) / pow(Ts, d) - floor_) / L[d];
                    if (r > worst[d])
                        worst[d] = r;
                    if (!(r <= 1.0 + 1e-9)) {
                        CHECK(r <= 1.0 + 1e-9);
                        fprintf(stderr, "  axis %zu window sample %zu difference %d ratio %.9g\n",
                                i, k, d, r);
                        return;
                    }
                }
            }
        }
    }
}

static void long_move(double T, sms_sync sync)
{
    sms_multi_generator_config c;
    sms_multi_generator g;
    sms_multi_move saved[SMS_MULTI_MAX_AXES];
    sms_real start[SMS_MULTI_MAX_AXES], target[SMS_MULTI_MAX_AXES], turn[SMS_MULTI_MAX_AXES];
    double delta[SMS_MULTI_MAX_AXES], Q[SMS_MULTI_MAX_AXES], Ts = 1e-3, Tp = 0.0;
    size_t n = 3, i, k, w, groups = sync == SMS_SYNC_PHASE ? 1 : n;
    memset(&c, 0, sizeof c);
    c.n_axes = n;
    c.sync = sync;
    for (i = 0; i < n; ++i) {
        c.vmax[i] = real(log_uniform(0.1, 100.0));
        c.amax[i] = real(c.vmax[i] * log_uniform(1.0, 100.0));
        c.jmax[i] = real(c.amax[i] * log_uniform(1.0, 100.0));
        start[i] = (sms_real)((2.0 * urand() - 1.0) * 10.0);
        /* axis 0 cruises at vmax for about T; the others move less (phase) or arrive
         * earlier (independent) */
        target[i] = (sms_real)((double)start[i] +
                               (i == 0 ? 1.0 : 2.0 * urand() - 1.0) * c.vmax[i] * T);
        delta[i] = (double)target[i] - (double)start[i];
        /* a target that replaces it mid-cruise (the blend window) */
        turn[i] = (sms_real)((double)start[i] + (2.0 * urand() - 1.0) * c.vmax[i] * T);
        Q[i] = fmax(fabs((double)start[i]), fmax(fabs((double)target[i]), fabs((double)turn[i])));
    }
    Ts = real(Ts);
    CHECK_STATUS(sms_multi_generator_init(&g, &c, Ts, NULL, 0, NULL, 0, NULL), SMS_OK);
    sms_multi_generator_reset(&g, start);
    sms_multi_generator_step(&g, target, out[0]);
    CHECK(g.dropped == 0 && sms_multi_generator_busy(&g));
    if (sync == SMS_SYNC_PHASE) {
        double nT;
        CHECK_STATUS(sms_multi_phase_duration(&c, delta, &Tp), SMS_OK);
        nT = Tp / Ts;
        CHECK((double)g.move[0].k_end >= nT - 16.0 * UNIT_ROUNDOFF * nT &&
              (double)g.move[0].k_end <= nT + 1.0 + 16.0 * UNIT_ROUNDOFF * nT);
    }
    memcpy(saved, g.move, sizeof saved);
    for (w = 0; w < 5; ++w) {
        for (i = 0; i < groups; ++i) {
            sms_multi_move *m = &g.move[i];
            const double k_end = (double)saved[i].k_end;
            const double at[5] = {1.0, saved[i].T1 / Ts - WIN / 2, 0.5 * k_end,
                                  k_end - saved[i].T2 / Ts - WIN / 2, k_end - WIN + 100};
            double k0 = at[w] < 1.0 ? 1.0 : at[w];
            *m = saved[i];
            if (k0 > k_end - 1.0)
                k0 = k_end - 1.0;
            m->k = (size_t)k0 - 1u; /* the next step outputs sample k0 */
        }
        for (k = 0; k < WIN; ++k)
            sms_multi_generator_step(&g, target, out[k]);
        check_window(&c, Ts, Q);
        if (w == 4) /* arrived: exactly on the target, at rest */
            for (i = 0; i < n; ++i)
                CHECK(out[WIN - 1][4 * i] == target[i] && out[WIN - 1][4 * i + 1] == 0);
    }
    /* a new target 100 samples into a window at 30 % of the move: the move blends into one
     * towards it from the cruise, at a move time of up to 10^5 s */
    for (i = 0; i < groups; ++i) {
        g.move[i] = saved[i];
        g.move[i].k = (size_t)(0.3 * (double)saved[i].k_end);
    }
    for (k = 0; k < WIN; ++k)
        sms_multi_generator_step(&g, k < 100 ? target : turn, out[k]);
    CHECK(g.dropped == 0);
    check_window(&c, Ts, Q);
}

int main(void)
{
    static const double lengths[3] = {1e3, 1e4, 1e5};
    int m, trial;
    for (m = 0; m < 3; ++m)
        for (trial = 0; trial < 4; ++trial)
            long_move(lengths[m] * log_uniform(1.0, 2.0),
                      trial % 2 ? SMS_SYNC_INDEPENDENT : SMS_SYNC_PHASE);
    printf("long moves: largest (|d^i q|/Ts^i - rounding)/limit %.9g %.9g %.9g, "
           "reported v, a, j / limit %.9g %.9g %.9g\n",
           worst[1], worst[2], worst[3], worst_reported[1], worst_reported[2],
           worst_reported[3]);
    return check_summary("test_multi_generator_long");
}
