/* SPDX-License-Identifier: Apache-2.0 */
/**
 * @file smoothshaper.h
 * @brief Umbrella header: include this one.
 */
#ifndef SMOOTHSHAPER_H
#define SMOOTHSHAPER_H

#include "smoothshaper/types.h"
#include "smoothshaper/config.h"
#include "smoothshaper/smoother.h"
#include "smoothshaper/shaper.h"
#include "smoothshaper/notch.h"
#include "smoothshaper/stage.h"
#include "smoothshaper/chain.h"
#include "smoothshaper/coeffs.h"
#include "smoothshaper/tunable.h"
#include "smoothshaper/align.h"
#include "smoothshaper/scheduled.h"
#include "smoothshaper/design.h"
#include "smoothshaper/trajectory.h"
#include "smoothshaper/multi_generator.h"

#endif
