/*
 * MultiAxisGenerator: the multi-axis online generator of the smoothshaper library
 * (sms_multi_generator_*, multi_generator.h) as an FMU. Inputs target[i]; outputs q[i], v[i],
 * a[i], j[i] at the internal ticks, every axis within its own vmax[i], amax[i], jmax[i].
 * Parameters: Ts, axes (1..8), sync (0 phase-synchronised, 1 independent), per-axis limits
 * and the rest position q0[i]. At fmi2ExitInitializationMode the generator rests at q0 (so a
 * target that differs from q0 at t = 0 moves from the first tick on).
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
    double Ts;
    int axes, sync;
    int built;
    sms_multi_generator gen;
} ma_model;

/* Fields in the order of MA_FIELDS (generate.py): index f - 1 of value reference 100 f + i. */
enum { F_TARGET, F_Q, F_V, F_A, F_J, F_VMAX, F_AMAX, F_JMAX, F_Q0 };
static const char *const field_names[MA_FIELD_COUNT] = {
    "target", "q", "v", "a", "j", "vmax", "amax", "jmax", "q0"
};

/* Field and axis of a Real value reference; 0 if it is not an axis variable. */
static int axis_var(fmi2ValueReference vr, int *field, int *axis)
{
    if (vr < 100 || vr >= 100u * (MA_FIELD_COUNT + 1) || vr % 100 >= MA_MAX_AXES)
        return 0;
    *field = (int)(vr / 100) - 1;
    *axis = (int)(vr % 100);
    return 1;
}

size_t fmu_model_size(void) { return sizeof(ma_model); }
const char *fmu_model_identifier(void) { return FMU_MODEL_IDENTIFIER; }
const char *fmu_model_guid(void) { return FMU_MODEL_GUID; }

void fmu_model_defaults(void *model)
{
    ma_model *m = (ma_model *)model;   /* the start values of modelDescription.xml */
    int i;
    memset(m->field, 0, sizeof m->field);
    for (i = 0; i < MA_MAX_AXES; ++i) {
        m->field[F_VMAX][i] = 1.0;
        m->field[F_AMAX][i] = 10.0;
        m->field[F_JMAX][i] = 100.0;
    }
    m->Ts = 0.001;
    m->axes = 3;
    m->sync = SMS_SYNC_PHASE;
    m->built = 0;
}

fmu_var_class fmu_model_class(fmu_type type, fmi2ValueReference vr)
{
    int f, i;
    if (type == FMU_INTEGER)
        return vr == MA_VR_AXES || vr == MA_VR_SYNC ? FMU_VAR_PARAMETER : FMU_VAR_UNKNOWN;
    if (vr == MA_VR_TS)
        return FMU_VAR_PARAMETER;
    if (!axis_var(vr, &f, &i))
        return FMU_VAR_UNKNOWN;
    return f == F_TARGET ? FMU_VAR_INPUT : f <= F_J ? FMU_VAR_OUTPUT : FMU_VAR_PARAMETER;
}

void fmu_model_name(fmu_type type, fmi2ValueReference vr, char *buf, size_t len)
{
    int f, i;
    if (type == FMU_INTEGER && (vr == MA_VR_AXES || vr == MA_VR_SYNC))
        snprintf(buf, len, "%s", vr == MA_VR_AXES ? "axes" : "sync");
    else if (type == FMU_REAL && vr == MA_VR_TS)
        snprintf(buf, len, "Ts");
    else if (type == FMU_REAL && axis_var(vr, &f, &i))
        snprintf(buf, len, "%s[%d]", field_names[f], i);
    else
        snprintf(buf, len, "vr %lu", (unsigned long)vr);
}

size_t fmu_model_settable(fmu_type type, fmi2ValueReference *out, size_t cap)
{
    size_t n = 0;
    int f, i;
    if (type == FMU_INTEGER) {
        if (cap > 0) out[0] = MA_VR_AXES;
        if (cap > 1) out[1] = MA_VR_SYNC;
        return 2;
    }
    if (n < cap) out[n] = MA_VR_TS;
    ++n;
    for (f = 0; f < MA_FIELD_COUNT; ++f) {
        if (f >= F_Q && f <= F_J)
            continue;
        for (i = 0; i < MA_MAX_AXES; ++i) {
            if (n < cap) out[n] = (fmi2ValueReference)(100 * (f + 1) + i);
            ++n;
        }
    }
    return n;
}

double fmu_model_get_real(const void *model, fmi2ValueReference vr)
{
    const ma_model *m = (const ma_model *)model;
    int f, i;
    if (vr == MA_VR_TS)
        return m->Ts;
    return axis_var(vr, &f, &i) ? m->field[f][i] : 0.0;
}

int fmu_model_get_integer(const void *model, fmi2ValueReference vr)
{
    const ma_model *m = (const ma_model *)model;
    return vr == MA_VR_AXES ? m->axes : vr == MA_VR_SYNC ? m->sync : 0;
}

void fmu_model_set_real(void *model, fmi2ValueReference vr, double value)
{
    ma_model *m = (ma_model *)model;
    int f, i;
    if (vr == MA_VR_TS)
        m->Ts = value;
    else if (axis_var(vr, &f, &i))
        m->field[f][i] = value;
}

void fmu_model_set_integer(void *model, fmi2ValueReference vr, int value)
{
    ma_model *m = (ma_model *)model;
    if (vr == MA_VR_AXES)
        m->axes = value;
    else if (vr == MA_VR_SYNC)
        m->sync = value;
}

double fmu_model_sample_period(const void *model) { return ((const ma_model *)model)->Ts; }

unsigned fmu_model_real_bytes(void) { return (unsigned)sizeof(sms_real); }

/* Validate every parameter into c (O(axes)); 0, or 1 with msg naming the variable. */
static int configure(const ma_model *m, sms_multi_generator_config *c, char *msg, size_t len)
{
    sms_multi_generator check;
    size_t bad = 0;
    sms_status st;
    int i, f;
    if (!(m->Ts > 0.0))
        return snprintf(msg, len, "Ts = %.17g: must be finite and > 0", m->Ts), 1;
    if (m->axes < 1 || m->axes > MA_MAX_AXES)
        return snprintf(msg, len, "axes = %d: must be 1 .. %d", m->axes, MA_MAX_AXES), 1;
    if (m->sync != SMS_SYNC_PHASE && m->sync != SMS_SYNC_INDEPENDENT)
        return snprintf(msg, len, "sync = %d is not phase (0) or independent (1)", m->sync), 1;
    for (f = F_VMAX; f <= F_JMAX; ++f)
        for (i = 0; i < m->axes; ++i)
            if (!(m->field[f][i] > 0.0))
                return snprintf(msg, len, "%s[%d] = %.17g: must be > 0", field_names[f], i,
                                m->field[f][i]), 1;
    memset(c, 0, sizeof *c);
    c->n_axes = (size_t)m->axes;
    c->sync = (sms_sync)m->sync;
    for (i = 0; i < m->axes; ++i) {
        c->vmax[i] = m->field[F_VMAX][i];
        c->amax[i] = m->field[F_AMAX][i];
        c->jmax[i] = m->field[F_JMAX][i];
    }
    st = sms_multi_generator_init(&check, c, m->Ts, &bad); /* the core's own checks */
    if (st == SMS_ERR_LIMIT)
        return snprintf(msg, len, "vmax[%d], amax[%d], jmax[%d] = %.17g, %.17g, %.17g: %s",
                        (int)bad, (int)bad, (int)bad, c->vmax[bad], c->amax[bad], c->jmax[bad],
                        sms_status_string(st)), 1;
    if (st != SMS_OK)
        return snprintf(msg, len, "Ts = %.17g: %s", m->Ts, sms_status_string(st)), 1;
    return 0;
}

int fmu_model_plan(const void *model, size_t *bytes, char *msg, size_t len)
{
    sms_multi_generator_config c;
    if (configure((const ma_model *)model, &c, msg, len) != 0)
        return 1;
    *bytes = 0; /* everything lives in the model struct */
    return 0;
}

int fmu_model_build(void *model, void *mem, size_t bytes, char *msg, size_t len)
{
    ma_model *m = (ma_model *)model;
    sms_multi_generator_config c;
    sms_real rest[MA_MAX_AXES];
    int i;
    (void)mem;
    (void)bytes;
    if (configure(m, &c, msg, len) != 0)
        return 1;
    if (sms_multi_generator_init(&m->gen, &c, m->Ts, NULL) != SMS_OK)
        return snprintf(msg, len, "Ts = %.17g: refused", m->Ts), 1;
    for (i = 0; i < m->axes; ++i)
        rest[i] = (sms_real)m->field[F_Q0][i];
    sms_multi_generator_reset(&m->gen, rest);
    for (i = 0; i < MA_MAX_AXES; ++i) {
        m->field[F_Q][i] = i < m->axes ? (double)rest[i] : 0.0;
        m->field[F_V][i] = m->field[F_A][i] = m->field[F_J][i] = 0.0;
    }
    m->built = 1;
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

void fmu_model_rebind(void *model, void *mem)
{
    (void)model; /* the generator holds no pointers */
    (void)mem;
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
    sms_multi_generator_save_state(&m->gen, dst);
}

int fmu_model_load_state(void *model, const double *src, size_t n)
{
    ma_model *m = (ma_model *)model;
    size_t own = 4u * (size_t)m->axes;
    int i, k;
    if (n != fmu_model_state_count(m))
        return 1;
    for (i = 0; i < (int)own; ++i)
        if (!isfinite(src[i]))
            return 1;
    if (sms_multi_generator_load_state(&m->gen, src + own, n - own) != SMS_OK)
        return 1;
    for (k = 0; k < 4; ++k)
        for (i = 0; i < m->axes; ++i)
            m->field[F_Q + k][i] = *src++;
    return 0;
}
