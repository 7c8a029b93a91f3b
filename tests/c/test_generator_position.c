/* SPDX-License-Identifier: Apache-2.0 */
/* The single-axis generator with position limits [qmin, qmax]: every sample's q within them
 * exactly, v, a, j within their bounds (1 + SMS_LIMIT_RTOL), the rest on the last target
 * exactly; the refusals (configuration, targets, start states) with the generator untouched;
 * the brake-then-move re-plan exercised (the same runs without limits cross them); hold equal
 * to steps and a saved state continuing bit for bit. */
#include <string.h>
#include "check.h"
#include "xorshift.h"

static uint64_t rng = 0x9E3779B97F4A7C15ull;

static double urand(void) { return xorshift_uniform(&rng); }

static sms_generator_config config(double qmin, double qmax, sms_profile profile, double wn)
{
    sms_generator_config c;
    memset(&c, 0, sizeof c);
    c.vmax = 1.0;
    c.amax = 10.0;
    c.jmax = 100.0;
    c.profile = profile;
    c.wn = wn;
    c.qmin = qmin;
    c.qmax = qmax;
    return c;
}

static sms_target rest_at(double q)
{
    sms_target t;
    memset(&t, 0, sizeof t);
    t.interface = SMS_INTERFACE_POSITION;
    t.position = (sms_real)q;
    return t;
}

static sms_real buffers[2][4096];

static void test_config_refusals(void)
{
    sms_generator g;
    sms_generator_reach_info r;
    sms_generator_config c = config(1.0, -1.0, SMS_PROFILE_POLYNOMIAL, 0.0);
    sms_real out[4];
    CHECK_STATUS(sms_generator_reach(&c, 1e-3, &r), SMS_ERR_LIMIT);
    CHECK(strcmp(r.quantity, "qmax") == 0);
    c.qmax = 1.0; /* qmin == qmax: empty */
    CHECK_STATUS(sms_generator_init(&g, &c, 1e-3, NULL, 0), SMS_ERR_LIMIT);
    c.qmin = NAN;
    CHECK_STATUS(sms_generator_reach(&c, 1e-3, &r), SMS_ERR_LIMIT);
    CHECK(strcmp(r.quantity, "qmin") == 0);
    c = config(-1.0, INFINITY, SMS_PROFILE_POLYNOMIAL, 0.0);
    CHECK_STATUS(sms_generator_reach(&c, 1e-3, &r), SMS_ERR_LIMIT);
    CHECK(strcmp(r.quantity, "qmax") == 0);
    c = config(-1.0, 1.0, SMS_PROFILE_TRIGONOMETRIC, 0.0);
    CHECK_STATUS(sms_generator_reach(&c, 1e-3, &r), SMS_ERR_LIMIT);
    CHECK(strcmp(r.quantity, "qmin") == 0);
    /* one limit at 0 is a limit: [0, 2] */
    c = config(0.0, 2.0, SMS_PROFILE_POLYNOMIAL, 0.0);
    CHECK_STATUS(sms_generator_init(&g, &c, 1e-3, NULL, 0), SMS_OK);
    CHECK(g.bounded == 1);
    /* init rests at the limit nearer to 0 when 0 is outside */
    c = config(1.5, 3.0, SMS_PROFILE_POLYNOMIAL, 0.0);
    CHECK_STATUS(sms_generator_init(&g, &c, 1e-3, NULL, 0), SMS_OK);
    sms_generator_step(&g, (sms_real)1.5, out);
    CHECK(out[0] == (sms_real)1.5 && out[1] == 0 && out[2] == 0);
    sms_generator_reset(&g, (sms_real)5.0); /* outside: ignored */
    sms_generator_step(&g, (sms_real)1.5, out);
    CHECK(out[0] == (sms_real)1.5);
}

static void test_target_and_start_refusals(void)
{
    sms_generator g;
    sms_generator_config c = config(-1.0, 2.0, SMS_PROFILE_POLYNOMIAL, 0.0);
    sms_target t = rest_at(2.5);
    double before[64], after[64];
    sms_real out[4];
    size_t n, k;
    CHECK_STATUS(sms_generator_init(&g, &c, 1e-3, NULL, 0), SMS_OK);
    CHECK_STATUS(sms_generator_check_target(&g, &t), SMS_ERR_POSITION_LIMIT);
    t.position = (sms_real)-1.25;
    CHECK_STATUS(sms_generator_check_target(&g, &t), SMS_ERR_POSITION_LIMIT);
    t.position = (sms_real)2.0; /* on the limit: a target */
    CHECK_STATUS(sms_generator_check_target(&g, &t), SMS_OK);
    t.velocity = (sms_real)0.5; /* it would drift on: refused */
    CHECK_STATUS(sms_generator_check_target(&g, &t), SMS_ERR_TARGET_VELOCITY);
    t.velocity = 0;
    t.acceleration = (sms_real)1.0;
    CHECK_STATUS(sms_generator_check_target(&g, &t), SMS_ERR_TARGET_ACCELERATION);
    t.acceleration = 0;
    t.interface = SMS_INTERFACE_VELOCITY;
    t.velocity = (sms_real)0.5;
    CHECK_STATUS(sms_generator_check_target(&g, &t), SMS_ERR_TARGET_VELOCITY);
    t.interface = SMS_INTERFACE_STOP;
    CHECK_STATUS(sms_generator_check_target(&g, &t), SMS_OK);

    /* a refused start changes nothing */
    n = sms_generator_state_count(&g);
    CHECK(n <= 64);
    sms_generator_get_state(&g, before);
    t = rest_at(1.0);
    CHECK_STATUS(sms_generator_start(&g, (sms_real)2.25, 0, 0, &t), SMS_ERR_POSITION_LIMIT);
    /* at vmax towards qmax the brake (a triangle of 0.1 s ramps to -amax and back: amax^2 =
     * vmax jmax) covers 1/12 + 1/60 = 0.1: from 0.05 below qmax it crosses; 0.15 below not */
    CHECK_STATUS(sms_generator_start(&g, (sms_real)1.95, (sms_real)1.0, 0, &t),
                 SMS_ERR_POSITION_LIMIT);
    sms_generator_get_state(&g, after);
    CHECK(memcmp(before, after, n * sizeof(double)) == 0);
    /* 0.098 below: the brake crosses (by 0.002), the time-optimal reversal to the target
     * (a held at -amax through v = 0: 1/12 + 1/80 = 0.0958 on) does not: taken */
    CHECK_STATUS(sms_generator_start(&g, (sms_real)1.902, (sms_real)1.0, 0, &t), SMS_OK);
    for (k = 0; k < 2000; ++k) {
        sms_generator_step_target(&g, &t, out);
        CHECK(out[0] <= (sms_real)2.0 && out[0] >= (sms_real)-1.0);
    }
    CHECK(out[0] == (sms_real)1.0 && out[1] == 0);
        CHECK_STATUS(sms_generator_start(&g, (sms_real)1.85, (sms_real)1.0, 0, &t), SMS_OK);
    for (k = 0; k < 2000; ++k) {
        sms_generator_step_target(&g, &t, out);
        CHECK(out[0] <= (sms_real)2.0 && out[0] >= (sms_real)-1.0);
    }
    CHECK(out[0] == (sms_real)1.0 && out[1] == 0);
    /* a target outside given to step is ignored: the held one stays */
    t = rest_at(3.0);
    sms_generator_step_target(&g, &t, out);
    CHECK(out[0] == (sms_real)1.0 && out[1] == 0);
}

/* The extremes of the run of an unbounded generator from the same state and targets. */
typedef struct run_stats {
    double lo, hi;
} run_stats;

static void note(run_stats *s, const sms_real o[4])
{
    if ((double)o[0] < s->lo)
        s->lo = (double)o[0];
    if ((double)o[0] > s->hi)
        s->hi = (double)o[0];
}

#define MAX_TARGETS 12

static void test_campaign(int cases)
{
    int c, accepted = 0, refused = 0, crossed = 0, refused_right = 0;
    const double rtol = SMS_LIMIT_RTOL;
    for (c = 0; c < cases; ++c) {
        const int damped = c % 3 == 2;
        const double Ts = c % 2 ? 1e-3 : 7.3e-3;
        const double span = urand() < 0.3 ? 0.02 + 0.1 * urand() : 0.2 + 2.0 * urand();
        const double qmin = -span * urand(), qmax = qmin + span;
        sms_generator_config cb = config(qmin, qmax, damped ? SMS_PROFILE_DAMPED
                                                            : SMS_PROFILE_POLYNOMIAL,
                                         damped ? 60.0 : 0.0);
        sms_generator_config cu = cb;
        sms_generator g, u, h;
        sms_target tg[MAX_TARGETS];
        int hold[MAX_TARGETS], nt = 1 + (int)(urand() * (MAX_TARGETS - 1)), i, k;
        double q0, v0, a0, saved[256];
        sms_real o[4], w[4];
        sms_status st;
        run_stats su = {1e300, -1e300};
        sms_generator_config cf;
        cu.qmin = cu.qmax = 0.0;
        cf = cu; /* the fine twin's plan alone (the damped profile plans the same ramps) */
        cf.wn = 0.0;
        cf.profile = SMS_PROFILE_POLYNOMIAL;
        CHECK_STATUS(sms_generator_init(&g, &cb, Ts, buffers[0], 4096), SMS_OK);
        /* the twin samples 64 times finer: its samples show the continuous extremes to
         * amax (Ts/64)^2/2, 7e-7 at most here */
        CHECK_STATUS(sms_generator_init(&u, &cf, Ts / 64.0, NULL, 0),
                     SMS_OK);
        /* a start near a limit, often moving fast towards it */
        q0 = urand() < 0.5 ? qmax - 0.3 * span * urand() : qmin + 0.3 * span * urand();
        v0 = (q0 > 0.5 * (qmin + qmax) ? 1.0 : -1.0) * (urand() < 0.7 ? urand() : -urand());
        a0 = 10.0 * (2.0 * urand() - 1.0) * (1.0 - fabs(v0));
        a0 *= 0.9;
        if (fabs(v0 + a0 * fabs(a0) / 200.0) > 1.0)
            a0 = 0.0;
        for (i = 0; i < nt; ++i) {
            double x = urand();
            tg[i] = rest_at(x < 0.2 ? qmax : x < 0.4 ? qmin : qmin + span * urand());
            hold[i] = 1 + (int)(urand() * (urand() < 0.5 ? 60.0 : 400.0));
            if (urand() < 0.3)
                tg[i].minimum_duration = (sms_real)(1.5 * urand());
        }
        hold[nt - 1] = (int)(4.0 / Ts) + 200 + (int)(g.stage_length);
        st = sms_generator_start(&g, (sms_real)q0, (sms_real)v0, (sms_real)a0, &tg[0]);
        CHECK_STATUS(sms_generator_start(&u, (sms_real)q0, (sms_real)v0, (sms_real)a0, NULL),
                     SMS_OK);
        if (st != SMS_OK) {
            /* refused: the unbounded brake from there crosses a limit */
            CHECK_STATUS(st, SMS_ERR_POSITION_LIMIT);
            ++refused;
            for (k = 0; k < (int)(2.0 * 64.0 / Ts) + 1000; ++k) {
                sms_target stop;
                memset(&stop, 0, sizeof stop);
                stop.interface = SMS_INTERFACE_STOP;
                sms_generator_step_target(&u, &stop, o);
                note(&su, o);
            }
            if (su.hi > qmax - 1e-6 || su.lo < qmin + 1e-6) {
                /* and the time-optimal motion to the target crosses too */
                run_stats sd = {1e300, -1e300};
                CHECK_STATUS(sms_generator_init(&u, &cf, Ts / 64.0, NULL, 0), SMS_OK);
                CHECK_STATUS(sms_generator_start(&u, (sms_real)q0, (sms_real)v0, (sms_real)a0,
                                                 &tg[0]), SMS_OK);
                for (k = 0; k < (int)(4.0 * 64.0 / Ts) + 1000; ++k) {
                    sms_generator_step_target(&u, &tg[0], o);
                    note(&sd, o);
                }
                if (sd.hi > qmax - 1e-6 || sd.lo < qmin + 1e-6)
                    ++refused_right;
            }
            continue;
        }
        ++accepted;
        CHECK_STATUS(sms_generator_init(&u, &cu, Ts, buffers[1], 4096), SMS_OK);
        CHECK_STATUS(sms_generator_start(&u, (sms_real)q0, (sms_real)v0, (sms_real)a0, &tg[0]),
                     SMS_OK);
        for (i = 0; i < nt; ++i) {
            for (k = 0; k < hold[i]; ++k) {
                if (i == nt / 2 && k == hold[i] / 2 && !damped) {
                    /* a saved state loads into a fresh generator and continues bit for bit */
                    size_t n = sms_generator_state_count(&g);
                    CHECK(n <= 256);
                    sms_generator_get_state(&g, saved);
                    CHECK_STATUS(sms_generator_init(&h, &cb, Ts, NULL, 0), SMS_OK);
                    CHECK_STATUS(sms_generator_set_state(&h, saved, n), SMS_OK);
                }
                sms_generator_step_target(&g, &tg[i], o);
                if (i == nt / 2 && k >= hold[i] / 2 && !damped) {
                    sms_generator_step_target(&h, &tg[i], w);
                    CHECK(memcmp(o, w, sizeof o) == 0);
                }
                CHECK(o[0] >= (sms_real)qmin && o[0] <= (sms_real)qmax);
                CHECK(fabs((double)o[1]) <= 1.0 * (1 + rtol));
                CHECK(fabs((double)o[2]) <= 10.0 * (1 + rtol));
                CHECK(fabs((double)o[3]) <= 100.0 * (1 + rtol));
                if (!(o[0] >= (sms_real)qmin && o[0] <= (sms_real)qmax)) {
                    fprintf(stderr, "case %d target %d sample %d: q %.17g outside [%.17g, %.17g]\n",
                            c, i, k, (double)o[0], qmin, qmax);
                    return;
                }
                sms_generator_step_target(&u, &tg[i], w);
                note(&su, w);
            }
        }
        CHECK(o[0] == tg[nt - 1].position && o[1] == 0 && o[2] == 0 && o[3] == 0);
        if (su.hi > qmax + 1e-6 * span || su.lo < qmin - 1e-6 * span)
            ++crossed;
    }
    printf("position limits [%s]: %d starts accepted, %d refused (%d of them with the unbounded "
           "brake and motion to the target crossing a limit), %d runs whose unbounded twin "
           "crosses a limit\n",
           SMS_TEST_PRECISION, accepted, refused, refused_right, crossed);
    CHECK(refused_right == refused);
    CHECK(refused > cases / 20);
    CHECK(crossed >= 10); /* the brake-then-move re-plan taken */
}

static void test_hold_equals_steps(void)
{
    /* from a fast approach: the re-plan brakes, waits, moves; hold_target of n equals n steps */
    sms_generator_config c = config(-0.5, 0.5, SMS_PROFILE_POLYNOMIAL, 60.0);
    sms_generator a, b;
    sms_target t = rest_at(0.45), s = rest_at(-0.2);
    sms_real oa[4], ob[4];
    int n;
    CHECK_STATUS(sms_generator_init(&a, &c, 1e-3, buffers[0], 4096), SMS_OK);
    CHECK_STATUS(sms_generator_start(&a, (sms_real)0.1, (sms_real)1.0, 0, &s), SMS_OK);
    for (n = 0; n < 30; ++n)
        sms_generator_step_target(&a, &s, oa);
    b = a;
    memcpy(buffers[1], buffers[0], sizeof buffers[0]);
    sms_generator_rebind(&b, buffers[1]);
    sms_generator_hold_target(&b, &t, 2500u, ob);
    for (n = 0; n < 2500; ++n) {
        sms_generator_step_target(&a, &t, oa);
        CHECK(oa[0] <= (sms_real)0.5 && oa[0] >= (sms_real)-0.5);
    }
    CHECK(memcmp(oa, ob, sizeof oa) == 0);
    CHECK(oa[0] == (sms_real)0.45);
}

static void test_state_identity(void)
{
    sms_generator_config c2 = config(-1.0, 2.0, SMS_PROFILE_POLYNOMIAL, 0.0), c3 = c2;
    sms_generator a, b;
    double st[64];
    c3.qmax = 3.0;
    CHECK_STATUS(sms_generator_init(&a, &c2, 1e-3, NULL, 0), SMS_OK);
    CHECK_STATUS(sms_generator_init(&b, &c3, 1e-3, NULL, 0), SMS_OK);
    CHECK(SMS_GENERATOR_IDENTITY_COUNT == 15);
    sms_generator_get_state(&a, st);
    CHECK(st[13] == -1.0 && st[14] == 2.0);
    CHECK_STATUS(sms_generator_set_state(&b, st, sms_generator_state_count(&a)),
                 SMS_ERR_POSITION_LIMIT);
    /* a saved plan starting outside the limits is refused */
    st[SMS_GENERATOR_IDENTITY_COUNT + SMS_GENERATOR_STATE_Q] = 2.5;
    CHECK_STATUS(sms_generator_check_state(&a, st, sms_generator_state_count(&a)), SMS_ERR_STATE);
}

int main(void)
{
    test_config_refusals();
    test_target_and_start_refusals();
    test_campaign(600);
    test_hold_equals_steps();
    test_state_identity();
    return check_summary("test_generator_position");
}
