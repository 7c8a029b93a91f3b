/* SPDX-License-Identifier: Apache-2.0 */
/* Internal: what the parts of the online multi-axis generator share. The public side and the
 * planning argument (transitions, landing, why no limit is exceeded) are in multi_generator.h.
 *   multi_generator.c  configuration: reach, memory, init, reset, the phase-synchronised duration
 *   multi_plan.c       planning one move of a group of axes (transitions, landing on the grid)
 *   multi_step.c       one sample: follow, blend into a new target, evaluate; then the stages
 *   multi_hold.c       n samples under a held target at a cost bounded whatever n
 *   multi_state.c      the configuration identity and the state vector
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

/* One sample of the profile alone (the targets, the moves, out), without the stages. */
void sms_multi_step_profile(sms_multi_generator *g, const sms_real *target, sms_real *out);

/* The configuration identity a saved state starts with (SMS_MULTI_IDENTITY_COUNT doubles). */
void sms_multi_identity_write(const sms_multi_generator_config *c, double Ts,
                              double id[SMS_MULTI_IDENTITY_COUNT]);

#endif
