/* SPDX-License-Identifier: Apache-2.0 */
/**
 * @file motion.h
 * @brief The trajectory area: the kinematic design, the online single-axis generator and the
 * B-spline filters (trajectory.h), and the online multi-axis generator (multi_generator.h).
 *
 * trajectory.h keeps its single-axis content, so the whole area has this header of its own.
 * Builds on the filter and core areas (docs/architecture.md).
 */
#ifndef SMOOTHSHAPER_MOTION_H
#define SMOOTHSHAPER_MOTION_H

#include "smoothshaper/trajectory.h"
#include "smoothshaper/multi_generator.h"

#endif
