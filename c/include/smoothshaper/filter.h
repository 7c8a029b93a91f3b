/* SPDX-License-Identifier: Apache-2.0 */
/**
 * @file filter.h
 * @brief The filter area: the four smoother families (smoother.h), the input shapers
 * (shaper.h), the notch (notch.h), one stage over all of them (stage.h), stages in series
 * (chain.h), stages retuned while they run (tunable.h), lags and the fractional delay that
 * aligns them (align.h), the scheduled ZV^n shaper (scheduled.h), the design of a stage for a
 * vibration mode (design.h) and the precomputed coefficients a firmware target builds its
 * stages from without designing them (coeffs.h).
 *
 * Builds on the core area only (core.h; docs/architecture.md). design.h also declares the
 * mode identification, whose area header is identify.h.
 */
#ifndef SMOOTHSHAPER_FILTER_H
#define SMOOTHSHAPER_FILTER_H

#include "smoothshaper/core.h"
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

#endif
