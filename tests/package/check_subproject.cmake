# Configure tests/package/subproject, which adds minksum with add_subdirectory:
# without a build type the parent's cache must keep none, and minksum must not
# configure its test suites, its command (which needs node) or its Python module; then build the parent's program (with the build
# type minksum's own build uses, so that its objects come from the compiler
# cache) and run it.
# Usage: cmake -DSOURCE_DIR=... -DWORK=... -P check_subproject.cmake
file(REMOVE_RECURSE ${WORK})
execute_process(COMMAND ${CMAKE_COMMAND} -S ${SOURCE_DIR}/tests/package/subproject -B ${WORK}
                        -DMINKSUM_SOURCE_DIR=${SOURCE_DIR}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "configuring the parent project failed:\n${out}\n${err}")
endif()
file(STRINGS ${WORK}/CMakeCache.txt build_type REGEX "^CMAKE_BUILD_TYPE:")
if(NOT build_type STREQUAL "CMAKE_BUILD_TYPE:STRING=")
  message(FATAL_ERROR "minksum wrote the parent's build type: ${build_type}")
endif()
file(STRINGS ${WORK}/CMakeCache.txt tests REGEX "^MINKSUM_(TESTS|STATIC_CLI|CLI|PYTHON):")
list(SORT tests)
if(NOT tests STREQUAL "MINKSUM_CLI:BOOL=OFF;MINKSUM_PYTHON:BOOL=OFF;MINKSUM_STATIC_CLI:BOOL=OFF;MINKSUM_TESTS:BOOL=OFF")
  message(FATAL_ERROR "minksum as a subproject defaults to: ${tests}")
endif()
if(EXISTS ${WORK}/minksum/tests)
  message(FATAL_ERROR "minksum configured its tests as a subproject")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -S ${SOURCE_DIR}/tests/package/subproject -B ${WORK}
                        -DCMAKE_BUILD_TYPE=Release
                RESULT_VARIABLE rc OUTPUT_QUIET ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "reconfiguring the parent project failed:\n${err}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} --build ${WORK} --target consumer
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "building the parent's program failed:\n${out}\n${err}")
endif()
execute_process(COMMAND ${WORK}/consumer ${WORK}/sum.off RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT out STREQUAL "8 vertices, 6 facets, volume 27\n")
  message(FATAL_ERROR "the parent's program printed '${out}' (status ${rc}) ${err}")
endif()
message(STATUS "minksum as a subproject works: ${out}")
