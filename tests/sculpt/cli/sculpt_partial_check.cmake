# `argil sculpt` whose run ends but cannot write some outputs, for CTest: it must
# exit 1 with EXPECT (a regex) in stderr, list the files it wrote on stdout,
# and leave every file of WRITTEN in OUT while no file of MISSING exists.
# Variables: ARGIL, SCENE, OUT, EXPECT, WRITTEN, MISSING (;-lists of file names).
cmake_minimum_required(VERSION 3.20)
file(REMOVE_RECURSE "${OUT}")
execute_process(COMMAND ${ARGIL} sculpt ${SCENE} --out ${OUT} OUTPUT_VARIABLE out
                ERROR_VARIABLE err RESULT_VARIABLE rc)
if(NOT rc EQUAL 1)
  message(FATAL_ERROR "expected exit 1, got ${rc}:\n${out}${err}")
endif()
if(NOT err MATCHES "${EXPECT}")
  message(FATAL_ERROR "stderr does not match '${EXPECT}':\n${err}")
endif()
foreach(_file ${WRITTEN})
  if(NOT EXISTS "${OUT}/${_file}")
    message(FATAL_ERROR "${_file} was not written:\n${out}${err}")
  endif()
  if(NOT out MATCHES "${_file}")
    message(FATAL_ERROR "${_file} is not listed on stdout:\n${out}")
  endif()
endforeach()
foreach(_file ${MISSING})
  if(EXISTS "${OUT}/${_file}")
    message(FATAL_ERROR "${_file} exists, though its export failed")
  endif()
endforeach()
message(STATUS "exit ${rc}: ${err}")
