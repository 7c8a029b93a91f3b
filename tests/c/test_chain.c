/* SPDX-License-Identifier: Apache-2.0 */
/* Chains of mixed stages: equal to the convolution of their stages' taps (then the notch
 * recursion), block/split invariance, state save/load, untouched-on-error, rebind. */
#include <string.h>
#include <stdlib.h>
#include "check.h"

#define PI 3.14159265358979323846
#define N_IN 3000
#define MAX_BUF 4096
#define MAX_TAPS 4096

static const double Ts = 500e-6;

/* Rectangular (T/Ts = 40.3), damped harmonic on the seed 000 mode (T/Ts = 153.6), ZVD and EI
 * on other modes, exponential, and a matched notch. */
static size_t mixed_configs(sms_stage_config *c)
{
    c[0] = sms_stage_config_default(SMS_RECTANGULAR);
    c[0].T = 40.3 * Ts;
    (void)sms_design_for_mode(SMS_DAMPED_HARMONIC, 123.7129, 0.12654, 1, &c[1]);
    (void)sms_design_for_mode(SMS_SHAPER_ZVD, 400.0, 0.05, 1, &c[2]);
    (void)sms_design_for_mode(SMS_SHAPER_EI, 900.0, 0.02, 1, &c[3]);
    (void)sms_design_for_mode(SMS_EXPONENTIAL, 300.0, 0.1, 1, &c[4]);
    (void)sms_design_for_mode(SMS_NOTCH_MATCHED, 1500.0, 0.01, 1, &c[5]);
    c[5].notch_pole_zeta = 0.5;
    return 6;
}

static size_t stage_taps(const sms_stage_config *c, double *taps)
{
    size_t L = 0;
    if (c->kind <= SMS_EXPONENTIAL) {
        CHECK_STATUS(sms_smoother_length(c, Ts, &L), SMS_OK);
        CHECK_STATUS(sms_smoother_taps(c, Ts, taps, MAX_TAPS), SMS_OK);
    } else {
        CHECK_STATUS(sms_shaper_buffer_size(c, Ts, &L), SMS_OK);
        CHECK_STATUS(sms_shaper_taps(c, Ts, taps, MAX_TAPS), SMS_OK);
    }
    return L;
}

static void random_input(sms_real *x, size_t n, unsigned seed, double offset)
{
    size_t i;
    srand(seed);
    for (i = 0; i < n; ++i)
        x[i] = (sms_real)(offset + 2.0 * rand() / RAND_MAX - 1.0);
}

static int same_bits(const sms_real *a, const sms_real *b, size_t n)
{
    return memcmp(a, b, n * sizeof *a) == 0;
}

static void test_equals_convolution(void)
{
    static sms_stage_config c[8];
    static sms_stage stages[8];
    static sms_memory_cell buf[MAX_BUF];
    static sms_real in[N_IN], out[N_IN];
    static double h[MAX_TAPS], tap[MAX_TAPS], tmp[MAX_TAPS], ref[N_IN];
    sms_chain chain;
    size_t n = mixed_configs(c), need, L = 1, i, j, s, Ls;
    double b[3], a[3], x1 = 0, x2 = 0, y1 = 0, y2 = 0, scale = 0, worst = 0;
    sms_notch probe;
    CHECK_STATUS(sms_chain_memory_size(c, n, Ts, &need), SMS_OK);
    CHECK(need <= MAX_BUF);
    CHECK_STATUS(sms_chain_init(&chain, stages, c, n, Ts, buf, MAX_BUF), SMS_OK);
    /* FIR part: convolution of the stages' taps */
    h[0] = 1;
    for (s = 0; s < n - 1; ++s) {
        Ls = stage_taps(&c[s], tap);
        for (i = 0; i < L + Ls - 1; ++i)
            tmp[i] = 0;
        for (i = 0; i < L; ++i)
            for (j = 0; j < Ls; ++j)
                tmp[i + j] += h[i] * tap[j];
        L += Ls - 1;
        memcpy(h, tmp, L * sizeof *h);
    }
    CHECK(sms_chain_length(&chain) == L);
    CHECK_STATUS(sms_notch_init(&probe, &c[n - 1], Ts), SMS_OK);
    /* the notch's realised transfer function: B = A + (1 - z^-1)(d0 - d2 z^-1) */
    a[1] = probe.a1; a[2] = probe.a2;
    b[0] = 1.0 + probe.d0; b[1] = a[1] - probe.d0 - probe.d2; b[2] = a[2] + probe.d2;
    random_input(in, N_IN, 5, 0.0);
    for (i = 0; i < N_IN; ++i) {
        double fir = 0, y;
        for (j = 0; j < L && j <= i; ++j)
            fir += h[j] * (double)in[i - j];
        y = b[0] * fir + b[1] * x1 + b[2] * x2 - a[1] * y1 - a[2] * y2;
        x2 = x1; x1 = fir; y2 = y1; y1 = y;
        ref[i] = y;
        if (fabs(y) > scale) scale = fabs(y);
    }
    sms_chain_process(&chain, in, out, N_IN);
    for (i = 0; i < N_IN; ++i)
        if (fabs((double)out[i] - ref[i]) > worst)
            worst = fabs((double)out[i] - ref[i]);
    /* a handful of stages, each exact to its precision's tolerance */
    CHECK(worst <= 10 * SMS_TEST_REL_TOL * scale);
}

static void test_splits_state_rebind(void)
{
    static sms_stage_config c[8];
    static sms_stage stages[8], stages2[8], stages_copy[8], saved_stages[8];
    static sms_memory_cell buf[MAX_BUF], buf2[MAX_BUF], buf_copy[MAX_BUF], saved_buf[MAX_BUF];
    static sms_real in[N_IN], one[N_IN], split[N_IN], other[N_IN];
    static double state[MAX_BUF + 200], bad[MAX_BUF + 200];
    sms_chain chain, chain2, copy, saved;
    size_t n = mixed_configs(c), pos = 0, cnt, half = N_IN / 2, i;
    random_input(in, N_IN, 9, 1e3);
    CHECK_STATUS(sms_chain_init(&chain, stages, c, n, Ts, buf, MAX_BUF), SMS_OK);
    CHECK_STATUS(sms_chain_init(&chain2, stages2, c, n, Ts, buf2, MAX_BUF), SMS_OK);
    sms_chain_process(&chain, in, one, N_IN);
    /* random splits, mixing process (in place) and step */
    srand(17);
    while (pos < N_IN) {
        size_t len = (size_t)(rand() % 120);
        if (len > N_IN - pos) len = N_IN - pos;
        memcpy(split + pos, in + pos, len * sizeof *in);
        if (len % 3 == 0) {
            for (i = 0; i < len; ++i)
                sms_chain_step(&chain2, &split[pos + i]);
        } else {
            sms_chain_process(&chain2, split + pos, split + pos, len);
        }
        pos += len;
    }
    CHECK(same_bits(one, split, N_IN));
    /* save mid-run, continue; load into a fresh chain: same continuation bit for bit */
    sms_chain_reset(&chain, 0);
    sms_chain_process(&chain, in, one, half);
    cnt = sms_chain_state_count(&chain);
    CHECK(cnt <= sizeof state / sizeof state[0]);
    sms_chain_get_state(&chain, state);
    sms_chain_process(&chain, in + half, one + half, N_IN - half);
    CHECK_STATUS(sms_chain_init(&chain2, stages2, c, n, Ts, buf2, MAX_BUF), SMS_OK);
    CHECK_STATUS(sms_chain_set_state(&chain2, state, cnt), SMS_OK);
    sms_chain_process(&chain2, in + half, split + half, N_IN - half);
    CHECK(same_bits(one + half, split + half, N_IN - half));
    /* wrong vectors change nothing: wrong length; a bad value in the last stages' part */
    saved = chain2;
    memcpy(saved_stages, stages2, sizeof stages2);
    memcpy(saved_buf, buf2, sizeof buf2);
    CHECK_STATUS(sms_chain_set_state(&chain2, state, cnt - 1), SMS_ERR_STATE);
    CHECK_STATUS(sms_chain_set_state(&chain2, state, cnt + 1), SMS_ERR_STATE);
    memcpy(bad, state, cnt * sizeof *state);
    bad[cnt - 6] = (double)SMS_NOTCH_TUSTIN;        /* notch state: kind tag of another kind */
    CHECK_STATUS(sms_chain_set_state(&chain2, bad, cnt), SMS_ERR_STATE);
    {   /* the ZVD stage (third) state: head out of range */
        size_t off = sms_stage_state_count(&stages2[0]) + sms_stage_state_count(&stages2[1]);
        memcpy(bad, state, cnt * sizeof *state);
        bad[off + SMS_STATE_IDENTITY_COUNT + 2] = 1e9;
        CHECK_STATUS(sms_chain_set_state(&chain2, bad, cnt), SMS_ERR_STATE);
    }
    CHECK(memcmp(&saved, &chain2, sizeof chain2) == 0);
    CHECK(memcmp(saved_stages, stages2, sizeof stages2) == 0);
    CHECK(memcmp(saved_buf, buf2, sizeof buf2) == 0);
    /* rebind: copy the chain, its stages and memory, rebind the copy, run both */
    sms_chain_reset(&chain, (sms_real)1e3);
    sms_chain_process(&chain, in, one, half);
    copy = chain;
    memcpy(stages_copy, stages, sizeof stages);
    memcpy(buf_copy, buf, sizeof buf);
    sms_chain_rebind(&copy, stages_copy, buf_copy);
    sms_chain_process(&chain, in + half, one + half, N_IN - half);
    memset(buf, 0, sizeof buf);                      /* the copy must not read the original */
    sms_chain_process(&copy, in + half, other + half, N_IN - half);
    CHECK(same_bits(one + half, other + half, N_IN - half));
}

static void test_errors(void)
{
    static sms_stage_config c[8];
    static sms_stage stages[8], before_stages[8];
    static sms_memory_cell buf[MAX_BUF], before_buf[MAX_BUF];
    sms_chain chain, before;
    size_t n = mixed_configs(c), need, i;
    memset(&chain, 0x42, sizeof chain);
    memset(stages, 0x43, sizeof stages);
    for (i = 0; i < MAX_BUF; ++i)
        buf[i].r = (sms_real)i;
    before = chain;
    memcpy(before_stages, stages, sizeof stages);
    memcpy(before_buf, buf, sizeof buf);
    CHECK_STATUS(sms_chain_memory_size(c, n, Ts, &need), SMS_OK);
    CHECK_STATUS(sms_chain_init(&chain, stages, c, n, Ts, buf, need - 1), SMS_ERR_BUFFER_TOO_SMALL);
    CHECK_STATUS(sms_chain_init(&chain, stages, c, n, Ts, NULL, need), SMS_ERR_NULL);
    CHECK_STATUS(sms_chain_init(&chain, stages, c, 0, Ts, buf, MAX_BUF), SMS_ERR_ORDER);
    CHECK_STATUS(sms_chain_init(&chain, stages, c, SMS_CHAIN_MAX_STAGES + 1, Ts, buf, MAX_BUF), SMS_ERR_ORDER);
    CHECK_STATUS(sms_chain_init(&chain, stages, c, n, 0.0, buf, MAX_BUF), SMS_ERR_SAMPLE_PERIOD);
    /* one bad config (the last one) among good ones */
    c[n - 1].notch_pole_zeta = 0.0;
    CHECK_STATUS(sms_chain_init(&chain, stages, c, n, Ts, buf, MAX_BUF), SMS_ERR_NOTCH_DAMPING);
    c[n - 1].notch_pole_zeta = 0.5;
    c[2].wn = 1e5;
    CHECK_STATUS(sms_chain_init(&chain, stages, c, n, Ts, buf, MAX_BUF), SMS_ERR_ABOVE_NYQUIST);
    c[2].wn = 400.0;
    c[0].T = 0.5 * Ts;
    CHECK_STATUS(sms_chain_init(&chain, stages, c, n, Ts, buf, MAX_BUF), SMS_ERR_DURATION_BELOW_TS);
    c[0].T = 40.3 * Ts;
    c[3].kind = (sms_kind)77;
    CHECK_STATUS(sms_chain_init(&chain, stages, c, n, Ts, buf, MAX_BUF), SMS_ERR_KIND);
    CHECK(memcmp(&chain, &before, sizeof chain) == 0);
    CHECK(memcmp(stages, before_stages, sizeof stages) == 0);
    CHECK(memcmp(buf, before_buf, sizeof buf) == 0);
    CHECK_STATUS(sms_chain_memory_size(c, n, Ts, NULL), SMS_ERR_NULL);
    CHECK_STATUS(sms_chain_init(NULL, stages, c, n, Ts, buf, MAX_BUF), SMS_ERR_NULL);
}

static size_t cells(size_t bytes)
{
    return (bytes + sizeof(sms_memory_cell) - 1) / sizeof(sms_memory_cell);
}

/* Memory follows the family: a stage is a kind and a pointer; its memory holds its own
 * instance, a shaper's own taps and its delay line, nothing sized for other families. */
static void test_memory_per_family(void)
{
    static sms_stage_config c[8];
    static sms_memory_cell buf[MAX_BUF];
    static sms_stage stages[8];
    const size_t per_cell = sizeof(sms_memory_cell) / sizeof(sms_real);
    size_t n = mixed_configs(c), i, sum = 0, total, used = 0;
    sms_chain chain;
    CHECK(sizeof(sms_stage) <= 2 * sizeof(void *));
    for (i = 0; i < n; ++i) {
        size_t need, reals, n_taps, expect;
        CHECK_STATUS(sms_stage_memory_size(&c[i], Ts, &need), SMS_OK);
        CHECK_STATUS(sms_stage_buffer_size(&c[i], Ts, &reals), SMS_OK);
        if (c[i].kind <= SMS_EXPONENTIAL) {
            expect = cells(sizeof(sms_smoother)) + (reals + per_cell - 1) / per_cell;
        } else if (c[i].kind >= SMS_NOTCH_TUSTIN && c[i].kind <= SMS_NOTCH_MATCHED) {
            expect = cells(sizeof(sms_notch));
            CHECK(reals == 0);
        } else {
            CHECK_STATUS(sms_shaper_tap_count(&c[i], Ts, &n_taps), SMS_OK);
            expect = cells(sizeof(sms_shaper)) + cells(n_taps * sizeof(sms_shaper_tap))
                     + (reals + per_cell - 1) / per_cell;
        }
        CHECK(need == expect);
        sum += need;
    }
    CHECK_STATUS(sms_chain_memory_size(c, n, Ts, &total), SMS_OK);
    CHECK(total == sum && total <= MAX_BUF);
    /* exactly the queried memory suffices, and each stage reports the part it uses */
    CHECK_STATUS(sms_chain_init(&chain, stages, c, n, Ts, buf, total), SMS_OK);
    for (i = 0; i < n; ++i)
        used += sms_stage_memory_len(&stages[i]);
    CHECK(used == total && chain.memory_len == total);
}

int main(void)
{
    test_memory_per_family();
    test_equals_convolution();
    test_splits_state_rebind();
    test_errors();
    return check_summary("test_chain");
}
