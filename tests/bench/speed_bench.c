/* SPDX-License-Identifier: Apache-2.0 */
/* Per-sample cost of every filter next to the plain recursion of the same filter, measured in
 * one run: contenders interleaved round by round, CPU time, median over the rounds. A
 * retunable stage (tunable.h) and a scheduled shaper (scheduled.h) next to the fixed stage.
 *
 * The plain references are the textbook realisations, in sms_real like the library:
 * - rectangular: running sum s += x[n] - x[n-N], y = s/N (drifts: its rounding never leaves);
 * - harmonic / damped harmonic: the second-order form of Biagiotti and Melchiorri's smoother,
 *   y[n] = 2 r cos(pi/N) y[n-1] - r^2 y[n-2] + K (x[n-1] + r^N x[n-N-1]) (its rounding is
 *   amplified ~N^2 times and accumulates);
 * - exponential: y[n] = r y[n-1] + g (x[n] - r^N x[n-N]);
 * - notch: the direct-form-I biquad y = b0 x + b1 x1 + b2 x2 - a1 y1 - a2 y2;
 * - shaper: a sparse FIR sum_k g_k x[n - d_k] over a ring, same taps as the library's;
 * - direct-form FIR: sum_i h[i] x[n-i] over all L taps (what the O(1) smoothers replace).
 * Each row is measured twice: on blocks (sms_stage_process against the plain loop) and one
 * call per sample ("<path> step": sms_stage_step against the plain form's one-sample call).
 *
 * Trajectory paths: the online generator's cost per sample (cruise, no re-plan) and the
 * kinematic design's cost in each regime of a velocity/acceleration/jerk move.
 *
 * Output: a readable table, and one machine-readable line per figure,
 *   "speed<TAB>path<TAB>contender<TAB>ns_per_sample" or "design<TAB>regime<TAB>ns_per_design",
 * read by python -m smoothshaper.bench.
 * Usage: speed_bench [--quick]   (--quick: a few short rounds, a smoke test of the harness). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "smoothshaper/smoothshaper.h"
#include "cpu_time.h"

#define PI 3.14159265358979323846
#define BLOCK 4096
#define MAX_RING 8192
#define MAX_CONTENDERS 4
#define MAX_ROUNDS 64

static sms_real input[BLOCK], output[BLOCK];
static sms_memory_cell stage_memory[MAX_RING];

/* ---- plain references ---------------------------------------------------------------- */

typedef struct plain {
    size_t n, head, len;
    sms_real ring[MAX_RING];
    sms_real a1, a2, b0, b1, b2, g, tail, y1, y2, x1, x2, s;
    size_t n_taps, delay[64];
    sms_real gain[64];
    double taps[MAX_RING];
    sms_real gain_reversed[MAX_RING];
} plain;

static plain plain_state;

static void plain_running_sum(plain *p, const sms_real *in, sms_real *out, size_t n)
{
    size_t i, head = p->head;
    sms_real s = p->s, *ring = p->ring;
    const sms_real g = p->g;
    const size_t len = p->len;
    for (i = 0; i < n; ++i) {
        s += in[i] - ring[head];
        ring[head] = in[i];
        head = head + 1 == len ? 0 : head + 1;
        out[i] = s * g;
    }
    p->s = s;
    p->head = head;
}

/* y = a1 y1 - a2 y2 + g (x[n-1] + tail x[n-N-1]); ring of N+1 inputs. */
static void plain_resonator(plain *p, const sms_real *in, sms_real *out, size_t n)
{
    size_t i, head = p->head;
    sms_real y1 = p->y1, y2 = p->y2, x1 = p->x1, *ring = p->ring;
    const sms_real a1 = p->a1, a2 = p->a2, g = p->g, tail = p->tail;
    const size_t len = p->len;
    for (i = 0; i < n; ++i) {
        sms_real oldest = ring[head], y;
        ring[head] = in[i];
        head = head + 1 == len ? 0 : head + 1;
        y = a1 * y1 - a2 * y2 + g * (x1 + tail * oldest);
        x1 = in[i];
        y2 = y1;
        y1 = y;
        out[i] = y;
    }
    p->y1 = y1;
    p->y2 = y2;
    p->x1 = x1;
    p->head = head;
}

static void plain_first_order(plain *p, const sms_real *in, sms_real *out, size_t n)
{
    size_t i, head = p->head;
    sms_real y = p->y1, *ring = p->ring;
    const sms_real a1 = p->a1, g = p->g, tail = p->tail;
    const size_t len = p->len;
    for (i = 0; i < n; ++i) {
        sms_real oldest = ring[head];
        ring[head] = in[i];
        head = head + 1 == len ? 0 : head + 1;
        y = a1 * y + g * (in[i] + tail * oldest);
        out[i] = y;
    }
    p->y1 = y;
    p->head = head;
}

static void plain_biquad(plain *p, const sms_real *in, sms_real *out, size_t n)
{
    size_t i;
    sms_real x1 = p->x1, x2 = p->x2, y1 = p->y1, y2 = p->y2;
    const sms_real b0 = p->b0, b1 = p->b1, b2 = p->b2, a1 = p->a1, a2 = p->a2;
    for (i = 0; i < n; ++i) {
        sms_real y = b0 * in[i] + b1 * x1 + b2 * x2 - a1 * y1 - a2 * y2;
        x2 = x1;
        x1 = in[i];
        y2 = y1;
        y1 = y;
        out[i] = y;
    }
    p->x1 = x1;
    p->x2 = x2;
    p->y1 = y1;
    p->y2 = y2;
}

static void plain_sparse_fir(plain *p, const sms_real *in, sms_real *out, size_t n)
{
    size_t i, k, head = p->head;
    const size_t len = p->len, n_taps = p->n_taps;
    sms_real *ring = p->ring;
    for (i = 0; i < n; ++i) {
        sms_real acc = 0;
        ring[head] = in[i];
        for (k = 0; k < n_taps; ++k) {
            size_t d = p->delay[k];
            acc += p->gain[k] * ring[head >= d ? head - d : head + len - d];
        }
        head = head + 1 == len ? 0 : head + 1;
        out[i] = acc;
    }
    p->head = head;
}

/* Direct form over a doubled ring (each input stored twice, L apart), so the L taps meet
 * L contiguous samples: taps reversed, one dot product per output. */
static void plain_direct_fir(plain *p, const sms_real *in, sms_real *out, size_t n)
{
    size_t i, k, head = p->head;
    const size_t len = p->len;
    sms_real *ring = p->ring;
    for (i = 0; i < n; ++i) {
        const sms_real *window;
        sms_real acc = 0;
        ring[head] = ring[head + len] = in[i];
        head = head + 1 == len ? 0 : head + 1;
        window = ring + head; /* oldest .. newest */
        for (k = 0; k < len; ++k)
            acc += p->gain_reversed[k] * window[k];
        out[i] = acc;
    }
    p->head = head;
}

/* The same plain forms called once per sample, as firmware calls a filter from its sample
 * interrupt: state in the struct, one call (never inlined into the caller) per sample. These
 * are what the library's step functions are measured against. */
#if defined(__GNUC__)
#define NOINLINE __attribute__((noinline))
#else
#define NOINLINE
#endif

static NOINLINE void plain_running_sum_step(plain *p, sms_real *x)
{
    const sms_real v = *x;
    p->s += v - p->ring[p->head];
    p->ring[p->head] = v;
    p->head = p->head + 1 == p->len ? 0 : p->head + 1;
    *x = p->s * p->g;
}

static NOINLINE void plain_resonator_step(plain *p, sms_real *x)
{
    const sms_real v = *x, oldest = p->ring[p->head];
    sms_real y;
    p->ring[p->head] = v;
    p->head = p->head + 1 == p->len ? 0 : p->head + 1;
    y = p->a1 * p->y1 - p->a2 * p->y2 + p->g * (p->x1 + p->tail * oldest);
    p->x1 = v;
    p->y2 = p->y1;
    p->y1 = y;
    *x = y;
}

static NOINLINE void plain_first_order_step(plain *p, sms_real *x)
{
    const sms_real v = *x, oldest = p->ring[p->head];
    p->ring[p->head] = v;
    p->head = p->head + 1 == p->len ? 0 : p->head + 1;
    p->y1 = p->a1 * p->y1 + p->g * (v + p->tail * oldest);
    *x = p->y1;
}

static NOINLINE void plain_biquad_step(plain *p, sms_real *x)
{
    const sms_real v = *x;
    const sms_real y = p->b0 * v + p->b1 * p->x1 + p->b2 * p->x2 - p->a1 * p->y1 - p->a2 * p->y2;
    p->x2 = p->x1;
    p->x1 = v;
    p->y2 = p->y1;
    p->y1 = y;
    *x = y;
}

static NOINLINE void plain_sparse_fir_step(plain *p, sms_real *x)
{
    const size_t len = p->len, n_taps = p->n_taps, head = p->head;
    sms_real acc = 0;
    size_t k;
    p->ring[head] = *x;
    for (k = 0; k < n_taps; ++k) {
        const size_t d = p->delay[k];
        acc += p->gain[k] * p->ring[head >= d ? head - d : head + len - d];
    }
    p->head = head + 1 == len ? 0 : head + 1;
    *x = acc;
}

/* ---- contenders ---------------------------------------------------------------------- */

typedef struct contender {
    const char *name;
    void (*plain_run)(plain *, const sms_real *, sms_real *, size_t);
    void (*plain_step)(plain *, sms_real *);
    sms_stage *stage;
    sms_tunable *tunable;              /* a retunable stage instead of stage */
    const sms_stage_config *alt;       /* with alt: retuned to alt[0], alt[1], ... in turn as
                                          soon as each switch ends (always switching) */
    sms_scheduled *scheduled;          /* a scheduled shaper, driven by `schedule` */
} contender;

/* 0: each contender filters a block in one call (process); 1: one call per sample (step). */
static int per_sample;

static double schedule[BLOCK];

static unsigned next_alt;

/* A tunable that keeps switching: filtered in pieces, retuned whenever its switch has ended. */
static void run_switching(const contender *c, size_t n)
{
    size_t done = 0;
    while (done < n) {
        size_t m = n - done;
        if (!sms_tunable_switching(c->tunable)) {
            next_alt ^= 1u;
            (void)sms_tunable_retune(c->tunable, &c->alt[next_alt]);
        }
        if (sms_tunable_switching(c->tunable) && c->tunable->fade < (uint64_t)m)
            m = (size_t)c->tunable->fade;
        sms_tunable_process(c->tunable, input + done, output + done, m);
        done += m;
    }
}

static void run(const contender *c, size_t n)
{
    size_t i;
    if (per_sample) {
        for (i = 0; i < n; ++i) {
            sms_real x = input[i];
            if (c->stage != NULL)
                sms_stage_step(c->stage, &x);
            else
                c->plain_step(&plain_state, &x);
            output[i] = x;
        }
    } else if (c->scheduled != NULL) {
        sms_scheduled_process(c->scheduled, input, schedule, output, n);
    } else if (c->tunable != NULL && c->alt != NULL) {
        run_switching(c, n);
    } else if (c->tunable != NULL) {
        sms_tunable_process(c->tunable, input, output, n);
    } else if (c->stage != NULL) {
        sms_stage_process(c->stage, input, output, n);
    } else {
        c->plain_run(&plain_state, input, output, n);
    }
}

static int compare_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Median ns/sample of each contender; rounds interleave the contenders, rotating who goes
 * first, each timed over `blocks` blocks of BLOCK samples. */
static void measure(const char *path, contender *c, size_t n_c, int rounds, int blocks)
{
    static double samples[MAX_CONTENDERS][MAX_ROUNDS];
    size_t j;
    int r, b;
    for (j = 0; j < n_c; ++j)
        run(&c[j], BLOCK); /* warm caches and branch predictors */
    for (r = 0; r < rounds; ++r) {
        for (j = 0; j < n_c; ++j) {
            const contender *cj = &c[(j + (size_t)r) % n_c];
            double t0 = cpu_seconds();
            for (b = 0; b < blocks; ++b)
                run(cj, BLOCK);
            samples[(j + (size_t)r) % n_c][r] = 1e9 * (cpu_seconds() - t0) / ((double)blocks * BLOCK);
        }
    }
    for (j = 0; j < n_c; ++j) {
        double median;
        qsort(samples[j], (size_t)rounds, sizeof(double), compare_double);
        median = samples[j][rounds / 2];
        printf("speed\t%s\t%s\t%.4f\n", path, c[j].name, median);
    }
    for (j = 1; j < n_c; ++j)
        printf("  %-22s %-14s / %-16s %.2fx\n", path, c[0].name, c[j].name,
               samples[0][rounds / 2] / samples[j][rounds / 2]);
}

/* The block row, then the same contenders one call per sample ("<path> step"). */
static void measure_both(const char *path, contender *c, size_t n_c, int rounds, int blocks)
{
    char step_path[64];
    measure(path, c, n_c, rounds, blocks);
    snprintf(step_path, sizeof step_path, "%s step", path);
    per_sample = 1;
    measure(step_path, c, n_c, rounds, blocks);
    per_sample = 0;
}

static sms_stage stage;

static int init_stage(const sms_stage_config *c, double Ts)
{
    sms_status st = sms_stage_init(&stage, c, Ts, stage_memory, MAX_RING);
    if (st != SMS_OK) {
        printf("init failed: %s\n", sms_status_string(st));
        return 0;
    }
    return 1;
}

static void reset_plain(size_t len)
{
    memset(&plain_state, 0, sizeof plain_state);
    plain_state.len = len;
}

static void smoother_row(const char *path, sms_kind kind, double T, double sigma, double Ts,
                         int rounds, int blocks, int with_direct)
{
    sms_stage_config c = sms_stage_config_default(kind);
    contender list[3];
    size_t n_c = 0, N;
    double r, cs;
    memset(list, 0, sizeof list);
    c.T = T;
    c.sigma = sigma;
    c.timing = SMS_TIMING_PAPER;
    if (!init_stage(&c, Ts))
        return;
    N = sms_stage_length(&stage);
    r = exp(sigma * Ts);
    cs = cos(PI / (double)N);
    list[n_c].name = "smoothshaper";
    list[n_c].stage = &stage;
    list[n_c].plain_step = NULL;
    list[n_c++].plain_run = NULL;
    list[n_c].name = "plain recursion";
    list[n_c].stage = NULL;
    switch (kind) {
    case SMS_RECTANGULAR:
        reset_plain(N);
        plain_state.g = (sms_real)(1.0 / (double)N);
        list[n_c].plain_step = plain_running_sum_step;
        list[n_c++].plain_run = plain_running_sum;
        break;
    case SMS_EXPONENTIAL:
        reset_plain(N);
        plain_state.a1 = (sms_real)r;
        plain_state.g = (sms_real)((1.0 - r) / (1.0 - pow(r, (double)N)));
        plain_state.tail = (sms_real)(-pow(r, (double)N));
        list[n_c].plain_step = plain_first_order_step;
        list[n_c++].plain_run = plain_first_order;
        break;
    default: /* harmonic families: the seed's S(z) / S_sigma(z) */
        reset_plain(N + 1);
        plain_state.a1 = (sms_real)(2.0 * r * cs);
        plain_state.a2 = (sms_real)(r * r);
        plain_state.g = (sms_real)((1.0 - 2.0 * r * cs + r * r) / (1.0 + pow(r, (double)N)));
        plain_state.tail = (sms_real)pow(r, (double)N);
        list[n_c].plain_step = plain_resonator_step;
        list[n_c++].plain_run = plain_resonator;
        break;
    }
    (void)with_direct;
    measure_both(path, list, n_c, rounds, blocks);
}

static void direct_fir_row(const char *path, sms_kind kind, double T, double Ts, int rounds, int blocks)
{
    sms_stage_config c = sms_stage_config_default(kind);
    contender list[2];
    size_t i;
    memset(list, 0, sizeof list);
    c.T = T;
    c.timing = SMS_TIMING_PAPER;
    if (!init_stage(&c, Ts))
        return;
    reset_plain(sms_stage_length(&stage));
    (void)sms_smoother_taps(&c, Ts, plain_state.taps, MAX_RING);
    for (i = 0; i < plain_state.len; ++i)
        plain_state.gain_reversed[i] = (sms_real)plain_state.taps[plain_state.len - 1 - i];
    list[0].name = "smoothshaper";
    list[0].stage = &stage;
    list[0].plain_run = NULL;
    list[0].plain_step = NULL;
    list[1].name = "direct-form FIR";
    list[1].stage = NULL;
    list[1].plain_run = plain_direct_fir;
    list[1].plain_step = NULL;
    measure(path, list, 2, rounds, blocks);
}

static void notch_row(const char *path, double wn, double Ts, int rounds, int blocks)
{
    sms_stage_config c = sms_stage_config_default(SMS_NOTCH_TUSTIN);
    contender list[2];
    double t, a0, xi1, xi2;
    memset(list, 0, sizeof list);
    c.wn = wn;
    c.zeta = 0.0;
    c.notch_pole_zeta = 0.7;
    if (!init_stage(&c, Ts))
        return;
    reset_plain(1);
    t = tan(0.5 * wn * Ts);
    xi1 = c.zeta;
    xi2 = c.notch_pole_zeta;
    a0 = 1.0 + 2.0 * xi2 * t + t * t;
    plain_state.b0 = (sms_real)((1.0 + 2.0 * xi1 * t + t * t) / a0);
    plain_state.b1 = (sms_real)(2.0 * (t * t - 1.0) / a0);
    plain_state.b2 = (sms_real)((1.0 - 2.0 * xi1 * t + t * t) / a0);
    plain_state.a1 = plain_state.b1;
    plain_state.a2 = (sms_real)((1.0 - 2.0 * xi2 * t + t * t) / a0);
    list[0].name = "smoothshaper";
    list[0].stage = &stage;
    list[0].plain_run = NULL;
    list[0].plain_step = NULL;
    list[1].name = "plain biquad";
    list[1].stage = NULL;
    list[1].plain_run = plain_biquad;
    list[1].plain_step = plain_biquad_step;
    measure_both(path, list, 2, rounds, blocks);
}

static void shaper_row(const char *path, sms_kind kind, double wn, double zeta, double Ts,
                       int rounds, int blocks)
{
    sms_stage_config c = sms_stage_config_default(kind);
    contender list[2];
    size_t L, i;
    memset(list, 0, sizeof list);
    c.wn = wn;
    c.zeta = zeta;
    if (!init_stage(&c, Ts))
        return;
    L = sms_stage_length(&stage);
    reset_plain(L);
    (void)sms_shaper_taps(&c, Ts, plain_state.taps, MAX_RING);
    for (i = 0; i < L; ++i) {
        if (plain_state.taps[i] != 0.0) {
            plain_state.delay[plain_state.n_taps] = i;
            plain_state.gain[plain_state.n_taps++] = (sms_real)plain_state.taps[i];
        }
    }
    list[0].name = "smoothshaper";
    list[0].stage = &stage;
    list[0].plain_run = NULL;
    list[0].plain_step = NULL;
    list[1].name = "sparse FIR";
    list[1].stage = NULL;
    list[1].plain_run = plain_sparse_fir;
    list[1].plain_step = plain_sparse_fir_step;
    measure_both(path, list, 2, rounds, blocks);
}

static sms_tunable tunable;
static sms_memory_cell tunable_memory[2 * MAX_RING];

/* A fixed stage of config a, the same in a retunable stage (not switching), and a retunable
 * stage switching between a and b all the time (each retune as soon as the previous switch
 * has ended: its design, the zeroing of its delay line and both filters running). */
static void tunable_row(const char *path, const sms_stage_config *ab, double Ts, int rounds,
                        int blocks)
{
    static sms_tunable switching;
    static sms_memory_cell switching_memory[2 * MAX_RING];
    contender list[3];
    size_t cells = 0;
    memset(list, 0, sizeof list);
    if (!init_stage(&ab[0], Ts) || sms_tunable_slot_cells(ab, 2, Ts, &cells) != SMS_OK
        || sms_tunable_init(&tunable, &ab[0], Ts, cells, tunable_memory, 2 * MAX_RING) != SMS_OK
        || sms_tunable_init(&switching, &ab[0], Ts, cells, switching_memory, 2 * MAX_RING)
               != SMS_OK) {
        printf("tunable init failed\n");
        return;
    }
    list[0].name = "fixed";
    list[0].stage = &stage;
    list[1].name = "tunable";
    list[1].tunable = &tunable;
    list[2].name = "tunable, switching";
    list[2].tunable = &switching;
    list[2].alt = ab;
    measure(path, list, 3, rounds, blocks);
}

/* A fixed ZVD at the table's middle mode, and the scheduled ZVD over a 9-point table from
 * 0.8 to 1.2 of that mode, its schedule sweeping the table (every sample, and every 16). */
static void scheduled_row(const char *path, double wn, double zeta, double Ts, int rounds,
                          int blocks)
{
    static sms_scheduled every1, every16;
    static sms_real ring1[MAX_RING], ring16[MAX_RING];
    sms_schedule_point points[9];
    sms_scheduled_config sc;
    sms_stage_config c = sms_stage_config_default(SMS_SHAPER_ZVD);
    contender list[3];
    size_t i;
    memset(list, 0, sizeof list);
    for (i = 0; i < 9; ++i) {
        points[i].value = (double)i;
        points[i].wn = wn * (0.8 + 0.05 * (double)i);
        points[i].zeta = zeta;
    }
    for (i = 0; i < BLOCK; ++i)
        schedule[i] = 4.0 + 4.0 * sin(2.0 * PI * (double)i / (double)BLOCK);
    sc.kind = SMS_SHAPER_ZVD;
    sc.order = 2;
    sc.points = points;
    sc.n_points = 9;
    sc.update_every = 1;
    c.wn = wn;
    c.zeta = zeta;
    if (!init_stage(&c, Ts) || sms_scheduled_init(&every1, &sc, Ts, ring1, MAX_RING) != SMS_OK) {
        printf("scheduled init failed\n");
        return;
    }
    sc.update_every = 16;
    (void)sms_scheduled_init(&every16, &sc, Ts, ring16, MAX_RING);
    list[0].name = "fixed";
    list[0].stage = &stage;
    list[1].name = "scheduled, every sample";
    list[1].scheduled = &every1;
    list[2].name = "scheduled, every 16";
    list[2].scheduled = &every16;
    measure(path, list, 3, rounds, blocks);
}

static sms_real generator_table[1 << 16];

static void generator_row(int rounds)
{
    sms_generator g;
    sms_generator_config c;
    sms_real out[4];
    size_t need, k;
    double samples[MAX_ROUNDS];
    int r;
    volatile sms_real sink = 0;
    c.vmax = 250.0;
    c.amax = 5000.0;
    c.jmax = 200000.0;
    c.profile = SMS_PROFILE_POLYNOMIAL;
    c.wn = 0.0;
    c.zeta = 0.0;
    c.vmin = c.amin = 0.0; /* symmetric */
    c.qmin = c.qmax = 0.0; /* no position limits */
    if (sms_generator_buffer_size(&c, 1e-4, &need) != SMS_OK || need > sizeof generator_table / sizeof generator_table[0]
        || sms_generator_init(&g, &c, 1e-4, generator_table, need) != SMS_OK) {
        printf("generator init failed\n");
        return;
    }
    for (r = 0; r < rounds; ++r) {
        double t0 = cpu_seconds();
        for (k = 0; k < 16u * BLOCK; ++k) {
            sms_generator_step(&g, (sms_real)1e6, out); /* one long move: cruise, no re-plan */
            sink += out[0];
        }
        samples[r] = 1e9 * (cpu_seconds() - t0) / (16.0 * BLOCK);
    }
    qsort(samples, (size_t)rounds, sizeof(double), compare_double);
    printf("speed\tgenerator\tsmoothshaper\t%.4f\n", samples[rounds / 2]);
}

/* Kinematic design of a rest-to-rest move h within {vmax, amax, jmax} in each regime. */
static void design_rows(int rounds)
{
    static const struct { const char *regime; double h, limits[3]; } cases[] = {
        {"vmax reached", 1.0, {0.5, 5.0, 100.0}},
        {"amax reached, vmax not", 0.1, {2.0, 5.0, 100.0}},
        {"jmax only", 0.001, {2.0, 5.0, 100.0}},
    };
    size_t c;
    for (c = 0; c < sizeof cases / sizeof cases[0]; ++c) {
        double samples[MAX_ROUNDS], T[3];
        size_t count, k;
        int r;
        volatile double sink = 0.0;
        for (r = 0; r < rounds; ++r) {
            double t0 = cpu_seconds();
            for (k = 0; k < 20000u; ++k) {
                /* a slightly different move each time: nothing cached */
                double h = cases[c].h * (1.0 + 1e-9 * (double)(k & 15u));
                (void)sms_kinematic_design(h, cases[c].limits, 3, SMS_PROFILE_POLYNOMIAL, 0.0,
                                           0.0, 0.0, T, 3, &count); /* continuous, as ruckig */
                sink += T[0];
            }
            samples[r] = 1e9 * (cpu_seconds() - t0) / 20000.0;
        }
        qsort(samples, (size_t)rounds, sizeof(double), compare_double);
        printf("design\t%s\t%.2f\n", cases[c].regime, samples[rounds / 2]);
    }
}

int main(int argc, char **argv)
{
    const int quick = argc > 1 && strcmp(argv[1], "--quick") == 0;
    const int rounds = quick ? 3 : 31, blocks = quick ? 1 : 24;
    const double Ts = 1e-3, T = 0.2, sigma = -10.0;
    const double wn = 2.0 * PI * 40.0, zeta = 0.05;
    unsigned long s = 12345u;
    size_t i;
    for (i = 0; i < BLOCK; ++i) {
        s = s * 6364136223846793005u + 1442695040888963407u;
        input[i] = (sms_real)(1e3 + ((double)(s >> 11) / 9007199254740992.0 * 2.0 - 1.0));
    }
    printf("precision\t%s\n", sizeof(sms_real) == sizeof(float) ? "float" : "double");
    printf("# ns/sample, median of %d rounds of %d x %d samples, CPU time; N = T/Ts = %.0f\n",
           rounds, blocks, BLOCK, T / Ts);
    smoother_row("rectangular", SMS_RECTANGULAR, T, 0.0, Ts, rounds, blocks, 0);
    smoother_row("harmonic", SMS_HARMONIC, T, 0.0, Ts, rounds, blocks, 0);
    smoother_row("damped harmonic", SMS_DAMPED_HARMONIC, T, sigma, Ts, rounds, blocks, 0);
    smoother_row("exponential", SMS_EXPONENTIAL, T, sigma, Ts, rounds, blocks, 0);
    direct_fir_row("rectangular (FIR)", SMS_RECTANGULAR, T, Ts, rounds, quick ? 1 : 2);
    notch_row("notch", wn, Ts, rounds, blocks);
    shaper_row("ZV shaper", SMS_SHAPER_ZV, wn, zeta, Ts, rounds, blocks);
    shaper_row("ZVD shaper", SMS_SHAPER_ZVD, wn, zeta, Ts, rounds, blocks);
    shaper_row("EI shaper", SMS_SHAPER_EI, wn, zeta, Ts, rounds, blocks);
    {
        sms_stage_config ab[2];
        ab[0] = sms_stage_config_default(SMS_SHAPER_ZVD);
        ab[0].wn = wn;
        ab[0].zeta = zeta;
        ab[1] = ab[0];
        ab[1].wn = 0.8 * wn;
        tunable_row("ZVD shaper, retunable", ab, Ts, rounds, blocks);
        ab[0] = sms_stage_config_default(SMS_RECTANGULAR);
        ab[0].T = T;
        ab[0].timing = SMS_TIMING_PAPER;
        ab[1] = ab[0];
        ab[1].T = 0.8 * T;
        tunable_row("rectangular, retunable", ab, Ts, rounds, blocks);
    }
    scheduled_row("ZVD shaper, scheduled", wn, zeta, Ts, rounds, blocks);
    generator_row(rounds);
    design_rows(rounds);
    return 0;
}
