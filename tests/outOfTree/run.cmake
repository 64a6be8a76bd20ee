# Install the build tree into a temporary prefix, build this folder's plugin
# against it out of tree, and load it by name. Fails on any step.
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR})
include(${CMAKE_CURRENT_LIST_DIR}/../runStep.cmake)
step(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${WORK_DIR}/prefix)
step(${CMAKE_COMMAND} -S ${SOURCE_DIR}/tests/outOfTree -B ${WORK_DIR}/build
     -DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix -DCMAKE_BUILD_TYPE=Release)
step(${CMAKE_COMMAND} --build ${WORK_DIR}/build)
step(${CMAKE_COMMAND} -E env MAG_PLUGIN_PATH=${WORK_DIR}/build ${WORK_DIR}/build/loadOutOfTree)
message(STATUS "${STEP_OUT}")
# The installed apps list the new type too.
step(${CMAKE_COMMAND} -E env MAG_PLUGIN_PATH=${WORK_DIR}/build ${WORK_DIR}/prefix/bin/magCheckMesh -listModules)
expect_output("outOfTreeField" "installed magCheckMesh -listModules does not list outOfTreeField")
message(STATUS "out-of-tree plugin OK")
