/* SPDX-License-Identifier: Apache-2.0 */
/* sms_design_for_mode: every family placed on a mode cancels it (where the family can), for
 * integer and non-integer T/Ts, through the stage interface; and every bad argument. */
#include <complex.h>
#include <string.h>
#include "check.h"

#define PI 3.14159265358979323846
#define MAX_LEN 8192

/* |H(z)| for taps h[0..L-1] */
static double complex transfer(const double *h, size_t L, double complex z)
{
    double complex acc = 0, zi = 1.0, zinv = 1.0 / z;
    size_t i;
    for (i = 0; i < L; ++i) {
        acc += h[i] * zi;
        zi *= zinv;
    }
    return acc;
}

static int is_smoother(sms_kind k) { return k <= SMS_EXPONENTIAL; }
static int is_notch(sms_kind k) { return k == SMS_NOTCH_TUSTIN || k == SMS_NOTCH_MATCHED; }

/* Can this family cancel a mode of damping zeta exactly? Undamped families (rectangular,
 * harmonic) only zeta = 0; the Tustin notch's zeros are the bilinear images of the s-zeros,
 * exactly on e^{p Ts} only on the unit circle (zeta = 0, thanks to pre-warping). */
static int cancels(sms_kind k, double zeta)
{
    if (k == SMS_RECTANGULAR || k == SMS_HARMONIC || k == SMS_NOTCH_TUSTIN)
        return zeta == 0.0;
    return 1;
}

static void test_fields(void)
{
    const double wn = 50.0, zeta = 0.1, wd = wn * sqrt(1 - zeta * zeta);
    sms_stage_config c;
    CHECK_STATUS(sms_design_for_mode(SMS_RECTANGULAR, wn, zeta, 2, &c), SMS_OK);
    CHECK_CLOSE(c.T, 2 * 2 * PI / wd, 1e-15, c.T);
    CHECK(c.k == 2 && c.sigma == 0 && c.timing == SMS_TIMING_EXACT && c.kind == SMS_RECTANGULAR);
    CHECK_STATUS(sms_design_for_mode(SMS_HARMONIC, wn, zeta, 3, &c), SMS_OK);
    CHECK_CLOSE(c.T, 3 * 3 * PI / wd, 1e-15, c.T);
    CHECK_STATUS(sms_design_for_mode(SMS_DAMPED_HARMONIC, wn, zeta, 1, &c), SMS_OK);
    CHECK_CLOSE(c.T, 3 * PI / wd, 1e-15, c.T);
    CHECK_CLOSE(c.sigma, -zeta * wn, 1e-15, zeta * wn);
    CHECK_STATUS(sms_design_for_mode(SMS_EXPONENTIAL, wn, zeta, 4, &c), SMS_OK);
    CHECK_CLOSE(c.T, 4 * 2 * PI / wd, 1e-15, c.T);
    CHECK_CLOSE(c.sigma, -zeta * wn, 1e-15, zeta * wn);
    CHECK_STATUS(sms_design_for_mode(SMS_SHAPER_EI, wn, zeta, 1, &c), SMS_OK);
    CHECK(c.wn == wn && c.zeta == zeta && c.tolerance == 0.05 && c.k == 1);
    CHECK_STATUS(sms_design_for_mode(SMS_NOTCH_MATCHED, wn, zeta, 1, &c), SMS_OK);
    CHECK(c.wn == wn && c.zeta == zeta && c.notch_pole_zeta == 0.7);
}

/* For every kind, modes with integer and non-integer T/Ts: the stage's impulse response equals
 * the family's taps, and the residual |H(z_p)| of a unit step on the mode is <= 1e-9. */
static void test_cancels(void)
{
    static double taps[MAX_LEN];
    static sms_memory_cell buf[MAX_LEN];
    struct { double wn, zeta, Ts; } modes[] = {
        {123.7129, 0.12654, 500e-6},          /* seed 000: sigma -15.6539, wd 122.7185, T/Ts 153.6 */
        {2 * PI / (200 * 1e-3), 0.0, 1e-3},   /* undamped, integer T/Ts (rectangular N = 200) */
        {260.4, 0.0, 1e-3},                   /* seed 001 Table 1 mode, non-integer */
        {37.0, 0.3, 2e-3},
    };
    unsigned k;
    size_t im;
    int kind;
    for (im = 0; im < 4; ++im) {
        double wn = modes[im].wn, zeta = modes[im].zeta, Ts = modes[im].Ts;
        double complex p = -zeta * wn + I * wn * sqrt(1 - zeta * zeta), zp = cexp(p * Ts);
        for (kind = 0; kind < SMS_KIND_COUNT; ++kind) {
            for (k = 1; k <= 3; k += 2) {
                sms_stage_config c;
                sms_stage stage;
                size_t need = 0, L = 0, i;
                double scale = 0;
                if (!is_smoother((sms_kind)kind) && k != 1)
                    continue;
                if (kind == SMS_SHAPER_IMPULSES)      /* no mode to design for */
                    continue;
                if ((kind == SMS_SMOOTH_ZV || kind == SMS_SMOOTH_MZV || kind == SMS_SMOOTH_EI)
                    && zeta > 0.25)                   /* the kernels' damping range */
                    continue;
                CHECK_STATUS(sms_design_for_mode((sms_kind)kind, wn, zeta, k, &c), SMS_OK);
                CHECK_STATUS(sms_stage_memory_size(&c, Ts, &need), SMS_OK);
                CHECK(need <= MAX_LEN);
                CHECK_STATUS(sms_stage_init(&stage, &c, Ts, buf, MAX_LEN), SMS_OK);
                if (is_notch((sms_kind)kind)) {
                    const sms_notch *f = stage.u.notch;
                    /* realised numerator A + (1 - z^-1)(d0 - d2 z^-1) (notch.h) */
                    double complex num = 1.0 + (double)f->a1 / zp + (double)f->a2 / (zp * zp)
                                         + (1.0 - 1.0 / zp) * ((double)f->d0 - (double)f->d2 / zp);
                    double s = 1.0 + (fabs((double)f->a1) + 2 * fabs((double)f->d0) + 2 * fabs((double)f->d2)) / cabs(zp)
                               + (fabs((double)f->a2) + fabs((double)f->d2)) / cabs(zp * zp);
                    if (cancels((sms_kind)kind, zeta))
                        CHECK(cabs(num) <= 4 * SMS_TEST_REL_TOL * s);
                    continue;
                }
                if (is_smoother((sms_kind)kind)) {
                    CHECK_STATUS(sms_smoother_length(&c, Ts, &L), SMS_OK);
                    CHECK_STATUS(sms_smoother_taps(&c, Ts, taps, MAX_LEN), SMS_OK);
                } else {
                    CHECK_STATUS(sms_shaper_buffer_size(&c, Ts, &L), SMS_OK);
                    CHECK_STATUS(sms_shaper_taps(&c, Ts, taps, MAX_LEN), SMS_OK);
                }
                CHECK(sms_stage_length(&stage) == L);
                for (i = 0; i < L; ++i)
                    if (fabs(taps[i]) > scale)
                        scale = fabs(taps[i]);
                for (i = 0; i < L + 3; ++i) {
                    sms_real x = i == 0 ? (sms_real)1 : (sms_real)0;
                    sms_stage_step(&stage, &x);
                    CHECK_CLOSE(x, i < L ? taps[i] : 0.0, 4 * SMS_TEST_REL_TOL, scale);
                }
                if (cancels((sms_kind)kind, zeta)) {
                    double complex target = 0;
                    /* the smooth EI2, ZVD-EI and SI kernels do not read zeta: they pin the
                     * undamped design point */
                    int undamped = kind == SMS_SMOOTH_EI2 || kind == SMS_SMOOTH_ZVD_EI
                                   || kind == SMS_SMOOTH_SI;
                    double complex pk = undamped ? I * wn : p, zk = cexp(pk * Ts);
                    if (kind == SMS_SHAPER_EI || kind == SMS_SHAPER_EI3 || kind >= SMS_SMOOTH_ZV) {
                        /* EI, EI3, SI and the input smoothers leave their designed residual
                         * H_c(p) by construction */
                        double h_re, h_im;
                        CHECK_STATUS(sms_shaper_transfer(&c, creal(pk), cimag(pk), &h_re, &h_im), SMS_OK);
                        target = h_re + I * h_im;
                    }
                    if (!(cabs(transfer(taps, L, zk) - target) <= 1e-9))
                        fprintf(stderr, "kind %s mode %u k %u: residual %.3g\n", sms_kind_name((sms_kind)kind),
                                (unsigned)im, k, cabs(transfer(taps, L, zk) - target));
                    CHECK(cabs(transfer(taps, L, zk) - target) <= 1e-9);
                }
            }
        }
    }
}

/* Why k must be odd: T = 2 * 3 pi/wn (integer N, seed formula) leaves wn between two zeros. */
static void test_even_k_leaves_residual(void)
{
    static double taps[MAX_LEN];
    const double Ts = 1e-3, wn = 6 * PI / (300 * Ts);
    sms_stage_config c = sms_stage_config_default(SMS_HARMONIC);
    size_t L;
    c.T = 300 * Ts;
    c.timing = SMS_TIMING_PAPER;
    CHECK_STATUS(sms_smoother_length(&c, Ts, &L), SMS_OK);
    CHECK_STATUS(sms_smoother_taps(&c, Ts, taps, MAX_LEN), SMS_OK);
    /* docs/errata.md quotes about 2.9 % */
    CHECK(cabs(transfer(taps, L, cexp(I * wn * Ts))) > 0.02);
    CHECK(cabs(transfer(taps, L, cexp(I * wn * Ts))) < 0.04);
}

static void test_invalid(void)
{
    sms_stage_config c, before;
    memset(&c, 0x77, sizeof c);
    before = c;
    CHECK_STATUS(sms_design_for_mode(SMS_RECTANGULAR, 10, 0, 1, NULL), SMS_ERR_NULL);
    CHECK_STATUS(sms_design_for_mode((sms_kind)SMS_KIND_COUNT, 10, 0, 1, &c), SMS_ERR_KIND);
    CHECK_STATUS(sms_design_for_mode((sms_kind)-1, 10, 0, 1, &c), SMS_ERR_KIND);
    CHECK_STATUS(sms_design_for_mode(SMS_RECTANGULAR, 0, 0, 1, &c), SMS_ERR_WN);
    CHECK_STATUS(sms_design_for_mode(SMS_RECTANGULAR, -3, 0, 1, &c), SMS_ERR_WN);
    CHECK_STATUS(sms_design_for_mode(SMS_RECTANGULAR, NAN, 0, 1, &c), SMS_ERR_WN);
    CHECK_STATUS(sms_design_for_mode(SMS_RECTANGULAR, INFINITY, 0, 1, &c), SMS_ERR_WN);
    CHECK_STATUS(sms_design_for_mode(SMS_EXPONENTIAL, 10, 1.0, 1, &c), SMS_ERR_ZETA);
    CHECK_STATUS(sms_design_for_mode(SMS_EXPONENTIAL, 10, -0.1, 1, &c), SMS_ERR_ZETA);
    CHECK_STATUS(sms_design_for_mode(SMS_EXPONENTIAL, 10, NAN, 1, &c), SMS_ERR_ZETA);
    CHECK_STATUS(sms_design_for_mode(SMS_EXPONENTIAL, 10, 0.1, 0, &c), SMS_ERR_MULTIPLE);
    CHECK_STATUS(sms_design_for_mode(SMS_HARMONIC, 10, 0.0, 2, &c), SMS_ERR_EVEN_MULTIPLE);
    CHECK_STATUS(sms_design_for_mode(SMS_DAMPED_HARMONIC, 10, 0.1, 4, &c), SMS_ERR_EVEN_MULTIPLE);
    CHECK_STATUS(sms_design_for_mode(SMS_HARMONIC, 10, 0.0, 0, &c), SMS_ERR_MULTIPLE);
    CHECK_STATUS(sms_design_for_mode(SMS_SHAPER_ZVD, 10, 0.1, 2, &c), SMS_ERR_MULTIPLE);
    CHECK_STATUS(sms_design_for_mode(SMS_NOTCH_TUSTIN, 10, 0.1, 3, &c), SMS_ERR_MULTIPLE);
    CHECK(memcmp(&c, &before, sizeof c) == 0);
    /* any k >= 1 for the rectangular and exponential families */
    CHECK_STATUS(sms_design_for_mode(SMS_RECTANGULAR, 10, 0.0, 2, &c), SMS_OK);
}

int main(void)
{
    test_fields();
    test_cancels();
    test_even_k_leaves_residual();
    test_invalid();
    return check_summary("test_design");
}
