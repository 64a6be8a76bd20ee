# Adaptive time steps (docs/dynamics.md#adaptive-time-step), scripted:
#  1. the dropMagnet scene from a 1 ms first step, maxDeltaT 10 ms, for 0.3 s:
#     no audit warning, the cube at rest at the end, and a time folder on every
#     write time (0.005 s apart) and on no other time; the summary's
#     "steps set by:" counts each step once;
#  2. restart: 0 -> SPLIT s (default 0.1: the cube at rest on the disc), then
#     startFrom latestTime to 0.3 s, ends in the same state, bit for bit
#     (bodies.yaml of 0.3), as the run in one go.
# -DMAGFOAM=<exe> -DSRC=<case> -DWORK=<scratch dir> [-DCONTROL=<controlDict line>,
# e.g. "magneticStiffness: implicit", appended to the case's] [-DSPLIT=<write time>]
include(${CMAKE_CURRENT_LIST_DIR}/../runStep.cmake)
file(REMOVE_RECURSE ${WORK})
file(COPY ${SRC}/ DESTINATION ${WORK}/whole)
file(COPY ${SRC}/ DESTINATION ${WORK}/restart)
if(DEFINED CONTROL)
  file(APPEND ${WORK}/whole/system/controlDict.yaml "${CONTROL}\n")
  file(APPEND ${WORK}/restart/system/controlDict.yaml "${CONTROL}\n")
endif()

step(${MAGFOAM} -case ${WORK}/whole)
if(STEP_OUT MATCHES "Warning")
  message(FATAL_ERROR "the adaptive run warned:\n${STEP_OUT}")
endif()
expect_output("1 of 1 dynamic bodies at rest at the end" "the cube is not at rest at the end")
# The summary's "steps set by:" counts every step once.
expect_output("End: ([0-9]+) steps" "no End: line")
set(steps ${STEP_MATCH})
expect_output("steps set by: ([^\n]*)" "no 'steps set by:' line")
set(limits "${STEP_MATCH}")
string(REGEX MATCHALL "[a-z]+ [0-9]+ \\(" counts "${limits}")
set(sum 0)
foreach(c IN LISTS counts)
  string(REGEX REPLACE "[a-z]+ ([0-9]+) \\(" "\\1" n "${c}")
  math(EXPR sum "${sum} + ${n}")
endforeach()
if(NOT sum EQUAL steps OR NOT limits MATCHES "stiffness [0-9]+ \\([0-9.e-]+ s; cube in [0-9]+\\)")
  message(FATAL_ERROR "'steps set by:' counts ${sum} steps of ${steps}: ${limits}")
endif()
foreach(k RANGE 0 60)
  math(EXPR ms "${k} * 5")
  if(ms EQUAL 0)
    set(name 0)
  elseif(ms LESS 10)
    set(name "0.00${ms}")
  elseif(ms LESS 100)
    set(name "0.0${ms}")
  else()
    set(name "0.${ms}")
  endif()
  if(name MATCHES "\\.")
    string(REGEX REPLACE "0+$" "" name "${name}")
  endif()
  if(NOT EXISTS ${WORK}/whole/${name}/bodies.yaml)
    message(FATAL_ERROR "no time folder ${name}/ (write times every 0.005 s)")
  endif()
endforeach()

# ... and no other: 61 time folders (names are the time rounded to 1e-12 s).
file(GLOB folders LIST_DIRECTORIES true ${WORK}/whole/[0-9]*)
list(LENGTH folders count)
if(NOT count EQUAL 61)
  message(FATAL_ERROR "${count} time folders, expected the 61 write times: ${folders}")
endif()

file(READ ${WORK}/restart/system/controlDict.yaml ctl)
if(NOT DEFINED SPLIT)
  set(SPLIT 0.1)
endif()
string(REPLACE "endTime: 0.3" "endTime: ${SPLIT}" first "${ctl}")
file(WRITE ${WORK}/restart/system/controlDict.yaml "${first}")
step(${MAGFOAM} -case ${WORK}/restart)
file(WRITE ${WORK}/restart/system/controlDict.yaml "${ctl}\nstartFrom: latestTime\n")
step(${MAGFOAM} -case ${WORK}/restart)
expect_output("Restarting from" "the second part did not restart")
file(READ ${WORK}/whole/0.3/bodies.yaml a)
file(READ ${WORK}/restart/0.3/bodies.yaml b)
if(NOT a STREQUAL b)
  message(FATAL_ERROR "restarted run differs at 0.3 s:\n${a}\n---\n${b}")
endif()
