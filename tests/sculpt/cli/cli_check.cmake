# Runs the argil program for CTest. Modes:
#   same_faces: convert IN to OUT, then `info` on both must list the same faces
#               (degrees, pole counts, rational, trimmed); stdout carries no
#               OpenCASCADE chatter.
#   fails:      ARGS must exit non-zero with EXPECT in stderr (and, when
#               NOT_EXPECT is given, no match of it); when ABSENT names a
#               file, it must not exist afterwards (removed first).
#   warns:      ARGS must exit 0 with EXPECT in stderr (a warning that does not stop it).
# Variables: ARGIL, MODE, IN, OUT, ARGS (;-list), EXPECT, NOT_EXPECT, ABSENT.
cmake_minimum_required(VERSION 3.20)

function(run_argil out_var err_var rc_var)
  execute_process(COMMAND ${ARGIL} ${ARGN} OUTPUT_VARIABLE out ERROR_VARIABLE err
                  RESULT_VARIABLE rc)
  set(${out_var} "${out}" PARENT_SCOPE)
  set(${err_var} "${err}" PARENT_SCOPE)
  set(${rc_var} "${rc}" PARENT_SCOPE)
endfunction()

# The face table of `argil info` without the source column (ids differ by format).
function(face_table text out_var)
  string(REGEX MATCH "faces: [0-9]+[^\n]*" summary "${text}")
  string(REGEX MATCHALL "\n +[0-9]+  [0-9]+x[0-9]+ +[0-9]+x[0-9]+ +(yes|no) +(yes|no) +[0-9]+"
         rows "${text}")
  set(${out_var} "${summary}${rows}" PARENT_SCOPE)
endfunction()

if(MODE STREQUAL "same_faces")
  file(REMOVE "${OUT}")
  run_argil(out err rc convert "${IN}" "${OUT}")
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "convert failed (${rc}): ${err}")
  endif()
  if(NOT out MATCHES "^converted [^\n]*\n$")
    message(FATAL_ERROR "convert printed more than its one line:\n${out}")
  endif()
  run_argil(info_in err_in rc_in info "${IN}")
  run_argil(info_out err_out rc_out info "${OUT}")
  if(NOT rc_in EQUAL 0 OR NOT rc_out EQUAL 0)
    message(FATAL_ERROR "info failed: ${err_in} ${err_out}")
  endif()
  face_table("${info_in}" table_in)
  face_table("${info_out}" table_out)
  if(table_in STREQUAL "" OR NOT table_in STREQUAL table_out)
    message(FATAL_ERROR "faces differ:\n--- ${IN}\n${table_in}\n--- ${OUT}\n${table_out}")
  endif()
  message(STATUS "same faces: ${table_in}")
elseif(MODE STREQUAL "fails")
  if(DEFINED ABSENT)
    file(REMOVE "${ABSENT}")
  endif()
  run_argil(out err rc ${ARGS})
  if(DEFINED ABSENT AND EXISTS "${ABSENT}")
    message(FATAL_ERROR "the failed command wrote ${ABSENT}")
  endif()
  if(rc EQUAL 0)
    message(FATAL_ERROR "expected a failure, got exit 0:\n${out}")
  endif()
  if(NOT err MATCHES "${EXPECT}")
    message(FATAL_ERROR "stderr does not mention '${EXPECT}':\n${err}")
  endif()
  if(DEFINED NOT_EXPECT AND err MATCHES "${NOT_EXPECT}")
    message(FATAL_ERROR "stderr matches '${NOT_EXPECT}' ('${CMAKE_MATCH_0}'):\n${err}")
  endif()
  message(STATUS "failed as expected (${rc}): ${err}")
elseif(MODE STREQUAL "warns")
  run_argil(out err rc ${ARGS})
  if(NOT rc EQUAL 0 OR NOT err MATCHES "${EXPECT}")
    message(FATAL_ERROR "expected exit 0 and '${EXPECT}' on stderr, got exit ${rc}:\n${err}")
  endif()
  message(STATUS "warned as expected: ${err}")
else()
  message(FATAL_ERROR "unknown MODE ${MODE}")
endif()
