/* SPDX-License-Identifier: Apache-2.0 */
/* B-spline filters (Biagiotti & Melchiorri 2011b): p rectangular stages per axis, control
 * points from via-points by a banded solve (no pivoting: the collocation matrix of a B-spline
 * basis is totally positive, for which elimination without pivoting is stable). */
#include <math.h>
#include "smoothshaper/trajectory.h"
#include "core/state_identity.h"

/* The identity fields after the common head, in this order (trajectory.h). */
enum { ID_DEGREE = SMS_STATE_IDENTITY_HEAD, ID_AXES, ID_T };

static sms_status knot_samples(unsigned degree, size_t n_axes, double T, double Ts, size_t *N)
{
    double nu;
    if (degree < 1u || degree > SMS_BSPLINE_MAX_DEGREE || n_axes < 1u || n_axes > SMS_BSPLINE_MAX_AXES)
        return SMS_ERR_ORDER;
    if (!isfinite(Ts) || !(Ts > 0.0))
        return SMS_ERR_SAMPLE_PERIOD;
    if (!(Ts <= SMS_TS_MAX))
        return SMS_ERR_SAMPLE_PERIOD_RANGE;
    if (!isfinite(T) || !(T > 0.0))
        return SMS_ERR_DURATION;
    /* The rule of every duration: T below Ts is refused; T within the grid tolerance (1e-9
     * relative) of Ts is one sample. */
    if (T / Ts < 1.0 - 1e-9)
        return SMS_ERR_DURATION_BELOW_TS;
    nu = floor(T / Ts + 0.5);
    if (nu > 1e12)
        return SMS_ERR_TOO_LONG;
    *N = (size_t)nu;
    return SMS_OK;
}

static sms_stage_config stage_config(size_t N, double Ts)
{
    sms_stage_config c = sms_stage_config_default(SMS_RECTANGULAR);
    c.T = (double)N * Ts;
    return c;
}

sms_status sms_bspline_buffer_size(unsigned degree, size_t n_axes, double T, double Ts,
                                   size_t *n_reals)
{
    size_t N, one, count;
    sms_stage_config c;
    sms_status st;
    if (n_reals == NULL)
        return SMS_ERR_NULL;
    st = knot_samples(degree, n_axes, T, Ts, &N);
    if (st != SMS_OK)
        return st;
    c = stage_config(N, Ts);
    st = sms_smoother_buffer_size(&c, Ts, &one);
    if (st != SMS_OK)
        return st;
    count = n_axes * degree;
    if (one > ((size_t)-1) / count)
        return SMS_ERR_TOO_LONG;
    *n_reals = one * count;
    return SMS_OK;
}

static void axis_step(sms_bspline *b, size_t axis, sms_real *x)
{
    size_t i;
    for (i = 0; i < b->degree; ++i)
        sms_smoother_step(&b->stages[axis * b->degree + i], x);
}

sms_status sms_bspline_init(sms_bspline *b, unsigned degree, size_t n_axes, double T, double Ts,
                            sms_real *buffer, size_t n_reals)
{
    sms_bspline built;
    size_t N = 0, need, one = 0, i, k, last;
    sms_stage_config c;
    sms_status st;
    if (b == NULL)
        return SMS_ERR_NULL;
    st = sms_bspline_buffer_size(degree, n_axes, T, Ts, &need);
    if (st != SMS_OK)
        return st;
    if (buffer == NULL)
        return SMS_ERR_NULL;
    if (n_reals < need)
        return SMS_ERR_BUFFER_TOO_SMALL;
    (void)knot_samples(degree, n_axes, T, Ts, &N);
    c = stage_config(N, Ts);
    (void)sms_smoother_buffer_size(&c, Ts, &one);
    built.degree = degree;
    built.n_axes = n_axes;
    built.N = N;
    built.Ts = Ts;
    for (i = 0; i < n_axes * degree; ++i) {
        st = sms_smoother_init(&built.stages[i], &c, Ts, buffer + i * one, one);
        if (st != SMS_OK)
            return st;
    }
    /* d[k]: one control point held N samples through the chain, support 0 .. (p+1)(N-1) */
    last = (size_t)(degree + 1u) * (N - 1u);
    built.k0 = last / 2u;
    built.m_first = -(long)(built.k0 / N);
    built.n_coeff = (size_t)((long)((last - built.k0) / N) - built.m_first + 1);
    for (i = 0; i < SMS_BSPLINE_MAX_DEGREE + 2; ++i)
        built.coeff[i] = 0.0;
    for (k = 0; k <= last; ++k) {
        sms_real x = k < N ? (sms_real)1 : (sms_real)0;
        long m;
        axis_step(&built, 0, &x);
        if (k >= built.k0 % N && (k - built.k0 % N) % N == 0) {
            m = (long)((k - built.k0 % N) / N) + built.m_first;
            if (m - built.m_first < (long)built.n_coeff)
                built.coeff[m - built.m_first] = (double)x;
        }
    }
    for (i = 0; i < n_axes * degree; ++i)
        sms_smoother_reset(&built.stages[i], 0);
    sms_state_identity_head(built.identity, SMS_STATE_KIND_BSPLINE, Ts);
    built.identity[ID_DEGREE] = (double)degree;
    built.identity[ID_AXES] = (double)n_axes;
    built.identity[ID_T] = (double)N * Ts;
    *b = built;
    return SMS_OK;
}

void sms_bspline_reset(sms_bspline *b, const sms_real *rest)
{
    size_t a, i;
    for (a = 0; a < b->n_axes; ++a)
        for (i = 0; i < b->degree; ++i)
            sms_smoother_reset(&b->stages[a * b->degree + i], rest[a]);
}

void sms_bspline_step(sms_bspline *b, const sms_real *in, sms_real *out)
{
    size_t a;
    for (a = 0; a < b->n_axes; ++a) {
        sms_real x = in[a];
        axis_step(b, a, &x);
        out[a] = x;
    }
}

static size_t band_width(const sms_bspline *b)
{
    return b->n_coeff;
}

size_t sms_bspline_work_size(const sms_bspline *b, size_t n_via)
{
    return n_via > 2u ? (n_via - 2u) * band_width(b) : 0u;
}

size_t sms_bspline_pass_sample(const sms_bspline *b, size_t i)
{
    return (i >= 1u ? i - 1u : 0u) * b->N + b->k0;
}

sms_status sms_bspline_control_points(const sms_bspline *b, const double *via, size_t n_via,
                                      double *control, double *work, size_t n_work)
{
    const size_t A = b != NULL ? b->n_axes : 0u;
    size_t n, W, ml, mu, r, c, a, i;
    if (b == NULL || via == NULL || control == NULL)
        return SMS_ERR_NULL;
    if (n_via < 2u)
        return SMS_ERR_ORDER;
    for (i = 0; i < n_via * A; ++i)
        if (!isfinite(via[i]))
            return SMS_ERR_LIMIT;
    if (n_work < sms_bspline_work_size(b, n_via))
        return SMS_ERR_BUFFER_TOO_SMALL;
    if (n_via > 2u && work == NULL)
        return SMS_ERR_NULL;
    n = n_via - 2u;                     /* unknowns C_1 .. C_{M-2}, row r is C_{r+1} */
    W = band_width(b);
    mu = (size_t)(-b->m_first);         /* columns right of the diagonal: m < 0 */
    ml = W - 1u - mu;                   /* columns left of it: m > 0 */
    /* band[r][col - r + ml] = c_{r - col} = coeff[(r - col) - m_first] */
    for (r = 0; r < n; ++r)
        for (c = 0; c < W; ++c) {
            long col = (long)r + (long)c - (long)ml;
            long m = (long)r - col;
            work[r * W + c] = (col >= 0 && col < (long)n) ? b->coeff[m - b->m_first] : 0.0;
        }
    /* LU in place, no pivoting */
    for (r = 0; r < n; ++r) {
        double piv = work[r * W + ml];
        size_t below;
        for (below = 1; below <= ml && r + below < n; ++below) {
            size_t q = r + below, j;
            double f = work[q * W + (ml - below)] / piv;
            work[q * W + (ml - below)] = f;
            for (j = 1; j <= mu && r + j < n; ++j)
                work[q * W + (ml - below + j)] -= f * work[r * W + ml + j];
        }
    }
    for (a = 0; a < A; ++a) {
        const double first = via[a], lastv = via[(n_via - 1u) * A + a];
        control[a] = first;
        control[(n_via - 1u) * A + a] = lastv;
        /* right-hand sides: Q_i minus the known control points (C_j = Q_0 for j <= 0,
         * Q_{M-1} for j >= M-1) */
        for (r = 0; r < n; ++r) {
            long iq = (long)r + 1, m;
            double rhs = via[(size_t)iq * A + a];
            for (m = b->m_first; m < b->m_first + (long)b->n_coeff; ++m) {
                long j = iq - m;
                if (j <= 0)
                    rhs -= b->coeff[m - b->m_first] * first;
                else if (j >= (long)n_via - 1)
                    rhs -= b->coeff[m - b->m_first] * lastv;
            }
            control[(r + 1u) * A + a] = rhs;
        }
        /* forward: L y = rhs (unit diagonal) */
        for (r = 0; r < n; ++r) {
            double y = control[(r + 1u) * A + a];
            size_t t;
            for (t = 1; t <= ml && t <= r; ++t)
                y -= work[r * W + (ml - t)] * control[(r - t + 1u) * A + a];
            control[(r + 1u) * A + a] = y;
        }
        /* backward: U x = y */
        for (r = n; r-- > 0;) {
            double x = control[(r + 1u) * A + a];
            size_t t;
            for (t = 1; t <= mu && r + t < n; ++t)
                x -= work[r * W + ml + t] * control[(r + t + 1u) * A + a];
            control[(r + 1u) * A + a] = x / work[r * W + ml];
        }
    }
    return SMS_OK;
}

sms_status sms_bspline_period_for_modes(const double *wn, size_t n, double Ts, double *T)
{
    double wmin = HUGE_VAL, N;
    size_t i;
    if (wn == NULL || T == NULL)
        return SMS_ERR_NULL;
    if (n == 0)
        return SMS_ERR_ORDER;
    if (!isfinite(Ts) || !(Ts > 0.0))
        return SMS_ERR_SAMPLE_PERIOD;
    for (i = 0; i < n; ++i) {
        if (!isfinite(wn[i]) || !(wn[i] > 0.0))
            return SMS_ERR_WN;
        if (wn[i] < wmin)
            wmin = wn[i];
    }
    N = ceil(2.0 * 3.14159265358979323846 / (wmin * Ts) * (1.0 - 1e-12));
    if (N < 1.0)
        N = 1.0;
    /* a period beyond double (a mode far below 1/Ts, or Ts itself near DBL_MAX) is refused,
     * never returned as inf */
    if (!isfinite(N * Ts))
        return SMS_ERR_TOO_LONG;
    *T = N * Ts;
    return SMS_OK;
}

size_t sms_bspline_state_count(const sms_bspline *b)
{
    size_t i, total = SMS_BSPLINE_IDENTITY_COUNT;
    for (i = 0; i < b->n_axes * b->degree; ++i)
        total += sms_smoother_state_count(&b->stages[i]);
    return total;
}

void sms_bspline_get_state(const sms_bspline *b, double *dst)
{
    size_t i;
    for (i = 0; i < SMS_BSPLINE_IDENTITY_COUNT; ++i)
        dst[i] = b->identity[i];
    dst += SMS_BSPLINE_IDENTITY_COUNT;
    for (i = 0; i < b->n_axes * b->degree; ++i) {
        sms_smoother_get_state(&b->stages[i], dst);
        dst += sms_smoother_state_count(&b->stages[i]);
    }
}

sms_status sms_bspline_check_state(const sms_bspline *b, const double *src, size_t n)
{
    static const sms_status field_status[SMS_BSPLINE_IDENTITY_COUNT - SMS_STATE_IDENTITY_HEAD] = {
        SMS_ERR_STATE_DEGREE, SMS_ERR_STATE_AXES, SMS_ERR_STATE_T
    };
    size_t i, off = SMS_BSPLINE_IDENTITY_COUNT;
    sms_status st;
    if (b == NULL || src == NULL)
        return SMS_ERR_NULL;
    /* another configuration first, whatever the length: its state often has another one */
    if (n >= SMS_BSPLINE_IDENTITY_COUNT
        && (st = sms_state_identity_compare(b->identity, src,
                                            SMS_BSPLINE_IDENTITY_COUNT - SMS_STATE_IDENTITY_HEAD,
                                            field_status)) != SMS_OK)
        return st;
    if (n != sms_bspline_state_count(b))
        return SMS_ERR_STATE;
    for (i = 0; i < b->n_axes * b->degree; ++i) {
        size_t cnt = sms_smoother_state_count(&b->stages[i]);
        if (sms_smoother_check_state(&b->stages[i], src + off, cnt) != SMS_OK)
            return SMS_ERR_STATE;
        off += cnt;
    }
    return SMS_OK;
}

sms_status sms_bspline_set_state(sms_bspline *b, const double *src, size_t n)
{
    size_t i, off = SMS_BSPLINE_IDENTITY_COUNT;
    sms_status st = sms_bspline_check_state(b, src, n);
    if (st != SMS_OK)
        return st;
    for (i = 0; i < b->n_axes * b->degree; ++i) {
        size_t cnt = sms_smoother_state_count(&b->stages[i]);
        (void)sms_smoother_set_state(&b->stages[i], src + off, cnt);
        off += cnt;
    }
    return SMS_OK;
}
