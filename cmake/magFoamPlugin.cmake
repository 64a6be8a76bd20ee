# mag_add_plugin(<Name> SOURCES ...): build libmag<Name>.so, a runtime-loadable
# magFoam module that registers its types when loaded. Works in tree (links the
# `core` target) and out of tree (links the installed magFoam::core).
function(mag_add_plugin name)
  cmake_parse_arguments(ARG "NO_INSTALL" "" "SOURCES;LIBS" ${ARGN})
  set(target mag${name})
  add_library(${target} MODULE ${ARG_SOURCES})
  if(TARGET core)
    target_link_libraries(${target} PRIVATE core ${ARG_LIBS})
  else()
    target_link_libraries(${target} PRIVATE magFoam::core ${ARG_LIBS})
  endif()
  set_target_properties(${target} PROPERTIES PREFIX "lib" OUTPUT_NAME ${target})
  if(NOT ARG_NO_INSTALL)
    install(TARGETS ${target} LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
  endif()
endfunction()
