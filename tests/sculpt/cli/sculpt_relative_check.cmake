# `argil sculpt scene.json` run from the scene's own folder: a relative path
# names the run as an absolute one does (the folder's name, which titles the
# pictures), so the default output folder is out/<name>.
# Variables: ARGIL, EXAMPLE (a folder holding scene.json and its inputs), WORK.
cmake_minimum_required(VERSION 3.20)

get_filename_component(name "${EXAMPLE}" NAME)
file(REMOVE_RECURSE "${WORK}")
file(COPY "${EXAMPLE}" DESTINATION "${WORK}")
execute_process(COMMAND ${ARGIL} sculpt scene.json --fresh WORKING_DIRECTORY "${WORK}/${name}"
                RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "argil sculpt scene.json exited ${rc}: ${err}")
endif()
set(summary "${WORK}/${name}/out/${name}/summary.json")
if(NOT EXISTS "${summary}")
  message(FATAL_ERROR "no ${summary}: the default output folder is not out/${name}")
endif()
