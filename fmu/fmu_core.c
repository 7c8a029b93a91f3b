/* SPDX-License-Identifier: Apache-2.0 */
/*
 * The FMI Co-Simulation calls, implemented once for every smoothshaper model (fmu_model.h) and
 * both FMI versions: fmi2_glue.c and fmi3_glue.c translate their types and call these.
 *
 * State machine (FMI 2.0 section 4.2.4, FMI 3.0 section 4.2.1, the states that can occur with a
 * synchronous doStep and no event mode):
 *   instantiated --enterInitializationMode--> initializationMode --exitInitializationMode-->
 *   stepComplete (FMI 3.0: Step Mode) --doStep--> stepComplete --terminate--> terminated;
 *   reset from any state goes back to instantiated with every variable at its start value.
 * Which call is allowed in which state is the glue's (fmu_enter's `allowed`): a call in a state
 * where its FMI version does not allow it returns an error with a logged message and changes
 * nothing. Every error leaves the instance as it was before the call.
 *
 * Time: internal ticks happen at t0 + n*Ts (n = 1, 2, ... an integer counter, so no drift).
 * doStep(t, h) computes every tick in (t, t+h]: the instance counts the ticks done and the time
 * advanced since the last one (fmu_clock), and a step of length h computes
 * floor((since_tick + h + slack)/Ts) ticks, the slack covering the rounding of the importer's
 * times (fmu_clock.c). So the tick count follows the step lengths, not the importer's
 * accumulated t: a host doing t += h (whose t drifts from k*h by many ticks over 1e9 steps)
 * gets exactly one tick per step of h = Ts, and so does a host with t = t0 + k*h whatever t0.
 * Each of those ticks filters the input value set before the call (the input is held over the
 * step). The outputs after the call are those of the last tick computed; a step that contains
 * no tick leaves the outputs unchanged. Before the first tick the outputs are the rest point:
 * the input value at exitInitializationMode. A step of many ticks costs a bounded time: the
 * model holds the input over them in closed form where it can (fmu_model_hold()), see
 * run_ticks.
 *
 * Identity: every entry point first checks that the instance (and any FMU state) was made by
 * this binary (same model, same precision) for this FMI version; another model's instance gets
 * an error and is never written to.
 */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "fmu_core.h"
#include "fmu_serialize.h"
#include "smoothshaper/types.h"

static const char *const category_names[FMU_LOG_CATEGORIES] = {
    "logStatusError", "logStatusWarning", "logCalls"
};

/* A model's message (up to FMU_MESSAGE_LEN) after the call's prefix ("fmi2DoStep at t = ...: "). */
#define LOG_LEN (FMU_MESSAGE_LEN + 128)

static void vlog(const fmu_host *host, const char *name, fmu_status status, int category,
                 const char *fmt, va_list ap)
{
    char buf[LOG_LEN];
    vsnprintf(buf, sizeof buf, fmt, ap);
    host->log(host, name, status, category_names[category], buf);
}

void fmu_log(const fmu_instance *c, fmu_status status, int category, const char *fmt, ...)
{
    va_list ap;
    /* Errors and warnings always reach the logger; only the debug categories obey loggingOn
     * and SetDebugLogging. */
    if (c == NULL || c->host.log == NULL || (category >= FMU_LOG_CALLS && !c->log_on[category]))
        return;
    va_start(ap, fmt);
    vlog(&c->host, c->name, status, category, fmt, ap);
    va_end(ap);
}

fmu_status fmu_fail(const fmu_instance *c, const char *fmt, ...)
{
    va_list ap;
    if (c == NULL || c->host.log == NULL)
        return FMU_ERROR;
    va_start(ap, fmt);
    vlog(&c->host, c->name, FMU_ERROR, FMU_LOG_ERROR, fmt, ap);
    va_end(ap);
    return FMU_ERROR;
}

void fmu_log_host(const fmu_host *host, const char *instance, const char *fmt, ...)
{
    va_list ap;
    if (host == NULL || host->log == NULL)
        return;
    va_start(ap, fmt);
    vlog(host, instance, FMU_ERROR, FMU_LOG_ERROR, fmt, ap);
    va_end(ap);
}

#define FAIL fmu_fail

static const char *const phase_names[] = {
    "instantiated", "initialization mode", "step complete", "terminated"
};

/* One per binary: its address tells this binary's instances and states from any other's. */
static const char glue_token = 0;

/* Made by this binary (so by this model, in this precision) with this magic. */
static int is_ours(const fmu_identity *id, uint32_t magic)
{
    return id->magic == magic && id->binary == &glue_token;
}

static fmu_identity identity(uint32_t magic)
{
    fmu_identity id;
    id.magic = magic;
    id.binary = &glue_token;
    id.real_bytes = fmu_model_real_bytes();
    return id;
}

fmu_instance *fmu_enter(void *comp, uint32_t magic, const char *func, unsigned allowed)
{
    fmu_instance *c = (fmu_instance *)comp;
    if (c == NULL || c->id.magic != magic)
        return NULL;
    if (!is_ours(&c->id, magic)) {
        /* Another smoothshaper model's (or precision's) instance: same glue layout, so its
         * logger can say so; nothing of it is written. */
        fmu_log(c, FMU_ERROR, FMU_LOG_ERROR, "%s: instance '%s' belongs to another FMU (not "
                "%s, %u-byte reals): refused", func, c->name ? c->name : "?",
                fmu_model_identifier(), fmu_model_real_bytes());
        return NULL;
    }
    if (c->log_on[FMU_LOG_CALLS])
        fmu_log(c, FMU_OK, FMU_LOG_CALLS, "%s", func);
    if (!(allowed & (1u << c->clock.phase))) {
        fmu_log(c, FMU_ERROR, FMU_LOG_ERROR, "%s is not allowed in state '%s'", func,
                phase_names[c->clock.phase]);
        return NULL;
    }
    return c;
}

/* ---------------------------------------------------------------- life cycle */

fmu_status fmu_set_debug_logging(fmu_instance *c, const char *func, int on, size_t n,
                                 const char *const categories[])
{
    int flags[FMU_LOG_CATEGORIES];
    size_t i;
    int k;
    if (n == 0) {
        for (k = 0; k < FMU_LOG_CATEGORIES; ++k)
            c->log_on[k] = on ? 1 : 0;
        return FMU_OK;
    }
    if (categories == NULL)
        return FAIL(c, "%s: categories is NULL but nCategories = %lu", func, (unsigned long)n);
    memcpy(flags, c->log_on, sizeof flags);
    for (i = 0; i < n; ++i) {
        int found = 0;
        if (categories[i] == NULL)
            return FAIL(c, "%s: categories[%lu] is NULL", func, (unsigned long)i);
        for (k = 0; k < FMU_LOG_CATEGORIES; ++k) {
            if (strcmp(categories[i], category_names[k]) == 0) {
                flags[k] = on ? 1 : 0;
                found = 1;
            }
        }
        if (!found)
            return FAIL(c, "%s: unknown log category '%s'", func, categories[i]);
    }
    memcpy(c->log_on, flags, sizeof flags);
    return FMU_OK;
}

fmu_instance *fmu_instantiate(const fmu_host *host, uint32_t magic, const char *func,
                              const char *name, const char *token, const char *expected,
                              int logging_on)
{
    fmu_instance *c;
    size_t name_len;
    int k;
    if (host == NULL || host->alloc == NULL || host->release == NULL)
        return NULL;
    if (name == NULL || name[0] == '\0') {
        fmu_log_host(host, "?", "%s: instanceName is NULL or empty", func);
        return NULL;
    }
    if (token == NULL || strcmp(token, expected) != 0) {
        fmu_log_host(host, name, "%s: instantiation token '%s' does not match '%s' of this "
                     "binary", func, token ? token : "(NULL)", expected);
        return NULL;
    }
    c = (fmu_instance *)host->alloc(1, sizeof *c);
    if (c == NULL) {
        fmu_log_host(host, name, "%s: out of memory", func);
        return NULL;
    }
    c->host = *host;
    name_len = strlen(name);
    c->name = (char *)host->alloc(name_len + 1, 1);
    c->model = host->alloc(1, fmu_model_size());
    if (c->name == NULL || c->model == NULL) {
        fmu_log_host(host, name, "%s: out of memory", func);
        if (c->name)
            host->release(c->name);
        if (c->model)
            host->release(c->model);
        host->release(c);
        return NULL;
    }
    memcpy(c->name, name, name_len + 1);
    for (k = 0; k < FMU_LOG_CATEGORIES; ++k)   /* loggingOn switches all categories */
        c->log_on[k] = logging_on ? 1 : 0;
    c->id = identity(magic);
    fmu_model_defaults(c->model);
    memset(&c->clock, 0, sizeof c->clock);
    c->clock.phase = FMU_INSTANTIATED;
    return c;
}

/* Free the filters' block (the model is unbuilt afterwards). */
static void release_blocks(fmu_instance *c)
{
    if (c->mem != NULL)
        c->host.release(c->mem);
    c->mem = NULL;
    c->mem_bytes = 0;
}

void fmu_free_instance(fmu_instance *c)
{
    void (*release)(void *) = c->host.release;
    release_blocks(c);
    fmu_values_image_free(&c->values, &c->host);
    c->id.magic = 0;
    release(c->model);
    release(c->name);
    release(c);
}

fmu_status fmu_setup(fmu_instance *c, const char *func, double start, int stop_defined,
                     double stop)
{
    if (!isfinite(start))
        return FAIL(c, "%s: startTime must be finite", func);
    if (stop_defined && !(stop >= start))
        return FAIL(c, "%s: stopTime must be >= startTime", func);
    c->clock.start_time = start;
    c->clock.time = start;
    return FMU_OK;
}

fmu_status fmu_enter_initialization(fmu_instance *c)
{
    c->clock.phase = FMU_INITIALIZATION_MODE;
    return FMU_OK;
}

fmu_status fmu_exit_initialization(fmu_instance *c, const char *func)
{
    char msg[FMU_MESSAGE_LEN];
    int built;
    msg[0] = '\0';
    c->values.valid = 0;
    {
        const double Ts = fmu_model_sample_period(c->model);
        if (isfinite(Ts) && Ts > SMS_TS_MAX) /* NaN, infinities: the model names them */
            return FAIL(c, "%s: Ts = %.17g is above %.17g (SMS_TS_MAX): 2^56 Ts, the longest "
                        "sum of tick and duration times in a state, would overflow", func, Ts,
                        SMS_TS_MAX);
    }
    built = fmu_build(&c->host, c->model, &c->mem, &c->mem_bytes, msg, sizeof msg);
    if (built > 0)
        return FAIL(c, "%s: %s", func, msg);
    c->clock.time = c->clock.start_time;
    c->clock.ticks = 0;
    c->clock.since_tick = 0.0;
    c->clock.steady = 0;
    c->clock.phase = FMU_STEP_COMPLETE;
    if (built < 0) { /* built, with a warning about the parameters */
        fmu_log(c, FMU_WARNING, FMU_LOG_WARNING, "%s: %s", func, msg);
        return FMU_WARNING;
    }
    return FMU_OK;
}

fmu_status fmu_terminate(fmu_instance *c)
{
    c->clock.phase = FMU_TERMINATED;
    return FMU_OK;
}

fmu_status fmu_reset(fmu_instance *c)
{
    release_blocks(c);
    c->values.valid = 0;
    memset(c->model, 0, fmu_model_size());
    fmu_model_defaults(c->model);
    memset(&c->clock, 0, sizeof c->clock);
    c->clock.phase = FMU_INSTANTIATED;
    return FMU_OK;
}

/* ---------------------------------------------------------------- get / set */

static fmu_status check_arrays(fmu_instance *c, const char *func, const fmu_vr vr[], size_t nvr,
                               const void *value)
{
    if (nvr > 0 && (vr == NULL || value == NULL))
        return FAIL(c, "%s: vr or value is NULL with nvr = %lu", func, (unsigned long)nvr);
    return FMU_OK;
}

/* The independent variable time, where the interface declares it (FMI 3.0). */
static int is_time(const fmu_instance *c, fmu_type type, fmu_vr vr)
{
    return c->has_time && type == FMU_REAL && vr == c->time_vr;
}

fmu_status fmu_get(fmu_instance *c, const char *func, fmu_type type, const fmu_vr vr[],
                   size_t nvr, void *value)
{
    size_t i;
    if (check_arrays(c, func, vr, nvr, value) != FMU_OK)
        return FMU_ERROR;
    for (i = 0; i < nvr; ++i)   /* check all first: an error writes nothing */
        if (fmu_model_class(type, vr[i]) == FMU_VAR_UNKNOWN && !is_time(c, type, vr[i]))
            return FAIL(c, "%s: unknown value reference %lu", func, (unsigned long)vr[i]);
    for (i = 0; i < nvr; ++i) {
        if (type == FMU_REAL)
            ((double *)value)[i] = is_time(c, type, vr[i]) ? c->clock.time
                                                           : fmu_model_get_real(c->model, vr[i]);
        else
            ((int32_t *)value)[i] = (int32_t)fmu_model_get_integer(c->model, vr[i]);
    }
    return FMU_OK;
}

/* Largest |input| a model accepts: SMS_INPUT_MAX, or its built configuration's own range. */
static double model_input_max(const void *model)
{
    const double own = fmu_model_input_max(model);
    return own < SMS_INPUT_MAX ? own : SMS_INPUT_MAX;
}

/* Largest |input| accepted now. */
static double input_max(const fmu_instance *c)
{
    return model_input_max(c->model);
}

/* The message for a value fmu_set refuses (formatted only here, never on the hot path). */
static fmu_status refuse_value(fmu_instance *c, const char *func, fmu_type type,
                               fmu_var_class cls, fmu_vr vr, const void *value, size_t i)
{
    char name[96];
    fmu_model_name(type, vr, name, sizeof name);
    if (cls == FMU_VAR_OUTPUT)
        return FAIL(c, "%s: %s is an output and cannot be set", func, name);
    if (cls == FMU_VAR_PARAMETER && c->clock.phase == FMU_STEP_COMPLETE)
        return FAIL(c, "%s: %s is a fixed parameter: set it before %.4sExitInitializationMode",
                    func, name, func);
    if (cls == FMU_VAR_INPUT && isfinite(((const double *)value)[i]))
        return FAIL(c, "%s: %s = %g is beyond %.17g, the input range within which the filters' "
                    "internal sums stay finite (SMS_INPUT_MAX, or less for a configuration with "
                    "a large internal gain, now or after a retune still to take effect)", func,
                    name, ((const double *)value)[i], input_max(c));
    return FAIL(c, "%s: %s must be finite, got %g", func, name, ((const double *)value)[i]);
}

fmu_status fmu_set(fmu_instance *c, const char *func, fmu_type type, const fmu_vr vr[],
                   size_t nvr, const void *value)
{
    size_t i;
    if (check_arrays(c, func, vr, nvr, value) != FMU_OK)
        return FMU_ERROR;
    if (nvr == 1 && type == FMU_REAL && fmu_model_class(type, vr[0]) == FMU_VAR_INPUT) {
        /* one input, the call of every step: one pass */
        const double v = *(const double *)value;
        if (!(fabs(v) <= input_max(c)))
            return refuse_value(c, func, type, FMU_VAR_INPUT, vr[0], value, 0);
        if (c->clock.steady != 0 && fmu_model_get_real(c->model, vr[0]) != v)
            c->clock.steady = 0;   /* a new input: it has to be absorbed again */
        fmu_model_set_real(c->model, vr[0], v);
        return FMU_OK;
    }
    for (i = 0; i < nvr; ++i) {   /* check all first: an error writes nothing */
        fmu_var_class cls = fmu_model_class(type, vr[i]);
        if (cls == FMU_VAR_UNKNOWN)
            return is_time(c, type, vr[i])
                   ? FAIL(c, "%s: time (value reference %lu) is the independent variable and "
                          "cannot be set", func, (unsigned long)vr[i])
                   : FAIL(c, "%s: unknown value reference %lu", func, (unsigned long)vr[i]);
        if (cls == FMU_VAR_OUTPUT
            || (cls == FMU_VAR_PARAMETER && c->clock.phase == FMU_STEP_COMPLETE)
            || (type == FMU_REAL && !isfinite(((const double *)value)[i]))
            || (type == FMU_REAL && cls == FMU_VAR_INPUT
                && fabs(((const double *)value)[i]) > input_max(c)))
            return refuse_value(c, func, type, cls, vr[i], value, i);
    }
    if (c->clock.phase == FMU_STEP_COMPLETE) {   /* tunable parameters: the model checks */
        int tunable = 0;
        for (i = 0; i < nvr; ++i)
            tunable |= fmu_model_class(type, vr[i]) == FMU_VAR_TUNABLE;
        if (tunable) {
            char msg[FMU_MESSAGE_LEN];
            msg[0] = '\0';
            if (fmu_model_check_tunable(c->model, type, vr, value, nvr, msg, sizeof msg) != 0)
                return FAIL(c, "%s: %s", func, msg);
            c->clock.steady = 0;   /* a retune changes the outputs: tick again */
        }
    }
    c->values.valid = 0;   /* a parameter may change: the values image is made again */
    for (i = 0; i < nvr; ++i) {
        if (c->clock.steady != 0 && fmu_model_class(type, vr[i]) == FMU_VAR_INPUT
            && (type == FMU_REAL
                    ? fmu_model_get_real(c->model, vr[i]) != ((const double *)value)[i]
                    : fmu_model_get_integer(c->model, vr[i]) != ((const int *)value)[i]))
            c->clock.steady = 0;   /* a new input (a Real or an Integer one): absorbed again */
        if (type == FMU_REAL)
            fmu_model_set_real(c->model, vr[i], ((const double *)value)[i]);
        else
            fmu_model_set_integer(c->model, vr[i], (int)((const int32_t *)value)[i]);
    }
    return FMU_OK;
}

fmu_status fmu_no_variables(fmu_instance *c, const char *func, const fmu_vr vr[], size_t nvr,
                            const void *value)
{
    if (check_arrays(c, func, vr, nvr, value) != FMU_OK)
        return FMU_ERROR;
    if (nvr > 0)
        return FAIL(c, "%s: unknown value reference %lu (this model has no such variables)",
                    func, (unsigned long)vr[0]);
    return FMU_OK;
}

/* ---------------------------------------------------------------- FMU state */

static void free_snapshot(const fmu_instance *c, fmu_snapshot *s)
{
    if (s == NULL)
        return;
    s->id.magic = 0;
    if (s->mem != NULL)
        c->host.release(s->mem);
    c->host.release(s->model);
    c->host.release(s);
}

static fmu_snapshot *new_snapshot(const fmu_instance *c)
{
    fmu_snapshot *s = (fmu_snapshot *)c->host.alloc(1, sizeof *s);
    if (s == NULL)
        return NULL;
    s->model = c->host.alloc(1, fmu_model_size());
    if (s->model == NULL) {
        c->host.release(s);
        return NULL;
    }
    s->id = identity(FMU_SNAPSHOT_MAGIC);
    return s;
}

/* A state made by this binary (another FMU in the same process has another token address). */
static int is_snapshot(const void *p)
{
    return p != NULL && is_ours(&((const fmu_snapshot *)p)->id, FMU_SNAPSHOT_MAGIC);
}

/* Make *dst (block of *dst_bytes) a block of `bytes` holding src; O(bytes). The old block is
 * replaced only once the new one exists. @return 0, or non-zero when out of memory. */
static int copy_block(const fmu_instance *c, void **dst, size_t *dst_bytes, const void *src,
                      size_t bytes)
{
    if (*dst == NULL || *dst_bytes != bytes) {
        void *block = bytes > 0 ? c->host.alloc(bytes, 1) : NULL;
        if (bytes > 0 && block == NULL)
            return 1;
        if (*dst != NULL)
            c->host.release(*dst);
        *dst = block;
        *dst_bytes = bytes;
    }
    if (bytes > 0)
        memcpy(*dst, src, bytes);
    return 0;
}

fmu_status fmu_get_state(fmu_instance *c, const char *func, void **state)
{
    fmu_snapshot *s;
    int fresh;
    if (state == NULL)
        return FAIL(c, "%s: FMUstate is NULL", func);
    if (*state != NULL && !is_snapshot(*state))
        return FAIL(c, "%s: *FMUstate is neither NULL nor a state of this FMU", func);
    fresh = *state == NULL;
    s = fresh ? new_snapshot(c) : (fmu_snapshot *)*state;
    if (s == NULL || copy_block(c, &s->mem, &s->mem_bytes, c->mem, c->mem_bytes) != 0) {
        if (fresh)
            free_snapshot(c, s);
        return FAIL(c, "%s: out of memory", func);
    }
    s->clock = c->clock;
    memcpy(s->model, c->model, fmu_model_size());
    fmu_model_rebind(s->model, s->mem);   /* the copy describes its own block (serialise reads) */
    *state = s;
    return FMU_OK;
}

fmu_status fmu_set_state(fmu_instance *c, const char *func, void *state)
{
    const fmu_snapshot *s = (const fmu_snapshot *)state;
    if (!is_snapshot(state))
        return FAIL(c, "%s: FMUstate is NULL or not a state of this FMU", func);
    if (copy_block(c, &c->mem, &c->mem_bytes, s->mem, s->mem_bytes) != 0)
        return FAIL(c, "%s: out of memory", func);
    c->clock = s->clock;
    memcpy(c->model, s->model, fmu_model_size());
    fmu_model_rebind(c->model, c->mem);
    c->values.valid = 0;
    return FMU_OK;
}

fmu_status fmu_free_state(fmu_instance *c, const char *func, void **state)
{
    if (state == NULL)
        return FAIL(c, "%s: FMUstate is NULL", func);
    if (*state == NULL)
        return FMU_OK;
    if (!is_snapshot(*state))
        return FAIL(c, "%s: *FMUstate is not a state of this FMU", func);
    free_snapshot(c, (fmu_snapshot *)*state);
    *state = NULL;
    return FMU_OK;
}

fmu_status fmu_state_size(fmu_instance *c, const char *func, void *state, size_t *size)
{
    if (!is_snapshot(state) || size == NULL)
        return FAIL(c, "%s: FMUstate or size is NULL or foreign", func);
    *size = fmu_serialized_size((const fmu_snapshot *)state);
    return FMU_OK;
}

fmu_status fmu_serialize_state(fmu_instance *c, const char *func, void *state,
                               unsigned char *out, size_t size)
{
    size_t need;
    if (!is_snapshot(state) || out == NULL)
        return FAIL(c, "%s: FMUstate or serializedState is NULL or foreign", func);
    need = fmu_serialized_size((const fmu_snapshot *)state);
    if (size != need)
        return FAIL(c, "%s: size %lu differs from the serialized state size %lu", func,
                    (unsigned long)size, (unsigned long)need);
    if (fmu_serialize((const fmu_snapshot *)state, &c->host, out) != 0)
        return FAIL(c, "%s: out of memory", func);
    return FMU_OK;
}

/* The inputs a loaded state holds within the range fmu_set kept them in when they were set (a
 * state of this FMU never holds others; fmu_model_state_input_max()). 1, or 0 with msg. */
static int inputs_in_range(const fmu_snapshot *s, const fmu_values_image *img, char *msg,
                           size_t len)
{
    fmu_vr vrs[1024];
    const double own = fmu_model_state_input_max(s->model);
    const double bound = own < SMS_INPUT_MAX ? own : SMS_INPUT_MAX;
    size_t n, i;
    if (img->valid) {   /* the Real inputs, listed by the image */
        for (i = n = 0; i < img->n_inputs; ++i)
            if (img->input_type[i] == FMU_REAL)
                vrs[n++] = img->input_vr[i];
    } else {
        n = fmu_model_settable(FMU_REAL, vrs, 1024);
    }
    for (i = 0; i < n && i < 1024; ++i) {
        double v;
        if (fmu_model_class(FMU_REAL, vrs[i]) != FMU_VAR_INPUT)
            continue;
        v = fmu_model_get_real(s->model, vrs[i]);
        if (!(fabs(v) <= bound)) {
            char name[96];
            fmu_model_name(FMU_REAL, vrs[i], name, sizeof name);
            snprintf(msg, len, "the state's input %s = %.17g is beyond %.17g, the input range",
                     name, v, bound);
            return 0;
        }
    }
    return 1;
}

fmu_status fmu_deserialize_state(fmu_instance *c, const char *func, const unsigned char *in,
                                 size_t size, void **state)
{
    fmu_snapshot *s;
    char msg[FMU_MESSAGE_LEN];
    if (in == NULL || state == NULL)
        return FAIL(c, "%s: serializedState or FMUstate is NULL", func);
    if (*state != NULL && !is_snapshot(*state))
        return FAIL(c, "%s: *FMUstate is neither NULL nor a state of this FMU", func);
    s = new_snapshot(c);
    if (s == NULL)
        return FAIL(c, "%s: out of memory", func);
    msg[0] = '\0';
    /* the instance's values as a state writes them, once per change of its parameters (if
     * that fails, the state is read value by value) */
    if (!c->values.valid && c->mem != NULL
        && (c->clock.phase == FMU_STEP_COMPLETE || c->clock.phase == FMU_TERMINATED))
        (void)fmu_values_image_make(&c->values, c->model, &c->host);
    if (fmu_deserialize(in, size, s, c, &c->host, msg, sizeof msg) != 0) {
        free_snapshot(c, s);
        return FAIL(c, "%s: %s", func, msg);
    }
    if (s->mem != NULL && !inputs_in_range(s, &c->values, msg, sizeof msg)) {
        free_snapshot(c, s);
        return FAIL(c, "%s: %s", func, msg);
    }
    if (*state != NULL)
        free_snapshot(c, (fmu_snapshot *)*state);
    *state = s;
    return FMU_OK;
}

/* ---------------------------------------------------------------- co-simulation */

/* Run n ticks with the held input: first the model's own hold (fmu_model_hold(): closed forms
 * under a constant input, bit for bit the ticks), then one tick after another for what it
 * leaves. For those, once the outputs have not changed for
 * FMU_STEADY_TICKS(state count) ticks in a row under the same input, the held input is absorbed:
 * every delay line and restart cycle of the filters has been filled with it (their lengths are
 * bounded by the state count) and the state repeats with outputs that no longer change, so the
 * remaining ticks are skipped. A step of any length costs at most that many ticks. */
static void run_ticks(fmu_instance *c, uint64_t n)
{
    uint64_t i, limit = 0;   /* computed once the outputs have held for 16 ticks */
    if (n == 1) {   /* the usual step of h = Ts: one tick, no closed form to set up */
        if (fmu_model_tick(c->model))
            c->clock.steady = 0;
        else
            ++c->clock.steady;
        return;
    }
    i = fmu_model_hold(c->model, n);
    if (i > 0)
        c->clock.steady = 0;
    for (; i < n; ++i) {
        if (c->clock.steady >= 16) {
            if (limit == 0)
                limit = FMU_STEADY_TICKS(fmu_model_state_count(c->model));
            if (c->clock.steady >= limit)
                return;
        }
        if (fmu_model_tick(c->model))
            c->clock.steady = 0;
        else
            ++c->clock.steady;
    }
}

fmu_status fmu_do_step(fmu_instance *c, const char *func, double t, double h)
{
    double Ts, advanced, end, n;
    if (!isfinite(t) || !isfinite(h) || !(h > 0.0))
        return FAIL(c, "%s: currentCommunicationPoint must be finite and communicationStepSize "
                    "finite and > 0 (got %g, %g)", func, t, h);
    end = t + h;
    if (!isfinite(end))
        return FAIL(c, "%s: the step would end beyond the largest double (t = %.17g, h = %.17g)",
                    func, t, h);
    Ts = fmu_model_sample_period(c->model);
    /* Importers compute t + h in their own rounding: accept that, refuse a jump. */
    if (fabs(t - c->clock.time) > FMU_TICK_SLACK * Ts + 1e-9 * fabs(c->clock.time))
        return FAIL(c, "%s: currentCommunicationPoint %.17g is not the end of the last step "
                    "%.17g", func, t, c->clock.time);
    advanced = c->clock.since_tick + h;
    n = floor((advanced + fmu_clock_slack(Ts, c->clock.start_time, end)) / Ts);
    if (n < 0.0)
        n = 0.0;
    if (!((double)c->clock.ticks + n < FMU_MAX_TICK_INDEX))
        return FAIL(c, "%s: the step (h = %g) would end beyond %g ticks", func, h,
                    FMU_MAX_TICK_INDEX);
    {
        /* inputs that are only invalid together (a target's velocity with its acceleration):
         * refused before any tick, the instance unchanged */
        char msg[FMU_MESSAGE_LEN];
        msg[0] = '\0';
        if (fmu_model_check_inputs(c->model, msg, sizeof msg))
            return FAIL(c, "%s at t = %.17g: %s", func, c->clock.time, msg);
    }
    run_ticks(c, (uint64_t)n);
    c->clock.ticks += (uint64_t)n;
    /* The remainder exactly (no drift over long runs): advanced - Ts is exact for one tick
     * (Sterbenz), fma rounds once for many. */
    c->clock.since_tick = n == 1.0 ? advanced - Ts : fma(-n, Ts, advanced);
    c->clock.time = end;
    {
        char msg[FMU_MESSAGE_LEN];
        msg[0] = '\0';
        if (fmu_model_warning(c->model, msg, sizeof msg)) {
            fmu_log(c, FMU_WARNING, FMU_LOG_WARNING, "%s at t = %.17g: %s", func, c->clock.time,
                    msg);
            return FMU_WARNING;
        }
    }
    return FMU_OK;
}
