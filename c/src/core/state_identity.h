/* SPDX-License-Identifier: Apache-2.0 */
/* Internal: the configuration identity that starts every saved state (config.h): a common head
 * (tag, format version, precision, object kind, Ts) and then the object's own fields, written
 * at init from the configuration, compared on load. One helper for every stateful object:
 * stages (smoother, shaper, notch), the generator, the B-spline, the multi-axis generator. */
#ifndef SMS_STATE_IDENTITY_INTERNAL_H
#define SMS_STATE_IDENTITY_INTERNAL_H

#include "smoothshaper/config.h"

/* Doubles of the common head: tag, version, precision, kind, Ts (SMS_STATE_IDENTITY_HEAD). */
enum { SMS_ID_TAG, SMS_ID_VERSION, SMS_ID_PRECISION, SMS_ID_KIND, SMS_ID_TS };

/* Write the common head into id[0 .. SMS_STATE_IDENTITY_HEAD): kind is an sms_kind for a stage
 * or an SMS_STATE_KIND_... value for another object. */
void sms_state_identity_head(double *id, double kind, double Ts);

/* SMS_OK if saved[0 .. SMS_STATE_IDENTITY_HEAD + n_fields) equals id (exact equality; NaN
 * differs); else the status of the first field that differs: SMS_ERR_STATE_FORMAT (tag,
 * version), SMS_ERR_STATE_PRECISION, SMS_ERR_STATE_KIND, SMS_ERR_STATE_TS, then
 * field_status[i] for the object's field i. */
sms_status sms_state_identity_compare(const double *id, const double *saved, size_t n_fields,
                                      const sms_status *field_status);

/* The identity of (config, Ts) for a stage of this build (SMS_STATE_IDENTITY_COUNT doubles):
 * fields the kind does not read are 0. */
void sms_state_identity(const sms_stage_config *config, double Ts,
                        double identity[SMS_STATE_IDENTITY_COUNT]);

/* sms_state_identity_compare() of a stage identity. */
sms_status sms_state_identity_check(const double identity[SMS_STATE_IDENTITY_COUNT],
                                    const double *saved);

#endif
