# SPDX-License-Identifier: Apache-2.0
cmake_minimum_required(VERSION 3.16)
# Mixing precisions fails at link time (precision.h): precision_probe.c compiled for float and
# linked against the double library, and compiled for double and linked against the float
# library, must both fail with an undefined reference to a library function (the float name
# carries _f32, the double one does not); compiled and linked with the matching library it
# must link and print y[20] = 0.060473 (the README example's value).
# Variables: CC, PROBE (the source), INCLUDE (public headers), LIB_DOUBLE, LIB_FLOAT (static
# libraries), WORK_DIR, LIBM (link flag for libm, may be empty), FLAGS (the libraries'
# sanitizer flags, may be empty).
file(MAKE_DIRECTORY ${WORK_DIR})
set(failures 0)
foreach(case "float double" "double float" "double double" "float float")
  separate_arguments(pair UNIX_COMMAND "${case}")
  list(GET pair 0 compiled)
  list(GET pair 1 library)
  set(defines)
  if(compiled STREQUAL "float")
    set(defines -DSMS_USE_FLOAT)
  endif()
  if(library STREQUAL "float")
    set(lib ${LIB_FLOAT})
  else()
    set(lib ${LIB_DOUBLE})
  endif()
  set(exe ${WORK_DIR}/probe_${compiled}_on_${library})
  file(REMOVE ${exe})
  execute_process(COMMAND ${CC} -std=c99 ${FLAGS} ${defines} -I${INCLUDE} ${PROBE} ${lib} ${LIBM}
                          -o ${exe}
    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(compiled STREQUAL library)
    if(NOT rc EQUAL 0)
      message(SEND_ERROR "${compiled} code against the ${library} library does not link:\n${err}")
      math(EXPR failures "${failures} + 1")
      continue()
    endif()
    execute_process(COMMAND ${exe} RESULT_VARIABLE run_rc OUTPUT_VARIABLE printed)
    if(NOT run_rc EQUAL 0 OR NOT printed MATCHES "y\\[20\\] = 0\\.060473")
      message(SEND_ERROR "${compiled} on ${library}: printed '${printed}' (exit ${run_rc})")
      math(EXPR failures "${failures} + 1")
    else()
      message(STATUS "${compiled} code on the ${library} library links and prints ${printed}")
    endif()
  else()
    set(missing "sms_[a-z_]+")
    if(compiled STREQUAL "float")
      set(missing "sms_[a-z_]+_f32")
    endif()
    if(rc EQUAL 0)
      message(SEND_ERROR "${compiled} code linked against the ${library} library: precisions "
                         "mix silently")
      math(EXPR failures "${failures} + 1")
    elseif(NOT err MATCHES "undefined reference to [`']?(${missing})")
      message(SEND_ERROR "${compiled} code on the ${library} library failed, but not on an "
                         "undefined library function:\n${err}")
      math(EXPR failures "${failures} + 1")
    else()
      string(REGEX MATCH "undefined reference to [`']?(${missing})" first "${err}")
      message(STATUS "${compiled} code on the ${library} library fails to link: ${first}")
    endif()
  endif()
endforeach()
if(failures GREATER 0)
  message(FATAL_ERROR "${failures} precision link check(s) failed")
endif()
