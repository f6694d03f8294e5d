# csm-bench --walk on a model file given by its path (MODEL), small and short: a row per path
# (orbit, dolly, still) and technique (unshadowed, VTK's pass, ours), the scene named by the
# path, and on every path ours misclassifies fewer pixels than VTK's pass against the truth.
file(REMOVE_RECURSE "${DIR}")
file(MAKE_DIRECTORY "${DIR}")
execute_process(COMMAND "${BENCH}" --walk --scenes "${MODEL}" --frames 3 --rounds 1
  --size 160x120 --out "${DIR}/walk.csv" RESULT_VARIABLE result)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "csm-bench --walk failed: ${result}")
endif()
file(STRINGS "${DIR}/walk.csv" rows)
list(LENGTH rows lines)
if(NOT lines EQUAL 10) # a header, 3 paths x 3 techniques
  message(FATAL_ERROR "expected a header and 9 rows, found ${lines} lines")
endif()
list(REMOVE_AT rows 0)
foreach(row IN LISTS rows)
  string(REPLACE "," ";" cells "${row}")
  list(GET cells 0 scene)
  list(GET cells 1 path)
  list(GET cells 3 label)
  list(GET cells 11 misclassified)
  if(NOT scene STREQUAL MODEL)
    message(FATAL_ERROR "a row of scene '${scene}', expected '${MODEL}'")
  endif()
  string(REPLACE " " "_" label "${label}")
  set(${label}_${path} "${misclassified}")
endforeach()
foreach(path orbit dolly still)
  if(NOT DEFINED default_${path} OR NOT DEFINED vtk_default_${path})
    message(FATAL_ERROR "${path}: no row for ours or for VTK's pass")
  endif()
  if(NOT default_${path} LESS vtk_default_${path})
    message(FATAL_ERROR "${path}: ours misclassified ${default_${path}} %, VTK's pass "
      "${vtk_default_${path}} %")
  endif()
  message(STATUS "${path}: misclassified ours ${default_${path}} %, VTK's pass "
    "${vtk_default_${path}} %")
endforeach()
