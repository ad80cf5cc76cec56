# Install minksum from BUILD_DIR into a fresh prefix, build a project that
# finds it with find_package(minksum), run it and check what it prints.
# Usage: cmake -DBUILD_DIR=... -DSOURCE_DIR=... -DWORK=... -P check_package.cmake
file(REMOVE_RECURSE ${WORK})
execute_process(COMMAND ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${WORK}/prefix
                RESULT_VARIABLE rc OUTPUT_QUIET)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "cmake --install failed (${rc})")
endif()
foreach(f include/minksum/kernel.hpp include/minksum/minkowski.hpp include/minksum/sum_result.hpp
          include/minksum/operand.hpp lib/libminksum.a bin/minksum lib/cmake/minksum/minksumConfig.cmake)
  if(NOT EXISTS ${WORK}/prefix/${f})
    message(FATAL_ERROR "not installed: ${f}")
  endif()
endforeach()
file(GLOB_RECURSE internal ${WORK}/prefix/include/kernel/* ${WORK}/prefix/include/mesh/*)
if(internal)
  message(FATAL_ERROR "internal headers installed: ${internal}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -S ${SOURCE_DIR}/tests/package -B ${WORK}/consumer
                        -DCMAKE_PREFIX_PATH=${WORK}/prefix -DCMAKE_BUILD_TYPE=Release
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "configuring the consumer failed:\n${out}\n${err}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} --build ${WORK}/consumer RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "building the consumer failed:\n${out}\n${err}")
endif()
execute_process(COMMAND ${WORK}/consumer/consumer ${WORK}/sum.off RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT out STREQUAL "8 vertices, 6 facets, volume 27\n")
  message(FATAL_ERROR "the consumer printed '${out}' (status ${rc}) ${err}")
endif()
message(STATUS "installed package works: ${out}")

# The same program built without CMake, by the compiler and pkg-config.
find_program(PKG_CONFIG pkg-config REQUIRED)
foreach(f lib/pkgconfig/minksum.pc)
  if(NOT EXISTS ${WORK}/prefix/${f})
    message(FATAL_ERROR "not installed: ${f}")
  endif()
endforeach()
set(ENV{PKG_CONFIG_PATH} ${WORK}/prefix/lib/pkgconfig)
execute_process(COMMAND ${PKG_CONFIG} --cflags --libs minksum RESULT_VARIABLE rc OUTPUT_VARIABLE flags
                ERROR_VARIABLE err OUTPUT_STRIP_TRAILING_WHITESPACE)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "pkg-config --cflags --libs minksum failed: ${err}")
endif()
separate_arguments(flags UNIX_COMMAND "${flags}")
execute_process(COMMAND ${CXX} -std=c++20 -O1 ${SOURCE_DIR}/tests/package/consumer.cpp ${flags} -o ${WORK}/consumer-pc
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "building the consumer with pkg-config's flags (${flags}) failed:\n${out}\n${err}")
endif()
execute_process(COMMAND ${WORK}/consumer-pc ${WORK}/sum-pc.off RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT out STREQUAL "8 vertices, 6 facets, volume 27\n")
  message(FATAL_ERROR "the pkg-config consumer printed '${out}' (status ${rc}) ${err}")
endif()
message(STATUS "pkg-config package works: ${out}")
