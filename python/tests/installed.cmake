# cmake --install into a scratch prefix, then import the installed module from
# there with the build tree out of sight: it must find libmagCore through its
# RPATH and the plugins beside it, and evaluate a field.
file(REMOVE_RECURSE ${WORK_DIR})
include(${SOURCE_DIR}/tests/runStep.cmake)
step(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${WORK_DIR}/prefix)
step(${CMAKE_COMMAND} -E env --unset=MAG_PLUGIN_PATH PYTHONPATH=${WORK_DIR}/prefix/${PYTHON_DIR}
     ${PYTHON} ${SOURCE_DIR}/python/tests/installed_import.py ${WORK_DIR}/prefix)
if(NOT STEP_OUT MATCHES "MBM.*0\\.666666")
  message(FATAL_ERROR "the installed module did not evaluate the field of a cube (2/3 T at its centre):\n${STEP_OUT}")
endif()
message(STATUS "installed module OK: ${STEP_OUT}")
