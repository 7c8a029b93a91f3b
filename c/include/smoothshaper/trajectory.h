/**
 * @file trajectory.h
 * @brief Kinematic design, online multi-point generation and B-spline filters (SPEC 3.7, 4.1, 4.4).
 * OWNER: trajectory work package.
 */
#ifndef SMOOTHSHAPER_TRAJECTORY_H
#define SMOOTHSHAPER_TRAJECTORY_H

#include "smoothshaper/chain.h"

#endif
