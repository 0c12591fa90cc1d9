# Converts each of FILES to glb with the argil program and validates it with
# the Khronos glTF validator (web/validate_gltf.cjs, installed by `make` from
# web/package-lock.json). Prints "skipped: ..." (CTest's SKIP_REGULAR_EXPRESSION)
# and stops when node or the validator is not installed. Variables: ARGIL, OUT, WEB, FILES (;-list).
cmake_minimum_required(VERSION 3.20)

find_program(NODE node)
if(NOT NODE OR NOT EXISTS "${WEB}/node_modules/gltf-validator")
  message("skipped: node or web/node_modules/gltf-validator is missing (make deps installs them)")
  return()
endif()
file(MAKE_DIRECTORY "${OUT}")
set(glbs)
foreach(in ${FILES})
  get_filename_component(stem "${in}" NAME_WE)
  set(glb "${OUT}/${stem}.glb")
  file(REMOVE "${glb}")
  execute_process(COMMAND ${ARGIL} convert "${in}" "${glb}" ERROR_VARIABLE err RESULT_VARIABLE rc
                  OUTPUT_QUIET)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "argil convert ${in} ${glb} failed (${rc}): ${err}")
  endif()
  list(APPEND glbs "${glb}")
endforeach()
execute_process(COMMAND ${NODE} "${WEB}/validate_gltf.cjs" ${glbs} OUTPUT_VARIABLE report
                RESULT_VARIABLE rc)
message("${report}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the glTF validator refused a file (${rc})")
endif()
