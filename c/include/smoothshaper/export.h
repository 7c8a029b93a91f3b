/* SPDX-License-Identifier: Apache-2.0 */
/**
 * @file export.h
 * @brief Symbol visibility. The shared library is built with hidden visibility and
 * `SMS_BUILDING_SHARED`; only functions marked ::SMS_API are exported.
 * Static builds (and the FMU, which compiles the sources in) define nothing.
 */
/**
 * @def SMS_API
 * @brief Marks a public function: exported from the shared library (dllexport when building
 * it on Windows, dllimport with `SMS_USING_SHARED`), empty in static builds.
 */
#ifndef SMOOTHSHAPER_EXPORT_H
#define SMOOTHSHAPER_EXPORT_H

#if defined(SMS_BUILDING_SHARED)
#  if defined(_WIN32)
#    define SMS_API __declspec(dllexport)
#  elif defined(__GNUC__)
#    define SMS_API __attribute__((visibility("default")))
#  else
#    define SMS_API
#  endif
#elif defined(SMS_USING_SHARED) && defined(_WIN32)
#  define SMS_API __declspec(dllimport)
#else
#  define SMS_API
#endif

#endif
