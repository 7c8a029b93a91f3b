# SPDX-License-Identifier: Apache-2.0
# Runs a win64 program under wine64 for ctest (cmake -P): EXE the program, ARGS its arguments
# (a ;-list), PREFIX the wine prefix to use (created on first use; the user's ~/.wine is never
# touched). Without EXE: only the check that wine runs, which creates the prefix. Prints
# "SKIPPED: <reason>" (the test's SKIP_REGULAR_EXPRESSION) without wine64, or when wine cannot
# start even its own cmd.exe: a broken tool, not a broken program. Otherwise the program's exit
# status decides.
cmake_minimum_required(VERSION 3.16)
find_program(WINE64 wine64 HINTS /usr/lib/wine /usr/lib64/wine /opt/wine-stable/bin)
if(NOT WINE64)
  message("SKIPPED: wine64 is not installed (scripts/install-cross-tools.sh installs it)")
  return()
endif()
get_filename_component(wine_dir ${WINE64} DIRECTORY)
set(env ${CMAKE_COMMAND} -E env --unset=DISPLAY WINEPREFIX=${PREFIX} WINEDEBUG=-all
    "PATH=${wine_dir}:$ENV{PATH}")
execute_process(COMMAND ${env} ${WINE64} cmd /c echo wine-runs TIMEOUT 600
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT out MATCHES "wine-runs")
  message("SKIPPED: wine64 cannot start a program on this machine (${rc}): ${out}${err}")
  return()
endif()
if(NOT EXE)
  return()
endif()
execute_process(COMMAND ${env} ${WINE64} ${EXE} ${ARGS} RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${EXE} ${ARGS} under wine64 exited with ${rc}")
endif()
