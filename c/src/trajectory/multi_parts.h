/* SPDX-License-Identifier: Apache-2.0 */
/* Internal: what the parts of the online multi-axis generator share. The public side and the
 * planning argument (transitions, landing, why no limit is exceeded) are in multi_generator.h.
 *   multi_generator.c  configuration: reach, memory, init, reset, the phase-synchronised duration
 *   multi_plan.c       planning one move of a group of axes (transitions, landing on the grid)
 *   multi_step.c       one sample: follow, blend into a new target, evaluate; then the stages
 *   multi_hold.c       n samples under a held target at a cost bounded whatever n
 *   multi_state.c      the configuration identity and the state vector
 *   multi_align.c      the common lag and the delays that pad every axis to it (align)
 * All in sms_real without libm on the per-sample path (roots by Newton), so a float build
 * stays single precision. */
#ifndef SMS_MULTI_PARTS_H
#define SMS_MULTI_PARTS_H

#include <float.h>
#include "smoothshaper/multi_generator.h"

#ifdef SMS_USE_FLOAT
#define REAL_EPS ((sms_real)FLT_EPSILON)
#define REAL_MAX ((sms_real)FLT_MAX)
#else
#define REAL_EPS ((sms_real)DBL_EPSILON)
#define REAL_MAX ((sms_real)DBL_MAX)
#endif

/* The axes a move drives and their limits. */
typedef struct sms_multi_group {
    size_t n;
    const sms_real *vmax, *amax, *jmax;
} sms_multi_group;

/* Plan a move from (p, V, a = 0) at move time 0 towards the target; the first sample of the
 * new move is at move time off. Returns 1 when planned; 0 when the move cannot be represented
 * in sms_real (a displacement, duration or velocity not finite, or more than MAX_MOVE_SAMPLES
 * samples: e.g. |d| = 1e300 with jmax = 1e-300), and then the generator is untouched. */
int sms_multi_plan(sms_multi_generator *g, size_t first, const sms_multi_group *G,
                   sms_multi_move *m, const sms_real *p, const sms_real *V, sms_real off);

/* Has an axis of the group [first, first + n) position limits (then it does not blend)? */
int sms_multi_group_bounded(const sms_multi_generator *g, size_t first, size_t n);

/* One sample of the profile alone (the targets, the moves, out), without the stages. */
void sms_multi_step_profile(sms_multi_generator *g, const sms_real *target, sms_real *out);

/* Alignment (multi_align.c; every function does nothing when the generator is not aligned):
 * each axis's chain lag and their maximum from a config; the cells of the delays' rings;
 * building them after the stages' memory; rebinding to a copy's memory past its stages;
 * reset (q at the position, v, a, j at 0); a block of one axis's signal; a sample of every
 * axis's four signals in out; the longest settle length; the absorbed state under the four
 * signals' constants x[4 i + m]; the phase advance; the state's count, writing, check and
 * reading (the delays' states after the stages'). */
sms_status sms_multi_align_lags(const sms_multi_generator_config *c, double Ts, double *axis_lag,
                                double *common);
sms_status sms_multi_align_cells(const sms_multi_generator_config *c, double Ts, size_t *cells);
void sms_multi_align_init(sms_multi_generator *g, const sms_multi_generator_config *c,
                          double Ts, sms_memory_cell *memory);
void sms_multi_align_rebind(sms_multi_generator *g, sms_memory_cell *memory);
void sms_multi_align_reset(sms_multi_generator *g, const sms_real *position);
void sms_multi_align_process(sms_multi_generator *g, size_t axis, size_t signal, sms_real *x,
                             size_t n);
void sms_multi_align_step(sms_multi_generator *g, sms_real *out);
uint64_t sms_multi_align_settle_length(const sms_multi_generator *g);
void sms_multi_align_settle(sms_multi_generator *g, const sms_real *x, uint64_t n);
void sms_multi_align_advance(sms_multi_generator *g, uint64_t n);
size_t sms_multi_align_state_count(const sms_multi_generator *g);
void sms_multi_align_get_state(const sms_multi_generator *g, double *dst);
/* The largest |input| of axis i's chain for signal m (0 q, 1 v, 2 a, 3 j) in a run: the
 * chain's input range for q, the limits to the reported values' tolerance for the others. */
double sms_multi_signal_range(const sms_multi_generator *g, size_t i, size_t m);
/* The alignment delays' part of a saved state: each delay's own check, and its ring within
 * what its chain can output. */
sms_status sms_multi_align_check_state(const sms_multi_generator *g, const double *src);
void sms_multi_align_set_state(sms_multi_generator *g, const double *src);

/* Per-axis plan modes (multi_sync.c): reset at rest; one sample of the profile towards a
 * target (taken first) or under the held one; step()'s positions at rest as a target; is a
 * target new; busy; n samples of index only (nothing pending, the request held); re-form an
 * axis's plan from its saved start (1: formed); is a saved start state one a plan can start
 * from. */
void sms_multi_sync_reset(sms_multi_generator *g, const sms_real *position);
void sms_multi_sync_step_profile(sms_multi_generator *g, const sms_multi_target *t,
                                 sms_real *out);
void sms_multi_sync_step_held(sms_multi_generator *g, sms_real *out);
void sms_multi_sync_rest_target(const sms_multi_generator *g, const sms_real *position,
                                sms_multi_target *t);
int sms_multi_sync_fresh(const sms_multi_generator *g, const sms_multi_target *t);
/* Does sms_multi_generator_step() take x as axis i's target position (finite, and inside
 * the axis's position limits if it has them; else the previous one is kept)? */
int sms_multi_takes_position(const sms_multi_generator *g, size_t i, sms_real x);
/* Does a valid request wait for its plans (not the running plans' target)? */
int sms_multi_sync_fresh_aim(const sms_multi_generator *g);
int sms_multi_sync_busy(const sms_multi_generator *g);
void sms_multi_sync_skip(sms_multi_generator *g, uint64_t n);
int sms_multi_sync_replan_axis(const sms_multi_generator *g, size_t i,
                               const sms_multi_target *t, sms_multi_axis_plan *ax);
int sms_multi_sync_start_ok(const sms_multi_generator *g, size_t i, double q, double v,
                            double a);

/* The stages and the alignment delays on one sample of the profile's output (in place). */
void sms_multi_filter_output(sms_multi_generator *g, sms_real *out);

/* The configuration identity a saved state starts with (SMS_MULTI_IDENTITY_COUNT doubles). */
void sms_multi_identity_write(const sms_multi_generator_config *c, double Ts,
                              double id[SMS_MULTI_IDENTITY_COUNT]);

#endif
