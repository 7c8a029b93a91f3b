# SPDX-License-Identifier: Apache-2.0
cmake_minimum_required(VERSION 3.16)
# The shared library must export exactly the functions the public headers mark SMS_API:
# nothing else (hidden visibility works, no helper or libc symbol leaks) and none missing.
# The float library exports them under their link names, the usual name plus SUFFIX (_f32,
# precision.h): a function precision.h does not rename shows up here as missing.
# Variables: LIB (the .so), NM, HEADERS (directory of the public headers), SUFFIX.
execute_process(COMMAND ${NM} -D --defined-only ${LIB}
  RESULT_VARIABLE rc OUTPUT_VARIABLE table ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${NM} -D --defined-only ${LIB} failed: ${err}")
endif()
string(REGEX REPLACE "\n$" "" table "${table}")
string(REPLACE "\n" ";" lines "${table}")
set(exported)
foreach(line ${lines})
  # "<address> <type> <name>[@version]"; absolute version nodes (type A) are not code.
  if(line MATCHES "^[0-9a-fA-F]* *([A-Za-z]) ([^@ ]+)")
    if(NOT CMAKE_MATCH_1 STREQUAL "A")
      list(APPEND exported ${CMAKE_MATCH_2})
    endif()
  endif()
endforeach()

file(GLOB headers ${HEADERS}/*.h)
set(declared)
foreach(header ${headers})
  file(STRINGS ${header} api_lines REGEX "^[ \t]*SMS_API ")
  foreach(line ${api_lines})
    if(line MATCHES "([A-Za-z_][A-Za-z0-9_]*)[ \t]*\\(")
      list(APPEND declared ${CMAKE_MATCH_1}${SUFFIX})
    endif()
  endforeach()
endforeach()

list(LENGTH exported n_exported)
list(LENGTH declared n_declared)
if(n_declared EQUAL 0)
  message(FATAL_ERROR "no SMS_API declarations found under ${HEADERS}")
endif()
set(failures 0)
foreach(sym ${exported})
  if(NOT sym MATCHES "^sms_")
    message(SEND_ERROR "${LIB} exports ${sym}, which is not in the sms_ namespace")
  elseif(NOT sym IN_LIST declared)
    message(SEND_ERROR "${LIB} exports ${sym}, which no public header declares SMS_API")
  endif()
endforeach()
foreach(sym ${declared})
  if(NOT sym IN_LIST exported)
    message(SEND_ERROR "${sym} is declared SMS_API but ${LIB} does not export it (a float "
                       "link name missing from precision.h?)")
  endif()
endforeach()
message(STATUS "${LIB}: ${n_exported} exported symbols, ${n_declared} SMS_API declarations")
