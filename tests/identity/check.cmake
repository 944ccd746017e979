# cmake -DPROGRAM=hsr_identity -DSCENES=scenes -DEXPECTED=expected.txt -DOUTPUT=out.txt -P check.cmake
# Runs hsr_identity on every scene, hard case and 100 random scenes (two threads) and
# compares its lines with the expected ones; with HSR_UPDATE_IDENTITY=1 in the
# environment, writes them as the expected ones instead (on purpose only, as goldens).
execute_process(COMMAND ${PROGRAM} ${SCENES} --random 100 --threads 2 OUTPUT_FILE ${OUTPUT} RESULT_VARIABLE result)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "hsr_identity failed (${result})")
endif()
if("$ENV{HSR_UPDATE_IDENTITY}" STREQUAL "1")
  file(COPY_FILE ${OUTPUT} ${EXPECTED})
  message(STATUS "wrote ${EXPECTED}")
  return()
endif()
execute_process(COMMAND diff ${EXPECTED} ${OUTPUT} OUTPUT_VARIABLE differences RESULT_VARIABLE differ)
if(NOT differ EQUAL 0)
  string(REGEX MATCHALL "\n<" removed "\n${differences}")
  list(LENGTH removed count)
  string(SUBSTRING "${differences}" 0 3000 shown)
  message(FATAL_ERROR "${count} renders differ from ${EXPECTED} (< expected, > now; the full output is ${OUTPUT}):\n${shown}")
endif()
file(STRINGS ${OUTPUT} lines)
list(LENGTH lines count)
message(STATUS "${count} renders, every one the bits ${EXPECTED} holds")
