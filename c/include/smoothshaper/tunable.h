/* SPDX-License-Identifier: Apache-2.0 */
/**
 * @file tunable.h
 * @brief Stages that can be retuned while they run, alone (::sms_tunable) or in series
 * (::sms_tunable_chain): a shaper's wn and zeta, a smoother's T or family, a notch, changed at
 * a sample instant without a jump (docs/retune.md has the proof of what follows).
 *
 * **The rule.** Every input increment dx[k] = x[k] - x[k-1] is filtered by the filter that was
 * active when it arrived. With s_a the step response of filter a (s_a[m] = h_a[0] + ... +
 * h_a[m], 1 from its length L_a - 1 on) and a(k) the filter active at sample k,
 *
 *     y[n] = x_rest + sum_k s_{a(k)}[n - k] dx[k].
 *
 * A switch from A to B before sample n0 is realised with two slots: B starts at rest at
 * h = x[n0-1] (the last finite input) and takes the input from n0 on; A keeps running on the
 * constant h, and y = y_B + (y_A - h). So, for every family (unit DC gain):
 * - at the switch, y differs from what A alone would give by (h_B[0] - h_A[0]) dx[n0]: at
 *   most one sample's motion of the input (0 for the half-sine families, whose first tap is 0);
 *   every derivative of the output keeps the continuity each design has (the kernel of an
 *   increment never changes after it arrived);
 * - FIR stages (smoothers, shapers): from n0 + L_A - 2 on, y = h + B(x - h after n0): the old
 *   filter's share is the constant h, and every increment since the switch has been shaped by
 *   B alone (B's zeros hold exactly for them); from n0 + max(L_A, L_B) - 2 on, y equals B's
 *   output as if B had always run, to rounding. The old filter runs for L_A samples and is then
 *   dropped (its share is h to rounding);
 * - notches (IIR): the same two slots; the old notch's share is its free response, which
 *   decays with its poles. It is dropped once what it can still add is provably below a quarter
 *   of the unit roundoff of |h| (a bound from its state and its poles, computed in O(1)), or
 *   once it has settled exactly (sms_notch_is_settled()). With h = 0 only the exact settling
 *   ends it (the limit is relative to |h|).
 * While a switch is in progress (sms_tunable_switching()) a further retune is refused with
 * ::SMS_ERR_RETUNE_BUSY: at most two filters run, whatever the caller does. The per-sample work
 * is that of the active filter (plus one test per block); during a switch, that of both.
 * Each slot is an ordinary stage (stage.h): drift-free, O(1) per sample, no allocation, float
 * and double from one source.
 *
 * **Memory.** A tunable has two slots of the same size, enough for the largest configuration
 * the caller declares: sms_tunable_slot_cells() takes the configurations the stage may ever be
 * retuned to (any families) and returns the cells one slot needs; the caller provides
 * 2 * slot_cells ::sms_memory_cell (sms_tunable_memory_size()). A retune to a configuration
 * that needs more is refused with ::SMS_ERR_BUFFER_TOO_SMALL. Nothing is allocated; a retune
 * costs one design (libm, O(1) for smoothers, O(taps) for shapers) and the zeroing of the new
 * delay line, like sms_stage_init().
 */
#ifndef SMOOTHSHAPER_TUNABLE_H
#define SMOOTHSHAPER_TUNABLE_H

#include <stdint.h>
#include "smoothshaper/chain.h"

#ifdef __cplusplus
extern "C" {
#endif

/** @brief Kind field of a saved ::sms_tunable state (beyond every ::sms_kind, config.h). */
#define SMS_STATE_KIND_TUNABLE 103.0
/** @brief Doubles of a saved ::sms_tunable state before its stages: the head of config.h
 * (::SMS_STATE_IDENTITY_HEAD) and slot_cells, switching (0/1), samples left (FIR) or age
 * (notch) of the switch, the last finite input, the held input h. */
#define SMS_TUNABLE_STATE_HEAD (SMS_STATE_IDENTITY_HEAD + 5)

/** @brief One retunable stage. Fields are public for inspection; change them only through
 * the functions below. */
typedef struct sms_tunable {
    sms_stage slot[2];          /**< slot[active] filters; the other fades out during a switch */
    sms_memory_cell *memory;    /**< 2 * slot_cells cells: slot 0, then slot 1 */
    size_t slot_cells;          /**< cells of one slot */
    unsigned n_slots;           /**< 2, or 1 for a stage built without room to switch */
    double Ts;                  /**< sample period [s] */
    unsigned active;            /**< 0 or 1 */
    int switching;              /**< 1 while the old filter still adds to the output */
    uint64_t fade;              /**< FIR: samples the old filter still runs; notch: its age */
    sms_real last;              /**< last finite input (the rest value after a reset) */
    sms_real hold;              /**< h: the old filter's constant input during a switch */
    /* Old notch: bounds on its remaining free response from its last two w's and its poles
     * (tunable.c). */
    int fade_real_poles;        /**< old notch: 1 for real poles, 0 complex */
    sms_real fade_c1;           /**< complex poles: Re p; real: the first pole */
    sms_real fade_c2;           /**< complex poles: Im p; real: the second pole */
    sms_real fade_scale;        /**< complex: Im p; real: |p1 - p2| */
    sms_real fade_k;            /**< max over k >= 1 of k rho^(k-1), rho the pole radius */
} sms_tunable;

/**
 * @brief Cells of memory one slot needs to hold any of the declared configurations: the
 * largest sms_stage_memory_size() among them. O(n) (closed forms).
 * @param declared    the configurations the stage may be built or retuned to (>= 1)
 * @param n_declared  how many
 * @param Ts          sample period [s]
 * @param slot_cells  receives the cells of one slot
 * @return ::SMS_OK, ::SMS_ERR_NULL, ::SMS_ERR_ORDER (n_declared = 0), or the status of the first
 *         declared configuration that is invalid at Ts.
 */
SMS_API sms_status sms_tunable_slot_cells(const sms_stage_config *declared, size_t n_declared,
                                          double Ts, size_t *slot_cells);
/** @brief Cells a tunable with slots of slot_cells needs (2 slot_cells).
 * @return ::SMS_OK, ::SMS_ERR_NULL, ::SMS_ERR_TOO_LONG (overflows size_t).
 * @param slot_cells cells of one slot, from sms_tunable_slot_cells()
 * @param n_cells    receives 2 slot_cells
 */
SMS_API sms_status sms_tunable_memory_size(size_t slot_cells, size_t *n_cells);
/**
 * @brief Validate and build a tunable stage at rest at 0, filtering with config.
 * @param slot_cells  from sms_tunable_slot_cells(); config must fit (its memory size at most)
 * @param memory      caller memory of n_cells >= 2 slot_cells cells; the tunable keeps it.
 *                    With slot_cells <= n_cells < 2 slot_cells it has one slot: a stage that
 *                    is never retuned (every retune refused with ::SMS_ERR_BUFFER_TOO_SMALL),
 *                    for callers that build fixed and retunable stages alike.
 * @return ::SMS_OK, ::SMS_ERR_NULL, the config's status, ::SMS_ERR_BUFFER_TOO_SMALL (config
 *         needs more than slot_cells, or n_cells < slot_cells), ::SMS_ERR_TOO_LONG. Nothing
 *         is written on error.
 * @param t           instance to fill; untouched on error
 * @param config      the first filter (config.h for ranges)
 * @param Ts          sample period [s], finite, > 0
 * @param n_cells     length of memory in cells
 */
SMS_API sms_status sms_tunable_init(sms_tunable *t, const sms_stage_config *config, double Ts,
                                    size_t slot_cells, sms_memory_cell *memory, size_t n_cells);
/**
 * @brief Switch to config from the next sample on (the rule above). O(design + delay line).
 * @return ::SMS_OK; ::SMS_ERR_NULL; ::SMS_ERR_RETUNE_BUSY (the previous switch is still in
 *         progress: see sms_tunable_switching()); the config's status at the tunable's Ts;
 *         ::SMS_ERR_BUFFER_TOO_SMALL (it needs more memory than a slot holds, or the tunable
 *         has one slot); ::SMS_ERR_KIND (config, or the active filter, is
 *         ::SMS_SHAPER_IMPULSES: a saved state names user-defined impulses by a checksum
 *         only, so a switch to or from them could not be restored; such a stage runs as
 *         built). On error nothing changes.
 * @param t      the tunable, built by sms_tunable_init()
 * @param config the new filter, at the tunable's Ts
 */
SMS_API sms_status sms_tunable_retune(sms_tunable *t, const sms_stage_config *config);
/** @brief 1 while a switch is in progress (a retune would be refused), else 0. O(1).
 * @param t      the tunable (read only)
 * @return 1 or 0
 */
SMS_API int sms_tunable_switching(const sms_tunable *t);
/**
 * @brief Samples until the switch in progress ends (0 when none is): exactly the samples left
 * for a FIR old filter; for an old notch an upper bound from its poles and its current free
 * response (tunable.c), at most its exact settling bound (sms_notch_settle_bound()). Not for
 * the per-sample path (uses libm).
 * @param t      the tunable (read only)
 * @return samples, >= 0
 */
SMS_API double sms_tunable_switch_left(const sms_tunable *t);
/** @brief Put the stage at rest at rest (any switch in progress ends; the active filter stays).
 * @param t      the tunable, built by sms_tunable_init()
 * @param rest   finite, |rest| <= sms_tunable_input_max()
 */
SMS_API void sms_tunable_reset(sms_tunable *t, sms_real rest);
/** @brief Filter one sample in place.
 * @param t      the tunable, built by sms_tunable_init()
 * @param x      in: the input x[n], |x| <= sms_tunable_input_max(); out: the output y[n]
 */
SMS_API void sms_tunable_step(sms_tunable *t, sms_real *x);
/** @brief Filter n samples; in == out allowed, other overlaps not. The same, bit for bit, as n
 * calls of sms_tunable_step() and any split into blocks.
 * @param t      the tunable, built by sms_tunable_init()
 * @param in     n inputs
 * @param out    n outputs; may be in itself
 * @param n      number of samples, any
 */
SMS_API void sms_tunable_process(sms_tunable *t, const sms_real *in, sms_real *out, size_t n);
/** @brief The active filter (the stage a retune last built).
 * @param t      the tunable (read only)
 * @return the active stage, inside t (valid while t is)
 */
SMS_API const sms_stage *sms_tunable_active(const sms_tunable *t);
/** @brief The configuration of the active filter, rebuilt from its saved identity (config.h):
 * the fields its kind reads, the others at sms_stage_config_default(). For
 * ::SMS_SHAPER_IMPULSES (never retuned) only the kind: the caller holds the impulses.
 * @param t      the tunable (read only)
 * @return the configuration (by value)
 */
SMS_API sms_stage_config sms_tunable_config(const sms_tunable *t);
/** @brief Input range: the smaller of the two filters' sms_stage_input_max() during a switch,
 * the active one's otherwise. O(1).
 * @param t      the tunable (read only)
 * @return the largest |input|, in (0, ::SMS_INPUT_MAX]
 */
SMS_API double sms_tunable_input_max(const sms_tunable *t);
/** @brief Input limit before the cap at ::SMS_INPUT_MAX (sms_stage_input_limit()): the smaller
 * of the two filters' during a switch (the old one runs on the held h, the new one on the
 * inputs since: each sees only inputs within both limits), the active one's otherwise. The
 * chain's ranges below divide it by each stage's R_i and cap only then. O(1).
 * @param t      the tunable (read only)
 * @return L, in [sms_tunable_input_max(), REAL_MAX]
 */
SMS_API double sms_tunable_input_limit(const sms_tunable *t);
/** @brief Bound G on |y - r| / max |x - r| (sms_stage_gain_bound()): G_B of the active filter,
 * 1 + 2 G_A + 2 G_B during a switch (the two shares and their different rests). O(1).
 * @param t      the tunable (read only)
 * @return G >= 1
 */
SMS_API double sms_tunable_gain_bound(const sms_tunable *t);
/** @brief Doubles sms_tunable_get_state() writes: ::SMS_TUNABLE_STATE_HEAD, then the active
 * stage's state (sms_stage_state_count()), then the old one's during a switch.
 * @param t      the tunable (read only)
 * @return the count
 */
SMS_API size_t sms_tunable_state_count(const sms_tunable *t);
/** @brief The length of the saved state that opens src, as t would read it: the
 * sms_tunable_state_count() of the tunable that saved it, if t is in its configurations (as
 * sms_tunable_set_state() requires). It differs from sms_tunable_state_count() of t when t is
 * switching and the state is not, or the other way round: a state saved during a switch,
 * loaded into a tunable brought there by sms_tunable_init() with the old configuration and
 * sms_tunable_retune() to the active one, whose freshly built old notch is at rest, so that
 * the retune started no switch (nothing to fade yet; the state's old values are loaded with it).
 * @param t      the tunable (read only)
 * @param src    a saved state of a tunable (and perhaps more values after it)
 * @param n      the doubles readable at src
 * @return ::SMS_TUNABLE_STATE_HEAD + 2 ::SMS_STATE_IDENTITY_COUNT + the active stage's
 *         sms_stage_state_count() + during a switch (src's switching field 1) that of the
 *         stage built in t's other slot, if any; 0 if t or src is NULL or n is shorter than
 *         the head and both identities (the count is then not known)
 */
SMS_API size_t sms_tunable_saved_state_count(const sms_tunable *t, const double *src, size_t n);
/** @brief Write the state: head, the stages' states (each opening with its configuration
 * identity, config.h).
 * @param t      the tunable (read only)
 * @param dst    sms_tunable_state_count() doubles
 */
SMS_API void sms_tunable_get_state(const sms_tunable *t, double *dst);
/**
 * @brief Restore a state written by sms_tunable_get_state() of a tunable in the same
 * configuration: the same Ts, precision and slot size, the same active configuration and, for
 * a state saved during a switch, the old configuration built in the other slot (as the retune
 * that started the switch left it). To restore a state of another configuration, first bring
 * the tunable there (sms_tunable_state_configs() tells which: sms_tunable_init() with the old
 * one and sms_tunable_retune() to the active one, or init with the active one). Checks
 * everything before writing: on error nothing changes.
 * @return ::SMS_OK, ::SMS_ERR_NULL, ::SMS_ERR_STATE_FORMAT, ::SMS_ERR_STATE_PRECISION,
 *         ::SMS_ERR_STATE_KIND, ::SMS_ERR_STATE_TS, ::SMS_ERR_STATE (another slot size or
 *         switch, n or a value that does not fit), or a stage's status naming the first field
 *         of its identity that differs.
 * @param t      the tunable, built by sms_tunable_init(); untouched on error
 * @param src    the saved state
 * @param n      its length in doubles, sms_tunable_state_count() of the saving tunable
 */
SMS_API sms_status sms_tunable_set_state(sms_tunable *t, const double *src, size_t n);
/** @brief Would sms_tunable_set_state() accept this vector? Writes nothing.
 * @param t      the tunable (read only)
 * @param src    the saved state
 * @param n      its length in doubles
 * @return what sms_tunable_set_state() would return
 */
SMS_API sms_status sms_tunable_check_state(const sms_tunable *t, const double *src, size_t n);
/** @brief Is src, besides what sms_tunable_check_state() accepts, a state a run with every
 * input |x| <= x_max could reach? The last input and the held h within x_max, and each
 * filter's part as sms_stage_check_state_range() with x_max (the old filter ran on h since the
 * switch). For loading states that come from outside. Writes nothing.
 * @return as sms_tunable_check_state(), or ::SMS_ERR_STATE.
 * @param t      the tunable (read only)
 * @param src    the saved state
 * @param n      its length in doubles
 * @param x_max  the largest |input| of the run, at most sms_tunable_input_max()
 */
SMS_API sms_status sms_tunable_check_state_range(const sms_tunable *t, const double *src,
                                                 size_t n, double x_max);
/**
 * @brief The configurations a saved tunable state belongs to, read from its stages'
 * identities (the fields each kind reads; the others at sms_stage_config_default()).
 * @param active     receives the active configuration
 * @param old        receives the fading one (or NULL); written only when *switching is 1
 * @param switching  receives 1 if the state was saved during a switch
 * @return ::SMS_OK, ::SMS_ERR_NULL, ::SMS_ERR_STATE_FORMAT, ::SMS_ERR_STATE_PRECISION,
 *         ::SMS_ERR_STATE_KIND, ::SMS_ERR_STATE (too short, or a kind that is no stage);
 *         ::SMS_ERR_KIND: the stage is ::SMS_SHAPER_IMPULSES, whose identity holds a checksum
 *         of the impulses: build the tunable with the caller's own configuration, and
 *         sms_tunable_set_state() refuses the state if the impulses differ.
 * @param src        the saved state of a tunable
 * @param n          its length in doubles
 */
SMS_API sms_status sms_tunable_state_configs(const double *src, size_t n, sms_stage_config *active,
                                             sms_stage_config *old, int *switching);
/** @brief After copying the tunable and its memory (cell for cell), point the copy at it.
 * @param t      the copied tunable
 * @param memory the copy of its memory
 */
SMS_API void sms_tunable_rebind(sms_tunable *t, sms_memory_cell *memory);

/** @brief Retunable stages in series: y = T_{n-1}( ... T_0(x)), each an ::sms_tunable. The
 * caller owns the ::sms_tunable_chain, the array of n ::sms_tunable and one memory block, laid
 * out stage after stage (2 slot_cells[i] cells each). */
typedef struct sms_tunable_chain {
    sms_tunable *stages;        /**< caller array of n_stages tunables, first applied first */
    size_t n_stages;            /**< 1 .. ::SMS_CHAIN_MAX_STAGES */
    sms_memory_cell *memory;    /**< the stages' memory, stage after stage */
    size_t memory_len;          /**< cells in use: sum of 2 slot_cells[i] */
} sms_tunable_chain;

/** @brief Cells a tunable chain with these slot sizes needs (sum of 2 slot_cells[i]).
 * @return ::SMS_OK, ::SMS_ERR_NULL, ::SMS_ERR_ORDER (n = 0 or > ::SMS_CHAIN_MAX_STAGES),
 *         ::SMS_ERR_TOO_LONG.
 * @param slot_cells n slot sizes, from sms_tunable_slot_cells()
 * @param n          stages, 1 .. ::SMS_CHAIN_MAX_STAGES
 * @param n_cells    receives the sum of 2 slot_cells[i]
 */
SMS_API sms_status sms_tunable_chain_memory_size(const size_t *slot_cells, size_t n,
                                                 size_t *n_cells);
/** @brief Validate every config against its slot, then build all stages at rest at 0.
 * @return as sms_tunable_init() for the first failing stage, ::SMS_ERR_ORDER, or
 *         ::SMS_ERR_BUFFER_TOO_SMALL (n_cells below sms_tunable_chain_memory_size()). On error
 *         nothing is touched.
 * @param chain      instance to fill; untouched on error
 * @param stages     caller array of n tunables
 * @param configs    n first filters, first applied first
 * @param slot_cells n slot sizes, from sms_tunable_slot_cells()
 * @param n          stages, 1 .. ::SMS_CHAIN_MAX_STAGES
 * @param Ts         sample period [s], finite, > 0
 * @param memory     caller memory, kept by the chain
 * @param n_cells    length of memory in cells, >= sms_tunable_chain_memory_size()
 */
SMS_API sms_status sms_tunable_chain_init(sms_tunable_chain *chain, sms_tunable *stages,
                                          const sms_stage_config *configs,
                                          const size_t *slot_cells, size_t n, double Ts,
                                          sms_memory_cell *memory, size_t n_cells);
/** @brief sms_tunable_retune() of stage i (::SMS_ERR_ORDER if i >= n_stages).
 * @param chain  the tunable chain, built by sms_tunable_chain_init()
 * @param i      the stage, 0 .. n_stages - 1
 * @param config its new filter
 * @return as sms_tunable_retune(), or ::SMS_ERR_ORDER
 */
SMS_API sms_status sms_tunable_chain_retune(sms_tunable_chain *chain, size_t i,
                                            const sms_stage_config *config);
/** @brief Put every stage at rest at `rest` (sms_tunable_reset(): switches in progress end).
 * @param chain  the tunable chain
 * @param rest   finite, |rest| <= sms_tunable_chain_input_max() */
SMS_API void sms_tunable_chain_reset(sms_tunable_chain *chain, sms_real rest);
/** @brief Filter one sample in place through every stage in order.
 * @param chain  the tunable chain
 * @param x      in: the input x[n], |x| <= sms_tunable_chain_input_max(); out: y[n] */
SMS_API void sms_tunable_chain_step(sms_tunable_chain *chain, sms_real *x);
/** @brief Filter n samples through all stages; in == out allowed.
 * @param chain  the tunable chain, built by sms_tunable_chain_init()
 * @param in     n inputs
 * @param out    n outputs; may be in itself
 * @param n      number of samples, any
 */
SMS_API void sms_tunable_chain_process(sms_tunable_chain *chain, const sms_real *in,
                                       sms_real *out, size_t n);
/** @brief 1 while any stage is switching.
 * @param chain  the tunable chain (read only)
 * @return 1 or 0
 */
SMS_API int sms_tunable_chain_switching(const sms_tunable_chain *chain);
/** @brief The FIR length of the active filters (sms_chain_length() of them).
 * @param chain  the tunable chain (read only)
 * @return the length [samples]
 */
SMS_API size_t sms_tunable_chain_length(const sms_tunable_chain *chain);
/** @brief Input range: sms_chain_input_max() of the active filters when no stage is switching;
 * during a switch the same bound with the stages' sms_tunable_input_limit() and
 * sms_tunable_gain_bound(): min(::SMS_INPUT_MAX, min_i L_i / R_i), R_0 = 1,
 * R_i = 1 + 2 G_0 ... G_{i-1}. Stage i's inputs are within R_i |x| (every stage maps
 * x - rest to y - rest with gain at most G, both of its filters during a switch together at
 * most 1 + 2 G_A + 2 G_B), and within L_i its sums are finite; each L_i enters before the cap
 * (capping it first would put a chain of two stages or more below ::SMS_INPUT_MAX / 3 during
 * every switch). O(stages).
 * @param chain  the tunable chain (read only)
 * @return the largest |input|, in (0, ::SMS_INPUT_MAX]
 */
SMS_API double sms_tunable_chain_input_max(const sms_tunable_chain *chain);
/**
 * @brief Input range from now until retunes still to come have ended: the smallest
 * sms_tunable_chain_input_max() the chain has while stage i (retuned[i] != 0) switches from its
 * active filter to a configuration of range input_max[i] and gain bound gain_bound[i]
 * (sms_stage_config_range() of it) and after, the other stages as they are. Each stage counts
 * with its smallest range and largest gain over those phases: its sms_tunable_input_max() and
 * sms_tunable_gain_bound() now, the switch's 1 + 2 G_new + 2 G_active and range
 * min(input_max[i], its filters' limits). Limits enter before the cap at ::SMS_INPUT_MAX
 * (sms_tunable_input_limit(), and input_max from sms_stage_config_limit()), which applies to
 * the result only: min(::SMS_INPUT_MAX, min_i L_i / R_i) over every phase; a capped input_max
 * (sms_stage_config_range()) gives a smaller, still valid bound. A retune narrows the range
 * when this is below
 * sms_tunable_chain_input_max(): inputs beyond it, held or in the filters' memory, would
 * overflow after it. O(stages).
 * @param chain       the tunable chain (read only)
 * @param retuned     n_stages flags: non-zero for a stage to be retuned
 * @param input_max   n_stages entries: the new configuration's limit L (sms_stage_config_limit(),
 *                    > 0, or its capped range; read only where retuned[i] != 0)
 * @param gain_bound  n_stages entries: the new configuration's gain bound (at least 1 up to
 *                    the rounding of its taps; read only where retuned[i] != 0)
 * @return the largest |input|, in (0, ::SMS_INPUT_MAX], at most sms_tunable_chain_input_max()
 */
SMS_API double sms_tunable_chain_retune_input_max(const sms_tunable_chain *chain,
                                                  const int *retuned, const double *input_max,
                                                  const double *gain_bound);
/** @brief sms_chain_hold() over the active filters: n samples of the constant x at a bounded
 * cost; a stage that is switching is first run sample by sample until its switch has ended.
 * Bit for bit n calls of sms_tunable_chain_step().
 * @param chain  the tunable chain, built by sms_tunable_chain_init()
 * @param x      the held input, finite, |x| <= sms_tunable_chain_input_max()
 * @param n      samples (0: nothing changes)
 * @param y      receives the last output (untouched when n = 0)
 */
SMS_API void sms_tunable_chain_hold(sms_tunable_chain *chain, sms_real x, uint64_t n,
                                    sms_real *y);
/** @brief Doubles of the saved state: the sum of sms_tunable_state_count() over the stages
 * (it grows while a stage is switching).
 * @param chain  the tunable chain (read only)
 * @return the count */
SMS_API size_t sms_tunable_chain_state_count(const sms_tunable_chain *chain);
/** @brief Write the state: each stage's sms_tunable_get_state() one after the other.
 * @param chain  the tunable chain (read only)
 * @param dst    sms_tunable_chain_state_count() doubles */
SMS_API void sms_tunable_chain_get_state(const sms_tunable_chain *chain, double *dst);
/** @brief Restore a state of sms_tunable_chain_get_state() (each stage as
 * sms_tunable_set_state(), its part's length sms_tunable_saved_state_count(); all checked
 * before any is written).
 * @param chain  the tunable chain, built by sms_tunable_chain_init(); untouched on error
 * @param src    the saved state
 * @param n      its length in doubles
 * @return ::SMS_OK, ::SMS_ERR_NULL, ::SMS_ERR_STATE (n does not fit), or the first failing
 *         stage's status of sms_tunable_set_state()
 */
SMS_API sms_status sms_tunable_chain_set_state(sms_tunable_chain *chain, const double *src,
                                               size_t n);
/** @brief After copying chain, stages and memory elsewhere, point the copy at them (the
 * stages' memory one after the other, n_slots slot_cells cells each).
 * @param chain  the copied chain
 * @param stages the copy of its tunables
 * @param memory the copy of its memory
 */
SMS_API void sms_tunable_chain_rebind(sms_tunable_chain *chain, sms_tunable *stages,
                                      sms_memory_cell *memory);

#ifdef __cplusplus
}
#endif
#endif
