# The viewer page in a real browser: sculpts SCENE into OUT, writes its page
# with `argil view`, and checks it in headless Chromium (web/check_view.cjs:
# it renders, the timeline plays to its last frame where the dent shows blue,
# a click picks the face and (u, v) under it, no network, no script error);
# then the same for the model file MODEL. Screenshots go to OUT. Prints
# "skipped: ..." (CTest's SKIP_REGULAR_EXPRESSION) when node, playwright-core
# or Chromium is missing. Variables: ARGIL, WEB, SCENE, MODEL, OUT.
cmake_minimum_required(VERSION 3.20)

find_program(NODE node)
if(NOT NODE OR NOT EXISTS "${WEB}/node_modules/playwright-core")
  message("skipped: node or web/node_modules/playwright-core is missing (make deps installs them)")
  return()
endif()
if(NOT EXISTS "/usr/bin/chromium" AND NOT DEFINED ENV{ARGIL_CHROMIUM})
  message("skipped: no Chromium at /usr/bin/chromium (make deps installs Debian's chromium)")
  return()
endif()

function(run what)
  execute_process(COMMAND ${ARGN} OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE rc)
  message("${out}")
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${what} failed (${rc}): ${err}")
  endif()
endfunction()

file(REMOVE_RECURSE "${OUT}")
run("argil sculpt" ${ARGIL} sculpt "${SCENE}" --out "${OUT}/run" --fresh)
run("argil view of the run" ${ARGIL} view "${OUT}/run")
if(NOT EXISTS "${OUT}/run/view.html")
  message(FATAL_ERROR "argil view did not write ${OUT}/run/view.html")
endif()
run("the run's page in Chromium" ${NODE} "${WEB}/check_view.cjs" "${OUT}/run/view.html"
    "${OUT}/run.png" --run)
run("argil view of ${MODEL}" ${ARGIL} view "${MODEL}" --out "${OUT}/model.html")
run("the model's page in Chromium" ${NODE} "${WEB}/check_view.cjs" "${OUT}/model.html"
    "${OUT}/model.png")
