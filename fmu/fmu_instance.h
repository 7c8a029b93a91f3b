/* SPDX-License-Identifier: Apache-2.0 */
/*
 * Internal types of the shared FMI 2.0 glue: the instance, the FMU state snapshot, and the
 * build of a model into an instance's block (fmu_build.c). The serialised state has its own
 * header (fmu_serialize.h).
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

/**
 * The glue's clock. Ticks are counted, never derived from the importer's time alone: a doStep
 * of length h advances the position since_tick + h and computes floor of that over Ts ticks, so
 * a host that accumulates t += h (whose t drifts from k*h) still gets exactly one tick per
 * step of h = Ts. The importer's time is kept only to check that steps are contiguous.
 */
typedef struct fmu_clock {
    fmu_phase phase;
    double start_time;   /**< t0 from fmi2SetupExperiment */
    double time;         /**< last communication point reached (the importer's number) */
    uint64_t ticks;      /**< internal ticks computed so far; tick n is at t0 + n*Ts */
    double since_tick;   /**< time advanced since tick `ticks` [s], in [-slack*Ts, Ts) */
    uint64_t steady;     /**< ticks in a row whose outputs did not change (same input) */
} fmu_clock;

/** Ticks of unchanged outputs after which a held input counts as absorbed, for a model with
 * `count` state values: more than any delay line, restart cycle or pure delay it holds. */
#define FMU_STEADY_TICKS(count) (8u * (uint64_t)(count) + 16u)

/** What identifies the binary an instance or a state belongs to: one model, one precision.
 * Each FMU binary links its own copy of the glue, so the address of a static object of the glue
 * is unique to the binary: one pointer comparison, no call, at every entry. */
typedef struct fmu_identity {
    uint32_t magic;
    const void *binary;  /**< address of this binary's glue token */
    uint32_t real_bytes; /**< fmu_model_real_bytes() (for messages) */
} fmu_identity;

typedef struct fmu_instance {
    fmu_identity id;     /**< first: checked at every entry before anything else is read */
    fmi2CallbackFunctions cb;
    char *name;
    int log_on[FMU_LOG_CATEGORIES];
    fmu_clock clock;
    void *model;         /**< fmu_model_size() bytes */
    void *mem;           /**< the filters' block (NULL before build) */
    size_t mem_bytes;
} fmu_instance;

/** An fmi2FMUstate: a copy of the clock, the model struct and its block (rebound on set). */
typedef struct fmu_snapshot {
    fmu_identity id;
    fmu_clock clock;
    void *model;
    void *mem;
    size_t mem_bytes;
} fmu_snapshot;

#define FMU_INSTANCE_MAGIC 0x32534d53u  /* "SMS2" */
#define FMU_SNAPSHOT_MAGIC 0x32534d54u

/** Fraction of Ts by which a tick may follow the end of a step and still belong to it. */
#define FMU_TICK_SLACK 1e-6

/**
 * Plan, allocate (through cb) and build model; on success *mem and *bytes hold the new block and
 * the previous block is freed. Returns 0 (built), -1 (built, msg holds a warning about the
 * parameters) or 1 (failed: nothing changes and msg says why).
 */
int fmu_build(const fmi2CallbackFunctions *cb, void *model, void **mem, size_t *bytes, char *msg,
              size_t len);

#endif
