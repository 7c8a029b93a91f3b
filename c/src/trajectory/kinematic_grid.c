/* SPDX-License-Identifier: Apache-2.0 */
/* Kinematic design on a sample grid (docs/sampled-limits.md): whole-sample lengths that keep
 * every bound at every sample, and the taps of a stage tuned to a mode as the grid samples
 * it. Design-time code: libm is allowed here. */
#include <string.h>

#include "filter/smoother_design.h"
#include "trajectory/kinematic_parts.h"

/* The timing of a stage tuned to the mode on a grid: bounded taps (no tap above the peak
 * density the design budgets for), which only the half sine does not need. */
sms_timing sms_kin_tuned_timing(sms_kind kind)
{
    return kind == SMS_HARMONIC ? SMS_TIMING_EXACT : SMS_TIMING_BOUNDED;
}

/* Largest tap of the stage tuned to the mode, its length in samples and the sum of its
 * first and last taps. */
sms_status sms_kin_tuned_taps(sms_kind kind, double T, double sigma, unsigned k, double Ts,
                              double *peak, double *support, double *ends, sms_kin_tuned *form)
{
    sms_stage_config c = sms_stage_config_default(kind);
    sms_smoother_design d;
    size_t cand[6], i;
    double best = 0.0;
    sms_status st;
    c.T = T;
    c.sigma = sigma;
    c.k = k;
    c.timing = sms_kin_tuned_timing(kind);
    st = sms_smoother_design_make(&c, Ts, &d);
    if (st != SMS_OK)
        return st;
    /* base taps are constant, decaying or one half sine: the peak is at an end, at the
     * corrected taps or at the middle of the sine */
    cand[0] = 0u;
    cand[1] = 1u;
    cand[2] = (size_t)(0.5 * d.nu);
    cand[3] = cand[2] + 1u;
    cand[4] = d.length >= 2u ? d.length - 2u : 0u;
    cand[5] = d.length - 1u;
    for (i = 0; i < 6; ++i)
        if (cand[i] < d.length) {
            double t = fabs(sms_smoother_design_tap(&d, cand[i]));
            if (t > best)
                best = t;
        }
    *peak = best;
    *support = (double)d.length;
    *ends = sms_smoother_design_tap(&d, 0u) + sms_smoother_design_tap(&d, d.length - 1u);
    form->bounded = c.timing == SMS_TIMING_BOUNDED && d.length >= 3u;
    form->tap0 = sms_smoother_design_tap(&d, 0u);
    form->tapL = sms_smoother_design_tap(&d, d.length - 1u);
    form->gain = d.gain;
    form->decay = d.decay;
    form->L = (double)d.length;
    return SMS_OK;
}

/* Largest tap of the integer-N harmonic stage: tan(pi/2N) (N even) or sin(pi/2N) (N odd). */
static double harmonic_peak_tap(double N)
{
    double x = 0.5 * KIN_PI / N;
    return fmod(N, 2.0) == 0.0 ? tan(x) : sin(x);
}

/* The sampled bounds of a chain of whole-sample stages N[0..n-1] (the last one may be tuned:
 * fixed taps of largest value tap_last over supp_last samples), all in logarithms:
 *  - structure: N[i] >= samples of the stages after it, so that the shifted copies in each
 *    backward difference never overlap (the discrete form of T_k >= T_k+1 + ... + T_n-1);
 *  - level i < n-1: h / (N[0] ... N[i] Ts^(i+1)) <= L[i];
 *  - top: h / (N[0] ... N[n-2] Ts^(n-1)) * (largest tap of the last stage) / Ts <= L[n-1].
 * Returns 1 when all hold (to 1e-12 relative). rhs[i] is the right-hand side of level i,
 * logh - log L[i] - (i + 1) log Ts - 1e-12 (grid_bounds(): the same for every candidate);
 * logN, when not NULL, holds log N[i] for the stages the caller varies (i < n, or i < n - 1
 * with a tuned last stage), so a candidate costs no logarithm of its own. */
static int grid_feasible(const sms_kin_plan *p, const double *rhs, const double *N,
                         const double *logN, sms_kind last_kind, int tuned, double tap_last,
                         double supp_last)
{
    size_t n = p->n, i;
    double below = tuned ? supp_last : N[n - 1], logprod = 0.0, logtap;
    for (i = n - 1; i-- > 0;) {
        if (N[i] < below)
            return 0;
        below += N[i];
    }
    for (i = 0; i + 1 < n; ++i) {
        logprod += logN != NULL ? logN[i] : log(N[i]);
        if (logprod < rhs[i])
            return 0;
    }
    if (tuned)
        logtap = log(tap_last);
    else if (last_kind == SMS_HARMONIC) {
        if (N[n - 1] < 2.0)
            return 0; /* one sample of a half sine is its zero: not a stage */
        logtap = log(harmonic_peak_tap(N[n - 1]));
    }
    else
        logtap = -(logN != NULL ? logN[n - 1] : log(N[n - 1]));
    return logprod - logtap >= rhs[n - 1];
}

/* The neighbourhood search of sms_kin_on_grid(): stage i takes base[i] - 1, base[i] or
 * base[i] + 1 samples, chosen depth first from stage 0, so that a level test that fails on
 * the first i + 1 stages (which it alone depends on), a stage shorter than the fewest
 * samples the stages after it can have, or a partial total that no completion keeps within
 * the best, drops every completion at once. Each test gives the answer of grid_feasible()
 * (the same sums in the same order where it is taken in logarithms), and the rule for keeping
 * a chain (shorter, or as short with the first differing stage longer) orders all chains
 * strictly, so the chain kept is the one the plain loop over all 3^m chains keeps.
 *
 * A level test in logarithms, sum log N_j >= log h - log L_i - (i+1) log Ts - tau (tau =
 * 1e-12), is first asked of the product: P = N_0 ... N_i against Q_i = h / (L_i Ts^(i+1)).
 * The logarithmic side is within E_i of its exact value (each logarithm within an ulp, each
 * sum within half an ulp of the magnitudes it adds: E_i <= (n + 8) 2^-52 (the sum of
 * |log x| over its terms + 1), each |log x| bounded by x's binary exponent), the product
 * side within a few roundings; where P >= Q_i (1 - tau + M_i) or P < Q_i (1 - tau - M_i),
 * M_i = E_i + the roundings, both sides give the same answer, and only in between (or where
 * Q_i is not a normal number) are the logarithms taken. */
typedef struct grid_hood {
    const sms_kin_plan *p;
    size_t n, m;
    sms_kind last_kind;
    int tuned, have_rhs, have_logtap;
    double h, Ts, tap_last, supp_last, best, logh, logTs, logtap_tuned;
    double *N;
    double rhs[SMS_KINEMATIC_MAX_ORDER];
    double base[SMS_KINEMATIC_MAX_ORDER], cand[SMS_KINEMATIC_MAX_ORDER];
    double prod[SMS_KINEMATIC_MAX_ORDER];
    double lo[SMS_KINEMATIC_MAX_ORDER], hi[SMS_KINEMATIC_MAX_ORDER];
    unsigned dig[SMS_KINEMATIC_MAX_ORDER];
    /* rest_min[i]: the fewest samples stages i .. m-1 can have together; need[i]: the
     * fewest the stages after i take in the structure (a tuned last stage's support and the
     * shortest candidates of stages i+1 .. m-1) */
    double rest_min[SMS_KINEMATIC_MAX_ORDER + 1], need[SMS_KINEMATIC_MAX_ORDER];
    double logv[SMS_KINEMATIC_MAX_ORDER][3]; /* log of base - 1, base, base + 1 ... */
    unsigned char have[SMS_KINEMATIC_MAX_ORDER][3]; /* ... once computed */
} grid_hood;

/* The right-hand sides of grid_feasible()'s levels, once. */
static void hood_rhs(grid_hood *g)
{
    size_t i;
    if (g->have_rhs)
        return;
    g->logh = log(g->h);
    g->logTs = log(g->Ts);
    for (i = 0; i < g->n; ++i)
        g->rhs[i] = g->logh - log(g->p->L[i]) - (double)(i + 1) * g->logTs - 1e-12;
    g->have_rhs = 1;
}

static double hood_log(grid_hood *g, size_t i)
{
    unsigned d = g->dig[i];
    if (!g->have[i][d]) {
        g->logv[i][d] = log(g->cand[i]);
        g->have[i][d] = 1u;
    }
    return g->logv[i][d];
}

/* Sum of log N_j over stages 0 .. k-1 of the current candidate, in grid_feasible()'s order. */
static double hood_logprod(grid_hood *g, size_t k)
{
    double lp = 0.0;
    size_t j;
    for (j = 0; j < k; ++j)
        lp += hood_log(g, j);
    return lp;
}

/* Upper bound of |log x| for a normal x > 0: (|binary exponent| + 1) log 2; -1 otherwise. */
static double log_bound(double x)
{
    int e;
    if (!(x >= 2.2250738585072014e-308) || !(x <= 1.7976931348623157e308))
        return -1.0;
    (void)frexp(x, &e); /* x = f 2^e, f in [0.5, 1): |log x| <= (|e - 1| + 1) log 2 */
    return (double)((e - 1 < 0 ? 1 - e : e - 1) + 1) * 0.6931471805599453;
}

/* The product thresholds lo[i], hi[i] (-inf, +inf where the logarithms must decide). */
static void hood_thresholds(grid_hood *g)
{
    const double u = 2.220446049250313e-16, tau = 1e-12; /* 2^-52, grid_feasible's margin */
    double bh = log_bound(g->h), bTs = log_bound(g->Ts), bN = 0.0, tsp = 1.0;
    size_t i;
    for (i = 0; i < g->n; ++i) {
        double bL = log_bound(g->p->L[i]), den, Q, M, bi;
        g->lo[i] = -HUGE_VAL;
        g->hi[i] = HUGE_VAL;
        if (i < g->m)
            bN += log_bound(g->base[i] + 1.0); /* every candidate of stage i is at most that */
        tsp *= g->Ts;
        if (bh < 0.0 || bTs < 0.0 || bL < 0.0 || (i < g->m && bN < 0.0))
            continue;
        den = g->p->L[i] * tsp;
        Q = g->h / den;
        if (!(tsp >= 2.2250738585072014e-308) || !(den >= 2.2250738585072014e-308) ||
            !(den <= 1e300) || !(Q >= 2.2250738585072014e-308) || !(Q <= 1e300))
            continue;
        bi = bh + bL + (double)(i + 1) * bTs + bN + 1.0;
        M = (double)(g->n + 8u) * u * bi + (double)(2u * g->n + 16u) * u;
        if (!(M < 0.5 * tau))
            continue;
        g->lo[i] = Q * (1.0 - tau - M);
        g->hi[i] = Q * (1.0 - tau + M);
    }
}

/* Level i < n-1 of grid_feasible() for the current stages 0 .. i, whose product is P. */
static int hood_level(grid_hood *g, size_t i, double P)
{
    if (P >= g->hi[i])
        return 1;
    if (P < g->lo[i])
        return 0;
    hood_rhs(g);
    return !(hood_logprod(g, i + 1) < g->rhs[i]);
}

/* A complete candidate of total `sum` whose levels below the top hold: the rest of
 * grid_feasible() (the structure and the top level) and the rule for keeping it. */
static void hood_leaf(grid_hood *g, double sum)
{
    size_t n = g->n, m = g->m, i;
    const double *cand = g->cand;
    double below = g->tuned ? g->supp_last : cand[n - 1], logtap;
    int better;
    for (i = n - 1; i-- > 0;) {
        if (cand[i] < below)
            return;
        below += cand[i];
    }
    if (!g->tuned && g->last_kind != SMS_HARMONIC) {
        /* log prod N_0..N_{n-2} - (-log N_{n-1}) is the sum over all n stages */
        double P = n >= 2u ? g->prod[n - 2] * cand[n - 1] : cand[0];
        if (P < g->hi[n - 1]) {
            if (P < g->lo[n - 1])
                return;
            hood_rhs(g);
            if (hood_logprod(g, n) < g->rhs[n - 1])
                return;
        }
    } else {
        if (g->tuned) {
            if (!g->have_logtap) {
                g->logtap_tuned = log(g->tap_last);
                g->have_logtap = 1;
            }
            logtap = g->logtap_tuned;
        } else {
            if (cand[n - 1] < 2.0)
                return; /* one sample of a half sine is its zero: not a stage */
            logtap = log(harmonic_peak_tap(cand[n - 1]));
        }
        hood_rhs(g);
        if (!(hood_logprod(g, n - 1) - logtap >= g->rhs[n - 1]))
            return;
    }
    better = sum < g->best;
    for (i = 0; i < m && !better && sum == g->best; ++i) {
        if (cand[i] != g->N[i]) {
            better = cand[i] > g->N[i];
            break;
        }
    }
    if (better) {
        g->best = sum;
        for (i = 0; i < m; ++i)
            g->N[i] = cand[i];
    }
}

/* Stage i's three candidates after stages 0 .. i-1 (total `sum`). */
static void hood_visit(grid_hood *g, size_t i, double sum)
{
    unsigned d;
    for (d = 0; d < 3u; ++d) {
        double c = g->base[i] + (double)d - 1.0, s = sum + c;
        if (c < 1.0 || s + g->rest_min[i + 1] > g->best || c < g->need[i])
            continue;
        g->cand[i] = c;
        g->dig[i] = d;
        if (i + 1 < g->n) { /* level i: its test needs stages 0 .. i only */
            g->prod[i] = i == 0u ? c : g->prod[i - 1] * c;
            if (!hood_level(g, i, g->prod[i]))
                continue;
            if (i + 1 < g->m)
                hood_visit(g, i + 1, s);
            else
                hood_leaf(g, s);
        } else { /* the free last stage: the top level */
            hood_leaf(g, s);
        }
    }
}

/* Whole-sample lengths: the shortest total among N[i] = ceil(T[i]/Ts) + {-1, 0, 1} that
 * meets grid_feasible() (ties: longer early stages), with the greedy rounding (each N[i]
 * the larger of its ceiling and the samples after it, which is always feasible) as the
 * fallback. N[n-1] = 0 for a tuned last stage (it keeps its exact length). */
sms_status sms_kin_on_grid(const sms_kin_plan *p, double h, const double *T, sms_kind last_kind,
                           int tuned, double supp_last, const sms_kin_tuned *form, double Ts,
                           double *N)
{
    size_t n = p->n, m = tuned ? n - 1 : n, i, c;
    double base[SMS_KINEMATIC_MAX_ORDER], cand[SMS_KINEMATIC_MAX_ORDER], below, total, best;
    double tap_last = 0.0, logh, logTs;
    const double *rhs;
    grid_hood g;
    for (i = 0; i < n; ++i)
        if (!(T[i] / Ts <= 4503599627370496.0)) /* 2^52 samples */
            return SMS_ERR_TOO_LONG;
    for (i = 0; i < m; ++i)
        base[i] = sms_kin_grid_ceil(T[i] / Ts);
    if (tuned)
        tap_last = p->rho_fixed * Ts; /* >= the largest tap: the density the design used */
    /* greedy */
    if (tuned) {
        N[n - 1] = 0.0;
        below = supp_last;
    } else {
        double nu = T[n - 1] / Ts;
        N[n - 1] = base[n - 1];
        if (last_kind == SMS_HARMONIC) {
            if (N[n - 1] < 2.0)
                N[n - 1] = 2.0;
            if (harmonic_peak_tap(N[n - 1]) > 0.5 * KIN_PI / nu)
                N[n - 1] += 1.0; /* an odd N always has peak sin(pi/2N) < pi/2N */
        }
        below = N[n - 1];
    }
    total = tuned ? 0.0 : N[n - 1];
    for (i = n - 1; i-- > 0;) {
        double Ni = base[i];
        if (Ni < below)
            Ni = below;
        N[i] = Ni;
        below += Ni;
        total += Ni;
    }
    if (!(total <= 4503599627370496.0))
        return SMS_ERR_TOO_LONG;
    best = total;
    /* neighbourhood search */
    g.p = p;
    g.n = n;
    g.m = m;
    g.h = h;
    g.Ts = Ts;
    g.have_rhs = 0;
    g.have_logtap = 0;
    g.logh = g.logTs = 0.0;
    if (m >= 1u) {
        g.last_kind = last_kind;
        g.tuned = tuned;
        g.tap_last = tap_last;
        g.supp_last = supp_last;
        g.best = best;
        g.N = N;
        g.rest_min[m] = 0.0;
        g.cand[n - 1] = 0.0;
        memset(g.have, 0, sizeof g.have);
        for (i = m; i-- > 0;) {
            double low = base[i] - 1.0 < 1.0 ? 1.0 : base[i] - 1.0;
            g.base[i] = base[i];
            g.rest_min[i] = g.rest_min[i + 1] + low;
            g.need[i] = (tuned ? supp_last : 0.0) + g.rest_min[i + 1];
        }
        hood_thresholds(&g);
        hood_visit(&g, 0u, 0.0);
        best = g.best;
    }
    /* Tight stages (each as long as the stages after it) double the rounding of the stages
     * below them, so with five or more bounds the neighbourhood can leave the chain many
     * samples over the continuous optimum (13.7 samples for 5 bounds where 1.7 exist). When it
     * is more than one sample per rounded stage over: move each stage by +1 .. -2 samples
     * from its ceiling and let the structure lift it (N_k = max(that, the samples after k)),
     * keeping the shortest feasible chain; 4^m chains, only on this path. A rectangular chain
     * first tries the search that lets copies overlap where they cancel (overlap_search):
     * cheaper, usually shorter, and when it lands within the bar the 4^m chains are skipped. */
    {
        double cont = 0.0;
        for (i = 0; i < m; ++i)
            cont += T[i] / Ts;
        int free_last = !tuned && n >= 2, harmonic = last_kind == SMS_HARMONIC;
        double before4;
        if (best - cont > 0.0)
            hood_rhs(&g); /* the searches below test in logarithms */
        rhs = g.rhs;
        logh = g.logh;
        logTs = g.logTs;
        if (free_last && best - cont > (double)m)
            sms_kin_overlap_search(p, logh, logTs, T, Ts, harmonic, NULL, &best, N);
        before4 = best;
        if (m >= 2 && best - cont > (double)m) {
            size_t combos4 = 1;
            for (i = 0; i < m; ++i)
                combos4 *= 4u;
            for (c = 0; c < combos4; ++c) {
                size_t code = c;
                double sum = 0.0, after = tuned ? supp_last : 0.0;
                for (i = m; i-- > 0;) {
                    double Ni = base[i] + 1.0 - (double)(code % 4u);
                    code /= 4u;
                    if (Ni < 1.0)
                        Ni = 1.0;
                    if (i + 1 < n && Ni < after)
                        Ni = after; /* the structure: at least the samples after it */
                    cand[i] = Ni;
                    after += Ni;
                    sum += Ni;
                }
                if (sum >= best)
                    continue;
                if (!grid_feasible(p, rhs, cand, NULL, last_kind, tuned, tap_last, supp_last))
                    continue;
                best = sum;
                for (i = 0; i < m; ++i)
                    N[i] = cand[i];
            }
        }
        /* still over, with a shorter chain to beat: the overlap search prunes harder */
        if (free_last && best < before4 && best - cont > (double)m)
            sms_kin_overlap_search(p, logh, logTs, T, Ts, harmonic, NULL, &best, N);
        /* a bounded tuned stage costs up to two samples of its own: its boxes get the search
         * that lets copies overlap once they are more than a sample per box over */
        if (tuned && form->bounded && m >= 1u && best - cont > 0.0)
            sms_kin_overlap_search(p, logh, logTs, T, Ts, 0, form, &best, N);
    }
    return SMS_OK;
}
