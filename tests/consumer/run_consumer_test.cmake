# Installs the build tree to a temporary prefix, then configures, builds and runs a tiny
# downstream project that uses find_package(Sysid) + target_link_libraries(app sysid::sysid).
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR})
set(prefix ${WORK_DIR}/prefix)
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGN}\n${out}\n${err}")
  endif()
endfunction()
run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})
run(${CMAKE_COMMAND} -S ${SOURCE_DIR}/tests/consumer/project -B ${WORK_DIR}/build
    -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_BUILD_TYPE=Release)
run(${CMAKE_COMMAND} --build ${WORK_DIR}/build)
execute_process(COMMAND ${WORK_DIR}/build/consumer ${SOURCE_DIR}/datasets/paper/pulse_table.csv
                RESULT_VARIABLE rc OUTPUT_VARIABLE out)
if(NOT rc EQUAL 0 OR NOT out MATCHES "a1p=104.0154")
  message(FATAL_ERROR "consumer ran with ${rc}: ${out}")
endif()
if(NOT EXISTS ${prefix}/bin/sysid)
  message(FATAL_ERROR "the sysid program was not installed")
endif()
message(STATUS "consumer: ${out}")
