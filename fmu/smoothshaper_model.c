/* SPDX-License-Identifier: Apache-2.0 */
/*
 * SmoothShaper: y = S(H_7(...H_0(u))) at the internal ticks, a chain of up to SS_MAX_STAGES
 * stages of any family, set by the parameters stage[k].* (unused stages have kind = none), and
 * optionally a scheduled ZV^n shaper S whose mode follows the input s through the table
 * schedule.*. Only the public smoothshaper API is used. At fmi2ExitInitializationMode the
 * chain is put at rest at the current value of u (as if u had held that value forever), so y
 * starts at u.
 *
 * Retuning (retune_max_delay > 0): the stages are retunable (sms_tunable_chain, tunable.h),
 * each with memory for any configuration of its kind lasting at most retune_max_delay; a
 * tunable parameter set between steps is checked at once (fmi2Error naming it, nothing
 * changed) and applied at the next communication point, or, while that stage's previous
 * switch is still running, at the first tick after it has ended (the core's rule: one switch
 * at a time). The output lag is the active stages' lag (align.h) plus the scheduled shaper's.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "smoothshaper/smoothshaper.h"
#include "SmoothShaper_variables.h"
#include "fmu_model.h"

/* The generated kind codes are the core's sms_kind values, and a stage's impulse parameters
 * fit a config (compile-time checks). */
typedef char ss_kind_codes_match_sms_kind[(SS_KIND_COUNT == SMS_KIND_COUNT) ? 1 : -1];
typedef char ss_impulses_fit_config[(SS_MAX_IMPULSES == SMS_SHAPER_MAX_IMPULSES) ? 1 : -1];

static const char *const field_names[SS_FIELD_COUNT] = {
    "kind", "design", "timing", "T", "sigma", "k", "wn", "zeta", "order", "tolerance",
    "notch_pole_zeta", "duration"
};

typedef struct ss_params {
    int ints[SS_FIELD_COUNT];     /* kind, design, timing, k, order (by SS_FIELD_*) */
    double reals[SS_FIELD_COUNT]; /* T, sigma, wn, zeta, tolerance, notch_pole_zeta, duration */
    double amplitude[SS_MAX_IMPULSES], time[SS_MAX_IMPULSES];   /* kind = impulses */
} ss_params;

/* Parameters (as set: a tunable value takes effect at the next communication point) and the
 * filters; the stages' slots and the scheduled shaper's ring live in the glue's block. */
typedef struct ss_model {
    double u, y, Ts, retune_max_delay, s;
    ss_params stage[SS_MAX_STAGES];
    int sched_kind, sched_order, sched_every, sched_points;
    double sched[SS_SCHEDULE_POINTS][3];  /* value, wn, zeta of each row */
    int built;
    size_t n_active;                     /* stages with kind != none, in chain order */
    unsigned used[SS_MAX_STAGES];        /* stage k at each chain position */
    int pending[SS_MAX_STAGES];          /* chain position: its parameters await a retune */
    int any_pending;
    sms_tunable_chain chain;
    sms_tunable tunables[SS_MAX_STAGES];
    size_t slot_cells[SS_MAX_STAGES];
    size_t region[SS_MAX_STAGES];        /* doubles of each stage's part of the saved state */
    size_t chain_cells;                  /* cells of the stages; the scheduled ring follows */
    int scheduled;                       /* 1: a scheduled shaper after the chain */
    sms_scheduled sch;
    sms_schedule_point points[SS_SCHEDULE_POINTS];
    double chain_lag;                    /* the active stages' lag [samples] */
    /* sms_tunable_chain_input_max() of the chain, asked by every set of u: computed once per
     * configuration (stale: recomputed on each ask until a tick finds the chain not switching;
     * a build, a retune and a loaded state make it stale) */
    double input_max;
    int input_max_stale;
    /* the limit and gain bound (sms_stage_config_limit(), uncapped) of each chain position's pending
     * configuration, kept from the set that made it pending (pend_gain 0: none valid), so that
     * every set of u is checked against the range of the retunes to come in O(stages) */
    double pend_limit[SS_MAX_STAGES], pend_gain[SS_MAX_STAGES];
    /* The held-input bound (held_bound()): peak_cur and peak_prev are the largest |u| (and |s|)
     * ticked in the current epoch (epoch_ticks ticks so far) and in the one before, each epoch
     * span_max ticks long (memory_span()); after a state was loaded both start at the
     * configuration's whole range (the inputs before it are not known). */
    double peak_cur, peak_prev;
    uint64_t epoch_ticks, span_max;
} ss_model;

static int is_integer_field(unsigned f)
{
    return f == SS_FIELD_KIND || f == SS_FIELD_DESIGN || f == SS_FIELD_TIMING || f == SS_FIELD_K
           || f == SS_FIELD_ORDER;
}

/* kind, design and timing stay fixed; the other fields are tunable */
static int is_tunable_field(unsigned f)
{
    return f != SS_FIELD_KIND && f != SS_FIELD_DESIGN && f != SS_FIELD_TIMING;
}

/* Split a stage value reference into (stage, field); 0 if it is not one. */
static int stage_field(fmu_vr vr, unsigned *k, unsigned *f)
{
    if (vr < SS_STAGE_BASE || vr >= SS_STAGE_BASE + SS_STAGE_STRIDE * SS_MAX_STAGES)
        return 0;
    *k = (vr - SS_STAGE_BASE) / SS_STAGE_STRIDE;
    *f = (vr - SS_STAGE_BASE) % SS_STAGE_STRIDE;
    return *f < SS_FIELD_COUNT;
}

/* Split an impulse value reference into (stage, impulse, is_time); 0 if it is not one. */
static int impulse_field(fmu_vr vr, unsigned *k, unsigned *i, int *is_time)
{
    unsigned r;
    if (vr < SS_IMPULSE_BASE || vr >= SS_IMPULSE_BASE + SS_IMPULSE_STRIDE * SS_MAX_STAGES)
        return 0;
    *k = (vr - SS_IMPULSE_BASE) / SS_IMPULSE_STRIDE;
    r = (vr - SS_IMPULSE_BASE) % SS_IMPULSE_STRIDE;
    *is_time = r >= SS_MAX_IMPULSES;
    *i = *is_time ? r - SS_MAX_IMPULSES : r;
    return *i < SS_MAX_IMPULSES;
}

/* The stored impulse parameter vr names (valid per impulse_field). */
static double *impulse_slot(ss_model *m, fmu_vr vr)
{
    unsigned k, i;
    int is_time;
    (void)impulse_field(vr, &k, &i, &is_time);
    return is_time ? &m->stage[k].time[i] : &m->stage[k].amplitude[i];
}

/* A schedule table value reference into (row, field 0 value / 1 wn / 2 zeta); 0 if not one. */
static int sched_field(fmu_vr vr, unsigned *j, unsigned *f)
{
    if (vr < SS_SCHEDULE_BASE || vr >= SS_SCHEDULE_BASE + 3u * SS_SCHEDULE_POINTS)
        return 0;
    *j = (vr - SS_SCHEDULE_BASE) / 3u;
    *f = (vr - SS_SCHEDULE_BASE) % 3u;
    return 1;
}

static int is_sched_integer(fmu_vr vr)
{
    return vr == SS_VR_SCHED_KIND || vr == SS_VR_SCHED_ORDER || vr == SS_VR_SCHED_EVERY
           || vr == SS_VR_SCHED_POINTS;
}

size_t fmu_model_size(void) { return sizeof(ss_model); }
const char *fmu_model_identifier(void) { return FMU_MODEL_IDENTIFIER; }
const char *fmu_model_guid(void) { return FMU_MODEL_GUID; }

void fmu_model_defaults(void *model)
{
    ss_model *m = (ss_model *)model;
    unsigned k;
    memset(m, 0, sizeof *m);
    m->Ts = 0.001;
    for (k = 0; k < SS_MAX_STAGES; ++k) {   /* the start values of modelDescription.xml */
        ss_params *p = &m->stage[k];
        p->ints[SS_FIELD_KIND] = SS_DEFAULT_KIND(k);
        p->ints[SS_FIELD_K] = 1;
        p->ints[SS_FIELD_ORDER] = 1;
        p->reals[SS_FIELD_T] = 0.01;
        p->reals[SS_FIELD_WN] = 100.0;
        p->reals[SS_FIELD_TOLERANCE] = 0.05;
        p->reals[SS_FIELD_NOTCH_POLE_ZETA] = 0.7;
        p->reals[SS_FIELD_DURATION] = 0.75;
    }
    m->sched_kind = -1;
    m->sched_order = 1;
    m->sched_every = 1;
    m->sched_points = 1;
    for (k = 0; k < SS_SCHEDULE_POINTS; ++k) {
        m->sched[k][0] = (double)k;
        m->sched[k][1] = 100.0;
    }
}

fmu_var_class fmu_model_class(fmu_type type, fmu_vr vr)
{
    unsigned k, f, i;
    int is_time;
    if (type == FMU_REAL && impulse_field(vr, &k, &i, &is_time)) return FMU_VAR_PARAMETER;
    if (type == FMU_REAL && (vr == SS_VR_U || vr == SS_VR_S)) return FMU_VAR_INPUT;
    if (type == FMU_REAL && (vr == SS_VR_Y || vr == SS_VR_LAG)) return FMU_VAR_OUTPUT;
    if (type == FMU_REAL && (vr == SS_VR_TS || vr == SS_VR_RETUNE_MAX_DELAY)) return FMU_VAR_PARAMETER;
    if (type == FMU_INTEGER && is_sched_integer(vr)) return FMU_VAR_PARAMETER;
    if (type == FMU_REAL && sched_field(vr, &k, &f)) return FMU_VAR_PARAMETER;
    if (stage_field(vr, &k, &f) && is_integer_field(f) == (type == FMU_INTEGER))
        return is_tunable_field(f) ? FMU_VAR_TUNABLE : FMU_VAR_PARAMETER;
    return FMU_VAR_UNKNOWN;
}

void fmu_model_name(fmu_type type, fmu_vr vr, char *buf, size_t len)
{
    static const char *const sched_names[3] = {"value", "wn", "zeta"};
    unsigned k, f, i;
    int is_time;
    if (type == FMU_REAL && impulse_field(vr, &k, &i, &is_time)) {
        snprintf(buf, len, "stage[%u].%s[%u]", k, is_time ? "time" : "amplitude", i);
    } else if (type == FMU_REAL && vr <= SS_VR_LAG) {
        static const char *const names[6] = {"u", "y", "Ts", "retune_max_delay", "s", "lag"};
        snprintf(buf, len, "%s", names[vr]);
    } else if (type == FMU_INTEGER && is_sched_integer(vr)) {
        snprintf(buf, len, "schedule.%s", vr == SS_VR_SCHED_KIND ? "kind" : vr == SS_VR_SCHED_ORDER
                 ? "order" : vr == SS_VR_SCHED_EVERY ? "update_every" : "points");
    } else if (type == FMU_REAL && sched_field(vr, &k, &f)) {
        snprintf(buf, len, "schedule.%s[%u]", sched_names[f], k);
    } else if (stage_field(vr, &k, &f)) {
        snprintf(buf, len, "stage[%u].%s", k, field_names[f]);
    } else {
        snprintf(buf, len, "vr %lu", (unsigned long)vr);
    }
}

size_t fmu_model_settable(fmu_type type, fmu_vr *out, size_t cap)
{
    size_t n = 0;
    unsigned k, f;
#define PUT(v) do { if (n < cap) out[n] = (v); ++n; } while (0)
    if (type == FMU_REAL) {
        PUT(SS_VR_U);
        PUT(SS_VR_TS);
        PUT(SS_VR_RETUNE_MAX_DELAY);
        PUT(SS_VR_S);
        for (k = 0; k < 3u * SS_SCHEDULE_POINTS; ++k)
            PUT(SS_SCHEDULE_BASE + k);
    } else {
        PUT(SS_VR_SCHED_KIND);
        PUT(SS_VR_SCHED_ORDER);
        PUT(SS_VR_SCHED_EVERY);
        PUT(SS_VR_SCHED_POINTS);
    }
    for (k = 0; k < SS_MAX_STAGES; ++k)
        for (f = 0; f < SS_FIELD_COUNT; ++f)
            if (is_integer_field(f) == (type == FMU_INTEGER))
                PUT(SS_STAGE_BASE + SS_STAGE_STRIDE * k + f);
    if (type == FMU_REAL)
        for (k = 0; k < SS_MAX_STAGES; ++k)
            for (f = 0; f < 2u * SS_MAX_IMPULSES; ++f)
                PUT(SS_IMPULSE_BASE + SS_IMPULSE_STRIDE * k + f);
#undef PUT
    return n;
}

/* The lag output: the active stages' and the scheduled shaper's taps in use [s]. */
static double lag_seconds(const ss_model *m)
{
    double lag = m->chain_lag;
    if (m->built && m->scheduled)
        lag += sms_scheduled_lag(&m->sch);
    return lag * m->Ts;
}

double fmu_model_get_real(const void *model, fmu_vr vr)
{
    const ss_model *m = (const ss_model *)model;
    unsigned k, f, i;
    int is_time;
    if (impulse_field(vr, &k, &i, &is_time))
        return is_time ? m->stage[k].time[i] : m->stage[k].amplitude[i];
    switch (vr) {
    case SS_VR_U: return m->u;
    case SS_VR_Y: return m->y;
    case SS_VR_TS: return m->Ts;
    case SS_VR_RETUNE_MAX_DELAY: return m->retune_max_delay;
    case SS_VR_S: return m->s;
    case SS_VR_LAG: return m->built ? lag_seconds(m) : 0.0;
    default: break;
    }
    if (sched_field(vr, &k, &f))
        return m->sched[k][f];
    return stage_field(vr, &k, &f) ? m->stage[k].reals[f] : 0.0;
}

int fmu_model_get_integer(const void *model, fmu_vr vr)
{
    const ss_model *m = (const ss_model *)model;
    unsigned k, f;
    switch (vr) {
    case SS_VR_SCHED_KIND: return m->sched_kind;
    case SS_VR_SCHED_ORDER: return m->sched_order;
    case SS_VR_SCHED_EVERY: return m->sched_every;
    case SS_VR_SCHED_POINTS: return m->sched_points;
    default: break;
    }
    return stage_field(vr, &k, &f) ? m->stage[k].ints[f] : 0;
}

static int stage_config(const ss_model *m, unsigned k, sms_stage_config *c, char *msg, size_t len);

/* The range and gain bound of chain position i's configuration from its parameters as set
 * (a retune to come), or none (pend_gain 0) while they are no valid configuration, which
 * fmu_model_input_max() then counts as a range of 0: a set call is checked as a whole before
 * its values are written one by one, so that lasts only until its last value. */
static void pending_range(ss_model *m, size_t i)
{
    char why[FMU_MESSAGE_LEN];
    sms_stage_config c;
    m->pend_limit[i] = 0.0;
    m->pend_gain[i] = 0.0;
    if (stage_config(m, m->used[i], &c, why, sizeof why) != 0)
        return;
    if (c.kind == SMS_SHAPER_IMPULSES)
        m->pend_gain[i] = -1.0;   /* never retuned (it reads no tunable field) */
    else if (sms_stage_config_limit(&c, m->Ts, &m->pend_limit[i], &m->pend_gain[i]) != SMS_OK)
        m->pend_limit[i] = m->pend_gain[i] = 0.0;
}

/* A tunable field of stage k was set: after the build, its chain position awaits a retune. */
static void mark_pending(ss_model *m, unsigned k)
{
    size_t i;
    if (!m->built)
        return;
    for (i = 0; i < m->n_active; ++i)
        if (m->used[i] == k) {
            m->pending[i] = 1;
            m->any_pending = 1;
        }
}

/* After a tunable value of stage k was written: its pending configuration's range. */
static void update_pending_range(ss_model *m, unsigned k)
{
    size_t i;
    for (i = 0; m->built && i < m->n_active; ++i)
        if (m->used[i] == k && m->pending[i])
            pending_range(m, i);
}

void fmu_model_set_real(void *model, fmu_vr vr, double value)
{
    ss_model *m = (ss_model *)model;
    unsigned k, f, i;
    int is_time;
    if (impulse_field(vr, &k, &i, &is_time)) *impulse_slot(m, vr) = value;
    else if (vr == SS_VR_U) m->u = value;
    else if (vr == SS_VR_S) m->s = value;
    else if (vr == SS_VR_TS) m->Ts = value;
    else if (vr == SS_VR_RETUNE_MAX_DELAY) m->retune_max_delay = value;
    else if (sched_field(vr, &k, &f)) m->sched[k][f] = value;
    else if (stage_field(vr, &k, &f)) {
        const int changed = m->stage[k].reals[f] != value && is_tunable_field(f);
        if (changed)
            mark_pending(m, k);
        m->stage[k].reals[f] = value;
        if (changed)
            update_pending_range(m, k);
    }
}

void fmu_model_set_integer(void *model, fmu_vr vr, int value)
{
    ss_model *m = (ss_model *)model;
    unsigned k, f;
    if (vr == SS_VR_SCHED_KIND) m->sched_kind = value;
    else if (vr == SS_VR_SCHED_ORDER) m->sched_order = value;
    else if (vr == SS_VR_SCHED_EVERY) m->sched_every = value;
    else if (vr == SS_VR_SCHED_POINTS) m->sched_points = value;
    else if (stage_field(vr, &k, &f)) {
        const int changed = m->stage[k].ints[f] != value && is_tunable_field(f);
        if (changed)
            mark_pending(m, k);
        m->stage[k].ints[f] = value;
        if (changed)
            update_pending_range(m, k);
    }
}

double fmu_model_sample_period(const void *model) { return ((const ss_model *)model)->Ts; }

/* The field a core status points at (note: what it stands for when designed for a mode). */
static unsigned offending_field(sms_status st, int design_for_mode, const char **note)
{
    *note = "";
    switch (st) {
    case SMS_ERR_DURATION: case SMS_ERR_DURATION_BELOW_TS: case SMS_ERR_TOO_LONG:
        if (!design_for_mode)
            return SS_FIELD_T;
        *note = " (the designed T)";
        return SS_FIELD_WN;
    case SMS_ERR_SIGMA:
        if (!design_for_mode)
            return SS_FIELD_SIGMA;
        *note = " (the designed sigma)";
        return SS_FIELD_ZETA;
    case SMS_ERR_WN: case SMS_ERR_ABOVE_NYQUIST: return SS_FIELD_WN;
    case SMS_ERR_ZETA: return SS_FIELD_ZETA;
    case SMS_ERR_MULTIPLE: case SMS_ERR_EVEN_MULTIPLE: return SS_FIELD_K;
    case SMS_ERR_ORDER: return SS_FIELD_ORDER;
    case SMS_ERR_TOLERANCE: return SS_FIELD_TOLERANCE;
    case SMS_ERR_NOTCH_DAMPING: return SS_FIELD_NOTCH_POLE_ZETA;
    case SMS_ERR_SHAPER_DURATION: return SS_FIELD_DURATION;
    default: return SS_FIELD_KIND;
    }
}

/* User-defined impulses: the first impulse parameter the refusal st is about (the core
 * checks amplitudes, then times, in order), as the refusal text. */
static int impulses_error(const ss_model *m, unsigned k, sms_status st, char *msg, size_t len)
{
    const ss_params *p = &m->stage[k];
    unsigned n = (unsigned)p->ints[SS_FIELD_ORDER], i, bad = 0;
    double sum = 0.0;
    if (st == SMS_ERR_IMPULSE_AMPLITUDE) {
        for (i = 0; i < n; ++i) {
            sum += p->amplitude[i];
            if (!(p->amplitude[i] - p->amplitude[i] == 0.0))
                return snprintf(msg, len, "stage[%u].amplitude[%u] = %.17g: %s", k, i,
                                p->amplitude[i], sms_status_string(st)), 1;
        }
        return snprintf(msg, len, "stage[%u].amplitude[0 .. %u] sum to %.17g: %s", k, n - 1u,
                        sum, sms_status_string(st)), 1;
    }
    bad = st == SMS_ERR_TOO_LONG ? n - 1u : 0u;      /* too long: the last time */
    for (i = 0; i < n && st != SMS_ERR_TOO_LONG; ++i)
        if (!(p->time[i] - p->time[i] == 0.0) || p->time[i] < 0.0
            || (i > 0u && !(p->time[i] > p->time[i - 1u]))) {
            bad = i;
            break;
        }
    return snprintf(msg, len, "stage[%u].time[%u] = %.17g: %s", k, bad, p->time[bad],
                    sms_status_string(st)), 1;
}

/* "stage[k].field = value<note>: <status>" into msg; returns 1 (the build fails). */
static int stage_error(const ss_model *m, unsigned k, sms_status st, int design_for_mode,
                       char *msg, size_t len)
{
    const char *note;
    unsigned f = offending_field(st, design_for_mode, &note);
    if (is_integer_field(f))
        snprintf(msg, len, "stage[%u].%s = %d%s: %s", k, field_names[f], m->stage[k].ints[f], note,
                 sms_status_string(st));
    else
        snprintf(msg, len, "stage[%u].%s = %.17g%s: %s", k, field_names[f], m->stage[k].reals[f],
                 note, sms_status_string(st));
    return 1;
}

/* Stage k's configuration from its parameters, without the check of the whole configuration
 * (stage_config() adds it): 0, or 1 with msg for an integer field out of its codes. */
static int stage_fields(const ss_model *m, unsigned k, sms_stage_config *c, char *msg, size_t len)
{
    const ss_params *p = &m->stage[k];
    int kind = p->ints[SS_FIELD_KIND], for_mode = p->ints[SS_FIELD_DESIGN] == 1;
    sms_status st;
    if (kind < 0 || kind >= SMS_KIND_COUNT)
        return snprintf(msg, len, "stage[%u].kind = %d is not a stage kind code (-1 = none, "
                        "0 .. %d)", k, kind, SMS_KIND_COUNT - 1), 1;
    if (p->ints[SS_FIELD_DESIGN] != 0 && !for_mode)
        return snprintf(msg, len, "stage[%u].design = %d is not raw (0) or for_mode (1)", k,
                        p->ints[SS_FIELD_DESIGN]), 1;
    if (p->ints[SS_FIELD_TIMING] != SMS_TIMING_EXACT && p->ints[SS_FIELD_TIMING] != SMS_TIMING_PAPER
        && p->ints[SS_FIELD_TIMING] != SMS_TIMING_BOUNDED)
        return snprintf(msg, len, "stage[%u].timing = %d is not exact (0), paper (1) or "
                        "bounded (2)", k, p->ints[SS_FIELD_TIMING]), 1;
    if (p->ints[SS_FIELD_TIMING] == SMS_TIMING_BOUNDED && kind != SMS_RECTANGULAR
        && kind != SMS_EXPONENTIAL)
        return snprintf(msg, len, "stage[%u].timing = 2 (bounded) is for the rectangular (0) and "
                        "exponential (3) smoothers; stage[%u].kind = %d", k, k, kind), 1;
    if (p->ints[SS_FIELD_K] < 1 || p->ints[SS_FIELD_ORDER] < 1)
        return snprintf(msg, len, "stage[%u].%s = %d: must be >= 1", k,
                        p->ints[SS_FIELD_K] < 1 ? "k" : "order",
                        p->ints[SS_FIELD_K] < 1 ? p->ints[SS_FIELD_K] : p->ints[SS_FIELD_ORDER]), 1;
    if (for_mode) {
        st = sms_design_for_mode((sms_kind)kind, p->reals[SS_FIELD_WN], p->reals[SS_FIELD_ZETA],
                                 (unsigned)p->ints[SS_FIELD_K], c);
        if (st != SMS_OK)
            return stage_error(m, k, st, 0, msg, len);
    } else {
        *c = sms_stage_config_default((sms_kind)kind);
        c->T = p->reals[SS_FIELD_T];
        c->sigma = p->reals[SS_FIELD_SIGMA];
        c->k = (unsigned)p->ints[SS_FIELD_K];
        c->wn = p->reals[SS_FIELD_WN];
        c->zeta = p->reals[SS_FIELD_ZETA];
    }
    c->timing = (sms_timing)p->ints[SS_FIELD_TIMING];
    c->order = (unsigned)p->ints[SS_FIELD_ORDER];
    c->tolerance = p->reals[SS_FIELD_TOLERANCE];
    c->notch_pole_zeta = p->reals[SS_FIELD_NOTCH_POLE_ZETA];
    c->duration = p->reals[SS_FIELD_DURATION];
    memcpy(c->amplitudes, p->amplitude, sizeof c->amplitudes);
    memcpy(c->times, p->time, sizeof c->times);
    return 0;
}

/* Config of stage k from its parameters; 0 or non-zero with msg. */
static int stage_config(const ss_model *m, unsigned k, sms_stage_config *c, char *msg, size_t len)
{
    const int kind = m->stage[k].ints[SS_FIELD_KIND];
    const int for_mode = m->stage[k].ints[SS_FIELD_DESIGN] == 1;
    sms_status st;
    if (stage_fields(m, k, c, msg, len) != 0)
        return 1;
    st = sms_stage_config_validate(c, m->Ts);
    if (st == SMS_ERR_SAMPLE_PERIOD)
        return snprintf(msg, len, "Ts = %.17g: must be finite and > 0", m->Ts), 1;
    if (st == SMS_ERR_IMPULSE_AMPLITUDE || st == SMS_ERR_IMPULSE_TIME
        || (kind == SMS_SHAPER_IMPULSES && st == SMS_ERR_TOO_LONG))
        return impulses_error(m, k, st, msg, len);
    if (st != SMS_OK)
        return stage_error(m, k, st, for_mode, msg, len);
    return 0;
}

/* The filtering a long step needs to absorb a new input (sms_chain_hold_cost()) within
 * FMU_MAX_HOLD_SAMPLES; else 1 with msg naming the stage that takes longest alone. */
static int hold_too_long(const ss_model *m, const sms_stage_config *configs,
                         const unsigned *used, size_t n, char *msg, size_t len)
{
    double cost, worst = -1.0;
    size_t i, slowest = 0;
    char names[256], why[160];
    const ss_params *p;
    if (sms_chain_hold_cost(configs, n, m->Ts, &cost) != SMS_OK || cost <= FMU_MAX_HOLD_SAMPLES)
        return 0;
    for (i = 0; i < n; ++i) {
        double alone;
        (void)sms_chain_hold_cost(&configs[i], 1, m->Ts, &alone);
        if (alone > worst) {
            worst = alone;
            slowest = i;
        }
    }
    p = &m->stage[used[slowest]];
    if (configs[slowest].kind == SMS_NOTCH_TUSTIN || configs[slowest].kind == SMS_NOTCH_MATCHED) {
        snprintf(names, sizeof names, "stage[%u].wn = %.17g, stage[%u].notch_pole_zeta = %.17g, "
                 "Ts = %.17g", used[slowest], p->reals[SS_FIELD_WN], used[slowest],
                 p->reals[SS_FIELD_NOTCH_POLE_ZETA], m->Ts);
        snprintf(why, sizeof why, "the notch's transient lasts up to %.4g samples "
                 "(sms_notch_settle_bound: its slowest pole decays too slowly)", worst);
        return fmu_refuse_hold(msg, len, names, cost, why, "raise stage[k].wn, its "
                               "notch_pole_zeta or Ts, or use fewer stages");
    }
    snprintf(names, sizeof names, "stage[%u].kind = %d (the longest stage), Ts = %.17g",
             used[slowest], p->ints[SS_FIELD_KIND], m->Ts);
    snprintf(why, sizeof why, "each stage is filtered until every stage before it has absorbed "
             "the input; the longest alone needs %.4g", worst);
    return fmu_refuse_hold(msg, len, names, cost, why, "shorten the stages or use fewer of them");
}

unsigned fmu_model_real_bytes(void) { return (unsigned)sizeof(sms_real); }

/* The range of the chain from now until the retunes to come have ended
 * (sms_tunable_chain_retune_input_max()): chain position i goes to a configuration of range
 * limit[i] and gain bound gain[i] where pending[i] is set, unless gain[i] is -1 (user-defined
 * impulses, never retuned); 0 while one of them is not valid yet (see pending_range()). */
static double retune_range(const ss_model *m, const int *pending, const double *limit,
                           const double *gain)
{
    int retuned[SS_MAX_STAGES];
    size_t i;
    for (i = 0; i < m->n_active; ++i) {
        retuned[i] = pending[i] && gain[i] != -1.0;
        if (retuned[i] && !(gain[i] > 0.0))
            return 0.0;
    }
    return sms_tunable_chain_retune_input_max(&m->chain, retuned, limit, gain);
}

/* The finite input range of the chain now (sms_tunable_chain_input_max(): below SMS_INPUT_MAX
 * for heavily damped harmonic smoothers and large-gain stages), and with retunes pending the
 * smaller range they lead to: an input set now stays held across them. */
double fmu_model_input_max(const void *model)
{
    const ss_model *m = (const ss_model *)model;
    double x;
    if (!m->built || m->n_active == 0)
        return HUGE_VAL;
    x = m->input_max_stale ? sms_tunable_chain_input_max(&m->chain) : m->input_max;
    if (m->any_pending) {
        const double pending = retune_range(m, m->pending, m->pend_limit, m->pend_gain);
        x = pending < x ? pending : x;
    }
    return x;
}

/* A retune that would narrow the range below a held input is refused (fmu_model_check_tunable),
 * so the inputs a state holds are within its own configuration's range. */
double fmu_model_state_input_max(const void *model)
{
    return fmu_model_input_max(model);
}

/* After ticks: the range of a chain that no longer switches is its configuration's. */
static void refresh_input_max(ss_model *m)
{
    if (m->n_active > 0 && !sms_tunable_chain_switching(&m->chain)) {
        m->input_max = sms_tunable_chain_input_max(&m->chain);
        m->input_max_stale = 0;
    }
}

/* The memory of the longest input smoother of this kind whose delay line holds at most
 * `reals`: every sample of its window is a tap, so its memory grows with its length alone,
 * and each length is reached by some wn (the kernel lasts c/wn). Bisection on log wn for the
 * smallest wn whose length fits (below it: too long; above: fits, or too short to be valid).
 * 0 if none fits. */
static size_t input_smoother_capacity(int kind, size_t reals, double Ts)
{
    sms_stage_config c = sms_stage_config_default((sms_kind)kind);
    double lo = 1e-300, hi = 3.14159265358979323846 / Ts;
    size_t r = 0, cells = 0;
    int i;
    for (i = 0; i < 128; ++i) {
        sms_status st;
        c.wn = sqrt(lo) * sqrt(hi);
        st = sms_stage_buffer_size(&c, Ts, &r);
        if (st == SMS_ERR_TOO_LONG || (st == SMS_OK && r > reals))
            lo = c.wn;
        else
            hi = c.wn;
    }
    c.wn = hi;
    if (sms_stage_buffer_size(&c, Ts, &r) != SMS_OK || r > reals
        || sms_stage_memory_size(&c, Ts, &cells) != SMS_OK)
        return 0;
    return cells;
}

/* The largest memory among configs of a family lasting `delay` [s] at Ts: the candidates
 * below, each for the wn (shapers) or T (smoothers) that makes it last that long; 0 if none
 * is valid. */
static size_t family_capacity(int kind, double delay, double Ts)
{
    static const double pi = 3.14159265358979323846;
    sms_stage_config c[6];
    size_t n = 0, i, most = 0;
    if (kind >= SMS_SMOOTH_ZV && kind <= SMS_SMOOTH_SI) {
        /* a dense FIR of the kind: the delay line lasts_longer() still accepts */
        const double reals = floor(delay / Ts + 1e-9) + 2.0;
        return reals < (double)SMS_INPUT_SMOOTHER_MAX_LENGTH
               ? input_smoother_capacity(kind, (size_t)reals, Ts)
               : input_smoother_capacity(kind, SMS_INPUT_SMOOTHER_MAX_LENGTH, Ts);
    }
    if (kind <= SMS_EXPONENTIAL) {   /* smoothers: the longest ring is a bounded rectangle's */
        static const sms_timing timings[3] = {SMS_TIMING_BOUNDED, SMS_TIMING_EXACT, SMS_TIMING_PAPER};
        for (i = 0; i < 3; ++i) {
            c[n] = sms_stage_config_default(SMS_RECTANGULAR);
            c[n].T = delay;
            c[n++].timing = timings[i];
        }
    } else if (kind == SMS_NOTCH_TUSTIN || kind == SMS_NOTCH_MATCHED) {
        c[n] = sms_stage_config_default((sms_kind)kind);
        c[n++].wn = 0.5 * pi / Ts;
    } else {   /* shapers: the most taps and the longest ring for that span */
        unsigned order = (unsigned)(delay / Ts) > 8u ? 8u : (unsigned)(delay / Ts);
        c[n] = sms_stage_config_default(SMS_SHAPER_ZVN);
        c[n].order = order < 1u ? 1u : order;
        c[n].wn = (double)c[n].order * pi / delay;   /* n Td/2 = delay */
        ++n;
        c[n] = sms_stage_config_default(SMS_SHAPER_GMZV);
        c[n].order = SMS_SHAPER_MAX_IMPULSES;
        c[n].wn = 2.0 * pi * c[n].duration / delay;  /* D Td = delay */
        ++n;
        c[n] = sms_stage_config_default(SMS_SHAPER_EI3);
        c[n++].wn = 4.0 * pi / delay;                 /* 2 Td */
    }
    for (i = 0; i < n; ++i) {
        size_t cells;
        if (sms_stage_memory_size(&c[i], Ts, &cells) == SMS_OK && cells > most)
            most = cells;
    }
    return most;
}

/* 1 if config c's delay line is longer than a stage lasting retune_max_delay (whole samples
 * plus the two of exact timing). */
static int lasts_longer(const ss_model *m, const sms_stage_config *c)
{
    size_t reals = 0;
    (void)sms_stage_buffer_size(c, m->Ts, &reals);
    return (double)reals > floor(m->retune_max_delay / m->Ts + 1e-9) + 2.0;
}

/* Cells of the slot of stage k (config c): its own, or with retune_max_delay > 0 those of its
 * family lasting retune_max_delay (fixed parameters only, so a loaded state finds the same
 * slots). 0 or 1 with msg. */
static int slot_size(const ss_model *m, unsigned k, const sms_stage_config *c, size_t *cells,
                     char *msg, size_t len)
{
    size_t own = 0, cap;
    (void)sms_stage_memory_size(c, m->Ts, &own);   /* the config was validated */
    *cells = own;
    /* user-defined impulses are never retuned (their fields are fixed; sms_tunable_retune()
     * refuses them): their own size, whatever retune_max_delay */
    if (!(m->retune_max_delay > 0.0) || c->kind == SMS_SHAPER_IMPULSES)
        return 0;
    cap = family_capacity((int)c->kind, m->retune_max_delay, m->Ts);
    if (cap == 0)
        return snprintf(msg, len, "retune_max_delay = %.17g: no stage of stage[%u]'s family "
                        "(kind = %d) lasts that long at Ts = %.17g (at least a few samples)",
                        m->retune_max_delay, k, (int)c->kind, m->Ts), 1;
    if (own > cap || lasts_longer(m, c))
        return snprintf(msg, len, "stage[%u] (kind = %d) lasts longer than retune_max_delay = "
                        "%.17g s: raise retune_max_delay or shorten the stage", k, (int)c->kind,
                        m->retune_max_delay), 1;
    *cells = cap;
    return 0;
}

/* The scheduled shaper's config from its parameters; 0 (none, or valid) or 1 with msg. */
static int schedule_config(ss_model *m, sms_scheduled_config *c, size_t *reals, char *msg,
                           size_t len)
{
    int j;
    sms_status st;
    *reals = 0;
    if (m->sched_kind == -1)
        return 0;
    if (m->sched_kind < 0 || m->sched_kind > 3)
        return snprintf(msg, len, "schedule.kind = %d is not none (-1), zv (0), zvd (1), zvdd "
                        "(2) or zvn (3)", m->sched_kind), 1;
    if (m->sched_points < 1 || m->sched_points > SS_SCHEDULE_POINTS)
        return snprintf(msg, len, "schedule.points = %d: must be 1 .. %d", m->sched_points,
                        SS_SCHEDULE_POINTS), 1;
    if (m->sched_every < 1 || m->sched_order < 1)
        return snprintf(msg, len, "schedule.%s = %d: must be >= 1", m->sched_every < 1
                        ? "update_every" : "order", m->sched_every < 1 ? m->sched_every
                        : m->sched_order), 1;
    for (j = 0; j < m->sched_points; ++j) {
        m->points[j].value = m->sched[j][0];
        m->points[j].wn = m->sched[j][1];
        m->points[j].zeta = m->sched[j][2];
    }
    c->kind = (sms_kind)(SMS_SHAPER_ZV + m->sched_kind);   /* ZV, ZVD, ZVDD, ZVN in order */
    c->order = (unsigned)m->sched_order;
    c->points = m->points;
    c->n_points = (size_t)m->sched_points;
    c->update_every = (unsigned)m->sched_every;
    st = sms_scheduled_buffer_size(c, m->Ts, reals);
    if (st == SMS_ERR_STATE)
        return snprintf(msg, len, "schedule.value[0 .. %d] must be finite and strictly "
                        "increasing", m->sched_points - 1), 1;
    if (st != SMS_OK)
        return snprintf(msg, len, "schedule (kind = %d, %d rows): %s", m->sched_kind,
                        m->sched_points, sms_status_string(st)), 1;
    return 0;
}

/* Slots per stage: two to switch in when the stages are retunable, else one. */
static size_t slots_per_stage(const ss_model *m)
{
    return m->retune_max_delay > 0.0 ? 2u : 1u;
}

/* Cells holding n reals. */
static size_t cells_of_reals(size_t n)
{
    const size_t per = sizeof(sms_memory_cell) / sizeof(sms_real);
    return n / per + (n % per != 0);
}

/* Validate every parameter: the configs of the used stages, their slots, the scheduled
 * shaper, the reals they need together (within FMU_MAX_REALS) and the cells. 0, or non-zero
 * with msg. */
static int configure(ss_model *m, sms_stage_config *configs, size_t *n, size_t *slots,
                     sms_scheduled_config *sc, size_t *need, char *msg, size_t len)
{
    unsigned k, used[SS_MAX_STAGES];
    size_t i, chain_cells = 0, sched_reals = 0;
    double reals = 0.0;
    *n = 0;
    *need = 0;
    if (!(m->Ts > 0.0))
        return snprintf(msg, len, "Ts = %.17g: must be finite and > 0", m->Ts), 1;
    if (!(m->retune_max_delay >= 0.0))
        return snprintf(msg, len, "retune_max_delay = %.17g: must be >= 0", m->retune_max_delay), 1;
    for (k = 0; k < SS_MAX_STAGES; ++k) {
        if (m->stage[k].ints[SS_FIELD_KIND] == SS_KIND_NONE)
            continue;
        if (stage_config(m, k, &configs[*n], msg, len) != 0)
            return 1;
        if (slot_size(m, k, &configs[*n], &slots[*n], msg, len) != 0)
            return 1;
        used[(*n)++] = k;
    }
    if (schedule_config(m, sc, &sched_reals, msg, len) != 0)
        return 1;
    {   /* the delay lines (per slot) and the ring; name what sets the longest stage */
        size_t most = 0;
        unsigned longest = 0;
        char names[256];
        const ss_params *p;
        for (i = 0; i < *n; ++i) {
            size_t r = 0;
            (void)sms_stage_buffer_size(&configs[i], m->Ts, &r);
            reals += (double)slots_per_stage(m) * (double)(r > slots[i] ? r : slots[i]);
            if (r >= most) {
                most = r;
                longest = used[i];
            }
        }
        reals += (double)sched_reals;
        if (reals > (double)FMU_MAX_REALS) {
            p = &m->stage[longest];
            if (*n == 0)
                snprintf(names, sizeof names, "schedule.wn[0 .. %d], Ts = %.17g",
                         m->sched_points - 1, m->Ts);
            else if (p->ints[SS_FIELD_KIND] == SMS_SHAPER_IMPULSES)
                snprintf(names, sizeof names, "stage[%u].time[%d] = %.17g, Ts = %.17g", longest,
                         p->ints[SS_FIELD_ORDER] - 1, p->time[p->ints[SS_FIELD_ORDER] - 1], m->Ts);
            else if (p->ints[SS_FIELD_DESIGN] == 1 || p->ints[SS_FIELD_KIND] >= SMS_SHAPER_ZV)
                snprintf(names, sizeof names, "stage[%u].wn = %.17g, stage[%u].zeta = %.17g, "
                         "Ts = %.17g", longest, p->reals[SS_FIELD_WN], longest,
                         p->reals[SS_FIELD_ZETA], m->Ts);
            else
                snprintf(names, sizeof names, "stage[%u].T = %.17g, Ts = %.17g", longest,
                         p->reals[SS_FIELD_T], m->Ts);
            return fmu_refuse_size(msg, len, names, reals, m->retune_max_delay > 0.0
                                   ? "shorten the stages or retune_max_delay, or raise Ts"
                                   : *n > 1 ? "shorten the stages (this one is the longest) or "
                                   "raise Ts" : "shorten the stage or raise Ts");
        }
    }
    if (*n > 0 && hold_too_long(m, configs, used, *n, msg, len))
        return 1;
    for (i = 0; i < *n; ++i) {
        m->used[i] = used[i];
        chain_cells += slots_per_stage(m) * slots[i];   /* each below FMU_MAX_REALS: no overflow */
    }
    *need = chain_cells + cells_of_reals(sched_reals);
    return 0;
}

int fmu_model_plan(const void *model, size_t *bytes, char *msg, size_t len)
{
    ss_model probe = *(const ss_model *)model;   /* configure fills the table's points */
    sms_stage_config configs[SS_MAX_STAGES];
    sms_scheduled_config sc;
    size_t n, need, slots[SS_MAX_STAGES];
    if (configure(&probe, configs, &n, slots, &sc, &need, msg, len) != 0)
        return 1;
    *bytes = need * sizeof(sms_memory_cell);
    return 0;
}

/* Doubles of a retunable stage's part of the saved state: a tunable's head and identities, and
 * a stage state of at most the slot's reals per slot (a bound for every family). */
static size_t region_of(size_t slot_cells, size_t slots)
{
    const size_t reals = slot_cells * (sizeof(sms_memory_cell) / sizeof(sms_real));
    return SMS_TUNABLE_STATE_HEAD + 2u * SMS_STATE_IDENTITY_COUNT
           + slots * (SMS_STATE_IDENTITY_COUNT + 14u + reals);
}

static double active_lag(const ss_model *m)
{
    double lag = 0.0;
    size_t i;
    for (i = 0; i < m->n_active; ++i)
        lag += sms_stage_lag(sms_tunable_active(&m->tunables[i]));
    return lag;
}

int fmu_model_build(void *model, void *mem, size_t bytes, char *msg, size_t len)
{
    ss_model *m = (ss_model *)model;
    ss_model b = *m;   /* the model changes only once the build succeeds */
    sms_stage_config configs[SS_MAX_STAGES];
    sms_scheduled_config sc;
    size_t n, need, i, slots[SS_MAX_STAGES], chain_cells = 0, reals = 0;
    if (configure(&b, configs, &n, slots, &sc, &need, msg, len) != 0)
        return 1;
    if (need > bytes / sizeof(sms_memory_cell))
        return snprintf(msg, len, "the stages need %lu bytes of memory, the block holds %lu",
                        (unsigned long)(need * sizeof(sms_memory_cell)), (unsigned long)bytes), 1;
    if (n > 0) {
        double bound;
        for (i = 0; i < n; ++i) {   /* stage after stage, one or two slots each */
            const size_t cells = slots_per_stage(&b) * slots[i];
            if (sms_tunable_init(&b.tunables[i], &configs[i], b.Ts, slots[i],
                                 (sms_memory_cell *)mem + chain_cells, cells) != SMS_OK)
                return snprintf(msg, len, "the chain could not be built"), 1;
            chain_cells += cells;
        }
        b.chain.stages = b.tunables;
        b.chain.n_stages = n;
        b.chain.memory = (sms_memory_cell *)mem;
        b.chain.memory_len = chain_cells;
        bound = sms_tunable_chain_input_max(&b.chain);
        if (fabs(b.u) > bound)
            return snprintf(msg, len, "u = %.17g is beyond %.17g, the finite input range of these "
                            "stages (sms_chain_input_max: the internal sums of a heavily damped "
                            "or high-gain stage would overflow)", b.u, bound), 1;
    }
    b.scheduled = b.sched_kind != -1;
    if (b.scheduled) {
        (void)sms_scheduled_buffer_size(&sc, b.Ts, &reals);
        if (sms_scheduled_init(&b.sch, &sc, b.Ts, &((sms_memory_cell *)mem + chain_cells)->r,
                               reals) != SMS_OK)
            return snprintf(msg, len, "the scheduled shaper could not be built"), 1;
    }
    b.n_active = n;
    b.chain_cells = chain_cells;
    for (i = 0; i < SS_MAX_STAGES; ++i) {
        b.slot_cells[i] = i < n ? slots[i] : 0u;
        /* a fixed stage never switches: its state's own size; a retunable one's bound */
        b.region[i] = i >= n ? 0u : slots_per_stage(&b) == 1u ? sms_tunable_state_count(&b.tunables[i])
                                  : region_of(slots[i], 2u);
        b.pending[i] = 0;
    }
    b.any_pending = 0;
    b.built = 1;
    b.input_max_stale = 1;
    b.peak_cur = fabs(b.u) > fabs(b.s) || !b.scheduled ? fabs(b.u) : fabs(b.s);
    b.peak_prev = 0.0;
    b.epoch_ticks = b.span_max = 0;
    if (n > 0)
        sms_tunable_chain_reset(&b.chain, (sms_real)b.u);
    if (b.scheduled)
        sms_scheduled_reset(&b.sch, (sms_real)b.u, b.s);
    b.y = b.u;
    *m = b;
    if (n > 0)
        sms_tunable_chain_rebind(&m->chain, m->tunables, (sms_memory_cell *)mem);
    m->chain_lag = active_lag(m);
    return 0;
}

/* The rest a stage's slot holds (every family keeps the value of its last reset). */
static double slot_rest(const sms_stage *st)
{
    if (st->kind <= SMS_EXPONENTIAL)
        return fabs((double)st->u.smoother->rest);
    if (st->kind == SMS_NOTCH_TUSTIN || st->kind == SMS_NOTCH_MATCHED)
        return fabs((double)st->u.notch->rest);
    return fabs((double)st->u.shaper->rest);
}

/* Ticks of chain inputs the stages' memory can still depend on, besides the values kept from
 * a reset (slot_rest(), the tunables' h and last input), or 0 when that is not bounded: a
 * notch (IIR: every past input stays in its state, decaying) or the scheduled shaper (not a
 * stage of the chain). A shaper's delay line holds its last L inputs; a smoother's its last
 * `window` inputs and two running sums, each restarted from zero every window samples with a
 * reference input of that moment, so at most 2 window + 2 samples back. A stage's inputs at
 * tick n depend on the chain's inputs back to n - (the lengths of the stages before it), so the
 * sum over every slot (both during a switch) of those counts bounds the chain's. */
static uint64_t memory_span(const ss_model *m)
{
    uint64_t w = 2u;
    size_t i;
    unsigned s;
    if (m->scheduled)
        return 0u;
    for (i = 0; i < m->n_active; ++i) {
        const sms_tunable *t = &m->tunables[i];
        for (s = 0; s < (t->switching ? 2u : 1u); ++s) {
            const sms_stage *st = &t->slot[s == 0 ? t->active : 1u - t->active];
            if (st->kind == SMS_NOTCH_TUSTIN || st->kind == SMS_NOTCH_MATCHED)
                return 0u;
            w += (uint64_t)sms_stage_length(st) + 2u;
            if (st->kind <= SMS_EXPONENTIAL)
                w += 2u * (uint64_t)st->u.smoother->window + 2u;
        }
    }
    return w;
}

/* n ticks of the inputs held: the epochs of held_bound(). With a span (memory_span() > 0) an
 * epoch lasts span_max ticks, the largest span since the build (a retune to a longer filter
 * puts only inputs from its start on into the new slot, so no input older than the spans
 * before it re-enters; the largest is a safe length for every epoch); at its end the epoch
 * becomes the previous one and a new one starts empty. So peak_prev and peak_cur together
 * cover at least the last span_max ticks, which is every input the memory can depend on. With
 * no span nothing rotates and the epoch restarts, so the first two rotations after a notch
 * leaves the chain still count every input before it. O(1) whatever n. */
static void note_inputs(ss_model *m, uint64_t n)
{
    double a = fabs(m->u);
    const uint64_t span = memory_span(m);
    uint64_t left;
    if (m->scheduled && fabs(m->s) > a)
        a = fabs(m->s);
    if (n == 0)
        return;
    if (span == 0) {
        m->peak_cur = a > m->peak_cur ? a : m->peak_cur;
        m->epoch_ticks = 0;
        return;
    }
    if (span > m->span_max)
        m->span_max = span;
    left = m->span_max - (m->epoch_ticks < m->span_max ? m->epoch_ticks : m->span_max);
    m->peak_cur = a > m->peak_cur ? a : m->peak_cur;
    if (n < left) {
        m->epoch_ticks += n;
        return;
    }
    m->peak_prev = m->peak_cur;   /* this epoch ends */
    m->peak_cur = 0.0;
    m->epoch_ticks = 0;
    n -= left;
    if (n >= m->span_max) {       /* whole epochs of a alone; the last is the previous one */
        m->peak_prev = a;
        n %= m->span_max;
    }
    if (n > 0) {
        m->peak_cur = a;
        m->epoch_ticks = n;
    }
}

/* The largest |input| the stages' memory may hold: the inputs of the last span_max ticks or
 * more (note_inputs()), and every value a stage keeps from a reset, whatever its age: each
 * slot's rest, the tunables' held h and last input (the new filter of a retune starts at rest
 * at h = the last input; a stage's rest after ExitInitializationMode is u). A rest of stage
 * i > 0 is a value of that stage's input, which a chain input bound P covers once
 * |rest| <= (1 + 2 G_0 ... G_(i-1)) P: taking |rest| itself is the safe side. O(stages). */
static double held_bound(const ss_model *m)
{
    double b = m->peak_cur > m->peak_prev ? m->peak_cur : m->peak_prev;
    size_t i;
    for (i = 0; i < m->n_active; ++i) {
        const sms_tunable *t = &m->tunables[i];
        double r = slot_rest(&t->slot[t->active]);
        if (t->switching && slot_rest(&t->slot[1u - t->active]) > r)
            r = slot_rest(&t->slot[1u - t->active]);
        if (fabs((double)t->hold) > r)
            r = fabs((double)t->hold);
        if (fabs((double)t->last) > r)
            r = fabs((double)t->last);
        b = r > b ? r : b;
    }
    return b;
}

/* A retune must not narrow the chain's range below an input it holds: u, s, or one in the
 * stages' memory (held_bound()). The range from now until the retunes (those of this call, configs of
 * the stages touched, and those pending) have ended is retune_range(); 1 with msg naming the
 * call's first variable and the values if an input held is beyond it. */
static int narrows_below_held(const ss_model *m, fmu_type type, const fmu_vr *vr,
                              const void *values, size_t n, const int *touched,
                              const sms_stage_config *configs, char *msg, size_t len)
{
    int pend[SS_MAX_STAGES];
    double lim[SS_MAX_STAGES], gain[SS_MAX_STAGES], x;
    const char *what;
    double held;
    char name[64], value[40];
    size_t i, j;
    unsigned k, f;
    for (i = 0; i < m->n_active; ++i) {
        pend[i] = touched[m->used[i]] || m->pending[i];
        lim[i] = m->pend_limit[i];
        gain[i] = m->pend_gain[i];
        if (!touched[m->used[i]])
            continue;
        if (configs[i].kind == SMS_SHAPER_IMPULSES)
            gain[i] = -1.0;   /* never retuned */
        else if (sms_stage_config_limit(&configs[i], m->Ts, &lim[i], &gain[i]) != SMS_OK)
            lim[i] = gain[i] = 0.0;   /* validated above: cannot happen */
    }
    x = retune_range(m, pend, lim, gain);
    if (fabs(m->u) > x) {
        what = "the input u it holds";
        held = fabs(m->u);
    } else if (fabs(m->s) > x) {
        what = "the scheduling input s it holds";
        held = fabs(m->s);
    } else if (held_bound(m) > x) {
        held = held_bound(m);
        what = held >= fmu_model_input_max(m) ? "the largest input the stages' memory may "
               "hold (its whole range: inputs taken before a restored state are not known, "
               "until the stages' memory has been refilled)"
               : "the largest input the stages' memory may hold (the largest |u| or |s| ticked "
               "within the stages' memory span, or a rest value a stage keeps)";
    } else {
        return 0;
    }
    for (j = 0; j + 1 < n && !stage_field(vr[j], &k, &f); ++j)
        ;
    fmu_model_name(type, vr[j], name, sizeof name);
    if (type == FMU_REAL)
        snprintf(value, sizeof value, "%.17g", ((const double *)values)[j]);
    else
        snprintf(value, sizeof value, "%d", (int)((const int32_t *)values)[j]);
    return snprintf(msg, len, "%s = %s: the retuned stages' input range would be %.17g "
                    "(sms_tunable_chain_retune_input_max: larger negative impulses, notch gain "
                    "or correction), below %.17g, %s: the chain would overflow; retune to a "
                    "configuration of a wider range", name, value, x, held, what), 1;
}

int fmu_model_check_tunable(const void *model, fmu_type type, const fmu_vr *vr,
                            const void *values, size_t n, char *msg, size_t len)
{
    const ss_model *m = (const ss_model *)model;
    ss_params trial[SS_MAX_STAGES];
    ss_model probe;
    size_t i;
    unsigned k, f;
    int touched[SS_MAX_STAGES] = {0};
    char name[64];
    if (!(m->retune_max_delay > 0.0)) {
        fmu_model_name(type, vr[0], name, sizeof name);
        return snprintf(msg, len, "%s: the stages are fixed (retune_max_delay = 0): set "
                        "retune_max_delay > 0 before ExitInitializationMode to retune "
                        "them", name), 1;
    }
    memcpy(trial, m->stage, sizeof trial);
    for (i = 0; i < n; ++i)
        if (stage_field(vr[i], &k, &f)) {
            if (type == FMU_REAL)
                trial[k].reals[f] = ((const double *)values)[i];
            else
                trial[k].ints[f] = (int)((const int32_t *)values)[i];
            touched[k] = 1;
        }
    probe.Ts = m->Ts;
    memcpy(probe.stage, trial, sizeof trial);
    for (i = 0; i < m->n_active; ++i) {
        sms_stage_config c;
        size_t cells = 0, j;
        k = m->used[i];
        if (!touched[k])
            continue;
        if (stage_config(&probe, k, &c, msg, len) != 0)
            return 1;
        if (c.kind == SMS_SHAPER_IMPULSES)
            continue;   /* it reads none of the tunable fields: nothing to retune */
        (void)sms_stage_memory_size(&c, m->Ts, &cells);
        if (cells <= m->slot_cells[i] && !lasts_longer(m, &c))
            continue;
        for (j = 0; j < n; ++j)   /* name the first variable of that stage in this call */
            if (stage_field(vr[j], &k, &f) && k == m->used[i])
                break;
        fmu_model_name(type, vr[j < n ? j : 0], name, sizeof name);
        return snprintf(msg, len, "%s: stage[%u] would last longer than retune_max_delay = "
                        "%.17g s, which its memory was sized for", name, m->used[i],
                        m->retune_max_delay), 1;
    }
    {   /* the chain the retunes lead to must absorb a held input within FMU_MAX_HOLD_SAMPLES,
         * as configure() requires at initialization and again when a saved state holding these
         * parameters is loaded (a notch retuned to slowly decaying poles would pass the size
         * check above and then make the FMU refuse its own saved states) */
        sms_stage_config configs[SS_MAX_STAGES];
        unsigned used[SS_MAX_STAGES];
        for (i = 0; i < m->n_active; ++i) {
            used[i] = m->used[i];
            if (stage_config(&probe, m->used[i], &configs[i], msg, len) != 0)
                return 1;
        }
        if (m->n_active > 0 && hold_too_long(&probe, configs, used, m->n_active, msg, len)) {
            char why[FMU_MESSAGE_LEN];
            fmu_model_name(type, vr[0], name, sizeof name);
            snprintf(why, sizeof why, "%s", msg);
            return snprintf(msg, len, "%s: the retuned stages would be too slow to hold: %s",
                            name, why), 1;
        }
        if (m->n_active > 0 && narrows_below_held(m, type, vr, values, n, touched, configs, msg,
                                                  len))
            return 1;
    }
    return 0;
}

/* Retune every chain position whose parameters changed; one still switching waits. */
static void apply_pending(ss_model *m)
{
    char msg[FMU_MESSAGE_LEN];
    size_t i;
    int left = 0, changed = 0;
    for (i = 0; i < m->n_active; ++i) {
        sms_stage_config c;
        sms_status st;
        if (!m->pending[i])
            continue;
        if (stage_config(m, m->used[i], &c, msg, sizeof msg) != 0
            || c.kind == SMS_SHAPER_IMPULSES) {
            m->pending[i] = 0;   /* refused at set: cannot happen; impulses read no tunable */
            continue;
        }
        st = sms_tunable_chain_retune(&m->chain, i, &c);
        if (st == SMS_ERR_RETUNE_BUSY) {
            left = 1;
            continue;
        }
        m->pending[i] = 0;
        changed |= st == SMS_OK;
        m->input_max_stale |= st == SMS_OK;
    }
    m->any_pending = left;
    if (changed)
        m->chain_lag = active_lag(m);
}

int fmu_model_tick(void *model)
{
    ss_model *m = (ss_model *)model;
    sms_real x = (sms_real)m->u;
    double before = m->y;
    note_inputs(m, 1u);
    if (m->any_pending)
        apply_pending(m);
    if (m->n_active > 0)
        sms_tunable_chain_step(&m->chain, &x);
    if (m->scheduled)
        sms_scheduled_step(&m->sch, &x, m->s);
    if (m->input_max_stale)
        refresh_input_max(m);
    m->y = (double)x;
    return m->y != before;
}

/* Every input is valid alone (the glue checks its range when it is set). */
int fmu_model_check_inputs(const void *model, char *msg, size_t len)
{
    (void)model;
    (void)msg;
    (void)len;
    return 0;
}

/* The chain's closed forms under a constant input (sms_tunable_chain_hold()): bit for bit the
 * ticks, bounded by the chain's hold cost, which configure() keeps within
 * FMU_MAX_HOLD_SAMPLES. A pending retune or the scheduled shaper: ticked one by one. */
uint64_t fmu_model_hold(void *model, uint64_t n)
{
    ss_model *m = (ss_model *)model;
    sms_real y;
    if (n == 0 || m->any_pending || m->scheduled)
        return 0;
    note_inputs(m, n);
    if (m->n_active == 0) {
        m->y = (double)(sms_real)m->u;
        return n;
    }
    sms_tunable_chain_hold(&m->chain, (sms_real)m->u, n, &y);
    if (m->input_max_stale)
        refresh_input_max(m);
    m->y = (double)y;
    return n;
}

int fmu_model_warning(void *model, char *msg, size_t len)
{
    (void)model; (void)msg; (void)len;
    return 0; /* every input is taken as it is: nothing to report */
}

void fmu_model_rebind(void *model, void *mem)
{
    ss_model *m = (ss_model *)model;
    if (!m->built)
        return;
    if (m->n_active > 0)
        sms_tunable_chain_rebind(&m->chain, m->tunables, (sms_memory_cell *)mem);
    if (m->scheduled)
        m->sch.ring = &((sms_memory_cell *)mem + m->chain_cells)->r;
}

size_t fmu_model_state_count(const void *model)
{
    const ss_model *m = (const ss_model *)model;
    size_t i, n = 1;
    for (i = 0; i < m->n_active; ++i)
        n += m->region[i];
    return n + (m->scheduled ? sms_scheduled_state_count(&m->sch) : 0u);
}

void fmu_model_save_state(const void *model, double *dst)
{
    const ss_model *m = (const ss_model *)model;
    size_t i, j;
    dst[0] = m->y;
    ++dst;
    for (i = 0; i < m->n_active; ++i) {
        const size_t used = sms_tunable_state_count(&m->tunables[i]);
        sms_tunable_get_state(&m->tunables[i], dst);
        for (j = used; j < m->region[i]; ++j)
            dst[j] = 0.0;
        dst += m->region[i];
    }
    if (m->scheduled)
        sms_scheduled_get_state(&m->sch, dst);
}

/* Same configuration on the fields the kind reads. */
static int same_config(const sms_stage_config *a, const sms_stage_config *b)
{
    const sms_kind k = a->kind;
    if (a->kind != b->kind)
        return 0;
    if (k <= SMS_EXPONENTIAL)
        return a->timing == b->timing && a->T == b->T && a->k == b->k
               && (k == SMS_RECTANGULAR || k == SMS_HARMONIC || a->sigma == b->sigma);
    if (k == SMS_NOTCH_TUSTIN || k == SMS_NOTCH_MATCHED)
        return a->wn == b->wn && a->zeta == b->zeta && a->notch_pole_zeta == b->notch_pole_zeta;
    if (k == SMS_SHAPER_IMPULSES)
        return 1;   /* its fields are fixed parameters: the same as built */
    return a->timing == b->timing && a->wn == b->wn
           && (a->zeta == b->zeta   /* the input smoothers that read no zeta */
               || k == SMS_SMOOTH_EI2 || k == SMS_SMOOTH_ZVD_EI || k == SMS_SMOOTH_SI)
           && ((k != SMS_SHAPER_ZVN && k != SMS_SHAPER_GMZV && k != SMS_SHAPER_SI)
               || a->order == b->order)
           && ((k != SMS_SHAPER_EI && k != SMS_SHAPER_EI2 && k != SMS_SHAPER_EI3
                && k != SMS_SHAPER_SI) || a->tolerance == b->tolerance)
           && ((k != SMS_SHAPER_GMZV && k != SMS_SHAPER_SI) || a->duration == b->duration);
}

/* A state must be one a run can reach: inputs within the chain's range X (the glue refuses
 * others), so stage i's values within what inputs within (1 + 2 G_0 ... G_{i-1}) X leave in it
 * (sms_tunable_check_state_range(), the ranges of sms_chain_check_state_range()), the scheduled
 * shaper's line within the chain's output bound R = (1 + 2 G_0 ... G_{n-1}) X, and y within R,
 * times 1 + 2 sum |g_k| behind the scheduled shaper. */
int fmu_model_load_state(void *model, const double *src, size_t n, char *msg, size_t len)
{
    ss_model *m = (ss_model *)model;
    sms_memory_cell *mem = m->chain.memory;
    const double slack = 1.0 + 0x1p-20;
    double x, product = 1.0, range = 1.0;
    size_t i, j, off = 1, at = 0;
    sms_status st;
    int rebuilt = 0;   /* 1: a stage was built again here (its lag may differ) */
    int kept[SS_MAX_STAGES];   /* stage i was already in its saved configuration */
    if (n != fmu_model_state_count(m))
        return snprintf(msg, len, "it holds %lu values, the stages need %lu", (unsigned long)n,
                        (unsigned long)fmu_model_state_count(m)), 1;
    for (i = 0; i < m->n_active; ++i) {   /* each stage into the configuration it was saved in */
        const double *part = src + off;
        sms_stage_config active, old;
        int switching = 0;
        char why[FMU_MESSAGE_LEN];
        /* already in that configuration (the instance's own, copied, or just built): keep
         * the built filters, no design; sms_tunable_set_state() below loads the values (a
         * stage not switching accepts only a state not switching of its own configuration) */
        if (!m->tunables[i].switching
            && sms_tunable_state_count(&m->tunables[i]) <= m->region[i]
            && sms_tunable_check_state(&m->tunables[i], part,
                                       sms_tunable_state_count(&m->tunables[i])) == SMS_OK) {
            kept[i] = 1;
            off += m->region[i];
            at += slots_per_stage(m) * m->slot_cells[i];
            continue;
        }
        st = sms_tunable_state_configs(part, m->region[i], &active, &old, &switching);
        /* user-defined impulses: the state names them by a checksum; they are fixed
         * parameters, so build them as configured (set_state refuses other impulses) */
        if (st == SMS_ERR_KIND && m->stage[m->used[i]].ints[SS_FIELD_KIND] == SMS_SHAPER_IMPULSES
            && stage_config(m, m->used[i], &active, why, sizeof why) == 0)
            st = SMS_OK;
        if (st != SMS_OK)
            return snprintf(msg, len, "stage %lu's state is not a retunable stage's",
                            (unsigned long)i), 1;
        kept[i] = 0;
        rebuilt = 1;
        m->input_max_stale = 1;   /* the stage is built again */
        if (sms_tunable_init(&m->tunables[i], switching ? &old : &active, m->Ts, m->slot_cells[i],
                             mem + at, slots_per_stage(m) * m->slot_cells[i]) != SMS_OK
            || (switching && sms_tunable_retune(&m->tunables[i], &active) != SMS_OK))
            return snprintf(msg, len, "stage %lu was saved in a configuration its memory "
                            "(retune_max_delay) does not hold", (unsigned long)i), 1;
        off += m->region[i];
        at += slots_per_stage(m) * m->slot_cells[i];
    }
    /* the input range X of the configuration the state was saved in, fixed or retunable alike
     * (sms_tunable_chain_input_max() of the stages as rebuilt: during a switch its smaller
     * range of both filters). Its inputs are within it: every input ticked into the stages'
     * memory and every rest was within the range at its tick, and a retune that would narrow
     * the range below one that memory still holds is refused (narrows_below_held()), so no
     * configuration since has a smaller range than those inputs; the pending retunes' range
     * (smaller still) bounds the held u and s, which the glue checks
     * (fmu_model_state_input_max()). */
    x = m->n_active > 0 ? sms_tunable_chain_input_max(&m->chain) : SMS_INPUT_MAX;
    x = x < SMS_INPUT_MAX ? x : SMS_INPUT_MAX;
    for (i = 0, off = 1; i < m->n_active; ++i) {
        const double *part = src + off;
        /* the part's length as the saving stage had it: a switch saved with a notch fading
         * is loaded into a stage whose rebuilt old notch is at rest (no switch begun yet) */
        const size_t count = sms_tunable_saved_state_count(&m->tunables[i], part, m->region[i]);
        if (count == 0 || count > m->region[i])
            return snprintf(msg, len, "stage %lu's state needs %lu values, its region holds %lu",
                            (unsigned long)i, (unsigned long)count,
                            (unsigned long)m->region[i]), 1;
        for (j = count; j < m->region[i]; ++j)
            if (part[j] != 0.0)
                return snprintf(msg, len, "stage %lu's region is not zero after its %lu values",
                                (unsigned long)i, (unsigned long)count), 1;
        if (sms_tunable_check_state_range(&m->tunables[i], part, count, range * x * slack)
            != SMS_OK)
            return snprintf(msg, len, "stage %lu's values are beyond what inputs within the "
                            "chain's range %.17g leave in it (sms_tunable_check_state_range)",
                            (unsigned long)i, x), 1;
        st = sms_tunable_set_state(&m->tunables[i], part, count);
        if (st != SMS_OK)
            return snprintf(msg, len, "stage %lu refuses its values (sms_tunable_set_state: %s)",
                            (unsigned long)i, sms_status_string(st)), 1;
        product *= sms_tunable_gain_bound(&m->tunables[i]);
        range = 1.0 + 2.0 * product;   /* what stage i + 1 (or the shaper, or y) sees */
        off += m->region[i];
    }
    if (m->scheduled) {   /* its ring holds the chain's outputs; y its taps' sum of them */
        const size_t ring = sms_scheduled_state_count(&m->sch) - 5u;
        double taps = 0.0;
        /* the scheduling input s it follows: an input, so within the range as u is */
        if (!(fabs(src[off + 3]) <= x * slack))
            return snprintf(msg, len, "the scheduled shaper's scheduling input s = %.17g is "
                            "beyond the input range %.17g", src[off + 3], x), 1;
        for (j = 0; j < ring; ++j)
            if (!(fabs(src[off + 5 + j]) <= range * x * slack))
                return snprintf(msg, len, "the scheduled shaper's delay line holds %.17g, beyond "
                                "what inputs within the chain's range %.17g can give",
                                src[off + 5 + j], x), 1;
        st = sms_scheduled_set_state(&m->sch, src + off, n - off);
        if (st != SMS_OK)
            return snprintf(msg, len, "the scheduled shaper refuses its values "
                            "(sms_scheduled_set_state: %s)", sms_status_string(st)), 1;
        for (j = 0; j < m->sch.n_taps; ++j)
            taps += fabs((double)m->sch.gain[j]);
        range *= 1.0 + 2.0 * taps;   /* y = x + sum g_k (x[n - d_k] - x) */
    }
    if (!(fabs(src[0]) <= range * x * slack))
        return snprintf(msg, len, "its output y = %.17g is beyond what inputs within the "
                        "chain's range %.17g can give", src[0], x), 1;
    m->y = src[0];
    m->any_pending = 0;
    for (i = 0; i < m->n_active; ++i) {   /* parameters set since, not yet applied */
        sms_stage_config want, now;
        char why[FMU_MESSAGE_LEN];
        /* a stage kept in its configuration with nothing pending: the model's parameters
         * (the instance's own, copied, or the state's, just built) are the ones that
         * configuration was built or last retuned from, so none awaits a retune (what the
         * comparison below finds, without designing two configs) */
        if (kept[i] && !m->pending[i])
            continue;
        now = sms_tunable_config(&m->tunables[i]);
        /* the parameters of the configuration the stage runs (a valid one): no check, no
         * design; others are checked as a retune would be */
        if (stage_fields(m, m->used[i], &want, why, sizeof why) == 0 && same_config(&want, &now))
            m->pending[i] = 0;
        else
            m->pending[i] = stage_config(m, m->used[i], &want, why, sizeof why) == 0
                            && !same_config(&want, &now);
        m->any_pending |= m->pending[i];
        if (m->pending[i])
            pending_range(m, i);
    }
    if (rebuilt)
        m->chain_lag = active_lag(m);
    /* the inputs the loaded memory holds are not known: up to the range (fmu_model_input_max()
     * after the pending ranges above) */
    m->peak_cur = m->peak_prev = fmu_model_input_max(m) < SMS_INPUT_MAX ? fmu_model_input_max(m)
                                                                         : SMS_INPUT_MAX;
    m->epoch_ticks = 0;   /* two epochs from now the loaded memory has been refilled */
    return 0;
}
