# Three copies of the audit case: largeStep (as is), strict (as is, run with
# -strict), stable (the tutorial's own step).
file(REMOVE_RECURSE ${DST})
foreach(name largeStep strict stable)
  file(COPY ${SRC}/ DESTINATION ${DST}/${name})
endforeach()
file(COPY_FILE ${DST}/stable/system/controlDict.stable.yaml ${DST}/stable/system/controlDict.yaml)
