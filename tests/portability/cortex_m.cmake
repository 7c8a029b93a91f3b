# SPDX-License-Identifier: Apache-2.0
cmake_minimum_required(VERSION 3.16)
# Cross-compiles every C source under c/src (all areas) for a Cortex-M4F (hard float,
# single-precision FPU) in both precisions with the library's strict C99 flags, and prints the
# code size of each build.
# Then links per_sample_probe.c (step/process/reset only) against those objects with newlib
# and --gc-sections, fails if any newlib libm function survives in the image, and prints
# the size of what the per-sample path keeps: the probe's text + rodata minus that of an
# empty program with the same start-up code, i.e. the library's step/process/reset functions,
# the dispatch and the newlib memset the smoothers' reset calls. The float filters probe is
# also built from -Os objects (the size-optimised firmware build), and the bytes of each
# family's instance on this target are printed (the memory of a stage, stage.h).
# Variables: SOURCE_DIR (repository root), WORK_DIR (scratch). Prints "SKIPPED: <reason>"
# (the ctest skip marker) when arm-none-eabi-gcc is not on PATH.
find_program(ARM_GCC arm-none-eabi-gcc)
if(NOT ARM_GCC)
  message("SKIPPED: arm-none-eabi-gcc not on PATH (apt-get install gcc-arm-none-eabi)")
  return()
endif()
get_filename_component(arm_bin ${ARM_GCC} DIRECTORY)
find_program(ARM_SIZE arm-none-eabi-size HINTS ${arm_bin})
find_program(ARM_NM arm-none-eabi-nm HINTS ${arm_bin})
if(NOT ARM_SIZE OR NOT ARM_NM)
  message(FATAL_ERROR "arm-none-eabi-gcc found but not arm-none-eabi-size / -nm next to it")
endif()

file(GLOB_RECURSE sources ${SOURCE_DIR}/c/src/*.c)
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
  execute_process(COMMAND ${ARM_SIZE} -t ${objects} OUTPUT_VARIABLE sizes RESULT_VARIABLE rc)
  string(REGEX MATCH "[ \t]*([0-9]+)[ \t]+([0-9]+)[ \t]+([0-9]+)[^\n]*\\(TOTALS\\)" totals "${sizes}")
  message(STATUS "cortex-m4 ${precision}: ${n} sources, text ${CMAKE_MATCH_1} B, data "
                 "${CMAKE_MATCH_2} B, bss ${CMAKE_MATCH_3} B (all objects, before gc-sections)\n${sizes}")
  set(objects_${precision} ${objects})
endforeach()

# The float build again at -Os, for the size-optimised figure of the filters probe below.
set(objects_float_Os)
foreach(src ${sources})
  get_filename_component(name ${src} NAME_WE)
  set(obj ${WORK_DIR}/float_Os/${name}.o)
  file(MAKE_DIRECTORY ${WORK_DIR}/float_Os)
  string(REPLACE "-O2" "-Os" os_flags "${strict_flags}")
  execute_process(COMMAND ${ARM_GCC} ${target_flags} ${os_flags} -DSMS_USE_FLOAT
    -I${SOURCE_DIR}/c/include -I${SOURCE_DIR}/c/src -c ${src} -o ${obj}
    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "cortex-m4 float -Os: ${name}.c does not compile:\n${out}${err}")
  endif()
  list(APPEND objects_float_Os ${obj})
endforeach()

# Bytes of each family's instance and of the stage descriptor on this target (nm -S of arrays
# sized by sizeof: the compiler's own answer, no target run needed).
foreach(precision float double)
  set(defines)
  if(precision STREQUAL "float")
    set(defines -DSMS_USE_FLOAT)
  endif()
  file(WRITE ${WORK_DIR}/sizes.c "#include <smoothshaper/smoothshaper.h>\n"
    "char size_sms_stage[sizeof(sms_stage)];\nchar size_sms_smoother[sizeof(sms_smoother)];\n"
    "char size_sms_shaper[sizeof(sms_shaper)];\nchar size_sms_shaper_tap[sizeof(sms_shaper_tap)];\n"
    "char size_sms_notch[sizeof(sms_notch)];\nchar size_sms_memory_cell[sizeof(sms_memory_cell)];\n")
  execute_process(COMMAND ${ARM_GCC} ${target_flags} ${strict_flags} ${defines}
    -I${SOURCE_DIR}/c/include -c ${WORK_DIR}/sizes.c -o ${WORK_DIR}/sizes_${precision}.o
    RESULT_VARIABLE rc ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "cortex-m4 ${precision}: sizes.c does not compile:\n${err}")
  endif()
  execute_process(COMMAND ${ARM_NM} -S ${WORK_DIR}/sizes_${precision}.o OUTPUT_VARIABLE table)
  string(REGEX MATCHALL "[0-9a-f]+ [BC] size_[a-z_]+" rows "${table}")
  set(listing)
  foreach(row ${rows})
    string(REGEX REPLACE "^([0-9a-f]+) [BC] size_([a-z_]+)$" "\\2 \\1" pair "${row}")
    string(REGEX REPLACE " .*" "" type "${pair}")
    string(REGEX REPLACE ".* " "" hex "${pair}")
    math(EXPR bytes "0x${hex}")
    list(APPEND listing "${type} ${bytes}")
  endforeach()
  list(JOIN listing ", " listing)
  message(STATUS "cortex-m4 ${precision}: sizeof ${listing} B")
endforeach()

# Per-sample path on the target: which newlib libm functions does a --gc-sections image of
# step/process/reset keep? Compared against the functions libm.a defines for this multilib.
set(link_flags ${target_flags} -O2 --specs=nosys.specs -Wl,--gc-sections)
execute_process(COMMAND ${ARM_GCC} ${target_flags} -print-file-name=libm.a
  OUTPUT_VARIABLE libm_archive OUTPUT_STRIP_TRAILING_WHITESPACE)
execute_process(COMMAND ${ARM_NM} --defined-only ${libm_archive}
  OUTPUT_VARIABLE libm_table ERROR_QUIET)
string(REGEX MATCHALL " [TW] [A-Za-z_][A-Za-z0-9_]*" libm_entries "${libm_table}")
set(libm_symbols)
foreach(entry ${libm_entries})
  string(REGEX REPLACE "^ [TW] " "" name "${entry}")
  list(APPEND libm_symbols ${name})
endforeach()
list(LENGTH libm_symbols n_libm)
if(n_libm LESS 50)
  message(FATAL_ERROR "only ${n_libm} functions read from ${libm_archive}")
endif()

# Size baseline: an empty program with the same start-up code.
file(WRITE ${WORK_DIR}/empty.c "int main(void)\n{\n    return 0;\n}\n")
execute_process(COMMAND ${ARM_GCC} ${link_flags} ${WORK_DIR}/empty.c -o ${WORK_DIR}/empty.elf
  RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "cortex-m4: cannot link an empty program with nosys.specs:\n${err}")
endif()
function(elf_text elf out_var)
  execute_process(COMMAND ${ARM_SIZE} ${elf} OUTPUT_VARIABLE table)
  string(REGEX MATCH "\n[ \t]*([0-9]+)" row "${table}")
  set(${out_var} ${CMAKE_MATCH_1} PARENT_SCOPE)
endfunction()
elf_text(${WORK_DIR}/empty.elf empty_text)

set(group 0)
foreach(group_name filters bspline generator)   # PROBE_GROUP 1, 2, 3
  math(EXPR group "${group} + 1")
  set(builds float double)
  if(group_name STREQUAL "filters")
    list(APPEND builds float_Os)
  endif()
  foreach(build ${builds})
    string(REGEX REPLACE "_Os$" "" precision "${build}")
    set(defines)
    if(precision STREQUAL "float")
      set(defines -DSMS_USE_FLOAT)
    endif()
    set(elf ${WORK_DIR}/probe_${group_name}_${build}.elf)
    execute_process(COMMAND ${ARM_GCC} ${link_flags} ${strict_flags} ${defines}
      -DPROBE_GROUP=${group} -I${SOURCE_DIR}/c/include ${CMAKE_CURRENT_LIST_DIR}/per_sample_probe.c
      ${objects_${build}} -lm -o ${elf} RESULT_VARIABLE rc ERROR_VARIABLE err)
    if(NOT rc EQUAL 0)
      message(FATAL_ERROR "cortex-m4 ${precision}: the ${group_name} probe does not link:\n${err}")
    endif()
    execute_process(COMMAND ${ARM_NM} --defined-only ${elf} OUTPUT_VARIABLE elf_table)
    string(REGEX MATCHALL " [TtWw] [A-Za-z_][A-Za-z0-9_]*" elf_entries "${elf_table}")
    set(kept_math)
    foreach(entry ${elf_entries})
      string(REGEX REPLACE "^ [TtWw] " "" name "${entry}")
      if(name IN_LIST libm_symbols)
        list(APPEND kept_math ${name})
      endif()
    endforeach()
    if(kept_math)
      list(JOIN kept_math ", " listing)
      message(SEND_ERROR "cortex-m4 ${precision}: the ${group_name} per-sample path keeps libm: ${listing}")
      set(libm_note "keeps libm")
    else()
      set(libm_note "no libm")
    endif()
    if(precision STREQUAL "float")
      # On an FPU without double precision, double arithmetic is libgcc soft-float, tens of
      # times slower: the float build's per-sample paths must not use it.
      string(REGEX MATCHALL " [TtWw] __aeabi_(d[a-z]+|f2d|[iu]2d|l2d|ul2d|d2[a-z]+)" soft_double "${elf_table}")
      list(LENGTH soft_double n_soft)
      if(n_soft GREATER 0)
        message(SEND_ERROR "cortex-m4 float: the ${group_name} per-sample path links ${n_soft} "
                           "soft-float double helpers: ${soft_double}")
      else()
        message(STATUS "cortex-m4 float: the ${group_name} per-sample path is single precision only")
      endif()
    endif()
    # Includes the libgcc soft-float routines the double build needs on this single-precision FPU.
    elf_text(${elf} probe_text)
    math(EXPR path_text "${probe_text} - ${empty_text}")
    set(opt "-O2")
    if(build MATCHES "_Os$")
      set(opt "-Os")
    endif()
    message(STATUS "cortex-m4 ${precision} ${opt}: ${group_name} per-sample path ${path_text} B "
                   "text after gc-sections (empty program subtracted), ${libm_note}")
  endforeach()
endforeach()

# The firmware path (coeffs.h, docs/firmware.md): one axis filter (the README's chain) linked
# three ways by firmware_probe.c, float -Os and -O2: per-sample only, built from precomputed
# coefficients (examples/firmware/), designed on the target. The first two must link no
# soft-float double routine and no libm function, and the one built from coefficients must
# stay within 4 kB of code, init included.
set(firmware_dir ${SOURCE_DIR}/examples/firmware)
foreach(build float_Os float)
  set(opt "-O2")
  set(build_flags ${strict_flags})
  if(build STREQUAL "float_Os")
    set(opt "-Os")
    string(REPLACE "-O2" "-Os" build_flags "${strict_flags}")
  endif()
  set(app_objects)
  foreach(src ${firmware_dir}/axis_filter.c ${firmware_dir}/chain_coeffs.c)
    get_filename_component(name ${src} NAME_WE)
    set(obj ${WORK_DIR}/firmware_${build}_${name}.o)
    execute_process(COMMAND ${ARM_GCC} ${target_flags} ${build_flags} -DSMS_USE_FLOAT
      -I${SOURCE_DIR}/c/include -I${firmware_dir} -c ${src} -o ${obj}
      RESULT_VARIABLE rc ERROR_VARIABLE err)
    if(NOT rc EQUAL 0)
      message(FATAL_ERROR "cortex-m4 float ${opt}: examples/firmware/${name}.c does not compile:\n${err}")
    endif()
    list(APPEND app_objects ${obj})
  endforeach()
  set(probe 0)
  foreach(label "per-sample only" "init from precomputed coefficients" "full on-target design")
    math(EXPR probe "${probe} + 1")
    set(extra)
    if(probe EQUAL 2)
      set(extra ${app_objects})
    endif()
    set(elf ${WORK_DIR}/firmware_${probe}_${build}.elf)
    execute_process(COMMAND ${ARM_GCC} ${link_flags} ${build_flags} -DSMS_USE_FLOAT
      -DFIRMWARE_PROBE=${probe} -I${SOURCE_DIR}/c/include -I${firmware_dir}
      ${CMAKE_CURRENT_LIST_DIR}/firmware_probe.c ${extra} ${objects_${build}} -lm -o ${elf}
      RESULT_VARIABLE rc ERROR_VARIABLE err)
    if(NOT rc EQUAL 0)
      message(FATAL_ERROR "cortex-m4 float ${opt}: firmware probe ${probe} does not link:\n${err}")
    endif()
    execute_process(COMMAND ${ARM_NM} --defined-only ${elf} OUTPUT_VARIABLE elf_table)
    string(REGEX MATCHALL " [TtWw] __aeabi_(d[a-z]+|f2d|[iu]2d|l2d|ul2d|d2[a-z]+)" soft_double "${elf_table}")
    string(REGEX MATCHALL " [TtWw] [A-Za-z_][A-Za-z0-9_]*" elf_entries "${elf_table}")
    set(kept_math)
    foreach(entry ${elf_entries})
      string(REGEX REPLACE "^ [TtWw] " "" name "${entry}")
      if(name IN_LIST libm_symbols)
        list(APPEND kept_math ${name})
      endif()
    endforeach()
    list(LENGTH soft_double n_soft)
    list(LENGTH kept_math n_math)
    elf_text(${elf} probe_text)
    math(EXPR path_text "${probe_text} - ${empty_text}")
    message(STATUS "cortex-m4 float ${opt}: firmware ${label} ${path_text} B text after "
                   "gc-sections (empty program subtracted), ${n_soft} soft-double helpers, "
                   "${n_math} libm functions")
    if(probe LESS 3 AND (n_soft GREATER 0 OR n_math GREATER 0))
      message(SEND_ERROR "cortex-m4 float ${opt}: the firmware path (${label}) links "
                         "soft-float double or libm: ${soft_double} ${kept_math}")
    endif()
    if(probe EQUAL 2 AND build STREQUAL "float_Os" AND path_text GREATER 4096)
      message(SEND_ERROR "cortex-m4 float -Os: the axis filter built from coefficients takes "
                         "${path_text} B of code, above the 4 kB budget")
    endif()
  endforeach()
endforeach()
