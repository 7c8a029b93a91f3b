/* Internal: continuous shaper designs (amplitudes and times), see shaper_designs.c. */
#ifndef SMS_SHAPER_DESIGNS_H
#define SMS_SHAPER_DESIGNS_H

#include "smoothshaper/shaper.h"

/* ZV^n order of a shaper kind (order field for ZVN), 0 for EI, EI2, MZV. */
unsigned sms_shaper_zv_order(const sms_stage_config *config);

/* Fill amp[] (sum 1) and time[] [s] (increasing, time[0] = 0) for a validated config; returns
 * the number of impulses (<= SMS_SHAPER_MAX_IMPULSES). */
size_t sms_shaper_design(const sms_stage_config *config, double *amp, double *time);

#endif
