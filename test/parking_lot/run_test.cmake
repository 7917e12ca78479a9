# The second simulator (scripts/parking_lot/simulate.py) writes datasets that pcl_crf
# reads, and its clockwise preset (the scenes of sick, each scan listed clockwise)
# scores exactly as sick: the methods read a clockwise scan backwards.
file(REMOVE_RECURSE ${WORK_DIR})

include(${CMAKE_CURRENT_LIST_DIR}/../run_step.cmake)

foreach(preset sick clockwise)
  run_step(${PYTHON} ${SOURCE_DIR}/scripts/parking_lot/simulate.py --preset ${preset} --pairs 3 -o ${WORK_DIR}/${preset} -q)
  run_step(${APPS_DIR}/pcl_crf_eval ${WORK_DIR}/${preset} --method crf-matching,joint --models ${SOURCE_DIR}/data/models
           --format csv --output ${WORK_DIR}/${preset}.csv -q)
  file(STRINGS ${WORK_DIR}/${preset}.csv rows REGEX "^(crf-matching|joint),")
  list(FILTER rows EXCLUDE REGEX ",seconds,")
  list(LENGTH rows count)
  if(count LESS 30)
    message(FATAL_ERROR "${preset}: expected the metrics of two methods, got ${count} rows")
  endif()
  set(scores_${preset} "${rows}")
endforeach()
if(NOT scores_sick STREQUAL scores_clockwise)
  message(FATAL_ERROR "clockwise scores differ from sick:\n${scores_sick}\n---\n${scores_clockwise}")
endif()
message("parking lot datasets read; clockwise scores as sick")
