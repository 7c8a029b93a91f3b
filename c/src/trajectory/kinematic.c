/* Kinematic design (docs/design.md, docs/sampled-limits.md): lengths of the shortest
 * rest-to-rest chain within n derivative bounds, as a continuous design and on a sample grid.
 * Design-time code: libm is allowed here (not in any per-sample path). */
#include <math.h>
#include "smoothshaper/trajectory.h"
#include "trajectory/trajectory_internal.h"
#include "filter/smoother_design.h"

#define KIN_PI 3.14159265358979323846

/*
 * The recursion. A chain M(T0) * C' turns a step of X into a motion whose velocity is
 * (X/T0) times the step response of C' (the rise), held, then the mirrored fall, provided
 * T0 >= D' (the rise's duration) so that rise and fall do not overlap. The rise is the same
 * problem one derivative down: displacement V = X/T0 with the bounds limits[k+1..]. So
 *   D_k(X) = min over V <= cap_k of X/V + D_{k+1}(V)   subject to X/V >= D_{k+1}(V).
 * Time scaling gives D(lambda X) <= lambda D(X) for lambda >= 1, hence V D'(V) <= D(V) and
 * X/V + D_{k+1}(V) decreases with V on the feasible set: V is cap_k when feasible ("stage k
 * at its bound"), else the largest V with X/V = D_{k+1}(V) ("stage k tight": T_k equals the
 * duration of the stages below it).
 *
 * Closed form per regime (no nested root finding, so the cost is O(n^2) for any input).
 * Let m >= k be the first stage at its bound, stages k..m-1 tight, S = T_m + ... + T_{n-1}.
 * Tight stages double the duration: T_{m-1} = S, T_{m-2} = 2 S, ..., T_k = 2^(m-1-k) S, and
 * the level entering m is X_m = X / (2^(d(d-1)/2) S^d), d = m - k. Below a stage at its bound
 * the problem restarts from the known level cap_m, whose duration C_m = D_{m+1}(cap_m) is a
 * constant (computed once, bottom up). With T_m = X_m / cap_m and S = T_m + C_m:
 *   S^d (S - C_m) = X / (2^(d(d-1)/2) cap_m),
 * increasing in S >= C_m with its root in [max(C_m, K^(1/(d+1))), C_m + K^(1/(d+1))]. The
 * last stage ends the recursion: free, T = c X_{n-1}/L_{n-1} gives S^(d+1) = c X/(2^.. L);
 * fixed (tuned to a mode), S = T_fixed. The regime is the first m whose decisions agree with
 * the recursion: not at the bound at j < m (X_j/cap_j < C_j), at the bound at m.
 */

#define KIN_TOL 1e-12

/* Largest level allowed at stage k (a fixed last stage caps the level below it). */
static double level_cap(const sms_kin_plan *p, size_t k)
{
    double cap = p->L[k];
    if (p->fixed && k + 2 == p->n) {
        double c = p->L[p->n - 1] / p->rho_fixed;
        if (c < cap)
            cap = c;
    }
    return cap;
}

/* Root S of d ln S + ln(S - C) = ln K, i.e. S^d (S - C) = K, on the bracket of the header
 * comment (r = K^(1/(d+1))). d = 0: S = C + K. d = 1 (a velocity/acceleration/jerk move
 * with vmax out of reach and amax reached): the quadratic, S = (C + sqrt(C^2 + 4 r^2))/2.
 * d >= 2: Newton on F(S) = d ln S + ln(S - C) - ln K, which is increasing and concave, from
 * S0 = C + K/(C + r)^d (F(S0) <= 0, since S0 <= C + r): the iterates rise monotonically to
 * the root, quadratically. Finally S moves up by ulps until F(S) >= 0 (the side on which
 * the stages fit, as the recursion's decisions expect). */
static double tight_root(unsigned d, double C, double logK)
{
    double r = exp(logK / (double)(d + 1u)), S;
    int it;
    if (d == 0u) {
        S = C + r;
    } else if (d == 1u) {
        S = 0.5 * (C + hypot(C, 2.0 * r));
    } else {
        S = C + exp(logK - (double)d * log(C + r));
        for (it = 0; it < 100; ++it) {
            double f = (double)d * log(S) + log(S - C) - logK;
            double step = f / ((double)d / S + 1.0 / (S - C));
            if (!(step < 0.0) || -step <= 1e-16 * S)
                break;
            S -= step;
        }
    }
    if (S <= C) /* C + r rounded to C: the root is within an ulp of C */
        S = nextafter(C, HUGE_VAL);
    /* d <= 1: compare S^d (S - C) with K = r^(d+1) directly (no logarithm) */
    for (it = 0; it < 8; ++it) {
        int low = d == 0u ? S - C < r
                : d == 1u ? S * (S - C) < r * r
                          : (double)d * log(S) + log(S - C) < logK;
        if (!low)
            break;
        S = nextafter(S, HUGE_VAL);
    }
    return S;
}

/* The end of a solve from stage k whose stage m is at its bound with length Tm and whose
 * stages below m last `rest`: the tight stages k..m-1 above m are each exactly the sum of
 * those below them. Lengths into T[k..m] when T != NULL; returns the duration from k. */
static double at_bound(size_t k, size_t m, double Tm, double rest, double *T)
{
    if (Tm < rest) /* rounding at a regime boundary: keep the structure exact */
        Tm = rest;
    if (T != NULL) {
        double below = Tm + rest;
        size_t i;
        T[m] = Tm;
        for (i = m; i-- > k;) {
            T[i] = below;
            below += T[i];
        }
    }
    return m > k ? ldexp(Tm + rest, (int)(m - k)) : Tm + rest;
}

/* Duration D_k(X) of stages k..n-1; lengths into T[k..] when T != NULL. C[j] = D_{j+1}(cap_j)
 * must be known for j >= k. */
static double solve_from(const sms_kin_plan *p, const double *C, size_t k, double X, double *T)
{
    size_t m, best_m = p->n - 1, j;
    double best_S = 0.0, best_bad = HUGE_VAL, logX = log(X);
    for (m = k; m < p->n; ++m) {
        unsigned d = (unsigned)(m - k);
        double logc = 0.5 * (double)d * ((double)d - 1.0) * 0.69314718055994530942;
        double S, logXm, bad = 0.0, lx;
        if (m + 1 == p->n) {
            if (p->fixed)
                S = p->T_fixed;
            else
                S = exp((log(p->c_last) + logX - logc - log(p->L[m])) / (double)(d + 1u));
        } else {
            S = tight_root(d, C[m], logX - logc - log(level_cap(p, m)));
        }
        logXm = logX - logc - (double)d * log(S);
        /* the recursion's decisions: stages k..m-1 below their bound, m at it */
        lx = logX;
        for (j = k; j < m; ++j) {
            double Tj = ldexp(S, (int)(m - 1 - j)), excess = lx - log(level_cap(p, j) * C[j]);
            if (excess > bad)
                bad = excess;
            lx -= log(Tj);
        }
        if (m + 1 < p->n) {
            double deficit = log(C[m] * level_cap(p, m)) - logXm;
            if (deficit > bad)
                bad = deficit;
        }
        if (bad <= KIN_TOL) {
            best_m = m;
            best_S = S;
            best_bad = bad;
            break;
        }
        if (bad < best_bad) {
            best_bad = bad;
            best_m = m;
            best_S = S;
        }
    }
    m = best_m;
    {
        double S = best_S, total;
        if (T != NULL)
            for (j = k; j < m; ++j)
                T[j] = ldexp(S, (int)(m - 1 - j));
        total = ldexp(S, (int)(m - k));
        if (m + 1 == p->n) {
            if (T != NULL)
                T[m] = S;
            return total;
        }
        /* stage m at its bound, then the problem from the level cap_m */
        {
            double X_m = exp(logX - 0.5 * (double)(m - k) * ((double)(m - k) - 1.0) *
                             0.69314718055994530942 - (double)(m - k) * log(S));
            double cap = level_cap(p, m), rest;
            rest = solve_from(p, C, m + 1, cap, T);
            return at_bound(k, m, X_m / cap, rest, T);
        }
    }
}

/*
 * The same recursion in plain arithmetic, for problems of moderate size (plan_is_moderate:
 * n <= 4 and every input within [1e-30, 1e30]). There every intermediate stays far inside
 * double's range (levels X_j within 1e-150..1e210, S^d with d <= 3, products cap_j C_j below
 * 1e90), so no logarithm is needed: a design costs a few divisions and at most one or two
 * roots (sqrt, cbrt) instead of tens of log/exp calls. Decisions and tolerances are the
 * logarithmic ones: bad <= KIN_TOL there is ratio <= e^KIN_TOL = 1 + KIN_TOL here.
 */
#define KIN_RATIO_TOL (1.0 + KIN_TOL)
#define KIN_MODERATE_MAX 1e30
#define KIN_MODERATE_MIN 1e-30

static int moderate(double v)
{
    return v >= KIN_MODERATE_MIN && v <= KIN_MODERATE_MAX;
}

static int plan_is_moderate(const sms_kin_plan *p, double h)
{
    size_t i;
    if (p->n > 4u || !moderate(h))
        return 0;
    for (i = 0; i < p->n; ++i)
        if (!moderate(p->L[i]))
            return 0;
    return !p->fixed || (moderate(p->T_fixed) && moderate(p->rho_fixed));
}

/* v^(1/e) for e = 1..4 (the free last stage below d = e - 1 tight stages). */
static double root_of(double v, unsigned e)
{
    switch (e) {
    case 1u: return v;
    case 2u: return sqrt(v);
    case 3u: return cbrt(v);
    default: return sqrt(sqrt(v));
    }
}

/* Root S >= C of S^d (S - C) = K (d <= 2 here). d = 0, 1: closed forms. d = 2: Newton on the
 * increasing convex G(S) = S^2 (S - C) - K from S0 = C + K^(1/3) >= the root: the iterates
 * fall monotonically to it, quadratically. Then, as tight_root(), S moves up by ulps until
 * G(S) >= 0. */
static double tight_root_plain(unsigned d, double C, double K)
{
    double S;
    int it;
    if (d == 0u) {
        S = C + K;
    } else if (d == 1u) {
        S = 0.5 * (C + sqrt(C * C + 4.0 * K));
    } else {
        S = C + cbrt(K);
        for (it = 0; it < 100; ++it) {
            double g = S * S * (S - C) - K;
            double step = g / (S * (3.0 * S - 2.0 * C));
            if (!(step > 0.0) || step <= 1e-16 * S)
                break;
            S -= step;
        }
    }
    if (S <= C)
        S = nextafter(C, HUGE_VAL);
    for (it = 0; it < 8; ++it) {
        double lhs = d == 0u ? S - C : d == 1u ? S * (S - C) : S * S * (S - C);
        if (!(lhs < K))
            break;
        S = nextafter(S, HUGE_VAL);
    }
    return S;
}

/* solve_from() in plain arithmetic (moderate problems only). */
static double solve_from_plain(const sms_kin_plan *p, const double *C, size_t k, double X,
                               double *T)
{
    size_t m, best_m = p->n - 1, j;
    double best_S = 0.0, best_bad = HUGE_VAL, S, Sd, Xm, rest, cap, c2;
    for (m = k; m < p->n; ++m) {
        unsigned d = (unsigned)(m - k), i;
        double bad = 1.0, lx;
        c2 = ldexp(1.0, (int)(d * (d - (d > 0u)) / 2u));   /* 2^(d(d-1)/2) */
        if (m + 1 == p->n)
            S = p->fixed ? p->T_fixed : root_of(p->c_last * X / (c2 * p->L[m]), d + 1u);
        else
            S = tight_root_plain(d, C[m], X / (c2 * level_cap(p, m)));
        for (i = 0, Sd = 1.0; i < d; ++i)
            Sd *= S;
        Xm = X / (c2 * Sd);
        /* the recursion's decisions: stages k..m-1 below their bound, m at it */
        lx = X;
        for (j = k; j < m; ++j) {
            double excess = lx / (level_cap(p, j) * C[j]);
            if (excess > bad)
                bad = excess;
            lx /= ldexp(S, (int)(m - 1 - j));
        }
        if (m + 1 < p->n) {
            double deficit = C[m] * level_cap(p, m) / Xm;
            if (deficit > bad)
                bad = deficit;
        }
        if (bad <= KIN_RATIO_TOL || bad < best_bad) {
            best_bad = bad;
            best_m = m;
            best_S = S;
            if (bad <= KIN_RATIO_TOL)
                break;
        }
    }
    m = best_m;
    S = best_S;
    if (T != NULL)
        for (j = k; j < m; ++j)
            T[j] = ldexp(S, (int)(m - 1 - j));
    if (m + 1 == p->n) {
        if (T != NULL)
            T[m] = S;
        return ldexp(S, (int)(m - k));
    }
    /* stage m at its bound, then the problem from the level cap_m */
    {
        unsigned d = (unsigned)(m - k), i;
        c2 = ldexp(1.0, (int)(d * (d - (d > 0u)) / 2u));
        for (i = 0, Sd = 1.0; i < d; ++i)
            Sd *= S;
    }
    cap = level_cap(p, m);
    rest = solve_from_plain(p, C, m + 1, cap, T);
    return at_bound(k, m, X / (c2 * Sd) / cap, rest, T);
}

/* D(h) and lengths for the whole chain: in plain arithmetic when the problem is moderate,
 * else in logarithms (any accepted input, ratios up to 1e60, up to 8 stages). */
static double solve_plan(const sms_kin_plan *p, double h, double *T)
{
    double C[SMS_KINEMATIC_MAX_ORDER];
    size_t m;
    if (plan_is_moderate(p, h)) {
        for (m = p->n - 1; m-- > 0;)
            C[m] = solve_from_plain(p, C, m + 1, level_cap(p, m), NULL);
        return solve_from_plain(p, C, 0, h, T);
    }
    for (m = p->n - 1; m-- > 0;)
        C[m] = solve_from(p, C, m + 1, level_cap(p, m), NULL);
    return solve_from(p, C, 0, h, T);
}

static double peak_density(sms_kind kind, double T, double sigma)
{
    switch (kind) {
    case SMS_HARMONIC:
        return 0.5 * KIN_PI / T;
    case SMS_EXPONENTIAL:
        /* 1/T (1 + |sigma T|/2 + ...): below 1e-15 that is 1/T to rounding, and a subnormal
         * sigma T would carry too few bits for the quotient */
        if (sigma * T < -1e-15)
            return -sigma / -expm1(sigma * T);
        return 1.0 / T;
    default:
        return 1.0 / T;
    }
}

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

/* Smallest whole number of samples N with N Ts >= T: round(nu) when nu passes the integer
 * test of docs/exact-mode.md, else ceil(nu); at least 1. */
static double grid_ceil(double nu)
{
    double r = floor(nu + 0.5);
    if (fabs(nu - r) <= 1e-9 * (nu > 1.0 ? nu : 1.0))
        return r < 1.0 ? 1.0 : r;
    return ceil(nu);
}

/* The taps of a bounded tuned stage as the exact top-level test reads them: tap0 on 0, gain q^i
 * on 1 .. L-2, tapL on L-1 (q = e^decay); `bounded` 0 when the stage is not of this form. */
typedef struct {
    int bounded;
    double tap0, tapL, gain, decay, L;
} kin_tuned;

/* The timing of a stage tuned to the mode on a grid: bounded taps (no tap above the peak
 * density the design budgets for), which only the half sine does not need. */
static sms_timing tuned_timing(sms_kind kind)
{
    return kind == SMS_HARMONIC ? SMS_TIMING_EXACT : SMS_TIMING_BOUNDED;
}

/* Largest tap of the stage tuned to the mode, its length in samples and the sum of its
 * first and last taps. */
static sms_status tuned_taps(sms_kind kind, double T, double sigma, unsigned k, double Ts,
                             double *peak, double *support, double *ends, kin_tuned *form)
{
    sms_stage_config c = sms_stage_config_default(kind);
    sms_smoother_design d;
    size_t cand[6], i;
    double best = 0.0;
    sms_status st;
    c.T = T;
    c.sigma = sigma;
    c.k = k;
    c.timing = tuned_timing(kind);
    st = sms_smoother_design_make(&c, Ts, &d);
    if (st != SMS_OK)
        return st;
    /* base taps are constant, decaying or one half sine: the peak is at an end, at the
     * corrected taps or at the middle of the sine */
    cand[0] = 0u;
    cand[1] = 1u;
    cand[2] = (size_t)(0.5 * d.nu);
    cand[3] = cand[2] + 1u;
    cand[4] = d.length >= 2u ? d.length - 2u : 0u;
    cand[5] = d.length - 1u;
    for (i = 0; i < 6; ++i)
        if (cand[i] < d.length) {
            double t = fabs(sms_smoother_design_tap(&d, cand[i]));
            if (t > best)
                best = t;
        }
    *peak = best;
    *support = (double)d.length;
    *ends = sms_smoother_design_tap(&d, 0u) + sms_smoother_design_tap(&d, d.length - 1u);
    form->bounded = c.timing == SMS_TIMING_BOUNDED && d.length >= 3u;
    form->tap0 = sms_smoother_design_tap(&d, 0u);
    form->tapL = sms_smoother_design_tap(&d, d.length - 1u);
    form->gain = d.gain;
    form->decay = d.decay;
    form->L = (double)d.length;
    return SMS_OK;
}

/* Largest tap of the integer-N harmonic stage: tan(pi/2N) (N even) or sin(pi/2N) (N odd). */
static double harmonic_peak_tap(double N)
{
    double x = 0.5 * KIN_PI / N;
    return fmod(N, 2.0) == 0.0 ? tan(x) : sin(x);
}

/* The sampled bounds of a chain of whole-sample stages N[0..n-1] (the last one may be tuned:
 * fixed taps of largest value tap_last over supp_last samples), all in logarithms:
 *  - structure: N[i] >= samples of the stages after it, so that the shifted copies in each
 *    backward difference never overlap (the discrete form of T_k >= T_k+1 + ... + T_n-1);
 *  - level i < n-1: h / (N[0] ... N[i] Ts^(i+1)) <= L[i];
 *  - top: h / (N[0] ... N[n-2] Ts^(n-1)) * (largest tap of the last stage) / Ts <= L[n-1].
 * Returns 1 when all hold (to 1e-12 relative). */
static int grid_feasible(const sms_kin_plan *p, double logh, double logTs, const double *N,
                         sms_kind last_kind, int tuned, double tap_last, double supp_last)
{
    size_t n = p->n, i;
    double below = tuned ? supp_last : N[n - 1], logprod = 0.0, logtap;
    for (i = n - 1; i-- > 0;) {
        if (N[i] < below)
            return 0;
        below += N[i];
    }
    for (i = 0; i + 1 < n; ++i) {
        logprod += log(N[i]);
        if (logprod < logh - log(p->L[i]) - (double)(i + 1) * logTs - 1e-12)
            return 0;
    }
    if (tuned)
        logtap = log(tap_last);
    else if (last_kind == SMS_HARMONIC) {
        if (N[n - 1] < 2.0)
            return 0; /* one sample of a half sine is its zero: not a stage */
        logtap = log(harmonic_peak_tap(N[n - 1]));
    }
    else
        logtap = -log(N[n - 1]);
    return logprod - logtap >= logh - log(p->L[n - 1]) - (double)n * logTs - 1e-12;
}

/*
 * The sampled differences of a chain of whole-sample moving averages, exactly. In samples, a
 * step of h through boxes of N_0 .. N_{n-1} samples has the i-th backward difference
 *   h / (N_0 ... N_{n-1}) * p(z) / (1 - z^-1)^(n-i+1),   p(z) = prod_j (1 - z^-N_j),
 * which depends on the multiset of lengths only. Split p = p_A p_B with A the i largest
 * lengths: p_A / (1 - z^-1) is a running count c_A (the signed number of subsets of A whose
 * sum is at most m) and p_B / (1 - z^-1)^(n-i) is a chain of n-i boxes, non-negative and
 * summing to prod_B N. Hence
 *   |i-th difference| <= h * max|c_A| / prod_A N,
 * equal to the non-overlap value h / (N_0 ... N_{i-1}) when max|c_A| = 1. Copies that overlap
 * with opposite signs cancel in c_A, so chains shorter than the "each stage at least the
 * stages after it" rule pass this test (at the top difference, i = n, it is exact).
 */

/* Budget of level tests of the search below per pair of first two lengths (at most 7 * 7 of
 * them; each test O(2^i), i <= n <= 8): 4 * 2^n, 1024 for eight bounds. One budget per first
 * length let a second length that cannot work use it all up (eight bounds cost up to 20
 * samples, seven with a half sine 29). */
#define KIN_OVERLAP_NODES(n) (4u << (n))

typedef struct {
    const sms_kin_plan *p;
    double logh, logTs, c[SMS_KINEMATIC_MAX_ORDER], rest_min[SMS_KINEMATIC_MAX_ORDER + 1];
    double N[SMS_KINEMATIC_MAX_ORDER], best[SMS_KINEMATIC_MAX_ORDER], best_sum;
    /* subset sums of the k largest lengths, sorted, with their signs: list k at 2^k - 1 */
    double sums[2u << SMS_KINEMATIC_MAX_ORDER];
    signed char signs[2u << SMS_KINEMATIC_MAX_ORDER];
    unsigned nodes;
    int found, harmonic; /* harmonic: the last stage is a half sine (harmonic_fits) */
    const kin_tuned *tuned; /* a fixed bounded last stage (tuned_fits), or NULL */
} kin_overlap;

/* Adds length x to list k (the subset sums of N[0..k-1]) giving list k+1, and returns the
 * largest |running count| over it (taken at the end of each run of equal sums). */
static double overlap_count_peak(kin_overlap *s, size_t k, double x)
{
    size_t len = (size_t)1 << k, a = 0, b = 0, o = 0;
    const double *in = s->sums + (len - 1u);
    const signed char *sg = s->signs + (len - 1u);
    double *out = s->sums + (2u * len - 1u);
    signed char *osg = s->signs + (2u * len - 1u);
    long run = 0, peak = 0;
    while (a < len || b < len) {
        if (b >= len || (a < len && in[a] <= in[b] + x)) {
            out[o] = in[a];
            osg[o++] = sg[a++];
        } else {
            out[o] = in[b] + x;
            osg[o++] = (signed char)-sg[b++];
        }
    }
    for (o = 0; o < 2u * len; ++o) {
        run += osg[o];
        if (o + 1u == 2u * len || out[o + 1u] != out[o]) {
            long r = run < 0 ? -run : run;
            if (r > peak)
                peak = r;
        }
    }
    return (double)peak;
}

/*
 * A half-sine last stage of N samples (taps tan(pi/2N) sin(pi j/N), j = 0..N-1) after boxes
 * whose signed subset sums sigma_S are list n-1: the top difference exactly. In samples it is
 *   h / prod(boxes) * tan(pi/2N) * f(m),   f(m) = sum_S sign_S sin(pi (m - sigma_S)/N),
 * each copy S taken over m in [sigma_S, sigma_S + N] (zero at both ends). Between two events
 * (a copy starting at sigma_S or ending at sigma_S + N) the live copies share one frequency:
 * with C = sum_live sign_S e^(i pi (b - sigma_S)/N) at the interval's start b,
 * f(b + t) = Im(e^(i pi t/N) C). A start adds sign_S to C (e^0); an end removes
 * sign_S e^(i pi), i.e. adds sign_S too. So one sweep over the 2^n sorted events, rotating C
 * between them, gives f; an interval is accepted on |C| <= lim when it can, else f is
 * evaluated at its ends and at the samples next to the sinusoid's extremes. lim: the allowed
 * max|f|. Returns 1 when it holds. (The level below needs no such test: there the half sine
 * is a ramp of non-negative weights summing to one, so the running count of the boxes bounds
 * it.)
 */
static int interval_fits(double cr, double ci, double dt, double N, double lim)
{
    double w = KIN_PI / N, t0, ts[6];
    size_t q;
    if (hypot(cr, ci) <= lim)
        return 1;
    /* |f| peaks where pi t/N + arg C = pi/2 (mod pi): t0 + k N */
    t0 = N * (0.5 - atan2(ci, cr) / KIN_PI);
    t0 -= N * floor(t0 / N);
    ts[0] = 0.0;
    ts[1] = dt;
    ts[2] = floor(t0);
    ts[3] = ts[2] + 1.0;
    ts[4] = ts[2] + N;
    ts[5] = ts[3] + N;
    for (q = 0; q < 6u; ++q)
        if (ts[q] >= 0.0 && ts[q] <= dt &&
            fabs(ci * cos(w * ts[q]) + cr * sin(w * ts[q])) > lim)
            return 0;
    return 1;
}

static int harmonic_fits(const kin_overlap *s, double N, double lim)
{
    size_t len = (size_t)1 << (s->p->n - 1u), a = 0, e = 0;
    const double *st = s->sums + (len - 1u);
    const signed char *sg = s->signs + (len - 1u);
    double cr = 0.0, ci = 0.0, b = st[0];
    while (a < len || e < len) {
        double pos = e >= len || (a < len && st[a] <= st[e] + N) ? st[a] : st[e] + N;
        if (pos > b) {
            double x = KIN_PI * (pos - b) / N, c = cos(x), sn = sin(x), r;
            if (!interval_fits(cr, ci, pos - b, N, lim))
                return 0;
            r = cr * c - ci * sn;
            ci = cr * sn + ci * c;
            cr = r;
            b = pos;
        }
        while (a < len && st[a] == pos)
            cr += sg[a++];
        while (e < len && st[e] + N == pos)
            cr += sg[e++];
    }
    return 1;
}

/*
 * A fixed bounded last stage (taps tap0, gain q^i for i = 1 .. L-2, tapL) after boxes whose
 * signed subset sums sigma_S are list n-1: the top difference exactly. In samples it is
 * h / prod(boxes) * F(m), F(m) = sum_S sign_S t(m - sigma_S). F changes only where a copy
 * starts (sigma_S: tap0), enters its interior (+1), leaves it (L-1: tapL) or ends (L);
 * between those the interior part is K q^t (constant for a box, decaying for q < 1), so
 * |F| peaks at one of them. One sweep over the four shifted lists of sums, carrying K.
 * Returns 1 when max |F| <= lim.
 */
static int tuned_fits(const kin_overlap *s, double lim)
{
    const kin_tuned *t = s->tuned;
    const size_t len = (size_t)1 << (s->p->n - 1u);
    const double *st = s->sums + (len - 1u);
    const signed char *sg = s->signs + (len - 1u);
    const double off[4] = {0.0, 1.0, t->L - 1.0, t->L};
    const double q_in = t->gain * exp(t->decay), q_out = t->gain * exp(t->decay * (t->L - 1.0));
    size_t at[4] = {0u, 0u, 0u, 0u}, e;
    double K = 0.0, b = st[0];
    for (;;) {
        double pos = HUGE_VAL, spike = 0.0;
        for (e = 0; e < 4u; ++e)
            if (at[e] < len && st[at[e]] + off[e] < pos)
                pos = st[at[e]] + off[e];
        if (pos == HUGE_VAL)
            return 1;
        if (t->decay != 0.0)
            K *= exp(t->decay * (pos - b));
        b = pos;
        for (e = 0; e < 4u; ++e)
            while (at[e] < len && st[at[e]] + off[e] == pos) {
                const double sign = (double)sg[at[e]++];
                if (e == 0u) {          /* a copy starts: its first tap */
                    spike += sign * t->tap0;
                } else if (e == 1u) {   /* its interior begins */
                    K += sign * q_in;
                } else if (e == 2u) {   /* its interior ends, its last tap */
                    K -= sign * q_out;
                    spike += sign * t->tapL;
                }                       /* e == 3: it has ended (only evaluated) */
            }
        if (fabs(K + spike) > lim)
            return 0;
    }
}

static void overlap_dfs(kin_overlap *s, size_t k, double logprod, double psum)
{
    size_t n = s->p->n, nx = 0, j, q, boxes = s->tuned ? n - 1u : n;
    double xs[7];
    if (k == boxes) {
        if (s->tuned) {
            /* the top level through the fixed stage, exactly (tuned_fits) */
            double lt = log(s->p->L[n - 1u]) + (double)n * s->logTs + logprod - s->logh;
            if (!tuned_fits(s, lt > 60.0 ? HUGE_VAL : exp(lt) * (1.0 + 1e-12)))
                return;
        }
        if (psum < s->best_sum) {
            s->best_sum = psum;
            for (j = 0; j < n; ++j)
                s->best[j] = s->N[j];
            s->found = 1;
        }
        return;
    }
    if (k + 1u == n && s->harmonic) {
        /* a half sine: the fewest samples whose largest tap (about pi/2N) keeps the top
         * level without overlaps, from two less (overlapping copies can lower the peak) to
         * three more */
        double x0 = ceil(0.5 * KIN_PI * exp(s->logh - log(s->p->L[k]) - (double)n * s->logTs -
                                             logprod) * (1.0 - 1e-12));
        if (!(x0 >= 2.0))
            x0 = 2.0;
        for (j = 0; j < 6u; ++j)
            if (x0 - 2.0 + (double)j >= 2.0)
                xs[nx++] = x0 - 2.0 + (double)j;
    } else if (k + 1u == n || ((s->harmonic || s->tuned) && k + 2u == n)) {
        /* the last box: the fewest samples its level allows without overlaps, and a few
         * more; before a half sine or a fixed tuned stage also the ceiling -1 .. +1 */
        double x0 = ceil(exp(s->logh - log(s->p->L[k]) - (double)(k + 1u) * s->logTs -
                             logprod) * (1.0 - 1e-12));
        if (!(x0 >= 1.0))
            x0 = 1.0;
        for (j = 0; j < 4u; ++j)
            xs[nx++] = x0 + (double)j;
        for (j = 0; j < 3u && k + 1u < n; ++j) {
            double x = s->c[k] - 1.0 + (double)j;
            if (x < x0 || x > x0 + 3.0)
                xs[nx++] = x;
        }
    } else {
        /* the ceiling moved by -1 .. +2, then the structure's lift. Order: after a stage one
         * sample off its ceiling, the other way first (pairs of +1/-1 keep the sums and break
         * the collisions of tight stages); the first stage -1, +1; else one sample less
         * first where an odd number of stages follows (there the overlap with the next copy
         * cancels) */
        static const double odd[4] = {-1.0, 0.0, 1.0, 2.0}, even[4] = {0.0, -1.0, 1.0, 2.0};
        static const double first[4] = {-1.0, 1.0, 0.0, 2.0};
        static const double after_down[4] = {1.0, 0.0, -1.0, 2.0};
        static const double after_up[4] = {-1.0, 0.0, 1.0, 2.0};
        const double *off = ((n - 1u - k) % 2u) ? odd : even;
        double lift = 0.0, prev = k > 0u ? s->N[k - 1u] - s->c[k - 1u] : 0.0;
        if (prev == -1.0)
            off = after_down;
        else if (prev == 1.0)
            off = after_up;
        else if (k == 0u)
            off = first;
        for (j = 0; j < 4u; ++j)
            xs[nx++] = s->c[k] + off[j];
        for (j = k + 1u; j < n; ++j)
            lift += s->c[j];
        for (j = 0; j < 3u; ++j) {
            double x = lift - 1.0 + (double)j;
            int seen = 0;
            for (q = 0; q < nx; ++q)
                seen |= xs[q] == x;
            if (!seen)
                xs[nx++] = x;
        }
    }
    for (j = 0; j < nx; ++j) {
        double x = xs[j], peak, lp;
        int last_sine = s->harmonic && k + 1u == n;
        if (x < 1.0 || (k > 0u && x > s->N[k - 1u] && !last_sine))
            continue;
        if (psum + x + s->rest_min[k + 1u] >= s->best_sum)
            continue;
        if (k <= 1u)
            s->nodes = 0u; /* each pair of first two lengths gets its own budget */
        if (s->nodes >= KIN_OVERLAP_NODES(n))
            return;
        ++s->nodes;
        if (last_sine) {
            /* the top level exactly (harmonic_fits), against the boxes' product */
            double lt = log(s->p->L[k]) + (double)n * s->logTs + logprod - s->logh -
                        log(tan(0.5 * KIN_PI / x));
            if (!harmonic_fits(s, x, lt > 60.0 ? HUGE_VAL : exp(lt) * (1.0 + 1e-12)))
                continue;
            s->N[k] = x;
            overlap_dfs(s, k + 1u, logprod, psum + x);
            continue;
        }
        peak = overlap_count_peak(s, k, x);
        lp = logprod + log(x);
        if (s->logh + log(peak) > log(s->p->L[k]) + (double)(k + 1u) * s->logTs + lp + 1e-12)
            continue;
        s->N[k] = x;
        overlap_dfs(s, k + 1u, lp, psum + x);
    }
}

/* Chains without a tuned stage still more than a sample per stage over the continuous
 * optimum: a depth first search, largest stage first, of non-increasing whole-sample box
 * lengths that pass the exact test above level by level (each level needs only the lengths
 * chosen so far), then a half sine (harmonic) of any length whose top level harmonic_fits(),
 * within KIN_OVERLAP_NODES(n) level tests per pair of first two lengths; replaces N when it
 * finds a shorter chain. */
static void overlap_search(const sms_kin_plan *p, double logh, double logTs, const double *T,
                           double Ts, int harmonic, const kin_tuned *tuned, double *best,
                           double *N)
{
    kin_overlap s;
    size_t n = p->n, boxes = tuned != NULL ? n - 1u : n, i;
    s.p = p;
    s.harmonic = harmonic;
    s.tuned = tuned;
    s.logh = logh;
    s.logTs = logTs;
    for (i = 0; i < SMS_KINEMATIC_MAX_ORDER; ++i)
        s.N[i] = s.c[i] = 0.0;
    s.rest_min[boxes] = 0.0;
    for (i = n; i-- > 0;) {
        s.c[i] = grid_ceil(T[i] / Ts); /* a tuned stage's only enters the lift */
        if (i < boxes)
            s.rest_min[i] = s.rest_min[i + 1u] + (s.c[i] > 2.0 ? s.c[i] - 1.0 : 1.0);
    }
    s.best_sum = *best;
    s.nodes = 0u;
    s.found = 0;
    s.sums[0] = 0.0;
    s.signs[0] = 1;
    overlap_dfs(&s, 0u, 0.0, 0.0);
    if (s.found) {
        *best = s.best_sum;
        for (i = 0; i < boxes; ++i)
            N[i] = s.best[i];
    }
}

/* Whole-sample lengths: the shortest total among N[i] = ceil(T[i]/Ts) + {-1, 0, 1} that
 * meets grid_feasible() (ties: longer early stages), with the greedy rounding (each N[i]
 * the larger of its ceiling and the samples after it, which is always feasible) as the
 * fallback. N[n-1] = 0 for a tuned last stage (it keeps its exact length). */
static sms_status on_grid(const sms_kin_plan *p, double h, const double *T, sms_kind last_kind,
                          int tuned, double supp_last, const kin_tuned *form, double Ts,
                          double *N)
{
    size_t n = p->n, m = tuned ? n - 1 : n, i, combos = 1, c;
    double base[SMS_KINEMATIC_MAX_ORDER], cand[SMS_KINEMATIC_MAX_ORDER], below, total, best;
    double logh = log(h), logTs = log(Ts), tap_last = 0.0;
    for (i = 0; i < n; ++i)
        if (!(T[i] / Ts <= 4503599627370496.0)) /* 2^52 samples */
            return SMS_ERR_TOO_LONG;
    if (tuned)
        tap_last = p->rho_fixed * Ts; /* >= the largest tap: the density the design used */
    /* greedy */
    if (tuned) {
        N[n - 1] = 0.0;
        below = supp_last;
    } else {
        double nu = T[n - 1] / Ts;
        N[n - 1] = grid_ceil(nu);
        if (last_kind == SMS_HARMONIC) {
            if (N[n - 1] < 2.0)
                N[n - 1] = 2.0;
            if (harmonic_peak_tap(N[n - 1]) > 0.5 * KIN_PI / nu)
                N[n - 1] += 1.0; /* an odd N always has peak sin(pi/2N) < pi/2N */
        }
        below = N[n - 1];
    }
    total = tuned ? 0.0 : N[n - 1];
    for (i = n - 1; i-- > 0;) {
        double Ni = grid_ceil(T[i] / Ts);
        if (Ni < below)
            Ni = below;
        N[i] = Ni;
        below += Ni;
        total += Ni;
    }
    if (!(total <= 4503599627370496.0))
        return SMS_ERR_TOO_LONG;
    best = total;
    /* neighbourhood search */
    for (i = 0; i < m; ++i) {
        base[i] = grid_ceil(T[i] / Ts);
        combos *= 3u;
    }
    cand[n - 1] = 0.0;
    for (c = 0; c < combos; ++c) {
        size_t code = c;
        double sum = 0.0;
        int ok = 1, better;
        for (i = 0; i < m; ++i) {
            cand[i] = base[i] + (double)(code % 3u) - 1.0;
            code /= 3u;
            if (cand[i] < 1.0)
                ok = 0;
            sum += cand[i];
        }
        if (!ok || sum > best)
            continue;
        if (!grid_feasible(p, logh, logTs, cand, last_kind, tuned, tap_last, supp_last))
            continue;
        better = sum < best;
        for (i = 0; i < m && !better && sum == best; ++i) {
            if (cand[i] != N[i]) {
                better = cand[i] > N[i];
                break;
            }
        }
        if (better) {
            best = sum;
            for (i = 0; i < m; ++i)
                N[i] = cand[i];
        }
    }
    /* Tight stages (each as long as the stages after it) double the rounding of the stages
     * below them, so with five or more bounds the neighbourhood can leave the chain many
     * samples over the continuous optimum (13.7 samples for 5 bounds where 1.7 exist). When it
     * is more than one sample per rounded stage over: move each stage by +1 .. -2 samples
     * from its ceiling and let the structure lift it (N_k = max(that, the samples after k)),
     * keeping the shortest feasible chain; 4^m chains, only on this path. A rectangular chain
     * first tries the search that lets copies overlap where they cancel (overlap_search):
     * cheaper, usually shorter, and when it lands within the bar the 4^m chains are skipped. */
    {
        double cont = 0.0;
        for (i = 0; i < m; ++i)
            cont += T[i] / Ts;
        int free_last = !tuned && n >= 2, harmonic = last_kind == SMS_HARMONIC;
        double before4;
        if (free_last && best - cont > (double)m)
            overlap_search(p, logh, logTs, T, Ts, harmonic, NULL, &best, N);
        before4 = best;
        if (m >= 2 && best - cont > (double)m) {
            size_t combos4 = 1;
            for (i = 0; i < m; ++i)
                combos4 *= 4u;
            for (c = 0; c < combos4; ++c) {
                size_t code = c;
                double sum = 0.0, after = tuned ? supp_last : 0.0;
                for (i = m; i-- > 0;) {
                    double Ni = base[i] + 1.0 - (double)(code % 4u);
                    code /= 4u;
                    if (Ni < 1.0)
                        Ni = 1.0;
                    if (i + 1 < n && Ni < after)
                        Ni = after; /* the structure: at least the samples after it */
                    cand[i] = Ni;
                    after += Ni;
                    sum += Ni;
                }
                if (sum >= best)
                    continue;
                if (!grid_feasible(p, logh, logTs, cand, last_kind, tuned, tap_last, supp_last))
                    continue;
                best = sum;
                for (i = 0; i < m; ++i)
                    N[i] = cand[i];
            }
        }
        /* still over, with a shorter chain to beat: the overlap search prunes harder */
        if (free_last && best < before4 && best - cont > (double)m)
            overlap_search(p, logh, logTs, T, Ts, harmonic, NULL, &best, N);
        /* a bounded tuned stage costs up to two samples of its own: its boxes get the search
         * that lets copies overlap once they are more than a sample per box over */
        if (tuned && form->bounded && m >= 1u && best - cont > 0.0)
            overlap_search(p, logh, logTs, T, Ts, 0, form, &best, N);
    }
    return SMS_OK;
}

/* The design: continuous lengths (Ts == 0) or lengths on the grid of Ts (docs/sampled-limits.md):
 * every stage but a mode-tuned last one lasts a whole number of samples N_k >= T_k/Ts, and
 * N_k >= N_{k+1} + ... + N_{n-1}, so the sampled differences obey the bounds. */
sms_status sms_kin_solve_sampled(double h, const double *limits, size_t n, sms_profile profile,
                                 double wn, double zeta, double Ts, double *T, sms_kin_last *last)
{
    sms_kin_plan p;
    kin_tuned form = {0, 0.0, 0.0, 0.0, 0.0, 0.0};
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
        (void)solve_plan(&p, h, T);
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
            p.rho_fixed = peak_density(last->kind, p.T_fixed, last->sigma);
            if (n == 1) {
                if (h * p.rho_fixed > p.L[0])
                    continue;
                uncapped = 1;
            } else {
                uncapped = p.L[n - 2] * p.rho_fixed <= p.L[n - 1];
            }
            dur = solve_plan(&p, h, Tk);
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
                p.rho_fixed = peak_density(last->kind, p.T_fixed, last->sigma);
                st = tuned_taps(last->kind, p.T_fixed, last->sigma, kbest, Ts, &tap,
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
                (void)solve_plan(&p, h, Tbest);
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
            last->timing = tuned_timing(last->kind);
        support_last = supp_best;
        for (i = 0; i < n; ++i)
            T[i] = Tbest[i];
    }
    if (Ts > 0.0) {
        double N[SMS_KINEMATIC_MAX_ORDER];
        st = on_grid(&p, h, T, last->kind, wn > 0.0, support_last, &form, Ts, N);
        if (st != SMS_OK)
            return st;
        for (i = 0; i < n; ++i)
            if (N[i] > 0.0)
                T[i] = N[i] * Ts;
    }
    return SMS_OK;
}

sms_status sms_kin_solve(double h, const double *limits, size_t n, sms_profile profile,
                         double wn, double zeta, double *T, sms_kin_last *last)
{
    return sms_kin_solve_sampled(h, limits, n, profile, wn, zeta, 0.0, T, last);
}

double sms_kin_peak_density(sms_kind kind, double T, double sigma)
{
    return peak_density(kind, T, sigma);
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
