# step(COMMAND...): run one command of a scripted test (cmake -P); stop with its
# output when it fails. STEP_OUT holds what it printed (stdout, then stderr).
function(step)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "step failed (${rc}): ${ARGN}\n${out}\n${err}")
  endif()
  set(STEP_OUT "${out}${err}" PARENT_SCOPE)
endfunction()

# expect_output(REGEX what): STEP_OUT must match REGEX, else stop with `what`
# and the output. STEP_MATCH holds the regex's first group.
function(expect_output regex what)
  if(NOT STEP_OUT MATCHES "${regex}")
    message(FATAL_ERROR "${what}:\n${STEP_OUT}")
  endif()
  set(STEP_MATCH "${CMAKE_MATCH_1}" PARENT_SCOPE)
endfunction()
