/* SPDX-License-Identifier: Apache-2.0 */
/* Mode identification (docs/design.md): from two peaks, and from a sampled free decay by a
 * least-squares fit of c + e^{sigma t}(A cos wd t + B sin wd t) over the whole record. */
#include <math.h>
#include "smoothshaper/design.h"

static const double pi = 3.14159265358979323846;

enum { N_PARAM = 5 };  /* c, A, B, sigma, wd */

static int is_finite(double v)
{
    return v - v == 0.0;
}

/* The mode of (sigma, wd); 0 unless every derived value is finite with wn > 0 (hypot: sigma^2
 * would overflow long before wn does). */
static int fill_mode(double sigma, double wd, sms_mode *mode)
{
    double wn = hypot(sigma, wd);
    if (!(is_finite(sigma) && is_finite(wd) && is_finite(wn) && wn > 0.0))
        return 0;
    mode->sigma = sigma;
    mode->wd = wd;
    mode->wn = wn;
    mode->zeta = -sigma / wn;
    return 1;
}

sms_status sms_identify_from_peaks(double t1, double p1, double t2, double p2, sms_mode *mode)
{
    double T0, half, ratio_log, sigma, wd;
    if (mode == NULL)
        return SMS_ERR_NULL;
    if (!is_finite(t1) || !is_finite(t2) || !is_finite(p1) || !is_finite(p2) || !(t2 > t1))
        return SMS_ERR_RECORD;
    /* same sign, strictly decaying in magnitude */
    if (!((p1 > 0.0 && p2 > 0.0) || (p1 < 0.0 && p2 < 0.0)) || !(fabs(p2) < fabs(p1)))
        return SMS_ERR_RECORD;
    /* ln|p2| - ln|p1|, not ln(p2/p1): the quotient can underflow to 0 (or a subnormal). */
    ratio_log = log(fabs(p2)) - log(fabs(p1));
    T0 = t2 - t1;
    if (is_finite(T0)) {
        sigma = ratio_log / T0;
        wd = 2.0 * pi / T0;
    } else { /* t2 - t1 overflows: the same quotients from half the interval */
        half = 0.5 * t2 - 0.5 * t1;
        sigma = 0.5 * ratio_log / half;
        wd = pi / half;
    }
    /* Peaks closer than about 1e-305 s would give an infinite frequency or decay rate. */
    return fill_mode(sigma, wd, mode) ? SMS_OK : SMS_ERR_RECORD;
}

/* Solve the n x n system M y = r (row-major, overwritten) by Gaussian elimination with
 * partial pivoting; returns 0 if singular. */
static int solve(double *M, double *r, double *y, int n)
{
    int i, j, k;
    for (k = 0; k < n; ++k) {
        int p = k;
        for (i = k + 1; i < n; ++i)
            if (fabs(M[i * n + k]) > fabs(M[p * n + k]))
                p = i;
        if (M[p * n + k] == 0.0)
            return 0;
        if (p != k) {
            double t;
            for (j = 0; j < n; ++j) {
                t = M[k * n + j]; M[k * n + j] = M[p * n + j]; M[p * n + j] = t;
            }
            t = r[k]; r[k] = r[p]; r[p] = t;
        }
        for (i = k + 1; i < n; ++i) {
            double f = M[i * n + k] / M[k * n + k];
            for (j = k; j < n; ++j)
                M[i * n + j] -= f * M[k * n + j];
            r[i] -= f * r[k];
        }
    }
    for (i = n - 1; i >= 0; --i) {
        double acc = r[i];
        for (j = i + 1; j < n; ++j)
            acc -= M[i * n + j] * y[j];
        y[i] = acc / M[i * n + i];
    }
    return 1;
}

/* Model value and Jacobian row at sample k for parameters q = (c, A, B, sigma, wd). */
static double model(const double *q, double t, double *jac)
{
    double e = exp(q[3] * t), co = cos(q[4] * t), si = sin(q[4] * t);
    double osc = e * (q[1] * co + q[2] * si);
    if (jac != NULL) {
        jac[0] = 1.0;
        jac[1] = e * co;
        jac[2] = e * si;
        jac[3] = t * osc;
        jac[4] = t * e * (q[2] * co - q[1] * si);
    }
    return q[0] + osc;
}

static double sse(const double *x, size_t n, double Ts, const double *q)
{
    double acc = 0.0;
    size_t k;
    for (k = 0; k < n; ++k) {
        double r = x[k] - model(q, (double)k * Ts, NULL);
        acc += r * r;
    }
    return acc;
}

/* Linear least squares for (c, A, B) at fixed (sigma, wd). */
static int fit_linear(const double *x, size_t n, double Ts, double *q)
{
    double M[9] = {0}, r[3] = {0}, y[3];
    size_t k;
    int i, j;
    for (k = 0; k < n; ++k) {
        double jac[N_PARAM];
        (void)model(q, (double)k * Ts, jac);
        for (i = 0; i < 3; ++i) {
            r[i] += jac[i] * x[k];
            for (j = 0; j < 3; ++j)
                M[i * 3 + j] += jac[i] * jac[j];
        }
    }
    if (!solve(M, r, y, 3))
        return 0;
    q[0] = y[0];
    q[1] = y[1];
    q[2] = y[2];
    return 1;
}

/* Levenberg-Marquardt on all five parameters from q; returns the final sum of squares. */
static double refine(const double *x, size_t n, double Ts, double *q)
{
    double lambda = 1e-3, cost = sse(x, n, Ts, q);
    int iter;
    for (iter = 0; iter < 200 && is_finite(cost); ++iter) {
        double JtJ[N_PARAM * N_PARAM] = {0}, Jtr[N_PARAM] = {0}, trial[N_PARAM], step[N_PARAM];
        double M[N_PARAM * N_PARAM], r[N_PARAM], new_cost;
        size_t k;
        int i, j, improved = 0;
        for (k = 0; k < n; ++k) {
            double jac[N_PARAM], res = x[k] - model(q, (double)k * Ts, jac);
            for (i = 0; i < N_PARAM; ++i) {
                Jtr[i] += jac[i] * res;
                for (j = 0; j < N_PARAM; ++j)
                    JtJ[i * N_PARAM + j] += jac[i] * jac[j];
            }
        }
        while (lambda < 1e12) {
            for (i = 0; i < N_PARAM * N_PARAM; ++i)
                M[i] = JtJ[i];
            for (i = 0; i < N_PARAM; ++i) {
                M[i * N_PARAM + i] *= 1.0 + lambda;
                r[i] = Jtr[i];
            }
            if (solve(M, r, step, N_PARAM)) {
                for (i = 0; i < N_PARAM; ++i)
                    trial[i] = q[i] + step[i];
                new_cost = sse(x, n, Ts, trial);
                if (is_finite(new_cost) && new_cost <= cost) {
                    double gain = cost - new_cost;
                    for (i = 0; i < N_PARAM; ++i)
                        q[i] = trial[i];
                    cost = new_cost;
                    lambda = lambda * 0.1 > 1e-12 ? lambda * 0.1 : 1e-12;
                    improved = gain > 1e-14 * cost;
                    break;
                }
            }
            lambda *= 10.0;
        }
        if (!improved)
            break;
    }
    return cost;
}

/* Start values from an AR(2) fit with a constant at lag d:
 * x[k] = a1 x[k-d] + a2 x[k-2d] + c; complex roots r e^{+-j th} give sigma = ln r/(d Ts),
 * wd = th/(d Ts). Returns 0 if the roots are not an oscillating pair. */
static int ar2_start(const double *x, size_t n, double Ts, size_t d, double *q)
{
    double M[9] = {0}, r[3] = {0}, y[3], mean = 0.0, disc, rad, th;
    size_t k;
    int i, j;
    for (k = 0; k < n; ++k)
        mean += x[k];
    mean /= (double)n;
    for (k = 2 * d; k < n; ++k) {
        double phi[3];
        phi[0] = x[k - d] - mean;
        phi[1] = x[k - 2 * d] - mean;
        phi[2] = 1.0;
        for (i = 0; i < 3; ++i) {
            r[i] += phi[i] * (x[k] - mean);
            for (j = 0; j < 3; ++j)
                M[i * 3 + j] += phi[i] * phi[j];
        }
    }
    if (!solve(M, r, y, 3))
        return 0;
    disc = y[0] * y[0] + 4.0 * y[1];
    if (!(disc < 0.0))
        return 0;
    rad = sqrt(-y[1]);
    th = acos(fmax(-1.0, fmin(1.0, y[0] / (2.0 * rad))));
    q[3] = log(rad) / ((double)d * Ts);
    q[4] = th / ((double)d * Ts);
    return is_finite(q[3]) && is_finite(q[4]) && q[4] > 0.0;
}

sms_status sms_identify_from_record(const double *x, size_t n, double Ts, sms_mode *mode)
{
    double best[N_PARAM] = {0.0, 0.0, 0.0, 0.0, 0.0}, best_cost = HUGE_VAL;
    size_t k, d;
    int found = 0;
    if (x == NULL || mode == NULL)
        return SMS_ERR_NULL;
    if (!is_finite(Ts) || Ts <= 0.0)
        return SMS_ERR_SAMPLE_PERIOD;
    if (n < 8)
        return SMS_ERR_RECORD;
    for (k = 0; k < n; ++k)
        if (!is_finite(x[k]))
            return SMS_ERR_RECORD;
    /* Several AR(2) lags (1, 2, 4, ...): slow sampling suits lag 1, fast sampling with noise
     * suits longer lags. The two starts with the least squared error after the linear fit are
     * refined (refinement dominates the cost); the better refined fit wins. */
    {
        double start[2][N_PARAM], start_cost[2] = {HUGE_VAL, HUGE_VAL};
        int s;
        for (d = 1; 4 * d <= n; d *= 2) {
            double q[N_PARAM], cost;
            q[0] = q[1] = q[2] = 0.0;
            if (!ar2_start(x, n, Ts, d, q) || !fit_linear(x, n, Ts, q))
                continue;
            cost = sse(x, n, Ts, q);
            if (!is_finite(cost) || cost >= start_cost[1])
                continue;
            s = cost < start_cost[0] ? 0 : 1;
            if (s == 0) {
                for (k = 0; k < N_PARAM; ++k)
                    start[1][k] = start[0][k];
                start_cost[1] = start_cost[0];
            }
            for (k = 0; k < N_PARAM; ++k)
                start[s][k] = q[k];
            start_cost[s] = cost;
        }
        for (s = 0; s < 2; ++s) {
            double cost;
            if (!is_finite(start_cost[s]))
                continue;
            cost = refine(x, n, Ts, start[s]);
            if (is_finite(cost) && cost < best_cost) {
                for (k = 0; k < N_PARAM; ++k)
                    best[k] = start[s][k];
                best_cost = cost;
                found = 1;
            }
        }
    }
    if (!found)
        return SMS_ERR_RECORD;
    if (best[4] < 0.0)
        best[4] = -best[4];
    /* a decaying oscillation below Nyquist with at least one period in the record */
    if (!(best[3] < 0.0) || !(best[4] < pi / Ts) || best[4] * (double)(n - 1) * Ts < 2.0 * pi
        || (best[1] == 0.0 && best[2] == 0.0))
        return SMS_ERR_RECORD;
    return fill_mode(best[3], best[4], mode) ? SMS_OK : SMS_ERR_RECORD;
}
