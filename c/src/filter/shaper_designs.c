/* SPDX-License-Identifier: Apache-2.0 */
/* Continuous input-shaper designs: amplitudes (normalised to sum 1) and impulse times.
 * Mode: wn, zeta; wd = wn sqrt(1 - zeta^2), Td = 2 pi / wd. Each formula cites its source. */
#include <math.h>
#include "filter/shaper_designs.h"

static const double pi = 3.14159265358979323846;

unsigned sms_shaper_zv_order(const sms_stage_config *config)
{
    switch (config->kind) {
    case SMS_SHAPER_ZV: return 1u;
    case SMS_SHAPER_ZVD: return 2u;
    case SMS_SHAPER_ZVDD: return 3u;
    case SMS_SHAPER_ZVN: return config->order;
    default: return 0u;
    }
}

static size_t normalise(double *amp, size_t n)
{
    double sum = 0.0;
    size_t i;
    for (i = 0; i < n; ++i)
        sum += amp[i];
    for (i = 0; i < n; ++i)
        amp[i] /= sum;
    return n;
}

/* ZV^n. ZV: Smith (1957); damped form Singer & Seering, "Preshaping command inputs to reduce
 * system vibration", ASME J. Dyn. Sys. Meas. Control 112 (1990) 76-82, and seed 004:
 * [1, K]/(1+K) at [0, Td/2]. ZVD, ZVDD, ZV^n: the n-fold convolution (Singer & Seering 1990;
 * Singhose, Seering & Singer, ASME J. Mech. Des. 116 (1994) 654-659; seed 003 for the undamped
 * form): A_m = C(n,m) K^m / (1+K)^n at m Td/2. Undamped: K = 1, binomial weights. */
static size_t design_zvn(unsigned n, double K, double Td, double *amp, double *time)
{
    double binom = 1.0, Km = 1.0;
    unsigned m;
    for (m = 0; m <= n; ++m) {
        amp[m] = binom * Km;
        time[m] = 0.5 * Td * (double)m;
        binom = binom * (double)(n - m) / (double)(m + 1u);
        Km *= K;
    }
    return normalise(amp, (size_t)n + 1u);
}

/* EI (extra-insensitive, one hump): Singhose, Seering & Singer, "Residual vibration reduction
 * using vector diagrams to generate shaping inputs", ASME J. Mech. Des. 116 (1994) 654-659;
 * Singhose, Porter, Tuttle & Singer, "Vibration reduction using multi-hump input shapers",
 * ASME J. Dyn. Sys. Meas. Control 119 (1997) 320-326.
 * Undamped closed form: [(1+V)/4, (1-V)/2, (1+V)/4] at [0, Td/2, Td]; then
 * |H(j wn)| = |(1+V)/2 - (1-V)/2| = V and d|H|/dw = 0 there (the hump peaks at the mode), with
 * zeros where cos(w Td/2) = -(1-V)/(1+V) on either side.
 * Damped: the amplitudes weighted by K^m (Klipper klippy/extras/shaper_defs.py,
 * get_ei_shaper; the same transformation the NumPy reference uses), A_m ~ B_m e^{sigma t_m}.
 * Then H_c(sigma + j w) = H_undamped(j w) / sum_m B_m e^{sigma t_m} for every w: the hump and
 * the two zeros are kept along Re s = sigma, valid for every zeta in [0,1) and V in (0,1).
 * Singhose's curve fit (A1 = 0.24968 + 0.24961 V + 0.80008 z + ..., 1994 Table) is not used: it
 * only holds for zeta <= 0.3 and small V (we measured its residual at the mode within 5 % of
 * V there) and gives negative amplitudes outside (e.g. zeta = 0.9, V = 0.05: A2 = -0.64). */
static size_t design_ei(double V, double K, double Td, double *amp, double *time)
{
    amp[0] = 0.25 * (1.0 + V);
    amp[1] = 0.5 * (1.0 - V) * K;
    amp[2] = 0.25 * (1.0 + V) * K * K;
    time[0] = 0.0;
    time[1] = 0.5 * Td;
    time[2] = Td;
    return normalise(amp, 3);
}

/* Two-hump EI: Singhose, Porter, Tuttle & Singer, ASME J. Dyn. Sys. Meas. Control 119 (1997)
 * 320-326, undamped closed form: X = (V^2 (sqrt(1-V^2) + 1))^(1/3),
 * A1 = A4 = (3 X^2 + 2 X + 3 V^2)/(16 X), A2 = A3 = 1/2 - A1, at [0, Td/2, Td, 3Td/2]:
 * zero at the mode, two humps of height V. Damped: amplitudes weighted by K^m (the form used by
 * Klipper's shaper_defs.py, get_2hump_ei_shaper), which keeps the exact zero at p because
 * e^{-p m Td/2} = (-1/K)^m turns the weights back into A1 - A2 + A3 - A4 = 0. */
static size_t design_ei2(double V, double K, double Td, double *amp, double *time)
{
    /* X = V^(2/3) (sqrt(1-V^2) + 1)^(1/3) and A1 = (3 X + 2 + 3 V (V/X))/16, written so that
     * no intermediate underflows: V^2 is 0 below V = 1e-162, and 0/0 made every tap NaN. */
    double c = cbrt(V), X = c * c * cbrt(sqrt(1.0 - V * V) + 1.0);
    double a1 = (3.0 * X + 2.0 + 3.0 * V * (V / X)) / 16.0;
    amp[0] = a1;
    amp[1] = (0.5 - a1) * K;
    amp[2] = (0.5 - a1) * K * K;
    amp[3] = a1 * K * K * K;
    time[0] = 0.0;
    time[1] = 0.5 * Td;
    time[2] = Td;
    time[3] = 1.5 * Td;
    return normalise(amp, 4);
}

/* MZV as in 3-D printer firmware (Klipper klippy/extras/shaper_defs.py, get_mzv_shaper; also
 * Kalico/Marlin ports): K' = exp(-0.75 zeta pi / sqrt(1-zeta^2)),
 * [1 - 1/sqrt2, (sqrt2 - 1) K', (1 - 1/sqrt2) K'^2] at [0, 0.375 Td, 0.75 Td], normalised.
 * Zero at p: e^{-p 0.375 Td} = e^{-j 3pi/4}/K', e^{-p 0.75 Td} = e^{-j 3pi/2}/K'^2 = j/K'^2, so
 * H_c(p) ~ a1 + (sqrt2-1)(-1-j)/sqrt2 + j a1 = 0 with a1 = 1 - 1/sqrt2. */
static size_t design_mzv(double z, double df, double Td, double *amp, double *time)
{
    double K = exp(-0.75 * z * pi / df);
    double a1 = 1.0 - 1.0 / sqrt(2.0);
    amp[0] = a1;
    amp[1] = (sqrt(2.0) - 1.0) * K;
    amp[2] = a1 * K * K;
    time[0] = 0.0;
    time[1] = 0.375 * Td;
    time[2] = 0.75 * Td;
    return normalise(amp, 3);
}

/* Three-hump EI: Singhose, Porter, Tuttle & Singer, ASME J. Dyn. Sys. Meas. Control 119 (1997)
 * 320-326, undamped closed form for tolerance V:
 * A1 = A5 = (1 + 3V + 2 sqrt(2 V (V+1)))/16, A2 = A4 = (1-V)/4, A3 = (1+V)/2 - 2 A1,
 * at [0, Td/2, Td, 3Td/2, 2Td]. With c = cos(w Td/2), H(jw) e^{j w Td} = A3 + 2 A2 c +
 * 2 A1 (2c^2 - 1): V at the mode (c = -1, the middle hump) and -V at the vertex
 * c = -A2/(4 A1) reached on either side (the outer humps). Damped: weighted by K^m, as EI and
 * EI2 (and Klipper's get_3hump_ei_shaper), which keeps the humps and zeros along Re s = sigma. */
static size_t design_ei3(double V, double K, double Td, double *amp, double *time)
{
    double a1 = 0.0625 * (1.0 + 3.0 * V + 2.0 * sqrt(2.0 * (V + 1.0) * V));
    double a2 = 0.25 * (1.0 - V);
    double Km = 1.0;
    size_t m;
    amp[0] = a1;
    amp[1] = a2;
    amp[2] = 0.5 * (1.0 + V) - 2.0 * a1;
    amp[3] = a2;
    amp[4] = a1;
    for (m = 0; m < 5; ++m) {
        amp[m] *= Km;
        time[m] = 0.5 * Td * (double)m;
        Km *= K;
    }
    return normalise(amp, 5);
}

/* Least squares min |M x - f| by Householder QR, M row-major rows x cols (rows >= cols,
 * full column rank, both small); M and f are overwritten. 0 if rank deficient. */
static int least_squares(double *M, double *f, size_t rows, size_t cols, double *x)
{
    size_t k, i, j;
    for (k = 0; k < cols; ++k) {
        double norm = 0.0, alpha, vtv, dot;
        for (i = k; i < rows; ++i)
            norm += M[i * cols + k] * M[i * cols + k];
        norm = sqrt(norm);
        if (norm == 0.0)
            return 0;
        alpha = M[k * cols + k] > 0.0 ? -norm : norm;
        M[k * cols + k] -= alpha;                       /* v = column k below the diagonal - alpha e_k */
        vtv = 0.0;
        for (i = k; i < rows; ++i)
            vtv += M[i * cols + k] * M[i * cols + k];
        for (j = k + 1; j < cols; ++j) {                /* apply I - 2 v v^T / v^T v */
            dot = 0.0;
            for (i = k; i < rows; ++i)
                dot += M[i * cols + k] * M[i * cols + j];
            for (i = k; i < rows; ++i)
                M[i * cols + j] -= 2.0 * dot / vtv * M[i * cols + k];
        }
        dot = 0.0;
        for (i = k; i < rows; ++i)
            dot += M[i * cols + k] * f[i];
        for (i = k; i < rows; ++i)
            f[i] -= 2.0 * dot / vtv * M[i * cols + k];
        M[k * cols + k] = alpha;                        /* R's diagonal */
    }
    for (k = cols; k-- > 0;) {                          /* back substitution R x = Q^T f */
        double r = f[k];
        for (j = k + 1; j < cols; ++j)
            r -= M[k * cols + j] * x[j];
        x[k] = r / M[k * cols + k];
    }
    return 1;
}

int sms_gmzv_undamped(unsigned n, double duration, double *amp, double *units)
{
    /* rows: sum A = 1, then Re and Im of H at the n-1 zero frequencies */
    double M[(2 * SMS_SHAPER_MAX_IMPULSES - 1) * SMS_SHAPER_MAX_IMPULSES];
    double f[2 * SMS_SHAPER_MAX_IMPULSES - 1];
    double tau, sum = 0.0;
    size_t rows = 2u * n - 1u, i, j;
    if (n < 3u || n > SMS_SHAPER_MAX_IMPULSES || !(duration > 0.0)
        || !(duration < 0.5 * (double)(n - 1u)))
        return 0;
    tau = duration * (double)(n - 2u) / ((double)n - 2.0 * duration - 1.0);
    for (j = 0; j < n; ++j) {
        units[j] = duration * (double)j / (double)(n - 1u);
        M[j] = 1.0;
    }
    f[0] = 1.0;
    for (i = 0; i + 1u < n; ++i) {
        double w = 2.0 * pi * (1.0 + (double)i / tau);
        for (j = 0; j < n; ++j) {
            M[(1u + 2u * i) * n + j] = cos(w * units[j]);
            M[(2u + 2u * i) * n + j] = sin(w * units[j]);
        }
        f[1u + 2u * i] = 0.0;
        f[2u + 2u * i] = 0.0;
    }
    if (!least_squares(M, f, rows, n, amp))
        return 0;
    for (j = 0; j < n; ++j) {
        if (!(amp[j] >= 0.0))
            return 0;
        sum += amp[j];
    }
    return sum > 0.0;
}

/* Generalised MZV, as 3-D printer firmware defines it (D. Butyugin's shaper_defs.py in Kalico
 * and Klipper forks, get_mzv_coeffs / get_mzv_shaper with parameters n and t): n impulses evenly
 * spaced over t damped periods, t_j = j t Td/(n-1). With tau = t (n-2)/(n-2t-1) (the span the
 * zeros are placed for as n grows), the amplitudes are the least-squares solution of sum A = 1
 * and H(j w_i) = 0 at w_i = wd (1 + i/tau), i = 0..n-2 (2n-1 equations, n unknowns); n = 3,
 * t = 0.75 is MZV exactly (zeros at wd and 5/3 wd). Damped: weighted by
 * K^j = exp(-zeta wn t_j), which moves every zero to Re s = -zeta wn; normalised to sum 1. */
static size_t design_gmzv(unsigned n, double duration, double zeta, double df, double Td,
                          double *amp, double *time)
{
    double units[SMS_SHAPER_MAX_IMPULSES];
    double Kstep = exp(-2.0 * pi * zeta * duration / ((double)(n - 1u) * df)), Kj = 1.0;
    size_t j;
    (void)sms_gmzv_undamped(n, duration, amp, units);   /* validated by the caller */
    for (j = 0; j < n; ++j) {
        amp[j] *= Kj;
        time[j] = units[j] * Td;
        Kj *= Kstep;
    }
    return normalise(amp, n);
}

/* SI: the undamped design of shaper_si.c weighted by e^{-zeta wn t_m} (as EI), normalised. */
static size_t design_si(const sms_stage_config *c, double zeta, double df, double Td,
                        double *amp, double *time)
{
    double units[SMS_SHAPER_MAX_IMPULSES];
    size_t m;
    (void)sms_si_undamped(c->order, c->duration, c->tolerance, amp, units, NULL); /* validated */
    for (m = 0; m < c->order; ++m) {
        time[m] = units[m] * Td;
        amp[m] *= exp(-2.0 * pi * zeta * units[m] / df);
    }
    return normalise(amp, c->order);
}

/* User-defined impulses: the amplitudes normalised to sum 1 (as 3-D printer firmware applies
 * its shapers: Klipper's input_shaper divides by sum A), the times as given. */
static size_t design_impulses(const sms_stage_config *c, double *amp, double *time)
{
    size_t m;
    for (m = 0; m < c->order; ++m) {
        amp[m] = c->amplitudes[m];
        time[m] = c->times[m];
    }
    return normalise(amp, c->order);
}

size_t sms_shaper_design(const sms_stage_config *config, double *amp, double *time)
{
    double z = config->zeta, df, Td, K;
    if (config->kind == SMS_SHAPER_IMPULSES)     /* no mode: wn and zeta are not read */
        return design_impulses(config, amp, time);
    df = sqrt(1.0 - z * z);
    Td = 2.0 * pi / (config->wn * df);
    K = exp(-z * pi / df);
    switch (config->kind) {
    case SMS_SHAPER_EI:
        return design_ei(config->tolerance, K, Td, amp, time);
    case SMS_SHAPER_EI2:
        return design_ei2(config->tolerance, K, Td, amp, time);
    case SMS_SHAPER_MZV:
        return design_mzv(z, df, Td, amp, time);
    case SMS_SHAPER_EI3:
        return design_ei3(config->tolerance, K, Td, amp, time);
    case SMS_SHAPER_GMZV:
        return design_gmzv(config->order, config->duration, z, df, Td, amp, time);
    case SMS_SHAPER_SI:
        return design_si(config, z, df, Td, amp, time);
    default:
        return design_zvn(sms_shaper_zv_order(config), K, Td, amp, time);
    }
}
