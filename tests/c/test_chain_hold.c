/* SPDX-License-Identifier: Apache-2.0 */
/* sms_chain_hold(): n samples of a constant input give the state and output of n samples
 * filtered one by one, bit for bit, for random chains (smoothers on and off the grid, shapers,
 * notches), random histories and every n around the stages' absorption (short holds filter,
 * long ones use the closed forms); holds of up to 2^60 samples against the sample-by-sample
 * reference reduced by the period of the absorbed state (lcm of 2M and L, which the short
 * holds show to hold). Also: the notch's transient ends exactly (w = +0) within its bound,
 * and sms_chain_hold_cost() bounds the filtering the hold needs. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include "check.h"
#include "xorshift.h"

#define MAX_CELLS 4096
#define MAX_STATE 4096

static uint64_t rng = 0x9E3779B97F4A7C15ull;
static double uniform(void)
{
    return xorshift_uniform(&rng);
}

static const sms_kind kinds[] = {
    SMS_RECTANGULAR, SMS_HARMONIC, SMS_DAMPED_HARMONIC, SMS_EXPONENTIAL, SMS_SHAPER_ZV,
    SMS_SHAPER_ZVD, SMS_SHAPER_EI, SMS_NOTCH_TUSTIN, SMS_NOTCH_MATCHED
};

static sms_stage_config random_config(void)
{
    sms_stage_config c = sms_stage_config_default(kinds[(size_t)(uniform() * 9.0) % 9u]);
    double len = 2.0 + 30.0 * uniform();
    if (uniform() < 0.5)
        len = floor(len);                         /* on the grid (no correction taps) */
    c.T = len;
    c.sigma = c.kind == SMS_DAMPED_HARMONIC || c.kind == SMS_EXPONENTIAL ? -0.2 * uniform() : 0.0;
    c.wn = 6.283185307179586 / len;               /* shapers: period len samples */
    c.zeta = 0.1 * uniform();
    if (c.kind == SMS_NOTCH_TUSTIN || c.kind == SMS_NOTCH_MATCHED) {
        c.wn = 0.05 + 2.0 * uniform();            /* rad per sample */
        c.zeta = 0.05 * uniform();
        c.notch_pole_zeta = 0.1 + 1.5 * uniform();
    }
    return c;
}

static size_t gcd(size_t a, size_t b)
{
    while (b != 0) {
        size_t t = a % b;
        a = b;
        b = t;
    }
    return a;
}

/* The period of an absorbed chain's state: only the smoothers' ages (2M) and the rings'
 * heads (M, L) move. */
static size_t absorbed_period(const sms_chain *c)
{
    size_t p = 1, i;
    for (i = 0; i < c->n_stages; ++i) {
        size_t q = 1;
        const sms_stage *s = &c->stages[i];
        if (s->kind <= SMS_EXPONENTIAL)
            q = 2u * s->u.smoother->window;
        else if (s->kind != SMS_NOTCH_TUSTIN && s->kind != SMS_NOTCH_MATCHED)
            q = s->u.shaper->length;
        p = p / gcd(p, q) * q;
    }
    return p;
}

/* The reference: n samples of x, one block of constant input after another. */
static sms_real filter_samples(sms_chain *c, sms_real x, uint64_t n)
{
    sms_real buf[512], y = 0;
    while (n > 0) {
        size_t b = n < 512u ? (size_t)n : 512u, i;
        for (i = 0; i < b; ++i)
            buf[i] = x;
        sms_chain_process(c, buf, buf, b);
        y = buf[b - 1];
        n -= b;
    }
    return y;
}

typedef struct fixture {
    sms_stage_config configs[3];
    size_t n;
    sms_chain chain;
    sms_stage stages[3];
    sms_memory_cell mem[MAX_CELLS];
} fixture;

static int build(fixture *f, const fixture *src)
{
    size_t cells;
    memcpy(f->configs, src->configs, sizeof f->configs);
    f->n = src->n;
    if (sms_chain_memory_size(f->configs, f->n, 1.0, &cells) != SMS_OK || cells > MAX_CELLS)
        return 1;
    return sms_chain_init(&f->chain, f->stages, f->configs, f->n, 1.0, f->mem, MAX_CELLS) != SMS_OK;
}

static int same_state(const sms_chain *a, const sms_chain *b)
{
    static double sa[MAX_STATE], sb[MAX_STATE];
    size_t n = sms_chain_state_count(a);
    if (n != sms_chain_state_count(b) || n > MAX_STATE)
        return 0;
    sms_chain_get_state(a, sa);
    sms_chain_get_state(b, sb);
    return memcmp(sa, sb, n * sizeof sa[0]) == 0;
}

/* One case: a random history into both copies, then hold x for n samples in one and filter
 * them in the other (reduced by the absorbed period beyond `settled`). */
static void compare(fixture *held, fixture *ticked, sms_real x, uint64_t n, uint64_t settled)
{
    sms_real y_hold = (sms_real)12345, y_ref;
    uint64_t m = n;
    sms_chain_hold(&held->chain, x, n, &y_hold);
    if (n > settled) {
        uint64_t p = absorbed_period(&ticked->chain);
        m = settled + (n - settled) % p;
    }
    y_ref = filter_samples(&ticked->chain, x, m);
    CHECK(memcmp(&y_hold, &y_ref, sizeof y_ref) == 0);
    CHECK(same_state(&held->chain, &ticked->chain));
    if (memcmp(&y_hold, &y_ref, sizeof y_ref) != 0 || !same_state(&held->chain, &ticked->chain))
        fprintf(stderr, "  n = %llu, kinds %d %d %d (%lu stages), y %.17g vs %.17g\n",
                (unsigned long long)n, (int)held->configs[0].kind, (int)held->configs[1].kind,
                (int)held->configs[2].kind, (unsigned long)held->n, (double)y_hold,
                (double)y_ref);
}

static void random_holds(void)
{
    static fixture proto, a, b;
    int trial, cases = 0;
    for (trial = 0; trial < 400; ++trial) {
        double cost;
        size_t i, hist;
        uint64_t settled, k, ns[12];
        sms_real x;
        proto.n = 1u + (size_t)(uniform() * 3.0) % 3u;
        for (i = 0; i < proto.n; ++i)
            proto.configs[i] = random_config();
        if (build(&a, &proto) != 0)
            continue;
        CHECK_STATUS(sms_chain_hold_cost(proto.configs, proto.n, 1.0, &cost), SMS_OK);
        if (cost > 2e5)
            continue;   /* keep the reference quick */
        /* T = the last stage's absorption bound: cost is the sum of the T_i, T_n-1 the largest */
        settled = (uint64_t)cost + 16u;
        for (k = 0; k < 12; ++k) {
            static const double frac[12] = {0.0, 0.0, 0.1, 0.3, 0.5, 0.7, 0.9, 1.0, 1.1, 1.5, 3.0,
                                            0.0};
            ns[k] = (uint64_t)(frac[k] * (double)cost / (double)proto.n) + 1u + k % 2u;
        }
        ns[11] = ((uint64_t)1 << 60) + (uint64_t)(uniform() * 1e6);
        for (k = 0; k < 12; ++k) {
            build(&a, &proto);
            build(&b, &proto);
            sms_chain_reset(&a.chain, (sms_real)(uniform() - 0.5));
            /* identical histories: the same reset and random samples into both */
            {
                static double st[MAX_STATE];
                sms_chain_get_state(&a.chain, st);
                sms_chain_set_state(&b.chain, st, sms_chain_state_count(&a.chain));
            }
            hist = (size_t)(uniform() * 80.0);
            for (i = 0; i < hist; ++i) {
                sms_real v = (sms_real)(4.0 * uniform() - 2.0), w = v;
                sms_chain_step(&a.chain, &v);
                sms_chain_step(&b.chain, &w);
            }
            x = (sms_real)(uniform() < 0.1 ? 0.0 : 10.0 * uniform() - 5.0);
            compare(&a, &b, x, ns[k], settled);
            ++cases;
        }
    }
    CHECK(cases > 1000);
    printf("chain hold: %d random cases\n", cases);
}

/* A notch's transient ends with w = +0 exactly (no subnormal cycle), within its bound. */
static void notch_settles(void)
{
    const double wn[4] = {0.02, 0.3, 1.5, 3.0}, xi2[4] = {0.05, 0.7, 1.0, 3.0};
    int i, j, kind;
    for (kind = 0; kind < 2; ++kind)
        for (i = 0; i < 4; ++i)
            for (j = 0; j < 4; ++j) {
                sms_stage_config c = sms_stage_config_default(kind ? SMS_NOTCH_MATCHED
                                                                   : SMS_NOTCH_TUSTIN);
                sms_notch f;
                double bound;
                uint64_t t = 0;
                sms_real x = (sms_real)1e3, v;
                c.wn = wn[i];
                c.zeta = 0.0;
                c.notch_pole_zeta = xi2[j];
                CHECK_STATUS(sms_notch_init(&f, &c, 1.0), SMS_OK);
                sms_notch_reset(&f, (sms_real)-1e3);
                bound = sms_notch_settle_bound(&f);
                CHECK(bound > 0.0 && bound < 1e7);
                while (!sms_notch_is_settled(&f, x) && (double)t <= bound) {
                    v = x;
                    sms_notch_step(&f, &v);
                    ++t;
                }
                CHECK(sms_notch_is_settled(&f, x));
                CHECK((double)t <= bound);
                v = x;
                sms_notch_step(&f, &v);
                CHECK(v == x && sms_notch_is_settled(&f, x));
            }
}

int main(void)
{
    random_holds();
    notch_settles();
    return check_summary("test_chain_hold");
}
