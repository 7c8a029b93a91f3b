/* SPDX-License-Identifier: Apache-2.0 */
/*
 * The FMI calls, once for both FMI versions (fmu_core.c): what fmi2_glue.c and fmi3_glue.c
 * call after translating their arguments. Every function that takes an instance expects one
 * that fmu_enter() returned for this call (ours, in an allowed state); `func` is the FMI name of
 * the call, for its messages. Every FMU_ERROR is logged and leaves the instance as it was.
 */
#ifndef FMU_CORE_H
#define FMU_CORE_H

#include <stddef.h>
#include <stdint.h>
#include "fmu_instance.h"

/** Masks of fmu_phase values, for fmu_enter()'s `allowed`. */
#define FMU_IN_INSTANTIATED (1u << FMU_INSTANTIATED)
#define FMU_IN_INIT (1u << FMU_INITIALIZATION_MODE)
#define FMU_IN_STEP (1u << FMU_STEP_COMPLETE)
#define FMU_IN_TERMINATED (1u << FMU_TERMINATED)
#define FMU_IN_ANY (FMU_IN_INSTANTIATED | FMU_IN_INIT | FMU_IN_STEP | FMU_IN_TERMINATED)

/** Log through an instance: errors and warnings always, the debug categories (FMU_LOG_CALLS)
 * only when switched on. printf-style; the message is finished text when it reaches the
 * importer. */
void fmu_log(const fmu_instance *c, fmu_status status, int category, const char *fmt, ...);
/** Log an error (category logStatusError) and return FMU_ERROR. */
fmu_status fmu_fail(const fmu_instance *c, const char *fmt, ...);
/** Log an error through the importer's services before an instance exists. */
void fmu_log_host(const fmu_host *host, const char *instance, const char *fmt, ...);

/**
 * A new instance in state instantiated, every variable at its start value.
 * @param magic  FMU_INSTANCE_MAGIC_FMI2 or _FMI3: an instance of one version is never accepted
 *               by the other version's calls
 * @param token  the importer's instantiation token, compared with `expected`
 * @return the instance, or NULL (logged through host when it has a logger).
 */
fmu_instance *fmu_instantiate(const fmu_host *host, uint32_t magic, const char *func,
                              const char *name, const char *token, const char *expected,
                              int logging_on);
/** The instance if comp is one of ours of this version (magic) and its state is in `allowed`
 * (a mask of FMU_IN_*); else NULL, with a logged message when comp is a smoothshaper instance
 * (another model's, precision's, or in a state where func is not allowed). */
fmu_instance *fmu_enter(void *comp, uint32_t magic, const char *func, unsigned allowed);
void fmu_free_instance(fmu_instance *c);

fmu_status fmu_set_debug_logging(fmu_instance *c, const char *func, int on, size_t n,
                                 const char *const categories[]);
/** The start (and stop) time of the experiment; the state is not changed. */
fmu_status fmu_setup(fmu_instance *c, const char *func, double start, int stop_defined,
                     double stop);
fmu_status fmu_enter_initialization(fmu_instance *c);
/** Build the filters at rest at the current inputs; FMU_ERROR leaves initialization mode on. */
fmu_status fmu_exit_initialization(fmu_instance *c, const char *func);
fmu_status fmu_terminate(fmu_instance *c);
fmu_status fmu_reset(fmu_instance *c);

/** Read values: doubles for FMU_REAL, int32_t for FMU_INTEGER. An unknown value reference
 * writes nothing. */
fmu_status fmu_get(fmu_instance *c, const char *func, fmu_type type, const fmu_vr vr[],
                   size_t nvr, void *value);
/** Write values (all checked before any is written): an output, a fixed parameter after
 * initialization, a non-finite Real, an input beyond the model's range or a tunable parameter's
 * value that fmu_model_check_tunable() refuses after initialization is refused. */
fmu_status fmu_set(fmu_instance *c, const char *func, fmu_type type, const fmu_vr vr[],
                   size_t nvr, const void *value);
/** A base type the model has no variables of: any value reference is unknown. */
fmu_status fmu_no_variables(fmu_instance *c, const char *func, const fmu_vr vr[], size_t nvr,
                            const void *value);

/** The communication step from t of length h: the ticks in (t, t+h] under the held inputs. */
fmu_status fmu_do_step(fmu_instance *c, const char *func, double t, double h);

/** FMU states: get into *state (a new one when *state is NULL), set, free, size, serialise,
 * deserialise (into a new state; *state, if not NULL, is freed once the new one exists). */
fmu_status fmu_get_state(fmu_instance *c, const char *func, void **state);
fmu_status fmu_set_state(fmu_instance *c, const char *func, void *state);
fmu_status fmu_free_state(fmu_instance *c, const char *func, void **state);
fmu_status fmu_state_size(fmu_instance *c, const char *func, void *state, size_t *size);
fmu_status fmu_serialize_state(fmu_instance *c, const char *func, void *state,
                               unsigned char *out, size_t size);
fmu_status fmu_deserialize_state(fmu_instance *c, const char *func, const unsigned char *in,
                                 size_t size, void **state);

#endif
