# Installs argil from its build tree into a fresh prefix, checks what was
# installed, then configures and builds the API examples as a downstream
# project that finds argil with find_package(argil).
# Usage: cmake -DBUILD=<argil build dir> -DPREFIX=<empty dir> -DEXAMPLES=<examples/api>
#              -DDOWNSTREAM=<build dir for the examples> -DGENERATOR=<generator>
#              [-DFLAGS=<extra compile and link flags>] -P package_check.cmake
file(REMOVE_RECURSE "${PREFIX}" "${DOWNSTREAM}")

function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    string(REPLACE ";" " " cmd "${ARGN}")
    message(FATAL_ERROR "'${cmd}' failed (${rc}):\n${out}\n${err}")
  endif()
endfunction()

run(${CMAKE_COMMAND} --install "${BUILD}" --prefix "${PREFIX}")

# The package: config and version files, the libraries, public headers only.
file(GLOB_RECURSE config RELATIVE "${PREFIX}" "${PREFIX}/*/argilConfig*.cmake")
list(LENGTH config n_config)
if(NOT n_config EQUAL 2)
  message(FATAL_ERROR "expected argilConfig.cmake and argilConfigVersion.cmake, found: ${config}")
endif()
foreach(header argil/core.hpp argil/io.hpp argil/sculpt.hpp)
  if(NOT EXISTS "${PREFIX}/include/${header}")
    message(FATAL_ERROR "the entry header ${header} was not installed")
  endif()
endforeach()
file(GLOB_RECURSE private RELATIVE "${PREFIX}" "${PREFIX}/include/*/detail/*")
if(private)
  message(FATAL_ERROR "private headers were installed: ${private}")
endif()

set(flags_args "")
if(FLAGS)
  list(APPEND flags_args "-DCMAKE_CXX_FLAGS=${FLAGS}" "-DCMAKE_EXE_LINKER_FLAGS=${FLAGS}")
endif()
run(${CMAKE_COMMAND} -S "${EXAMPLES}" -B "${DOWNSTREAM}" -G "${GENERATOR}"
  -DCMAKE_BUILD_TYPE=Release "-DCMAKE_PREFIX_PATH=${PREFIX}" ${flags_args})
run(${CMAKE_COMMAND} --build "${DOWNSTREAM}")
message(STATUS "installed into ${PREFIX}; the downstream examples built in ${DOWNSTREAM}")
