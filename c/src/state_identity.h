/* Internal: the configuration identity that starts every saved stage state (config.h,
 * SMS_STATE_IDENTITY_COUNT): written at init from the config and Ts, compared on load. */
#ifndef SMS_STATE_IDENTITY_INTERNAL_H
#define SMS_STATE_IDENTITY_INTERNAL_H

#include "smoothshaper/config.h"

/* The identity of (config, Ts) for a stage of this build: fields the kind does not read are 0. */
void sms_state_identity(const sms_stage_config *config, double Ts,
                        double identity[SMS_STATE_IDENTITY_COUNT]);

/* SMS_OK if saved starts with identity; else the status naming the first field that differs
 * (SMS_ERR_STATE_FORMAT for another tag or version). */
sms_status sms_state_identity_check(const double identity[SMS_STATE_IDENTITY_COUNT],
                                    const double *saved);

#endif
