/* The O(1) drift-free engine shared by the four smoothers: two restarted copies of a complex
 * first-order recursion plus at most two direct taps (exact timing) (see smoother.h). */
#include <float.h>
#include <math.h>
#include "smoothshaper/smoother.h"
#include "filter/smoother_design.h"
#include "core/state_identity.h"

#ifdef SMS_USE_FLOAT
#define SMS_REAL_MAX FLT_MAX
#else
#define SMS_REAL_MAX DBL_MAX
#endif

/* Fixed part of the saved state, before the ring. */
enum {
    STATE_HEAD, STATE_AGE0, STATE_AGE1, STATE_REST,
    STATE_W0_RE, STATE_W0_IM, STATE_W1_RE, STATE_W1_IM,
    STATE_LO0_RE, STATE_LO0_IM, STATE_LO1_RE, STATE_LO1_IM,
    STATE_REF0, STATE_REF1, STATE_FIXED
};

sms_status sms_smoother_buffer_size(const sms_stage_config *config, double Ts, size_t *n_reals)
{
    sms_smoother_design d;
    sms_status st;
    if (config == NULL || n_reals == NULL)
        return SMS_ERR_NULL;
    st = sms_smoother_design_make(config, Ts, &d);
    if (st == SMS_OK)
        *n_reals = d.window;
    return st;
}

sms_status sms_smoother_length(const sms_stage_config *config, double Ts, size_t *length)
{
    sms_smoother_design d;
    sms_status st;
    if (config == NULL || length == NULL)
        return SMS_ERR_NULL;
    st = sms_smoother_design_make(config, Ts, &d);
    if (st == SMS_OK)
        *length = d.length;
    return st;
}

sms_status sms_smoother_taps(const sms_stage_config *config, double Ts, double *taps, size_t n_taps)
{
    sms_smoother_design d;
    sms_status st;
    size_t i;
    if (config == NULL || taps == NULL)
        return SMS_ERR_NULL;
    st = sms_smoother_design_make(config, Ts, &d);
    if (st != SMS_OK)
        return st;
    if (n_taps < d.length)
        return SMS_ERR_BUFFER_TOO_SMALL;
    for (i = 0; i < d.length; ++i)
        taps[i] = sms_smoother_design_tap(&d, i);
    return SMS_OK;
}

sms_status sms_smoother_init(sms_smoother *f, const sms_stage_config *config, double Ts,
                             sms_real *buffer, size_t n_reals)
{
    sms_smoother_design d;
    sms_smoother built;
    sms_status st;
    size_t j;
    if (f == NULL || config == NULL)
        return SMS_ERR_NULL;
    st = sms_smoother_design_make(config, Ts, &d);
    if (st != SMS_OK)
        return st;
    if (buffer == NULL)
        return SMS_ERR_NULL;
    if (n_reals < d.window)
        return SMS_ERR_BUFFER_TOO_SMALL;
    built.kind = config->kind;
    built.length = d.length;
    built.window = d.window;
    built.pole_m1_re = (sms_real)d.pole_m1_re;
    built.pole_im = (sms_real)d.pole_im;
    /* What rounding to sms_real lost (exact in double for float), plus the long double part. */
    built.pole_lo_re = (sms_real)((d.pole_m1_re - (double)built.pole_m1_re) + d.pole_m1_lo_re);
    built.pole_lo_im = (sms_real)((d.pole_im - (double)built.pole_im) + d.pole_lo_im);
    built.gain_re = (sms_real)d.gain;
    built.gain_im = (sms_real)0;
    built.tail_re = (sms_real)d.tail_re;
    built.tail_im = (sms_real)d.tail_im;
    built.imag_out = d.family.half_sine;
    built.real_only = !d.family.half_sine;
    built.n_corrections = d.n_corrections;
    for (j = 0; j < SMS_SMOOTHER_MAX_CORRECTIONS; ++j) {
        built.correction_delay[j] = j < d.n_corrections ? d.correction_delay[j] : 0u;
        built.correction_gain[j] = (sms_real)(j < d.n_corrections ? d.correction_gain[j] : 0.0);
    }
    built.input_limit = d.input_limit;
    sms_state_identity(config, Ts, built.identity);
    built.history = buffer;
    built.history_len = d.window;
    sms_smoother_reset(&built, (sms_real)0);
    *f = built;
    return SMS_OK;
}

void sms_smoother_reset(sms_smoother *f, sms_real rest)
{
    size_t i;
    for (i = 0; i < f->window; ++i)
        f->history[i] = (sms_real)0;
    f->head = 0;
    f->rest = rest;
    f->w_re[0] = f->w_re[1] = f->w_im[0] = f->w_im[1] = (sms_real)0;
    f->lo_re[0] = f->lo_re[1] = f->lo_im[0] = f->lo_im[1] = (sms_real)0;
    f->ref[0] = f->ref[1] = (sms_real)0;
    /* All past inputs are zero (relative to rest), so a zero copy is exact at any age: copy 0
     * is in use now, copy 1 takes over after M samples. */
    f->age[0] = f->window;
    f->age[1] = 0;
}

/* The per-sample engine. Between two events (a copy restarts, the ring head wraps) the roles
 * are fixed: the "old" copy has consumed M..2M samples, takes x[n-M] and gives the output; the
 * "young" one has consumed fewer than M and takes no x[n-M] (its inputs before the restart
 * must not reach it, so that a NaN there cannot either). sms_smoother_process() therefore
 * runs segments: the state goes into locals, a tight loop runs the segment, the state goes
 * back. The two copies do the same arithmetic on different data, so they run as the two lanes
 * of one small vector (lane 0 old, lane 1 young; the young lane sees x[n-M] replaced by its
 * reference, i.e. 0, and a zero tail weight). Each copy's state is w + lo, updated for the
 * input u = c (x - ref) + t (x[n-M] - ref) as
 *   d = (q - 1) w + u,  w' + e = w + d (Fast2Sum),  lo' = lo + ((q - 1) lo + q_lo w + e):
 * lo collects what the addition rounds away and what the rounded pole misses, and rotates on
 * the same pole. Fast2Sum needs IEEE evaluation in sms_real: no -ffast-math reassociation,
 * no x87 excess precision (FLT_EVAL_METHOD 0). */

#if defined(__GNUC__) && (defined(__SSE2__) || defined(__ARM_NEON)) \
    && !defined(SMS_NO_VECTOR_EXTENSIONS)
/* GCC/Clang vector extension on targets with 128-bit SIMD (SSE2, NEON): one register holds
 * both copies (float: twice, lanes 2 and 3 repeat 0 and 1; 64-bit float vectors would go
 * through general registers). Each lane does exactly the IEEE operations of the portable
 * version below, so both give the same bits. */
typedef sms_real lanes __attribute__((vector_size(16)));
#ifdef SMS_USE_FLOAT
#define LANES(a, b) ((lanes){(a), (b), (a), (b)})
#else
#define LANES(a, b) ((lanes){(a), (b)})
#endif
#define LANE(v, i) ((v)[i])
/* Fast targets: one loop per variant (real or complex pole, with or without corrections). */
#define SMS_SMOOTHER_VARIANT_LOOPS 1
#define ADD(a, b) ((a) + (b))
#define SUB(a, b) ((a) - (b))
#define MUL(a, b) ((a) * (b))
#else
/* Elsewhere (no SIMD, e.g. Cortex-M): scalar lanes, and the two copies run one after the
 * other over each segment (young first: it only reads the input, which the old one may
 * overwrite in place). One loop per pole type keeps the code small. */
typedef sms_real lanes;
#define LANES(a, b) ((void)(b), (a))
#define LANE(v, i) ((void)(i), (v))
#define ADD(a, b) ((a) + (b))
#define SUB(a, b) ((a) - (b))
#define MUL(a, b) ((a) * (b))
#endif

/* Dekker's Fast2Sum (3 operations instead of TwoSum's 6): s + e == a + b exactly when
 * |a| >= |b|, a the state and b its increment. That is the case where the lost part is
 * systematic (an increment far below the state, for a pole near 1) and must be kept. Where
 * |b| > |a| (just after a restart, or where w crosses zero), e may miss the exact error by
 * about an ulp of b: no more than the rounding already made in computing b, and not
 * systematic. */
#define FAST_TWO_SUM(s, e, a, b)                                                          \
    do {                                                                             \
        const lanes s_ = ADD((a), (b));                                              \
        (e) = SUB((b), SUB(s_, (a)));                                                \
        (s) = s_;                                                                    \
    } while (0)

/* Both copies of one segment, by role (lane 0 old, lane 1 young), and the constants. */
typedef struct segment {
    lanes w_re, w_im, lo_re, lo_im, ref;
    sms_real pm1_re, p_im, plo_re, plo_im, gain, tail_re, tail_im, corr0, corr1, rest;
    sms_real *ring;
    size_t head, window;
} segment;

/* Direct taps: none, on x[n-M+1] and x[n-M] (exact timing), on x[n] and x[n-M] (bounded). */
enum { TAPS_NONE, TAPS_EXACT, TAPS_BOUNDED };

/* The old copy's sample i of a segment: add the direct taps (on x[n-M+1], the ring slot after
 * this one, `wrap` being the segment's sample where that slot is ring[0]; or on x itself) and
 * x[n-M], store x in the ring, write the output. */
static void finish_sample(sms_real *ring, sms_real *out, size_t i, sms_real x, sms_real oldest,
                          sms_real y, sms_real ref0, sms_real base, int corrections,
                          const sms_real *ring0, size_t wrap, sms_real corr0, sms_real corr1)
{
    if (corrections != TAPS_NONE) {
        const sms_real first = corrections == TAPS_BOUNDED ? x
                             : i == wrap ? ring0[0] : ring[i + 1u];
        y += corr0 * (first - ref0) + corr1 * (oldest - ref0);
    }
    ring[i] = x;
    out[i] = y + base;
}

#ifdef SMS_SMOOTHER_VARIANT_LOOPS
/* Real pole (rectangular, exponential): Re w. unit_pole: q = 1 exactly (rectangular), so
 * (q - 1) w and q_lo w vanish. */
static void segment_real(segment *g, const sms_real *in, sms_real *out, size_t n, int emit,
                         int corrections, int unit_pole)
{
    const lanes pm1 = LANES(g->pm1_re, g->pm1_re), plo = LANES(g->plo_re, g->plo_re);
    const lanes gain = LANES(g->gain, g->gain), tail = LANES(g->tail_re, (sms_real)0);
    const lanes ref = g->ref;
    const sms_real ref0 = LANE(ref, 0), ref1 = LANE(ref, 1), rest = g->rest;
    const sms_real base = ref0 + rest; /* added back to the output: the reference, the rest */
    const sms_real corr0 = g->corr0, corr1 = g->corr1;
    const size_t wrap = g->window - g->head - 1u;
    sms_real *ring = g->ring + g->head;
    lanes w = g->w_re, lo = g->lo_re;
    size_t i;
    for (i = 0; i < n; ++i) {
        const sms_real x = in[i] - rest, oldest = emit ? ring[i] : ref0;
        const lanes u = ADD(MUL(gain, SUB(LANES(x, x), ref)),
                            MUL(tail, SUB(LANES(oldest, ref1), ref)));
        const lanes d = unit_pole ? u : ADD(MUL(pm1, w), u);
        lanes s, e;
        sms_real y;
        FAST_TWO_SUM(s, e, w, d);
        lo = unit_pole ? ADD(lo, e) : ADD(lo, ADD(ADD(MUL(pm1, lo), MUL(plo, w)), e));
        w = s;
        y = LANE(w, 0) + LANE(lo, 0);
        if (emit)
            finish_sample(ring, out, i, x, oldest, y, ref0, base, corrections, g->ring, wrap,
                              corr0, corr1);
    }
    g->w_re = w;
    g->lo_re = lo;
}

#endif

/* Complex pole (harmonic families): Im w (real_out: Re w, for the portable path). */
static void segment_complex(segment *g, const sms_real *in, sms_real *out, size_t n, int emit,
                            int corrections, int real_out)
{
    const lanes pm1 = LANES(g->pm1_re, g->pm1_re), pim = LANES(g->p_im, g->p_im);
    const lanes plo_re = LANES(g->plo_re, g->plo_re), plo_im = LANES(g->plo_im, g->plo_im);
    const lanes gain = LANES(g->gain, g->gain);
    const lanes tail_re = LANES(g->tail_re, (sms_real)0), tail_im = LANES(g->tail_im, (sms_real)0);
    const lanes ref = g->ref;
    const sms_real ref0 = LANE(ref, 0), ref1 = LANE(ref, 1), rest = g->rest;
    const sms_real base = ref0 + rest; /* added back to the output: the reference, the rest */
    const sms_real corr0 = g->corr0, corr1 = g->corr1;
    const size_t wrap = g->window - g->head - 1u;
    sms_real *ring = g->ring + g->head;
    lanes w_re = g->w_re, w_im = g->w_im, lo_re = g->lo_re, lo_im = g->lo_im;
    size_t i;
    for (i = 0; i < n; ++i) {
        const sms_real x = in[i] - rest, oldest = emit ? ring[i] : ref0;
        const lanes o = SUB(LANES(oldest, ref1), ref);
        const lanes d_re = ADD(SUB(MUL(pm1, w_re), MUL(pim, w_im)),
                               ADD(MUL(gain, SUB(LANES(x, x), ref)), MUL(tail_re, o)));
        const lanes d_im = ADD(ADD(MUL(pm1, w_im), MUL(pim, w_re)), MUL(tail_im, o));
        lanes s_re, s_im, e_re, e_im, r_re, r_im;
        sms_real y;
        FAST_TWO_SUM(s_re, e_re, w_re, d_re);
        FAST_TWO_SUM(s_im, e_im, w_im, d_im);
        r_re = ADD(ADD(SUB(MUL(pm1, lo_re), MUL(pim, lo_im)),
                       SUB(MUL(plo_re, w_re), MUL(plo_im, w_im))), e_re);
        r_im = ADD(ADD(ADD(MUL(pm1, lo_im), MUL(pim, lo_re)),
                       ADD(MUL(plo_re, w_im), MUL(plo_im, w_re))), e_im);
        lo_re = ADD(lo_re, r_re);
        lo_im = ADD(lo_im, r_im);
        w_re = s_re;
        w_im = s_im;
        /* Tap 0 of the half-sine families is 0: x reaches Im w a sample later. 0 x (0, or NaN
         * for a non-finite x) gives the output the NaN that the convolution's 0 x[n] has. */
        y = real_out ? LANE(w_re, 0) + LANE(lo_re, 0)
                     : LANE(w_im, 0) + LANE(lo_im, 0) + (sms_real)0 * x;
        if (emit)
            finish_sample(ring, out, i, x, oldest, y, ref0, base, corrections, g->ring, wrap,
                              corr0, corr1);
    }
    g->w_re = w_re;
    g->w_im = w_im;
    g->lo_re = lo_re;
    g->lo_im = lo_im;
}

void sms_smoother_process(sms_smoother *f, const sms_real *in, sms_real *out, size_t n)
{
    const size_t window = f->window;
    const int corrections = f->n_corrections == 0u ? TAPS_NONE
                          : f->correction_delay[0] == 0u ? TAPS_BOUNDED : TAPS_EXACT;
#ifdef SMS_SMOOTHER_VARIANT_LOOPS
    const int unit_pole = f->real_only && f->pole_m1_re == (sms_real)0 && f->pole_lo_re == (sms_real)0;
#endif
    segment g;
    g.pm1_re = f->pole_m1_re;
    g.p_im = f->pole_im;
    g.plo_re = f->pole_lo_re;
    g.plo_im = f->pole_lo_im;
    g.gain = f->gain_re;
    g.tail_re = f->tail_re;
    g.tail_im = f->tail_im;
    /* the direct taps sit on delays M-1 and M, or 0 and M (see the design) */
    g.corr0 = corrections ? f->correction_gain[0] : (sms_real)0;
    g.corr1 = corrections ? f->correction_gain[1] : (sms_real)0;
    g.rest = f->rest;
    g.ring = f->history;
    g.window = window;
    while (n > 0u) {
        int old, young;
        size_t seg;
        /* The old copy has consumed 2M samples: it restarts on this sample and the young one,
         * exact now (M samples), takes over. A finite input (x - x == 0) becomes the
         * restarted copy's reference; NaN/Inf must not. */
        old = f->age[0] >= f->age[1] ? 0 : 1;
        if (f->age[old] == 2u * window) {
            const sms_real x = in[0] - f->rest;
            f->w_re[old] = f->w_im[old] = (sms_real)0;
            f->lo_re[old] = f->lo_im[old] = (sms_real)0;
            f->ref[old] = x - x == (sms_real)0 ? x : (sms_real)0;
            f->age[old] = 0;
            old = 1 - old;
        }
        young = 1 - old;
        seg = window - f->age[young];
        if (window - f->head < seg)
            seg = window - f->head;
        if (n < seg)
            seg = n;
        g.head = f->head;
#ifdef SMS_SMOOTHER_VARIANT_LOOPS
        g.w_re = LANES(f->w_re[old], f->w_re[young]);
        g.w_im = LANES(f->w_im[old], f->w_im[young]);
        g.lo_re = LANES(f->lo_re[old], f->lo_re[young]);
        g.lo_im = LANES(f->lo_im[old], f->lo_im[young]);
        g.ref = LANES(f->ref[old], f->ref[young]);
        /* Constant flags per call: the compiler drops the unused branches from each loop. */
        if (f->real_only) {
            if (corrections == TAPS_BOUNDED)
                segment_real(&g, in, out, seg, 1, TAPS_BOUNDED, unit_pole);
            else if (corrections == TAPS_EXACT)
                segment_real(&g, in, out, seg, 1, TAPS_EXACT, unit_pole);
            else if (unit_pole)
                segment_real(&g, in, out, seg, 1, TAPS_NONE, 1);
            else
                segment_real(&g, in, out, seg, 1, TAPS_NONE, 0);
        } else if (corrections) { /* half-sine families: exact timing only */
            segment_complex(&g, in, out, seg, 1, TAPS_EXACT, 0);
        } else {
            segment_complex(&g, in, out, seg, 1, TAPS_NONE, 0);
        }
        f->w_re[old] = LANE(g.w_re, 0);
        f->w_re[young] = LANE(g.w_re, 1);
        f->w_im[old] = LANE(g.w_im, 0);
        f->w_im[young] = LANE(g.w_im, 1);
        f->lo_re[old] = LANE(g.lo_re, 0);
        f->lo_re[young] = LANE(g.lo_re, 1);
        f->lo_im[old] = LANE(g.lo_im, 0);
        f->lo_im[young] = LANE(g.lo_im, 1);
#else
        {
            int pass;
            for (pass = 0; pass < 2; ++pass) {
                const int c = pass == 0 ? young : old;
                g.w_re = f->w_re[c];
                g.w_im = f->w_im[c];
                g.lo_re = f->lo_re[c];
                g.lo_im = f->lo_im[c];
                g.ref = f->ref[c];
                g.tail_re = pass == 0 ? (sms_real)0 : f->tail_re;
                g.tail_im = pass == 0 ? (sms_real)0 : f->tail_im;
                /* One loop for every family (smaller code): a real pole has Im q = 0 and
                 * Im c = Im t = Im q_lo = 0, so Im w stays 0 and Re w follows exactly the
                 * real recursion (the extra terms add exact zeros). */
                segment_complex(&g, in, out, seg, pass, pass ? corrections : TAPS_NONE,
                                f->real_only);
                f->w_re[c] = g.w_re;
                f->w_im[c] = g.w_im;
                f->lo_re[c] = g.lo_re;
                f->lo_im[c] = g.lo_im;
            }
        }
#endif
        f->age[old] += seg;
        f->age[young] += seg;
        f->head += seg;
        if (f->head == window)
            f->head = 0;
        in += seg;
        out += seg;
        n -= seg;
    }
}

/* The phase of the two copies: the one in use (the elder) has consumed M + s samples,
 * s in [0, M] (s = 0 only right after a reset; the elder restarts on the next sample when
 * s = M). */
static size_t elder_of(const sms_smoother *f)
{
    return f->age[0] >= f->age[1] ? 0u : 1u;
}

uint64_t sms_smoother_settle_length(const sms_smoother *f)
{
    const uint64_t M = f->window, s = f->age[elder_of(f)] - f->window;
    /* the elder restarts on sample M - s + 1, the other M samples later */
    return 2u * M - s + 2u;
}

void sms_smoother_advance(sms_smoother *f, uint64_t n)
{
    const uint64_t M = f->window;
    size_t elder = elder_of(f);
    uint64_t s, restarts;
    if (n == 0u)
        return;
    s = f->age[elder] - f->window;
    /* a restart on each sample that starts with the elder at 2M (s = M): after n samples
     * (s + n - 1)/M of them, and the elder has consumed M + s' samples */
    restarts = (s + n - 1u) / M;
    s = (s + n - 1u) % M + 1u;
    if (restarts % 2u == 1u)
        elder = 1u - elder;
    f->age[elder] = (size_t)(M + s);
    f->age[1u - elder] = (size_t)s;
    f->head = (size_t)((f->head + n % M) % M);
}

sms_real sms_smoother_settle(sms_smoother *f, sms_real x, uint64_t n)
{
    const sms_real v = x - f->rest;   /* what the ring and a restarted reference hold */
    size_t i;
    for (i = 0; i < f->window; ++i)
        f->history[i] = v;
    for (i = 0; i < 2u; ++i) {
        f->w_re[i] = f->w_im[i] = (sms_real)0;
        f->lo_re[i] = f->lo_im[i] = (sms_real)0;
        f->ref[i] = v;
    }
    sms_smoother_advance(f, n - 1u);
    sms_smoother_process(f, &x, &x, 1u);
    return x;
}

double sms_smoother_input_max(const sms_smoother *f)
{
    return f->input_limit < SMS_INPUT_MAX ? f->input_limit : SMS_INPUT_MAX;
}

size_t sms_smoother_state_count(const sms_smoother *f)
{
    return SMS_STATE_IDENTITY_COUNT + (size_t)STATE_FIXED + f->window;
}

void sms_smoother_get_state(const sms_smoother *f, double *dst)
{
    size_t i;
    for (i = 0; i < SMS_STATE_IDENTITY_COUNT; ++i)
        dst[i] = f->identity[i];
    dst += SMS_STATE_IDENTITY_COUNT;
    dst[STATE_HEAD] = (double)f->head;
    dst[STATE_AGE0] = (double)f->age[0];
    dst[STATE_AGE1] = (double)f->age[1];
    dst[STATE_REST] = (double)f->rest;
    dst[STATE_W0_RE] = (double)f->w_re[0];
    dst[STATE_W0_IM] = (double)f->w_im[0];
    dst[STATE_W1_RE] = (double)f->w_re[1];
    dst[STATE_W1_IM] = (double)f->w_im[1];
    dst[STATE_LO0_RE] = (double)f->lo_re[0];
    dst[STATE_LO0_IM] = (double)f->lo_im[0];
    dst[STATE_LO1_RE] = (double)f->lo_re[1];
    dst[STATE_LO1_IM] = (double)f->lo_im[1];
    dst[STATE_REF0] = (double)f->ref[0];
    dst[STATE_REF1] = (double)f->ref[1];
    for (i = 0; i < f->window; ++i)
        dst[STATE_FIXED + i] = (double)f->history[i];
}

static int is_index(double v, double bound_inclusive)
{
    return v >= 0.0 && v <= bound_inclusive && v == floor(v);
}

/* Finite values must fit sms_real (converting a larger double to float is undefined). */
static int fits_real_or_nonfinite(double v)
{
    return !isfinite(v) || fabs(v) <= SMS_REAL_MAX;
}

sms_status sms_smoother_check_state(const sms_smoother *f, const double *src, size_t n)
{
    const double window = (double)(f != NULL ? f->window : 0u);
    size_t i;
    sms_status id;
    if (f == NULL || src == NULL)
        return SMS_ERR_NULL;
    if (n >= SMS_STATE_IDENTITY_COUNT
        && (id = sms_state_identity_check(f->identity, src)) != SMS_OK)
        return id;
    if (n != sms_smoother_state_count(f))
        return SMS_ERR_STATE;
    src += SMS_STATE_IDENTITY_COUNT;
    n -= SMS_STATE_IDENTITY_COUNT;
    if (!is_index(src[STATE_HEAD], window - 1.0))
        return SMS_ERR_STATE;
    if (!is_index(src[STATE_AGE0], 2.0 * window) || !is_index(src[STATE_AGE1], 2.0 * window)
        || fabs(src[STATE_AGE0] - src[STATE_AGE1]) != window)
        return SMS_ERR_STATE;
    if (!isfinite(src[STATE_REST]) || !fits_real_or_nonfinite(src[STATE_REST]))
        return SMS_ERR_STATE;
    if (!isfinite(src[STATE_REF0]) || !isfinite(src[STATE_REF1]))
        return SMS_ERR_STATE;
    for (i = STATE_W0_RE; i < n; ++i)
        if (!fits_real_or_nonfinite(src[i]))
            return SMS_ERR_STATE;
    return SMS_OK;
}

/* |v| <= bound, v finite (NaN fails the negated test). */
static int within(double v, double bound)
{
    return fabs(v) <= bound;
}

sms_status sms_smoother_check_state_range(const sms_smoother *f, const double *src, size_t n,
                                          double x_max)
{
    /* x - rest, rounded once in sms_real; and the room the input range leaves the copies */
    const double margin = 1.0 + 0x1p-20;
    double signal, internal;
    size_t i;
    sms_status st = sms_smoother_check_state(f, src, n);
    if (st != SMS_OK)
        return st;
    if (!(x_max >= 0.0))
        return SMS_ERR_STATE;
    signal = 2.0 * x_max * margin;
    /* never above half the largest sms_real: the next sample could overflow */
    internal = signal * ((double)SMS_REAL_MAX / f->input_limit);
    if (!(internal <= 0.5 * (double)SMS_REAL_MAX))
        internal = 0.5 * (double)SMS_REAL_MAX;
    src += SMS_STATE_IDENTITY_COUNT;
    if (!within(src[STATE_REST], x_max * margin))
        return SMS_ERR_STATE;
    for (i = STATE_W0_RE; i < STATE_REF0; ++i)
        if (!within(src[i], internal))
            return SMS_ERR_STATE;
    if (!within(src[STATE_REF0], signal) || !within(src[STATE_REF1], signal))
        return SMS_ERR_STATE;
    for (i = 0; i < f->window; ++i)
        if (!within(src[STATE_FIXED + i], signal))
            return SMS_ERR_STATE;
    return SMS_OK;
}

sms_status sms_smoother_set_state(sms_smoother *f, const double *src, size_t n)
{
    size_t i;
    sms_status st = sms_smoother_check_state(f, src, n);
    if (st != SMS_OK)
        return st;
    src += SMS_STATE_IDENTITY_COUNT;
    f->head = (size_t)src[STATE_HEAD];
    f->age[0] = (size_t)src[STATE_AGE0];
    f->age[1] = (size_t)src[STATE_AGE1];
    f->rest = (sms_real)src[STATE_REST];
    f->w_re[0] = (sms_real)src[STATE_W0_RE];
    f->w_im[0] = (sms_real)src[STATE_W0_IM];
    f->w_re[1] = (sms_real)src[STATE_W1_RE];
    f->w_im[1] = (sms_real)src[STATE_W1_IM];
    f->lo_re[0] = (sms_real)src[STATE_LO0_RE];
    f->lo_im[0] = (sms_real)src[STATE_LO0_IM];
    f->lo_re[1] = (sms_real)src[STATE_LO1_RE];
    f->lo_im[1] = (sms_real)src[STATE_LO1_IM];
    f->ref[0] = (sms_real)src[STATE_REF0];
    f->ref[1] = (sms_real)src[STATE_REF1];
    for (i = 0; i < f->window; ++i)
        f->history[i] = (sms_real)src[STATE_FIXED + i];
    return SMS_OK;
}
