# One real-browser test of `ccma view` (CTest): writes the page for MODEL
# (animated along a trajectory or a replay of WAYPOINTS when KIND says so;
# with KIND=workspace, under the cloud of a small `ccma workspace` map over
# x, y, z, reachable and unreachable points both; with KIND=meshes, with
# `--meshes`) and opens it with
# viewer/js/test/browser_test.mjs in headless Chromium.
#   cmake -DTOOL=.. -DNODE=.. -DTEST_JS=.. -DMODEL=.. -DWORK=.. -DKIND=model|trajectory|replay|workspace|meshes
#         [-DWAYPOINTS=..] -P viewer_browser_test.cmake
# Skipped (CTest's SKIP_REGULAR_EXPRESSION on "SKIPPED: chromium", with the
# reason printed) only when Chromium is missing; never a silent pass.
cmake_minimum_required(VERSION 3.16)
file(MAKE_DIRECTORY "${WORK}")
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGN}\n${out}\n${err}")
  endif()
endfunction()
set(source "")
set(animation "")
if(KIND STREQUAL "trajectory")
  run("${TOOL}" trajectory "--model=${MODEL}" "--waypoints=${WAYPOINTS}" "--out=${WORK}/path.csv")
  set(source "--trajectory=${WORK}/path.csv")
  set(animation --expect-animation)
elseif(KIND STREQUAL "replay")
  run("${TOOL}" replay "--model=${MODEL}" "--waypoints=${WAYPOINTS}" "--out=${WORK}/replay")
  set(source "--replay=${WORK}/replay")
  set(animation --expect-animation)
elseif(KIND STREQUAL "meshes")
  set(source --meshes)  # the model names its STL meshes; browser_test.mjs checks where they are drawn
elseif(KIND STREQUAL "workspace")
  run("${TOOL}" workspace "--model=${MODEL}" --x=-0.4:0.4 --y=-0.4:0.4 --z=0.45:1.0 --resolution=7 --threads=2
      "--out=${WORK}/map.csv")
  set(source "--workspace=${WORK}/map.csv")
endif()
run("${TOOL}" view "--model=${MODEL}" ${source} "--out=${WORK}/page.html")
execute_process(COMMAND "${NODE}" "${TEST_JS}" --html "${WORK}/page.html" ${animation}
                        --screenshot "${WORK}/page.png"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}${err}")
if(rc EQUAL 77)
  message(FATAL_ERROR "SKIPPED: chromium is not installed (scripts/test.sh installs it: apt-get install chromium)")
endif()
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the browser test failed (${rc})")
endif()
