# Checks the argil program's command-line conventions, stdout and stderr apart.
# Modes:
#   usage:      ARGS exit 0 with stdout matching EXPECT and nothing on stderr
#               (help goes to stdout, and no file is opened).
#   error:      ARGS exit with status RC (default: any non-zero), nothing on
#               stdout, and stderr matching EXPECT followed by the usage
#               (USAGE, a regex: "usage: argil info").
#   version:    `argil --version` prints "argil VERSION" and nothing else.
# Variables: ARGIL, MODE, ARGS (;-list), EXPECT, USAGE, RC, VERSION.
cmake_minimum_required(VERSION 3.20)

execute_process(COMMAND ${ARGIL} ${ARGS} OUTPUT_VARIABLE out ERROR_VARIABLE err
                RESULT_VARIABLE rc)
set(_report "argil ${ARGS}\n--- exit ${rc}\n--- stdout\n${out}\n--- stderr\n${err}")

if(MODE STREQUAL "usage")
  if(NOT rc EQUAL 0 OR NOT err STREQUAL "" OR NOT out MATCHES "${EXPECT}")
    message(FATAL_ERROR "expected exit 0, '${EXPECT}' on stdout, empty stderr:\n${_report}")
  endif()
elseif(MODE STREQUAL "error")
  if(rc EQUAL 0 OR (DEFINED RC AND NOT rc EQUAL RC))
    message(FATAL_ERROR "expected exit ${RC} (non-zero):\n${_report}")
  endif()
  if(NOT out STREQUAL "")
    message(FATAL_ERROR "expected nothing on stdout:\n${_report}")
  endif()
  if(NOT err MATCHES "${EXPECT}[^\n]*\n(.*\n)?${USAGE}")
    message(FATAL_ERROR "expected '${EXPECT}' then the usage '${USAGE}' on stderr:\n${_report}")
  endif()
elseif(MODE STREQUAL "version")
  if(NOT rc EQUAL 0 OR NOT out STREQUAL "argil ${VERSION}\n" OR NOT err STREQUAL "")
    message(FATAL_ERROR "expected exactly 'argil ${VERSION}' on stdout:\n${_report}")
  endif()
else()
  message(FATAL_ERROR "unknown MODE ${MODE}")
endif()
message(STATUS "as expected:\n${_report}")
