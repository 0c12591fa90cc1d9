# Runs `argil sculpt SCENE --out OUT --fresh` for CTest. Not on a terminal, the
# program must stay quiet on stderr (no progress bar) and list its files on stdout.
# Variables: ARGIL, SCENE, OUT.
cmake_minimum_required(VERSION 3.20)
execute_process(COMMAND ${ARGIL} sculpt ${SCENE} --out ${OUT} --fresh
                OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "argil sculpt failed (${rc}):\n${err}")
endif()
# A scene that loads some faces of a solid leaves their edges with the others
# free: a press near one opens it, and the export says so (docs/io.md). Shown,
# not failed; the examples' checks fail an edge between loaded faces that opened.
string(REGEX MATCHALL "argil sculpt: [^\n]*shared edges are open wider than eps[^\n]*\n?"
       open_edges "${err}")
string(REGEX REPLACE "argil sculpt: [^\n]*shared edges are open wider than eps[^\n]*\n?" ""
       err "${err}")
if(open_edges)
  message(STATUS "known: ${open_edges}")
endif()
if(NOT err STREQUAL "")
  message(FATAL_ERROR "stderr is not a terminal, yet argil sculpt wrote to it:\n${err}")
endif()
if(NOT out MATCHES "files in [^\n]+:\n" OR NOT out MATCHES "tick time: p50")
  message(FATAL_ERROR "no summary on stdout:\n${out}")
endif()
message(STATUS "${out}")
