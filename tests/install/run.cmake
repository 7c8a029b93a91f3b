# SPDX-License-Identifier: Apache-2.0
# Installs a smoothshaper build tree into a scratch prefix and builds + runs the consumer in
# this directory against it. Run with cmake -P; variables:
#   MODE        cmake: install, then find_package consumers (static double + float, and the
#                      shared ones when SHARED); pkgconfig: build main.c with the flags
#                      pkg-config gives for the prefix MODE=cmake installed
#   BUILD_DIR   the smoothshaper build tree        CONFIG     its build type
#   WORK_DIR    scratch directory (prefix, consumer build)
#   GENERATOR, MAKE_PROGRAM, C_COMPILER            SHARED, SANITIZE  ON/OFF as in the build
# Prints "SKIPPED: <reason>" (the ctest skip marker) when pkg-config is absent.
cmake_minimum_required(VERSION 3.16)
set(consumer_source ${CMAKE_CURRENT_LIST_DIR})
set(prefix ${WORK_DIR}/prefix)

function(run_checked what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  message(STATUS "${what}:\n${out}${err}")
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${what} failed (${rc})")
  endif()
endfunction()

# The library directory under the prefix (lib, lib64 or lib/<multiarch>), found from the
# package config file that every install must contain.
function(find_installed_libdir out_var)
  file(GLOB_RECURSE config_files ${prefix}/*/smoothshaperConfig.cmake)
  list(LENGTH config_files n)
  if(NOT n EQUAL 1)
    message(FATAL_ERROR "expected one smoothshaperConfig.cmake under ${prefix}, found ${n}")
  endif()
  get_filename_component(config_dir ${config_files} DIRECTORY)   # <libdir>/cmake/smoothshaper
  get_filename_component(libdir ${config_dir}/../.. ABSOLUTE)
  set(${out_var} ${libdir} PARENT_SCOPE)
endfunction()

function(run_consumer what exe libdir)
  # The shared variants must load the installed library, not anything else on the system.
  run_checked("${what}" ${CMAKE_COMMAND} -E env LD_LIBRARY_PATH=${libdir} ${exe})
endfunction()

set(sanitize_flags)
if(SANITIZE)
  set(sanitize_flags -fsanitize=address,undefined)
endif()

if(MODE STREQUAL "cmake")
  file(REMOVE_RECURSE ${WORK_DIR})
  run_checked("install" ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix} --config ${CONFIG})
  if(NOT EXISTS ${prefix}/include/smoothshaper/smoothshaper.h)
    message(FATAL_ERROR "headers not installed under ${prefix}/include")
  endif()
  find_installed_libdir(libdir)
  if(NOT EXISTS ${libdir}/pkgconfig/smoothshaper.pc OR NOT EXISTS ${libdir}/pkgconfig/smoothshaper_float.pc)
    message(FATAL_ERROR "pkg-config files not installed under ${libdir}/pkgconfig")
  endif()

  set(consumer_build ${WORK_DIR}/consumer)
  run_checked("configure consumer" ${CMAKE_COMMAND} -S ${consumer_source} -B ${consumer_build}
    -G ${GENERATOR} -DCMAKE_MAKE_PROGRAM=${MAKE_PROGRAM} -DCMAKE_C_COMPILER=${C_COMPILER}
    -DCMAKE_BUILD_TYPE=${CONFIG}
    -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF
    -DCONSUMER_EXPECT_SHARED=${SHARED} -DCONSUMER_SANITIZE=${SANITIZE})
  # find_package must have found the scratch prefix, not some other installed copy.
  file(STRINGS ${consumer_build}/CMakeCache.txt found_dir REGEX "^smoothshaper_DIR:")
  string(FIND "${found_dir}" "${prefix}/" at)
  if(NOT at GREATER -1)
    message(FATAL_ERROR "find_package used ${found_dir}, not ${prefix}")
  endif()
  run_checked("build consumer" ${CMAKE_COMMAND} --build ${consumer_build} --config ${CONFIG})

  set(targets smoothshaper smoothshaper_float)
  if(SHARED)
    list(APPEND targets smoothshaper_shared smoothshaper_float_shared)
  endif()
  foreach(target ${targets})
    set(exe ${consumer_build}/consume_${target})
    if(EXISTS ${consumer_build}/${CONFIG}/consume_${target}${CMAKE_EXECUTABLE_SUFFIX})
      set(exe ${consumer_build}/${CONFIG}/consume_${target})   # multi-config generators
    endif()
    run_consumer("find_package consumer ${target}" ${exe} ${libdir})
  endforeach()

elseif(MODE STREQUAL "pkgconfig")
  find_program(PKG_CONFIG_EXECUTABLE NAMES pkg-config pkgconf)
  if(NOT PKG_CONFIG_EXECUTABLE)
    message("SKIPPED: no pkg-config or pkgconf on PATH")
    return()
  endif()
  find_installed_libdir(libdir)
  # Only the scratch prefix: no system .pc file may answer for smoothshaper.
  set(ENV{PKG_CONFIG_PATH} ${libdir}/pkgconfig)
  set(ENV{PKG_CONFIG_LIBDIR} ${libdir}/pkgconfig)
  set(link_mode)
  if(NOT SHARED)
    set(link_mode --static)   # only the archive is installed: it needs Libs.private (-lm)
  endif()
  foreach(package smoothshaper smoothshaper_float)
    execute_process(COMMAND ${PKG_CONFIG_EXECUTABLE} ${link_mode} --cflags --libs ${package}
      RESULT_VARIABLE rc OUTPUT_VARIABLE flags ERROR_VARIABLE err OUTPUT_STRIP_TRAILING_WHITESPACE)
    if(NOT rc EQUAL 0)
      message(FATAL_ERROR "pkg-config ${package}: ${err}")
    endif()
    message(STATUS "pkg-config ${link_mode} --cflags --libs ${package}: ${flags}")
    separate_arguments(flag_list UNIX_COMMAND "${flags}")
    # The .pc file must be relocatable: after --install --prefix it points into that prefix.
    set(include_dir)
    foreach(flag ${flag_list})
      if(flag MATCHES "^-I(.+)$")
        get_filename_component(include_dir ${CMAKE_MATCH_1} REALPATH)
      endif()
    endforeach()
    get_filename_component(expected_include ${prefix}/include REALPATH)
    if(NOT include_dir STREQUAL expected_include)
      message(FATAL_ERROR "pkg-config ${package} include dir '${include_dir}' is not ${expected_include}")
    endif()
    if(package STREQUAL "smoothshaper_float")
      set(real_size 4)
    else()
      set(real_size 8)
    endif()
    set(exe ${WORK_DIR}/pkgconfig_consume_${package})
    run_checked("pkg-config build ${package}" ${C_COMPILER} -std=c99 -Wall -Wextra -Werror
      -pedantic -Wshadow -Wstrict-prototypes -Wmissing-prototypes ${sanitize_flags}
      -DCONSUMER_EXPECT_REAL_SIZE=${real_size} ${consumer_source}/main.c ${flag_list} -o ${exe})
    run_consumer("pkg-config consumer ${package}" ${exe} ${libdir})
    if(SHARED AND NOT WIN32 AND NOT APPLE)
      # The README's way without LD_LIBRARY_PATH: the library directory as the run path.
      execute_process(COMMAND ${PKG_CONFIG_EXECUTABLE} --variable=libdir ${package}
        OUTPUT_VARIABLE pc_libdir OUTPUT_STRIP_TRAILING_WHITESPACE)
      run_checked("pkg-config build ${package} with rpath" ${C_COMPILER} -std=c99
        ${sanitize_flags} -DCONSUMER_EXPECT_REAL_SIZE=${real_size} ${consumer_source}/main.c
        ${flag_list} -Wl,-rpath,${pc_libdir} -o ${exe}_rpath)
      run_checked("pkg-config consumer ${package} with rpath" ${CMAKE_COMMAND} -E env
        --unset=LD_LIBRARY_PATH ${exe}_rpath)
    endif()
  endforeach()
else()
  message(FATAL_ERROR "MODE must be cmake or pkgconfig, not '${MODE}'")
endif()
