/* SPDX-License-Identifier: Apache-2.0 */
/*
 * ElasticPlant: the two-mass elastic transmission of Lambrechts, Boerlage and Steinbuch,
 * "Trajectory planning and feedforward design for electromechanical motion systems" (2005), as
 * used by Biagiotti and Melchiorri's FIR smoother paper (2012, eq. 12, Table 1): the load
 * position y follows the motor-side position u through
 *
 *     G_ml(s) = (2 zeta wn s + wn^2) / (s^2 + 2 zeta wn s + wn^2),
 *     wn = sqrt(k_t / J_l),  zeta = b_t / (2 sqrt(k_t J_l)),
 *
 * in controllable canonical form x' = A x + B u, y = C x with A = [0 1; -wn^2 -2 zeta wn],
 * B = [0; 1], C = [wn^2, 2 zeta wn]. The input is held over each internal tick of Ts (zero-order
 * hold) and the state is advanced by the exact discretisation x[n+1] = Ad x[n] + Bd u[n],
 * Ad = e^{A Ts}, Bd = A^-1 (Ad - I) B, computed once at fmi2ExitInitializationMode from the
 * closed form of the matrix exponential of an underdamped mode (the only libm calls); each
 * tick is four multiply-adds. At initialization the plant rests at the input (y = u).
 * The state is kept scaled, z = (wn^2 x0, wn x1) (a position and a velocity over wn, both of
 * the size of y), so every matrix entry is of order one and the recursion stays finite for
 * any input up to SMS_INPUT_MAX, whatever wn (x0 = u/wn^2 itself overflows for a slow mode).
 */
#include <float.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include "ElasticPlant_variables.h"
#include "fmu_model.h"

typedef struct ep_model {
    double u, y, Ts, J_l, k_t, b_t;
    int built;
    double ad[2][2], bd[2], c[2];   /* exact ZOH matrices and the output row, scaled */
    double x[2];                    /* scaled state: wn^2 x0 and wn x0' (see above) */
} ep_model;

size_t fmu_model_size(void) { return sizeof(ep_model); }
const char *fmu_model_identifier(void) { return FMU_MODEL_IDENTIFIER; }
const char *fmu_model_guid(void) { return FMU_MODEL_GUID; }
unsigned fmu_model_real_bytes(void) { return (unsigned)sizeof(double); }
/* The scaled realisation keeps any input up to SMS_INPUT_MAX finite (see the top). */
double fmu_model_input_max(const void *model) { (void)model; return HUGE_VAL; }
double fmu_model_state_input_max(const void *model) { return fmu_model_input_max(model); }

void fmu_model_defaults(void *model)
{
    ep_model *m = (ep_model *)model;   /* the start values of modelDescription.xml */
    memset(m, 0, sizeof *m);
    m->Ts = 0.001;
    m->J_l = 0.23e-5;
    m->k_t = 0.156;
    m->b_t = 1.0e-5;
}

/* Offset of each Real variable in the struct, by value reference: u, y, Ts, J_l, k_t, b_t. */
static const size_t offsets[] = {
    offsetof(ep_model, u), offsetof(ep_model, y), offsetof(ep_model, Ts), offsetof(ep_model, J_l),
    offsetof(ep_model, k_t), offsetof(ep_model, b_t)
};
#define N_REALS (sizeof offsets / sizeof offsets[0])

static const char *field_name(fmu_vr vr)
{
    static const char *const names[N_REALS] = { "u", "y", "Ts", "J_l", "k_t", "b_t" };
    return vr < N_REALS ? names[vr] : NULL;
}

fmu_var_class fmu_model_class(fmu_type type, fmu_vr vr)
{
    if (type != FMU_REAL || field_name(vr) == NULL)
        return FMU_VAR_UNKNOWN;
    return vr == EP_VR_U ? FMU_VAR_INPUT : vr == EP_VR_Y ? FMU_VAR_OUTPUT : FMU_VAR_PARAMETER;
}

void fmu_model_name(fmu_type type, fmu_vr vr, char *buf, size_t len)
{
    const char *name = type == FMU_REAL ? field_name(vr) : NULL;
    if (name != NULL)
        snprintf(buf, len, "%s", name);
    else
        snprintf(buf, len, "vr %lu", (unsigned long)vr);
}

size_t fmu_model_settable(fmu_type type, fmu_vr *out, size_t cap)
{
    static const fmu_vr vrs[] = { EP_VR_U, EP_VR_TS, EP_VR_J_L, EP_VR_K_T, EP_VR_B_T };
    size_t i, n = type == FMU_REAL ? sizeof vrs / sizeof vrs[0] : 0;
    for (i = 0; i < n && i < cap; ++i)
        out[i] = vrs[i];
    return n;
}

double fmu_model_get_real(const void *model, fmu_vr vr)
{
    return vr < N_REALS ? *(const double *)(const void *)((const char *)model + offsets[vr]) : 0.0;
}

int fmu_model_get_integer(const void *model, fmu_vr vr)
{
    (void)model;
    (void)vr;
    return 0;
}

int fmu_model_check_tunable(const void *model, fmu_type type, const fmu_vr *vr,
                            const void *values, size_t n, char *msg, size_t len)
{
    (void)model; (void)type; (void)vr; (void)values; (void)n; (void)msg; (void)len;
    return 0;   /* no tunable parameters */
}

void fmu_model_set_real(void *model, fmu_vr vr, double value)
{
    if (vr < N_REALS)
        *(double *)(void *)((char *)model + offsets[vr]) = value;
}

void fmu_model_set_integer(void *model, fmu_vr vr, int value)
{
    (void)model;
    (void)vr;
    (void)value;
}

double fmu_model_sample_period(const void *model) { return ((const ep_model *)model)->Ts; }

/* wn and zeta from the physical parameters; 0 or 1 with msg naming the variable and value. */
static int mode(const ep_model *m, double *wn, double *zeta, char *msg, size_t len)
{
    if (!(m->Ts > 0.0))
        return snprintf(msg, len, "Ts = %.17g: must be finite and > 0", m->Ts), 1;
    if (!(m->J_l > 0.0))
        return snprintf(msg, len, "J_l = %.17g: the load inertia must be > 0", m->J_l), 1;
    if (!(m->k_t > 0.0))
        return snprintf(msg, len, "k_t = %.17g: the stiffness must be > 0", m->k_t), 1;
    if (!(m->b_t >= 0.0))
        return snprintf(msg, len, "b_t = %.17g: the damping must be >= 0", m->b_t), 1;
    *wn = sqrt(m->k_t / m->J_l);
    *zeta = m->b_t / (2.0 * sqrt(m->k_t * m->J_l));
    if (!(*zeta < 1.0))
        return snprintf(msg, len, "b_t = %.17g: gives zeta = %.6g, the mode must be underdamped "
                        "(zeta < 1)", m->b_t, *zeta), 1;
    if (!(*wn > 0.0))
        return snprintf(msg, len, "k_t / J_l = %.17g: the mode's wn^2 underflows to 0",
                        m->k_t / m->J_l), 1;
    if (!isfinite(*wn) || !(*wn * m->Ts < 1e3))
        return snprintf(msg, len, "k_t / J_l = %.17g: wn * Ts must be finite and < 1000",
                        m->k_t / m->J_l), 1;
    return 0;
}

int fmu_model_plan(const void *model, size_t *bytes, char *msg, size_t len)
{
    double wn, zeta;
    *bytes = 0;   /* the state lives in the struct */
    return mode((const ep_model *)model, &wn, &zeta, msg, len);
}

int fmu_model_build(void *model, void *mem, size_t bytes, char *msg, size_t len)
{
    ep_model *m = (ep_model *)model;
    double wn, zeta, sigma, wd, e, co, si, a1, d01, d11;
    (void)mem;
    (void)bytes;
    if (mode(m, &wn, &zeta, msg, len) != 0)
        return 1;
    a1 = 2.0 * zeta * wn;
    sigma = -zeta * wn;
    wd = wn * sqrt(1.0 - zeta * zeta);
    /* e^{A h} = e^{sigma h} (cos(wd h) I + sin(wd h)/wd (A - sigma I)) for an underdamped pair */
    e = exp(sigma * m->Ts);
    co = cos(wd * m->Ts);
    si = wd > 0.0 ? sin(wd * m->Ts) / wd : m->Ts;   /* wd = 0: zeta^2 rounds to 1, the limit */
    m->ad[0][0] = e * (co - sigma * si);
    m->ad[0][1] = e * si;
    m->ad[1][0] = -wn * e * si;   /* -a0 e si / wn: scaled below, wn^2 never formed */
    m->ad[1][1] = e * (co + (-a1 - sigma) * si);
    /* Bd = A^-1 (Ad - I) B with B = [0; 1] and A^-1 = [-a1 -1; a0 0] / a0 (unscaled Ad) */
    d01 = m->ad[0][1];
    d11 = m->ad[1][1] - 1.0;
    /* The scaled state z = S x, S = diag(a0, wn): Ad S^-1 conjugated, S Bd, C S^-1. */
    m->ad[0][1] *= wn;
    m->bd[0] = -a1 * d01 - d11;
    m->bd[1] = wn * d01;
    m->c[0] = 1.0;
    m->c[1] = 2.0 * zeta;
    m->x[0] = m->u;   /* at rest at u: A x + B u = 0 */
    m->x[1] = 0.0;
    m->y = m->u;
    m->built = 1;
    return 0;
}

int fmu_model_tick(void *model)
{
    ep_model *m = (ep_model *)model;
    double x0 = m->x[0], x1 = m->x[1], before = m->y;
    m->x[0] = m->ad[0][0] * x0 + m->ad[0][1] * x1 + m->bd[0] * m->u;
    m->x[1] = m->ad[1][0] * x0 + m->ad[1][1] * x1 + m->bd[1] * m->u;
    m->y = m->c[0] * m->x[0] + m->c[1] * m->x[1];
    return m->y != before || m->x[0] != x0 || m->x[1] != x1;
}

/* Steps of up to this many ticks are ticked (bit for bit); longer ones use the closed form. */
#define EP_TICKED_MAX 65536u

/* P = Ad^k by repeated squaring (about 2 log2 k products of 2 x 2 matrices). */
static void ad_power(double ad[2][2], uint64_t k, double p[2][2])
{
    double b[2][2], t[2][2];
    int i, j;
    memcpy(b, ad, sizeof b);
    p[0][0] = p[1][1] = 1.0;
    p[0][1] = p[1][0] = 0.0;
    while (k > 0u) {
        if (k & 1u) {
            for (i = 0; i < 2; ++i)
                for (j = 0; j < 2; ++j)
                    t[i][j] = p[i][0] * b[0][j] + p[i][1] * b[1][j];
            memcpy(p, t, sizeof t);
        }
        k >>= 1;
        if (k > 0u) {
            for (i = 0; i < 2; ++i)
                for (j = 0; j < 2; ++j)
                    t[i][j] = b[i][0] * b[0][j] + b[i][1] * b[1][j];
            memcpy(b, t, sizeof t);
        }
    }
}

/* Under a held u the plant's rest is z* = (u, 0) (A x + B u = 0 scaled) and the deviation
 * evolves as z[n] - z* = Ad^n (z[0] - z*). A step of at most EP_TICKED_MAX ticks is ticked;
 * a longer one advances the deviation by Ad^(n-1) in closed form, then ticks once. Against
 * ticking every sample the result differs only by the ticks' rounding, which grows at most
 * linearly: |dz| <= 8 n eps (max |z| + |u|) (tests/fmu/test_fmu_long_step.c checks it), and
 * the closed form is the more exact of the two. */
/* Every input is valid alone (the glue checks its range when it is set). */
int fmu_model_check_inputs(const void *model, char *msg, size_t len)
{
    (void)model;
    (void)msg;
    (void)len;
    return 0;
}

uint64_t fmu_model_hold(void *model, uint64_t n)
{
    ep_model *m = (ep_model *)model;
    uint64_t i;
    if (n <= EP_TICKED_MAX) {
        for (i = 0; i < n; ++i)
            (void)fmu_model_tick(m);
        return n;
    }
    {
        double p[2][2], d0 = m->x[0] - m->u, d1 = m->x[1];
        ad_power(m->ad, n - 1u, p);
        m->x[0] = m->u + (p[0][0] * d0 + p[0][1] * d1);
        m->x[1] = p[1][0] * d0 + p[1][1] * d1;
    }
    (void)fmu_model_tick(m);
    return n;
}

int fmu_model_warning(void *model, char *msg, size_t len)
{
    (void)model; (void)msg; (void)len;
    return 0; /* every input is taken as it is: nothing to report */
}

void fmu_model_rebind(void *model, void *mem)
{
    (void)model;
    (void)mem;   /* no pointers inside */
}

size_t fmu_model_state_count(const void *model)
{
    (void)model;
    return 3;
}

void fmu_model_save_state(const void *model, double *dst)
{
    const ep_model *m = (const ep_model *)model;
    dst[0] = m->y;
    dst[1] = m->x[0];
    dst[2] = m->x[1];
}

int fmu_model_load_state(void *model, const double *src, size_t n, char *msg, size_t len)
{
    ep_model *m = (ep_model *)model;
    (void)msg;
    (void)len;
    /* finite, and below a quarter of the largest double: a tick at most doubles |z| (Ad's rows
     * sum to at most about 2 in magnitude), so a larger state could overflow on the next one */
    if (n != 3 || !(fabs(src[0]) <= 0.25 * DBL_MAX) || !(fabs(src[1]) <= 0.25 * DBL_MAX)
        || !(fabs(src[2]) <= 0.25 * DBL_MAX))
        return 1;
    m->y = src[0];
    m->x[0] = src[1];
    m->x[1] = src[2];
    return 0;
}
