# A new model is one folder: copy the project's sources into a scratch tree,
# add the template field module (etc/templates/fieldModule) there as
# modules/fields/CheckDipole/ renamed as README.md ("Plugins") says, configure,
# build only core, the new plugin, magForces and the module's own test, run
# that test, and run magForces on a case whose magSchemes.yaml selects the new
# type by name. Fails on any step.
#
#   cmake -DSOURCE_DIR=<repo> -DWORK_DIR=<scratch> [-DGENERATOR=...] [-DCXX=...]
#         [-DLAUNCHER=ccache] [-DBUILD_TYPE=Release] [-DARCH=...] [-DNATIVE=OFF]
#         [-DJOBS=2] -P run.cmake
#
# The scratch build folder is kept between runs (a rerun builds what changed);
# the sources are copied afresh every time.
cmake_minimum_required(VERSION 3.22)
foreach(v SOURCE_DIR WORK_DIR)
  if(NOT ${v})
    message(FATAL_ERROR "run.cmake: set -D${v}=...")
  endif()
endforeach()
if(NOT JOBS)
  set(JOBS 2)
endif()
set(SRC ${WORK_DIR}/src)
set(BUILD ${WORK_DIR}/build)
set(CASE ${WORK_DIR}/case)
string(TIMESTAMP t0 "%s")

include(${CMAKE_CURRENT_LIST_DIR}/../runStep.cmake)

# The project's sources, not its build folders.
file(REMOVE_RECURSE ${SRC} ${CASE})
file(MAKE_DIRECTORY ${SRC})
file(COPY ${SOURCE_DIR}/CMakeLists.txt DESTINATION ${SRC})
foreach(dir cmake core reference modules solvers)
  file(COPY ${SOURCE_DIR}/${dir} DESTINATION ${SRC} PATTERN ".*" EXCLUDE)
endforeach()

# The new model: the template folder, PointDipole/pointDipole renamed in file
# names and contents. Staged outside the copy and written only where changed
# (file(COPY) keeps time stamps), so a rerun rebuilds nothing.
set(NEW ${SRC}/modules/fields/CheckDipole)
if(EXISTS ${NEW})
  message(FATAL_ERROR "modules/fields/CheckDipole already exists in the sources: pick another name")
endif()
set(STAGE ${WORK_DIR}/CheckDipole)
set(TEMPLATE ${SOURCE_DIR}/etc/templates/fieldModule)
file(MAKE_DIRECTORY ${STAGE})
file(GLOB files RELATIVE ${TEMPLATE} ${TEMPLATE}/*)
file(REMOVE_RECURSE ${WORK_DIR}/renamed)
foreach(f ${files})
  file(READ ${TEMPLATE}/${f} text)
  string(REPLACE "PointDipole" "CheckDipole" text "${text}")
  string(REPLACE "pointDipole" "checkDipole" text "${text}")
  string(REPLACE "PointDipole" "CheckDipole" f "${f}")
  string(REPLACE "pointDipole" "checkDipole" f "${f}")
  file(WRITE ${WORK_DIR}/renamed/${f} "${text}")
  file(COPY_FILE ${WORK_DIR}/renamed/${f} ${STAGE}/${f} ONLY_IF_DIFFERENT)
  list(APPEND renamed ${f})
endforeach()
file(GLOB staged RELATIVE ${STAGE} ${STAGE}/*)
foreach(f ${staged})
  if(NOT f IN_LIST renamed)
    file(REMOVE ${STAGE}/${f})
  endif()
endforeach()
file(COPY ${STAGE}/ DESTINATION ${NEW})

# Configure: the parent build's compiler, launcher (ccache) and flags; tests on
# for the module's own test, which then does not pull in every other plugin.
set(args -S ${SRC} -B ${BUILD} -DMAG_BUILD_TESTS=ON -DMAG_TESTS_DEPEND_ON_PLUGINS=OFF)
if(GENERATOR)
  list(APPEND args -G ${GENERATOR})
endif()
foreach(pair "CXX;CMAKE_CXX_COMPILER" "LAUNCHER;CMAKE_CXX_COMPILER_LAUNCHER" "BUILD_TYPE;CMAKE_BUILD_TYPE"
             "ARCH;MAG_ARCH" "NATIVE;MAG_NATIVE")
  list(GET pair 0 in)
  list(GET pair 1 var)
  if(DEFINED ${in} AND NOT "${${in}}" STREQUAL "")
    list(APPEND args "-D${var}=${${in}}")
  endif()
endforeach()
step(${CMAKE_COMMAND} ${args})
step(${CMAKE_COMMAND} --build ${BUILD} --parallel ${JOBS} --target core magCheckDipole magForces test_checkDipole)

# The build found the folder and listed the library and its type in the manifest.
file(GLOB manifests ${BUILD}/lib/*.magPlugins.yaml)
set(manifestText "")
foreach(m ${manifests})
  file(READ ${m} text)
  string(APPEND manifestText "${text}")
endforeach()
if(NOT manifestText MATCHES "libmagCheckDipole\\.so: {field: \\[checkDipole\\]}")
  message(FATAL_ERROR "no manifest in ${BUILD}/lib lists libmagCheckDipole.so with field: [checkDipole]:\n${manifestText}")
endif()

# The module's own Catch2 test.
step(${CMAKE_COMMAND} -E env MAG_BUILD_DIR=${BUILD} ${BUILD}/tests/test_checkDipole)
message(STATUS "test_checkDipole: ${STEP_OUT}")

# magForces on two coaxial 1 cm, 1 T cubes 2 cm apart, selected by `type: checkDipole`
# only (no libs:): the point-dipole force 3 mu0 m^2 / (2 pi z^4) = 2.3747152416 N
# (m = 1e-6 m^3 x 1 T / mu0), attracting.
file(COPY ${CMAKE_CURRENT_LIST_DIR}/case/ DESTINATION ${CASE})
step(${BUILD}/bin/magForces -case ${CASE})
file(READ ${CASE}/postProcessing/forces.csv csv)
message(STATUS "forces.csv:\n${csv}")
if(NOT csv MATCHES "\na,[-+0-9.e]+,[-+0-9.e]+,2\\.37471524[0-9]*," OR
   NOT csv MATCHES "\nb,[-+0-9.e]+,[-+0-9.e]+,-2\\.37471524[0-9]*,")
  message(FATAL_ERROR "magForces with type checkDipole: expected Fz = +-2.37471524 N on a and b:\n${csv}\n${STEP_OUT}")
endif()
string(TIMESTAMP t1 "%s")
math(EXPR seconds "${t1} - ${t0}")
message(STATUS "template module OK (${seconds} s)")
