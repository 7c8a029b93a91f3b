/* SPDX-License-Identifier: Apache-2.0 */
/* Kinematic design (docs/design.md, docs/sampled-limits.md): lengths of the shortest
 * rest-to-rest chain within n derivative bounds, as a continuous design and on a sample grid:
 * what is valid, which multiple of a mode the tuned last stage takes, and the public designs.
 * The recursion is in kinematic_continuous.c, the grid in kinematic_grid.c and
 * kinematic_overlap.c. Design-time code: libm is allowed here (not in any per-sample path). */
#include <math.h>
#include "smoothshaper/trajectory.h"
#include "trajectory/kinematic_parts.h"

/* Every duration the design can produce is a combination of these ratios (h/vmax, vmax/amax,
 * ...); keeping each within [KIN_RATIO_MIN, KIN_RATIO_MAX] keeps every intermediate of the
 * closed forms finite and non-zero, so the check makes the design O(n^2) for any input. */
#define KIN_RATIO_MAX 1e60
#define KIN_RATIO_MIN 1e-60

static sms_status check_ratio(double r)
{
    if (!(r <= KIN_RATIO_MAX))
        return SMS_ERR_TOO_LONG; /* also NaN (never here: inputs are finite and > 0) */
    if (!(r >= KIN_RATIO_MIN))
        return SMS_ERR_LIMIT;
    return SMS_OK;
}

static sms_status validate(double h, const double *limits, size_t n, sms_profile profile,
                           double wn, double zeta)
{
    size_t i;
    sms_status st;
    if (limits == NULL)
        return SMS_ERR_NULL;
    if (n < 1 || n > SMS_KINEMATIC_MAX_ORDER)
        return SMS_ERR_ORDER;
    if (!isfinite(h) || h == 0.0)
        return SMS_ERR_LIMIT;
    for (i = 0; i < n; ++i)
        if (!isfinite(limits[i]) || !(limits[i] > 0.0))
            return SMS_ERR_LIMIT;
    if ((unsigned)profile > (unsigned)SMS_PROFILE_DAMPED)
        return SMS_ERR_KIND;
    if (!isfinite(wn) || wn < 0.0 || (profile == SMS_PROFILE_DAMPED && wn == 0.0))
        return SMS_ERR_WN;
    if (profile == SMS_PROFILE_DAMPED && n < 2)
        return SMS_ERR_ORDER;
    if (wn > 0.0 && (!isfinite(zeta) || zeta < 0.0 || zeta >= 1.0))
        return SMS_ERR_ZETA;
    st = check_ratio(fabs(h) / limits[0]);
    for (i = 1; i < n && st == SMS_OK; ++i)
        st = check_ratio(limits[i - 1] / limits[i]);
    if (st == SMS_OK && wn > 0.0)
        st = check_ratio(1.0 / wn);
    return st;
}

/* The design: continuous lengths (Ts == 0) or lengths on the grid of Ts (docs/sampled-limits.md):
 * every stage but a mode-tuned last one lasts a whole number of samples N_k >= T_k/Ts, and
 * N_k >= N_{k+1} + ... + N_{n-1}, so the sampled differences obey the bounds. */
sms_status sms_kin_solve_sampled(double h, const double *limits, size_t n, sms_profile profile,
                                 double wn, double zeta, double Ts, double *T, sms_kin_last *last)
{
    sms_kin_plan p;
    sms_kin_tuned form = {0, 0.0, 0.0, 0.0, 0.0, 0.0};
    size_t i;
    double support_last = 0.0;
    sms_status st = validate(h, limits, n, profile, wn, zeta);
    if (st != SMS_OK)
        return st;
    if (!(Ts >= 0.0) || !isfinite(Ts))
        return SMS_ERR_SAMPLE_PERIOD;
    p.n = n;
    for (i = 0; i < n; ++i)
        p.L[i] = limits[i];
    h = fabs(h);
    last->sigma = 0.0;
    last->k = 1u;
    last->timing = SMS_TIMING_EXACT;
    last->kind = profile == SMS_PROFILE_TRIGONOMETRIC ? SMS_HARMONIC : SMS_RECTANGULAR;
    if (wn == 0.0) {
        p.fixed = 0;
        p.c_last = profile == SMS_PROFILE_TRIGONOMETRIC ? 0.5 * KIN_PI : 1.0;
        p.T_fixed = p.rho_fixed = 0.0;
        (void)sms_kin_solve_plan(&p, h, T);
    } else {
        /* Mode-tuned last stage: try the multiples k Tm, keep the shortest feasible chain.
         * Past the first k whose peak no longer caps the level below, durations only grow.
         * On a grid the stage keeps its exact length (its zero stays on the mode) and its
         * sampled peak density (largest tap / Ts) bounds the top derivative. */
        double wd = wn * sqrt(1.0 - zeta * zeta);
        double Tm, best = HUGE_VAL, Tbest[SMS_KINEMATIC_MAX_ORDER], supp_best = 0.0;
        const double reach = h / p.L[0]; /* h/vmax */
        unsigned k, step = 1u, kbest = 0u;
        if (profile == SMS_PROFILE_DAMPED) {
            last->kind = SMS_EXPONENTIAL;
            last->sigma = -zeta * wn;
        }
        if (profile == SMS_PROFILE_TRIGONOMETRIC) {
            Tm = 3.0 * KIN_PI / wd;
            step = 2u; /* odd multiples only */
        } else {
            Tm = 2.0 * KIN_PI / wd;
        }
        p.fixed = 1;
        p.c_last = 0.0;
        for (k = 1u; k <= SMS_KINEMATIC_MAX_MULTIPLE; k += step) {
            double Tk[SMS_KINEMATIC_MAX_ORDER], dur;
            int uncapped;
            p.T_fixed = k * Tm;
            if (p.T_fixed >= best)
                break; /* the chain lasts at least its tuned stage: no longer multiple wins */
            if (last->kind == SMS_RECTANGULAR && n > 1 && p.T_fixed < reach &&
                (p.T_fixed + reach) * (1.0 - 1e-12) >= best) {
                /* A tuned box F < h/vmax leaves the velocity to the other boxes: their
                 * convolution r (support R) is unimodal, so some window of length F holds at
                 * least F/R of its mass, and the chain's velocity peak h max(r over F)/F is at
                 * least h/R: within vmax, R >= h/vmax and the chain lasts at least
                 * F + h/vmax (docs/sampled-limits.md). That grows with F: no multiple below
                 * h/vmax wins; go on from the first one at or above it (the margin covers
                 * the durations' rounding). */
                double first = ceil(reach / Tm);
                if (first <= (double)k)
                    first = (double)k + 1.0; /* F rounded below h/vmax: still move on */
                if (first > (double)SMS_KINEMATIC_MAX_MULTIPLE)
                    break;
                k = (unsigned)first - 1u; /* the loop's increment lands on it (step 1) */
                continue;
            }
            p.rho_fixed = sms_kin_peak_density(last->kind, p.T_fixed, last->sigma);
            if (n == 1) {
                if (h * p.rho_fixed > p.L[0])
                    continue;
                uncapped = 1;
            } else {
                uncapped = p.L[n - 2] * p.rho_fixed <= p.L[n - 1];
            }
            dur = sms_kin_solve_plan(&p, h, Tk);
            if (dur < best) {
                best = dur;
                kbest = k;
                for (i = 0; i < n; ++i)
                    Tbest[i] = Tk[i];
            }
            if (uncapped)
                break;
        }
        if (kbest == 0u)
            return SMS_ERR_TOO_LONG;
        if (Ts > 0.0) {
            /* k is chosen on the continuous design (O(1) per multiple); its sampled taps
             * (the few that can be largest, O(1)) then set the density that bounds the top
             * derivative */
            double tap, ends;
            int changed = 0; /* density raised or multiple moved: the lengths are solved again */
            for (;;) {
                p.T_fixed = kbest * Tm;
                p.rho_fixed = sms_kin_peak_density(last->kind, p.T_fixed, last->sigma);
                st = sms_kin_tuned_taps(last->kind, p.T_fixed, last->sigma, kbest, Ts, &tap,
                                &supp_best, &ends, &form);
                if (st != SMS_OK)
                    return st;
                if (!(tap / Ts > p.rho_fixed * (1.0 + 1e-12))) /* within the taps' rounding */
                    break;
                p.rho_fixed = tap / Ts;
                changed = 1;
                if (n > 1 || h * p.rho_fixed <= p.L[0])
                    break;
                /* alone, the stage is the velocity stage: a half sine's sampled peak over
                 * vmax takes the next multiple (its peak falls as it grows) */
                kbest += step;
                if (kbest > SMS_KINEMATIC_MAX_MULTIPLE)
                    return SMS_ERR_TOO_LONG;
            }
            if (changed)
                (void)sms_kin_solve_plan(&p, h, Tbest);
            /* Copies of the stage one sample closer than its length overlap only where the
             * last tap of one meets the first tap of the next: with the taps non-negative,
             * that sample is at most their sum (same signs) or their difference, so the
             * structure may count one sample less when the sum is within the bound
             * (docs/sampled-limits.md). */
            if (ends <= p.rho_fixed * Ts)
                supp_best -= 1.0;
        }
        last->k = kbest;
        if (Ts > 0.0)
            last->timing = sms_kin_tuned_timing(last->kind);
        support_last = supp_best;
        for (i = 0; i < n; ++i)
            T[i] = Tbest[i];
    }
    if (Ts > 0.0) {
        double N[SMS_KINEMATIC_MAX_ORDER];
        st = sms_kin_on_grid(&p, h, T, last->kind, wn > 0.0, support_last, &form, Ts, N);
        if (st != SMS_OK)
            return st;
        for (i = 0; i < n; ++i)
            if (N[i] > 0.0)
                T[i] = N[i] * Ts;
    }
    /* A length beyond double (a whole number of samples of a Ts near DBL_MAX, pi/2 of a huge
     * ratio) is no design: refused rather than returned as inf. */
    for (i = 0; i < n; ++i)
        if (!isfinite(T[i]))
            return SMS_ERR_TOO_LONG;
    return SMS_OK;
}

sms_status sms_kin_solve(double h, const double *limits, size_t n, sms_profile profile,
                         double wn, double zeta, double *T, sms_kin_last *last)
{
    return sms_kin_solve_sampled(h, limits, n, profile, wn, zeta, 0.0, T, last);
}

/* The solve both public designs share, with their capacity check. */
static sms_status solve_into(double h, const double *limits, size_t n, sms_profile profile,
                             double wn, double zeta, double Ts, size_t capacity,
                             double lengths[SMS_KINEMATIC_MAX_ORDER], sms_kin_last *last)
{
    sms_status st = sms_kin_solve_sampled(h, limits, n, profile, wn, zeta, Ts, lengths, last);
    if (st != SMS_OK)
        return st;
    return capacity < n ? SMS_ERR_BUFFER_TOO_SMALL : SMS_OK;
}

sms_status sms_kinematic_design(double h, const double *limits, size_t n, sms_profile profile,
                                double wn, double zeta, double Ts, double *T, size_t capacity,
                                size_t *count)
{
    double lengths[SMS_KINEMATIC_MAX_ORDER];
    sms_kin_last last;
    size_t i;
    sms_status st;
    if (T == NULL || count == NULL)
        return SMS_ERR_NULL;
    st = solve_into(h, limits, n, profile, wn, zeta, Ts, capacity, lengths, &last);
    if (st != SMS_OK)
        return st;
    for (i = 0; i < n; ++i)
        T[i] = lengths[i];
    *count = n;
    return SMS_OK;
}

sms_status sms_kinematic_configs(double h, const double *limits, size_t n, sms_profile profile,
                                 double wn, double zeta, double Ts, sms_stage_config *configs,
                                 size_t capacity, size_t *count)
{
    double lengths[SMS_KINEMATIC_MAX_ORDER];
    sms_kin_last last;
    size_t i;
    sms_status st;
    if (configs == NULL || count == NULL)
        return SMS_ERR_NULL;
    if (!(Ts > 0.0) || !isfinite(Ts))
        return SMS_ERR_SAMPLE_PERIOD;
    st = solve_into(h, limits, n, profile, wn, zeta, Ts, capacity, lengths, &last);
    if (st != SMS_OK)
        return st;
    for (i = 0; i < n; ++i) {
        configs[i] = sms_stage_config_default(SMS_RECTANGULAR);
        configs[i].T = lengths[i];
    }
    configs[n - 1].kind = last.kind;
    configs[n - 1].sigma = last.sigma;
    configs[n - 1].k = last.k;
    configs[n - 1].timing = last.timing;
    *count = n;
    return SMS_OK;
}

