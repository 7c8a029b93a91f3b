/* SPDX-License-Identifier: Apache-2.0 */
/**
 * @file identify.h
 * @brief The identify area: a vibration mode (::sms_mode) from two peaks of a free decay or
 * from a sampled record, sms_identify_from_peaks() and sms_identify_from_record().
 *
 * They are declared in design.h next to the design they feed, sms_design_for_mode(), where
 * existing code includes them; this header names the area (docs/architecture.md). It builds on
 * the filter and core areas.
 */
#ifndef SMOOTHSHAPER_IDENTIFY_H
#define SMOOTHSHAPER_IDENTIFY_H

#include "smoothshaper/design.h"

#endif
