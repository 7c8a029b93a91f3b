/* Kinematic design (docs/design.md): lengths of the shortest rest-to-rest chain within
 * n derivative bounds. Design-time code: libm is allowed here (not in any per-sample path). */
#include <math.h>
#include "smoothshaper/trajectory.h"
#include "trajectory_internal.h"

/*
 * The recursion. A chain M(T0) * C' turns a step of X into a motion whose velocity is
 * (X/T0) times the step response of C' (the rise), held, then the mirrored fall, provided
 * T0 >= D' (the rise's duration) so that rise and fall do not overlap. The rise is the same
 * problem one derivative down: displacement V = X/T0 with the bounds limits[k+1..]. So
 *   D_k(X) = min over V <= L_k of X/V + D_{k+1}(V)   subject to X/V >= D_{k+1}(V).
 * Time scaling gives D(lambda X) <= lambda D(X) for lambda >= 1, hence V D'(V) <= D(V) and
 * X/V + D_{k+1}(V) decreases with V on the feasible set: V is L_k when feasible, else the
 * root of V D_{k+1}(V) = X (the bound L_k is unreachable; the effective bound is that V).
 */

static double last_stage_length(const sms_kin_plan *p, double X)
{
    return p->fixed ? p->T_fixed : p->c_last * X / p->L[p->n - 1];
}

/* Largest displacement level V allowed at stage k (a fixed last stage caps the level below it). */
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

static double solve_level(const sms_kin_plan *p, size_t k, double X, double *T);

/* g(V) = V * D_{k+1}(V), increasing in V. */
static double g_of(const sms_kin_plan *p, size_t k, double V)
{
    return V * solve_level(p, k + 1, V, NULL);
}

/* Root of g(V) = X with g(hi) > X; Illinois regula falsi on (log V, log g): g is a power of V
 * piecewise, so this converges in a few iterations; bisection steps guard the bracket. */
static double root_level(const sms_kin_plan *p, size_t k, double X, double hi)
{
    double ghi = g_of(p, k, hi);
    double lo = hi * (X / ghi); /* g(lambda V) <= lambda g(V) for lambda <= 1 */
    double glo = g_of(p, k, lo);
    double ulo, uhi, flo, fhi;
    int side = 0, it;
    if (glo >= X)
        return lo;
    ulo = log(lo);
    uhi = log(hi);
    flo = log(glo) - log(X);
    fhi = log(ghi) - log(X);
    for (it = 0; it < 200; ++it) {
        double u, f;
        if (uhi - ulo <= 4e-16 * (fabs(uhi) + fabs(ulo)) + 1e-300)
            break;
        u = (it % 8 == 7) ? 0.5 * (ulo + uhi) : (ulo * fhi - uhi * flo) / (fhi - flo);
        if (!(u > ulo && u < uhi))
            u = 0.5 * (ulo + uhi);
        f = log(g_of(p, k, exp(u))) - log(X);
        if (f == 0.0)
            return exp(u);
        if (f < 0.0) {
            ulo = u;
            flo = f;
            if (side == -1)
                fhi *= 0.5;
            side = -1;
        } else {
            uhi = u;
            fhi = f;
            if (side == 1)
                flo *= 0.5;
            side = 1;
        }
    }
    return exp(ulo); /* the feasible side: X/V >= D_{k+1}(V) */
}

/* Level V of stage k for displacement X (closed form when only the last stage is below). */
static double level_of(const sms_kin_plan *p, size_t k, double X)
{
    double cap = level_cap(p, k);
    double below = solve_level(p, k + 1, cap, NULL);
    if (X / cap >= below)
        return cap;
    if (k + 2 == p->n) {
        if (p->fixed)
            return X / p->T_fixed;                           /* X/V = T_fixed */
        return sqrt(X * p->L[p->n - 1] / p->c_last);         /* X/V = c V / L */
    }
    return root_level(p, k, X, cap);
}

/* Duration of stages k..n-1 for displacement X; writes their lengths to T[k..] if T != NULL. */
static double solve_level(const sms_kin_plan *p, size_t k, double X, double *T)
{
    double V, Tk, rest;
    if (k + 1 == p->n) {
        Tk = last_stage_length(p, X);
        if (T != NULL)
            T[k] = Tk;
        return Tk;
    }
    V = level_of(p, k, X);
    rest = solve_level(p, k + 1, V, T);
    Tk = X / V;
    if (Tk < rest) /* rounding at the root: keep the structure exact */
        Tk = rest;
    if (T != NULL)
        T[k] = Tk;
    return Tk + rest;
}

static double peak_density(sms_kind kind, double T, double sigma)
{
    switch (kind) {
    case SMS_HARMONIC:
        return 1.5707963267948966 / T;
    case SMS_EXPONENTIAL:
        if (sigma < 0.0)
            return -sigma / -expm1(sigma * T);
        return 1.0 / T;
    default:
        return 1.0 / T;
    }
}

static sms_status validate(double h, const double *limits, size_t n, sms_profile profile,
                           double wn, double zeta)
{
    size_t i;
    if (limits == NULL)
        return SMS_ERR_NULL;
    if (n < 1 || n > SMS_KINEMATIC_MAX_ORDER)
        return SMS_ERR_ORDER;
    if (!isfinite(h) || h == 0.0)
        return SMS_ERR_LIMIT;
    for (i = 0; i < n; ++i)
        if (!isfinite(limits[i]) || !(limits[i] > 0.0))
            return SMS_ERR_LIMIT;
    if (profile != SMS_PROFILE_POLYNOMIAL && profile != SMS_PROFILE_TRIGONOMETRIC &&
        profile != SMS_PROFILE_DAMPED)
        return SMS_ERR_KIND;
    if (!isfinite(wn) || wn < 0.0 || (profile == SMS_PROFILE_DAMPED && wn == 0.0))
        return SMS_ERR_WN;
    if (profile == SMS_PROFILE_DAMPED && n < 2)
        return SMS_ERR_ORDER;
    if (wn > 0.0 && (!isfinite(zeta) || zeta < 0.0 || zeta >= 1.0))
        return SMS_ERR_ZETA;
    return SMS_OK;
}

sms_status sms_kin_solve(double h, const double *limits, size_t n, sms_profile profile,
                         double wn, double zeta, double *T, sms_kin_last *last)
{
    sms_kin_plan p;
    size_t i;
    sms_status st = validate(h, limits, n, profile, wn, zeta);
    if (st != SMS_OK)
        return st;
    p.n = n;
    for (i = 0; i < n; ++i)
        p.L[i] = limits[i];
    h = fabs(h);
    last->sigma = 0.0;
    last->k = 1u;
    last->kind = profile == SMS_PROFILE_TRIGONOMETRIC ? SMS_HARMONIC : SMS_RECTANGULAR;
    if (wn == 0.0) {
        p.fixed = 0;
        p.c_last = profile == SMS_PROFILE_TRIGONOMETRIC ? 1.5707963267948966 : 1.0;
        p.T_fixed = p.rho_fixed = 0.0;
        (void)solve_level(&p, 0, h, T);
        return SMS_OK;
    } else {
        /* Mode-tuned last stage: try the multiples k Tm, keep the shortest feasible chain.
         * Past the first k whose peak no longer caps the level below, durations only grow. */
        double wd = wn * sqrt(1.0 - zeta * zeta);
        double Tm, best = HUGE_VAL, Tbest[SMS_KINEMATIC_MAX_ORDER];
        unsigned k, step = 1u, kbest = 0u;
        if (profile == SMS_PROFILE_DAMPED) {
            last->kind = SMS_EXPONENTIAL;
            last->sigma = -zeta * wn;
        }
        if (profile == SMS_PROFILE_TRIGONOMETRIC) {
            Tm = 3.0 * 3.14159265358979323846 / wd;
            step = 2u; /* odd multiples only (docs/errata.md) */
        } else {
            Tm = 2.0 * 3.14159265358979323846 / wd;
        }
        p.fixed = 1;
        p.c_last = 0.0;
        for (k = 1u; k <= SMS_KINEMATIC_MAX_MULTIPLE; k += step) {
            double Tk[SMS_KINEMATIC_MAX_ORDER], dur;
            int uncapped;
            p.T_fixed = k * Tm;
            p.rho_fixed = peak_density(last->kind, p.T_fixed, last->sigma);
            if (n == 1) {
                if (h * p.rho_fixed > p.L[0])
                    continue;
                uncapped = 1;
            } else {
                uncapped = p.L[n - 2] * p.rho_fixed <= p.L[n - 1];
            }
            dur = solve_level(&p, 0, h, Tk);
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
        last->k = kbest;
        for (i = 0; i < n; ++i)
            T[i] = Tbest[i];
        return SMS_OK;
    }
}

double sms_kin_peak_density(sms_kind kind, double T, double sigma)
{
    return peak_density(kind, T, sigma);
}

/* The solve both public designs share, with their capacity check. */
static sms_status solve_into(double h, const double *limits, size_t n, sms_profile profile,
                             double wn, double zeta, size_t capacity,
                             double lengths[SMS_KINEMATIC_MAX_ORDER], sms_kin_last *last)
{
    sms_status st = sms_kin_solve(h, limits, n, profile, wn, zeta, lengths, last);
    if (st != SMS_OK)
        return st;
    return capacity < n ? SMS_ERR_BUFFER_TOO_SMALL : SMS_OK;
}

sms_status sms_kinematic_design(double h, const double *limits, size_t n, sms_profile profile,
                                double wn, double zeta, double *T, size_t capacity, size_t *count)
{
    double lengths[SMS_KINEMATIC_MAX_ORDER];
    sms_kin_last last;
    size_t i;
    sms_status st;
    if (T == NULL || count == NULL)
        return SMS_ERR_NULL;
    st = solve_into(h, limits, n, profile, wn, zeta, capacity, lengths, &last);
    if (st != SMS_OK)
        return st;
    for (i = 0; i < n; ++i)
        T[i] = lengths[i];
    *count = n;
    return SMS_OK;
}

sms_status sms_kinematic_configs(double h, const double *limits, size_t n, sms_profile profile,
                                 double wn, double zeta, sms_stage_config *configs,
                                 size_t capacity, size_t *count)
{
    double lengths[SMS_KINEMATIC_MAX_ORDER];
    sms_kin_last last;
    size_t i;
    sms_status st;
    if (configs == NULL || count == NULL)
        return SMS_ERR_NULL;
    st = solve_into(h, limits, n, profile, wn, zeta, capacity, lengths, &last);
    if (st != SMS_OK)
        return st;
    for (i = 0; i < n; ++i) {
        configs[i] = sms_stage_config_default(SMS_RECTANGULAR);
        configs[i].T = lengths[i];
    }
    configs[n - 1].kind = last.kind;
    configs[n - 1].sigma = last.sigma;
    configs[n - 1].k = last.k;
    *count = n;
    return SMS_OK;
}
