# Tutorials copied out of the source tree (as `cp -r` into a run folder):
#  1. without MAGFOAM_DIR, dropMagnet's ./Allrun fails and names etc/bashrc;
#  2. after `. etc/bashrc` of the tree, every tutorial's ./Allrun runs (each
#     copied on its own), and dropMagnet's ./Allclean cleans.
# -DSOURCE_DIR=<tree> -DWORK=<scratch>
include(${CMAKE_CURRENT_LIST_DIR}/../runStep.cmake)
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
file(COPY ${SOURCE_DIR}/tutorials/dropMagnet DESTINATION ${WORK}/bare USE_SOURCE_PERMISSIONS)
execute_process(COMMAND env -u MAGFOAM_DIR -u MAG_ROOT bash ${WORK}/bare/dropMagnet/Allrun
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(rc EQUAL 0 OR NOT err MATCHES "source <magFoam>/etc/bashrc first")
  message(FATAL_ERROR "without MAGFOAM_DIR the copy must fail naming etc/bashrc (rc ${rc}):\n${out}\n${err}")
endif()

# Every tutorial, each copied on its own, runs after `. etc/bashrc`.
file(GLOB tutorials LIST_DIRECTORIES true ${SOURCE_DIR}/tutorials/*)
foreach(dir ${tutorials})
  if(NOT EXISTS ${dir}/Allrun)
    continue()
  endif()
  get_filename_component(name ${dir} NAME)
  file(COPY ${dir} DESTINATION ${WORK} USE_SOURCE_PERMISSIONS)
  set(case ${WORK}/${name})
  execute_process(COMMAND bash -c "cd '${case}' && ./Allclean" OUTPUT_QUIET ERROR_QUIET)
  step(bash -c ". '${SOURCE_DIR}/etc/bashrc' && '${case}/Allrun'")
  file(GLOB logs ${case}/log.*)
  if(NOT logs)
    message(FATAL_ERROR "the copy of ${name} wrote no log:\n${STEP_OUT}")
  endif()
endforeach()
if(NOT EXISTS ${WORK}/dropMagnet/0.3/bodies.yaml)
  message(FATAL_ERROR "the copy of dropMagnet wrote no 0.3/bodies.yaml")
endif()
step(bash -c ". '${SOURCE_DIR}/etc/bashrc' && '${WORK}/dropMagnet/Allclean'")
if(EXISTS ${WORK}/dropMagnet/0.3 OR EXISTS ${WORK}/dropMagnet/log.magFoam)
  message(FATAL_ERROR "Allclean left results in the copy")
endif()
