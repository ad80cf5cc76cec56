# Test python.install: cmake --install into a fresh prefix puts the package in
# a directory that the interpreter's site module lists for that prefix (as it
# lists /usr/local/lib/python3.X/dist-packages for /usr/local), and the
# installed package imports and computes there, away from the build tree.
foreach(var BUILD_DIR WORK PYTHON)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "check_install.cmake needs -D${var}=...")
  endif()
endforeach()
file(REMOVE_RECURSE ${WORK})
execute_process(COMMAND ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${WORK}/prefix
                RESULT_VARIABLE rc OUTPUT_QUIET)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "cmake --install failed (${rc})")
endif()
file(GLOB_RECURSE init ${WORK}/prefix/__init__.py)
list(FILTER init INCLUDE REGEX "/minksum/__init__\\.py$")
list(LENGTH init n)
if(NOT n EQUAL 1)
  message(FATAL_ERROR "expected one installed minksum/__init__.py, found: ${init}")
endif()
get_filename_component(package ${init} DIRECTORY)
get_filename_component(site ${package} DIRECTORY)
set(check [=[
import os, site, sys
prefix, where = sys.argv[1], sys.argv[2]
listed = [os.path.realpath(p) for p in site.getsitepackages([prefix])]
assert os.path.realpath(where) in listed, f"{where} is not a site directory of {prefix}: {listed}"
sys.path.insert(0, where)
import minksum, minksum.dask
assert os.path.realpath(minksum.__file__).startswith(os.path.realpath(where)), minksum.__file__
from fractions import Fraction
assert minksum.minkowski_sum("cube", "tetra").volume() == Fraction(176, 3)
print("installed in", where)
]=])
execute_process(COMMAND ${PYTHON} -c "${check}" ${WORK}/prefix ${site}
                WORKING_DIRECTORY ${WORK} RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the installed package does not import or compute (${rc})")
endif()
file(REMOVE_RECURSE ${WORK})
