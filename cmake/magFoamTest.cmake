# Test helpers usable from any CMakeLists of the tree (tests/, a module's folder).
# All of them do nothing when MAG_BUILD_TESTS is OFF.
#
# mag_add_module_test(<name> SOURCES ... [LIBS ...])
#   A Catch2 executable build/tests/<name>, its test cases registered with CTest
#   (run in this folder's build directory, MAG_BUILD_DIR set), linking core,
#   Catch2's main and LIBS; it includes this folder and tests/ (the shared
#   fixtures) and sees MAG_SOURCE_DIR. Tests select models by name at run time
#   (plugins are loaded, not linked), so building one builds every plugin
#   (MAG_PLUGIN_TARGETS) unless MAG_TESTS_DEPEND_ON_PLUGINS is OFF.
#
# mag_tests_link(<library> TESTS <test> ...)
#   The named tests, wherever they are defined, link <library> (e.g. a module's
#   kernel that its tests call directly). Tests that do not exist are skipped.
#
# Both take effect at the end of the top-level CMakeLists, once every plugin
# and test is known, so the order of the folders does not matter.
option(MAG_TESTS_DEPEND_ON_PLUGINS "Building a test builds every plugin" ON)

function(mag_add_module_test name)
  if(NOT MAG_BUILD_TESTS)
    return()
  endif()
  cmake_parse_arguments(ARG "" "" "SOURCES;LIBS" ${ARGN})
  if(NOT ARG_SOURCES)
    message(FATAL_ERROR "mag_add_module_test(${name}): no SOURCES")
  endif()
  add_executable(${name} ${ARG_SOURCES})
  target_include_directories(${name} PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})
  if(EXISTS ${PROJECT_SOURCE_DIR}/tests)
    target_include_directories(${name} PRIVATE ${PROJECT_SOURCE_DIR}/tests)
  endif()
  target_compile_definitions(${name} PRIVATE MAG_SOURCE_DIR="${CMAKE_SOURCE_DIR}")
  target_link_libraries(${name} PRIVATE core Catch2::Catch2WithMain ${ARG_LIBS})
  if(TARGET magOracles)  # independent references (reference/oracles)
    target_link_libraries(${name} PRIVATE magOracles)
  endif()
  set_target_properties(${name} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/tests)
  # -w NoTests: a test whose name filter matches no test case fails instead of
  # passing with nothing run (a ';' in a name splits it into such filters).
  catch_discover_tests(${name} WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR}
    EXTRA_ARGS -w NoTests
    PROPERTIES ENVIRONMENT "MAG_BUILD_DIR=${CMAKE_BINARY_DIR}")
  set_property(GLOBAL APPEND PROPERTY MAG_TEST_TARGETS ${name})
endfunction()

function(mag_tests_link library)
  cmake_parse_arguments(ARG "" "" "TESTS" ${ARGN})
  foreach(test IN LISTS ARG_TESTS)
    set_property(GLOBAL APPEND PROPERTY MAG_TEST_LINKS "${test}=${library}")
  endforeach()
endfunction()

function(_mag_finish_tests)
  get_property(tests GLOBAL PROPERTY MAG_TEST_TARGETS)
  get_property(plugins GLOBAL PROPERTY MAG_PLUGIN_TARGETS)
  get_property(links GLOBAL PROPERTY MAG_TEST_LINKS)
  foreach(link IN LISTS links)
    string(REPLACE "=" ";" link "${link}")
    list(GET link 0 test)
    list(GET link 1 library)
    if(TARGET ${test})
      target_link_libraries(${test} PRIVATE ${library})
    endif()
  endforeach()
  if(MAG_TESTS_DEPEND_ON_PLUGINS AND plugins)
    foreach(test IN LISTS tests)
      add_dependencies(${test} ${plugins})
    endforeach()
  endif()
endfunction()

if(MAG_BUILD_TESTS)
  include(Catch)
  cmake_language(DEFER DIRECTORY ${CMAKE_SOURCE_DIR} CALL _mag_finish_tests)
endif()
