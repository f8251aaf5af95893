# The Python module `geodual` (python/): pybind11 and the Python 3 headers
# from Debian packages (pybind11-dev, python3-dev; python3-numpy at run time,
# python3-pytest for its tests).
#
# GEODUAL_BUILD_PYTHON defaults to ON where pybind11, the Python 3 headers and
# an interpreter that imports numpy are found; set ON explicitly, their absence
# is an error.
#
# The interpreter: Python3_EXECUTABLE when given; otherwise the first python3
# on PATH that imports numpy, which the module needs at run time (a python3
# first on PATH without numpy, such as a pyenv shim, would build a module its
# own interpreter cannot load, and tests that cannot run).

if(NOT Python3_EXECUTABLE)
  string(REPLACE ":" ";" _geodual_path "$ENV{PATH}")
  foreach(dir IN LISTS _geodual_path)
    if(EXISTS "${dir}/python3")
      execute_process(COMMAND "${dir}/python3" -c "import numpy"
                      RESULT_VARIABLE _geodual_no_numpy OUTPUT_QUIET ERROR_QUIET)
      if(_geodual_no_numpy EQUAL 0)
        set(Python3_EXECUTABLE "${dir}/python3")
        break()
      endif()
    endif()
  endforeach()
endif()

find_package(Python3 3.8 COMPONENTS Interpreter Development.Module QUIET)
if(Python3_FOUND)
  find_package(pybind11 2.6 CONFIG QUIET)  # pybind11-dev -> pybind11_add_module
  execute_process(COMMAND "${Python3_EXECUTABLE}" -c "import numpy"
                  RESULT_VARIABLE _geodual_no_numpy OUTPUT_QUIET ERROR_QUIET)
endif()

set(_geodual_python_missing "")
if(NOT Python3_FOUND)
  set(_geodual_python_missing "the Python 3 interpreter and headers (Debian: python3-dev)")
elseif(NOT pybind11_FOUND)
  set(_geodual_python_missing "pybind11 (Debian: pybind11-dev)")
elseif(NOT _geodual_no_numpy EQUAL 0)
  set(_geodual_python_missing "numpy for ${Python3_EXECUTABLE} (Debian: python3-numpy)")
endif()

if(_geodual_python_missing STREQUAL "")
  set(_geodual_python_default ON)
else()
  set(_geodual_python_default OFF)
endif()
option(GEODUAL_BUILD_PYTHON "Build the Python module geodual (needs pybind11, Python 3 headers, numpy)"
       ${_geodual_python_default})

if(GEODUAL_BUILD_PYTHON AND NOT _geodual_python_missing STREQUAL "")
  message(FATAL_ERROR "GEODUAL_BUILD_PYTHON is ON but ${_geodual_python_missing} was not found: "
                      "install it, point Python3_EXECUTABLE at an interpreter that has it, "
                      "or configure with -DGEODUAL_BUILD_PYTHON=OFF")
elseif(GEODUAL_BUILD_PYTHON)
  message(STATUS "geodual: Python module for ${Python3_EXECUTABLE} (${Python3_VERSION}), pybind11 ${pybind11_VERSION}")
elseif(NOT _geodual_python_missing STREQUAL "")
  message(STATUS "geodual: no Python module: ${_geodual_python_missing} not found")
endif()
