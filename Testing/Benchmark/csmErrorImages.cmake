# csm-bench --quick --labels default --error-images DIR on the platform: one PNG per
# measured view (orbit0, fly3, gamma45) and the CSV holds the one row asked for.
file(REMOVE_RECURSE "${DIR}")
file(MAKE_DIRECTORY "${DIR}")
execute_process(COMMAND "${BENCH}" --quick --labels default --out "${DIR}/bench.csv"
  --error-images "${DIR}" RESULT_VARIABLE result)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "csm-bench failed: ${result}")
endif()
file(GLOB images "${DIR}/platform-default-*.png")
list(LENGTH images count)
if(NOT count EQUAL 3)
  message(FATAL_ERROR "expected 3 error images, found ${count}: ${images}")
endif()
file(STRINGS "${DIR}/bench.csv" rows)
list(LENGTH rows lines)
if(NOT lines EQUAL 2)
  message(FATAL_ERROR "expected a header and one row, found ${lines} lines")
endif()
