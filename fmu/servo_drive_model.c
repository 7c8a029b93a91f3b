/* SPDX-License-Identifier: Apache-2.0 */
/*
 * ServoDrive: the servomechanism of Bascetta, "Motion control: advanced control techniques"
 * (Politecnico di Milano lecture notes) in closed loop, as the Python testbed smoothshaper.servo
 * builds it (docs/servo.md): motor, elastic transmission and load,
 *
 *     J_m  q_m''     = tau_m - D_m q_m' - K_el (q_m - n q_l) - D_el (q_m' - n q_l')
 *     J_lr (n q_l)'' = K_el (q_m - n q_l) + D_el (q_m' - n q_l') - tau_l / n,   J_lr = J_l/n^2,
 *
 * state x = [q_m, q_m', n q_l, n q_l'], discretised exactly (zero-order hold of the motor
 * torque and the load torque, one matrix exponential), under one of four controllers sampled
 * at Ts: the P/PI cascade with velocity feed-forward (optionally a library notch on its torque
 * or on its velocity reference, and a torque disturbance observer), observer-based pole
 * placement with integral action, or LQ state feedback with a Kalman predictor, both with the
 * reference model's feed-forward. Tick n is the drive's sample at (n-1) Ts: it reads the held
 * q_ref and the plant at (n-1) Ts, computes the torque, holds it with tau_load over the tick,
 * and reports the plant at n Ts and that torque.
 *
 * The design (ZOH, gains, Riccati solutions, the reference model) is computed once, in double,
 * when the model is built (servo_design.c); the tick is a fixed sequence of multiply-adds. The
 * whole loop is linear, so build also reads the loop's matrices off the tick (X' = Acl X +
 * Bcl w): the loop must be stable (repeated squares of Acl), its rest at the inputs is
 * (I - Acl)^-1 Bcl w, a long held step advances the deviation from that rest by Acl^(n-1) in
 * O(log n), and the powers bound the inputs and states that keep every value finite.
 */
#include <float.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include "smoothshaper/smoothshaper.h"
#include "ServoDrive_variables.h"
#include "fmu_model.h"
#include "servo_design.h"

enum { SV_PID = 0, SV_PID_TDO = 1, SV_PLACE = 2, SV_LQG = 3 };
enum { SV_NOTCH_NONE = 0, SV_NOTCH_LOOP = 1, SV_NOTCH_REFERENCE = 2 };

#define SV_NX 4            /* plant states */
#define SV_STATES 13       /* plant and controller states: 4 + 2 (P/PI), 4 + 5 (with the
                            * TDO) or 4 + 4 + 1 (+ 4 with the reference model) */
#define SV_LOOP 13         /* loop states: those in use and the notch's 4 */
#define SV_NOTCH_AT (SMS_STATE_IDENTITY_COUNT + 1)   /* x1, x2, w1, w2 in a saved notch */

/* Every variable, declared from the generated table: one field each, named as its c_name. */
#define SV_CTYPE_REAL double
#define SV_CTYPE_INTEGER int
#define SV_DECLARE(vr, name, field, type, cls, start) SV_CTYPE_##type field;
typedef struct sv_vars {
    SV_VARIABLES(SV_DECLARE)
} sv_vars;

typedef struct sv_var {
    const char *name;   /* NULL: no variable at this value reference */
    size_t offset;
    fmu_type type;
    fmu_var_class cls;
} sv_var;

#define SV_ENTRY(vr, name, field, type, cls, start) \
    [vr] = { name, offsetof(sv_vars, field), FMU_##type, FMU_VAR_##cls },
static const sv_var vars[SV_VR_END] = { SV_VARIABLES(SV_ENTRY) };

/* What build computes from the parameters. */
typedef struct sv_design {
    int kind, notch_at;
    int states;                   /* entries of X in use */
    int loop;                     /* entries of the loop state: states + 4 with a notch */
    double Ts, n, inv_n;
    double Ad[SV_NX * SV_NX], Bu[SV_NX], Bd[SV_NX];
    /* P/PI cascade and TDO */
    double kpv, kpp, ki, inv_ts, a, b, alpha;
    /* state feedback: gains, observer, reference model (m = 4 states, or 0 without) */
    double K[SV_NX], kI, L[SV_NX];
    int m;
    double Phi[SV_NX * SV_NX], Gam[SV_NX], M[SV_NX * SV_NX], N[SV_NX], N0;
    /* the closed loop Z' = Acl Z + Bcl [q_ref, tau_load], tau_m = Cu Z + Du w */
    double Acl[SV_LOOP * SV_LOOP], Bcl[SV_LOOP * 2], Cu[SV_LOOP], Du[2];
    double rest[SV_LOOP * 2];     /* (I - Acl)^-1 Bcl: the rest per unit input */
    double input_max, state_max;
} sv_design;

typedef struct sv_model {
    sv_vars v;
    int built;
    sv_design d;
    sms_notch notch;
    double X[SV_STATES];          /* plant, then controller (layout: see control()) */
} sv_model;

size_t fmu_model_size(void) { return sizeof(sv_model); }
const char *fmu_model_identifier(void) { return FMU_MODEL_IDENTIFIER; }
const char *fmu_model_guid(void) { return FMU_MODEL_GUID; }
unsigned fmu_model_real_bytes(void) { return (unsigned)sizeof(double); }

double fmu_model_input_max(const void *model)
{
    const sv_model *m = (const sv_model *)model;
    return m->built ? m->d.input_max : HUGE_VAL;
}

/* Its inputs are checked against the configuration that holds them: the same range. */
double fmu_model_state_input_max(const void *model)
{
    return fmu_model_input_max(model);
}

void fmu_model_defaults(void *model)
{
    sv_model *m = (sv_model *)model;
    memset(m, 0, sizeof *m);
#define SV_START(vr, name, field, type, cls, start) m->v.field = start;
    SV_VARIABLES(SV_START)
#undef SV_START
}

static const sv_var *lookup(fmu_type type, fmu_vr vr)
{
    return vr < SV_VR_END && vars[vr].name != NULL && vars[vr].type == type ? &vars[vr] : NULL;
}

fmu_var_class fmu_model_class(fmu_type type, fmu_vr vr)
{
    const sv_var *var = lookup(type, vr);
    return var != NULL ? var->cls : FMU_VAR_UNKNOWN;
}

void fmu_model_name(fmu_type type, fmu_vr vr, char *buf, size_t len)
{
    const sv_var *var = lookup(type, vr);
    if (var != NULL)
        snprintf(buf, len, "%s", var->name);
    else
        snprintf(buf, len, "vr %lu", (unsigned long)vr);
}

size_t fmu_model_settable(fmu_type type, fmu_vr *out, size_t cap)
{
    size_t n = 0;
    fmu_vr vr;
    for (vr = 0; vr < SV_VR_END; ++vr) {
        const sv_var *var = lookup(type, vr);
        if (var == NULL || var->cls == FMU_VAR_OUTPUT)
            continue;
        if (n < cap)
            out[n] = vr;
        ++n;
    }
    return n;
}

double fmu_model_get_real(const void *model, fmu_vr vr)
{
    const sv_var *var = lookup(FMU_REAL, vr);
    return var ? *(const double *)(const void *)((const char *)model + var->offset) : 0.0;
}

int fmu_model_get_integer(const void *model, fmu_vr vr)
{
    const sv_var *var = lookup(FMU_INTEGER, vr);
    return var ? *(const int *)(const void *)((const char *)model + var->offset) : 0;
}

int fmu_model_check_tunable(const void *model, fmu_type type, const fmu_vr *vr,
                            const void *values, size_t n, char *msg, size_t len)
{
    (void)model; (void)type; (void)vr; (void)values; (void)n; (void)msg; (void)len;
    return 0;   /* no tunable parameters: the loop is designed once, at initialization */
}

void fmu_model_set_real(void *model, fmu_vr vr, double value)
{
    const sv_var *var = lookup(FMU_REAL, vr);
    if (var != NULL)
        *(double *)(void *)((char *)model + var->offset) = value;
}

void fmu_model_set_integer(void *model, fmu_vr vr, int value)
{
    const sv_var *var = lookup(FMU_INTEGER, vr);
    if (var != NULL)
        *(int *)(void *)((char *)model + var->offset) = value;
}

double fmu_model_sample_period(const void *model) { return ((const sv_model *)model)->v.ts; }

/* ------------------------------------------------------------------ the parameters' checks */

#define REFUSE(...) return (snprintf(msg, len, __VA_ARGS__), 1)

static int positive(const char *name, double x, char *msg, size_t len)
{
    if (!(x > 0.0) || !isfinite(x))
        REFUSE("%s = %.17g: must be finite and > 0", name, x);
    return 0;
}

static int nonnegative(const char *name, double x, char *msg, size_t len)
{
    if (!(x >= 0.0) || !isfinite(x))
        REFUSE("%s = %.17g: must be finite and >= 0", name, x);
    return 0;
}

/* The continuous plant x' = A x + Bu tau_m + Bd tau_l (the file's top). */
static void plant_matrices(const sv_vars *p, double A[SV_NX * SV_NX], double Bu[SV_NX],
                           double Bd[SV_NX])
{
    const double Jr = p->jl / (p->n * p->n), K = p->kel, D = p->del;
    const double rows[SV_NX * SV_NX] = {
        0.0, 1.0, 0.0, 0.0,
        -K / p->jm, -(p->dm + D) / p->jm, K / p->jm, D / p->jm,
        0.0, 0.0, 0.0, 1.0,
        K / Jr, D / Jr, -K / Jr, -D / Jr };
    memcpy(A, rows, sizeof rows);
    Bu[0] = Bu[2] = Bu[3] = 0.0;
    Bu[1] = 1.0 / p->jm;
    Bd[0] = Bd[1] = Bd[2] = 0.0;
    Bd[3] = -1.0 / (p->n * Jr);
}

static int check_plant(const sv_vars *p, char *msg, size_t len)
{
    double A[SV_NX * SV_NX], Bu[SV_NX], Bd[SV_NX], fastest = 0.0;
    int i;
    if (positive("Ts", p->ts, msg, len) || positive("Jm", p->jm, msg, len)
        || positive("Jl", p->jl, msg, len) || positive("n", p->n, msg, len)
        || nonnegative("Dm", p->dm, msg, len) || positive("Kel", p->kel, msg, len)
        || nonnegative("Del", p->del, msg, len))
        return 1;
    plant_matrices(p, A, Bu, Bd);
    for (i = 0; i < SV_NX * SV_NX; ++i) {
        if (!isfinite(A[i]))
            REFUSE("Jl / n^2 = %.17g, Jm = %.17g: the plant's coefficients are beyond the range "
                   "of a double", p->jl / (p->n * p->n), p->jm);
        if (fabs(A[i]) > fastest)
            fastest = fabs(A[i]);
    }
    if (!isfinite(Bd[3]) || !(A[12] != 0.0) || !(A[4] != 0.0))   /* K/J_lr, K/J_m underflow */
        REFUSE("Jl = %.17g, n = %.17g: the plant's coefficients are beyond the range of a double",
               p->jl, p->n);
    if (!(fastest * p->ts <= 50.0))
        REFUSE("Ts = %.17g: too long for this plant: its fastest coefficient times Ts is %.3g "
               "(> 50; the fastest mode is far above the Nyquist frequency)", p->ts,
               fastest * p->ts);
    return 0;
}

static int check_notch(const sv_vars *p, sms_notch *notch, char *msg, size_t len)
{
    sms_stage_config cfg;
    sms_status st;
    if (p->notch_at < SV_NOTCH_NONE || p->notch_at > SV_NOTCH_REFERENCE)
        REFUSE("notch.at = %d: must be 0 (none), 1 (loop) or 2 (reference)", p->notch_at);
    if (p->notch_at == SV_NOTCH_NONE)
        return 0;
    if (p->notch_discretization != 0 && p->notch_discretization != 1)
        REFUSE("notch.discretization = %d: must be 0 (matched) or 1 (tustin)",
               p->notch_discretization);
    cfg = sms_stage_config_default(p->notch_discretization ? SMS_NOTCH_TUSTIN : SMS_NOTCH_MATCHED);
    cfg.wn = p->notch_wn;
    cfg.zeta = p->notch_zeta;
    cfg.notch_pole_zeta = p->notch_pole_zeta;
    st = sms_notch_init(notch, &cfg, p->ts);
    if (st == SMS_ERR_WN || st == SMS_ERR_ABOVE_NYQUIST)
        REFUSE("notch.wn = %.17g: must be finite, > 0 and below the Nyquist frequency pi/Ts = "
               "%.17g", p->notch_wn, 3.14159265358979323846 / p->ts);
    if (st == SMS_ERR_ZETA)
        REFUSE("notch.zeta = %.17g: must be in [0, 1)", p->notch_zeta);
    if (st == SMS_ERR_NOTCH_DAMPING)
        REFUSE("notch.pole_zeta = %.17g: must be finite, > notch.zeta = %.17g and <= %g",
               p->notch_pole_zeta, p->notch_zeta, SMS_NOTCH_MAX_POLE_ZETA);
    if (st != SMS_OK)
        REFUSE("notch: %s", sms_status_string(st));
    return 0;
}

static int check_pid(const sv_vars *p, char *msg, size_t len)
{
    if (positive("pid.wcv", p->pid_wcv, msg, len) || positive("pid.Ti", p->pid_ti, msg, len)
        || positive("pid.wcp", p->pid_wcp, msg, len) || nonnegative("pid.J", p->pid_j, msg, len))
        return 1;
    if (!(p->pid_wcp < p->pid_wcv))
        REFUSE("pid.wcp = %.17g: must be below pid.wcv = %.17g (the position loop is the outer, "
               "slower one)", p->pid_wcp, p->pid_wcv);
    if (p->controller == SV_PID_TDO) {
        if (positive("tdo.Tf", p->tdo_tf, msg, len) || positive("tdo.Jn", p->tdo_jn, msg, len)
            || nonnegative("tdo.Dn", p->tdo_dn, msg, len))
            return 1;
        if (!isfinite(p->tdo_dn * p->ts / p->tdo_jn) || !isfinite(p->ts / p->tdo_jn)
            || !(p->tdo_dn * p->ts / p->tdo_jn <= 700.0))
            REFUSE("tdo.Jn = %.17g: the nominal model's decay Dn Ts / Jn (or Ts / Jn) is beyond "
                   "the range of a double", p->tdo_jn);
    }
    return 0;
}

/* One continuous pole pair (wn, zeta) or real pole; fills re/im (Laplace, 1/s). */
static int check_pair(const char *wn_name, const char *zeta_name, double wn, double zeta, double Ts,
                      double *re, double *im, char *msg, size_t len)
{
    if (positive(wn_name, wn, msg, len))
        return 1;
    if (!(zeta > 0.0 && zeta < 1.0))
        REFUSE("%s = %.17g: must be in (0, 1) (a complex pair in the left half-plane)", zeta_name,
               zeta);
    *re = -zeta * wn;
    *im = wn * sqrt(1.0 - zeta * zeta);
    if (!(wn * Ts <= 50.0))
        REFUSE("%s = %.17g: wn Ts = %.3g must be <= 50", wn_name, wn, wn * Ts);
    if (!(*im * Ts < 3.14159265358979323846))
        REFUSE("%s = %.17g: the damped frequency %.17g rad/s must be below the Nyquist frequency "
               "pi/Ts (else the sampled pair aliases)", wn_name, wn, *im);
    return 0;
}

static int check_real(const char *name, double p, double Ts, char *msg, size_t len)
{
    if (positive(name, p, msg, len))
        return 1;
    if (!(p * Ts <= 50.0))
        REFUSE("%s = %.17g: the pole's rate times Ts, %.3g, must be <= 50", name, p, p * Ts);
    return 0;
}

static int distinct(double r1, double i1, double r2, double i2)
{
    return hypot(r1 - r2, i1 - i2) > 1e-9 * hypot(r1, i1);
}

/* The continuous poles of pole placement (5) and of the observer (4), pairs first. */
static int check_place(const sv_vars *p, double re[5], double im[5], double ore[4],
                       double oim[4], char *msg, size_t len)
{
    if (check_pair("place.wn[0]", "place.zeta[0]", p->place_wn0, p->place_zeta0, p->ts, &re[0],
                   &im[0], msg, len)
        || check_pair("place.wn[1]", "place.zeta[1]", p->place_wn1, p->place_zeta1, p->ts, &re[2],
                      &im[2], msg, len)
        || check_real("place.real", p->place_real, p->ts, msg, len)
        || check_pair("observer.wn", "observer.zeta", p->observer_wn, p->observer_zeta, p->ts,
                      &ore[0], &oim[0], msg, len)
        || check_real("observer.real[0]", p->observer_real0, p->ts, msg, len)
        || check_real("observer.real[1]", p->observer_real1, p->ts, msg, len))
        return 1;
    re[1] = re[0], im[1] = -im[0];
    re[3] = re[2], im[3] = -im[2];
    re[4] = -p->place_real, im[4] = 0.0;
    ore[1] = ore[0], oim[1] = -oim[0];
    ore[2] = -p->observer_real0, ore[3] = -p->observer_real1, oim[2] = oim[3] = 0.0;
    if (!distinct(re[0], im[0], re[2], im[2]))
        REFUSE("place.wn[1] = %.17g, place.zeta[1] = %.17g: the two pole pairs must be distinct "
               "(a single input cannot place a repeated pole robustly)", p->place_wn1,
               p->place_zeta1);
    if (!distinct(ore[2], 0.0, ore[3], 0.0))
        REFUSE("observer.real[1] = %.17g: must differ from observer.real[0] (a single output "
               "cannot place a repeated pole robustly)", p->observer_real1);
    return 0;
}

static int check_lqg(const sv_vars *p, char *msg, size_t len)
{
    const double q[5] = { p->lq_q0, p->lq_q1, p->lq_q2, p->lq_q3, p->lq_q4 };
    int i, any = 0;
    for (i = 0; i < 5; ++i) {
        if (!(q[i] >= 0.0) || !isfinite(q[i]))
            REFUSE("lq.Q[%d] = %.17g: must be finite and >= 0", i, q[i]);
        any |= q[i] > 0.0;
    }
    if (!any)
        REFUSE("lq.Q: every weight is 0: weight at least the motor position or the integrated "
               "error, or nothing stabilises the drive");
    if (positive("lq.R", p->lq_r, msg, len)
        || nonnegative("kalman.torque_noise", p->kalman_torque_noise, msg, len)
        || nonnegative("kalman.load_torque_noise", p->kalman_load_torque_noise, msg, len)
        || positive("kalman.encoder_noise", p->kalman_encoder_noise, msg, len))
        return 1;
    if (p->kalman_torque_noise == 0.0 && p->kalman_load_torque_noise == 0.0)
        REFUSE("kalman.torque_noise = kalman.load_torque_noise = 0: one must be > 0");
    return 0;
}

static int check_params(const sv_vars *p, sms_notch *notch, char *msg, size_t len)
{
    double re[5], im[5], ore[4], oim[4];
    if (check_plant(p, msg, len))
        return 1;
    if (p->controller < SV_PID || p->controller > SV_LQG)
        REFUSE("controller = %d: must be 0 (pid), 1 (pid_tdo), 2 (pole_placement) or 3 (lqg)",
               p->controller);
    if (p->controller <= SV_PID_TDO)
        return check_pid(p, msg, len) || check_notch(p, notch, msg, len);
    if (nonnegative("wf", p->wf, msg, len))
        return 1;
    if (!(p->wf * p->ts <= 50.0))
        REFUSE("wf = %.17g: wf Ts = %.3g must be <= 50", p->wf, p->wf * p->ts);
    if (p->controller == SV_PLACE)
        return check_place(p, re, im, ore, oim, msg, len);
    return check_lqg(p, msg, len);
}

int fmu_model_plan(const void *model, size_t *bytes, char *msg, size_t len)
{
    sms_notch notch;
    *bytes = 0;   /* everything lives in the struct */
    return check_params(&((const sv_model *)model)->v, &notch, msg, len);
}

/* ------------------------------------------------------------------ the design */

/* Zero-order hold of x' = A x + B u (n states, k inputs): [Ad Bd] from e^([A B; 0 0] Ts). */
static int zoh(int n, int k, const double *A, const double *B, double Ts, double *Ad, double *Bd)
{
    double M[SD_MAX * SD_MAX], E[SD_MAX * SD_MAX];
    const int s = n + k;
    int i, j;
    for (i = 0; i < s * s; ++i)
        M[i] = 0.0;
    for (i = 0; i < n; ++i) {
        for (j = 0; j < n; ++j)
            M[i * s + j] = A[i * n + j] * Ts;
        for (j = 0; j < k; ++j)
            M[i * s + n + j] = B[i * k + j] * Ts;
    }
    if (sd_expm(s, M, E) != 0)
        return 1;
    for (i = 0; i < n; ++i) {
        for (j = 0; j < n; ++j)
            Ad[i * n + j] = E[i * s + j];
        for (j = 0; j < k; ++j)
            Bd[i * k + j] = E[i * s + n + j];
    }
    return 0;
}

/* The integral-action model F = [[Ad, 0], [-Ts e1', 1]], G = [Bu; 0]. */
static void augmented(const sv_design *d, double F[25], double G[5])
{
    int i, j;
    for (i = 0; i < 25; ++i)
        F[i] = 0.0;
    for (i = 0; i < SV_NX; ++i) {
        for (j = 0; j < SV_NX; ++j)
            F[i * 5 + j] = d->Ad[i * SV_NX + j];
        G[i] = d->Bu[i];
    }
    F[4 * 5 + 0] = -d->Ts;
    F[4 * 5 + 4] = 1.0;
    G[4] = 0.0;
}

/* Discrete poles e^(p Ts) of continuous poles (pairs adjacent, im > 0 first). */
static void discrete(int n, const double *re, const double *im, double Ts, double *zre,
                     double *zim)
{
    int i;
    for (i = 0; i < n; ++i) {
        const double r = exp(re[i] * Ts);
        zre[i] = r * cos(im[i] * Ts);
        zim[i] = r * sin(im[i] * Ts);
    }
}

/* The reference model F^o(s) = wf^3/(s + wf)^3 with the plant's state and torque along it
 * (servo.design.reference_model): v = F^o/(c s + 1) r, c = Del/Kel (1/wf when Del = 0), in
 * controllable canonical form xi = [v, v', v'', v''']; n q_l = v + c v',
 * q_m = v + c v' + (J_lr/K_el) v'', and the motor equation gives the torque. */
static int reference_model(const sv_vars *p, sv_design *d, char *msg, size_t len)
{
    const double wf = p->wf, c = p->del / p->kel, e = c > 0.0 ? c : 1.0 / wf;
    const double c2 = p->jl / (p->n * p->n) / p->kel, K = p->kel, D = p->del;
    double den[5], Ac[16], Bc[4], dv[5][5], qm[5], wm[5], ql[5], wl[5], am[5], ud[5];
    int i, j;
    /* (s + wf)^3 (e s + 1) / e, highest power first */
    const double cube[4] = { 1.0, 3.0 * wf, 3.0 * wf * wf, wf * wf * wf };
    den[0] = e * cube[0];
    for (i = 1; i < 4; ++i)
        den[i] = e * cube[i] + cube[i - 1];
    den[4] = cube[3];
    for (i = 0; i < 5; ++i)
        den[i] /= e;
    for (i = 0; i < 16; ++i)
        Ac[i] = 0.0;
    for (i = 0; i < 3; ++i)
        Ac[i * 4 + i + 1] = 1.0;
    for (j = 0; j < 4; ++j)
        Ac[12 + j] = -den[4 - j];
    Bc[0] = Bc[1] = Bc[2] = 0.0;
    Bc[3] = wf * wf * wf / e;
    /* row i: v^(i) as a combination of [xi, r] */
    for (i = 0; i < 5; ++i)
        for (j = 0; j < 5; ++j)
            dv[i][j] = i < 4 ? (i == j ? 1.0 : 0.0) : (j < 4 ? Ac[12 + j] : Bc[3]);
    for (j = 0; j < 5; ++j) {
        ql[j] = dv[0][j] + c * dv[1][j];
        wl[j] = dv[1][j] + c * dv[2][j];
        qm[j] = dv[0][j] + c * dv[1][j] + c2 * dv[2][j];
        wm[j] = dv[1][j] + c * dv[2][j] + c2 * dv[3][j];
        am[j] = dv[2][j] + c * dv[3][j] + c2 * dv[4][j];
        ud[j] = p->jm * am[j] + (p->dm + D) * wm[j] + K * (qm[j] - ql[j]) - D * wl[j];
    }
    for (j = 0; j < 4; ++j) {
        d->M[0 * 4 + j] = qm[j];
        d->M[1 * 4 + j] = wm[j];
        d->M[2 * 4 + j] = ql[j];
        d->M[3 * 4 + j] = wl[j];
        d->N[j] = ud[j];
    }
    d->N0 = ud[4];
    if (zoh(4, 1, Ac, Bc, p->ts, d->Phi, d->Gam) != 0)
        REFUSE("wf = %.17g: the reference model cannot be discretised at Ts = %.17g (its fastest "
               "pole, Kel/Del = %.3g rad/s, times Ts is too large; Del = 0 drops that factor)",
               wf, p->ts, 1.0 / e);
    d->m = 4;
    return 0;
}

static int design_state_feedback(const sv_vars *p, sv_design *d, char *msg, size_t len)
{
    double F[25], G[5], Kt[5], zre[5], zim[5], At[16], e1[4] = { 1.0, 0.0, 0.0, 0.0 };
    int i, j;
    augmented(d, F, G);
    for (i = 0; i < SV_NX; ++i)
        for (j = 0; j < SV_NX; ++j)
            At[i * SV_NX + j] = d->Ad[j * SV_NX + i];
    if (p->controller == SV_PLACE) {
        double re[5], im[5], ore[4], oim[4];
        (void)check_place(p, re, im, ore, oim, msg, len);   /* validated by the plan */
        discrete(5, re, im, p->ts, zre, zim);
        if (sd_place(5, F, G, zre, zim, Kt) != 0)
            REFUSE("place.*: the closed loop's poles cannot be placed (the eigenvector matrix is "
                   "singular: move the poles apart)");
        discrete(4, ore, oim, p->ts, zre, zim);
        if (sd_place(4, At, e1, zre, zim, d->L) != 0)
            REFUSE("observer.*: the observer's poles cannot be placed (the eigenvector matrix is "
                   "singular: move the poles apart)");
    } else {
        const double q[5] = { p->lq_q0, p->lq_q1, p->lq_q2, p->lq_q3, p->lq_q4 };
        const double su = p->kalman_torque_noise, sl = p->kalman_load_torque_noise;
        const double V = p->kalman_encoder_noise * p->kalman_encoder_noise;
        double Q[25], P[25], W[16], PF[5], PG[5], num = 0.0, den;
        for (i = 0; i < 25; ++i)
            Q[i] = 0.0;
        for (i = 0; i < 5; ++i)
            Q[i * 5 + i] = q[i] * p->ts;
        if (sd_dare(5, F, G, Q, p->lq_r * p->ts, P) == 0)
            REFUSE("lq.*: the LQ Riccati equation has no stabilising solution in double with "
                   "these weights (lq.R = %.17g)", p->lq_r);
        /* Ktot = -(G' P F) / (R Ts + G' P G) */
        sd_mul(1, 5, 5, G, P, PG);
        sd_mul(1, 5, 5, PG, F, PF);
        for (i = 0; i < 5; ++i)
            num += PG[i] * G[i];
        den = p->lq_r * p->ts + num;
        for (i = 0; i < 5; ++i)
            Kt[i] = -PF[i] / den;
        for (i = 0; i < SV_NX; ++i)
            for (j = 0; j < SV_NX; ++j)
                W[i * SV_NX + j] = su * su * d->Bu[i] * d->Bu[j] + sl * sl * d->Bd[i] * d->Bd[j];
        if (sd_dare(4, At, e1, W, V, P) == 0)
            REFUSE("kalman.*: the Kalman filter's Riccati equation has no stabilising solution "
                   "in double with these noises (kalman.encoder_noise = %.17g)",
                   p->kalman_encoder_noise);
        /* L = -Ad P e1 / (P00 + V) */
        for (i = 0; i < SV_NX; ++i) {
            double s = 0.0;
            for (j = 0; j < SV_NX; ++j)
                s += d->Ad[i * SV_NX + j] * P[j * SV_NX + 0];
            d->L[i] = -s / (P[0] + V);
        }
    }
    for (i = 0; i < SV_NX; ++i)
        d->K[i] = Kt[i];
    d->kI = Kt[4];
    d->states = SV_NX + SV_NX + 1;
    d->m = 0;
    if (p->wf > 0.0) {
        if (reference_model(p, d, msg, len) != 0)
            return 1;
        d->states += 4;
    }
    return 0;
}

static void design_pid(const sv_vars *p, sv_design *d)
{
    const double rule = p->controller == SV_PID_TDO ? p->jm : p->jm + p->jl / (p->n * p->n);
    const double J = p->pid_j > 0.0 ? p->pid_j : rule;
    d->kpv = J * p->pid_wcv;
    d->kpp = p->pid_wcp;
    d->ki = d->kpv * p->ts / p->pid_ti;
    d->inv_ts = 1.0 / p->ts;
    if (p->controller == SV_PID_TDO) {
        d->a = exp(-p->tdo_dn * p->ts / p->tdo_jn);
        d->b = p->tdo_dn > 0.0 ? -expm1(-p->tdo_dn * p->ts / p->tdo_jn) / p->tdo_dn
                               : p->ts / p->tdo_jn;
        d->alpha = exp(-p->ts / p->tdo_tf);
    }
    d->notch_at = p->notch_at;
    d->states = SV_NX + (p->controller == SV_PID_TDO ? 5 : 2);
}

/* ------------------------------------------------------------------ the tick */

/* The controller's sample: reads r (the motor-side reference n q_ref), q_m and q_m' (X[0],
 * X[1]), updates its states and returns the torque. X[4..]: P/PI r_prev, integral, TDO d,
 * u_prev, w_prev; state feedback x~ (4), x_I, xi (4). */
static double control(sv_model *m, double r)
{
    const sv_design *d = &m->d;
    double *X = m->X, u;
    const double qm = X[0], wm = X[1];
    int i, j;
    if (d->kind <= SV_PID_TDO) {
        double vref = d->kpp * (r - qm) + (r - X[4]) * d->inv_ts, e;
        if (d->notch_at == SV_NOTCH_REFERENCE) {
            sms_real v = vref;
            sms_notch_step(&m->notch, &v);
            vref = v;
        }
        e = vref - wm;
        u = d->kpv * e + X[5];
        X[4] = r;
        X[5] += d->ki * e;
        if (d->notch_at == SV_NOTCH_LOOP) {
            sms_real v = u;
            sms_notch_step(&m->notch, &v);
            u = v;
        }
        if (d->kind == SV_PID_TDO) {
            const double dist = d->alpha * X[6]
                                + (1.0 - d->alpha) * (X[7] - (wm - d->a * X[8]) / d->b);
            u += dist;
            X[6] = dist;
            X[7] = u;
            X[8] = wm;
        }
    } else {
        double xd[SV_NX] = { 0.0, 0.0, 0.0, 0.0 }, ud = 0.0, ybar = r, fb = 0.0, xt[SV_NX];
        double *xi = X + 9;
        if (d->m > 0) {
            double xi_next[SV_NX];
            for (i = 0; i < SV_NX; ++i) {
                double s = 0.0;
                for (j = 0; j < SV_NX; ++j)
                    s += d->M[i * SV_NX + j] * xi[j];
                xd[i] = s;
                ud += d->N[i] * xi[i];
            }
            ud += d->N0 * r;
            ybar = xd[0];
            for (i = 0; i < SV_NX; ++i) {
                double s = 0.0;
                for (j = 0; j < SV_NX; ++j)
                    s += d->Phi[i * SV_NX + j] * xi[j];
                xi_next[i] = s + d->Gam[i] * r;
            }
            memcpy(xi, xi_next, sizeof xi_next);
        }
        for (i = 0; i < SV_NX; ++i) {
            xt[i] = X[4 + i];
            fb += d->K[i] * (xt[i] - xd[i]);
        }
        u = ud + fb + d->kI * X[8];
        for (i = 0; i < SV_NX; ++i) {
            double s = 0.0;
            for (j = 0; j < SV_NX; ++j)
                s += d->Ad[i * SV_NX + j] * xt[j];
            X[4 + i] = s + d->Bu[i] * u + d->L[i] * (xt[0] - qm);
        }
        X[8] += d->Ts * (ybar - qm);
    }
    return u;
}

/* One sample of the drive under the held inputs; the outputs are the plant at its end. */
static void step(sv_model *m)
{
    const sv_design *d = &m->d;
    const double u = control(m, d->n * m->v.q_ref), tau = m->v.tau_load;
    double x[SV_NX];
    int i, j;
    for (i = 0; i < SV_NX; ++i) {
        double s = 0.0;
        for (j = 0; j < SV_NX; ++j)
            s += d->Ad[i * SV_NX + j] * m->X[j];
        x[i] = s + d->Bu[i] * u + d->Bd[i] * tau;
    }
    memcpy(m->X, x, sizeof x);
    m->v.q_m = x[0];
    m->v.w_m = x[1];
    m->v.q_l = x[2] * d->inv_n;
    m->v.w_l = x[3] * d->inv_n;
    m->v.tau_m = u;
}

/* The loop state Z: X's entries in use, then the notch's x1, x2, w1, w2. */
static void pack(const sv_model *m, double *Z)
{
    memcpy(Z, m->X, sizeof(double) * (size_t)m->d.states);
    if (m->d.notch_at != SV_NOTCH_NONE) {
        double st[SMS_STATE_IDENTITY_COUNT + 6];
        sms_notch_get_state(&m->notch, st);
        memcpy(Z + m->d.states, st + SV_NOTCH_AT, 4 * sizeof(double));
    }
}

static int unpack(sv_model *m, const double *Z)
{
    memcpy(m->X, Z, sizeof(double) * (size_t)m->d.states);
    if (m->d.notch_at != SV_NOTCH_NONE) {
        double st[SMS_STATE_IDENTITY_COUNT + 6];
        sms_notch_get_state(&m->notch, st);
        memcpy(st + SV_NOTCH_AT, Z + m->d.states, 4 * sizeof(double));
        return sms_notch_set_state(&m->notch, st, SMS_STATE_IDENTITY_COUNT + 6) != SMS_OK;
    }
    return 0;
}

/* The loop's matrices, read off the tick with unit states and inputs (every operation of the
 * tick is linear). */
static void linearise(sv_model *m)
{
    sv_design *d = &m->d;
    const int nl = d->loop;
    double Z[SV_LOOP];
    int i, j;
    for (i = 0; i < nl + 2; ++i) {
        sv_model t = *m;
        for (j = 0; j < nl; ++j)
            Z[j] = i == j ? 1.0 : 0.0;
        t.v.q_ref = i == nl ? 1.0 : 0.0;
        t.v.tau_load = i == nl + 1 ? 1.0 : 0.0;
        (void)unpack(&t, Z);
        step(&t);
        pack(&t, Z);
        for (j = 0; j < nl; ++j) {
            if (i < nl)
                d->Acl[j * nl + i] = Z[j];
            else
                d->Bcl[j * 2 + i - nl] = Z[j];
        }
        if (i < nl)
            d->Cu[i] = t.v.tau_m;
        else
            d->Du[i - nl] = t.v.tau_m;
    }
}

static double largest(const double *a, int n, double best)
{
    int i;
    for (i = 0; i < n; ++i)
        if (fabs(a[i]) > best)
            best = fabs(a[i]);
    return best;
}

/* The bounds (file's top): with H = sup ||Acl^k|| + sum ||Acl^k|| ||Bcl|| + 1, every state
 * reached from |Z| <= state_max under inputs |w| <= input_max stays below H^2 input_max, and
 * every product the tick forms below c (loop + 2) times that, c its largest coefficient. */
static int bounds(sv_model *m, const sd_bounds *b)
{
    sv_design *d = &m->d;
    const int nl = d->loop;
    double c = 1.0, H, lim;
    const double scalars[] = { d->n, d->inv_n, d->Ts, d->kpv, d->kpp, d->ki, d->inv_ts, d->a,
                               d->b != 0.0 ? 1.0 / d->b : 0.0, d->alpha, d->kI, d->N0,
                               (double)m->notch.d0, (double)m->notch.d2, (double)m->notch.a1,
                               (double)m->notch.a2 };
    c = largest(d->Acl, nl * nl, c);
    c = largest(d->Bcl, nl * 2, c);
    c = largest(d->Cu, nl, c);
    c = largest(d->Du, 2, c);
    c = largest(d->Ad, 16, c);
    c = largest(d->Bu, 4, c);
    c = largest(d->Bd, 4, c);
    c = largest(d->K, 4, c);
    c = largest(d->L, 4, c);
    c = largest(d->Phi, 16, c);
    c = largest(d->Gam, 4, c);
    c = largest(d->M, 16, c);
    c = largest(d->N, 4, c);
    c = largest(scalars, (int)(sizeof scalars / sizeof scalars[0]), c);
    H = b->sup + b->sum * sd_norm_inf(nl, 2, d->Bcl) + 1.0;
    lim = DBL_MAX / (64.0 * (double)(nl + 2) * c * H * H);
    d->input_max = lim < SMS_INPUT_MAX ? lim : SMS_INPUT_MAX;
    d->state_max = 2.0 * H * lim;
    return !(isfinite(H) && lim > 0.0 && isfinite(d->state_max));
}

/* The rest at the held inputs: Z* = rest [q_ref, tau_load]. */
static void rest_state(const sv_model *m, double *Z)
{
    int i;
    for (i = 0; i < m->d.loop; ++i)
        Z[i] = m->d.rest[i * 2] * m->v.q_ref + m->d.rest[i * 2 + 1] * m->v.tau_load;
}

static void set_outputs_at_rest(sv_model *m, const double *Z)
{
    const sv_design *d = &m->d;
    double u = d->Du[0] * m->v.q_ref + d->Du[1] * m->v.tau_load;
    int i;
    for (i = 0; i < d->loop; ++i)
        u += d->Cu[i] * Z[i];
    m->v.q_m = Z[0];
    m->v.w_m = Z[1];
    m->v.q_l = Z[2] * d->inv_n;
    m->v.w_l = Z[3] * d->inv_n;
    m->v.tau_m = u;
}

int fmu_model_build(void *model, void *mem, size_t bytes, char *msg, size_t len)
{
    sv_model *m = (sv_model *)model;
    sv_model t = *m;
    const sv_vars *p = &t.v;
    sv_design *d = &t.d;
    double A[SV_NX * SV_NX], B[SV_NX * 2], Bc[SV_NX], Bdc[SV_NX], IA[SV_LOOP * SV_LOOP];
    double Z[SV_LOOP];
    sd_bounds b;
    int i, nl;
    (void)mem;
    (void)bytes;
    memset(d, 0, sizeof *d);
    memset(t.X, 0, sizeof t.X);
    memset(&t.notch, 0, sizeof t.notch);   /* (only a configured notch is read) */
    if (check_params(p, &t.notch, msg, len))
        return 1;
    d->kind = p->controller;
    d->Ts = p->ts;
    d->n = p->n;
    d->inv_n = 1.0 / p->n;
    plant_matrices(p, A, Bc, Bdc);
    for (i = 0; i < SV_NX; ++i) {
        B[i * 2] = Bc[i];
        B[i * 2 + 1] = Bdc[i];
    }
    if (zoh(SV_NX, 2, A, B, p->ts, d->Ad, B) != 0)
        REFUSE("Ts = %.17g: the plant cannot be discretised (matrix exponential)", p->ts);
    for (i = 0; i < SV_NX; ++i) {
        d->Bu[i] = B[i * 2];
        d->Bd[i] = B[i * 2 + 1];
    }
    if (d->kind <= SV_PID_TDO)
        design_pid(p, d);
    else if (design_state_feedback(p, d, msg, len) != 0)
        return 1;
    d->loop = nl = d->states + (d->notch_at != SV_NOTCH_NONE ? 4 : 0);
    linearise(&t);
    sd_powers(nl, d->Acl, &b);
    if (!b.stable)
        REFUSE("controller = %d: the closed loop is unstable with these parameters (spectral "
               "radius about %.6g; a stable loop has < 1): retune the gains or poles",
               p->controller, b.rho);
    for (i = 0; i < nl * nl; ++i)
        IA[i] = (i % (nl + 1) == 0 ? 1.0 : 0.0) - d->Acl[i];
    memcpy(d->rest, d->Bcl, sizeof(double) * (size_t)(nl * 2));
    if (sd_solve(nl, IA, d->rest, 2) != 0)
        REFUSE("controller = %d: the closed loop has no rest (I - Acl is singular)",
               p->controller);
    if (bounds(&t, &b) != 0)
        REFUSE("controller = %d: the closed loop is too slow or its gain too large to bound in "
               "double (sum of ||Acl^k|| about %.3g, spectral radius %.17g)", p->controller,
               b.sum, b.rho);
    if (!(fabs(p->q_ref) <= d->input_max))
        REFUSE("q_ref = %.17g: beyond %.3g, the largest input this loop keeps finite", p->q_ref,
               d->input_max);
    if (!(fabs(p->tau_load) <= d->input_max))
        REFUSE("tau_load = %.17g: beyond %.3g, the largest input this loop keeps finite",
               p->tau_load, d->input_max);
    rest_state(&t, Z);
    if (unpack(&t, Z) != 0)
        REFUSE("notch: its rest state was refused");
    set_outputs_at_rest(&t, Z);
    t.built = 1;
    *m = t;
    return 0;
}

/* Every input is valid alone (checked when set): none depends on another. */
int fmu_model_check_inputs(const void *model, char *msg, size_t len)
{
    (void)model;
    (void)msg;
    (void)len;
    return 0;
}

int fmu_model_tick(void *model)
{
    sv_model *m = (sv_model *)model;
    const double before[5] = { m->v.q_m, m->v.w_m, m->v.q_l, m->v.w_l, m->v.tau_m };
    step(m);
    return before[0] != m->v.q_m || before[1] != m->v.w_m || before[2] != m->v.q_l
           || before[3] != m->v.w_l || before[4] != m->v.tau_m;
}

/* Steps of up to this many ticks are ticked (bit for bit); longer ones use the closed form. */
#define SV_TICKED_MAX 16384u

/* Under held inputs the loop's rest is Z* = rest w and the deviation evolves as
 * Z[k] - Z* = Acl^k (Z[0] - Z*). A step of at most SV_TICKED_MAX ticks is ticked; a longer one
 * advances the deviation by Acl^(n-1) (repeated squaring), then ticks once: the result differs
 * from ticking every sample only by the ticks' rounding (the closed form being the more exact). */
uint64_t fmu_model_hold(void *model, uint64_t n)
{
    sv_model *m = (sv_model *)model;
    uint64_t i;
    if (n <= SV_TICKED_MAX) {
        for (i = 0; i < n; ++i)
            (void)fmu_model_tick(m);
        return n;
    }
    {
        const int nl = m->d.loop;
        double P[SV_LOOP * SV_LOOP], Z[SV_LOOP], rest[SV_LOOP], dev[SV_LOOP];
        int r, c;
        pack(m, Z);
        rest_state(m, rest);
        for (r = 0; r < nl; ++r)
            dev[r] = Z[r] - rest[r];
        sd_power(nl, m->d.Acl, n - 1u, P);
        for (r = 0; r < nl; ++r) {
            double s = 0.0;
            for (c = 0; c < nl; ++c)
                s += P[r * nl + c] * dev[c];
            Z[r] = rest[r] + s;
        }
        (void)unpack(m, Z);
    }
    (void)fmu_model_tick(m);
    return n;
}

/* Every input is taken as it is (nothing to warn about); the model holds no pointers. */
int fmu_model_warning(void *model, char *msg, size_t len)
{ (void)model, (void)msg, (void)len; return 0; }
void fmu_model_rebind(void *model, void *mem) { (void)model, (void)mem; }

size_t fmu_model_state_count(const void *model)
{
    const sv_model *m = (const sv_model *)model;
    return m->built ? 5u + (size_t)m->d.loop : 0u;
}

void fmu_model_save_state(const void *model, double *dst)
{
    const sv_model *m = (const sv_model *)model;
    dst[0] = m->v.q_m;
    dst[1] = m->v.w_m;
    dst[2] = m->v.q_l;
    dst[3] = m->v.w_l;
    dst[4] = m->v.tau_m;
    pack(m, dst + 5);
}

int fmu_model_load_state(void *model, const double *src, size_t n, char *msg, size_t len)
{
    sv_model *m = (sv_model *)model;
    sv_model t;
    size_t i;
    if (!m->built || n != fmu_model_state_count(m))
        return 1;
    for (i = 0; i < n; ++i)
        if (!isfinite(src[i]))
            return 1;
    for (i = 5; i < n; ++i)
        if (!(fabs(src[i]) <= m->d.state_max)) {
            snprintf(msg, len, "its loop state %lu = %.17g is beyond %.3g, the largest this loop "
                     "keeps finite", (unsigned long)(i - 5), src[i], m->d.state_max);
            return 1;
        }
    /* The outputs are the plant at the last tick (the loop state's first four values) and the
     * torque of that tick, which the bounds keep below DBL_MAX / 64 (bounds()): a state whose
     * outputs are other is none a run makes. */
    if (!(src[0] == src[5] && src[1] == src[6] && src[2] == src[7] * m->d.inv_n
          && src[3] == src[8] * m->d.inv_n)) {
        snprintf(msg, len, "its outputs q_m, w_m, q_l, w_l = %.17g, %.17g, %.17g, %.17g are not "
                 "the plant's state they are read from", src[0], src[1], src[2], src[3]);
        return 1;
    }
    if (!(fabs(src[4]) <= DBL_MAX / 64.0)) {
        snprintf(msg, len, "its output tau_m = %.17g is beyond %.3g, the largest this loop "
                 "forms", src[4], DBL_MAX / 64.0);
        return 1;
    }
    t = *m;
    if (unpack(&t, src + 5) != 0)
        return 1;
    t.v.q_m = src[0];
    t.v.w_m = src[1];
    t.v.q_l = src[2];
    t.v.w_l = src[3];
    t.v.tau_m = src[4];
    *m = t;
    return 0;
}
