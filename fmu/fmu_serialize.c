/* SPDX-License-Identifier: Apache-2.0 */
/*
 * The serialised FMU state: a versioned, portable byte format with no pointers.
 *
 * Layout (every integer and double little-endian, doubles as IEEE-754 binary64):
 *   "SMSF"                      magic (4 bytes)
 *   u32 version                 FMU_STATE_VERSION
 *   u32 G, G bytes              instantiation token (guid) of the model that wrote it
 *   u32 R                       bytes of a signal real (sms_real) in the binary that wrote it
 *   u32 phase, f64 t0, f64 t, u32 ticks_lo, u32 ticks_hi, f64 since_tick, u32 steady_lo,
 *   u32 steady_hi               the glue's clock
 *   u32 nR, nR x (u32 vr, f64)  every Real input and parameter (fmu_model_settable order)
 *   u32 nI, nI x (u32 vr, i32)  every Integer/Enumeration parameter
 *   u32 nS, 0-7 zero bytes, nS x f64
 *                               the model's dynamic state (outputs, filter state) if built; the
 *                               zero bytes put the doubles at an offset that is a multiple of 8
 *   u64 checksum                XXH64 (seed 0; Y. Collet's xxHash, 64-bit variant) of all the
 *                               bytes before it
 * Reading re-validates the parameters and rebuilds the filters through the model's own
 * fmu_model_plan() / fmu_model_build(), then loads the dynamic state. A state read for a built
 * instance whose settable values it holds bit for bit (the instance's values image compared
 * with memcmp between the inputs, fmu_values_image) copies the instance's built filters
 * instead, reading only the inputs; everything after the values is checked alike: a blob from another model,
 * version or precision, truncated or altered, or whose clock disagrees with its tick count
 * (t != t0 + ticks*Ts + since_tick beyond the rounding of an accumulating host) is refused with
 * a message, so a crafted state can never make the next doStep run a huge number of ticks; so is
 * a dynamic state with a NaN or an infinity, or one beyond what the parameters' ranges allow
 * (the model's fmu_model_load_state()), which would reach the outputs.
 *
 * Speed: the dynamic part is nearly all of a large state (delay lines of up to FMU_MAX_REALS),
 * so on a host whose doubles are stored as the format stores them (little-endian binary64,
 * checked at run time) it is written and read with the model's own save/load, in place when the
 * importer's buffer puts it at an address aligned for double, else through one scratch copy;
 * any other host converts value by value. XXH64 reads 8 bytes per step in four independent
 * lanes: about 0.1 ns per byte here, against 0.34 for the table-driven CRC-32 the format used
 * up to version 4 (tests/fmu/bench_fmu_state_size.c prints the cost of every call).
 */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "fmu_instance.h"
#include "fmu_serialize.h"

#define FMU_STATE_VERSION 5u   /* 3: the filter states start with their configuration identity;
                                  4: so do the generators' states;
                                  5: XXH64 checksum, dynamic part aligned to 8 bytes */
#define MAX_SETTABLE 1024u

/* Does this host store a double as the format does (IEEE binary64, little-endian)? Decided by
 * the bytes of 1 + 2^-52 (portable C99: no byte-order macros). */
static int native_doubles(void)
{
    static const unsigned char expected[8] = { 1, 0, 0, 0, 0, 0, 0xf0, 0x3f };
    const double probe = 1.0 + DBL_EPSILON;
    unsigned char bytes[8];
    if (sizeof(double) != 8)
        return 0;
    memcpy(bytes, &probe, 8);
    return memcmp(bytes, expected, 8) == 0;
}

/* ---------------------------------------------------------------- XXH64 */

#define P1 0x9E3779B185EBCA87u
#define P2 0xC2B2AE3D27D4EB4Fu
#define P3 0x165667B19E3779F9u
#define P4 0x85EBCA77C2B2AE63u
#define P5 0x27D4EB2F165667C5u

static uint64_t rotl64(uint64_t x, unsigned r) { return (x << r) | (x >> (64u - r)); }

static uint64_t le64(const unsigned char *p)
{
    return (uint64_t)p[0] | (uint64_t)p[1] << 8 | (uint64_t)p[2] << 16 | (uint64_t)p[3] << 24
           | (uint64_t)p[4] << 32 | (uint64_t)p[5] << 40 | (uint64_t)p[6] << 48
           | (uint64_t)p[7] << 56;
}

static uint64_t xxh_round(uint64_t acc, uint64_t lane)
{
    return rotl64(acc + lane * P2, 31) * P1;
}

static uint64_t xxh_merge(uint64_t h, uint64_t acc)
{
    return (h ^ xxh_round(0, acc)) * P1 + P4;
}

/* XXH64 of p[0..n-1] with seed 0: the reference algorithm (xxhash.h and doc/xxhash_spec.md of
 * Y. Collet's xxHash project): 32-byte stripes into four lanes, the lanes merged, then the tail
 * 8, 4 and 1 bytes at a time and the final avalanche. The states' lengths are multiples of 8,
 * so the 4- and 1-byte tails run only in tests/fmu/test_fmu_checksum.c, kept for a hash that
 * equals the library's for every length. */
uint64_t fmu_xxh64(const unsigned char *p, size_t n)
{
    const unsigned char *end = p + n;
    uint64_t h;
    if (n >= 32) {
        uint64_t v1 = P1 + P2, v2 = P2, v3 = 0, v4 = 0 - P1;
        const unsigned char *limit = end - 32;
        do {
            v1 = xxh_round(v1, le64(p));
            v2 = xxh_round(v2, le64(p + 8));
            v3 = xxh_round(v3, le64(p + 16));
            v4 = xxh_round(v4, le64(p + 24));
            p += 32;
        } while (p <= limit);
        h = rotl64(v1, 1) + rotl64(v2, 7) + rotl64(v3, 12) + rotl64(v4, 18);
        h = xxh_merge(xxh_merge(xxh_merge(xxh_merge(h, v1), v2), v3), v4);
    } else {
        h = P5;
    }
    h += (uint64_t)n;
    for (; end - p >= 8; p += 8)
        h = rotl64(h ^ xxh_round(0, le64(p)), 27) * P1 + P4;
    if (end - p >= 4) {
        h ^= ((uint64_t)p[0] | (uint64_t)p[1] << 8 | (uint64_t)p[2] << 16 | (uint64_t)p[3] << 24)
             * P1;
        h = rotl64(h, 23) * P2 + P3;
        p += 4;
    }
    for (; p < end; ++p)
        h = rotl64(h ^ (uint64_t)*p * P5, 11) * P1;
    h ^= h >> 33;
    h *= P2;
    h ^= h >> 29;
    h *= P3;
    return h ^ (h >> 32);
}

/* Zero bytes after the u32 nS that put the doubles at a multiple of 8 from the blob's start. */
static size_t padding(size_t offset) { return (8u - offset % 8u) % 8u; }

/* Is p aligned for double? (Only then are the doubles used in place.) */
static int double_aligned(const void *p)
{
    return (uintptr_t)p % sizeof(double) == 0;
}

/* ---------------------------------------------------------------- writer */

typedef struct writer { unsigned char *p; size_t n; } writer;   /* p == NULL: only count */

static void put_u32(writer *w, uint32_t v)
{
    int i;
    if (w->p)
        for (i = 0; i < 4; ++i)
            w->p[w->n + (size_t)i] = (unsigned char)(v >> (8 * i));
    w->n += 4;
}

static void put_f64(writer *w, double d)
{
    uint64_t v;
    int i;
    memcpy(&v, &d, sizeof v);
    if (w->p)
        for (i = 0; i < 8; ++i)
            w->p[w->n + (size_t)i] = (unsigned char)(v >> (8 * i));
    w->n += 8;
}

static void put_bytes(writer *w, const char *s, size_t n)
{
    if (w->p)
        memcpy(w->p + w->n, s, n);
    w->n += n;
}

static int is_built(const fmu_snapshot *s)
{
    return s->clock.phase == FMU_STEP_COMPLETE || s->clock.phase == FMU_TERMINATED;
}

static void write_values(const void *model, writer *w);

static void write_all(const fmu_snapshot *s, writer *w)
{
    const char *guid = fmu_model_guid();
    put_bytes(w, "SMSF", 4);
    put_u32(w, FMU_STATE_VERSION);
    put_u32(w, (uint32_t)strlen(guid));
    put_bytes(w, guid, strlen(guid));
    put_u32(w, fmu_model_real_bytes());
    put_u32(w, (uint32_t)s->clock.phase);
    put_f64(w, s->clock.start_time);
    put_f64(w, s->clock.time);
    put_u32(w, (uint32_t)(s->clock.ticks & 0xffffffffu));
    put_u32(w, (uint32_t)(s->clock.ticks >> 32));
    put_f64(w, s->clock.since_tick);
    put_u32(w, (uint32_t)(s->clock.steady & 0xffffffffu));
    put_u32(w, (uint32_t)(s->clock.steady >> 32));
    write_values(s->model, w);
}

/* Offset of the first settable value's field (the u32 nR) in a state of this model: the
 * values image starts there. */
static size_t values_offset(void)
{
    return 4u + 4u + 4u + strlen(fmu_model_guid()) + 4u + 4u + 8u + 8u + 4u + 4u + 8u + 4u + 4u;
}

int fmu_values_image_make(fmu_values_image *img, const void *model, const fmu_host *host)
{
    fmu_vr vrs[MAX_SETTABLE];
    writer w;
    size_t n, i, at = 4u, k = 0;
    img->valid = 0;
    w.p = NULL;
    w.n = 0;
    write_values(model, &w);
    if (img->bytes == NULL || img->len != w.n) {
        fmu_values_image_free(img, host);
        img->bytes = (unsigned char *)host->alloc(w.n, 1);
        if (img->bytes == NULL)
            return 1;
        img->len = w.n;
    }
    w.p = img->bytes;
    w.n = 0;
    write_values(model, &w);
    /* the inputs' values: u32 vr then the value, 12 (Real) or 8 (Integer) bytes per entry */
    n = fmu_model_settable(FMU_REAL, vrs, MAX_SETTABLE);
    for (i = 0; i < n; ++i, at += 12u)
        if (fmu_model_class(FMU_REAL, vrs[i]) == FMU_VAR_INPUT) {
            if (k == FMU_MAX_IMAGE_INPUTS)
                return 1;
            img->input_at[k] = at + 4u;
            img->input_vr[k] = vrs[i];
            img->input_type[k++] = FMU_REAL;
        }
    at += 4u;   /* nI */
    n = fmu_model_settable(FMU_INTEGER, vrs, MAX_SETTABLE);
    for (i = 0; i < n; ++i, at += 8u)
        if (fmu_model_class(FMU_INTEGER, vrs[i]) == FMU_VAR_INPUT) {
            if (k == FMU_MAX_IMAGE_INPUTS)
                return 1;
            img->input_at[k] = at + 4u;
            img->input_vr[k] = vrs[i];
            img->input_type[k++] = FMU_INTEGER;
        }
    img->n_inputs = k;
    img->valid = 1;
    return 0;
}

void fmu_values_image_free(fmu_values_image *img, const fmu_host *host)
{
    if (img->bytes != NULL)
        host->release(img->bytes);
    img->bytes = NULL;
    img->len = 0;
    img->valid = 0;
}

/* The settable values (nR, every Real; nI, every Integer) of model. */
static void write_values(const void *model, writer *w)
{
    fmu_vr vrs[MAX_SETTABLE];
    size_t n, i;
    n = fmu_model_settable(FMU_REAL, vrs, MAX_SETTABLE);
    put_u32(w, (uint32_t)n);
    for (i = 0; i < n; ++i) {
        put_u32(w, vrs[i]);
        put_f64(w, fmu_model_get_real(model, vrs[i]));
    }
    n = fmu_model_settable(FMU_INTEGER, vrs, MAX_SETTABLE);
    put_u32(w, (uint32_t)n);
    for (i = 0; i < n; ++i) {
        put_u32(w, vrs[i]);
        put_u32(w, (uint32_t)fmu_model_get_integer(model, vrs[i]));
    }
}

size_t fmu_serialized_size(const fmu_snapshot *s)
{
    writer w;
    size_t n = is_built(s) ? fmu_model_state_count(s->model) : 0;
    w.p = NULL;
    w.n = 0;
    write_all(s, &w);
    w.n += 4;   /* nS */
    return w.n + padding(w.n) + 8 * n + 8;   /* + the state doubles, the checksum */
}

int fmu_serialize(const fmu_snapshot *s, const fmu_host *host, unsigned char *out)
{
    writer w;
    size_t n = is_built(s) ? fmu_model_state_count(s->model) : 0, i;
    uint64_t sum;
    w.p = out;
    w.n = 0;
    write_all(s, &w);
    put_u32(&w, (uint32_t)n);   /* nS = 0 when nothing is built yet */
    for (i = padding(w.n); i > 0; --i)
        out[w.n++] = 0;
    if (n > 0) {
        unsigned char *at = out + w.n;
        if (native_doubles() && double_aligned(at)) {
            fmu_model_save_state(s->model, (double *)(void *)at);
        } else {
            double *state = (double *)host->alloc(n, sizeof(double));
            if (state == NULL)
                return -1;
            fmu_model_save_state(s->model, state);
            if (native_doubles())
                memcpy(at, state, 8 * n);
            else
                for (i = 0; i < n; ++i)
                    put_f64(&w, state[i]);
            host->release(state);
        }
        w.n = (size_t)(at - out) + 8 * n;
    }
    sum = fmu_xxh64(out, w.n);
    put_u32(&w, (uint32_t)(sum & 0xffffffffu));
    put_u32(&w, (uint32_t)(sum >> 32));
    return 0;
}

/* ---------------------------------------------------------------- reader */

typedef struct reader { const unsigned char *p; size_t n, pos; int bad; } reader;

static uint32_t get_u32(reader *r)
{
    uint32_t v = 0;
    int i;
    if (r->bad || r->n - r->pos < 4) {
        r->bad = 1;
        return 0;
    }
    for (i = 0; i < 4; ++i)
        v |= (uint32_t)r->p[r->pos + (size_t)i] << (8 * i);
    r->pos += 4;
    return v;
}

static double get_f64(reader *r)
{
    uint64_t v;
    double d;
    if (r->bad || r->n - r->pos < 8) {
        r->bad = 1;
        return 0.0;
    }
    v = le64(r->p + r->pos);   /* the same byte order as the checksum's reads */
    r->pos += 8;
    memcpy(&d, &v, sizeof d);
    return d;
}

#define REFUSE(...) do { snprintf(msg, len, __VA_ARGS__); return -1; } while (0)

/* What the reader learns about the state's settable values on the way: whether its parameters
 * are the built instance `like`'s (NULL: there is none) and its inputs. */
typedef struct settables {
    const void *like;
    int same;
    size_t n_inputs, n_int_inputs;
    fmu_vr input_vr[MAX_SETTABLE], int_input_vr[FMU_MAX_IMAGE_INPUTS];
    double input[MAX_SETTABLE];
    int int_input[FMU_MAX_IMAGE_INPUTS];
} settables;

static int read_values(reader *r, fmu_type type, void *model, settables *seen, char *msg,
                       size_t len)
{
    uint32_t n = get_u32(r), i;
    const size_t expected = fmu_model_settable(type, NULL, 0);
    char name[96];
    if (r->bad)
        REFUSE("truncated state");
    if (n != expected)
        REFUSE("state holds %lu %s variables, this model has %lu", (unsigned long)n,
               type == FMU_REAL ? "Real" : "Integer", (unsigned long)expected);
    for (i = 0; i < n; ++i) {
        fmu_vr vr = get_u32(r);
        fmu_var_class cls = fmu_model_class(type, vr);
        if (r->bad)
            REFUSE("truncated state");
        if (cls != FMU_VAR_INPUT && cls != FMU_VAR_PARAMETER && cls != FMU_VAR_TUNABLE)
            REFUSE("state names value reference %lu, not a settable variable", (unsigned long)vr);
        if (type == FMU_REAL) {
            double v = get_f64(r), w;
            if (!r->bad && !isfinite(v)) {
                fmu_model_name(type, vr, name, sizeof name);
                REFUSE("state holds a non-finite %s", name);
            }
            fmu_model_set_real(model, vr, v);
            if (cls == FMU_VAR_INPUT && seen->n_inputs < MAX_SETTABLE) {
                seen->input_vr[seen->n_inputs] = vr;
                seen->input[seen->n_inputs++] = v;
            } else if (cls == FMU_VAR_INPUT) {
                seen->same = 0;   /* an input copy_built could not set: build instead */
            } else if (seen->same) {   /* a fixed or tunable parameter: like's own, bit for bit */
                w = fmu_model_get_real(seen->like, vr);
                seen->same = memcmp(&v, &w, sizeof v) == 0;   /* bit for bit */
            }
        } else {
            const int v = (int)(int32_t)get_u32(r);
            fmu_model_set_integer(model, vr, v);
            if (cls == FMU_VAR_INPUT && seen->n_int_inputs < FMU_MAX_IMAGE_INPUTS) {
                seen->int_input_vr[seen->n_int_inputs] = vr;
                seen->int_input[seen->n_int_inputs++] = v;
            } else if (cls == FMU_VAR_INPUT) {
                seen->same = 0;
            } else if (seen->same) {
                seen->same = fmu_model_get_integer(seen->like, vr) == v;
            }
        }
    }
    return r->bad ? (snprintf(msg, len, "truncated state"), -1) : 0;
}

/* The dynamic state into the model: no value may be NaN or infinite (the FMU refuses
 * non-finite inputs and parameters, so no run produces one, and a forged one would reach the
 * outputs), then the model's own checks (ranges, limits). 0, or non-zero with why. */
static int load_state(void *model, const double *v, size_t n, char *why, size_t len)
{
    size_t i;
    for (i = 0; i < n; ++i)
        if (!isfinite(v[i])) {
            snprintf(why, len, "value %lu of %lu is %s, which no run of the FMU produces",
                     (unsigned long)i, (unsigned long)n, v[i] != v[i] ? "NaN" : "infinite");
            return 1;
        }
    return fmu_model_load_state(model, v, n, why, len);
}

/* Is `like` an instance whose filters are built? */
static int built_instance(const fmu_instance *like)
{
    return like != NULL && like->mem != NULL
           && (like->clock.phase == FMU_STEP_COMPLETE || like->clock.phase == FMU_TERMINATED);
}

/* The model of a state with like's parameters, fixed and tunable (seen->same: a tunable value
 * of like's that differs would be copied over the state's, and with fixed stages it sizes the
 * block): like's built struct and block copied, the state's inputs set on the copy, which is
 * what a build would give (the designs are functions of the parameters alone; a stage the
 * state holds retuned is brought to its saved configuration by the model's load_state):
 * O(block), no design. 0, or non-zero when out of memory. */
static int copy_built(fmu_snapshot *dst, const fmu_instance *like, const settables *seen,
                      const fmu_host *host, int model_copied)
{
    size_t i;
    dst->mem = host->alloc(like->mem_bytes > 0 ? like->mem_bytes : 1, 1);
    if (dst->mem == NULL)
        return 1;
    memcpy(dst->mem, like->mem, like->mem_bytes);
    dst->mem_bytes = like->mem_bytes;
    if (model_copied) {   /* like's model with the state's inputs already (same_as_image()) */
        fmu_model_rebind(dst->model, dst->mem);
        return 0;
    }
    memcpy(dst->model, like->model, fmu_model_size());
    fmu_model_rebind(dst->model, dst->mem);
    for (i = 0; i < seen->n_inputs; ++i)
        fmu_model_set_real(dst->model, seen->input_vr[i], seen->input[i]);
    for (i = 0; i < seen->n_int_inputs; ++i)
        fmu_model_set_integer(dst->model, seen->int_input_vr[i], seen->int_input[i]);
    return 0;
}

/* Do the state's settable values at r->pos equal like's image outside the inputs' values?
 * Then they are like's parameters bit for bit (value references, order and counts included):
 * the inputs are read into seen (a non-finite Real input refused as read_values() refuses
 * it), r moves past the region and 1 is returned; else 0 and nothing moves. */
static int same_as_image(reader *r, const fmu_values_image *img, settables *seen, char *msg,
                         size_t len, int *refused)
{
    const unsigned char *at = r->p + r->pos;
    size_t from = 0, k;
    *refused = 0;
    if (!img->valid || r->bad || r->n - r->pos < img->len)
        return 0;
    for (k = 0; k < img->n_inputs; ++k) {   /* the runs between the inputs' values */
        if (memcmp(at + from, img->bytes + from, img->input_at[k] - from) != 0)
            return 0;
        from = img->input_at[k] + (img->input_type[k] == FMU_REAL ? 8u : 4u);
    }
    if (memcmp(at + from, img->bytes + from, img->len - from) != 0)
        return 0;
    seen->n_inputs = seen->n_int_inputs = 0;
    for (k = 0; k < img->n_inputs; ++k) {
        reader v;
        v.p = at;
        v.n = img->len;
        v.pos = img->input_at[k];
        v.bad = 0;
        if (img->input_type[k] == FMU_REAL) {
            const double x = get_f64(&v);
            if (!isfinite(x)) {
                char name[96];
                fmu_model_name(FMU_REAL, img->input_vr[k], name, sizeof name);
                *refused = 1;
                snprintf(msg, len, "state holds a non-finite %s", name);
                return 0;
            }
            seen->input_vr[seen->n_inputs] = img->input_vr[k];
            seen->input[seen->n_inputs++] = x;
        } else {
            seen->int_input_vr[seen->n_int_inputs] = img->input_vr[k];
            seen->int_input[seen->n_int_inputs++] = (int)(int32_t)get_u32(&v);
        }
    }
    r->pos += img->len;
    return 1;
}

int fmu_deserialize(const unsigned char *in, size_t size, fmu_snapshot *dst,
                    const fmu_instance *like, const fmu_host *host, char *msg, size_t len)
{
    reader r;
    const char *guid = fmu_model_guid();
    uint32_t glen, real_bytes, phase, lo, hi, lo2, n_state;
    size_t i;
    int rc, model_copied = 0;
    char why[FMU_MESSAGE_LEN / 2];
    settables seen;
    rc = 0;
    why[0] = '\0';
    if (size < 16 || memcmp(in, "SMSF", 4) != 0)
        REFUSE("not a smoothshaper FMU state (bad magic)");
    r.p = in;
    r.n = size - 8;
    r.pos = 4;
    r.bad = 0;
    if (get_u32(&r) != FMU_STATE_VERSION)
        REFUSE("unsupported state format version");
    if (fmu_xxh64(in, size - 8) != le64(in + size - 8))
        REFUSE("checksum mismatch: the state is truncated or corrupted");
    glen = get_u32(&r);
    if (r.bad || glen != strlen(guid) || r.n - r.pos < glen || memcmp(in + r.pos, guid, glen) != 0)
        REFUSE("the state was written by another model or model version (instantiation token differs)");
    r.pos += glen;
    real_bytes = get_u32(&r);
    if (!r.bad && real_bytes != fmu_model_real_bytes())
        REFUSE("the state was written by a build with %lu-byte reals, this one has %lu-byte reals "
               "(other precision)", (unsigned long)real_bytes, (unsigned long)fmu_model_real_bytes());
    phase = get_u32(&r);
    dst->clock.start_time = get_f64(&r);
    dst->clock.time = get_f64(&r);
    lo = get_u32(&r);
    hi = get_u32(&r);
    dst->clock.since_tick = get_f64(&r);
    lo2 = get_u32(&r);
    dst->clock.steady = (uint64_t)get_u32(&r) << 32 | lo2;
    if (r.bad || phase > FMU_TERMINATED || !isfinite(dst->clock.start_time)
        || !isfinite(dst->clock.time) || !isfinite(dst->clock.since_tick))
        REFUSE("truncated or invalid clock in the state");
    dst->clock.phase = (fmu_phase)phase;
    dst->clock.ticks = (uint64_t)hi << 32 | lo;
    seen.like = built_instance(like) && is_built(dst) ? like->model : NULL;
    seen.same = seen.like != NULL;
    seen.n_inputs = seen.n_int_inputs = 0;
    if (seen.same && r.pos == values_offset()
        && same_as_image(&r, &like->values, &seen, msg, len, &rc)) {
        /* like's parameters: its model with the state's inputs (what read_values() would
         * set), so that the clock check below reads the same Ts */
        memcpy(dst->model, like->model, fmu_model_size());   /* bound by copy_built() */
        for (i = 0; i < seen.n_inputs; ++i)
            fmu_model_set_real(dst->model, seen.input_vr[i], seen.input[i]);
        for (i = 0; i < seen.n_int_inputs; ++i)
            fmu_model_set_integer(dst->model, seen.int_input_vr[i], seen.int_input[i]);
        model_copied = 1;
    } else if (rc != 0) {
        return -1;
    } else {
        fmu_model_defaults(dst->model);
        if (read_values(&r, FMU_REAL, dst->model, &seen, msg, len) != 0
            || read_values(&r, FMU_INTEGER, dst->model, &seen, msg, len) != 0)
            return -1;
    }
    n_state = get_u32(&r);
    for (i = padding(r.pos); i > 0 && !r.bad; --i)
        if (r.pos >= r.n || in[r.pos++] != 0)
            r.bad = 1;
    if (r.bad || (r.n - r.pos) / 8 < n_state || r.n - r.pos != 8 * (size_t)n_state)
        REFUSE("truncated state (dynamic part)");
    if (!is_built(dst))
        return n_state == 0 ? 0 : (snprintf(msg, len, "state of an unbuilt FMU holds filter state"), -1);
    /* The clock before any work proportional to the filters (Ts itself is checked by the build). */
    if (fmu_model_sample_period(dst->model) > 0.0
        && fmu_clock_check(&dst->clock, fmu_model_sample_period(dst->model), msg, len) != 0)
        return -1;
    if (seen.same) {
        if (copy_built(dst, like, &seen, host, model_copied) != 0)
            REFUSE("out of memory");
    } else if (fmu_build(host, dst->model, &dst->mem, &dst->mem_bytes, msg, len) > 0) {
        return -1;
    }
    if (n_state != fmu_model_state_count(dst->model))
        REFUSE("state holds %lu filter values, the parameters need %lu", (unsigned long)n_state,
               (unsigned long)fmu_model_state_count(dst->model));
    if (native_doubles() && double_aligned(in + r.pos)) {
        rc = load_state(dst->model, (const double *)(const void *)(in + r.pos), n_state, why,
                        sizeof why);
    } else {
        double *state = (double *)host->alloc(n_state > 0 ? n_state : 1, sizeof(double));
        if (state == NULL)
            REFUSE("out of memory");
        if (native_doubles())
            memcpy(state, in + r.pos, 8 * (size_t)n_state);
        else
            for (i = 0; i < n_state; ++i)
                state[i] = get_f64(&r);
        rc = load_state(dst->model, state, n_state, why, sizeof why);
        host->release(state);
    }
    if (rc != 0)
        REFUSE("the filter state does not fit the parameters%s%s", why[0] != '\0' ? ": " : "",
               why);
    return 0;
}
