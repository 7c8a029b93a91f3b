# SPDX-License-Identifier: Apache-2.0
cmake_minimum_required(VERSION 3.16)
# Fails if a program linked with --gc-sections (per_sample_probe.c: only step/process/reset
# referenced, or the init from precomputed coefficients) still imports a symbol that the C
# math library defines: the per-sample path and the firmware path must not call libm
# (docs/numerics.md, docs/firmware.md), whatever init does in the same translation unit.
# Variables: EXE (the linked probe), NM, LIBM (the math library's shared object), GROUP (label).
execute_process(COMMAND ${NM} -D --defined-only ${LIBM}
  RESULT_VARIABLE rc OUTPUT_VARIABLE libm_table ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${NM} -D --defined-only ${LIBM} failed: ${err}")
endif()
string(REGEX MATCHALL "[ \t][TtWwi] [A-Za-z_][A-Za-z0-9_]*" libm_entries "${libm_table}")
set(libm_symbols)
foreach(entry ${libm_entries})
  string(REGEX REPLACE "^[ \t][TtWwi] " "" name "${entry}")
  list(APPEND libm_symbols ${name})
endforeach()
list(LENGTH libm_symbols n_libm)
if(n_libm LESS 50)
  message(FATAL_ERROR "only ${n_libm} function symbols read from ${LIBM}: is it the math library?")
endif()

execute_process(COMMAND ${NM} -u ${EXE} RESULT_VARIABLE rc OUTPUT_VARIABLE undefined ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${NM} -u ${EXE} failed: ${err}")
endif()
string(REGEX MATCHALL "U [A-Za-z_][A-Za-z0-9_]*" imports "${undefined}")
set(math_imports)
foreach(entry ${imports})
  string(REGEX REPLACE "^U " "" name "${entry}")
  if(name IN_LIST libm_symbols)
    list(APPEND math_imports ${name})
  endif()
endforeach()
if(math_imports)
  list(JOIN math_imports ", " listing)
  message(FATAL_ERROR "${GROUP} per-sample path reaches libm: ${listing}")
endif()
message(STATUS "${GROUP} per-sample path: no libm symbol among the imports of ${EXE}")
