# SPDX-License-Identifier: Apache-2.0
# The long mode's portability run (ctest label "long"): this source tree built again as on a
# platform whose long double is a double (SMS_LONG_DOUBLE_AS_DOUBLE: MSVC x64, Apple arm64,
# Cortex-M), its whole ctest suite (the FMU tests with it; with mingw-w64 and wine, the win64
# FMU fuzz of WIN64_FUZZ_SEQUENCES sequences per model, default 1e4, built with a 64-bit long
# double as MSVC x64 has it), then the FMU fuzz campaign of FUZZ_SEQUENCES sequences per
# model, which must end with 0 failures (no FMU refuses a state it saved). Run with cmake -P;
# variables:
#   SOURCE_DIR  the source tree               WORK_DIR  the build tree of this run
#   GENERATOR, MAKE_PROGRAM, C_COMPILER       PYTHON    the interpreter with fmpy (FMI headers)
#   FMI_HEADERS the FMI 2.0/3.0 headers       FUZZ_SEQUENCES  default 100000
#   WIN64_FUZZ_SEQUENCES  default 10000
cmake_minimum_required(VERSION 3.16)
if(NOT FUZZ_SEQUENCES)
  set(FUZZ_SEQUENCES 100000)
endif()
if(NOT WIN64_FUZZ_SEQUENCES)
  set(WIN64_FUZZ_SEQUENCES 10000)
endif()

function(run_checked what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  message(STATUS "${what}:\n${out}${err}")
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${what} failed (${rc})")
  endif()
endfunction()

run_checked("configure (long double as double)" ${CMAKE_COMMAND} -S ${SOURCE_DIR} -B ${WORK_DIR}
  -G ${GENERATOR} -DCMAKE_MAKE_PROGRAM=${MAKE_PROGRAM} -DCMAKE_C_COMPILER=${C_COMPILER}
  -DCMAKE_BUILD_TYPE=Release -DSMS_LONG_DOUBLE_AS_DOUBLE=ON -DSMS_BUILD_SHARED=OFF
  -DPython3_EXECUTABLE=${PYTHON} -DFMI2_HEADERS_DIR=${FMI_HEADERS}
  -DWIN64_FUZZ_SEQUENCES=${WIN64_FUZZ_SEQUENCES})
run_checked("build" ${CMAKE_COMMAND} --build ${WORK_DIR} -j2)
run_checked("ctest (long double as double)" ${CMAKE_CTEST_COMMAND} --test-dir ${WORK_DIR}
  --output-on-failure -j2)
foreach(model SmoothShaper TrajectoryGenerator MultiAxisGenerator ElasticPlant ServoDrive)
  run_checked("FMU fuzz ${model}, ${FUZZ_SEQUENCES} sequences"
    ${WORK_DIR}/fmu/test_fmu_fuzz_${model} ${FUZZ_SEQUENCES} 1)
endforeach()
