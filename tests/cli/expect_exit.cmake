# Runs RELIEF with ARGS (a ;-list) and checks the exit code (EXPECTED) and that
# stdout + stderr match REGEX. Used where CTest's own properties cannot check both.
execute_process(COMMAND ${RELIEF} ${ARGS} RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
set(all "${out}${err}")
string(STRIP "${all}" all)
message("${all}")
if(NOT code EQUAL EXPECTED)
  message(FATAL_ERROR "exit code ${code}, expected ${EXPECTED}")
endif()
if(NOT "${REGEX}" STREQUAL "" AND NOT "${all}" MATCHES "${REGEX}")
  message(FATAL_ERROR "output does not match: ${REGEX}")
endif()
