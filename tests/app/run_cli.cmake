# Runs the shadowvol CLI and checks its exit code and output, so that one CTest test can assert
# both "fails" and "says why". Arguments (-D): EXE, ARGS (;-list), EXPECT_RC, EXPECT_REGEX,
# and optionally REJECT_REGEX (output that must not appear) and ABSENT (a ;-list of files that
# must not exist after the run: removed before it).
foreach(path IN LISTS ABSENT)
  file(REMOVE "${path}")
endforeach()
execute_process(COMMAND ${EXE} ${ARGS} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err
                TIMEOUT 60)
set(all "${out}${err}")
if(NOT rc STREQUAL EXPECT_RC)
  message(FATAL_ERROR "exit code ${rc}, expected ${EXPECT_RC}; output:\n${all}")
endif()
if(NOT all MATCHES "${EXPECT_REGEX}")
  message(FATAL_ERROR "output does not match '${EXPECT_REGEX}':\n${all}")
endif()
if(DEFINED REJECT_REGEX AND all MATCHES "${REJECT_REGEX}")
  message(FATAL_ERROR "output matches '${REJECT_REGEX}', which it must not:\n${all}")
endif()
foreach(path IN LISTS ABSENT)
  if(EXISTS "${path}")
    message(FATAL_ERROR "${path} exists after the run, which it must not:\n${all}")
  endif()
endforeach()
message(STATUS "ok: ${all}")
