# `cmake --install BUILD_DIR --component python` into a fresh prefix, then import sysid from
# there (not from the build tree) in another folder and use it on a bundled recording.
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR})
execute_process(COMMAND ${CMAKE_COMMAND} --install ${BUILD_DIR} --component python
                        --prefix ${WORK_DIR}/prefix
                RESULT_VARIABLE rc OUTPUT_QUIET)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "cmake --install --component python failed: ${rc}")
endif()
set(ENV{PYTHONPATH} ${WORK_DIR}/prefix/${INSTALL_DIR})
execute_process(
  COMMAND ${PYTHON} -c
    "import sysid,sys; assert sysid.__file__.startswith(sys.argv[1]), sysid.__file__; r=sysid.identify_pulses(sys.argv[2]); print(r.model)"
    ${WORK_DIR}/prefix ${SOURCE_DIR}/datasets/virtual/pulses.csv
  WORKING_DIRECTORY ${WORK_DIR}
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "import of the installed sysid failed: ${err}")
endif()
message(STATUS "installed sysid: ${out}")
