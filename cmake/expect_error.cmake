# cmake -DCOMMAND="program;arg;..." -DEXIT=N -DMESSAGE=regex -P expect_error.cmake
# Bad input's contract, for programs outside GoogleTest (the peers in bench/): the exit
# code is N, and standard error is exactly one line matching MESSAGE.
execute_process(COMMAND ${COMMAND} RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE error)
string(REGEX REPLACE "\n$" "" line "${error}")
if(NOT result STREQUAL "${EXIT}")
  message(FATAL_ERROR "exit code ${result}, expected ${EXIT}; standard error:\n${error}")
elseif(line MATCHES "\n")
  message(FATAL_ERROR "standard error is more than one line:\n${error}")
elseif(NOT line MATCHES "${MESSAGE}")
  message(FATAL_ERROR "standard error does not match '${MESSAGE}':\n${error}")
endif()
