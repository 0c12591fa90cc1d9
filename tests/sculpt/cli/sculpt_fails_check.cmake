# `argil sculpt` on bad input, for CTest: ARGS (;-list, OUT is appended as
# --out) must exit non-zero with EXPECT (a regex) in stderr, and leave no
# output folder behind (nothing half-written).
# Variables: ARGIL, ARGS, OUT, EXPECT.
cmake_minimum_required(VERSION 3.20)
file(REMOVE_RECURSE "${OUT}")
execute_process(COMMAND ${ARGIL} ${ARGS} --out ${OUT} OUTPUT_VARIABLE out ERROR_VARIABLE err
                RESULT_VARIABLE rc)
if(rc EQUAL 0)
  message(FATAL_ERROR "expected a failure, got exit 0:\n${out}${err}")
endif()
if(NOT rc MATCHES "^[0-9]+$")
  message(FATAL_ERROR "argil did not exit normally (${rc}):\n${err}")
endif()
if(NOT err MATCHES "${EXPECT}")
  message(FATAL_ERROR "stderr does not match '${EXPECT}':\n${err}")
endif()
if(EXISTS "${OUT}")
  message(FATAL_ERROR "a failed run left ${OUT} behind")
endif()
message(STATUS "exit ${rc}: ${err}")
