cmake_minimum_required(VERSION 3.16)
# Cross-compiles every c/src/*.c for a Cortex-M4F (hard float, single-precision FPU) in both
# precisions with the library's strict C99 flags, and prints the code size of each build.
# Variables: SOURCE_DIR (repository root), WORK_DIR (scratch). Prints "SKIPPED: <reason>"
# (the ctest skip marker) when arm-none-eabi-gcc is not on PATH.
find_program(ARM_GCC arm-none-eabi-gcc)
if(NOT ARM_GCC)
  message("SKIPPED: arm-none-eabi-gcc not on PATH (apt-get install gcc-arm-none-eabi)")
  return()
endif()
get_filename_component(arm_bin ${ARM_GCC} DIRECTORY)
find_program(ARM_SIZE arm-none-eabi-size HINTS ${arm_bin})

file(GLOB sources ${SOURCE_DIR}/c/src/*.c)
set(target_flags -mcpu=cortex-m4 -mthumb -mfloat-abi=hard -mfpu=fpv4-sp-d16)
# -ffreestanding: no hosted-library assumptions; <math.h>/<string.h> come from newlib.
set(strict_flags -std=c99 -Wall -Wextra -Werror -pedantic -Wshadow -Wstrict-prototypes
    -Wmissing-prototypes -O2 -ffreestanding -ffunction-sections -fdata-sections)
file(REMOVE_RECURSE ${WORK_DIR})

foreach(precision float double)
  set(defines)
  if(precision STREQUAL "float")
    set(defines -DSMS_USE_FLOAT)
  endif()
  set(objects)
  foreach(src ${sources})
    get_filename_component(name ${src} NAME_WE)
    set(obj ${WORK_DIR}/${precision}/${name}.o)
    file(MAKE_DIRECTORY ${WORK_DIR}/${precision})
    execute_process(COMMAND ${ARM_GCC} ${target_flags} ${strict_flags} ${defines}
      -I${SOURCE_DIR}/c/include -I${SOURCE_DIR}/c/src -c ${src} -o ${obj}
      RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
    if(NOT rc EQUAL 0)
      message(SEND_ERROR "cortex-m4 ${precision}: ${name}.c does not compile:\n${out}${err}")
      set(failed TRUE)
    else()
      list(APPEND objects ${obj})
    endif()
  endforeach()
  if(failed)
    message(FATAL_ERROR "cortex-m4 ${precision}: some sources do not compile (above)")
  endif()
  list(LENGTH objects n)
  if(ARM_SIZE)
    execute_process(COMMAND ${ARM_SIZE} -t ${objects} OUTPUT_VARIABLE sizes RESULT_VARIABLE rc)
    string(REGEX MATCH "[ \t]*([0-9]+)[ \t]+([0-9]+)[ \t]+([0-9]+)[^\n]*\\(TOTALS\\)" totals "${sizes}")
    message(STATUS "cortex-m4 ${precision}: ${n} sources, text ${CMAKE_MATCH_1} B, data "
                   "${CMAKE_MATCH_2} B, bss ${CMAKE_MATCH_3} B (all objects, before gc-sections)\n${sizes}")
  else()
    message(STATUS "cortex-m4 ${precision}: ${n} sources compiled (no arm-none-eabi-size)")
  endif()
endforeach()
