/* SPDX-License-Identifier: Apache-2.0 */
/* Kinematic design, continuous part (docs/design.md): the lengths of the shortest rest-to-rest
 * chain within n derivative bounds, by the recursion's closed forms, in plain arithmetic or in
 * logarithms. Design-time code: libm is allowed here. */
#include "trajectory/kinematic_parts.h"

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

/* 2^e, e < SMS_KINEMATIC_MAX_ORDER (the exponents of at_bound and of the plain path):
 * x * pow2[e] is exactly ldexp(x, e) for e >= 0 (both are the correctly rounded x 2^e)
 * without a libm call, which was a quarter of a three-bound design's time. */
static const double pow2[8] = {1.0, 2.0, 4.0, 8.0, 16.0, 32.0, 64.0, 128.0};

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
    return (Tm + rest) * pow2[m - k];
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
        c2 = pow2[d * (d - (d > 0u)) / 2u];   /* 2^(d(d-1)/2) */
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
            lx /= S * pow2[m - 1 - j];
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
            T[j] = S * pow2[m - 1 - j];
    if (m + 1 == p->n) {
        if (T != NULL)
            T[m] = S;
        return S * pow2[m - k];
    }
    /* stage m at its bound, then the problem from the level cap_m */
    {
        unsigned d = (unsigned)(m - k), i;
        c2 = pow2[d * (d - (d > 0u)) / 2u];
        for (i = 0, Sd = 1.0; i < d; ++i)
            Sd *= S;
    }
    cap = level_cap(p, m);
    rest = solve_from_plain(p, C, m + 1, cap, T);
    return at_bound(k, m, X / (c2 * Sd) / cap, rest, T);
}

/* The regime where every stage is at its bound (vmax reached, and below it every bound; the
 * common trapezoid / double-S move): T_0 = h/L_0, T_k = L_{k-1}/L_k, the free last stage
 * c L_{n-2}/L_{n-1}, valid when each stage lasts at least the sum of those below it. There
 * solve_from_plain() takes m = k at every level (its decision allows 1 + KIN_TOL of excess;
 * this check none) and computes the same quotients and sums in the same order, so the lengths
 * and the duration are the same bits at a few divisions' cost. Returns the duration, or -1 if
 * the regime does not hold (the recursion then decides). Moderate free plans only. */
static double all_at_bound(const sms_kin_plan *p, double h, double *T)
{
    double L[SMS_KINEMATIC_MAX_ORDER], rest;
    size_t n = p->n, k;
    if (n == 1u) {
        L[0] = p->c_last * h / (1.0 * p->L[0]);
    } else {
        L[0] = h / p->L[0];
        for (k = 1; k + 1 < n; ++k)
            L[k] = p->L[k - 1] / p->L[k];
        L[n - 1] = p->c_last * p->L[n - 2] / (1.0 * p->L[n - 1]);
    }
    rest = L[n - 1];
    for (k = n - 1; k-- > 0;) {
        if (!(L[k] >= rest))
            return -1.0;
        rest = L[k] + rest;
    }
    if (T != NULL)
        for (k = 0; k < n; ++k)
            T[k] = L[k];
    return rest;
}

/* The contract is in kinematic_parts.h. */
double sms_kin_solve_plan(const sms_kin_plan *p, double h, double *T)
{
    double C[SMS_KINEMATIC_MAX_ORDER];
    size_t m;
    if (plan_is_moderate(p, h)) {
        if (!p->fixed) {
            double D = all_at_bound(p, h, T);
            if (D >= 0.0)
                return D;
        }
        for (m = p->n - 1; m-- > 0;)
            C[m] = solve_from_plain(p, C, m + 1, level_cap(p, m), NULL);
        return solve_from_plain(p, C, 0, h, T);
    }
    for (m = p->n - 1; m-- > 0;)
        C[m] = solve_from(p, C, m + 1, level_cap(p, m), NULL);
    return solve_from(p, C, 0, h, T);
}

double sms_kin_peak_density(sms_kind kind, double T, double sigma)
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
