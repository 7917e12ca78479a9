# Installs the built pcl_crf into a scratch prefix, then configures, builds and runs
# an outside project that uses find_package(pcl_crf) against that prefix.
file(REMOVE_RECURSE ${WORK_DIR})
set(prefix ${WORK_DIR}/install)

function(run_step)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE result OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "step failed (${result}): ${ARGN}\n${out}\n${err}")
  endif()
endfunction()

run_step(${CMAKE_COMMAND} --install ${BINARY_DIR} --prefix ${prefix})
run_step(${CMAKE_COMMAND} -S ${SOURCE_DIR}/test/find_package_project -B ${WORK_DIR}/build
  -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_BUILD_TYPE=Release)
run_step(${CMAKE_COMMAND} --build ${WORK_DIR}/build)
execute_process(COMMAND ${WORK_DIR}/build/outside_app RESULT_VARIABLE result OUTPUT_VARIABLE out)
message("${out}")
if(NOT result EQUAL 0 OR NOT out MATCHES "outside project OK")
  message(FATAL_ERROR "outside_app failed (${result}): ${out}")
endif()
