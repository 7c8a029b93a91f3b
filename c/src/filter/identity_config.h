/* SPDX-License-Identifier: Apache-2.0 */
/* Internal: a stage configuration from its identity (config.h, SMS_STATE_IDENTITY_COUNT
 * doubles). */
#ifndef SMS_IDENTITY_CONFIG_INTERNAL_H
#define SMS_IDENTITY_CONFIG_INTERNAL_H

#include "smoothshaper/stage.h"

/* The configuration an identity describes: the fields its kind reads, the others at
 * sms_stage_config_default(). 0 (and *out untouched) if the kind is no stage kind, an
 * integer field does not fit, or the kind is user-defined impulses (their identity holds a
 * checksum of the impulses, which gives no impulses back). */
int sms_identity_config(const double *id, sms_stage_config *out);

/* The configuration identity a built stage carries (NULL for a stage of no family). */
const double *sms_stage_identity(const sms_stage *stage);

#endif
