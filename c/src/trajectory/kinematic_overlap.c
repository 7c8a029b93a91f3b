/* SPDX-License-Identifier: Apache-2.0 */
/* Kinematic design on a sample grid: the exact test and search for chains of whole-sample
 * stages whose shifted copies overlap where they cancel (docs/sampled-limits.md), which the
 * rounding in kinematic_grid.c calls when its chain is more than a sample per stage over the
 * continuous optimum. Design-time code: libm is allowed here. */
#include "trajectory/kinematic_parts.h"

/*
 * The sampled differences of a chain of whole-sample moving averages, exactly. In samples, a
 * step of h through boxes of N_0 .. N_{n-1} samples has the i-th backward difference
 *   h / (N_0 ... N_{n-1}) * p(z) / (1 - z^-1)^(n-i+1),   p(z) = prod_j (1 - z^-N_j),
 * which depends on the multiset of lengths only. Split p = p_A p_B with A the i largest
 * lengths: p_A / (1 - z^-1) is a running count c_A (the signed number of subsets of A whose
 * sum is at most m) and p_B / (1 - z^-1)^(n-i) is a chain of n-i boxes, non-negative and
 * summing to prod_B N. Hence
 *   |i-th difference| <= h * max|c_A| / prod_A N,
 * equal to the non-overlap value h / (N_0 ... N_{i-1}) when max|c_A| = 1. Copies that overlap
 * with opposite signs cancel in c_A, so chains shorter than the "each stage at least the
 * stages after it" rule pass this test (at the top difference, i = n, it is exact).
 */

/* Budget of level tests of the search below per pair of first two lengths (at most 7 * 7 of
 * them; each test O(2^i), i <= n <= 8): 4 * 2^n, 1024 for eight bounds. One budget per first
 * length let a second length that cannot work use it all up (eight bounds cost up to 20
 * samples, seven with a half sine 29). */
#define KIN_OVERLAP_NODES(n) (4u << (n))

typedef struct {
    const sms_kin_plan *p;
    double logh, logTs, c[SMS_KINEMATIC_MAX_ORDER], rest_min[SMS_KINEMATIC_MAX_ORDER + 1];
    double N[SMS_KINEMATIC_MAX_ORDER], best[SMS_KINEMATIC_MAX_ORDER], best_sum;
    /* subset sums of the k largest lengths, sorted, with their signs: list k at 2^k - 1 */
    double sums[2u << SMS_KINEMATIC_MAX_ORDER];
    signed char signs[2u << SMS_KINEMATIC_MAX_ORDER];
    unsigned nodes;
    int found, harmonic; /* harmonic: the last stage is a half sine (harmonic_fits) */
    const sms_kin_tuned *tuned; /* a fixed bounded last stage (tuned_fits), or NULL */
} kin_overlap;

/* Adds length x to list k (the subset sums of N[0..k-1]) giving list k+1, and returns the
 * largest |running count| over it (taken at the end of each run of equal sums). */
static double overlap_count_peak(kin_overlap *s, size_t k, double x)
{
    size_t len = (size_t)1 << k, a = 0, b = 0, o = 0;
    const double *in = s->sums + (len - 1u);
    const signed char *sg = s->signs + (len - 1u);
    double *out = s->sums + (2u * len - 1u);
    signed char *osg = s->signs + (2u * len - 1u);
    long run = 0, peak = 0;
    while (a < len || b < len) {
        if (b >= len || (a < len && in[a] <= in[b] + x)) {
            out[o] = in[a];
            osg[o++] = sg[a++];
        } else {
            out[o] = in[b] + x;
            osg[o++] = (signed char)-sg[b++];
        }
    }
    for (o = 0; o < 2u * len; ++o) {
        run += osg[o];
        if (o + 1u == 2u * len || out[o + 1u] != out[o]) {
            long r = run < 0 ? -run : run;
            if (r > peak)
                peak = r;
        }
    }
    return (double)peak;
}

/*
 * A half-sine last stage of N samples (taps tan(pi/2N) sin(pi j/N), j = 0..N-1) after boxes
 * whose signed subset sums sigma_S are list n-1: the top difference exactly. In samples it is
 *   h / prod(boxes) * tan(pi/2N) * f(m),   f(m) = sum_S sign_S sin(pi (m - sigma_S)/N),
 * each copy S taken over m in [sigma_S, sigma_S + N] (zero at both ends). Between two events
 * (a copy starting at sigma_S or ending at sigma_S + N) the live copies share one frequency:
 * with C = sum_live sign_S e^(i pi (b - sigma_S)/N) at the interval's start b,
 * f(b + t) = Im(e^(i pi t/N) C). A start adds sign_S to C (e^0); an end removes
 * sign_S e^(i pi), i.e. adds sign_S too. So one sweep over the 2^n sorted events, rotating C
 * between them, gives f; an interval is accepted on |C| <= lim when it can, else f is
 * evaluated at its ends and at the samples next to the sinusoid's extremes. lim: the allowed
 * max|f|. Returns 1 when it holds. (The level below needs no such test: there the half sine
 * is a ramp of non-negative weights summing to one, so the running count of the boxes bounds
 * it.)
 */
static int interval_fits(double cr, double ci, double dt, double N, double lim)
{
    double w = KIN_PI / N, t0, ts[6];
    size_t q;
    if (hypot(cr, ci) <= lim)
        return 1;
    /* |f| peaks where pi t/N + arg C = pi/2 (mod pi): t0 + k N */
    t0 = N * (0.5 - atan2(ci, cr) / KIN_PI);
    t0 -= N * floor(t0 / N);
    ts[0] = 0.0;
    ts[1] = dt;
    ts[2] = floor(t0);
    ts[3] = ts[2] + 1.0;
    ts[4] = ts[2] + N;
    ts[5] = ts[3] + N;
    for (q = 0; q < 6u; ++q)
        if (ts[q] >= 0.0 && ts[q] <= dt &&
            fabs(ci * cos(w * ts[q]) + cr * sin(w * ts[q])) > lim)
            return 0;
    return 1;
}

static int harmonic_fits(const kin_overlap *s, double N, double lim)
{
    size_t len = (size_t)1 << (s->p->n - 1u), a = 0, e = 0;
    const double *st = s->sums + (len - 1u);
    const signed char *sg = s->signs + (len - 1u);
    double cr = 0.0, ci = 0.0, b = st[0];
    while (a < len || e < len) {
        double pos = e >= len || (a < len && st[a] <= st[e] + N) ? st[a] : st[e] + N;
        if (pos > b) {
            double x = KIN_PI * (pos - b) / N, c = cos(x), sn = sin(x), r;
            if (!interval_fits(cr, ci, pos - b, N, lim))
                return 0;
            r = cr * c - ci * sn;
            ci = cr * sn + ci * c;
            cr = r;
            b = pos;
        }
        while (a < len && st[a] == pos)
            cr += sg[a++];
        while (e < len && st[e] + N == pos)
            cr += sg[e++];
    }
    return 1;
}

/*
 * A fixed bounded last stage (taps tap0, gain q^i for i = 1 .. L-2, tapL) after boxes whose
 * signed subset sums sigma_S are list n-1: the top difference exactly. In samples it is
 * h / prod(boxes) * F(m), F(m) = sum_S sign_S t(m - sigma_S). F changes only where a copy
 * starts (sigma_S: tap0), enters its interior (+1), leaves it (L-1: tapL) or ends (L);
 * between those the interior part is K q^t (constant for a box, decaying for q < 1), so
 * |F| peaks at one of them. One sweep over the four shifted lists of sums, carrying K.
 * Returns 1 when max |F| <= lim.
 */
static int tuned_fits(const kin_overlap *s, double lim)
{
    const sms_kin_tuned *t = s->tuned;
    const size_t len = (size_t)1 << (s->p->n - 1u);
    const double *st = s->sums + (len - 1u);
    const signed char *sg = s->signs + (len - 1u);
    const double off[4] = {0.0, 1.0, t->L - 1.0, t->L};
    const double q_in = t->gain * exp(t->decay), q_out = t->gain * exp(t->decay * (t->L - 1.0));
    size_t at[4] = {0u, 0u, 0u, 0u}, e;
    double K = 0.0, b = st[0];
    for (;;) {
        double pos = HUGE_VAL, spike = 0.0;
        for (e = 0; e < 4u; ++e)
            if (at[e] < len && st[at[e]] + off[e] < pos)
                pos = st[at[e]] + off[e];
        if (pos == HUGE_VAL)
            return 1;
        if (t->decay != 0.0)
            K *= exp(t->decay * (pos - b));
        b = pos;
        for (e = 0; e < 4u; ++e)
            while (at[e] < len && st[at[e]] + off[e] == pos) {
                const double sign = (double)sg[at[e]++];
                if (e == 0u) {          /* a copy starts: its first tap */
                    spike += sign * t->tap0;
                } else if (e == 1u) {   /* its interior begins */
                    K += sign * q_in;
                } else if (e == 2u) {   /* its interior ends, its last tap */
                    K -= sign * q_out;
                    spike += sign * t->tapL;
                }                       /* e == 3: it has ended (only evaluated) */
            }
        if (fabs(K + spike) > lim)
            return 0;
    }
}

static void overlap_dfs(kin_overlap *s, size_t k, double logprod, double psum)
{
    size_t n = s->p->n, nx = 0, j, q, boxes = s->tuned ? n - 1u : n;
    double xs[7];
    if (k == boxes) {
        if (s->tuned) {
            /* the top level through the fixed stage, exactly (tuned_fits) */
            double lt = log(s->p->L[n - 1u]) + (double)n * s->logTs + logprod - s->logh;
            if (!tuned_fits(s, lt > 60.0 ? HUGE_VAL : exp(lt) * (1.0 + 1e-12)))
                return;
        }
        if (psum < s->best_sum) {
            s->best_sum = psum;
            for (j = 0; j < n; ++j)
                s->best[j] = s->N[j];
            s->found = 1;
        }
        return;
    }
    if (k + 1u == n && s->harmonic) {
        /* a half sine: the fewest samples whose largest tap (about pi/2N) keeps the top
         * level without overlaps, from two less (overlapping copies can lower the peak) to
         * three more */
        double x0 = ceil(0.5 * KIN_PI * exp(s->logh - log(s->p->L[k]) - (double)n * s->logTs -
                                             logprod) * (1.0 - 1e-12));
        if (!(x0 >= 2.0))
            x0 = 2.0;
        for (j = 0; j < 6u; ++j)
            if (x0 - 2.0 + (double)j >= 2.0)
                xs[nx++] = x0 - 2.0 + (double)j;
    } else if (k + 1u == n || ((s->harmonic || s->tuned) && k + 2u == n)) {
        /* the last box: the fewest samples its level allows without overlaps, and a few
         * more; before a half sine or a fixed tuned stage also the ceiling -1 .. +1 */
        double x0 = ceil(exp(s->logh - log(s->p->L[k]) - (double)(k + 1u) * s->logTs -
                             logprod) * (1.0 - 1e-12));
        if (!(x0 >= 1.0))
            x0 = 1.0;
        for (j = 0; j < 4u; ++j)
            xs[nx++] = x0 + (double)j;
        for (j = 0; j < 3u && k + 1u < n; ++j) {
            double x = s->c[k] - 1.0 + (double)j;
            if (x < x0 || x > x0 + 3.0)
                xs[nx++] = x;
        }
    } else {
        /* the ceiling moved by -1 .. +2, then the structure's lift. Order: after a stage one
         * sample off its ceiling, the other way first (pairs of +1/-1 keep the sums and break
         * the collisions of tight stages); the first stage -1, +1; else one sample less
         * first where an odd number of stages follows (there the overlap with the next copy
         * cancels) */
        static const double odd[4] = {-1.0, 0.0, 1.0, 2.0}, even[4] = {0.0, -1.0, 1.0, 2.0};
        static const double first[4] = {-1.0, 1.0, 0.0, 2.0};
        static const double after_down[4] = {1.0, 0.0, -1.0, 2.0};
        static const double after_up[4] = {-1.0, 0.0, 1.0, 2.0};
        const double *off = ((n - 1u - k) % 2u) ? odd : even;
        double lift = 0.0, prev = k > 0u ? s->N[k - 1u] - s->c[k - 1u] : 0.0;
        if (prev == -1.0)
            off = after_down;
        else if (prev == 1.0)
            off = after_up;
        else if (k == 0u)
            off = first;
        for (j = 0; j < 4u; ++j)
            xs[nx++] = s->c[k] + off[j];
        for (j = k + 1u; j < n; ++j)
            lift += s->c[j];
        for (j = 0; j < 3u; ++j) {
            double x = lift - 1.0 + (double)j;
            int seen = 0;
            for (q = 0; q < nx; ++q)
                seen |= xs[q] == x;
            if (!seen)
                xs[nx++] = x;
        }
    }
    for (j = 0; j < nx; ++j) {
        double x = xs[j], peak, lp;
        int last_sine = s->harmonic && k + 1u == n;
        if (x < 1.0 || (k > 0u && x > s->N[k - 1u] && !last_sine))
            continue;
        if (psum + x + s->rest_min[k + 1u] >= s->best_sum)
            continue;
        if (k <= 1u)
            s->nodes = 0u; /* each pair of first two lengths gets its own budget */
        if (s->nodes >= KIN_OVERLAP_NODES(n))
            return;
        ++s->nodes;
        if (last_sine) {
            /* the top level exactly (harmonic_fits), against the boxes' product */
            double lt = log(s->p->L[k]) + (double)n * s->logTs + logprod - s->logh -
                        log(tan(0.5 * KIN_PI / x));
            if (!harmonic_fits(s, x, lt > 60.0 ? HUGE_VAL : exp(lt) * (1.0 + 1e-12)))
                continue;
            s->N[k] = x;
            overlap_dfs(s, k + 1u, logprod, psum + x);
            continue;
        }
        peak = overlap_count_peak(s, k, x);
        lp = logprod + log(x);
        if (s->logh + log(peak) > log(s->p->L[k]) + (double)(k + 1u) * s->logTs + lp + 1e-12)
            continue;
        s->N[k] = x;
        overlap_dfs(s, k + 1u, lp, psum + x);
    }
}

/* Chains without a tuned stage still more than a sample per stage over the continuous
 * optimum: a depth first search, largest stage first, of non-increasing whole-sample box
 * lengths that pass the exact test above level by level (each level needs only the lengths
 * chosen so far), then a half sine (harmonic) of any length whose top level harmonic_fits(),
 * within KIN_OVERLAP_NODES(n) level tests per pair of first two lengths; replaces N when it
 * finds a shorter chain. */
void sms_kin_overlap_search(const sms_kin_plan *p, double logh, double logTs, const double *T,
                            double Ts, int harmonic, const sms_kin_tuned *tuned, double *best,
                            double *N)
{
    kin_overlap s;
    size_t n = p->n, boxes = tuned != NULL ? n - 1u : n, i;
    s.p = p;
    s.harmonic = harmonic;
    s.tuned = tuned;
    s.logh = logh;
    s.logTs = logTs;
    for (i = 0; i < SMS_KINEMATIC_MAX_ORDER; ++i)
        s.N[i] = s.c[i] = 0.0;
    s.rest_min[boxes] = 0.0;
    for (i = n; i-- > 0;) {
        s.c[i] = sms_kin_grid_ceil(T[i] / Ts); /* a tuned stage's only enters the lift */
        if (i < boxes)
            s.rest_min[i] = s.rest_min[i + 1u] + (s.c[i] > 2.0 ? s.c[i] - 1.0 : 1.0);
    }
    s.best_sum = *best;
    s.nodes = 0u;
    s.found = 0;
    s.sums[0] = 0.0;
    s.signs[0] = 1;
    overlap_dfs(&s, 0u, 0.0, 0.0);
    if (s.found) {
        *best = s.best_sum;
        for (i = 0; i < boxes; ++i)
            N[i] = s.best[i];
    }
}
