/* Online multi-point generator (docs/design.md). The bound argument is in trajectory.h; here:
 * init designs the tail and tabulates its responses (libm allowed), step is O(1) without libm. */
#include <math.h>
#include "smoothshaper/trajectory.h"
#include "trajectory_internal.h"
#include "plan.h"

#define GEN_STATE_COUNT 9u
#define GEN_PLAN_STATE_COUNT 6u

/* phi_k(x) = (e^x - sum_{i<k} x^i/i!) / x^k, accurate for small |x| (series) and large. */
static double phi(int k, double x)
{
    if (fabs(x) < 0.5) {
        double term = 1.0, sum = 0.0, fact = 1.0;
        int i;
        for (i = 1; i <= k; ++i)
            fact *= i;
        term = 1.0 / fact;
        for (i = k + 1; i < k + 30; ++i) {
            sum += term;
            term *= x / i;
        }
        return sum;
    } else {
        double e = expm1(x);
        if (k == 1)
            return e / x;
        e -= x;
        if (k == 2)
            return e / (x * x);
        e -= 0.5 * x * x;
        return e / (x * x * x);
    }
}

/* The last tail stage L on [0, T3]: density l and its iterated integrals P1, P2, P3. */
typedef struct last_stage {
    sms_kind kind;
    double T, sigma, A; /* A: exponential normalisation 1 / (T phi_1(sigma T)) */
    double m1, m2;      /* first two moments, for the continuation beyond T */
} last_stage;

/* l(s) by its formula, for s in [0, T] (the caller decides the support, see l_at_sample). */
static double l_formula(const last_stage *L, double s)
{
    switch (L->kind) {
    case SMS_HARMONIC:
        return 1.5707963267948966 / L->T * sin(3.14159265358979323846 * s / L->T);
    case SMS_EXPONENTIAL:
        return L->A * exp(L->sigma * s);
    default:
        return 1.0 / L->T;
    }
}

/* Where a breakpoint b [s] falls on the sample axis: the integer round(b/Ts) when b/Ts passes
 * the integer test of docs/exact-mode.md, else b/Ts itself. Comparing a sample index with it
 * decides the side of a jump exactly: m Ts - b would round either way when b is on the grid. */
static double breakpoint_samples(double b, double Ts)
{
    double nu = b / Ts, n = floor(nu + 0.5);
    return fabs(nu - n) <= 1e-9 * (nu > 1.0 ? nu : 1.0) ? n : nu;
}

/* l(m Ts - delay) with the right limit at its jumps (trajectory.h): the stage is on for
 * on <= m < off, on and off its start and end in samples (breakpoint_samples). */
static double l_at_sample(const last_stage *L, size_t m, double Ts, double delay, double on,
                          double off)
{
    double s = (double)m * Ts - delay;
    if ((double)m < on || (double)m >= off)
        return 0.0;
    s = s < 0.0 ? 0.0 : (s > L->T ? L->T : s); /* a snapped breakpoint may leave s an ulp out */
    return l_formula(L, s);
}

/* P_k(s) = int_0^s l(tau) (s - tau)^(k-1)/(k-1)! dtau on [0, T]. */
static double P_inside(const last_stage *L, int k, double s)
{
    double T = L->T;
    switch (L->kind) {
    case SMS_HARMONIC: {
        double w = 3.14159265358979323846 / T, c = cos(w * s), sn = sin(w * s);
        if (k == 1)
            return 0.5 * (1.0 - c);
        if (k == 2)
            return 0.5 * (s - sn / w);
        return 0.5 * (0.5 * s * s - (1.0 - c) / (w * w));
    }
    case SMS_EXPONENTIAL: {
        double x = L->sigma * s, p = s;
        if (k >= 2)
            p *= s;
        if (k >= 3)
            p *= s;
        return L->A * p * phi(k, x);
    }
    default:
        if (k == 1)
            return s / T;
        if (k == 2)
            return s * s / (2.0 * T);
        return s * s * s / (6.0 * T);
    }
}

static double P(const last_stage *L, int k, double s)
{
    if (s <= 0.0)
        return 0.0;
    if (s <= L->T)
        return P_inside(L, k, s);
    if (k == 1)
        return 1.0;
    if (k == 2)
        return s - L->m1;
    return 0.5 * (s * s - 2.0 * L->m1 * s + L->m2);
}

static sms_status design_tail(const sms_generator_config *c, double Ts, double *T2,
                              sms_kin_last *last_out, double *T3, size_t *Nc)
{
    double L2[2], T[2], nu, Tc;
    sms_status st;
    if (c == NULL)
        return SMS_ERR_NULL;
    if (!isfinite(Ts) || !(Ts > 0.0))
        return SMS_ERR_SAMPLE_PERIOD;
    if (!isfinite(c->vmax) || !(c->vmax > 0.0))
        return SMS_ERR_LIMIT;
    if (c->wn > 0.0 && isfinite(c->wn) && c->wn * Ts >= 3.14159265358979323846)
        return SMS_ERR_ABOVE_NYQUIST;
    L2[0] = c->amax;
    L2[1] = c->jmax;
    /* the tail is the velocity rise: displacement vmax under the bounds {amax, jmax} */
    st = sms_kin_solve(c->vmax, L2, 2, c->profile, c->wn, c->zeta, T, last_out);
    if (st != SMS_OK)
        return st;
    if (T[0] < Ts || T[1] < Ts)
        return SMS_ERR_DURATION_BELOW_TS;
    Tc = T[0] + T[1];
    nu = Tc / Ts;
    if (nu > 1e15)
        return SMS_ERR_TOO_LONG;
    {
        double n_round = floor(nu + 0.5);
        if (fabs(nu - n_round) <= 1e-9 * (nu > 1.0 ? nu : 1.0))
            *Nc = (size_t)n_round;
        else
            *Nc = (size_t)ceil(nu);
    }
    *T2 = T[0];
    *T3 = T[1];
    return SMS_OK;
}

/* The time-optimal realisation: polynomial profile, no mode. */
static int is_time_optimal(const sms_generator_config *c)
{
    return c->profile == SMS_PROFILE_POLYNOMIAL && c->wn == 0.0;
}

/* Validation of the time-optimal realisation (no tail to design). */
static sms_status check_time_optimal(const sms_generator_config *c, double Ts)
{
    if (!isfinite(Ts) || !(Ts > 0.0))
        return SMS_ERR_SAMPLE_PERIOD;
    if (!isfinite(c->vmax) || !(c->vmax > 0.0) || !isfinite(c->amax) || !(c->amax > 0.0) ||
        !isfinite(c->jmax) || !(c->jmax > 0.0))
        return SMS_ERR_LIMIT;
    if (!isfinite(c->zeta) || c->zeta < 0.0 || c->zeta >= 1.0)
        return SMS_ERR_ZETA;
    /* every limit, Ts and their products must be finite non-zero reals of the build */
    {
        sms_real v = (sms_real)c->vmax, a = (sms_real)c->amax, j = (sms_real)c->jmax,
                 t = (sms_real)Ts;
        if (!(v > 0) || !(a > 0) || !(j > 0) || !(t > 0) || v - v != 0 || a - a != 0 ||
            j - j != 0)
            return SMS_ERR_LIMIT;
        /* the plan forms products like a^2/j and v j: keep them finite */
        if (!((a * a) / j - (a * a) / j == 0) || !(v * j - v * j == 0) || !(a * a > 0))
            return SMS_ERR_LIMIT;
    }
    return SMS_OK;
}

sms_status sms_generator_buffer_size(const sms_generator_config *config, double Ts, size_t *n_reals)
{
    double T2, T3;
    sms_kin_last last;
    size_t Nc;
    sms_status st;
    if (n_reals == NULL || config == NULL)
        return SMS_ERR_NULL;
    if (is_time_optimal(config)) {
        st = check_time_optimal(config, Ts);
        if (st == SMS_OK)
            *n_reals = 0;
        return st;
    }
    st = design_tail(config, Ts, &T2, &last, &T3, &Nc);
    if (st != SMS_OK)
        return st;
    if (Nc > ((size_t)-1) / 4u - 1u)
        return SMS_ERR_TOO_LONG;
    *n_reals = 4u * (Nc + 1u);
    return SMS_OK;
}

sms_status sms_generator_init(sms_generator *g, const sms_generator_config *config, double Ts,
                              sms_real *buffer, size_t n_reals)
{
    double T2, T3, mu, on2, off1, off2;
    sms_kin_last kl;
    last_stage L;
    size_t Nc, m, need;
    sms_real *E, *F, *X2, *X2d;
    sms_status st;
    if (g == NULL || config == NULL)
        return SMS_ERR_NULL;
    if (is_time_optimal(config)) {
        st = check_time_optimal(config, Ts);
        if (st != SMS_OK)
            return st;
        g->Ts = Ts;
        g->vmax = config->vmax;
        g->T2 = g->T3 = 0.0;
        g->last_kind = SMS_RECTANGULAR;
        g->sigma = 0.0;
        g->n_tail = 0;
        g->mean_delay = 0.0;
        g->Ts_signal = (sms_real)Ts;
        g->mean_delay_signal = 0;
        g->step_distance = (sms_real)(config->vmax * Ts);
        g->table = buffer;
        g->time_optimal = 1;
        g->limits.vmax = (sms_real)config->vmax;
        g->limits.amax = (sms_real)config->amax;
        g->limits.jmax = (sms_real)config->jmax;
        sms_generator_reset(g, 0);
        return SMS_OK;
    }
    st = design_tail(config, Ts, &T2, &kl, &T3, &Nc);
    if (st != SMS_OK)
        return st;
    if (Nc > ((size_t)-1) / 4u - 1u)
        return SMS_ERR_TOO_LONG;
    need = 4u * (Nc + 1u);
    if (buffer == NULL)
        return SMS_ERR_NULL;
    if (n_reals < need)
        return SMS_ERR_BUFFER_TOO_SMALL;

    L.kind = kl.kind;
    L.T = T3;
    L.sigma = kl.sigma;
    L.A = kl.kind == SMS_EXPONENTIAL ? 1.0 / (T3 * phi(1, kl.sigma * T3)) : 0.0;
    L.m1 = 0.0;
    L.m2 = 0.0;
    /* moments from continuity at T: P2(T) = T - m1, P3(T) = (T^2 - 2 m1 T + m2)/2 */
    L.m1 = T3 - P_inside(&L, 2, T3);
    L.m2 = 2.0 * P_inside(&L, 3, T3) - T3 * T3 + 2.0 * L.m1 * T3;
    mu = 0.5 * T2 + L.m1;

    E = buffer;
    F = buffer + (Nc + 1u);
    X2 = buffer + 2u * (Nc + 1u);
    X2d = buffer + 3u * (Nc + 1u);
    /* the jerk response l(s) - l(s - T2) jumps where the two copies of l start and end */
    off1 = breakpoint_samples(T3, Ts);
    on2 = breakpoint_samples(T2, Ts);
    off2 = breakpoint_samples(T2 + T3, Ts);
    for (m = 0; m < Nc; ++m) {
        double s = (double)m * Ts;
        /* X = M(T2) * L: responses are differences of L's integrals over the window T2 */
        double x2 = (P(&L, 1, s) - P(&L, 1, s - T2)) / T2;
        double Fs = (P(&L, 2, s) - P(&L, 2, s - T2)) / T2;
        double Gs = (P(&L, 3, s) - P(&L, 3, s - T2)) / T2;
        double x2d = (l_at_sample(&L, m, Ts, 0.0, 0.0, off1) -
                      l_at_sample(&L, m, Ts, T2, on2, off2)) / T2;
        E[m] = (sms_real)(Gs - s + mu);
        F[m] = (sms_real)Fs;
        X2[m] = (sms_real)x2;
        X2d[m] = (sms_real)x2d;
    }
    /* settled: the change has passed through the whole tail */
    E[Nc] = 0;
    F[Nc] = 1;
    X2[Nc] = 0;
    X2d[Nc] = 0;

    g->Ts = Ts;
    g->vmax = config->vmax;
    g->T2 = T2;
    g->T3 = T3;
    g->last_kind = kl.kind;
    g->sigma = kl.sigma;
    g->n_tail = Nc;
    g->mean_delay = mu;
    g->Ts_signal = (sms_real)Ts;
    g->mean_delay_signal = (sms_real)mu;
    g->step_distance = (sms_real)(config->vmax * Ts);
    g->table = buffer;
    g->time_optimal = 0;
    g->limits.vmax = (sms_real)config->vmax;
    g->limits.amax = (sms_real)config->amax;
    g->limits.jmax = (sms_real)config->jmax;
    sms_generator_reset(g, 0);
    return SMS_OK;
}

void sms_generator_reset(sms_generator *g, sms_real position)
{
    if (position - position != 0)
        return; /* NaN/Inf: stay where it is */
    g->plan_q = position;
    g->plan_v = 0;
    g->plan_a = 0;
    g->k = 0;
    g->plan.count = 0;
    g->plan.goal = position;
    g->plan.end = 0;
    g->plan.end_f = 0;
    g->plan.duration = 0;
    g->target = position;
    g->start = position;
    g->goal = position;
    g->r = position;
    g->velocity = 0;
    g->change = 0;
    g->seg_len = 0;
    g->seg_pos = 0;
    g->age = g->n_tail;
}

/* Largest segment in samples; keeps counts exact in sms_real and far from overflow. */
#define GEN_MAX_SEGMENT 4194304.0 /* 2^22 */

/* Start a new constant-velocity segment from r towards the target (only when allowed). */
static void replan(sms_generator *g)
{
    sms_real d = g->target - g->r;
    sms_real V = g->velocity;
    sms_real samples, m; /* signal precision: no double arithmetic in a float build */
    sms_real Vn;
    if (V != 0 && (d == 0 || (d > 0) != (V > 0))) {
        /* past or at the target while moving: stop first (a change of |V| <= vmax) */
        g->change = -V;
        g->velocity = 0;
        g->seg_len = 0;
        g->seg_pos = 0;
        g->start = g->goal = g->r;
        g->age = 0;
        return;
    }
    samples = (d < 0 ? -d : d) / g->step_distance;
    if (samples > (sms_real)GEN_MAX_SEGMENT) {
        /* absurdly far: go part of the way at vmax; the next re-plan continues */
        samples = (sms_real)GEN_MAX_SEGMENT;
        d = d > 0 ? samples * g->step_distance : -samples * g->step_distance;
    }
    m = (sms_real)(size_t)samples;
    if (m < samples)
        m += 1;
    if (m < (sms_real)g->n_tail)
        m = (sms_real)g->n_tail; /* T1 >= Tc: the stop is >= Nc samples after the start */
    Vn = d / (m * g->Ts_signal);
    g->start = g->r;
    g->goal = g->r + d;
    g->seg_len = (size_t)m;
    g->seg_pos = 0;
    if (Vn != V) {
        g->change = Vn - V; /* same sign, both within vmax: |change| <= vmax */
        g->velocity = Vn;
        g->age = 0;
    }
}

/* Time-optimal step: advance one sample on the plan; re-plan from the exact state there when
 * the target differs from the plan's goal. */
static void step_time_optimal(sms_generator *g, sms_real target, sms_real out[4])
{
    if (target - target == 0) /* finite (NaN and Inf give NaN) */
        g->target = target;
    ++g->k;
    sms_plan_eval(&g->plan, g->Ts_signal, g->k, out);
    if (g->target != g->plan.goal) {
        g->plan_q = out[0];
        g->plan_v = out[1];
        g->plan_a = out[2];
        g->k = 0;
        sms_plan_to_rest(&g->plan, &g->limits, g->Ts_signal, out[0], out[1], out[2], g->target);
        sms_plan_eval(&g->plan, g->Ts_signal, 0, out); /* the same q, v, a; the new jerk */
    }
}

void sms_generator_step(sms_generator *g, sms_real target, sms_real out[4])
{
    const size_t Nc = g->n_tail;
    const sms_real *E = g->table, *F = E + (Nc + 1u), *X2 = E + 2u * (Nc + 1u),
                   *X2d = E + 3u * (Nc + 1u);
    sms_real dv;
    size_t s;
    if (g->time_optimal) {
        step_time_optimal(g, target, out);
        return;
    }
    if (target - target == 0) /* finite (NaN and Inf give NaN) */
        g->target = target;
    if (g->age < Nc)
        ++g->age;
    /* 1. advance the first stage to this instant */
    if (g->seg_len > 0) {
        ++g->seg_pos;
        if (g->seg_pos >= g->seg_len) {
            g->r = g->goal; /* exact end of the segment */
            g->seg_len = 0;
            g->seg_pos = 0;
            g->start = g->goal;
            if (g->age >= Nc && g->target != g->r) {
                replan(g); /* continue (same direction) or stop (reversal) right here */
            } else {
                g->change = -g->velocity;
                g->velocity = 0;
                g->age = 0;
            }
        } else {
            g->r = g->start + g->velocity * ((sms_real)g->seg_pos * g->Ts_signal);
        }
    }
    /* 2. re-plan if the target moved and the last change has left the tail */
    if (g->age >= Nc && g->target != (g->seg_len > 0 ? g->goal : g->r))
        replan(g);
    /* 3. output: only the last change is still inside the tail (header argument) */
    s = g->age;
    dv = g->change;
    out[0] = g->r - g->mean_delay_signal * g->velocity + dv * E[s];
    out[1] = g->velocity - dv * (1 - F[s]);
    out[2] = dv * X2[s];
    out[3] = dv * X2d[s];
}

void sms_generator_process(sms_generator *g, const sms_real *targets, size_t n, sms_real *out)
{
    size_t i;
    for (i = 0; i < n; ++i)
        sms_generator_step(g, targets[i], out + 4u * i);
}

double sms_generator_tail_duration(const sms_generator *g)
{
    return g->T2 + g->T3;
}

size_t sms_generator_state_count(const sms_generator *g)
{
    return g->time_optimal ? GEN_PLAN_STATE_COUNT : GEN_STATE_COUNT;
}

void sms_generator_get_state(const sms_generator *g, double *dst)
{
    if (g->time_optimal) {
        dst[0] = (double)g->target;
        dst[1] = (double)g->plan.goal;
        dst[2] = (double)g->plan_q;
        dst[3] = (double)g->plan_v;
        dst[4] = (double)g->plan_a;
        dst[5] = (double)g->k;
        return;
    }
    dst[0] = (double)g->target;
    dst[1] = (double)g->start;
    dst[2] = (double)g->goal;
    dst[3] = (double)g->r;
    dst[4] = (double)g->velocity;
    dst[5] = (double)g->change;
    dst[6] = (double)g->seg_len;
    dst[7] = (double)g->seg_pos;
    dst[8] = (double)g->age;
}

static int is_count(double x, double max)
{
    return x >= 0.0 && x <= max && x == (double)(size_t)x;
}

sms_status sms_generator_check_state(const sms_generator *g, const double *src, size_t n)
{
    size_t i;
    if (g == NULL || src == NULL)
        return SMS_ERR_NULL;
    if (g->time_optimal) {
        double V = (double)g->limits.vmax, A = (double)g->limits.amax,
               J = (double)g->limits.jmax, brake;
        if (n != GEN_PLAN_STATE_COUNT)
            return SMS_ERR_STATE;
        for (i = 0; i < 5; ++i)
            if (!isfinite(src[i]) || (sms_real)src[i] - (sms_real)src[i] != 0)
                return SMS_ERR_STATE;
        /* a state a plan can start from: within the bounds, and able to stop its
         * acceleration without passing vmax */
        brake = src[3] + src[4] * fabs(src[4]) / (2.0 * J);
        if (fabs(src[3]) > V * (1.0 + 1e-6) || fabs(src[4]) > A * (1.0 + 1e-6) ||
            fabs(brake) > V * (1.0 + 1e-6))
            return SMS_ERR_STATE;
        if (!is_count(src[5], 9007199254740992.0)) /* 2^53 */
            return SMS_ERR_STATE;
        return SMS_OK;
    }
    if (n != GEN_STATE_COUNT)
        return SMS_ERR_STATE;
    for (i = 0; i < 6; ++i)
        if (!isfinite(src[i]))
            return SMS_ERR_STATE;
    if (fabs(src[4]) > g->vmax * (1.0 + 1e-6) || fabs(src[5]) > g->vmax * (1.0 + 1e-6))
        return SMS_ERR_STATE;
    if (!is_count(src[6], GEN_MAX_SEGMENT) || !is_count(src[7], src[6]) ||
        !is_count(src[8], (double)g->n_tail))
        return SMS_ERR_STATE;
    if (src[6] > 0.0 && src[7] >= src[6])
        return SMS_ERR_STATE;
    return SMS_OK;
}

sms_status sms_generator_set_state(sms_generator *g, const double *src, size_t n)
{
    sms_status st = sms_generator_check_state(g, src, n);
    if (st != SMS_OK)
        return st;
    if (g->time_optimal) {
        g->target = (sms_real)src[0];
        g->plan_q = (sms_real)src[2];
        g->plan_v = (sms_real)src[3];
        g->plan_a = (sms_real)src[4];
        g->k = (size_t)src[5];
        sms_plan_to_rest(&g->plan, &g->limits, g->Ts_signal, g->plan_q, g->plan_v, g->plan_a,
                         (sms_real)src[1]);
        return SMS_OK;
    }
    g->target = (sms_real)src[0];
    g->start = (sms_real)src[1];
    g->goal = (sms_real)src[2];
    g->r = (sms_real)src[3];
    g->velocity = (sms_real)src[4];
    g->change = (sms_real)src[5];
    g->seg_len = (size_t)src[6];
    g->seg_pos = (size_t)src[7];
    g->age = (size_t)src[8];
    return SMS_OK;
}

void sms_generator_rebind(sms_generator *g, sms_real *buffer)
{
    g->table = buffer;
}
