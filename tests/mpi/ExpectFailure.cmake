# Runs COMMAND (arguments separated by '|') and passes only when it exits non-zero, its output matches
# EXPECT and, when given, not REJECT: a rank that fails must end every rank with a clear message (a hang
# fails by the test's timeout).
string(REPLACE "|" ";" command "${COMMAND}")
execute_process(COMMAND ${command} RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE output)
message("${output}")
if(result EQUAL 0)
  message(FATAL_ERROR "expected a failure, but the command exited with 0")
endif()
if(NOT output MATCHES "${EXPECT}")
  message(FATAL_ERROR "the output does not match: ${EXPECT}")
endif()
if(DEFINED REJECT AND NOT REJECT STREQUAL "" AND output MATCHES "${REJECT}")
  message(FATAL_ERROR "the output matches what it must not: ${REJECT}")
endif()
