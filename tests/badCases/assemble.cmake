# A bad-input case of tests/badCases/variants: the base case with the
# variant's files over it, in a fresh folder of the build tree.
#   cmake -DBASE=... -DVARIANT=... -DDST=... [-DDANGLING=relative/path] -P assemble.cmake
file(REMOVE_RECURSE ${DST})
file(COPY ${BASE}/ DESTINATION ${DST})
# COPY_FILE, not COPY: file(COPY) skips a file whose copy has the same time stamp.
if(VARIANT)
  file(GLOB_RECURSE files RELATIVE ${VARIANT} ${VARIANT}/*)
  foreach(f ${files})
    get_filename_component(dir ${DST}/${f} DIRECTORY)
    file(MAKE_DIRECTORY ${dir})
    file(COPY_FILE ${VARIANT}/${f} ${DST}/${f})
  endforeach()
endif()
# A link to a file that does not exist, in place of an optional dictionary.
if(DANGLING)
  file(REMOVE ${DST}/${DANGLING})
  file(CREATE_LINK missing.yaml ${DST}/${DANGLING} SYMBOLIC)
endif()
