/* SPDX-License-Identifier: Apache-2.0 */
/*
 * SmoothShaper: y = H_7(...H_0(u)) at the internal ticks, a chain of up to SS_MAX_STAGES
 * stages of any family, set by the parameters stage[k].* (unused stages have kind = none).
 * Only the public smoothshaper API is used. At fmi2ExitInitializationMode the chain is put at
 * rest at the current value of u (as if u had held that value forever), so y starts at u.
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

/* Parameters and the chain's descriptors; the stages' memory (instances, tap tables, delay
 * lines) lives in the glue's block, sized to the configured chain. */
typedef struct ss_model {
    double u, y, Ts;
    ss_params stage[SS_MAX_STAGES];
    int built;
    size_t n_active;                     /* stages with kind != none, in chain order */
    sms_chain chain;
    sms_stage stages[SS_MAX_STAGES];
    size_t n_cells;                      /* memory cells of all stages (the glue's block) */
    double input_max;                    /* sms_chain_input_max() of the built chain */
} ss_model;

static int is_integer_field(unsigned f)
{
    return f == SS_FIELD_KIND || f == SS_FIELD_DESIGN || f == SS_FIELD_TIMING || f == SS_FIELD_K
           || f == SS_FIELD_ORDER;
}

/* Split a stage value reference into (stage, field); 0 if it is not one. */
static int stage_field(fmi2ValueReference vr, unsigned *k, unsigned *f)
{
    if (vr < SS_STAGE_BASE || vr >= SS_STAGE_BASE + SS_STAGE_STRIDE * SS_MAX_STAGES)
        return 0;
    *k = (vr - SS_STAGE_BASE) / SS_STAGE_STRIDE;
    *f = (vr - SS_STAGE_BASE) % SS_STAGE_STRIDE;
    return *f < SS_FIELD_COUNT;
}

/* Split an impulse value reference into (stage, impulse, is_time); 0 if it is not one. */
static int impulse_field(fmi2ValueReference vr, unsigned *k, unsigned *i, int *is_time)
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
static double *impulse_slot(ss_model *m, fmi2ValueReference vr)
{
    unsigned k, i;
    int is_time;
    (void)impulse_field(vr, &k, &i, &is_time);
    return is_time ? &m->stage[k].time[i] : &m->stage[k].amplitude[i];
}

size_t fmu_model_size(void) { return sizeof(ss_model); }
const char *fmu_model_identifier(void) { return FMU_MODEL_IDENTIFIER; }
const char *fmu_model_guid(void) { return FMU_MODEL_GUID; }

void fmu_model_defaults(void *model)
{
    ss_model *m = (ss_model *)model;
    unsigned k;
    m->u = 0.0;
    m->y = 0.0;
    m->Ts = 0.001;
    m->built = 0;
    m->n_active = 0;
    for (k = 0; k < SS_MAX_STAGES; ++k) {   /* the start values of modelDescription.xml */
        ss_params *p = &m->stage[k];
        memset(p, 0, sizeof *p);
        p->ints[SS_FIELD_KIND] = SS_DEFAULT_KIND(k);
        p->ints[SS_FIELD_K] = 1;
        p->ints[SS_FIELD_ORDER] = 1;
        p->reals[SS_FIELD_T] = 0.01;
        p->reals[SS_FIELD_WN] = 100.0;
        p->reals[SS_FIELD_TOLERANCE] = 0.05;
        p->reals[SS_FIELD_NOTCH_POLE_ZETA] = 0.7;
        p->reals[SS_FIELD_DURATION] = 0.75;
    }
}

fmu_var_class fmu_model_class(fmu_type type, fmi2ValueReference vr)
{
    unsigned k, f, i;
    int is_time;
    if (type == FMU_REAL && impulse_field(vr, &k, &i, &is_time)) return FMU_VAR_PARAMETER;
    if (type == FMU_REAL && vr == SS_VR_U) return FMU_VAR_INPUT;
    if (type == FMU_REAL && vr == SS_VR_Y) return FMU_VAR_OUTPUT;
    if (type == FMU_REAL && vr == SS_VR_TS) return FMU_VAR_PARAMETER;
    if (stage_field(vr, &k, &f) && is_integer_field(f) == (type == FMU_INTEGER))
        return FMU_VAR_PARAMETER;
    return FMU_VAR_UNKNOWN;
}

void fmu_model_name(fmu_type type, fmi2ValueReference vr, char *buf, size_t len)
{
    unsigned k, f, i;
    int is_time;
    (void)type;
    if (impulse_field(vr, &k, &i, &is_time))
        snprintf(buf, len, "stage[%u].%s[%u]", k, is_time ? "time" : "amplitude", i);
    else if (vr == SS_VR_U || vr == SS_VR_Y || vr == SS_VR_TS)
        snprintf(buf, len, "%s", vr == SS_VR_U ? "u" : vr == SS_VR_Y ? "y" : "Ts");
    else if (stage_field(vr, &k, &f))
        snprintf(buf, len, "stage[%u].%s", k, field_names[f]);
    else
        snprintf(buf, len, "vr %lu", (unsigned long)vr);
}

size_t fmu_model_settable(fmu_type type, fmi2ValueReference *out, size_t cap)
{
    size_t n = 0;
    unsigned k, f;
    if (type == FMU_REAL) {
        if (n < cap) out[n] = SS_VR_U;
        ++n;
        if (n < cap) out[n] = SS_VR_TS;
        ++n;
    }
    for (k = 0; k < SS_MAX_STAGES; ++k)
        for (f = 0; f < SS_FIELD_COUNT; ++f)
            if (is_integer_field(f) == (type == FMU_INTEGER)) {
                if (n < cap) out[n] = SS_STAGE_BASE + SS_STAGE_STRIDE * k + f;
                ++n;
            }
    if (type == FMU_REAL)
        for (k = 0; k < SS_MAX_STAGES; ++k)
            for (f = 0; f < 2u * SS_MAX_IMPULSES; ++f) {
                if (n < cap) out[n] = SS_IMPULSE_BASE + SS_IMPULSE_STRIDE * k + f;
                ++n;
            }
    return n;
}

double fmu_model_get_real(const void *model, fmi2ValueReference vr)
{
    const ss_model *m = (const ss_model *)model;
    unsigned k, f, i;
    int is_time;
    if (impulse_field(vr, &k, &i, &is_time))
        return is_time ? m->stage[k].time[i] : m->stage[k].amplitude[i];
    if (vr == SS_VR_U) return m->u;
    if (vr == SS_VR_Y) return m->y;
    if (vr == SS_VR_TS) return m->Ts;
    return stage_field(vr, &k, &f) ? m->stage[k].reals[f] : 0.0;
}

int fmu_model_get_integer(const void *model, fmi2ValueReference vr)
{
    unsigned k, f;
    return stage_field(vr, &k, &f) ? ((const ss_model *)model)->stage[k].ints[f] : 0;
}

void fmu_model_set_real(void *model, fmi2ValueReference vr, double value)
{
    ss_model *m = (ss_model *)model;
    unsigned k, f, i;
    int is_time;
    if (impulse_field(vr, &k, &i, &is_time)) *impulse_slot(m, vr) = value;
    else if (vr == SS_VR_U) m->u = value;
    else if (vr == SS_VR_TS) m->Ts = value;
    else if (stage_field(vr, &k, &f)) m->stage[k].reals[f] = value;
}

void fmu_model_set_integer(void *model, fmi2ValueReference vr, int value)
{
    unsigned k, f;
    if (stage_field(vr, &k, &f))
        ((ss_model *)model)->stage[k].ints[f] = value;
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

/* Config of stage k from its parameters; 0 or non-zero with msg. */
static int stage_config(const ss_model *m, unsigned k, sms_stage_config *c, char *msg, size_t len)
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

unsigned fmu_model_real_bytes(void) { return (unsigned)sizeof(sms_real); }

/* The chain's finite input range (sms_chain_input_max(): below SMS_INPUT_MAX for heavily
 * damped harmonic smoothers and large-gain stages). */
double fmu_model_input_max(const void *model)
{
    const ss_model *m = (const ss_model *)model;
    return m->built && m->n_active > 0 ? m->input_max : HUGE_VAL;
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

/* Validate every parameter: the configs of the used stages, their count, the delay-line
 * reals they need together (within FMU_MAX_REALS) and the memory cells (the core's size
 * queries: closed forms). 0, or non-zero with msg. */
static int configure(const ss_model *m, sms_stage_config *configs, size_t *n, size_t *need,
                     char *msg, size_t len)
{
    unsigned k, used[SS_MAX_STAGES], longest = 0;
    size_t i, most = 0;
    double samples = 0.0;
    *n = 0;
    *need = 0;
    if (!(m->Ts > 0.0))
        return snprintf(msg, len, "Ts = %.17g: must be finite and > 0", m->Ts), 1;
    for (k = 0; k < SS_MAX_STAGES; ++k) {
        if (m->stage[k].ints[SS_FIELD_KIND] == SS_KIND_NONE)
            continue;
        if (stage_config(m, k, &configs[*n], msg, len) != 0)
            return 1;
        used[(*n)++] = k;
    }
    for (i = 0; i < *n; ++i) {
        size_t reals = 0;
        (void)sms_stage_buffer_size(&configs[i], m->Ts, &reals);
        samples += (double)reals;
        if (reals > most) {
            most = reals;
            longest = used[i];
        }
    }
    if (samples > (double)FMU_MAX_REALS) {
        /* name what sets the longest stage's length: T, or the mode it is designed for */
        const ss_params *p = &m->stage[longest];
        char names[256];
        if (p->ints[SS_FIELD_KIND] == SMS_SHAPER_IMPULSES)
            snprintf(names, sizeof names, "stage[%u].time[%d] = %.17g, Ts = %.17g", longest,
                     p->ints[SS_FIELD_ORDER] - 1, p->time[p->ints[SS_FIELD_ORDER] - 1], m->Ts);
        else if (p->ints[SS_FIELD_DESIGN] == 1 || p->ints[SS_FIELD_KIND] >= SMS_SHAPER_ZV)
            snprintf(names, sizeof names, "stage[%u].wn = %.17g, stage[%u].zeta = %.17g, "
                     "Ts = %.17g", longest, p->reals[SS_FIELD_WN], longest,
                     p->reals[SS_FIELD_ZETA], m->Ts);
        else
            snprintf(names, sizeof names, "stage[%u].T = %.17g, Ts = %.17g", longest,
                     p->reals[SS_FIELD_T], m->Ts);
        return fmu_refuse_size(msg, len, names, samples, *n > 1
                               ? "shorten the stages (this one is the longest) or raise Ts"
                               : "shorten the stage or raise Ts");
    }
    if (*n > 0 && hold_too_long(m, configs, used, *n, msg, len))
        return 1;
    if (*n > 0 && sms_chain_memory_size(configs, *n, m->Ts, need) != SMS_OK)
        return snprintf(msg, len, "the stages do not form a valid chain"), 1;
    return 0;
}

int fmu_model_plan(const void *model, size_t *bytes, char *msg, size_t len)
{
    sms_stage_config configs[SS_MAX_STAGES];
    size_t n, need;
    if (configure((const ss_model *)model, configs, &n, &need, msg, len) != 0)
        return 1;
    *bytes = need * sizeof(sms_memory_cell);
    return 0;
}

int fmu_model_build(void *model, void *mem, size_t bytes, char *msg, size_t len)
{
    ss_model *m = (ss_model *)model;
    sms_stage_config configs[SS_MAX_STAGES];
    size_t n, need;
    if (configure(m, configs, &n, &need, msg, len) != 0)
        return 1;
    if (need > bytes / sizeof(sms_memory_cell))
        return snprintf(msg, len, "the stages need %lu bytes of memory, the block holds %lu",
                        (unsigned long)(need * sizeof(sms_memory_cell)), (unsigned long)bytes), 1;
    if (n > 0) {
        sms_chain chain;
        sms_stage stages[SS_MAX_STAGES];
        double bound;
        if (sms_chain_init(&chain, stages, configs, n, m->Ts, (sms_memory_cell *)mem, need)
            != SMS_OK)
            return snprintf(msg, len, "the chain could not be built"), 1;
        bound = sms_chain_input_max(&chain);
        if (fabs(m->u) > bound)
            return snprintf(msg, len, "u = %.17g is beyond %.17g, the finite input range of these "
                            "stages (sms_chain_input_max: the internal sums of a heavily damped "
                            "or high-gain stage would overflow)", m->u, bound), 1;
        memcpy(m->stages, stages, sizeof stages);
        m->chain = chain;
        m->chain.stages = m->stages;
        m->input_max = bound;
    }
    m->n_active = n;
    m->n_cells = need;
    m->built = 1;
    if (n > 0)
        sms_chain_reset(&m->chain, (sms_real)m->u);
    m->y = m->u;
    return 0;
}

int fmu_model_tick(void *model)
{
    ss_model *m = (ss_model *)model;
    sms_real x = (sms_real)m->u;
    double before = m->y;
    if (m->n_active > 0)
        sms_chain_step(&m->chain, &x);
    m->y = (double)x;
    return m->y != before;
}

/* The chain's closed forms under a constant input (sms_chain_hold()): bit for bit the ticks,
 * bounded by the chain's hold cost, which configure() keeps within FMU_MAX_HOLD_SAMPLES. */
uint64_t fmu_model_hold(void *model, uint64_t n)
{
    ss_model *m = (ss_model *)model;
    sms_real y;
    if (n == 0)
        return 0;
    if (m->n_active == 0) {
        m->y = (double)(sms_real)m->u;
        return n;
    }
    sms_chain_hold(&m->chain, (sms_real)m->u, n, &y);
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
    if (m->built && m->n_active > 0)
        sms_chain_rebind(&m->chain, m->stages, (sms_memory_cell *)mem);
}

size_t fmu_model_state_count(const void *model)
{
    const ss_model *m = (const ss_model *)model;
    return 1 + (m->n_active > 0 ? sms_chain_state_count(&m->chain) : 0);
}

void fmu_model_save_state(const void *model, double *dst)
{
    const ss_model *m = (const ss_model *)model;
    dst[0] = m->y;
    if (m->n_active > 0)
        sms_chain_get_state(&m->chain, dst + 1);
}

int fmu_model_load_state(void *model, const double *src, size_t n, char *msg, size_t len)
{
    ss_model *m = (ss_model *)model;
    (void)msg;
    (void)len;
    if (n != fmu_model_state_count(m) || src[0] != src[0])
        return 1;
    if (m->n_active > 0 && sms_chain_set_state(&m->chain, src + 1, n - 1) != SMS_OK)
        return 1;
    m->y = src[0];
    return 0;
}
