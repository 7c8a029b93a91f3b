/* SPDX-License-Identifier: Apache-2.0 */
/*
 * The contract between the shared FMI glue (fmu_core.c, under fmi2_glue.c and fmi3_glue.c) and
 * one model file. It names no FMI type: a model file is the same for FMI 2.0 and FMI 3.0.
 *
 * Each FMU binary links the glue with exactly one model file, which defines the functions
 * below. A model keeps its parameters and filter descriptors in one small plain struct of
 * fmu_model_size() bytes, and its delay lines / tables in one block sized to the configured
 * filters: fmu_model_plan() validates the parameters and says how many bytes (closed form, no
 * work proportional to the size), the glue allocates them through the importer's callbacks
 * and fmu_model_build() builds into them. FMU states copy the struct and the block and call
 * fmu_model_rebind() so the copy's internal pointers point at the copy's own block.
 *
 * Variables: the glue checks the call order and the value references' causality; the model
 * stores and returns the values. Non-finite Reals are rejected by the glue at set.
 */
#ifndef FMU_MODEL_H
#define FMU_MODEL_H

#include <stddef.h>
#include <stdint.h>

/** A value reference: the variable's number in modelDescription.xml (FMI 2.0 and 3.0 alike;
 * an FMI 3.0 array variable is the value reference of its first element). */
typedef uint32_t fmu_vr;

/** What a value reference of a given base type is. */
typedef enum fmu_var_class {
    FMU_VAR_UNKNOWN = 0,  /**< no variable of this type has this value reference */
    FMU_VAR_INPUT,        /**< settable in every state before termination */
    FMU_VAR_PARAMETER,    /**< fixed: settable only before the end of initialization */
    FMU_VAR_OUTPUT,       /**< read only */
    FMU_VAR_TUNABLE       /**< a parameter settable in every state before termination; after
                               initialization only when fmu_model_check_tunable() accepts it */
} fmu_var_class;

/** The base types the models use: FMI 2.0 Real / FMI 3.0 Float64, FMI 2.0 Integer / FMI 3.0
 * Int32 (the choices are Integer codes with min and max). */
typedef enum fmu_type { FMU_REAL = 0, FMU_INTEGER = 1 } fmu_type;

/** The per-instance limit on an FMU's state: all its delay lines and tables together, in reals
 * (2^22 = 4,194,304: 32 MiB in double, and the serialised state is then at most 32 MiB plus a
 * few hundred bytes). Every FMI call that touches the whole state (ExitInitializationMode,
 * Get/SetFMUstate, (De)SerializeFMUstate, Reset, FreeInstance) costs at most
 * about 0.8 ns per byte of it in the release build (tests/fmu/bench_fmu_state_size.c), so at
 * this limit the slowest takes about 25 ms, a fourth of the 100 ms any call is allowed. Beyond
 * it fmu_model_plan() refuses at once (closed forms, O(1)) through fmu_refuse_size(). The Python
 * package has its own, larger limit for arrays it holds (smoothshaper.filters.MAX_BUFFER_REALS). */
#define FMU_MAX_REALS ((size_t)1 << 22)

/** The limit on the filtering a long doStep may need, in stage-samples (2^24): a held input
 * is absorbed by a model's filters in a bounded number of samples, after which closed forms
 * take over (fmu_model_hold()); until then each filter stage is run, at about 1.5 to 4 ns per
 * stage-sample (release build, x86-64), so a step of any length costs at most about 25 to
 * 70 ms. A single stage at FMU_MAX_REALS needs 2^23 + 2 (a smoother absorbs in at most twice
 * its ring length). Beyond it fmu_model_plan() refuses at once (closed forms, O(1)) through
 * fmu_refuse_hold(). */
#define FMU_MAX_HOLD_SAMPLES ((double)(1u << 24))

/** The limit on the whole-model steps a long doStep may take one by one (2^20, about 40 ns
 * each for a generator: 40 ms): the trigonometric profile waits, sample by sample, for a state
 * a new plan can start from, at most one acceleration transition of pi amax/jmax. */
#define FMU_MAX_HOLD_STEPS ((double)(1u << 20))

/**
 * @brief The refusal of a configuration whose filters would need more than
 * FMU_MAX_HOLD_SAMPLES stage-samples to absorb a held input (fmu_refuse.c).
 * @param parameters  the variables that set the slowest stage, with their values
 * @param need        the stage-samples the configuration needs (sms_chain_hold_cost())
 * @param slowest     what the slowest stage needs alone, and why ("a notch decaying in ...")
 * @param fix         what to change
 * @return 1 (the plan fails), msg holding the message.
 */
int fmu_refuse_hold(char *msg, size_t len, const char *parameters, double need,
                    const char *slowest, const char *fix);

/** Largest message fmu_model_build() or fmu_model_warning() may write (including the
 * terminating 0): room for a MultiAxisGenerator warning naming 8 targets and the limits. */
#define FMU_MESSAGE_LEN 768

/**
 * @brief The refusal of a configuration whose delay lines and tables need more than
 * FMU_MAX_REALS reals (fmu_refuse.c: one wording for every model).
 * @param parameters  the variables that set the size, with their values ("stage[0].T = 20, Ts =
 *                    1e-06")
 * @param need        reals the configuration needs (all delay lines and tables together)
 * @param fix         what to change ("shorten the stage or raise Ts")
 * @return 1 (the plan fails), msg holding the message.
 */
int fmu_refuse_size(char *msg, size_t len, const char *parameters, double need, const char *fix);

/** @return sizeof the model's data struct. */
size_t fmu_model_size(void);
/** @return the model identifier (= modelIdentifier in modelDescription.xml). */
const char *fmu_model_identifier(void);
/** @return the FMI 2.0 guid the generated header carries (also the tag of a serialised state,
 * so a state moves between a model's FMI 2.0 and FMI 3.0 binaries of one build). */
const char *fmu_model_guid(void);
/** @brief Put every variable at its start value, nothing built (the state after instantiate). */
void fmu_model_defaults(void *model);
/** @brief Classify a value reference of the given type. */
fmu_var_class fmu_model_class(fmu_type type, fmu_vr vr);
/** @brief Name of the variable (for log messages) into buf (always 0-terminated). */
void fmu_model_name(fmu_type type, fmu_vr vr, char *buf, size_t len);
/** @brief Every settable (input or parameter) value reference of the type, in a fixed order:
 * the serialised state stores their values in this order. Writes at most cap; returns the
 * count. */
size_t fmu_model_settable(fmu_type type, fmu_vr *out, size_t cap);
/** @brief Read a variable (vr already classified as known). */
double fmu_model_get_real(const void *model, fmu_vr vr);
int fmu_model_get_integer(const void *model, fmu_vr vr);
/**
 * @brief After the end of initialization, may these tunable parameters take these values (one
 * set call of either FMI version, all checked together with the model's other values)? The
 * glue writes none of them unless it returns 0. A model without tunable parameters returns 0
 * (it is never asked).
 * @param values  doubles for FMU_REAL, int32_t for FMU_INTEGER, one per vr
 * @return 0, or non-zero with msg naming the variable and why (nothing is written then).
 */
int fmu_model_check_tunable(const void *model, fmu_type type, const fmu_vr *vr,
                            const void *values, size_t n, char *msg, size_t len);
/** @brief Write an input or parameter (vr already classified, Real already finite). */
void fmu_model_set_real(void *model, fmu_vr vr, double value);
void fmu_model_set_integer(void *model, fmu_vr vr, int value);
/** @return the sample period parameter Ts [s] (validated by fmu_model_plan). */
double fmu_model_sample_period(const void *model);
/** @return sizeof(sms_real) of this build (a saved state of the other precision is refused). */
unsigned fmu_model_real_bytes(void);
/** @return the largest |input| the model keeps every output and state finite for, from its
 * current parameters (O(1); valid after fmu_model_build, and fmu_model_build refuses an input
 * beyond it naming the variable), or HUGE_VAL when only the glue's SMS_INPUT_MAX applies. */
double fmu_model_input_max(const void *model);
/**
 * @brief The largest |input| a loaded state may hold (an input saved with it): what
 * fmu_model_input_max() gives (SmoothShaper refuses a retune that would narrow the range below
 * a held input, so no input accepted under an earlier configuration is beyond it); valid as
 * that one.
 */
double fmu_model_state_input_max(const void *model);
/**
 * @brief Validate every parameter; O(1) in the size of the filters.
 * @param bytes  out: bytes of memory fmu_model_build() needs (may be 0).
 * @return 0 on success; otherwise non-zero, msg naming the variable and its value.
 */
int fmu_model_plan(const void *model, size_t *bytes, char *msg, size_t len);
/**
 * @brief Build the filters into mem (bytes from fmu_model_plan, aligned for any type), at rest
 * at the current input.
 * @return 0 on success; negative: built, with a warning about the parameters in msg (the glue
 * logs it as a warning); positive: refused, msg says why, and the model untouched.
 */
int fmu_model_build(void *model, void *mem, size_t bytes, char *msg, size_t len);
/** @brief Before fmi2DoStep's ticks: are the inputs valid together (each was checked alone
 * when it was set)? Only after build.
 * @return 0, or 1 with msg naming the inputs and why: the step then fails, nothing changed. */
int fmu_model_check_inputs(const void *model, char *msg, size_t len);
/** @brief One internal tick: filter the held input, update the outputs. Only after build.
 * @return non-zero if an output changed (bitwise), 0 if all kept their values. */
int fmu_model_tick(void *model);
/**
 * @brief A doStep's n ticks under the held input, at a cost bounded whatever n: the first k of
 * them computed with the state and outputs of k calls of fmu_model_tick(), bit for bit (closed
 * forms of the model's filters under a constant input: the model's file says how); the glue
 * ticks the remaining n - k one by one until the outputs have held (FMU_STEADY_TICKS). Only
 * after build.
 * @return k (n when the model holds any step itself).
 */
uint64_t fmu_model_hold(void *model, uint64_t n);
/** @brief After a doStep's ticks: a warning about something the model did with the inputs
 * (e.g. a target it dropped), once per cause: the glue logs msg as a warning and the step
 * returns a warning status. Only after build.
 * @return 1 with msg written, 0 when there is nothing to report. */
int fmu_model_warning(void *model, char *msg, size_t len);
/** @brief After a bytewise copy of a built model and its block, point it at its own block. */
void fmu_model_rebind(void *model, void *mem);
/** @brief Number of doubles of dynamic state (outputs and filter state) of a built model: a
 * complete description (loading it continues bit for bit). */
size_t fmu_model_state_count(const void *model);
void fmu_model_save_state(const void *model, double *dst);
/** @return 0 if accepted (model updated), non-zero if the vector does not fit (untouched); then
 * msg (len bytes, empty on entry) may say why, else the caller's generic message stands. */
int fmu_model_load_state(void *model, const double *src, size_t n, char *msg, size_t len);

#endif
