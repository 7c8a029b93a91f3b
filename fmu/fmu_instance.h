/* SPDX-License-Identifier: Apache-2.0 */
/*
 * Internal types of the shared FMI glue, the same for FMI 2.0 and FMI 3.0: the importer's
 * services, the instance, the FMU state snapshot, the clock, and the build of a model into an
 * instance's block (fmu_build.c). The serialised state has its own header (fmu_serialize.h),
 * the calls that use these types theirs (fmu_core.h).
 */
#ifndef FMU_INSTANCE_H
#define FMU_INSTANCE_H

#include <stdint.h>
#include "fmu_model.h"

/** A call's outcome: the values of fmi2Status and fmi3Status alike (OK 0 .. Fatal 4). */
typedef enum fmu_status {
    FMU_OK = 0,
    FMU_WARNING = 1,
    FMU_DISCARD = 2,
    FMU_ERROR = 3,
    FMU_FATAL = 4
} fmu_status;

/**
 * What the importer provides, in the glue's terms. FMI 2.0 passes memory functions and a
 * printf-style logger; FMI 3.0 passes a logger of finished text and no memory functions (the
 * FMI 3.0 glue gives calloc and free). The version's glue file fills this in and translates a
 * message for its logger in `log`.
 */
typedef struct fmu_host {
    void *(*alloc)(size_t count, size_t size);   /**< zeroed memory; NULL when out of it */
    void (*release)(void *p);
    /** Pass a finished message to the importer's logger (NULL: the importer gave none). */
    void (*log)(const struct fmu_host *host, const char *instance, fmu_status status,
                const char *category, const char *message);
    void (*logger)(void);   /**< the importer's logger as given (`log` casts it back) */
    void *environment;      /**< the importer's componentEnvironment / instanceEnvironment */
} fmu_host;

/** The Co-Simulation states this FMU can be in, FMI 2.0 and 3.0 alike (doStep is synchronous
 * and there is no event mode, so stepInProgress, stepFailed, stepCanceled, stepDiscarded,
 * eventMode and the configuration modes never occur). */
typedef enum fmu_phase {
    FMU_INSTANTIATED = 0,
    FMU_INITIALIZATION_MODE = 1,
    FMU_STEP_COMPLETE = 2,    /**< FMI 2.0 stepComplete, FMI 3.0 Step Mode */
    FMU_TERMINATED = 3
} fmu_phase;

enum { FMU_LOG_ERROR = 0, FMU_LOG_WARNING = 1, FMU_LOG_CALLS = 2, FMU_LOG_CATEGORIES = 3 };

/**
 * The glue's clock. Ticks are counted, never derived from the importer's time alone: a doStep
 * of length h advances the position since_tick + h and computes the ticks it passes (fmu_clock.c),
 * so a host that accumulates t += h (whose t drifts from k*h) still gets exactly one tick per
 * step of h = Ts. The importer's time is kept to check that steps are contiguous and to scale
 * the slack that the rounding of its times needs.
 */
typedef struct fmu_clock {
    fmu_phase phase;
    double start_time;   /**< t0 from SetupExperiment / EnterInitializationMode */
    double time;         /**< last communication point reached (the importer's number) */
    uint64_t ticks;      /**< internal ticks computed so far; tick n is at t0 + n*Ts */
    double since_tick;   /**< time advanced since tick `ticks` [s], in [-slack, Ts - slack) */
    uint64_t steady;     /**< ticks in a row whose outputs did not change (same input) */
} fmu_clock;

/** Ticks of unchanged outputs after which a held input counts as absorbed, for a model with
 * `count` state values: more than any delay line, restart cycle or pure delay it holds. */
#define FMU_STEADY_TICKS(count) (8u * (uint64_t)(count) + 16u)

/** What identifies the binary an instance or a state belongs to: one model, one precision, one
 * FMI version. Each FMU binary links its own copy of the glue, so the address of a static object
 * of the glue is unique to the binary: one pointer comparison, no call, at every entry; the
 * magic tells the FMI versions (and instances from states) apart. */
typedef struct fmu_identity {
    uint32_t magic;
    const void *binary;  /**< address of this binary's glue token */
    uint32_t real_bytes; /**< fmu_model_real_bytes() (for messages) */
} fmu_identity;

/** Most input variables (Real and Integer) a values image records (fmu_values_image). */
#define FMU_MAX_IMAGE_INPUTS 16

/**
 * The settable values of an instance as fmu_serialize() writes them (the region from nR to the
 * last Integer), made from its current parameters: a state whose region equals it outside the
 * inputs' values holds the instance's parameters bit for bit, which one memcmp tells instead
 * of reading and checking every value (fmu_deserialize()). Made on demand by
 * fmu_values_image_make(), dropped (valid = 0) by every glue call that may write a parameter.
 */
typedef struct fmu_values_image {
    unsigned char *bytes;        /**< the region's bytes (NULL: none made yet) */
    size_t len;                  /**< its length */
    int valid;                   /**< 1: bytes are the current parameters' */
    size_t n_inputs;             /**< the inputs among the values, in region order */
    size_t input_at[FMU_MAX_IMAGE_INPUTS];   /**< offset of each input's value in bytes */
    fmu_vr input_vr[FMU_MAX_IMAGE_INPUTS];
    fmu_type input_type[FMU_MAX_IMAGE_INPUTS];
} fmu_values_image;

typedef struct fmu_instance {
    fmu_identity id;     /**< first: checked at every entry before anything else is read */
    fmu_host host;
    char *name;
    int log_on[FMU_LOG_CATEGORIES];
    int has_time;        /**< 1: the interface declares the independent variable time (FMI 3.0) */
    fmu_vr time_vr;      /**< its value reference: reads the communication point reached */
    fmu_clock clock;
    void *model;         /**< fmu_model_size() bytes */
    void *mem;           /**< the filters' block (NULL before build) */
    size_t mem_bytes;
    fmu_values_image values;   /**< its settable values as a state writes them */
} fmu_instance;

/** An FMU state: a copy of the clock, the model struct and its block (rebound on set). */
typedef struct fmu_snapshot {
    fmu_identity id;
    fmu_clock clock;
    void *model;
    void *mem;
    size_t mem_bytes;
} fmu_snapshot;

#define FMU_INSTANCE_MAGIC_FMI2 0x32534d53u  /* "SMS2" */
#define FMU_INSTANCE_MAGIC_FMI3 0x33534d53u  /* "SMS3" */
#define FMU_SNAPSHOT_MAGIC 0x32534d54u       /* a state is the same for both versions */

/** Fraction of Ts by which a tick may follow the end of a step and still belong to it, beyond
 * the rounding of the importer's times (fmu_clock_slack()). */
#define FMU_TICK_SLACK 1e-6
/** Tick counts stay below this, so that they are exact as doubles. */
#define FMU_MAX_TICK_INDEX 4.0e15

/** The slack [s] by which a tick may follow the end of a step ending at t (start time t0) and
 * still belong to it: FMU_TICK_SLACK Ts + 2^-51 max(|t|, |t0|), the rounding of an importer's
 * t0 + k h, at most Ts/2 (fmu_clock.c explains it; here to be inlined into every doStep). */
static inline double fmu_clock_slack(double Ts, double t0, double t)
{
    const double at = t < 0.0 ? -t : t, from = t0 < 0.0 ? -t0 : t0;
    const double slack = FMU_TICK_SLACK * Ts + 0x1p-51 * (at > from ? at : from);
    return slack < 0.5 * Ts ? slack : 0.5 * Ts;
}
/** Is a loaded clock one a run could have reached (ticks in range, the time since the last tick
 * within the slack, the time where the ticks put it)? 0, or -1 with msg saying why. */
int fmu_clock_check(const fmu_clock *k, double Ts, char *msg, size_t len);

/**
 * Plan, allocate (through host) and build model; on success *mem and *bytes hold the new block
 * and the previous block is freed. Returns 0 (built), -1 (built, msg holds a warning about the
 * parameters) or 1 (failed: nothing changes and msg says why).
 */
int fmu_build(const fmu_host *host, void *model, void **mem, size_t *bytes, char *msg,
              size_t len);

#endif
