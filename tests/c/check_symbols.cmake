# SPDX-License-Identifier: Apache-2.0
# Fails if the library references allocator or stdio symbols.
execute_process(COMMAND ${NM} -u ${LIB} OUTPUT_VARIABLE undefined RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "nm failed on ${LIB}")
endif()
foreach(sym malloc calloc realloc free printf fprintf puts putchar fputs sprintf snprintf)
  if(undefined MATCHES "(^|[ \n\t_])${sym}(@|\n|$)")
    message(FATAL_ERROR "${LIB} references ${sym}")
  endif()
endforeach()
message(STATUS "${LIB}: no allocator or stdio symbols")
