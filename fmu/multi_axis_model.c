/* SPDX-License-Identifier: Apache-2.0 */
/*
 * MultiAxisGenerator: the multi-axis online generator of the smoothshaper library
 * (sms_multi_generator_*, multi_generator.h) as an FMU. Inputs target[i]; outputs q[i], v[i],
 * a[i], j[i] at the internal ticks, every axis within its own vmax[i], amax[i], jmax[i].
 * Parameters: Ts, axes (1..8), sync (0 phase-synchronised, 1 independent), align (1: every
 * axis padded to the common lag of the stages; the output lag reports it), per-axis limits,
 * the rest position q0[i] and up to MA_MAX_STAGES vibration stages per axis
 * (stage[k].kind[i], designed for the mode stage[k].wn[i], stage[k].zeta[i]), and per-axis
 * position limits qmin[i], qmax[i] (both 0: none; a target outside fails the step). At
 * fmi2ExitInitializationMode the generator rests at q0 (so a target that differs from q0 at
 * t = 0 moves from the first tick on); axes in use with different stages get a warning (they
 * bend straight moves). The stage structs and delay lines live in the glue's block.
 */
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include "smoothshaper/smoothshaper.h"
#include "MultiAxisGenerator_variables.h"
#include "fmu_model.h"

typedef struct ma_model {
    double field[MA_FIELD_COUNT][MA_MAX_AXES]; /* target, q, v, a, j, vmax, amax, jmax, q0 */
    int kind[MA_MAX_STAGES][MA_MAX_AXES];      /* stage[k].kind[i] */
    double wn[MA_MAX_STAGES][MA_MAX_AXES], zeta[MA_MAX_STAGES][MA_MAX_AXES];
    double qlim[2][MA_MAX_AXES];               /* qmin[i], qmax[i]; both 0: none */
    double Ts;
    int axes, sync, align;
    int built;
    int warned[MA_MAX_AXES];                   /* 1: move i's dropped target was logged */
    double dropped[MA_MAX_AXES];               /* the target of axis i when it was */
    size_t n_cells;                            /* stage memory cells at the block's start,
                                                  then the sms_stage structs */
    sms_multi_generator gen;
} ma_model;

/* The stage configs of every axis in use (stages of kind none skipped). */
typedef struct ma_stages {
    sms_stage_config config[MA_MAX_AXES][MA_MAX_STAGES];
    int index[MA_MAX_AXES][MA_MAX_STAGES]; /* k of each config: stage[k] */
    size_t n[MA_MAX_AXES];
} ma_stages;

/* Fields in the order of MA_FIELDS (generate.py): index f - 1 of value reference 100 f + i. */
enum { F_TARGET, F_Q, F_V, F_A, F_J, F_VMAX, F_AMAX, F_JMAX, F_Q0 };
static const char *const field_names[MA_FIELD_COUNT] = {
    "target", "q", "v", "a", "j", "vmax", "amax", "jmax", "q0"
};

/* Stage k, field g and axis i of a stage value reference; 0 if it is not one. */
static int stage_var(fmu_vr vr, int *k, int *g, int *axis)
{
    unsigned r;
    if (vr < MA_STAGE_BASE || vr >= MA_STAGE_BASE + 100u * MA_STAGE_STRIDE * MA_MAX_STAGES ||
        vr % 100 >= MA_MAX_AXES)
        return 0;
    r = (vr - MA_STAGE_BASE) / 100;
    *k = (int)(r / MA_STAGE_STRIDE);
    *g = (int)(r % MA_STAGE_STRIDE);
    *axis = (int)(vr % 100);
    return 1;
}

static const char *const stage_field_names[MA_STAGE_STRIDE] = {"kind", "wn", "zeta"};

/* Field and axis of a Real value reference; 0 if it is not an axis variable. */
static int axis_var(fmu_vr vr, int *field, int *axis)
{
    if (vr < 100 || vr >= 100u * (MA_FIELD_COUNT + 1) || vr % 100 >= MA_MAX_AXES)
        return 0;
    *field = (int)(vr / 100) - 1;
    *axis = (int)(vr % 100);
    return 1;
}

/* Position limit (0 qmin, 1 qmax) and axis of a value reference; 0 if it is not one. */
static int qlim_var(fmu_vr vr, int *which, int *axis)
{
    if (vr < MA_QLIM_BASE || vr >= MA_QLIM_BASE + 200u || vr % 100 >= MA_MAX_AXES)
        return 0;
    *which = (int)((vr - MA_QLIM_BASE) / 100);
    *axis = (int)(vr % 100);
    return 1;
}

static const char *const qlim_names[2] = {"qmin", "qmax"};

size_t fmu_model_size(void) { return sizeof(ma_model); }
const char *fmu_model_identifier(void) { return FMU_MODEL_IDENTIFIER; }
const char *fmu_model_guid(void) { return FMU_MODEL_GUID; }

void fmu_model_defaults(void *model)
{
    ma_model *m = (ma_model *)model;   /* the start values of modelDescription.xml */
    int i;
    memset(m->field, 0, sizeof m->field);
    memset(m->qlim, 0, sizeof m->qlim);
    memset(m->warned, 0, sizeof m->warned);
    for (i = 0; i < MA_MAX_AXES; ++i) {
        int k;
        m->field[F_VMAX][i] = 1.0;
        m->field[F_AMAX][i] = 10.0;
        m->field[F_JMAX][i] = 100.0;
        for (k = 0; k < MA_MAX_STAGES; ++k) {
            m->kind[k][i] = -1;
            m->wn[k][i] = 100.0;
            m->zeta[k][i] = 0.0;
        }
    }
    m->n_cells = 0;
    m->Ts = 0.001;
    m->axes = 3;
    m->sync = SMS_SYNC_PHASE;
    m->align = 0;
    m->built = 0;
}

fmu_var_class fmu_model_class(fmu_type type, fmu_vr vr)
{
    int f, i, k;
    if (stage_var(vr, &k, &f, &i))
        return (f == MA_STAGE_KIND) == (type == FMU_INTEGER) ? FMU_VAR_PARAMETER
                                                             : FMU_VAR_UNKNOWN;
    if (type == FMU_INTEGER)
        return vr == MA_VR_AXES || vr == MA_VR_SYNC || vr == MA_VR_ALIGN ? FMU_VAR_PARAMETER
                                                                         : FMU_VAR_UNKNOWN;
    if (vr == MA_VR_TS || qlim_var(vr, &f, &i))
        return FMU_VAR_PARAMETER;
    if (vr == MA_VR_LAG)
        return FMU_VAR_OUTPUT;
    if (!axis_var(vr, &f, &i))
        return FMU_VAR_UNKNOWN;
    return f == F_TARGET ? FMU_VAR_INPUT : f <= F_J ? FMU_VAR_OUTPUT : FMU_VAR_PARAMETER;
}

void fmu_model_name(fmu_type type, fmu_vr vr, char *buf, size_t len)
{
    int f, i, k;
    if (stage_var(vr, &k, &f, &i))
        snprintf(buf, len, "stage[%d].%s[%d]", k, stage_field_names[f], i);
    else if (type == FMU_INTEGER && (vr == MA_VR_AXES || vr == MA_VR_SYNC || vr == MA_VR_ALIGN))
        snprintf(buf, len, "%s", vr == MA_VR_AXES ? "axes" : vr == MA_VR_SYNC ? "sync" : "align");
    else if (type == FMU_REAL && (vr == MA_VR_TS || vr == MA_VR_LAG))
        snprintf(buf, len, "%s", vr == MA_VR_TS ? "Ts" : "lag");
    else if (type == FMU_REAL && axis_var(vr, &f, &i))
        snprintf(buf, len, "%s[%d]", field_names[f], i);
    else if (type == FMU_REAL && qlim_var(vr, &f, &i))
        snprintf(buf, len, "%s[%d]", qlim_names[f], i);
    else
        snprintf(buf, len, "vr %lu", (unsigned long)vr);
}

size_t fmu_model_settable(fmu_type type, fmu_vr *out, size_t cap)
{
    size_t n = 0;
    int f, i, k;
    if (type == FMU_INTEGER) {
        if (n < cap) out[n] = MA_VR_AXES;
        ++n;
        if (n < cap) out[n] = MA_VR_SYNC;
        ++n;
        if (n < cap) out[n] = MA_VR_ALIGN;
        ++n;
    } else {
        if (n < cap) out[n] = MA_VR_TS;
        ++n;
        for (f = 0; f < MA_FIELD_COUNT; ++f) {
            if (f >= F_Q && f <= F_J)
                continue;
            for (i = 0; i < MA_MAX_AXES; ++i) {
                if (n < cap) out[n] = (fmu_vr)(100 * (f + 1) + i);
                ++n;
            }
        }
        for (f = 0; f < 2; ++f)
            for (i = 0; i < MA_MAX_AXES; ++i) {
                if (n < cap) out[n] = (fmu_vr)(MA_QLIM_BASE + 100 * f + i);
                ++n;
            }
    }
    for (k = 0; k < MA_MAX_STAGES; ++k)
        for (f = 0; f < MA_STAGE_STRIDE; ++f) {
            if ((f == MA_STAGE_KIND) != (type == FMU_INTEGER))
                continue;
            for (i = 0; i < MA_MAX_AXES; ++i) {
                if (n < cap)
                    out[n] = (fmu_vr)(MA_STAGE_BASE + 100 * (MA_STAGE_STRIDE * k + f) + i);
                ++n;
            }
        }
    return n;
}

double fmu_model_get_real(const void *model, fmu_vr vr)
{
    const ma_model *m = (const ma_model *)model;
    int f, i, k;
    if (vr == MA_VR_TS)
        return m->Ts;
    if (vr == MA_VR_LAG)
        return m->built ? sms_multi_generator_lag(&m->gen) : 0.0;
    if (stage_var(vr, &k, &f, &i))
        return f == MA_STAGE_WN ? m->wn[k][i] : m->zeta[k][i];
    if (qlim_var(vr, &f, &i))
        return m->qlim[f][i];
    return axis_var(vr, &f, &i) ? m->field[f][i] : 0.0;
}

int fmu_model_get_integer(const void *model, fmu_vr vr)
{
    const ma_model *m = (const ma_model *)model;
    int f, i, k;
    if (stage_var(vr, &k, &f, &i))
        return m->kind[k][i];
    return vr == MA_VR_AXES ? m->axes : vr == MA_VR_SYNC ? m->sync
           : vr == MA_VR_ALIGN ? m->align : 0;
}

int fmu_model_check_tunable(const void *model, fmu_type type, const fmu_vr *vr,
                            const void *values, size_t n, char *msg, size_t len)
{
    (void)model; (void)type; (void)vr; (void)values; (void)n; (void)msg; (void)len;
    return 0;   /* no tunable parameters */
}

void fmu_model_set_real(void *model, fmu_vr vr, double value)
{
    ma_model *m = (ma_model *)model;
    int f, i, k;
    if (vr == MA_VR_TS)
        m->Ts = value;
    else if (stage_var(vr, &k, &f, &i))
        *(f == MA_STAGE_WN ? &m->wn[k][i] : &m->zeta[k][i]) = value;
    else if (qlim_var(vr, &f, &i))
        m->qlim[f][i] = value;
    else if (axis_var(vr, &f, &i))
        m->field[f][i] = value;
}

void fmu_model_set_integer(void *model, fmu_vr vr, int value)
{
    ma_model *m = (ma_model *)model;
    int f, i, k;
    if (stage_var(vr, &k, &f, &i))
        m->kind[k][i] = value;
    else if (vr == MA_VR_AXES)
        m->axes = value;
    else if (vr == MA_VR_SYNC)
        m->sync = value;
    else if (vr == MA_VR_ALIGN)
        m->align = value;
}

double fmu_model_sample_period(const void *model) { return ((const ma_model *)model)->Ts; }

unsigned fmu_model_real_bytes(void) { return (unsigned)sizeof(sms_real); }
/* The finite input range of the stages, the smallest over the axes in use (sms_chain_input_max of
 * each axis's chain, the same for its four signals): targets beyond it are refused at set, as
 * q0, vmax, amax and jmax beyond it are at initialisation. HUGE_VAL without stages. */
static double stages_input_max(const ma_model *m)
{
    double bound = HUGE_VAL;
    int i;
    for (i = 0; i < m->axes; ++i)
        if (m->gen.chain[i][0].n_stages > 0 && sms_chain_input_max(&m->gen.chain[i][0]) < bound)
            bound = sms_chain_input_max(&m->gen.chain[i][0]);
    return bound;
}

double fmu_model_input_max(const void *model)
{
    const ma_model *m = (const ma_model *)model;
    return m->built ? stages_input_max(m) : HUGE_VAL;
}

/* Its inputs are checked against the configuration that holds them: the same range. */
double fmu_model_state_input_max(const void *model)
{
    return fmu_model_input_max(model);
}

/* Config of stage k of axis i (designed for its mode); 0, or 1 with msg naming the variable. */
static int stage_config(const ma_model *m, int k, int i, sms_stage_config *c, char *msg,
                        size_t len)
{
    int kind = m->kind[k][i];
    const char *why;
    sms_status st;
    if (kind < 0 || kind >= SMS_KIND_COUNT)
        return snprintf(msg, len, "stage[%d].kind[%d] = %d is not a stage kind code (-1 = none, "
                        "0 .. %d)", k, i, kind, SMS_KIND_COUNT - 1), 1;
    st = sms_design_for_mode((sms_kind)kind, m->wn[k][i], m->zeta[k][i], 1u, c);
    if (st == SMS_OK)
        st = sms_stage_config_validate(c, m->Ts);
    if (st == SMS_OK)
        return 0;
    why = sms_status_string(st);
    switch (st) {
    case SMS_ERR_ZETA: case SMS_ERR_SIGMA:
        return snprintf(msg, len, "stage[%d].zeta[%d] = %.17g: %s", k, i, m->zeta[k][i], why), 1;
    case SMS_ERR_KIND:
        return snprintf(msg, len, "stage[%d].kind[%d] = %d: %s", k, i, kind, why), 1;
    default: /* wn, and the durations designed from it */
        return snprintf(msg, len, "stage[%d].wn[%d] = %.17g: %s", k, i, m->wn[k][i], why), 1;
    }
}

/* A long step filters every stage of every axis and signal for the last S + 2 samples, S the
 * largest chain's settle bound (sms_chain_settle_bound(): sum of 2 M + 2, L + 1, a notch's
 * decay): within FMU_MAX_HOLD_SAMPLES stage-samples, else 1 with msg naming the axis whose
 * chain is slowest. */
static int hold_too_long(const ma_model *m, const ma_stages *s, char *msg, size_t len)
{
    double worst = 0.0, stages = 0.0;
    int i, slowest = 0;
    size_t k;
    for (i = 0; i < m->axes; ++i) {
        double bound = 0.0;
        for (k = 0; k < s->n[i]; ++k) {
            double b;
            if (sms_chain_hold_cost(&s->config[i][k], 1, m->Ts, &b) != SMS_OK)
                return 0;   /* an invalid stage: refused by its own check */
            bound += b;
        }
        stages += 4.0 * (double)s->n[i];
        if (bound > worst) {
            worst = bound;
            slowest = i;
        }
    }
    if (!((worst + 2.0) * stages > FMU_MAX_HOLD_SAMPLES))
        return 0;
    {
        char names[160], why[200];
        snprintf(names, sizeof names, "the stages of axis %d (stage[k].kind[%d], stage[k].wn[%d]),"
                 " Ts = %.17g", slowest, slowest, slowest, m->Ts);
        snprintf(why, sizeof why, "%.0f stages (4 signals per axis) over the last %.4g samples, "
                 "the slowest chain's settle bound", stages, worst + 2.0);
        return fmu_refuse_hold(msg, len, names, (worst + 2.0) * stages, why,
                               "raise the stages' wn or Ts, or use fewer stages or axes");
    }
}

/* The stages of every axis in use, their delay lines (4 signals each) within FMU_MAX_REALS
 * together; 0, or 1 with msg. */
static int stage_configs(const ma_model *m, ma_stages *s, char *msg, size_t len)
{
    double samples = 0.0;
    size_t most = 0;
    int i, k, longest_k = 0, longest_i = 0;
    for (i = 0; i < m->axes; ++i) {
        s->n[i] = 0;
        for (k = 0; k < MA_MAX_STAGES; ++k) {
            size_t reals = 0;
            if (m->kind[k][i] == -1)
                continue;
            if (stage_config(m, k, i, &s->config[i][s->n[i]], msg, len) != 0)
                return 1;
            (void)sms_stage_buffer_size(&s->config[i][s->n[i]], m->Ts, &reals);
            samples += 4.0 * (double)reals;
            if (reals > most) {
                most = reals;
                longest_k = k;
                longest_i = i;
            }
            s->index[i][s->n[i]++] = k;
        }
    }
    if (samples > (double)FMU_MAX_REALS) {
        char names[256];
        snprintf(names, sizeof names, "stage[%d].wn[%d] = %.17g, stage[%d].zeta[%d] = %.17g, "
                 "Ts = %.17g (the longest stage, 4 signals each)", longest_k, longest_i,
                 m->wn[longest_k][longest_i], longest_k, longest_i,
                 m->zeta[longest_k][longest_i], m->Ts);
        return fmu_refuse_size(msg, len, names, samples,
                               "raise the stages' wn or Ts, or use fewer stages or axes");
    }
    return hold_too_long(m, s, msg, len);
}

/* Do axes i and 0 have the same stages (kinds and modes, in order)? */
static int same_stages(const ma_model *m, const ma_stages *s, int i)
{
    size_t n;
    if (s->n[i] != s->n[0])
        return 0;
    for (n = 0; n < s->n[0]; ++n) {
        int a = s->index[0][n], b = s->index[i][n];
        if (m->kind[a][0] != m->kind[b][i] || m->wn[a][0] != m->wn[b][i] ||
            m->zeta[a][0] != m->zeta[b][i])
            return 0;
    }
    return 1;
}

/* Validate every parameter into c and s (O(axes stages)); sizes of the stages' memory.
 * 0, or 1 with msg naming the variable. */
static int configure(const ma_model *m, sms_multi_generator_config *c, ma_stages *s,
                     size_t *n_structs, size_t *n_cells, char *msg, size_t len)
{
    size_t bad = 0;
    sms_status st;
    int i, f;
    if (!(m->Ts > 0.0))
        return snprintf(msg, len, "Ts = %.17g: must be finite and > 0", m->Ts), 1;
    if (m->axes < 1 || m->axes > MA_MAX_AXES)
        return snprintf(msg, len, "axes = %d: must be 1 .. %d", m->axes, MA_MAX_AXES), 1;
    if (m->sync != SMS_SYNC_PHASE && m->sync != SMS_SYNC_INDEPENDENT)
        return snprintf(msg, len, "sync = %d is not phase (0) or independent (1)", m->sync), 1;
    if (m->align != 0 && m->align != 1)
        return snprintf(msg, len, "align = %d is not off (0) or on (1)", m->align), 1;
    for (f = F_VMAX; f <= F_JMAX; ++f)
        for (i = 0; i < m->axes; ++i)
            if (!(m->field[f][i] > 0.0))
                return snprintf(msg, len, "%s[%d] = %.17g: must be > 0", field_names[f], i,
                                m->field[f][i]), 1;
    for (i = 0; i < m->axes; ++i) {
        sms_real q0 = (sms_real)m->field[F_Q0][i]; /* finite in double, maybe not in float */
        const double lo = m->qlim[0][i], hi = m->qlim[1][i];
        if (q0 - q0 != 0)
            return snprintf(msg, len, "q0[%d] = %.17g: the rest position must be finite in "
                            "the signal type", i, m->field[F_Q0][i]), 1;
        if (lo == 0.0 && hi == 0.0)
            continue;
        if (!isfinite(lo) || !isfinite(hi) || !((sms_real)lo < (sms_real)hi))
            return snprintf(msg, len, "qmin[%d] = %.17g, qmax[%d] = %.17g: position limits "
                            "must be finite with qmin < qmax (both 0: none)", i, lo, i, hi), 1;
        if (!(m->field[F_Q0][i] >= lo && m->field[F_Q0][i] <= hi))
            return snprintf(msg, len, "q0[%d] = %.17g is outside [qmin[%d], qmax[%d]] = "
                            "[%.17g, %.17g]", i, m->field[F_Q0][i], i, i, lo, hi), 1;
    }
    if (stage_configs(m, s, msg, len) != 0)
        return 1;
    memset(c, 0, sizeof *c);
    c->n_axes = (size_t)m->axes;
    c->sync = (sms_sync)m->sync;
    c->align = m->align;
    for (i = 0; i < m->axes; ++i) {
        c->vmax[i] = m->field[F_VMAX][i];
        c->amax[i] = m->field[F_AMAX][i];
        c->jmax[i] = m->field[F_JMAX][i];
        c->stages[i] = s->n[i] > 0 ? s->config[i] : NULL;
        c->n_stages[i] = s->n[i];
        c->qmin[i] = m->qlim[0][i]; /* both 0: no position limits */
        c->qmax[i] = m->qlim[1][i];
    }
    st = sms_multi_generator_memory(c, m->Ts, n_structs, n_cells, &bad); /* the core's checks */
    if (st == SMS_ERR_LIMIT) {
        sms_generator_reach_info r;
        (void)sms_multi_generator_reach(c, m->Ts, &r, &bad);
        if (r.quantity == NULL) /* a limit not finite and > 0 */
            return snprintf(msg, len, "vmax[%d], amax[%d], jmax[%d] = %.17g, %.17g, %.17g: %s",
                            (int)bad, (int)bad, (int)bad, c->vmax[bad], c->amax[bad],
                            c->jmax[bad], sms_status_string(st)), 1;
        /* limits with which no move of axis `bad` can reach its vmax: the quantity out of
         * range, formed from the arguments r.arguments of that axis */
        return snprintf(msg, len, "axis %d: vmax[%d] = %.17g, amax[%d] = %.17g, jmax[%d] = "
                        "%.17g, Ts = %.17g: %s (of %s) = %.6g is %s its bound %.6g, so no move "
                        "of axis %d that reaches vmax[%d] can be planned "
                        "(sms_multi_generator_reach())", (int)bad, (int)bad, c->vmax[bad],
                        (int)bad, c->amax[bad], (int)bad, c->jmax[bad], m->Ts, r.quantity,
                        r.arguments, r.value, r.value < r.bound ? "below" : "above", r.bound,
                        (int)bad, (int)bad), 1;
    }
    if (st != SMS_OK && s->n[bad] > 0)
        return snprintf(msg, len, "stages of axis %d (stage[k].kind[%d]): %s", (int)bad, (int)bad,
                        sms_status_string(st)), 1;
    if (st != SMS_OK)
        return snprintf(msg, len, "Ts = %.17g: %s", m->Ts, sms_status_string(st)), 1;
    return 0;
}

/* Bytes of the block: the stage memory cells (aligned for anything a stage holds), then the
 * stage structs. */
static size_t block_bytes(size_t n_structs, size_t n_cells)
{
    return n_cells * sizeof(sms_memory_cell) + n_structs * sizeof(sms_stage);
}

int fmu_model_plan(const void *model, size_t *bytes, char *msg, size_t len)
{
    sms_multi_generator_config c;
    ma_stages s;
    size_t n_structs, n_cells;
    if (configure((const ma_model *)model, &c, &s, &n_structs, &n_cells, msg, len) != 0)
        return 1;
    *bytes = block_bytes(n_structs, n_cells);
    return 0;
}

int fmu_model_build(void *model, void *mem, size_t bytes, char *msg, size_t len)
{
    ma_model *m = (ma_model *)model;
    sms_multi_generator_config c;
    sms_multi_generator g;   /* the model changes only once the build succeeds */
    ma_stages s;
    sms_real rest[MA_MAX_AXES];
    size_t n_structs, n_cells;
    int i, differ = -1;
    if (configure(m, &c, &s, &n_structs, &n_cells, msg, len) != 0)
        return 1;
    if (block_bytes(n_structs, n_cells) > bytes)
        return snprintf(msg, len, "the stages need %lu bytes, the block holds %lu",
                        (unsigned long)block_bytes(n_structs, n_cells), (unsigned long)bytes), 1;
    if (sms_multi_generator_init(&g, &c, m->Ts,
                                 (sms_stage *)((sms_memory_cell *)mem + n_cells), n_structs,
                                 (sms_memory_cell *)mem, n_cells, NULL) != SMS_OK)
        return snprintf(msg, len, "Ts = %.17g: refused", m->Ts), 1;
    for (i = 0; i < m->axes; ++i) {   /* what the stages filter must keep them finite */
        static const int fields[4] = { F_Q0, F_VMAX, F_AMAX, F_JMAX };
        double bound;
        int f;
        bound = g.chain[i][0].n_stages > 0 ? sms_chain_input_max(&g.chain[i][0]) : SMS_INPUT_MAX;
        if (g.chain[i][0].n_stages == 0) {   /* the positions within the glue's input range */
            if (fabs(m->field[F_Q0][i]) > bound)
                return snprintf(msg, len, "q0[%d] = %.17g is beyond %.17g, the input range "
                                "(SMS_INPUT_MAX)", i, m->field[F_Q0][i], bound), 1;
            continue;
        }
        for (f = 0; f < 4; ++f)
            if (fabs(m->field[fields[f]][i]) > bound)
                return snprintf(msg, len, "%s[%d] = %.17g is beyond %.17g, the finite input range "
                                "of axis %d's stages (sms_chain_input_max: their internal sums "
                                "would overflow)", field_names[fields[f]], i,
                                m->field[fields[f]][i], bound, i), 1;
    }
    m->gen = g;
    m->n_cells = n_cells;
    for (i = 0; i < m->axes; ++i)
        rest[i] = (sms_real)m->field[F_Q0][i];
    sms_multi_generator_reset(&m->gen, rest);
    for (i = 0; i < MA_MAX_AXES; ++i) {
        m->field[F_Q][i] = i < m->axes ? (double)rest[i] : 0.0;
        m->field[F_V][i] = m->field[F_A][i] = m->field[F_J][i] = 0.0;
    }
    m->built = 1;
    for (i = 1; i < m->axes && differ < 0; ++i)
        if (!same_stages(m, &s, i))
            differ = i;
    if (differ > 0 && m->align)
        return snprintf(msg, len, "axes 0 and %d have different vibration stages "
                        "(stage[k].kind/wn/zeta): aligned (align = 1), straight moves stay on "
                        "the line at constant speed, but the accelerations are smoothed "
                        "differently and bend", differ), -1;
    if (differ > 0)
        return snprintf(msg, len, "axes 0 and %d have different vibration stages "
                        "(stage[k].kind/wn/zeta): straight moves bend, the axes are delayed and "
                        "smoothed differently (align = 1 keeps constant-speed segments on the "
                        "line)", differ), -1;
    return 0;
}

int fmu_model_tick(void *model)
{
    ma_model *m = (ma_model *)model;
    sms_real target[MA_MAX_AXES], out[4 * MA_MAX_AXES];
    int i, k, changed = 0;
    for (i = 0; i < m->axes; ++i)
        target[i] = (sms_real)m->field[F_TARGET][i];
    sms_multi_generator_step(&m->gen, target, out);
    for (i = 0; i < m->axes; ++i)
        for (k = 0; k < 4; ++k) {
            changed |= m->field[F_Q + k][i] != (double)out[4 * i + k];
            m->field[F_Q + k][i] = (double)out[4 * i + k];
        }
    return changed;
}

/* The generator's closed form under held targets (sms_multi_generator_hold()), the ticks to
 * rounding; it returns 0 (the glue then ticks) only for a notch that does not decay, which
 * fmi2ExitInitializationMode refuses through the hold limit. */
/* Every input is valid alone (the glue checks its range when it is set); with position limits
 * a target outside its axis's [qmin, qmax] fails the step (the generator would keep the
 * previous one without a word). */
int fmu_model_check_inputs(const void *model, char *msg, size_t len)
{
    const ma_model *m = (const ma_model *)model;
    int i;
    for (i = 0; i < m->axes; ++i) {
        const double x = m->field[F_TARGET][i], lo = m->qlim[0][i], hi = m->qlim[1][i];
        if ((lo != 0.0 || hi != 0.0) && !(x >= lo && x <= hi))
            return snprintf(msg, len, "target[%d] = %.17g is outside [qmin[%d], qmax[%d]] = "
                            "[%.17g, %.17g]", i, x, i, i, lo, hi), 1;
    }
    return 0;
}

uint64_t fmu_model_hold(void *model, uint64_t n)
{
    ma_model *m = (ma_model *)model;
    sms_real target[MA_MAX_AXES], out[4 * MA_MAX_AXES];
    uint64_t done;
    int i, k;
    for (i = 0; i < m->axes; ++i)
        target[i] = (sms_real)m->field[F_TARGET][i];
    done = sms_multi_generator_hold(&m->gen, target, n, out);
    if (done > 0)
        for (i = 0; i < m->axes; ++i)
            for (k = 0; k < 4; ++k)
                m->field[F_Q + k][i] = (double)out[4 * i + k];
    return done;
}

/* A dropped target vector (a move's `refused`), once per target: the axes of every group that
 * dropped a new target in this step (all axes in phase synchronisation, each axis alone when
 * independent, so two axes dropping in one step are both named) with their targets, and the
 * user's limits of the farthest of them. */
int fmu_model_warning(void *model, char *msg, size_t len)
{
    ma_model *m = (ma_model *)model;
    int g, i, n, groups = m->sync == SMS_SYNC_PHASE ? 1 : m->axes, far = -1;
    int fresh[MA_MAX_AXES] = { 0 };   /* 1: axis i is in a group that dropped a new target */
    double farthest = -1.0;
    for (g = 0; g < groups && m->built; ++g) {
        int first = m->sync == SMS_SYNC_PHASE ? 0 : g, last = m->sync == SMS_SYNC_PHASE
                                                              ? m->axes : g + 1, same = 1;
        if (!m->gen.move[g].refused) {
            m->warned[g] = 0;
            continue;
        }
        for (i = first; i < last; ++i)
            same &= m->dropped[i] == (double)m->gen.target[i];
        if (m->warned[g] && same)
            continue;
        m->warned[g] = 1;
        for (i = first; i < last; ++i) {
            m->dropped[i] = (double)m->gen.target[i];
            fresh[i] = 1;
        }
    }
    n = 0;
    for (i = 0; i < m->axes && n >= 0 && (size_t)n < len; ++i) {
        double span;
        if (!fresh[i])
            continue;
        span = fabs(m->dropped[i] - (double)m->gen.goal[i]) / m->field[F_VMAX][i] / m->Ts;
        n += snprintf(msg + n, len - (size_t)n, "%starget[%d] = %.17g", n > 0 ? ", " : "", i,
                      m->dropped[i]);
        if (far < 0 || !(span <= farthest)) {   /* the cruise alone, in samples (may be inf) */
            farthest = span;
            far = i;
        }
    }
    if (far < 0)
        return 0;
    if (n >= 0 && (size_t)n < len)   /* the user's limits of the farthest axis, and Ts */
        snprintf(msg + n, len - (size_t)n, " dropped: the move cannot be represented with "
                 "Ts = %.17g (farthest, axis %d: |target - goal|/vmax[%d] alone is %.3g samples "
                 "of Ts with vmax[%d] = %.17g, amax[%d] = %.17g, jmax[%d] = %.17g; a plan holds "
                 "at most 2^52 and every value must stay finite); the axes keep their goals "
                 "until the target changes", m->Ts, far, far, farthest, far,
                 m->field[F_VMAX][far], far, m->field[F_AMAX][far], far, m->field[F_JMAX][far]);
    return 1;
}

void fmu_model_rebind(void *model, void *mem)
{
    ma_model *m = (ma_model *)model;
    sms_multi_generator_rebind(&m->gen, (sms_stage *)((sms_memory_cell *)mem + m->n_cells),
                               (sms_memory_cell *)mem);
}

size_t fmu_model_state_count(const void *model)
{
    const ma_model *m = (const ma_model *)model;
    return 4u * (size_t)m->axes + sms_multi_generator_state_count(&m->gen);
}

void fmu_model_save_state(const void *model, double *dst)
{
    const ma_model *m = (const ma_model *)model;
    int i, k;
    for (k = 0; k < 4; ++k)
        for (i = 0; i < m->axes; ++i)
            *dst++ = m->field[F_Q + k][i];
    sms_multi_generator_get_state(&m->gen, dst);
}

/* The range of axis i's positions: its stages' finite input range (q0 and the targets are held
 * to it), or the glue's SMS_INPUT_MAX without stages. */
static double position_range(const ma_model *m, int i)
{
    return m->gen.chain[i][0].n_stages > 0 ? sms_chain_input_max(&m->gen.chain[i][0])
                                           : SMS_INPUT_MAX;
}

/* What axis i reports for signal k = 1, 2, 3 (v, a, j): the profile's value within the limit
 * to the reported values' tolerance, passed through the axis's stages when it has some, which
 * can overshoot the limit (shapers with negative impulses, notches, corrected smoothers): the
 * chain's output range, the bound the generator's align ring holds the same outputs to
 * (sms_multi_generator_output_range()). */
static double signal_range(const ma_model *m, int i, int k)
{
    return sms_multi_generator_output_range(&m->gen, (size_t)i, (size_t)k);
}

/* A state must be one a run can reach: besides the generator's own checks (finite, velocities
 * and the stages' values within the limits), the reported outputs and the positions it holds
 * (target, goal, start of the running plan) within the axis's output ranges (signal_range())
 * and position range. */
int fmu_model_load_state(void *model, const double *src, size_t n, char *msg, size_t len)
{
    static const char *const names[4] = {"q", "v", "a", "j"};
    ma_model *m = (ma_model *)model;
    const size_t own = 4u * (size_t)m->axes, na = (size_t)m->axes;
    const double *positions = src + own + SMS_MULTI_IDENTITY_COUNT;   /* target, goal, p */
    const double margin = 1.0 + 0x1p-20;
    sms_status st;
    int i, k;
    if (n != fmu_model_state_count(m) || n < own + SMS_MULTI_IDENTITY_COUNT + 3u * na)
        return 1;
    for (i = 0; i < m->axes; ++i) {
        const double limit[4] = { position_range(m, i) * margin, signal_range(m, i, 1),
                                  signal_range(m, i, 2), signal_range(m, i, 3) };
        for (k = 0; k < 4; ++k)
            if (!isfinite(src[(size_t)k * na + (size_t)i])
                || !(fabs(src[(size_t)k * na + (size_t)i]) <= limit[k]))
                return snprintf(msg, len, "its output %s[%d] = %.17g is beyond %.17g (the axis's "
                                "%s)", names[k], i, src[(size_t)k * na + (size_t)i], limit[k],
                                k == 0 ? "position range" : "limit, to the reported values' "
                                "tolerance, times its stages' gain"), 1;
        for (k = 0; k < 3; ++k)
            if (!(fabs(positions[(size_t)k * na + (size_t)i]) <= position_range(m, i)))
                return snprintf(msg, len, "its %s of axis %d, %.17g, is beyond the axis's "
                                "position range %.17g", k == 0 ? "target" : k == 1 ? "goal"
                                : "plan start", i, positions[(size_t)k * na + (size_t)i],
                                position_range(m, i)), 1;
    }
    st = sms_multi_generator_set_state(&m->gen, src + own, n - own);
    if (st != SMS_OK) {
        snprintf(msg, len, "the generator refuses its state (%s): a value non-finite or out of "
                 "range, or an axis's start or cruise velocity beyond its vmax by more than "
                 "the reported values' relative %.3g", sms_status_string(st), SMS_LIMIT_RTOL);
        return 1;
    }
    for (k = 0; k < 4; ++k)
        for (i = 0; i < m->axes; ++i)
            m->field[F_Q + k][i] = *src++;
    memset(m->warned, 0, sizeof m->warned);   /* as a build leaves them */
    memset(m->dropped, 0, sizeof m->dropped);
    return 0;
}
