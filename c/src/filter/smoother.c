/* SPDX-License-Identifier: Apache-2.0 */
/* The O(1) drift-free engine shared by the four smoothers: two restarted copies of a complex
 * first-order recursion plus at most two direct taps (exact timing) (see smoother.h). */
#include <float.h>
#include <math.h>
#include <string.h>
#include "smoothshaper/coeffs.h"
#include "filter/coeffs_check.h"
#include "filter/smoother_design.h"
#include "core/state_identity.h"

#ifdef SMS_USE_FLOAT
#define SMS_REAL_MAX FLT_MAX
#else
#define SMS_REAL_MAX DBL_MAX
#endif

/* Fixed part of the saved state, before the ring. */
enum {
    STATE_HEAD, STATE_RUN, STATE_REST,
    STATE_W0_RE, STATE_W0_IM, STATE_W1_RE, STATE_W1_IM,
    STATE_LO0_RE, STATE_LO0_IM, STATE_LO1_RE, STATE_LO1_IM,
    STATE_REF0, STATE_REF1, STATE_FIXED
};

/* Direct taps: none, on x[n-M+1] and x[n-M] (exact timing), on x[n] and x[n-M] (bounded). */
enum { TAPS_NONE, TAPS_EXACT, TAPS_BOUNDED };

/* sms_smoother::variant, 3 * pole + taps: the pole q = 1 (rectangular), real, complex. */
enum { POLE_UNIT, POLE_REAL, POLE_COMPLEX };

static int taps_of(const sms_smoother *f)
{
    return f->n_corrections == 0u ? TAPS_NONE
           : f->correction_delay[0] == 0u ? TAPS_BOUNDED : TAPS_EXACT;
}

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

/* The design's constants in sms_real: what the instance runs on (host side). */
static void coeffs_of_design(const sms_smoother_design *d, sms_smoother_coeffs *c)
{
    size_t j;
    c->length = d->length;
    c->window = d->window;
    c->pole_m1_re = (sms_real)d->pole_m1_re;
    c->pole_im = (sms_real)d->pole_im;
    /* What rounding to sms_real lost (exact in double for float), plus the double-double low
     * part. */
    c->pole_lo_re = (sms_real)((d->pole_m1_re - (double)c->pole_m1_re) + d->pole_m1_lo_re);
    c->pole_lo_im = (sms_real)((d->pole_im - (double)c->pole_im) + d->pole_lo_im);
    c->gain = (sms_real)d->gain;
    c->tail_re = (sms_real)d->tail_re;
    c->tail_im = (sms_real)d->tail_im;
    c->n_corrections = d->n_corrections;
    for (j = 0; j < SMS_SMOOTHER_MAX_CORRECTIONS; ++j) {
        c->correction_delay[j] = j < d->n_corrections ? d->correction_delay[j] : 0u;
        c->correction_gain[j] = (sms_real)(j < d->n_corrections ? d->correction_gain[j] : 0.0);
    }
    c->input_limit = d->input_limit;
}

sms_status sms_smoother_coeffs_make(const sms_stage_config *config, double Ts,
                                    sms_stage_coeffs *coeffs)
{
    sms_smoother_design d;
    sms_status st = sms_smoother_design_make(config, Ts, &d);
    if (st != SMS_OK)
        return st;
    coeffs->kind = config->kind;
    sms_state_identity(config, Ts, coeffs->identity);
    coeffs_of_design(&d, &coeffs->u.smoother);
    return SMS_OK;
}

static int is_smoother_kind(sms_kind kind)
{
    return kind == SMS_RECTANGULAR || kind == SMS_HARMONIC || kind == SMS_DAMPED_HARMONIC
           || kind == SMS_EXPONENTIAL;
}

static int finite_real(sms_real v)
{
    return v - v == (sms_real)0;
}

/* What sms_smoother_coeffs_make() can write (integer and sms_real tests only). */
sms_status sms_smoother_coeffs_check(const sms_stage_coeffs *coeffs)
{
    const sms_smoother_coeffs *c = &coeffs->u.smoother;
    size_t j;
    if (!is_smoother_kind(coeffs->kind))
        return SMS_ERR_KIND;
    if (c->window < 1u || c->window > (size_t)-1 / 32u)
        return SMS_ERR_COEFFS;
    if (c->n_corrections == 0u) {
        if (c->length != c->window)
            return SMS_ERR_COEFFS;
    } else if (c->n_corrections != SMS_SMOOTHER_MAX_CORRECTIONS || c->length != c->window + 1u
               || c->correction_delay[1] != c->window
               || (c->correction_delay[0] != 0u && c->correction_delay[0] != c->window - 1u)) {
        return SMS_ERR_COEFFS;
    }
    if (!finite_real(c->pole_m1_re) || !finite_real(c->pole_im) || !finite_real(c->pole_lo_re)
        || !finite_real(c->pole_lo_im) || !finite_real(c->gain) || !finite_real(c->tail_re)
        || !finite_real(c->tail_im))
        return SMS_ERR_COEFFS;
    for (j = 0; j < SMS_SMOOTHER_MAX_CORRECTIONS; ++j)
        if (!finite_real(c->correction_gain[j]))
            return SMS_ERR_COEFFS;
    return SMS_OK;
}

sms_status sms_smoother_init_coeffs(sms_smoother *f, const sms_stage_coeffs *coeffs,
                                    sms_real *buffer, size_t n_reals)
{
    const sms_smoother_coeffs *c;
    sms_smoother built;
    sms_status st;
    size_t j;
    if (f == NULL || coeffs == NULL)
        return SMS_ERR_NULL;
    st = sms_smoother_coeffs_check(coeffs);
    if (st != SMS_OK)
        return st;
    c = &coeffs->u.smoother;
    if (buffer == NULL)
        return SMS_ERR_NULL;
    if (n_reals < c->window)
        return SMS_ERR_BUFFER_TOO_SMALL;
    built.kind = coeffs->kind;
    built.length = c->length;
    built.window = c->window;
    built.pole_m1_re = c->pole_m1_re;
    built.pole_im = c->pole_im;
    built.pole_lo_re = c->pole_lo_re;
    built.pole_lo_im = c->pole_lo_im;
    built.gain_re = c->gain;
    built.gain_im = (sms_real)0;
    built.tail_re = c->tail_re;
    built.tail_im = c->tail_im;
    built.imag_out = coeffs->kind == SMS_HARMONIC || coeffs->kind == SMS_DAMPED_HARMONIC;
    built.real_only = !built.imag_out;
    built.n_corrections = c->n_corrections;
    for (j = 0; j < SMS_SMOOTHER_MAX_CORRECTIONS; ++j) {
        built.correction_delay[j] = c->correction_delay[j];
        built.correction_gain[j] = c->correction_gain[j];
    }
    built.variant = 3u * (unsigned)(!built.real_only ? POLE_COMPLEX
                                    : built.pole_m1_re == (sms_real)0
                                      && built.pole_lo_re == (sms_real)0
                                      && built.tail_re == -built.gain_re ? POLE_UNIT : POLE_REAL)
                    + (unsigned)taps_of(&built);
    built.input_limit = c->input_limit;
    for (j = 0; j < SMS_STATE_IDENTITY_COUNT; ++j)
        built.identity[j] = coeffs->identity[j];
    built.history = buffer;
    built.history_len = c->window;
    sms_smoother_reset(&built, (sms_real)0);
    *f = built;
    return SMS_OK;
}

sms_status sms_smoother_init(sms_smoother *f, const sms_stage_config *config, double Ts,
                             sms_real *buffer, size_t n_reals)
{
    sms_stage_coeffs coeffs;
    sms_status st;
    if (f == NULL || config == NULL)
        return SMS_ERR_NULL;
    st = sms_smoother_coeffs_make(config, Ts, &coeffs);
    if (st != SMS_OK)
        return st;
    return sms_smoother_init_coeffs(f, &coeffs, buffer, n_reals);
}

void sms_smoother_reset(sms_smoother *f, sms_real rest)
{
    size_t i;
    for (i = 0; i < f->window; ++i)
        f->history[i] = rest;
    f->head = 0;
    f->rest = rest;
    f->w_re[0] = f->w_re[1] = f->w_im[0] = f->w_im[1] = (sms_real)0;
    f->lo_re[0] = f->lo_re[1] = f->lo_im[0] = f->lo_im[1] = (sms_real)0;
    /* Every past input was rest: a zero copy referred to rest is exact at any age, and the
     * last L inputs are equal (the output is rest until the input changes). */
    f->ref[0] = f->ref[1] = rest;
    f->run = f->length;
}

/* The per-sample engine. The two copies have fixed roles: copy 0, the old one, has consumed
 * M + head samples (at least M, so it is exact), takes x[n-M] and gives the output; copy 1,
 * the young one, has consumed head samples and takes no x[n-M] (its inputs before its restart
 * must not reach it, so that a NaN there cannot either). On the sample where head is 0 the
 * old copy retires: the young one (M samples now) becomes the old one and a new young copy
 * starts from zero, its reference the sample's input. Between two such samples nothing
 * changes roles, so sms_smoother_process() runs segments up to the ring's end with the state
 * in locals; the two copies do the same arithmetic on different data and run as the two
 * lanes of one small vector (lane 0 old, lane 1 young; the young lane sees x[n-M] replaced by
 * its reference, i.e. 0, and a zero tail weight). Each copy's state is w + lo, updated for
 * the input u = c (x - ref) + t (x[n-M] - ref) as
 *   a + e1 = w + u,  w' + e2 = a + (q - 1) w (two Fast2Sums),  lo' = q lo + (q_lo w + e1 + e2):
 * lo collects what the additions round away and what the rounded pole misses, and rotates on
 * the same pole. For the rectangular stage (q = 1, t = -c) u is c (x - x[n-M]) in the old
 * copy. Fast2Sum needs IEEE evaluation in sms_real: no -ffast-math reassociation, no x87
 * excess precision (FLT_EVAL_METHOD 0).
 *
 * Exact rest: run counts the latest inputs equal to the one before them (at most L). When
 * the last L inputs are equal (run >= L - 1) the convolution with taps summing to 1 is that
 * input, and it is output as it is; the recursion's rounding (below an ulp of the input's
 * variation, but not zero) would otherwise leave y one ulp off x until both copies restart
 * under it. The copies are not touched: their state stays a function of the last M + head
 * inputs. */

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
/* The lane-wise result of comparing two lanes (all ones where equal). */
#ifdef SMS_USE_FLOAT
typedef int lane_mask __attribute__((vector_size(16)));
#else
typedef long long lane_mask __attribute__((vector_size(16)));
#endif
/* Fast targets: one loop per variant (real or complex pole, with or without direct taps). */
#define SMS_SMOOTHER_VARIANT_LOOPS 1
#else
/* Elsewhere (no SIMD, e.g. Cortex-M): scalar lanes, and the two copies run one after the
 * other (young first: it only reads the input, which the old one may overwrite in place).
 * One loop for every family keeps the code small. */
typedef sms_real lanes;
#define LANES(a, b) ((void)(b), (a))
#define LANE(v, i) ((void)(i), (v))
#endif
/* The per-variant loops are instances of segment() with constant flags: on the vector path
 * each must be inlined (GCC at -O2 otherwise keeps one generic copy that tests the flags on
 * every sample); the portable path keeps one copy for code size. */
#ifdef SMS_SMOOTHER_VARIANT_LOOPS
#define SEGMENT_BODY static inline __attribute__((always_inline))
#else
#define SEGMENT_BODY static inline
#endif
/* Blocks of a complex pole on targets whose vector holds four sms_real (float on SSE2/NEON,
 * double with AVX): both copies' Re and Im in one vector. The complex products need Re and Im
 * swapped, which must stay within a 128-bit lane (one cheap shuffle): double (AVX) keeps
 * {Re, Im} of the old copy, then of the young one; float keeps the instance's own order
 * {Re old, Re young, Im old, Im young}, where SSE2 merges two vectors' halves in one shuffle
 * (the input term's Re and Im parts). QL() builds a vector from the lanes in the order
 * {Re old, Im old, Re young, Im young}, whatever the layout; RE0 .. IM1 are their indices.
 * Each lane still does exactly the IEEE operations of the two-lane form (a - b c is computed
 * as a + (-b) c, the same number bit for bit), so every build gives the same bits. Needs
 * __builtin_shufflevector (GCC 12, Clang). */
/* Only where no product can be fused into a sum behind the code's back (no FMA on the target,
 * or GCC in ISO C mode, which does not contract): a contracted sum in one layout and not in
 * the other would make sms_smoother_step() (two lanes) and sms_smoother_process() differ. */
#if defined(SMS_SMOOTHER_VARIANT_LOOPS) && (defined(SMS_USE_FLOAT) || defined(__AVX__)) \
    && (defined(__clang__) || __GNUC__ >= 12) && !defined(SMS_NO_QUAD_LANES) \
    && ((!defined(__FP_FAST_FMA) && !defined(__FP_FAST_FMAF)) \
        || (!defined(__clang__) && defined(__STRICT_ANSI__)))
#define SMS_SMOOTHER_QUAD 1
typedef sms_real quad __attribute__((vector_size(4 * sizeof(sms_real))));
#define QUAD(a, b, c, d) ((quad){(a), (b), (c), (d)})
#ifdef SMS_USE_FLOAT
enum { RE0 = 0, RE1 = 1, IM0 = 2, IM1 = 3 };
#define QL(re0, im0, re1, im1) QUAD((re0), (re1), (im0), (im1))
#define SWAP_PAIRS(v) __builtin_shufflevector((v), (v), 2, 3, 0, 1)
/* Re lanes of a, Im lanes of b; the old copy's lanes of a, the young one's of b */
#define RE_OF_IM_OF(a, b) __builtin_shufflevector((a), (b), 0, 1, 6, 7)
#define OLD_OF_YOUNG_OF(a, b) __builtin_shufflevector((a), (b), 0, 4, 2, 6)
#else
enum { RE0 = 0, IM0 = 1, RE1 = 2, IM1 = 3 };
#define QL(re0, im0, re1, im1) QUAD((re0), (im0), (re1), (im1))
#define SWAP_PAIRS(v) __builtin_shufflevector((v), (v), 1, 0, 3, 2)
#define RE_OF_IM_OF(a, b) __builtin_shufflevector((a), (b), 0, 5, 2, 7)
#define OLD_OF_YOUNG_OF(a, b) __builtin_shufflevector((a), (b), 0, 1, 6, 7)
#endif
#endif
#define ADD(a, b) ((a) + (b))
#define SUB(a, b) ((a) - (b))
#define MUL(a, b) ((a) * (b))

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

/* The recursion's constants by lane (lane 0 old, lane 1 young: no tail). */
typedef struct constants {
    lanes pm1, q, pim, plo_re, plo_im, gain, tail_re, tail_im;
} constants;

/* Both copies' state by lane. */
typedef struct copies {
    lanes w_re, w_im, lo_re, lo_im, ref;
} copies;


/* With_tail 0: the constants of a copy that takes no x[n-M] (the young one, portable path). */
static inline constants constants_of(const sms_smoother *f, int with_tail)
{
    constants k;
    k.pm1 = LANES(f->pole_m1_re, f->pole_m1_re);
    k.q = LANES((sms_real)1 + f->pole_m1_re, (sms_real)1 + f->pole_m1_re);
    k.pim = LANES(f->pole_im, f->pole_im);
    k.plo_re = LANES(f->pole_lo_re, f->pole_lo_re);
    k.plo_im = LANES(f->pole_lo_im, f->pole_lo_im);
    k.gain = LANES(f->gain_re, f->gain_re);
    k.tail_re = LANES(with_tail ? f->tail_re : (sms_real)0, (sms_real)0);
    k.tail_im = LANES(with_tail ? f->tail_im : (sms_real)0, (sms_real)0);
    return k;
}

/* The copies' state: on the vector path both (one load per field: the two copies of a field
 * are adjacent), on the portable one copy c. */
#ifdef SMS_SMOOTHER_VARIANT_LOOPS
/* float: one 8-byte load, the pair repeated in lanes 2 and 3 as LANES() does (a bit copy
 * through a double vector, no arithmetic). Filling a zeroed 16-byte vector through memory
 * instead made a 16-byte load of store_pair()'s 8-byte store a sample earlier (a
 * store-forwarding stall per field: the float step took twice the double one), and building
 * it from the two floats takes four instructions instead of two. */
static inline lanes load_pair(const sms_real *pair)
{
#ifdef SMS_USE_FLOAT
    typedef double pair_bits __attribute__((vector_size(16)));
    double bits;
    memcpy(&bits, pair, sizeof bits);
    return (lanes)(pair_bits){bits, bits};
#else
    lanes v;
    memcpy(&v, pair, sizeof v);
    return v;
#endif
}

static inline void store_pair(sms_real *pair, lanes v)
{
    memcpy(pair, &v, 2u * sizeof(sms_real));
}

static inline copies copies_of(const sms_smoother *f, int c)
{
    copies s;
    (void)c;
    s.w_re = load_pair(f->w_re);
    s.w_im = load_pair(f->w_im);
    s.lo_re = load_pair(f->lo_re);
    s.lo_im = load_pair(f->lo_im);
    s.ref = load_pair(f->ref);
    return s;
}

/* A real pole leaves Im w and Im lo alone: only what the pole changes is written back. */
static inline void store_copies(sms_smoother *f, const copies *s, int c, int pole)
{
    (void)c;
    store_pair(f->w_re, s->w_re);
    store_pair(f->lo_re, s->lo_re);
    if (pole == POLE_COMPLEX) {
        store_pair(f->w_im, s->w_im);
        store_pair(f->lo_im, s->lo_im);
    }
}
#else
static inline copies copies_of(const sms_smoother *f, int c)
{
    copies s;
    s.w_re = f->w_re[c];
    s.w_im = f->w_im[c];
    s.lo_re = f->lo_re[c];
    s.lo_im = f->lo_im[c];
    s.ref = f->ref[c];
    return s;
}

static inline void store_copies(sms_smoother *f, const copies *s, int c, int pole)
{
    f->w_re[c] = s->w_re;
    f->lo_re[c] = s->lo_re;
    if (pole == POLE_COMPLEX) {
        f->w_im[c] = s->w_im;
        f->lo_im[c] = s->lo_im;
    }
}
#endif

/* One sample of the recursion in both lanes; the old lane's w + lo (Re w for a real pole, Im w
 * for a complex one). `oldest` is x[n-M] (for the young lane its reference stands in). */
/* The increment of w is split in two Fast2Sums, w + u then + (q - 1) w: the chain from w to
 * its next value is then one product and one sum (w + u does not wait for the product), not a
 * product and two sums, and both roundings are kept (the rounding of d = (q - 1) w + u, which a
 * single Fast2Sum of w + d leaves out, no longer occurs). lo rotates as q lo with q rounded:
 * lo is about an ulp of w, so the ulp of q that this loses is far below what lo tracks, and its
 * chain is one product and one sum as well. */
#ifdef SMS_SMOOTHER_VARIANT_LOOPS
/* The state's part of recur_real(): w + lo advanced by the input term u. */
static inline sms_real advance_real(const constants *k, copies *s, lanes u, int pole)
{
    lanes a, e1, p, w, e2;
    if (pole == POLE_UNIT) {
        FAST_TWO_SUM(w, e1, s->w_re, u);
        s->lo_re = ADD(s->lo_re, e1);
    } else {
        p = MUL(k->pm1, s->w_re);
        FAST_TWO_SUM(a, e1, s->w_re, u);
        FAST_TWO_SUM(w, e2, a, p);
        s->lo_re = ADD(MUL(k->q, s->lo_re), ADD(ADD(MUL(k->plo_re, s->w_re), e1), e2));
    }
    s->w_re = w;
    return LANE(s->w_re, 0) + LANE(s->lo_re, 0);
}

static inline sms_real recur_real(const constants *k, copies *s, sms_real x, sms_real oldest,
                                  int pole)
{
    /* POLE_UNIT (q = 1, t = -c): c (x - x[n-M]) in the old lane, c (x - ref) in the young one */
    const lanes u = pole == POLE_UNIT
                        ? MUL(k->gain, SUB(LANES(x, x), LANES(oldest, LANE(s->ref, 1))))
                        : ADD(MUL(k->gain, SUB(LANES(x, x), s->ref)),
                              MUL(k->tail_re, SUB(LANES(oldest, LANE(s->ref, 1)), s->ref)));
    return advance_real(k, s, u, pole);
}
#endif

/* The state's part of recur_complex(): w + lo advanced by the input term u_re + j u_im. */
static inline void advance_complex(const constants *k, copies *s, lanes u_re, lanes u_im)
{
    const lanes p_re = SUB(MUL(k->pm1, s->w_re), MUL(k->pim, s->w_im));
    const lanes p_im = ADD(MUL(k->pm1, s->w_im), MUL(k->pim, s->w_re));
    lanes a_re, a_im, s_re, s_im, e1_re, e1_im, e2_re, e2_im, r_re, r_im;
    FAST_TWO_SUM(a_re, e1_re, s->w_re, u_re);
    FAST_TWO_SUM(a_im, e1_im, s->w_im, u_im);
    FAST_TWO_SUM(s_re, e2_re, a_re, p_re);
    FAST_TWO_SUM(s_im, e2_im, a_im, p_im);
    r_re = ADD(ADD(SUB(MUL(k->plo_re, s->w_re), MUL(k->plo_im, s->w_im)), e1_re), e2_re);
    r_im = ADD(ADD(ADD(MUL(k->plo_re, s->w_im), MUL(k->plo_im, s->w_re)), e1_im), e2_im);
    {
        const lanes lo_re = ADD(SUB(MUL(k->q, s->lo_re), MUL(k->pim, s->lo_im)), r_re);
        s->lo_im = ADD(ADD(MUL(k->q, s->lo_im), MUL(k->pim, s->lo_re)), r_im);
        s->lo_re = lo_re;
    }
    s->w_re = s_re;
    s->w_im = s_im;
}

static inline sms_real recur_complex(const constants *k, copies *s, sms_real x, sms_real oldest,
                                     int real_out)
{
    const lanes o = SUB(LANES(oldest, LANE(s->ref, 1)), s->ref);
    advance_complex(k, s, ADD(MUL(k->gain, SUB(LANES(x, x), s->ref)), MUL(k->tail_re, o)),
                    MUL(k->tail_im, o));
    /* Tap 0 of the half-sine families is 0: x reaches Im w a sample later. 0 x (0, or NaN
     * for a non-finite x) gives the output the NaN that the convolution's 0 x[n] has. */
    return real_out ? LANE(s->w_re, 0) + LANE(s->lo_re, 0)
                    : LANE(s->w_im, 0) + LANE(s->lo_im, 0) + (sms_real)0 * x;
}

#ifdef SMS_SMOOTHER_QUAD
/* The recursion's constants in the four-lane layout {Re, Im} old copy, {Re, Im} young copy;
 * *_ims carry the sign the product with the swapped pair takes: {-b, +b} (Re: - b Im w,
 * Im: + b Re w). */
typedef struct quad_constants {
    quad ref, ref_young, gain, tail, pm1, pim_s, q, plo_re, plo_im_s;
} quad_constants;

static inline quad_constants quad_constants_of(const sms_smoother *f)
{
    quad_constants k;
    const sms_real r0 = f->ref[0], r1 = f->ref[1], q = (sms_real)1 + f->pole_m1_re;
    k.ref = QL(r0, r0, r1, r1);
    k.ref_young = QL(r1, r1, r1, r1);
    k.gain = QL(f->gain_re, f->gain_re, f->gain_re, f->gain_re);
    k.tail = QL(f->tail_re, f->tail_im, (sms_real)0, (sms_real)0);
    k.pm1 = QL(f->pole_m1_re, f->pole_m1_re, f->pole_m1_re, f->pole_m1_re);
    k.pim_s = QL(-f->pole_im, f->pole_im, -f->pole_im, f->pole_im);
    k.q = QL(q, q, q, q);
    k.plo_re = QL(f->pole_lo_re, f->pole_lo_re, f->pole_lo_re, f->pole_lo_re);
    k.plo_im_s = QL(-f->pole_lo_im, f->pole_lo_im, -f->pole_lo_im, f->pole_lo_im);
    return k;
}

/* recur_complex() (Im out) on w = {Re w, Im w} of the old copy then of the young one, lo the
 * same: the same operations lane by lane. u's Re lanes are c (x - ref) + t o, its Im lanes
 * t_im o (taken from t o alone: adding the Re lanes' c (x - ref) there would change -0 and
 * NaN). */
/* The state's part of recur_quad(): w, lo advanced by u = {u_re, u_im} of both copies; returns
 * Im (w + lo) of the old copy. */
static inline sms_real advance_quad(const quad_constants *k, quad *w, quad *lo, quad u)
{
    const quad ws = SWAP_PAIRS(*w), los = SWAP_PAIRS(*lo);
    const quad p = k->pm1 * *w + k->pim_s * ws;
    const quad r0 = k->plo_re * *w + k->plo_im_s * ws;
    const quad a = *w + u, e1 = u - (a - *w);   /* FAST_TWO_SUM() in quads */
    const quad s = a + p, e2 = p - (s - a);
    quad out;
    *lo = (k->q * *lo + k->pim_s * los) + ((r0 + e1) + e2);
    *w = s;
    out = s + *lo;
    return out[IM0];
}

static inline sms_real recur_quad(const quad_constants *k, quad *w, quad *lo, sms_real x,
                                  sms_real oldest)
{
    const quad xq = QUAD(x, x, x, x), oq = QUAD(oldest, oldest, oldest, oldest);
    const quad o = OLD_OF_YOUNG_OF(oq, k->ref_young) - k->ref;
    const quad to = k->tail * o;
    const quad u = RE_OF_IM_OF(k->gain * (xq - k->ref) + to, to);
    return advance_quad(k, w, lo, u) + (sms_real)0 * x;
}
#endif

/* The vector path runs each pole type's own recursion; the portable path runs the complex one
 * for every pole (smaller code): a real pole has Im q = 0 and Im c = Im t = Im q_lo = 0, so
 * Im w stays 0 and Re w follows the real recursion's general form (the extra terms add exact
 * zeros; the rectangular stage's c (x - x[n-M]) is the vector path's shortcut). */
static inline sms_real recur(const constants *k, copies *s, sms_real x, sms_real oldest, int pole)
{
#ifdef SMS_SMOOTHER_VARIANT_LOOPS
    return pole == POLE_COMPLEX ? recur_complex(k, s, x, oldest, 0)
                                : recur_real(k, s, x, oldest, pole);
#else
    return recur_complex(k, s, x, oldest, pole != POLE_COMPLEX);
#endif
}

/* The run of equal inputs up to x (at most L) and the output: x itself once the last L inputs
 * are equal, else y. */
static inline sms_real rest_exactly(size_t *run, size_t length, sms_real x, sms_real prev,
                                    sms_real y)
{
    const size_t r = x == prev ? *run + (*run < length) : 0u;
    *run = r;
    return r + 1u >= length ? x : y;
}

/* On the sample where head is 0 the old copy retires, the young one takes over and a new
 * young copy starts from zero referred to the latest input, x[n-1] (the input level, so that
 * the copy's rounding scales with how much the input varies, not with its offset; right after
 * a reset it is the rest, as every past input; a NaN/Inf must not become a reference). */
static void retire_old_copy(sms_smoother *f)
{
    const sms_real x = f->history[f->window - 1u];
    f->w_re[0] = f->w_re[1];
    f->w_im[0] = f->w_im[1];
    f->lo_re[0] = f->lo_re[1];
    f->lo_im[0] = f->lo_im[1];
    f->ref[0] = f->ref[1];
    f->w_re[1] = f->w_im[1] = (sms_real)0;
    f->lo_re[1] = f->lo_im[1] = (sms_real)0;
    f->ref[1] = x - x == (sms_real)0 ? x : f->rest;
}

/* The exact rest of a segment run as varied (segment()) when some input equalled the one
 * before it: the runs counted again from the inputs (now in the segment's ring slots, as out
 * may have overwritten in) and the outputs of the samples whose last L inputs are equal set to
 * the input, as rest_exactly() does sample by sample. Rare in a block; not inlined. */
#if defined(__GNUC__)
__attribute__((noinline, cold))
#endif
static void rest_after(sms_smoother *f, sms_real *out, size_t n, size_t run, sms_real prev)
{
    const sms_real *ring = f->history + f->head;
    size_t i;
    for (i = 0; i < n; ++i) {
        out[i] = rest_exactly(&run, f->length, ring[i], prev, out[i]);
        prev = ring[i];
    }
    f->run = run;
}

/* Samples head .. head + n - 1 (n <= M - head: no copy retires within) through the old copy
 * (lane 0) and, on the vector path, the young one (lane 1): the recursion, the direct taps
 * (on x[n-M+1], the ring slot after this one, ring[0] on the ring's last slot; or on x
 * itself) and x[n-M], the reference, the ring, the exact rest. Each instance loads only the
 * constants its variant reads. varied (L >= 2): the loop assumes that no input equals the one
 * before it (so run stays 0 and the output is never the input itself, what a block usually
 * is) and only notes whether one did, without a branch: then rest_after() does the runs'
 * bookkeeping afterwards, with the same outputs. The copies never depend on the runs. The
 * exact timing's tap on the ring's next slot wraps to ring[0] on the ring's last slot, the
 * segment's last sample at most: that sample is run after the loop, so the loop has no
 * per-sample test of it. */
SEGMENT_BODY void segment(sms_smoother *f, const sms_real *in, sms_real *out, size_t n,
                          int pole, int taps, int varied, int wide)
{
    const constants k = constants_of(f, 1);
    const sms_real corr0 = f->correction_gain[0], corr1 = f->correction_gain[1];
    const size_t length = f->length, last = f->window - f->head - 1u;
    /* the samples whose direct tap reads ring[i + 1] (exact timing): all but a last slot */
    const size_t body = taps == TAPS_EXACT && n > last ? last : n;
    sms_real *ring = f->history + f->head;
    const sms_real prev0 = f->history[(f->head == 0u ? f->window : f->head) - 1u];
    const size_t run0 = f->run;
    sms_real prev = prev0;
    copies s = copies_of(f, 0);
    const sms_real ref0 = LANE(s.ref, 0);
    size_t i, run = varied ? 0u : f->run;
    int repeated = 0;   /* varied: an input equal to the one before it was seen */
#ifdef SMS_SMOOTHER_VARIANT_LOOPS
    /* varied: x == prev noted lane-wise in a mask, one compare and one or a sample (the scalar
     * test and its unordered flag take five instructions, on the integer units); the same IEEE
     * equality. Not for a complex pole in double: that loop is bound by the vector adders
     * (30 additions of 91 instructions a sample on SSE2, 18 256-bit ones on AVX), which the
     * compare would take a slot of; measured slower there, faster for the others. */
    const int masked = pole != POLE_COMPLEX || sizeof(sms_real) < sizeof(double);
    lane_mask seen = {0};
    lanes prev_v = LANES(prev0, prev0);
#define NOTE_REPEAT(x)                                                                      \
    do {                                                                                    \
        if (masked)                                                                         \
            seen |= LANES((x), (x)) == prev_v, prev_v = LANES((x), (x));                    \
        else                                                                                \
            repeated |= (x) == prev;                                                        \
    } while (0)
#else
#define NOTE_REPEAT(x) (repeated |= (x) == prev)
#endif
#ifdef SMS_SMOOTHER_QUAD
    /* wide: a complex pole runs in the four-lane layout (a block: the state's layout changes
     * once per segment, not per sample) */
    const int in_quads = wide && pole == POLE_COMPLEX;
    const quad_constants qk = quad_constants_of(f);
    quad qw = QL(f->w_re[0], f->w_im[0], f->w_re[1], f->w_im[1]);
    quad qlo = QL(f->lo_re[0], f->lo_im[0], f->lo_re[1], f->lo_im[1]);
#define RECUR(x, oldest) \
    (in_quads ? recur_quad(&qk, &qw, &qlo, (x), (oldest)) : recur(&k, &s, (x), (oldest), pole))
#else
#define RECUR(x, oldest) ((void)wide, recur(&k, &s, (x), (oldest), pole))
#endif
    for (i = 0; i < body; ++i) {
        const sms_real x = in[i], oldest = ring[i];
        sms_real y = RECUR(x, oldest);
        if (taps != TAPS_NONE) {
            const sms_real first = taps == TAPS_BOUNDED ? x : ring[i + 1u];
            y += corr0 * (first - ref0) + corr1 * (oldest - ref0);
        }
        ring[i] = x;
        if (varied) {
            out[i] = y + ref0;
            NOTE_REPEAT(x);
        } else
            out[i] = rest_exactly(&run, length, x, prev, y + ref0);
        prev = x;
    }
    if (body < n) {   /* exact timing, the ring's last slot: the tap wraps to ring[0] */
        const sms_real x = in[i], oldest = ring[i], first = f->history[0];
        sms_real y = RECUR(x, oldest);
        y += corr0 * (first - ref0) + corr1 * (oldest - ref0);
        ring[i] = x;
        if (varied) {
            out[i] = y + ref0;
            NOTE_REPEAT(x);
        } else
            out[i] = rest_exactly(&run, length, x, prev, y + ref0);
    }
#undef RECUR
#undef NOTE_REPEAT
#ifdef SMS_SMOOTHER_VARIANT_LOOPS
    repeated |= seen[0] != 0;
#endif
#ifdef SMS_SMOOTHER_QUAD
    if (in_quads) {
        f->w_re[0] = qw[RE0], f->w_im[0] = qw[IM0], f->w_re[1] = qw[RE1], f->w_im[1] = qw[IM1];
        f->lo_re[0] = qlo[RE0], f->lo_im[0] = qlo[IM0];
        f->lo_re[1] = qlo[RE1], f->lo_im[1] = qlo[IM1];
    } else
#endif
    store_copies(f, &s, 0, pole);
    f->run = run;
    if (repeated)
        rest_after(f, out, n, run0, prev0);
}

#ifdef SMS_SMOOTHER_VARIANT_LOOPS
/* A block runs as varied (segment()) when L >= 2. (The portable path keeps one loop, which
 * counts the runs on every sample: smaller code.) */
#define block_varied(f) ((f)->length >= 2u)
#else
#define block_varied(f) 0
#endif

#ifndef SMS_SMOOTHER_VARIANT_LOOPS
/* The young copy alone over a segment (portable path): it only reads the input. */
static void young_segment(sms_smoother *f, const sms_real *in, size_t n, int pole)
{
    const constants k = constants_of(f, 0);
    copies s = copies_of(f, 1);
    size_t i;
    for (i = 0; i < n; ++i)
        (void)recur(&k, &s, in[i], f->ref[1], pole);
    store_copies(f, &s, 1, pole);
}
#endif

#ifdef SMS_SMOOTHER_VARIANT_LOOPS
#define SEGMENT(pole, taps)                                                                 \
    do {                                                                                    \
        if (varied)                                                                         \
            segment(f, in, out, n, pole, taps, 1, 1);                                       \
        else                                                                                \
            segment(f, in, out, n, pole, taps, 0, 1);                                       \
    } while (0)
#endif

/* Inlined into process() and step() where there are vectors (speed); one copy of the loops
 * on the portable path (firmware: code size). */
#ifdef SMS_SMOOTHER_VARIANT_LOOPS
#define SEGMENT_LINKAGE static inline
#else
#define SEGMENT_LINKAGE static
#endif

/* n samples from head, n <= M - head (the old copy retires first when head is 0); varied as
 * segment() (0 when not known). */
SEGMENT_LINKAGE void run_segment(sms_smoother *f, const sms_real *in, sms_real *out, size_t n,
                               int varied)
{
    if (f->head == 0u)
        retire_old_copy(f);
#ifdef SMS_SMOOTHER_VARIANT_LOOPS
    /* Constant flags per loop: the compiler drops the unused branches from each. */
    switch (f->variant) {
    case 3 * POLE_UNIT + TAPS_NONE: SEGMENT(POLE_UNIT, TAPS_NONE); break;
    case 3 * POLE_UNIT + TAPS_EXACT: SEGMENT(POLE_UNIT, TAPS_EXACT); break;
    case 3 * POLE_UNIT + TAPS_BOUNDED: SEGMENT(POLE_UNIT, TAPS_BOUNDED); break;
    case 3 * POLE_REAL + TAPS_NONE: SEGMENT(POLE_REAL, TAPS_NONE); break;
    case 3 * POLE_REAL + TAPS_EXACT: SEGMENT(POLE_REAL, TAPS_EXACT); break;
    case 3 * POLE_REAL + TAPS_BOUNDED: SEGMENT(POLE_REAL, TAPS_BOUNDED); break;
    case 3 * POLE_COMPLEX + TAPS_EXACT: SEGMENT(POLE_COMPLEX, TAPS_EXACT); break;
    default: SEGMENT(POLE_COMPLEX, TAPS_NONE); break;
    }
#else
    /* One loop for every variant (smaller code), the same arithmetic. */
    young_segment(f, in, n, (int)(f->variant / 3u));
    segment(f, in, out, n, (int)(f->variant / 3u), (int)(f->variant % 3u), varied, 0);
#endif
    f->head += n;
    if (f->head == f->window)
        f->head = 0;
}

void sms_smoother_process(sms_smoother *f, const sms_real *in, sms_real *out, size_t n)
{
    while (n > 0u) {
        size_t seg = f->window - f->head;
        if (n < seg)
            seg = n;
        run_segment(f, in, out, seg, block_varied(f));
        in += seg;
        out += seg;
        n -= seg;
    }
}

#ifdef SMS_SMOOTHER_VARIANT_LOOPS
/* One sample of one variant: the segment of length 1 unrolled, no loop, no look-ahead. */
#define STEP_CASE(pole, taps)                                                               \
    case 3 * (pole) + (taps): segment(f, x, x, 1u, pole, taps, 0, 0); break

void sms_smoother_step(sms_smoother *f, sms_real *x)
{
    if (f->head == 0u)
        retire_old_copy(f);
    switch (f->variant) {
    STEP_CASE(POLE_UNIT, TAPS_NONE);
    STEP_CASE(POLE_UNIT, TAPS_EXACT);
    STEP_CASE(POLE_UNIT, TAPS_BOUNDED);
    STEP_CASE(POLE_REAL, TAPS_NONE);
    STEP_CASE(POLE_REAL, TAPS_EXACT);
    STEP_CASE(POLE_REAL, TAPS_BOUNDED);
    STEP_CASE(POLE_COMPLEX, TAPS_EXACT);
    default: segment(f, x, x, 1u, POLE_COMPLEX, TAPS_NONE, 0, 0); break;
    }
    f->head = f->head + 1u == f->window ? 0u : f->head + 1u;
}
#else
void sms_smoother_step(sms_smoother *f, sms_real *x)
{
    run_segment(f, x, x, 1u, 0);
}
#endif

/* After n samples of a constant input x from now, the state depends on x alone (the
 * absorbed state: ring all x, both copies zero referred to x, run saturated at L) once both
 * copies in use have restarted under x (on samples where head is 0, M apart, each referred to
 * the input before it: the first such sample from the second one on) and run has counted L
 * equal inputs after the first; one more sample, as settle() computes the last one. */
uint64_t sms_smoother_settle_length(const sms_smoother *f)
{
    const uint64_t M = f->window, L = f->length;
    const uint64_t first = (M - f->head) % M + 1u;
    const uint64_t second = (first >= 2u ? first : first + M) + M;
    return (second > L + 1u ? second : L + 1u) + 1u;
}

void sms_smoother_advance(sms_smoother *f, uint64_t n)
{
    /* The roles swap on every retirement, but an absorbed state's two copies are equal. */
    f->head = (size_t)((f->head + n % f->window) % f->window);
}

sms_real sms_smoother_settle(sms_smoother *f, sms_real x, uint64_t n)
{
    size_t i;
    for (i = 0; i < f->window; ++i)
        f->history[i] = x;
    for (i = 0; i < 2u; ++i) {
        f->w_re[i] = f->w_im[i] = (sms_real)0;
        f->lo_re[i] = f->lo_im[i] = (sms_real)0;
        f->ref[i] = x;
    }
    f->run = f->length;
    sms_smoother_advance(f, n - 1u);
    sms_smoother_step(f, &x);
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
    dst[STATE_RUN] = (double)f->run;
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
    if (!is_index(src[STATE_RUN], (double)f->length))
        return SMS_ERR_STATE;
    if (!isfinite(src[STATE_REST]) || !fits_real_or_nonfinite(src[STATE_REST]))
        return SMS_ERR_STATE;
    if (!isfinite(src[STATE_REF0]) || !isfinite(src[STATE_REF1])
        || !fits_real_or_nonfinite(src[STATE_REF0]) || !fits_real_or_nonfinite(src[STATE_REF1]))
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
    f->run = (size_t)src[STATE_RUN];
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
