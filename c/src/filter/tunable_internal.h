/* SPDX-License-Identifier: Apache-2.0 */
/* Internal: what the retunable stage's files share (tunable.c the switch, tunable_state.c the
 * saved state and configurations, tunable_chain.c the series). */
#ifndef SMS_TUNABLE_INTERNAL_H
#define SMS_TUNABLE_INTERNAL_H

#include "smoothshaper/tunable.h"

/* The first cell of slot 0 or 1. */
sms_memory_cell *sms_tunable_slot_memory(const sms_tunable *t, unsigned slot);

/* SMS_OK if config is valid at Ts and fits a slot of slot_cells; else its status or
 * SMS_ERR_BUFFER_TOO_SMALL. */
sms_status sms_tunable_fits(const sms_stage_config *config, double Ts, size_t slot_cells);

/* Start the old filter's fade (tunable.h): t->hold set, old the filter being replaced. */
void sms_tunable_begin_fade(sms_tunable *t, const sms_stage *old);

#endif
