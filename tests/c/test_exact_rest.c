/* SPDX-License-Identifier: Apache-2.0 */
/* Exact rest, a property over every family: random configurations of every kind, random rests
 * and constants, a random history before the constant. After sms_stage_reset(s, r) an input
 * of r comes out as r, bit for bit, from the first sample; a constant c after any history
 * comes out as c once the stage's length L has passed (from the L-th sample of c on), and a
 * chain's once its length (sms_chain_length()) has. A notch is IIR: its output is c once its
 * transient has ended exactly (notch.h), within sms_notch_settle_bound() samples. Every
 * sequence runs through step() on one instance and through process() in random blocks on a
 * twin, and the two must agree bit for bit. */
#include <string.h>
#include "check.h"
#include "xorshift.h"

#define MAX_CELLS 60000
#define STAGE_CASES 400
#define CHAIN_CASES 120
#define MAX_RUN 400000

static sms_memory_cell mem_a[MAX_CELLS], mem_b[MAX_CELLS];
static sms_real in[MAX_RUN], out_step[MAX_RUN], out_block[MAX_RUN];
static uint64_t rng = 0x2545F4914F6CDD1Dull;

static double uniform(double lo, double hi)
{
    return lo + (hi - lo) * xorshift_uniform(&rng);
}

/* A value of random sign and magnitude 1e-3 .. 1e6, or 0, or a value with a long mantissa. */
static sms_real value(void)
{
    const double u = xorshift_uniform(&rng);
    if (u < 0.1)
        return (sms_real)0;
    if (u < 0.2)
        return (sms_real)3.7;
    return (sms_real)((xorshift_uniform(&rng) < 0.5 ? -1.0 : 1.0) * pow(10.0, uniform(-3.0, 6.0)));
}

/* A random configuration of the given kind at Ts = 1 ms (may be invalid: the caller retries). */
static sms_stage_config random_config(sms_kind kind)
{
    sms_stage_config c = sms_stage_config_default(kind);
    const double Ts = 1e-3;
    const double t = xorshift_uniform(&rng);
    c.timing = t < 0.3 ? SMS_TIMING_PAPER : t < 0.5 ? SMS_TIMING_BOUNDED : SMS_TIMING_EXACT;
    c.T = uniform(1.0, 300.0) * Ts;
    c.sigma = -uniform(0.0, 40.0);
    c.k = 1u + 2u * (unsigned)(xorshift_uniform(&rng) * 2.0);
    c.wn = uniform(0.02, 1.0) / Ts;
    c.zeta = xorshift_uniform(&rng) < 0.3 ? 0.0 : uniform(0.0, 0.3);
    c.order = kind == SMS_SHAPER_GMZV ? 3u + (unsigned)(xorshift_uniform(&rng) * 3.0)
                                      : 1u + (unsigned)(xorshift_uniform(&rng) * 4.0);
    c.duration = uniform(0.5, 0.45 * (double)(c.order - 1u) + 0.5);
    c.tolerance = uniform(0.02, 0.2);
    c.notch_pole_zeta = c.zeta + uniform(0.1, 0.8);
    if (kind >= SMS_NOTCH_TUSTIN && kind <= SMS_NOTCH_MATCHED)
        c.wn = uniform(0.1, 1.0) / Ts;   /* a transient of at most ~1e5 samples */
    return c;
}

static int is_notch(sms_kind kind)
{
    return kind == SMS_NOTCH_TUSTIN || kind == SMS_NOTCH_MATCHED;
}

/* Samples after which a stage or chain given a constant must output it exactly. */
static size_t settle_after(const sms_chain *chain)
{
    double bound = (double)sms_chain_length(chain);
    size_t i;
    for (i = 0; i < chain->n_stages; ++i)
        if (is_notch(chain->stages[i].kind))
            bound += sms_notch_settle_bound(chain->stages[i].u.notch);
    return (size_t)bound;
}

/* The sequence: rest r for `lead` samples, a random history of `noise` samples, then the
 * constant c for `hold` samples; through a (step) and b (process in random blocks). */
static void run_sequence(sms_chain *a, sms_chain *b, sms_real r, sms_real c, size_t lead,
                         size_t noise, size_t hold, size_t settle)
{
    const size_t n = lead + noise + hold;
    size_t i, done = 0;
    int exact_rest = 1, exact_hold = 1, same = 1;
    for (i = 0; i < n; ++i)
        in[i] = i < lead ? r
                : i < lead + noise ? (sms_real)((double)r + uniform(-1.0, 1.0) * 100.0) : c;
    sms_chain_reset(a, r);
    sms_chain_reset(b, r);
    for (i = 0; i < n; ++i) {
        out_step[i] = in[i];
        sms_chain_step(a, &out_step[i]);
    }
    while (done < n) {
        size_t len = 1u + (size_t)(xorshift_uniform(&rng) * 300.0);
        if (len > n - done)
            len = n - done;
        sms_chain_process(b, in + done, out_block + done, len);
        done += len;
    }
    for (i = 0; i < n; ++i) {
        if (memcmp(&out_step[i], &out_block[i], sizeof(sms_real)) != 0)
            same = 0;
        if (i < lead && out_step[i] != r)
            exact_rest = 0;
        if (i >= lead + noise + settle && out_step[i] != c)
            exact_hold = 0;
    }
    CHECK(same);
    CHECK(exact_rest);
    CHECK(exact_hold);
    if (!exact_rest || !exact_hold) {
        for (i = 0; i < a->n_stages; ++i)
            fprintf(stderr, "  stage %zu: %s, L %zu\n", i, sms_kind_name(a->stages[i].kind),
                    sms_stage_length(&a->stages[i]));
        fprintf(stderr, "  rest %.17g, constant %.17g, settle %zu, last output %.17g\n",
                (double)r, (double)c, settle, (double)out_step[n - 1u]);
    }
}

/* n random stages (kinds drawn from all, or the one given when n == 1 and kind >= 0). */
static int build(sms_chain *a, sms_chain *b, sms_stage *sa, sms_stage *sb, size_t n, int kind)
{
    sms_stage_config cfg[4];
    size_t i, need;
    for (i = 0; i < n; ++i) {
        int tries;
        for (tries = 0; tries < 50; ++tries) {
            const sms_kind k = kind >= 0 ? (sms_kind)kind
                                         : (sms_kind)(int)(xorshift_uniform(&rng) * SMS_KIND_COUNT);
            size_t cells;
            cfg[i] = random_config(k);
            if (sms_stage_memory_size(&cfg[i], 1e-3, &cells) == SMS_OK && cells < MAX_CELLS / 4)
                break;
        }
        if (tries == 50)
            return 0;
    }
    if (sms_chain_memory_size(cfg, n, 1e-3, &need) != SMS_OK || need > MAX_CELLS)
        return 0;
    CHECK_STATUS(sms_chain_init(a, sa, cfg, n, 1e-3, mem_a, MAX_CELLS), SMS_OK);
    CHECK_STATUS(sms_chain_init(b, sb, cfg, n, 1e-3, mem_b, MAX_CELLS), SMS_OK);
    return 1;
}

int main(void)
{
    sms_stage sa[4], sb[4];
    sms_chain a, b;
    int kind, built = 0, i;
    /* every kind alone, STAGE_CASES / SMS_KIND_COUNT configurations each */
    for (kind = 0; kind < SMS_KIND_COUNT; ++kind) {
        for (i = 0; i < STAGE_CASES / SMS_KIND_COUNT; ++i) {
            size_t settle, L;
            if (!build(&a, &b, sa, sb, 1, kind))
                continue;
            ++built;
            settle = settle_after(&a);
            L = settle + 10u;
            if (L + 800u > MAX_RUN)
                continue;
            run_sequence(&a, &b, value(), value(), 5u + (size_t)uniform(0.0, 400.0),
                         (size_t)uniform(0.0, 600.0), L, settle > 0u ? settle - 1u : 0u);
        }
    }
    CHECK(built >= STAGE_CASES * 9 / 10);
    /* chains of two to four random stages */
    for (i = 0; i < CHAIN_CASES; ++i) {
        const size_t n = 2u + (size_t)(xorshift_uniform(&rng) * 3.0);
        size_t settle;
        if (!build(&a, &b, sa, sb, n, -1))
            continue;
        settle = settle_after(&a);
        if (settle + 1000u > MAX_RUN)
            continue;
        run_sequence(&a, &b, value(), value(), 5u + (size_t)uniform(0.0, 300.0),
                     (size_t)uniform(0.0, 600.0), settle + 10u, settle > 0u ? settle - 1u : 0u);
    }
    return check_summary("test_exact_rest");
}
