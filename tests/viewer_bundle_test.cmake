# The viewer's bundle as the build makes it (esbuild's binary with the
# options in viewer/CMakeLists.txt) against the one viewer/js/build.mjs makes
# with esbuild's JavaScript API: the same bytes, so that the two stay one.
#   cmake -DNODE=.. -DBUILD_MJS=.. -DBUNDLE=.. -DWORK=.. -P viewer_bundle_test.cmake
cmake_minimum_required(VERSION 3.16)
file(MAKE_DIRECTORY "${WORK}")
execute_process(COMMAND "${NODE}" "${BUILD_MJS}" --out "${WORK}/build_mjs_bundle.js"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "node ${BUILD_MJS} failed (${rc}):\n${out}\n${err}")
endif()
execute_process(COMMAND "${CMAKE_COMMAND}" -E compare_files "${BUNDLE}" "${WORK}/build_mjs_bundle.js"
                RESULT_VARIABLE differ)
if(NOT differ EQUAL 0)
  file(SIZE "${BUNDLE}" build_size)
  file(SIZE "${WORK}/build_mjs_bundle.js" mjs_size)
  message(FATAL_ERROR "the build's bundle ${BUNDLE} (${build_size} bytes) differs from build.mjs's "
                      "${WORK}/build_mjs_bundle.js (${mjs_size} bytes): the esbuild options of "
                      "viewer/CMakeLists.txt and viewer/js/build.mjs disagree")
endif()
message(STATUS "the same ${BUNDLE}")
