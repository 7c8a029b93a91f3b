/* SPDX-License-Identifier: Apache-2.0 */
/*
 * FMI 3.0 Co-Simulation for every smoothshaper model, over the same interface-neutral glue as
 * FMI 2.0 (fmu_core.h). What is FMI 3.0's alone lives here:
 * - the callbacks: a logger of finished text, no memory functions (calloc and free serve);
 * - array variables: an array's value reference is that of its first element, and its
 *   elements' value references follow one by one (modelDescription/generate.py; the model file
 *   knows only the elements), so a call's value references expand to the elements before the
 *   core sees them, and nValues must be the number of values they hold;
 * - the independent variable time (read only: the communication point reached);
 * - the base types: Float64 (the FMI 2.0 Reals) and Int32 (the Integer codes); every other type
 *   has no variables;
 * - the call rules of FMI 3.0 section 4.2.1 for an FMU without event mode, clocks,
 *   structural parameters or intermediate update: those calls, the derivatives and the Model
 *   Exchange and Scheduled Execution entry points refuse with a logged message.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fmi3Functions.h"
#include "fmu_core.h"
#include "fmu_fmi3_variables.h"

#define MAGIC FMU_INSTANCE_MAGIC_FMI3
#define ENTER(comp, func, allowed) fmu_enter((comp), MAGIC, (func), (allowed))
#define IN_ANY FMU_IN_ANY
/* FMI 3.0 lets every state read values (the Reference FMUs' masks); values are written before
 * termination only. */
#define IN_GET FMU_IN_ANY
#define IN_SET (FMU_IN_INSTANTIATED | FMU_IN_INIT | FMU_IN_STEP)

typedef char fmi3_status_values_match[(fmi3Error == (int)FMU_ERROR
                                       && fmi3Warning == (int)FMU_WARNING) ? 1 : -1];

/* The array variables (first element's value reference, element count); the table holds one
 * unused entry when the model has none. */
typedef struct fmi3_array { fmu_vr vr; uint32_t n; } fmi3_array;
static const fmi3_array arrays[] = FMU_FMI3_ARRAYS;

/* Values held by FMI 3.0 variable vr: the element count of an array, 1 for a scalar, 0 for the
 * value reference of an array's later element (not an FMI 3.0 variable). */
static size_t values_of(fmu_vr vr)
{
    size_t i;
    for (i = 0; i < sizeof arrays / sizeof arrays[0]; ++i)   /* (the unused entry matches none) */
        if (vr >= arrays[i].vr && vr - arrays[i].vr < arrays[i].n)
            return vr == arrays[i].vr ? arrays[i].n : 0;
    return 1;
}

static void log_fmi3(const fmu_host *host, const char *instance, fmu_status status,
                     const char *category, const char *message)
{
    (void)instance;   /* FMI 3.0's logger takes no instance name */
    ((fmi3LogMessageCallback)host->logger)(host->environment, (fmi3Status)status, category,
                                           message);
}

/* calloc and free as the importer's memory functions (FMI 3.0 gives none). */
static void *alloc3(size_t count, size_t size) { return calloc(count, size); }
static void release3(void *p) { free(p); }

/* ---------------------------------------------------------------- get / set */

/* Expanded value references of a call on up to this many values stay on the stack. */
#define STACK_VALUES 64

/*
 * The element value references of vr[0..nvr-1] into *out (buf, or memory from the host when
 * they are more than STACK_VALUES), after checking that every value reference is an FMI 3.0
 * variable and that they hold nValues values. Returns FMU_OK, else an error logged.
 */
static fmu_status expand(fmu_instance *c, const char *func, const fmi3ValueReference vr[],
                         size_t nvr, const void *values, size_t nValues, fmu_vr *buf,
                         const fmu_vr **out, fmu_vr **owned, size_t *total)
{
    size_t i, n = 0, k;
    fmu_vr *elements;
    *out = vr;
    *owned = NULL;
    *total = nvr;
    if (nvr > 0 && (vr == NULL || values == NULL))
        return fmu_fail(c, "%s: valueReferences or values is NULL with nValueReferences = %lu",
                        func, (unsigned long)nvr);
#if FMU_FMI3_ARRAY_COUNT == 0   /* no arrays: every value reference holds one value */
    (void)buf; (void)elements; (void)i; (void)n; (void)k;
    if (nvr != nValues)
        return fmu_fail(c, "%s: nValues = %lu, but the %lu variables hold %lu values", func,
                        (unsigned long)nValues, (unsigned long)nvr, (unsigned long)nvr);
    return FMU_OK;
#endif
    for (i = 0; i < nvr; ++i) {
        size_t e = values_of(vr[i]);
        if (e == 0)
            return fmu_fail(c, "%s: value reference %lu is an element of an array variable, "
                            "not an FMI 3.0 variable (the array's value reference is its "
                            "first element's)", func, (unsigned long)vr[i]);
        n += e;
    }
    if (n != nValues)
        return fmu_fail(c, "%s: nValues = %lu, but the %lu variables hold %lu values", func,
                        (unsigned long)nValues, (unsigned long)nvr, (unsigned long)n);
    if (n == nvr)   /* scalars only: the value references are the elements */
        return FMU_OK;
    elements = n <= STACK_VALUES ? buf : (fmu_vr *)c->host.alloc(n, sizeof(fmu_vr));
    if (elements == NULL)
        return fmu_fail(c, "%s: out of memory", func);
    for (i = 0, k = 0; i < nvr; ++i) {
        size_t e = values_of(vr[i]), j;
        for (j = 0; j < e; ++j)
            elements[k++] = vr[i] + (fmu_vr)j;
    }
    if (elements != buf)
        *owned = elements;
    *out = elements;
    *total = n;
    return FMU_OK;
}

static fmi3Status get_or_set(fmi3Instance instance, const char *func, int set, fmu_type type,
                             const fmi3ValueReference vr[], size_t nvr, void *values,
                             size_t nValues)
{
    fmu_instance *c = ENTER(instance, func, set ? IN_SET : IN_GET);
    fmu_vr buf[STACK_VALUES], *owned;
    const fmu_vr *elements;
    size_t n;
    fmu_status st;
    if (c == NULL)
        return fmi3Error;
    if (expand(c, func, vr, nvr, values, nValues, buf, &elements, &owned, &n) != FMU_OK)
        return fmi3Error;
    st = set ? fmu_set(c, func, type, elements, n, values)
             : fmu_get(c, func, type, elements, n, values);
    if (owned != NULL)
        c->host.release(owned);
    return (fmi3Status)st;
}

/* A base type the models have no variables of: any value reference is unknown. */
static fmi3Status none(fmi3Instance instance, const char *func, int set,
                       const fmi3ValueReference vr[], size_t nvr, const void *values)
{
    fmu_instance *c = ENTER(instance, func, set ? IN_SET : IN_GET);
    return c == NULL ? fmi3Error : (fmi3Status)fmu_no_variables(c, func, vr, nvr, values);
}

fmi3Status fmi3GetFloat64(fmi3Instance instance, const fmi3ValueReference vr[], size_t nvr,
                          fmi3Float64 values[], size_t nValues)
{ return get_or_set(instance, "fmi3GetFloat64", 0, FMU_REAL, vr, nvr, values, nValues); }
fmi3Status fmi3SetFloat64(fmi3Instance instance, const fmi3ValueReference vr[], size_t nvr,
                          const fmi3Float64 values[], size_t nValues)
{ return get_or_set(instance, "fmi3SetFloat64", 1, FMU_REAL, vr, nvr, (void *)values, nValues); }
fmi3Status fmi3GetInt32(fmi3Instance instance, const fmi3ValueReference vr[], size_t nvr,
                        fmi3Int32 values[], size_t nValues)
{ return get_or_set(instance, "fmi3GetInt32", 0, FMU_INTEGER, vr, nvr, values, nValues); }
fmi3Status fmi3SetInt32(fmi3Instance instance, const fmi3ValueReference vr[], size_t nvr,
                        const fmi3Int32 values[], size_t nValues)
{ return get_or_set(instance, "fmi3SetInt32", 1, FMU_INTEGER, vr, nvr, (void *)values, nValues); }

#define NONE_GET(name, type) \
    fmi3Status name(fmi3Instance instance, const fmi3ValueReference vr[], size_t nvr, \
                    type values[], size_t nValues) \
    { (void)nValues; return none(instance, #name, 0, vr, nvr, values); }
#define NONE_SET(name, type) \
    fmi3Status name(fmi3Instance instance, const fmi3ValueReference vr[], size_t nvr, \
                    const type values[], size_t nValues) \
    { (void)nValues; return none(instance, #name, 1, vr, nvr, values); }

NONE_GET(fmi3GetFloat32, fmi3Float32)
NONE_GET(fmi3GetInt8, fmi3Int8)
NONE_GET(fmi3GetUInt8, fmi3UInt8)
NONE_GET(fmi3GetInt16, fmi3Int16)
NONE_GET(fmi3GetUInt16, fmi3UInt16)
NONE_GET(fmi3GetUInt32, fmi3UInt32)
NONE_GET(fmi3GetInt64, fmi3Int64)
NONE_GET(fmi3GetUInt64, fmi3UInt64)
NONE_GET(fmi3GetBoolean, fmi3Boolean)
NONE_GET(fmi3GetString, fmi3String)
NONE_SET(fmi3SetFloat32, fmi3Float32)
NONE_SET(fmi3SetInt8, fmi3Int8)
NONE_SET(fmi3SetUInt8, fmi3UInt8)
NONE_SET(fmi3SetInt16, fmi3Int16)
NONE_SET(fmi3SetUInt16, fmi3UInt16)
NONE_SET(fmi3SetUInt32, fmi3UInt32)
NONE_SET(fmi3SetInt64, fmi3Int64)
NONE_SET(fmi3SetUInt64, fmi3UInt64)
NONE_SET(fmi3SetBoolean, fmi3Boolean)
NONE_SET(fmi3SetString, fmi3String)

fmi3Status fmi3GetBinary(fmi3Instance instance, const fmi3ValueReference vr[], size_t nvr,
                         size_t valueSizes[], fmi3Binary values[], size_t nValues)
{
    (void)valueSizes; (void)nValues;
    return none(instance, "fmi3GetBinary", 0, vr, nvr, values);
}

fmi3Status fmi3SetBinary(fmi3Instance instance, const fmi3ValueReference vr[], size_t nvr,
                         const size_t valueSizes[], const fmi3Binary values[], size_t nValues)
{
    (void)valueSizes; (void)nValues;
    return none(instance, "fmi3SetBinary", 1, vr, nvr, values);
}

/* No clocks: any clock value reference is unknown. */
fmi3Status fmi3GetClock(fmi3Instance instance, const fmi3ValueReference vr[], size_t nvr,
                        fmi3Clock values[])
{ return none(instance, "fmi3GetClock", 0, vr, nvr, values); }
fmi3Status fmi3SetClock(fmi3Instance instance, const fmi3ValueReference vr[], size_t nvr,
                        const fmi3Clock values[])
{ return none(instance, "fmi3SetClock", 1, vr, nvr, values); }

/* ---------------------------------------------------------------- life cycle */

const char *fmi3GetVersion(void) { return fmi3Version; }

fmi3Status fmi3SetDebugLogging(fmi3Instance instance, fmi3Boolean loggingOn, size_t nCategories,
                               const fmi3String categories[])
{
    fmu_instance *c = ENTER(instance, "fmi3SetDebugLogging", IN_ANY);
    return c == NULL ? fmi3Error
                     : (fmi3Status)fmu_set_debug_logging(c, "fmi3SetDebugLogging", loggingOn,
                                                         nCategories, categories);
}

fmi3Instance fmi3InstantiateCoSimulation(fmi3String instanceName, fmi3String instantiationToken,
                                         fmi3String resourcePath, fmi3Boolean visible,
                                         fmi3Boolean loggingOn, fmi3Boolean eventModeUsed,
                                         fmi3Boolean earlyReturnAllowed,
                                         const fmi3ValueReference requiredIntermediateVariables[],
                                         size_t nRequiredIntermediateVariables,
                                         fmi3InstanceEnvironment instanceEnvironment,
                                         fmi3LogMessageCallback logMessage,
                                         fmi3IntermediateUpdateCallback intermediateUpdate)
{
    fmu_host host;
    fmu_instance *c;
    const char *name = instanceName ? instanceName : "?";
    (void)resourcePath; (void)visible; (void)earlyReturnAllowed; (void)intermediateUpdate;
    (void)requiredIntermediateVariables;
    host.alloc = alloc3;
    host.release = release3;
    host.log = logMessage != NULL ? log_fmi3 : NULL;
    host.logger = (void (*)(void))logMessage;
    host.environment = instanceEnvironment;
    if (eventModeUsed) {   /* hasEventMode = false: the FMU never needs event handling */
        fmu_log_host(&host, name, "fmi3InstantiateCoSimulation: %s has no event mode "
                     "(hasEventMode = false): instantiate with eventModeUsed = false",
                     fmu_model_identifier());
        return NULL;
    }
    if (nRequiredIntermediateVariables > 0) {
        fmu_log_host(&host, name, "fmi3InstantiateCoSimulation: %s provides no intermediate "
                     "update (providesIntermediateUpdate = false), %lu variables were required",
                     fmu_model_identifier(), (unsigned long)nRequiredIntermediateVariables);
        return NULL;
    }
    c = fmu_instantiate(&host, MAGIC, "fmi3InstantiateCoSimulation", instanceName,
                        instantiationToken, FMU_FMI3_TOKEN, loggingOn);
    if (c != NULL) {
        c->has_time = 1;
        c->time_vr = FMU_FMI3_TIME_VR;
    }
    return c;
}

fmi3Instance fmi3InstantiateModelExchange(fmi3String instanceName, fmi3String instantiationToken,
                                          fmi3String resourcePath, fmi3Boolean visible,
                                          fmi3Boolean loggingOn,
                                          fmi3InstanceEnvironment instanceEnvironment,
                                          fmi3LogMessageCallback logMessage)
{
    fmu_host host;
    (void)instantiationToken; (void)resourcePath; (void)visible; (void)loggingOn;
    host.alloc = alloc3;
    host.release = release3;
    host.log = logMessage != NULL ? log_fmi3 : NULL;
    host.logger = (void (*)(void))logMessage;
    host.environment = instanceEnvironment;
    fmu_log_host(&host, instanceName ? instanceName : "?", "fmi3InstantiateModelExchange: %s "
                 "supports Co-Simulation only", fmu_model_identifier());
    return NULL;
}

fmi3Instance fmi3InstantiateScheduledExecution(fmi3String instanceName,
                                               fmi3String instantiationToken,
                                               fmi3String resourcePath, fmi3Boolean visible,
                                               fmi3Boolean loggingOn,
                                               fmi3InstanceEnvironment instanceEnvironment,
                                               fmi3LogMessageCallback logMessage,
                                               fmi3ClockUpdateCallback clockUpdate,
                                               fmi3LockPreemptionCallback lockPreemption,
                                               fmi3UnlockPreemptionCallback unlockPreemption)
{
    fmu_host host;
    (void)instantiationToken; (void)resourcePath; (void)visible; (void)loggingOn;
    (void)clockUpdate; (void)lockPreemption; (void)unlockPreemption;
    host.alloc = alloc3;
    host.release = release3;
    host.log = logMessage != NULL ? log_fmi3 : NULL;
    host.logger = (void (*)(void))logMessage;
    host.environment = instanceEnvironment;
    fmu_log_host(&host, instanceName ? instanceName : "?", "fmi3InstantiateScheduledExecution: "
                 "%s supports Co-Simulation only", fmu_model_identifier());
    return NULL;
}

void fmi3FreeInstance(fmi3Instance instance)
{
    fmu_instance *c = ENTER(instance, "fmi3FreeInstance", IN_ANY);
    if (c != NULL)
        fmu_free_instance(c);
}

fmi3Status fmi3EnterInitializationMode(fmi3Instance instance, fmi3Boolean toleranceDefined,
                                       fmi3Float64 tolerance, fmi3Float64 startTime,
                                       fmi3Boolean stopTimeDefined, fmi3Float64 stopTime)
{
    fmu_instance *c = ENTER(instance, "fmi3EnterInitializationMode", FMU_IN_INSTANTIATED);
    (void)toleranceDefined;
    (void)tolerance;   /* the filters are exact: there is no solver tolerance to honour */
    if (c == NULL)
        return fmi3Error;
    if (fmu_setup(c, "fmi3EnterInitializationMode", startTime, stopTimeDefined, stopTime)
        != FMU_OK)
        return fmi3Error;
    return (fmi3Status)fmu_enter_initialization(c);
}

fmi3Status fmi3ExitInitializationMode(fmi3Instance instance)
{
    fmu_instance *c = ENTER(instance, "fmi3ExitInitializationMode", FMU_IN_INIT);
    return c == NULL ? fmi3Error
                     : (fmi3Status)fmu_exit_initialization(c, "fmi3ExitInitializationMode");
}

fmi3Status fmi3Terminate(fmi3Instance instance)
{
    fmu_instance *c = ENTER(instance, "fmi3Terminate", FMU_IN_STEP);
    return c == NULL ? fmi3Error : (fmi3Status)fmu_terminate(c);
}

fmi3Status fmi3Reset(fmi3Instance instance)
{
    fmu_instance *c = ENTER(instance, "fmi3Reset", IN_ANY);
    return c == NULL ? fmi3Error : (fmi3Status)fmu_reset(c);
}

/* ---------------------------------------------------------------- FMU state */

fmi3Status fmi3GetFMUState(fmi3Instance instance, fmi3FMUState *FMUState)
{
    fmu_instance *c = ENTER(instance, "fmi3GetFMUState", IN_ANY);
    return c == NULL ? fmi3Error : (fmi3Status)fmu_get_state(c, "fmi3GetFMUState", FMUState);
}

fmi3Status fmi3SetFMUState(fmi3Instance instance, fmi3FMUState FMUState)
{
    fmu_instance *c = ENTER(instance, "fmi3SetFMUState", IN_ANY);
    return c == NULL ? fmi3Error : (fmi3Status)fmu_set_state(c, "fmi3SetFMUState", FMUState);
}

fmi3Status fmi3FreeFMUState(fmi3Instance instance, fmi3FMUState *FMUState)
{
    fmu_instance *c = ENTER(instance, "fmi3FreeFMUState", IN_ANY);
    return c == NULL ? fmi3Error : (fmi3Status)fmu_free_state(c, "fmi3FreeFMUState", FMUState);
}

fmi3Status fmi3SerializedFMUStateSize(fmi3Instance instance, fmi3FMUState FMUState, size_t *size)
{
    fmu_instance *c = ENTER(instance, "fmi3SerializedFMUStateSize", IN_ANY);
    return c == NULL ? fmi3Error
                     : (fmi3Status)fmu_state_size(c, "fmi3SerializedFMUStateSize", FMUState, size);
}

fmi3Status fmi3SerializeFMUState(fmi3Instance instance, fmi3FMUState FMUState,
                                 fmi3Byte serializedState[], size_t size)
{
    fmu_instance *c = ENTER(instance, "fmi3SerializeFMUState", IN_ANY);
    return c == NULL ? fmi3Error
                     : (fmi3Status)fmu_serialize_state(c, "fmi3SerializeFMUState", FMUState,
                                                       serializedState, size);
}

fmi3Status fmi3DeserializeFMUState(fmi3Instance instance, const fmi3Byte serializedState[],
                                   size_t size, fmi3FMUState *FMUState)
{
    fmu_instance *c = ENTER(instance, "fmi3DeserializeFMUState", IN_ANY);
    return c == NULL ? fmi3Error
                     : (fmi3Status)fmu_deserialize_state(c, "fmi3DeserializeFMUState",
                                                         serializedState, size, FMUState);
}

/* ---------------------------------------------------------------- co-simulation */

fmi3Status fmi3DoStep(fmi3Instance instance, fmi3Float64 currentCommunicationPoint,
                      fmi3Float64 communicationStepSize,
                      fmi3Boolean noSetFMUStatePriorToCurrentPoint,
                      fmi3Boolean *eventHandlingNeeded, fmi3Boolean *terminateSimulation,
                      fmi3Boolean *earlyReturn, fmi3Float64 *lastSuccessfulTime)
{
    fmu_instance *c = ENTER(instance, "fmi3DoStep", FMU_IN_STEP);
    fmu_status st;
    (void)noSetFMUStatePriorToCurrentPoint;
    if (c == NULL)
        return fmi3Error;
    if (eventHandlingNeeded == NULL || terminateSimulation == NULL || earlyReturn == NULL
        || lastSuccessfulTime == NULL)
        return (fmi3Status)fmu_fail(c, "fmi3DoStep: eventHandlingNeeded, terminateSimulation, "
                                    "earlyReturn or lastSuccessfulTime is NULL");
    st = fmu_do_step(c, "fmi3DoStep", currentCommunicationPoint, communicationStepSize);
    if (st != FMU_ERROR) {
        *eventHandlingNeeded = fmi3False;
        *terminateSimulation = fmi3False;
        *earlyReturn = fmi3False;
        *lastSuccessfulTime = c->clock.time;
    }
    return (fmi3Status)st;
}

/* Calls for what the FMU does not have: each refuses, naming why. */
#define REFUSE(instance, func, why) \
    do { fmu_instance *c_ = ENTER((instance), func, IN_ANY); \
         if (c_ != NULL) fmu_fail(c_, "%s: %s", func, why); \
         return fmi3Error; } while (0)

#define NO_EVENTS "the FMU has no event mode (hasEventMode = false)"
#define NO_CLOCKS "the FMU has no clocks"
#define CS_ONLY "Co-Simulation only"

fmi3Status fmi3EnterEventMode(fmi3Instance instance)
{ REFUSE(instance, "fmi3EnterEventMode", NO_EVENTS); }
fmi3Status fmi3EnterStepMode(fmi3Instance instance)
{ REFUSE(instance, "fmi3EnterStepMode", NO_EVENTS); }
fmi3Status fmi3EvaluateDiscreteStates(fmi3Instance instance)
{ REFUSE(instance, "fmi3EvaluateDiscreteStates", NO_EVENTS); }
fmi3Status fmi3UpdateDiscreteStates(fmi3Instance instance, fmi3Boolean *discreteStatesNeedUpdate,
                                    fmi3Boolean *terminateSimulation,
                                    fmi3Boolean *nominalsOfContinuousStatesChanged,
                                    fmi3Boolean *valuesOfContinuousStatesChanged,
                                    fmi3Boolean *nextEventTimeDefined, fmi3Float64 *nextEventTime)
{
    (void)discreteStatesNeedUpdate; (void)terminateSimulation;
    (void)nominalsOfContinuousStatesChanged; (void)valuesOfContinuousStatesChanged;
    (void)nextEventTimeDefined; (void)nextEventTime;
    REFUSE(instance, "fmi3UpdateDiscreteStates", NO_EVENTS);
}
fmi3Status fmi3EnterConfigurationMode(fmi3Instance instance)
{ REFUSE(instance, "fmi3EnterConfigurationMode", "the FMU has no structural parameters"); }
fmi3Status fmi3ExitConfigurationMode(fmi3Instance instance)
{ REFUSE(instance, "fmi3ExitConfigurationMode", "the FMU has no structural parameters"); }

fmi3Status fmi3GetNumberOfVariableDependencies(fmi3Instance instance,
                                               fmi3ValueReference valueReference,
                                               size_t *nDependencies)
{
    (void)valueReference; (void)nDependencies;
    REFUSE(instance, "fmi3GetNumberOfVariableDependencies", "not provided (the dependencies "
           "are in modelDescription.xml: no output depends on an input within a step)");
}
fmi3Status fmi3GetVariableDependencies(fmi3Instance instance, fmi3ValueReference dependent,
                                       size_t elementIndicesOfDependent[],
                                       fmi3ValueReference independents[],
                                       size_t elementIndicesOfIndependents[],
                                       fmi3DependencyKind dependencyKinds[], size_t nDependencies)
{
    (void)dependent; (void)elementIndicesOfDependent; (void)independents;
    (void)elementIndicesOfIndependents; (void)dependencyKinds; (void)nDependencies;
    REFUSE(instance, "fmi3GetVariableDependencies", "not provided (the dependencies are in "
           "modelDescription.xml)");
}

fmi3Status fmi3GetDirectionalDerivative(fmi3Instance instance, const fmi3ValueReference unknowns[],
                                        size_t nUnknowns, const fmi3ValueReference knowns[],
                                        size_t nKnowns, const fmi3Float64 seed[], size_t nSeed,
                                        fmi3Float64 sensitivity[], size_t nSensitivity)
{
    (void)unknowns; (void)nUnknowns; (void)knowns; (void)nKnowns; (void)seed; (void)nSeed;
    (void)sensitivity; (void)nSensitivity;
    REFUSE(instance, "fmi3GetDirectionalDerivative", "not provided "
           "(providesDirectionalDerivatives = false)");
}
fmi3Status fmi3GetAdjointDerivative(fmi3Instance instance, const fmi3ValueReference unknowns[],
                                    size_t nUnknowns, const fmi3ValueReference knowns[],
                                    size_t nKnowns, const fmi3Float64 seed[], size_t nSeed,
                                    fmi3Float64 sensitivity[], size_t nSensitivity)
{
    (void)unknowns; (void)nUnknowns; (void)knowns; (void)nKnowns; (void)seed; (void)nSeed;
    (void)sensitivity; (void)nSensitivity;
    REFUSE(instance, "fmi3GetAdjointDerivative", "not provided "
           "(providesAdjointDerivatives = false)");
}
fmi3Status fmi3GetOutputDerivatives(fmi3Instance instance, const fmi3ValueReference vr[],
                                    size_t nvr, const fmi3Int32 orders[], fmi3Float64 values[],
                                    size_t nValues)
{
    (void)vr; (void)nvr; (void)orders; (void)values; (void)nValues;
    REFUSE(instance, "fmi3GetOutputDerivatives", "not provided (maxOutputDerivativeOrder = 0)");
}

fmi3Status fmi3GetIntervalDecimal(fmi3Instance instance, const fmi3ValueReference vr[],
                                  size_t nvr, fmi3Float64 intervals[],
                                  fmi3IntervalQualifier qualifiers[])
{ (void)vr; (void)nvr; (void)intervals; (void)qualifiers;
  REFUSE(instance, "fmi3GetIntervalDecimal", NO_CLOCKS); }
fmi3Status fmi3GetIntervalFraction(fmi3Instance instance, const fmi3ValueReference vr[],
                                   size_t nvr, fmi3UInt64 counters[], fmi3UInt64 resolutions[],
                                   fmi3IntervalQualifier qualifiers[])
{ (void)vr; (void)nvr; (void)counters; (void)resolutions; (void)qualifiers;
  REFUSE(instance, "fmi3GetIntervalFraction", NO_CLOCKS); }
fmi3Status fmi3GetShiftDecimal(fmi3Instance instance, const fmi3ValueReference vr[], size_t nvr,
                               fmi3Float64 shifts[])
{ (void)vr; (void)nvr; (void)shifts; REFUSE(instance, "fmi3GetShiftDecimal", NO_CLOCKS); }
fmi3Status fmi3GetShiftFraction(fmi3Instance instance, const fmi3ValueReference vr[], size_t nvr,
                                fmi3UInt64 counters[], fmi3UInt64 resolutions[])
{ (void)vr; (void)nvr; (void)counters; (void)resolutions;
  REFUSE(instance, "fmi3GetShiftFraction", NO_CLOCKS); }
fmi3Status fmi3SetIntervalDecimal(fmi3Instance instance, const fmi3ValueReference vr[],
                                  size_t nvr, const fmi3Float64 intervals[])
{ (void)vr; (void)nvr; (void)intervals; REFUSE(instance, "fmi3SetIntervalDecimal", NO_CLOCKS); }
fmi3Status fmi3SetIntervalFraction(fmi3Instance instance, const fmi3ValueReference vr[],
                                   size_t nvr, const fmi3UInt64 counters[],
                                   const fmi3UInt64 resolutions[])
{ (void)vr; (void)nvr; (void)counters; (void)resolutions;
  REFUSE(instance, "fmi3SetIntervalFraction", NO_CLOCKS); }
fmi3Status fmi3SetShiftDecimal(fmi3Instance instance, const fmi3ValueReference vr[], size_t nvr,
                               const fmi3Float64 shifts[])
{ (void)vr; (void)nvr; (void)shifts; REFUSE(instance, "fmi3SetShiftDecimal", NO_CLOCKS); }
fmi3Status fmi3SetShiftFraction(fmi3Instance instance, const fmi3ValueReference vr[], size_t nvr,
                                const fmi3UInt64 counters[], const fmi3UInt64 resolutions[])
{ (void)vr; (void)nvr; (void)counters; (void)resolutions;
  REFUSE(instance, "fmi3SetShiftFraction", NO_CLOCKS); }
fmi3Status fmi3ActivateModelPartition(fmi3Instance instance, fmi3ValueReference clockReference,
                                      fmi3Float64 activationTime)
{ (void)clockReference; (void)activationTime;
  REFUSE(instance, "fmi3ActivateModelPartition", CS_ONLY); }

/* ---------------------------------------------------------------- model exchange */

fmi3Status fmi3EnterContinuousTimeMode(fmi3Instance instance)
{ REFUSE(instance, "fmi3EnterContinuousTimeMode", CS_ONLY); }
fmi3Status fmi3CompletedIntegratorStep(fmi3Instance instance,
                                       fmi3Boolean noSetFMUStatePriorToCurrentPoint,
                                       fmi3Boolean *enterEventMode,
                                       fmi3Boolean *terminateSimulation)
{ (void)noSetFMUStatePriorToCurrentPoint; (void)enterEventMode; (void)terminateSimulation;
  REFUSE(instance, "fmi3CompletedIntegratorStep", CS_ONLY); }
fmi3Status fmi3SetTime(fmi3Instance instance, fmi3Float64 time)
{ (void)time; REFUSE(instance, "fmi3SetTime", CS_ONLY); }
fmi3Status fmi3SetContinuousStates(fmi3Instance instance, const fmi3Float64 continuousStates[],
                                   size_t nContinuousStates)
{ (void)continuousStates; (void)nContinuousStates;
  REFUSE(instance, "fmi3SetContinuousStates", CS_ONLY); }
fmi3Status fmi3GetContinuousStateDerivatives(fmi3Instance instance, fmi3Float64 derivatives[],
                                             size_t nContinuousStates)
{ (void)derivatives; (void)nContinuousStates;
  REFUSE(instance, "fmi3GetContinuousStateDerivatives", CS_ONLY); }
fmi3Status fmi3GetEventIndicators(fmi3Instance instance, fmi3Float64 eventIndicators[],
                                  size_t nEventIndicators)
{ (void)eventIndicators; (void)nEventIndicators;
  REFUSE(instance, "fmi3GetEventIndicators", CS_ONLY); }
fmi3Status fmi3GetContinuousStates(fmi3Instance instance, fmi3Float64 continuousStates[],
                                   size_t nContinuousStates)
{ (void)continuousStates; (void)nContinuousStates;
  REFUSE(instance, "fmi3GetContinuousStates", CS_ONLY); }
fmi3Status fmi3GetNominalsOfContinuousStates(fmi3Instance instance, fmi3Float64 nominals[],
                                             size_t nContinuousStates)
{ (void)nominals; (void)nContinuousStates;
  REFUSE(instance, "fmi3GetNominalsOfContinuousStates", CS_ONLY); }
fmi3Status fmi3GetNumberOfEventIndicators(fmi3Instance instance, size_t *nEventIndicators)
{ (void)nEventIndicators; REFUSE(instance, "fmi3GetNumberOfEventIndicators", CS_ONLY); }
fmi3Status fmi3GetNumberOfContinuousStates(fmi3Instance instance, size_t *nContinuousStates)
{ (void)nContinuousStates; REFUSE(instance, "fmi3GetNumberOfContinuousStates", CS_ONLY); }
