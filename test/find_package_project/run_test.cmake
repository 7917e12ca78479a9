# Installs the built pcl_crf into a scratch prefix, then configures, builds and runs
# an outside project that uses find_package(pcl_crf) against that prefix.
file(REMOVE_RECURSE ${WORK_DIR})
set(prefix ${WORK_DIR}/install)

include(${CMAKE_CURRENT_LIST_DIR}/../run_step.cmake)

run_step(${CMAKE_COMMAND} --install ${BINARY_DIR} --prefix ${prefix})
run_step(${CMAKE_COMMAND} -S ${SOURCE_DIR}/test/find_package_project -B ${WORK_DIR}/build
  -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_BUILD_TYPE=Release)
run_step(${CMAKE_COMMAND} --build ${WORK_DIR}/build)
# An installed tool runs with the installed library and models only (no LD_LIBRARY_PATH, no
# ldconfig): the tools' install RPATH, and the models under share/pcl_crf/models.
execute_process(COMMAND ${CMAKE_COMMAND} -E env --unset=LD_LIBRARY_PATH
    ${prefix}/bin/pcl_crf_eval ${SOURCE_DIR}/data/default/test --method joint --models ${prefix}/share/pcl_crf/models
    --max-pairs 1 --format csv -q
  RESULT_VARIABLE result OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT result EQUAL 0 OR NOT out MATCHES "joint")
  message(FATAL_ERROR "the installed pcl_crf_eval failed (${result}): ${out}\n${err}")
endif()
execute_process(COMMAND ${WORK_DIR}/build/outside_app RESULT_VARIABLE result OUTPUT_VARIABLE out)
message("${out}")
if(NOT result EQUAL 0 OR NOT out MATCHES "outside project OK")
  message(FATAL_ERROR "outside_app failed (${result}): ${out}")
endif()
