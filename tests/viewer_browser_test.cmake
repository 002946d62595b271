# One real-browser test of `ccma view` (CTest): writes the page for MODEL
# (animated along a trajectory or a replay of WAYPOINTS when KIND says so;
# with KIND=workspace, under the cloud of a small `ccma workspace` map over
# x, y, z, reachable and unreachable points both; with KIND=meshes, with
# `--meshes`; with KIND=collision, MODEL given capsules and obstacles; with
# KIND=load, `--color_by=load`; with KIND=deflection, `--deflection=100`; with KIND=effort,
# `--dynamics` of a retimed trajectory) and opens it with
# viewer/js/test/browser_test.mjs in headless Chromium.
#   cmake -DTOOL=.. -DNODE=.. -DTEST_JS=.. -DMODEL=.. -DWORK=.. -DKIND=model|trajectory|replay|workspace|meshes|collision|load|deflection|effort
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
elseif(KIND STREQUAL "collision")
  # MODEL (4dof_reduced) with capsules on its legs and posts, seen with obstacles
  # (--obstacles) along a trajectory planned without them: base2 starts 5 mm into
  # the pillar, leaves it and comes back, so some frames are below the margin
  # and some are not (collision_checks.mjs checks both).
  file(READ "${MODEL}" model_text)
  file(WRITE "${WORK}/model.yaml" "${model_text}
collision:
  margin: 0.05
  links:
    - {body: link0, from: [0, 0.583012702, 0.35], to: [0, 0.15, 0.6], radius: 0.03}
    - {body: link1, from: [-0.504903811, -0.291506351, 0.35], to: [-0.129903811, -0.075, 0.6], radius: 0.03}
    - {body: link2, from: [0.504903811, -0.291506351, 0.35], to: [0.129903811, -0.075, 0.6], radius: 0.03}
    - {body: post0, from: [0, 0.583012702, 0.1], to: [0, 0.583012702, 0.35], radius: 0.04}
    - {body: post1, from: [-0.504903811, -0.291506351, 0.1], to: [-0.504903811, -0.291506351, 0.35], radius: 0.04}
    - {body: post2, from: [0.504903811, -0.291506351, 0.1], to: [0.504903811, -0.291506351, 0.35], radius: 0.04}
")
  file(WRITE "${WORK}/obstacles.yaml" "obstacles:
  - {name: pillar, cylinder: {center: [1.0, -0.3], radius: 0.2, height: 1.0}}
  - {name: crate, box: {center: [-0.9, 0.6, 0.25], size: [0.5, 0.4, 0.5], yaw: 0.4}}
")
  run("${TOOL}" trajectory "--model=${MODEL}" "--waypoints=${WAYPOINTS}" "--out=${WORK}/path.csv")
  set(MODEL "${WORK}/model.yaml")
  set(source "--obstacles=${WORK}/obstacles.yaml" "--trajectory=${WORK}/path.csv")
  set(animation --expect-animation)
elseif(KIND STREQUAL "load")
  # --color_by=load (browser_test.mjs checks the colours, the legend and the
  # bar's load line). With WAYPOINTS: MODEL given a 5 kg payload and animated
  # along a trajectory (4dof_reduced's closed loops make every frame's
  # statics indeterminate: "minimum-norm loads"); without: MODEL at home.
  set(source --color_by=load)
  if(WAYPOINTS)
    file(READ "${MODEL}" model_text)
    string(REPLACE "end_effector:\n" "end_effector:\n  payload: {mass: 5}\n" model_text "${model_text}")
    file(WRITE "${WORK}/model.yaml" "${model_text}")
    set(MODEL "${WORK}/model.yaml")
    run("${TOOL}" trajectory "--model=${MODEL}" "--waypoints=${WAYPOINTS}" "--out=${WORK}/path.csv")
    list(APPEND source "--trajectory=${WORK}/path.csv")
    set(animation --expect-animation)
  endif()
elseif(KIND STREQUAL "effort")
  # --dynamics (browser_test.mjs checks the colours, the legend and the bar's
  # effort line): MODEL (with push limits) along WAYPOINTS, retimed to the
  # fastest timing within its limits (shares up to about 1), then its
  # `ccma dynamics --out`.
  run("${TOOL}" trajectory "--model=${MODEL}" "--waypoints=${WAYPOINTS}" "--out=${WORK}/path.csv")
  run("${TOOL}" retime "--model=${MODEL}" "--trajectory=${WORK}/path.csv" "--out=${WORK}/fast.csv")
  run("${TOOL}" dynamics "--model=${MODEL}" "--trajectory=${WORK}/fast.csv" "--out=${WORK}/efforts.csv")
  set(source "--trajectory=${WORK}/fast.csv" "--dynamics=${WORK}/efforts.csv")
  set(animation --expect-animation)
elseif(KIND STREQUAL "deflection")
  # --deflection (browser_test.mjs checks the legend, the colours and the
  # loaded copy's poses): MODEL is compliant, seen at home, exaggerated 100 times.
  set(source --deflection=100)
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
