# csm-bench --changes on the columns (16 parts over a ground), small and short: a row per change
# and technique; ours draws no texel a step for colour and scalars, one part of 16 moved draws
# some but at most a quarter of the first frame's texels, and where geometry moves ours
# misclassifies fewer pixels than VTK's pass against the ray-cast truth.
file(REMOVE_RECURSE "${DIR}")
file(MAKE_DIRECTORY "${DIR}")
execute_process(COMMAND "${BENCH}" --changes --scenes columns --steps 2 --rounds 1
  --size 320x240 --out "${DIR}/changes.csv" RESULT_VARIABLE result)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "csm-bench --changes failed: ${result}")
endif()
file(STRINGS "${DIR}/changes.csv" rows)
list(LENGTH rows lines)
if(NOT lines EQUAL 19) # a header, 6 changes x 3 techniques
  message(FATAL_ERROR "expected a header and 18 rows, found ${lines} lines")
endif()
foreach(row IN LISTS rows)
  string(REPLACE "," ";" cells "${row}")
  list(GET cells 1 change)
  string(REPLACE " " "_" change "${change}")
  list(GET cells 2 label)
  list(GET cells 5 texels)
  list(GET cells 6 first)
  list(GET cells 7 misclassified)
  if(label STREQUAL "default")
    set(texels_${change} "${texels}")
    set(first_${change} "${first}")
    set(ours_${change} "${misclassified}")
  elseif(label STREQUAL "vtk default")
    set(vtk_${change} "${misclassified}")
  endif()
endforeach()
foreach(change nothing colour scalars)
  if(NOT texels_${change} EQUAL 0)
    message(FATAL_ERROR "${change}: ours drew ${texels_${change}} texels a step, expected 0")
  endif()
endforeach()
math(EXPR quarter "${first_part_moved} / 4")
if(NOT texels_part_moved GREATER 0 OR texels_part_moved GREATER quarter)
  message(FATAL_ERROR "one part of 16 moved drew ${texels_part_moved} texels a step, the first "
    "frame ${first_part_moved}: expected more than 0 and at most a quarter")
endif()
foreach(change part_moved deforming new_dataset)
  if(NOT ours_${change} LESS vtk_${change})
    message(FATAL_ERROR "${change}: ours misclassified ${ours_${change}} %, VTK's pass "
      "${vtk_${change}} %: expected fewer")
  endif()
endforeach()
message(STATUS "texels a step: part moved ${texels_part_moved} of ${first_part_moved}, "
  "deforming ${texels_deforming}; "
  "misclassified ours / VTK: deforming ${ours_deforming} / ${vtk_deforming} %")
