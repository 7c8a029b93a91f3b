/* SPDX-License-Identifier: Apache-2.0 */
/* A retunable stage: two stage slots, the rule of tunable.h (each input increment filtered by
 * the filter active when it arrived), the switch and its end. Built on the stage API only. */
#include <float.h>
#include <math.h>
#include "smoothshaper/tunable.h"
#include "core/kind.h"
#include "filter/tunable_internal.h"

#ifdef SMS_USE_FLOAT
#define REAL_EPS ((sms_real)FLT_EPSILON)
#else
#define REAL_EPS ((sms_real)DBL_EPSILON)
#endif

/* The old filter's constant input is processed in blocks of this many samples on the stack. */
#define FADE_BLOCK 64u

sms_memory_cell *sms_tunable_slot_memory(const sms_tunable *t, unsigned slot)
{
    return t->memory + (size_t)slot * t->slot_cells;
}

sms_status sms_tunable_slot_cells(const sms_stage_config *declared, size_t n_declared, double Ts,
                                  size_t *slot_cells)
{
    size_t most = 0, i;
    if (declared == NULL || slot_cells == NULL)
        return SMS_ERR_NULL;
    if (n_declared == 0)
        return SMS_ERR_ORDER;
    for (i = 0; i < n_declared; ++i) {
        size_t need;
        sms_status st = sms_stage_memory_size(&declared[i], Ts, &need);
        if (st != SMS_OK)
            return st;
        if (need > most)
            most = need;
    }
    *slot_cells = most;
    return SMS_OK;
}

sms_status sms_tunable_memory_size(size_t slot_cells, size_t *n_cells)
{
    if (n_cells == NULL)
        return SMS_ERR_NULL;
    if (slot_cells > (size_t)-1 / 2u)
        return SMS_ERR_TOO_LONG;
    *n_cells = 2u * slot_cells;
    return SMS_OK;
}

sms_status sms_tunable_fits(const sms_stage_config *config, double Ts, size_t slot_cells)
{
    size_t need;
    sms_status st = sms_stage_memory_size(config, Ts, &need);
    if (st != SMS_OK)
        return st;
    return need <= slot_cells ? SMS_OK : SMS_ERR_BUFFER_TOO_SMALL;
}

sms_status sms_tunable_init(sms_tunable *t, const sms_stage_config *config, double Ts,
                            size_t slot_cells, sms_memory_cell *memory, size_t n_cells)
{
    sms_tunable built;
    size_t total;
    sms_status st;
    if (t == NULL || config == NULL)
        return SMS_ERR_NULL;
    st = sms_tunable_fits(config, Ts, slot_cells);
    if (st != SMS_OK)
        return st;
    st = sms_tunable_memory_size(slot_cells, &total);
    if (st != SMS_OK)
        return st;
    if (memory == NULL)
        return SMS_ERR_NULL;
    if (n_cells < slot_cells)
        return SMS_ERR_BUFFER_TOO_SMALL;
    built.memory = memory;
    built.slot_cells = slot_cells;
    built.n_slots = n_cells >= total ? 2u : 1u;
    built.Ts = Ts;
    built.active = 0;
    st = sms_stage_init(&built.slot[0], config, Ts, memory, slot_cells);
    if (st != SMS_OK)
        return st;
    built.slot[1].kind = (sms_kind)SMS_KIND_COUNT;   /* never built: no family */
    built.slot[1].u.smoother = NULL;
    built.switching = 0;
    built.fade = 0;
    built.last = built.hold = (sms_real)0;
    built.fade_real_poles = 0;
    built.fade_c1 = built.fade_c2 = built.fade_scale = built.fade_k = (sms_real)0;
    *t = built;
    return SMS_OK;
}

/* How the old filter's share ends (tunable.h). FIR: it equals h from L - 2 samples after the
 * switch on. Notch: once its last two inputs are h, its share is the free response
 * w[m] = -a1 w[m-1] - a2 w[m-2] from w1 = w[-1], w2 = w[-2]. With p, q its poles and
 * D_k = (p^k - q^k)/(p - q) = sum_{i<k} p^i q^(k-1-i), w[m] = q^(m+2) w2 + D_(m+2) (w1 - q w2),
 * and |D_k| <= k rho^(k-1) <= K = max_k k rho^(k-1), rho = max(|p|, |q|): so
 *   |w[m]| <= |w2| + K |w1 - q w2|   for every later m (any poles, equal ones too);
 * and for complex poles (q = conj p) also |w[m]| <= |w1 - q w2| / Im p (w[m] = 2 Re(c p^m)),
 * for distinct real ones (|w1 - q w2| + |w1 - p w2|) / |p - q|. The fade ends when either bound
 * is below the limit. */
void sms_tunable_begin_fade(sms_tunable *t, const sms_stage *old)
{
    t->fade = 0;
    t->switching = 0;
    if (sms_family_of(old->kind) != SMS_FAMILY_NOTCH) {
        const size_t len = sms_stage_length(old);
        t->fade = len > 2u ? (uint64_t)(len - 2u) : 0u;
        t->switching = t->fade > 0u;
        return;
    }
    {
        const double a1 = (double)old->u.notch->a1, a2 = (double)old->u.notch->a2;
        const double disc = a1 * a1 - 4.0 * a2;
        double rho, k;
        if (disc < 0.0) {
            t->fade_real_poles = 0;
            t->fade_c1 = (sms_real)(-0.5 * a1);
            t->fade_c2 = (sms_real)(0.5 * sqrt(-disc));
            t->fade_scale = t->fade_c2;
            rho = sqrt(a2);
        } else {
            const double q = sqrt(disc);
            t->fade_real_poles = 1;
            t->fade_c1 = (sms_real)(0.5 * (-a1 + q));
            t->fade_c2 = (sms_real)(0.5 * (-a1 - q));
            t->fade_scale = (sms_real)q;
            rho = fabs((double)t->fade_c1) > fabs((double)t->fade_c2) ? fabs((double)t->fade_c1)
                                                                      : fabs((double)t->fade_c2);
        }
        /* k rho^(k-1) peaks near k = 1/ln(1/rho) at most 1/(e rho ln(1/rho)); at least 1 */
        k = rho < 1.0 && rho > 0.0 ? 1.0 / (2.718281828459045 * rho * -log(rho)) : HUGE_VAL;
        t->fade_k = (sms_real)(k > 1.0 ? k : 1.0);
        t->switching = !sms_notch_is_settled(old->u.notch, t->hold);
    }
}

sms_status sms_tunable_retune(sms_tunable *t, const sms_stage_config *config)
{
    unsigned next;
    sms_status st;
    if (t == NULL || config == NULL)
        return SMS_ERR_NULL;
    if (t->switching)
        return SMS_ERR_RETUNE_BUSY;
    /* user-defined impulses: a saved state names them by a checksum, so a switch to or from
     * them could not be brought back (sms_tunable_state_configs()) */
    if (config->kind == SMS_SHAPER_IMPULSES || t->slot[t->active].kind == SMS_SHAPER_IMPULSES)
        return SMS_ERR_KIND;
    st = sms_tunable_fits(config, t->Ts, t->slot_cells);
    if (st == SMS_OK && t->n_slots < 2u)
        st = SMS_ERR_BUFFER_TOO_SMALL;   /* no room to switch */
    if (st != SMS_OK)
        return st;
    next = 1u - t->active;
    /* valid and fitting: this cannot fail, and the slot is free (no switch in progress) */
    st = sms_stage_init(&t->slot[next], config, t->Ts, sms_tunable_slot_memory(t, next),
                        t->slot_cells);
    if (st != SMS_OK)
        return st;
    sms_stage_reset(&t->slot[next], t->last);
    t->hold = t->last;
    sms_tunable_begin_fade(t, &t->slot[t->active]);
    t->active = next;
    return SMS_OK;
}

int sms_tunable_switching(const sms_tunable *t)
{
    return t->switching;
}

static sms_real magnitude(sms_real v)
{
    return v < 0 ? -v : v;
}

/* 1 once the old notch's remaining share is below a quarter of the unit roundoff of |h|
 * (eps/8 |h|) for every later sample (the bounds of sms_tunable_begin_fade()), or it has
 * settled exactly. */
static int notch_faded(const sms_tunable *t, const sms_notch *f)
{
    const sms_real h = t->hold, limit = magnitude(h) * (REAL_EPS / (sms_real)8);
    const sms_real w1 = f->w1, w2 = f->w2, k = t->fade_k;
    sms_real e1, e2, e_sq, rest;
    if (sms_notch_is_settled(f, h))
        return 1;
    if (!(f->x1 == h && f->x2 == h))   /* its input differences are not yet all zero */
        return 0;
    if (t->fade_real_poles) {
        e1 = w1 - t->fade_c2 * w2;
        e2 = (sms_real)0;
        if (magnitude(e1) + magnitude(w1 - t->fade_c1 * w2) <= limit * t->fade_scale)
            return 1;
    } else {
        const sms_real s = limit * t->fade_scale;
        e1 = w1 - t->fade_c1 * w2;
        e2 = t->fade_c2 * w2;
        if (e1 * e1 + e2 * e2 <= s * s)
            return 1;
    }
    /* |w2| + K |w1 - q w2| <= limit */
    rest = limit - magnitude(w2);
    e_sq = e1 * e1 + e2 * e2;
    return rest >= 0 && e_sq * k * k <= rest * rest;
}

/* Add the old filter's share y_A - h to out[0 .. m), the old filter running on h. */
static void fade_samples(sms_tunable *t, sms_real *out, size_t m)
{
    sms_stage *old = &t->slot[1u - t->active];
    const sms_real h = t->hold;
    sms_real block[FADE_BLOCK];
    if (sms_family_of(old->kind) == SMS_FAMILY_NOTCH) {
        size_t i;
        for (i = 0; i < m; ++i) {
            sms_real y = h;
            sms_notch_step(old->u.notch, &y);
            out[i] += y - h;
            ++t->fade;
            if (notch_faded(t, old->u.notch)) {
                t->switching = 0;
                t->fade = 0;
                return;
            }
        }
        return;
    }
    while (m > 0u) {
        const size_t b = m < FADE_BLOCK ? m : FADE_BLOCK;
        size_t i;
        for (i = 0; i < b; ++i)
            block[i] = h;
        sms_stage_process(old, block, block, b);
        for (i = 0; i < b; ++i)
            out[i] += block[i] - h;
        out += b;
        m -= b;
        t->fade -= b;
    }
    if (t->fade == 0u)
        t->switching = 0;
}

/* The last finite value of in[0 .. n), else last. */
static sms_real last_finite(const sms_real *in, size_t n, sms_real last)
{
    while (n > 0u) {
        --n;
        if (in[n] - in[n] == (sms_real)0)
            return in[n];
    }
    return last;
}

void sms_tunable_process(sms_tunable *t, const sms_real *in, sms_real *out, size_t n)
{
    while (n > 0u) {
        size_t m = n;
        sms_real last;
        const int fir_fade = t->switching
                             && sms_family_of(t->slot[1u - t->active].kind) != SMS_FAMILY_NOTCH;
        if (fir_fade && t->fade < (uint64_t)m)
            m = (size_t)t->fade;
        last = last_finite(in, m, t->last);   /* before in == out is overwritten */
        sms_stage_process(&t->slot[t->active], in, out, m);
        if (t->switching)
            fade_samples(t, out, m);
        t->last = last;
        in += m;
        out += m;
        n -= m;
    }
}

void sms_tunable_step(sms_tunable *t, sms_real *x)
{
    sms_tunable_process(t, x, x, 1);
}

void sms_tunable_reset(sms_tunable *t, sms_real rest)
{
    sms_stage_reset(&t->slot[t->active], rest);
    t->switching = 0;
    t->fade = 0;
    t->last = t->hold = rest;
}

const sms_stage *sms_tunable_active(const sms_tunable *t)
{
    return &t->slot[t->active];
}

double sms_tunable_switch_left(const sms_tunable *t)
{
    const sms_stage *old;
    const sms_notch *f;
    double limit, settle;
    if (!t->switching)
        return 0.0;
    old = &t->slot[1u - t->active];
    if (sms_family_of(old->kind) != SMS_FAMILY_NOTCH)
        return (double)t->fade;
    f = old->u.notch;
    limit = fabs((double)t->hold) * (double)REAL_EPS / 8.0;
    settle = sms_notch_settle_bound(f);
    {
        const double w1 = (double)f->w1, w2 = (double)f->w2, k = (double)t->fade_k;
        const double c1 = (double)t->fade_c1, c2 = (double)t->fade_c2;
        double rho, e, m = 0.0;
        int i;
        if (t->fade_real_poles) {
            rho = fabs(c1) > fabs(c2) ? fabs(c1) : fabs(c2);
            e = fabs(w1 - c2 * w2);
        } else {
            rho = sqrt(c1 * c1 + c2 * c2);
            e = sqrt((w1 - c1 * w2) * (w1 - c1 * w2) + (c2 * w2) * (c2 * w2));
        }
        /* |w[j]| <= (|w2| + e (j + 2)) rho^(j+1) (the D_k form of sms_tunable_begin_fade()),
         * and the end test's bound is at most (1 + K (1 + rho)) times the larger of the last
         * two: it passes once that is below the limit, which the fixed point m of
         * m = 2 + ln((1 + K (1 + rho)) (|w2| + e (m + 2)) / limit) / ln(1/rho) bounds (two
         * samples more for the input differences) */
        if (!(limit > 0.0) || !(rho < 1.0) || !(e < HUGE_VAL) || !(k < HUGE_VAL))
            return settle;
        for (i = 0; i < 60; ++i) {
            const double need = (1.0 + k * (1.0 + rho)) * (fabs(w2) + e * (m + 2.0)) / limit;
            const double next = need <= 1.0 ? 0.0 : 2.0 + log(need) / -log(rho);
            if (next <= m + 0.5)
                break;
            m = next;
        }
        return m + 2.0 < settle ? m + 2.0 : settle;
    }
}

double sms_tunable_input_max(const sms_tunable *t)
{
    double a = sms_stage_input_max(&t->slot[t->active]);
    if (t->switching) {
        const double b = sms_stage_input_max(&t->slot[1u - t->active]);
        if (b < a)
            a = b;
    }
    return a;
}

double sms_tunable_input_limit(const sms_tunable *t)
{
    double a = sms_stage_input_limit(&t->slot[t->active]);
    if (t->switching) {
        const double b = sms_stage_input_limit(&t->slot[1u - t->active]);
        if (b < a)
            a = b;
    }
    return a;
}

double sms_tunable_gain_bound(const sms_tunable *t)
{
    const double g = sms_stage_gain_bound(&t->slot[t->active]);
    if (!t->switching)
        return g;
    return 1.0 + 2.0 * g + 2.0 * sms_stage_gain_bound(&t->slot[1u - t->active]);
}
