/* SPDX-License-Identifier: Apache-2.0 */
/*
 * TrajectoryGenerator: the online generator of the smoothshaper library (sms_generator_*,
 * trajectory.h) as an FMU. Inputs: the target (position, velocity and acceleration at arrival,
 * the interface: position, velocity or stop, and the move's minimum duration), held over
 * each step; outputs: q, v, a, j at the internal ticks, never beyond vmax, amax, jmax for any target sequence. At
 * fmi2ExitInitializationMode the generator rests at the parameter q0 (default 0): a target that
 * differs from q0 from the first step on is a move. A target the generator cannot take (a
 * velocity or acceleration beyond the limits) fails fmi2DoStep naming it, nothing changed.
 */
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include "smoothshaper/smoothshaper.h"
#include "TrajectoryGenerator_variables.h"
#include "fmu_model.h"

typedef struct tg_model {
    double target, out[4];                     /* q, v, a, j */
    double target_velocity, target_acceleration, minimum_duration;
    int interface;                             /* sms_interface */
    double Ts, vmax, amax, jmax, wn, zeta, q0, vmin, amin, qmin, qmax;
    int profile;
    int built;
    int warned;                                /* 1: the dropped target `dropped` was logged */
    double dropped;
    sms_generator gen;                         /* tables in the glue's block */
} tg_model;

/* Real value references and the field each one is, in modelDescription order: the inputs,
 * then the outputs (N_REAL_INPUTS .. N_REAL_INPUTS + 3), then the parameters. */
static const fmu_vr real_vrs[] = {
    TG_VR_TARGET, TG_VR_TARGET_VELOCITY, TG_VR_TARGET_ACCELERATION, TG_VR_MINIMUM_DURATION,
    TG_VR_Q, TG_VR_V, TG_VR_A, TG_VR_J, TG_VR_TS, TG_VR_VMAX, TG_VR_AMAX, TG_VR_JMAX, TG_VR_WN,
    TG_VR_ZETA, TG_VR_Q0, TG_VR_VMIN, TG_VR_AMIN, TG_VR_QMIN, TG_VR_QMAX
};
static const char *const real_names[] = {
    "target", "target_velocity", "target_acceleration", "minimum_duration", "q", "v", "a", "j",
    "Ts", "vmax", "amax", "jmax", "wn", "zeta", "q0", "vmin", "amin", "qmin", "qmax"
};
#define N_REALS (sizeof real_vrs / sizeof real_vrs[0])
#define N_REAL_INPUTS 4u

static const size_t real_offsets[] = {
    offsetof(tg_model, target), offsetof(tg_model, target_velocity),
    offsetof(tg_model, target_acceleration), offsetof(tg_model, minimum_duration),
    offsetof(tg_model, out[0]),
    offsetof(tg_model, out[1]), offsetof(tg_model, out[2]), offsetof(tg_model, out[3]),
    offsetof(tg_model, Ts), offsetof(tg_model, vmax), offsetof(tg_model, amax),
    offsetof(tg_model, jmax), offsetof(tg_model, wn), offsetof(tg_model, zeta),
    offsetof(tg_model, q0), offsetof(tg_model, vmin), offsetof(tg_model, amin),
    offsetof(tg_model, qmin), offsetof(tg_model, qmax)
};

/* Index of a Real value reference in real_vrs, or N_REALS. */
static size_t real_index(fmu_vr vr)
{
    size_t i;
    for (i = 0; i < N_REALS && real_vrs[i] != vr; ++i)
        ;
    return i;
}

size_t fmu_model_size(void) { return sizeof(tg_model); }
const char *fmu_model_identifier(void) { return FMU_MODEL_IDENTIFIER; }
const char *fmu_model_guid(void) { return FMU_MODEL_GUID; }

void fmu_model_defaults(void *model)
{
    tg_model *m = (tg_model *)model;   /* the start values of modelDescription.xml */
    m->target = 0.0;
    m->target_velocity = 0.0;
    m->target_acceleration = 0.0;
    m->minimum_duration = 0.0;
    m->interface = SMS_INTERFACE_POSITION;
    memset(m->out, 0, sizeof m->out);
    m->Ts = 0.001;
    m->vmax = 1.0;
    m->amax = 10.0;
    m->jmax = 100.0;
    m->profile = SMS_PROFILE_POLYNOMIAL;
    m->wn = 0.0;
    m->zeta = 0.0;
    m->q0 = 0.0;
    m->vmin = 0.0;
    m->amin = 0.0;
    m->qmin = 0.0;
    m->qmax = 0.0;
    m->built = 0;
    m->warned = 0;
    m->dropped = 0.0;
}

fmu_var_class fmu_model_class(fmu_type type, fmu_vr vr)
{
    size_t i;
    if (type == FMU_INTEGER)
        return vr == TG_VR_PROFILE ? FMU_VAR_PARAMETER
             : vr == TG_VR_INTERFACE ? FMU_VAR_INPUT : FMU_VAR_UNKNOWN;
    for (i = 0; i < N_REALS; ++i)
        if (real_vrs[i] == vr)
            return i < N_REAL_INPUTS ? FMU_VAR_INPUT
                 : i < N_REAL_INPUTS + 4u ? FMU_VAR_OUTPUT : FMU_VAR_PARAMETER;
    return FMU_VAR_UNKNOWN;
}

void fmu_model_name(fmu_type type, fmu_vr vr, char *buf, size_t len)
{
    size_t i;
    if (type == FMU_INTEGER && (vr == TG_VR_PROFILE || vr == TG_VR_INTERFACE)) {
        snprintf(buf, len, vr == TG_VR_PROFILE ? "profile" : "interface");
        return;
    }
    for (i = 0; i < N_REALS; ++i)
        if (type == FMU_REAL && real_vrs[i] == vr) {
            snprintf(buf, len, "%s", real_names[i]);
            return;
        }
    snprintf(buf, len, "vr %lu", (unsigned long)vr);
}

size_t fmu_model_settable(fmu_type type, fmu_vr *out, size_t cap)
{
    size_t i, n = 0;
    if (type == FMU_INTEGER) {
        if (cap > 0) out[0] = TG_VR_PROFILE;
        if (cap > 1) out[1] = TG_VR_INTERFACE;
        return 2;
    }
    for (i = 0; i < N_REALS; ++i)
        if (i < N_REAL_INPUTS || i >= N_REAL_INPUTS + 4u) {
            if (n < cap) out[n] = real_vrs[i];
            ++n;
        }
    return n;
}

double fmu_model_get_real(const void *model, fmu_vr vr)
{
    size_t i = real_index(vr);
    return i < N_REALS ? *(const double *)(const void *)((const char *)model + real_offsets[i]) : 0.0;
}

int fmu_model_get_integer(const void *model, fmu_vr vr)
{
    const tg_model *m = (const tg_model *)model;
    return vr == TG_VR_PROFILE ? m->profile : vr == TG_VR_INTERFACE ? m->interface : 0;
}

int fmu_model_check_tunable(const void *model, fmu_type type, const fmu_vr *vr,
                            const void *values, size_t n, char *msg, size_t len)
{
    (void)model; (void)type; (void)vr; (void)values; (void)n; (void)msg; (void)len;
    return 0;   /* no tunable parameters */
}

void fmu_model_set_real(void *model, fmu_vr vr, double value)
{
    size_t i = real_index(vr);
    if (i < N_REALS)
        *(double *)(void *)((char *)model + real_offsets[i]) = value;
}

void fmu_model_set_integer(void *model, fmu_vr vr, int value)
{
    if (vr == TG_VR_PROFILE)
        ((tg_model *)model)->profile = value;
    else if (vr == TG_VR_INTERFACE)
        ((tg_model *)model)->interface = value;
}

double fmu_model_sample_period(const void *model) { return ((const tg_model *)model)->Ts; }

/* Limits with which no plan can reach vmax: the variables, their values and the derived
 * quantity out of range (sms_generator_reach()); returns 1. */
static int refuse_limits(const tg_model *m, char *msg, size_t len)
{
    sms_generator_config c;
    sms_generator_reach_info r;
    char names[96];
    const char *args;
    int n = 0;
    c.vmax = m->vmax;
    c.amax = m->amax;
    c.jmax = m->jmax;
    c.profile = (sms_profile)m->profile;
    c.wn = m->wn;
    c.zeta = m->zeta;
    c.vmin = m->vmin; /* 0: symmetric */
    c.amin = m->amin;
    c.qmin = m->qmin; /* both 0: no position limits */
    c.qmax = m->qmax;
    (void)sms_generator_reach(&c, m->Ts, &r);
    if (r.quantity == NULL) /* not expected: init and the check are one function */
        return snprintf(msg, len, "vmax = %.17g, amax = %.17g, jmax = %.17g: %s", m->vmax,
                        m->amax, m->jmax, sms_status_string(SMS_ERR_LIMIT)), 1;
    args = r.arguments;
    names[0] = '\0';
    if (strstr(args, "vmax") != NULL)
        n += snprintf(names + n, sizeof names - (size_t)n, "vmax = %.17g, ", m->vmax);
    if (strstr(args, "amax") != NULL)
        n += snprintf(names + n, sizeof names - (size_t)n, "amax = %.17g, ", m->amax);
    if (strstr(args, "jmax") != NULL)
        n += snprintf(names + n, sizeof names - (size_t)n, "jmax = %.17g, ", m->jmax);
    if (strstr(args, "vmin") != NULL)
        n += snprintf(names + n, sizeof names - (size_t)n, "vmin = %.17g, ", m->vmin);
    if (strstr(args, "amin") != NULL)
        n += snprintf(names + n, sizeof names - (size_t)n, "amin = %.17g, ", m->amin);
    if (strstr(args, "profile") != NULL) /* asymmetric limits with the trigonometric profile */
        return snprintf(msg, len, "%s= %.17g: the trigonometric profile takes symmetric limits "
                        "only (%s = 0)", r.quantity, r.value, r.quantity), 1;
    if (strchr(r.quantity, '/') != NULL) /* a duration beyond the plan's sample counts */
        return snprintf(msg, len, "%sTs = %.17g: %s = %.6g s, so reaching vmax from rest takes "
                        "%.6g s = %.6g samples, more than the 2^50 a plan holds: no move that "
                        "reaches vmax can be planned", names, m->Ts, r.quantity, r.value,
                        r.duration, r.samples), 1;
    if (n >= 2)
        names[n - 2] = '\0';
    if (strcmp(r.quantity, args) == 0) /* a limit itself out of range */
        return snprintf(msg, len, r.value < r.bound ? "%s: below %.6g, the smallest normal number "
                        "of this precision" : "%s: above %.6g, the largest number of this "
                        "precision over 16 (room for a reversal)", names, r.bound), 1;
    return snprintf(msg, len, "%s: %s = %.6g %s %.6g: the planner's values would %s", names,
                    r.quantity, r.value, r.value < r.bound ? "is below" : "exceeds", r.bound,
                    r.value < r.bound ? "underflow" : "overflow"), 1;
}

/* "name = value: <status>" for the parameter a core status points at; returns 1. */
static int refuse(const tg_model *m, sms_status st, char *msg, size_t len)
{
    const char *why = sms_status_string(st);
    switch (st) {
    case SMS_ERR_SAMPLE_PERIOD: return snprintf(msg, len, "Ts = %.17g: %s", m->Ts, why), 1;
    case SMS_ERR_KIND: return snprintf(msg, len, "profile = %d: %s", m->profile, why), 1;
    case SMS_ERR_WN: case SMS_ERR_ABOVE_NYQUIST:
        return snprintf(msg, len, "wn = %.17g: %s", m->wn, why), 1;
    case SMS_ERR_ZETA: return snprintf(msg, len, "zeta = %.17g: %s", m->zeta, why), 1;
    case SMS_ERR_DURATION_BELOW_TS: case SMS_ERR_TOO_LONG:
        return snprintf(msg, len, "wn = %.17g (the stage tuned to the mode on the grid of "
                        "Ts = %.17g): %s", m->wn, m->Ts, why), 1;
    case SMS_ERR_LIMIT: return refuse_limits(m, msg, len);
    default:
        return snprintf(msg, len, "vmax = %.17g, amax = %.17g, jmax = %.17g: %s", m->vmax, m->amax,
                        m->jmax, why), 1;
    }
}

unsigned fmu_model_real_bytes(void) { return (unsigned)sizeof(sms_real); }

/* The range of the positions (q0, the targets, the plan): the tuned stage's finite input range
 * with a mode, the glue's SMS_INPUT_MAX without. Only after build. */
static double position_range(const tg_model *m)
{
    return m->gen.stage_length > 0 ? sms_smoother_input_max(&m->gen.stage[0]) : SMS_INPUT_MAX;
}

double fmu_model_input_max(const void *model)
{
    const tg_model *m = (const tg_model *)model;
    return m->built ? position_range(m) : HUGE_VAL;
}

/* Its inputs are checked against the configuration that holds them: the same range. */
double fmu_model_state_input_max(const void *model)
{
    return fmu_model_input_max(model);
}

/* Validate every parameter into c; need = table reals (the core's size query). 0 or 1 + msg. */
static int configure(const tg_model *m, sms_generator_config *c, size_t *need, char *msg,
                     size_t len)
{
    sms_status st;
    if (!(m->Ts > 0.0))
        return snprintf(msg, len, "Ts = %.17g: must be finite and > 0", m->Ts), 1;
    if (!(m->vmax > 0.0) || !(m->amax > 0.0) || !(m->jmax > 0.0))
        return snprintf(msg, len, "%s = %.17g: must be > 0", !(m->vmax > 0.0) ? "vmax"
                        : !(m->amax > 0.0) ? "amax" : "jmax", !(m->vmax > 0.0) ? m->vmax
                        : !(m->amax > 0.0) ? m->amax : m->jmax), 1;
    if (m->profile < SMS_PROFILE_POLYNOMIAL || m->profile > SMS_PROFILE_DAMPED)
        return snprintf(msg, len, "profile = %d is not polynomial (0), trigonometric (1) or "
                        "damped (2)", m->profile), 1;
    if (!(m->vmin <= 0.0) || !(m->amin <= 0.0) || !isfinite(m->vmin) || !isfinite(m->amin))
        return snprintf(msg, len, "%s = %.17g: must be 0 (symmetric) or finite and < 0",
                        !(m->vmin <= 0.0) || !isfinite(m->vmin) ? "vmin" : "amin",
                        !(m->vmin <= 0.0) || !isfinite(m->vmin) ? m->vmin : m->amin), 1;
    if (m->qmin != 0.0 || m->qmax != 0.0) {
        if (!isfinite(m->qmin) || !isfinite(m->qmax) || !((sms_real)m->qmin < (sms_real)m->qmax))
            return snprintf(msg, len, "qmin = %.17g, qmax = %.17g: position limits must be "
                            "finite with qmin < qmax (both 0: none)", m->qmin, m->qmax), 1;
        if (m->profile == SMS_PROFILE_TRIGONOMETRIC)
            return snprintf(msg, len, "qmin = %.17g, qmax = %.17g: position limits take the "
                            "polynomial or damped profile, not the trigonometric one", m->qmin,
                            m->qmax), 1;
        if (!(m->q0 >= m->qmin && m->q0 <= m->qmax))
            return snprintf(msg, len, "q0 = %.17g is outside [qmin, qmax] = [%.17g, %.17g]",
                            m->q0, m->qmin, m->qmax), 1;
    }
    if (m->wn < 0.0)
        return snprintf(msg, len, "wn = %.17g: must be 0 (no mode) or > 0", m->wn), 1;
    if (!isfinite(m->q0) || (sms_real)m->q0 - (sms_real)m->q0 != 0)
        return snprintf(msg, len, "q0 = %.17g: the initial position must be finite", m->q0), 1;
    if (m->profile == SMS_PROFILE_TRIGONOMETRIC
        && !(3.14159265358979323846 * m->amax / m->jmax / m->Ts <= FMU_MAX_HOLD_STEPS))
        return snprintf(msg, len, "amax = %.17g, jmax = %.17g, Ts = %.17g: with the "
                        "trigonometric profile a new target may wait for the end of an "
                        "acceleration transition of up to pi amax/jmax = %.6g samples, stepped "
                        "one by one, more than the %.0f that keep a doStep of any length "
                        "well under 100 ms: raise jmax or Ts, or lower amax",
                        m->amax, m->jmax, m->Ts,
                        3.14159265358979323846 * m->amax / m->jmax / m->Ts,
                        FMU_MAX_HOLD_STEPS), 1;
    c->vmax = m->vmax;
    c->amax = m->amax;
    c->jmax = m->jmax;
    c->profile = (sms_profile)m->profile;
    c->wn = m->wn;
    c->zeta = m->zeta;
    c->vmin = m->vmin; /* 0: symmetric */
    c->amin = m->amin;
    c->qmin = m->qmin; /* both 0: no position limits */
    c->qmax = m->qmax;
    *need = 0;
    st = sms_generator_buffer_size(c, m->Ts, need);
    if (st != SMS_OK)
        return refuse(m, st, msg, len);
    if (*need > FMU_MAX_REALS) {
        char names[256];
        snprintf(names, sizeof names, "wn = %.17g, zeta = %.17g, Ts = %.17g (the stage tuned to "
                 "the mode, 4 signals)", m->wn, m->zeta, m->Ts);
        return fmu_refuse_size(msg, len, names, (double)*need,
                               "raise wn or Ts, or set wn = 0 (no mode)");
    }
    return 0;
}

int fmu_model_plan(const void *model, size_t *bytes, char *msg, size_t len)
{
    sms_generator_config c;
    size_t need;
    if (configure((const tg_model *)model, &c, &need, msg, len) != 0)
        return 1;
    *bytes = need * sizeof(sms_real);
    return 0;
}

int fmu_model_build(void *model, void *mem, size_t bytes, char *msg, size_t len)
{
    tg_model *m = (tg_model *)model;
    sms_generator_config c;
    size_t need;
    sms_status st;
    if (configure(m, &c, &need, msg, len) != 0)
        return 1;
    st = sms_generator_init(&m->gen, &c, m->Ts, (sms_real *)mem, bytes / sizeof(sms_real));
    if (st != SMS_OK)
        return refuse(m, st, msg, len);
    if (fabs(m->q0) > position_range(m))
        return snprintf(msg, len, "q0 = %.17g is beyond %.17g, the input range of the "
                        "generator's filters (SMS_INPUT_MAX, or the stage tuned to the mode's "
                        "smaller range)", m->q0, position_range(m)), 1;
    sms_generator_reset(&m->gen, (sms_real)m->q0);
    m->out[0] = (double)(sms_real)m->q0;
    m->out[1] = m->out[2] = m->out[3] = 0.0;
    m->built = 1;
    return 0;
}

/* The target the inputs hold (checked by fmu_model_check_inputs() before every step). */
static sms_target held(const tg_model *m)
{
    sms_target t;
    t.position = (sms_real)m->target;
    t.velocity = (sms_real)m->target_velocity;
    t.acceleration = (sms_real)m->target_acceleration;
    t.interface = m->interface;
    t.minimum_duration = (sms_real)m->minimum_duration;
    return t;
}

int fmu_model_check_inputs(const void *model, char *msg, size_t len)
{
    const tg_model *m = (const tg_model *)model;
    sms_target t = held(m);
    sms_status st = sms_generator_check_target(&m->gen, &t);
    const double v = m->target_velocity, a = m->target_acceleration;
    const double V = (double)m->gen.limits.vmax, A = (double)m->gen.limits.amax;
    const double J = (double)m->gen.limits.jmax, reach = a * fabs(a) / (2.0 * J);
    switch (st) {
    case SMS_OK:
        return 0;
    case SMS_ERR_INTERFACE:
        return snprintf(msg, len, "interface = %d is not position (0), velocity (1) or stop (2)",
                        m->interface), 1;
    case SMS_ERR_TARGET_POSITION:
        return snprintf(msg, len, "target = %.17g: %s", m->target, sms_status_string(st)), 1;
    case SMS_ERR_POSITION_LIMIT:
        return snprintf(msg, len, "target = %.17g is outside [qmin, qmax] = [%.17g, %.17g]",
                        m->target, m->qmin, m->qmax), 1;
    case SMS_ERR_DURATION:
        if (m->profile == SMS_PROFILE_TRIGONOMETRIC && m->minimum_duration >= 0.0)
            return snprintf(msg, len, "minimum_duration = %.17g: the trigonometric profile does "
                            "not stretch a move (minimum_duration 0)", m->minimum_duration), 1;
        return snprintf(msg, len, "minimum_duration = %.17g must be finite, >= 0 and below 2^50 "
                        "ticks of Ts = %.17g", m->minimum_duration, m->Ts), 1;
    case SMS_ERR_TARGET_VELOCITY:
        if (m->gen.bounded && v != 0.0)
            return snprintf(msg, len, "target_velocity = %.17g: with position limits [qmin, qmax] "
                            "a target rests (target_velocity 0)", v), 1;
        if (m->profile == SMS_PROFILE_TRIGONOMETRIC && fabs(v) <= V)
            return snprintf(msg, len, "target_velocity = %.17g: the trigonometric profile plans "
                            "position targets at rest only (target_velocity 0)", v), 1;
        if (m->gen.asymmetric)
            return snprintf(msg, len, "target_velocity = %.17g is outside [vmin, vmax] = "
                            "[%.17g, %.17g]", v, (double)m->gen.vmin, V), 1;
        return snprintf(msg, len, "target_velocity = %.17g is beyond vmax = %.17g", v, V), 1;
    default:
        if (m->gen.bounded && a != 0.0)
            return snprintf(msg, len, "target_acceleration = %.17g: with position limits [qmin, "
                            "qmax] a target rests (target_acceleration 0)", a), 1;
        if (m->profile == SMS_PROFILE_TRIGONOMETRIC && a != 0.0)
            return snprintf(msg, len, "target_acceleration = %.17g: the trigonometric profile "
                            "holds no acceleration at a target (target_acceleration 0)", a), 1;
        return snprintf(msg, len, "target_acceleration = %.17g with target_velocity = %.17g: "
                        "|a| must be within amax = %.17g and v - a|a|/(2 jmax) = %.17g, "
                        "v + a|a|/(2 jmax) = %.17g within vmax = %.17g (jmax = %.17g: the "
                        "velocity where the acceleration was zero on the way in and where it "
                        "returns to zero after)", a, v, A, v - reach, v + reach, V, J), 1;
    }
}

int fmu_model_tick(void *model)
{
    tg_model *m = (tg_model *)model;
    sms_target t = held(m);
    sms_real out[4];
    int i, changed = 0;
    sms_generator_step_target(&m->gen, &t, out);
    for (i = 0; i < 4; ++i) {
        changed |= m->out[i] != (double)out[i];
        m->out[i] = (double)out[i];
    }
    return changed;
}

/* A dropped target (sms_generator `refused`), once per target: a target that stays dropped
 * over many steps, or comes back after a state is restored, is reported once. */
/* The generator's closed form under a held target (sms_generator_hold()): bit for bit the
 * ticks; at most one acceleration transition and 2M + 2 samples of the tuned stage stepped. */
uint64_t fmu_model_hold(void *model, uint64_t n)
{
    tg_model *m = (tg_model *)model;
    sms_target t = held(m);
    sms_real out[4];
    int i;
    if (n == 0)
        return 0;
    sms_generator_hold_target(&m->gen, &t, n, out);
    for (i = 0; i < 4; ++i)
        m->out[i] = (double)out[i];
    return n;
}

int fmu_model_warning(void *model, char *msg, size_t len)
{
    tg_model *m = (tg_model *)model;
    double goal, span;
    if (!m->built || !m->gen.refused) {
        m->warned = 0;
        return 0;
    }
    if (m->warned && m->dropped == (double)m->gen.target.position)
        return 0;
    m->warned = 1;
    m->dropped = (double)m->gen.target.position;
    goal = (double)m->gen.plan.goal;
    span = fabs(m->dropped - goal) / m->vmax / m->Ts;
    snprintf(msg, len, "target = %.17g dropped: its move cannot be represented with vmax = "
             "%.17g, amax = %.17g, jmax = %.17g, Ts = %.17g (|target - goal|/vmax alone is %.3g "
             "samples of Ts, a plan holds at most 2^52; every value must stay finite); the "
             "generator keeps its goal %.17g until target changes", m->dropped, m->vmax, m->amax,
             m->jmax, m->Ts, span, goal);
    return 1;
}

void fmu_model_rebind(void *model, void *mem)
{
    tg_model *m = (tg_model *)model;
    if (m->built)
        sms_generator_rebind(&m->gen, (sms_real *)mem);
}

size_t fmu_model_state_count(const void *model)
{
    return 4 + sms_generator_state_count(&((const tg_model *)model)->gen);
}

void fmu_model_save_state(const void *model, double *dst)
{
    const tg_model *m = (const tg_model *)model;
    memcpy(dst, m->out, sizeof m->out);
    sms_generator_get_state(&m->gen, dst + 4);
}

/* The saved outputs v, a, j are reported until the next tick, and the generator's state is
 * where its plan starts: both must be ones the generator could have produced, within the
 * limits to the reported values' tolerance, SMS_LIMIT_RTOL (32 u: trajectory.h). */
int fmu_model_load_state(void *model, const double *src, size_t n, char *msg, size_t len)
{
    static const char *const names[4] = {"q", "v", "a", "j"};
    tg_model *m = (tg_model *)model;
    const double limit[4] = {0.0, (double)m->gen.limits.vmax, (double)m->gen.limits.amax,
                             (double)m->gen.limits.jmax};
    const double *plan = src + 4 + SMS_GENERATOR_IDENTITY_COUNT; /* trajectory.h's layout */
    sms_status st;
    int i;
    if (n != fmu_model_state_count(m))
        return 1;
    for (i = 0; i < 4; ++i)
        if (!isfinite(src[i]))
            return 1;
    if (!(fabs(src[0]) <= position_range(m) * (1.0 + 0x1p-20)))
        return snprintf(msg, len, "its output q = %.17g is beyond the position range %.17g",
                        src[0], position_range(m)), 1;
    for (i = 0; i < 3; ++i) {   /* the plan's target, goal and start position */
        static const int at[3] = { SMS_GENERATOR_STATE_TARGET, SMS_GENERATOR_STATE_GOAL,
                                   SMS_GENERATOR_STATE_Q };
        if (!(fabs(plan[at[i]]) <= position_range(m)))
            return snprintf(msg, len, "its plan's %s %.17g is beyond the position range %.17g",
                            i == 0 ? "target" : i == 1 ? "goal" : "start", plan[at[i]],
                            position_range(m)), 1;
    }
    for (i = 0; i < 2; ++i) {   /* the minimum_duration of target and goal: an input's range */
        const double d = plan[(i == 0 ? SMS_GENERATOR_STATE_TARGET : SMS_GENERATOR_STATE_GOAL) + 4];
        if (!(fabs(d) <= SMS_INPUT_MAX))
            return snprintf(msg, len, "its plan's %s minimum_duration %.17g is beyond the input "
                            "range %.17g", i == 0 ? "target" : "goal", d, SMS_INPUT_MAX), 1;
    }
    for (i = 1; i < 4; ++i)
        if (!(fabs(src[i]) <= limit[i] * (1.0 + SMS_LIMIT_RTOL))) {
            snprintf(msg, len, "its output %s = %.17g is beyond %smax = %.17g by more than the "
                     "reported values' relative %.3g", names[i], src[i], names[i], limit[i],
                     SMS_LIMIT_RTOL);
            return 1;
        }
    st = sms_generator_set_state(&m->gen, src + 4, n - 4);
    if (st != SMS_OK) {
        if (st == SMS_ERR_STATE)
            snprintf(msg, len, "the generator refuses its state (%s): a value non-finite or "
                     "out of range, a plan it cannot form, or the plan's start v = %.17g, "
                     "a = %.17g beyond vmax = %.17g, amax = %.17g (v, a and the brake velocity "
                     "v + a|a|/(2 J) within them to a relative %.3g)", sms_status_string(st),
                     plan[SMS_GENERATOR_STATE_V], plan[SMS_GENERATOR_STATE_A], limit[1],
                     limit[2], SMS_LIMIT_RTOL);
        else
            snprintf(msg, len, "the generator's state: %s", sms_status_string(st));
        return 1;
    }
    memcpy(m->out, src, sizeof m->out);
    m->warned = 0;      /* as a build leaves it: a dropped target is reported again */
    m->dropped = 0.0;
    return 0;
}
