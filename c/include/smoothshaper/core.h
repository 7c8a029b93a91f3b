/* SPDX-License-Identifier: Apache-2.0 */
/**
 * @file core.h
 * @brief The core area: the scalar type ::sms_real, status codes and their strings, stage kinds
 * and the stage configuration with its validation rules (types.h, config.h).
 *
 * Every other area builds on these and nothing here depends on another area
 * (docs/architecture.md).
 */
#ifndef SMOOTHSHAPER_CORE_H
#define SMOOTHSHAPER_CORE_H

#include "smoothshaper/types.h"
#include "smoothshaper/config.h"

#endif
