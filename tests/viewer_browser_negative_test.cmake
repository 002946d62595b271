# The browser test can fail: pages that are broken on purpose must be refused.
#  1. a page whose scene is not valid (the viewer reports it; console error);
#  2. a valid page that also asks for a remote image (a network request;
#     the page's CSP blocks it, the test still sees the attempt);
#  3. a valid page whose mechanism is never drawn (bodies hidden by a script);
#  4. a valid workspace page whose cloud is never drawn (hidden by a script);
#  5. a valid page of MESH_MODEL (`--meshes`) whose meshes are never drawn;
#  6. that page with a mesh naming a file the scene does not carry;
#  7. a valid page of MODEL with obstacles (--obstacles) whose shapes are never drawn;
#  8. that page with an obstacle of an unknown shape.
#   cmake -DNODE=.. -DTEST_JS=.. -DBUNDLE=.. -DTOOL=.. -DMODEL=.. -DMESH_MODEL=.. -DWORK=.. -P this
cmake_minimum_required(VERSION 3.16)
file(MAKE_DIRECTORY "${WORK}")
execute_process(COMMAND "${TOOL}" view "--model=${MODEL}" "--out=${WORK}/good.html" RESULT_VARIABLE rc OUTPUT_QUIET)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "ccma view failed")
endif()
file(READ "${WORK}/good.html" good)
file(READ "${BUNDLE}" bundle)
set(shell_start "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>bad</title></head><body>\n")
file(WRITE "${WORK}/bad_scene.html"
     "${shell_start}<script type=\"application/json\" id=\"ccma-scene\">{\"format\":\"nope\"}</script>\n<script>${bundle}</script></body></html>\n")
string(REPLACE "<body>" "<body><img src=\"http://192.0.2.1/x.png\">" remote "${good}")
file(WRITE "${WORK}/remote.html" "${remote}")
string(REPLACE "</body>" "<script>window.ccmaView.showMechanism(false); window.ccmaView.showMechanism = () => {};</script></body>" hidden "${good}")
# (The CSP allows inline scripts, so this one runs after the viewer's.)
file(WRITE "${WORK}/hidden.html" "${hidden}")
# A hand-written map of MODEL (4dof_reduced: x, y, z, yaw): a 4 x 4 x 3 grid.
set(map "x,y,z,yaw,reachable,sigma_min,limited_by\n")
foreach(z 0.5 0.6 0.7)
  foreach(x -0.3 -0.1 0.1 0.3)
    foreach(y -0.3 -0.1 0.1 0.3)
      string(APPEND map "${x},${y},${z},0,1,0.4,\n")
    endforeach()
  endforeach()
endforeach()
file(WRITE "${WORK}/map.csv" "${map}")
execute_process(COMMAND "${TOOL}" view "--model=${MODEL}" "--workspace=${WORK}/map.csv" "--out=${WORK}/cloud.html"
                RESULT_VARIABLE rc OUTPUT_QUIET)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "ccma view --workspace failed")
endif()
file(READ "${WORK}/cloud.html" cloud)
string(REPLACE "</body>" "<script>window.ccmaView.showWorkspace(false); window.ccmaView.showWorkspace = () => {};</script></body>" cloud "${cloud}")
file(WRITE "${WORK}/hidden_cloud.html" "${cloud}")
execute_process(COMMAND "${TOOL}" view "--model=${MESH_MODEL}" --meshes "--out=${WORK}/meshes.html"
                RESULT_VARIABLE rc OUTPUT_QUIET)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "ccma view --meshes failed")
endif()
file(READ "${WORK}/meshes.html" meshes)
string(REPLACE "</body>" "<script>window.ccmaView.showMeshes(false); window.ccmaView.showMeshes = () => {};</script></body>"
       hidden_meshes "${meshes}")
file(WRITE "${WORK}/hidden_meshes.html" "${hidden_meshes}")
string(REPLACE "{\"file\":0," "{\"file\":7," bad_mesh "${meshes}")
if(bad_mesh STREQUAL meshes)
  message(FATAL_ERROR "test bug: no mesh with file 0 in ${WORK}/meshes.html")
endif()
file(WRITE "${WORK}/bad_mesh.html" "${bad_mesh}")
file(WRITE "${WORK}/obstacles.yaml" "obstacles:
  - {name: pillar, cylinder: {center: [1.0, -0.3], radius: 0.2, height: 1.0}}
  - {name: crate, box: {center: [-0.9, 0.6, 0.25], size: [0.5, 0.4, 0.5], yaw: 0.4}}
")
execute_process(COMMAND "${TOOL}" view "--model=${MODEL}" "--obstacles=${WORK}/obstacles.yaml" "--out=${WORK}/room.html"
                RESULT_VARIABLE rc OUTPUT_QUIET ERROR_QUIET)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "ccma view --obstacles failed")
endif()
file(READ "${WORK}/room.html" room)
string(REPLACE "</body>" "<script>window.ccmaView.showCollision(false); window.ccmaView.showCollision = () => {};</script></body>"
       hidden_shapes "${room}")
file(WRITE "${WORK}/hidden_shapes.html" "${hidden_shapes}")
string(REPLACE "\"shape\":\"cylinder\"" "\"shape\":\"cone\"" bad_shape "${room}")
if(bad_shape STREQUAL room)
  message(FATAL_ERROR "test bug: no cylinder in ${WORK}/room.html")
endif()
file(WRITE "${WORK}/bad_shape.html" "${bad_shape}")
foreach(case "bad_scene|console errors" "remote|network requests" "hidden|body points drawn"
             "hidden_cloud|workspace points drawn" "hidden_meshes|meshes drawn at their centroid"
             "bad_mesh|meshes\\[0\\]\\.file: an index into meshes"
             "hidden_shapes|collision shapes drawn at their centre"
             "bad_shape|collision\\.obstacles\\[0\\]\\.shape")
  string(REPLACE "|" ";" parts "${case}")
  list(GET parts 0 page)
  list(GET parts 1 expected)
  execute_process(COMMAND "${NODE}" "${TEST_JS}" --html "${WORK}/${page}.html"
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  message("${page}: ${out}${err}")
  if(out MATCHES "^SKIP")
    message(FATAL_ERROR "SKIPPED: chromium is not installed")
  endif()
  if(rc EQUAL 0 OR NOT out MATCHES "${expected}")
    message(FATAL_ERROR "the browser test accepted the broken page ${page}.html (expected a failure naming '${expected}')")
  endif()
endforeach()
