# Installs ccma into a scratch prefix, builds tests/consumer against it with
# find_package(ccma CONFIG REQUIRED), and runs the result on a model.
# Invoked by CTest: cmake -DBUILD_DIR=.. -DSOURCE_DIR=.. -DWORK_DIR=.. -P this
cmake_minimum_required(VERSION 3.16)  # policies (IN_LIST)
file(REMOVE_RECURSE "${WORK_DIR}")
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGN}\n${out}\n${err}")
  endif()
  set(last_output "${out}" PARENT_SCOPE)
endfunction()
run(${CMAKE_COMMAND} --install "${BUILD_DIR}" --prefix "${WORK_DIR}/prefix")
# Only the public headers are installed: no internal/ folder, no cost functions.
file(GLOB_RECURSE installed RELATIVE "${WORK_DIR}/prefix/include" "${WORK_DIR}/prefix/include/*")
foreach(header ${installed})
  if(header MATCHES "internal/|cost_functions/")
    message(FATAL_ERROR "an internal header is installed: ${header}")
  endif()
endforeach()
if(NOT "ccma/ccma/ccma.h" IN_LIST installed)
  message(FATAL_ERROR "ccma/ccma.h is not installed: ${installed}")
endif()
run(${CMAKE_COMMAND} -S "${SOURCE_DIR}/tests/consumer" -B "${WORK_DIR}/build"
    -DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix -DCMAKE_BUILD_TYPE=Release
    -DEXAMPLE_SOURCE=${SOURCE_DIR}/apps/embed_example.cc)
run(${CMAKE_COMMAND} --build "${WORK_DIR}/build")
run("${WORK_DIR}/build/app" "${WORK_DIR}/prefix/share/ccma/models/6dof_six_agents.yaml")
if(NOT last_output MATCHES "summary: assembled=1 converged=1")
  message(FATAL_ERROR "consumer ran but did not assemble:\n${last_output}")
endif()
message(STATUS "consumer output:\n${last_output}")

# The Python package: `import ccma` from the installed prefix alone.
if(PYTHON)
  set(site "${WORK_DIR}/prefix/${PYTHON_SITE}")
  if(NOT EXISTS "${site}/ccma/__init__.py")
    message(FATAL_ERROR "the Python package is not installed in ${site}")
  endif()
  run(${CMAKE_COMMAND} -E env PYTHONPATH=${site} ${PYTHON} -c
      "import ccma, sys; assert ccma.__file__.startswith(sys.argv[1]), ccma.__file__; m = ccma.load_model(sys.argv[2]); r = ccma.ForwardProblem(m).assemble(m.home_controls); print('python: assembled', r.assembled, ccma.__file__); assert r.assembled"
      "${site}" "${WORK_DIR}/prefix/share/ccma/models/4dof_reduced.yaml")
  message(STATUS "${last_output}")
endif()
