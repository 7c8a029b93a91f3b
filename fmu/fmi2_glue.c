/* SPDX-License-Identifier: Apache-2.0 */
/*
 * FMI 2.0 Co-Simulation, implemented once for every smoothshaper model (see fmu_model.h).
 *
 * State machine (FMI 2.0 section 4.2.4, the states that can occur with a synchronous doStep):
 *   instantiated --enterInitializationMode--> initializationMode --exitInitializationMode-->
 *   stepComplete --doStep--> stepComplete --terminate--> terminated; reset from any state goes
 *   back to instantiated with every variable at its start value.
 * A call in a state where FMI 2.0 does not allow it returns fmi2Error with a logged message and
 * changes nothing. Every fmi2Error leaves the instance as it was before the call.
 *
 * Time: internal ticks happen at t0 + n*Ts (n = 1, 2, ... an integer counter, so no drift).
 * fmi2DoStep(t, h) computes every tick in (t, t+h]: the instance counts the ticks done and the
 * time advanced since the last one (fmu_clock), and a step of length h computes
 * floor((since_tick + h)/Ts + 1e-6) ticks. So the tick count follows the step lengths, not the
 * importer's accumulated t: a host doing t += h (whose t drifts from k*h by many ticks over
 * 1e9 steps) gets exactly one tick per step of h = Ts, and a host with exact t = k*h gets the
 * ticks n*Ts <= t+h (a tick up to 1e-6 Ts after t+h counts as inside). Each of those ticks
 * filters the input value set before the call (the input is held over the step). The outputs
 * after the call are those of the last tick computed; a step that contains no tick leaves the
 * outputs unchanged. Before the first tick the outputs are the rest point: the input value at
 * fmi2ExitInitializationMode. A step of many ticks costs a bounded time: the model holds the
 * input over them in closed form where it can (fmu_model_hold()), see run_ticks.
 *
 * Identity: every entry point first checks that the instance (and any FMU state) was made by
 * this binary (same model, same precision); another model's instance gets fmi2Error and is
 * never written to.
 */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "fmu_instance.h"
#include "fmu_serialize.h"
#include "smoothshaper/types.h"

#define TICK_SLACK FMU_TICK_SLACK
#define MAX_TICK_INDEX 4.0e15    /* keeps tick counts exactly representable as doubles */

static const char *const category_names[FMU_LOG_CATEGORIES] = {
    "logStatusError", "logStatusWarning", "logCalls"
};

static void log_message(const fmu_instance *c, fmi2Status status, int category, const char *fmt, ...)
{
    /* a model's message (up to FMU_MESSAGE_LEN) after the call's prefix ("fmi2DoStep at t = ...: ") */
    char buf[FMU_MESSAGE_LEN + 128], escaped[2 * (FMU_MESSAGE_LEN + 128)];
    size_t i, j = 0;
    va_list ap;
    /* Errors and warnings always reach the logger; only the debug categories obey loggingOn
     * and fmi2SetDebugLogging. */
    if (c == NULL || c->cb.logger == NULL || (category >= FMU_LOG_CALLS && !c->log_on[category]))
        return;
    va_start(ap, fmt);
    vsnprintf(buf, sizeof buf, fmt, ap);
    va_end(ap);
    /* The logger's message is a printf format, but importers written in other languages print
     * it verbatim: pass the finished text with every '%' doubled, which suits both. */
    for (i = 0; buf[i] != '\0' && j + 2 < sizeof escaped; ++i) {
        if (buf[i] == '%')
            escaped[j++] = '%';
        escaped[j++] = buf[i];
    }
    escaped[j] = '\0';
    c->cb.logger(c->cb.componentEnvironment, c->name, status, category_names[category], escaped);
}

#define FAIL(c, ...) (log_message((c), fmi2Error, FMU_LOG_ERROR, __VA_ARGS__), fmi2Error)

static const char *const phase_names[] = {
    "instantiated", "initialization mode", "step complete", "terminated"
};

/* One per binary: its address tells this binary's instances and states from any other's. */
static const char glue_token = 0;

/* Made by this binary (so by this model, in this precision). */
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

/* The instance if the pointer is one of ours and its state is in `allowed` (bit mask). */
static fmu_instance *checked(fmi2Component comp, const char *func, unsigned allowed)
{
    fmu_instance *c = (fmu_instance *)comp;
    if (c == NULL || c->id.magic != FMU_INSTANCE_MAGIC)
        return NULL;
    if (!is_ours(&c->id, FMU_INSTANCE_MAGIC)) {
        /* Another smoothshaper model's (or precision's) instance: same glue layout, so its
         * logger can say so; nothing of it is written. */
        log_message(c, fmi2Error, FMU_LOG_ERROR, "%s: instance '%s' belongs to another FMU (not "
                    "%s, %u-byte reals): refused", func, c->name ? c->name : "?",
                    fmu_model_identifier(), fmu_model_real_bytes());
        return NULL;
    }
    if (c->log_on[FMU_LOG_CALLS])
        log_message(c, fmi2OK, FMU_LOG_CALLS, "%s", func);
    if (!(allowed & (1u << c->clock.phase))) {
        log_message(c, fmi2Error, FMU_LOG_ERROR, "%s is not allowed in state '%s'", func,
                    phase_names[c->clock.phase]);
        return NULL;
    }
    return c;
}

#define IN_INSTANTIATED (1u << FMU_INSTANTIATED)
#define IN_INIT (1u << FMU_INITIALIZATION_MODE)
#define IN_STEP (1u << FMU_STEP_COMPLETE)
#define IN_TERMINATED (1u << FMU_TERMINATED)
#define IN_ANY (IN_INSTANTIATED | IN_INIT | IN_STEP | IN_TERMINATED)

static void *alloc_zeroed(const fmu_instance *c, size_t size)
{
    return c->cb.allocateMemory(1, size);
}

/* ---------------------------------------------------------------- common functions */

const char *fmi2GetTypesPlatform(void) { return fmi2TypesPlatform; }
const char *fmi2GetVersion(void) { return fmi2Version; }

fmi2Status fmi2SetDebugLogging(fmi2Component comp, fmi2Boolean loggingOn, size_t nCategories,
                               const fmi2String categories[])
{
    fmu_instance *c = checked(comp, "fmi2SetDebugLogging", IN_ANY);
    int on[FMU_LOG_CATEGORIES];
    size_t i;
    int k;
    if (c == NULL)
        return fmi2Error;
    if (nCategories == 0) {
        for (k = 0; k < FMU_LOG_CATEGORIES; ++k)
            c->log_on[k] = loggingOn ? 1 : 0;
        return fmi2OK;
    }
    if (categories == NULL)
        return FAIL(c, "fmi2SetDebugLogging: categories is NULL but nCategories = %lu",
                    (unsigned long)nCategories);
    memcpy(on, c->log_on, sizeof on);
    for (i = 0; i < nCategories; ++i) {
        int found = 0;
        if (categories[i] == NULL)
            return FAIL(c, "fmi2SetDebugLogging: categories[%lu] is NULL", (unsigned long)i);
        for (k = 0; k < FMU_LOG_CATEGORIES; ++k) {
            if (strcmp(categories[i], category_names[k]) == 0) {
                on[k] = loggingOn ? 1 : 0;
                found = 1;
            }
        }
        if (!found)
            return FAIL(c, "fmi2SetDebugLogging: unknown log category '%s'", categories[i]);
    }
    memcpy(c->log_on, on, sizeof on);
    return fmi2OK;
}

fmi2Component fmi2Instantiate(fmi2String instanceName, fmi2Type fmuType, fmi2String fmuGUID,
                              fmi2String fmuResourceLocation, const fmi2CallbackFunctions *functions,
                              fmi2Boolean visible, fmi2Boolean loggingOn)
{
    fmu_instance probe, *c;
    size_t name_len;
    int k;
    (void)fmuResourceLocation;
    (void)visible;
    if (functions == NULL || functions->allocateMemory == NULL || functions->freeMemory == NULL)
        return NULL;
    /* A stack probe that can log (errors only) before anything is allocated. */
    memset(&probe, 0, sizeof probe);
    probe.cb = *functions;
    probe.name = (char *)(instanceName ? instanceName : "?");
    probe.log_on[FMU_LOG_ERROR] = 1;
    if (instanceName == NULL || instanceName[0] == '\0') {
        log_message(&probe, fmi2Error, FMU_LOG_ERROR, "fmi2Instantiate: instanceName is NULL or empty");
        return NULL;
    }
    if (fmuType != fmi2CoSimulation) {
        log_message(&probe, fmi2Error, FMU_LOG_ERROR,
                    "fmi2Instantiate: %s supports Co-Simulation only", fmu_model_identifier());
        return NULL;
    }
    if (fmuGUID == NULL || strcmp(fmuGUID, fmu_model_guid()) != 0) {
        log_message(&probe, fmi2Error, FMU_LOG_ERROR,
                    "fmi2Instantiate: instantiation token '%s' does not match '%s' of this binary",
                    fmuGUID ? fmuGUID : "(NULL)", fmu_model_guid());
        return NULL;
    }
    c = (fmu_instance *)functions->allocateMemory(1, sizeof *c);
    if (c == NULL)
        return NULL;
    *c = probe;
    name_len = strlen(instanceName);
    c->name = (char *)alloc_zeroed(c, name_len + 1);
    c->model = alloc_zeroed(c, fmu_model_size());
    if (c->name == NULL || c->model == NULL) {
        log_message(&probe, fmi2Error, FMU_LOG_ERROR, "fmi2Instantiate: out of memory");
        if (c->name)
            functions->freeMemory(c->name);
        if (c->model)
            functions->freeMemory(c->model);
        functions->freeMemory(c);
        return NULL;
    }
    memcpy(c->name, instanceName, name_len + 1);
    for (k = 0; k < FMU_LOG_CATEGORIES; ++k)   /* FMI 2.0: loggingOn switches all categories */
        c->log_on[k] = loggingOn ? 1 : 0;
    c->id = identity(FMU_INSTANCE_MAGIC);
    fmu_model_defaults(c->model);
    memset(&c->clock, 0, sizeof c->clock);
    c->clock.phase = FMU_INSTANTIATED;
    return c;
}

/* Free the filters' block (the model is unbuilt afterwards). */
static void release_blocks(fmu_instance *c)
{
    if (c->mem != NULL)
        c->cb.freeMemory(c->mem);
    c->mem = NULL;
    c->mem_bytes = 0;
}

void fmi2FreeInstance(fmi2Component comp)
{
    fmu_instance *c = checked(comp, "fmi2FreeInstance", IN_INSTANTIATED | IN_INIT | IN_STEP
                              | IN_TERMINATED);
    fmi2CallbackFreeMemory release;
    if (c == NULL)
        return;
    release = c->cb.freeMemory;
    release_blocks(c);
    c->id.magic = 0;
    release(c->model);
    release(c->name);
    release(c);
}

fmi2Status fmi2SetupExperiment(fmi2Component comp, fmi2Boolean toleranceDefined, fmi2Real tolerance,
                               fmi2Real startTime, fmi2Boolean stopTimeDefined, fmi2Real stopTime)
{
    fmu_instance *c = checked(comp, "fmi2SetupExperiment", IN_INSTANTIATED);
    (void)toleranceDefined;
    (void)tolerance;   /* the filters are exact: there is no solver tolerance to honour */
    if (c == NULL)
        return fmi2Error;
    if (!isfinite(startTime))
        return FAIL(c, "fmi2SetupExperiment: startTime must be finite");
    if (stopTimeDefined && !(stopTime >= startTime))
        return FAIL(c, "fmi2SetupExperiment: stopTime must be >= startTime");
    c->clock.start_time = startTime;
    c->clock.time = startTime;
    return fmi2OK;
}

fmi2Status fmi2EnterInitializationMode(fmi2Component comp)
{
    fmu_instance *c = checked(comp, "fmi2EnterInitializationMode", IN_INSTANTIATED);
    if (c == NULL)
        return fmi2Error;
    c->clock.phase = FMU_INITIALIZATION_MODE;
    return fmi2OK;
}

fmi2Status fmi2ExitInitializationMode(fmi2Component comp)
{
    fmu_instance *c = checked(comp, "fmi2ExitInitializationMode", IN_INIT);
    char msg[FMU_MESSAGE_LEN];
    int built;
    if (c == NULL)
        return fmi2Error;
    msg[0] = '\0';
    built = fmu_build(&c->cb, c->model, &c->mem, &c->mem_bytes, msg, sizeof msg);
    if (built > 0)
        return FAIL(c, "fmi2ExitInitializationMode: %s", msg);
    c->clock.time = c->clock.start_time;
    c->clock.ticks = 0;
    c->clock.since_tick = 0.0;
    c->clock.steady = 0;
    c->clock.phase = FMU_STEP_COMPLETE;
    if (built < 0) { /* built, with a warning about the parameters */
        log_message(c, fmi2Warning, FMU_LOG_WARNING, "fmi2ExitInitializationMode: %s", msg);
        return fmi2Warning;
    }
    return fmi2OK;
}

fmi2Status fmi2Terminate(fmi2Component comp)
{
    fmu_instance *c = checked(comp, "fmi2Terminate", IN_STEP);
    if (c == NULL)
        return fmi2Error;
    c->clock.phase = FMU_TERMINATED;
    return fmi2OK;
}

fmi2Status fmi2Reset(fmi2Component comp)
{
    fmu_instance *c = checked(comp, "fmi2Reset", IN_ANY);
    if (c == NULL)
        return fmi2Error;
    release_blocks(c);
    memset(c->model, 0, fmu_model_size());
    fmu_model_defaults(c->model);
    memset(&c->clock, 0, sizeof c->clock);
    c->clock.phase = FMU_INSTANTIATED;
    return fmi2OK;
}

/* ---------------------------------------------------------------- get / set */

static fmi2Status check_arrays(fmu_instance *c, const char *func, const fmi2ValueReference vr[],
                               size_t nvr, const void *value)
{
    if (nvr > 0 && (vr == NULL || value == NULL))
        return FAIL(c, "%s: vr or value is NULL with nvr = %lu", func, (unsigned long)nvr);
    return fmi2OK;
}

static fmi2Status get_values(fmi2Component comp, const char *func, fmu_type type,
                             const fmi2ValueReference vr[], size_t nvr, void *value)
{
    fmu_instance *c = checked(comp, func, IN_INIT | IN_STEP | IN_TERMINATED);
    size_t i;
    if (c == NULL || check_arrays(c, func, vr, nvr, value) != fmi2OK)
        return fmi2Error;
    for (i = 0; i < nvr; ++i)   /* check all first: an error writes nothing */
        if (fmu_model_class(type, vr[i]) == FMU_VAR_UNKNOWN)
            return FAIL(c, "%s: unknown value reference %lu", func, (unsigned long)vr[i]);
    for (i = 0; i < nvr; ++i) {
        if (type == FMU_REAL)
            ((fmi2Real *)value)[i] = fmu_model_get_real(c->model, vr[i]);
        else
            ((fmi2Integer *)value)[i] = fmu_model_get_integer(c->model, vr[i]);
    }
    return fmi2OK;
}

/* Largest |input| accepted now: SMS_INPUT_MAX, or the built configuration's own range. */
static double input_max(const fmu_instance *c)
{
    const double own = fmu_model_input_max(c->model);
    return own < SMS_INPUT_MAX ? own : SMS_INPUT_MAX;
}

/* The message for a value set_values refuses (formatted only here, never on the hot path). */
static fmi2Status refuse_value(fmu_instance *c, const char *func, fmu_type type, fmu_var_class cls,
                               fmi2ValueReference vr, const void *value, size_t i)
{
    char name[96];
    fmu_model_name(type, vr, name, sizeof name);
    if (cls == FMU_VAR_OUTPUT)
        return FAIL(c, "%s: %s is an output and cannot be set", func, name);
    if (cls == FMU_VAR_PARAMETER && c->clock.phase == FMU_STEP_COMPLETE)
        return FAIL(c, "%s: %s is a fixed parameter: set it before fmi2ExitInitializationMode",
                    func, name);
    if (cls == FMU_VAR_INPUT && isfinite(((const fmi2Real *)value)[i]))
        return FAIL(c, "%s: %s = %g is beyond %.17g, the input range within which the filters' "
                    "internal sums stay finite (SMS_INPUT_MAX, or less for a configuration with "
                    "a large internal gain)", func, name, ((const fmi2Real *)value)[i],
                    input_max(c));
    return FAIL(c, "%s: %s must be finite, got %g", func, name, ((const fmi2Real *)value)[i]);
}

static fmi2Status set_values(fmi2Component comp, const char *func, fmu_type type,
                             const fmi2ValueReference vr[], size_t nvr, const void *value)
{
    fmu_instance *c = checked(comp, func, IN_INSTANTIATED | IN_INIT | IN_STEP);
    size_t i;
    if (c == NULL || check_arrays(c, func, vr, nvr, value) != fmi2OK)
        return fmi2Error;
    for (i = 0; i < nvr; ++i) {   /* check all first: an error writes nothing */
        fmu_var_class cls = fmu_model_class(type, vr[i]);
        if (cls == FMU_VAR_UNKNOWN)
            return FAIL(c, "%s: unknown value reference %lu", func, (unsigned long)vr[i]);
        if (cls == FMU_VAR_OUTPUT
            || (cls == FMU_VAR_PARAMETER && c->clock.phase == FMU_STEP_COMPLETE)
            || (type == FMU_REAL && !isfinite(((const fmi2Real *)value)[i]))
            || (type == FMU_REAL && cls == FMU_VAR_INPUT
                && fabs(((const fmi2Real *)value)[i]) > input_max(c)))
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
    for (i = 0; i < nvr; ++i) {
        if (c->clock.steady != 0 && fmu_model_class(type, vr[i]) == FMU_VAR_INPUT
            && (type == FMU_REAL
                    ? fmu_model_get_real(c->model, vr[i]) != ((const fmi2Real *)value)[i]
                    : fmu_model_get_integer(c->model, vr[i]) != ((const fmi2Integer *)value)[i]))
            c->clock.steady = 0;   /* a new input: it has to be absorbed again */
        if (type == FMU_REAL)
            fmu_model_set_real(c->model, vr[i], ((const fmi2Real *)value)[i]);
        else
            fmu_model_set_integer(c->model, vr[i], ((const fmi2Integer *)value)[i]);
    }
    return fmi2OK;
}

fmi2Status fmi2GetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2Real value[])
{ return get_values(c, "fmi2GetReal", FMU_REAL, vr, nvr, value); }
fmi2Status fmi2GetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2Integer value[])
{ return get_values(c, "fmi2GetInteger", FMU_INTEGER, vr, nvr, value); }
fmi2Status fmi2SetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2Real value[])
{ return set_values(c, "fmi2SetReal", FMU_REAL, vr, nvr, value); }
fmi2Status fmi2SetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                          const fmi2Integer value[])
{ return set_values(c, "fmi2SetInteger", FMU_INTEGER, vr, nvr, value); }

/* The models have no Boolean or String variables: any value reference is unknown. */
static fmi2Status no_variables(fmi2Component comp, const char *func, unsigned allowed,
                               const fmi2ValueReference vr[], size_t nvr, const void *value)
{
    fmu_instance *c = checked(comp, func, allowed);
    if (c == NULL || check_arrays(c, func, vr, nvr, value) != fmi2OK)
        return fmi2Error;
    if (nvr > 0)
        return FAIL(c, "%s: unknown value reference %lu (this model has no such variables)", func,
                    (unsigned long)vr[0]);
    return fmi2OK;
}

fmi2Status fmi2GetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2Boolean value[])
{ return no_variables(c, "fmi2GetBoolean", IN_INIT | IN_STEP | IN_TERMINATED, vr, nvr, value); }
fmi2Status fmi2GetString(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2String value[])
{ return no_variables(c, "fmi2GetString", IN_INIT | IN_STEP | IN_TERMINATED, vr, nvr, value); }
fmi2Status fmi2SetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                          const fmi2Boolean value[])
{ return no_variables(c, "fmi2SetBoolean", IN_INSTANTIATED | IN_INIT | IN_STEP, vr, nvr, value); }
fmi2Status fmi2SetString(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2String value[])
{ return no_variables(c, "fmi2SetString", IN_INSTANTIATED | IN_INIT | IN_STEP, vr, nvr, value); }

/* ---------------------------------------------------------------- FMU state */

static void free_snapshot(const fmu_instance *c, fmu_snapshot *s)
{
    if (s == NULL)
        return;
    s->id.magic = 0;
    if (s->mem != NULL)
        c->cb.freeMemory(s->mem);
    c->cb.freeMemory(s->model);
    c->cb.freeMemory(s);
}

static fmu_snapshot *new_snapshot(const fmu_instance *c)
{
    fmu_snapshot *s = (fmu_snapshot *)alloc_zeroed(c, sizeof *s);
    if (s == NULL)
        return NULL;
    s->model = alloc_zeroed(c, fmu_model_size());
    if (s->model == NULL) {
        c->cb.freeMemory(s);
        return NULL;
    }
    s->id = identity(FMU_SNAPSHOT_MAGIC);
    return s;
}

/* A state made by this binary (another FMU in the same process has another guid address). */
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
        void *block = bytes > 0 ? c->cb.allocateMemory(bytes, 1) : NULL;
        if (bytes > 0 && block == NULL)
            return 1;
        if (*dst != NULL)
            c->cb.freeMemory(*dst);
        *dst = block;
        *dst_bytes = bytes;
    }
    if (bytes > 0)
        memcpy(*dst, src, bytes);
    return 0;
}

fmi2Status fmi2GetFMUstate(fmi2Component comp, fmi2FMUstate *FMUstate)
{
    fmu_instance *c = checked(comp, "fmi2GetFMUstate", IN_ANY);
    fmu_snapshot *s;
    int fresh;
    if (c == NULL)
        return fmi2Error;
    if (FMUstate == NULL)
        return FAIL(c, "fmi2GetFMUstate: FMUstate is NULL");
    if (*FMUstate != NULL && !is_snapshot(*FMUstate))
        return FAIL(c, "fmi2GetFMUstate: *FMUstate is neither NULL nor a state of this FMU");
    fresh = *FMUstate == NULL;
    s = fresh ? new_snapshot(c) : (fmu_snapshot *)*FMUstate;
    if (s == NULL || copy_block(c, &s->mem, &s->mem_bytes, c->mem, c->mem_bytes) != 0) {
        if (fresh)
            free_snapshot(c, s);
        return FAIL(c, "fmi2GetFMUstate: out of memory");
    }
    s->clock = c->clock;
    memcpy(s->model, c->model, fmu_model_size());
    fmu_model_rebind(s->model, s->mem);   /* the copy describes its own block (serialise reads it) */
    *FMUstate = s;
    return fmi2OK;
}

fmi2Status fmi2SetFMUstate(fmi2Component comp, fmi2FMUstate FMUstate)
{
    fmu_instance *c = checked(comp, "fmi2SetFMUstate", IN_ANY);
    const fmu_snapshot *s = (const fmu_snapshot *)FMUstate;
    if (c == NULL)
        return fmi2Error;
    if (!is_snapshot(FMUstate))
        return FAIL(c, "fmi2SetFMUstate: FMUstate is NULL or not a state of this FMU");
    if (copy_block(c, &c->mem, &c->mem_bytes, s->mem, s->mem_bytes) != 0)
        return FAIL(c, "fmi2SetFMUstate: out of memory");
    c->clock = s->clock;
    memcpy(c->model, s->model, fmu_model_size());
    fmu_model_rebind(c->model, c->mem);
    return fmi2OK;
}

fmi2Status fmi2FreeFMUstate(fmi2Component comp, fmi2FMUstate *FMUstate)
{
    fmu_instance *c = checked(comp, "fmi2FreeFMUstate", IN_ANY);
    if (c == NULL)
        return fmi2Error;
    if (FMUstate == NULL)
        return FAIL(c, "fmi2FreeFMUstate: FMUstate is NULL");
    if (*FMUstate == NULL)
        return fmi2OK;
    if (!is_snapshot(*FMUstate))
        return FAIL(c, "fmi2FreeFMUstate: *FMUstate is not a state of this FMU");
    free_snapshot(c, (fmu_snapshot *)*FMUstate);
    *FMUstate = NULL;
    return fmi2OK;
}

fmi2Status fmi2SerializedFMUstateSize(fmi2Component comp, fmi2FMUstate FMUstate, size_t *size)
{
    fmu_instance *c = checked(comp, "fmi2SerializedFMUstateSize", IN_ANY);
    if (c == NULL)
        return fmi2Error;
    if (!is_snapshot(FMUstate) || size == NULL)
        return FAIL(c, "fmi2SerializedFMUstateSize: FMUstate or size is NULL or foreign");
    *size = fmu_serialized_size((const fmu_snapshot *)FMUstate);
    return fmi2OK;
}

fmi2Status fmi2SerializeFMUstate(fmi2Component comp, fmi2FMUstate FMUstate, fmi2Byte serializedState[],
                                 size_t size)
{
    fmu_instance *c = checked(comp, "fmi2SerializeFMUstate", IN_ANY);
    if (c == NULL)
        return fmi2Error;
    if (!is_snapshot(FMUstate) || serializedState == NULL)
        return FAIL(c, "fmi2SerializeFMUstate: FMUstate or serializedState is NULL or foreign");
    if (size != fmu_serialized_size((const fmu_snapshot *)FMUstate))
        return FAIL(c, "fmi2SerializeFMUstate: size %lu differs from fmi2SerializedFMUstateSize %lu",
                    (unsigned long)size,
                    (unsigned long)fmu_serialized_size((const fmu_snapshot *)FMUstate));
    if (fmu_serialize((const fmu_snapshot *)FMUstate, &c->cb, (unsigned char *)serializedState) != 0)
        return FAIL(c, "fmi2SerializeFMUstate: out of memory");
    return fmi2OK;
}

fmi2Status fmi2DeSerializeFMUstate(fmi2Component comp, const fmi2Byte serializedState[], size_t size,
                                   fmi2FMUstate *FMUstate)
{
    fmu_instance *c = checked(comp, "fmi2DeSerializeFMUstate", IN_ANY);
    fmu_snapshot *s;
    char msg[FMU_MESSAGE_LEN];
    if (c == NULL)
        return fmi2Error;
    if (serializedState == NULL || FMUstate == NULL)
        return FAIL(c, "fmi2DeSerializeFMUstate: serializedState or FMUstate is NULL");
    if (*FMUstate != NULL && !is_snapshot(*FMUstate))
        return FAIL(c, "fmi2DeSerializeFMUstate: *FMUstate is neither NULL nor a state of this FMU");
    s = new_snapshot(c);
    if (s == NULL)
        return FAIL(c, "fmi2DeSerializeFMUstate: out of memory");
    msg[0] = '\0';
    if (fmu_deserialize((const unsigned char *)serializedState, size, s, &c->cb, msg, sizeof msg) != 0) {
        free_snapshot(c, s);
        return FAIL(c, "fmi2DeSerializeFMUstate: %s", msg);
    }
    if (*FMUstate != NULL)
        free_snapshot(c, (fmu_snapshot *)*FMUstate);
    *FMUstate = s;
    return fmi2OK;
}

fmi2Status fmi2GetDirectionalDerivative(fmi2Component comp, const fmi2ValueReference vUnknown_ref[],
                                        size_t nUnknown, const fmi2ValueReference vKnown_ref[],
                                        size_t nKnown, const fmi2Real dvKnown[], fmi2Real dvUnknown[])
{
    fmu_instance *c = checked(comp, "fmi2GetDirectionalDerivative", IN_ANY);
    (void)vUnknown_ref; (void)nUnknown; (void)vKnown_ref; (void)nKnown; (void)dvKnown; (void)dvUnknown;
    if (c == NULL)
        return fmi2Error;
    return FAIL(c, "fmi2GetDirectionalDerivative: not provided (providesDirectionalDerivative=false)");
}

/* ---------------------------------------------------------------- co-simulation */

fmi2Status fmi2SetRealInputDerivatives(fmi2Component comp, const fmi2ValueReference vr[], size_t nvr,
                                       const fmi2Integer order[], const fmi2Real value[])
{
    fmu_instance *c = checked(comp, "fmi2SetRealInputDerivatives", IN_ANY);
    (void)vr; (void)nvr; (void)order; (void)value;
    if (c == NULL)
        return fmi2Error;
    return FAIL(c, "fmi2SetRealInputDerivatives: inputs are held over a step "
                   "(canInterpolateInputs=false)");
}

fmi2Status fmi2GetRealOutputDerivatives(fmi2Component comp, const fmi2ValueReference vr[], size_t nvr,
                                        const fmi2Integer order[], fmi2Real value[])
{
    fmu_instance *c = checked(comp, "fmi2GetRealOutputDerivatives", IN_ANY);
    (void)vr; (void)nvr; (void)order; (void)value;
    if (c == NULL)
        return fmi2Error;
    return FAIL(c, "fmi2GetRealOutputDerivatives: not provided (maxOutputDerivativeOrder=0)");
}

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

fmi2Status fmi2DoStep(fmi2Component comp, fmi2Real currentCommunicationPoint,
                      fmi2Real communicationStepSize, fmi2Boolean noSetFMUStatePriorToCurrentPoint)
{
    fmu_instance *c = checked(comp, "fmi2DoStep", IN_STEP);
    double Ts, advanced, n;
    (void)noSetFMUStatePriorToCurrentPoint;
    if (c == NULL)
        return fmi2Error;
    if (!isfinite(currentCommunicationPoint) || !isfinite(communicationStepSize)
        || !(communicationStepSize > 0.0))
        return FAIL(c, "fmi2DoStep: currentCommunicationPoint must be finite and "
                       "communicationStepSize finite and > 0 (got %g, %g)",
                    currentCommunicationPoint, communicationStepSize);
    if (!isfinite(currentCommunicationPoint + communicationStepSize))
        return FAIL(c, "fmi2DoStep: the step would end beyond the largest double (t = %.17g, "
                       "h = %.17g)", currentCommunicationPoint, communicationStepSize);
    Ts = fmu_model_sample_period(c->model);
    /* Importers compute t + h in their own rounding: accept that, refuse a jump. */
    if (fabs(currentCommunicationPoint - c->clock.time) > TICK_SLACK * Ts + 1e-9 * fabs(c->clock.time))
        return FAIL(c, "fmi2DoStep: currentCommunicationPoint %.17g is not the end of the last "
                       "step %.17g", currentCommunicationPoint, c->clock.time);
    advanced = c->clock.since_tick + communicationStepSize;
    n = floor(advanced / Ts + TICK_SLACK);
    if (n < 0.0)
        n = 0.0;
    if (!((double)c->clock.ticks + n < MAX_TICK_INDEX))
        return FAIL(c, "fmi2DoStep: the step (h = %g) would end beyond %g ticks",
                    communicationStepSize, MAX_TICK_INDEX);
    {
        /* inputs that are only invalid together (a target's velocity with its acceleration):
         * refused before any tick, the instance unchanged */
        char msg[FMU_MESSAGE_LEN];
        msg[0] = '\0';
        if (fmu_model_check_inputs(c->model, msg, sizeof msg))
            return FAIL(c, "fmi2DoStep at t = %.17g: %s", c->clock.time, msg);
    }
    run_ticks(c, (uint64_t)n);
    c->clock.ticks += (uint64_t)n;
    /* The remainder exactly (no drift over long runs): advanced - Ts is exact for one tick
     * (Sterbenz), fma rounds once for many. */
    c->clock.since_tick = n == 1.0 ? advanced - Ts : fma(-n, Ts, advanced);
    c->clock.time = currentCommunicationPoint + communicationStepSize;
    {
        char msg[FMU_MESSAGE_LEN];
        msg[0] = '\0';
        if (fmu_model_warning(c->model, msg, sizeof msg)) {
            log_message(c, fmi2Warning, FMU_LOG_WARNING, "fmi2DoStep at t = %.17g: %s",
                        c->clock.time, msg);
            return fmi2Warning;
        }
    }
    return fmi2OK;
}

fmi2Status fmi2CancelStep(fmi2Component comp)
{
    fmu_instance *c = checked(comp, "fmi2CancelStep", IN_ANY);
    if (c == NULL)
        return fmi2Error;
    return FAIL(c, "fmi2CancelStep: fmi2DoStep is synchronous, there is no step to cancel");
}

fmi2Status fmi2GetStatus(fmi2Component comp, const fmi2StatusKind s, fmi2Status *value)
{
    fmu_instance *c = checked(comp, "fmi2GetStatus", IN_STEP | IN_TERMINATED);
    (void)s;
    if (c == NULL)
        return fmi2Error;
    if (value == NULL)
        return FAIL(c, "fmi2GetStatus: value is NULL");
    return FAIL(c, "fmi2GetStatus: no asynchronous step is pending (doStep never returns fmi2Pending)");
}

fmi2Status fmi2GetRealStatus(fmi2Component comp, const fmi2StatusKind s, fmi2Real *value)
{
    fmu_instance *c = checked(comp, "fmi2GetRealStatus", IN_STEP | IN_TERMINATED);
    if (c == NULL)
        return fmi2Error;
    if (value == NULL)
        return FAIL(c, "fmi2GetRealStatus: value is NULL");
    if (s != fmi2LastSuccessfulTime)
        return FAIL(c, "fmi2GetRealStatus: only fmi2LastSuccessfulTime is a Real status");
    *value = c->clock.time;
    return fmi2OK;
}

fmi2Status fmi2GetIntegerStatus(fmi2Component comp, const fmi2StatusKind s, fmi2Integer *value)
{
    fmu_instance *c = checked(comp, "fmi2GetIntegerStatus", IN_STEP | IN_TERMINATED);
    (void)s;
    if (c == NULL)
        return fmi2Error;
    if (value == NULL)
        return FAIL(c, "fmi2GetIntegerStatus: value is NULL");
    return FAIL(c, "fmi2GetIntegerStatus: FMI 2.0 defines no Integer status");
}

fmi2Status fmi2GetBooleanStatus(fmi2Component comp, const fmi2StatusKind s, fmi2Boolean *value)
{
    fmu_instance *c = checked(comp, "fmi2GetBooleanStatus", IN_STEP | IN_TERMINATED);
    if (c == NULL)
        return fmi2Error;
    if (value == NULL)
        return FAIL(c, "fmi2GetBooleanStatus: value is NULL");
    if (s != fmi2Terminated)
        return FAIL(c, "fmi2GetBooleanStatus: only fmi2Terminated is a Boolean status");
    *value = fmi2False;   /* the model never asks to end the simulation */
    return fmi2OK;
}

fmi2Status fmi2GetStringStatus(fmi2Component comp, const fmi2StatusKind s, fmi2String *value)
{
    fmu_instance *c = checked(comp, "fmi2GetStringStatus", IN_STEP | IN_TERMINATED);
    (void)s;
    if (c == NULL)
        return fmi2Error;
    if (value == NULL)
        return FAIL(c, "fmi2GetStringStatus: value is NULL");
    return FAIL(c, "fmi2GetStringStatus: no asynchronous step is pending");
}

/* ---------------------------------------------------------------- model exchange */

/* The FMU is Co-Simulation only, so fmi2Instantiate never returns a Model Exchange instance;
 * the Model Exchange entry points exist (some importers resolve every symbol) and refuse. */
#define ME_ONLY(c, func) \
    do { fmu_instance *c_ = checked((c), func, IN_ANY); \
         if (c_ != NULL) log_message(c_, fmi2Error, FMU_LOG_ERROR, "%s: Co-Simulation only", func); \
         return fmi2Error; } while (0)

fmi2Status fmi2EnterEventMode(fmi2Component c) { ME_ONLY(c, "fmi2EnterEventMode"); }
fmi2Status fmi2NewDiscreteStates(fmi2Component c, fmi2EventInfo *info)
{ (void)info; ME_ONLY(c, "fmi2NewDiscreteStates"); }
fmi2Status fmi2EnterContinuousTimeMode(fmi2Component c) { ME_ONLY(c, "fmi2EnterContinuousTimeMode"); }
fmi2Status fmi2CompletedIntegratorStep(fmi2Component c, fmi2Boolean noSet, fmi2Boolean *enterEvent,
                                       fmi2Boolean *terminate)
{ (void)noSet; (void)enterEvent; (void)terminate; ME_ONLY(c, "fmi2CompletedIntegratorStep"); }
fmi2Status fmi2SetTime(fmi2Component c, fmi2Real time) { (void)time; ME_ONLY(c, "fmi2SetTime"); }
fmi2Status fmi2SetContinuousStates(fmi2Component c, const fmi2Real x[], size_t nx)
{ (void)x; (void)nx; ME_ONLY(c, "fmi2SetContinuousStates"); }
fmi2Status fmi2GetDerivatives(fmi2Component c, fmi2Real derivatives[], size_t nx)
{ (void)derivatives; (void)nx; ME_ONLY(c, "fmi2GetDerivatives"); }
fmi2Status fmi2GetEventIndicators(fmi2Component c, fmi2Real eventIndicators[], size_t ni)
{ (void)eventIndicators; (void)ni; ME_ONLY(c, "fmi2GetEventIndicators"); }
fmi2Status fmi2GetContinuousStates(fmi2Component c, fmi2Real x[], size_t nx)
{ (void)x; (void)nx; ME_ONLY(c, "fmi2GetContinuousStates"); }
fmi2Status fmi2GetNominalsOfContinuousStates(fmi2Component c, fmi2Real x_nominal[], size_t nx)
{ (void)x_nominal; (void)nx; ME_ONLY(c, "fmi2GetNominalsOfContinuousStates"); }
