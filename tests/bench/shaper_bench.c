/* SPDX-License-Identifier: Apache-2.0 */
/* Shaper, notch and identification figures (printed, never asserted): cost per sample,
 * residual vibration on the seed 000 mode for paper vs exact timing, identification accuracy. */
#include <complex.h>
#include <math.h>
#include <stdio.h>
#include "smoothshaper/smoothshaper.h"
#include "cpu_time.h"

#define PI 3.14159265358979323846
#define N_RUN 2000000
#define MAX_LEN 4096

static sms_memory_cell buf[MAX_LEN];
static double taps[MAX_LEN], rec[20000];

static void cost(const char *name, const sms_stage_config *c, double Ts)
{
    sms_stage stage;
    sms_real x = 0, acc = 0;
    double t0, t1;
    size_t i;
    if (sms_stage_init(&stage, c, Ts, buf, MAX_LEN) != SMS_OK) {
        printf("%-28s init failed\n", name);
        return;
    }
    t0 = cpu_seconds();
    for (i = 0; i < N_RUN; ++i) {
        x = (sms_real)(i & 1023);
        sms_stage_step(&stage, &x);
        acc += x;
    }
    t1 = cpu_seconds();
    /* a notch is IIR: 4 coefficients, no delay line */
    printf("%-28s taps %2zu  L %5zu  %6.2f ns/sample  (checksum %g)\n", name,
           c->kind >= SMS_NOTCH_TUSTIN ? (size_t)4 : stage.u.shaper->n_taps, sms_stage_length(&stage),
           1e9 * (t1 - t0) / N_RUN, (double)acc);
}

static double residual(const sms_stage_config *c, double Ts, double complex zp)
{
    size_t L, i;
    double complex acc = 0, zi = 1;
    if (sms_shaper_buffer_size(c, Ts, &L) != SMS_OK || sms_shaper_taps(c, Ts, taps, MAX_LEN) != SMS_OK)
        return NAN;
    for (i = 0; i < L; ++i) {
        acc += taps[i] * zi;
        zi /= zp;
    }
    return cabs(acc);
}

int main(void)
{
    const double Ts = 500e-6, sigma = -15.6539, wd = 122.7185;
    const double wn = sqrt(sigma * sigma + wd * wd), zeta = -sigma / wn;
    const double complex zp = cexp((sigma + I * wd) * Ts);
    sms_kind kinds[] = {SMS_SHAPER_ZV, SMS_SHAPER_ZVD, SMS_SHAPER_ZVDD, SMS_SHAPER_MZV, SMS_SHAPER_EI2};
    sms_stage_config c;
    size_t i;
    printf("precision: %s\n", sizeof(sms_real) == sizeof(float) ? "float" : "double");
    printf("\nresidual |H(e^{p Ts})| on the seed 000 mode (Td/(2 Ts) = %.3f):\n", PI / wd / Ts);
    for (i = 0; i < sizeof kinds / sizeof kinds[0]; ++i) {
        double exact, paper;
        (void)sms_design_for_mode(kinds[i], wn, zeta, 1, &c);
        exact = residual(&c, Ts, zp);
        c.timing = SMS_TIMING_PAPER;
        paper = residual(&c, Ts, zp);
        printf("  %-5s exact %.3g   paper %.3g\n", sms_kind_name(kinds[i]), exact, paper);
    }
    printf("\ncost per sample (%d samples):\n", N_RUN);
    (void)sms_design_for_mode(SMS_SHAPER_ZV, wn, zeta, 1, &c);
    cost("zv exact", &c, Ts);
    (void)sms_design_for_mode(SMS_SHAPER_ZVDD, wn, zeta, 1, &c);
    cost("zvdd exact", &c, Ts);
    (void)sms_design_for_mode(SMS_SHAPER_ZVN, wn, zeta, 1, &c);
    c.order = SMS_SHAPER_MAX_ORDER;
    cost("zv^8 exact", &c, Ts);
    (void)sms_design_for_mode(SMS_SHAPER_EI, wn, zeta, 1, &c);
    cost("ei exact", &c, Ts);
    (void)sms_design_for_mode(SMS_NOTCH_MATCHED, wn, zeta, 1, &c);
    cost("notch matched", &c, Ts);
    printf("\nidentification from a record (offset 3, white noise std s, amplitude 2.06):\n");
    {
        const double noises[] = {0.0, 0.01, 0.1, 0.5};
        size_t n = 2000, k, j;
        unsigned long state = 1;
        for (j = 0; j < 4; ++j) {
            sms_mode m;
            double t0;
            for (k = 0; k < n; ++k) {
                double t = (double)k * Ts, u1, u2;
                state = (state * 1103515245u + 12345u) & 0x7fffffffu;
                u1 = ((double)state + 0.5) / 2147483648.0;
                state = (state * 1103515245u + 12345u) & 0x7fffffffu;
                u2 = ((double)state + 0.5) / 2147483648.0;
                rec[k] = 3.0 + exp(sigma * t) * (2.0 * cos(wd * t) + 0.5 * sin(wd * t))
                         + noises[j] * sqrt(-2 * log(u1)) * cos(2 * PI * u2);
            }
            t0 = cpu_seconds();
            if (sms_identify_from_record(rec, n, Ts, &m) == SMS_OK)
                printf("  s = %-5g  wd %.6f (err %.2e)  sigma %.6f (err %.2e)  %.1f ms\n", noises[j],
                       m.wd, m.wd - wd, m.sigma, m.sigma - sigma, 1e3 * (cpu_seconds() - t0));
            else
                printf("  s = %-5g  rejected\n", noises[j]);
        }
    }
    return 0;
}
