/* SPDX-License-Identifier: Apache-2.0 */
/* Input smoothers: D. Butyugin's polynomial kernels with zero end values (smooth_zv,
 * smooth_mzv, smooth_ei, smooth_2hump_ei, smooth_zvd_ei, smooth_si of Klipper-derived firmware:
 * dmbutyugin/klipper, branch advanced-features, klippy/extras/shaper_defs.py, commit 0e5f3bb5,
 * 2024-10-03; the same definitions as in Kalico's and Danger-Klipper's ports), realised as
 * dense FIR filters on the shaper engine.
 *
 * Kernel: g(tau) = (1/T) P(tau/T - 1/2) on [0, T] (tau the lag), P(u) = sum_k q_k u^k with
 * int_{-1/2}^{1/2} P = 1 and P(+-1/2) = 0, T = t(zeta)/f, f = wn/(2 pi). The source tabulates
 * q_k (and t) as cubic polynomials in zeta for smooth_zv, smooth_mzv and smooth_ei and as
 * constants for the others; its convolution x_sm(t) = int x(t - s) w(s) ds over
 * s in [-T/2, T/2] is g delayed by T/2. Residual for a step, as the source defines it:
 * |int_0^T g(T - s) e^{-zeta wn s} e^{-j wd s} ds| = e^{-zeta wn T} |H_c(p)|,
 * H_c(s) = int_0^T g(tau) e^{-s tau} dtau.
 *
 * Discretisation (exact timing only): h_k = int g(tau) L(tau/Ts - k) dtau, L the unit
 * triangle on [-1, 1]: the continuous smoother applied to the linear interpolation of the
 * samples, evaluated at the samples. It keeps sum h = 1 and sum k Ts h_k = int tau g exactly
 * (linear interpolation reproduces constants and ramps). Then the correction d_k = |h_k|
 * (c_k . y), c_k = (1, k, Re z_p^-k, Im z_p^-k), z_p = e^{p Ts}, of least weighted norm
 * sum d_k^2/|h_k| that makes sum h = 1, sum k h = int tau g/Ts and H(z_p) = H_c(p) hold to
 * rounding: the residual at the design mode is the continuous smoother's for any Ts, each tap
 * moves in proportion to itself (the end taps stay near 0). */
#include <math.h>
#include "filter/input_smoother.h"

static const double pi = 3.14159265358979323846;

/* Gauss-Legendre, 8 points on [-1, 1]: exact for polynomials of degree <= 15. */
static const double gl_x[4] = {0.18343464249564980, 0.52553240991632899,
                               0.79666647741362674, 0.96028985649753623};
static const double gl_w[4] = {0.36268378337836198, 0.31370664587788729,
                               0.22238103445337447, 0.10122853629037626};

/* Coefficient tables of the source (shaper_defs.py): T f = sum_j t[j] zeta^j and
 * q_k = sum_j a[k][j] zeta^j (before normalisation), k = 0..degree. */
typedef struct kernel_table {
    unsigned degree;
    unsigned zeta_terms;      /* 4: cubic in zeta; 1: a constant */
    double t[4];
    double a[11][4];
} kernel_table;

static const kernel_table smooth_zv = {6u, 4u,
    {0.66471804, 0.0039585139, 0.33614293, 0.2157273},
    {{0.1418285825, -0.4423501425, 0.696114325, -1.3609939},
     {0.0, 3.5635179, -3.83613985, -6.2783295},
     {-15.50842883, 29.06586482, -12.3383868, 112.6474131},
     {0.0, -206.8822741, 52.8629899, 152.492858},
     {452.7401905, -281.3808295, -2.555613, -1175.326975},
     {0.0, 770.51281, -150.073722, -509.51816},
     {-1571.90293, 688.77989, 163.085324, 2986.0529}}};

static const kernel_table smooth_mzv = {10u, 4u,
    {0.85165483, 0.0183642417, 0.39000898, 0.23209004},
    {{2.239795725, -0.3957072675, -5.57438075, 0.07195255},
     {0.0, 29.10368225, -3.461668825, -22.41514},
     {-154.4864979, 92.80041407, 23.0961391, 774.3910148},
     {0.0, -1362.168729, -35.59728045, 1147.640935},
     {3870.466035, -3292.00459, 7849.3652856, -36092.1938},
     {0.0, 21476.8835, 2071.594648, -21131.4185},
     {-43110.2746, 39792.0705, -138379.754, 483530.1615},
     {0.0, -134532.955, -15615.6118, 139113.6955},
     {214526.885, -191572.8415, 791628.475, -2450648.74},
     {0.0, 274229.94, 32481.346, -286062.83},
     {-378797.98, 316954.83, -1455001.66, 4177695.0}}};

static const kernel_table smooth_ei = {10u, 4u,
    {0.96753911, 0.48592866, -7.2991788, 18.2075661},
    {{2.4923607, 1.1935848, -46.9202175, 127.76906},
     {0.0, 33.3731105, 103.46339, -262.7533525},
     {-166.2319578, -317.4835492, 5178.61787, -13957.64074},
     {0.0, -1914.663767, -2867.941885, 6546.52041},
     {4043.65056, 13078.06184, -149368.2255, 386432.888},
     {0.0, 30664.02555, 11115.66415, 4553.999},
     {-43879.103, -162723.6625, 1672995.285, -4352601.97},
     {0.0, -184244.5385, 56995.0041, -422243.748},
     {213582.6565, 773861.825, -7739194.35, 2.06293873e7},
     {0.0, 360348.71, -248768.99, 1264398.56},
     {-371055.41, -1248811.1, 1.24707394e7, -3.4165302e7}}};

/* The damping-independent ones: the source lists q_8 first; here q_0 first. */
static const kernel_table smooth_ei2 = {8u, 1u, {1.14875, 0.0, 0.0, 0.0},
    {{0.8375784787864095}, {-4.018706414213658}, {57.95603221424528}, {121.2177946817349},
     {-1475.914693073253}, {-1051.778387878068}, {10554.22832043971}, {2524.826047114184},
     {-22525.88434486782}}};

static const kernel_table smooth_zvd_ei = {8u, 1u, {1.475, 0.0, 0.0, 0.0},
    {{1.083220648523371}, {-3.577268915175282}, {43.1595785340444}, {96.48879052981883},
     {-1209.429748155012}, {-807.3061869131075}, {8786.608981369287}, {1914.349309746547},
     {-18835.07746719777}}};

static const kernel_table smooth_si = {8u, 1u, {1.245, 0.0, 0.0, 0.0},
    {{1.267781046297883}, {-2.226157642004671}, {4.234582468800491}, {52.69679971161049},
     {-295.546608490564}, {-476.8554763069169}, {2579.985143622855}, {1206.747198930197},
     {-6186.76006449789}}};

int sms_is_input_smoother(sms_kind kind)
{
    return kind >= SMS_SMOOTH_ZV && kind <= SMS_SMOOTH_SI;
}

int sms_input_smoother_reads_zeta(sms_kind kind)
{
    return kind == SMS_SMOOTH_ZV || kind == SMS_SMOOTH_MZV || kind == SMS_SMOOTH_EI;
}

static const kernel_table *table_of(sms_kind kind)
{
    switch (kind) {
    case SMS_SMOOTH_ZV: return &smooth_zv;
    case SMS_SMOOTH_MZV: return &smooth_mzv;
    case SMS_SMOOTH_EI: return &smooth_ei;
    case SMS_SMOOTH_EI2: return &smooth_ei2;
    case SMS_SMOOTH_ZVD_EI: return &smooth_zvd_ei;
    default: return &smooth_si;
    }
}

static double in_zeta(const double *c, unsigned terms, double zeta)
{
    double v = 0.0;
    unsigned j = terms;
    while (j-- > 0u)
        v = v * zeta + c[j];
    return v;
}

unsigned sms_input_smoother_kernel(const sms_stage_config *c, double *q, double *T)
{
    const kernel_table *tab = table_of(c->kind);
    double zeta = sms_input_smoother_reads_zeta(c->kind) ? c->zeta : 0.0, area = 0.0;
    unsigned k;
    for (k = 0; k <= tab->degree; ++k) {
        q[k] = in_zeta(tab->a[k], tab->zeta_terms, zeta);
        if (k % 2u == 0u)                   /* int_{-1/2}^{1/2} u^k du = 2^-k/(k+1), k even */
            area += q[k] / (ldexp(1.0, (int)k) * (double)(k + 1u));
    }
    for (k = 0; k <= tab->degree; ++k)
        q[k] /= area;
    *T = in_zeta(tab->t, tab->zeta_terms, zeta) * 2.0 * pi / c->wn;
    return tab->degree;
}

/* g(tau) of the kernel (q, degree, T); 0 outside [0, T]. */
static double kernel_at(const double *q, unsigned degree, double T, double tau)
{
    double u = tau / T - 0.5, v = 0.0;
    unsigned k = degree + 1u;
    if (tau < 0.0 || tau > T)
        return 0.0;
    while (k-- > 0u)
        v = v * u + q[k];
    return v / T;
}

/* int_a^b g(tau) (alpha + beta tau) dtau by 8-point Gauss-Legendre (exact: degree <= 11). */
static double integral(const double *q, unsigned degree, double T, double a, double b,
                       double alpha, double beta)
{
    double mid = 0.5 * (a + b), half = 0.5 * (b - a), acc = 0.0;
    int i, s;
    if (!(b > a))
        return 0.0;
    for (i = 0; i < 4; ++i)
        for (s = -1; s <= 1; s += 2) {
            double tau = mid + (double)s * half * gl_x[i];
            acc += gl_w[i] * kernel_at(q, degree, T, tau) * (alpha + beta * tau);
        }
    return acc * half;
}

/* Linear-interpolation tap h_k = int g(tau) L(tau/Ts - k) dtau over [0, T]. */
static double foh_tap(const double *q, unsigned degree, double T, double Ts, size_t k)
{
    double kk = (double)k, t0 = (kk - 1.0) * Ts, t1 = kk * Ts, t2 = (kk + 1.0) * Ts;
    double rise = integral(q, degree, T, t0 > 0.0 ? t0 : 0.0, t1 < T ? t1 : T, 1.0 - kk, 1.0 / Ts);
    double fall = integral(q, degree, T, t1 > 0.0 ? t1 : 0.0, t2 < T ? t2 : T, 1.0 + kk, -1.0 / Ts);
    return rise + fall;
}

sms_status sms_input_smoother_length(const sms_stage_config *c, double Ts, size_t *length)
{
    double q[11], T, mu, r;
    (void)sms_input_smoother_kernel(c, q, &T);
    mu = T / Ts;
    if (!(mu - mu == 0.0) || mu + 2.0 > (double)SMS_INPUT_SMOOTHER_MAX_LENGTH)
        return SMS_ERR_TOO_LONG;
    if (mu < 4.0)
        return SMS_ERR_ABOVE_NYQUIST;          /* the kernel must span at least 4 samples */
    r = floor(mu + 0.5);
    *length = fabs(mu - r) <= 1e-9 * mu ? (size_t)r + 1u : (size_t)floor(mu) + 2u;
    return SMS_OK;
}

/* Solve the symmetric positive definite 4x4 system M y = r (Cholesky). */
static void solve4(double M[4][4], const double r[4], double y[4])
{
    double Lw[4][4] = {{0.0}}, z[4];
    int i, j, k;
    for (j = 0; j < 4; ++j) {
        double s = M[j][j];
        for (k = 0; k < j; ++k)
            s -= Lw[j][k] * Lw[j][k];
        Lw[j][j] = sqrt(s);
        for (i = j + 1; i < 4; ++i) {
            double t = M[i][j];
            for (k = 0; k < j; ++k)
                t -= Lw[i][k] * Lw[j][k];
            Lw[i][j] = t / Lw[j][j];
        }
    }
    for (i = 0; i < 4; ++i) {
        double t = r[i];
        for (k = 0; k < i; ++k)
            t -= Lw[i][k] * z[k];
        z[i] = t / Lw[i][i];
    }
    for (i = 3; i >= 0; --i) {
        double t = z[i];
        for (k = i + 1; k < 4; ++k)
            t -= Lw[k][i] * y[k];
        y[i] = t / Lw[i][i];
    }
}

/* The constraint functionals of tap k: 1, k, Re and Im of z_p^-k (e^{zeta wn k Ts} e^{-j wd k Ts}). */
static void functionals(size_t k, double sigma_ts, double wd_ts, double c[4])
{
    double mag = exp(-sigma_ts * (double)k), arg = wd_ts * (double)k;
    c[0] = 1.0;
    c[1] = (double)k;
    c[2] = mag * cos(arg);
    c[3] = -mag * sin(arg);
}

/* H_c(s) = int_0^T g(tau) e^{-s tau} dtau by composite 8-point Gauss-Legendre: panels of at
 * most a twelfth of a period of Im s (and at least 32), where the rule's error is below 1e-16
 * of the integral's scale for the decays a validated config has. */
static void kernel_transfer(const double *q, unsigned degree, double T, double s_re,
                            double s_im, double *h_re, double *h_im)
{
    double turns = fabs(s_im) * T / (2.0 * pi), re = 0.0, im = 0.0;
    int panels = 32, panel, i, side;
    if (turns * 12.0 > (double)panels)
        panels = turns * 12.0 < 1e6 ? (int)ceil(turns * 12.0) : 1000000;
    for (panel = 0; panel < panels; ++panel) {
        double a = T * panel / panels, b = T * (panel + 1) / panels;
        double mid = 0.5 * (a + b), half = 0.5 * (b - a);
        for (i = 0; i < 4; ++i)
            for (side = -1; side <= 1; side += 2) {
                double tau = mid + (double)side * half * gl_x[i];
                double g = gl_w[i] * half * kernel_at(q, degree, T, tau);
                double mag = exp(-s_re * tau);
                re += g * mag * cos(s_im * tau);
                im -= g * mag * sin(s_im * tau);
            }
    }
    *h_re = re;
    *h_im = im;
}

void sms_input_smoother_transfer(const sms_stage_config *c, double s_re, double s_im,
                                 double *h_re, double *h_im)
{
    double q[11], T;
    unsigned degree = sms_input_smoother_kernel(c, q, &T);
    kernel_transfer(q, degree, T, s_re, s_im, h_re, h_im);
}

double sms_input_smoother_lag(const sms_stage_config *c, double Ts)
{
    double q[11], T;
    unsigned degree = sms_input_smoother_kernel(c, q, &T);
    return integral(q, degree, T, 0.0, T, 0.0, 1.0) / Ts;
}

int sms_input_smoother_taps(const sms_stage_config *c, double Ts, size_t length,
                            sms_shaper_tap *taps, double *dense, double *abs_sum)
{
    double q[11], T, M[4][4] = {{0.0}}, r[4], y[4], cs[4];
    double zeta = sms_input_smoother_reads_zeta(c->kind) ? c->zeta : 0.0;
    double sigma = -zeta * c->wn, wd = c->wn * sqrt(1.0 - zeta * zeta);
    double hc_re, hc_im, moment, sum = 0.0;
    unsigned degree = sms_input_smoother_kernel(c, q, &T);
    size_t k;
    int i, j;
    /* continuous targets: H_c(p) and the first moment */
    kernel_transfer(q, degree, T, sigma, wd, &hc_re, &hc_im);
    moment = integral(q, degree, T, 0.0, T, 0.0, 1.0);
    r[0] = 1.0;
    r[1] = moment / Ts;
    r[2] = hc_re;
    r[3] = hc_im;
    /* first pass: the weighted normal matrix and what the linear-interpolation taps give */
    for (k = 0; k < length; ++k) {
        double h = foh_tap(q, degree, T, Ts, k), w = fabs(h);
        functionals(k, sigma * Ts, wd * Ts, cs);
        for (i = 0; i < 4; ++i) {
            r[i] -= h * cs[i];
            for (j = 0; j < 4; ++j)
                M[i][j] += w * cs[i] * cs[j];
        }
    }
    solve4(M, r, y);
    for (i = 0; i < 4; ++i)
        if (!(y[i] - y[i] == 0.0))
            return 0;
    /* second pass: the corrected taps */
    for (k = 0; k < length; ++k) {
        double h = foh_tap(q, degree, T, Ts, k);
        functionals(k, sigma * Ts, wd * Ts, cs);
        h += fabs(h) * (cs[0] * y[0] + cs[1] * y[1] + cs[2] * y[2] + cs[3] * y[3]);
        if (taps != NULL) {
            taps[k].delay = k;
            taps[k].gain = (sms_real)h;
        }
        if (dense != NULL)
            dense[k] = h;
        if (abs_sum != NULL)   /* of the gains as the stage holds them, in tap order */
            sum += fabs((double)(sms_real)h);
    }
    if (abs_sum != NULL)
        *abs_sum = sum;
    return 1;
}
