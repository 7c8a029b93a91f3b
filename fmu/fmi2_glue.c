/* SPDX-License-Identifier: Apache-2.0 */
/*
 * FMI 2.0 Co-Simulation for every smoothshaper model: each fmi2* function checks the instance
 * and the state it is called in (FMI 2.0 section 4.2.4) and calls the interface-neutral glue
 * (fmu_core.h), which implements the state machine, the clock, get/set and the FMU states once
 * for FMI 2.0 and 3.0. What is FMI 2.0's alone lives here: the callbacks (the importer's memory
 * functions; a printf-style logger), fmi2SetupExperiment, the status queries and the Model
 * Exchange entry points, which refuse.
 */
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "fmi2Functions.h"
#include "fmu_core.h"

#define MAGIC FMU_INSTANCE_MAGIC_FMI2
#define ENTER(comp, func, allowed) fmu_enter((comp), MAGIC, (func), (allowed))
#define IN_ANY FMU_IN_ANY
#define IN_GET (FMU_IN_INIT | FMU_IN_STEP | FMU_IN_TERMINATED)
#define IN_SET (FMU_IN_INSTANTIATED | FMU_IN_INIT | FMU_IN_STEP)

/* fmi2Integer and the glue's int32_t are one type on every platform FMI 2.0 binaries exist for;
 * fmi2Status and fmu_status share their values. */
typedef char fmi2_integer_is_int32[(sizeof(fmi2Integer) == sizeof(int32_t)) ? 1 : -1];
typedef char fmi2_status_values_match[(fmi2Error == (int)FMU_ERROR
                                       && fmi2Warning == (int)FMU_WARNING) ? 1 : -1];

/* The logger's message is a printf format, but importers written in other languages print it
 * verbatim: pass the finished text with every '%' doubled, which suits both. */
static void log_fmi2(const fmu_host *host, const char *instance, fmu_status status,
                 const char *category, const char *message)
{
    char escaped[2 * (FMU_MESSAGE_LEN + 128)];
    size_t i, j = 0;
    for (i = 0; message[i] != '\0' && j + 2 < sizeof escaped; ++i) {
        if (message[i] == '%')
            escaped[j++] = '%';
        escaped[j++] = message[i];
    }
    escaped[j] = '\0';
    ((fmi2CallbackLogger)host->logger)(host->environment, instance, (fmi2Status)status, category,
                                       escaped);
}

const char *fmi2GetTypesPlatform(void) { return fmi2TypesPlatform; }
const char *fmi2GetVersion(void) { return fmi2Version; }

fmi2Status fmi2SetDebugLogging(fmi2Component comp, fmi2Boolean loggingOn, size_t nCategories,
                               const fmi2String categories[])
{
    fmu_instance *c = ENTER(comp, "fmi2SetDebugLogging", IN_ANY);
    if (c == NULL)
        return fmi2Error;
    return (fmi2Status)fmu_set_debug_logging(c, "fmi2SetDebugLogging", loggingOn, nCategories,
                                             categories);
}

fmi2Component fmi2Instantiate(fmi2String instanceName, fmi2Type fmuType, fmi2String fmuGUID,
                              fmi2String fmuResourceLocation,
                              const fmi2CallbackFunctions *functions, fmi2Boolean visible,
                              fmi2Boolean loggingOn)
{
    fmu_host host;
    (void)fmuResourceLocation;
    (void)visible;
    if (functions == NULL || functions->allocateMemory == NULL || functions->freeMemory == NULL)
        return NULL;
    host.alloc = functions->allocateMemory;
    host.release = functions->freeMemory;
    host.log = functions->logger != NULL ? log_fmi2 : NULL;
    host.logger = (void (*)(void))functions->logger;
    host.environment = functions->componentEnvironment;
    if (fmuType != fmi2CoSimulation) {
        fmu_log_host(&host, instanceName ? instanceName : "?",
                     "fmi2Instantiate: %s supports Co-Simulation only", fmu_model_identifier());
        return NULL;
    }
    return fmu_instantiate(&host, MAGIC, "fmi2Instantiate", instanceName, fmuGUID,
                           fmu_model_guid(), loggingOn);
}

void fmi2FreeInstance(fmi2Component comp)
{
    fmu_instance *c = ENTER(comp, "fmi2FreeInstance", IN_ANY);
    if (c != NULL)
        fmu_free_instance(c);
}

fmi2Status fmi2SetupExperiment(fmi2Component comp, fmi2Boolean toleranceDefined,
                               fmi2Real tolerance, fmi2Real startTime,
                               fmi2Boolean stopTimeDefined, fmi2Real stopTime)
{
    fmu_instance *c = ENTER(comp, "fmi2SetupExperiment", FMU_IN_INSTANTIATED);
    (void)toleranceDefined;
    (void)tolerance;   /* the filters are exact: there is no solver tolerance to honour */
    if (c == NULL)
        return fmi2Error;
    return (fmi2Status)fmu_setup(c, "fmi2SetupExperiment", startTime, stopTimeDefined, stopTime);
}

fmi2Status fmi2EnterInitializationMode(fmi2Component comp)
{
    fmu_instance *c = ENTER(comp, "fmi2EnterInitializationMode", FMU_IN_INSTANTIATED);
    return c == NULL ? fmi2Error : (fmi2Status)fmu_enter_initialization(c);
}

fmi2Status fmi2ExitInitializationMode(fmi2Component comp)
{
    fmu_instance *c = ENTER(comp, "fmi2ExitInitializationMode", FMU_IN_INIT);
    return c == NULL ? fmi2Error
                     : (fmi2Status)fmu_exit_initialization(c, "fmi2ExitInitializationMode");
}

fmi2Status fmi2Terminate(fmi2Component comp)
{
    fmu_instance *c = ENTER(comp, "fmi2Terminate", FMU_IN_STEP);
    return c == NULL ? fmi2Error : (fmi2Status)fmu_terminate(c);
}

fmi2Status fmi2Reset(fmi2Component comp)
{
    fmu_instance *c = ENTER(comp, "fmi2Reset", IN_ANY);
    return c == NULL ? fmi2Error : (fmi2Status)fmu_reset(c);
}

/* ---------------------------------------------------------------- get / set */

#define GET(func, type) \
    fmu_instance *c = ENTER(comp, func, IN_GET); \
    return c == NULL ? fmi2Error : (fmi2Status)fmu_get(c, func, type, vr, nvr, value)
#define SET(func, type) \
    fmu_instance *c = ENTER(comp, func, IN_SET); \
    return c == NULL ? fmi2Error : (fmi2Status)fmu_set(c, func, type, vr, nvr, value)
/* The models have no Boolean or String variables: any value reference is unknown. */
#define NONE(func, allowed) \
    fmu_instance *c = ENTER(comp, func, allowed); \
    return c == NULL ? fmi2Error : (fmi2Status)fmu_no_variables(c, func, vr, nvr, value)

fmi2Status fmi2GetReal(fmi2Component comp, const fmi2ValueReference vr[], size_t nvr,
                       fmi2Real value[])
{ GET("fmi2GetReal", FMU_REAL); }
fmi2Status fmi2GetInteger(fmi2Component comp, const fmi2ValueReference vr[], size_t nvr,
                          fmi2Integer value[])
{ GET("fmi2GetInteger", FMU_INTEGER); }
fmi2Status fmi2SetReal(fmi2Component comp, const fmi2ValueReference vr[], size_t nvr,
                       const fmi2Real value[])
{ SET("fmi2SetReal", FMU_REAL); }
fmi2Status fmi2SetInteger(fmi2Component comp, const fmi2ValueReference vr[], size_t nvr,
                          const fmi2Integer value[])
{ SET("fmi2SetInteger", FMU_INTEGER); }
fmi2Status fmi2GetBoolean(fmi2Component comp, const fmi2ValueReference vr[], size_t nvr,
                          fmi2Boolean value[])
{ NONE("fmi2GetBoolean", IN_GET); }
fmi2Status fmi2GetString(fmi2Component comp, const fmi2ValueReference vr[], size_t nvr,
                         fmi2String value[])
{ NONE("fmi2GetString", IN_GET); }
fmi2Status fmi2SetBoolean(fmi2Component comp, const fmi2ValueReference vr[], size_t nvr,
                          const fmi2Boolean value[])
{ NONE("fmi2SetBoolean", IN_SET); }
fmi2Status fmi2SetString(fmi2Component comp, const fmi2ValueReference vr[], size_t nvr,
                         const fmi2String value[])
{ NONE("fmi2SetString", IN_SET); }

/* ---------------------------------------------------------------- FMU state */

fmi2Status fmi2GetFMUstate(fmi2Component comp, fmi2FMUstate *FMUstate)
{
    fmu_instance *c = ENTER(comp, "fmi2GetFMUstate", IN_ANY);
    return c == NULL ? fmi2Error : (fmi2Status)fmu_get_state(c, "fmi2GetFMUstate", FMUstate);
}

fmi2Status fmi2SetFMUstate(fmi2Component comp, fmi2FMUstate FMUstate)
{
    fmu_instance *c = ENTER(comp, "fmi2SetFMUstate", IN_ANY);
    return c == NULL ? fmi2Error : (fmi2Status)fmu_set_state(c, "fmi2SetFMUstate", FMUstate);
}

fmi2Status fmi2FreeFMUstate(fmi2Component comp, fmi2FMUstate *FMUstate)
{
    fmu_instance *c = ENTER(comp, "fmi2FreeFMUstate", IN_ANY);
    return c == NULL ? fmi2Error : (fmi2Status)fmu_free_state(c, "fmi2FreeFMUstate", FMUstate);
}

fmi2Status fmi2SerializedFMUstateSize(fmi2Component comp, fmi2FMUstate FMUstate, size_t *size)
{
    fmu_instance *c = ENTER(comp, "fmi2SerializedFMUstateSize", IN_ANY);
    return c == NULL ? fmi2Error
                     : (fmi2Status)fmu_state_size(c, "fmi2SerializedFMUstateSize", FMUstate, size);
}

fmi2Status fmi2SerializeFMUstate(fmi2Component comp, fmi2FMUstate FMUstate,
                                 fmi2Byte serializedState[], size_t size)
{
    fmu_instance *c = ENTER(comp, "fmi2SerializeFMUstate", IN_ANY);
    return c == NULL ? fmi2Error
                     : (fmi2Status)fmu_serialize_state(c, "fmi2SerializeFMUstate", FMUstate,
                                                       (unsigned char *)serializedState, size);
}

fmi2Status fmi2DeSerializeFMUstate(fmi2Component comp, const fmi2Byte serializedState[],
                                   size_t size, fmi2FMUstate *FMUstate)
{
    fmu_instance *c = ENTER(comp, "fmi2DeSerializeFMUstate", IN_ANY);
    return c == NULL ? fmi2Error
                     : (fmi2Status)fmu_deserialize_state(c, "fmi2DeSerializeFMUstate",
                                                         (const unsigned char *)serializedState,
                                                         size, FMUstate);
}

fmi2Status fmi2GetDirectionalDerivative(fmi2Component comp, const fmi2ValueReference vUnknown_ref[],
                                        size_t nUnknown, const fmi2ValueReference vKnown_ref[],
                                        size_t nKnown, const fmi2Real dvKnown[],
                                        fmi2Real dvUnknown[])
{
    fmu_instance *c = ENTER(comp, "fmi2GetDirectionalDerivative", IN_ANY);
    (void)vUnknown_ref; (void)nUnknown; (void)vKnown_ref; (void)nKnown; (void)dvKnown;
    (void)dvUnknown;
    if (c == NULL)
        return fmi2Error;
    return (fmi2Status)fmu_fail(c, "fmi2GetDirectionalDerivative: not provided "
                                "(providesDirectionalDerivative=false)");
}

/* ---------------------------------------------------------------- co-simulation */

fmi2Status fmi2SetRealInputDerivatives(fmi2Component comp, const fmi2ValueReference vr[],
                                       size_t nvr, const fmi2Integer order[],
                                       const fmi2Real value[])
{
    fmu_instance *c = ENTER(comp, "fmi2SetRealInputDerivatives", IN_ANY);
    (void)vr; (void)nvr; (void)order; (void)value;
    if (c == NULL)
        return fmi2Error;
    return (fmi2Status)fmu_fail(c, "fmi2SetRealInputDerivatives: inputs are held over a step "
                                "(canInterpolateInputs=false)");
}

fmi2Status fmi2GetRealOutputDerivatives(fmi2Component comp, const fmi2ValueReference vr[],
                                        size_t nvr, const fmi2Integer order[], fmi2Real value[])
{
    fmu_instance *c = ENTER(comp, "fmi2GetRealOutputDerivatives", IN_ANY);
    (void)vr; (void)nvr; (void)order; (void)value;
    if (c == NULL)
        return fmi2Error;
    return (fmi2Status)fmu_fail(c, "fmi2GetRealOutputDerivatives: not provided "
                                "(maxOutputDerivativeOrder=0)");
}

fmi2Status fmi2DoStep(fmi2Component comp, fmi2Real currentCommunicationPoint,
                      fmi2Real communicationStepSize, fmi2Boolean noSetFMUStatePriorToCurrentPoint)
{
    fmu_instance *c = ENTER(comp, "fmi2DoStep", FMU_IN_STEP);
    (void)noSetFMUStatePriorToCurrentPoint;
    return c == NULL ? fmi2Error
                     : (fmi2Status)fmu_do_step(c, "fmi2DoStep", currentCommunicationPoint,
                                               communicationStepSize);
}

fmi2Status fmi2CancelStep(fmi2Component comp)
{
    fmu_instance *c = ENTER(comp, "fmi2CancelStep", IN_ANY);
    if (c == NULL)
        return fmi2Error;
    return (fmi2Status)fmu_fail(c, "fmi2CancelStep: fmi2DoStep is synchronous, there is no step "
                                "to cancel");
}

#define IN_STATUS (FMU_IN_STEP | FMU_IN_TERMINATED)

fmi2Status fmi2GetStatus(fmi2Component comp, const fmi2StatusKind s, fmi2Status *value)
{
    fmu_instance *c = ENTER(comp, "fmi2GetStatus", IN_STATUS);
    (void)s;
    if (c == NULL)
        return fmi2Error;
    if (value == NULL)
        return (fmi2Status)fmu_fail(c, "fmi2GetStatus: value is NULL");
    return (fmi2Status)fmu_fail(c, "fmi2GetStatus: no asynchronous step is pending (doStep "
                                "never returns fmi2Pending)");
}

fmi2Status fmi2GetRealStatus(fmi2Component comp, const fmi2StatusKind s, fmi2Real *value)
{
    fmu_instance *c = ENTER(comp, "fmi2GetRealStatus", IN_STATUS);
    if (c == NULL)
        return fmi2Error;
    if (value == NULL)
        return (fmi2Status)fmu_fail(c, "fmi2GetRealStatus: value is NULL");
    if (s != fmi2LastSuccessfulTime)
        return (fmi2Status)fmu_fail(c, "fmi2GetRealStatus: only fmi2LastSuccessfulTime is a Real "
                                    "status");
    *value = c->clock.time;
    return fmi2OK;
}

fmi2Status fmi2GetIntegerStatus(fmi2Component comp, const fmi2StatusKind s, fmi2Integer *value)
{
    fmu_instance *c = ENTER(comp, "fmi2GetIntegerStatus", IN_STATUS);
    (void)s;
    if (c == NULL)
        return fmi2Error;
    if (value == NULL)
        return (fmi2Status)fmu_fail(c, "fmi2GetIntegerStatus: value is NULL");
    return (fmi2Status)fmu_fail(c, "fmi2GetIntegerStatus: FMI 2.0 defines no Integer status");
}

fmi2Status fmi2GetBooleanStatus(fmi2Component comp, const fmi2StatusKind s, fmi2Boolean *value)
{
    fmu_instance *c = ENTER(comp, "fmi2GetBooleanStatus", IN_STATUS);
    if (c == NULL)
        return fmi2Error;
    if (value == NULL)
        return (fmi2Status)fmu_fail(c, "fmi2GetBooleanStatus: value is NULL");
    if (s != fmi2Terminated)
        return (fmi2Status)fmu_fail(c, "fmi2GetBooleanStatus: only fmi2Terminated is a Boolean "
                                    "status");
    *value = fmi2False;   /* the model never asks to end the simulation */
    return fmi2OK;
}

fmi2Status fmi2GetStringStatus(fmi2Component comp, const fmi2StatusKind s, fmi2String *value)
{
    fmu_instance *c = ENTER(comp, "fmi2GetStringStatus", IN_STATUS);
    (void)s;
    if (c == NULL)
        return fmi2Error;
    if (value == NULL)
        return (fmi2Status)fmu_fail(c, "fmi2GetStringStatus: value is NULL");
    return (fmi2Status)fmu_fail(c, "fmi2GetStringStatus: no asynchronous step is pending");
}

/* ---------------------------------------------------------------- model exchange */

/* The FMU is Co-Simulation only, so fmi2Instantiate never returns a Model Exchange instance;
 * the Model Exchange entry points exist (some importers resolve every symbol) and refuse. */
#define ME_ONLY(comp, func) \
    do { fmu_instance *c_ = ENTER((comp), func, IN_ANY); \
         if (c_ != NULL) fmu_fail(c_, "%s: Co-Simulation only", func); \
         return fmi2Error; } while (0)

fmi2Status fmi2EnterEventMode(fmi2Component c) { ME_ONLY(c, "fmi2EnterEventMode"); }
fmi2Status fmi2NewDiscreteStates(fmi2Component c, fmi2EventInfo *info)
{ (void)info; ME_ONLY(c, "fmi2NewDiscreteStates"); }
fmi2Status fmi2EnterContinuousTimeMode(fmi2Component c)
{ ME_ONLY(c, "fmi2EnterContinuousTimeMode"); }
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
