# tutorials/dropMagnet copied out of the source tree (as `cp -r` into a run folder):
#  1. without MAGFOAM_DIR, ./Allrun fails and names etc/bashrc;
#  2. after `. etc/bashrc` of the tree, ./Allrun runs (magCheckMesh, magFoam, the
#     plot) and ./Allclean cleans.
# -DSOURCE_DIR=<tree> -DWORK=<scratch>
include(${CMAKE_CURRENT_LIST_DIR}/../runStep.cmake)
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
file(COPY ${SOURCE_DIR}/tutorials/dropMagnet DESTINATION ${WORK} USE_SOURCE_PERMISSIONS)
set(case ${WORK}/dropMagnet)
file(REMOVE_RECURSE ${case}/VTK ${case}/postProcessing)

execute_process(COMMAND env -u MAGFOAM_DIR -u MAG_ROOT bash ${case}/Allrun
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(rc EQUAL 0 OR NOT err MATCHES "source <magFoam>/etc/bashrc first")
  message(FATAL_ERROR "without MAGFOAM_DIR the copy must fail naming etc/bashrc (rc ${rc}):\n${out}\n${err}")
endif()

step(bash -c ". '${SOURCE_DIR}/etc/bashrc' && '${case}/Allrun'")
foreach(f log.magFoam postProcessing/energy.csv 0.3/bodies.yaml)
  if(NOT EXISTS ${case}/${f})
    message(FATAL_ERROR "the copied tutorial's Allrun wrote no ${f}:\n${STEP_OUT}")
  endif()
endforeach()
step(bash -c ". '${SOURCE_DIR}/etc/bashrc' && '${case}/Allclean'")
if(EXISTS ${case}/0.3 OR EXISTS ${case}/log.magFoam)
  message(FATAL_ERROR "Allclean left results in the copy")
endif()
