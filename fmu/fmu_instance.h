/*
 * Internal types of the shared FMI 2.0 glue: the instance, the FMU state snapshot, and the
 * serialisation entry points (fmu_serialize.c).
 */
#ifndef FMU_INSTANCE_H
#define FMU_INSTANCE_H

#include <stdint.h>
#include "fmu_model.h"

/** The FMI 2.0 Co-Simulation states this FMU can be in (doStep is synchronous, so the
 * stepInProgress/stepFailed/stepCanceled states never occur). */
typedef enum fmu_phase {
    FMU_INSTANTIATED = 0,
    FMU_INITIALIZATION_MODE = 1,
    FMU_STEP_COMPLETE = 2,
    FMU_TERMINATED = 3
} fmu_phase;

enum { FMU_LOG_ERROR = 0, FMU_LOG_WARNING = 1, FMU_LOG_CALLS = 2, FMU_LOG_CATEGORIES = 3 };

/** Everything the glue keeps besides the model data. */
typedef struct fmu_clock {
    fmu_phase phase;
    double start_time;   /**< t0 from fmi2SetupExperiment */
    double time;         /**< last communication point reached */
    uint64_t ticks;      /**< internal ticks computed so far; tick n is at t0 + n*Ts */
} fmu_clock;

typedef struct fmu_instance {
    uint32_t magic;
    fmi2CallbackFunctions cb;
    char *name;
    int log_on[FMU_LOG_CATEGORIES];
    fmu_clock clock;
    void *model;
} fmu_instance;

/** An fmi2FMUstate: a copy of the clock and of the model data (pointers rebound on set). */
typedef struct fmu_snapshot {
    uint32_t magic;
    const char *owner;   /**< fmu_model_guid() of the binary that made it: refuses another model's */
    fmu_clock clock;
    void *model;
} fmu_snapshot;

#define FMU_INSTANCE_MAGIC 0x534d5349u  /* "SMSI" */
#define FMU_SNAPSHOT_MAGIC 0x534d5353u  /* "SMSS" */

/** Bytes fmu_serialize() writes for this snapshot. */
size_t fmu_serialized_size(const fmu_snapshot *s);
/** Write the snapshot into out[0..size-1] (size from fmu_serialized_size); the model's state
 * vector passes through scratch memory from cb. @return 0, or non-zero when out of memory. */
int fmu_serialize(const fmu_snapshot *s, const fmi2CallbackFunctions *cb, unsigned char *out);
/**
 * Parse a serialised state into dst (whose model data is allocated, fmu_model_size() bytes).
 * @return 0 on success, else non-zero with msg saying why (foreign, truncated, corrupted,
 *         invalid parameters); dst is then unspecified and must not be used.
 */
int fmu_deserialize(const unsigned char *in, size_t size, fmu_snapshot *dst,
                    const fmi2CallbackFunctions *cb, char *msg, size_t len);

#endif
