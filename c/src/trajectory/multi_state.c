/* SPDX-License-Identifier: Apache-2.0 */
/* The multi-axis generator's saved state: its configuration identity, the profile's fields and
 * the stages' states, checked before anything is written (multi_generator.h). */
#include <float.h>
#include <math.h>
#include <string.h>
#include "core/state_identity.h"
#include "trajectory/multi_parts.h"

/* The configuration identity of a saved state (multi_generator.h, SMS_MULTI_IDENTITY_COUNT):
 * the common head, n_axes, sync, then per axis slot vmax, amax, jmax, n_stages, qmin, qmax
 * (0 beyond n_axes). The stages' configs are in their own stage states. */
enum { ID_AXES = SMS_STATE_IDENTITY_HEAD, ID_SYNC, ID_AXIS, ID_AXIS_FIELDS = 6 };

void sms_multi_identity_write(const sms_multi_generator_config *c, double Ts,
                              double id[SMS_MULTI_IDENTITY_COUNT])
{
    size_t i;
    sms_state_identity_head(id, SMS_STATE_KIND_MULTI_GENERATOR, Ts);
    id[ID_AXES] = (double)c->n_axes;
    id[ID_SYNC] = (double)c->sync;
    for (i = 0; i < SMS_MULTI_MAX_AXES; ++i) {
        double *axis = id + ID_AXIS + ID_AXIS_FIELDS * i;
        axis[0] = i < c->n_axes ? c->vmax[i] : 0.0;
        axis[1] = i < c->n_axes ? c->amax[i] : 0.0;
        axis[2] = i < c->n_axes ? c->jmax[i] : 0.0;
        axis[3] = i < c->n_axes ? (double)c->n_stages[i] : 0.0;
        axis[4] = i < c->n_axes ? c->qmin[i] : 0.0;
        axis[5] = i < c->n_axes ? c->qmax[i] : 0.0;
    }
}

static sms_status check_identity(const sms_multi_generator *g, const double *src)
{
    sms_status field_status[SMS_MULTI_IDENTITY_COUNT - SMS_STATE_IDENTITY_HEAD];
    size_t i;
    field_status[ID_AXES - SMS_STATE_IDENTITY_HEAD] = SMS_ERR_STATE_AXES;
    field_status[ID_SYNC - SMS_STATE_IDENTITY_HEAD] = SMS_ERR_STATE_SYNC;
    for (i = 0; i < SMS_MULTI_MAX_AXES; ++i) {
        sms_status *axis = field_status + ID_AXIS - SMS_STATE_IDENTITY_HEAD + ID_AXIS_FIELDS * i;
        axis[0] = SMS_ERR_STATE_VMAX;
        axis[1] = SMS_ERR_STATE_AMAX;
        axis[2] = SMS_ERR_STATE_JMAX;
        axis[3] = SMS_ERR_STATE_STAGES;
        axis[4] = SMS_ERR_POSITION_LIMIT;
        axis[5] = SMS_ERR_POSITION_LIMIT;
    }
    return sms_state_identity_compare(g->identity, src,
                                      SMS_MULTI_IDENTITY_COUNT - SMS_STATE_IDENTITY_HEAD,
                                      field_status);
}
/* ---- state vector: the identity; per axis target, goal, p, V, W; per move its 12 fields;
 * the stages' states ---- */

#define AXIS_FIELDS 5u
#define MOVE_FIELDS 12u

static size_t move_count(const sms_multi_generator *g)
{
    return g->sync == SMS_SYNC_PHASE ? 1u : g->n_axes;
}

/* The per-axis plan modes save, in place of the moves: the request and the aim (each per axis
 * position, velocity, acceleration, sync, then the minimum duration), per axis the running
 * plan's start q0, v0, a0, its minimum duration and k, and the refused flag. Loading re-forms
 * each plan from its start (the planner is a function of these). */
static size_t target_fields(const sms_multi_generator *g)
{
    return 4u * g->n_axes + 1u;
}

static size_t moves_fields(const sms_multi_generator *g)
{
    if (SMS_SYNC_PER_AXIS_PLANS(g->sync))
        return 2u * target_fields(g) + 5u * g->n_axes + 1u;
    return MOVE_FIELDS * move_count(g);
}

static void put_target(const sms_multi_target *t, size_t n, double *dst)
{
    size_t i;
    for (i = 0; i < n; ++i) {
        dst[i] = (double)t->position[i];
        dst[n + i] = (double)t->velocity[i];
        dst[2 * n + i] = (double)t->acceleration[i];
        dst[3 * n + i] = (double)t->sync[i];
    }
    dst[4 * n] = (double)t->minimum_duration;
}

static void get_target(const double *src, size_t n, sms_multi_target *t)
{
    size_t i;
    memset(t, 0, sizeof *t);
    for (i = 0; i < n; ++i) {
        t->position[i] = (sms_real)src[i];
        t->velocity[i] = (sms_real)src[n + i];
        t->acceleration[i] = (sms_real)src[2 * n + i];
        t->sync[i] = (int)src[3 * n + i];
    }
    t->minimum_duration = (sms_real)src[4 * n];
}

static void put_plans(const sms_multi_generator *g, double *dst)
{
    size_t i, n = g->n_axes;
    put_target(&g->request, n, dst);
    dst += target_fields(g);
    put_target(&g->aim, n, dst);
    dst += target_fields(g);
    for (i = 0; i < n; ++i, dst += 5) {
        const sms_multi_axis_plan *ax = &g->axis[i];
        dst[0] = (double)ax->q0;
        dst[1] = (double)ax->v0;
        dst[2] = (double)ax->a0;
        dst[3] = (double)ax->tmin;
        dst[4] = (double)ax->k;
    }
    dst[0] = (double)g->plan_refused;
}

static int whole(double x);

/* The plans of a saved state, re-formed into ax (1: all formed and the fields valid). */
static int read_plans(const sms_multi_generator *g, const double *src, sms_multi_target *request,
                      sms_multi_target *aim, sms_multi_axis_plan *ax, int *refused)
{
    size_t i, n = g->n_axes;
    for (i = 0; i < n; ++i) {
        const double sr = src[3 * n + i], sa = src[target_fields(g) + 3 * n + i];
        if (!(fabs(sr) <= 64.0) || !(fabs(sa) <= 64.0) || sr != (double)(int)sr ||
            sa != (double)(int)sa)
            return 0;
    }
    get_target(src, n, request);
    src += target_fields(g);
    get_target(src, n, aim);
    src += target_fields(g);
    if (sms_multi_generator_check_target(g, aim, NULL) != SMS_OK)
        return 0;
    for (i = 0; i < n; ++i, src += 5) {
        if (!sms_multi_sync_start_ok(g, i, src[0], src[1], src[2]) || !(src[3] >= 0.0) ||
            !whole(src[4]))
            return 0;
        ax[i].q0 = (sms_real)src[0];
        ax[i].v0 = (sms_real)src[1];
        ax[i].a0 = (sms_real)src[2];
        ax[i].tmin = (sms_real)src[3];
        ax[i].k = (size_t)src[4];
        if (!sms_multi_sync_replan_axis(g, i, aim, &ax[i]))
            return 0;
    }
    if (src[0] != 0.0 && src[0] != 1.0)
        return 0;
    *refused = (int)src[0];
    return 1;
}

static size_t stages_state_count(const sms_multi_generator *g)
{
    size_t i, m, total = 0;
    for (i = 0; i < g->n_axes; ++i)
        for (m = 0; m < SMS_MULTI_SIGNALS; ++m)
            total += sms_chain_state_count(&g->chain[i][m]);
    return total;
}

size_t sms_multi_generator_state_count(const sms_multi_generator *g)
{
    return SMS_MULTI_IDENTITY_COUNT + AXIS_FIELDS * g->n_axes + moves_fields(g)
           + stages_state_count(g) + sms_multi_align_state_count(g);
}

void sms_multi_generator_get_state(const sms_multi_generator *g, double *dst)
{
    size_t i, n = g->n_axes;
    for (i = 0; i < SMS_MULTI_IDENTITY_COUNT; ++i)
        dst[i] = g->identity[i];
    dst += SMS_MULTI_IDENTITY_COUNT;
    for (i = 0; i < n; ++i) {
        dst[i] = (double)g->target[i];
        dst[n + i] = (double)g->goal[i];
        dst[2 * n + i] = (double)g->p[i];
        dst[3 * n + i] = (double)g->V[i];
        dst[4 * n + i] = (double)g->W[i];
    }
    dst += AXIS_FIELDS * n;
    if (SMS_SYNC_PER_AXIS_PLANS(g->sync)) {
        put_plans(g, dst);
        dst += moves_fields(g);
    }
    for (i = 0; i < move_count(g) && !SMS_SYNC_PER_AXIS_PLANS(g->sync); ++i, dst += MOVE_FIELDS) {
        const sms_multi_move *m = &g->move[i];
        dst[0] = (double)m->T1;
        dst[1] = (double)m->rho1;
        dst[2] = (double)m->tau;
        dst[3] = (double)m->T2;
        dst[4] = (double)m->rho2;
        dst[5] = (double)m->off;
        dst[6] = (double)m->seen;
        dst[7] = (double)m->k;
        dst[8] = (double)m->k_end;
        dst[9] = (double)m->active;
        dst[10] = (double)m->pending;
        dst[11] = (double)m->refused;
    }
    for (i = 0; i < n; ++i) {
        size_t s;
        for (s = 0; s < SMS_MULTI_SIGNALS; ++s) {
            sms_chain_get_state(&g->chain[i][s], dst);
            dst += sms_chain_state_count(&g->chain[i][s]);
        }
    }
    sms_multi_align_get_state(g, dst);
}

/* Would every stage of every chain accept its part of src (n doubles)? Writes nothing. A stage
 * saved by another stage configuration gets the status naming the field (its stage identity),
 * also when that made the vector longer or shorter. */
static sms_status check_stages_state(const sms_multi_generator *g, const double *src, size_t n)
{
    size_t i, m, k;
    for (i = 0; i < g->n_axes; ++i)
        for (m = 0; m < SMS_MULTI_SIGNALS; ++m)
            for (k = 0; k < g->chain[i][m].n_stages; ++k) {
                const sms_stage *st = &g->chain[i][m].stages[k];
                size_t count = sms_stage_state_count(st);
                sms_status status;
                if (n < SMS_STATE_IDENTITY_COUNT)
                    return SMS_ERR_STATE;
                status = sms_stage_check_state(st, src, n < count ? n : count);
                if (status != SMS_OK)
                    return status <= SMS_ERR_STATE_FORMAT ? status : SMS_ERR_STATE;
                src += count;
                n -= count;
            }
    return n == 0 ? SMS_OK : SMS_ERR_STATE;
}

/* Every chain's values within what its signal leaves in it: the positions within the chain's
 * input range, v, a, j within the axis's limits to the reported values' tolerance
 * (SMS_LIMIT_RTOL): a state no run produces (a forged one) would report beyond them. */
static sms_status check_stages_range(const sms_multi_generator *g, const double *src)
{
    size_t i, m;
    for (i = 0; i < g->n_axes; ++i)
        for (m = 0; m < SMS_MULTI_SIGNALS; ++m) {
            const sms_chain *c = &g->chain[i][m];
            const size_t count = sms_chain_state_count(c);
            if (c->n_stages > 0
                && sms_chain_check_state_range(c, src, count, sms_multi_signal_range(g, i, m))
                   != SMS_OK)
                return SMS_ERR_STATE;
            src += count;
        }
    return SMS_OK;
}

static int whole(double x)
{
    return x >= 0.0 && x <= 9007199254740992.0 && x == (double)(size_t)x;
}

sms_status sms_multi_generator_check_state(const sms_multi_generator *g, const double *src,
                                           size_t n)
{
    size_t i, na;
    const double *mv;
    sms_status st;
    if (g == NULL || src == NULL)
        return SMS_ERR_NULL;
    /* another configuration first, whatever the length: its state often has another one */
    if (n >= SMS_MULTI_IDENTITY_COUNT && (st = check_identity(g, src)) != SMS_OK)
        return st;
    na = g->n_axes;
    if (n != sms_multi_generator_state_count(g)) {
        /* the same limits, another length: a stage of another configuration, named by the
         * first stage identity that differs */
        const size_t fixed = SMS_MULTI_IDENTITY_COUNT + AXIS_FIELDS * na + moves_fields(g);
        if (n > fixed && (st = check_stages_state(g, src + fixed, n - fixed)) <= SMS_ERR_STATE_FORMAT)
            return st;
        return SMS_ERR_STATE;
    }
    src += SMS_MULTI_IDENTITY_COUNT;
    n -= SMS_MULTI_IDENTITY_COUNT;
    for (i = 0; i < n; ++i)
        if (!isfinite(src[i]))
            return SMS_ERR_STATE;
    for (i = 0; i < na; ++i) {
        /* as sms_real holds them: the start and cruise velocities within the tolerance of
         * the reported values (the planner's own within 12 eps, above) */
        const double vmax = (double)g->vmax[i] * (1.0 + SMS_LIMIT_RTOL);
        if (!(fabs((double)(sms_real)src[3 * na + i]) <= vmax) ||
            !(fabs((double)(sms_real)src[4 * na + i]) <= vmax))
            return SMS_ERR_STATE;
    }
    mv = src + AXIS_FIELDS * na;
    if (SMS_SYNC_PER_AXIS_PLANS(g->sync)) {
        sms_multi_target request, aim;
        sms_multi_axis_plan ax[SMS_MULTI_MAX_AXES];
        int refused;
        if (!read_plans(g, mv, &request, &aim, ax, &refused))
            return SMS_ERR_STATE;
    }
    for (i = 0; i < move_count(g) && !SMS_SYNC_PER_AXIS_PLANS(g->sync); ++i) {
        /* durations [s] within the 2^53 samples a move's counts hold (finite: init holds Ts
         * to SMS_TS_MAX) and below half the largest sms_real (the float build holds them in
         * floats; a move's durations add up), the first sample's move time within one sample */
        const double *f = mv + MOVE_FIELDS * i;
        const double span = 9007199254740992.0 * g->Ts;
        const double horizon = span < 0.5 * (double)REAL_MAX ? span : 0.5 * (double)REAL_MAX;
        if (f[0] < 0.0 || f[2] < 0.0 || f[3] < 0.0 || f[5] < 0.0 || f[6] < 0.0 ||
            f[0] > horizon || f[2] > horizon || f[3] > horizon || f[5] > g->Ts
            || f[6] > horizon ||
            !(f[1] > 0.0 && f[1] <= 0.5) || !(f[4] > 0.0 && f[4] <= 0.5) || !whole(f[7]) ||
            !whole(f[8]) || f[7] > f[8] || (f[9] != 0.0 && f[9] != 1.0) ||
            (f[10] != 0.0 && f[10] != 1.0) || (f[11] != 0.0 && f[11] != 1.0))
            return SMS_ERR_STATE;
    }
    mv += moves_fields(g);
    st = check_stages_state(g, mv, stages_state_count(g));
    if (st == SMS_OK)
        st = check_stages_range(g, mv);
    if (st != SMS_OK)
        return st;
    return sms_multi_align_check_state(g, mv + stages_state_count(g));
}

sms_status sms_multi_generator_set_state(sms_multi_generator *g, const double *src, size_t n)
{
    size_t i, na;
    const double *mv;
    sms_status st = sms_multi_generator_check_state(g, src, n);
    if (st != SMS_OK)
        return st;
    src += SMS_MULTI_IDENTITY_COUNT;
    na = g->n_axes;
    mv = src + AXIS_FIELDS * na;
    for (i = 0; i < na; ++i) {
        g->target[i] = (sms_real)src[i];
        g->goal[i] = (sms_real)src[na + i];
        g->p[i] = (sms_real)src[2 * na + i];
        g->V[i] = (sms_real)src[3 * na + i];
        g->W[i] = (sms_real)src[4 * na + i];
    }
    if (SMS_SYNC_PER_AXIS_PLANS(g->sync)) {
        sms_multi_axis_plan ax[SMS_MULTI_MAX_AXES];
        int refused = 0;
        (void)read_plans(g, mv, &g->request, &g->aim, ax, &refused); /* checked above */
        for (i = 0; i < na; ++i)
            g->axis[i] = ax[i];
        g->plan_refused = refused;
        /* a valid request not yet planned (position limits: a re-plan that waits for a
         * state from which it stays inside) is tried again on the next sample */
        g->plan_pending = !refused && sms_multi_sync_fresh_aim(g);
    }
    for (i = 0; i < move_count(g) && !SMS_SYNC_PER_AXIS_PLANS(g->sync); ++i) {
        const double *f = mv + MOVE_FIELDS * i;
        sms_multi_move *m = &g->move[i];
        m->T1 = (sms_real)f[0];
        m->rho1 = (sms_real)f[1];
        m->tau = (sms_real)f[2];
        m->T2 = (sms_real)f[3];
        m->rho2 = (sms_real)f[4];
        m->off = (sms_real)f[5];
        m->seen = (sms_real)f[6];
        m->k = (size_t)f[7];
        m->k_end = (size_t)f[8];
        m->active = (int)f[9];
        m->pending = (int)f[10];
        m->refused = (int)f[11];
    }
    mv += moves_fields(g);
    for (i = 0; i < na; ++i) {
        size_t s;
        for (s = 0; s < SMS_MULTI_SIGNALS; ++s) {
            size_t count = sms_chain_state_count(&g->chain[i][s]);
            if (count > 0)
                (void)sms_chain_set_state(&g->chain[i][s], mv, count); /* checked above */
            mv += count;
        }
    }
    sms_multi_align_set_state(g, mv);
    return SMS_OK;
}

void sms_multi_generator_rebind(sms_multi_generator *g, sms_stage *stages,
                                sms_memory_cell *memory)
{
    size_t i, m;
    for (i = 0; i < g->n_axes; ++i)
        for (m = 0; m < SMS_MULTI_SIGNALS; ++m) {
            sms_chain *c = &g->chain[i][m];
            if (c->n_stages == 0)
                continue;
            sms_chain_rebind(c, stages, memory);
            stages += c->n_stages;
            memory += c->memory_len;
        }
    sms_multi_align_rebind(g, memory);
}

