# mag_add_plugin(<Name> SOURCES ... [LIBS ...] [TYPES <registry>:<type> ...] [NO_INSTALL])
#
# Builds libmag<Name>.so, a runtime-loadable magFoam module that registers its
# types when loaded. Works in tree (links the `core` target) and out of tree
# (links the installed magFoam::core).
#
# TYPES names what the library registers, e.g. `TYPES field:MBM` or
# `TYPES rigidBody:free`; registries: field (magSchemes.yaml field.type),
# induction (magSchemes.yaml induction.type), rigidBody (rigidBody.yaml type),
# appliedField (appliedField.yaml type).
# The build then lists the library in the plugin manifest of the folder it is
# built into (<project>.magPlugins.yaml, beside the libraries; installed too),
# and the apps load what the manifests on the plugin search path list, find the
# library of a `type:` there, and check at load time that a library registers
# exactly the types its manifest says. A plugin without TYPES is left out of the
# manifest: it loads by name only (`libs:` in controlDict.yaml, or a type named
# like the library, magFoo for type Foo).
#
# Every plugin target is appended to the global property MAG_PLUGIN_TARGETS
# (the tests depend on all of them).
function(mag_add_plugin name)
  cmake_parse_arguments(ARG "NO_INSTALL" "" "SOURCES;LIBS;TYPES" ${ARGN})
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

  foreach(t IN LISTS ARG_TYPES)
    if(NOT t MATCHES "^(field|induction|rigidBody|appliedField):[A-Za-z_][A-Za-z0-9_]*$")
      message(FATAL_ERROR "mag_add_plugin(${name}): TYPES entry '${t}' is not <registry>:<type> "
                          "with registry field, induction, rigidBody or appliedField")
    endif()
  endforeach()
  if(NOT ARG_TYPES AND NOT ARG_NO_INSTALL)
    message(AUTHOR_WARNING "mag_add_plugin(${name}): no TYPES; lib${target}.so is left out of the plugin "
                           "manifest and loads only by name")
  endif()
  # Where the library lands when LIBRARY_OUTPUT_DIRECTORY is not set (read later:
  # the caller may still set it).
  if(ARG_NO_INSTALL)
    set(installed OFF)
  else()
    set(installed ON)
  endif()
  set_target_properties(${target} PROPERTIES MAG_PLUGIN_TYPES "${ARG_TYPES}"
    MAG_PLUGIN_INSTALLED ${installed} MAG_PLUGIN_BINARY_DIR "${CMAKE_CURRENT_BINARY_DIR}")
  set_property(GLOBAL APPEND PROPERTY MAG_PLUGIN_TARGETS ${target})

  # The manifests are written once every plugin of the project is known: at the
  # end of the top-level CMakeLists.
  get_property(scheduled GLOBAL PROPERTY _MAG_PLUGIN_MANIFESTS_SCHEDULED)
  if(NOT scheduled)
    set_property(GLOBAL PROPERTY _MAG_PLUGIN_MANIFESTS_SCHEDULED ON)
    cmake_language(DEFER DIRECTORY ${CMAKE_SOURCE_DIR} CALL _mag_write_plugin_manifests)
  endif()
endfunction()

# One manifest line: `libmagMBM.so: {field: [MBM]}`.
function(_mag_plugin_manifest_line target out)
  get_target_property(types ${target} MAG_PLUGIN_TYPES)
  get_target_property(name ${target} OUTPUT_NAME)
  set(fields)
  foreach(registry field induction rigidBody)
    set(names)
    foreach(t IN LISTS types)
      if(t MATCHES "^${registry}:(.*)$")
        list(APPEND names ${CMAKE_MATCH_1})
      endif()
    endforeach()
    if(names)
      list(JOIN names ", " names)
      list(APPEND fields "${registry}: [${names}]")
    endif()
  endforeach()
  list(JOIN fields ", " fields)
  set(${out} "lib${name}${CMAKE_SHARED_MODULE_SUFFIX}: {${fields}}\n" PARENT_SCOPE)
endfunction()

# Write <dir>/<project>.magPlugins.yaml for every folder that plugins are built
# into, and install one for the installed plugins.
function(_mag_write_plugin_manifests)
  set(header "# Plugin manifest of ${PROJECT_NAME}, written by mag_add_plugin (magFoamPlugin.cmake):\n"
             "# each library of this folder and the model types it registers.\n")
  string(CONCAT header ${header})
  set(file "${PROJECT_NAME}.magPlugins.yaml")
  get_property(targets GLOBAL PROPERTY MAG_PLUGIN_TARGETS)
  set(dirs)
  set(installed)
  foreach(target IN LISTS targets)
    get_target_property(types ${target} MAG_PLUGIN_TYPES)
    if(NOT types)
      continue()
    endif()
    get_target_property(dir ${target} LIBRARY_OUTPUT_DIRECTORY)
    if(NOT dir)
      get_target_property(dir ${target} MAG_PLUGIN_BINARY_DIR)
    endif()
    string(MAKE_C_IDENTIFIER "${dir}" key)
    if(NOT DEFINED _lines_${key})
      list(APPEND dirs "${dir}")
      set(_lines_${key} "")
    endif()
    _mag_plugin_manifest_line(${target} line)
    string(APPEND _lines_${key} "${line}")
    get_target_property(inst ${target} MAG_PLUGIN_INSTALLED)
    if(inst)
      string(APPEND installed "${line}")
    endif()
  endforeach()
  foreach(dir IN LISTS dirs)
    string(MAKE_C_IDENTIFIER "${dir}" key)
    file(GENERATE OUTPUT "${dir}/${file}" CONTENT "${header}${_lines_${key}}")
  endforeach()
  if(installed)
    set(libdir "${CMAKE_INSTALL_LIBDIR}")
    if(NOT libdir)
      set(libdir lib)
    endif()
    set(staged "${CMAKE_BINARY_DIR}/CMakeFiles/magPluginManifest/${file}")
    file(GENERATE OUTPUT "${staged}" CONTENT "${header}${installed}")
    install(FILES "${staged}" DESTINATION ${libdir})
  endif()
endfunction()
